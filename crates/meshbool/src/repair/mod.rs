//! Mesh repair. This first part: consistent orientation ([`orient`]). Weld with a
//! tolerance, T-junctions, degenerate removal, hole capping, stitching and curtains follow
//! (issue 5).

mod orient;

pub use orient::{orient, Facing, OrientReport};
