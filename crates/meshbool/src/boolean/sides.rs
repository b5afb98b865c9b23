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

use rayon::prelude::*;

use crate::arrange::Arranged;
use crate::bvh::Bvh;
use crate::edges::{EdgeTopology, Roots};
use crate::kernel::{orient2d, orient3d_plane, Point, Sign, Triangle};
use crate::Mesh;

/// The winding numbers on both sides of every patch.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct PatchSides {
    /// Just in front of the patch (beyond the sheets coincident with it).
    pub(super) front: Vec<i64>,
    /// Behind it minus in front of it: 1 for a patch alone; for a stack of coincident
    /// patches, those facing as this one does less those facing the other way.
    pub(super) net: Vec<i64>,
    /// Whether the patch is the first (lowest id) of its stack of coincident patches (a
    /// patch alone is).
    pub(super) first: Vec<bool>,
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
    /// The winding number in front of it, relative to the others at the edge.
    front: i64,
    /// Its stack's net facing (1 alone).
    net: i64,
    /// The uses at its angle (coincident sheets), counted from `0` at the edge.
    angle: u32,
    /// Whether another use shares that angle.
    coincident: bool,
}

type EdgeFacts = Vec<Fact>;

/// The facts of seam edge `e`; `None` where a far vertex lies on the edge's line, or the
/// winding numbers around it do not close (not closed sheets).
fn edge_facts(
    arr: &Arranged,
    input: &Mesh,
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
    // Winding numbers of the wedges, the wedge after group g at `after[g]`, relative to
    // the wedge before the first group: crossing a side counter-clockwise goes from its
    // back to its front (−1) when it runs p → q, else from its front to its back (+1).
    let mut after = Vec::with_capacity(groups.len());
    let mut w = 0i64;
    for g in &groups {
        w += g
            .iter()
            .map(|&i| if sides[i].forward { -1 } else { 1 })
            .sum::<i64>();
        after.push(w);
    }
    if w != 0 {
        return None;
    }
    let mut facts = Vec::with_capacity(sides.len());
    for (gi, g) in groups.iter().enumerate() {
        let before = if gi == 0 { 0 } else { after[gi - 1] };
        for &i in g.iter() {
            let s = &sides[i];
            let front = if s.forward { after[gi] } else { before };
            let net = g
                .iter()
                .map(|&j| if sides[j].forward == s.forward { 1 } else { -1 })
                .sum();
            facts.push(Fact {
                patch: s.patch,
                front,
                net,
                angle: gi as u32,
                coincident: g.len() > 1,
            });
        }
    }
    Some(facts)
}

/// Offsets between patches: a union-find whose nodes keep their value less their
/// parent's (the whole path pointed at the root on each find).
struct Offsets {
    parent: Vec<u32>,
    offset: Vec<i64>,
}

impl Offsets {
    fn new(n: usize) -> Self {
        Offsets {
            parent: (0..n as u32).collect(),
            offset: vec![0; n],
        }
    }

    /// The root of `x` and `value(x) − value(root)`; every node on the way is pointed at
    /// the root.
    fn find(&mut self, x: u32) -> (u32, i64) {
        let (mut r, mut total) = (x, 0i64);
        while self.parent[r as usize] != r {
            total += self.offset[r as usize];
            r = self.parent[r as usize];
        }
        // Down the path again: each node's offset to the root is what is left of the total.
        let (mut y, mut left) = (x, total);
        while y != r {
            let (up, own) = (self.parent[y as usize], self.offset[y as usize]);
            self.parent[y as usize] = r;
            self.offset[y as usize] = left;
            left -= own;
            y = up;
        }
        (r, total)
    }

    /// Records `value(b) − value(a) = d`; false where that contradicts what is known.
    fn relate(&mut self, a: u32, b: u32, d: i64) -> bool {
        let ((ra, oa), (rb, ob)) = (self.find(a), self.find(b));
        if ra == rb {
            return ob - oa == d;
        }
        // value(rb) − value(ra) = d + oa − ob; the lower id stays the root.
        let between = d + oa - ob;
        if ra < rb {
            self.parent[rb as usize] = ra;
            self.offset[rb as usize] = between;
        } else {
            self.parent[ra as usize] = rb;
            self.offset[ra as usize] = -between;
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
        let mut before = 0i64;
        for (i, sc) in tris {
            match self.hit(&sc) {
                Hit::Miss => {}
                Hit::Before(d) => before += d,
                Hit::At if own(i) => {}
                Hit::At | Hit::Edge => return None,
            }
        }
        Some(before)
    }

    /// The ray's box.
    pub(super) fn span(&self) -> &[[f64; 3]; 2] {
        &self.span
    }
}

/// The winding number in front of triangle `t` of the arrangement (beyond the sheets
/// coincident with it, whose net facing is `net`), by a ray along an axis from beyond the
/// mesh (`lo`, `hi`: the mesh's box) to the point of `t`'s plane over its rounded
/// centroid, crossing the input triangles (exact tests; those in `t`'s plane are its
/// stack and left out); `None` where the point is not strictly inside `t` or the ray
/// meets an edge.
fn ray(
    arr: &Arranged,
    input: &Mesh,
    index: Option<&Bvh>,
    lo: &[f64; 3],
    hi: &[f64; 3],
    t: usize,
    net: i64,
) -> Option<i64> {
    let parent = arr.parent[t] as usize;
    let plane = input.corners(parent);
    let tri = arr.mesh.triangles[t].map(|v| arr.point(v));
    let probe = Probe::new(&plane, &tri, arr.mesh.centroid(t), lo, hi)?;
    let found = meeting(input, index, probe.span());
    let beyond = probe.winding(
        found
            .iter()
            .map(|&s| (s as usize, input.corners(s as usize))),
        |s| s == parent || crate::arrange::coplanar(input, s as u32, parent as u32),
    )?;
    // `beyond`: the winding number on t's +axis side; its front is there when its normal
    // points up the axis, else past its stack (rising by `net` from front to back).
    Some(if probe.facing == Sign::Positive {
        beyond
    } else {
        beyond - net
    })
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
            .with_min_len(1 << 12)
            .filter(|&t| crate::bvh::overlaps(&crate::bvh::tri_box(input, t), b))
            .collect(),
    }
}

/// The winding numbers on both sides of each of the `count` patches (`patch`: each
/// triangle's) of `arr`, the self-arrangement of `input` (`topo`: its edges); patches
/// whose largest triangle (`largest`: its twice area and id, `usize::MAX` for none of
/// positive area) is none are left at 0. `None` where the exact
/// route does not decide: triangles the arrangement failed to cut, a degenerate fan or
/// ray, a patch on a sheet no seam edge tells of, or winding numbers that contradict one
/// another (not closed sheets).
pub(super) fn patch_sides(
    input: &Mesh,
    arr: &Arranged,
    topo: &EdgeTopology,
    patch: &[u32],
    count: usize,
    largest: &[(f64, usize)],
) -> Option<PatchSides> {
    if !arr.failed.is_empty() {
        return None;
    }
    let seams: Vec<usize> = (0..topo.edge_count())
        .filter(|&e| topo.uses_of(e).len() != 2)
        .collect();
    let facts: Vec<EdgeFacts> = seams
        .par_iter()
        .map(|&e| {
            if topo.uses_of(e).len() < 2 {
                return None;
            }
            edge_facts(arr, input, topo, patch, e)
        })
        .collect::<Option<_>>()?;
    let mut offsets = Offsets::new(count);
    let mut net: Vec<Option<i64>> = vec![None; count];
    let mut stacked = vec![false; count];
    // Stacks: patches sharing an angle at some edge (the lowest id the root).
    let mut stacks = Roots::new(count);
    for f in &facts {
        let f0 = f[0];
        for (i, x) in f.iter().enumerate() {
            if !offsets.relate(f0.patch, x.patch, x.front - f0.front) {
                return None;
            }
            match net[x.patch as usize] {
                Some(m) if m != x.net => return None,
                _ => net[x.patch as usize] = Some(x.net),
            }
            if x.coincident {
                stacked[x.patch as usize] = true;
                if let Some(y) = f[..i].iter().rev().find(|y| y.angle == x.angle) {
                    stacks.join(y.patch, x.patch);
                }
            }
        }
    }
    // One ray per group of patches, from the group's largest triangles down.
    let crate::Aabb { min: lo, max: hi } = input.bounds()?;
    // Each patch's group (root) and offset to it.
    let found: Vec<(u32, i64)> = (0..count as u32).map(|p| offsets.find(p)).collect();
    let mut members: Vec<Vec<u32>> = vec![Vec::new(); count];
    for (p, &(r, _)) in found.iter().enumerate() {
        members[r as usize].push(p as u32);
    }
    let roots: Vec<u32> = (0..count as u32)
        .filter(|&r| !members[r as usize].is_empty())
        .collect();
    // A tree pays where there are many rays; a few are cheaper as passes over all.
    let bvh = (roots.len() > FEW_RAYS).then(|| Bvh::new(input));
    const TRIES: usize = 16;
    let root_values: Vec<Option<(u32, i64)>> = roots
        .par_iter()
        .map(|&r| {
            let mut cands: Vec<(bool, f64, u32)> = members[r as usize]
                .iter()
                .filter(|&&p| largest[p as usize].1 != usize::MAX)
                .map(|&p| (stacked[p as usize], -largest[p as usize].0, p))
                .collect();
            if cands.is_empty() {
                // Only zero-area pieces: dropped by the caller whatever their sides.
                return Some((r, 0));
            }
            cands.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)).then(a.2.cmp(&b.2)));
            // Patches alone (no coincident sheet) first, then stacked ones.
            for &(_, _, p) in cands.iter().take(TRIES) {
                let t = largest[p as usize].1;
                let n = net[p as usize].unwrap_or(1);
                if let Some(front) = ray(arr, input, bvh.as_ref(), &lo, &hi, t, n) {
                    return Some((r, front - found[p as usize].1));
                }
            }
            None
        })
        .collect();
    let mut root_value = vec![0i64; count];
    for v in root_values {
        let (r, value) = v?;
        root_value[r as usize] = value;
    }
    let first = (0..count as u32).map(|p| stacks.find(p) == p).collect();
    let front = found
        .iter()
        .map(|&(r, o)| root_value[r as usize] + o)
        .collect();
    Some(PatchSides {
        front,
        // A patch without seam edges is alone (its ray found no coincident sheet).
        net: net.into_iter().map(|n| n.unwrap_or(1)).collect(),
        first,
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
                let direct = ray(&arr, m, None, &b.min, &b.max, t, net);
                assert_eq!(direct, ray(&arr, m, Some(&bvh), &b.min, &b.max, t, net));
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
        let mut o = Offsets::new(6);
        // value(1) = value(0) + 1, value(3) = value(2) − 4, then join the chains:
        // value(2) = value(1) + 2.
        assert!(o.relate(0, 1, 1));
        assert!(o.relate(3, 2, 4));
        assert!(o.relate(1, 2, 2));
        assert!(o.relate(5, 4, -7));
        for (x, want) in [(0, 0), (1, 1), (2, 3), (3, -1)] {
            assert_eq!(o.find(x), (0, want), "{x}");
        }
        assert_eq!(o.find(4), (4, 0));
        assert_eq!(o.find(5), (4, 7));
        assert!(o.relate(3, 0, 1));
        assert!(!o.relate(3, 0, 2));
        assert!(!o.relate(1, 3, 0));
        // Joining the two groups keeps both sides' offsets.
        assert!(o.relate(3, 5, 10));
        assert_eq!(o.find(5), (0, 9));
        assert_eq!(o.find(4), (0, 2));
    }
}
