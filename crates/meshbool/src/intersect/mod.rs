//! Intersection of two meshes: the seam (every point and segment where their surfaces
//! meet, found exactly), and the seam chained into polylines (`curves`).
//!
//! Pipeline position: broad phase ([`crate::bvh`]) → exact triangle–triangle tests
//! ([`tritri`]) → seam points named by [`Label`]s (so the same point reached from several
//! triangle pairs is one point) → segments. The arrangement stage consumes the seam; the
//! curves are also useful on their own (`meshbool curves`).

use crate::par::Grain;
use rayon::prelude::*;
use rustc_hash::{FxHashMap, FxHashSet};

use crate::broad::Slivers;
use crate::bvh::Bvh;
use crate::kept::Keeps;
use crate::kernel::{cross_sign, same_plane_same_facing, Enclosure, Point, Sign};
use crate::Mesh;

mod curves;
mod fans;
mod patches;
#[doc(hidden)]
pub mod tritri;

#[cfg(feature = "internals")]
pub use curves::Polyline;
pub use curves::{chain, PolylineXyz};
use tritri::Piece;
pub use tritri::{Feature, Label, TriTri};

/// One of the two input meshes: the first (A) or the second (B) of a seam, boolean or
/// split.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum Source {
    /// The first input.
    A,
    /// The second input.
    B,
}

/// One seam segment between two distinct seam points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SeamSegment {
    /// Seam point ids (indices into [`Seam::points`]), in ascending order.
    pub ends: [u32; 2],
    /// True when the segment comes from coplanar triangles (a boundary or crossing edge of
    /// a shared region) rather than from surfaces that cross.
    pub coplanar: bool,
}

/// Where a seam segment lies: in the closure of triangle `tri_a` of A and `tri_b` of B.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SegmentSource {
    /// Index into [`Seam::segments`].
    pub segment: u32,
    /// Triangle of mesh A.
    pub tri_a: u32,
    /// Triangle of mesh B.
    pub tri_b: u32,
}

/// The intersection of two meshes.
#[derive(Clone, Debug, Default)]
pub struct Seam {
    /// Every seam point, by label (unique).
    pub points: Vec<Label>,
    /// Exact constructions of the points (same order).
    pub exact: Vec<Point>,
    /// Approximate coordinates of the points (same order), for output only.
    pub positions: Vec<[f64; 3]>,
    /// Interval enclosures of the points (same order, or empty), evaluated once for the
    /// arrangements of both meshes.
    pub(crate) enclosures: Vec<Enclosure>,
    /// Distinct seam segments.
    pub segments: Vec<SeamSegment>,
    /// Every triangle pair each segment was found in (a segment along an edge lies in
    /// several triangles).
    pub sources: Vec<SegmentSource>,
    /// Points where the meshes only touch (not on any segment).
    pub touching: Vec<u32>,
    /// Degenerate (zero-area) triangles of A and of B among the broad-phase candidates,
    /// left out of the test (degenerate triangles elsewhere touch nothing).
    pub degenerate: [usize; 2],
    /// Triangle pairs whose boxes overlapped (broad-phase candidates).
    pub candidate_pairs: usize,
    /// True when the candidates came from the grid broad phase ([`crate::broad`]), false
    /// when from two trees.
    pub from_grid: bool,
    /// Of a mesh's own seam ([`self_seam`]): each vertex that lies on an edge or in the
    /// face of another of the mesh's triangles, with that feature (sorted, unique). The
    /// labels name such a point by the vertex alone; the arrangement inserts the vertex
    /// into those features. Empty for the seam of two meshes.
    pub vertex_on: Vec<(u32, Feature)>,
    /// The triangles of A and of B among the broad-phase candidates (each once), where
    /// known: every triangle with a seam point in its closure is one of them.
    pub(crate) near: Option<[Vec<u32>; 2]>,
}

impl Seam {
    /// The enclosure of point `s`, when the seam has one for every point.
    pub(crate) fn enclosure(&self, s: usize) -> Option<Enclosure> {
        if self.enclosures.len() == self.exact.len() {
            self.enclosures.get(s).cloned()
        } else {
            None
        }
    }

    /// The enclosures and approximate positions of the exact points.
    fn locate(&mut self) {
        self.enclosures = self.exact.par_iter().grained().map(Enclosure::of).collect();
        self.positions = self
            .exact
            .par_iter()
            .grained()
            .zip(&self.enclosures)
            .map(|(p, e)| p.approx_within(e))
            .collect();
    }
}

/// The canonical exact construction of a labelled seam point.
#[doc(hidden)]
pub fn label_point(l: &Label, a: &Mesh, b: &Mesh) -> Point {
    let pa = |v: u32| a.positions[v as usize];
    let pb = |v: u32| b.positions[v as usize];
    match (l.a, l.b) {
        (Feature::Vertex(v), _) => Point::Explicit(pa(v)),
        (_, Feature::Vertex(v)) => Point::Explicit(pb(v)),
        (Feature::Edge(u, v), Feature::Face(t)) => {
            let [x, y, z] = b.corners(t as usize);
            Point::lpi(pa(u), pa(v), x, y, z)
        }
        (Feature::Face(t), Feature::Edge(u, v)) => {
            let [x, y, z] = a.corners(t as usize);
            Point::lpi(pb(u), pb(v), x, y, z)
        }
        (Feature::Edge(u, v), Feature::Edge(r, s)) => {
            let (p, q, r, s) = (pa(u), pa(v), pb(r), pb(s));
            // Crossing edges span a plane; intersect in a projection where it is not edge-on.
            let axis = (0..3)
                .find(|&k| cross_sign(&p, &q, &r, &s, k) != Sign::Zero)
                .unwrap_or(2);
            Point::ssi(p, q, r, s, axis as u8)
        }
        (Feature::Face(_), Feature::Face(_)) => {
            unreachable!("two faces do not meet in a single point")
        }
    }
}

/// From this many triangles in both meshes together, candidate pairs come from
/// [`crate::broad`] (a pass over each mesh, then work only near the other mesh); below, from
/// two trees ([`Bvh`]), which cost less to set up. Both give the same sorted pairs. Measured
/// crossover: about 50k triangles per sphere (BENCHMARKS.md).
pub const GRID_FROM: usize = 100_000;

fn tri(m: &Mesh, t: usize) -> Option<tritri::Tri> {
    tritri::Tri::new(t as u32, m.triangles[t], m.corners(t))
}

/// Intersects meshes `a` and `b` exactly. Inputs must be valid ([`Mesh::validate`]) and
/// should be welded ([`crate::weld_exact`]): points are named by vertex ids, so two vertices
/// at the same position would name one point twice and break the curves there.
/// Degenerate triangles are left out and counted in [`Seam::degenerate`]. Threads as
/// [`crate::boolean::boolean`]'s. Coplanar overlaps meet along their boundaries, not along
/// the edges of either triangulation inside them ([`intersect_coplanar`] for those too).
// The library itself asks through `intersect_coplanar`; this is for tests and benches.
#[cfg_attr(not(any(test, feature = "internals")), allow(dead_code))]
pub fn intersect(a: &Mesh, b: &Mesh) -> Seam {
    intersect_coplanar(a, b, false)
}

/// [`intersect`], and with `refinement` coplanar overlaps cut along every edge of either
/// mesh that crosses them (the common refinement of both triangulations there) instead of
/// along the overlaps' boundaries only ([`Needed`]).
pub fn intersect_coplanar(a: &Mesh, b: &Mesh, refinement: bool) -> Seam {
    let triangles = a.triangles.len() + b.triangles.len();
    crate::par::run_for(triangles, || {
        intersect_with(a, b, GRID_FROM, [None, None], refinement)
    })
}

/// [`intersect_coplanar`], with candidate pairs from the grid from `grid_from` triangles
/// in both meshes together ([`GRID_FROM`] by default; tests set it to force either path),
/// and below from the whole trees `kept` keeps of `a` and `b` where they have them (and
/// with their slivers, [`crate::broad::Slivers`], where they keep those).
pub(crate) fn intersect_with(
    a: &Mesh,
    b: &Mesh,
    grid_from: usize,
    kept: [Option<&Keeps>; 2],
    refinement: bool,
) -> Seam {
    let from_grid = a.triangles.len() + b.triangles.len() >= grid_from;
    let pairs = candidate_pairs(a, b, from_grid, kept);
    // Set up every candidate triangle once (`slot[t]`: where triangle `t` is set up); the
    // degenerate ones are left out of the test and counted. Degenerate triangles elsewhere
    // cannot touch the other mesh and change nothing.
    type SetUp = (Vec<u32>, Vec<Option<tritri::Tri>>, Vec<u32>);
    let prepare = |m: &Mesh, mut ids: Vec<u32>| -> SetUp {
        let mut slot = crate::par::filled(u32::MAX, m.triangles.len());
        if ids.len() < 1 << 16 {
            // Few: each triangle once, in the order first met, told by its slot (a pass
            // where a sort would be the larger part of this step).
            let mut k = 0;
            ids.retain(|&t| {
                let s = &mut slot[t as usize];
                let first = *s == u32::MAX;
                if first {
                    *s = k;
                    k += 1;
                }
                first
            });
        } else {
            ids.par_sort_unstable();
            ids.dedup();
            for (k, &t) in ids.iter().enumerate() {
                slot[t as usize] = k as u32;
            }
        }
        let tris = ids
            .par_iter()
            .grained()
            .map(|&t| tri(m, t as usize))
            .collect();
        (slot, tris, ids)
    };
    let ((slot_a, tris_a, near_a), (slot_b, tris_b, near_b)) = crate::par::join(
        || prepare(a, pairs.iter().map(|p| p.0).collect()),
        || prepare(b, pairs.iter().map(|p| p.1).collect()),
    );
    // The pieces each pair shares, a block of pairs at a time (in pair order: the seam's
    // points are numbered in the order they are first met). Coplanar pairs' pieces are
    // made in place, with no allocation per pair. In rounds: once a round has met a
    // coplanar pair's segment, the flat edges are found ([`Needed`]), that round's
    // pieces sifted, and the later rounds' sifted as they are made (two fanned caps in
    // one plane: millions of segments, almost all along flat edges). Not with
    // `refinement`, which keeps them all.
    let mut needed: Option<Needed> = None;
    let mut results: Vec<Block> = Vec::new();
    for round in pairs.chunks(1 << 20) {
        let found: Vec<(Block, bool)> = round
            .par_chunks(1 << 10)
            .grained()
            .map(|block| {
                let mut out = Vec::with_capacity(2 * block.len());
                let mut coplanar = false;
                for &(i, j) in block {
                    let (si, sj) = (slot_a[i as usize], slot_b[j as usize]);
                    let (Some(x), Some(y)) = (&tris_a[si as usize], &tris_b[sj as usize]) else {
                        continue;
                    };
                    let (sx, sy) = ((x, si), (y, sj));
                    let flat = needed.as_ref().map_or([0, 0], |n| n.flat(sx, sy));
                    tritri::meet_beyond_flat(x, y, flat, |p| {
                        coplanar |= matches!(p, Piece::Segment(_, true));
                        if needed.as_ref().is_none_or(|n| n.keeps(&p, sx, sy)) {
                            out.push((i, j, p));
                        }
                    });
                }
                // Room for what the pairs gave, not for what they might have.
                if out.len() < out.capacity() / 2 {
                    out.shrink_to_fit();
                }
                (out, coplanar)
            })
            .collect();
        let coplanar = found.iter().any(|b| b.1);
        let mut found: Vec<Block> = found.into_iter().map(|b| b.0).collect();
        if coplanar && needed.is_none() && !refinement {
            let n = Needed(crate::par::join(
                || FlatEdges::of(a, &near_a),
                || FlatEdges::of(b, &near_b),
            ).into());
            let set_up = |i: u32, j: u32| {
                let (si, sj) = (slot_a[i as usize], slot_b[j as usize]);
                let x = tris_a[si as usize].as_ref().expect("a pair with pieces is set up");
                let y = tris_b[sj as usize].as_ref().expect("a pair with pieces is set up");
                ((x, si), (y, sj))
            };
            results
                .par_iter_mut()
                .chain(found.par_iter_mut())
                .for_each(|block| {
                    block.retain(|&(i, j, p)| {
                        let (x, y) = set_up(i, j);
                        n.keeps(&p, x, y)
                    })
                });
            needed = Some(n);
        }
        results.append(&mut found);
    }
    let (da, db) = (
        tris_a.iter().filter(|t| t.is_none()).count(),
        tris_b.iter().filter(|t| t.is_none()).count(),
    );

    let blocks: Vec<&[(u32, u32, Piece)]> = results.iter().map(Vec::as_slice).collect();
    let mut seam = assemble(&blocks, |l| l);
    seam.degenerate = [da, db];
    seam.candidate_pairs = pairs.len();
    seam.from_grid = from_grid;
    seam.near = Some([near_a, near_b]);
    seam.exact = seam
        .points
        .par_iter()
        .grained()
        .map(|l| label_point(l, a, b))
        .collect();
    seam.locate();
    seam
}

/// The pieces of a block of candidate pairs, with the pair each is of.
type Block = Vec<(u32, u32, Piece)>;

/// The edge of one mesh on which two points of a triangle lie, given by their features
/// there (the segment between them then runs along it), if they lie on one.
fn common_edge(x: Feature, y: Feature) -> Option<(u32, u32)> {
    match (x, y) {
        (Feature::Edge(u, v), Feature::Edge(p, q)) if (u, v) == (p, q) => Some((u, v)),
        (Feature::Edge(u, v), Feature::Vertex(w)) | (Feature::Vertex(w), Feature::Edge(u, v))
            if w == u || w == v =>
        {
            Some((u, v))
        }
        // Two corners of one triangle: its edge between them.
        (Feature::Vertex(u), Feature::Vertex(v)) if u != v => Some((u.min(v), u.max(v))),
        _ => None,
    }
}

/// Which edges of one mesh are flat: held by exactly two triangles that use it once each
/// way, lie in one plane and face the same way (exact), so that the surface on both sides
/// of it is one planar region. Built over some of the mesh's triangles (`near`, each with
/// its place there); an edge is judged only where every triangle holding it is among
/// them. Each triangle's edges are decided when first asked.
struct FlatEdges<'m> {
    mesh: &'m Mesh,
    /// The edges of the triangles, `lo << 32 | hi`, sorted, each once.
    keys: Vec<u64>,
    /// Per edge, its two triangles where exactly two hold it, once each way; else none.
    held: Vec<Option<[u32; 2]>>,
    /// Per triangle of `near` (by its place there): bit `k` set when its edge from corner
    /// `k` to `k + 1` is flat, bit 3 once that is known.
    masks: Vec<std::sync::atomic::AtomicU8>,
}

/// Bit 3 of a [`FlatEdges`] mask: the triangle's edges are decided.
const DECIDED: u8 = 8;

impl<'m> FlatEdges<'m> {
    fn of(mesh: &'m Mesh, near: &[u32]) -> FlatEdges<'m> {
        // (edge, triangle, whether the triangle runs along it from lo to hi)
        let mut uses: Vec<(u64, u32, bool)> = near
            .par_iter()
            .grained()
            .flat_map_iter(|&t| {
                let v = mesh.triangles[t as usize];
                (0..3).map(move |k| {
                    let (p, q) = (v[k], v[(k + 1) % 3]);
                    (edge_key(p, q), t, p < q)
                })
            })
            .collect();
        uses.par_sort_unstable();
        let (mut keys, mut held) = (Vec::new(), Vec::new());
        for run in uses.chunk_by(|x, y| x.0 == y.0) {
            keys.push(run[0].0);
            held.push(match run {
                [(_, t, f), (_, o, g)] if f != g => Some([*t, *o]),
                _ => None,
            });
        }
        let masks = (0..near.len())
            .map(|_| std::sync::atomic::AtomicU8::new(0))
            .collect();
        FlatEdges {
            mesh,
            keys,
            held,
            masks,
        }
    }

    /// Whether the edge from `u` to `v` is flat.
    fn is_flat(&self, u: u32, v: u32) -> bool {
        let Ok(i) = self.keys.binary_search(&edge_key(u, v)) else {
            return false;
        };
        let Some([t, o]) = self.held[i] else {
            return false;
        };
        same_plane_same_facing(&self.mesh.corners(t as usize), &self.mesh.corners(o as usize))
    }

    /// The flat edges of triangle `t` (place `slot` in `near`), as bits by corner.
    fn mask(&self, slot: u32, t: u32) -> u8 {
        use std::sync::atomic::Ordering::Relaxed;
        let m = &self.masks[slot as usize];
        let known = m.load(Relaxed);
        if known & DECIDED != 0 {
            return known & !DECIDED;
        }
        let v = self.mesh.triangles[t as usize];
        let bits = (0..3).fold(0, |bits, k| {
            bits | (self.is_flat(v[k], v[(k + 1) % 3]) as u8) << k
        });
        m.store(bits | DECIDED, Relaxed);
        bits
    }
}

/// An edge's key in [`FlatEdges`]: `lo << 32 | hi`.
fn edge_key(u: u32, v: u32) -> u64 {
    (u.min(v) as u64) << 32 | u.max(v) as u64
}

/// The flat edges of both meshes ([`FlatEdges`]), and which pieces of coplanar pairs the
/// seam needs: not the segments that run along flat edges only. Where the edge of one
/// mesh lies inside a planar region of that mesh which the other mesh's triangle lies in,
/// the other triangle's points on both sides of it are in the same class (on that region,
/// facing as it does), so the edge need not cut it. The seam of two coplanar regions is
/// then their boundaries, not every edge of each mesh's triangulation inside the other's
/// region: two fanned caps in one plane cross in a number of points that grows as the
/// product of their triangle counts, and each such point would be a vertex of both
/// arrangements. A segment along an edge of each mesh goes where both edges are flat;
/// a coplanar pair of triangles whose six edges are flat gives nothing. Seam points that
/// only such segments reached go with them; no triangle that is not coplanar with the
/// region holds one (its edges there would not be flat).
///
/// Built over every triangle of each mesh in a candidate pair: each triangle holding an
/// edge along which a coplanar pair's segment runs is a candidate of the other triangle
/// of that pair.
struct Needed<'m>([FlatEdges<'m>; 2]);

impl Needed<'_> {
    /// The flat edges of triangles `x` and `y` (of A and B, with their places among the
    /// candidates), as [`tritri::meet_beyond_flat`] takes them.
    fn flat(&self, x: (&tritri::Tri, u32), y: (&tritri::Tri, u32)) -> [u8; 2] {
        [self.0[0].mask(x.1, x.0.id), self.0[1].mask(y.1, y.0.id)]
    }

    /// Whether the seam needs `piece` of triangles `x` and `y`, with their places among
    /// the candidates.
    fn keeps(&self, piece: &Piece, x: (&tritri::Tri, u32), y: (&tritri::Tri, u32)) -> bool {
        let Piece::Segment([p, q], true) = piece else {
            return true;
        };
        // Along an edge of the triangle of mesh `k` (an edge it lies on): whether flat.
        let flat = |k: usize, (t, slot): (&tritri::Tri, u32), e: Option<(u32, u32)>| {
            e.map(|e| {
                let v = t.v;
                (0..3).any(|c| {
                    edge_key(v[c], v[(c + 1) % 3]) == edge_key(e.0, e.1)
                        && self.0[k].mask(slot, t.id) & 1 << c != 0
                })
            })
        };
        match (
            flat(0, x, common_edge(p.a, q.a)),
            flat(1, y, common_edge(p.b, q.b)),
        ) {
            (None, None) => true,
            (a, b) => !(a.unwrap_or(true) && b.unwrap_or(true)),
        }
    }
}

/// The triangle pairs of `a` and `b` whose boxes overlap, sorted; large triangles are
/// looked at through the smaller boxes of their pieces ([`crate::broad::cover_large`]).
/// Of two trees, a mesh used whole takes the one `kept` keeps of it, where it has one
/// ([`Kept`]).
fn candidate_pairs(
    a: &Mesh,
    b: &Mesh,
    from_grid: bool,
    kept: [Option<&Keeps>; 2],
) -> Vec<(u32, u32)> {
    let pairs_of = |a: &Mesh, b: &Mesh, kept: [Option<&Bvh>; 2]| match kept {
        _ if from_grid => crate::broad::overlapping_pairs(a, b),
        _ if a.triangles.len().saturating_mul(b.triangles.len()) <= crate::bvh::ALL_PAIRS_UP_TO => {
            crate::bvh::all_overlapping_pairs(a, b)
        }
        [Some(ta), Some(tb)] => ta.overlapping_pairs(a, tb, b),
        // One whole tree kept: the other mesh's tree holds what meets its box.
        [Some(ta), None] => {
            let Some(box_a) = ta.bounds() else {
                return Vec::new();
            };
            ta.overlapping_pairs(a, &Bvh::new_within(b, &box_a), b)
        }
        [None, Some(tb)] => {
            let Some(box_b) = tb.bounds() else {
                return Vec::new();
            };
            Bvh::new_within(a, &box_b).overlapping_pairs(a, tb, b)
        }
        [None, None] => {
            // Each tree holds only the triangles that can meet the other mesh at all. Of
            // meshes of unlike sizes (a terrain and a pit shell), the larger is indexed
            // within the smaller's box first, and the smaller within what that kept:
            // the larger mesh's own box is never needed.
            let (na, nb) = (a.triangles.len(), b.triangles.len());
            let (ba, bb) = if na >= 4 * nb || nb >= 4 * na {
                let (small, large) = if na < nb { (a, b) } else { (b, a) };
                let Some(box_small) = small.bounds() else {
                    return Vec::new();
                };
                let tree_large = Bvh::new_within(large, &box_small);
                let Some(box_kept) = tree_large.bounds() else {
                    return Vec::new();
                };
                let tree_small = Bvh::new_within(small, &box_kept);
                if na < nb {
                    (tree_small, tree_large)
                } else {
                    (tree_large, tree_small)
                }
            } else {
                let (Some(box_a), Some(box_b)) = (a.bounds(), b.bounds()) else {
                    return Vec::new();
                };
                crate::par::join(|| Bvh::new_within(a, &box_b), || Bvh::new_within(b, &box_a))
            };
            ba.overlapping_pairs(a, &bb, b)
        }
    };
    let typical = crate::broad::typical_size(a, b);
    let slivers = |k: usize, m: &Mesh| kept[k]?.slivers.get(|| Slivers::of(m));
    let (ca, cb) = crate::par::join(
        || crate::broad::cover_large(a, typical, slivers(0, a)),
        || crate::broad::cover_large(b, typical, slivers(1, b)),
    );
    // Only a mesh used whole has its tree kept.
    let tree = |k: usize, m: &Mesh, whole: bool| {
        kept[k]
            .filter(|_| whole && !from_grid)?
            .tree
            .get(|| Bvh::new_for_queries(m))
    };
    let trees = [tree(0, a, ca.is_none()), tree(1, b, cb.is_none())];
    if ca.is_none() && cb.is_none() {
        return pairs_of(a, b, trees);
    }
    let (ma, pa) = ca.as_ref().map_or((a, None), |(m, p)| (m, Some(p)));
    let (mb, pb) = cb.as_ref().map_or((b, None), |(m, p)| (m, Some(p)));
    let mut pairs = pairs_of(ma, mb, trees);
    pairs.par_iter_mut().grained().for_each(|(i, j)| {
        if let Some(p) = pa {
            *i = p[*i as usize];
        }
        if let Some(p) = pb {
            *j = p[*j as usize];
        }
    });
    crate::bvh::sort_pairs(pairs, a.triangles.len(), true)
}

/// `key`'s number in `ids`; a key not numbered before gets the next number, and `item()`
/// goes to the end of `list` (the list of numbered things, in the order first met).
#[inline]
fn number<K: std::hash::Hash + Eq, T>(
    ids: &mut FxHashMap<K, u32>,
    key: K,
    list: &mut Vec<T>,
    item: impl FnOnce() -> T,
) -> u32 {
    *ids.entry(key).or_insert_with(|| {
        list.push(item());
        (list.len() - 1) as u32
    })
}

/// A run of blocks of pieces with its points and segments numbered on their own, each in
/// the order first met ([`assemble`]).
#[derive(Default)]
struct Part {
    /// The names of the run's segment ends, each once.
    points: Vec<Label>,
    /// The run's distinct segments, as indices into `points` (smaller first), each with
    /// whether all its pieces in the run are coplanar ones.
    segments: Vec<([u32; 2], bool)>,
    /// Per segment piece, in order: its index in `segments` and its triangle pair.
    sources: Vec<(u32, u32, u32)>,
    /// The names of the run's touching points, each once.
    touching: Vec<Label>,
    /// Each of `points`' number.
    point_ids: FxHashMap<Label, u32>,
}

impl Part {
    fn of(blocks: &[&[(u32, u32, Piece)]], name: &impl Fn(Label) -> Label) -> Part {
        let mut part = Part::default();
        let pieces = blocks.iter().map(|b| b.len()).sum();
        let mut point_ids: FxHashMap<Label, u32> = FxHashMap::default();
        let mut seg_ids: FxHashMap<[u32; 2], u32> = FxHashMap::default();
        // Sized once for as many as there can be (a piece has two ends; most are met
        // again by neighbouring pairs, but growing the maps cost more than the room).
        point_ids.reserve(pieces);
        seg_ids.reserve(pieces);
        part.sources.reserve(pieces);
        let mut touched: FxHashSet<Label> = FxHashSet::default();
        for &(i, j, piece) in blocks.iter().copied().flatten() {
            match piece {
                Piece::Point(l) => {
                    let l = name(l);
                    if touched.insert(l) {
                        part.touching.push(l);
                    }
                }
                Piece::Segment(s, coplanar) => {
                    let [x, y] = s.map(|l| {
                        let l = name(l);
                        number(&mut point_ids, l, &mut part.points, || l)
                    });
                    if x == y {
                        continue;
                    }
                    let ends = [x.min(y), x.max(y)];
                    let k = number(&mut seg_ids, ends, &mut part.segments, || (ends, coplanar));
                    part.segments[k as usize].1 &= coplanar;
                    part.sources.push((k, i, j));
                }
            }
        }
        part.point_ids = point_ids;
        part
    }
}

/// A seam from the pieces of the triangle pairs' intersections (`(i, j, piece)`, in pair
/// order, in blocks): points named by `name(label)` (one point per name), distinct
/// segments with every pair they were found in, touching points; points and segments
/// numbered in the order first met. Exact constructions and positions are left to the
/// caller.
///
/// Runs of consecutive blocks are numbered on their own, side by side ([`Part`]); then the
/// runs in order give their points and segments the next free numbers where they have
/// none yet. A name first met in run `k` is first met there in the whole order too, and
/// each run keeps its own order of first meetings: the numbers are those of one pass over
/// all pieces, but the one pass left looks at each run's distinct points and segments
/// only (neighbouring pairs meet the same points many times). A few runs per thread; one
/// on one thread and in a serial call, whose numbers are then already the whole seam's
/// ([`Seam::of_part`]: no second pass).
fn assemble(blocks: &[&[(u32, u32, Piece)]], name: impl Fn(Label) -> Label + Sync) -> Seam {
    let runs = match rayon::current_num_threads() {
        n if n == 1 || crate::par::is_serial() => 1,
        n => 4 * n,
    };
    let mut parts: Vec<Part> = blocks
        .par_chunks(blocks.len().div_ceil(runs).max(1))
        .grained()
        .map(|run| Part::of(run, &name))
        .collect();
    if parts.len() <= 1 {
        return Seam::of_part(parts.pop().unwrap_or_default());
    }
    let mut seam = Seam::default();
    let mut point_ids: FxHashMap<Label, u32> = FxHashMap::default();
    let mut seg_ids: FxHashMap<[u32; 2], u32> = FxHashMap::default();
    seam.sources
        .reserve(parts.iter().map(|p| p.sources.len()).sum());
    for part in &parts {
        let ids: Vec<u32> = part
            .points
            .iter()
            .map(|&l| number(&mut point_ids, l, &mut seam.points, || l))
            .collect();
        let segment_ids: Vec<u32> = part
            .segments
            .iter()
            .map(|&([x, y], coplanar)| {
                let (x, y) = (ids[x as usize], ids[y as usize]);
                let ends = [x.min(y), x.max(y)];
                let id = number(&mut seg_ids, ends, &mut seam.segments, || SeamSegment {
                    ends,
                    coplanar,
                });
                seam.segments[id as usize].coplanar &= coplanar;
                id
            })
            .collect();
        seam.sources
            .extend(part.sources.iter().map(|&(k, i, j)| SegmentSource {
                segment: segment_ids[k as usize],
                tri_a: i,
                tri_b: j,
            }));
    }
    let on_segment = segment_ends(seam.points.len(), seam.segments.iter().map(|s| s.ends));
    let mut listed = FxHashSet::default();
    for part in &parts {
        for &l in &part.touching {
            let id = number(&mut point_ids, l, &mut seam.points, || l);
            if on_segment.get(id as usize) != Some(&true) && listed.insert(id) {
                seam.touching.push(id);
            }
        }
    }
    seam
}

impl Seam {
    /// The seam of one run ([`assemble`]): its numbers are already those of the whole.
    fn of_part(part: Part) -> Seam {
        let Part {
            mut points,
            segments,
            sources,
            touching: touching_labels,
            point_ids,
        } = part;
        // A touching point that is no segment's end is listed (numbered after the
        // segments' points where it is none of theirs), as `assemble` lists it.
        let on_segment = segment_ends(points.len(), segments.iter().map(|s| s.0));
        let mut touching = Vec::new();
        for l in touching_labels {
            match point_ids.get(&l) {
                Some(&id) if on_segment[id as usize] => {}
                Some(&id) => touching.push(id),
                None => {
                    touching.push(points.len() as u32);
                    points.push(l);
                }
            }
        }
        Seam {
            points,
            segments: segments
                .into_iter()
                .map(|(ends, coplanar)| SeamSegment { ends, coplanar })
                .collect(),
            sources: sources
                .into_iter()
                .map(|(segment, tri_a, tri_b)| SegmentSource {
                    segment,
                    tri_a,
                    tri_b,
                })
                .collect(),
            touching,
            ..Seam::default()
        }
    }
}

/// Per point of `points`, whether it is an end of one of the segments `ends`.
fn segment_ends(points: usize, ends: impl Iterator<Item = [u32; 2]>) -> Vec<bool> {
    let mut on = vec![false; points];
    for [x, y] in ends {
        on[x as usize] = true;
        on[y as usize] = true;
    }
    on
}

/// The name of a point where two triangles of one mesh meet: a vertex by itself, else the
/// two features in order, so that the pair `(i, j)` and the pair `(j, i)` name it alike.
fn own_label(l: Label) -> Label {
    match (l.a, l.b) {
        (Feature::Vertex(v), _) | (_, Feature::Vertex(v)) => Label {
            a: Feature::Vertex(v),
            b: Feature::Vertex(v),
        },
        (a, b) => Label {
            a: a.min(b),
            b: a.max(b),
        },
    }
}

/// Where a mesh crosses itself: the seam of the mesh with itself over the triangle pairs
/// `pairs` (as [`self_intersections`] finds them), without what neighbouring triangles
/// share (their common vertex or edge). Points are named by the features of the one mesh
/// ([`Label::a`] ≤ [`Label::b`]; a vertex as itself twice), segments' sources name the
/// two triangles (`tri_a < tri_b`). `m` valid and exactly welded.
pub fn self_seam(m: &Mesh, pairs: &[(u32, u32)]) -> Seam {
    let results: Vec<(u32, u32, TriTri)> = pairs
        .par_iter()
        .grained()
        .filter_map(|&(i, j)| {
            let (x, y) = (tri(m, i as usize)?, tri(m, j as usize)?);
            let (vi, vj) = (m.triangles[i as usize], m.triangles[j as usize]);
            let shared: Vec<u32> = vi.iter().copied().filter(|v| vj.contains(v)).collect();
            // What the two share: their common vertices and the edge between them.
            let in_shared = |l: &Label| match own_label(*l) {
                Label {
                    a: Feature::Vertex(v),
                    ..
                } => shared.contains(&v),
                Label {
                    a: Feature::Edge(u, v),
                    b,
                } => b == Feature::Edge(u, v) && shared.contains(&u) && shared.contains(&v),
                _ => false,
            };
            let r = match tritri::intersect(&x, &y) {
                TriTri::Point(l) if in_shared(&l) => TriTri::None,
                TriTri::Segment(s) if s.iter().all(in_shared) => TriTri::None,
                TriTri::Coplanar { segments, points } => TriTri::Coplanar {
                    segments: segments
                        .into_iter()
                        .filter(|s| !s.iter().all(in_shared))
                        .collect(),
                    points: points.into_iter().filter(|l| !in_shared(l)).collect(),
                },
                r => r,
            };
            match r {
                TriTri::None => None,
                r => Some((i, j, r)),
            }
        })
        .collect();
    let mut pieces = Vec::with_capacity(results.len());
    for (i, j, r) in &results {
        tritri::pieces_of(r, |p| pieces.push((*i, *j, p)));
    }
    let blocks: Vec<&[(u32, u32, Piece)]> = pieces.chunks(1 << 12).collect();
    let mut seam = assemble(&blocks, own_label);
    seam.vertex_on = vertices_on_features(pieces.iter().copied());
    seam.candidate_pairs = pairs.len();
    seam.exact = seam
        .points
        .par_iter()
        .grained()
        .map(|l| label_point(l, m, m))
        .collect();
    seam.locate();
    seam
}

/// The vertices that lie on another triangle's edge or face, from the raw labels of the
/// self-intersection results' pieces (before [`own_label`] names such points by the
/// vertex).
fn vertices_on_features(results: impl Iterator<Item = (u32, u32, Piece)>) -> Vec<(u32, Feature)> {
    let mut found = Vec::new();
    let mut note = |l: &Label| match (l.a, l.b) {
        (Feature::Vertex(v), f @ (Feature::Edge(..) | Feature::Face(_)))
        | (f @ (Feature::Edge(..) | Feature::Face(_)), Feature::Vertex(v)) => found.push((v, f)),
        _ => {}
    };
    for (_, _, piece) in results {
        match piece {
            Piece::Point(l) => note(&l),
            Piece::Segment(s, _) => s.iter().for_each(&mut note),
        }
    }
    found.sort_unstable();
    found.dedup();
    found
}

/// Pairs of triangles of one mesh that meet anywhere other than in the vertices and edges
/// they share: self-intersections (or coplanar overlaps). Exact. Degenerate triangles are
/// left out. Sorted `(i, j)` with `i < j`. Pairs in one certified patch (`patches`:
/// pieces of up to a thousand triangles proven not to meet themselves) or in one
/// certified run around a vertex they share (`fans`: almost every vertex's whole fan on
/// a smooth mesh, a fanned cap's triangles around its corner) are settled, and tree nodes
/// whose triangles all share a patch or a run are not looked into; the rest by the exact
/// pair test.
pub fn self_intersections(m: &Mesh) -> Vec<(u32, u32)> {
    // Where some triangles are large (a CAD part's slivers side by side): the corners at
    // each vertex (for both certificates), the patches, then the tree with each patch's
    // triangles together, so that it fills whole subtrees, which the traversal does not
    // look into, beside the runs of the fans not inside a patch. The tree is over the
    // whole triangles where their boxes meet few of other patches, else over the large
    // triangles' pieces ([`crate::broad::cover_large`]). On meshes of triangles of one
    // size, the runs alone cost less (the patches' growth and the grouped tree take more
    // than the traversal they spare: BENCHMARKS.md).
    let n = m.triangles.len();
    let large = crate::broad::large_triangles(m, crate::broad::typical_size(m, m), None);
    let (runs, patch, cover, bvh) = match large {
        Some(large) if n < (u32::MAX / 3) as usize => {
            let (start, slots) = fans::corners_at_vertices(m);
            let patch = patches::patches(m, &start, &slots);
            let one_patch = |v: usize| {
                let fan = &slots[start[v] as usize..start[v + 1] as usize];
                let p = fan
                    .first()
                    .map_or(patches::NO_PATCH, |&c| patch[c as usize / 3]);
                p != patches::NO_PATCH && fan.iter().all(|&c| patch[c as usize / 3] == p)
            };
            let (runs, (cover, bvh)) = crate::par::join(
                || fans::runs_where(m, &start, &slots, |v| !one_patch(v)),
                || {
                    if let Some(whole) = whole_tree(m, &patch) {
                        return (None, whole);
                    }
                    let (stand_in, parent) = crate::broad::cut_large(m, &large);
                    let group: Vec<u32> = parent.iter().map(|&t| patch_group(&patch, t)).collect();
                    let bvh = Bvh::new_grouped(&stand_in, &group, n);
                    (Some((stand_in, parent)), bvh)
                },
            );
            (runs, Some(patch), cover, bvh)
        }
        large => {
            let cover = large.map(|l| crate::broad::cut_large(m, &l));
            let (runs, bvh) = crate::par::join(
                || fans::runs(m),
                || Bvh::new(cover.as_ref().map_or(m, |c| &c.0)),
            );
            (runs, None, cover, bvh)
        }
    };
    let patch_of = |t: u32| patch.as_ref().map_or(patches::NO_PATCH, |p| p[t as usize]);
    let corner_runs = |t: u32| -> [u32; 3] { std::array::from_fn(|k| runs[3 * t as usize + k]) };
    // A patch's label comes after every run's (runs are named by corners, below 3n).
    let labels = |t: u32| -> crate::bvh::Labels {
        let [a, b, c] = corner_runs(t);
        let p = match patch_of(t) {
            patches::NO_PATCH => crate::bvh::NO_LABEL,
            p => 3 * n as u32 + p,
        };
        [a, b, c, p]
    };
    let meets = |i: u32, j: u32| -> bool {
        if patch.is_some() {
            let pi = patch_of(i);
            if pi != patches::NO_PATCH && pi == patch_of(j) {
                return false; // in one certified patch
            }
        }
        let (vi, vj) = (m.triangles[i as usize], m.triangles[j as usize]);
        let shared = (0..3).filter(|&k| vj.contains(&vi[k])).count();
        if shared == 3 {
            return true; // the same triangle twice
        }
        if shared > 0 {
            let (ri, rj): ([u32; 3], [u32; 3]) = (corner_runs(i), corner_runs(j));
            if ri.iter().any(|&r| r != fans::NO_RUN && rj.contains(&r)) {
                return false; // both in one certified run around a vertex they share
            }
        }
        meets_beyond_shared(m, i, j, shared)
    };
    let mut found: Vec<(u32, u32)> = match &cover {
        None => {
            let settled = bvh.common_labels(labels);
            bvh.self_candidates_where(m, &meets, Some(&settled))
                .into_iter()
                .map(|(i, j)| (i.min(j), i.max(j)))
                .collect()
        }
        // Large triangles through their pieces: the candidates (pieces of one triangle
        // aside) named by the triangles they stand for, tested as the traversal finds
        // them. A pair of triangles that more than one pair of their pieces stands for is
        // tested (and found) more than once, which costs less than storing and sorting
        // every candidate (1.5M pairs of pieces for 15k slivers side by side) and keeps
        // the memory to the pairs found; the repeats go below.
        Some((stand_in, parent)) => {
            let settled = bvh.common_labels(|p| labels(parent[p as usize]));
            piece_pairs(&bvh, stand_in, parent, true, Some(&settled), &meets)
        }
    };
    found.par_sort_unstable();
    found.dedup();
    found
}

/// Candidate pairs per triangle, across patches, up to which the self-intersection check
/// looks at a mesh with large triangles through the whole triangles (grouped by patch)
/// rather than their pieces. Measured on CAD parts (BENCHMARKS.md, pairs a triangle as
/// [`few_across_patches`] estimates them): at 6 to 11 (abc5, adis16480, gears, wing) the
/// whole triangles cost half to a quarter of the pieces, at 7 (thingi 908460) no more;
/// at 18 (thingi 73416) the pieces cost less, at 897 (thingi 79741: slivers around
/// slanted cylinders, each box over much of its neighbours) ten times less.
const WHOLE_UP_TO: usize = 16;

/// The group of triangle `t` in a tree grouped by patch ([`Bvh::new_grouped`]): its
/// patch, or itself outside any (a patch is named by its seed, a triangle of it, so the
/// two kinds of names do not collide).
fn patch_group(patch: &[u32], t: u32) -> u32 {
    match patch[t as usize] {
        patches::NO_PATCH => t,
        p => p,
    }
}

/// The tree over the whole triangles of `m`, each patch's together, where their boxes
/// meet few triangles of other patches ([`few_across_patches`]); `None` where the large
/// triangles' pieces are to be looked at instead.
fn whole_tree(m: &Mesh, patch: &[u32]) -> Option<Bvh> {
    let n = m.triangles.len();
    let group: Vec<u32> = (0..n as u32).map(|t| patch_group(patch, t)).collect();
    let whole = Bvh::new_grouped(m, &group, n);
    few_across_patches(m, &whole, patch).then_some(whole)
}

/// Whether the tree `whole` over the triangles of `m` (grouped by `patch`) has few
/// candidate pairs across patches: at most [`WHOLE_UP_TO`] a triangle, estimated on an
/// even sample of up to 256 triangles (every triangle of a smaller mesh) as half the
/// triangles their boxes meet that are not in their own patch (each pair is met from
/// both sides).
fn few_across_patches(m: &Mesh, whole: &Bvh, patch: &[u32]) -> bool {
    const SAMPLE: usize = 256;
    let n = m.triangles.len();
    let step = n.div_ceil(SAMPLE).max(1);
    let limit = 2 * WHOLE_UP_TO * n.div_ceil(step);
    // On one thread, stopping once over the limit: a mesh of many such pairs is told
    // after a few triangles.
    let mut met = 0;
    for t in (0..n as u32).step_by(step) {
        let p = patch[t as usize];
        met += whole
            .in_box(m, &crate::bvh::tri_box(m, t))
            .into_iter()
            .filter(|&u| u != t && (p == patches::NO_PATCH || patch[u as usize] != p))
            .count();
        if met > limit {
            return false;
        }
    }
    true
}

/// The pairs of triangles (`(lo, hi)`, unsorted, perhaps repeated) that a cover's
/// pieces stand for (`stand_in` with `parent`, from [`crate::broad::cut_large`], in a
/// tree `bvh` of its own), among the pairs of pieces of different triangles whose boxes
/// meet once rounded outward to `f32`: each pair of triangles that some pair of their
/// pieces stands for, at least once.
///
/// Two slivers side by side are such a pair through every pair of their pieces whose
/// boxes meet (a CAD model's fans: 8.9M pairs of pieces for 1.0M pairs of triangles).
/// With `first_only`, a pair of pieces is left out where a pair that comes before it
/// (pieces taken in the stand-in's order, the piece of the triangle of lower id first)
/// is a candidate too: the piece before either, of the same triangle, against the other
/// or one of its neighbours along its triangle, found by the boxes as the tree rounds
/// them. The first candidate pair of pieces of two triangles has none before it and
/// always stays; those of pieces side by side along two slivers, running either way,
/// are left out but for a few. With `settled` (the tree's nodes labelled by the runs of
/// their pieces' triangles, [`crate::bvh::Bvh::common_labels`]), nodes whose triangles
/// all share a certified run are not looked into: every pair they stand for is settled.
/// Only pairs of triangles for which `test(lo, hi)` holds are kept, tested as the
/// traversal finds them (so perhaps more than once for a pair).
fn piece_pairs(
    bvh: &Bvh,
    stand_in: &Mesh,
    parent: &[u32],
    first_only: bool,
    settled: Option<&[crate::bvh::Labels]>,
    test: &(dyn Fn(u32, u32) -> bool + Sync),
) -> Vec<(u32, u32)> {
    let n = stand_in.triangles.len() as u32;
    // The pieces' boxes as the tree rounds them: two meet here exactly when the tree
    // finds the pair.
    let rounded: Vec<crate::bvh::Box3f> = if first_only {
        (0..n)
            .into_par_iter()
            .grained()
            .map(|t| crate::bvh::round_out(&crate::bvh::tri_box(stand_in, t)))
            .collect()
    } else {
        Vec::new()
    };
    let boxes_meet =
        |i: u32, j: u32| crate::bvh::overlaps_f(&rounded[i as usize], &rounded[j as usize]);
    // Piece `i + d` when it is of the same triangle as piece `i`.
    let sibling = |i: u32, d: i32| {
        let k = i.checked_add_signed(d).filter(|&k| k < n)?;
        (parent[k as usize] == parent[i as usize]).then_some(k)
    };
    let keep = |i: u32, j: u32| {
        let (pi, pj) = (parent[i as usize], parent[j as usize]);
        if pi == pj {
            return false;
        }
        if first_only {
            let (p, q) = if pi < pj { (i, j) } else { (j, i) };
            let before = [(-1, 0), (0, -1), (-1, -1), (-1, 1)];
            if before.iter().any(|&(dp, dq)| {
                matches!((sibling(p, dp), sibling(q, dq)), (Some(a), Some(b)) if boxes_meet(a, b))
            }) {
                return false;
            }
        }
        test(pi.min(pj), pi.max(pj))
    };
    bvh.self_candidates_where(stand_in, &keep, settled)
        .into_par_iter()
        .grained()
        .map(|(i, j)| {
            let (i, j) = (parent[i as usize], parent[j as usize]);
            (i.min(j), i.max(j))
        })
        .collect()
}

/// The triangle pairs of `all`, the concatenation of `parts` in order (`starts`: each
/// part's first triangle there), that meet and belong to different parts, as
/// [`self_intersections`] of `all` names them (`(lo, hi)`, sorted); the parts' own pairs
/// are left out (parts that do not cross themselves, as a boolean's operands). Parts
/// whose boxes overlap are paired with the candidate search of [`intersect`] (large
/// triangles through their pieces), a pair of parts and the candidates of each in
/// parallel.
pub(crate) fn crossings_between(parts: &[&Mesh], all: &Mesh, starts: &[u32]) -> Vec<(u32, u32)> {
    let boxes: Vec<Option<crate::Aabb>> = parts.par_iter().grained().map(|m| m.bounds()).collect();
    let mut meeting = Vec::new();
    for i in 0..parts.len() {
        for j in i + 1..parts.len() {
            if let (Some(a), Some(b)) = (&boxes[i], &boxes[j]) {
                if crate::bvh::overlaps(&[a.min, a.max], &[b.min, b.max]) {
                    meeting.push((i, j));
                }
            }
        }
    }
    let mut found: Vec<(u32, u32)> = meeting
        .par_iter()
        .grained()
        .flat_map_iter(|&(i, j)| {
            let (a, b) = (parts[i], parts[j]);
            let from_grid = a.triangles.len() + b.triangles.len() >= GRID_FROM;
            candidate_pairs(a, b, from_grid, [None, None])
                .into_par_iter()
                .grained()
                .map(|(x, y)| (x + starts[i], y + starts[j]))
                .filter(|&(x, y)| meets_beyond_shared(all, x, y, 0))
                .collect::<Vec<_>>()
        })
        .collect();
    found.par_sort_unstable();
    found
}

/// Whether triangles `i` and `j` of `m`, which share `shared` (< 3) vertices, meet
/// anywhere else than in those vertices and the edge between them. Exact.
#[inline(never)]
fn meets_beyond_shared(m: &Mesh, i: u32, j: u32, shared: usize) -> bool {
    let (vi, vj) = (m.triangles[i as usize], m.triangles[j as usize]);
    let (pi, pj) = (m.corners(i as usize), m.corners(j as usize));
    corners_meet_beyond_shared([(i, vi, pi), (j, vj, pj)], shared)
}

/// Whether two triangles, given by their ids (distinct), vertex ids and corners, meet
/// anywhere else than in the `shared` (< 3) vertex ids they have in common and the edge
/// between them ([`meets_beyond_shared`] for triangles of no mesh: the snap's candidates).
/// Exact.
pub(crate) fn corners_meet_beyond_shared(
    [(i, vi, pi), (j, vj, pj)]: [(u32, [u32; 3], [[f64; 3]; 3]); 2],
    shared: usize,
) -> bool {
    use crate::kernel::{
        certainly_apart_beyond_corner, certainly_apart_projected, certainly_separated,
        certainly_unfolded, orient2d, FloatPlane,
    };
    // The corners of `q` that `p` does not share, all strictly on one side of `p`'s plane
    // (and at least one of them): then the two meet at most in what they share. Decided
    // exactly, or (`exact` false) by the floating-point filter alone, which answers only
    // where it is certain.
    let apart = |p: &[[f64; 3]; 3], vp: &[u32; 3], q: &[[f64; 3]; 3], vq: &[u32; 3], exact| {
        let plane = FloatPlane::new(p);
        let mut side = Sign::Zero;
        for k in 0..3 {
            if vp.contains(&vq[k]) {
                continue;
            }
            let s = if exact {
                plane.side_exact(p, &q[k])
            } else {
                plane.side(&q[k]).unwrap_or(Sign::Zero)
            };
            if s == Sign::Zero || (side != Sign::Zero && s != side) {
                return false;
            }
            side = s;
        }
        side != Sign::Zero
    };
    // Two triangles sharing an edge whose far vertices lie certainly more than a right
    // angle apart around it (seen along the edge) can only meet in that edge, coplanar or
    // not. The kernel's floating-point filter only ever answers "certainly unfolded";
    // anything else goes to the exact tests below. This is what almost every edge-sharing
    // pair of a smooth or flat surface is, and it spares the exact orientation test its
    // slow path on planar quads.
    let unfolded = |p: &[[f64; 3]; 3], vp: &[u32; 3], q: &[[f64; 3]; 3], vq: &[u32; 3]| {
        let (Some(fp), Some(fq)) = (
            (0..3).find(|&k| !vq.contains(&vp[k])),
            (0..3).find(|&k| !vp.contains(&vq[k])),
        ) else {
            return false;
        };
        certainly_unfolded(&p[(fp + 1) % 3], &p[(fp + 2) % 3], &p[fp], &q[fq])
    };
    if shared == 2 && unfolded(&pi, &vi, &pj, &vj) {
        return false;
    }
    // Floating-point filters that only answer "certainly apart" first: a plane that
    // separates, then (for pairs sharing nothing) the other separating axes. Coplanar
    // pairs (the flat faces of CAD models, cut into many slivers whose boxes overlap) get
    // no answer from the planes, and their exact plane test is the slow path of the
    // adaptive predicate. Then the exact planes, before any set-up: sharing an edge, the
    // far vertex off the other's plane is enough; otherwise one plane must separate.
    let separated = |exact| {
        apart(&pi, &vi, &pj, &vj, exact) || (shared < 2 && apart(&pj, &vj, &pi, &vi, exact))
    };
    // Sharing one corner: the shared corner's place in each.
    let corner = || {
        (0..3)
            .find_map(|kj| vi.iter().position(|&v| v == vj[kj]).map(|ki| (ki, kj)))
            .filter(|&(ki, kj)| pi[ki] == pj[kj])
    };
    // Then shadows apart in a plane (cheap; what settles the coplanar pairs), and a
    // separating axis (through the shared corner).
    let shadows = || match shared {
        0 => certainly_apart_projected(&pi, &pj, None),
        _ => corner().is_some_and(|c| certainly_apart_projected(&pi, &pj, Some(c))),
    };
    let beyond_corner =
        || corner().is_some_and(|(ki, kj)| certainly_apart_beyond_corner(&pi, ki, &pj, kj));
    if separated(false)
        || (shared < 2 && shadows())
        || (shared == 0 && certainly_separated(&pi, &pj))
        || (shared == 1 && beyond_corner())
        || separated(true)
    {
        return false;
    }
    let (Some(x), Some(y)) = (tritri::Tri::new(i, vi, pi), tritri::Tri::new(j, vj, pj)) else {
        return false;
    };
    if shared == 2 {
        // Sharing an edge with the far vertex in this one's plane: they overlap when
        // it lies on the same side of the shared edge as this one's far vertex.
        let ks: Vec<usize> = (0..3).filter(|&k| y.v.contains(&x.v[k])).collect();
        let far_x = 3 - ks[0] - ks[1];
        let Some(far_y) = (0..3).find(|&k| !x.v.contains(&y.v[k])) else {
            return true;
        };
        let (e0, e1) = (
            Point::Explicit(x.corners()[ks[0]]),
            Point::Explicit(x.corners()[ks[1]]),
        );
        let sx = orient2d(&e0, &e1, &Point::Explicit(x.corners()[far_x]), x.axis());
        return sx == orient2d(&e0, &e1, &Point::Explicit(y.corners()[far_y]), x.axis());
    }
    meet_beyond_shared_points(&x, &y)
}

/// Whether triangles `x` and `y` meet in a point that is not a vertex of both (their
/// exact intersection, every point of it labelled: a label naming the same vertex on
/// both sides is a shared corner).
fn meet_beyond_shared_points(x: &tritri::Tri, y: &tritri::Tri) -> bool {
    let mut beyond = false;
    tritri::meet(x, y, |p| {
        beyond |= match p {
            Piece::Point(l) => l.a != l.b,
            Piece::Segment(s, _) => s.iter().any(|l| l.a != l.b),
        }
    });
    beyond
}

#[cfg(test)]
mod tests;
