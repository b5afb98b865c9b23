//! The one data model: [`Mesh`] (positions + triangles), soup ↔ indexed conversion,
//! exact welding (on the crate's weld table) and bounds.

use crate::error::{Error, Location, Result};
use crate::par::Grain;

/// A triangle mesh: vertex positions and triangles as triples of vertex indices
/// (counter-clockwise seen from the side the normal points to).
///
/// Every `Mesh` has valid indices: each names a vertex, and there are at most `u32::MAX`
/// vertices. [`Mesh::new`] checks this, and nothing else can break it, so no function
/// taking a `Mesh` can fail on an index. Nothing else is assumed: a mesh may be open,
/// non-manifold, inconsistently oriented, contain degenerate or repeated triangles, or
/// even non-finite coordinates ([`Mesh::validate`] checks those; operations that need
/// finite coordinates check them and return an error).
/// [`crate::measure::mesh_stats`] tells what a mesh is like.
///
/// A triangle soup is a `Mesh` whose triangles share no vertices ([`Mesh::from_soup_unwelded`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions `[x, y, z]`.
    pub(crate) positions: Vec<[f64; 3]>,
    /// Triangles as indices into `positions`.
    pub(crate) triangles: Vec<[u32; 3]>,
}

/// An axis-aligned bounding box.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Aabb {
    /// Smallest coordinates.
    pub min: [f64; 3],
    /// Largest coordinates.
    pub max: [f64; 3],
}

impl Aabb {
    /// The box's centre.
    pub fn center(&self) -> [f64; 3] {
        std::array::from_fn(|i| 0.5 * (self.min[i] + self.max[i]))
    }

    /// Whether `p` is in the closed box.
    pub fn contains(&self, p: &[f64; 3]) -> bool {
        (0..3).all(|k| self.min[k] <= p[k] && p[k] <= self.max[k])
    }

    /// The box grown to hold `p`.
    pub(crate) fn grown(self, p: &[f64; 3]) -> Aabb {
        Aabb {
            min: std::array::from_fn(|k| self.min[k].min(p[k])),
            max: std::array::from_fn(|k| self.max[k].max(p[k])),
        }
    }

    /// The box's edge lengths.
    pub fn size(&self) -> [f64; 3] {
        std::array::from_fn(|i| self.max[i] - self.min[i])
    }
}

/// The result of [`weld_exact`]: the welded mesh and, for every input vertex, its new index.
#[derive(Clone, Debug, PartialEq)]
pub struct Welded {
    /// The mesh with every set of equal positions merged into one vertex.
    pub mesh: Mesh,
    /// `vertex_map[old] = new` for every input vertex.
    pub vertex_map: Vec<u32>,
}

impl Mesh {
    /// A mesh from positions and triangles. Errors ([`Error::InvalidMesh`], naming the
    /// first offending triangle) when an index is out of range or there are more than
    /// `u32::MAX` vertices. Coordinates are taken as they are.
    pub fn new(positions: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>) -> Result<Self> {
        let mesh = Mesh {
            positions,
            triangles,
        };
        mesh.check_indices()?;
        Ok(mesh)
    }

    /// A mesh from parts the crate built and knows to be valid.
    pub(crate) fn new_unchecked(positions: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>) -> Self {
        let mesh = Mesh {
            positions,
            triangles,
        };
        debug_assert!(mesh.check_indices().is_ok());
        mesh
    }

    /// The vertex positions `[x, y, z]`.
    pub fn positions(&self) -> &[[f64; 3]] {
        &self.positions
    }

    /// The vertex positions, to move them (the mesh's connectivity stays as it is).
    pub fn positions_mut(&mut self) -> &mut [[f64; 3]] {
        &mut self.positions
    }

    /// The triangles, as indices into [`Mesh::positions`].
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// Adds `other`'s vertices and triangles to this mesh (its vertices after this mesh's,
    /// not welded to them). Errors, changing nothing, when the two together would have
    /// more than `u32::MAX` vertices.
    pub fn append(&mut self, other: &Mesh) -> Result<()> {
        if self.positions.len() + other.positions.len() > u32::MAX as usize {
            return Err(Error::invalid(
                Location::Whole,
                "appending would exceed the limit of u32::MAX vertices",
            ));
        }
        let offset = self.positions.len() as u32;
        self.positions.extend_from_slice(&other.positions);
        self.triangles
            .extend(other.triangles.iter().map(|t| t.map(|v| v + offset)));
        Ok(())
    }

    /// The positions and triangles, giving up the mesh.
    pub fn into_parts(self) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
        (self.positions, self.triangles)
    }

    /// The axis-aligned unit cube `[0,1]^3`, 8 vertices, 12 outward-facing triangles.
    pub fn unit_cube() -> Self {
        Self::cuboid([0.0; 3], [1.0; 3])
    }

    /// An axis-aligned box from `min` to `max`, 8 vertices, 12 outward-facing triangles.
    pub fn cuboid(min: [f64; 3], max: [f64; 3]) -> Self {
        let positions = (0..8)
            .map(|i| {
                [
                    if i & 1 == 0 { min[0] } else { max[0] },
                    if i & 2 == 0 { min[1] } else { max[1] },
                    if i & 4 == 0 { min[2] } else { max[2] },
                ]
            })
            .collect();
        let triangles = vec![
            [0, 2, 1],
            [1, 2, 3], // z = min
            [4, 5, 6],
            [5, 7, 6], // z = max
            [0, 1, 4],
            [1, 5, 4], // y = min
            [2, 6, 3],
            [3, 6, 7], // y = max
            [0, 4, 2],
            [2, 4, 6], // x = min
            [1, 3, 5],
            [3, 7, 5], // x = max
        ];
        Mesh {
            positions,
            triangles,
        }
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Number of vertices (including any that no triangle uses).
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// True when the mesh has no triangles.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// The three corner positions of triangle `t`. Panics if `t` is out of range, as
    /// indexing does.
    #[inline]
    pub fn corners(&self, t: usize) -> [[f64; 3]; 3] {
        let [a, b, c] = self.triangles[t];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }

    /// Twice the area of triangle `t` (the length of its normal `(b − a) × (c − a)`).
    pub(crate) fn twice_area(&self, t: usize) -> f64 {
        use crate::vec3::{cross, norm, sub};
        let [a, b, c] = self.corners(t);
        norm(&cross(&sub(&b, &a), &sub(&c, &a)))
    }

    /// The centroid of triangle `t`.
    pub(crate) fn centroid(&self, t: usize) -> [f64; 3] {
        let [a, b, c] = self.corners(t);
        std::array::from_fn(|k| (a[k] + b[k] + c[k]) / 3.0)
    }

    /// The centroid of the largest of the triangles `tris` (none: `None`): a point on the
    /// surface as far from its edges as the triangles allow, where winding numbers of
    /// other surfaces are evaluated.
    pub(crate) fn probe(&self, tris: impl Iterator<Item = usize>) -> Option<[f64; 3]> {
        let t = tris.max_by(|&i, &j| self.twice_area(i).total_cmp(&self.twice_area(j)))?;
        Some(self.centroid(t))
    }

    /// A mesh from a triangle soup (three corner positions per triangle), with corners at
    /// exactly equal positions welded into one vertex ([`weld_exact`]).
    pub fn from_soup(soup: &[[[f64; 3]; 3]]) -> Self {
        let corners = soup.as_flattened();
        let (positions, ids) = crate::welder::weld_all(corners.len(), soup.len() / 2, |r, out| {
            out.extend_from_slice(&corners[r])
        });
        Mesh {
            positions,
            triangles: crate::welder::triangles_of(&ids),
        }
    }

    /// A mesh from a triangle soup without welding: triangle `t` uses vertices `3t..3t+3`.
    pub fn from_soup_unwelded(soup: &[[[f64; 3]; 3]]) -> Self {
        let positions = soup.iter().flatten().copied().collect();
        let triangles = (0..soup.len() as u32)
            .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
            .collect();
        Mesh {
            positions,
            triangles,
        }
    }

    /// The triangle soup: three corner positions per triangle.
    pub fn to_soup(&self) -> Vec<[[f64; 3]; 3]> {
        (0..self.triangles.len()).map(|t| self.corners(t)).collect()
    }

    /// Checks that every coordinate is finite (indices are always in range). The error
    /// names the first offending vertex.
    pub fn validate(&self) -> Result<()> {
        debug_assert!(self.check_indices().is_ok());
        use rayon::prelude::*;
        if let Some(v) = self
            .positions
            .par_iter()
            .grained()
            .with_min_len(1 << 14)
            .position_first(|p| p.iter().any(|c| !c.is_finite()))
        {
            return Err(Error::invalid(
                Location::Vertex(v),
                format!("non-finite coordinate {:?}", self.positions[v]),
            ));
        }
        Ok(())
    }

    /// Every index in range, at most `u32::MAX` vertices.
    fn check_indices(&self) -> Result<()> {
        if self.positions.len() > u32::MAX as usize {
            return Err(Error::invalid(
                Location::Whole,
                format!(
                    "{} vertices exceed the limit of {}",
                    self.positions.len(),
                    u32::MAX
                ),
            ));
        }
        let n = self.positions.len() as u64;
        if let Some(t) = self
            .triangles
            .iter()
            .position(|tri| tri.iter().any(|&i| u64::from(i) >= n))
        {
            return Err(Error::invalid(
                Location::Triangle(t),
                format!(
                    "vertex index out of range in {:?} (the mesh has {n} vertices)",
                    self.triangles[t]
                ),
            ));
        }
        Ok(())
    }

    /// The bounding box of the vertices that triangles use; `None` for a mesh without triangles.
    pub fn bounds(&self) -> Option<Aabb> {
        use rayon::prelude::*;
        // Pieces of fixed size combined in order: the same box on any number of threads.
        const PIECE: usize = 1 << 16;
        let piece = |tris: &[[u32; 3]]| {
            let mut it = tris.iter().flatten();
            let first = self.positions[*it.next()? as usize];
            let mut b = Aabb {
                min: first,
                max: first,
            };
            for &i in it {
                b = b.grown(&self.positions[i as usize]);
            }
            Some(b)
        };
        if self.triangles.len() <= PIECE {
            return piece(&self.triangles);
        }
        let boxes: Vec<Option<Aabb>> = self
            .triangles
            .par_chunks(PIECE)
            .grained()
            .map(piece)
            .collect();
        let mut it = boxes.into_iter().flatten();
        let first = it.next()?;
        Some(it.fold(first, |b, c| b.grown(&c.min).grown(&c.max)))
    }

    /// The same mesh with every triangle's orientation reversed.
    pub fn flipped(&self) -> Mesh {
        Mesh {
            positions: self.positions.clone(),
            triangles: self.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect(),
        }
    }

    /// The triangles `ids` (in range) of this mesh as a mesh of their own, with only the
    /// vertices they use, numbered in order of first use.
    pub(crate) fn subset(&self, ids: &[u32]) -> Mesh {
        self.subset_renumbered(ids).0
    }

    /// [`Mesh::subset`], with the new id of each vertex of `self` (`u32::MAX` for those
    /// the subset does not use).
    pub(crate) fn subset_renumbered(&self, ids: &[u32]) -> (Mesh, Vec<u32>) {
        let mut id = vec![u32::MAX; self.positions.len()];
        let mut positions = Vec::new();
        let triangles = ids
            .iter()
            .map(|&t| {
                self.triangles[t as usize].map(|v| {
                    if id[v as usize] == u32::MAX {
                        id[v as usize] = positions.len() as u32;
                        positions.push(self.positions[v as usize]);
                    }
                    id[v as usize]
                })
            })
            .collect();
        (Mesh::new_unchecked(positions, triangles), id)
    }

    /// The same mesh without the vertices no triangle uses, the rest renumbered in order of
    /// first use; also returns how many were dropped.
    pub fn without_unreferenced(self) -> (Mesh, usize) {
        let (kept, _) = self.without_unreferenced_renumbered();
        let dropped = self.positions.len() - kept.positions.len();
        (kept, dropped)
    }

    /// [`Mesh::without_unreferenced`], with the new id of each old vertex (`u32::MAX` for
    /// those dropped).
    pub(crate) fn without_unreferenced_renumbered(&self) -> (Mesh, Vec<u32>) {
        let all: Vec<u32> = (0..self.triangles.len() as u32).collect();
        self.subset_renumbered(&all)
    }
}

/// Welds vertices whose positions are exactly equal (as `f64` numbers; `0.0` and `-0.0`
/// are equal). No tolerance: for welding within a distance use the repair tools.
///
/// Input: any mesh. Output: the welded mesh, vertices in order
/// of first appearance in `positions`, triangles unchanged in number and order (a triangle
/// whose corners become equal stays, as a degenerate triangle), plus the old→new vertex map.
/// Deterministic.
pub fn weld_exact(mesh: &Mesh) -> Welded {
    use rayon::prelude::*;
    // Mostly distinct positions: as many vertices expected as there are.
    let n = mesh.positions.len();
    let (positions, vertex_map) =
        crate::welder::weld_all(n, n, |r, out| out.extend_from_slice(&mesh.positions[r]));
    let triangles = mesh
        .triangles
        .par_iter()
        .grained()
        .map(|t| t.map(|i| vertex_map[i as usize]))
        .collect();
    Welded {
        mesh: Mesh {
            positions,
            triangles,
        },
        vertex_map,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn soup_round_trip_welds_shared_corners() {
        let cube = Mesh::unit_cube();
        let soup = cube.to_soup();
        assert_eq!(soup.len(), 12);
        let unwelded = Mesh::from_soup_unwelded(&soup);
        assert_eq!(unwelded.vertex_count(), 36);
        let welded = Mesh::from_soup(&soup);
        assert_eq!(welded.vertex_count(), 8);
        assert_eq!(welded.to_soup(), soup);
    }

    #[test]
    fn weld_merges_negative_zero_but_not_neighbours() {
        let m = Mesh::new_unchecked(
            vec![
                [0.0, 0.0, 1.0],
                [-0.0, 0.0, 1.0],
                [0.0, 0.0, f64::from_bits(1.0f64.to_bits() + 1)],
            ],
            vec![[0, 1, 2]],
        );
        let w = weld_exact(&m);
        assert_eq!(w.vertex_map, vec![0, 0, 1]);
        assert_eq!(w.mesh.triangles, vec![[0, 0, 1]]);
    }

    #[test]
    fn validate_names_offender() {
        let (positions, mut triangles) = Mesh::unit_cube().into_parts();
        triangles[5] = [0, 1, 8];
        assert!(matches!(
            Mesh::new(positions, triangles),
            Err(Error::InvalidMesh {
                location: Location::Triangle(5),
                ..
            })
        ));
        let mut m = Mesh::unit_cube();
        m.positions[3][1] = f64::NAN;
        assert!(matches!(
            m.validate(),
            Err(Error::InvalidMesh {
                location: Location::Vertex(3),
                ..
            })
        ));
        assert!(Mesh::unit_cube().validate().is_ok());
    }

    #[test]
    fn bounds_of_cuboid() {
        let b = Mesh::cuboid([-1.0, 2.0, 3.0], [4.0, 5.0, 6.0])
            .bounds()
            .unwrap();
        assert_eq!(b.min, [-1.0, 2.0, 3.0]);
        assert_eq!(b.max, [4.0, 5.0, 6.0]);
        assert_eq!(Mesh::default().bounds(), None);
    }
}
