//! Spatial queries on a mesh's triangles through its bounding-volume hierarchy: which
//! triangles meet a box, contain a point, or meet a segment (a ray cut to a length). The
//! reference library's spatial grids and ray votes, answered exactly: box tests compare
//! the exact `f64` boxes, point and segment tests are exact predicates on the input
//! coordinates.
//!
//! ```
//! use meshbool::query::TriangleIndex;
//! use meshbool::{Aabb, Mesh};
//!
//! let cube = Mesh::unit_cube();
//! let index = TriangleIndex::new(&cube);
//! // The two triangles of the face x = 1 hold the point (1, 0.25, 0.5)...
//! assert_eq!(index.containing(&[1.0, 0.25, 0.5]).len(), 1);
//! // ...and a vertical segment through the cube meets its top and bottom.
//! assert_eq!(index.on_segment(&[0.3, 0.4, -1.0], &[0.3, 0.4, 2.0]).len(), 2);
//! let near = index.in_box(&Aabb { min: [0.9; 3], max: [1.1; 3] });
//! assert!(!near.is_empty());
//! ```

use crate::bvh::Bvh;
use crate::kernel::{orient2d, orient3d_explicit, Point, Sign, Triangle};
use crate::{Aabb, Mesh};

/// The triangles of a mesh indexed for queries (built once, in parallel; queries take
/// `&self` and may run from several threads).
pub struct TriangleIndex<'a> {
    mesh: &'a Mesh,
    bvh: Bvh,
}

impl<'a> TriangleIndex<'a> {
    /// Indexes `mesh`'s triangles.
    pub fn new(mesh: &'a Mesh) -> Self {
        TriangleIndex {
            mesh,
            bvh: Bvh::new(mesh),
        }
    }

    /// The triangles whose bounding boxes meet the closed box `b` (touching counts),
    /// ascending.
    pub fn in_box(&self, b: &Aabb) -> Vec<u32> {
        let mut t = self.bvh.in_box(self.mesh, &[b.min, b.max]);
        t.sort_unstable();
        t
    }

    /// The triangles that contain `p`, edges and corners included, decided exactly;
    /// ascending. Degenerate (zero-area) triangles contain nothing.
    pub fn containing(&self, p: &[f64; 3]) -> Vec<u32> {
        let mut t: Vec<u32> = self
            .bvh
            .in_box(self.mesh, &[*p, *p])
            .into_iter()
            .filter(|&t| contains(self.mesh, t, p))
            .collect();
        t.sort_unstable();
        t
    }

    /// The triangles the closed segment from `p` to `q` meets (crossing, touching, or
    /// lying in the triangle's plane across it), decided exactly; ascending. A ray is a
    /// segment to a point far enough along it.
    pub fn on_segment(&self, p: &[f64; 3], q: &[f64; 3]) -> Vec<u32> {
        let b = [
            std::array::from_fn(|k| p[k].min(q[k])),
            std::array::from_fn(|k| p[k].max(q[k])),
        ];
        let mut t: Vec<u32> = self
            .bvh
            .in_box(self.mesh, &b)
            .into_iter()
            .filter(|&t| meets_segment(self.mesh, t, p, q))
            .collect();
        t.sort_unstable();
        t
    }
}

/// Exactly whether `p` lies in triangle `t` of `m`, boundary included.
pub(crate) fn contains(m: &Mesh, t: u32, p: &[f64; 3]) -> bool {
    let [a, b, c] = m.corners(t as usize);
    if orient3d_explicit(&a, &b, &c, p) != Sign::Zero {
        return false;
    }
    let Some(shape) = Triangle::new([a, b, c]) else {
        return false;
    };
    in_closed_2d(&[a, b, c], p, shape.axis())
}

/// Whether `p` (in the triangle's plane) lies in the closed triangle, projected along
/// `axis`.
fn in_closed_2d(tri: &[[f64; 3]; 3], p: &[f64; 3], axis: usize) -> bool {
    let [a, b, c, q] = [tri[0], tri[1], tri[2], *p].map(Point::Explicit);
    let s = [
        orient2d(&a, &b, &q, axis),
        orient2d(&b, &c, &q, axis),
        orient2d(&c, &a, &q, axis),
    ];
    !(s.contains(&Sign::Positive) && s.contains(&Sign::Negative))
}

/// Exactly whether the closed segment `p q` meets triangle `t` of `m`.
fn meets_segment(m: &Mesh, t: u32, p: &[f64; 3], q: &[f64; 3]) -> bool {
    let [a, b, c] = m.corners(t as usize);
    let Some(shape) = Triangle::new([a, b, c]) else {
        return false;
    };
    let (sp, sq) = (
        orient3d_explicit(&a, &b, &c, p),
        orient3d_explicit(&a, &b, &c, q),
    );
    if sp == sq && sp != Sign::Zero {
        return false; // both ends strictly on one side
    }
    if sp == Sign::Zero && sq == Sign::Zero {
        // In the triangle's plane: an end inside, or the segment crossing an edge.
        let axis = shape.axis();
        if in_closed_2d(&[a, b, c], p, axis) || in_closed_2d(&[a, b, c], q, axis) {
            return true;
        }
        let [pp, qq] = [*p, *q].map(Point::Explicit);
        return [(a, b), (b, c), (c, a)].iter().any(|(u, v)| {
            let [u, v] = [*u, *v].map(Point::Explicit);
            let apart = |x: Sign, y: Sign| x.times(y) != Sign::Positive;
            apart(orient2d(&pp, &qq, &u, axis), orient2d(&pp, &qq, &v, axis))
                && apart(orient2d(&u, &v, &pp, axis), orient2d(&u, &v, &qq, axis))
        });
    }
    // The segment reaches the plane: it meets the triangle where the line through it
    // passes inside (or on) all three edges.
    let s = [
        orient3d_explicit(p, q, &a, &b),
        orient3d_explicit(p, q, &b, &c),
        orient3d_explicit(p, q, &c, &a),
    ];
    !(s.contains(&Sign::Positive) && s.contains(&Sign::Negative))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn boxes_points_and_segments_against_a_cube() {
        let cube = Mesh::unit_cube();
        let index = TriangleIndex::new(&cube);
        // Every triangle meets a box around the cube; none a box apart from it.
        let all = index.in_box(&Aabb {
            min: [-1.0; 3],
            max: [2.0; 3],
        });
        assert_eq!(all, (0..12).collect::<Vec<u32>>());
        assert!(index
            .in_box(&Aabb {
                min: [1.5; 3],
                max: [2.0; 3]
            })
            .is_empty());
        // A box touching the cube at its corner (1, 1, 1) only: the triangles whose boxes
        // reach it, those of the three faces at that corner (boxes, not shapes).
        let corner = index.in_box(&Aabb {
            min: [1.0; 3],
            max: [2.0; 3],
        });
        let at_faces: Vec<u32> = (0..12)
            .filter(|&t| {
                let c = cube.corners(t as usize);
                (0..3).any(|k| c.iter().all(|p| p[k] == 1.0))
            })
            .collect();
        assert_eq!((corner.len(), &corner), (6, &at_faces));
        // Points: inside a face (one triangle), on a face diagonal (two), at a corner (the
        // fan), off the surface (none), just off a face (none).
        assert_eq!(index.containing(&[0.25, 0.5, 0.0]).len(), 1);
        assert_eq!(index.containing(&[0.5, 0.5, 1.0]).len(), 2);
        let fan = index.containing(&[1.0; 3]);
        assert_eq!(
            fan.len(),
            cube.triangles.iter().filter(|t| t.contains(&7)).count()
        );
        assert!(index.containing(&[0.5; 3]).is_empty());
        assert!(index.containing(&[1.0 + f64::EPSILON, 0.5, 0.5]).is_empty());
        // Segments: through the cube (two faces), along the z axis through a face's
        // diagonal (four triangles: two per face), grazing an edge, lying in a face,
        // stopping short of the surface.
        assert_eq!(
            index.on_segment(&[0.3, 0.4, -1.0], &[0.3, 0.4, 2.0]).len(),
            2
        );
        assert_eq!(
            index.on_segment(&[0.5, 0.5, -1.0], &[0.5, 0.5, 2.0]).len(),
            4
        );
        let graze = index.on_segment(&[-1.0, 0.0, 0.5], &[2.0, 0.0, 0.5]);
        assert!(graze.len() >= 2, "{graze:?}");
        let in_face = index.on_segment(&[0.1, 0.2, 1.0], &[0.9, 0.7, 1.0]);
        assert!(in_face
            .iter()
            .all(|&t| cube.corners(t as usize).iter().all(|c| c[2] == 1.0)));
        assert!(!in_face.is_empty());
        assert!(index
            .on_segment(&[0.2, 0.2, 0.2], &[0.8, 0.8, 0.8])
            .is_empty());
        // A ray cast along +z from inside meets the top once: odd parity, inside.
        assert_eq!(
            index.on_segment(&[0.3, 0.7, 0.4], &[0.3, 0.7, 10.0]).len(),
            1
        );
    }
}
