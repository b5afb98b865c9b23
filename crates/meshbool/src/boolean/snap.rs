//! Snapping a boolean's result at a tolerance ([`crate::repair::snap_in_place`] with what
//! the pipeline knows: which vertices are seam points, which input each triangle comes
//! from), provenance and seam vertices carried over.

use crate::par::Grain;
use rayon::prelude::*;

use super::{merge, BooleanResult, Group, Keep, Provenance, Source, Split};
use crate::mesh_edit::remove_sorted;
use crate::repair::{check_tolerance, snap_filling, snap_unchecked, SnapOptions, SnapReport};
use crate::{Mesh, Result};

/// Snaps `r` at `tolerance` in place where the boolean cut (the bad triangles with a
/// corner at a seam point; the inputs' own short edges and needles elsewhere stay): seam
/// points move before input vertices, no edge between A's part and B's is flipped,
/// provenance and `seam_vertices` follow. The order is kept but for the last triangles
/// and vertices, moved into the slots of those removed (as the clean-up does).
///
/// Errors: a tolerance that is negative, NaN or infinite (then `r` is unchanged). `r`'s
/// mesh has finite coordinates, as every boolean's result of valid meshes does.
pub fn snap_result(r: &mut BooleanResult, tolerance: f64) -> Result<SnapReport> {
    check_tolerance(tolerance)?;
    let opts = SnapOptions {
        tolerance,
        seam: &r.seam_vertices,
        labels: None,
        seam_only: true,
        sheets: None,
    };
    // Each triangle labelled by its input, read from its provenance where asked.
    let (report, filled) = snap_filling(&mut r.mesh, &opts, &mut r.provenance, source_label);
    if report.vertices_removed > 0 {
        r.seam_vertices = r
            .seam_vertices
            .iter()
            .filter_map(|&v| filled.renamed(v))
            .collect();
        r.seam_vertices.sort_unstable();
    }
    Ok(report)
}

/// A group of a split: which, its triangles as a mesh, their provenance.
pub type GroupMesh = (Group, Mesh, Vec<Provenance>);

/// The groups of the split `s` ([`Split::group`]) snapped at `tolerance` together, so that
/// they stay conforming: every group's triangles in one mesh (the seam's edges have four
/// triangles there), A's and B's pieces as two sheets and each group a label (no flip
/// across a group's border), the bad triangles at a seam point fixed as in
/// [`snap_result`]. A pick of any set of the snapped groups is closed where the same
/// pick of the exact groups is (vertices only merge, so every piece's border moves with
/// the seam), and no picked piece crosses another. Returns the non-empty groups in the
/// order of [`Group::ALL`], each with its mesh (vertices in the order of the exact
/// groups', collapsed ones dropped) and provenance, and the report; its volume change is
/// that of A's and B's pieces together.
///
/// Errors: a tolerance that is negative, NaN or infinite.
pub fn snap_split(s: &Split, tolerance: f64) -> Result<(Vec<GroupMesh>, SnapReport)> {
    check_tolerance(tolerance)?;
    let mut all = merge(s, |_| Keep::AsIs, |_| Keep::AsIs);
    let mut labels = s.group_labels(all.mesh.triangles.len());
    let sheets = by_source(&all.provenance);
    let opts = SnapOptions {
        tolerance,
        seam: &all.seam_vertices,
        labels: Some(&labels),
        seam_only: true,
        sheets: Some(&sheets),
    };
    let (report, removed) = snap_unchecked(&mut all.mesh, &opts);
    remove_sorted(&mut labels, &removed.triangles);
    remove_sorted(&mut all.provenance, &removed.triangles);
    Ok((groups_of(&all.mesh, &all.provenance, &labels), report))
}

/// The non-empty groups of a mesh of all of them (`labels`: each triangle's index in
/// [`Group::ALL`]), in that order, each with its mesh (vertices in `m`'s order) and
/// provenance.
pub(super) fn groups_of(m: &Mesh, provenance: &[Provenance], labels: &[u32]) -> Vec<GroupMesh> {
    Group::ALL
        .iter()
        .enumerate()
        .filter_map(|(i, &g)| {
            let ids: Vec<u32> = (0..labels.len() as u32)
                .filter(|&t| labels[t as usize] == i as u32)
                .collect();
            if ids.is_empty() {
                return None;
            }
            let provenance = ids.iter().map(|&t| provenance[t as usize]).collect();
            Some((g, in_order(m, &ids), provenance))
        })
        .collect()
}

/// Each triangle's input as a label: 0 for A, 1 for B.
fn by_source(provenance: &[Provenance]) -> Vec<u32> {
    provenance.par_iter().grained().map(source_label).collect()
}

/// A triangle's label by the input it comes from: 0 for A, 1 for B.
fn source_label(p: &Provenance) -> u32 {
    u32::from(p.source == Source::B)
}

/// The triangles `ids` of `m` as a mesh of the vertices they use, in `m`'s order.
fn in_order(m: &Mesh, ids: &[u32]) -> Mesh {
    let mut id = vec![u32::MAX; m.positions.len()];
    for &t in ids {
        for v in m.triangles[t as usize] {
            id[v as usize] = 0;
        }
    }
    let mut positions = Vec::new();
    for (v, slot) in id.iter_mut().enumerate() {
        if *slot == 0 {
            *slot = positions.len() as u32;
            positions.push(m.positions[v]);
        }
    }
    let triangles = ids
        .iter()
        .map(|&t| m.triangles[t as usize].map(|v| id[v as usize]))
        .collect();
    Mesh {
        positions,
        triangles,
    }
}
