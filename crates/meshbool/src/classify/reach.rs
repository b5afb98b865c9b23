//! Fewer winding numbers for the triangles the seam leaves undecided: one winding number
//! clear of the threshold settles every triangle within reach of it.
//!
//! Off the other mesh `y`, the solid angle `y` subtends changes only through `y`'s
//! boundary: its gradient is the Biot–Savart field of the boundary chain (the edges whose
//! uses do not cancel), so the winding number's gradient is at most
//! `(1/4π) Σ |e| / dist(p, e)²` over the chain's edges `e`. Along a path that does not
//! cross `y`, the winding number then moves by at most the path's length times that bound
//! over the path. Queried triangles joined across an edge that is not a seam edge are such
//! a path (centroid, the shared edge's midpoint, centroid): the arrangement cut them along
//! every crossing with `y`, so only their seam edges touch it.
//!
//! A seed triangle whose winding number `w` clears the threshold by `m` more than its error
//! bound (0 for an exact sum; the hierarchy's own bound, see
//! [`super::FastWinding::sided_many`]) and the sums' rounding ([`side_margin`]) gives its
//! class to the triangles reached by paths shorter than `m / G`, `G` the gradient bound
//! over a ball around the seed that holds those paths (the ball whose radius is that
//! length, [`Chain::reach`]). Against a closed, consistently
//! oriented mesh the chain is empty and the winding number constant between crossings: a
//! seed reaches its whole piece. Seeds are taken in rounds, every `stride`-th triangle
//! still open in Morton order, evaluated together and their reaches flooded side by side (a
//! seed with a corner on the seam settles only itself: its centroid may lie within rounding
//! of `y`); what is left after the rounds is evaluated one by one. The classes do not
//! depend on the threads (a triangle reached by several seeds takes the first seed's class
//! in Morton order; all agree, each seed's error being within its bound).

use rayon::prelude::*;
use std::cmp::Ordering::Greater;
use std::collections::VecDeque;

use super::winding::morton_order_of_points;
use super::{class_of_winding, side_margin, Class};
use crate::par::Grain;
use crate::vec3::{dot, norm, sub};
use crate::Mesh;

/// Below this many queried triangles, each is evaluated on its own (the chain and the
/// links would cost more than they save).
pub(super) const REACH_FROM: usize = 64;

/// Rounds of seeds: every `stride`-th open triangle in Morton order; a seed's flood stops
/// after `FLOOD_PER_STRIDE · stride` triangles (bounding a round's work where the reach
/// is long, as against closed meshes).
const STRIDES: [usize; 4] = [64, 16, 4, 2];
const FLOOD_PER_STRIDE: usize = 16;

/// Segments per leaf of [`Chain`].
const LEAF: usize = 8;

/// A cluster of chain segments: their box and its diagonal, their total length (each
/// segment times how many times it counts), their range in the chain's order, and the
/// right child (0 for a leaf; the left child follows the node).
#[derive(Clone, Copy, Debug, Default)]
struct ChainNode {
    lo: [f64; 3],
    hi: [f64; 3],
    diagonal: f64,
    length: f64,
    start: u32,
    end: u32,
    right: u32,
}

/// The boundary chain of a mesh ([`crate::edges::unbalanced_edges`]) as segments in a hierarchy of
/// boxes: the nearest segment to a point, and bounds on the winding number's gradient.
pub(super) struct Chain {
    /// Segment ends, in the hierarchy's order.
    ends: Vec<[[f64; 3]; 2]>,
    /// Each segment's length times how many times it counts (its uses that do not
    /// cancel).
    length: Vec<f64>,
    nodes: Vec<ChainNode>,
}

/// Room for the pending nodes of a walk of a [`Chain`] (two per level: the tree is
/// balanced, at most 32 levels deep for `u32` segment counts).
type Stack = ([u32; 64], usize);

/// Squared distance from `p` to the box `[lo, hi]` (0 inside).
fn box_distance2(p: &[f64; 3], lo: &[f64; 3], hi: &[f64; 3]) -> f64 {
    (0..3)
        .map(|k| (lo[k] - p[k]).max(p[k] - hi[k]).max(0.0).powi(2))
        .sum()
}

/// Squared distance from `p` to the segment `[a, b]`.
fn segment_distance2(p: &[f64; 3], [a, b]: &[[f64; 3]; 2]) -> f64 {
    let (ab, ap) = (sub(b, a), sub(p, a));
    let len2 = dot(&ab, &ab);
    let t = if len2 > 0.0 {
        (dot(&ab, &ap) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let d: [f64; 3] = std::array::from_fn(|k| ap[k] - t * ab[k]);
    dot(&d, &d)
}

impl Chain {
    /// The boundary chain of `mesh`.
    #[cfg(test)]
    fn new(mesh: &Mesh) -> Chain {
        Chain::over(mesh, &crate::edges::unbalanced_edges(mesh))
    }

    /// The chain of `mesh`'s boundary `edges`, its [`crate::edges::unbalanced_edges`].
    pub(super) fn over(mesh: &Mesh, edges: &[([u32; 2], i32)]) -> Chain {
        let at = |v: u32| mesh.positions[v as usize];
        let mids: Vec<[f64; 3]> = edges
            .iter()
            .map(|&([u, v], _)| std::array::from_fn(|k| (at(u)[k] + at(v)[k]) / 2.0))
            .collect();
        let order = morton_order_of_points(&mids, true);
        let ends: Vec<[[f64; 3]; 2]> = order.iter().map(|&i| edges[i as usize].0.map(at)).collect();
        let length = order
            .iter()
            .zip(&ends)
            .map(|(&i, [a, b])| f64::from(edges[i as usize].1.unsigned_abs()) * norm(&sub(b, a)))
            .collect();
        let mut chain = Chain {
            ends,
            length,
            nodes: Vec::new(),
        };
        if !chain.ends.is_empty() {
            chain.build(0, chain.ends.len());
        }
        chain
    }

    /// Appends the subtree over segments `start..end` (pre-order) and returns its root.
    fn build(&mut self, start: usize, end: usize) -> usize {
        let i = self.nodes.len();
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for s in &self.ends[start..end] {
            for p in s {
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
        }
        self.nodes.push(ChainNode {
            lo,
            hi,
            diagonal: norm(&sub(&hi, &lo)),
            length: self.length[start..end].iter().sum(),
            start: start as u32,
            end: end as u32,
            right: 0,
        });
        if end - start > LEAF {
            let mid = start + (end - start) / 2;
            self.build(start, mid);
            let right = self.build(mid, end);
            self.nodes[i].right = right as u32;
        }
        i
    }

    /// Distance from `p` to the nearest segment (infinite without segments).
    fn nearest(&self, p: &[f64; 3]) -> f64 {
        self.nearest2(p).sqrt()
    }

    /// The square of [`Chain::nearest`].
    fn nearest2(&self, p: &[f64; 3]) -> f64 {
        let mut best = f64::INFINITY;
        if self.nodes.is_empty() {
            return best;
        }
        let (mut stack, mut depth): Stack = ([0; 64], 1);
        while depth > 0 {
            depth -= 1;
            let i = stack[depth];
            let n = &self.nodes[i as usize];
            if box_distance2(p, &n.lo, &n.hi) >= best {
                continue;
            }
            if n.right == 0 {
                for s in &self.ends[n.start as usize..n.end as usize] {
                    best = best.min(segment_distance2(p, s));
                }
            } else {
                // The nearer child first: its segments narrow the search soonest.
                let (l, r) = (&self.nodes[i as usize + 1], &self.nodes[n.right as usize]);
                let near_left = box_distance2(p, &l.lo, &l.hi) <= box_distance2(p, &r.lo, &r.hi);
                let (first, then) = match near_left {
                    true => (i + 1, n.right),
                    false => (n.right, i + 1),
                };
                stack[depth] = then;
                stack[depth + 1] = first;
                depth += 2;
            }
        }
        best
    }

    /// A bound `G₀` on `(1/4π) Σ n · |e| / dist(p, e)²` over the chain's segments `e` (`n`:
    /// the times `e` counts), `d` being the distance from `p` to the nearest: a cluster
    /// of segments is taken whole, by its total length over the square of its box's
    /// distance or `d`, the larger (each of its segments is at least that far), where
    /// the box is farther than [`WHOLE`] times as wide (which overstates its part by at
    /// most `(1 + 1/WHOLE)²`).
    ///
    /// Over the ball of radius `r < d` about `p`, every segment is at least
    /// `dist(p, e) − r ≥ dist(p, e) (1 − r/d)` away, so the winding number's gradient there
    /// (the Biot–Savart field of the chain, at most `(1/4π) Σ n |e| / dist²`) is at most
    /// `G₀ / (1 − r/d)²`.
    fn inverse_square_sum(&self, p: &[f64; 3], d: f64) -> f64 {
        let mut sum = 0.0;
        if self.nodes.is_empty() {
            return sum;
        }
        let (mut stack, mut depth): Stack = ([0; 64], 1);
        while depth > 0 {
            depth -= 1;
            let i = stack[depth];
            let n = &self.nodes[i as usize];
            let b2 = box_distance2(p, &n.lo, &n.hi);
            if b2 > (WHOLE * n.diagonal).powi(2) {
                sum += n.length / b2.max(d * d);
            } else if n.right == 0 {
                let range = n.start as usize..n.end as usize;
                for (e, &len) in self.ends[range.clone()].iter().zip(&self.length[range]) {
                    sum += len / segment_distance2(p, e).max(d * d);
                }
            } else {
                stack[depth] = n.right;
                stack[depth + 1] = i + 1;
                depth += 2;
            }
        }
        sum / (4.0 * std::f64::consts::PI)
    }

    /// How long a path from `p` may be while the winding number cannot move by `margin`
    /// along it: the radius `r = ρ d` of the best ball about `p` (`d`: the distance to
    /// the chain), where `r` equals `margin` over the gradient bound there,
    /// `G₀ / (1 − ρ)²` ([`Chain::inverse_square_sum`]): `ρ = k (1 − ρ)²` with
    /// `k = margin / (G₀ d)`, whose root in `[0, 1)` is `2k / (2k + 1 + √(4k + 1))`; at
    /// most `3d/4`. Infinite without a chain; 0 on it (and where anything is not a
    /// number).
    fn reach(&self, p: &[f64; 3], margin: f64) -> f64 {
        if !p.iter().all(|c| c.is_finite()) {
            return 0.0;
        }
        let d = self.nearest(p);
        if d == f64::INFINITY {
            return d;
        }
        if d.is_nan() || d <= 0.0 {
            return 0.0;
        }
        let g0 = self.inverse_square_sum(p, d);
        if g0 == 0.0 {
            return 0.75 * d;
        }
        // A bound or margin that is not a positive number (NaN included) reaches nothing.
        if g0.partial_cmp(&0.0) != Some(Greater) || margin.partial_cmp(&0.0) != Some(Greater) {
            return 0.0;
        }
        let k = margin / (g0 * d);
        let rho = (2.0 * k / (2.0 * k + 1.0 + (4.0 * k + 1.0).sqrt())).min(0.75);
        // Both sides of the root's equation, the smaller: rounding cannot make the reach
        // longer than the ball or than the bound allows.
        (rho * d).min(margin * (1.0 - rho).powi(2) / g0)
    }
}

/// How far from a point, in widths of its box, a cluster of chain segments must be for
/// [`Chain::inverse_square_sum`] to take it whole.
const WHOLE: f64 = 1.0;

/// The queried triangles' neighbours across edges that are not seam edges, with the
/// length of the path between their centroids through the shared edge's midpoint: up to
/// three per triangle (one per edge), `to[i][..count[i]]`.
struct Links {
    to: Vec<[(u32, f64); 3]>,
    count: Vec<u8>,
}

impl Links {
    /// Links of the triangles `queries` of `x` (centroids `centroids`), `seam` being the
    /// seam edges of `x` (sorted pairs, lower vertex first). Only edges with exactly two
    /// uses among the queried triangles link them.
    fn new(x: &Mesh, queries: &[usize], centroids: &[[f64; 3]], seam: &[[u32; 2]]) -> Links {
        // The queried triangles' edges by their lower vertex, each use as (higher vertex,
        // query): in edge order once each bucket is sorted.
        let nv = x.positions.len();
        let (start, mut half) = crate::edges::bucket_by_lower_of(
            queries.len(),
            |i| x.triangles[queries[i]],
            0,
            nv as u32,
            |a, b, id| (a.max(b), id / 3),
        );
        let mut to = vec![[(0u32, 0.0); 3]; queries.len()];
        let mut count = vec![0u8; queries.len()];
        // Edges come in order, so the seam edges are met by walking their sorted list.
        let mut seam = seam.iter().peekable();
        for lo in 0..nv {
            let bucket = &mut half[start[lo] as usize..start[lo + 1] as usize];
            bucket.sort_unstable();
            let mut rest = &*bucket;
            while let Some(&(hi, i)) = rest.first() {
                let n = rest.iter().take_while(|h| h.0 == hi).count();
                let edge = [lo as u32, hi];
                while seam.next_if(|s| **s < edge).is_some() {}
                if n == 2 && rest[1].1 != i && seam.peek() != Some(&&edge) {
                    let j = rest[1].1;
                    let [a, b] = edge.map(|v| x.positions[v as usize]);
                    let m: [f64; 3] = std::array::from_fn(|k| (a[k] + b[k]) / 2.0);
                    let len = norm(&sub(&centroids[i as usize], &m))
                        + norm(&sub(&m, &centroids[j as usize]));
                    // A triangle has three edges: at most three links.
                    for (from, other) in [(i, j), (j, i)] {
                        let c = &mut count[from as usize];
                        to[from as usize][usize::from(*c)] = (other, len);
                        *c += 1;
                    }
                }
                rest = &rest[n..];
            }
        }
        Links { to, count }
    }

    /// The triangles reached from `seed` by paths shorter than `reach`, in the order they
    /// are first reached (breadth first, a triangle's distance lowered and passed on
    /// again where a shorter path comes), at most `cap` of them (the seed not counted).
    /// `room`: the flood's working memory, reused from flood to flood (each seed floods
    /// once per [`Room`]).
    fn flood(&self, seed: u32, reach: f64, cap: usize, room: &mut Room) -> Vec<u32> {
        let stamp = seed + 1;
        if room.stamp.len() < self.to.len() {
            room.stamp = vec![0; self.to.len()];
            room.dist = vec![0.0; self.to.len()];
        }
        let Room {
            stamp: seen,
            dist,
            queue,
        } = room;
        queue.clear();
        seen[seed as usize] = stamp;
        dist[seed as usize] = 0.0;
        queue.push_back(seed);
        let mut out = Vec::new();
        while let Some(i) = queue.pop_front() {
            let i = i as usize;
            let d = dist[i];
            for &(j, len) in &self.to[i][..usize::from(self.count[i])] {
                let nd = d + len;
                let k = j as usize;
                if nd >= reach {
                    continue;
                }
                if seen[k] != stamp {
                    seen[k] = stamp;
                    out.push(j);
                    if out.len() >= cap {
                        return out;
                    }
                } else if nd >= dist[k] {
                    continue;
                }
                dist[k] = nd;
                queue.push_back(j);
            }
        }
        out
    }
}

/// Working memory of [`Links::flood`]: per triangle, the last flood (its seed + 1) that
/// reached it and its distance in that flood; the flood's queue.
#[derive(Default)]
struct Room {
    stamp: Vec<u32>,
    dist: Vec<f64>,
    queue: VecDeque<u32>,
}

/// The classes of the triangles `queries` of `x` (with centroids `centroids`) against
/// `y`: inside where the winding number of `y` is above `threshold`. `eval` gives the
/// winding numbers at points, each with a bound on its error that its distance to
/// `threshold` exceeds (or that is 0); it is asked for the seeds and for what no seed reaches
/// (see the module's comment). `seam`: the seam edges of `x`, sorted; `boundary`: those
/// of `y` whose uses do not cancel ([`crate::edges::unbalanced_edges`]).
#[allow(clippy::too_many_arguments)]
pub(super) fn classes_by_reach(
    x: &Mesh,
    queries: &[usize],
    centroids: &[[f64; 3]],
    seam: &[[u32; 2]],
    y: &Mesh,
    boundary: &[([u32; 2], i32)],
    threshold: f64,
    eval: impl Fn(&[[f64; 3]]) -> Vec<(f64, f64)>,
) -> Vec<Class> {
    let class_of = |w: f64| class_of_winding(w, threshold);
    let (chain, links) = crate::par::join(
        || Chain::over(y, boundary),
        || Links::new(x, queries, centroids, seam),
    );
    let order = morton_order_of_points(centroids, false);
    // A seed with a corner on the seam settles only itself: a sliver beside the seam may
    // have its centroid within rounding of `y`, where its winding number is off by ½.
    let mut on_seam: Vec<u32> = seam.iter().flatten().copied().collect();
    on_seam.sort_unstable();
    on_seam.dedup();
    let touches_seam = |i: u32| {
        x.triangles[queries[i as usize]]
            .iter()
            .any(|v| on_seam.binary_search(v).is_ok())
    };
    let mut class: Vec<Option<Class>> = vec![None; queries.len()];
    // The triangles without a class yet, in Morton order.
    let still_open = |class: &[Option<Class>]| -> Vec<u32> {
        order
            .iter()
            .copied()
            .filter(|&i| class[i as usize].is_none())
            .collect()
    };
    for stride in STRIDES {
        let open = still_open(&class);
        if open.len() < 2 * stride {
            continue;
        }
        let seeds: Vec<u32> = open.iter().copied().step_by(stride).collect();
        let points: Vec<[f64; 3]> = seeds.iter().map(|&s| centroids[s as usize]).collect();
        let w = eval(&points);
        let reached: Vec<Vec<u32>> = seeds
            .par_iter()
            .zip(&w)
            .grained()
            .map_init(Room::default, |room, (&s, &(w, e))| {
                let margin = side_margin(w, e, threshold);
                if margin.is_nan() || margin <= 0.0 || touches_seam(s) {
                    return Vec::new();
                }
                let reach = chain.reach(&centroids[s as usize], margin);
                links.flood(s, reach, FLOOD_PER_STRIDE * stride, room)
            })
            .collect();
        for (&s, &(w, _)) in seeds.iter().zip(&w) {
            class[s as usize] = Some(class_of(w));
        }
        for (&(w, _), region) in w.iter().zip(&reached) {
            for &t in region {
                class[t as usize].get_or_insert(class_of(w));
            }
        }
    }
    let open = still_open(&class);
    let points: Vec<[f64; 3]> = open.iter().map(|&s| centroids[s as usize]).collect();
    for (&i, (w, _)) in open.iter().zip(eval(&points)) {
        class[i as usize] = Some(class_of(w));
    }
    class
        .into_iter()
        .map(|c| c.expect("every queried triangle is a seed, reached, or evaluated"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::classify::{winding_number, FastWinding};
    use crate::edges::unbalanced_edges;
    use crate::shapes::{heightfield, uv_sphere};
    use crate::test_util::Rng;

    /// [`classes_by_reach`] of every triangle of `x` (no seam) against `y`.
    fn all_by_reach(
        x: &Mesh,
        y: &Mesh,
        threshold: f64,
        eval: impl Fn(&[[f64; 3]]) -> Vec<(f64, f64)>,
    ) -> Vec<Class> {
        let (queries, centroids) = every_triangle(x);
        let boundary = unbalanced_edges(y);
        classes_by_reach(x, &queries, &centroids, &[], y, &boundary, threshold, eval)
    }

    /// Every triangle of `x` as a query, with its centroid.
    fn every_triangle(x: &Mesh) -> (Vec<usize>, Vec<[f64; 3]>) {
        let centroids = (0..x.triangles.len()).map(|t| x.centroid(t)).collect();
        ((0..x.triangles.len()).collect(), centroids)
    }

    /// The gradient bound holds: the winding number of an open surface, between random
    /// pairs of points on segments that cross neither the surface nor come near its
    /// boundary, moves by no more than the segment's length times the bound over the ball
    /// about its start that holds it.
    #[test]
    fn the_winding_number_moves_no_more_than_the_bound_allows() {
        let surface = heightfield([-1.0, -1.0], [1.0, 1.0], 12, 12, |x, y| 0.3 * x * y);
        let chain = Chain::new(&surface);
        assert_eq!(chain.ends.len(), 4 * 12, "the boundary of a 12 × 12 grid");
        let mut rng = Rng(0x9a7d);
        // The end of a straight step of `length` from `p` in a random direction, where
        // the step stays over the surface's square and on one side of the surface (above
        // or below it) all along.
        let mut step = |p: &[f64; 3], length: f64| -> Option<[f64; 3]> {
            let dir: [f64; 3] = std::array::from_fn(|_| rng.unit() - 0.5);
            let q: [f64; 3] = std::array::from_fn(|k| p[k] + length * dir[k] / norm(&dir));
            let side = |s: &[f64; 3]| {
                let inside = s[0].abs() < 1.0 && s[1].abs() < 1.0;
                (inside, inside && s[2] > 0.3 * s[0] * s[1])
            };
            let mut along =
                (0..=20).map(|k| std::array::from_fn(|j| p[j] + (q[j] - p[j]) * k as f64 / 20.0));
            along
                .all(|s| side(&s) == side(p) && side(&s).0)
                .then_some(q)
        };
        let mut points = Rng(0x51e9);
        let mut point = || -> [f64; 3] { std::array::from_fn(|_| 3.0 * (points.unit() - 0.5)) };
        let (mut tested, mut tight) = (0, 0.0f64);
        while tested < 300 {
            let p = point();
            let d = chain.nearest(&p);
            let r = d / 2.0;
            let Some(q) = step(&p, r) else {
                continue;
            };
            let g = chain.inverse_square_sum(&p, d) / (1.0 - r / d).powi(2);
            let moved = (winding_number(&surface, q) - winding_number(&surface, p)).abs();
            assert!(moved <= g * r + 1e-12, "{p:?} → {q:?}: {moved} > {}", g * r);
            tight = tight.max(moved / (g * r));
            tested += 1;
        }
        // The bound is not idle: somewhere the winding number moves by a fair part of it.
        assert!(tight > 0.1, "{tight}");
        // A reach keeps within its margin: straight paths as long as the reach, with
        // margins from 0.001 to 0.3.
        let (mut tested, mut used, mut margins) = (0, 0.0f64, Rng(0x3b07));
        while tested < 300 {
            let p = point();
            let margin = 0.001 * 300f64.powf(margins.unit());
            let r = chain.reach(&p, margin);
            let Some(q) = step(&p, r) else {
                continue;
            };
            let moved = (winding_number(&surface, q) - winding_number(&surface, p)).abs();
            assert!(moved <= margin, "{p:?} → {q:?}: {moved} > {margin}");
            used = used.max(moved / margin);
            tested += 1;
        }
        // Nor is the reach: somewhere it is long enough to use a fair part of its margin
        // (0.61 when written; the bound above 0.18).
        assert!(used > 0.25, "{used}");
        // A closed, consistently oriented mesh has no chain: nothing bounds a reach.
        let sphere = uv_sphere([0.0; 3], 1.0, 16, 8);
        let closed = Chain::new(&sphere);
        assert!(closed.ends.is_empty());
        assert_eq!(closed.reach(&[0.2, 0.0, 0.0], 0.4), f64::INFINITY);
        // On the chain: no reach.
        assert_eq!(chain.reach(&[-1.0, -1.0, 0.3], 0.4), 0.0);
        // Turning one triangle of the sphere gives its three edges, twice each.
        let mut turned = sphere.clone();
        turned.triangles[5].swap(1, 2);
        let c = Chain::new(&turned);
        let [a, b, cc] = turned.corners(5);
        let perimeter = norm(&sub(&a, &b)) + norm(&sub(&b, &cc)) + norm(&sub(&cc, &a));
        assert_eq!(c.ends.len(), 3);
        assert!((c.length.iter().sum::<f64>() - 2.0 * perimeter).abs() < 1e-12);
    }

    /// Classes by reach are the classes of each triangle's own winding number: on a
    /// tilted plane that passes under an open surface and on past its edge, where the
    /// winding number crosses the threshold without crossing the surface. With exact sums
    /// and with the hierarchy's sided values, every class is the exact one. Fewer than
    /// two in five points are evaluated.
    #[test]
    fn classes_by_reach_are_the_classes_of_each_triangle() {
        let x = heightfield([-1.2, -1.2], [1.6, 1.2], 60, 60, |x, _| 0.25 * (x - 1.1));
        let y = heightfield([-1.0, -1.0], [1.0, 1.0], 25, 25, |x, y| 0.01 * x * y);
        let (queries, centroids) = every_triangle(&x);
        let exact: Vec<f64> = centroids.iter().map(|&p| winding_number(&y, p)).collect();
        let inside = exact.iter().filter(|&&w| w > 0.0).count();
        assert!(inside > 300 && inside < queries.len() - 300, "{inside}");
        let fast = FastWinding::new(&y);
        for by_fast in [false, true] {
            let asked = std::sync::atomic::AtomicUsize::new(0);
            let eval = |pts: &[[f64; 3]]| {
                asked.fetch_add(pts.len(), std::sync::atomic::Ordering::Relaxed);
                match by_fast {
                    true => fast.sided_many(pts, 0.0),
                    false => pts.iter().map(|&p| (winding_number(&y, p), 0.0)).collect(),
                }
            };
            let got = all_by_reach(&x, &y, 0.0, eval);
            for (t, (&w, c)) in exact.iter().zip(&got).enumerate() {
                assert_eq!(*c == Class::Inside, w > 0.0, "{t}: {w} (fast {by_fast})");
            }
            let asked = asked.into_inner();
            assert!(
                5 * asked < 2 * queries.len(),
                "{asked} of {}",
                queries.len()
            );
        }
    }

    /// Against a closed sphere the chain is empty and a seed reaches its whole piece (up
    /// to the flood's cap): a grid inside and one outside, as one mesh, each take one
    /// class, the right one, from few evaluations.
    #[test]
    fn against_a_closed_mesh_one_seed_settles_its_piece() {
        let y = uv_sphere([0.0; 3], 1.0, 24, 12);
        let inner = heightfield([-0.5, -0.5], [0.5, 0.5], 30, 30, |_, _| 0.1);
        let outer = heightfield([-2.0, -2.0], [2.0, 2.0], 30, 30, |_, _| 1.5);
        let mut x = inner.clone();
        let base = x.positions.len() as u32;
        x.positions.extend(&outer.positions);
        x.triangles
            .extend(outer.triangles.iter().map(|t| t.map(|v| v + base)));
        let asked = std::sync::atomic::AtomicUsize::new(0);
        let eval = |pts: &[[f64; 3]]| {
            asked.fetch_add(pts.len(), std::sync::atomic::Ordering::Relaxed);
            pts.iter().map(|&p| (winding_number(&y, p), 0.0)).collect()
        };
        let got = all_by_reach(&x, &y, 0.5, eval);
        let n = inner.triangles.len();
        assert!(got[..n].iter().all(|&c| c == Class::Inside));
        assert!(got[n..].iter().all(|&c| c == Class::Outside));
        // The first round's seeds (every 64th) and no more.
        assert_eq!(asked.into_inner(), x.triangles.len().div_ceil(64));
    }

    /// No link crosses a seam edge: a grid cut along its middle column of edges floods
    /// from one side to exactly that side's triangles.
    #[test]
    fn links_do_not_cross_the_seam() {
        let x = heightfield([-1.0, -1.0], [1.0, 1.0], 10, 10, |_, _| 0.0);
        let at = |v: u32| x.positions[v as usize];
        let mut seam: Vec<[u32; 2]> = Vec::new();
        for t in &x.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                if at(a)[0] == 0.0 && at(b)[0] == 0.0 {
                    seam.push([a.min(b), a.max(b)]);
                }
            }
        }
        seam.sort_unstable();
        seam.dedup();
        assert_eq!(seam.len(), 10);
        let (queries, centroids) = every_triangle(&x);
        let links = Links::new(&x, &queries, &centroids, &seam);
        let left = (0..queries.len()).filter(|&t| centroids[t][0] < 0.0);
        let seed = left.clone().next().expect("a triangle on the left") as u32;
        // One room for every flood below, as a round's seeds share one.
        let mut room = Room::default();
        let mut reached = links.flood(seed, f64::INFINITY, usize::MAX, &mut room);
        reached.push(seed);
        reached.sort_unstable();
        assert_eq!(reached, left.map(|t| t as u32).collect::<Vec<_>>());
        // Without the seam, everything.
        let all = Links::new(&x, &queries, &centroids, &[]);
        let n = all
            .flood(seed, f64::INFINITY, usize::MAX, &mut Room::default())
            .len();
        assert_eq!(n + 1, queries.len());
        // A short reach: only the nearest neighbours.
        let near = all.flood(seed + 3, 0.3, usize::MAX, &mut room);
        assert!(!near.is_empty() && near.len() < 12, "{}", near.len());
    }
}
