//! # meshbool
//!
//! Exact boolean operations on triangle meshes — closed solids and open surfaces such as
//! terrain — with the tools around them: intersection curves, split-and-pick, closing,
//! repair, measures and file formats.
//!
//! The whole library works on one data model, [`Mesh`]: vertex positions (`f64`) and
//! triangles as vertex indices (libigl's `V, F`). A triangle soup is a `Mesh` whose
//! triangles share no vertices.
//!
//! ```
//! use meshbool::{Mesh, measure};
//!
//! let cube = Mesh::unit_cube();
//! let stats = measure::mesh_stats(&cube);
//! assert_eq!(stats.volume, 1.0);
//! assert_eq!(stats.boundary_edges, 0);
//! assert!(stats.closed);
//! ```
//!
//! Reading and writing files goes through [`io`]:
//!
//! ```no_run
//! let mesh = meshbool::io::read_path("terrain.obj")?;
//! meshbool::io::write_path("terrain.ply", &mesh)?;
//! # Ok::<(), meshbool::Error>(())
//! ```
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod arrange;
pub mod boolean;
pub mod broad;
pub mod bvh;
pub mod classify;
pub mod edges;
mod error;
mod format;
pub mod intersect;
pub mod io;
pub mod kernel;
pub mod measure;
mod mesh;
pub mod repair;
pub mod shapes;
#[cfg(test)]
mod test_util;
mod vec3;
mod welder;

pub use edges::EdgeTopology;
pub use error::{Error, Location, Result};
pub(crate) use mesh::Welder;
pub use mesh::{weld_exact, Aabb, Mesh, Welded};
