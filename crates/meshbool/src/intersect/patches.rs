//! Patches certified free of self-intersection: connected pieces of a mesh, up to
//! [`CAPS`] triangles each, proven not to meet themselves anywhere but in the vertices
//! and edges their triangles share. Where a mesh has large triangles (a CAD part's
//! slivers side by side), the self-intersection check skips every pair of triangles in
//! one patch, and every node of its tree (over the whole triangles or the large ones'
//! pieces) whose triangles are all of one patch, so that it looks only at pairs near the
//! patches' boundaries.
//!
//! A patch is grown across edges of exactly two triangles (used once in each direction)
//! from a seed, taking triangles that keep the seed's orientation seen along one coordinate
//! axis (the one nearest the seed's normal): every `orient2d` of a patch triangle in that
//! projection has one sign. It stays a disk (a triangle joins along one edge with a new
//! corner, or along two), and takes only triangles whose normals are within 60 degrees of
//! the axis: steeper ones are where a curved surface's patches fold over in the
//! projection, which fails the certificate (they go to patches of their own axis). It is
//! certified when its boundary (the edges of its triangles that no other of its
//! triangles uses), seen along that axis, is a set of simple closed polygons that nowhere
//! meet one another or themselves (edges meet only where they follow each other, at their
//! common vertex, without folding back), exactly one of them turning the way the
//! triangles do (a disk's boundary is one polygon; the test allows holes all the same).
//!
//! The proof: for a point `p` of the projection plane off every edge, the number of patch
//! triangles whose image holds `p` is the winding number of the image of the patch's
//! boundary around `p` (each triangle's image winds once around the points inside it, and
//! the interior edges cancel, used once each way). Simple polygons that do not meet wind
//! once (+1 or −1) around the points inside each; with one of them positive, no point is
//! covered twice: the triangles' images have disjoint interiors. Two patch triangles that
//! met at a point `x` other than a shared vertex or edge would then have to meet where
//! their images only touch: `x` on the patch's interior edges or vertices is impossible
//! (the triangles around it cover a whole neighbourhood of its image once), and `x` on
//! the boundary of both is a meeting of boundary edges, which the certificate excludes.
//!
//! Every test is exact: `orient2d` in the projection (a floating-point filter with an exact
//! fallback) and comparisons of coordinates. A patch that fails any test is not certified,
//! and its pairs go to the fan certificates and the exact pair tests as before.

use rayon::prelude::*;

use crate::kernel::{orient2d_inputs, robust_safe, Sign};
use crate::par::Grain;
use crate::Mesh;

/// A triangle in no certified patch.
pub(crate) const NO_PATCH: u32 = u32::MAX;

/// At most this many triangles in a patch, first; a patch that fails the certificate is
/// grown again into patches of the next size, and so on. Big patches leave few triangles
/// on their boundaries (where the check's pairs are); on a scanned surface they fail more
/// often.
const CAPS: [usize; 3] = [1024, 128, 16];

/// For every triangle of `m`, the certified patch it is in, named by its seed (the least
/// triangle id in it: unique over the mesh), or [`NO_PATCH`] (see the module text).
/// Patches of one triangle are not named (they settle nothing). `start` and `slots` are
/// the corners at each vertex ([`super::fans::corners_at_vertices`]).
pub(crate) fn patches(m: &Mesh, start: &[u32], slots: &[u32]) -> Vec<u32> {
    let n = m.triangles.len();
    if n < 2 || n >= (u32::MAX / 4) as usize {
        return vec![NO_PATCH; n];
    }
    let across = across_edges(m, start, slots);
    // Per triangle, the (axis, sign) it may join a patch of: bit `2 axis + 1` where it
    // faces the axis's positive side and its normal is within 60 degrees of it, bit
    // `2 axis` the same for the negative side; and its nearest axis.
    let faces: Vec<(u8, u8)> = (0..n)
        .into_par_iter()
        .grained()
        .map(|t| {
            let [a, b, c] = m.corners(t);
            let safe = robust_safe(&[&a, &b, &c]);
            let normal = crate::vec3::cross(&crate::vec3::sub(&b, &a), &crate::vec3::sub(&c, &a));
            let len = crate::vec3::norm(&normal);
            let mut bits = 0u8;
            for (axis, x) in normal.iter().enumerate() {
                if 2.0 * x.abs() >= len {
                    bits |= match orient2d_inputs(&a, &b, &c, axis, safe) {
                        Sign::Positive => 2 << (2 * axis),
                        Sign::Negative => 1 << (2 * axis),
                        Sign::Zero => 0,
                    };
                }
            }
            let nearest = (0..3)
                .filter(|&k| normal[k].is_finite())
                .max_by(|&i, &j| normal[i].abs().total_cmp(&normal[j].abs()))
                .unwrap_or(0);
            (bits, nearest as u8)
        })
        .collect();
    // Grown one after the other from the least triangle not yet in a patch, breadth
    // first, up to a size; the triangles of patches that fail the certificate are grown
    // again into smaller ones.
    let mut patch = vec![NO_PATCH; n];
    // The growth each vertex was last taken into.
    let mut taken = vec![u32::MAX; m.positions.len()];
    let mut growth = 0u32;
    let mut order: Vec<u32> = Vec::with_capacity(n);
    let mut grown: Vec<(usize, usize, usize, Sign)> = Vec::new();
    for cap in CAPS {
        order.clear();
        grown.clear();
        for seed in 0..n {
            if patch[seed] != NO_PATCH {
                continue;
            }
            // The seed's nearest axis and its bit there: what every triangle must share.
            let (bits, axis) = (faces[seed].0, faces[seed].1 as usize);
            let want = bits & (3 << (2 * axis));
            let sign = match want >> (2 * axis) {
                2 => Sign::Positive,
                1 => Sign::Negative,
                _ => continue,
            };
            let first = order.len();
            let name = seed as u32;
            growth += 1;
            let take = |t: usize, patch: &mut [u32], order: &mut Vec<u32>, taken: &mut [u32]| {
                patch[t] = name;
                order.push(t as u32);
                for v in m.triangles[t] {
                    taken[v as usize] = growth;
                }
            };
            take(seed, &mut patch, &mut order, &mut taken);
            let mut head = first;
            'grow: while head < order.len() {
                let t = order[head] as usize;
                head += 1;
                for k in 0..3 {
                    let o = across[3 * t + k];
                    if o == NO_PATCH || patch[o as usize] != NO_PATCH {
                        continue;
                    }
                    // The patch stays a disk: a triangle joins along one edge with a
                    // corner new to the patch, or along two (filling the corner between).
                    let o = o as usize;
                    let joined = (0..3)
                        .filter(|&j| {
                            let x = across[3 * o + j];
                            x != NO_PATCH && patch[x as usize] == name
                        })
                        .count();
                    let apex = m.triangles[o]
                        .into_iter()
                        .find(|v| !m.triangles[t].contains(v));
                    let new_corner = apex.is_some_and(|v| taken[v as usize] != growth);
                    let disk = if new_corner { joined == 1 } else { joined == 2 };
                    if disk && faces[o].0 & want != 0 {
                        take(o, &mut patch, &mut order, &mut taken);
                        if order.len() - first == cap {
                            break 'grow;
                        }
                    }
                }
            }
            grown.push((first, order.len(), axis, sign));
        }
        let certified: Vec<bool> = grown
            .par_iter()
            .grained()
            .map_init(Scratch::default, |s, &(first, end, axis, sign)| {
                end - first >= 2 && s.certify(m, &order[first..end], &patch, &across, axis, sign)
            })
            .collect();
        let mut failed = false;
        for (&(first, end, ..), ok) in grown.iter().zip(certified) {
            if !ok {
                failed |= end - first >= 2;
                for &t in &order[first..end] {
                    patch[t as usize] = NO_PATCH;
                }
            }
        }
        if !failed {
            break;
        }
    }
    patch
}

/// The triangle across each edge of `m` (3 × triangle + corner: the edge from that corner
/// to the next) where that edge has exactly two triangles, using it one way each, else
/// [`NO_PATCH`]; from the corners at each vertex (`start`, `slots`:
/// [`super::fans::corners_at_vertices`]), each vertex's fan read once.
fn across_edges(m: &Mesh, start: &[u32], slots: &[u32]) -> Vec<u32> {
    use std::sync::atomic::{AtomicU32, Ordering::Relaxed};
    let across: Vec<AtomicU32> = (0..slots.len()).map(|_| AtomicU32::new(NO_PATCH)).collect();
    (0..m.positions.len())
        .into_par_iter()
        .grained()
        .for_each_init(Vec::new, |fan: &mut Vec<[u32; 3]>, u| {
            // Each corner at `u` as (corner, the vertex after `u`, the one before).
            fan.clear();
            fan.extend(
                slots[start[u] as usize..start[u + 1] as usize]
                    .iter()
                    .map(|&c| {
                        let (t, k) = (m.triangles[c as usize / 3], c as usize % 3);
                        [c, t[(k + 1) % 3], t[(k + 2) % 3]]
                    }),
            );
            for &[c, v, _] in fan.iter() {
                // The edge from `u` to `v`: the one other triangle on it, from `v` to `u`.
                let mut on_edge = fan
                    .iter()
                    .filter(|e| e[0] != c && (e[1] == v || e[2] == v));
                if let (Some(&[d, next, prev]), None) = (on_edge.next(), on_edge.next()) {
                    if prev == v && next != v {
                        across[c as usize].store(d / 3, Relaxed);
                    }
                }
            }
        });
    across.into_iter().map(AtomicU32::into_inner).collect()
}

/// Per-thread buffers for one patch.
#[derive(Default)]
struct Scratch {
    /// The boundary edges (from, to), sorted by `from`.
    edges: Vec<[u32; 2]>,
    /// Their `to` vertices, sorted.
    ends: Vec<u32>,
    /// Whether each edge has been walked.
    walked: Vec<bool>,
    /// The edges by their least coordinate along the sweep.
    sweep: Vec<u32>,
}

impl Scratch {
    /// Whether the patch of triangles `tris` (named in `patch`, grown across `across`, all
    /// facing `sign` seen along `axis`) is certified (see the module text).
    fn certify(
        &mut self,
        m: &Mesh,
        tris: &[u32],
        patch: &[u32],
        across: &[u32],
        axis: usize,
        sign: Sign,
    ) -> bool {
        let name = patch[tris[0] as usize];
        self.edges.clear();
        for &t in tris {
            let v = m.triangles[t as usize];
            for k in 0..3 {
                let o = across[3 * t as usize + k];
                if o == NO_PATCH || patch[o as usize] != name {
                    self.edges.push([v[k], v[(k + 1) % 3]]);
                }
            }
        }
        if self.edges.is_empty() {
            return false; // closed, which no patch of one facing can be
        }
        // Each boundary vertex starts one edge and ends one (no pinched vertices): the
        // edges then form loops, walked without choice.
        self.edges.sort_unstable();
        self.ends.clear();
        self.ends.extend(self.edges.iter().map(|e| e[1]));
        self.ends.sort_unstable();
        if self.edges.windows(2).any(|w| w[0][0] == w[1][0])
            || self.ends.windows(2).any(|w| w[0] == w[1])
        {
            return false;
        }
        let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
        let at = |v: u32| m.positions[v as usize];
        let orient = |a: u32, b: u32, c: u32| {
            let (a, b, c) = (at(a), at(b), at(c));
            orient2d_inputs(&a, &b, &c, axis, robust_safe(&[&a, &b, &c]))
        };
        // Lexicographic order of vertices in the projection.
        let before = |a: u32, b: u32| {
            let (p, q) = (at(a), at(b));
            p[i] < q[i] || (p[i] == q[i] && p[j] < q[j])
        };
        // The loops: exactly one turns as the triangles do (at its lexicographically least
        // vertex, where a simple polygon is convex).
        let edges = &self.edges;
        let next = |v: u32| edges.binary_search_by_key(&v, |e| e[0]).ok();
        self.walked.clear();
        self.walked.resize(edges.len(), false);
        let mut positive = 0;
        for first in 0..edges.len() {
            if self.walked[first] {
                continue;
            }
            let (mut e, mut least, mut prev_of_least) = (first, edges[first][1], edges[first][0]);
            loop {
                self.walked[e] = true;
                let Some(f) = next(edges[e][1]) else {
                    return false;
                };
                if before(edges[f][0], least) {
                    (least, prev_of_least) = (edges[f][0], edges[e][0]);
                }
                if f == first {
                    break;
                }
                if self.walked[f] {
                    return false;
                }
                e = f;
            }
            let Some(after) = next(least) else {
                return false;
            };
            match orient(prev_of_least, least, edges[after][1]) {
                s if s == sign => positive += 1,
                Sign::Zero => return false,
                _ => {}
            }
        }
        if positive != 1 {
            return false;
        }
        // No two edges meet but consecutive ones at their common vertex: a sweep along
        // the projection's longer side, exact tests where the boxes meet.
        let (lo, hi) = edges.iter().flatten().fold(
            ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
            |(lo, hi), &v| {
                let p = at(v);
                (
                    [lo[0].min(p[i]), lo[1].min(p[j])],
                    [hi[0].max(p[i]), hi[1].max(p[j])],
                )
            },
        );
        let (x, y) = if hi[0] - lo[0] >= hi[1] - lo[1] {
            (i, j)
        } else {
            (j, i)
        };
        let span = |e: usize, d: usize| {
            let (p, q) = (at(edges[e][0])[d], at(edges[e][1])[d]);
            (p.min(q), p.max(q))
        };
        self.sweep.clear();
        self.sweep.extend(0..edges.len() as u32);
        self.sweep
            .sort_unstable_by(|&a, &b| span(a as usize, x).0.total_cmp(&span(b as usize, x).0));
        for (k, &a) in self.sweep.iter().enumerate() {
            let (a, (_, a_hi)) = (a as usize, span(a as usize, x));
            let (a_ylo, a_yhi) = span(a, y);
            for &b in &self.sweep[k + 1..] {
                let b = b as usize;
                let (b_lo, _) = span(b, x);
                if b_lo > a_hi {
                    break;
                }
                let (b_ylo, b_yhi) = span(b, y);
                if b_ylo > a_yhi || a_ylo > b_yhi {
                    continue;
                }
                if edges_meet(edges[a], edges[b], &orient, &at, [i, j]) {
                    return false;
                }
            }
        }
        true
    }
}

/// Whether boundary edges `a` and `b` (vertex ids), whose boxes in the projection meet,
/// meet anywhere but at a common endpoint, where they must not overlap: `orient` is
/// `orient2d` in the projection, `at` a vertex's position, `ij` the projection's
/// coordinates.
fn edges_meet(
    a: [u32; 2],
    b: [u32; 2],
    orient: &impl Fn(u32, u32, u32) -> Sign,
    at: &impl Fn(u32) -> [f64; 3],
    ij: [usize; 2],
) -> bool {
    let shared = a.iter().filter(|v| b.contains(v)).count();
    if shared == 2 {
        return true;
    }
    if shared == 1 {
        // On one line through the common vertex `c`, on the same side of it.
        let c = if b.contains(&a[0]) { a[0] } else { a[1] };
        let (p, q) = (
            if a[0] == c { a[1] } else { a[0] },
            if b[0] == c { b[1] } else { b[0] },
        );
        if orient(c, p, q) != Sign::Zero {
            return false;
        }
        let (pc, pp, pq) = (at(c), at(p), at(q));
        return ij.iter().any(|&d| {
            pp[d] != pc[d] && (pp[d] > pc[d]) == (pq[d] > pc[d]) && pq[d] != pc[d]
        });
    }
    let (o1, o2) = (orient(a[0], a[1], b[0]), orient(a[0], a[1], b[1]));
    let (o3, o4) = (orient(b[0], b[1], a[0]), orient(b[0], b[1], a[1]));
    if (o1 == o2 && o1 != Sign::Zero) || (o3 == o4 && o3 != Sign::Zero) {
        return false;
    }
    // Collinear with meeting boxes, or crossing or touching: they meet.
    true
}

