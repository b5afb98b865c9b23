//! Constrained triangulation of one input triangle in its own plane, with exact predicates
//! on (possibly implicit) points only. Incremental: insert points (walking to the triangle
//! that holds them, splitting it or the edge they lie on), then constraint segments (by
//! flipping the edges that cross them, as in Sloan's algorithm), then Delaunay-style flips
//! of unconstrained edges for shape (an approximate in-circle test chooses a flip, the exact
//! orientation test allows it). The in-circle choice is the same for every order of its
//! four points ([`incircle_canonical`](crate::kernel::incircle_canonical)), so the triangulation does not depend on the order
//! the points and constraints came in.

use super::FailReason;
use crate::kernel::{incircle_canonical, orient2d_prepared, Point, Prepared, Sign};

const NONE: u32 = u32::MAX;

/// A triangulation of one triangle's interior, vertices given as kernel points.
pub(crate) struct Local {
    /// The vertices, with interval enclosures for the many predicates on each.
    pts: Vec<Prepared>,
    approx: Vec<[f64; 3]>,
    /// Per vertex, bit `k` set when it lies on the outer triangle's edge `k` (known from
    /// the seam labels): three vertices sharing a bit are collinear, no predicate needed.
    on: Vec<u8>,
    /// Bit `k` set while the outer triangle's edge `k` holds no vertex but its ends: a
    /// point on it then splits the one triangle along it, found without a predicate.
    whole: u8,
    /// Triangles as local vertex indices, counter-clockwise in the normalised frame.
    pub(crate) tris: Vec<[u32; 3]>,
    /// Neighbour across edge k (from corner k to k+1), or NONE on the outer boundary.
    nbr: Vec<[u32; 3]>,
    /// Edge k is constrained (a seam segment or the outer boundary).
    fixed: Vec<[bool; 3]>,
    /// Per vertex, a triangle holding it (for walks around the vertex).
    vt: Vec<u32>,
    /// Per vertex, its side of the line of the constraint being inserted, valid when the
    /// stamp is `stamp`.
    sides: Vec<(std::cell::Cell<u32>, std::cell::Cell<Sign>)>,
    stamp: u32,
    axis: usize,
    sign: Sign,
    last: u32,
    /// The edges [`Local::improve`] has yet to test, as (triangle, slot): kept for its
    /// room.
    pending: Vec<(u32, u8)>,
}

/// What went wrong: the inputs broke an assumption (e.g. a constraint crossing another).
#[derive(Debug)]
pub(crate) struct Failed(pub FailReason);

/// The triangles around a vertex with the vertex's slot in each ([`Local::ring`]):
/// clockwise from the vertex's triangle across the edge leaving it, then, where that met
/// the outer boundary, counter-clockwise from the start across the edge entering it.
struct Ring<'a> {
    local: &'a Local,
    v: u32,
    t0: u32,
    /// The next triangle, or NONE.
    t: u32,
    /// Walking counter-clockwise (the second part).
    back: bool,
}

impl Iterator for Ring<'_> {
    type Item = (u32, usize);

    fn next(&mut self) -> Option<(u32, usize)> {
        let l = self.local;
        let slot = |t: u32| {
            (0..3)
                .find(|&k| l.tris[t as usize][k] == self.v)
                .expect("a vertex's triangle holds it")
        };
        if self.t == NONE {
            if self.back {
                return None;
            }
            // Clockwise ended at the boundary: counter-clockwise from the start.
            self.back = true;
            self.t = l.nbr[self.t0 as usize][(slot(self.t0) + 2) % 3];
            if self.t == NONE {
                return None;
            }
        }
        let (t, k) = (self.t, slot(self.t));
        self.t = if self.back {
            l.nbr[t as usize][(k + 2) % 3]
        } else {
            match l.nbr[t as usize][k] {
                // Around once: done.
                n if n == self.t0 => {
                    self.back = true;
                    NONE
                }
                n => n,
            }
        };
        Some((t, k))
    }
}

fn rot<T: Copy>(a: [T; 3], k: usize) -> [T; 3] {
    [a[k % 3], a[(k + 1) % 3], a[(k + 2) % 3]]
}

impl Local {
    /// The triangle `corners` (counter-clockwise when `sign` is positive in the projection
    /// dropping `axis`; `sign` must be non-zero), with room for `points` more vertices.
    pub(crate) fn new(corners: [[f64; 3]; 3], axis: usize, sign: Sign, points: usize) -> Local {
        let mut local = Local {
            pts: Vec::new(),
            approx: Vec::new(),
            on: Vec::new(),
            whole: 0,
            tris: Vec::new(),
            nbr: Vec::new(),
            fixed: Vec::new(),
            vt: Vec::new(),
            sides: Vec::new(),
            stamp: 0,
            axis,
            sign,
            last: 0,
            pending: Vec::new(),
        };
        local.reset(corners, axis, sign, points);
        local
    }

    /// How many points its arrays hold room for.
    pub(crate) fn room(&self) -> usize {
        self.pts.capacity()
    }

    /// [`Local::new`] in this one's memory: a triangulation per cut triangle, one after
    /// another, without allocating for each.
    pub(crate) fn reset(&mut self, corners: [[f64; 3]; 3], axis: usize, sign: Sign, points: usize) {
        // Each point adds a vertex and at most two triangles.
        let (n, t) = (3 + points, 1 + 2 * points);
        fn refill<T: Copy>(v: &mut Vec<T>, first: &[T], n: usize) {
            v.clear();
            v.reserve(n);
            v.extend_from_slice(first);
        }
        self.pts.clear();
        self.pts.reserve(n);
        self.pts
            .extend(corners.iter().map(|&p| Prepared::new(Point::Explicit(p))));
        refill(&mut self.approx, &corners, n);
        refill(&mut self.on, &[0b101, 0b011, 0b110], n);
        self.whole = 0b111;
        refill(&mut self.tris, &[[0, 1, 2]], t);
        refill(&mut self.nbr, &[[NONE; 3]], t);
        refill(&mut self.fixed, &[[true; 3]], t);
        refill(&mut self.vt, &[0; 3], n);
        // `sides` stays: its entries are valid only under the current stamp, which only
        // grows (cleared where it wraps).
        (self.axis, self.sign, self.last) = (axis, sign, 0);
    }

    /// Locates every later point by the walk, also those on an outer edge not split
    /// before (the tests compare the two ways).
    #[cfg(test)]
    pub(crate) fn walk_only(&mut self) {
        self.whole = 0;
    }

    fn orient(&self, a: u32, b: u32, c: u32) -> Sign {
        if self.on[a as usize] & self.on[b as usize] & self.on[c as usize] != 0 {
            return Sign::Zero;
        }
        orient2d_prepared(
            &self.pts[a as usize],
            &self.pts[b as usize],
            &self.pts[c as usize],
            self.axis,
        )
        .times(self.sign)
    }

    fn orient_pt(&self, a: u32, b: u32, x: &Prepared, x_on: u8) -> Sign {
        if self.on[a as usize] & self.on[b as usize] & x_on != 0 {
            return Sign::Zero;
        }
        orient2d_prepared(&self.pts[a as usize], &self.pts[b as usize], x, self.axis)
            .times(self.sign)
    }

    /// Points `t`'s neighbour that pointed to `old` at `new` instead.
    fn relink(&mut self, t: u32, old: u32, new: u32) {
        if t != NONE {
            for k in 0..3 {
                if self.nbr[t as usize][k] == old {
                    self.nbr[t as usize][k] = new;
                }
            }
        }
    }

    /// Rotates triangle `t`'s arrays so that its slot `k` becomes slot 0.
    fn rotate(&mut self, t: u32, k: usize) {
        let t = t as usize;
        self.tris[t] = rot(self.tris[t], k);
        self.nbr[t] = rot(self.nbr[t], k);
        self.fixed[t] = rot(self.fixed[t], k);
    }

    fn slot_of(&self, t: u32, neighbour: u32) -> usize {
        (0..3)
            .find(|&k| self.nbr[t as usize][k] == neighbour)
            .expect("neighbours link both ways")
    }

    fn push(&mut self, v: [u32; 3], n: [u32; 3], f: [bool; 3]) -> u32 {
        self.tris.push(v);
        self.nbr.push(n);
        self.fixed.push(f);
        (self.tris.len() - 1) as u32
    }

    /// Notes triangle `t` as the one of each of its vertices.
    fn claim(&mut self, t: u32) {
        for v in self.tris[t as usize] {
            self.vt[v as usize] = t;
        }
    }

    /// Inserts `x` (which must lie in the closed outer triangle) and returns its index; a
    /// point equal to an existing vertex returns that vertex. `on_edge`: `Some(k)` when `x`
    /// is known to lie on the outer triangle's edge `k` (from corner `k` to `k + 1`).
    pub(crate) fn insert(
        &mut self,
        x: Prepared,
        approx: [f64; 3],
        on_edge: Option<usize>,
    ) -> Result<u32, Failed> {
        let x_on = on_edge.map_or(0, |k| 1u8 << k);
        let first_on_edge = self.whole & x_on != 0;
        self.whole &= !x_on;
        if let Some(k) = on_edge.filter(|_| first_on_edge) {
            // Strictly inside an outer edge not split before (a seam point on an edge is
            // not one of its ends): it splits the one triangle along that edge, where the
            // walk below would end, and nothing else.
            let (p, q) = (k as u32, (k as u32 + 1) % 3);
            if let Some((t, s)) = self.tris.iter().enumerate().find_map(|(t, v)| {
                (0..3)
                    .find(|&s| v[s] == p && v[(s + 1) % 3] == q)
                    .map(|s| (t as u32, s))
            }) {
                debug_assert!((1..3).all(|d| {
                    let v = rot(self.tris[t as usize], (s + d) % 3);
                    self.orient_pt(v[0], v[1], &x, x_on) == Sign::Positive
                }));
                let id = self.add_vertex(x, approx, x_on, t);
                self.split_edge(t, s, id);
                self.last = t;
                return Ok(id);
            }
        }
        let mut t = self.last.min(self.tris.len() as u32 - 1);
        let mut steps = 0usize;
        let mut turn = 0usize;
        loop {
            steps += 1;
            if steps > 4 * self.tris.len() + 16 {
                return Err(Failed(FailReason::PointLocationDidNotConverge));
            }
            let v = self.tris[t as usize];
            let o: [Sign; 3] =
                std::array::from_fn(|k| self.orient_pt(v[k], v[(k + 1) % 3], &x, x_on));
            // Leave through a negative edge, starting the search at a rotating slot so that
            // the walk cannot cycle.
            turn += 1;
            if let Some(k) = (0..3)
                .map(|i| (i + turn) % 3)
                .find(|&k| o[k] == Sign::Negative)
            {
                let n = self.nbr[t as usize][k];
                if n == NONE {
                    return Err(Failed(FailReason::PointOutside));
                }
                t = n;
                continue;
            }
            let zeros: Vec<usize> = (0..3).filter(|&k| o[k] == Sign::Zero).collect();
            let id = self.pts.len() as u32;
            match zeros.as_slice() {
                [] => {
                    self.add_vertex(x, approx, x_on, t);
                    self.split_face(t, id);
                }
                [k] => {
                    self.add_vertex(x, approx, x_on, t);
                    self.split_edge(t, *k, id);
                }
                // On two edges: it is their shared corner.
                [0, 1] => return Ok(v[1]),
                [1, 2] => return Ok(v[2]),
                [0, 2] => return Ok(v[0]),
                _ => return Err(Failed(FailReason::DegenerateInTriangulation)),
            }
            self.last = t;
            return Ok(id);
        }
    }

    /// Adds vertex `x` (held by triangle `t`, which the caller splits next) and returns
    /// its index.
    fn add_vertex(&mut self, x: Prepared, approx: [f64; 3], x_on: u8, t: u32) -> u32 {
        self.pts.push(x);
        self.approx.push(approx);
        self.on.push(x_on);
        self.vt.push(t);
        (self.pts.len() - 1) as u32
    }

    fn split_face(&mut self, t: u32, x: u32) {
        let [a, b, c] = self.tris[t as usize];
        let [nab, nbc, nca] = self.nbr[t as usize];
        let [fab, fbc, fca] = self.fixed[t as usize];
        let t1 = self.push([b, c, x], [nbc, NONE, t], [fbc, false, false]);
        let t2 = self.push([c, a, x], [nca, t, t1], [fca, false, false]);
        self.nbr[t1 as usize][1] = t2;
        self.tris[t as usize] = [a, b, x];
        self.nbr[t as usize] = [nab, t1, t2];
        self.fixed[t as usize] = [fab, false, false];
        self.relink(nbc, t, t1);
        self.relink(nca, t, t2);
        for t in [t, t1, t2] {
            self.claim(t);
        }
    }

    fn split_edge(&mut self, t: u32, k: usize, x: u32) {
        self.rotate(t, k);
        let u = self.nbr[t as usize][0];
        let [p, q, r] = self.tris[t as usize];
        let [_, nqr, nrp] = self.nbr[t as usize];
        let [f, fqr, frp] = self.fixed[t as usize];
        // t becomes (p, x, r); tb = (x, q, r).
        let tb = self.push([x, q, r], [NONE, nqr, t], [f, fqr, false]);
        self.tris[t as usize] = [p, x, r];
        self.nbr[t as usize] = [NONE, tb, nrp];
        self.fixed[t as usize] = [f, false, frp];
        self.relink(nqr, t, tb);
        if u != NONE {
            let m = self.slot_of(u, t);
            self.rotate(u, m);
            let [_, _, s] = self.tris[u as usize];
            let [_, nps, nsq] = self.nbr[u as usize];
            let [_, fps, fsq] = self.fixed[u as usize];
            // u = (q, p, s) becomes (x, p, s); ua = (q, x, s).
            let ua = self.push([q, x, s], [tb, u, nsq], [f, false, fsq]);
            self.tris[u as usize] = [x, p, s];
            self.nbr[u as usize] = [t, nps, ua];
            self.fixed[u as usize] = [f, fps, false];
            self.relink(nsq, u, ua);
            self.nbr[t as usize][0] = u;
            self.nbr[tb as usize][0] = ua;
            self.claim(u);
            self.claim(ua);
        }
        self.claim(t);
        self.claim(tb);
    }

    /// Flips the edge in slot `k` of `t`; the caller has checked that the quad is strictly
    /// convex. Returns the two triangles now sharing the new diagonal.
    fn flip(&mut self, t: u32, k: usize) -> (u32, u32) {
        self.rotate(t, k);
        let u = self.nbr[t as usize][0];
        let m = self.slot_of(u, t);
        self.rotate(u, m);
        let [a, b, c] = self.tris[t as usize];
        let [_, nbc, nca] = self.nbr[t as usize];
        let [_, fbc, fca] = self.fixed[t as usize];
        let d = self.tris[u as usize][2];
        let [_, nad, ndb] = self.nbr[u as usize];
        let [_, fad, fdb] = self.fixed[u as usize];
        // t' = (c, a, d), u' = (d, b, c).
        self.tris[t as usize] = [c, a, d];
        self.nbr[t as usize] = [nca, nad, u];
        self.fixed[t as usize] = [fca, fad, false];
        self.tris[u as usize] = [d, b, c];
        self.nbr[u as usize] = [ndb, nbc, t];
        self.fixed[u as usize] = [fdb, fbc, false];
        self.relink(nad, u, t);
        self.relink(nbc, t, u);
        self.claim(t);
        self.claim(u);
        (t, u)
    }

    /// Whether flipping slot `k` of `t` is allowed: interior, unconstrained, strictly convex.
    fn flippable(&self, t: u32, k: usize) -> bool {
        let u = self.nbr[t as usize][k];
        if u == NONE || self.fixed[t as usize][k] {
            return false;
        }
        let v = rot(self.tris[t as usize], k);
        let (a, b, c) = (v[0], v[1], v[2]);
        let m = self.slot_of(u, t);
        let d = rot(self.tris[u as usize], m)[2];
        self.orient(c, a, d) == Sign::Positive && self.orient(d, b, c) == Sign::Positive
    }

    /// The triangles around vertex `v`, in turn; stops early when `f` returns `Some`.
    fn around<R>(&self, v: u32, mut f: impl FnMut(u32, usize) -> Option<R>) -> Option<R> {
        self.ring(v).find_map(|(t, k)| f(t, k))
    }

    /// The triangles around vertex `v` with `v`'s slot in each, in turn.
    fn ring(&self, v: u32) -> Ring<'_> {
        let t0 = self.vt[v as usize];
        Ring {
            local: self,
            v,
            t0,
            t: t0,
            back: false,
        }
    }

    /// The triangle and slot of the edge between `a` and `b` (either direction), if any.
    /// The fans of both ends are walked in turn, so the cost is that of the smaller one:
    /// a corner of the outer triangle joins most of the points on the edge across from it
    /// (a sliver crossed by many segments), and a walk around it alone would visit them
    /// all for each of the edges it holds.
    fn find_edge(&self, a: u32, b: u32) -> Option<(u32, usize)> {
        // In a triangle holding `x` at slot `k`: the slot of its edge to `y`, if it has one.
        let edge_to = |t: u32, k: usize, y: u32| {
            let v = self.tris[t as usize];
            if v[(k + 1) % 3] == y {
                Some((t, k))
            } else if v[(k + 2) % 3] == y {
                Some((t, (k + 2) % 3))
            } else {
                None
            }
        };
        // Each end's fan, the other end, and whether the fan has triangles left.
        let mut rings = [(self.ring(a), b, true), (self.ring(b), a, true)];
        while rings.iter().any(|r| r.2) {
            for (ring, other, left) in rings.iter_mut().filter(|r| r.2) {
                match ring.next() {
                    Some((t, k)) => {
                        if let Some(e) = edge_to(t, k, *other) {
                            return Some(e);
                        }
                    }
                    None => *left = false,
                }
            }
        }
        None
    }

    fn mark_fixed(&mut self, a: u32, b: u32) -> bool {
        let Some((t, k)) = self.find_edge(a, b) else {
            return false;
        };
        self.fixed[t as usize][k] = true;
        let u = self.nbr[t as usize][k];
        if u != NONE {
            let m = self.slot_of(u, t);
            self.fixed[u as usize][m] = true;
        }
        true
    }

    /// The side of vertex `v` of the line of the constraint being inserted, cached.
    fn side(&self, line: (u32, u32), v: u32) -> Sign {
        let c = &self.sides[v as usize];
        if c.0.get() == self.stamp {
            return c.1.get();
        }
        let s = self.orient(line.0, line.1, v);
        c.0.set(self.stamp);
        c.1.set(s);
        s
    }

    /// Whether `b` lies strictly between `a` and `c` on their line (all three collinear).
    fn between(&self, a: u32, b: u32, c: u32) -> bool {
        let k = crate::kernel::longest_axis(&self.approx[a as usize], &self.approx[c as usize]);
        let cmp = |x: u32, y: u32| {
            crate::kernel::cmp_coord_prepared(&self.pts[x as usize], &self.pts[y as usize], k)
        };
        let (x, y) = (cmp(a, b), cmp(b, c));
        x != std::cmp::Ordering::Equal && x == y
    }

    /// Makes segment `p q` (two vertices) an edge of the triangulation: walks from `p`
    /// along the segment through the triangles it crosses (splitting it at vertices that
    /// lie on it), then flips the crossed edges away (Sloan's algorithm). Only the
    /// triangles along the segment are looked at.
    pub(crate) fn constrain(&mut self, p: u32, q: u32) -> Result<(), Failed> {
        if p == q {
            return Ok(());
        }
        // One side cache for the whole line p q: its pieces lie on the same line.
        if self.sides.len() < self.pts.len() {
            self.sides.resize_with(self.pts.len(), || {
                (std::cell::Cell::new(0), std::cell::Cell::new(Sign::Zero))
            });
        }
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.sides.iter().for_each(|c| c.0.set(0));
            self.stamp = 1;
        }
        let line = (p, q);
        let mut from = p;
        let mut guard = 0usize;
        while from != q {
            guard += 1;
            if guard > self.pts.len() + 16 {
                return Err(Failed(FailReason::ConstraintInsertionDidNotConverge));
            }
            if self.mark_fixed(from, q) {
                return Ok(());
            }
            let (to, crossed) = self.walk(line, from, q)?;
            self.flip_away(line, from, to, crossed)?;
            from = to;
        }
        Ok(())
    }

    /// From `from` (a vertex on segment `line`) towards `q`: the first vertex `to` on the
    /// segment after `from` (a vertex lying on it, or `q`) and the edges crossed on the way.
    fn walk(&self, line: (u32, u32), from: u32, q: u32) -> Result<(u32, Vec<(u32, u32)>), Failed> {
        // The triangle of `from`'s fan whose wedge holds the direction to `q`.
        enum Start {
            Vertex(u32),
            Edge(u32, u32, u32),
        }
        let start = self.around(from, |t, k| {
            let v = self.tris[t as usize];
            let (b, c) = (v[(k + 1) % 3], v[(k + 2) % 3]);
            let (sb, sc) = (self.side(line, b), self.side(line, c));
            // Counter-clockwise (from, b, c): the direction is in the wedge when b is right
            // of (or on) the line and c left of (or on) it; a vertex on the line there lies
            // on the segment (the wedge is narrower than a half-turn).
            match (sb, sc) {
                (Sign::Zero, Sign::Positive) => Some(Start::Vertex(b)),
                (Sign::Negative, Sign::Zero) => Some(Start::Vertex(c)),
                (Sign::Negative, Sign::Positive) => Some(Start::Edge(t, b, c)),
                _ => None,
            }
        });
        let (mut t, mut r, mut l) = match start {
            None => return Err(Failed(FailReason::ConstraintMissing)),
            Some(Start::Vertex(v)) => {
                if v != q && !self.between(from, v, q) {
                    return Err(Failed(FailReason::ConstraintMissing));
                }
                return Ok((v, Vec::new()));
            }
            Some(Start::Edge(t, b, c)) => (t, b, c),
        };
        let mut crossed = Vec::new();
        loop {
            let k = (0..3)
                .find(|&k| {
                    let v = self.tris[t as usize];
                    v[k] == r && v[(k + 1) % 3] == l
                })
                .ok_or(Failed(FailReason::ConstraintMissing))?;
            if self.fixed[t as usize][k] {
                return Err(Failed(FailReason::ConstraintsCross));
            }
            crossed.push((r, l));
            let u = self.nbr[t as usize][k];
            if u == NONE {
                return Err(Failed(FailReason::ConstraintMissing));
            }
            let m = self.slot_of(u, t);
            let d = rot(self.tris[u as usize], m)[2];
            if d == q {
                return Ok((q, crossed));
            }
            match self.side(line, d) {
                Sign::Zero => return Ok((d, crossed)),
                Sign::Negative => r = d,
                Sign::Positive => l = d,
            }
            t = u;
        }
    }

    /// Flips the edges `crossed` (each crossing the open segment `from to` of `line`)
    /// until none crosses it, then marks the segment fixed.
    fn flip_away(
        &mut self,
        line: (u32, u32),
        from: u32,
        to: u32,
        crossed: Vec<(u32, u32)>,
    ) -> Result<(), Failed> {
        let limit = 64 * (crossed.len() + 16) * (crossed.len() + 16);
        let mut queue: std::collections::VecDeque<(u32, u32)> = crossed.into();
        let mut guard = 0usize;
        while let Some((a, b)) = queue.pop_front() {
            guard += 1;
            if guard > limit {
                return Err(Failed(FailReason::ConstraintInsertionDidNotConverge));
            }
            let Some((t, k)) = self.find_edge(a, b) else {
                continue;
            };
            if !self.flippable(t, k) {
                queue.push_back((a, b));
                continue;
            }
            let (t, _) = self.flip(t, k);
            // The new diagonal is (c, d): slot 2 of t' = (c, a, d) runs d → c.
            let v = self.tris[t as usize];
            let (c, d) = (v[0], v[2]);
            if c != from
                && c != to
                && d != from
                && d != to
                && self.side(line, c).times(self.side(line, d)) == Sign::Negative
            {
                queue.push_back((c, d));
            }
        }
        if self.mark_fixed(from, to) {
            Ok(())
        } else {
            Err(Failed(FailReason::ConstraintMissing))
        }
    }

    /// Lawson flips towards a Delaunay triangulation of the unconstrained edges. The
    /// in-circle test is approximate and canonical (it only chooses:
    /// [`incircle_canonical`](crate::kernel::incircle_canonical)); validity is the exact convexity test. Each edge is tested
    /// once, then again only when a flip changed a triangle beside it (a stack of edges,
    /// not passes over all of them until none flips).
    pub(crate) fn improve(&mut self) {
        let mut budget = 8 * self.tris.len() + 16;
        // Every inner edge once (from its lower triangle), the first triangle's on top;
        // then after each flip the four edges around the new pair, the only ones whose
        // opposite corners changed.
        let mut pending = std::mem::take(&mut self.pending);
        pending.clear();
        for t in (0..self.tris.len() as u32).rev() {
            for k in (0..3u8).rev() {
                let u = self.nbr[t as usize][k as usize];
                if u != NONE && t < u && !self.fixed[t as usize][k as usize] {
                    pending.push((t, k));
                }
            }
        }
        while let Some((t, k)) = pending.pop() {
            if budget == 0 {
                break;
            }
            if self.wants_flip(t, k as usize) {
                let (t, u) = self.flip(t, k as usize);
                budget -= 1;
                pending.extend([(u, 1), (u, 0), (t, 1), (t, 0)]);
            }
        }
        self.pending = pending;
    }

    /// Whether [`Local::improve`] flips slot `k` of `t`: an inner, unconstrained edge
    /// whose far corner is inside the circle (the cheap approximate choice first), and
    /// the exact test allows the flip.
    fn wants_flip(&self, t: u32, k: usize) -> bool {
        let u = self.nbr[t as usize][k];
        if u == NONE || self.fixed[t as usize][k] {
            return false;
        }
        let (i, j) = ((self.axis + 1) % 3, (self.axis + 2) % 3);
        let xy = |v: u32| [self.approx[v as usize][i], self.approx[v as usize][j]];
        let v = rot(self.tris[t as usize], k);
        let d = rot(self.tris[u as usize], self.slot_of(u, t))[2];
        let ic = incircle_canonical([xy(v[0]), xy(v[1]), xy(v[2]), xy(d)])
            * match self.sign {
                Sign::Negative => -1.0,
                _ => 1.0,
            };
        ic > 0.0 && self.flippable(t, k)
    }

    /// The edges [`Local::improve`] would still flip (none after it, unless its budget ran
    /// out).
    #[cfg(test)]
    pub(crate) fn flips_left(&self) -> usize {
        (0..self.tris.len() as u32)
            .flat_map(|t| (0..3).map(move |k| (t, k)))
            .filter(|&(t, k)| self.wants_flip(t, k))
            .count()
    }
}
