//! Stitching: closing the gap between two boundary loops with a band of triangles (a
//! "zipper"), e.g. two halves of a solid cut apart, or a surface and its offset copy.

use serde::Serialize;

use super::cap::boundary_loops;
use crate::vec3::{norm, sub};
use crate::Mesh;

/// What [`stitch`] did.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct StitchReport {
    /// Boundary loops found.
    pub loops: usize,
    /// Pairs of loops joined by a band.
    pub pairs: usize,
    /// Band triangles added (a band between loops of `n` and `m` vertices has `n + m`).
    pub triangles_added: usize,
    /// The largest gap bridged: for each stitched pair, the farthest any vertex of one loop
    /// is from the nearest vertex of the other (both ways); 0 when nothing was stitched.
    pub largest_gap: f64,
    /// Loops left open: no partner within the distance, or all partners taken.
    pub unpaired_loops: usize,
    /// Boundary edges that do not close into a loop, left as they are.
    pub open_boundary_edges: usize,
}

/// The band of triangles joining boundary loops `a` and `b` of one mesh, each given in
/// the direction its triangles run along it ([`super::boundary_loops`]). Every band
/// triangle uses one loop edge against that direction, so the band agrees in orientation
/// with both sides and the pair of loops becomes interior edges: `a.len() + b.len()`
/// triangles, no boundary left between the loops.
///
/// The zipper starts at the closest pair of vertices (one of each loop) and walks `a`
/// forwards and `b` backwards (facing loops of a consistently oriented mesh run opposite
/// ways), each step advancing along the loop whose next connecting edge is shorter.
/// Greedy and linear; loops that are far from facing each other (strongly twisted or of
/// very different shapes) can give a band that crosses itself: check with
/// [`crate::ops::self_curves`] (no curves: no crossing) where that matters.
pub fn zipper(positions: &[[f64; 3]], a: &[u32], b: &[u32]) -> Vec<[u32; 3]> {
    let (n, m) = (a.len(), b.len());
    if n == 0 || m == 0 {
        return Vec::new();
    }
    let p = |v: u32| &positions[v as usize];
    let dist = |u: u32, v: u32| norm(&sub(p(u), p(v)));
    // The closest pair starts the band (ties: the first found).
    let (mut i, mut j) = (0, 0);
    let mut best = f64::INFINITY;
    for (x, &u) in a.iter().enumerate() {
        for (y, &v) in b.iter().enumerate() {
            let d = dist(u, v);
            if d < best {
                (best, i, j) = (d, x, y);
            }
        }
    }
    let mut out = Vec::with_capacity(n + m);
    let (mut left_a, mut left_b) = (n, m);
    while left_a + left_b > 0 {
        let (ai, bj) = (a[i % n], b[j % m]);
        let (an, bp) = (a[(i + 1) % n], b[(j + m - 1) % m]);
        let step_a = left_b == 0 || (left_a > 0 && dist(an, bj) <= dist(ai, bp));
        if step_a {
            // Uses loop edge ai -> an against its direction.
            out.push([an, ai, bj]);
            i += 1;
            left_a -= 1;
        } else {
            // Uses loop edge bp -> bj against its direction.
            out.push([bj, bp, ai]);
            j += m - 1;
            left_b -= 1;
        }
    }
    out
}

/// The gap between two loops: the farthest any vertex of one is from the nearest vertex of
/// the other, both ways (a vertex-based Hausdorff distance).
fn gap(positions: &[[f64; 3]], a: &[u32], b: &[u32]) -> f64 {
    let one_way = |x: &[u32], y: &[u32]| {
        x.iter()
            .map(|&u| {
                y.iter()
                    .map(|&v| norm(&sub(&positions[u as usize], &positions[v as usize])))
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    };
    one_way(a, b).max(one_way(b, a))
}

/// Joins pairs of boundary loops of `mesh` with [`zipper`] bands. Loops are paired by
/// their gap (the vertex-based Hausdorff distance, see [`StitchReport::largest_gap`]):
/// the closest pair first, each loop at most once, and only pairs whose gap is at most
/// `max_gap` (pass `f64::INFINITY` for no limit). Loops without a partner are left open
/// and counted. Deterministic.
pub fn stitch(mesh: &Mesh, max_gap: f64) -> (Mesh, StitchReport) {
    let (loops, open) = boundary_loops(mesh);
    let pos = &mesh.positions;
    let bounds: Vec<([f64; 3], [f64; 3])> = loops
        .iter()
        .map(|lp| {
            lp.iter().fold(
                ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
                |(lo, hi), &v| {
                    let q = pos[v as usize];
                    (
                        std::array::from_fn(|k| lo[k].min(q[k])),
                        std::array::from_fn(|k| hi[k].max(q[k])),
                    )
                },
            )
        })
        .collect();
    // Candidate pairs: boxes within the distance of each other, then the exact gap.
    let mut candidates: Vec<(f64, usize, usize)> = Vec::new();
    for i in 0..loops.len() {
        for j in i + 1..loops.len() {
            let ((lo_i, hi_i), (lo_j, hi_j)) = (bounds[i], bounds[j]);
            let near = (0..3).all(|k| lo_i[k] - max_gap <= hi_j[k] && lo_j[k] - max_gap <= hi_i[k]);
            if !near {
                continue;
            }
            let g = gap(pos, &loops[i], &loops[j]);
            if g <= max_gap {
                candidates.push((g, i, j));
            }
        }
    }
    candidates.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)).then(x.2.cmp(&y.2)));
    let mut taken = vec![false; loops.len()];
    let mut out = mesh.clone();
    let mut report = StitchReport {
        loops: loops.len(),
        open_boundary_edges: open,
        ..StitchReport::default()
    };
    for (g, i, j) in candidates {
        if taken[i] || taken[j] {
            continue;
        }
        taken[i] = true;
        taken[j] = true;
        let band = zipper(pos, &loops[i], &loops[j]);
        report.pairs += 1;
        report.triangles_added += band.len();
        report.largest_gap = report.largest_gap.max(g);
        out.triangles.extend(band);
    }
    report.unpaired_loops = taken.iter().filter(|&&t| !t).count();
    (out, report)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::mesh_stats;

    /// A closed-bottom cup: a regular `n`-gon of radius `r` at height `z0` capped by a fan
    /// from its centre, and a tube up to `z1`, rotated by `phase` radians; outward facing.
    /// `top = true` builds the mirror image (closed at the top, open at the bottom).
    fn cup(n: u32, r: f64, z0: f64, z1: f64, phase: f64, top: bool) -> Mesh {
        let ring = |z: f64| -> Vec<[f64; 3]> {
            (0..n)
                .map(|k| {
                    let t = phase + std::f64::consts::TAU * f64::from(k) / f64::from(n);
                    [r * t.cos(), r * t.sin(), z]
                })
                .collect()
        };
        let (closed_z, open_z) = if top { (z1, z0) } else { (z0, z1) };
        let mut positions = ring(closed_z);
        positions.extend(ring(open_z));
        positions.push([0.0, 0.0, closed_z]);
        let c = 2 * n;
        let mut triangles = Vec::new();
        for k in 0..n {
            let k1 = (k + 1) % n;
            let (a, b, a2, b2) = (k, k1, n + k, n + k1);
            if top {
                // Lid faces up (counter-clockwise seen from above), tube faces out.
                triangles.push([c, a, b]);
                triangles.push([a, a2, b2]);
                triangles.push([a, b2, b]);
            } else {
                triangles.push([c, b, a]);
                triangles.push([a, b, b2]);
                triangles.push([a, b2, a2]);
            }
        }
        Mesh::new_unchecked(positions, triangles)
    }

    fn joined(a: &Mesh, b: &Mesh) -> Mesh {
        let mut m = a.clone();
        m.append(b).unwrap();
        m
    }

    fn regular_polygon_area(n: u32, r: f64) -> f64 {
        0.5 * f64::from(n) * r * r * (std::f64::consts::TAU / f64::from(n)).sin()
    }

    #[test]
    fn aligned_loops_stitch_into_the_exact_prism() {
        // Bottom cup z in [0, 1], top cup z in [2, 3], same 24 vertices per ring: the band
        // is the missing part of the prism side, so the solid is the prism exactly.
        let m = joined(
            &cup(24, 2.0, 0.0, 1.0, 0.0, false),
            &cup(24, 2.0, 2.0, 3.0, 0.0, true),
        );
        let before = mesh_stats(&m);
        assert_eq!(before.boundary_edges, 48);
        let (s, r) = stitch(&m, f64::INFINITY);
        let st = mesh_stats(&s);
        assert_eq!(
            (
                st.boundary_edges,
                st.non_manifold_edges,
                st.inconsistent_edges
            ),
            (0, 0, 0)
        );
        assert_eq!(
            (r.loops, r.pairs, r.triangles_added, r.unpaired_loops),
            (2, 1, 48, 0)
        );
        assert!((r.largest_gap - 1.0).abs() < 1e-12, "{}", r.largest_gap);
        let want = regular_polygon_area(24, 2.0) * 3.0;
        assert!(
            (st.volume - want).abs() < 1e-12 * want,
            "{} vs {want}",
            st.volume
        );
    }

    #[test]
    fn loops_of_different_counts_stitch_into_a_closed_band() {
        // 24 and 17 vertices, the top ring rotated: a band of 41 triangles.
        let m = joined(
            &cup(24, 2.0, 0.0, 1.0, 0.0, false),
            &cup(17, 1.8, 2.0, 3.0, 0.3, true),
        );
        let (s, r) = stitch(&m, 5.0);
        let st = mesh_stats(&s);
        assert_eq!(
            (
                st.boundary_edges,
                st.non_manifold_edges,
                st.inconsistent_edges
            ),
            (0, 0, 0)
        );
        assert_eq!((r.pairs, r.triangles_added), (1, 41));
        assert!(crate::intersect::self_intersections(&s).is_empty());
        // The solid lies between the two prisms over the smaller and larger polygon.
        let (lo, hi) = (
            regular_polygon_area(17, 1.8) * 3.0,
            regular_polygon_area(24, 2.0) * 3.0,
        );
        assert!(
            st.volume > lo && st.volume < hi,
            "{lo} < {} < {hi}",
            st.volume
        );
    }

    #[test]
    fn loops_farther_apart_than_the_limit_stay_open() {
        let m = joined(
            &cup(12, 1.0, 0.0, 1.0, 0.0, false),
            &cup(12, 1.0, 5.0, 6.0, 0.0, true),
        );
        let (s, r) = stitch(&m, 3.9);
        assert_eq!(
            (r.loops, r.pairs, r.unpaired_loops, r.triangles_added),
            (2, 0, 2, 0)
        );
        assert_eq!(s, m);
        // The gap is 4: allowed from exactly 4 on.
        let (_, r) = stitch(&m, 4.0);
        assert_eq!(r.pairs, 1);
    }

    #[test]
    fn closest_loops_pair_first() {
        // Two bottom cups side by side and one top cup above one of them: the top pairs
        // with the cup below it (gap 0.5), the other cup (gap about 10) stays open.
        let near = cup(10, 1.0, 0.0, 1.0, 0.0, false);
        let far = cup(10, 1.0, 0.0, 1.0, 0.0, false);
        let far = Mesh::new_unchecked(
            far.positions
                .iter()
                .map(|p| [p[0] + 10.0, p[1], p[2]])
                .collect(),
            far.triangles,
        );
        let top = cup(10, 1.0, 1.5, 2.5, 0.0, true);
        let m = joined(&joined(&far, &near), &top);
        let (s, r) = stitch(&m, f64::INFINITY);
        assert_eq!((r.loops, r.pairs, r.unpaired_loops), (3, 1, 1));
        assert!((r.largest_gap - 0.5).abs() < 1e-12);
        // The near cup and the top became one closed solid; the far cup keeps its rim.
        assert_eq!(mesh_stats(&s).boundary_edges, 10);
    }
}
