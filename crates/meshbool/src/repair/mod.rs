//! Mesh repair: consistent orientation ([`orient`]), boundary loops and hole capping
//! ([`cap_holes`]), stitching loop pairs ([`stitch`]), curtain walls to a floor
//! ([`curtain`]), welding within a distance ([`weld_within`], or boundary vertices only:
//! [`weld_boundary`]), T-junctions ([`resolve_t_junctions`], with a tolerance:
//! [`resolve_t_junctions_within`]), duplicate and anti-parallel triangles
//! ([`remove_duplicates`], with a tolerance: [`remove_overlapping`]), degenerate and
//! sliver triangles ([`remove_degenerates`]), non-manifold edges and vertices split into manifold sheets ([`split_nonmanifold`]),
//! short edges and needles removed at a tolerance without defects ([`snap`]).
//! Every step is a function on its own that returns a report of what it did.

mod cap;
mod curtain;
mod degenerate;
mod duplicates;
mod folds;
mod inside_out;
pub(crate) mod nonmanifold;
mod orient;
mod pipeline;
mod snap;
mod stitch;
mod tjunction;
mod weld;

pub use cap::{boundary_loops, cap_holes, cap_small_holes, CapReport};
pub(crate) use curtain::curtain_to;
pub use curtain::{curtain, CurtainReport};
pub use degenerate::{remove_degenerates, DegenerateOptions, DegenerateReport};
pub use duplicates::{remove_duplicates, remove_overlapping, DuplicateReport};
pub use folds::{remove_folds, FoldReport};
pub use inside_out::inside_out;
pub(crate) use inside_out::inward;
pub use nonmanifold::{split_nonmanifold, NonManifoldReport};
pub use orient::{orient, Facing, OrientReport};
pub use pipeline::{
    close, repair, repair_with_progress, CloseMode, CloseOptions, CloseReport, RepairConfig,
    RepairReport, UndoneStep,
};
pub(crate) use snap::{check_tolerance, snap_carrying, snap_filling, snap_unchecked};
pub use snap::{snap, snap_in_place, snap_with, SnapOptions, SnapReport, Snapped};
pub use stitch::{stitch, zipper, StitchReport};
pub use tjunction::{resolve_t_junctions, resolve_t_junctions_within, TJunctionReport};
pub(crate) use weld::weld_boundary_in_place;
pub use weld::{weld_boundary, weld_within, WeldReport};
