//! Vertex fans certified free of self-intersection: a cheap local proof, per vertex, that
//! no two triangles around the vertex meet anywhere but in the vertex and the edges they
//! share. The self-intersection check then skips every pair of triangles sharing such a
//! vertex (on a smooth mesh most of its candidate pairs) without looking at their corners.
//!
//! The proof: the triangles around `v` form one disk (or half-disk) fan, each edge at `v`
//! used once in each direction, and seen along one coordinate axis (the one nearest the
//! fan's mean normal) every fan triangle keeps its orientation and the fan's wedges at
//! `v` turn around it less than once (open fan) or exactly once (closed fan). The
//! projection maps each triangle one-to-one onto its wedge, and wedges of triangles that
//! are not neighbours in the fan meet only at `v`, neighbours' only along the image of
//! their shared edge; so the triangles themselves meet only in `v` or in the shared edge.
//!
//! Every sign is an exact `orient2d` in that projection (a floating-point filter with an
//! exact fallback), so the certificate is exact: a fan it cannot vouch for (a sharp
//! corner whose triangles face more than 90 degrees apart, a fold, a non-manifold vertex)
//! is simply not certified, and the pairs around it go to the exact tests.
//!
//! A fan that is not certified whole may still have certified *runs*: stretches of
//! consecutive triangles in one plane (exact `orient3d`; the plane's faces of a CAD
//! part meeting at a sharp corner) whose wedges, seen along the plane's nearest axis,
//! each turn counter-clockwise and together less than once. The same argument holds
//! within a run: two of its triangles meet only in `v` or their shared edge. A fanned
//! cap (an extruded profile's, every triangle from one corner of the outline) is one such
//! run around its corner, whose other triangles are the walls at right angles to it.
//!
//! The certificate is given per corner (3 × triangle + corner): the run the corner's
//! triangle is in around the corner's vertex, named by the run's least corner (unique
//! over the mesh), or [`NO_RUN`]. Two triangles sharing a vertex are settled where their
//! corners there name the same run.

use std::sync::atomic::AtomicU32;
use std::sync::atomic::Ordering::Relaxed;

use crate::par::Grain;
use rayon::prelude::*;

use crate::kernel::{orient2d_inputs, orient3d_explicit, robust_safe, Sign};
use crate::vec3::{cross, sub};
use crate::Mesh;

/// A corner in no certified run.
pub(crate) const NO_RUN: u32 = u32::MAX;

/// For every vertex of `m`, whether its fan is certified whole (see the module text).
/// Vertices on no triangle are certified trivially (nothing to skip).
#[cfg(test)]
pub(crate) fn certified(m: &Mesh) -> Vec<bool> {
    let run = runs(m);
    let mut first = vec![None; m.positions.len()];
    let mut whole = vec![true; m.positions.len()];
    for (c, &r) in run.iter().enumerate() {
        let v = m.triangles[c / 3][c % 3] as usize;
        whole[v] &= r != NO_RUN && *first[v].get_or_insert(r) == r;
    }
    whole
}

/// For every corner of `m` (3 × triangle + corner), the certified run it is in around its
/// vertex, or [`NO_RUN`] (see the module text). A fan certified whole is one run.
pub(crate) fn runs(m: &Mesh) -> Vec<u32> {
    if m.triangles.len() >= (u32::MAX / 3) as usize {
        return vec![NO_RUN; 3 * m.triangles.len()];
    }
    let (start, slots) = corners_at_vertices(m);
    runs_where(m, &start, &slots, |_| true)
}

/// [`runs`] from the corners at each vertex (`start`, `slots`: [`corners_at_vertices`]),
/// certifying only the fans of the vertices `v` where `wanted(v)`; the others' corners are
/// in no run. (The check does not want the fans inside a certified patch.)
pub(crate) fn runs_where(
    m: &Mesh,
    start: &[u32],
    slots: &[u32],
    wanted: impl Fn(usize) -> bool + Sync,
) -> Vec<u32> {
    if m.triangles.len() >= (u32::MAX / 3) as usize {
        // Corner numbers would not fit in 32 bits: certify nothing (all pairs exact).
        return vec![NO_RUN; 3 * m.triangles.len()];
    }
    // Each corner is at one vertex: its run is written once, by that vertex's fan.
    let run: Vec<AtomicU32> = (0..slots.len()).map(|_| AtomicU32::new(NO_RUN)).collect();
    (0..m.positions.len())
        .into_par_iter()
        .grained()
        .filter(|&v| wanted(v))
        .for_each_init(Scratch::default, |s, v| {
            let fan = &slots[start[v] as usize..start[v + 1] as usize];
            s.certify(m, v as u32, fan, &run);
        });
    run.into_iter().map(AtomicU32::into_inner).collect()
}

/// The corners (3 × triangle + corner) at each vertex of `m`, as offsets (`start[v]..start[v
/// + 1]`, one more than there are vertices) into one list, gathered in parallel: counts,
/// offsets, then each corner claims a slot. The order within a vertex's slots varies from
/// call to call. `m` has fewer than `u32::MAX / 3` triangles.
pub(crate) fn corners_at_vertices(m: &Mesh) -> (Vec<u32>, Vec<u32>) {
    let nv = m.positions.len();
    let count: Vec<AtomicU32> = (0..nv).map(|_| AtomicU32::new(0)).collect();
    m.triangles.par_iter().grained().for_each(|t| {
        for &v in t {
            count[v as usize].fetch_add(1, Relaxed);
        }
    });
    let mut start = Vec::with_capacity(nv + 1);
    let mut sum = 0u32;
    start.push(0);
    for c in &count {
        sum += c.load(Relaxed);
        start.push(sum);
    }
    let cursor: Vec<AtomicU32> = start[..nv].iter().map(|&s| AtomicU32::new(s)).collect();
    let slots: Vec<AtomicU32> = (0..sum).map(|_| AtomicU32::new(0)).collect();
    m.triangles
        .par_iter()
        .grained()
        .enumerate()
        .for_each(|(i, t)| {
            for (k, &v) in t.iter().enumerate() {
                let at = cursor[v as usize].fetch_add(1, Relaxed);
                slots[at as usize].store(3 * i as u32 + k as u32, Relaxed);
            }
        });
    (start, slots.into_iter().map(AtomicU32::into_inner).collect())
}

/// Per-thread buffers for one fan.
#[derive(Default)]
struct Scratch {
    /// The fan's triangles as (from, to, corner) sorted by `from`: the corner's triangle
    /// leads from rim vertex `from` to `to` around the fan's vertex.
    sorted: Vec<[u32; 3]>,
    /// The fan's corners in rim order (`corners[i]`: the wedge from `rim[i]` to
    /// `rim[i + 1]`).
    corners: Vec<u32>,
    /// The fan's `to` corners, sorted.
    ends: Vec<u32>,
    /// The fan's rim vertices in order.
    rim: Vec<u32>,
    /// Their positions.
    pts: Vec<[f64; 3]>,
}

impl Scratch {
    /// Certifies the fan of `v` and writes its corners' runs into `run`; `fan` holds its
    /// corners (3 × triangle + corner) in any order.
    fn certify(&mut self, m: &Mesh, v: u32, fan: &[u32], run: &[AtomicU32]) {
        self.sorted.clear();
        self.sorted.extend(fan.iter().map(|&c| {
            let (t, k) = (m.triangles[c as usize / 3], c as usize % 3);
            [t[(k + 1) % 3], t[(k + 2) % 3], c]
        }));
        // A run is named by its least corner.
        let name = |corners: &[u32]| {
            let least = corners.iter().copied().min().unwrap_or(NO_RUN);
            for &c in corners {
                run[c as usize].store(least, Relaxed);
            }
        };
        if let [[a, b, c]] = self.sorted[..] {
            if a != v && b != v && a != b {
                name(&[c]);
            }
            return;
        }
        if fan.is_empty() || !self.chain(v) {
            return;
        }
        let p = m.positions[v as usize];
        self.pts.clear();
        self.pts
            .extend(self.rim.iter().map(|&w| m.positions[w as usize]));
        let (pts, corners) = (&self.pts, &self.corners);
        let w = corners.len();
        if wedges_certified(p, pts, w) {
            name(corners);
            return;
        }
        // Runs in one plane: wedges `k` and `k + 1` are in one plane where the rim's
        // points `k..k + 3` are coplanar with `p`. A closed fan's runs are counted from a
        // wedge where the plane changes, so that none wraps past the start.
        let n = pts.len();
        let at = |k: usize| &pts[k % n];
        let joined = |k: usize| orient3d_explicit(&p, at(k), at(k + 1), at(k + 2)) == Sign::Zero;
        let closed = n == w;
        let start = if closed {
            match (0..w).find(|&k| !joined(k)) {
                Some(k) => k + 1,
                None => return, // one plane all round, and not certified whole
            }
        } else {
            0
        };
        let (mut group, mut members): (Vec<[f64; 3]>, Vec<u32>) = (Vec::new(), Vec::new());
        let mut t = 0;
        while t < w {
            let mut end = t + 1;
            while end < w && joined(start + end - 1) {
                end += 1;
            }
            if end - t >= 2 {
                group.clear();
                group.extend((t..=end).map(|k| *at(start + k)));
                if wedges_certified(p, &group, end - t) {
                    members.clear();
                    members.extend((t..end).map(|k| corners[(start + k) % w]));
                    name(&members);
                }
            }
            t = end;
        }
    }

    /// Orders the fan into `rim` and `corners`: each triangle (v, a, b) leads from `a` to
    /// `b`, and the next one starts at `b`; `corners[i]` is the corner of the triangle
    /// from `rim[i]`. False unless the fan is one chain (open: from the one `a` no
    /// triangle ends at, rim has a vertex more than the fan has triangles) or one cycle
    /// through all of it, with no edge at `v` used twice in the same direction.
    fn chain(&mut self, v: u32) -> bool {
        self.sorted.sort_unstable();
        let fan_len = self.sorted.len();
        self.ends.clear();
        self.ends.extend(self.sorted.iter().map(|e| e[1]));
        self.ends.sort_unstable();
        let repeated = |xs: &[u32]| xs.windows(2).any(|w| w[0] == w[1]);
        if self.sorted.iter().any(|&[a, b, _]| a == v || b == v || a == b)
            || self.sorted.windows(2).any(|w| w[0][0] == w[1][0])
            || repeated(&self.ends)
        {
            return false;
        }
        // Starts and ends are each distinct: following `next` never branches. An open
        // fan has exactly one start that is no end.
        let mut first = self.sorted[0][0];
        let mut opens = 0;
        for e in &self.sorted {
            if self.ends.binary_search(&e[0]).is_err() {
                first = e[0];
                opens += 1;
            }
        }
        if opens > 1 {
            return false;
        }
        let sorted = &self.sorted;
        let next = |a: u32| {
            sorted
                .binary_search_by_key(&a, |e| e[0])
                .ok()
                .map(|i| sorted[i])
        };
        self.rim.clear();
        self.corners.clear();
        let mut at = first;
        self.rim.push(at);
        for _ in 0..fan_len {
            match next(at) {
                // A closed walk back at its start before using every triangle: more
                // than one cycle.
                Some(_) if opens == 0 && self.rim.len() > 1 && at == first => return false,
                Some([_, b, c]) => {
                    at = b;
                    self.rim.push(b);
                    self.corners.push(c);
                }
                None => return false,
            }
        }
        if opens == 0 {
            // One cycle through every triangle: back at the start, which is not repeated.
            self.rim.pop();
            at == first
        } else {
            // The walk from the open start cannot revisit a vertex (ends are distinct and
            // the start is no end), so it used every triangle.
            true
        }
    }
}

/// Whether the `wedges` wedges at `p` between consecutive points of `pts` (closed when
/// there are as many as points: the last one back to the first) are certified: seen
/// along the coordinate axis nearest their mean normal, they turn around `p` exactly once
/// (closed) or less than once (open), each counter-clockwise ([`turns_once`]).
fn wedges_certified(p: [f64; 3], pts: &[[f64; 3]], wedges: usize) -> bool {
    // The mean normal (area-weighted): the axis it is closest to, and which way.
    let mut n = [0.0; 3];
    for i in 0..wedges {
        let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
        let c = cross(&sub(&a, &p), &sub(&b, &p));
        n = [n[0] + c[0], n[1] + c[1], n[2] + c[2]];
    }
    let Some(axis) = (0..3)
        .filter(|&k| n[k].is_finite() && n[k] != 0.0)
        .max_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
    else {
        return false;
    };
    let flip = if n[axis] > 0.0 {
        Sign::Positive
    } else {
        Sign::Negative
    };
    turns_once(p, pts, wedges, axis, flip)
}

/// Whether, seen along `axis` (from its `flip` side), the `wedges` wedges at `p` between
/// consecutive points of `pts` each turn counter-clockwise and together turn around `p`
/// exactly once (closed: as many wedges as points) or less than once (open: a point
/// more). With `s_i` the orientation of (p, E_i, E_0) for rim point E_i: a wedge passes
/// over E_0's direction exactly where `s` goes from + to −, which must happen nowhere
/// before the (closed) fan's last wedge returns to E_0; a rim point in E_0's own
/// direction is a full turn. (`s` = 0 opposite E_0 is a half turn: a wedge, under 180
/// degrees, cannot reach E_0's direction from there, nor arrive there from beyond it.)
fn turns_once(p: [f64; 3], pts: &[[f64; 3]], wedges: usize, axis: usize, flip: Sign) -> bool {
    // Shewchuk's predicate directly where its range holds for the whole fan (almost
    // always), the kernel's general one otherwise.
    let safe = robust_safe(&[&p]) && pts.iter().all(|q| robust_safe(&[q]));
    let orient = |i: usize, j: usize| orient2d_inputs(&p, &pts[i], &pts[j], axis, safe).times(flip);
    let n = pts.len();
    if (0..wedges).any(|i| orient(i, (i + 1) % n) != Sign::Positive) {
        return false;
    }
    // A coordinate of the projection plane along which E_0 leaves `p` (it does: the
    // first wedge is not degenerate).
    let e0 = pts[0];
    let Some(c) = [(axis + 1) % 3, (axis + 2) % 3]
        .into_iter()
        .find(|&c| e0[c] != p[c])
    else {
        return false;
    };
    let mut prev = Sign::Negative; // s_1, by the first wedge
    for (i, e) in pts.iter().enumerate().skip(2) {
        let s = orient(i, 0);
        if s == Sign::Zero {
            // On E_0's line: in its direction when on the same side along `c`.
            if (e[c] > p[c]) == (e0[c] > p[c]) {
                return false;
            }
        }
        if prev == Sign::Positive && s == Sign::Negative {
            return false;
        }
        prev = s;
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::{heightfield, torus, uv_sphere};

    /// A fan (closed, or open from the first rim point to the last) around an apex at
    /// `apex` over `rim` (points in the plane z = 0, in the given order); vertex 0 is
    /// the apex.
    fn fan(apex: [f64; 3], rim: &[[f64; 2]], closed: bool) -> Mesh {
        let mut positions = vec![apex];
        positions.extend(rim.iter().map(|p| [p[0], p[1], 0.0]));
        let n = rim.len() as u32;
        let wedges = if closed { n } else { n - 1 };
        let triangles = (0..wedges).map(|k| [0, 1 + k, 1 + (k + 1) % n]).collect();
        Mesh::new_unchecked(positions, triangles)
    }

    fn circle(angles_deg: &[f64]) -> Vec<[f64; 2]> {
        angles_deg
            .iter()
            .map(|a| [a.to_radians().cos(), a.to_radians().sin()])
            .collect()
    }

    #[test]
    fn smooth_and_flat_fans_are_certified() {
        for m in [
            uv_sphere([0.0; 3], 1.0, 24, 12),
            torus([0.0; 3], 2.0, 0.5, 24, 12),
            heightfield([0.0, 0.0], [1.0, 1.0], 6, 5, |x, y| 0.1 * x * y),
        ] {
            let ok = certified(&m);
            let bad: Vec<usize> = (0..ok.len()).filter(|&v| !ok[v]).collect();
            assert!(bad.is_empty(), "{bad:?} of {}", ok.len());
        }
        // Closed fans: a low cone, a flat one, one with a wedge of nearly 180 degrees.
        let regular = circle(&[0.0, 72.0, 144.0, 216.0, 288.0]);
        assert!(certified(&fan([0.0, 0.0, 0.2], &regular, true))[0]);
        assert!(certified(&fan([0.0, 0.0, 0.0], &regular, true))[0]);
        let wide = circle(&[0.0, 179.0, 270.0]);
        assert!(certified(&fan([0.0, 0.0, 0.0], &wide, true))[0]);
        // Open fans turning less than once, up to nearly all the way round.
        let open = circle(&[0.0, 90.0, 180.0, 270.0, 350.0]);
        assert!(certified(&fan([0.0, 0.0, 0.1], &open, false))[0]);
        // Huge and tiny coordinates, far from the origin: still decided.
        for (scale, offset) in [(1e-150, 0.0), (1e120, 0.0), (1.0, 5e6)] {
            let mut m = fan([0.0, 0.0, 0.2], &regular, true);
            for p in &mut m.positions {
                *p = p.map(|x| x * scale + offset);
            }
            assert!(certified(&m)[0], "{scale} {offset}");
        }
    }

    #[test]
    fn fans_that_overlap_or_may_are_not_certified() {
        // A rim visiting the circle as a pentagram: every wedge is under 180 degrees but
        // the fan winds twice.
        let twice = circle(&[0.0, 144.0, 288.0, 72.0, 216.0]);
        assert!(!certified(&fan([0.0, 0.0, 0.2], &twice, true))[0]);
        assert!(!certified(&fan([0.0, 0.0, 0.0], &twice, true))[0]);
        // An open fan going past a full turn (a spiral ramp seen from above), and one
        // ending exactly where it began.
        let past = circle(&[0.0, 100.0, 200.0, 300.0, 40.0]);
        assert!(!certified(&fan([0.0, 0.0, 0.1], &past, false))[0]);
        let full = circle(&[0.0, 120.0, 240.0, 0.0]);
        let mut m = fan([0.0, 0.0, 0.1], &full, false);
        m.positions[4][2] = 0.5;
        assert!(!certified(&m)[0]);
        // A flat fan with one wedge folded over its neighbour.
        let folded = circle(&[0.0, 90.0, 60.0, 180.0, 270.0]);
        assert!(!certified(&fan([0.0, 0.0, 0.0], &folded, true))[0]);
        let regular = circle(&[0.0, 72.0, 144.0, 216.0, 288.0]);
        // Not one fan: two cones sharing their apex, a triangle used twice, a repeated
        // corner, an edge used twice in the same direction.
        let mut cones = fan([0.0; 3], &regular, true);
        let n = cones.positions.len() as u32;
        cones
            .positions
            .extend(regular.iter().map(|p| [p[0], p[1], 1.0]));
        cones
            .triangles
            .extend((0..5).map(|k| [0, n + (k + 1) % 5, n + k]));
        assert!(!certified(&cones)[0]);
        let mut doubled = fan([0.0, 0.0, 0.2], &regular, true);
        doubled.triangles.push(doubled.triangles[0]);
        assert!(!certified(&doubled)[0]);
        let mut repeated = fan([0.0, 0.0, 0.2], &regular, true);
        repeated.triangles[2] = [0, 3, 3];
        assert!(!certified(&repeated)[0]);
        let mut flipped = fan([0.0, 0.0, 0.2], &regular, true);
        flipped.triangles[1] = [0, 3, 2];
        assert!(!certified(&flipped)[0]);
        // A zero-area wedge.
        let mut thin = fan([0.0, 0.0, 0.0], &regular, true);
        thin.positions[2] = thin.positions[1];
        assert!(!certified(&thin)[0]);
        // A cube's corners: their three faces are 90 degrees apart, so no axis sees all
        // of them face on (left to the exact pair tests, not wrongly certified).
        assert!(certified(&Mesh::unit_cube()).iter().all(|&ok| !ok));
    }
}
