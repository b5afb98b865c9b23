//! `transform` at the front door: a mesh moved, turned, scaled or mirrored by an affine
//! [`Transform`].

use serde::Serialize;

use super::{Measures, SCHEMA};
use crate::{Aabb, Error, Mesh, Result, Transform};

/// The result of [`transform()`].
#[derive(Clone, Debug)]
pub struct TransformOutput {
    /// The transformed mesh: the input's vertices mapped, its triangles as they were
    /// (reversed when the transform mirrors).
    pub mesh: Mesh,
    /// The transform applied.
    pub transform: Transform,
}

/// The JSON of `meshbool transform --json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TransformReport {
    /// [`SCHEMA`].
    pub schema: u32,
    /// The transform's matrix, 16 numbers row-major ([`Transform::to_row_major`]).
    pub matrix: [f64; 16],
    /// Its determinant (the volume factor).
    pub determinant: f64,
    /// Whether every triangle was reversed (the transform mirrors).
    pub reversed: bool,
    /// Measures of the result.
    #[serde(flatten)]
    pub result: Measures,
    /// The result's bounding box (`None` without triangles).
    pub bbox: Option<Aabb>,
}

impl TransformOutput {
    /// The report, with the result's measures.
    pub fn report(&self) -> TransformReport {
        TransformReport {
            schema: SCHEMA,
            matrix: self.transform.to_row_major(),
            determinant: self.transform.determinant(),
            reversed: self.transform.reverses_orientation(),
            result: Measures::of(&self.mesh),
            bbox: self.mesh.bounds(),
        }
    }
}

/// `mesh` mapped by `t` ([`Mesh::transformed`]: a mirroring transform reverses every
/// triangle, so solids keep facing outward). The mesh is taken as it is (not welded; its
/// vertices and triangles keep their order). Errors when the mesh has non-finite
/// coordinates, when `t` has non-finite numbers or is singular (determinant 0: it would
/// flatten the mesh), and when the result's coordinates overflow `f64`.
pub fn transform(mesh: &Mesh, t: &Transform) -> Result<TransformOutput> {
    mesh.validate()?;
    if !t.is_finite() {
        return Err(Error::InvalidParameter(format!(
            "the transform has non-finite numbers: {:?}",
            t.to_row_major()
        )));
    }
    let det = t.determinant();
    if det == 0.0 {
        return Err(Error::InvalidParameter(
            "the transform is singular (determinant 0): it would flatten the mesh".into(),
        ));
    }
    if !det.is_finite() {
        return Err(Error::InvalidParameter(
            "the transform's determinant overflows f64".into(),
        ));
    }
    let out = mesh.transformed(t);
    if out.validate().is_err() {
        return Err(Error::InvalidParameter(
            "the transform takes coordinates beyond the range of f64".into(),
        ));
    }
    Ok(TransformOutput {
        mesh: out,
        transform: *t,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn report_has_the_matrix_and_the_measures() {
        let t = Transform::scaling_xyz([-2.0, 2.0, 2.0]).translate([1.0, 0.0, 0.0]);
        let out = transform(&Mesh::unit_cube(), &t).unwrap();
        let r = out.report();
        assert_eq!(r.matrix[..4], [-2.0, 0.0, 0.0, 1.0]);
        assert_eq!((r.determinant, r.reversed), (-8.0, true));
        assert_eq!((r.result.volume, r.result.closed), (8.0, true));
        let b = r.bbox.unwrap();
        assert_eq!((b.min, b.max), ([-1.0, 0.0, 0.0], [1.0, 2.0, 2.0]));
    }

    #[test]
    fn refuses_singular_non_finite_and_overflowing_transforms() {
        let cube = Mesh::unit_cube();
        for t in [
            Transform::scaling_xyz([1.0, 0.0, 1.0]),
            Transform::translation([f64::NAN, 0.0, 0.0]),
            Transform::scaling(1e200),
            Transform::translation([f64::MAX, 0.0, 0.0]).translate([f64::MAX, 0.0, 0.0]),
        ] {
            assert!(
                matches!(transform(&cube, &t), Err(Error::InvalidParameter(_))),
                "{t:?}"
            );
        }
        let mut bad = cube.clone();
        bad.positions_mut()[0][0] = f64::INFINITY;
        assert!(transform(&bad, &Transform::IDENTITY).is_err());
    }
}
