//! Welding within a distance.

use rustc_hash::FxHashMap;
use serde::Serialize;

use crate::Mesh;

/// What [`weld_within`] did.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct WeldReport {
    /// Vertices merged into another one.
    pub merged_vertices: usize,
    /// Triangles removed because two of their corners became one vertex.
    pub collapsed_triangles: usize,
}

/// Merges vertices closer than `tolerance` (3D distance, inclusive).
///
/// Deterministic and without chaining: vertices are visited in index order; each one not
/// yet merged becomes a representative and takes every later unmerged vertex within
/// `tolerance` of *itself*. So three points spaced 0.6·tolerance apart on a line become two
/// vertices (the first two merge; the third is 1.2·tolerance from the representative), not
/// one. Merged vertices take the representative's position (no averaging, no drift).
/// Triangles whose corners collapse are removed and counted; unreferenced vertices are
/// dropped. `tolerance` must be finite and ≥ 0 (0 welds exactly equal positions only).
pub fn weld_within(mesh: &Mesh, tolerance: f64) -> (Mesh, WeldReport) {
    let tol = if tolerance.is_finite() {
        tolerance.max(0.0)
    } else {
        0.0
    };
    let n = mesh.positions.len();
    let cell = |p: &[f64; 3]| -> [i64; 3] {
        if tol > 0.0 {
            p.map(|x| (x / tol).floor() as i64)
        } else {
            p.map(|x| (x + 0.0).to_bits() as i64)
        }
    };
    let mut grid: FxHashMap<[i64; 3], Vec<u32>> = FxHashMap::default();
    for (v, p) in mesh.positions.iter().enumerate() {
        grid.entry(cell(p)).or_default().push(v as u32);
    }
    let mut rep = vec![u32::MAX; n];
    let mut report = WeldReport::default();
    let reach: i64 = if tol > 0.0 { 1 } else { 0 };
    for v in 0..n {
        if rep[v] != u32::MAX {
            continue;
        }
        rep[v] = v as u32;
        let p = mesh.positions[v];
        let c = cell(&p);
        for dx in -reach..=reach {
            for dy in -reach..=reach {
                for dz in -reach..=reach {
                    let Some(list) = grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) else {
                        continue;
                    };
                    for &w in list {
                        let w = w as usize;
                        if w <= v || rep[w] != u32::MAX {
                            continue;
                        }
                        let q = mesh.positions[w];
                        let d2 = (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>();
                        if d2 <= tol * tol {
                            rep[w] = v as u32;
                            report.merged_vertices += 1;
                        }
                    }
                }
            }
        }
    }
    let mut new_id = vec![u32::MAX; n];
    let mut positions = Vec::new();
    let mut triangles = Vec::with_capacity(mesh.triangles.len());
    for t in &mesh.triangles {
        let r = t.map(|v| rep[v as usize]);
        if r[0] == r[1] || r[1] == r[2] || r[2] == r[0] {
            report.collapsed_triangles += 1;
            continue;
        }
        triangles.push(r.map(|v| {
            if new_id[v as usize] == u32::MAX {
                new_id[v as usize] = positions.len() as u32;
                positions.push(mesh.positions[v as usize]);
            }
            new_id[v as usize]
        }));
    }
    (Mesh::new_unchecked(positions, triangles), report)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::mesh_stats;

    #[test]
    fn merges_within_tolerance_only_and_never_chains() {
        // Points on a line 0.6 apart with tolerance 1: 0 and 0.6 merge, 1.2 does not join
        // them (1.2 from the representative), 1.8 merges into 1.2.
        let xs = [0.0, 0.6, 1.2, 1.8];
        let mut m = Mesh::new_unchecked(xs.iter().map(|&x| [x, 0.0, 0.0]).collect(), vec![]);
        m.positions.extend([[0.0, 5.0, 0.0], [1.0, 5.0, 1.0]]);
        m.triangles = vec![[0, 4, 5], [1, 4, 5], [2, 4, 5], [3, 4, 5]];
        let (w, r) = weld_within(&m, 1.0);
        assert_eq!(r.merged_vertices, 2);
        assert_eq!(w.positions.len(), 4);
        assert_eq!(
            w.triangles,
            vec![[0, 1, 2], [0, 1, 2], [3, 1, 2], [3, 1, 2]]
        );
        assert_eq!(w.positions[3], [1.2, 0.0, 0.0]);
        // Exactly at the tolerance merges; just beyond does not.
        let pair = |d: f64| {
            Mesh::new_unchecked(
                vec![[0.0; 3], [d, 0.0, 0.0], [0.0, 9.0, 0.0], [9.0, 9.0, 0.0]],
                vec![[0, 2, 3], [1, 2, 3]],
            )
        };
        assert_eq!(weld_within(&pair(0.5), 0.5).1.merged_vertices, 1);
        assert_eq!(
            weld_within(&pair(0.5f64.next_up()), 0.5).1.merged_vertices,
            0
        );
    }

    #[test]
    fn closes_a_crack_and_counts_collapsed_triangles() {
        // Two unit squares side by side whose shared edge vertices differ by 1e-4: a crack.
        let mut m = Mesh::new_unchecked(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
                [1.0001, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [2.0, 1.0, 0.0],
                [1.0001, 1.0, 0.0],
            ],
            vec![[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]],
        );
        assert_eq!(mesh_stats(&m).boundary_edges, 8);
        let (w, r) = weld_within(&m, 1e-3);
        assert_eq!((r.merged_vertices, r.collapsed_triangles), (2, 0));
        let s = mesh_stats(&w);
        assert_eq!(
            (s.boundary_edges, s.vertices, s.inconsistent_edges),
            (6, 6, 0)
        );
        // A sliver whose short edge is below the tolerance collapses and is counted.
        m.positions.push([0.5, 0.5, 1e-5]);
        m.positions.push([0.5, 0.5, 0.0]);
        m.triangles.push([8, 9, 2]);
        let (w, r) = weld_within(&m, 1e-3);
        assert_eq!(r.collapsed_triangles, 1);
        assert_eq!(w.triangles.len(), 4);
    }
}
