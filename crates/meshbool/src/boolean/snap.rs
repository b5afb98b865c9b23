//! Snapping a boolean's result at a tolerance ([`crate::repair::snap_in_place`] with what
//! the pipeline knows: which vertices are seam points, which input each triangle comes
//! from), provenance and seam vertices carried over.

use rayon::prelude::*;

use super::{BooleanResult, Source};
use crate::repair::{check_tolerance, snap_carrying, SnapOptions, SnapReport};
use crate::Result;

/// Snaps `r` at `tolerance` in place where the boolean cut (the bad triangles with a
/// corner at a seam point; the inputs' own short edges and needles elsewhere stay): seam
/// points move before input vertices, no edge between A's part and B's is flipped,
/// provenance and `seam_vertices` follow.
///
/// Errors: a tolerance that is negative, NaN or infinite (then `r` is unchanged). `r`'s
/// mesh has finite coordinates, as every boolean's result of valid meshes does.
pub fn snap_result(r: &mut BooleanResult, tolerance: f64) -> Result<SnapReport> {
    check_tolerance(tolerance)?;
    let labels: Vec<u32> = r
        .provenance
        .par_iter()
        .map(|p| u32::from(p.source == Source::B))
        .collect();
    let opts = SnapOptions {
        tolerance,
        seam: &r.seam_vertices,
        labels: Some(&labels),
        seam_only: true,
    };
    let (report, dead) = snap_carrying(&mut r.mesh, &opts, &mut r.provenance);
    if !dead.is_empty() {
        // A seam vertex keeps its place among the vertices left: its id less the dead
        // vertices before it.
        r.seam_vertices = r
            .seam_vertices
            .iter()
            .filter(|v| dead.binary_search(v).is_err())
            .map(|&v| v - dead.partition_point(|&x| x < v) as u32)
            .collect();
    }
    Ok(report)
}
