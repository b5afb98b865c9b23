//! Mesh repair: consistent orientation ([`orient`]), boundary loops and hole capping
//! ([`cap_holes`]), curtain walls to a floor ([`curtain`]), welding
//! within a distance ([`weld_within`]), T-junctions ([`resolve_t_junctions`]), duplicate and
//! anti-parallel triangles ([`remove_duplicates`]). Weld with a
//! tolerance, T-junctions, degenerate removal, hole capping, stitching and curtains follow
//! (issue 5).

mod cap;
mod curtain;
mod duplicates;
mod orient;
mod tjunction;
mod weld;

pub use cap::{boundary_loops, cap_holes, CapReport};
pub use curtain::{curtain, CurtainReport};
pub use duplicates::{remove_duplicates, DuplicateReport};
pub use orient::{orient, Facing, OrientReport};
pub use tjunction::{resolve_t_junctions, TJunctionReport};
pub use weld::{weld_within, WeldReport};
