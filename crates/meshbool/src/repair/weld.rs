//! Welding within a distance: every vertex ([`weld_within`]) or the boundary vertices only
//! ([`weld_boundary`]).

use rustc_hash::FxHashMap;
use serde::Serialize;

use crate::edges::EdgeTopology;
use crate::Mesh;

/// What [`weld_within`] and [`weld_boundary`] did.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct WeldReport {
    /// Vertices merged into another one.
    pub merged_vertices: usize,
    /// Triangles removed because two of their corners became one vertex.
    pub collapsed_triangles: usize,
}

/// A tolerance as the repair steps take it: finite and ≥ 0, anything else is 0.
pub(super) fn clamp_tolerance(tolerance: f64) -> f64 {
    if tolerance.is_finite() {
        tolerance.max(0.0)
    } else {
        0.0
    }
}

/// Whether `p` and `q` are at most `tol` apart (3D distance, inclusive), without the
/// squares of small distances underflowing: the differences are scaled by the largest.
pub(super) fn within(p: &[f64; 3], q: &[f64; 3], tol: f64) -> bool {
    let d = [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
    let m = d[0].abs().max(d[1].abs()).max(d[2].abs());
    if m.is_nan() || m > tol {
        return false; // farther along one axis already, or not a number
    }
    if m == 0.0 {
        return true;
    }
    let s = tol / m; // >= 1
    d.iter().map(|x| (x / m).powi(2)).sum::<f64>() <= s * s
}

/// Points bucketed so that two within `reach` of each other are in the same or adjacent
/// cells (`reach` 0: the same cell, keyed by the exact coordinates). Non-finite points
/// are left out: they are within no distance of anything.
pub(super) struct NearGrid {
    origin: [f64; 3],
    /// The cell size; 0 for exact keys.
    cell: f64,
    cells: FxHashMap<[i64; 3], Vec<u32>>,
}

impl NearGrid {
    /// The grid of the points `ids` of `positions`.
    pub(super) fn new(
        positions: &[[f64; 3]],
        ids: impl Iterator<Item = u32> + Clone,
        reach: f64,
    ) -> Self {
        let finite = |v: &u32| positions[*v as usize].iter().all(|x| x.is_finite());
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for v in ids.clone().filter(finite) {
            let p = positions[v as usize];
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let extent = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        // Twice the reach: rounding in the cell index can never make two points within
        // `reach` land two cells apart. At least 2^-40 of the extent: indices stay small.
        let cell = if reach > 0.0 {
            (2.0 * reach).max(extent * 2f64.powi(-40))
        } else {
            0.0
        };
        let mut grid = NearGrid {
            origin: if lo[0].is_finite() { lo } else { [0.0; 3] },
            cell,
            cells: FxHashMap::default(),
        };
        for v in ids.filter(finite) {
            let key = grid.key(&positions[v as usize]);
            grid.cells.entry(key).or_default().push(v);
        }
        grid
    }

    fn key(&self, p: &[f64; 3]) -> [i64; 3] {
        if self.cell > 0.0 {
            // A NaN quotient (infinite cell and extent) reads as cell 0.
            [0, 1, 2].map(|k| ((p[k] - self.origin[k]) / self.cell).floor() as i64)
        } else {
            p.map(|x| (x + 0.0).to_bits() as i64)
        }
    }

    /// The points in the cells near `p` (a superset of those within `reach`), in no
    /// particular order.
    pub(super) fn near(&self, p: &[f64; 3]) -> impl Iterator<Item = u32> + '_ {
        let finite = p.iter().all(|x| x.is_finite());
        let c = self.key(p);
        let r: i64 = if self.cell > 0.0 { 1 } else { 0 };
        let offsets = (-r..=r)
            .flat_map(move |dx| (-r..=r).flat_map(move |dy| (-r..=r).map(move |dz| [dx, dy, dz])));
        offsets
            .filter(move |_| finite)
            .filter_map(move |d| {
                self.cells.get(&[
                    c[0].wrapping_add(d[0]),
                    c[1].wrapping_add(d[1]),
                    c[2].wrapping_add(d[2]),
                ])
            })
            .flatten()
            .copied()
    }
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
    weld_among(mesh, tolerance, &vec![true; mesh.positions.len()])
}

/// Merges *boundary* vertices (the ends of edges used by one triangle) closer than
/// `tolerance`, as [`weld_within`] merges all vertices (index order, no chaining, the
/// representative's position): cracks between open parts close while every other vertex
/// stays as it is, however close it is to another. Triangles whose corners collapse are
/// removed and counted; unreferenced vertices are dropped. `tolerance` must be finite and
/// ≥ 0 (0 welds exactly equal positions only).
pub fn weld_boundary(mesh: &Mesh, tolerance: f64) -> (Mesh, WeldReport) {
    weld_among(mesh, tolerance, &boundary_vertices(mesh))
}

/// Each vertex's representative under [`weld_among`]'s rule (index order, no chaining;
/// itself when not merged) among the vertices marked `eligible`, and how many merged.
fn representatives(mesh: &Mesh, tolerance: f64, eligible: &[bool]) -> (Vec<u32>, usize) {
    let tol = clamp_tolerance(tolerance);
    let n = mesh.positions.len();
    let grid = NearGrid::new(
        &mesh.positions,
        (0..n as u32).filter(|&v| eligible[v as usize]),
        tol,
    );
    let mut rep = vec![u32::MAX; n];
    let mut merged = 0;
    for v in 0..n {
        if rep[v] != u32::MAX {
            continue;
        }
        rep[v] = v as u32;
        if !eligible[v] {
            continue;
        }
        let p = mesh.positions[v];
        for w in grid.near(&p) {
            let w = w as usize;
            if w <= v || rep[w] != u32::MAX {
                continue;
            }
            if within(&p, &mesh.positions[w], tol) {
                rep[w] = v as u32;
                merged += 1;
            }
        }
    }
    (rep, merged)
}

/// The boundary vertices of `mesh` merged within `tolerance` as [`weld_boundary`] merges
/// them, every triangle kept in its place (one whose corners collapse stays, with two
/// equal corners); unreferenced vertices are dropped. Also how many vertices merged;
/// `None` when none did.
pub(crate) fn weld_boundary_in_place(mesh: &Mesh, tolerance: f64) -> Option<(Mesh, usize)> {
    let (rep, merged) = representatives(mesh, tolerance, &boundary_vertices(mesh));
    if merged == 0 {
        return None;
    }
    let triangles = mesh
        .triangles
        .iter()
        .map(|t| t.map(|v| rep[v as usize]))
        .collect();
    let welded = Mesh::new_unchecked(mesh.positions.clone(), triangles);
    Some((welded.without_unreferenced().0, merged))
}

/// Which vertices are ends of edges used by one triangle.
fn boundary_vertices(mesh: &Mesh) -> Vec<bool> {
    let topo = EdgeTopology::new(mesh);
    let mut boundary = vec![false; mesh.positions.len()];
    for e in 0..topo.edge_count() {
        if topo.uses_of(e).len() == 1 {
            for v in topo.edges[e] {
                boundary[v as usize] = true;
            }
        }
    }
    boundary
}

/// [`weld_within`] among the vertices marked `eligible`; the others stay as they are.
fn weld_among(mesh: &Mesh, tolerance: f64, eligible: &[bool]) -> (Mesh, WeldReport) {
    let (rep, merged) = representatives(mesh, tolerance, eligible);
    let mut report = WeldReport {
        merged_vertices: merged,
        ..WeldReport::default()
    };
    let n = mesh.positions.len();
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

    /// The unit cube cut at z = 0.5 into two open boxes, the upper one lifted by `gap`
    /// (vertices of its own), the bottom face fanned around two interior vertices 5e-4
    /// apart (indices 8 and 9).
    fn halves(gap: f64) -> Mesh {
        let low = Mesh::cuboid([0.0; 3], [1.0, 1.0, 0.5]);
        let high = Mesh::cuboid([0.0, 0.0, 0.5 + gap], [1.0; 3]);
        let keep = |m: &Mesh, z: f64| -> Vec<[u32; 3]> {
            (0..m.triangles.len())
                .filter(|&t| !m.corners(t).iter().all(|p| p[2] == z))
                .map(|t| m.triangles[t])
                .collect()
        };
        // The low box without its top or bottom; corners 0..4 are its bottom (x by bit 0,
        // y by bit 1).
        let mut triangles: Vec<[u32; 3]> = keep(&low, 0.5)
            .into_iter()
            .filter(|t| t.iter().any(|&v| v >= 4))
            .collect();
        let mut positions = low.positions.clone();
        positions.extend([[0.5, 0.5, 0.0], [0.5005, 0.5, 0.0]]);
        // Seen from below (outward): c0 c2 c3 c1 around, p = 8 left of q = 9.
        triangles.extend([
            [0, 9, 1],
            [1, 9, 3],
            [3, 8, 2],
            [2, 8, 0],
            [0, 8, 9],
            [9, 8, 3],
        ]);
        let off = positions.len() as u32;
        positions.extend(&high.positions);
        triangles.extend(keep(&high, 0.5 + gap).iter().map(|t| t.map(|v| v + off)));
        Mesh::new_unchecked(positions, triangles)
    }

    #[test]
    fn boundary_weld_closes_the_cut_and_leaves_interior_vertices() {
        let m = halves(1e-4);
        let s = mesh_stats(&m);
        assert_eq!(
            (s.boundary_edges, s.inconsistent_edges, s.vertices),
            (8, 0, 18)
        );
        let (w, r) = weld_boundary(&m, 1e-3);
        // The upper rim's four corners join the lower rim's; the two interior vertices,
        // as close as those, stay apart.
        assert_eq!((r.merged_vertices, r.collapsed_triangles), (4, 0));
        let s = mesh_stats(&w);
        assert_eq!(
            (
                s.boundary_edges,
                s.non_manifold_edges,
                s.inconsistent_edges,
                s.closed
            ),
            (0, 0, 0, true)
        );
        assert_eq!((s.vertices, s.triangles), (14, 24));
        assert_eq!(s.volume, 1.0);
        assert!(
            w.positions.contains(&[0.5, 0.5, 0.0]) && w.positions.contains(&[0.5005, 0.5, 0.0])
        );
        // Not within the tolerance: nothing; a weld of every vertex takes the pair too.
        assert_eq!(weld_boundary(&m, 1e-5).1.merged_vertices, 0);
        let (_, r) = weld_within(&m, 1e-3);
        assert_eq!((r.merged_vertices, r.collapsed_triangles), (5, 2));
    }
}
