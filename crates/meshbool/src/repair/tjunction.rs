//! T-junctions: a vertex lying on another triangle's edge without being its corner leaves a
//! crack. Resolved by splitting that edge (and its triangle) at the vertex: exactly on it
//! ([`resolve_t_junctions`]) or, with a tolerance, within a distance of it
//! ([`resolve_t_junctions_within`]).

use serde::Serialize;

use crate::edges::EdgeTopology;
use crate::kernel::{cmp_coord, longest_axis, orient2d, Point, Sign};
use crate::Mesh;

/// What [`resolve_t_junctions`] and [`resolve_t_junctions_within`] did.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct TJunctionReport {
    /// Boundary edges split.
    pub edges_split: usize,
    /// Vertices inserted into edges (a split edge may take several).
    pub vertices_inserted: usize,
    /// The largest distance from a vertex inserted into an edge to that edge (how far
    /// the split edge bends); 0 when every vertex lay exactly on its edge.
    pub largest_distance: f64,
}

/// Exactly whether `x` lies on the open segment `a b` (exact predicates, no tolerance).
fn on_open_segment(a: &[f64; 3], b: &[f64; 3], x: &[f64; 3]) -> bool {
    let (pa, pb, px) = (
        Point::Explicit(*a),
        Point::Explicit(*b),
        Point::Explicit(*x),
    );
    if (0..3).any(|axis| orient2d(&pa, &pb, &px, axis) != Sign::Zero) {
        return false;
    }
    let k = longest_axis(a, b);
    let (s, t) = (cmp_coord(&pa, &px, k), cmp_coord(&px, &pb, k));
    s != std::cmp::Ordering::Equal && s == t
}

/// The distance from `x` to the segment `a b` when the foot of the perpendicular lies
/// strictly inside the segment and the distance is at most `tol` (floating point).
fn near_open_segment(a: &[f64; 3], b: &[f64; 3], x: &[f64; 3], tol: f64) -> Option<f64> {
    let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let ax = [x[0] - a[0], x[1] - a[1], x[2] - a[2]];
    let len2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    let t = (ax[0] * ab[0] + ax[1] * ab[1] + ax[2] * ab[2]) / len2;
    if !(t > 0.0 && t < 1.0) {
        return None; // also for a zero-length edge or numbers out of range
    }
    let d = (0..3)
        .map(|k| (ax[k] - t * ab[k]).powi(2))
        .sum::<f64>()
        .sqrt();
    (d <= tol).then_some(d)
}

/// The position of `x` along `a b` as a fraction of its length (floating point).
fn along(a: &[f64; 3], b: &[f64; 3], x: &[f64; 3]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let dot = (0..3).map(|k| (x[k] - a[k]) * ab[k]).sum::<f64>();
    dot / (ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2])
}

/// Splits every boundary edge of `mesh` at the boundary vertices lying exactly on it (its
/// triangle becomes a fan from the opposite corner), closing T-junction cracks. Exact: a
/// vertex a hair off the edge is not moved onto it (weld first, or give a tolerance to
/// [`resolve_t_junctions_within`]).
/// Candidates come from sorting boundary vertices by x, so the cost is about
/// O(b log b + b·k) for b boundary vertices and k of them in an edge's x-range.
pub fn resolve_t_junctions(mesh: &Mesh) -> (Mesh, TJunctionReport) {
    split_boundary_edges(mesh, 0.0)
}

/// [`resolve_t_junctions`] with a tolerance: also splits a boundary edge at every boundary
/// vertex of another triangle whose distance to the edge is at most `tolerance`, the foot
/// of its perpendicular strictly inside the edge (floating point; vertices exactly on it
/// are found exactly, as without a tolerance). The vertex keeps its position: the edge is
/// split through it, so it bends by at most `tolerance` (the report's
/// `largest_distance`). Vertices along one edge go in the order of their feet.
/// `tolerance` must be finite and ≥ 0; 0 is [`resolve_t_junctions`].
pub fn resolve_t_junctions_within(mesh: &Mesh, tolerance: f64) -> (Mesh, TJunctionReport) {
    split_boundary_edges(mesh, super::weld::clamp_tolerance(tolerance))
}

/// Splits boundary edges at the boundary vertices on them (`tol` 0) or within `tol` of them.
fn split_boundary_edges(mesh: &Mesh, tol: f64) -> (Mesh, TJunctionReport) {
    let topo = EdgeTopology::new(mesh);
    let boundary: Vec<usize> = (0..topo.edge_count())
        .filter(|&e| topo.uses_of(e).len() == 1)
        .collect();
    // A vertex with a coordinate that is not a number lies on no edge.
    let finite = |v: &u32| mesh.positions[*v as usize].iter().all(|x| x.is_finite());
    let mut verts: Vec<u32> = boundary
        .iter()
        .flat_map(|&e| topo.edges[e])
        .filter(finite)
        .collect();
    verts.sort_unstable();
    verts.dedup();
    verts.sort_by(|&u, &v| mesh.positions[u as usize][0].total_cmp(&mesh.positions[v as usize][0]));
    let xs: Vec<f64> = verts
        .iter()
        .map(|&v| mesh.positions[v as usize][0])
        .collect();
    let mut out = mesh.clone();
    let mut report = TJunctionReport::default();
    let mut replaced = vec![false; mesh.triangles.len()];
    for &e in &boundary {
        let [u, v] = topo.edges[e];
        if !(finite(&u) && finite(&v)) {
            continue;
        }
        let (a, b) = (mesh.positions[u as usize], mesh.positions[v as usize]);
        let (lo, hi) = (a[0].min(b[0]) - tol, a[0].max(b[0]) + tol);
        let start = xs.partition_point(|&x| x < lo);
        let use_ = topo.uses_of(e)[0];
        let t = use_.triangle as usize;
        let tri = mesh.triangles[t];
        let candidates = verts[start..]
            .iter()
            .take_while(|&&w| mesh.positions[w as usize][0] <= hi)
            .copied()
            .filter(|&w| w != u && w != v);
        // The vertices to insert, each with its distance from the edge.
        let found: Vec<(u32, f64)> = if tol == 0.0 {
            candidates
                .filter(|&w| on_open_segment(&a, &b, &mesh.positions[w as usize]))
                .map(|w| (w, 0.0))
                .collect()
        } else {
            // Not the triangle's own third corner: splitting at it would fold the triangle.
            candidates
                .filter(|w| !tri.contains(w))
                .filter_map(|w| {
                    let x = &mesh.positions[w as usize];
                    if on_open_segment(&a, &b, x) {
                        Some((w, 0.0))
                    } else {
                        near_open_segment(&a, &b, x, tol).map(|d| (w, d))
                    }
                })
                .collect()
        };
        if found.is_empty() || replaced[t] {
            continue;
        }
        for &(_, d) in &found {
            report.largest_distance = report.largest_distance.max(d);
        }
        let mut on: Vec<u32> = found.iter().map(|&(w, _)| w).collect();
        // Order along the edge as the triangle runs it: from corner k to corner k+1.
        let k = use_.corner as usize;
        let (from, to, opp) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
        let (pf, pt) = (mesh.positions[from as usize], mesh.positions[to as usize]);
        if tol == 0.0 {
            let axis = longest_axis(&a, &b);
            let forward = cmp_coord(&Point::Explicit(pf), &Point::Explicit(pt), axis)
                == std::cmp::Ordering::Less;
            on.sort_by(|&p, &q| {
                let (pp, pq) = (
                    Point::Explicit(mesh.positions[p as usize]),
                    Point::Explicit(mesh.positions[q as usize]),
                );
                let o = cmp_coord(&pp, &pq, axis);
                if forward {
                    o
                } else {
                    o.reverse()
                }
            });
        } else {
            let key = |w: u32| along(&pf, &pt, &mesh.positions[w as usize]);
            on.sort_by(|&p, &q| key(p).total_cmp(&key(q)).then(p.cmp(&q)));
        }
        let mut chain = vec![from];
        chain.extend(&on);
        chain.push(to);
        replaced[t] = true;
        out.triangles[t] = [chain[0], chain[1], opp];
        for w in chain.windows(2).skip(1) {
            out.triangles.push([w[0], w[1], opp]);
        }
        report.edges_split += 1;
        report.vertices_inserted += on.len();
    }
    (out, report)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::mesh_stats;

    #[test]
    fn t_junction_crack_in_a_cube_closes() {
        // The x = 1 face is fanned around the midpoint of its bottom edge (1,0,0)-(1,1,0),
        // while the bottom face still uses the whole edge: a T-junction crack.
        let mut m = Mesh::unit_cube();
        m.positions.push([1.0, 0.5, 0.0]); // vertex 8
        m.triangles.truncate(10); // drop the x = 1 face (triangles 10, 11)
                                  // x = 1 face corners: 1 (1,0,0), 3 (1,1,0), 5 (1,0,1), 7 (1,1,1); outward = +x.
        m.triangles.extend([[1, 8, 5], [8, 3, 7], [8, 7, 5]]);
        let before = mesh_stats(&m);
        assert_eq!(before.boundary_edges, 3);
        let (f, r) = resolve_t_junctions(&m);
        assert_eq!((r.edges_split, r.vertices_inserted), (1, 1));
        let s = mesh_stats(&f);
        assert_eq!(
            (s.boundary_edges, s.non_manifold_edges, s.inconsistent_edges),
            (0, 0, 0)
        );
        assert_eq!(s.volume, 1.0);
    }

    /// Two unit squares side by side in z = 0: the left one two triangles, the right one a
    /// fan around a vertex `dx` to the right of the middle of the left square's right
    /// edge: a T-junction `dx` off the edge (an exact one for `dx` 0).
    fn near_t(dx: f64) -> Mesh {
        Mesh::new_unchecked(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
                [2.0, 0.0, 0.0],
                [2.0, 1.0, 0.0],
                [1.0 + dx, 0.5, 0.0],
            ],
            vec![[0, 1, 2], [0, 2, 3], [6, 1, 4], [6, 4, 5], [6, 5, 2]],
        )
    }

    #[test]
    fn a_near_t_junction_closes_within_the_tolerance_only() {
        let m = near_t(1e-4);
        let dx = (1.0f64 + 1e-4) - 1.0;
        // Four edges around each square, the right one's left edge in two: nine.
        assert_eq!(mesh_stats(&m).boundary_edges, 9);
        let (f, r) = resolve_t_junctions(&m);
        assert_eq!((r.edges_split, f), (0, m.clone()));
        for tol in [0.0, 1e-5, dx.next_down()] {
            let (f, r) = resolve_t_junctions_within(&m, tol);
            assert_eq!((r.edges_split, r.largest_distance), (0, 0.0), "{tol}");
            assert_eq!(f, m);
        }
        for tol in [dx, 1e-3] {
            let (f, r) = resolve_t_junctions_within(&m, tol);
            assert_eq!((r.edges_split, r.vertices_inserted), (1, 1));
            assert_eq!(r.largest_distance, dx);
            // The left square's right edge goes through the vertex: the seam is shared,
            // the outline of the two squares is all that is left open.
            let s = mesh_stats(&f);
            assert_eq!(
                (s.boundary_edges, s.non_manifold_edges, s.inconsistent_edges),
                (6, 0, 0)
            );
            assert_eq!(f.positions, m.positions);
            assert_eq!(f.triangles[0], [1, 6, 0]);
            assert_eq!(f.triangles[5], [6, 2, 0]);
            assert!((s.area - 2.0).abs() < 1e-12);
        }
        // A vertex exactly on the edge is split at with and without a tolerance alike.
        let exact = near_t(0.0);
        let (f, r) = resolve_t_junctions(&exact);
        let (g, s) = resolve_t_junctions_within(&exact, 1e-3);
        assert_eq!(
            (r.edges_split, s.edges_split, s.largest_distance),
            (1, 1, 0.0)
        );
        assert_eq!(f, g);
    }

    #[test]
    fn a_triangle_is_not_split_at_its_own_corner() {
        // A sliver whose apex is 1e-4 above its base: within the tolerance of its own edge.
        let m = Mesh::new_unchecked(
            vec![[0.0; 3], [1.0, 0.0, 0.0], [0.5, 1e-4, 0.0]],
            vec![[0, 1, 2]],
        );
        let (f, r) = resolve_t_junctions_within(&m, 1e-3);
        assert_eq!((r.edges_split, f), (0, m));
    }

    #[test]
    fn a_vertex_off_the_edge_by_one_ulp_is_not_moved() {
        let mut m = Mesh::unit_cube();
        m.positions.push([1.0, 0.5, 0.0f64.next_up()]);
        m.triangles.truncate(10);
        m.triangles.extend([[1, 8, 5], [8, 3, 7], [8, 7, 5]]);
        let (f, r) = resolve_t_junctions(&m);
        assert_eq!(r.edges_split, 0);
        assert_eq!(f, m);
    }
}
