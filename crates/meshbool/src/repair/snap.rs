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

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use crate::par::Grain;
use rayon::prelude::*;
use rustc_hash::{FxHashMap, FxHashSet};
use serde::{Deserialize, Serialize};

use crate::bvh::{overlaps as overlap, Box3};
use crate::intersect::corners_meet_beyond_shared;
use crate::kernel::{normals_dot_sign, orient3d_explicit, FloatPlane, Sign};
use crate::vec3::{cross, dot, norm, sub};
use crate::{Error, Mesh, Result};

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

/// What [`snap_filling`] did to the vertices: the dead ones, and the last ones moved
/// into their slots.
#[derive(Default)]
pub(crate) struct Filled {
    /// Vertices collapsed away (sorted ids in the mesh as it was).
    dead: Vec<u32>,
    /// The vertex count after.
    count: usize,
    /// (from, to) of the vertices moved into dead slots, sorted.
    moves: Vec<(u32, u32)>,
}

impl Filled {
    /// The new id of vertex `v` of the mesh as it was; `None` when it was collapsed away.
    pub(crate) fn renamed(&self, v: u32) -> Option<u32> {
        if self.dead.binary_search(&v).is_ok() {
            None
        } else if (v as usize) < self.count || self.moves.is_empty() {
            Some(v)
        } else {
            Some(moved(&self.moves, v))
        }
    }
}

/// Where vertex `v` (one of the moved ones) went: `moves` sorted by source.
#[inline]
fn moved(moves: &[(u32, u32)], v: u32) -> u32 {
    moves[moves.partition_point(|&(f, _)| f < v)].1
}

/// Removes the triangles `dead_triangles` and the unreferenced vertices `dead_vertices`
/// (both sorted, distinct) from `mesh`, each slot below the new counts taken by the last
/// live one, so that nothing else moves: `carry(from, to)` is told of every triangle moved
/// (what is kept per triangle follows it; truncate it to the new count after), and the
/// triangles' corners follow the vertices moved (one pass, only where vertices moved).
/// Returns what became of the vertices.
pub(crate) fn compact_from_end(
    mesh: &mut Mesh,
    dead_triangles: &[u32],
    dead_vertices: Vec<u32>,
    mut carry: impl FnMut(usize, usize),
) -> Filled {
    debug_assert!(dead_triangles.windows(2).all(|w| w[0] < w[1]));
    debug_assert!(dead_vertices.windows(2).all(|w| w[0] < w[1]));
    let (n, moves) = filled_from_end(dead_triangles, mesh.triangles.len());
    for &(from, to) in &moves {
        mesh.triangles[to as usize] = mesh.triangles[from as usize];
        carry(from as usize, to as usize);
    }
    mesh.triangles.truncate(n);
    let (count, moves) = filled_from_end(&dead_vertices, mesh.positions.len());
    for &(from, to) in &moves {
        mesh.positions[to as usize] = mesh.positions[from as usize];
    }
    mesh.positions.truncate(count);
    if !moves.is_empty() {
        let last = count as u32;
        mesh.triangles
            .par_iter_mut()
            .grained()
            .with_min_len(1 << 12)
            .for_each(|t| {
                if t.iter().any(|&v| v >= last) {
                    *t = t.map(|v| if v < last { v } else { moved(&moves, v) });
                }
            });
    }
    Filled {
        dead: dead_vertices,
        count,
        moves,
    }
}

/// Compaction that moves few: of `len` slots, `dead` (sorted, distinct) go, and each dead
/// slot below the new count takes a live one from the end. Returns the new count and the
/// moves (from, to), sorted by source.
fn filled_from_end(dead: &[u32], len: usize) -> (usize, Vec<(u32, u32)>) {
    let n = len - dead.len();
    let split = dead.partition_point(|&k| (k as usize) < n);
    let (holes, tail) = dead.split_at(split);
    let mut tail = tail.iter().peekable();
    let live_tail = (n as u32..len as u32).filter(|&k| {
        if tail.peek() == Some(&&k) {
            tail.next();
            false
        } else {
            true
        }
    });
    (n, live_tail.zip(holes.iter().copied()).collect())
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
    let mut w = Work::new(mesh, opts, labels, scan, grid, halo);
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
    let margin = (Work::HALO + 1.0) * grid.size() + 4.0 * opts.tolerance;
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

/// Removes the elements at the sorted, distinct positions `removed` from `v`, keeping the
/// order of the others (a few block moves).
pub(crate) fn remove_sorted<T: Copy>(v: &mut Vec<T>, removed: &[u32]) {
    let mut to = match removed.first() {
        Some(&r) => r as usize,
        None => return,
    };
    for (j, &r) in removed.iter().enumerate() {
        let end = removed.get(j + 1).map_or(v.len(), |&n| n as usize);
        let from = r as usize + 1;
        v.copy_within(from..end, to);
        to += end - from;
    }
    v.truncate(to);
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

/// The smallest edge length and the smallest altitude (twice the area over the longest
/// edge) of a triangle, and twice its area.
fn shape(p: &[[f64; 3]; 3]) -> (f64, f64, f64) {
    let l = [0, 1, 2].map(|k| norm(&sub(&p[(k + 1) % 3], &p[k])));
    let twice = norm(&cross(&sub(&p[1], &p[0]), &sub(&p[2], &p[0])));
    let longest = l[0].max(l[1]).max(l[2]);
    let h = if longest > 0.0 { twice / longest } else { 0.0 };
    (l[0].min(l[1]).min(l[2]), h, twice)
}

/// Whether a triangle is bad at tolerance `d`: its key (smallest altitude, or shortest
/// edge where smaller: worst first), `None` when it is not bad.
fn badness(p: &[[f64; 3]; 3], d: f64) -> Option<f64> {
    let (e, h, _) = shape(p);
    (e < d || h < d).then_some(h.min(e))
}

/// The smallest altitude of a triangle.
fn altitude(p: &[[f64; 3]; 3]) -> f64 {
    shape(p).1
}

/// Six times the signed volume of the tetrahedron of a triangle and `o`.
fn volume6(p: &[[f64; 3]; 3], o: &[f64; 3]) -> f64 {
    let [a, b, c] = p.map(|x| sub(&x, o));
    dot(&a, &cross(&b, &c))
}

/// The smaller of two numbers that are not NaN (`f64::min` also orders NaN, in more
/// instructions: this runs for every triangle).
#[inline]
fn min(a: f64, b: f64) -> f64 {
    if a < b {
        a
    } else {
        b
    }
}

/// The larger of two numbers that are not NaN.
#[inline]
fn max(a: f64, b: f64) -> f64 {
    if a > b {
        a
    } else {
        b
    }
}

#[inline]
fn tri_box(p: &[[f64; 3]; 3]) -> Box3 {
    let lo = |k: usize| min(min(p[0][k], p[1][k]), p[2][k]);
    let hi = |k: usize| max(max(p[0][k], p[1][k]), p[2][k]);
    [[lo(0), lo(1), lo(2)], [hi(0), hi(1), hi(2)]]
}

fn grown(b: &Box3, by: f64) -> Box3 {
    [b[0].map(|x| x - by), b[1].map(|x| x + by)]
}

/// The first pass, over every triangle: the bad ones (key, id) in triangle order (only
/// those with a corner in `seam` when given), the area (with `seam`: of the triangles
/// touching the halo, a lower bound), and the triangles touching the
/// halo's marked cells with their [`Grid::key`]s (the candidates of the first gathering).
/// Input triangles with their [`Grid::key`]s: (id, key).
type Keyed = Vec<(u32, u32)>;

/// What [`Scan::of`] finds in a piece of the triangles: bad ones, area, candidates.
type ScanPiece = (Vec<(f64, u32)>, f64, Keyed);

struct Scan {
    bad: Vec<(f64, u32)>,
    area: f64,
    candidates: Vec<(u32, u32)>,
}

impl Scan {
    /// `halos`: the halo, and the cells in it or next to it; `halo_box`: a box around the
    /// halo's cells (`None`: no halo).
    fn of(
        mesh: &Mesh,
        d: f64,
        grid: &Grid,
        seam: Option<&[bool]>,
        halos: [&Grid; 2],
        halo_box: Option<Box3>,
    ) -> Scan {
        const PIECE: usize = 1 << 13;
        let [halo, next_to_halo] = halos;
        let d2 = d * d;
        // A corner's cell, with bit [`Grid::NEAR_BIT`] set where the cell is in or next to
        // the halo: a triangle spanning at most two cells along each axis with no corner
        // there does not touch the halo.
        let cell = |p: &[f64; 3]| {
            let c = [0, 1, 2].map(|k| grid.cell(p[k], k));
            grid.pack(c) | u32::from(next_to_halo.get(grid.index(c))) << Grid::NEAR_BIT
        };
        // Each vertex's sides of the halo's box it is beyond (a bit per side): a triangle
        // whose corners are all beyond one side misses the box (an exact box test, on
        // a byte per corner). Nothing is near without a halo.
        let beyond: Vec<u8> = match halo_box {
            Some(hb) => mesh
                .positions
                .par_iter()
                .grained()
                .with_min_len(PIECE)
                .map(|p| {
                    (0..3).fold(0u8, |code, k| {
                        code | u8::from(p[k] < hb[0][k]) << (2 * k)
                            | u8::from(p[k] > hb[1][k]) << (2 * k + 1)
                    })
                })
                .collect(),
            None => Vec::new(),
        };
        let pieces: Vec<ScanPiece> = mesh
            .triangles
            .par_chunks(PIECE)
            .grained()
            .enumerate()
            .map(|(k, tris)| {
                let (mut bad, mut area, mut near) = (Vec::new(), 0.0, Vec::new());
                let pos = &mesh.positions;
                for (i, tri) in tris.iter().enumerate() {
                    let t = (k * PIECE + i) as u32;
                    // Outside the halo's box (most triangles, far from the seam) no cell is
                    // needed, nor (with a seam) anything else. Else, with no corner near
                    // the halo, only a triangle spanning more than two cells along an axis
                    // may touch it.
                    let in_box = !beyond.is_empty()
                        && beyond[tri[0] as usize]
                            & beyond[tri[1] as usize]
                            & beyond[tri[2] as usize]
                            == 0;
                    if !in_box && seam.is_some() {
                        continue;
                    }
                    let p = [
                        pos[tri[0] as usize],
                        pos[tri[1] as usize],
                        pos[tri[2] as usize],
                    ];
                    let key = Some(()).filter(|_| in_box).and_then(|_| {
                        let c = p.map(|q| cell(&q));
                        if (c[0] | c[1] | c[2]) >> Grid::NEAR_BIT != 0 {
                            Some(grid.key(c)).filter(|&key| halo.touches_key(key, || p))
                        } else {
                            Some(Grid::WIDE).filter(|_| grid.wide(c) && halo.touches(&tri_box(&p)))
                        }
                    });
                    if let Some(key) = key {
                        near.push((t, key));
                    } else if seam.is_some() {
                        // Far from the seam: neither bad nor counted in the area (the
                        // area of the triangles near it bounds the whole from below).
                        continue;
                    }
                    let (u, v, w) = (sub(&p[1], &p[0]), sub(&p[2], &p[0]), sub(&p[2], &p[1]));
                    let c = cross(&u, &v);
                    let twice2 = dot(&c, &c);
                    area += twice2.sqrt();
                    if seam.is_some_and(|s| !tri.iter().any(|&v| s[v as usize])) {
                        continue;
                    }
                    let (eu, ev, ew) = (dot(&u, &u), dot(&v, &v), dot(&w, &w));
                    let (short, long) = (min(min(eu, ev), ew), max(max(eu, ev), ew));
                    // A filter, squared: edge² ≤ d², or (2 · area)² ≤ d² · longest² (≤ so
                    // that zero edges and areas pass where d² underflows); `badness`
                    // decides, as everywhere else.
                    if short <= d2 || twice2 <= d2 * long {
                        if let Some(key) = badness(&p, d) {
                            bad.push((key, t));
                        }
                    }
                }
                (bad, area / 2.0, near)
            })
            .collect();
        let mut scan = Scan {
            bad: Vec::new(),
            area: 0.0,
            candidates: Vec::new(),
        };
        for (bad, area, near) in pieces {
            scan.bad.extend(bad);
            scan.area += area;
            scan.candidates.extend(near);
        }
        scan
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

/// Why a change was refused: the first gate that refused it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Refusal {
    Manifold,
    Inversion,
    SelfIntersection,
    Distance,
    Volume,
    Seam,
    NoGain,
}

/// Why a change was not made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Stop {
    /// A gate refused it.
    Refused(Refusal),
    /// The neighbourhood it needs is not gathered yet: the next round.
    Later,
}

use Refusal::*;

type Gate<T> = std::result::Result<T, Stop>;

fn refuse<T>(r: Refusal) -> Gate<T> {
    Err(Stop::Refused(r))
}

/// A bad triangle waiting in the queue, smallest key first.
#[derive(Clone, Copy, Debug)]
struct Item {
    key: f64,
    t: u32,
}

impl PartialEq for Item {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}

impl Eq for Item {}

impl PartialOrd for Item {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for Item {
    fn cmp(&self, o: &Self) -> Ordering {
        // Reversed: the max-heap pops the smallest key (then the lowest id).
        o.key.total_cmp(&self.key).then(o.t.cmp(&self.t))
    }
}

/// A uniform grid of cells over the mesh's box, some of them marked: the region where
/// the spatial index of the work is complete. A box's range of cells is monotone in its
/// coordinates, so a triangle whose box meets a box whose cells are all marked has a
/// marked cell in its own range.
#[derive(Clone)]
struct Grid {
    lo: [f64; 3],
    /// `1 / cell size` (0 for a mesh in one point).
    inv: f64,
    n: [usize; 3],
    /// Where each axis's cell sits in a [`Grid::packed`] cell, and its bits there.
    shift: [u32; 3],
    mask: [u32; 3],
    bits: Vec<u64>,
}

impl Grid {
    /// At most this many cells.
    const CELLS: usize = 1 << 24;
    /// At most this many cells along an axis.
    const AXIS: usize = 1 << 21;
    /// [`Grid::key`] of a box spanning more than two cells along an axis.
    const WIDE: u32 = u32::MAX;
    /// A bit of a [`Grid::packed`] cell that the packing leaves free (31: the three axes
    /// take at most 27 bits, as there are at most 2^24 cells), which [`Grid::key`] and
    /// [`Grid::unpacked`] ignore: the scan's mark of a vertex near the halo.
    const NEAR_BIT: u32 = 31;
    /// What a row's look-up costs in [`Grid::keyed_near`], in entries looked at.
    const ROW_COST: usize = 8;

    /// A grid over the mesh's vertices, with cells about the size of its triangles (so
    /// that most span one or two along each axis) and at most [`Grid::CELLS`].
    fn new(mesh: &Mesh, d: f64) -> Grid {
        let (lo, hi) = mesh
            .positions
            .par_chunks(1 << 14)
            .grained()
            .map(|ps| {
                ps.iter().fold(
                    ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
                    |(lo, hi), p| {
                        (
                            std::array::from_fn(|k| lo[k].min(p[k])),
                            std::array::from_fn(|k| hi[k].max(p[k])),
                        )
                    },
                )
            })
            .reduce(
                || ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
                |a, b| {
                    (
                        std::array::from_fn(|k| a.0[k].min(b.0[k])),
                        std::array::from_fn(|k| a.1[k].max(b.1[k])),
                    )
                },
            );
        let ext: [f64; 3] = std::array::from_fn(|k| (hi[k] - lo[k]).max(0.0));
        // A typical triangle's longest edge, from a sample.
        let step = (mesh.triangles.len() / 256).max(1);
        let mut sample: Vec<f64> = mesh
            .triangles
            .iter()
            .step_by(step)
            .map(|t| {
                let p = t.map(|v| mesh.positions[v as usize]);
                let b = tri_box(&p);
                (0..3).map(|k| b[1][k] - b[0][k]).fold(0.0, f64::max)
            })
            .collect();
        sample.sort_by(f64::total_cmp);
        let typical = sample.get(sample.len() / 2).copied().unwrap_or(0.0);
        let count = |h: f64| -> [usize; 3] {
            ext.map(|e| {
                if h > 0.0 {
                    ((e / h) as usize).saturating_add(1)
                } else {
                    1
                }
            })
        };
        let fits = |n: [usize; 3]| {
            n.iter().all(|&c| c <= Self::AXIS)
                && n[0].saturating_mul(n[1]).saturating_mul(n[2]) <= Self::CELLS
        };
        let largest = ext[0].max(ext[1]).max(ext[2]);
        let mut h = typical.max(4.0 * d).max(largest / (1 << 23) as f64);
        while h > 0.0 && !fits(count(h)) {
            h *= 1.25;
        }
        let n = count(h);
        // Each axis packs in the bits its largest cell needs.
        let width = n.map(|c| usize::BITS - (c - 1).leading_zeros());
        debug_assert!(width.iter().sum::<u32>() <= Self::NEAR_BIT);
        Grid {
            lo,
            inv: if h > 0.0 { 1.0 / h } else { 0.0 },
            n,
            shift: [0, width[0], width[0] + width[1]],
            mask: width.map(|w| (1u32 << w) - 1),
            bits: vec![0; (n[0] * n[1] * n[2]).div_ceil(64)],
        }
    }

    /// The same grid with no cell marked.
    fn empty(&self) -> Grid {
        Grid {
            bits: vec![0; self.bits.len()],
            ..*self
        }
    }

    /// Whether a triangle with [`Grid::key`] `key` touches a marked cell; `p` gives its
    /// corners, asked only for a triangle spanning many cells.
    #[inline]
    fn touches_key(&self, key: u32, p: impl FnOnce() -> [[f64; 3]; 3]) -> bool {
        if key == Self::WIDE {
            self.touches(&tri_box(&p()))
        } else {
            self.key_touches(key)
        }
    }

    /// The cells' edge length.
    fn size(&self) -> f64 {
        if self.inv > 0.0 {
            1.0 / self.inv
        } else {
            0.0
        }
    }

    /// The cell of coordinate `x` along axis `k`, clamped to the grid. Monotone in `x`.
    #[inline]
    fn cell(&self, x: f64, k: usize) -> usize {
        // `as` saturates: below the grid → 0.
        let c = ((x - self.lo[k]) * self.inv) as usize;
        if c < self.n[k] {
            c
        } else {
            self.n[k] - 1
        }
    }

    /// The cells a box meets: `[lo, hi]` per axis.
    #[inline]
    fn range(&self, b: &Box3) -> [[usize; 3]; 2] {
        let c = |i: usize, k: usize| self.cell(b[i][k], k);
        [[c(0, 0), c(0, 1), c(0, 2)], [c(1, 0), c(1, 1), c(1, 2)]]
    }

    fn index(&self, c: [usize; 3]) -> usize {
        Self::index_of(self.n, c)
    }

    /// The index of cell `c` in a grid of `n` cells a side.
    #[inline]
    fn index_of(n: [usize; 3], c: [usize; 3]) -> usize {
        (c[2] * n[1] + c[1]) * n[0] + c[0]
    }

    /// A point's cell, packed: each axis in its [`Grid::shift`] and [`Grid::mask`].
    #[inline]
    fn packed(&self, p: &[f64; 3]) -> u32 {
        self.pack([0, 1, 2].map(|k| self.cell(p[k], k)))
    }

    /// A cell's coordinates, packed as in [`Grid::packed`].
    #[inline]
    fn pack(&self, c: [usize; 3]) -> u32 {
        c[0] as u32 | (c[1] as u32) << self.shift[1] | (c[2] as u32) << self.shift[2]
    }

    /// A triangle's cells in 32 bits, from its corners' [`Grid::packed`] cells (the range
    /// of its box: cells are monotone): its lowest cell's index times 8, plus a bit per
    /// axis along which it spans two cells; [`Grid::WIDE`] when it spans more.
    #[inline]
    fn key(&self, c: [u32; 3]) -> u32 {
        let mut low = [0usize; 3];
        let mut span = 0;
        for (k, low) in low.iter_mut().enumerate() {
            let [a, b, d] = c.map(|x| x >> self.shift[k] & self.mask[k]);
            let (lo, hi) = (a.min(b).min(d), a.max(b).max(d));
            match hi - lo {
                0 => {}
                1 => span |= 1 << k,
                _ => return Self::WIDE,
            }
            *low = lo as usize;
        }
        (self.index(low) as u32) << 3 | span
    }

    /// A box that a box meets if and only if the range of its cells meets `r` (the cells
    /// are monotone: the range of a box's cells is that of its corners).
    fn enclosing(&self, r: &[[usize; 3]; 2]) -> Box3 {
        [
            std::array::from_fn(|k| self.first_at_least(k, r[0][k])),
            std::array::from_fn(|k| self.first_at_least(k, r[1][k] + 1)),
        ]
    }

    /// The least coordinate along axis `k` whose cell is `c` or more (a bisection over the
    /// doubles in order; `∞` where no cell is).
    fn first_at_least(&self, k: usize, c: usize) -> f64 {
        // The doubles in order as integers (an involution, as in `f64::total_cmp`).
        let ord = |x: i64| x ^ (((x >> 63) as u64) >> 1) as i64;
        let at = |i: i64| f64::from_bits(ord(i) as u64);
        if c == 0 {
            return f64::NEG_INFINITY;
        }
        if c >= self.n[k] {
            return f64::INFINITY;
        }
        // cell(−∞) = 0 < c ≤ n − 1 = cell(∞).
        let (mut below, mut above) = (
            ord(f64::NEG_INFINITY.to_bits() as i64),
            ord(f64::INFINITY.to_bits() as i64),
        );
        while below < above - 1 {
            let mid = ((i128::from(below) + i128::from(above)) >> 1) as i64;
            if self.cell(at(mid), k) >= c {
                above = mid;
            } else {
                below = mid;
            }
        }
        at(above)
    }

    /// Whether a triangle with corners in the [`Grid::packed`] cells `c` spans more than
    /// two cells along an axis (its [`Grid::key`] is [`Grid::WIDE`]).
    #[inline]
    fn wide(&self, c: [u32; 3]) -> bool {
        let mut wide = false;
        for k in 0..3 {
            let [a, b, d] = c.map(|x| x >> self.shift[k] & self.mask[k]);
            wide |= a.max(b).max(d) - a.min(b).min(d) > 1;
        }
        wide
    }

    /// The index of a [`Grid::packed`] cell.
    #[inline]
    fn unpacked(&self, c: u32) -> usize {
        self.index(self.coordinates(c))
    }

    /// The coordinates of a [`Grid::packed`] cell.
    #[inline]
    fn coordinates(&self, c: u32) -> [usize; 3] {
        [0, 1, 2].map(|k| (c >> self.shift[k] & self.mask[k]) as usize)
    }

    #[inline]
    fn get(&self, i: usize) -> bool {
        self.bits[i / 64] >> (i % 64) & 1 == 1
    }

    /// Whether any cell of a [`Grid::key`] (not [`Grid::WIDE`]) is marked.
    #[inline]
    fn key_touches(&self, key: u32) -> bool {
        let (base, span) = ((key >> 3) as usize, key & 7);
        if span == 0 {
            return self.get(base);
        }
        let (sy, sz) = (self.n[0], self.n[0] * self.n[1]);
        let (nx, ny, nz) = (span & 1, span >> 1 & 1, span >> 2 & 1);
        for z in 0..=nz {
            for y in 0..=ny {
                for x in 0..=nx {
                    if self.get(base + x as usize + y as usize * sy + z as usize * sz) {
                        return true;
                    }
                }
            }
        }
        false
    }

    /// The rows (along x) of a [`Grid::key`]-sorted list `keyed`: for each row that holds
    /// a key's lowest cell, the run of `keyed` there (`start`, `end`).
    fn rows_of_keys(&self, keyed: &[(u32, u32)]) -> FxHashMap<u32, (u32, u32)> {
        let mut rows = FxHashMap::default();
        for (run, i) in keyed
            .chunk_by(|a, b| (a.0 >> 3) / self.n[0] as u32 == (b.0 >> 3) / self.n[0] as u32)
            .scan(0u32, |i, run| {
                let start = *i;
                *i += run.len() as u32;
                Some((run, start))
            })
        {
            rows.insert(
                (run[0].0 >> 3) / self.n[0] as u32,
                (i, i + run.len() as u32),
            );
        }
        rows
    }

    /// Calls `f` with the position in `keyed` ((key, id) sorted, no [`Grid::WIDE`] key,
    /// its rows `rows` ([`Grid::rows_of_keys`])) of every entry whose cells meet those of
    /// box `b` (a superset of the triangles whose boxes meet `b`), each once; of every
    /// entry where the rows would cost more than the whole list.
    fn keyed_near(
        &self,
        keyed: &[(u32, u32)],
        rows: &FxHashMap<u32, (u32, u32)>,
        b: &Box3,
        mut f: impl FnMut(usize),
    ) {
        let r = self.range(b);
        // A triangle's cells along an axis are its key's lowest cell and perhaps the next:
        // those meeting the range have their lowest cell in it, or just below it and the
        // key's bit for that axis set. Row by row (along x, one run of keys each), or all
        // of them where the rows would cost more.
        let [x0, y0, z0] = r[0].map(|c| c.saturating_sub(1));
        let count = (r[1][1] - y0 + 1) * (r[1][2] - z0 + 1);
        if count.saturating_mul(Self::ROW_COST) > keyed.len() {
            (0..keyed.len()).for_each(f);
            return;
        }
        for z in z0..=r[1][2] {
            for y in y0..=r[1][1] {
                let Some(&(start, end)) = rows.get(&((z * self.n[1] + y) as u32)) else {
                    continue;
                };
                let run = &keyed[start as usize..end as usize];
                // The bits a key of this row must have.
                let need = u32::from(y < r[0][1]) << 1 | u32::from(z < r[0][2]) << 2;
                let lo = (self.index([x0, y, z]) as u32) << 3;
                let mid = (self.index([r[0][0], y, z]) as u32) << 3;
                let hi = (self.index([r[1][0], y, z]) as u32) << 3 | 7;
                let first = run.partition_point(|&(k, _)| k < lo);
                let last = first + run[first..].partition_point(|&(k, _)| k <= hi);
                let from = start as usize + first;
                for (i, &(k, _)) in (from..).zip(&run[first..last]) {
                    let need = need | u32::from(k < mid);
                    if k & need == need {
                        f(i);
                    }
                }
            }
        }
    }

    /// The blocks (of 4 × 4 × 4 cells) of the cells of a range, as a range.
    fn blocks(&self, r: &[[usize; 3]; 2]) -> [[usize; 3]; 2] {
        r.map(|c| c.map(|x| x / 4))
    }

    /// Calls `f` with the id of each block of the range of blocks `r`.
    fn all_blocks(&self, r: &[[usize; 3]; 2], mut f: impl FnMut(u32)) {
        let nb = self.n.map(|c| c.div_ceil(4));
        for z in r[0][2]..=r[1][2] {
            for y in r[0][1]..=r[1][1] {
                for x in r[0][0]..=r[1][0] {
                    f(Self::index_of(nb, [x, y, z]) as u32);
                }
            }
        }
    }

    /// The number of cells in a range.
    fn cells(r: &[[usize; 3]; 2]) -> usize {
        (0..3).map(|k| r[1][k] - r[0][k] + 1).product()
    }

    /// Calls `f(word, mask)` for the bits of every row (along x) of the cells of `r`, a
    /// word at a time, until it says stop; whether it went through all of them.
    fn rows(&self, r: &[[usize; 3]; 2], f: impl FnMut(usize, u64) -> bool) -> bool {
        Self::rows_of(self.n, r, f)
    }

    /// [`Grid::rows`] of a grid of `n` cells a side (without borrowing one, so that `f`
    /// may change its bits).
    fn rows_of(n: [usize; 3], r: &[[usize; 3]; 2], mut f: impl FnMut(usize, u64) -> bool) -> bool {
        let index = |c: [usize; 3]| Self::index_of(n, c);
        for z in r[0][2]..=r[1][2] {
            for y in r[0][1]..=r[1][1] {
                let (first, last) = (index([r[0][0], y, z]), index([r[1][0], y, z]));
                for w in first / 64..=last / 64 {
                    let lo = if w == first / 64 { first % 64 } else { 0 };
                    let hi = if w == last / 64 { last % 64 } else { 63 };
                    let mask = (u64::MAX >> (63 - hi)) & (u64::MAX << lo);
                    if !f(w, mask) {
                        return false;
                    }
                }
            }
        }
        true
    }

    /// Marks the cells of `b`; whether any was new.
    fn mark(&mut self, b: &Box3) -> bool {
        self.mark_range(&self.range(b))
    }

    /// [`Grid::mark`], noting the bits it set: (word, bits).
    fn mark_noting(&mut self, b: &Box3, set: &mut Vec<(usize, u64)>) -> bool {
        let r = self.range(b);
        self.mark_range_with(&r, |w, fresh| set.push((w, fresh)))
    }

    /// Marks the cells of the range `r`; whether any was new.
    fn mark_range(&mut self, r: &[[usize; 3]; 2]) -> bool {
        self.mark_range_with(r, |_, _| {})
    }

    /// [`Grid::mark_range`], telling `note` the bits newly set in each word.
    fn mark_range_with(&mut self, r: &[[usize; 3]; 2], mut note: impl FnMut(usize, u64)) -> bool {
        let (bits, mut new) = (&mut self.bits, false);
        Self::rows_of(self.n, r, |w, mask| {
            let fresh = mask & !bits[w];
            if fresh != 0 {
                new = true;
                bits[w] |= fresh;
                note(w, fresh);
            }
            true
        });
        new
    }

    /// Whether every cell of `b` is marked.
    fn covers(&self, b: &Box3) -> bool {
        self.rows(&self.range(b), |w, mask| self.bits[w] & mask == mask)
    }

    /// Whether some cell of `b` is marked.
    fn touches(&self, b: &Box3) -> bool {
        !self.rows(&self.range(b), |w, mask| self.bits[w] & mask == 0)
    }
}

/// What is known of the mesh near the work: the live triangles touching the marked
/// cells, gathered at the start of a round, sorted by their [`Grid::key`]s (the grid is
/// their spatial index: a box's triangles are found row by row of its cells), and the
/// triangles around each of their vertices; the triangles made since by grid cell.
#[derive(Default)]
struct Near {
    /// The gathered triangles spanning at most two cells along each axis, as ([`Grid::key`],
    /// id), sorted.
    keyed: Vec<(u32, u32)>,
    /// The boxes of the triangles of `keyed`, in its order, and its rows
    /// ([`Grid::rows_of_keys`]).
    boxes: Vec<Box3>,
    rows: FxHashMap<u32, (u32, u32)>,
    /// The gathered triangles spanning more ([`Grid::WIDE`]).
    wide_in: Vec<u32>,
    /// Each vertex's id among the gathered triangles' vertices plus one (0: none; zeroed
    /// memory, whose pages the system maps only where written), and those vertices (to
    /// clear `local` for the next gathering without a new buffer).
    local: Vec<u32>,
    verts: Vec<u32>,
    /// The triangles (ids) around local vertex `l`: `around[start[l]..start[l + 1]]`.
    start: Vec<u32>,
    around: Vec<u32>,
    /// The triangles indexed since (made, or gathered by [`Work::extend`]), in `later`
    /// and by the blocks ([`Grid::blocks`]) their boxes meet, or in `wide` where they meet
    /// many.
    later: Vec<u32>,
    blocks: FxHashMap<u32, Vec<u32>>,
    wide: Vec<u32>,
    /// Whether the index was built ([`Work::index`]).
    built: bool,
}

impl Near {
    /// The triangles around vertex `v` in the index as built (none where `v` is not a
    /// corner of a gathered triangle).
    fn indexed_around(&self, v: u32) -> &[u32] {
        match self.local.get(v as usize).filter(|&&l| l != 0) {
            Some(&l) => {
                let l = l - 1;
                &self.around[self.start[l as usize] as usize..self.start[l as usize + 1] as usize]
            }
            None => &[],
        }
    }
}

/// The working mesh. Triangles are never edited, only killed and made anew (so the
/// index's boxes stay true): ids below the input's triangle count are the input's,
/// those above are made, each in the place (`slot`) of an input triangle, which holds
/// at most one live triangle at a time.
struct Work<'a> {
    mesh: &'a Mesh,
    d: f64,
    seam: &'a [u32],
    labels: Labels<'a>,
    sheets: Option<&'a [u32]>,
    /// The input's triangle count: the first made triangle's id.
    base: u32,
    killed: Vec<bool>,
    /// The input triangles killed, in order.
    killed_list: Vec<u32>,
    made: Vec<[u32; 3]>,
    made_alive: Vec<bool>,
    made_slot: Vec<u32>,
    /// The live triangle made in each slot whose input triangle was killed.
    in_slot: FxHashMap<u32, u32>,
    /// The triangles around vertices changed since the round began (dead ones dropped
    /// lazily); the others' are in `near`.
    stars: FxHashMap<u32, Vec<u32>>,
    /// Vertices collapsed away.
    dead: FxHashSet<u32>,
    /// For a vertex that others were collapsed into: those (input) vertices.
    absorbed: FxHashMap<u32, Vec<u32>>,
    /// Changes made so far, and for each vertex the count when it last changed.
    changes: u32,
    /// A bound on the changes (each collapse removes a triangle and each flip makes two
    /// better, so the work ends anyway; this keeps it in proportion to what was found).
    max_changes: u32,
    touched: FxHashMap<u32, u32>,
    grid: Grid,
    /// Cells around the marked ones (by [`Work::HALO`] cells, marked at each full
    /// pass, or around the seam's points from the start), and the input triangles
    /// touching them at the last full pass (or the scan) with their [`Grid::key`]s.
    halo: Grid,
    candidates: Vec<(u32, u32)>,
    /// Each vertex's cell ([`Grid::packed`]), made at the first pass over all triangles
    /// (empty before).
    cells: Vec<u32>,
    near: Near,
    budget: f64,
    /// Whether `budget` is `D` times the whole area (else times a part of it).
    budget_whole: bool,
    spent: f64,
    heap: BinaryHeap<Item>,
    /// Every triangle found bad (to count those left).
    ever_bad: Vec<u32>,
    /// The refusal of the last attempt to fix a triangle.
    refusal: FxHashMap<u32, Refusal>,
    report: SnapReport,
}

/// Rounds of gathering neighbourhoods and fixing.
const MAX_ROUNDS: usize = 8;

/// In a list of triangles met ([`Work::crossings`]): a meeting of two of the triangles
/// tested, rather than of one of them and a live triangle.
const AMONG: u32 = u32::MAX;

/// Edge counts by kind around one vertex.
#[derive(Clone, Copy, Default, Debug)]
struct Defects {
    boundary: usize,
    non_manifold: usize,
    inconsistent: usize,
}

impl<'a> Work<'a> {
    /// Made triangles meeting at most this many blocks are indexed by block.
    const FEW_BLOCKS: usize = 8;
    /// The halo's margin around the boxes marked at a full pass, in cells.
    const HALO: f64 = 3.0;

    fn new(
        mesh: &'a Mesh,
        opts: &SnapOptions<'a>,
        labels: Labels<'a>,
        scan: Scan,
        grid: Grid,
        halo: Grid,
    ) -> Self {
        let n = mesh.triangles.len();
        Work {
            mesh,
            d: opts.tolerance,
            seam: opts.seam,
            labels,
            sheets: opts.sheets,
            base: n as u32,
            killed: vec![false; n],
            killed_list: Vec::new(),
            made: Vec::new(),
            made_alive: Vec::new(),
            made_slot: Vec::new(),
            in_slot: FxHashMap::default(),
            stars: FxHashMap::default(),
            dead: FxHashSet::default(),
            absorbed: FxHashMap::default(),
            changes: 0,
            max_changes: u32::try_from(16 * scan.bad.len() + 1024).unwrap_or(u32::MAX),
            touched: FxHashMap::default(),
            candidates: scan.candidates,
            cells: Vec::new(),
            halo,
            grid,
            near: Near::default(),
            budget: opts.tolerance * scan.area,
            budget_whole: !opts.seam_only,
            spent: 0.0,
            heap: BinaryHeap::new(),
            ever_bad: scan.bad.iter().map(|&(_, t)| t).collect(),
            refusal: FxHashMap::default(),
            report: SnapReport::default(),
        }
    }

    fn tri(&self, t: u32) -> [u32; 3] {
        if t < self.base {
            self.mesh.triangles[t as usize]
        } else {
            self.made[(t - self.base) as usize]
        }
    }

    fn alive(&self, t: u32) -> bool {
        if t < self.base {
            !self.killed[t as usize]
        } else {
            self.made_alive[(t - self.base) as usize]
        }
    }

    fn kill(&mut self, t: u32) {
        if t < self.base {
            self.killed[t as usize] = true;
            self.killed_list.push(t);
        } else {
            self.made_alive[(t - self.base) as usize] = false;
        }
    }

    fn slot(&self, t: u32) -> u32 {
        if t < self.base {
            t
        } else {
            self.made_slot[(t - self.base) as usize]
        }
    }

    fn label(&self, t: u32) -> Option<u32> {
        let slot = self.slot(t);
        match self.labels {
            Labels::Given(l) => l.map(|l| l[slot as usize]),
            Labels::Of(f) => Some(f(slot)),
        }
    }

    fn sheet(&self, t: u32) -> u32 {
        self.sheets.map_or(0, |s| s[self.slot(t) as usize])
    }

    fn corners(&self, t: &[u32; 3]) -> [[f64; 3]; 3] {
        t.map(|v| self.mesh.positions[v as usize])
    }

    fn pos(&self, v: u32) -> [f64; 3] {
        self.mesh.positions[v as usize]
    }

    fn bad_key(&self, t: u32) -> Option<f64> {
        badness(&self.corners(&self.tri(t)), self.d)
    }

    /// The live triangles around `v`; `Later` when they are not all gathered (`v` is not
    /// in a marked cell: then some of its triangles may not touch one).
    fn star(&self, v: u32) -> Gate<Vec<u32>> {
        let all: &[u32] = match self.stars.get(&v) {
            Some(s) => s,
            None => {
                if !self
                    .grid
                    .get(self.grid.unpacked(self.grid.packed(&self.pos(v))))
                {
                    return Err(Stop::Later);
                }
                self.near.indexed_around(v)
            }
        };
        // One allocation (a filter's `collect` would grow from nothing).
        let mut live = Vec::with_capacity(all.len());
        live.extend(all.iter().copied().filter(|&t| self.alive(t)));
        Ok(live)
    }

    /// Fixes bad triangles in rounds, starting from `seeds`.
    fn run(&mut self, mut seeds: Vec<u32>) {
        for _ in 0..MAX_ROUNDS {
            if seeds.is_empty() {
                break;
            }
            let gathered = self.gather(&seeds);
            let before = self.changes;
            self.queue(&seeds);
            let mut later = Vec::new();
            let mut failed: Vec<(u32, u32)> = Vec::new();
            while let Some(Item { t, .. }) = self.heap.pop() {
                if self.changes >= self.max_changes {
                    self.heap.clear();
                    break;
                }
                if !self.alive(t) || self.bad_key(t).is_none() {
                    continue;
                }
                match self.fix(t) {
                    Ok(()) => {}
                    Err(Stop::Later) => later.push(t),
                    Err(Stop::Refused(r)) => {
                        self.refusal.insert(t, r);
                        failed.push((t, self.changes));
                    }
                }
            }
            if self.changes == before && !gathered {
                break;
            }
            // Next: what waited for its neighbourhood, and what was refused before
            // something around it changed.
            let touched_since = |w: &Self, t: u32, at: u32| {
                w.tri(t)
                    .iter()
                    .any(|v| w.touched.get(v).is_some_and(|&c| c > at))
            };
            later.extend(
                failed
                    .into_iter()
                    .filter(|&(t, at)| self.alive(t) && touched_since(self, t, at))
                    .map(|(t, _)| t),
            );
            later.sort_unstable();
            later.dedup();
            later.retain(|&t| self.alive(t));
            seeds = later;
        }
    }

    /// Marks the cells around `seeds` (their boxes grown by a cell and a few tolerances,
    /// and the boxes of the triangles around their vertices where those are known) and
    /// gathers every live triangle touching a marked cell; whether anything new was
    /// marked. A change at a seed then finds everything it needs: the triangles around
    /// its vertices (in marked cells), and every triangle its new triangles could meet.
    fn gather(&mut self, seeds: &[u32]) -> bool {
        let by = self.grid.size() + 4.0 * self.d;
        let mut boxes: Vec<Box3> = Vec::new();
        let mut around: Vec<u32> = Vec::new();
        for &t in seeds {
            let tri = self.tri(t);
            boxes.push(grown(&tri_box(&self.corners(&tri)), by));
            for v in tri {
                around.extend(self.star(v).unwrap_or_default());
            }
        }
        // Each triangle once (a large one is around many seeds).
        around.sort_unstable();
        around.dedup();
        boxes.extend(
            around
                .iter()
                .map(|&s| grown(&tri_box(&self.corners(&self.tri(s))), 4.0 * self.d)),
        );
        let (mut marked, mut set) = (false, Vec::new());
        for b in &boxes {
            marked |= self.grid.mark_noting(b, &mut set);
        }
        if marked {
            // Within the halo the last full pass (or the scan) gathered its candidates
            // from, a pass over those finds every triangle (only those touching no cell
            // marked before, once there is an index); else the halo grows and all are
            // passed over.
            if boxes.iter().all(|b| self.halo.covers(b)) {
                if self.near.built {
                    let mut before = self.grid.clone();
                    for (w, bits) in set {
                        before.bits[w] &= !bits;
                    }
                    self.extend(&before);
                } else {
                    self.pass(false);
                }
            } else {
                let margin = Self::HALO * self.grid.size();
                for b in &boxes {
                    self.halo.mark(&grown(b, margin));
                }
                self.pass(true);
            }
        }
        marked
    }

    /// One pass over the triangles: every live one touching a marked cell, indexed (a
    /// tree, and the triangles around each vertex). `full`: over all of them, keeping
    /// those touching the halo as the candidates of the next passes; else over the
    /// candidates (the marked cells are all in the halo).
    fn pass(&mut self, full: bool) {
        const PIECE: usize = 1 << 13;
        if full && self.cells.is_empty() {
            let grid = &self.grid;
            self.cells = (self.mesh.positions.par_iter().grained().with_min_len(PIECE))
                .map(|p| grid.packed(p))
                .collect();
        }
        let w = &*self;
        let mut keyed: Vec<(u32, u32)> = if full {
            let pieces: Vec<(Keyed, Keyed)> = self
                .mesh
                .triangles
                .par_chunks(PIECE)
                .grained()
                .enumerate()
                .map(|(k, tris)| {
                    let (mut ids, mut halo) = (Vec::new(), Vec::new());
                    for (i, tri) in tris.iter().enumerate() {
                        let t = (k * PIECE + i) as u32;
                        let p = || w.corners(tri);
                        let key = w.grid.key(tri.map(|v| w.cells[v as usize]));
                        if w.halo.touches_key(key, p) && w.alive(t) {
                            halo.push((t, key));
                            if w.grid.touches_key(key, p) {
                                ids.push((t, key));
                            }
                        }
                    }
                    (ids, halo)
                })
                .collect();
            let (ids, halo): (Vec<Keyed>, Vec<Keyed>) = pieces.into_iter().unzip();
            self.candidates = halo.concat();
            ids.concat()
        } else {
            self.candidates
                .par_iter()
                .grained()
                .with_min_len(PIECE)
                .filter(|&&(t, key)| {
                    // The corners only for a triangle spanning many cells (read at
                    // random, they would cost more than the rest).
                    w.grid
                        .touches_key(key, || w.corners(&w.mesh.triangles[t as usize]))
                        && w.alive(t)
                })
                .copied()
                .collect()
        };
        for i in 0..self.made.len() {
            let t = self.base + i as u32;
            let tri = self.made[i];
            if self.made_alive[i] && self.grid.touches(&tri_box(&self.corners(&tri))) {
                keyed.push((
                    t,
                    self.grid.key(tri.map(|v| self.grid.packed(&self.pos(v)))),
                ));
            }
        }
        self.index(keyed);
    }

    /// Adds to the index the live triangles touching the cells marked since `before` and
    /// none marked in it (candidates: the marked cells are all in the halo). The vertices
    /// in the newly marked cells get their stars: the triangles around them in the index
    /// as built, and those indexed since ([`Near::later`]: made, or added here or by an
    /// earlier extension). None of those vertices had one: a triangle around a vertex in
    /// a cell marked before touches that cell, so it was indexed.
    fn extend(&mut self, before: &Grid) {
        const PIECE: usize = 1 << 13;
        let w = &*self;
        // The corners only for a triangle spanning many cells (read at random, they would
        // cost more than the rest).
        let newly = |key: u32, t: u32| {
            let p = || w.corners(&w.mesh.triangles[t as usize]);
            w.grid.touches_key(key, p) && !before.touches_key(key, p)
        };
        // (Every live triangle made before the index was built touches a cell marked
        // then: one of its corners is a changed vertex, whose star was known. So only
        // the candidates are new.)
        let added: Vec<u32> = self
            .candidates
            .par_iter()
            .grained()
            .with_min_len(PIECE)
            .filter(|&&(t, key)| newly(key, t) && w.alive(t))
            .map(|&(t, _)| t)
            .collect();
        for &t in &added {
            self.index_later(t);
        }
        // The vertices in newly marked cells, with the triangles indexed since around
        // them.
        let is_new = |v: u32| {
            let c = self.grid.unpacked(self.grid.packed(&self.pos(v)));
            self.grid.get(c) && !before.get(c)
        };
        let mut new_around: Vec<(u32, u32)> = (self.near.later.iter())
            .filter(|&&t| self.alive(t))
            .flat_map(|&t| self.tri(t).map(|v| (v, t)))
            .filter(|&(v, _)| is_new(v))
            .collect();
        new_around.sort_unstable();
        new_around.dedup();
        for run in new_around.chunk_by(|a, b| a.0 == b.0) {
            let v = run[0].0;
            let mut star = self.near.indexed_around(v).to_vec();
            for &(_, t) in run {
                if !star.contains(&t) {
                    star.push(t);
                }
            }
            debug_assert!(!self.stars.contains_key(&v));
            self.stars.insert(v, star);
        }
    }

    /// The index over the triangles `keyed` ((id, [`Grid::key`])): sorted by key, each
    /// vertex's triangles; the made triangles' cells and the changed stars start anew.
    fn index(&mut self, keyed: Keyed) {
        let old = std::mem::take(&mut self.near);
        let mut local = old.local;
        if local.len() == self.mesh.positions.len() {
            for &v in &old.verts {
                local[v as usize] = 0;
            }
        } else {
            local = vec![0; self.mesh.positions.len()];
        }
        let mut verts = old.verts;
        verts.clear();
        let triangles: Vec<[u32; 3]> = keyed
            .iter()
            .map(|&(t, _)| {
                self.tri(t).map(|v| {
                    let l = &mut local[v as usize];
                    if *l == 0 {
                        verts.push(v);
                        *l = verts.len() as u32;
                    }
                    *l - 1
                })
            })
            .collect();
        // The triangles around each local vertex (a counting sort).
        let mut start = vec![0u32; verts.len() + 1];
        for tri in &triangles {
            for (j, &l) in tri.iter().enumerate() {
                if !tri[..j].contains(&l) {
                    start[l as usize + 1] += 1;
                }
            }
        }
        for i in 0..verts.len() {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut around = vec![0u32; start[verts.len()] as usize];
        for (tri, &(t, _)) in triangles.iter().zip(&keyed) {
            for (j, &l) in tri.iter().enumerate() {
                if !tri[..j].contains(&l) {
                    around[fill[l as usize] as usize] = t;
                    fill[l as usize] += 1;
                }
            }
        }
        let wide_in: Vec<u32> = keyed
            .iter()
            .filter(|&&(_, key)| key == Grid::WIDE)
            .map(|&(t, _)| t)
            .collect();
        let mut keyed: Vec<(u32, u32)> = keyed
            .into_iter()
            .filter(|&(_, key)| key != Grid::WIDE)
            .map(|(t, key)| (key, t))
            .collect();
        keyed.par_sort_unstable();
        let boxes = keyed
            .par_iter()
            .grained()
            .with_min_len(1 << 12)
            .map(|&(_, t)| tri_box(&self.corners(&self.tri(t))))
            .collect();
        let rows = self.grid.rows_of_keys(&keyed);
        self.near = Near {
            keyed,
            boxes,
            rows,
            wide_in,
            local,
            verts,
            start,
            around,
            later: Vec::new(),
            blocks: FxHashMap::default(),
            wide: Vec::new(),
            built: true,
        };
        self.stars.clear();
    }

    /// The live triangles whose boxes meet `b`, which the grid must cover.
    fn near_triangles(&self, b: &Box3) -> Vec<u32> {
        let meets = |t: u32| self.alive(t) && overlap(&tri_box(&self.corners(&self.tri(t))), b);
        let mut out: Vec<u32> = Vec::with_capacity(64);
        let near = &self.near;
        self.grid.keyed_near(&near.keyed, &near.rows, b, |i| {
            let t = near.keyed[i].1;
            if overlap(&near.boxes[i], b) && self.alive(t) {
                out.push(t);
            }
        });
        out.extend(near.wide_in.iter().copied().filter(|&t| meets(t)));
        // Those indexed since: by block where the box meets few, else all of them.
        let r = self.grid.blocks(&self.grid.range(b));
        let later = if Grid::cells(&r) <= 4 * Self::FEW_BLOCKS {
            let mut later = near.wide.clone();
            self.grid.all_blocks(&r, |i| {
                if let Some(ids) = near.blocks.get(&i) {
                    later.extend(ids);
                }
            });
            later.sort_unstable();
            later.dedup();
            later
        } else {
            near.later.clone()
        };
        out.extend(later.into_iter().filter(|&t| meets(t)));
        out
    }

    /// Tries to fix bad triangle `t`: its short edges collapsed (shortest first, the
    /// better end kept first: the one that keeps the shape ([`Work::offset`]), else the
    /// better ranked ([`Work::rank`])), else its longest edge flipped.
    fn fix(&mut self, t: u32) -> Gate<()> {
        let tri = self.tri(t);
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0] {
            return refuse(Manifold);
        }
        let p = self.corners(&tri);
        let len = [0, 1, 2].map(|k| norm(&sub(&p[(k + 1) % 3], &p[k])));
        let mut order = [0usize, 1, 2];
        order.sort_by(|&i, &j| len[i].total_cmp(&len[j]));
        let mut first: Option<Refusal> = None;
        for &k in &order {
            if len[k] >= self.d {
                break;
            }
            let (u, v) = (tri[k], tri[(k + 1) % 3]);
            // Keep the end that keeps the shape; where both do, the better ranked.
            let keep_v = match self.offset(v, u)?.total_cmp(&self.offset(u, v)?) {
                Ordering::Less => true,
                Ordering::Greater => false,
                Ordering::Equal => {
                    let (ru, rv) = (self.rank(u)?, self.rank(v)?);
                    rv < ru || (rv == ru && v < u)
                }
            };
            let pairs = if keep_v {
                [(v, u), (u, v)]
            } else {
                [(u, v), (v, u)]
            };
            for (keep, gone) in pairs {
                let mut tried = self.collapse(keep, gone);
                if matches!(tried, Err(Stop::Refused(Manifold))) && self.unlock(keep, gone)? {
                    tried = self.collapse(keep, gone);
                }
                match tried {
                    Err(Stop::Refused(r)) => {
                        first.get_or_insert(r);
                    }
                    done => return done,
                }
            }
        }
        if altitude(&p) < self.d {
            match self.flip(t, order[2]) {
                Err(Stop::Refused(r)) => {
                    first.get_or_insert(r);
                }
                done => return done,
            }
        }
        refuse(first.unwrap_or(NoGain))
    }

    /// How far moving `other` onto `keep` takes it off the planes of its triangles: zero
    /// (up to the rounding of the coordinates) along a flat surface or a crease, where the
    /// shape stays.
    fn offset(&self, keep: u32, other: u32) -> Gate<f64> {
        let so = self.star(other)?;
        let (pk, po) = (self.pos(keep), self.pos(other));
        let step = sub(&pk, &po);
        let mut off = 0.0f64;
        let mut scale = pk.iter().chain(&po).fold(0.0f64, |m, x| m.max(x.abs()));
        for &t in &so {
            let tri = self.tri(t);
            if tri.contains(&keep) {
                continue;
            }
            let p = self.corners(&tri);
            let n = cross(&sub(&p[1], &p[0]), &sub(&p[2], &p[0]));
            let len = norm(&n);
            if len > 0.0 {
                off = off.max(dot(&n, &step).abs() / len);
            }
            scale = p.iter().flatten().fold(scale, |m, x| m.max(x.abs()));
        }
        // Rounded coordinates put a point of a plane up to about an ulp of the largest
        // coordinate off it: offsets below a thousand times that count as none.
        Ok(if off <= 1e-13 * scale { 0.0 } else { off })
    }

    /// How much `keep` is worth keeping in place, smaller being better: fewer creases
    /// through it (boundary, non-manifold and label edges, and edges between triangles
    /// not in one plane, decided exactly; three or more: a corner), then an input vertex
    /// before a seam point.
    fn rank(&self, keep: u32) -> Gate<(u8, bool)> {
        let sk = self.star(keep)?;
        let mut creases = 0u8;
        let sk_tris: Vec<[u32; 3]> = sk.iter().map(|&t| self.tri(t)).collect();
        for x in neighbours(sk_tris.iter().copied(), keep) {
            let on: Vec<u32> = sk
                .iter()
                .copied()
                .filter(|&t| self.tri(t).contains(&x))
                .collect();
            let crease = match on[..] {
                [s, t] => {
                    let far = self
                        .tri(t)
                        .into_iter()
                        .find(|&w| w != keep && w != x)
                        .unwrap_or(keep);
                    let [a, b, c] = self.corners(&self.tri(s));
                    self.label(s) != self.label(t)
                        || orient3d_explicit(&a, &b, &c, &self.pos(far)) != Sign::Zero
                }
                _ => true,
            };
            creases += u8::from(crease);
            if creases >= 3 {
                break;
            }
        }
        Ok((3 - creases, self.seam.binary_search(&keep).is_ok()))
    }

    /// Refuses a change that would spend more than the volume budget (measuring the
    /// whole area the first time a budget of a part of it would refuse).
    fn volume_gate(&mut self, dv: f64) -> Gate<()> {
        if self.spent + dv.abs() > self.budget && !self.budget_whole {
            let twice: f64 = self
                .mesh
                .triangles
                .par_iter()
                .grained()
                .with_min_len(1 << 13)
                .map(|t| shape(&self.corners(t)).2)
                .sum();
            self.budget = self.d * twice / 2.0;
            self.budget_whole = true;
        }
        if self.spent + dv.abs() > self.budget {
            refuse(Volume)
        } else {
            Ok(())
        }
    }

    /// Refuses new triangles that meet live triangles (other than `killed`) or each other
    /// beyond what they share, unless the `killed` triangles they replace met each of
    /// those live triangles too and each other at least as often (almost always: refuses
    /// any meeting; an exact result whose rounded seam points cross leaves crossings that
    /// a change may keep or remove but not move onto another triangle); `Later` where the
    /// index does not cover them yet.
    fn clear_of(&self, new: &[[u32; 3]], killed: &[u32]) -> Gate<()> {
        let after = self.crossings(new, killed)?;
        if after.is_empty() {
            return Ok(());
        }
        let old: Vec<[u32; 3]> = killed.iter().map(|&t| self.tri(t)).collect();
        let before = self.crossings(&old, killed)?;
        let among = |c: &[u32]| c.iter().filter(|&&t| t == AMONG).count();
        let kept = after.iter().all(|t| *t == AMONG || before.contains(t));
        if kept && among(&after) <= among(&before) {
            Ok(())
        } else {
            refuse(SelfIntersection)
        }
    }

    /// The live triangles other than `skip` that one of `tris` meets beyond what they share
    /// (exact), once per meeting, and [`AMONG`] once per pair of `tris` that meet; `Later`
    /// where the index does not cover them.
    fn crossings(&self, tris: &[[u32; 3]], skip: &[u32]) -> Gate<Vec<u32>> {
        if tris.is_empty() {
            return Ok(Vec::new());
        }
        let corners: Vec<[[f64; 3]; 3]> = tris.iter().map(|n| self.corners(n)).collect();
        let boxes: Vec<Box3> = corners.iter().map(tri_box).collect();
        if !boxes.iter().all(|b| self.grid.covers(b)) {
            return Err(Stop::Later);
        }
        let planes: Vec<FloatPlane> = corners.iter().map(FloatPlane::new).collect();
        let meets = |i: usize, m: [u32; 3], pm: [[f64; 3]; 3]| {
            let (n, pn) = (tris[i], corners[i]);
            let shared = n.iter().filter(|v| m.contains(v)).count();
            if shared == 3 {
                return true;
            }
            // The common case first: the corners of `m` that `n` does not share all
            // certainly on one side of `n`'s plane (floating-point filter): they meet at
            // most in what they share.
            let mut side = None;
            let apart = (0..3).filter(|&k| !n.contains(&m[k])).all(|k| {
                match (planes[i].side(&pm[k]), side) {
                    (Some(s), None) => {
                        side = Some(s);
                        true
                    }
                    (Some(s), Some(t)) => s == t,
                    (None, _) => false,
                }
            });
            !apart && corners_meet_beyond_shared([(0, n, pn), (1, m, pm)], shared)
        };
        // One query for all of them.
        let all = boxes.iter().fold(boxes[0], |a, b| {
            [
                [
                    min(a[0][0], b[0][0]),
                    min(a[0][1], b[0][1]),
                    min(a[0][2], b[0][2]),
                ],
                [
                    max(a[1][0], b[1][0]),
                    max(a[1][1], b[1][1]),
                    max(a[1][2], b[1][2]),
                ],
            ]
        });
        // (id, corners' ids, corners, box) of each live triangle near them.
        type Candidate = (u32, [u32; 3], [[f64; 3]; 3], Box3);
        let found = self.near_triangles(&all);
        let mut near: Vec<Candidate> = Vec::with_capacity(found.len());
        near.extend(found.into_iter().filter(|t| !skip.contains(t)).map(|t| {
            let m = self.tri(t);
            let pm = self.corners(&m);
            (t, m, pm, tri_box(&pm))
        }));
        let mut met = Vec::new();

        for i in 0..tris.len() {
            for &(t, m, pm, bm) in &near {
                if overlap(&boxes[i], &bm) && meets(i, m, pm) {
                    met.push(t);
                }
            }
            for j in i + 1..tris.len() {
                if overlap(&boxes[i], &boxes[j]) && meets(i, tris[j], corners[j]) {
                    met.push(AMONG);
                }
            }
        }
        Ok(met)
    }

    /// Collapses edge `keep`–`gone` onto `keep` if every gate passes.
    fn collapse(&mut self, keep: u32, gone: u32) -> Gate<()> {
        let (sk, sg) = (self.star(keep)?, self.star(gone)?);
        // Distance: `gone` and whatever was collapsed into it end up at `keep`.
        let pk = self.pos(keep);
        let mut moved = norm(&sub(&self.pos(gone), &pk));
        for &a in self.absorbed.get(&gone).into_iter().flatten() {
            moved = moved.max(norm(&sub(&self.pos(a), &pk)));
        }
        if moved > self.d {
            return refuse(Distance);
        }
        // Topology, in each sheet apart (one unless sheets were given), then across them.
        let sk_tris: Vec<[u32; 3]> = sk.iter().map(|&t| self.tri(t)).collect();
        let sg_tris: Vec<[u32; 3]> = sg.iter().map(|&t| self.tri(t)).collect();
        let mut sheets: Vec<u32> = sg.iter().map(|&t| self.sheet(t)).collect();
        sheets.sort_unstable();
        sheets.dedup();
        let mut shared: Vec<usize> = Vec::new();
        let mut far: Vec<u32> = Vec::new();
        for &sheet in &sheets {
            let of_k: Vec<[u32; 3]> = (0..sk.len())
                .filter(|&i| self.sheet(sk[i]) == sheet)
                .map(|i| sk_tris[i])
                .collect();
            let of_g: Vec<usize> = (0..sg.len())
                .filter(|&i| self.sheet(sg[i]) == sheet)
                .collect();
            let (s, f) = collapse_topology(keep, gone, &of_k, &of_g, &sg_tris)?;
            shared.extend(s);
            far.extend(f);
        }
        if shared.is_empty() {
            return refuse(Manifold);
        }
        // Across sheets: the end points' common neighbours are the far corners of the
        // edge's triangles (no edge of one sheet merged into another's).
        far.sort_unstable();
        far.dedup();
        if self.sheets.is_some() {
            let (nk, ng) = (
                neighbours(sk_tris.iter().copied(), keep),
                neighbours(sg_tris.iter().copied(), gone),
            );
            if common(&nk, &ng)[..] != far[..] {
                return refuse(Manifold);
            }
        }
        // (triangle, its corners, its corners with `gone` moved onto `keep`).
        let moved_tris: Vec<(u32, [u32; 3], [u32; 3])> = (0..sg.len())
            .filter(|i| !shared.contains(i))
            .map(|i| {
                let old = sg_tris[i];
                (sg[i], old, old.map(|v| if v == gone { keep } else { v }))
            })
            .collect();
        // Inversion.
        for &(_, old, n) in &moved_tris {
            if turns_over(&self.corners(&old), &self.corners(&n)) {
                return refuse(Inversion);
            }
        }
        // Volume.
        let mut dv6 = 0.0;
        for tri in &sg_tris {
            dv6 -= volume6(&self.corners(tri), &pk);
        }
        for &(_, _, n) in &moved_tris {
            dv6 += volume6(&self.corners(&n), &pk);
        }
        let dv = dv6 / 6.0;
        self.volume_gate(dv)?;
        // Self-intersection.
        let new: Vec<[u32; 3]> = moved_tris.iter().map(|&(_, _, n)| n).collect();
        self.clear_of(&new, &sg)?;
        // Commit.
        let mut da = 0.0;
        for (i, &t) in sg.iter().enumerate() {
            da -= shape(&self.corners(&sg_tris[i])).2 / 2.0;
            self.kill(t);
        }
        let mut made = Vec::with_capacity(moved_tris.len());
        for &(t, _, n) in &moved_tris {
            da += shape(&self.corners(&n)).2 / 2.0;
            made.push(self.make(n, self.slot(t)));
        }
        self.stars.insert(gone, Vec::new());
        self.dead.insert(gone);
        let mut taken = self.absorbed.remove(&gone).unwrap_or_default();
        taken.push(gone);
        self.absorbed.entry(keep).or_default().extend(taken);
        let around: Vec<u32> = sg_tris.iter().flatten().copied().collect();
        self.changed(&around, &made);
        self.report.collapsed += 1;
        self.report.max_move = self.report.max_move.max(moved);
        self.report.volume_change += dv;
        self.report.area_change += da;
        self.spent += dv.abs();
        // What is around `keep` now may be fixable.
        let around_keep = self.star(keep).unwrap_or_default();
        self.queue(&around_keep);
        Ok(())
    }

    /// Flips edge `k` of bad triangle `t` (corner `k` to `k + 1`) if every gate passes and
    /// both new triangles are better shaped than the worse of the two old ones.
    fn flip(&mut self, t: u32, k: usize) -> Gate<()> {
        self.flip_with(t, k, false)
    }

    /// Where collapsing `gone` onto `keep` fails the link condition only through
    /// neighbours `x` the two share beyond the edge's far corners: flips an edge
    /// `gone`–`x` (moving no vertex: the volume gate bounds it) so that the collapse may
    /// pass. Whether one was flipped.
    fn unlock(&mut self, keep: u32, gone: u32) -> Gate<bool> {
        let (sk, sg) = (self.star(keep)?, self.star(gone)?);
        let tk: Vec<[u32; 3]> = sk.iter().map(|&t| self.tri(t)).collect();
        let tg: Vec<[u32; 3]> = sg.iter().map(|&t| self.tri(t)).collect();
        let far: Vec<u32> = tg
            .iter()
            .filter(|t| t.contains(&keep))
            .filter_map(|t| t.iter().copied().find(|&w| w != keep && w != gone))
            .collect();
        let extra: Vec<u32> = common(&neighbours(tk, keep), &neighbours(tg.iter().copied(), gone))
            .into_iter()
            .filter(|x| !far.contains(x))
            .collect();
        for x in extra {
            for (i, t) in tg.iter().enumerate() {
                if let Some(k) = (0..3).find(|&k| t[k] == gone && t[(k + 1) % 3] == x) {
                    if self.flip_with(sg[i], k, true).is_ok() {
                        return Ok(true);
                    }
                }
            }
        }
        Ok(false)
    }

    /// [`Work::flip`]; `unlock`: for [`Work::unlock`], without the gates on the cap's
    /// height and on the triangles' shape.
    fn flip_with(&mut self, t: u32, k: usize, unlock: bool) -> Gate<()> {
        let tri = self.tri(t);
        let (a, b, c) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
        let (sa, sc) = (self.star(a)?, self.star(c)?);
        let on: Vec<u32> = sa
            .iter()
            .copied()
            .filter(|&s| self.tri(s).contains(&b))
            .collect();
        let [x, y] = on[..] else {
            return refuse(Manifold);
        };
        let u = if x == t { y } else { x };
        let ut = self.tri(u);
        let Some(kb) = (0..3).find(|&i| ut[i] == b && ut[(i + 1) % 3] == a) else {
            return refuse(Manifold); // not oriented consistently with `t`
        };
        let dd = ut[(kb + 2) % 3];
        if self.label(t) != self.label(u) {
            return refuse(Seam);
        }
        if dd == c || sc.iter().any(|&s| self.tri(s).contains(&dd)) {
            return refuse(Manifold);
        }
        let (t2, u2) = ([c, a, dd], [dd, b, c]);
        let (pt, pu) = (self.corners(&tri), self.corners(&ut));
        let (pt2, pu2) = (self.corners(&t2), self.corners(&u2));
        // Distance: the cap's height over the flipped edge.
        let (pa, pb, pc) = (self.pos(a), self.pos(b), self.pos(c));
        let height = norm(&cross(&sub(&pb, &pa), &sub(&pc, &pa))) / norm(&sub(&pb, &pa));
        if height >= self.d && !unlock {
            return refuse(Distance);
        }
        if altitude(&pt2).min(altitude(&pu2)) <= altitude(&pt).min(altitude(&pu)) && !unlock {
            return refuse(NoGain);
        }
        // The facing to keep: that of the replaced triangles that are not themselves
        // thinner than the tolerance (a sliver's normal is rounding noise at that
        // scale), or of both when both are.
        let flat = |p: &[[f64; 3]; 3]| normals_dot_sign(p, p) == Sign::Zero;
        if flat(&pt) && flat(&pu) {
            return refuse(Inversion); // nothing to tell which way is up
        }
        let sound: Vec<&[[f64; 3]; 3]> = [&pt, &pu]
            .into_iter()
            .filter(|p| altitude(p) >= self.d)
            .collect();
        let reference = if sound.is_empty() {
            vec![&pt, &pu]
        } else {
            sound
        };
        for new in [&pt2, &pu2] {
            for old in &reference {
                if turns_over(old, new) {
                    return refuse(Inversion);
                }
            }
        }
        let dv =
            (volume6(&pt2, &pa) + volume6(&pu2, &pa) - volume6(&pt, &pa) - volume6(&pu, &pa)) / 6.0;
        self.volume_gate(dv)?;
        self.clear_of(&[t2, u2], &[t, u])?;
        let twice = |p: &[[f64; 3]; 3]| shape(p).2;
        let da = (twice(&pt2) + twice(&pu2) - twice(&pt) - twice(&pu)) / 2.0;
        self.kill(t);
        self.kill(u);
        let made = [self.make(t2, self.slot(t)), self.make(u2, self.slot(u))];
        self.changed(&[a, b, c, dd], &made);
        self.report.flipped += 1;
        self.report.volume_change += dv;
        self.report.area_change += da;
        self.spent += dv.abs();
        Ok(())
    }

    /// A new triangle in the place of input triangle `slot`, indexed; its id.
    fn make(&mut self, tri: [u32; 3], slot: u32) -> u32 {
        let id = self.base + self.made.len() as u32;
        self.made.push(tri);
        self.made_alive.push(true);
        self.made_slot.push(slot);
        self.in_slot.insert(slot, id);
        self.index_later(id);
        id
    }

    /// Indexes triangle `t` after the gathering (in [`Near::later`]).
    fn index_later(&mut self, t: u32) {
        let r = self
            .grid
            .blocks(&self.grid.range(&tri_box(&self.corners(&self.tri(t)))));
        let near = &mut self.near;
        near.later.push(t);
        if Grid::cells(&r) <= Self::FEW_BLOCKS {
            let blocks = &mut near.blocks;
            self.grid
                .all_blocks(&r, |i| blocks.entry(i).or_default().push(t));
        } else {
            near.wide.push(t);
        }
    }

    /// After a change: the stars of the vertices of the new triangles `made` take them in,
    /// the vertices `around` are marked changed, bad new triangles are queued.
    fn changed(&mut self, around: &[u32], made: &[u32]) {
        self.changes += 1;
        for &v in around {
            self.touched.insert(v, self.changes);
        }
        for &m in made {
            for v in self.tri(m) {
                self.touched.insert(v, self.changes);
                // Only vertices whose triangles are all known keep a list (the dead ones
                // in it are dropped when it is read).
                if let Some(s) = self.stars.get_mut(&v) {
                    if !s.contains(&m) {
                        s.push(m);
                    }
                } else if let Ok(mut s) = self.star(v) {
                    if !s.contains(&m) {
                        s.push(m);
                    }
                    self.stars.insert(v, s);
                }
            }
        }
        for &m in made {
            if self.bad_key(m).is_some() {
                self.ever_bad.push(m);
            }
        }
        self.queue(made);
    }

    /// Queues the bad ones of `ts`.
    fn queue(&mut self, ts: &[u32]) {
        for &t in ts {
            if let Some(key) = self.bad_key(t) {
                self.heap.push(Item { key, t });
            }
        }
    }

    /// The report with the bad triangles left, counted by the refusal of their last fix.
    fn finish_report(&mut self) -> SnapReport {
        let mut r = std::mem::take(&mut self.report);
        self.ever_bad.sort_unstable();
        self.ever_bad.dedup();
        for &t in &self.ever_bad {
            if !self.alive(t) || self.bad_key(t).is_none() {
                continue;
            }
            r.left += 1;
            match self.refusal.get(&t) {
                Some(Manifold) => r.refused_manifold += 1,
                Some(Inversion) => r.refused_inversion += 1,
                Some(SelfIntersection) => r.refused_self_intersection += 1,
                Some(Distance) => r.refused_distance += 1,
                Some(Volume) => r.refused_volume += 1,
                Some(Seam) => r.refused_seam += 1,
                Some(NoGain) => r.refused_no_gain += 1,
                None => r.not_reached += 1,
            }
        }
        r
    }

    /// The changes made: dead vertices, slots left empty, slots with a new triangle.
    fn edit(&self) -> Edit {
        let mut dead: Vec<u32> = self.dead.iter().copied().collect();
        dead.sort_unstable();
        let (mut removed, mut replaced) = (Vec::new(), Vec::new());
        for &s in &self.killed_list {
            match self.in_slot.get(&s) {
                Some(&m) if self.alive(m) => replaced.push((s, self.tri(m))),
                _ => removed.push(s),
            }
        }
        removed.sort_unstable();
        Edit {
            dead,
            removed,
            replaced,
        }
    }
}

impl Defects {
    fn plus(self, o: Defects) -> Defects {
        Defects {
            boundary: self.boundary + o.boundary,
            non_manifold: self.non_manifold + o.non_manifold,
            inconsistent: self.inconsistent + o.inconsistent,
        }
    }
}

/// The topology gate of collapsing `gone` onto `keep` within one sheet: `of_keep` are
/// `keep`'s triangles in the sheet, `of_gone` the indices in `sg_tris` (`gone`'s
/// triangles) of those in the sheet. Returns the indices of the sheet's triangles on the
/// edge and their far corners; none where the sheet has `gone` but not `keep` (its
/// triangles there only take `keep`'s name). Refuses what would break the sheet's
/// manifoldness (see [`Work::collapse`]).
fn collapse_topology(
    keep: u32,
    gone: u32,
    of_keep: &[[u32; 3]],
    of_gone: &[usize],
    sg_tris: &[[u32; 3]],
) -> Gate<(Vec<usize>, Vec<u32>)> {
    let on_edge = |tri: &[u32; 3]| tri.contains(&keep);
    let shared: Vec<usize> = of_gone
        .iter()
        .copied()
        .filter(|&i| on_edge(&sg_tris[i]))
        .collect();
    if shared.is_empty() {
        // Both ends in the sheet but no edge between them there: it would be pinched.
        return if of_keep.is_empty() {
            Ok((Vec::new(), Vec::new()))
        } else {
            refuse(Manifold)
        };
    }
    if shared.len() > 2 {
        return refuse(Manifold);
    }
    let runs_keep_gone =
        |tri: &[u32; 3]| (0..3).any(|k| tri[k] == keep && tri[(k + 1) % 3] == gone);
    if shared.len() == 2
        && runs_keep_gone(&sg_tris[shared[0]]) == runs_keep_gone(&sg_tris[shared[1]])
    {
        return refuse(Manifold);
    }
    let mut far: Vec<u32> = shared
        .iter()
        .map(|&i| {
            sg_tris[i]
                .into_iter()
                .find(|&w| w != keep && w != gone)
                .unwrap_or(keep)
        })
        .collect();
    far.sort_unstable();
    if far.windows(2).any(|w| w[0] == w[1]) {
        return refuse(Manifold);
    }
    let sg_sheet: Vec<[u32; 3]> = of_gone.iter().map(|&i| sg_tris[i]).collect();
    let (nk, ng) = (
        neighbours(of_keep.iter().copied(), keep),
        neighbours(sg_sheet.iter().copied(), gone),
    );
    if common(&nk, &ng)[..] != far[..] {
        return refuse(Manifold);
    }
    let uses = |tris: &[[u32; 3]], x: u32| tris.iter().filter(|t| t.contains(&x)).count();
    for &x in &ng {
        let c = uses(&sg_sheet, x);
        // A vertex on a boundary (or a non-manifold edge) moves only along it.
        if c > 2 || (c == 1 && shared.len() == 2) {
            return refuse(Manifold);
        }
    }
    if shared.len() == 1 && uses(&sg_sheet, far[0]) == 1 && uses(of_keep, far[0]) == 1 {
        return refuse(Manifold); // a lone triangle: it would vanish
    }
    let after: Vec<[u32; 3]> = of_keep
        .iter()
        .copied()
        .filter(|t| !t.contains(&gone))
        .chain(
            of_gone
                .iter()
                .filter(|i| !shared.contains(i))
                .map(|&i| sg_tris[i].map(|v| if v == gone { keep } else { v })),
        )
        .collect();
    let before = defects(keep, of_keep, None).plus(defects(gone, &sg_sheet, Some(keep)));
    let now = defects(keep, &after, None);
    if now.boundary > before.boundary
        || now.non_manifold > before.non_manifold
        || now.inconsistent > before.inconsistent
    {
        return refuse(Manifold);
    }
    let mut sets: Vec<[u32; 3]> = after
        .iter()
        .map(|t| {
            let mut s = *t;
            s.sort_unstable();
            s
        })
        .collect();
    sets.sort_unstable();
    if sets.windows(2).any(|w| w[0] == w[1]) || fans(keep, &after) != 1 {
        return refuse(Manifold);
    }
    Ok((shared, far))
}

/// Whether a triangle with corners `old` turns over (or becomes degenerate) when its
/// corners become `new`: the new normal is zero, or at a right angle or more to the old
/// one (exact signs). A degenerate `old` has no side to keep: only the first test applies.
fn turns_over(old: &[[f64; 3]; 3], new: &[[f64; 3]; 3]) -> bool {
    if normals_dot_sign(new, new) == Sign::Zero {
        return true;
    }
    match normals_dot_sign(old, new) {
        Sign::Positive => false,
        Sign::Negative => true,
        Sign::Zero => normals_dot_sign(old, old) != Sign::Zero,
    }
}

/// Vertex or triangle ids around one vertex (its star, its neighbours): held inline up
/// to 16, almost always enough, so that the many small lists of the clean-ups do not each
/// go to the allocator.
pub(crate) type Ids = smallvec::SmallVec<[u32; 16]>;

/// The neighbours of `v` in the triangles `star` (all containing `v`), sorted.
pub(crate) fn neighbours(star: impl IntoIterator<Item = [u32; 3]>, v: u32) -> Ids {
    let mut n: Ids = star.into_iter().flatten().filter(|&x| x != v).collect();
    n.sort_unstable();
    n.dedup();
    n
}

/// The elements of sorted `a` that are in sorted `b`.
pub(crate) fn common(a: &[u32], b: &[u32]) -> Ids {
    a.iter()
        .copied()
        .filter(|x| b.binary_search(x).is_ok())
        .collect()
}

/// The kinds of the edges at `v` in the triangles `star` (all containing `v`), leaving
/// out the edge to `skip`.
fn defects(v: u32, star: &[[u32; 3]], skip: Option<u32>) -> Defects {
    // (other end, uses v -> other, uses other -> v).
    let mut uses: Vec<(u32, usize, usize)> = Vec::new();
    let mut add = |x: u32, forward: bool| {
        if Some(x) == skip || x == v {
            return;
        }
        let i = match uses.iter().position(|u| u.0 == x) {
            Some(i) => i,
            None => {
                uses.push((x, 0, 0));
                uses.len() - 1
            }
        };
        if forward {
            uses[i].1 += 1;
        } else {
            uses[i].2 += 1;
        }
    };
    for t in star {
        for k in 0..3 {
            if t[k] == v {
                add(t[(k + 1) % 3], true);
                add(t[(k + 2) % 3], false);
            }
        }
    }
    let mut d = Defects::default();
    for (_, f, b) in uses {
        match (f, b) {
            (1, 0) | (0, 1) => d.boundary += 1,
            (1, 1) => {}
            (f, b) if f + b == 2 => d.inconsistent += 1,
            _ => d.non_manifold += 1,
        }
    }
    d
}

/// The number of fans the triangles `star` (all containing `v`) form around `v`:
/// triangles sharing an edge at `v` are in one fan.
fn fans(v: u32, star: &[[u32; 3]]) -> usize {
    let n = star.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    let others: Vec<[u32; 3]> = star
        .iter()
        .map(|t| t.map(|w| if w == v { u32::MAX } else { w }))
        .collect();
    for i in 0..n {
        for j in i + 1..n {
            if others[i]
                .iter()
                .any(|&x| x != u32::MAX && others[j].contains(&x))
            {
                let (a, b) = (root(&mut parent, i), root(&mut parent, j));
                parent[a] = b;
            }
        }
    }
    (0..n).filter(|&i| root(&mut parent, i) == i).count()
}

#[cfg(test)]
mod tests;
