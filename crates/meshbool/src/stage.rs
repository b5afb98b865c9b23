//! What a running call reports and obeys: the [`Stage`]s it begins (told to a progress
//! callback) and the [`Cancel`] flag it checks as each begins. Below the pipeline and
//! repair, which report their stages and steps; the front door re-exports [`Cancel`].

use std::sync::Arc;

/// The stages of a boolean or split, and the steps of a repair, as reported to a progress
/// callback ([`crate::ops::RunOptions::progress`]) when each begins.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Checking the inputs (validity, orientation, self-intersections).
    Check,
    /// Intersection curves (broad phase and exact triangle pairs).
    Intersect,
    /// Re-triangulating the cut triangles of both meshes.
    Arrange,
    /// Inside/outside classification.
    Classify,
    /// Selecting and merging the result.
    Merge,
    /// Repair: welding vertices within a distance.
    Weld,
    /// Repair: removing duplicate (or, with a tolerance, overlapping) triangles.
    Duplicates,
    /// Repair: welding boundary vertices within a distance.
    WeldBoundary,
    /// Repair: splitting boundary edges at T-junctions.
    TJunctions,
    /// Repair: removing degenerate and sliver triangles.
    Degenerate,
    /// Snapping at a tolerance: short edges and needles removed (a boolean's or resolve's
    /// last step with a snap tolerance, and a repair step).
    Snap,
    /// Repair: making orientation consistent.
    Orient,
    /// Repair: removing the folds of a terrain.
    Folds,
    /// Repair: closing into a solid.
    Close,
    /// Repair: capping the small holes left.
    CloseGaps,
}

impl Stage {
    /// Every stage, in the order they run: a boolean's, then a repair's steps.
    pub const ALL: [Stage; 15] = [
        Stage::Check,
        Stage::Intersect,
        Stage::Arrange,
        Stage::Classify,
        Stage::Merge,
        Stage::Weld,
        Stage::Duplicates,
        Stage::WeldBoundary,
        Stage::TJunctions,
        Stage::Degenerate,
        Stage::Snap,
        Stage::Orient,
        Stage::Folds,
        Stage::Close,
        Stage::CloseGaps,
    ];

    /// The stage's name: `check`, `intersect`, `arrange`, `classify`, `merge`; a repair
    /// step's is its key in the repair report: `weld`, `duplicates`, `weld_boundary`,
    /// `tjunctions`, `degenerate`, `snap`, `orient`, `folds`, `close`, `close_gaps`.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Check => "check",
            Stage::Intersect => "intersect",
            Stage::Arrange => "arrange",
            Stage::Classify => "classify",
            Stage::Merge => "merge",
            Stage::Weld => "weld",
            Stage::Duplicates => "duplicates",
            Stage::WeldBoundary => "weld_boundary",
            Stage::TJunctions => "tjunctions",
            Stage::Degenerate => "degenerate",
            Stage::Snap => "snap",
            Stage::Orient => "orient",
            Stage::Folds => "folds",
            Stage::Close => "close",
            Stage::CloseGaps => "close_gaps",
        }
    }

    /// A short description for progress displays.
    pub fn describe(self) -> &'static str {
        match self {
            Stage::Check => "checking the inputs",
            Stage::Intersect => "intersecting",
            Stage::Arrange => "cutting along the seam",
            Stage::Classify => "classifying inside/outside",
            Stage::Merge => "merging the result",
            Stage::Weld => "welding vertices",
            Stage::Duplicates => "removing duplicate triangles",
            Stage::WeldBoundary => "welding boundary vertices",
            Stage::TJunctions => "splitting T-junctions",
            Stage::Degenerate => "removing degenerate triangles",
            Stage::Snap => "snapping short edges and needles",
            Stage::Orient => "orienting",
            Stage::Folds => "removing folds",
            Stage::Close => "closing",
            Stage::CloseGaps => "capping small holes",
        }
    }
}

by_name!(Stage, "stage");

/// A request to stop a running call, shared between the call and whoever may cancel it
/// (another thread, a signal handler, a progress callback): the call checks it as each
/// stage begins (and skips the intersection when it is set before that starts) and then
/// returns [`Error::Cancelled`](crate::Error::Cancelled), leaving nothing half done
/// behind. Clones share the flag.
#[derive(Clone, Debug, Default)]
pub struct Cancel(Arc<std::sync::atomic::AtomicBool>);

impl Cancel {
    /// A flag not set.
    pub fn new() -> Self {
        Cancel::default()
    }

    /// Asks the calls that hold this flag to stop.
    pub fn cancel(&self) {
        self.0.store(true, std::sync::atomic::Ordering::Relaxed);
    }

    /// Whether [`Cancel::cancel`] was called.
    pub fn is_cancelled(&self) -> bool {
        self.0.load(std::sync::atomic::Ordering::Relaxed)
    }
}
