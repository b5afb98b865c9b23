//! `make` at the front door: the primitives and mining examples of [`crate::shapes`] by
//! name, with a report.

use serde::Serialize;

use super::{Measures, SCHEMA};
use crate::{shapes, Aabb, Mesh, Result};

/// A primitive and its parameters (each as the [`crate::shapes`] function of its name
/// takes them).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// An axis-aligned box ([`shapes::cuboid`]; a cube of edge `s` about `c` is
    /// `c − s/2 .. c + s/2`, [`shapes::cube`]).
    Cube {
        /// Smallest corner.
        min: [f64; 3],
        /// Largest corner.
        max: [f64; 3],
    },
    /// A UV sphere ([`shapes::sphere`]).
    Sphere {
        /// Centre.
        center: [f64; 3],
        /// Radius.
        radius: f64,
        /// Meridians (≥ 3).
        segments: u32,
        /// Bands from pole to pole (≥ 2).
        rings: u32,
    },
    /// A cylinder along +z ([`shapes::cylinder`]).
    Cylinder {
        /// Centre of the bottom disc.
        base: [f64; 3],
        /// Radius.
        radius: f64,
        /// Height.
        height: f64,
        /// Sides of the polygons (≥ 3).
        segments: u32,
    },
    /// A cone or frustum along +z ([`shapes::cone`]).
    Cone {
        /// Centre of the bottom disc.
        base: [f64; 3],
        /// Bottom radius.
        radius: f64,
        /// Top radius (0: an apex).
        top_radius: f64,
        /// Height.
        height: f64,
        /// Sides of the polygons (≥ 3).
        segments: u32,
    },
    /// A flat rectangle facing +z ([`shapes::plane`]).
    Plane {
        /// Centre.
        center: [f64; 3],
        /// Extent along x.
        width: f64,
        /// Extent along y.
        depth: f64,
        /// Cells along x (≥ 1).
        nx: u32,
        /// Cells along y (≥ 1).
        ny: u32,
    },
    /// A seeded terrain, an open height field facing +z ([`shapes::terrain`]).
    Terrain {
        /// Centre (of the plan rectangle, and of the heights' range).
        center: [f64; 3],
        /// Extent along x and y.
        size: [f64; 2],
        /// Cells along x and y (each ≥ 1).
        cells: [u32; 2],
        /// Highest less lowest height (≥ 0).
        relief: f64,
        /// The relief's seed.
        seed: u64,
    },
    /// An open-pit design shell facing up ([`shapes::pit`]).
    Pit {
        /// Centre of the rim (its height is the rim's).
        center: [f64; 3],
        /// Semi-axes of the rim along x and y.
        radius: [f64; 2],
        /// Rim less floor height.
        depth: f64,
        /// Faces from rim to floor (≥ 1).
        benches: u32,
        /// Width of the flat berms between faces (≥ 0).
        berm: f64,
        /// Vertices of each ring (≥ 3).
        segments: u32,
    },
}

impl Shape {
    /// The example terrain with the defaults of `meshbool make terrain` (and of the
    /// Python and JavaScript packages): a 1 km square about the origin in 100 × 100 cells,
    /// 40 of relief, seed 1.
    pub const TERRAIN: Shape = Shape::Terrain {
        center: [0.0; 3],
        size: [1000.0; 2],
        cells: [100; 2],
        relief: 40.0,
        seed: 1,
    };

    /// The example pit shell with the defaults of `meshbool make pit`: rim at height 60
    /// with semi-axes 220 × 160, 140 deep, 5 benches with berms 8 wide, 64 segments. It
    /// crosses [`Shape::TERRAIN`] along one closed curve.
    pub const PIT: Shape = Shape::Pit {
        center: [0.0, 0.0, 60.0],
        radius: [220.0, 160.0],
        depth: 140.0,
        benches: 5,
        berm: 8.0,
        segments: 64,
    };

    /// The shape's name: `cube`, `sphere`, `cylinder`, `cone`, `plane`, `terrain` or `pit`.
    pub fn name(&self) -> &'static str {
        match self {
            Shape::Cube { .. } => "cube",
            Shape::Sphere { .. } => "sphere",
            Shape::Cylinder { .. } => "cylinder",
            Shape::Cone { .. } => "cone",
            Shape::Plane { .. } => "plane",
            Shape::Terrain { .. } => "terrain",
            Shape::Pit { .. } => "pit",
        }
    }

    /// The mesh, or the error for parameters out of range.
    pub fn mesh(&self) -> Result<Mesh> {
        match *self {
            Shape::Cube { min, max } => shapes::cuboid(min, max),
            Shape::Sphere {
                center,
                radius,
                segments,
                rings,
            } => shapes::sphere(center, radius, segments, rings),
            Shape::Cylinder {
                base,
                radius,
                height,
                segments,
            } => shapes::cylinder(base, radius, height, segments),
            Shape::Cone {
                base,
                radius,
                top_radius,
                height,
                segments,
            } => shapes::cone(base, radius, top_radius, height, segments),
            Shape::Plane {
                center,
                width,
                depth,
                nx,
                ny,
            } => shapes::plane(center, width, depth, nx, ny),
            Shape::Terrain {
                center,
                size,
                cells,
                relief,
                seed,
            } => shapes::terrain(center, size, cells, relief, seed),
            Shape::Pit {
                center,
                radius,
                depth,
                benches,
                berm,
                segments,
            } => shapes::pit(center, radius, depth, benches, berm, segments),
        }
    }
}

/// The result of [`make()`].
#[derive(Clone, Debug)]
pub struct MakeOutput {
    /// The generated mesh.
    pub mesh: Mesh,
    /// What was asked for.
    pub shape: Shape,
}

/// The JSON of `meshbool make --json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MakeReport {
    /// [`SCHEMA`].
    pub schema: u32,
    /// [`Shape::name`].
    pub shape: &'static str,
    /// Measures of the mesh.
    #[serde(flatten)]
    pub result: Measures,
    /// The mesh's bounding box.
    pub bbox: Option<Aabb>,
}

impl MakeOutput {
    /// The report, with the mesh's measures.
    pub fn report(&self) -> MakeReport {
        MakeReport {
            schema: SCHEMA,
            shape: self.shape.name(),
            result: Measures::of(&self.mesh),
            bbox: self.mesh.bounds(),
        }
    }
}

/// Generates `shape`. Errors ([`crate::Error::InvalidParameter`]) for parameters out of
/// range, as the [`crate::shapes`] functions do.
pub fn make(shape: &Shape) -> Result<MakeOutput> {
    Ok(MakeOutput {
        mesh: shape.mesh()?,
        shape: *shape,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_shape_by_name() {
        let shapes = [
            Shape::Cube {
                min: [0.0; 3],
                max: [1.0, 2.0, 3.0],
            },
            Shape::Sphere {
                center: [0.0; 3],
                radius: 1.0,
                segments: 8,
                rings: 4,
            },
            Shape::Cylinder {
                base: [0.0; 3],
                radius: 1.0,
                height: 2.0,
                segments: 4,
            },
            Shape::Cone {
                base: [0.0; 3],
                radius: 1.0,
                top_radius: 0.0,
                height: 3.0,
                segments: 4,
            },
            Shape::Plane {
                center: [0.0; 3],
                width: 2.0,
                depth: 1.0,
                nx: 2,
                ny: 1,
            },
            Shape::Terrain {
                center: [0.0; 3],
                size: [10.0, 20.0],
                cells: [2, 4],
                relief: 3.0,
                seed: 5,
            },
            Shape::Pit {
                center: [0.0; 3],
                radius: [10.0, 8.0],
                depth: 6.0,
                benches: 2,
                berm: 1.0,
                segments: 8,
            },
        ];
        let volumes = [6.0, f64::NAN, 4.0, 2.0, f64::NAN, f64::NAN, f64::NAN];
        let triangles = [12, 48, 16, 8, 4, 16, 56];
        let names = [
            "cube", "sphere", "cylinder", "cone", "plane", "terrain", "pit",
        ];
        for ((s, v), (n, name)) in shapes.iter().zip(volumes).zip(triangles.iter().zip(names)) {
            let r = make(s).unwrap().report();
            assert_eq!((r.shape, s.name()), (name, name));
            assert_eq!(r.result.triangles, *n, "{name}");
            assert_eq!(r.result.closed, v.is_finite() || name == "sphere");
            if !v.is_nan() {
                assert!((r.result.volume - v).abs() < 1e-14, "{}", s.name());
            }
        }
        let b = make(&shapes[5]).unwrap().report().bbox.unwrap();
        assert_eq!((b.min, b.max), ([-5.0, -10.0, -1.5], [5.0, 10.0, 1.5]));
        let bad = Shape::Cube {
            min: [0.0; 3],
            max: [1.0, 0.0, 1.0],
        };
        assert!(make(&bad).is_err());
    }
}
