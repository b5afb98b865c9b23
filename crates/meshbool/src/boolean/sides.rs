//! Exact winding numbers on both sides of the patches of a self-arrangement, for
//! [`super::resolve`].
//!
//! The winding number of a mesh made of closed sheets changes by one across each sheet
//! (rising from its front to its back) and nowhere else. A patch (a piece of the arranged
//! mesh between seam edges) is crossed by no other sheet, so the winding number just in
//! front of it is one integer, `front`, and just behind it `front + net`, where `net` is
//! 1 for a patch alone and the net facing of its stack where sheets coincide there.
//!
//! Around a seam edge the triangles that use it, taken in their exact angular order,
//! bound wedges of space; crossing each triangle from wedge to wedge changes the winding
//! number by one, so the `front` of every patch at the edge is known relative to any one
//! of them. The angular order compares far vertices (exact points) against the input
//! planes of the other triangles. Propagated edge by edge (a union-find keeping each
//! patch's offset to its root), this leaves one unknown per connected group of patches,
//! which one ray finds: from outside the mesh along a coordinate axis to a point of one
//! of the group's triangles, counting the input triangles it crosses, with exact tests.
//! No floating-point measure decides anything; where a test is degenerate (the ray
//! through an edge, a far vertex on the edge's line) another ray or the caller's measure
//! is used.

use crate::par::Grain;
use rayon::prelude::*;

use crate::arrange::Arranged;
use crate::bvh::Bvh;
use crate::edges::{EdgeTopology, Roots};
use crate::kernel::{orient2d, orient3d_plane, Point, Sign, Triangle};
use crate::Mesh;

/// Which of several meshes given together (their triangles concatenated) each input
/// triangle belongs to, for a winding number per mesh; [`Inputs::one`] for one mesh.
pub(super) struct Inputs<'a> {
    /// The first triangle of each mesh after the first (ascending).
    starts: &'a [u32],
}

impl<'a> Inputs<'a> {
    /// One mesh: one winding number.
    pub(super) fn one() -> Inputs<'static> {
        Inputs { starts: &[] }
    }

    /// Meshes whose triangles start at `starts` (ascending, the first mesh's `0` left out).
    pub(super) fn starting_at(starts: &'a [u32]) -> Inputs<'a> {
        Inputs { starts }
    }

    /// How many meshes.
    pub(super) fn count(&self) -> usize {
        self.starts.len() + 1
    }

    /// The mesh of input triangle `t`.
    pub(super) fn of(&self, t: u32) -> u32 {
        self.starts.partition_point(|&s| s <= t) as u32
    }
}

/// The winding numbers on both sides of every patch, one per input mesh ([`Inputs`]):
/// patch `p`'s are `[p * n, (p + 1) * n)` for `n` meshes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct PatchSides {
    /// Just in front of the patch (beyond the sheets coincident with it).
    pub(super) front: Vec<i64>,
    /// Behind it minus in front of it: 1 for a patch alone (in its own mesh's winding
    /// number); for a stack of coincident patches, those facing as this one does less
    /// those facing the other way, each in its own mesh's.
    pub(super) net: Vec<i64>,
    /// Whether the patch is the first (lowest id) of its stack of coincident patches (a
    /// patch alone is).
    pub(super) first: Vec<bool>,
    /// Whether the patch's winding numbers are decided: its group of patches (joined
    /// through the fans at seam edges) has a piece of positive area, from which a ray
    /// found the group's values. A patch of zero-area pieces only (seam points that
    /// round to one point) is decided through its group; a group of such patches alone
    /// is not (its values are left at 0).
    pub(super) decided: Vec<bool>,
}

/// +1, −1 or 0.
fn unit(s: Sign) -> i64 {
    match s {
        Sign::Positive => 1,
        Sign::Negative => -1,
        Sign::Zero => 0,
    }
}

/// One use of a seam edge `p → q` (its lower vertex to its higher).
struct Side {
    patch: u32,
    /// The triangle runs `p → q`: its front faces the wedge after it (counter-clockwise
    /// around `p → q`).
    forward: bool,
    /// Its vertex off the edge.
    far: Point,
    /// Its input triangle (the plane it lies in, oriented as it is).
    plane: [[f64; 3]; 3],
    /// The mesh of its input triangle ([`Inputs`]).
    input: u32,
}

impl Side {
    /// `orient3d(p, q, far, w)`: positive where `w` lies counter-clockwise of this side
    /// within half a turn (the triangle `p q far` lies in the input plane, oriented as
    /// the input triangle when the triangle runs `p → q`).
    fn towards(&self, w: &Point) -> Sign {
        let s = orient3d_plane(&self.plane[0], &self.plane[1], &self.plane[2], w);
        if self.forward {
            s
        } else {
            s.reversed()
        }
    }
}

/// The projection that keeps triangle `t` (explicit) non-degenerate ([`Triangle::new`]:
/// the largest normal component first) and the triangle's orientation there (the sign of
/// that normal component); `None` for a degenerate triangle.
fn projection(t: &[[f64; 3]; 3]) -> Option<(usize, Sign)> {
    Triangle::new(*t).map(|s| (s.axis(), s.sign()))
}

/// What a seam edge tells of one of its uses.
#[derive(Clone, Copy, Debug)]
struct Fact {
    patch: u32,
    /// The uses at its angle (coincident sheets), counted from `0` at the edge.
    angle: u32,
    /// Whether another use shares that angle.
    coincident: bool,
}

/// What a seam edge tells of its uses: per use, the winding numbers in front of it
/// relative to the others at the edge and its stack's net facing (1 alone), for each
/// mesh with a triangle at the edge (the others' do not change around it).
struct EdgeFacts {
    /// The meshes with a triangle at the edge ([`Inputs`], ascending).
    inputs: Vec<u32>,
    facts: Vec<Fact>,
    /// Per fact, the `front` then the `net` of each of `inputs`.
    values: Vec<i64>,
}

impl EdgeFacts {
    /// Fact `i`'s front and net, one value per mesh of [`EdgeFacts::inputs`].
    fn values(&self, i: usize) -> (&[i64], &[i64]) {
        let m = self.inputs.len();
        self.values[2 * m * i..2 * m * (i + 1)].split_at(m)
    }
}

/// The facts of seam edge `e`; `None` where a far vertex lies on the edge's line, or the
/// winding numbers around it do not close (not closed sheets).
fn edge_facts(
    arr: &Arranged,
    input: &Mesh,
    inputs: &Inputs,
    topo: &EdgeTopology,
    patch: &[u32],
    e: usize,
) -> Option<EdgeFacts> {
    let [lo, hi] = topo.edges[e];
    let (p, q) = (arr.point(lo), arr.point(hi));
    let sides: Vec<Side> = topo
        .uses_of(e)
        .iter()
        .map(|u| {
            let t = u.triangle as usize;
            let far = arr.mesh.triangles[t][(u.corner as usize + 2) % 3];
            Side {
                patch: patch[t],
                forward: u.forward,
                far: arr.point(far),
                plane: input.corners(arr.parent[t] as usize),
                input: inputs.of(arr.parent[t]),
            }
        })
        .collect();
    // Angular order from the first side: (half-turn, 0 on the first side's ray or the
    // opposite one, else 1).
    let first = &sides[0];
    let (axis, _) = projection(&first.plane)?;
    let sign_on = |w: &Point| orient2d(&p, &q, w, axis);
    let first_on = sign_on(&first.far);
    if first_on == Sign::Zero {
        return None;
    }
    let mut keys = Vec::with_capacity(sides.len());
    for s in &sides {
        keys.push(match first.towards(&s.far) {
            Sign::Positive => (0u8, 1u8),
            Sign::Negative => (1, 1),
            // In the first side's plane: on its ray or the opposite one.
            Sign::Zero => match sign_on(&s.far) {
                Sign::Zero => return None,
                x if x == first_on => (0, 0),
                _ => (1, 0),
            },
        });
    }
    let mut order: Vec<usize> = (0..sides.len()).collect();
    order.sort_by(|&i, &j| {
        keys[i].cmp(&keys[j]).then_with(|| {
            if keys[i].1 == 0 {
                return std::cmp::Ordering::Equal;
            }
            match sides[i].towards(&sides[j].far) {
                Sign::Positive => std::cmp::Ordering::Less,
                Sign::Negative => std::cmp::Ordering::Greater,
                Sign::Zero => std::cmp::Ordering::Equal,
            }
        })
    });
    // Groups of sides at one angle, counter-clockwise.
    let same_angle = |i: usize, j: usize| {
        keys[i] == keys[j] && (keys[i].1 == 0 || sides[i].towards(&sides[j].far) == Sign::Zero)
    };
    let mut groups: Vec<&[usize]> = Vec::new();
    let mut start = 0;
    for k in 1..=order.len() {
        if k == order.len() || !same_angle(order[k - 1], order[k]) {
            groups.push(&order[start..k]);
            start = k;
        }
    }
    // The meshes at the edge, and each side's among them.
    let mut present: Vec<u32> = sides.iter().map(|s| s.input).collect();
    present.sort_unstable();
    present.dedup();
    let m = present.len();
    let slot = |s: &Side| {
        if m == 1 {
            0
        } else {
            present.partition_point(|&k| k < s.input)
        }
    };
    // Winding numbers of the wedges, the wedge after group g at `after[g * m..]`,
    // relative to the wedge before the first group: crossing a side counter-clockwise
    // goes from its back to its front (−1) when it runs p → q, else from its front to its
    // back (+1), in its own mesh's winding number.
    let mut after = Vec::with_capacity(groups.len() * m);
    let mut w = vec![0i64; m];
    for g in &groups {
        for &i in g.iter() {
            w[slot(&sides[i])] += if sides[i].forward { -1 } else { 1 };
        }
        after.extend_from_slice(&w);
    }
    if w.iter().any(|&x| x != 0) {
        return None;
    }
    let mut facts = Vec::with_capacity(sides.len());
    let mut values = Vec::with_capacity(2 * m * sides.len());
    for (gi, g) in groups.iter().enumerate() {
        let before = if gi == 0 {
            &w[..]
        } else {
            &after[(gi - 1) * m..gi * m]
        };
        for &i in g.iter() {
            let s = &sides[i];
            values.extend_from_slice(if s.forward {
                &after[gi * m..(gi + 1) * m]
            } else {
                before
            });
            let net = values.len();
            values.resize(net + m, 0);
            for &j in g.iter() {
                values[net + slot(&sides[j])] += if sides[j].forward == s.forward { 1 } else { -1 };
            }
            facts.push(Fact {
                patch: s.patch,
                angle: gi as u32,
                coincident: g.len() > 1,
            });
        }
    }
    Some(EdgeFacts {
        inputs: present,
        facts,
        values,
    })
}

/// Offsets between patches: a union-find whose nodes keep their value (a vector of `dims`
/// integers) less their parent's, the whole path pointed at the root on each find.
struct Offsets {
    dims: usize,
    parent: Vec<u32>,
    /// Node `x`'s at `[x * dims, (x + 1) * dims)`.
    offset: Vec<i64>,
    /// What [`Offsets::find`] found last.
    found: Vec<i64>,
    /// What [`Offsets::relate`] found of its first node.
    first: Vec<i64>,
    /// What is left of `found` on the way down the path.
    left: Vec<i64>,
}

impl Offsets {
    fn new(n: usize, dims: usize) -> Self {
        Offsets {
            dims,
            parent: (0..n as u32).collect(),
            offset: vec![0; n * dims],
            found: vec![0; dims],
            first: vec![0; dims],
            left: vec![0; dims],
        }
    }

    /// The root of `x`; `value(x) − value(root)` is left in `self.found`. Every node on
    /// the way is pointed at the root.
    fn find(&mut self, x: u32) -> u32 {
        let d = self.dims;
        self.found.fill(0);
        let mut r = x;
        while self.parent[r as usize] != r {
            let own = &self.offset[r as usize * d..(r as usize + 1) * d];
            self.found.iter_mut().zip(own).for_each(|(t, o)| *t += o);
            r = self.parent[r as usize];
        }
        // Down the path again: each node's offset to the root is what is left of the total.
        let mut left = std::mem::take(&mut self.left);
        left.copy_from_slice(&self.found);
        let mut y = x;
        while y != r {
            let up = self.parent[y as usize];
            let own = &mut self.offset[y as usize * d..(y as usize + 1) * d];
            for (o, l) in own.iter_mut().zip(left.iter_mut()) {
                let was = *o;
                *o = *l;
                *l -= was;
            }
            self.parent[y as usize] = r;
            y = up;
        }
        self.left = left;
        r
    }

    /// Records `value(b) − value(a) = d`; false where that contradicts what is known.
    fn relate(&mut self, a: u32, b: u32, d: &[i64]) -> bool {
        let ra = self.find(a);
        std::mem::swap(&mut self.first, &mut self.found);
        let rb = self.find(b);
        // `first`: value(a) − value(ra); `found`: value(b) − value(rb).
        if ra == rb {
            return (0..self.dims).all(|k| self.found[k] - self.first[k] == d[k]);
        }
        // value(rb) − value(ra) = d + oa − ob; the lower id stays the root.
        let (child, sign) = if ra < rb { (rb, 1) } else { (ra, -1) };
        self.parent[child as usize] = ra.min(rb);
        let row = &mut self.offset[child as usize * self.dims..(child as usize + 1) * self.dims];
        for (k, o) in row.iter_mut().enumerate() {
            *o = sign * (d[k] + self.first[k] - self.found[k]);
        }
        true
    }
}

/// A point strictly inside a triangle and on its plane, and the ray to it along an axis
/// from beyond a box: what [`Probe::hit`] tests triangles against.
pub(super) struct Probe {
    /// The axis along which the ray runs (towards −axis), the one that keeps the
    /// triangle's plane widest.
    k: usize,
    /// The sign of the plane's normal along the axis (the triangle's facing).
    facing: Sign,
    /// The point (the plane's over `at`).
    h: Point,
    /// The triangle's rounded centroid, the ray's line in the projection.
    at: Point,
    /// The ray's box: from beyond the box's low side to beyond its high side.
    span: [[f64; 3]; 2],
}

/// What the ray of a [`Probe`] does at one triangle.
enum Hit {
    /// Misses it, runs parallel to it, or meets it on the far side of the point.
    Miss,
    /// Crosses it before the point, changing the winding number by this (towards −axis).
    Before(i64),
    /// Meets it at the point (its plane holds the point).
    At,
    /// Meets it on an edge or corner: no answer.
    Edge,
}

impl Probe {
    /// The probe of a triangle with corners `tri` (exact) in the plane of the explicit
    /// triangle `plane` (oriented as it is), at its rounded centroid `at`, the ray from
    /// beyond `lo`..`hi`; `None` where `at` is not strictly inside the triangle along the
    /// chosen axis, or the box is too large to go beyond.
    pub(super) fn new(
        plane: &[[f64; 3]; 3],
        tri: &[Point; 3],
        at: [f64; 3],
        lo: &[f64; 3],
        hi: &[f64; 3],
    ) -> Option<Probe> {
        let (k, facing) = projection(plane)?;
        let probe = Point::Explicit(at);
        if !(0..3).all(|i| orient2d(&tri[i], &tri[(i + 1) % 3], &probe, k) == facing) {
            return None;
        }
        let pad = |x: f64| 1.0 + x.abs();
        let (mut from, mut to) = (at, at);
        from[k] = lo[k] - pad(lo[k]);
        to[k] = hi[k] + pad(hi[k]);
        if !from[k].is_finite() || !to[k].is_finite() {
            return None;
        }
        Some(Probe {
            k,
            facing,
            h: Point::lpi(from, to, plane[0], plane[1], plane[2]),
            at: probe,
            span: [from, to],
        })
    }

    /// Tests the ray against triangle `sc` (explicit, exact tests).
    fn hit(&self, sc: &[[f64; 3]; 3]) -> Hit {
        let k = self.k;
        let pts = sc.map(Point::Explicit);
        let o = orient2d(&pts[0], &pts[1], &pts[2], k);
        if o == Sign::Zero {
            // Parallel to the ray: not crossed. Where the ray runs in it, it leaves it
            // (and the sheets coplanar with it) through an edge of a triangle that is not
            // parallel, which the test below finds.
            return Hit::Miss;
        }
        let e: [Sign; 3] =
            std::array::from_fn(|i| orient2d(&pts[i], &pts[(i + 1) % 3], &self.at, k));
        if e.contains(&o.reversed()) {
            return Hit::Miss;
        }
        if e.contains(&Sign::Zero) {
            return Hit::Edge;
        }
        match orient3d_plane(&sc[0], &sc[1], &sc[2], &self.h) {
            Sign::Zero => Hit::At,
            // Before the point along the ray (beyond it along the axis), the sign of the
            // point's side times the sign of the normal's axis component is negative;
            // crossing it towards −axis goes from front to back where that component is
            // positive.
            sd if unit(sd) * unit(o) < 0 => Hit::Before(unit(o)),
            _ => Hit::Miss,
        }
    }

    /// The winding number just on the +axis side of the point, of the triangles `tris`
    /// (closed sheets; `own(i)`: the ones whose plane holds the point by construction);
    /// `None` where the ray meets an edge, or another triangle at the point.
    pub(super) fn winding(
        &self,
        tris: impl Iterator<Item = (usize, [[f64; 3]; 3])>,
        own: impl Fn(usize) -> bool,
    ) -> Option<i64> {
        let mut w = [0i64];
        self.winding_into(tris, own, |_| 0, &mut w)?;
        Some(w[0])
    }

    /// [`Probe::winding`] of each of several meshes: the triangles `tris` of mesh
    /// `mesh(i)` count in `w[mesh(i)]` (added to what is there).
    fn winding_into(
        &self,
        tris: impl Iterator<Item = (usize, [[f64; 3]; 3])>,
        own: impl Fn(usize) -> bool,
        mesh: impl Fn(usize) -> usize,
        w: &mut [i64],
    ) -> Option<()> {
        for (i, sc) in tris {
            match self.hit(&sc) {
                Hit::Miss => {}
                Hit::Before(d) => w[mesh(i)] += d,
                Hit::At if own(i) => {}
                Hit::At | Hit::Edge => return None,
            }
        }
        Some(())
    }

    /// The ray's box.
    pub(super) fn span(&self) -> &[[f64; 3]; 2] {
        &self.span
    }
}

/// The winding numbers (one per mesh of `inputs`) in front of triangle `t` of the
/// arrangement (beyond the sheets coincident with it, whose net facing is `net`), by a
/// ray along an axis from beyond the mesh (`lo`, `hi`: the mesh's box) to the point of
/// `t`'s plane over its rounded centroid, crossing the input triangles (exact tests;
/// those in `t`'s plane are its stack and left out); `None` where the point is not
/// strictly inside `t` or the ray meets an edge.
#[allow(clippy::too_many_arguments)]
fn ray(
    arr: &Arranged,
    input: &Mesh,
    inputs: &Inputs,
    index: Option<&Bvh>,
    lo: &[f64; 3],
    hi: &[f64; 3],
    t: usize,
    net: &[i64],
) -> Option<Vec<i64>> {
    let parent = arr.parent[t] as usize;
    let plane = input.corners(parent);
    let tri = arr.mesh.triangles[t].map(|v| arr.point(v));
    let probe = Probe::new(&plane, &tri, arr.mesh.centroid(t), lo, hi)?;
    let found = meeting(input, index, probe.span());
    let mut beyond = vec![0i64; inputs.count()];
    probe.winding_into(
        found
            .iter()
            .map(|&s| (s as usize, input.corners(s as usize))),
        |s| s == parent || crate::arrange::coplanar(input, s as u32, parent as u32),
        |s| inputs.of(s as u32) as usize,
        &mut beyond,
    )?;
    // `beyond`: the winding numbers on t's +axis side; its front is there when its normal
    // points up the axis, else past its stack (rising by `net` from front to back).
    if probe.facing != Sign::Positive {
        beyond.iter_mut().zip(net).for_each(|(b, n)| *b -= n);
    }
    Some(beyond)
}

/// Rays up to which [`patch_sides`] passes over all input triangles for each, rather
/// than building a tree over them.
const FEW_RAYS: usize = 4;

/// The input triangles whose boxes meet box `b`: through `index`, else by a pass over all.
pub(super) fn meeting(input: &Mesh, index: Option<&Bvh>, b: &[[f64; 3]; 2]) -> Vec<u32> {
    match index {
        Some(bvh) => bvh.in_box(input, b),
        None => (0..input.triangles.len() as u32)
            .into_par_iter()
            .grained()
            .with_min_len(1 << 12)
            .filter(|&t| crate::bvh::overlaps(&crate::bvh::tri_box(input, t), b))
            .collect(),
    }
}

/// The winding numbers (one per mesh of `inputs`, the meshes whose concatenation is
/// `input`) on both sides of each of the `count` patches (`patch`: each triangle's) of
/// `arr`, the self-arrangement of `input` (`topo`: its edges); patches whose largest
/// triangle (`largest`: its twice area and id, `usize::MAX` for none of positive area) is
/// none are left at 0. `None` where the exact route does not decide: triangles the
/// arrangement failed to cut, a degenerate fan or ray, a patch on a sheet no seam edge
/// tells of, or winding numbers that contradict one another (not closed sheets).
pub(super) fn patch_sides(
    input: &Mesh,
    inputs: &Inputs,
    arr: &Arranged,
    topo: &EdgeTopology,
    patch: &[u32],
    count: usize,
    largest: &[(f64, usize)],
) -> Option<PatchSides> {
    if !arr.failed.is_empty() {
        return None;
    }
    let n = inputs.count();
    let seams: Vec<usize> = (0..topo.edge_count())
        .filter(|&e| topo.uses_of(e).len() != 2)
        .collect();
    let facts: Vec<EdgeFacts> = seams
        .par_iter()
        .grained()
        .map(|&e| {
            if topo.uses_of(e).len() < 2 {
                return None;
            }
            edge_facts(arr, input, inputs, topo, patch, e)
        })
        .collect::<Option<_>>()?;
    let mut offsets = Offsets::new(count, n);
    let mut net = vec![0i64; count * n];
    let mut known = vec![false; count];
    let mut stacked = vec![false; count];
    // Stacks: patches sharing an angle at some edge (the lowest id the root).
    let mut stacks = Roots::new(count);
    let (mut d, mut dense) = (vec![0i64; n], vec![0i64; n]);
    for f in &facts {
        let (front0, _) = f.values(0);
        let p0 = f.facts[0].patch;
        for (i, x) in f.facts.iter().enumerate() {
            let (front, x_net) = f.values(i);
            let p = x.patch as usize;
            d.fill(0);
            dense.fill(0);
            for (j, &k) in f.inputs.iter().enumerate() {
                d[k as usize] = front[j] - front0[j];
                dense[k as usize] = x_net[j];
            }
            if !offsets.relate(p0, x.patch, &d) {
                return None;
            }
            let row = &mut net[p * n..(p + 1) * n];
            if known[p] {
                if row != &dense[..] {
                    return None;
                }
            } else {
                row.copy_from_slice(&dense);
                known[p] = true;
            }
            if x.coincident {
                stacked[p] = true;
                if let Some(y) = f.facts[..i].iter().rev().find(|y| y.angle == x.angle) {
                    stacks.join(y.patch, x.patch);
                }
            }
        }
    }
    // A patch without seam edges is alone (its ray finds no coincident sheet): 1 in its
    // own mesh's winding number.
    if known.iter().any(|k| !k) {
        for (t, &p) in patch.iter().enumerate() {
            let p = p as usize;
            if !known[p] {
                net[p * n + inputs.of(arr.parent[t]) as usize] = 1;
                known[p] = true;
            }
        }
    }
    // One ray per group of patches, from the group's largest triangles down.
    let crate::Aabb { min: lo, max: hi } = input.bounds()?;
    // Each patch's group (root) and offset to it.
    let mut root_of = vec![0u32; count];
    let mut offset = vec![0i64; count * n];
    for p in 0..count {
        root_of[p] = offsets.find(p as u32);
        offset[p * n..(p + 1) * n].copy_from_slice(&offsets.found);
    }
    let mut members: Vec<Vec<u32>> = vec![Vec::new(); count];
    for (p, &r) in root_of.iter().enumerate() {
        members[r as usize].push(p as u32);
    }
    let roots: Vec<u32> = (0..count as u32)
        .filter(|&r| !members[r as usize].is_empty())
        .collect();
    // A tree pays where there are many rays; a few are cheaper as passes over all.
    let bvh = (roots.len() > FEW_RAYS).then(|| Bvh::new(input));
    const TRIES: usize = 16;
    let root_values: Vec<Option<(u32, Option<Vec<i64>>)>> = roots
        .par_iter()
        .grained()
        .map(|&r| {
            let mut cands: Vec<(bool, f64, u32)> = members[r as usize]
                .iter()
                .filter(|&&p| largest[p as usize].1 != usize::MAX)
                .map(|&p| (stacked[p as usize], -largest[p as usize].0, p))
                .collect();
            if cands.is_empty() {
                // Only zero-area pieces: not decided (dropped by the caller).
                return Some((r, None));
            }
            cands.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)).then(a.2.cmp(&b.2)));
            // Patches alone (no coincident sheet) first, then stacked ones.
            for &(_, _, p) in cands.iter().take(TRIES) {
                let (t, p) = (largest[p as usize].1, p as usize);
                let p_net = &net[p * n..(p + 1) * n];
                if let Some(mut front) = ray(arr, input, inputs, bvh.as_ref(), &lo, &hi, t, p_net) {
                    // value(root) = value(p) − (value(p) − value(root)).
                    let o = &offset[p * n..(p + 1) * n];
                    front.iter_mut().zip(o).for_each(|(f, o)| *f -= o);
                    return Some((r, Some(front)));
                }
            }
            None
        })
        .collect();
    let mut root_value = vec![0i64; count * n];
    let mut root_decided = vec![false; count];
    for v in root_values {
        let (r, value) = v?;
        if let Some(value) = value {
            root_value[r as usize * n..(r as usize + 1) * n].copy_from_slice(&value);
            root_decided[r as usize] = true;
        }
    }
    let first = (0..count as u32).map(|p| stacks.find(p) == p).collect();
    let front = (0..count * n)
        .map(|i| root_value[root_of[i / n] as usize * n + i % n] + offset[i])
        .collect();
    let decided = root_of.iter().map(|&r| root_decided[r as usize]).collect();
    Some(PatchSides {
        front,
        net,
        first,
        decided,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arrange::arrange_self;
    use crate::intersect::{self_intersections, self_seam};

    /// The rays of each triangle of `m` (arranged along its own seam; `net`: the net
    /// facing of the stack of sheets at each), with their triangle's input triangle.
    fn rays_in_stacks(m: &Mesh, net: i64) -> Vec<(u32, Option<i64>)> {
        let seam = self_seam(m, &self_intersections(m));
        let arr = arrange_self(m, &seam);
        let b = m.bounds().unwrap();
        let bvh = Bvh::new(m);
        (0..arr.mesh.triangles.len())
            .map(|t| {
                let one = Inputs::one();
                let direct = ray(&arr, m, &one, None, &b.min, &b.max, t, &[net]);
                let by_tree = ray(&arr, m, &one, Some(&bvh), &b.min, &b.max, t, &[net]);
                assert_eq!(direct, by_tree);
                let direct = direct.map(|w| w[0]);
                (arr.parent[t], direct)
            })
            .collect()
    }

    /// [`rays_in_stacks`] of sheets that coincide nowhere.
    fn rays(m: &Mesh) -> Vec<(u32, Option<i64>)> {
        rays_in_stacks(m, 1)
    }

    /// A box in a box: the winding number in front of the outer box's faces is 0, in
    /// front of the inner one's 1, or 0 when the inner box faces inward (a cavity); boxes
    /// turned about a skew axis so that rays go along no face.
    #[test]
    fn rays_count_the_sheets_they_cross() {
        for cavity in [false, true] {
            let outer = Mesh::cuboid([0.0; 3], [3.0; 3]);
            let inner = Mesh::cuboid([1.0; 3], [2.0; 3]);
            let mut m = outer.clone();
            m.append(&if cavity { inner.flipped() } else { inner })
                .unwrap();
            let m = crate::shapes::rigid_motion(&m, [1.0, 2.0, 3.0], 0.7, [0.1, 0.2, 0.3]);
            let found = rays(&m);
            assert_eq!(found.len(), 24);
            for (parent, front) in found {
                let want = if parent < 12 || cavity { 0 } else { 1 };
                assert_eq!(front, Some(want), "triangle of {parent}, cavity {cavity}");
            }
        }
    }

    /// A box given twice (vertices not shared), or with a reversed copy: every ray meets
    /// the other copy's face in its own triangle's plane, the stack at the point, and
    /// counts neither; in front of each stack is the outside (0), behind it 2 (`net` 2),
    /// or 0 for the box and its reversed copy (`net` 0). Given the wrong `net`, the faces
    /// whose back is up the ray's axis get it wrong.
    #[test]
    fn rays_through_a_coincident_sheet_count_the_stack() {
        let cube = Mesh::cuboid([0.0; 3], [1.0; 3]);
        let cube = crate::shapes::rigid_motion(&cube, [1.0, 2.0, 3.0], 0.7, [0.1, 0.2, 0.3]);
        for (copy, net) in [(cube.clone(), 2), (cube.flipped(), 0)] {
            let mut m = cube.clone();
            m.append(&copy).unwrap();
            let found = rays_in_stacks(&m, net);
            assert_eq!(found.len(), 24);
            assert!(found.iter().all(|(_, f)| *f == Some(0)), "{net} {found:?}");
            let wrong = rays_in_stacks(&m, 1);
            assert!(wrong.iter().any(|(_, f)| *f != Some(0)), "{net} {wrong:?}");
        }
    }

    /// A ray through an edge (a box whose top and bottom are split along crossing
    /// diagonals: the rays up from the centroids of the bottom triangles meet the top's
    /// diagonal) gives no answer; the others give the winding number 0 of the outside.
    #[test]
    fn rays_through_an_edge_give_none() {
        let mut cube = Mesh::cuboid([0.0; 3], [1.0; 3]);
        assert_eq!(cube.triangles[2..4], [[4, 5, 6], [5, 7, 6]]);
        cube.triangles[2] = [4, 5, 7];
        cube.triangles[3] = [4, 7, 6];
        let found = rays(&cube);
        assert_eq!(found[..2], [(0, None), (1, None)]);
        assert!(found[2..].iter().all(|(_, f)| *f == Some(0)), "{found:?}");
    }

    /// A ray that runs in a face along the axis (a second box whose face y = 1/3 holds
    /// the ray from the centroid of the first box's triangle with corners at y = 0, 1, 0
    /// on its face x = 1) gives no answer: it leaves that face through an edge.
    #[test]
    fn rays_along_a_face_give_none() {
        let mut m = Mesh::cuboid([0.0; 3], [1.0; 3]);
        assert_eq!(m.triangles[10], [1, 3, 5]);
        m.append(&Mesh::cuboid([2.0, 1.0 / 3.0, 0.0], [3.0, 1.0, 1.0]))
            .unwrap();
        let found = rays(&m);
        assert_eq!(found[10], (10, None));
        let answered = found.iter().filter(|(_, f)| *f == Some(0)).count();
        assert!(answered >= 20, "{found:?}");
    }

    /// Offsets compose along chains joined in any order, a relation that agrees is
    /// accepted and one that contradicts them is refused.
    #[test]
    fn offsets_compose_and_refuse_contradictions() {
        // Values of two integers: the second is the first times −2, so that a mix-up of
        // the two or of their signs shows.
        let v = |x: i64| [x, -2 * x];
        let mut o = Offsets::new(6, 2);
        let find = |o: &mut Offsets, x: u32| (o.find(x), o.found.clone());
        // value(1) = value(0) + 1, value(3) = value(2) − 4, then join the chains:
        // value(2) = value(1) + 2.
        assert!(o.relate(0, 1, &v(1)));
        assert!(o.relate(3, 2, &v(4)));
        assert!(o.relate(1, 2, &v(2)));
        assert!(o.relate(5, 4, &v(-7)));
        for (x, want) in [(0, 0), (1, 1), (2, 3), (3, -1)] {
            assert_eq!(find(&mut o, x), (0, v(want).to_vec()), "{x}");
        }
        assert_eq!(find(&mut o, 4), (4, v(0).to_vec()));
        assert_eq!(find(&mut o, 5), (4, v(7).to_vec()));
        assert!(o.relate(3, 0, &v(1)));
        assert!(!o.relate(3, 0, &v(2)));
        assert!(!o.relate(3, 0, &[1, 0]));
        assert!(!o.relate(1, 3, &v(0)));
        // Joining the two groups keeps both sides' offsets.
        assert!(o.relate(3, 5, &v(10)));
        assert_eq!(find(&mut o, 5), (0, v(9).to_vec()));
        assert_eq!(find(&mut o, 4), (0, v(2).to_vec()));
    }
}
