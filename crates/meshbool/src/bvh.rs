//! Bounding-volume hierarchy over triangle boxes and the broad phase: all pairs of
//! triangles (one from each mesh) whose boxes overlap.
//!
//! Build: triangles are sorted by the Morton code of their box centres, then the sorted
//! range is split at its middle recursively, so the tree is balanced by construction and
//! spatially coherent; leaf boxes are the exact min/max of input coordinates, inner boxes
//! their unions. O(n log n) for the (parallel) sort, O(n) for the rest.
//! Queries compare input coordinates only (closed boxes: touching counts as overlapping),
//! so they are exact and conservative.

use crate::par::Grain;
use rayon::prelude::*;

use crate::{Aabb, Mesh};

/// Triangles per leaf.
const LEAF: usize = 8;

/// An axis-aligned box as `[min, max]`.
pub(crate) type Box3 = [[f64; 3]; 2];

/// A box in `f32`, rounded outward so that it contains the `f64` box it was made from.
pub(crate) type Box3f = [[f32; 3]; 2];

/// Whether two closed boxes overlap (touching counts).
#[inline]
pub(crate) fn overlaps(a: &Box3, b: &Box3) -> bool {
    (0..3).all(|k| a[0][k] <= b[1][k] && b[0][k] <= a[1][k])
}

#[inline]
pub(crate) fn overlaps_f(a: &Box3f, b: &Box3f) -> bool {
    // Without short-circuits: six comparisons and no branch between them (about half of
    // the leaf pairs overlap, so branches would mispredict often).
    (a[0][0] <= b[1][0])
        & (b[0][0] <= a[1][0])
        & (a[0][1] <= b[1][1])
        & (b[0][1] <= a[1][1])
        & (a[0][2] <= b[1][2])
        & (b[0][2] <= a[1][2])
}

fn down(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) > x {
        f.next_down()
    } else {
        f
    }
}

fn up(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) < x {
        f.next_up()
    } else {
        f
    }
}

/// The exact box of triangle `t` of `m`.
pub(crate) fn tri_box(m: &Mesh, t: u32) -> Box3 {
    corners_box(&m.corners(t as usize))
}

/// The exact box of three corners: their smallest and largest coordinates.
pub(crate) fn corners_box([a, b, c]: &[[f64; 3]; 3]) -> Box3 {
    [
        std::array::from_fn(|k| a[k].min(b[k]).min(c[k])),
        std::array::from_fn(|k| a[k].max(b[k]).max(c[k])),
    ]
}

/// Below this many triangle pairs (the product of two meshes' triangle counts), the
/// pairs of overlapping boxes are found by testing every pair ([`all_overlapping_pairs`]):
/// for two meshes of a few dozen triangles, walking two trees costs more than the pair
/// tests themselves (a measured crossover, BENCHMARKS.md).
pub(crate) const ALL_PAIRS_UP_TO: usize = 1 << 12;

/// Every pair `(triangle of a, triangle of b)` whose exact boxes overlap, sorted, by
/// testing every pair: the pairs [`Bvh::overlapping_pairs`] finds, for meshes with few
/// triangles ([`ALL_PAIRS_UP_TO`]).
pub(crate) fn all_overlapping_pairs(a: &Mesh, b: &Mesh) -> Vec<(u32, u32)> {
    let boxes_b: Vec<Box3> = (0..b.triangles.len() as u32)
        .map(|j| tri_box(b, j))
        .collect();
    let mut pairs = Vec::new();
    for i in 0..a.triangles.len() as u32 {
        let bi = tri_box(a, i);
        pairs.extend(
            (0u32..)
                .zip(&boxes_b)
                .filter(|(_, bj)| overlaps(&bi, bj))
                .map(|(j, _)| (i, j)),
        );
    }
    pairs
}

/// `b` in `f32`, rounded outward (the result contains `b`).
pub(crate) fn round_out(b: &Box3) -> Box3f {
    [b[0].map(down), b[1].map(up)]
}

/// A node in pre-order layout: its left child follows it, `right` is the right child.
#[derive(Clone, Copy, Debug)]
struct Node {
    bbox: Box3f,
    /// Leaf: first index into `order`; inner: index of the right child.
    start: u32,
    /// Leaf: number of triangles (> 0); inner: 0.
    count: u32,
}

const EMPTY: Node = Node {
    bbox: [[0.0; 3]; 2],
    start: 0,
    count: 0,
};

/// A BVH over the triangles of one mesh. It keeps no copy of the mesh: queries take the
/// mesh again and must be given the same one.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    /// Triangle ids in leaf order.
    order: Vec<u32>,
    /// Triangle boxes in leaf order, in `f32` rounded outward, a leaf's at a time
    /// ([`LeafBoxes`]; leaves start at multiples of [`LEAF`]): leaf pairs test these
    /// (contiguous, no indirection) and confirm an overlap on the exact boxes.
    boxes: Vec<LeafBoxes>,
}

/// The `f32` boxes of the triangles of one leaf, coordinate by coordinate (the smallest
/// x of each, …, the largest z of each; places past the leaf's triangles hold the empty
/// box): one box is tested against all of them at once, as a mask, with no branch per
/// triangle; a leaf pair's triangle pairs are then walked along the masks' set bits.
#[derive(Clone, Copy, Debug)]
struct LeafBoxes([[f32; LEAF]; 6]);

impl LeafBoxes {
    /// The boxes of at most [`LEAF`] triangles.
    fn of(boxes: &[Box3f]) -> Self {
        let mut rows = [[f32::INFINITY; LEAF]; 6];
        for row in &mut rows[3..] {
            *row = [f32::NEG_INFINITY; LEAF];
        }
        for (k, b) in boxes.iter().enumerate() {
            for d in 0..3 {
                rows[d][k] = b[0][d];
                rows[3 + d][k] = b[1][d];
            }
        }
        LeafBoxes(rows)
    }

    /// Box `k`.
    fn get(&self, k: usize) -> Box3f {
        let r = &self.0;
        [[r[0][k], r[1][k], r[2][k]], [r[3][k], r[4][k], r[5][k]]]
    }

    /// Bit `k` set where box `k` overlaps `q` (closed boxes); set for an empty place
    /// only when `q` is infinite on both sides of every axis.
    #[inline(always)]
    // One place of six rows at a time reads more plainly than six zipped iterators.
    #[allow(clippy::needless_range_loop)]
    fn overlapping(&self, q: &Box3f) -> u32 {
        let r = &self.0;
        let mut bits = 0u32;
        // Without short-circuits: no branch per place (about half of them overlap).
        for k in 0..LEAF {
            let hit = (r[0][k] <= q[1][0])
                & (q[0][0] <= r[3][k])
                & (r[1][k] <= q[1][1])
                & (q[0][1] <= r[4][k])
                & (r[2][k] <= q[1][2])
                & (q[0][2] <= r[5][k]);
            bits |= u32::from(hit) << k;
        }
        bits
    }
}

/// The boxes of triangles in leaf order, a leaf's at a time.
fn leaf_boxes(boxes: &[Box3f]) -> Vec<LeafBoxes> {
    boxes
        .par_chunks(LEAF)
        .grained()
        .map(LeafBoxes::of)
        .collect()
}

/// Spreads the low 21 bits of `x` to every third bit.
fn spread(x: u64) -> u64 {
    let mut x = x & 0x1f_ffff;
    x = (x | x << 32) & 0x1f_0000_0000_ffff;
    x = (x | x << 16) & 0x1f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    (x | x << 2) & 0x1249_2492_4924_9249
}

/// Leaves in a range of `n` triangles.
fn leaves(n: usize) -> usize {
    n.div_ceil(LEAF)
}

/// The leaf-aligned middle of a range of `n` triangles.
fn split_at(n: usize) -> usize {
    (leaves(n) / 2) * LEAF
}

/// The triangles of `mesh` sorted by the Morton code of their centroids (21 bits per
/// axis over the mesh's bounding box): spatially coherent order for hierarchies. Empty
/// for a mesh without triangles.
pub(crate) fn morton_order(mesh: &Mesh) -> Vec<u32> {
    morton_order_within(mesh, None, false)
}

/// [`morton_order`] with cells of one size on every axis (the cube on the box's longest
/// side): a flat mesh, a terrain, keeps its few bits of height from splitting neighbours
/// apart. The winding numbers' hierarchy takes it: on terrain ∪ terrain its clusters'
/// error bounds came out tighter, fewer values needed completing, and the run's
/// instructions fell from 5.7G to 3.6G.
pub(crate) fn morton_order_cube(mesh: &Mesh) -> Vec<u32> {
    morton_order_within(mesh, None, true)
}

/// [`morton_order`] of the triangles whose box meets the closed box `within` (all of
/// them for `None`). Exact `f64` comparisons, so no triangle touching `within` is left out.
/// The Morton grid spans the box of the triangles ordered.
fn morton_order_within(mesh: &Mesh, within: Option<&Aabb>, cube: bool) -> Vec<u32> {
    let (ids, frame) = match within {
        None => (None, mesh.bounds()),
        Some(w) => {
            let (ids, frame) = meeting_box(mesh, w);
            (Some(ids), frame)
        }
    };
    let Some(all) = frame else {
        return Vec::new();
    };
    // Cells of one size on every axis over the box of what a boolean's tree keeps (often
    // flat, next to the other mesh) and where asked; per axis over a whole mesh's box,
    // as the whole-mesh trees have always had them.
    let longest = (0..3).map(|k| all.max[k] - all.min[k]).fold(0.0, f64::max);
    let scale: [f64; 3] = std::array::from_fn(|k| {
        let ext = if cube || ids.is_some() {
            longest
        } else {
            all.max[k] - all.min[k]
        };
        if ext > 0.0 {
            ((1u64 << 21) - 1) as f64 / ext
        } else {
            0.0
        }
    });
    let keyed_of = |t: u32| {
        let [a, b, c] = mesh.corners(t as usize);
        let cell = |k: usize| {
            let centre = (a[k] + b[k] + c[k]) / 3.0 - all.min[k];
            ((centre * scale[k]).max(0.0) as u64).min((1 << 21) - 1)
        };
        (
            spread(cell(0)) | spread(cell(1)) << 1 | spread(cell(2)) << 2,
            t,
        )
    };
    let mut keyed: Vec<(u64, u32)> = match &ids {
        None => (0..mesh.triangles.len() as u32)
            .into_par_iter()
            .grained()
            .map(keyed_of)
            .collect(),
        Some(ids) => ids.par_iter().grained().map(|&t| keyed_of(t)).collect(),
    };
    sort_keyed(&mut keyed);
    keyed.into_par_iter().grained().map(|(_, t)| t).collect()
}

/// The triangles of `mesh` whose boxes meet the closed box `w`, in order, and the box of
/// their corners (`None` when there are none). A triangle's box misses `w` exactly when
/// all three corners lie beyond one of its six sides, so each vertex is placed once (a bit
/// per side it lies beyond, as in Cohen–Sutherland clipping) and a triangle is kept when
/// its corners' bits have none in common: the same exact comparisons as the boxes', made
/// per vertex rather than per triangle corner.
fn meeting_box(mesh: &Mesh, w: &Aabb) -> (Vec<u32>, Option<Aabb>) {
    const CHUNK: usize = 1 << 14;
    let beyond = |p: &[f64; 3]| -> u8 {
        (0..3).fold(0, |c, k| {
            c | u8::from(p[k] < w.min[k]) << (2 * k) | u8::from(p[k] > w.max[k]) << (2 * k + 1)
        })
    };
    let codes: Vec<u8> = mesh
        .positions
        .par_iter()
        .grained()
        .with_min_len(CHUNK)
        .map(beyond)
        .collect();
    let part = |first: usize| {
        let tris = &mesh.triangles[first..(first + CHUNK).min(mesh.triangles.len())];
        let mut ids = Vec::new();
        let mut frame: Option<Aabb> = None;
        for (t, tri) in (first..).zip(tris) {
            if codes[tri[0] as usize] & codes[tri[1] as usize] & codes[tri[2] as usize] != 0 {
                continue;
            }
            ids.push(t as u32);
            for &v in tri {
                let p = &mesh.positions[v as usize];
                frame = Some(frame.map_or(Aabb { min: *p, max: *p }, |b| b.grown(p)));
            }
        }
        (ids, frame)
    };
    if mesh.triangles.len() <= CHUNK {
        return part(0);
    }
    let parts: Vec<(Vec<u32>, Option<Aabb>)> = (0..mesh.triangles.len())
        .into_par_iter()
        .grained()
        .step_by(CHUNK)
        .map(part)
        .collect();
    let mut ids = Vec::with_capacity(parts.iter().map(|p| p.0.len()).sum());
    let mut frame: Option<Aabb> = None;
    for (i, f) in parts {
        ids.extend(i);
        frame = match (frame, f) {
            (Some(x), Some(y)) => Some(x.grown(&y.min).grown(&y.max)),
            (x, y) => x.or(y),
        };
    }
    (ids, frame)
}

/// A triangle while a tree is built for queries: its box's centre, its box, its id.
#[derive(Clone, Copy)]
struct Rec {
    centre: [f32; 3],
    bbox: Box3f,
    t: u32,
}

/// The empty box (the identity of [`union`]).
const EMPTY_BOX: Box3f = [[f32::INFINITY; 3], [f32::NEG_INFINITY; 3]];

/// The union of two boxes. Plain comparisons (one instruction each), where `f32::min`
/// also orders NaN (none here: box corners are numbers, at most infinite).
#[inline]
fn union(a: &Box3f, b: &Box3f) -> Box3f {
    let lo = |x: f32, y: f32| if y < x { y } else { x };
    let hi = |x: f32, y: f32| if y > x { y } else { x };
    [
        std::array::from_fn(|k| lo(a[0][k], b[0][k])),
        std::array::from_fn(|k| hi(a[1][k], b[1][k])),
    ]
}

/// Half the surface area of a box (0 for the empty box).
fn half_area(b: &Box3f) -> f32 {
    let d: [f32; 3] = std::array::from_fn(|k| (b[1][k] - b[0][k]).max(0.0));
    d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
}

/// Bins per axis of the surface-area heuristic.
const SAH_BINS: usize = 16;

/// Levels split by the heuristic; deeper ranges are split at their middle.
const SAH_DEPTH: u32 = 40;

/// The axis and leaf-aligned split (the size of the lower part along that axis) of `recs`
/// (more than [`LEAF`], their centres within `centres`, `extent` its sides, some above
/// zero) that the surface-area heuristic prefers.
fn sah_split(recs: &[Rec], centres: &Box3f, extent: &[f32; 3]) -> (usize, usize) {
    let n = recs.len();
    let scale: [f32; 3] = std::array::from_fn(|k| {
        if extent[k] > 0.0 {
            SAH_BINS as f32 / extent[k]
        } else {
            0.0
        }
    });
    // Two sets of bins, for the even and the odd triangles: consecutive triangles are
    // near each other and often fall in the same bin, and one set would chain each
    // triangle's update of a bin to the previous one's through memory.
    let mut count = [[[0usize; SAH_BINS]; 3]; 2];
    let mut boxes = [[[EMPTY_BOX; SAH_BINS]; 3]; 2];
    for pair in recs.chunks(2) {
        for (s, r) in pair.iter().enumerate() {
            for k in 0..3 {
                let i = (((r.centre[k] - centres[0][k]) * scale[k]) as usize).min(SAH_BINS - 1);
                count[s][k][i] += 1;
                boxes[s][k][i] = union(&boxes[s][k][i], &r.bbox);
            }
        }
    }
    let [mut count, odd_count] = count;
    let [mut boxes, odd_boxes] = boxes;
    for k in 0..3 {
        for i in 0..SAH_BINS {
            count[k][i] += odd_count[k][i];
            boxes[k][i] = union(&boxes[k][i], &odd_boxes[k][i]);
        }
    }
    let mut best = (f32::INFINITY, 0, split_at(n));
    for k in (0..3).filter(|&k| extent[k] > 0.0) {
        // The area of the upper part from each bin on.
        let mut above = [0.0f32; SAH_BINS];
        let mut b = EMPTY_BOX;
        for i in (1..SAH_BINS).rev() {
            b = union(&b, &boxes[k][i]);
            above[i] = half_area(&b);
        }
        let (mut b, mut below) = (EMPTY_BOX, 0);
        for i in 0..SAH_BINS - 1 {
            b = union(&b, &boxes[k][i]);
            below += count[k][i];
            if below == 0 || below == n {
                continue;
            }
            let cost = half_area(&b) * below as f32 + above[i + 1] * (n - below) as f32;
            if cost < best.0 {
                // Whole leaves below, at least one on each side.
                let mid = ((below + LEAF / 2) / LEAF * LEAF).clamp(LEAF, leaves(n) * LEAF - LEAF);
                best = (cost, k, mid);
            }
        }
    }
    (best.1, best.2)
}

/// Sorts `(Morton code, triangle)` pairs: one counting-sort pass by the top bits of the
/// 63-bit code (about one bucket per 8 pairs, at most 2¹⁸ buckets: a triangle placed to
/// within ~1/64 of the box on each axis), then every bucket sorted by the whole pair in
/// parallel. The same order as a comparison sort, in a fraction of the time; the bucket
/// count follows the input so that small meshes do not pay for a large table.
fn sort_keyed(keyed: &mut Vec<(u64, u32)>) {
    if keyed.len() < 1 << 12 {
        keyed.sort_unstable();
        return;
    }
    let top_bits = (keyed.len().ilog2() - 3).min(18);
    let bucket = |k: u64| (k >> (63 - top_bits)) as usize;
    let mut start = vec![0u32; (1 << top_bits) + 1];
    for &(k, _) in keyed.iter() {
        start[bucket(k) + 1] += 1;
    }
    for i in 0..1 << top_bits {
        start[i + 1] += start[i];
    }
    let mut out = vec![(0u64, 0u32); keyed.len()];
    let mut fill = start.clone();
    for &(k, t) in keyed.iter() {
        let b = bucket(k);
        out[fill[b] as usize] = (k, t);
        fill[b] += 1;
    }
    // The non-trivial buckets as disjoint slices, sorted side by side.
    let mut slices = Vec::new();
    let mut rest = out.as_mut_slice();
    for w in start.windows(2) {
        let (b, r) = rest.split_at_mut((w[1] - w[0]) as usize);
        if b.len() > 1 {
            slices.push(b);
        }
        rest = r;
    }
    slices
        .into_par_iter()
        .grained()
        .with_min_len(64)
        .for_each(|b| {
            // One crowded bucket (a detailed spot in a large box) still sorts in parallel.
            if b.len() > 1 << 15 {
                b.par_sort_unstable();
            } else {
                b.sort_unstable();
            }
        });
    *keyed = out;
}

impl Bvh {
    /// The boxes of leaf `n`'s triangles.
    fn leaf(&self, n: &Node) -> &LeafBoxes {
        debug_assert!(n.count > 0 && n.start as usize % LEAF == 0);
        &self.boxes[n.start as usize / LEAF]
    }

    /// Builds the hierarchy of `mesh`.
    pub fn new(mesh: &Mesh) -> Self {
        Self::over(mesh, morton_order(mesh))
    }

    /// The hierarchy of `mesh` with the triangles of each group together: triangle `t` is
    /// in group `group[t]` (below `groups`); groups are ordered by their first triangle in
    /// the Morton order, and each group's triangles by that order. A group then fills whole
    /// subtrees but at its two ends: the self-intersection check's certified patches,
    /// whose subtrees it does not look into.
    pub(crate) fn new_grouped(mesh: &Mesh, group: &[u32], groups: usize) -> Self {
        let order = morton_order(mesh);
        let mut rank = vec![0u32; order.len()];
        let mut first = vec![u32::MAX; groups];
        for (r, &t) in order.iter().enumerate() {
            rank[t as usize] = r as u32;
            let g = &mut first[group[t as usize] as usize];
            *g = (*g).min(r as u32);
        }
        let mut keyed: Vec<(u64, u32)> = order
            .par_iter()
            .grained()
            .map(|&t| {
                let g = first[group[t as usize] as usize];
                ((u64::from(g) << 32) | u64::from(rank[t as usize]), t)
            })
            .collect();
        sort_keyed(&mut keyed);
        Self::over(mesh, keyed.into_par_iter().grained().map(|(_, t)| t).collect())
    }

    /// The hierarchy of only those triangles of `mesh` whose boxes meet the closed box
    /// `within` (exact comparisons): all a query against a mesh inside `within` can find.
    /// A boolean of a large terrain and a small pit shell indexes only the terrain near
    /// the shell.
    pub fn new_within(mesh: &Mesh, within: &Aabb) -> Self {
        Self::over(mesh, morton_order_within(mesh, Some(within), true))
    }

    /// The hierarchy of `mesh` built for many queries: splits chosen by the surface-area
    /// heuristic (binned, at whole leaves) instead of at the middle of the Morton order.
    /// Costs four to five times [`Bvh::new`]'s build and gives tighter boxes, so that a
    /// traversal visits fewer node pairs: for a tree kept between booleans (two 5k
    /// spheres' pairs in a third of the time) or an index queried again and again.
    pub fn new_for_queries(mesh: &Mesh) -> Self {
        Self::new_by_area(mesh, SAH_DEPTH)
    }

    /// [`Bvh::new_for_queries`] with the heuristic's splits down to `levels` levels.
    fn new_by_area(mesh: &Mesh, levels: u32) -> Self {
        let n = mesh.triangles.len();
        if n == 0 {
            return Bvh::default();
        }
        let mut recs: Vec<Rec> = (0..n as u32)
            .into_par_iter()
            .grained()
            .with_min_len(1 << 12)
            .map(|t| {
                let bbox = round_out(&tri_box(mesh, t));
                let centre = std::array::from_fn(|k| 0.5 * bbox[0][k] + 0.5 * bbox[1][k]);
                Rec { centre, bbox, t }
            })
            .collect();
        let mut nodes = vec![EMPTY; 2 * leaves(n) - 1];
        Self::build_sah(&mut nodes, 0, 0, &mut recs, levels);
        let (order, boxes): (Vec<u32>, Vec<Box3f>) = recs
            .into_par_iter()
            .grained()
            .map(|r| (r.t, r.bbox))
            .unzip();
        Bvh {
            nodes,
            order,
            boxes: leaf_boxes(&boxes),
        }
    }

    /// Fills `nodes` like [`Bvh::build`], reordering `recs` as it goes: each range is
    /// split where the surface-area heuristic, on [`SAH_BINS`] bins of the triangles'
    /// box centres along each axis, puts it (the smaller of `area × triangles` summed over
    /// both sides), rounded to whole leaves so that every leaf but a range's last is full
    /// and a range of `n` triangles still takes `2⌈n/LEAF⌉ − 1` nodes. Below
    /// `levels` levels (the heuristic's), at the middle of the longest axis's order, which
    /// bounds the depth on any input.
    fn build_sah(
        nodes: &mut [Node],
        base: usize,
        offset: usize,
        recs: &mut [Rec],
        levels: u32,
    ) -> Box3f {
        let n = recs.len();
        let (bbox, centres) = recs.iter().fold((EMPTY_BOX, EMPTY_BOX), |(b, c), r| {
            (union(&b, &r.bbox), union(&c, &[r.centre, r.centre]))
        });
        if n <= LEAF {
            nodes[0] = Node {
                bbox,
                start: offset as u32,
                count: n as u32,
            };
            return bbox;
        }
        let extent: [f32; 3] = std::array::from_fn(|k| centres[1][k] - centres[0][k]);
        let longest = (0..3).fold(0, |m, k| if extent[k] > extent[m] { k } else { m });
        // (Not spread when every centre is the same, or the extent is not a number: boxes
        // beyond the range of `f32` round to infinities.)
        let spread = extent[longest] > 0.0;
        let (axis, mid) = if levels == 0 || !spread {
            (longest, split_at(n))
        } else {
            sah_split(recs, &centres, &extent)
        };
        if extent[axis] > 0.0 {
            // Ties broken on the other axes: of triangles in one plane across the split
            // (a face of a grid cube), each side keeps a compact patch.
            let key = |r: &Rec| [0, 1, 2].map(|i| r.centre[(axis + i) % 3]);
            recs.select_nth_unstable_by(mid, |x, y| {
                let (kx, ky) = (key(x), key(y));
                kx[0]
                    .total_cmp(&ky[0])
                    .then(kx[1].total_cmp(&ky[1]))
                    .then(kx[2].total_cmp(&ky[2]))
            });
        }
        let (head, rest) = nodes.split_at_mut(1);
        let (left, right) = rest.split_at_mut(2 * leaves(mid) - 1);
        let (lo, hi) = recs.split_at_mut(mid);
        let right_base = base + 1 + left.len();
        let build = |nodes: &mut [Node], base: usize, offset: usize, recs: &mut [Rec]| {
            Self::build_sah(nodes, base, offset, recs, levels.saturating_sub(1))
        };
        if n > 1 << 12 {
            crate::par::join(
                || build(left, base + 1, offset, lo),
                || build(right, right_base, offset + mid, hi),
            );
        } else {
            build(left, base + 1, offset, lo);
            build(right, right_base, offset + mid, hi);
        }
        head[0] = Node {
            bbox,
            start: right_base as u32,
            count: 0,
        };
        bbox
    }

    fn over(mesh: &Mesh, order: Vec<u32>) -> Self {
        if order.is_empty() {
            return Bvh::default();
        }
        let boxes: Vec<Box3f> = order
            .par_iter()
            .grained()
            .map(|&t| round_out(&tri_box(mesh, t)))
            .collect();
        let mut nodes = vec![EMPTY; 2 * leaves(order.len()) - 1];
        Self::build(&mut nodes, 0, 0, &boxes);
        Bvh {
            nodes,
            order,
            boxes: leaf_boxes(&boxes),
        }
    }

    /// Fills `nodes` (the pre-order subtree over the triangles whose boxes are `boxes`,
    /// the first at `offset` in the whole order; its first node has index `base`) and
    /// returns its box. Leaf boxes are unions of the outward-rounded triangle boxes, which
    /// is the outward rounding of the exact union (rounding is monotone).
    fn build(nodes: &mut [Node], base: usize, offset: usize, boxes: &[Box3f]) -> Box3f {
        if boxes.len() <= LEAF {
            let bbox = boxes[1..].iter().fold(boxes[0], |b, c| union(&b, c));
            nodes[0] = Node {
                bbox,
                start: offset as u32,
                count: boxes.len() as u32,
            };
            return bbox;
        }
        let mid = split_at(boxes.len());
        let (head, rest) = nodes.split_at_mut(1);
        let (left, right) = rest.split_at_mut(2 * leaves(mid) - 1);
        let (lo, hi) = boxes.split_at(mid);
        let right_base = base + 1 + left.len();
        let (bl, br) = if boxes.len() > 1 << 14 {
            crate::par::join(
                || Self::build(left, base + 1, offset, lo),
                || Self::build(right, right_base, offset + mid, hi),
            )
        } else {
            (
                Self::build(left, base + 1, offset, lo),
                Self::build(right, right_base, offset + mid, hi),
            )
        };
        let bbox = union(&bl, &br);
        head[0] = Node {
            bbox,
            start: right_base as u32,
            count: 0,
        };
        bbox
    }

    /// Every triangle of `mesh` (the mesh this tree was built from) whose exact box meets
    /// the closed box `b` (touching counts), in no particular order. Nodes are pruned on
    /// their outward-rounded `f32` boxes, leaves confirmed on the exact boxes.
    pub(crate) fn in_box(&self, mesh: &Mesh, b: &Box3) -> Vec<u32> {
        let mut out = Vec::new();
        if self.nodes.is_empty() {
            return out;
        }
        let q = round_out(b);
        let mut stack = vec![0usize];
        while let Some(i) = stack.pop() {
            let n = &self.nodes[i];
            if !overlaps_f(&n.bbox, &q) {
                continue;
            }
            if n.count > 0 {
                for &t in &self.order[n.start as usize..(n.start + n.count) as usize] {
                    if overlaps(&tri_box(mesh, t), b) {
                        out.push(t);
                    }
                }
            } else {
                stack.push(n.start as usize);
                stack.push(i + 1);
            }
        }
        out
    }

    /// A box that holds every indexed triangle (the root's box, rounded outward to
    /// `f32`); `None` for an empty tree.
    pub fn bounds(&self) -> Option<Aabb> {
        let root = self.nodes.first()?;
        Some(Aabb {
            min: root.bbox[0].map(f64::from),
            max: root.bbox[1].map(f64::from),
        })
    }

    /// Number of triangles indexed.
    pub fn len(&self) -> usize {
        self.order.len()
    }

    /// True when no triangle is indexed.
    pub fn is_empty(&self) -> bool {
        self.order.is_empty()
    }

    /// Every pair `(triangle of mesh, triangle of other_mesh)` whose exact boxes overlap
    /// (closed boxes: touching counts). `self` must be built from `mesh`, `other` from
    /// `other_mesh`. Parallel; the pairs come sorted.
    pub fn overlapping_pairs(
        &self,
        mesh: &Mesh,
        other: &Bvh,
        other_mesh: &Mesh,
    ) -> Vec<(u32, u32)> {
        if self.is_empty() || other.is_empty() {
            return Vec::new();
        }
        let q = Query {
            a: self,
            b: other,
            ma: mesh,
            mb: other_mesh,
            keep: &|_, _| true,
            exact: true,
            settled: None,
        };
        sort_pairs(q.run(Task::Below(0, 0)), mesh.triangles.len(), false)
    }
}

impl Bvh {
    /// Every pair `(i, j)`, `i < j`, of triangles of `mesh` (the mesh this tree was built
    /// from) whose exact boxes overlap, in no particular order. Each node pair is visited
    /// once (a self-traversal), not twice as `overlapping_pairs(mesh, self, mesh)` would.
    #[cfg(test)]
    pub fn self_pairs(&self, mesh: &Mesh) -> Vec<(u32, u32)> {
        self.self_pairs_where(mesh, &|_, _| true)
    }

    /// The pairs of [`Bvh::self_pairs`] for which `keep(i, j)` (with `i < j`) holds,
    /// tested in parallel as the traversal finds them: the candidates are never stored.
    #[cfg(test)]
    pub fn self_pairs_where(
        &self,
        mesh: &Mesh,
        keep: &(dyn Fn(u32, u32) -> bool + Sync),
    ) -> Vec<(u32, u32)> {
        self.self_query(mesh, keep, true, None)
    }

    /// Like [`Bvh::self_pairs_where`], but the candidates are the pairs whose boxes overlap
    /// once rounded outward to `f32`: every pair of [`Bvh::self_pairs`] and possibly a few
    /// whose boxes only come within `f32` rounding of each other. For a `keep` that is an
    /// exact test of its own (such as a triangle–triangle intersection test), which then
    /// spares the exact box comparison of every candidate. With `settled` (per node, from
    /// [`Bvh::common_labels`]), two nodes that share a label, or one node with one, are
    /// not looked into: every pair of triangles below them shares that label, and `keep`
    /// must turn down every pair that shares a label.
    pub fn self_candidates_where(
        &self,
        mesh: &Mesh,
        keep: &(dyn Fn(u32, u32) -> bool + Sync),
        settled: Option<&[Labels]>,
    ) -> Vec<(u32, u32)> {
        self.self_query(mesh, keep, false, settled)
    }

    /// Per node, the labels (up to four; the other places [`NO_LABEL`]) that every
    /// triangle below it has among its own four (`labels(t)`, [`NO_LABEL`] where it has
    /// fewer): the `settled` of [`Bvh::self_candidates_where`]. Labels are such that two
    /// triangles sharing one need no test (the self-intersection check's certified fan
    /// runs and patches). A pass over the leaves' triangles and the nodes.
    pub fn common_labels(&self, labels: impl Fn(u32) -> Labels + Sync) -> Vec<Labels> {
        // The leaves' in parallel (the reads of the labels), then the inner nodes': their
        // children come after them (pre-order), so from the last node back each node's
        // children are done before it.
        let mut common: Vec<Labels> = self
            .nodes
            .par_iter()
            .grained()
            .map(|n| {
                if n.count == 0 {
                    return [NO_LABEL; 4];
                }
                let ts = &self.order[n.start as usize..(n.start + n.count) as usize];
                ts[1..]
                    .iter()
                    .fold(labels(ts[0]), |c, &t| shared_labels(c, labels(t)))
            })
            .collect();
        for x in (0..self.nodes.len()).rev() {
            let n = &self.nodes[x];
            if n.count == 0 {
                common[x] = shared_labels(common[x + 1], common[n.start as usize]);
            }
        }
        common
    }

    /// The self-traversal, confirming rounded-box overlaps on the exact boxes or not.
    fn self_query(
        &self,
        mesh: &Mesh,
        keep: &(dyn Fn(u32, u32) -> bool + Sync),
        exact: bool,
        settled: Option<&[Labels]>,
    ) -> Vec<(u32, u32)> {
        if self.is_empty() {
            return Vec::new();
        }
        let q = Query {
            a: self,
            b: self,
            ma: mesh,
            mb: mesh,
            keep,
            exact,
            settled,
        };
        q.run(Task::Within(0))
    }
}

/// No label: an empty place of a [`Bvh::common_labels`] entry.
pub const NO_LABEL: u32 = u32::MAX;

/// A triangle's or a node's labels ([`Bvh::common_labels`]): up to four, the other places
/// [`NO_LABEL`].
pub type Labels = [u32; 4];

/// The labels of `a` that are also in `b` (first, the rest [`NO_LABEL`]).
fn shared_labels(a: Labels, b: Labels) -> Labels {
    let mut out = [NO_LABEL; 4];
    let mut k = 0;
    for l in a {
        if l != NO_LABEL && b.contains(&l) {
            out[k] = l;
            k += 1;
        }
    }
    out
}

/// A unit of traversal work: the pairs inside one subtree (a self-query), or the pairs
/// between two subtrees.
#[derive(Clone, Copy, Debug)]
enum Task {
    Within(u32),
    Below(u32, u32),
}

/// Node pairs handed out as parallel tasks: enough for load balance on many cores, few
/// enough that a small query is not split into tasks smaller than their overhead.
const TASKS: usize = 256;

/// A tree-vs-tree traversal.
struct Query<'a> {
    a: &'a Bvh,
    b: &'a Bvh,
    ma: &'a Mesh,
    mb: &'a Mesh,
    /// Which overlapping pairs to report.
    keep: &'a (dyn Fn(u32, u32) -> bool + Sync),
    /// Confirm each overlap of rounded boxes on the exact boxes.
    exact: bool,
    /// A self-query's labels per node ([`Bvh::common_labels`]): nodes that share one are
    /// not looked into.
    settled: Option<&'a [Labels]>,
}

impl Query<'_> {
    /// Whether every pair of triangles below nodes `x` and `y` (of a self-query) shares
    /// a label: nothing there to report.
    #[inline]
    fn settled(&self, x: u32, y: u32) -> bool {
        self.settled
            .is_some_and(|c| shared_labels(c[x as usize], c[y as usize])[0] != NO_LABEL)
    }

    /// Every reported pair under `root`: the task is expanded breadth-first into a
    /// frontier of up to [`TASKS`] independent tasks, each then traversed depth-first on
    /// its own (parallel) with an explicit stack into one vector; the vectors are joined
    /// once at the end. No allocation per node pair.
    fn run(&self, root: Task) -> Vec<(u32, u32)> {
        let mut out = Vec::new();
        // Tasks are queued only for boxes that overlap (a pair of nodes is tested before
        // it is queued, not after).
        if let Task::Below(x, y) = root {
            if !overlaps_f(
                &self.a.nodes[x as usize].bbox,
                &self.b.nodes[y as usize].bbox,
            ) {
                return out;
            }
        }
        let mut frontier = vec![root];
        while frontier.len() < TASKS && !frontier.is_empty() {
            let mut next = Vec::with_capacity(2 * frontier.len());
            for t in frontier {
                self.expand(t, &mut next, &mut out);
            }
            frontier = next;
            // Little work in all (a small mesh): finish on this thread.
            if frontier.len() < 4 && self.a.len() + self.b.len() < 1 << 12 {
                break;
            }
        }
        let parts: Vec<Vec<(u32, u32)>> = if frontier.len() < 4 {
            let mut v = Vec::new();
            for t in frontier {
                self.traverse(t, &mut v);
            }
            vec![v]
        } else {
            frontier
                .into_par_iter()
                .grained()
                .map(|t| {
                    let mut v = Vec::new();
                    self.traverse(t, &mut v);
                    v
                })
                .collect()
        };
        out.reserve(parts.iter().map(Vec::len).sum());
        for p in parts {
            out.extend(p);
        }
        out
    }

    /// One step of the traversal: the sub-tasks of `task` go to `next`, pairs of leaves
    /// are tested and their pairs go to `out`.
    #[inline]
    fn expand(&self, task: Task, next: &mut Vec<Task>, out: &mut Vec<(u32, u32)>) {
        match task {
            Task::Within(x) => {
                let n = &self.a.nodes[x as usize];
                if self.settled(x, x) {
                    return;
                }
                if n.count > 0 {
                    self.leaf_within(n, out);
                } else {
                    let (l, r) = (x + 1, n.start);
                    next.extend([Task::Within(l), Task::Within(r)]);
                    let nodes = &self.a.nodes;
                    if overlaps_f(&nodes[l as usize].bbox, &nodes[r as usize].bbox)
                        && !self.settled(l, r)
                    {
                        next.push(Task::Below(l, r));
                    }
                }
            }
            Task::Below(x, y) => {
                let (na, nb) = (&self.a.nodes[x as usize], &self.b.nodes[y as usize]);
                debug_assert!(overlaps_f(&na.bbox, &nb.bbox));
                let split_a = match (na.count > 0, nb.count > 0) {
                    (true, true) => {
                        self.leaves(na, nb, out);
                        return;
                    }
                    (false, true) => true,
                    (true, false) => false,
                    (false, false) => {
                        let vol =
                            |n: &Node| (0..3).map(|k| n.bbox[1][k] - n.bbox[0][k]).product::<f32>();
                        vol(na) >= vol(nb)
                    }
                };
                if split_a {
                    for c in [x + 1, na.start] {
                        if overlaps_f(&self.a.nodes[c as usize].bbox, &nb.bbox)
                            && !self.settled(c, y)
                        {
                            next.push(Task::Below(c, y));
                        }
                    }
                } else {
                    for c in [y + 1, nb.start] {
                        if overlaps_f(&na.bbox, &self.b.nodes[c as usize].bbox)
                            && !self.settled(x, c)
                        {
                            next.push(Task::Below(x, c));
                        }
                    }
                }
            }
        }
    }

    /// Traverses `task` depth-first on this thread.
    fn traverse(&self, task: Task, out: &mut Vec<(u32, u32)>) {
        let mut stack = vec![task];
        while let Some(t) = stack.pop() {
            self.expand(t, &mut stack, out);
        }
    }

    /// Pairs among the triangles of one leaf (a self-query).
    fn leaf_within(&self, n: &Node, out: &mut Vec<(u32, u32)>) {
        let range = n.start as usize..(n.start + n.count) as usize;
        let (ts, bs) = (&self.a.order[range], self.a.leaf(n));
        for i in 0..ts.len() {
            for j in i + 1..ts.len() {
                let (p, q) = (ts[i].min(ts[j]), ts[i].max(ts[j]));
                if overlaps_f(&bs.get(i), &bs.get(j))
                    && (!self.exact || overlaps(&tri_box(self.ma, p), &tri_box(self.ma, q)))
                    && (self.keep)(p, q)
                {
                    out.push((p, q));
                }
            }
        }
    }

    /// Pairs between two leaves; in a self-query reported as `(min, max)`. The rounded
    /// boxes filter, the exact boxes decide.
    fn leaves(&self, na: &Node, nb: &Node, out: &mut Vec<(u32, u32)>) {
        let same = std::ptr::eq(self.a, self.b);
        let ra = na.start as usize..(na.start + na.count) as usize;
        let rb = nb.start as usize..(nb.start + nb.count) as usize;
        let (ta, ba) = (&self.a.order[ra], self.a.leaf(na));
        let (tb, bb) = (&self.b.order[rb], self.b.leaf(nb));
        // Only the triangles that reach into the other leaf's box can meet any of its
        // triangles: of two leaves that overlap at a corner, a few on each side.
        // (Masked to the leaves' triangles: an empty place meets a box with infinite
        // sides, boxes of coordinates beyond `f32`'s range.)
        let places = |n: &Node| (1u32 << n.count) - 1;
        let near_a = ba.overlapping(&nb.bbox) & places(na);
        let near_b = bb.overlapping(&na.bbox) & places(nb);
        if near_a == 0 || near_b == 0 {
            return;
        }
        let mut rest_a = near_a;
        while rest_a != 0 {
            let k = rest_a.trailing_zeros() as usize;
            rest_a &= rest_a - 1;
            let i = ta[k];
            let mut hits = bb.overlapping(&ba.get(k)) & near_b;
            let mut exact_i = None;
            while hits != 0 {
                let m = hits.trailing_zeros() as usize;
                hits &= hits - 1;
                let j = tb[m];
                let confirmed = !self.exact || {
                    let ei = *exact_i.get_or_insert_with(|| tri_box(self.ma, i));
                    overlaps(&ei, &tri_box(self.mb, j))
                };
                if confirmed && (self.keep)(i.min(j), i.max(j)) {
                    out.push(if same { (i.min(j), i.max(j)) } else { (i, j) });
                }
            }
        }
    }
}

/// `pairs` sorted, without repeats when `unique`, each first id below `n`: bucketed by the
/// first id (a counting pass and one scatter), then each bucket's second ids sorted on
/// their own, buckets in parallel. Linear but for the buckets' small sorts: a comparison
/// sort of all pairs was most of the self-check of a CAD model whose slivers are looked at
/// through many pieces (8.9M candidates, 1.0M distinct). Fewer pairs than half of `n`
/// (two meshes' candidates along their seam) go through a comparison sort on all threads
/// instead: the bucketing's arrays of `n` entries, filled on one thread, cost more there
/// (130k pairs of 2M triangles: 47 ms on one thread, 19 ms on 16).
pub(crate) fn sort_pairs(pairs: Vec<(u32, u32)>, n: usize, unique: bool) -> Vec<(u32, u32)> {
    if pairs.len() < (1 << 14).max(n / 2) {
        // As single `u64` keys, each pair's ids side by side in as few bits as the largest
        // need (`j` below `2^bj`, so the keys' order is the pairs'): a radix sort of those
        // bits for a few thousand pairs (the candidates of two small meshes), where a
        // comparison sort costs several times more; a comparison sort on all threads for
        // more.
        let bits = |x: u32| 32 - x.leading_zeros();
        let bj = bits(pairs.iter().map(|p| p.1).max().unwrap_or(0));
        let bi = bits(pairs.iter().map(|p| p.0).max().unwrap_or(0));
        let mut keys: Vec<u64> = pairs
            .into_iter()
            .map(|(i, j)| u64::from(i) << bj | u64::from(j))
            .collect();
        if keys.len() < 1 << 14 {
            radix_sort(&mut keys, bi + bj);
        } else {
            keys.par_sort_unstable();
        }
        if unique {
            keys.dedup();
        }
        let low = (1u64 << bj) - 1;
        return keys
            .into_iter()
            .map(|k| ((k >> bj) as u32, (k & low) as u32))
            .collect();
    }
    let mut start = vec![0usize; n + 1];
    for &(i, _) in &pairs {
        start[i as usize + 1] += 1;
    }
    for k in 0..n {
        start[k + 1] += start[k];
    }
    let mut second = vec![0u32; pairs.len()];
    let mut next = start.clone();
    for &(i, j) in &pairs {
        let at = &mut next[i as usize];
        second[*at] = j;
        *at += 1;
    }
    drop(pairs);
    let mut kept = vec![0usize; n];
    sort_buckets(&start, 0, &mut second, &mut kept, unique);
    let mut out = Vec::with_capacity(kept.iter().sum());
    for (i, &k) in kept.iter().enumerate() {
        out.extend(
            second[start[i]..start[i] + k]
                .iter()
                .map(|&j| (i as u32, j)),
        );
    }
    out
}

/// Sorts `keys`, all below `2^bits`, by their bytes from the lowest (a stable counting
/// sort each); a byte all keys share is skipped.
fn radix_sort(keys: &mut Vec<u64>, bits: u32) {
    let mut other = vec![0u64; keys.len()];
    for shift in (0..bits).step_by(8) {
        let mut count = [0usize; 256];
        for &k in keys.iter() {
            count[(k >> shift) as usize & 0xff] += 1;
        }
        if count.contains(&keys.len()) {
            continue;
        }
        let mut at = 0;
        for c in count.iter_mut() {
            (*c, at) = (at, at + *c);
        }
        for &k in keys.iter() {
            let d = (k >> shift) as usize & 0xff;
            other[count[d]] = k;
            count[d] += 1;
        }
        std::mem::swap(keys, &mut other);
    }
}

/// Sorts each bucket of `second` (the buckets `first ..` of [`sort_pairs`], `second`
/// beginning at bucket `first`), keeping in `kept` how many of its ids it keeps (at its
/// front).
fn sort_buckets(
    start: &[usize],
    first: usize,
    second: &mut [u32],
    kept: &mut [usize],
    unique: bool,
) {
    let n = kept.len();
    if n > 4096 {
        let mid = n / 2;
        let (sl, sr) = second.split_at_mut(start[first + mid] - start[first]);
        let (kl, kr) = kept.split_at_mut(mid);
        crate::par::join(
            || sort_buckets(start, first, sl, kl, unique),
            || sort_buckets(start, first + mid, sr, kr, unique),
        );
        return;
    }
    let base = start[first];
    for (b, k) in kept.iter_mut().enumerate() {
        let s = &mut second[start[first + b] - base..start[first + b + 1] - base];
        s.sort_unstable();
        *k = if unique && !s.is_empty() {
            let mut w = 1;
            for r in 1..s.len() {
                if s[r] != s[w - 1] {
                    s[w] = s[r];
                    w += 1;
                }
            }
            w
        } else {
            s.len()
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::uv_sphere;

    #[test]
    fn sorting_pairs_by_buckets_is_sorting_them() {
        let mut rng = crate::test_util::Rng(99);
        // Small (a radix sort: also with ids of 31 bits, and all pairs the same), large
        // with few and with many buckets (the buckets split between threads), with many
        // repeats, and large but fewer than half the first ids (a comparison sort on all
        // threads).
        for (count, n, spread) in [
            (100, 10, 50),
            (6_400, 5_000, 3_000),
            (3_000, 1 << 31, 1 << 31),
            (500, 1, 1),
            (50_000, 7, 1000),
            (300_000, 20_000, 40),
            (40_000, 1_000_000, 1000),
        ] {
            let pairs: Vec<(u32, u32)> = (0..count)
                .map(|_| {
                    let i = (rng.next() % n) as u32;
                    (i, (rng.next() % spread) as u32 + i / 2)
                })
                .collect();
            for unique in [false, true] {
                let mut want = pairs.clone();
                want.sort_unstable();
                if unique {
                    want.dedup();
                }
                assert_eq!(sort_pairs(pairs.clone(), n as usize, unique), want);
            }
        }
        assert!(sort_pairs(Vec::new(), 0, true).is_empty());
    }

    #[test]
    fn bucketed_sort_matches_a_comparison_sort() {
        // Spread codes, codes crowded into one top bucket, and repeated codes.
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        let spread: Vec<(u64, u32)> = (0..100_000).map(|t| (next() >> 1, t)).collect();
        let crowded: Vec<(u64, u32)> = (0..100_000)
            .map(|t| ((0x5u64 << 59) | (next() >> 30), t))
            .collect();
        let repeated: Vec<(u64, u32)> = (0..50_000).map(|t| ((next() % 7) << 40, t)).collect();
        for keys in [spread, crowded, repeated] {
            let mut want = keys.clone();
            want.sort_unstable();
            let mut got = keys;
            sort_keyed(&mut got);
            assert!(got == want);
        }
    }

    #[test]
    fn broad_phase_finds_exactly_the_brute_force_pairs() {
        let a = uv_sphere([0.0; 3], 1.0, 24, 12);
        let b = uv_sphere([0.5, 0.1, 0.0], 1.0, 20, 10);
        let pairs = Bvh::new(&a).overlapping_pairs(&a, &Bvh::new(&b), &b);
        let mut want = Vec::new();
        for i in 0..a.triangles.len() {
            for j in 0..b.triangles.len() {
                if overlaps(&tri_box(&a, i as u32), &tri_box(&b, j as u32)) {
                    want.push((i as u32, j as u32));
                }
            }
        }
        assert!(!want.is_empty());
        assert_eq!(pairs.len(), want.len());
        assert!(pairs == want);
        assert!(all_overlapping_pairs(&a, &b) == want);
        // Boxes that only touch (cubes sharing a face, an edge) overlap.
        let (c, d) = (Mesh::unit_cube(), Mesh::cuboid([1.0; 3], [2.0; 3]));
        let tree = Bvh::new(&c).overlapping_pairs(&c, &Bvh::new(&d), &d);
        assert!(!tree.is_empty() && all_overlapping_pairs(&c, &d) == tree);
    }

    #[test]
    fn trees_within_the_other_box_find_the_same_pairs() {
        // A small sphere over a large height field: most of the terrain is left out of
        // its tree; and two cubes that only touch along a face (closed boxes).
        let terrain = crate::shapes::heightfield([-5.0, -5.0], [5.0, 5.0], 60, 60, |x, y| {
            0.1 * (x * y).sin()
        });
        let ball = uv_sphere([0.3, -0.2, 0.0], 0.7, 20, 10);
        let touching = (
            Mesh::unit_cube(),
            Mesh::cuboid([1.0, 0.2, 0.2], [2.0, 0.8, 0.8]),
        );
        for (a, b) in [(terrain, ball), touching] {
            let (box_a, box_b) = (a.bounds().unwrap(), b.bounds().unwrap());
            let (wa, wb) = (Bvh::new_within(&a, &box_b), Bvh::new_within(&b, &box_a));
            let want = Bvh::new(&a).overlapping_pairs(&a, &Bvh::new(&b), &b);
            assert!(!want.is_empty());
            assert!(wa.overlapping_pairs(&a, &wb, &b) == want);
            assert!(wa.len() <= a.triangles.len() && wb.len() <= b.triangles.len());
        }
        let terrain = crate::shapes::heightfield([-5.0, -5.0], [5.0, 5.0], 60, 60, |_, _| 0.0);
        let small = Bvh::new_within(&terrain, &uv_sphere([0.0; 3], 0.5, 8, 4).bounds().unwrap());
        assert!(
            small.len() < terrain.triangles.len() / 20,
            "{}",
            small.len()
        );
    }

    #[test]
    fn meeting_a_box_keeps_exactly_the_triangles_whose_boxes_meet_it() {
        // A terrain of 20,000 triangles (split into parts between threads) and a sphere
        // of 480 (one part); random boxes, boxes whose sides pass exactly through
        // vertices (touching counts), a box that is one vertex, and one beside the mesh.
        let mut rng = crate::test_util::Rng(0xb0c5);
        let terrain = crate::shapes::heightfield([-5.0, -5.0], [5.0, 5.0], 100, 100, |x, y| {
            0.3 * (x + 0.5 * y).sin()
        });
        let ball = uv_sphere([0.3, -0.2, 0.0], 0.7, 20, 13);
        for m in [&terrain, &ball] {
            let mut boxes = Vec::new();
            for _ in 0..40 {
                let (c, r): ([f64; 3], [f64; 3]) = (
                    std::array::from_fn(|_| 10.0 * rng.unit() - 5.0),
                    std::array::from_fn(|_| 3.0 * rng.unit()),
                );
                boxes.push(Aabb {
                    min: std::array::from_fn(|k| c[k] - r[k]),
                    max: std::array::from_fn(|k| c[k] + r[k]),
                });
            }
            for _ in 0..40 {
                let n = m.positions.len() as u64;
                let (p, q) = (
                    m.positions[(rng.next() % n) as usize],
                    m.positions[(rng.next() % n) as usize],
                );
                boxes.push(Aabb {
                    min: std::array::from_fn(|k| p[k].min(q[k])),
                    max: std::array::from_fn(|k| p[k].max(q[k])),
                });
                boxes.push(Aabb { min: p, max: p });
            }
            boxes.push(Aabb {
                min: [6.0, 0.0, 0.0],
                max: [7.0, 1.0, 1.0],
            });
            for w in &boxes {
                let wb = [w.min, w.max];
                let want: Vec<u32> = (0..m.triangles.len() as u32)
                    .filter(|&t| overlaps(&tri_box(m, t), &wb))
                    .collect();
                let frame = want.iter().fold(None::<Aabb>, |b, &t| {
                    let [lo, hi] = tri_box(m, t);
                    Some(b.map_or(Aabb { min: lo, max: hi }, |b| b.grown(&lo).grown(&hi)))
                });
                assert_eq!(meeting_box(m, w), (want, frame), "{w:?}");
            }
        }
    }

    /// Checks the structure of `bvh` over `mesh`: pre-order layout, each node's box
    /// the union of its children's (leaves: of their triangles' rounded boxes), leaves of
    /// 1 to [`LEAF`] triangles, all full but the last of each range, every triangle once.
    /// Returns the depth and the summed half-areas of the inner nodes' boxes.
    fn check_tree(bvh: &Bvh, mesh: &Mesh) -> (usize, f64) {
        let n = mesh.triangles.len();
        assert_eq!(bvh.nodes.len(), 2 * leaves(n) - 1);
        let mut seen = bvh.order.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..n as u32).collect::<Vec<_>>());
        let boxes: Vec<Box3f> = (0..n).map(|i| bvh.boxes[i / LEAF].get(i % LEAF)).collect();
        for (&t, b) in bvh.order.iter().zip(&boxes) {
            assert_eq!(*b, round_out(&tri_box(mesh, t)));
        }
        // (node, first triangle, triangles, depth)
        let mut stack = vec![(0usize, 0usize, n, 1usize)];
        let (mut depth, mut area) = (0, 0.0);
        while let Some((i, first, count, d)) = stack.pop() {
            depth = depth.max(d);
            let node = &bvh.nodes[i];
            let want = boxes[first..first + count]
                .iter()
                .fold(EMPTY_BOX, |b, x| union(&b, x));
            assert_eq!(node.bbox, want, "node {i}");
            if node.count > 0 {
                assert_eq!((node.start as usize, node.count as usize), (first, count));
                assert!(count <= LEAF);
                continue;
            }
            area += f64::from(half_area(&node.bbox));
            let right = node.start as usize;
            // The left subtree's nodes lie between this node and the right child.
            let left_leaves = (right - i) / 2;
            let below = left_leaves * LEAF;
            assert!(below > 0 && below < count, "node {i}: {below} of {count}");
            stack.push((i + 1, first, below, d + 1));
            stack.push((right, first + below, count - below, d + 1));
        }
        (depth, area)
    }

    #[test]
    fn trees_built_for_queries_find_exactly_the_pairs_of_the_boxes() {
        let mut rng = crate::test_util::Rng(0x5a4);
        // Random triangles in a box, and bunched at one end (sizes spread over six
        // orders of magnitude); many copies of one triangle (all centres equal);
        // triangles along a line, each 1.2 times further out and larger than the last
        // (the heuristic splits off one leaf at a time, past the depth where it stops); a
        // terrain; a sphere; a grid of unit cubes (centres tied on every axis); and
        // triangles too large for `f32`.
        let soup = |rng: &mut crate::test_util::Rng, n: usize, skew: bool| {
            let mut positions = Vec::new();
            for _ in 0..n {
                let c: [f64; 3] = std::array::from_fn(|_| {
                    let u = rng.unit();
                    if skew {
                        1e-6 * (1e6f64).powf(u)
                    } else {
                        u
                    }
                });
                let r = if skew { 1e-7 + 0.01 * c[0] } else { 0.05 };
                for _ in 0..3 {
                    positions.push(std::array::from_fn(|k| c[k] + r * (rng.unit() - 0.5)));
                }
            }
            let triangles = (0..n as u32)
                .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
                .collect();
            Mesh::new(positions, triangles).unwrap()
        };
        let copies = Mesh::new(
            vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            vec![[0, 1, 2]; 300],
        )
        .unwrap();
        let line = {
            let positions = (0..400)
                .flat_map(|i| {
                    let (x, r) = (1.2f64.powi(i), 0.15 * 1.2f64.powi(i));
                    [[x - r, 0.0, 0.0], [x + r, 0.0, 0.0], [x, r, 0.0]]
                })
                .collect();
            Mesh::new(
                positions,
                (0..400).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect(),
            )
            .unwrap()
        };
        let terrain = crate::shapes::heightfield([-5.0, -5.0], [5.0, 5.0], 40, 40, |x, y| {
            0.3 * (x + 0.5 * y).sin()
        });
        let cubes = {
            let mut m = Mesh::default();
            for i in 0..6 {
                for j in 0..6 {
                    let lo = [f64::from(i), f64::from(j), 0.0];
                    m.append(&Mesh::cuboid(lo, [lo[0] + 1.0, lo[1] + 1.0, 1.0]))
                        .unwrap();
                }
            }
            m
        };
        // Beyond the range of `f32`: boxes and centres round to infinities.
        let mut huge = soup(&mut rng, 200, false);
        for p in &mut huge.positions {
            *p = p.map(|x| 1e39 * (x - 0.5));
        }
        let meshes = [
            soup(&mut rng, 3000, false),
            soup(&mut rng, 5000, true),
            copies,
            line,
            terrain,
            uv_sphere([0.2, 0.1, 0.0], 1.0, 40, 20),
            cubes,
            huge,
        ];
        let other = uv_sphere([0.5, 0.5, 0.5], 0.6, 24, 12);
        let other_tree = Bvh::new(&other);
        for (k, m) in meshes.iter().enumerate() {
            let tree = Bvh::new_for_queries(m);
            let (depth, _) = check_tree(&tree, m);
            let bound = SAH_DEPTH as usize + 2 + leaves(m.triangles.len()).ilog2() as usize;
            assert!(depth <= bound, "mesh {k}: depth {depth}");
            let mut want = Vec::new();
            for i in 0..m.triangles.len() as u32 {
                for j in 0..other.triangles.len() as u32 {
                    if overlaps(&tri_box(m, i), &tri_box(&other, j)) {
                        want.push((i, j));
                    }
                }
            }
            assert!(
                tree.overlapping_pairs(m, &other_tree, &other) == want,
                "mesh {k}"
            );
            let (mut got, mut want) = (tree.self_pairs(m), Bvh::new(m).self_pairs(m));
            got.sort_unstable();
            want.sort_unstable();
            assert!(got == want, "mesh {k}");
            assert!(!want.is_empty(), "mesh {k}");
        }
        // The line splits one or two leaves off at a time: 26 levels, 50 leaves. With the
        // heuristic's splits down to 10 levels, the middle splits below halve the rest.
        let line = &meshes[3];
        let (depth, _) = check_tree(&Bvh::new_for_queries(line), line);
        assert!(depth > 20, "{depth}");
        let shallow = Bvh::new_by_area(line, 10);
        let (depth, _) = check_tree(&shallow, line);
        assert!(depth <= 10 + 2 + leaves(line.triangles.len()).ilog2() as usize);
        let (mut got, mut want) = (shallow.self_pairs(line), Bvh::new(line).self_pairs(line));
        got.sort_unstable();
        want.sort_unstable();
        assert!(got == want);
        assert!(Bvh::new_for_queries(&Mesh::default()).is_empty());
    }

    #[test]
    fn trees_built_for_queries_have_smaller_boxes() {
        // The heuristic's aim, on two spheres (one of them of 5k triangles, as in the
        // benchmarks): less summed area of inner boxes than the middle splits of the
        // Morton order, by a margin.
        for m in [
            uv_sphere([0.0; 3], 1.0, 71, 36),
            uv_sphere([3.0; 3], 2.0, 33, 17),
        ] {
            let (_, sah) = check_tree(&Bvh::new_for_queries(&m), &m);
            let (_, morton) = check_tree(&Bvh::new(&m), &m);
            assert!(sah < 0.8 * morton, "{sah} vs {morton}");
        }
    }

    #[test]
    fn box_leaves_cover_every_triangle_once() {
        let m = uv_sphere([3.0; 3], 2.0, 33, 17);
        let bvh = Bvh::new(&m);
        let mut seen = bvh.order.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..m.triangles.len() as u32).collect::<Vec<_>>());
        assert!(Bvh::new(&Mesh::default())
            .overlapping_pairs(&Mesh::default(), &bvh, &m)
            .is_empty());
    }

    #[test]
    fn self_pairs_match_brute_force() {
        let m = uv_sphere([0.0; 3], 1.0, 20, 10);
        let mut got = Bvh::new(&m).self_pairs(&m);
        got.sort_unstable();
        let mut want = Vec::new();
        for i in 0..m.triangles.len() as u32 {
            for j in i + 1..m.triangles.len() as u32 {
                if overlaps(&tri_box(&m, i), &tri_box(&m, j)) {
                    want.push((i, j));
                }
            }
        }
        assert_eq!(got.len(), want.len());
        assert!(got == want);
        // The rounded-box candidates hold every exact pair, and the others have boxes
        // that come within f32 rounding (here |x| ≤ 1: 2⁻²³) of each other.
        let cand = Bvh::new(&m).self_candidates_where(&m, &|_, _| true, None);
        assert!(want.iter().all(|p| cand.contains(p)));
        for &(i, j) in &cand {
            let (a, b) = (tri_box(&m, i), tri_box(&m, j));
            let gap = (0..3)
                .map(|k| (a[0][k] - b[1][k]).max(b[0][k] - a[1][k]))
                .fold(f64::NEG_INFINITY, f64::max);
            assert!(i < j && gap < 2f64.powi(-22), "{i} {j} {gap}");
        }
        // Boxes 1e-12 apart: not an exact pair, but a candidate after rounding to f32.
        let mut soup = Mesh::cuboid([0.0; 3], [1.0; 3]).to_soup();
        soup.extend(Mesh::cuboid([1.0 + 1e-12, 0.0, 0.0], [2.0, 1.0, 1.0]).to_soup());
        let pair = Mesh::from_soup(&soup);
        let bvh = Bvh::new(&pair);
        let exact = bvh.self_pairs(&pair);
        let cands = bvh.self_candidates_where(&pair, &|_, _| true, None);
        assert!(exact.iter().all(|p| cands.contains(p)));
        assert!(cands.iter().any(|&(i, j)| (i < 12) != (j < 12)));
        assert!(exact.iter().all(|&(i, j)| (i < 12) == (j < 12)));
    }

    #[test]
    fn touching_boxes_count() {
        let a = Mesh::cuboid([0.0; 3], [1.0; 3]);
        let b = Mesh::cuboid([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]);
        let pairs = Bvh::new(&a).overlapping_pairs(&a, &Bvh::new(&b), &b);
        // a's x = 1 face (triangles 10, 11) touches b's x = 1 face (triangles 8, 9).
        for p in [(10, 8), (10, 9), (11, 8), (11, 9)] {
            assert!(pairs.contains(&p), "{p:?}");
        }
    }
}
