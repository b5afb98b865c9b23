//! Snapping at a tolerance: the short edges and needles that an exact arrangement keeps
//! faithfully (a cutter whose wall passes a millimetre from a solid's edge leaves triangles
//! a millimetre wide) removed by edge collapses and edge flips, where that costs nothing
//! the mesh had: after the boolean's assembly (`--snap D`), or on its own ([`snap`],
//! `meshbool repair --snap D`).
//!
//! A triangle is *bad* when one of its edges is shorter than the tolerance `D` or its
//! smallest altitude is below `D` (decided in floating point: `D` is the one tolerance).
//! Bad triangles are taken smallest altitude first. Each is fixed by collapsing one of its
//! short edges onto one end — the end that keeps the shape (the other end's move stays in
//! the planes of its triangles: along a crease or a flat face), else the end on more
//! creases, else an input vertex rather than a seam point; then the other way round — or
//! else by flipping its longest edge when that leaves both triangles there better shaped.
//! A collapse that the link condition refuses only through a neighbour both ends share (a
//! thin slab whose faces are cut along the same diagonal) is tried again after flipping the
//! edge to that neighbour, where that flip passes the gates but the distance one (it moves
//! no vertex; the volume gate bounds it). A change is made only where every gate passes,
//! each decided exactly where it is a question of topology:
//!
//! - *manifold*: the link condition (the end points' common neighbours are exactly the
//!   far corners of the edge's triangles), no boundary vertex moved off the boundary or
//!   pinched, and no edge at the collapsed vertex more often open, non-manifold or
//!   inconsistently oriented than before, no triangle repeated, the vertex's triangles one
//!   fan; a flip only of an edge with two consistently oriented triangles, to a diagonal
//!   that is not an edge yet;
//! - *inversion*: every changed triangle keeps a normal at less than a right angle to the
//!   normal of each triangle it replaces (the exact sign of their dot product), so none
//!   turns over or becomes degenerate;
//! - *self-intersection*: no changed triangle meets another triangle anywhere but in the
//!   vertices and edge they share (the exact triangle–triangle test, against every
//!   triangle near it) — or, where the mesh already crossed itself there (rounded seam
//!   points of an exact result can), no more often than the triangles it replaces did;
//! - *distance*: no vertex ends up farther than `D` from where it was in the input (a
//!   vertex collapsed into another twice is measured from its input position), and a flip
//!   only of a triangle lower than `D` over the flipped edge (but the flip that unlocks a
//!   collapse);
//! - *volume*: the volume changes swept by all changes together stay within
//!   `D × area` of the input (each change's swept volume, added up as absolute values,
//!   must fit in that budget), so `|volume_change| ≤ D × area`.
//!
//! Topology decisions never look at `D`; positions never change (a collapse moves a vertex
//! onto an existing one, a flip moves none), so every decision is on input coordinates.
//!
//! Cost: one parallel pass finds the bad triangles; vertex neighbourhoods and a spatial
//! index are built only around them (further passes test cell bits: over the triangles
//! near the seam, kept by the first pass, while the work stays there; over all otherwise),
//! never for the whole mesh, and changes are local.

//! The files, one job each: [`shape`] (a triangle's float measures), [`scan`] (the first
//! pass), [`grid`] (the bit grid and its keys), [`engine`] (the editor's rounds, queue and
//! index), [`gates`] (the tests a change must pass) and [`refusal`] (why one was not made),
//! [`link`] (link and fan topology).

mod engine;
mod gates;
mod grid;
mod link;
mod refusal;
mod scan;
mod shape;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::bvh::Box3;
use crate::mesh_edit::{compact_from_end, remove_sorted, Filled};
use crate::par::Grain;
use crate::{Error, Mesh, Result};
use engine::Editor;
use grid::Grid;
use scan::Scan;

/// What [`snap`] did. Serialised under the key `snap` of the boolean, resolve and repair
/// reports.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SnapReport {
    /// The tolerance `D`.
    pub tolerance: f64,
    /// Bad triangles at the start: an edge shorter than `D` or an altitude below `D`.
    pub found: usize,
    /// Edges collapsed (each removes one vertex and the one or two triangles on the edge).
    pub collapsed: usize,
    /// Edges flipped.
    pub flipped: usize,
    /// Triangles removed (by collapses; a flip replaces two by two).
    pub triangles_removed: usize,
    /// Vertices removed (one per collapse).
    pub vertices_removed: usize,
    /// Bad triangles left.
    pub left: usize,
    /// Of the bad triangles left, those no fix was tried on, or none finished: the work
    /// stopped first (after 8 rounds of gathering neighbourhoods, or at the cap on
    /// changes).
    pub not_reached: usize,
    /// Of the bad triangles left, those whose fix was refused (the reason of its last
    /// refused attempt; within an attempt, of the first alternative refused) because
    /// it would break manifoldness: the link condition, a boundary vertex moved off its
    /// boundary or pinched, more open, non-manifold or inconsistent edges, a repeated
    /// triangle, a vertex of several fans.
    pub refused_manifold: usize,
    /// ... because a triangle would turn over or become degenerate.
    pub refused_inversion: usize,
    /// ... because a changed triangle would cross or touch another one.
    pub refused_self_intersection: usize,
    /// ... because a vertex would end up more than `D` from its input position (or, for a
    /// flip, the triangle is not lower than `D` over the flipped edge).
    pub refused_distance: usize,
    /// ... because the volume budget (`D × area`) was spent.
    pub refused_volume: usize,
    /// ... because the only fix was a flip across a seam (between triangles of different
    /// labels: of A and of B in a boolean).
    pub refused_seam: usize,
    /// ... because no collapse was possible and a flip would make no triangle better.
    pub refused_no_gain: usize,
    /// The largest distance of a vertex from its input position.
    pub max_move: f64,
    /// Signed volume after minus before (meaningful for closed meshes);
    /// `|volume_change| ≤ tolerance × area`.
    pub volume_change: f64,
    /// Surface area after minus before.
    pub area_change: f64,
}

impl SnapReport {
    /// The report of a mesh snapped at unit size, for the mesh scaled by `2^e`: lengths
    /// times `2^e`, areas `2^2e`, volumes `2^3e`.
    pub(crate) fn scale_back(&mut self, e: i32) {
        use crate::scale::{scaled, scaled_measure};
        self.tolerance = scaled(self.tolerance, e);
        self.max_move = scaled(self.max_move, e);
        self.area_change = scaled_measure(self.area_change, e, 2);
        self.volume_change = scaled_measure(self.volume_change, e, 3);
    }
}

/// Options of [`snap_with`].
#[derive(Clone, Copy, Debug, Default)]
pub struct SnapOptions<'a> {
    /// The tolerance `D`: a finite length ≥ 0; 0 changes nothing.
    pub tolerance: f64,
    /// Vertices that an operation made rather than found (a boolean's seam points),
    /// sorted: where an edge could collapse either way and the ends are otherwise alike,
    /// these are the ones moved, so that input vertices stay where they were.
    pub seam: &'a [u32],
    /// A label for every triangle (a boolean: which input it comes from). Edges between
    /// labels count as creases, and no edge between two labels is flipped, so that the
    /// seam only ever moves along itself or by a collapse. `None`: all alike.
    pub labels: Option<&'a [u32]>,
    /// Fix only the bad triangles with a corner in `seam` (and those the fixes make bad):
    /// an operation's result cleaned where the operation cut, its inputs' own short
    /// edges and needles left as they were. `false`: every bad triangle.
    pub seam_only: bool,
    /// A sheet for every triangle: surfaces that share vertices but are each manifold on
    /// their own (a split's pieces of A and of B, glued along their seam). Manifoldness
    /// is judged in each sheet, and a collapse merges no edge of one sheet into another
    /// sheet's edge; the seam moves as one curve in all of them. `None`: one sheet.
    pub sheets: Option<&'a [u32]>,
}

/// The result of [`snap_with`].
#[derive(Clone, Debug, PartialEq)]
pub struct Snapped {
    /// The snapped mesh: the input's vertices that are still used, in their order
    /// (collapsed-away vertices dropped), and its triangles in their order, each changed
    /// one in the place of the triangle it replaces. The input itself, unchanged, when
    /// nothing was changed.
    pub mesh: Mesh,
    /// For every triangle of `mesh`, the triangle of the input it replaces (itself where
    /// unchanged).
    pub parent: Vec<u32>,
    /// What was done.
    pub report: SnapReport,
}

/// Checks a snap tolerance: a finite number ≥ 0.
pub(crate) fn check_tolerance(tolerance: f64) -> Result<()> {
    if tolerance.is_finite() && tolerance >= 0.0 {
        Ok(())
    } else {
        Err(Error::InvalidParameter(format!(
            "the snap tolerance must be a finite distance >= 0, got {tolerance}"
        )))
    }
}

/// Removes the edges shorter than `tolerance` and the triangles with an altitude below
/// it by edge collapses and flips, only where each change keeps the mesh manifold, turns
/// no triangle over, makes no self-intersection, moves no vertex more than `tolerance`
/// from its input position, and keeps the total volume change within
/// `tolerance × area` (see the module doc). `mesh` must be valid. Returns the mesh (the
/// input unchanged when nothing was done: exactly so for `tolerance` 0) and the report.
///
/// Errors: a tolerance that is negative, NaN or infinite; a mesh with a non-finite
/// coordinate.
///
/// ```
/// use meshbool::repair::snap;
/// use meshbool::Mesh;
///
/// // A unit square of four triangles around a vertex 1e-3 (diagonally) from its corner
/// // (1, 1): two needles there.
/// let square = Mesh::new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0], [0.999, 0.999, 0.0]],
///     vec![[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]],
/// )?;
/// let (snapped, report) = snap(&square, 0.01)?;
/// // The vertex went into the corner (a boundary vertex stays where it is).
/// assert_eq!((report.found, report.collapsed, report.left), (2, 1, 0));
/// assert_eq!((snapped.triangle_count(), snapped.vertex_count()), (2, 4));
/// assert!(report.max_move < 0.0015 && report.volume_change == 0.0);
/// // Without a tolerance nothing changes.
/// assert_eq!(snap(&square, 0.0)?.0, square);
/// # Ok::<(), meshbool::Error>(())
/// ```
pub fn snap(mesh: &Mesh, tolerance: f64) -> Result<(Mesh, SnapReport)> {
    check_tolerance(tolerance)?;
    mesh.validate()?;
    let mut out = mesh.clone();
    let (report, _) = snap_unchecked(
        &mut out,
        &SnapOptions {
            tolerance,
            ..SnapOptions::default()
        },
    );
    Ok((out, report))
}

/// [`snap`] with the options of a boolean's result: its seam points (moved rather than
/// input vertices) and a label per triangle (no flips across the seam), and the parent of
/// every result triangle (to carry provenance over).
///
/// Errors: a tolerance that is negative, NaN or infinite; a mesh with a non-finite
/// coordinate; labels not one per triangle.
pub fn snap_with(mesh: &Mesh, opts: &SnapOptions) -> Result<Snapped> {
    let mut out = mesh.clone();
    let (report, removed) = snap_in_place(&mut out, opts)?;
    let mut parent: Vec<u32> = (0..mesh.triangles.len() as u32).collect();
    remove_sorted(&mut parent, &removed);
    Ok(Snapped {
        mesh: out,
        parent,
        report,
    })
}

/// [`snap_with`] editing `mesh` in place, without copying it (for large meshes): returns
/// the report and the triangles removed, as their sorted ids in `mesh` as it was. Every
/// other triangle keeps its place in the order, changed or not, so whatever is kept per
/// triangle (provenance) follows by removing the same positions; vertices collapsed
/// away are removed the same way (the others keep their order).
///
/// Errors: as [`snap_with`] (then `mesh` is unchanged).
pub fn snap_in_place(mesh: &mut Mesh, opts: &SnapOptions) -> Result<(SnapReport, Vec<u32>)> {
    check_tolerance(opts.tolerance)?;
    mesh.validate()?;
    for (what, per) in [("labels", opts.labels), ("sheets", opts.sheets)] {
        if let Some(l) = per.filter(|l| l.len() != mesh.triangles.len()) {
            return Err(Error::InvalidParameter(format!(
                "snap: {} {what} for {} triangles",
                l.len(),
                mesh.triangles.len()
            )));
        }
    }
    let (report, removed) = snap_unchecked(mesh, opts);
    Ok((report, removed.triangles))
}

/// What [`snap_unchecked`] took out of a mesh: sorted ids in the mesh as it was.
#[derive(Default)]
pub(crate) struct Removed {
    /// Triangles removed (every other triangle keeps its place in the order).
    pub triangles: Vec<u32>,
    /// Vertices removed (every other vertex keeps its place in the order).
    pub vertices: Vec<u32>,
}

/// [`snap_in_place`] of options known to be valid.
pub(crate) fn snap_unchecked(mesh: &mut Mesh, opts: &SnapOptions) -> (SnapReport, Removed) {
    let (report, edit) = snap_edit(mesh, opts, Labels::Given(opts.labels));
    let Some(edit) = edit else {
        return (report, Removed::default());
    };
    let removed = edit.apply(mesh);
    let report = SnapReport {
        triangles_removed: removed.triangles.len(),
        vertices_removed: removed.vertices.len(),
        ..report
    };
    (report, removed)
}

/// [`snap_unchecked`] without keeping the order (for a boolean's result, whose order the
/// clean-up does not keep either): the slots of removed triangles and vertices below the
/// new counts take the last ones, so nothing else moves; `per_triangle` (provenance)
/// follows. `label`: each triangle's label, read from what is kept for it, in place of
/// `opts.labels` (which is not read: no array of labels for a whole large result, of
/// which only the triangles near the seam are ever asked). Returns the report and what
/// became of the vertices.
pub(crate) fn snap_filling<T: Copy + Sync>(
    mesh: &mut Mesh,
    opts: &SnapOptions,
    per_triangle: &mut Vec<T>,
    label: fn(&T) -> u32,
) -> (SnapReport, Filled) {
    let (report, edit) = {
        let kept: &[T] = per_triangle;
        snap_edit(mesh, opts, Labels::Of(&|t| label(&kept[t as usize])))
    };
    let Some(edit) = edit else {
        return (report, Filled::default());
    };
    let triangles_removed = edit.removed.len();
    let filled = edit.fill(mesh, per_triangle);
    let report = SnapReport {
        triangles_removed,
        vertices_removed: filled.dead.len(),
        ..report
    };
    (report, filled)
}

/// The work of a snap: the report (without the removal counts) and the changes, if any.
fn snap_edit(mesh: &Mesh, opts: &SnapOptions, labels: Labels) -> (SnapReport, Option<Edit>) {
    let d = opts.tolerance;
    let mut report = SnapReport {
        tolerance: d,
        ..SnapReport::default()
    };
    if d == 0.0 || mesh.triangles.is_empty() {
        return (report, None);
    }
    let grid = Grid::new(mesh, d);
    let (seam, [halo, next_to_halo], halo_box) = seam_and_halo(mesh, opts, &grid);
    let scan = Scan::of(
        mesh,
        d,
        &grid,
        seam.as_deref(),
        [&halo, &next_to_halo],
        halo_box,
    );
    report.found = scan.bad.len();
    if scan.bad.is_empty() {
        return (report, None);
    }
    let seeds = scan.bad.iter().map(|&(_, t)| t).collect();
    let mut w = Editor::new(mesh, opts, labels, scan, grid, halo);
    w.report = report;
    w.run(seeds);
    let report = w.finish_report();
    if report.collapsed + report.flipped == 0 {
        return (report, None);
    }
    (report, Some(w.edit()))
}

/// Where only the seam's bad triangles are taken (`seam_only`), the work stays near the
/// seam: which vertices are seam points, and the halo (the cells a few cells around the
/// seam's points, whose triangles the scan keeps as the first gathering's candidates: no
/// pass over all triangles unless the work leaves it) with the cells next to it (a
/// triangle spanning at most two cells along each axis and touching the halo has all its
/// corners there), and a box that every triangle touching the halo meets (`None` where
/// the halo is empty). Otherwise no seam and no halo.
fn seam_and_halo(mesh: &Mesh, opts: &SnapOptions, grid: &Grid) -> SeamAndHalo {
    let (mut halo, mut next_to_halo) = (grid.empty(), grid.empty());
    if !opts.seam_only {
        return (None, [halo, next_to_halo], None);
    }
    let mut at = vec![false; mesh.positions.len()];
    let mut cells = Vec::with_capacity(opts.seam.len());
    for &v in opts.seam {
        if let Some(a) = at.get_mut(v as usize) {
            *a = true;
            cells.push(grid.packed(&mesh.positions[v as usize]));
        }
    }
    // Every seam point's box grown by the margin, as the cells around its cell (one more
    // for rounding: a little more than the boxes, once per cell).
    cells.sort_unstable();
    cells.dedup();
    let margin = (Editor::HALO + 1.0) * grid.size() + 4.0 * opts.tolerance;
    let r = (margin * grid.inv).ceil().min(Grid::AXIS as f64) as usize + 1;
    let mut span: Option<[[usize; 3]; 2]> = None;
    for c in cells {
        let c = grid.coordinates(c);
        let around = |r: usize| {
            [
                c.map(|x| x.saturating_sub(r)),
                std::array::from_fn(|k| (c[k] + r).min(grid.n[k] - 1)),
            ]
        };
        let range = around(r);
        halo.mark_range(&range);
        next_to_halo.mark_range(&around(r + 1));
        span = Some(span.map_or(range, |s| {
            [
                std::array::from_fn(|k| s[0][k].min(range[0][k])),
                std::array::from_fn(|k| s[1][k].max(range[1][k])),
            ]
        }));
    }
    let halo_box = span.map(|s| grid.enclosing(&s));
    (Some(at), [halo, next_to_halo], halo_box)
}

/// What [`seam_and_halo`] finds: the seam's vertices, the halo and the cells next to it,
/// a box around the halo.
type SeamAndHalo = (Option<Vec<bool>>, [Grid; 2], Option<Box3>);

/// [`snap_unchecked`] carrying what is kept per triangle (`per_triangle`, one per
/// triangle: provenance, parents) over to the snapped mesh. Returns the report and the
/// vertices removed (sorted ids in `mesh` as it was).
pub(crate) fn snap_carrying<T: Copy>(
    mesh: &mut Mesh,
    opts: &SnapOptions,
    per_triangle: &mut Vec<T>,
) -> (SnapReport, Vec<u32>) {
    let (report, removed) = snap_unchecked(mesh, opts);
    remove_sorted(per_triangle, &removed.triangles);
    (report, removed.vertices)
}

/// The changes the work made, to apply to the mesh it worked on.
struct Edit {
    /// Vertices collapsed away (sorted).
    dead: Vec<u32>,
    /// Triangles left without a successor (sorted).
    removed: Vec<u32>,
    /// Triangles replaced: (id, new corners).
    replaced: Vec<(u32, [u32; 3])>,
}

impl Edit {
    /// Applies the changes to `mesh`: triangles replaced in their places, removed ones
    /// and dead vertices taken out (the rest keep their order), corners renumbered.
    fn apply(self, mesh: &mut Mesh) -> Removed {
        for &(t, tri) in &self.replaced {
            mesh.triangles[t as usize] = tri;
        }
        remove_sorted(&mut mesh.triangles, &self.removed);
        if !self.dead.is_empty() {
            // Vertex v becomes v minus the dead vertices before it.
            let nv = mesh.positions.len();
            let mut new_id = vec![0u32; nv];
            let mut j = 0;
            for (v, id) in new_id.iter_mut().enumerate() {
                while self.dead.get(j).is_some_and(|&x| (x as usize) < v) {
                    j += 1;
                }
                *id = (v - j) as u32;
            }
            mesh.triangles
                .par_iter_mut()
                .grained()
                .with_min_len(1 << 12)
                .for_each(|t| *t = t.map(|v| new_id[v as usize]));
            remove_sorted(&mut mesh.positions, &self.dead);
        }
        Removed {
            triangles: self.removed,
            vertices: self.dead,
        }
    }

    /// Applies the changes to `mesh` as [`Edit::apply`] does, but each removed triangle's
    /// and dead vertex's slot below the new count takes the last live one (and
    /// `per_triangle` follows): a few moves and one pass renaming the moved vertices,
    /// instead of shifting and renumbering everything.
    fn fill<T: Copy>(self, mesh: &mut Mesh, per_triangle: &mut Vec<T>) -> Filled {
        for &(t, tri) in &self.replaced {
            mesh.triangles[t as usize] = tri;
        }
        let filled = compact_from_end(mesh, &self.removed, self.dead, |from, to| {
            per_triangle[to] = per_triangle[from];
        });
        per_triangle.truncate(mesh.triangles.len());
        filled
    }
}

/// Each triangle's label ([`SnapOptions::labels`]), by its id in the input.
#[derive(Clone, Copy)]
enum Labels<'a> {
    /// As given in an array (or none: all alike).
    Given(Option<&'a [u32]>),
    /// Read from what is kept per triangle ([`snap_filling`]).
    Of(&'a (dyn Fn(u32) -> u32 + Sync)),
}

#[cfg(test)]
mod tests;
