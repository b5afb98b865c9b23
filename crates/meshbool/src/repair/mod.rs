//! Mesh repair: consistent orientation ([`orient`]), boundary loops and hole capping
//! ([`cap_holes`]), curtain walls to a floor ([`curtain`]). Weld with a
//! tolerance, T-junctions, degenerate removal, hole capping, stitching and curtains follow
//! (issue 5).

mod cap;
mod curtain;
mod orient;

pub use cap::{boundary_loops, cap_holes, CapReport};
pub use curtain::{curtain, CurtainReport};
pub use orient::{orient, Facing, OrientReport};
