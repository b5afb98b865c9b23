//! T-junctions: a vertex lying on another triangle's edge without being its corner leaves a
//! crack. Resolved by splitting that edge (and its triangle) at the vertex.

use serde::Serialize;

use crate::edges::EdgeTopology;
use crate::kernel::{cmp_coord, longest_axis, orient2d, Point, Sign};
use crate::Mesh;

/// What [`resolve_t_junctions`] did.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct TJunctionReport {
    /// Boundary edges split.
    pub edges_split: usize,
    /// Vertices inserted into edges (a split edge may take several).
    pub vertices_inserted: usize,
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

/// Splits every boundary edge of `mesh` at the boundary vertices lying exactly on it (its
/// triangle becomes a fan from the opposite corner), closing T-junction cracks. Exact: a
/// vertex a hair off the edge is not moved onto it (weld or snap first for that).
/// Candidates come from sorting boundary vertices by x, so the cost is about
/// O(b log b + b·k) for b boundary vertices and k of them in an edge's x-range.
pub fn resolve_t_junctions(mesh: &Mesh) -> (Mesh, TJunctionReport) {
    let topo = EdgeTopology::new(mesh);
    let boundary: Vec<usize> = (0..topo.edge_count())
        .filter(|&e| topo.uses_of(e).len() == 1)
        .collect();
    let mut verts: Vec<u32> = boundary.iter().flat_map(|&e| topo.edges[e]).collect();
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
        let (a, b) = (mesh.positions[u as usize], mesh.positions[v as usize]);
        let (lo, hi) = (a[0].min(b[0]), a[0].max(b[0]));
        let start = xs.partition_point(|&x| x < lo);
        let mut on: Vec<u32> = verts[start..]
            .iter()
            .take_while(|&&w| mesh.positions[w as usize][0] <= hi)
            .copied()
            .filter(|&w| w != u && w != v && on_open_segment(&a, &b, &mesh.positions[w as usize]))
            .collect();
        let use_ = topo.uses_of(e)[0];
        let t = use_.triangle as usize;
        if on.is_empty() || replaced[t] {
            continue;
        }
        // Order along the edge as the triangle runs it: from corner k to corner k+1.
        let tri = mesh.triangles[t];
        let k = use_.corner as usize;
        let (from, to, opp) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
        let pf = Point::Explicit(mesh.positions[from as usize]);
        let axis = longest_axis(&a, &b);
        let forward = cmp_coord(&pf, &Point::Explicit(mesh.positions[to as usize]), axis)
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
