//! Folds in height-field surfaces (terrain): triangles that face down once the surface is
//! consistently oriented up, because a vertex was moved across an opposite edge and the
//! surface now folds over itself in plan view. Each fold is removed by taking out one of
//! the fold's vertices and re-triangulating the hole it leaves in plan view.

use serde::Serialize;

use crate::kernel::{orient2d, Point, Sign};
use crate::Mesh;

/// What [`remove_folds`] did.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct FoldReport {
    /// Triangles facing down (exact, in plan view) at the start.
    pub down_facing: usize,
    /// Vertices taken out (each with the triangles around it; the hole re-triangulated).
    pub vertices_removed: usize,
    /// Triangles removed with those vertices.
    pub triangles_removed: usize,
    /// Triangles added to fill the holes.
    pub triangles_added: usize,
    /// Down-facing triangles left: none of their vertices could be taken out so that
    /// every new triangle faces up (boundary vertices are never taken out).
    pub left: usize,
    /// Vertical triangles (zero area in plan view), left as they are.
    pub vertical: usize,
}

fn plan_sign(p: &[[f64; 3]; 3]) -> Sign {
    let [a, b, c] = p.map(Point::Explicit);
    orient2d(&a, &b, &c, 2)
}

/// Removes the folds of a surface oriented up ([`super::orient`] with
/// [`super::Facing::ZUp`]): while a triangle faces down in plan view (exact), one of its
/// interior vertices is taken out with its star of triangles and the hole is triangulated
/// in plan view (ear clipping, `earcut`), accepted only if every new triangle faces up
/// (exact). The hole keeps its boundary, so the surface stays consistently oriented and
/// its boundary is unchanged. Heights of the remaining vertices do not change; the
/// removed vertices are left unreferenced (indices stay valid; see
/// [`Mesh::without_unreferenced`]). Vertical triangles are left alone.
pub fn remove_folds(mesh: &Mesh) -> (Mesh, FoldReport) {
    let pos = &mesh.positions;
    let corners = |t: &[u32; 3]| t.map(|v| pos[v as usize]);
    let mut tris = mesh.triangles.clone();
    let down = |tris: &[[u32; 3]]| -> Vec<usize> {
        (0..tris.len())
            .filter(|&t| plan_sign(&corners(&tris[t])) == Sign::Negative)
            .collect()
    };
    let mut report = FoldReport {
        down_facing: down(&tris).len(),
        vertical: tris
            .iter()
            .filter(|t| plan_sign(&corners(t)) == Sign::Zero)
            .count(),
        ..FoldReport::default()
    };
    let mut earcut = earcut::Earcut::new();
    let mut idx: Vec<u32> = Vec::new();
    for _pass in 0..32 {
        let todo = down(&tris);
        if todo.is_empty() {
            break;
        }
        let mut around: Vec<Vec<u32>> = vec![Vec::new(); pos.len()];
        for (i, t) in tris.iter().enumerate() {
            for &v in t {
                around[v as usize].push(i as u32);
            }
        }
        let mut alive = vec![true; tris.len()];
        let mut touched = vec![false; pos.len()];
        let mut added: Vec<[u32; 3]> = Vec::new();
        let mut progress = false;
        for t in todo {
            let tri = tris[t];
            if !alive[t] || tri.iter().any(|&v| touched[v as usize]) {
                continue;
            }
            for v in tri {
                let star: Vec<u32> = around[v as usize].clone();
                if star.iter().any(|&s| !alive[s as usize]) {
                    continue;
                }
                // The link of v: edges b -> c of the star's triangles (v, b, c), chained.
                let mut next: Vec<(u32, u32)> = star
                    .iter()
                    .map(|&s| {
                        let st = tris[s as usize];
                        let k = (0..3).find(|&k| st[k] == v).unwrap_or(0);
                        (st[(k + 1) % 3], st[(k + 2) % 3])
                    })
                    .collect();
                next.sort_unstable();
                let Some(ring) = chain(&next) else {
                    continue; // a boundary or non-manifold vertex
                };
                let Some(cap) = triangulate_plan(pos, &ring, &mut earcut, &mut idx) else {
                    continue;
                };
                for &s in &star {
                    alive[s as usize] = false;
                    for w in tris[s as usize] {
                        touched[w as usize] = true;
                    }
                }
                report.vertices_removed += 1;
                report.triangles_removed += star.len();
                report.triangles_added += cap.len();
                added.extend(cap);
                progress = true;
                break;
            }
        }
        tris = tris
            .into_iter()
            .zip(alive)
            .filter_map(|(t, a)| a.then_some(t))
            .chain(added)
            .collect();
        if !progress {
            break;
        }
    }
    report.left = down(&tris).len();
    (Mesh::new_unchecked(mesh.positions.clone(), tris), report)
}

/// Chains the directed edges (sorted by start) into one closed loop that uses each of
/// them once and visits no vertex twice; `None` otherwise.
fn chain(edges: &[(u32, u32)]) -> Option<Vec<u32>> {
    let n = edges.len();
    if n < 3 || edges.windows(2).any(|w| w[0].0 == w[1].0) {
        return None;
    }
    let find = |a: u32| {
        edges
            .binary_search_by_key(&a, |e| e.0)
            .ok()
            .map(|i| edges[i].1)
    };
    let start = edges[0].0;
    let mut ring = vec![start];
    let mut at = start;
    loop {
        at = find(at)?;
        if at == start {
            break;
        }
        if ring.len() == n {
            return None;
        }
        ring.push(at);
    }
    (ring.len() == n).then_some(ring)
}

/// Triangulates the closed polygon `ring` in plan view, keeping its direction; `None`
/// unless the ear clipping covers it with `n − 2` triangles that all face up (exact).
fn triangulate_plan(
    pos: &[[f64; 3]],
    ring: &[u32],
    earcut: &mut earcut::Earcut<f64>,
    idx: &mut Vec<u32>,
) -> Option<Vec<[u32; 3]>> {
    let o = pos[ring[0] as usize];
    let flat: Vec<[f64; 2]> = ring
        .iter()
        .map(|&v| {
            let p = pos[v as usize];
            [p[0] - o[0], p[1] - o[1]]
        })
        .collect();
    earcut.earcut(flat.iter().copied(), &[] as &[u32], idx);
    if idx.len() != 3 * (ring.len() - 2) {
        return None;
    }
    let mut out = Vec::with_capacity(ring.len() - 2);
    for t in idx.chunks_exact(3) {
        let mut tri = [
            ring[t[0] as usize],
            ring[t[1] as usize],
            ring[t[2] as usize],
        ];
        let p = tri.map(|v| pos[v as usize]);
        match plan_sign(&p) {
            Sign::Positive => {}
            Sign::Negative => tri.swap(1, 2),
            Sign::Zero => return None,
        }
        out.push(tri);
    }
    // The ring runs counter-clockwise (as up-facing triangles around an interior vertex
    // do) exactly when the triangles, all made to face up, use its edges in its direction.
    let runs_with = |a: u32, b: u32| {
        out.iter()
            .any(|t| (0..3).any(|k| t[k] == a && t[(k + 1) % 3] == b))
    };
    let n = ring.len();
    (0..n)
        .all(|i| runs_with(ring[i], ring[(i + 1) % n]))
        .then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::mesh_stats;
    use crate::repair::{orient, Facing};
    use crate::shapes::heightfield;

    #[test]
    fn a_vertex_pushed_across_its_neighbours_is_taken_out() {
        // A 4 x 4 grid with one interior vertex dragged in plan view past its
        // neighbours: the triangles around it fold over.
        let mut m = heightfield([0.0, 0.0], [4.0, 4.0], 4, 4, |x, y| 0.1 * x + 0.05 * y);
        let v = m
            .positions
            .iter()
            .position(|p| p[0] == 2.0 && p[1] == 2.0)
            .unwrap();
        m.positions[v][0] = 3.4;
        m.positions[v][1] = 2.3;
        let (o, _) = orient(&m, Facing::ZUp);
        let (r, rep) = remove_folds(&o);
        assert!(rep.down_facing > 0);
        assert_eq!((rep.left, rep.vertical), (0, 0), "{rep:?}");
        assert!(rep.vertices_removed >= 1);
        let s = mesh_stats(&r);
        let s0 = mesh_stats(&m);
        assert_eq!((s.inconsistent_edges, s.non_manifold_edges), (0, 0));
        assert_eq!(s.boundary_edges, s0.boundary_edges);
        assert_eq!(
            rep.triangles_removed - rep.triangles_added,
            m.triangles.len() - r.triangles.len()
        );
        for t in 0..r.triangles.len() {
            assert_eq!(plan_sign(&r.corners(t)), Sign::Positive);
        }
        // Up-facing and without folds, the plan area is exactly the footprint: 16.
        assert!(
            (s.projected_area.xy - 16.0).abs() < 1e-12,
            "{}",
            s.projected_area.xy
        );
    }

    #[test]
    fn a_surface_without_folds_is_unchanged() {
        let m = heightfield([0.0, 0.0], [3.0, 2.0], 6, 4, |x, y| x * y);
        let (r, rep) = remove_folds(&m);
        assert_eq!(r, m);
        assert_eq!(rep, FoldReport::default());
    }
}

#[cfg(test)]
mod kirra {
    use super::*;
    use crate::measure::mesh_stats;
    use crate::repair::{boundary_loops, orient, Facing};

    #[test]
    fn kirra_terrain_faces_up_everywhere_after_orient_and_fold_removal() {
        for (name, vertical) in [("kirra_terrain.obj", 8), ("kap_terrain.obj", 9)] {
            let Some(t) = crate::test_util::shared_data(name) else {
                return;
            };
            let (up, _) = orient(&t, Facing::ZUp);
            let (r, rep) = remove_folds(&up);
            // The 22 triangles orientation had to turn down are gone: 16 vertices out.
            assert_eq!(
                (
                    rep.down_facing,
                    rep.left,
                    rep.vertical,
                    rep.vertices_removed
                ),
                (22, 0, vertical, 16),
                "{name}"
            );
            assert_eq!((rep.triangles_removed, rep.triangles_added), (102, 70));
            let s = mesh_stats(&r);
            assert_eq!(
                (s.inconsistent_edges, s.non_manifold_edges, s.boundary_edges),
                (0, 0, 560)
            );
            assert!(crate::intersect::self_intersections(&r).is_empty());
            for k in 0..r.triangles.len() {
                assert_ne!(plan_sign(&r.corners(k)), Sign::Negative, "{name} {k}");
            }
            // No overlaps left in plan view: the plan areas add up to exactly the area
            // enclosed by the boundary (shoelace about the first vertex), to rounding.
            let (loops, _) = boundary_loops(&r);
            assert_eq!(loops.len(), 1);
            let o = r.positions[loops[0][0] as usize];
            let xy = |v: u32| {
                let p = r.positions[v as usize];
                (p[0] - o[0], p[1] - o[1])
            };
            let lp = &loops[0];
            let enclosed: f64 = (0..lp.len())
                .map(|i| {
                    let ((x0, y0), (x1, y1)) = (xy(lp[i]), xy(lp[(i + 1) % lp.len()]));
                    x0 * y1 - x1 * y0
                })
                .sum::<f64>()
                / 2.0;
            let plan = s.projected_area.xy;
            assert!(
                (plan - enclosed).abs() < 1e-9 * plan,
                "{name}: {plan} vs {enclosed}"
            );
            // Before fold removal the folds were counted twice: more than the footprint.
            assert!(mesh_stats(&up).projected_area.xy > plan + 5.0);
        }
    }
}
