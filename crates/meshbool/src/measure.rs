//! Measures: signed volume, area, projected area, and the edge/triangle statistics that
//! tell whether a mesh is closed, manifold and consistently oriented.
//!
//! Yes/no questions (is this triangle degenerate) are answered exactly; sums (volume,
//! area) are computed in `f64` relative to the bounding-box centre with compensated
//! summation, so that UTM-sized coordinates keep their precision.

use rayon::prelude::*;
use rustc_hash::FxHashSet;
use serde::Serialize;

use crate::edges::EdgeTopology;
use crate::kernel::{orient2d_inputs, robust_safe, Sign};
use crate::vec3::{cross, dot, norm, sub};
use crate::Aabb;
use crate::Mesh;

/// A coordinate plane to project onto.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Plane {
    /// Drop z.
    XY,
    /// Drop x.
    YZ,
    /// Drop y.
    XZ,
}

/// Neumaier's compensated sum: keeps volume sums of millions of terms accurate.
#[derive(Default)]
struct Sum {
    s: f64,
    c: f64,
}

impl Sum {
    fn add(&mut self, x: f64) {
        let t = self.s + x;
        if self.s.abs() >= x.abs() {
            self.c += (self.s - t) + x;
        } else {
            self.c += (x - t) + self.s;
        }
        self.s = t;
    }
    fn get(&self) -> f64 {
        self.s + self.c
    }
}

/// Triangles per piece of a parallel sum. Pieces, and the order their sums are combined
/// in, depend on the mesh alone: a sum is the same bit for bit on any number of threads.
const SUM_PIECE: usize = 1 << 14;

/// Sums `f(corners relative to the bounding-box centre)` over all triangles: each piece of
/// [`SUM_PIECE`] triangles compensated on its own, in parallel, the pieces' sums and
/// compensations then added in order (one piece: the plain compensated sum).
fn sum_over_triangles(mesh: &Mesh, f: impl Fn([f64; 3], [f64; 3], [f64; 3]) -> f64 + Sync) -> f64 {
    let Some(b) = mesh.bounds() else { return 0.0 };
    let o = b.center();
    let piece = |k: usize| {
        let mut sum = Sum::default();
        let end = ((k + 1) * SUM_PIECE).min(mesh.triangles.len());
        for t in k * SUM_PIECE..end {
            let [a, b, c] = mesh.corners(t);
            sum.add(f(sub(&a, &o), sub(&b, &o), sub(&c, &o)));
        }
        sum
    };
    let pieces = mesh.triangles.len().div_ceil(SUM_PIECE);
    if pieces == 1 {
        return piece(0).get();
    }
    let sums: Vec<Sum> = (0..pieces).into_par_iter().map(piece).collect();
    let mut total = Sum::default();
    for s in sums {
        total.add(s.s);
        total.add(s.c);
    }
    total.get()
}

/// Signed volume enclosed by the mesh: positive when a closed mesh's triangles face
/// outward. For an open mesh the value depends on the
/// reference point (the bounding-box centre here) and is not a meaningful volume.
pub fn signed_volume(mesh: &Mesh) -> f64 {
    sum_over_triangles(mesh, |a, b, c| dot(&a, &cross(&b, &c))) / 6.0
}

/// Total surface area.
pub fn area(mesh: &Mesh) -> f64 {
    sum_over_triangles(mesh, |a, b, c| norm(&cross(&sub(&b, &a), &sub(&c, &a)))) / 2.0
}

/// Sum of the absolute areas of the triangles projected onto `plane` (for a terrain
/// without overhangs: its footprint area; for a closed solid: twice its shadow).
pub fn projected_area(mesh: &Mesh, plane: Plane) -> f64 {
    let k = match plane {
        Plane::XY => 2,
        Plane::YZ => 0,
        Plane::XZ => 1,
    };
    sum_over_triangles(mesh, |a, b, c| cross(&sub(&b, &a), &sub(&c, &a))[k].abs()) / 2.0
}

/// Exactly whether three points are collinear (the triangle has zero area).
pub fn is_degenerate(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> bool {
    // The normal's components are the three 2D orientations of the projections; the
    // triangle has zero area exactly when all three are zero. On the corners as they
    // are (the adaptive predicate where they allow it), without wrapping them as points.
    let safe = robust_safe(&[&a, &b, &c]);
    (0..3).all(|axis| orient2d_inputs(&a, &b, &c, axis, safe) == Sign::Zero)
}

/// Number of degenerate triangles: a repeated vertex index or three collinear corners (exact).
pub fn degenerate_triangles(mesh: &Mesh) -> usize {
    (0..mesh.triangles.len())
        .filter(|&t| {
            let [i, j, k] = mesh.triangles[t];
            let [a, b, c] = mesh.corners(t);
            i == j || j == k || k == i || is_degenerate(a, b, c)
        })
        .count()
}

/// Number of duplicate triangles: triangles using the same three vertices as an earlier
/// one, in either orientation (each extra copy counts once).
pub fn duplicate_triangles(mesh: &Mesh) -> usize {
    let mut seen = FxHashSet::default();
    seen.reserve(mesh.triangles.len());
    mesh.triangles
        .iter()
        .filter(|t| {
            let mut s = **t;
            s.sort_unstable();
            !seen.insert(s)
        })
        .count()
}

/// Projected areas on the three coordinate planes.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ProjectedAreas {
    /// Onto the XY plane.
    pub xy: f64,
    /// Onto the YZ plane.
    pub yz: f64,
    /// Onto the XZ plane.
    pub xz: f64,
}

/// Everything [`mesh_stats`] measures. Serializes to the JSON of `meshbool info --json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MeshStats {
    /// Number of triangles.
    pub triangles: usize,
    /// Number of vertices (positions), including unreferenced ones.
    pub vertices: usize,
    /// Vertices that no triangle uses.
    pub unreferenced_vertices: usize,
    /// Undirected edges.
    pub edges: usize,
    /// Edges used by exactly one triangle.
    pub boundary_edges: usize,
    /// Edges used by more than two triangles.
    pub non_manifold_edges: usize,
    /// Edges used by two triangles in the same direction (orientation disagrees).
    pub inconsistent_edges: usize,
    /// Triangles with zero area (exact test) or a repeated vertex.
    pub degenerate_triangles: usize,
    /// Extra copies of triangles over the same three vertices.
    pub duplicate_triangles: usize,
    /// Edge-connected components.
    pub components: usize,
    /// True when the mesh has triangles, no boundary edges and no non-manifold edges.
    pub closed: bool,
    /// Signed volume ([`signed_volume`]); meaningful for closed meshes.
    pub volume: f64,
    /// Surface area.
    pub area: f64,
    /// Absolute projected areas.
    pub projected_area: ProjectedAreas,
    /// Bounding box of the used vertices; `None` without triangles.
    pub bbox: Option<Aabb>,
}

impl MeshStats {
    /// The measures of a mesh measured at unit size, for the mesh scaled by `2^e`:
    /// the box times `2^e`, areas `2^2e`, the volume `2^3e`.
    pub(crate) fn scale_back(&mut self, e: i32) {
        use crate::scale::scaled_measure;
        let area = |x: f64| scaled_measure(x, e, 2);
        self.volume = scaled_measure(self.volume, e, 3);
        self.area = area(self.area);
        let p = &mut self.projected_area;
        (p.xy, p.yz, p.xz) = (area(p.xy), area(p.yz), area(p.xz));
        if let Some(b) = &mut self.bbox {
            crate::scale::scale_points(std::slice::from_mut(&mut b.min), e);
            crate::scale::scale_points(std::slice::from_mut(&mut b.max), e);
        }
    }
}

/// Measures a mesh.
pub fn mesh_stats(mesh: &Mesh) -> MeshStats {
    let topo = EdgeTopology::new(mesh);
    let counts = topo.kind_counts();
    let (boundary, inconsistent, non_manifold) =
        (counts.boundary, counts.inconsistent, counts.non_manifold);
    let mut used = vec![false; mesh.positions.len()];
    for &i in mesh.triangles.iter().flatten() {
        used[i as usize] = true;
    }
    MeshStats {
        triangles: mesh.triangles.len(),
        vertices: mesh.positions.len(),
        unreferenced_vertices: used.iter().filter(|u| !**u).count(),
        edges: topo.edge_count(),
        boundary_edges: boundary,
        non_manifold_edges: non_manifold,
        inconsistent_edges: inconsistent,
        degenerate_triangles: degenerate_triangles(mesh),
        duplicate_triangles: duplicate_triangles(mesh),
        components: topo.components().0,
        closed: !mesh.is_empty() && boundary == 0 && non_manifold == 0,
        volume: signed_volume(mesh),
        area: area(mesh),
        projected_area: ProjectedAreas {
            xy: projected_area(mesh, Plane::XY),
            yz: projected_area(mesh, Plane::YZ),
            xz: projected_area(mesh, Plane::XZ),
        },
        bbox: mesh.bounds(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_over_many_pieces_are_the_same_on_any_number_of_threads() {
        // 2·128·255 triangles: four pieces of the parallel sum.
        let s = crate::shapes::uv_sphere([3.0e5, 6.0e6, 100.0], 2.0, 128, 256);
        assert!(s.triangles.len() > 3 * SUM_PIECE);
        let on = |threads| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| (signed_volume(&s), area(&s), s.bounds()))
        };
        let one = on(1);
        assert_eq!(one, on(2));
        assert_eq!(one, on(7));
        // Close to the sphere's (inscribed polyhedron: slightly less).
        let exact = 4.0 / 3.0 * std::f64::consts::PI * 8.0;
        assert!(one.0 > 0.999 * exact && one.0 < exact, "{}", one.0);
        let b = one.2.unwrap();
        assert_eq!((b.min[2], b.max[2]), (98.0, 102.0));
    }

    /// An `n`×`n` grid of unit squares in the plane z = 0, two triangles each, facing +z.
    fn grid(n: u32) -> Mesh {
        let positions = (0..=n)
            .flat_map(|j| (0..=n).map(move |i| [f64::from(i), f64::from(j), 0.0]))
            .collect();
        let v = |i: u32, j: u32| j * (n + 1) + i;
        let triangles = (0..n)
            .flat_map(|j| {
                (0..n).flat_map(move |i| {
                    [
                        [v(i, j), v(i + 1, j), v(i + 1, j + 1)],
                        [v(i, j), v(i + 1, j + 1), v(i, j + 1)],
                    ]
                })
            })
            .collect();
        Mesh::new_unchecked(positions, triangles)
    }

    #[test]
    fn unit_cube_exact() {
        let s = mesh_stats(&Mesh::unit_cube());
        assert_eq!(s.volume, 1.0);
        assert_eq!(s.area, 6.0);
        assert_eq!(s.projected_area.xy, 2.0);
        assert_eq!(
            (s.boundary_edges, s.non_manifold_edges, s.inconsistent_edges),
            (0, 0, 0)
        );
        assert_eq!((s.edges, s.components, s.degenerate_triangles), (18, 1, 0));
        assert!(s.closed);
        assert_eq!(signed_volume(&Mesh::unit_cube().flipped()), -1.0);
    }

    #[test]
    fn utm_cuboid_volume_keeps_precision() {
        let m = Mesh::cuboid(
            [478_614.7, 6_772_313.84, 120.5],
            [478_624.7, 6_772_333.84, 125.5],
        );
        let v = signed_volume(&m);
        assert!((v - 1000.0).abs() < 1e-6, "{v}");
    }

    #[test]
    fn cube_missing_a_face_has_4_boundary_edges() {
        let mut m = Mesh::unit_cube();
        m.triangles.drain(0..2);
        let s = mesh_stats(&m);
        assert_eq!(s.boundary_edges, 4);
        assert_eq!(s.edges, 17);
        assert!(!s.closed);
    }

    #[test]
    fn grid_patch_counts() {
        let s = mesh_stats(&grid(10));
        assert_eq!(s.triangles, 200);
        assert_eq!(s.boundary_edges, 40);
        assert_eq!(s.edges, 2 * 10 * 11 + 100);
        assert_eq!(s.projected_area.xy, 100.0);
        assert_eq!(s.area, 100.0);
        assert_eq!(s.projected_area.yz, 0.0);
    }

    #[test]
    fn flipped_triangle_gives_three_inconsistent_edges() {
        let mut m = grid(4);
        let [a, b, c] = m.triangles[10];
        m.triangles[10] = [a, c, b];
        let s = mesh_stats(&m);
        assert_eq!(s.inconsistent_edges, 3);
    }

    #[test]
    fn degenerate_and_duplicate() {
        let m = Mesh::new_unchecked(
            vec![
                [0.0; 3],
                [1.0, 1.0, 1.0],
                [3.0, 3.0, 3.0],
                [0.1, 0.2, 0.30000000000000004],
            ],
            vec![[0, 1, 2], [0, 1, 1], [0, 1, 3], [3, 1, 0], [1, 3, 0]],
        );
        // [0,1,2] collinear exactly, [0,1,1] repeated index; [0,1,3] is a sliver, not degenerate.
        assert_eq!(degenerate_triangles(&m), 2);
        assert_eq!(duplicate_triangles(&m), 2);
        // A few ulps off the line is off the line.
        assert!(!is_degenerate(
            [0.0; 3],
            [1.0, 1.0, 1.0],
            [2.0, 2.0, 2.0 + 4.0 * f64::EPSILON]
        ));
        assert!(is_degenerate([0.0; 3], [1.0, 1.0, 1.0], [2.0, 2.0, 2.0]));
        // Beyond the range of the adaptive predicate (the exact path): huge and tiny.
        for s in [1e250, 1e-250] {
            let p = |x: f64, y: f64, z: f64| [s * x, s * y, s * z];
            assert!(is_degenerate(
                p(1.0, 1.0, 1.0),
                p(2.0, 2.0, 2.0),
                p(3.0, 3.0, 3.0)
            ));
            let off = 3.0 + 4.0 * f64::EPSILON;
            assert!(!is_degenerate(
                p(1.0, 1.0, 1.0),
                p(2.0, 2.0, 2.0),
                p(3.0, 3.0, off)
            ));
        }
    }

    #[test]
    fn empty_mesh_measures_zero() {
        let s = mesh_stats(&Mesh::default());
        assert_eq!(
            (s.triangles, s.components, s.volume, s.area),
            (0, 0, 0.0, 0.0)
        );
        assert!(!s.closed);
        assert_eq!(s.bbox, None);
    }
}
