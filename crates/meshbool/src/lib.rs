//! # meshbool
//!
//! Exact boolean operations on triangle meshes — closed solids and open surfaces such as
//! terrain — with the tools around them: intersection curves, split-and-pick, closing,
//! repair, measures and file formats.
//!
//! ```
//! use meshbool::ops::{boolean, BooleanOptions};
//! use meshbool::{Mesh, Op};
//!
//! let a = Mesh::unit_cube();
//! let b = Mesh::cuboid([0.5; 3], [1.5; 3]);
//! let union = boolean(&a, &b, Op::Union, &BooleanOptions::default())?;
//! let inter = boolean(&a, &b, Op::Intersection, &BooleanOptions::default())?;
//! let (u, i) = (union.report().result, inter.report().result);
//! assert!(u.closed && i.closed);
//! assert_eq!(u.volume + i.volume, 1.0 + 1.0); // vol(A ∪ B) + vol(A ∩ B) = vol(A) + vol(B)
//! assert_eq!(i.volume, 0.125);
//! # Ok::<(), meshbool::Error>(())
//! ```
//!
//! ## Where to start
//!
//! - [`Mesh`]: the one data model, vertex positions (`f64`) and triangles as vertex
//!   indices (libigl's `V, F`). A triangle soup is a `Mesh` whose triangles share no
//!   vertices.
//! - [`ops`]: the front door, one function per command of the `meshbool` tool —
//!   [`ops::boolean`], [`ops::split`] and [`ops::SplitOutput::pick`], [`ops::curves`],
//!   [`ops::repair`], [`ops::close`], [`ops::orient`], [`ops::info`], [`ops::read`] and
//!   [`ops::write`] — each with an options struct and an output whose `report()` is the
//!   tool's `--json`. Inputs are checked at the door ([`ops::Operand`]).
//! - [`io`]: readers and writers (STL, OBJ, PLY, OFF (read only), DXF, JSON soups, binary
//!   glTF, GOCAD TSurf, Surpac DTM, LandXML) in `f64`.
//! - [`measure`]: volume, areas, edge statistics ([`measure::mesh_stats`]).
//! - [`repair`]: each repair step on its own (weld, T-junctions, degenerates, capping,
//!   stitching, curtains, orientation, folds) and the [`repair::repair`] pipeline.
//! - [`edges`]: edge adjacency and components; [`ops::curves`] and [`ops::self_curves`]:
//!   the exact intersection of two meshes, or of one with itself, chained into curves.
//! - [`shapes`]: primitives (cube, sphere, cylinder, cone, plane), mining examples (a
//!   seeded terrain, an open-pit shell) and generators for tests; [`Transform`]
//!   ([`transform`]): affine transforms by degrees, composed in the order applied, and
//!   [`Mesh::transformed`].
//! - The vocabulary of booleans: [`Op`] and its [`Rule`], [`Class`], [`Group`],
//!   [`Provenance`] and [`Source`], [`Stage`].
//!
//! Reading and writing files:
//!
//! ```no_run
//! let (mesh, format) = meshbool::ops::read("terrain.obj", None)?;
//! meshbool::ops::write("terrain.ply", &mesh, None)?;
//! # Ok::<(), meshbool::Error>(())
//! ```
//!
//! The pipeline's stages (`kernel`, `bvh`, `broad`, `kept`, `intersect`, `arrange`,
//! `classify`, and the pipeline itself in `boolean`) are private; the cargo feature
//! `internals` makes them public for the benchmarks and the tests that drive one stage on
//! its own. Their interfaces may change.
#![forbid(unsafe_code)]
#![warn(missing_docs)]
// A public type that cannot be named (public, in a private module, and not re-exported)
// is a hole in the curated surface.
#![warn(unnameable_types)]

/// A pipeline stage's module: public with the cargo feature `internals` (for the
/// benchmarks and tests that drive a stage on its own), private otherwise.
macro_rules! internal {
    ($m:ident) => {
        #[cfg(feature = "internals")]
        pub mod $m;
        #[cfg(not(feature = "internals"))]
        mod $m;
    };
}

/// `Display` and `FromStr` for an enum with `ALL` and `name()`: written and read by its
/// names (reading ignores ASCII case and lists the names when it fails).
macro_rules! by_name {
    ($t:ty, $what:literal) => {
        impl std::fmt::Display for $t {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl std::str::FromStr for $t {
            type Err = crate::Error;

            fn from_str(s: &str) -> Result<Self, Self::Err> {
                crate::error::parse_name(s, &<$t>::ALL, <$t>::name, $what)
            }
        }
    };
}

internal!(arrange);
internal!(boolean);
internal!(broad);
internal!(bvh);
internal!(classify);
pub mod csg;
pub mod edges;
mod error;
mod format;
internal!(intersect);
pub mod io;
internal!(kept);
internal!(kernel);
pub mod measure;
mod mesh;
mod mesh_edit;
pub mod ops;
mod par;
pub mod query;
pub mod repair;
mod scale;
pub mod shapes;
mod stage;
#[cfg(test)]
mod test_util;
pub mod transform;

/// The README's Rust examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
struct ReadmeDoctests;

/// The library guide's examples (docs/library.md), compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../../docs/library.md")]
struct LibraryGuideDoctests;

/// The CSG guide's examples (docs/csg.md), compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../../docs/csg.md")]
struct CsgGuideDoctests;
mod vec3;
mod welder;

pub use boolean::{FillRule, Group, Keep, Op, Provenance, Rule, Selection, Source};
pub use classify::Class;
pub use edges::EdgeTopology;
pub use error::{Error, Location, Result};
pub use format::Format;
pub use mesh::{weld_exact, Aabb, Mesh, Welded};
pub use stage::Stage;
pub use transform::Transform;
pub(crate) use welder::Welder;
