//! Operands: meshes checked at the door. A boolean needs to know inside from outside; an
//! operand is a valid, exactly welded mesh with what its checks found (orientation,
//! manifoldness, self-intersections), refused when inside/outside would be ambiguous
//! unless the caller forces it.

use std::borrow::Cow;
use std::path::Path;
use web_time::Instant;

use serde::{Deserialize, Serialize};

use super::RunOptions;
use crate::boolean::{resolve, FillRule, PipelineOptions, ResolveReport, Stage};
use crate::edges::{EdgeCounts, EdgeKind};
use crate::intersect::self_intersections;
use crate::kept::Keeps;
use crate::par;
use crate::par::with_threads_for;
use crate::{weld_exact, Error, Mesh, Result};

/// What to check of an operand, and what to do when a check finds a problem.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Checks {
    /// Count inconsistently oriented and non-manifold edges (linear time).
    pub edges: bool,
    /// Look for self-intersecting triangle pairs (exact; on large meshes it costs about as
    /// much as the boolean). Turn off only for inputs known to be clean: the report then
    /// says they were not checked.
    pub self_intersections: bool,
    /// Make an operand whose triangles are not consistently oriented consistent at the
    /// door, each component facing as most of its triangles do
    /// ([`crate::repair::orient`], majority), where that makes every edge consistent.
    /// Needs `edges`. Off: inconsistent edges are a problem.
    pub orient: bool,
    /// Resolve a self-intersecting operand made of closed, consistently oriented
    /// components into the solid it encloses (fill rule positive: the union of its
    /// overlapping parts, a self-crossing part cut along its own seam; see
    /// [`super::resolve()`]). Also an operand whose closed parts are glued along edges of
    /// more than two triangles (parts sharing an edge, a part given twice): its triangles
    /// are paired into closed sheets first, which are resolved as parts that touch or
    /// overlap. Needs `self_intersections` (and `edges` for glued parts). Off:
    /// self-intersections and non-manifold edges are a problem.
    pub resolve: bool,
    /// Proceed when a check finds a problem, taking the input as given; the problems are
    /// listed in the report's `assumed`. Without it they are an [`Error::Operand`].
    pub force: bool,
    /// Positions that differ by rounding are one vertex: boundary vertices within
    /// [`ROUNDING_ULPS`] units in the last place of the mesh's largest coordinate (in the
    /// precision the file stores: `f32` for binary STL, else `f64`) of one another are
    /// merged, where that opens no edge and makes none non-manifold or inconsistent
    /// (it closes cracks, and corners laid on corners become shared; [`NoiseMerge`]). Off: only exactly equal positions are one vertex.
    /// Needs `edges`.
    pub rounding_noise: bool,
}

/// Units in the last place of a mesh's largest coordinate within which boundary
/// positions are taken as one vertex ([`Checks::rounding_noise`]): writers that round
/// each corner on its own (binary STL's `f32`, text with few digits of a computed `f64`)
/// leave cracks of a unit or two.
pub const ROUNDING_ULPS: f64 = 4.0;

/// What [`Checks::rounding_noise`] merged.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NoiseMerge {
    /// Boundary vertices merged into another.
    pub vertices: usize,
    /// The distance they were merged within (a 3D distance).
    pub tolerance: f64,
    /// The precision the tolerance is counted in: `f32` or `f64`.
    pub precision: &'static str,
    /// Boundary edges before and after.
    pub boundary_edges: [usize; 2],
}

impl Default for Checks {
    /// Every check, nothing forced.
    fn default() -> Self {
        Checks {
            edges: true,
            self_intersections: true,
            orient: true,
            resolve: true,
            force: false,
            rounding_noise: true,
        }
    }
}

impl Checks {
    /// No checks (the mesh is still validated and welded): for operations that do not
    /// depend on inside and outside, such as intersection curves.
    pub const NONE: Checks = Checks {
        edges: false,
        self_intersections: false,
        orient: false,
        resolve: false,
        force: true,
        rounding_noise: false,
    };
}

/// What the checks found in an operand.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OperandReport {
    /// The operand's name: its file, or `A` / `B`.
    pub name: String,
    /// Triangles.
    pub triangles: usize,
    /// Vertices after the exact weld.
    pub vertices: usize,
    /// Triangles with two equal corners once the positions are welded (corners that were
    /// distinct vertices at one position, or repeated indices), removed at the door:
    /// they have no area, and every edge they use they use once each way, so the rest
    /// stays as closed as it was. 0 when none, or when edges are not checked
    /// ([`Checks::edges`]). Triangle ids in reports and provenance still name the input's.
    pub collapsed_triangles: usize,
    /// Boundary vertices merged as rounding noise ([`Checks::rounding_noise`]); `None`
    /// when none were.
    pub rounding_noise: Option<NoiseMerge>,
    /// Edges used twice in the same direction in the input; `None`: not checked.
    pub inconsistent_edges: Option<usize>,
    /// The midpoint of the first edge used twice in the same direction (in the order of
    /// the vertices), to find them, when some are left: not made consistent at the door.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub inconsistent_near: Option<[f64; 3]>,
    /// Triangles reversed at the door to make the orientation consistent (each component
    /// facing as most of its triangles did; [`Checks::orient`]); 0 when none.
    pub reoriented_triangles: usize,
    /// Where orienting was tried and could not make every edge consistent: the edges
    /// still inconsistent once each component faces as most of its triangles did (a
    /// one-sided, non-orientable part, as a twisted strip of triangles makes: no
    /// orientation has an inside there); 0 when none or not tried.
    pub one_sided_edges: usize,
    /// Edges used by more than two triangles in the input; `None`: not checked. Not a
    /// problem when the operand was resolved ([`OperandReport::resolved`] says how).
    pub non_manifold_edges: Option<usize>,
    /// The midpoint of the first edge of more than two triangles (in the order of the
    /// vertices), to find them, when there are any and the operand was not resolved.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub non_manifold_near: Option<[f64; 3]>,
    /// Self-intersecting triangle pairs; `None`: not checked.
    pub self_intersections: Option<SelfIntersections>,
    /// Closed components that faced inward without enclosing anything (inside out, as
    /// written with the other winding convention) and were reversed at the door
    /// ([`crate::repair::inside_out`]); 0 when none or not checked (an open or
    /// inconsistent operand, or [`Checks::edges`] off).
    pub reversed_components: usize,
    /// How the operand was resolved into the solid its overlapping parts enclose
    /// ([`Checks::resolve`]); `None`: it was not (no self-intersections, or not asked).
    pub resolved: Option<ResolveReport>,
    /// Signed volume of the operand as it enters the boolean: after the orientation, the
    /// inside-out reversal and the resolve at the door (meaningful for a closed operand
    /// only). The volume identities hold for it: vol(A ∪ B) + vol(A ∩ B) = vol(A) + vol(B)
    /// with these volumes.
    pub volume: f64,
    /// For an operand with problems and boundary edges: the smallest weld distance tried
    /// (1e-9 to 1e-4 of its diagonal, by steps of about 3) at which its boundary
    /// vertices merge and no boundary edge is left, the cracks being near-equal
    /// coordinates rather than holes (`meshbool repair --weld D` closes them); `None`
    /// when no such distance was found, or not looked for (no problem, no boundary).
    pub closes_at_weld: Option<f64>,
    /// True when problems were found and taken as given ([`Checks::force`]).
    pub forced: bool,
}

/// The self-intersections found in an operand.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SelfIntersections {
    /// Pairs of triangles that meet other than in shared vertices and edges.
    pub pairs: usize,
    /// The first pair (triangle ids of the welded mesh), if any.
    pub first: Option<[u32; 2]>,
    /// The centroid of the first pair's first triangle, to find it.
    pub near: Option<[f64; 3]>,
    /// Why they could not be resolved ([`Checks::resolve`]), if that was tried and failed.
    pub unresolved: Option<String>,
    /// True when every pair is of triangles of open parts (components with boundary
    /// edges), no small weld closes the boundary (then it is a cracked solid:
    /// [`OperandReport::closes_at_weld`]), and they were taken as given rather than
    /// refused: an open surface has no
    /// inside of its own to resolve, its pieces are classified against the other operand
    /// as usual, and the other operand's pieces against the sum of its sheets (the
    /// winding number, defined wherever the surface crosses itself).
    pub open_kept: bool,
}

impl OperandReport {
    /// Multiplies the report's coordinates (the `near` point of a self-intersection) by
    /// `2^e`, for a computation done at unit size.
    pub(crate) fn scale_back(&mut self, e: i32) {
        if let Some(near) = self
            .self_intersections
            .as_mut()
            .and_then(|s| s.near.as_mut())
        {
            super::scale_points(std::slice::from_mut(near), e);
        }
        for near in [&mut self.non_manifold_near, &mut self.inconsistent_near]
            .into_iter()
            .flatten()
        {
            super::scale_points(std::slice::from_mut(near), e);
        }
        self.volume = super::scaled_measure(self.volume, e, 3);
    }

    /// What makes inside/outside ambiguous, one phrase each; empty for a clean operand.
    pub fn problems(&self) -> Vec<String> {
        let mut problems = Vec::new();
        if let (Some(n @ 1..), 0) = (self.inconsistent_edges, self.reoriented_triangles) {
            let near = match self.inconsistent_near {
                Some(p) => format!(" (the first near {p:?})"),
                None => String::new(),
            };
            problems.push(match self.one_sided_edges {
                0 => format!("{n} inconsistently oriented edges{near}"),
                k => format!(
                    "{n} inconsistently oriented edges, {k} of which no orientation makes consistent{near}: the surface is one-sided (non-orientable) there and has no inside"
                ),
            });
        }
        if let (Some(n @ 1..), None) = (self.non_manifold_edges, &self.resolved) {
            problems.push(match self.non_manifold_near {
                Some(p) => format!("{n} non-manifold edges (the first near {p:?})"),
                None => format!("{n} non-manifold edges"),
            });
        }
        if let (
            Some(SelfIntersections {
                pairs,
                first: Some([i, j]),
                near: Some(near),
                unresolved,
                open_kept: false,
            }),
            None,
        ) = (&self.self_intersections, &self.resolved)
        {
            let why = match unresolved {
                Some(why) => format!(" that cannot be resolved: {why}"),
                None => String::new(),
            };
            problems.push(format!(
                "{pairs} self-intersecting triangle pairs (first: triangles {i} and {j}, near {near:?}){why}"
            ));
        }
        if let (Some(d), false) = (self.closes_at_weld, problems.is_empty()) {
            problems.push(format!(
                "its boundary edges close at a weld of {d:e} (`meshbool repair --weld {d:e}`)"
            ));
        }
        problems
    }

    /// What a result built on this operand assumes: checks that were skipped and problems
    /// taken as given, one line each, naming the operand.
    pub fn assumed(&self) -> Vec<String> {
        let mut lines = Vec::new();
        if self.inconsistent_edges.is_none() {
            lines.push(format!(
                "{}: not checked for inconsistent orientation or non-manifold edges",
                self.name
            ));
        }
        if self.self_intersections.is_none() {
            lines.push(format!("{}: not checked for self-intersections", self.name));
        }
        if let Some(n) = &self.rounding_noise {
            lines.push(format!(
                "{}: {} boundary vertices within {ROUNDING_ULPS} {} units in the last place ({:.1e}) of another merged as one vertex (rounding noise): {} boundary edges before, {} after",
                self.name, n.vertices, n.precision, n.tolerance, n.boundary_edges[0], n.boundary_edges[1]
            ));
        }
        if self.collapsed_triangles > 0 {
            lines.push(format!(
                "{}: {} triangles with two equal corners after the exact weld removed (no area; the edges they used are used as before by the rest)",
                self.name, self.collapsed_triangles
            ));
        }
        if self.reoriented_triangles > 0 {
            lines.push(format!(
                "{}: {} inconsistently oriented edges made consistent: {} triangles reversed (each component faces as most of its triangles did)",
                self.name,
                self.inconsistent_edges.unwrap_or(0),
                self.reoriented_triangles
            ));
        }
        if self.reversed_components > 0 {
            lines.push(format!(
                "{}: {} closed components faced inward without enclosing anything (inside out) and were reversed",
                self.name, self.reversed_components
            ));
        }
        if let Some(r) = &self.resolved {
            let how = if r.patches > 0 {
                format!(
                    "cut along its own seam into {} pieces, {} dropped, {} reversed",
                    r.patches, r.patches_dropped, r.patches_flipped
                )
            } else {
                format!(
                    "{} of its {} components united, {} nested ones dropped",
                    r.united_components, r.components, r.dropped_components
                )
            };
            let glued = match r.separated_input.edges_split {
                0 => String::new(),
                n => format!("{n} edges of more than two triangles separated into sheets, "),
            };
            // Nothing left: every part cancelled by another facing the other way.
            let empty = if self.triangles == 0 {
                "; it encloses no volume (its winding number is 0 everywhere off the surface, as where every face is given in both directions: a double-sided surface), so it is empty"
            } else {
                ""
            };
            lines.push(format!(
                "{}: {glued}{} self-intersecting triangle pairs resolved: the operand is the solid it encloses (fill rule positive; {how}){empty}",
                self.name, r.crossing_pairs
            ));
        }
        if let Some(SelfIntersections {
            pairs,
            near: Some(near),
            open_kept: true,
            ..
        }) = &self.self_intersections
        {
            lines.push(format!(
                "{}: {pairs} self-intersecting triangle pairs of its open parts (the first near {near:?}) taken as given: an open surface is not cut along its own crossings; its pieces are classified against the other operand, and the other's pieces by the sum of its sheets there",
                self.name
            ));
        }
        let problems = self.problems();
        if !problems.is_empty() {
            lines.push(format!(
                "{}: {} (input taken as given)",
                self.name,
                problems.join(", ")
            ));
        }
        lines
    }
}

/// A mesh checked for a boolean, split or curves: valid (finite coordinates, indices in
/// range), exactly welded, and either free of what its [`Checks`] look for or forced.
#[derive(Clone, Debug)]
pub struct Operand {
    mesh: Mesh,
    report: OperandReport,
    /// For a resolved operand, the input triangle each triangle of `mesh` is part of.
    parent: Option<Vec<u32>>,
    /// Where collapsed triangles were removed ([`OperandReport::collapsed_triangles`]):
    /// the input triangle of each triangle of the mesh that orientation and resolve then
    /// took.
    kept: Option<Vec<u32>>,
    /// Input triangles reversed at the door (orientation made consistent, inside-out
    /// components), sorted.
    reversed: Vec<u32>,
    /// Whether `mesh` is not manifold (a resolved operand whose parts touch along edges
    /// or at vertices, kept welded there).
    glued: bool,
    /// The whole tree of `mesh`'s triangles, built when a second boolean asks for it and
    /// kept for the later ones.
    keeps: Keeps,
    /// For an operand resolved at the door: the mesh before the resolve (oriented, its
    /// triangles the input's) and its crossing pairs, so that a boolean can resolve and
    /// combine in one exact arrangement rather than take the resolved surface, rounded
    /// to `f64` ([`crate::boolean::nary::boolean_in_one`]).
    unresolved: Option<Unresolved>,
}

/// A self-crossing operand as it was before the resolve: see [`Operand::unresolved`].
#[derive(Clone, Debug)]
pub(crate) struct Unresolved {
    /// The oriented mesh (closed, consistent sheets), triangle ids the input's.
    pub(crate) mesh: Mesh,
    /// Its crossing triangle pairs.
    pub(crate) pairs: Vec<(u32, u32)>,
}

impl Operand {
    /// Checks `mesh` as `checks` say, naming it `name` in reports and errors. Errors:
    /// [`Error::InvalidMesh`] when the mesh breaks the data model, [`Error::Operand`] when
    /// a check finds a problem and `checks.force` is off.
    pub fn new(name: impl Into<String>, mesh: &Mesh, checks: &Checks) -> Result<Operand> {
        mesh.validate()?;
        Operand::checked(name.into(), weld_exact(mesh).mesh, checks, false)
    }

    /// Reads a mesh file ([`super::read`]) and checks it as [`Operand::new`] does, named by
    /// its path. Formats that weld on read are not welded twice.
    pub fn read(path: impl AsRef<Path>, checks: &Checks) -> Result<Operand> {
        let path = path.as_ref();
        let (mesh, format) = super::read(path, None)?;
        let mesh = if format.welds_on_read() {
            mesh
        } else {
            weld_exact(&mesh).mesh
        };
        let f32_stored = format == crate::Format::StlBinary;
        Operand::checked(path.display().to_string(), mesh, checks, f32_stored)
    }

    /// Reads and checks two files side by side ([`Operand::read`]).
    pub fn read_pair(
        a: impl AsRef<Path> + Sync,
        b: impl AsRef<Path> + Sync,
        checks: &Checks,
    ) -> Result<(Operand, Operand)> {
        let (a, b) = par::join(|| Operand::read(&a, checks), || Operand::read(&b, checks));
        Ok((a?, b?))
    }

    /// Checks a valid, welded mesh. A mesh of extreme magnitude (beyond 2^±200) is
    /// checked (and resolved) at unit size and scaled back, as the functions taking meshes
    /// do ([`super::extreme_scale`]); problems are judged on the report scaled back.
    fn checked(name: String, mut mesh: Mesh, checks: &Checks, f32_stored: bool) -> Result<Operand> {
        if let Some(e) = super::extreme_scale(&[&mesh]) {
            super::scale_points(&mut mesh.positions, e);
            let forced = Checks {
                force: true,
                ..*checks
            };
            let mut op = Operand::checked(name, mesh, &forced, f32_stored)?;
            op.scale(-e);
            op.report.forced = false;
            op.report = settle(op.report, checks)?;
            return Ok(op);
        }
        // Triangles with two equal corners (distinct vertices at one position, welded):
        // no area, and every edge they use they use once each way; they would make edges
        // of more than two triangles, so they go, the rest keeping their input ids.
        let input_triangles = mesh.triangles.len();
        let mut kept = if checks.edges {
            without_collapsed(&mut mesh)
        } else {
            None
        };
        // On a large mesh and several threads, the components with negative volume are
        // found beside the edge counts (their parallel parts leave threads idle), used
        // below if the mesh is closed and its orientation stays as it is.
        let (mut found_counts, mut inward) = if checks.edges
            && mesh.triangles.len() >= 1 << 16
            && rayon::current_num_threads() > 2
        {
            let (c, i) = par::join(|| EdgeCounts::of(&mesh), || crate::repair::inward(&mesh));
            (Some(c), Some(i))
        } else {
            (checks.edges.then(|| EdgeCounts::of(&mesh)), None)
        };
        // Positions that differ by rounding are one vertex (boundary vertices only, so
        // only where there are boundary edges); triangles that this collapses go too.
        let mut rounding_noise = None;
        if let Some(before) = found_counts.filter(|c| checks.rounding_noise && c.boundary > 0) {
            if let Some((merge, after)) = merge_rounding_noise(&mut mesh, f32_stored, before) {
                if let Some(more) = without_collapsed(&mut mesh) {
                    kept = Some(match kept {
                        Some(k) => more.iter().map(|&t| k[t as usize]).collect(),
                        None => more,
                    });
                }
                found_counts = Some(after);
                inward = None;
                rounding_noise = Some(merge);
            }
        }
        let to_input = |t: u32| kept.as_ref().map_or(t, |k| k[t as usize]);
        // Triangles reversed at the door (orientation, inside-out components).
        let mut flipped = vec![false; mesh.triangles.len()];
        let mut counts = found_counts;
        let mut reoriented_triangles = 0;
        let mut one_sided = None;
        if checks.orient && found_counts.is_some_and(|c| c.inconsistent > 0) {
            let (oriented, r) = crate::repair::orient(&mesh, crate::repair::Facing::Majority);
            let after = EdgeCounts::of(&oriented);
            // Only where that makes every edge consistent; otherwise the input stays as
            // it is and its inconsistent edges are a problem, located where they are
            // left once oriented.
            if after.inconsistent > 0 {
                one_sided = Some((
                    after.inconsistent,
                    first_edge_near(&oriented, EdgeKind::Inconsistent),
                ));
            }
            if after.inconsistent == 0 {
                for (t, f) in flipped.iter_mut().enumerate() {
                    *f = oriented.triangles[t] != mesh.triangles[t];
                }
                reoriented_triangles = r.flipped;
                mesh = oriented;
                inward = None;
                counts = Some(after);
            }
        }
        let found = checks.self_intersections.then(|| self_intersections(&mesh));
        let mut self_intersections = found.as_ref().map(|found| {
            let first = found.first().map(|&(i, j)| [i, j]);
            SelfIntersections {
                pairs: found.len(),
                first: first.map(|f| f.map(to_input)),
                near: first.map(|[i, _]| mesh.centroid(i as usize)),
                unresolved: None,
                open_kept: false,
            }
        });
        let (mut resolved, mut parent, mut glued_result) = (None, None, false);
        let mut unresolved = None;
        let clean_edges = counts.is_some_and(|c| c.inconsistent == 0 && c.non_manifold == 0);
        // Inside-out closed components are reversed (a closed mesh's inside is where its
        // normals point away from; written the other way round it would be its complement).
        let (reversed, reversed_components) =
            if clean_edges && counts.is_some_and(|c| c.boundary == 0) {
                match inward {
                    Some(inward) => inward.inside_out(&mesh),
                    None => crate::repair::inside_out(&mesh),
                }
            } else {
                (Vec::new(), 0)
            };
        for &t in &reversed {
            mesh.triangles[t as usize].swap(1, 2);
            flipped[t as usize] ^= true;
        }
        // Listed from the flags only where any were set (a scan of every triangle): none
        // is when no triangle was reoriented or reversed.
        let reversed: Vec<u32> = if reoriented_triangles > 0 || !reversed.is_empty() {
            (0..flipped.len() as u32)
                .filter(|&t| flipped[t as usize])
                .map(to_input)
                .collect()
        } else {
            Vec::new()
        };
        // Edges of more than two triangles (closed parts glued along edges, a part given
        // twice) are separated into sheets by the resolve.
        let glued_input = counts.is_some_and(|c| c.inconsistent == 0 && c.non_manifold > 0);
        // Without the self-intersection check (the caller vouches that nothing crosses:
        // cut and fill's curtain solids), glued parts are still separated: resolved with
        // no crossings.
        let vouched = Vec::new();
        let pairs = found
            .as_ref()
            .or((glued_input && checks.resolve).then_some(&vouched));
        if let (Some(found), true, true) = (pairs, checks.resolve, clean_edges || glued_input) {
            if !found.is_empty() || glued_input {
                // Welded where parts touch: a later boolean takes edges of four triangles
                // (it pairs them into sheets on its result), not distinct vertices at
                // one position, which its seam would cut twice.
                let opts = PipelineOptions {
                    keep_nonmanifold: true,
                    ..PipelineOptions::default()
                };
                match resolve(&mesh, found, FillRule::Positive, &opts) {
                    Ok(r) => {
                        glued_result =
                            crate::repair::split_nonmanifold(&r.mesh).1.vertices_added > 0;
                        let before = std::mem::replace(&mut mesh, r.mesh);
                        // Glued parts as the resolve takes them: separated into closed
                        // sheets (triangle ids kept), their crossings found again.
                        unresolved = Some(if glued_input {
                            let sheets = crate::repair::split_nonmanifold(&before).0;
                            let pairs = crate::intersect::self_intersections(&sheets);
                            Unresolved {
                                mesh: sheets,
                                pairs,
                            }
                        } else {
                            Unresolved {
                                mesh: before,
                                pairs: found.clone(),
                            }
                        });
                        parent = Some(r.parent);
                        resolved = Some(r.report);
                    }
                    Err(why) => {
                        if let Some(si) = &mut self_intersections {
                            si.unresolved = Some(why);
                        }
                    }
                }
            }
        }
        // An open surface's own crossings leave no inside ambiguous: taken as given,
        // unless its boundary closes at a small weld (a cracked solid, whose inside the
        // crossings would make ambiguous: refused with the weld that closes it).
        let mut closes = None;
        if let (Some(found), Some(si), None) = (&found, &mut self_intersections, &resolved) {
            if !found.is_empty() && crossings_of_open_parts(&mesh, found) {
                closes = Some(closing_weld(&mesh));
                si.open_kept = closes == Some(None);
            }
        }
        // Resolved triangles' parents named by input ids.
        let parent = match (parent, &kept) {
            (Some(p), Some(_)) => Some(p.into_iter().map(to_input).collect()),
            (p, _) => p,
        };
        let report = OperandReport {
            name,
            collapsed_triangles: input_triangles - kept.as_ref().map_or(input_triangles, Vec::len),
            rounding_noise,
            triangles: mesh.triangles.len(),
            vertices: mesh.positions.len(),
            inconsistent_edges: found_counts.map(|c| c.inconsistent),
            inconsistent_near: match (found_counts, one_sided) {
                (_, Some((_, near))) => near,
                (Some(c), None) if c.inconsistent > 0 && reoriented_triangles == 0 => {
                    first_edge_near(&mesh, EdgeKind::Inconsistent)
                }
                _ => None,
            },
            reoriented_triangles,
            one_sided_edges: one_sided.map_or(0, |(n, _)| n),
            non_manifold_edges: counts.map(|c| c.non_manifold),
            non_manifold_near: match (counts, &resolved) {
                (Some(c), None) if c.non_manifold > 0 => {
                    first_edge_near(&mesh, EdgeKind::NonManifold)
                }
                _ => None,
            },
            self_intersections,
            reversed_components,
            resolved,
            volume: crate::measure::signed_volume(&mesh),
            closes_at_weld: None,
            forced: false,
        };
        let closes_at_weld = match counts {
            Some(c) if c.boundary > 0 && !report.problems().is_empty() => {
                closes.unwrap_or_else(|| closing_weld(&mesh))
            }
            _ => None,
        };
        let report = OperandReport {
            closes_at_weld,
            ..report
        };
        Ok(Operand {
            mesh,
            report: settle(report, checks)?,
            parent,
            reversed,
            glued: glued_result,
            keeps: Keeps::default(),
            unresolved,
            kept,
        })
    }

    /// Multiplies the operand's coordinates by `2^e` (exact for normal numbers): its mesh
    /// and its report's.
    pub(crate) fn scale(&mut self, e: i32) {
        super::scale_points(&mut self.mesh.positions, e);
        if let Some(u) = &mut self.unresolved {
            super::scale_points(&mut u.mesh.positions, e);
        }
        self.report.scale_back(e);
        self.keeps = Keeps::default();
    }

    /// The input triangle of triangle `t` of the mesh as orientation and resolve took it
    /// (the [`Unresolved`] mesh; [`Operand::mesh`] when not resolved): `t` itself unless
    /// collapsed triangles were removed.
    pub(crate) fn unresolved_to_input(&self, t: u32) -> u32 {
        self.kept.as_ref().map_or(t, |k| k[t as usize])
    }

    /// For an operand resolved at the door, the mesh before the resolve and its crossing
    /// pairs ([`Unresolved`]).
    pub(crate) fn unresolved(&self) -> Option<&Unresolved> {
        self.unresolved.as_ref()
    }

    /// What booleans keep of [`Operand::mesh`] between calls.
    pub(crate) fn keeps(&self) -> &Keeps {
        &self.keeps
    }

    /// The input triangle that triangle `t` of [`Operand::mesh`] is part of: `t` itself
    /// unless the operand was resolved or had collapsed triangles removed.
    pub fn input_triangle(&self, t: u32) -> u32 {
        match &self.parent {
            Some(p) => p[t as usize],
            None => self.unresolved_to_input(t),
        }
    }

    /// Whether the checked mesh is not manifold: an operand resolved at the door whose
    /// parts touch along edges or at vertices (kept welded there; a boolean on it splits
    /// its result there too).
    pub(crate) fn glued(&self) -> bool {
        self.glued
    }

    /// Whether no problem was taken as given ([`OperandReport::forced`]): the checked mesh
    /// is valid as far as its checks tell (a skipped check takes it as clean), so that a
    /// boolean may classify by first deciding votes
    /// ([`crate::boolean::PipelineOptions::first_votes`]).
    pub(crate) fn clean(&self) -> bool {
        !self.report.forced
    }

    /// Whether input triangle `t` was reversed at the door (orientation made consistent,
    /// an inside-out component).
    pub fn reversed(&self, t: u32) -> bool {
        self.reversed.binary_search(&t).is_ok()
    }

    /// Rewrites provenance from triangles of the operands' meshes (`a`'s for source A,
    /// `b`'s for B) to the input triangles they are part of, and `flipped` to say whether
    /// the result triangle faces against its input triangle.
    pub(crate) fn to_input_triangles(
        provenance: &mut [crate::boolean::Provenance],
        a: &Operand,
        b: &Operand,
    ) {
        Operand::provenance_to_input(provenance, a, b, Operand::input_triangle);
    }

    /// [`Operand::to_input_triangles`] for provenance that names triangles of the meshes
    /// as orientation and resolve took them ([`Operand::unresolved_to_input`]): a boolean
    /// that resolved and combined in one arrangement.
    pub(crate) fn unresolved_to_input_triangles(
        provenance: &mut [crate::boolean::Provenance],
        a: &Operand,
        b: &Operand,
    ) {
        Operand::provenance_to_input(provenance, a, b, Operand::unresolved_to_input);
    }

    /// Rewrites provenance by `input` (an operand's triangle to its input triangle) and
    /// tells the reversals at the door in `flipped`.
    fn provenance_to_input(
        provenance: &mut [crate::boolean::Provenance],
        a: &Operand,
        b: &Operand,
        input: fn(&Operand, u32) -> u32,
    ) {
        let plain = |o: &Operand| o.parent.is_none() && o.kept.is_none() && o.reversed.is_empty();
        if plain(a) && plain(b) {
            return;
        }
        for p in provenance {
            let o = match p.source {
                crate::Source::A => a,
                crate::Source::B => b,
            };
            p.triangle = input(o, p.triangle);
            p.flipped ^= o.reversed(p.triangle);
        }
    }

    /// The checked, welded mesh (the resolved solid when the operand was resolved: see
    /// [`OperandReport::resolved`] and [`Operand::input_triangle`]).
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// What the checks found.
    pub fn report(&self) -> &OperandReport {
        &self.report
    }

    /// The operand's name.
    pub fn name(&self) -> &str {
        &self.report.name
    }

    /// The welded mesh, giving up the report.
    pub fn into_mesh(self) -> Mesh {
        self.mesh
    }
}

/// Whether both triangles of every pair in `pairs` are in components of `mesh` with
/// boundary edges (open parts): crossings that leave no inside of the mesh's own
/// ambiguous.
fn crossings_of_open_parts(mesh: &Mesh, pairs: &[(u32, u32)]) -> bool {
    let topo = crate::EdgeTopology::new(mesh);
    let (count, component) = topo.components();
    let mut open = vec![false; count];
    for e in 0..topo.edge_count() {
        if topo.kind(e) == EdgeKind::Boundary {
            open[component[topo.uses_of(e)[0].triangle as usize] as usize] = true;
        }
    }
    pairs
        .iter()
        .all(|&(i, j)| open[component[i as usize] as usize] && open[component[j as usize] as usize])
}

/// The smallest of the weld distances 1e-9, 3e-9, 1e-8, ..., 1e-4 times the diagonal of
/// `mesh` (rounded up to one significant digit) at which welding its boundary vertices
/// leaves no boundary edge and no more non-manifold edges than before; `None` if none
/// does.
fn closing_weld(mesh: &Mesh) -> Option<f64> {
    let b = mesh.bounds()?;
    let diag = crate::vec3::norm(&crate::vec3::sub(&b.max, &b.min));
    if !(diag > 0.0 && diag.is_finite()) {
        return None;
    }
    let before = EdgeCounts::of(mesh).non_manifold;
    (-9..=-4)
        .flat_map(|e| [1.0, 3.0].map(|m| m * 10f64.powi(e)))
        .find_map(|k| {
            let d = round_up(k * diag);
            let (welded, _) = crate::repair::weld_boundary(mesh, d);
            let c = EdgeCounts::of(&welded);
            (c.boundary == 0 && c.non_manifold <= before && !welded.triangles.is_empty())
                .then_some(d)
        })
}

/// `x` (> 0) rounded up to one significant digit.
fn round_up(x: f64) -> f64 {
    let p = 10f64.powi(x.log10().floor() as i32);
    let r = (x / p).ceil() * p;
    // The decimal text of one digit, so that it prints as it reads.
    format!("{r:.0e}").parse().unwrap_or(r)
}

/// The midpoint of the first edge of `mesh` of `kind` (edges in the order of their
/// vertices), if any.
fn first_edge_near(mesh: &Mesh, kind: EdgeKind) -> Option<[f64; 3]> {
    let topo = crate::EdgeTopology::new(mesh);
    topo.first_of(kind).map(|e| topo.midpoint(mesh, e))
}

/// Whether a triangle has two equal corners.
fn collapsed(t: &[u32; 3]) -> bool {
    t[0] == t[1] || t[1] == t[2] || t[2] == t[0]
}

/// Merges the boundary vertices of `mesh` (without collapsed triangles; `before` its edge
/// counts) within [`ROUNDING_ULPS`] units in the last place of its largest coordinate
/// (`f32`'s where the file stored `f32`) of one another, where that raises none of the
/// boundary, non-manifold and inconsistent edge counts; triangles keep
/// their places (those that collapse are for the caller to remove). The merge and the
/// edge counts after it (collapsed triangles left out); `None` (and `mesh` as it was)
/// otherwise.
fn merge_rounding_noise(
    mesh: &mut Mesh,
    f32_stored: bool,
    before: EdgeCounts,
) -> Option<(NoiseMerge, EdgeCounts)> {
    merge_rounding_noise_gated(mesh, f32_stored, before, true)
}

/// [`merge_rounding_noise`], with the gate on inconsistent edges only where
/// `keep_consistent` (a caller about to orient the mesh lets the merge join triangles
/// wound against each other: the orientation is its next step).
fn merge_rounding_noise_gated(
    mesh: &mut Mesh,
    f32_stored: bool,
    before: EdgeCounts,
    keep_consistent: bool,
) -> Option<(NoiseMerge, EdgeCounts)> {
    let b = mesh.bounds()?;
    let largest = b.min.iter().chain(&b.max).fold(0f64, |m, x| m.max(x.abs()));
    let (precision, bits) = if f32_stored { ("f32", 23) } else { ("f64", 52) };
    // One unit in the last place of the largest coordinate, at most.
    let ulp = largest * 2f64.powi(-bits);
    let tolerance = ROUNDING_ULPS * ulp;
    if !(tolerance > 0.0 && tolerance.is_finite()) {
        return None;
    }
    let (welded, vertices) = crate::repair::weld_boundary_in_place(mesh, tolerance)?;
    let after = {
        let mut m = welded.clone();
        m.triangles.retain(|t| !collapsed(t));
        EdgeCounts::of(&m)
    };
    // Not worse is enough: corners that touch at rounding level (sheets laid corner to
    // corner) close no edge when merged, but become the touch they are.
    let better = after.boundary <= before.boundary
        && after.non_manifold <= before.non_manifold
        && (!keep_consistent || after.inconsistent <= before.inconsistent);
    if !better {
        return None;
    }
    *mesh = welded;
    let merge = NoiseMerge {
        vertices,
        tolerance,
        precision,
        boundary_edges: [before.boundary, after.boundary],
    };
    Some((merge, after))
}

/// The vertex-identity rule of the operand door on its own, for front ends that take
/// triangle soups (the JavaScript package): positions exactly equal are one vertex, and
/// boundary positions within [`ROUNDING_ULPS`] units in the last place of the largest
/// coordinate (`f64`) of one another are merged where that opens no edge and makes none
/// non-manifold (nor, with `keep_consistent`, inconsistently wound).
/// Triangles keep their places and count; those the merge collapses stay, with two equal
/// corners, for the caller to judge. The welded mesh and the merge, if one was made.
pub fn weld_rounding_noise(mesh: &Mesh, keep_consistent: bool) -> (Mesh, Option<NoiseMerge>) {
    let mut welded = crate::weld_exact(mesh).mesh;
    let mut rest = welded.clone();
    rest.triangles.retain(|t| !collapsed(t));
    let before = EdgeCounts::of(&rest);
    if before.boundary == 0 {
        return (welded, None);
    }
    let merge = merge_rounding_noise_gated(&mut welded, false, before, keep_consistent);
    (welded, merge.map(|(m, _)| m))
}

/// Removes the triangles of `mesh` with two equal corners (indices); `None` when there
/// are none, else the ids of the triangles kept, ascending.
fn without_collapsed(mesh: &mut Mesh) -> Option<Vec<u32>> {
    if !mesh.triangles.iter().any(collapsed) {
        return None;
    }
    let kept: Vec<u32> = (0..mesh.triangles.len() as u32)
        .filter(|&t| !collapsed(&mesh.triangles[t as usize]))
        .collect();
    mesh.triangles.retain(|t| !collapsed(t));
    Some(kept)
}

/// The report with the problems it lists judged: an error unless `checks.force`, which
/// marks the report forced.
fn settle(mut report: OperandReport, checks: &Checks) -> Result<OperandReport> {
    let problems = report.problems();
    if !problems.is_empty() {
        if !checks.force {
            return Err(Error::Operand {
                name: report.name,
                problems,
            });
        }
        report.forced = true;
    }
    Ok(report)
}

/// An input of a function of two meshes: a mesh, checked on the way in, or an operand
/// checked before.
#[derive(Clone, Copy, Debug)]
pub enum Input<'a> {
    /// A mesh, checked with the call's [`Checks`] and named `A` or `B`.
    Mesh(&'a Mesh),
    /// An operand, used as it is.
    Operand(&'a Operand),
}

impl<'a> From<&'a Mesh> for Input<'a> {
    fn from(m: &'a Mesh) -> Self {
        Input::Mesh(m)
    }
}

impl<'a> From<&'a Operand> for Input<'a> {
    fn from(o: &'a Operand) -> Self {
        Input::Operand(o)
    }
}

/// An input scaled by a power of two ([`Input::scaled`]), owned.
pub(crate) enum ScaledInput {
    /// A mesh.
    Mesh(Mesh),
    /// An operand (boxed: an operand carries its report).
    Operand(Box<Operand>),
}

impl ScaledInput {
    /// The scaled input as an input.
    pub(crate) fn input(&self) -> Input<'_> {
        match self {
            ScaledInput::Mesh(m) => Input::Mesh(m),
            ScaledInput::Operand(o) => Input::Operand(o),
        }
    }
}

impl<'a> Input<'a> {
    /// The mesh: the one given, or the operand's checked mesh.
    pub(crate) fn mesh(self) -> &'a Mesh {
        match self {
            Input::Mesh(m) => m,
            Input::Operand(o) => o.mesh(),
        }
    }

    /// A copy with every coordinate multiplied by `2^e` (a computation at unit size).
    pub(crate) fn scaled(self, e: i32) -> ScaledInput {
        match self {
            Input::Mesh(m) => ScaledInput::Mesh(super::scaled_mesh(m, e)),
            Input::Operand(o) => {
                let mut o = o.clone();
                o.scale(e);
                ScaledInput::Operand(Box::new(o))
            }
        }
    }

    /// The input as an operand named `name`: a mesh checked as `checks` say, an operand
    /// as it is.
    pub(crate) fn operand(self, name: &str, checks: &Checks) -> Result<Cow<'a, Operand>> {
        Ok(match self {
            Input::Mesh(m) => Cow::Owned(Operand::new(name, m, checks)?),
            Input::Operand(o) => Cow::Borrowed(o),
        })
    }

    /// Runs `f` on both inputs as operands (`A` and `B`, checked side by side) under
    /// `run`'s threads, with the time `f` took: how every function of two meshes begins.
    pub(crate) fn with_both<R: Send>(
        a: Input<'a>,
        b: Input<'a>,
        checks: &Checks,
        run: &RunOptions,
        f: impl FnOnce(&Operand, &Operand) -> R + Send,
    ) -> Result<(R, f64)> {
        let triangles = a.mesh().triangles.len() + b.mesh().triangles.len();
        with_threads_for(run.threads, triangles, || {
            if matches!(a, Input::Mesh(_)) || matches!(b, Input::Mesh(_)) {
                run.stage(Stage::Check)?;
            }
            let (a, b) = par::join(|| a.operand("A", checks), || b.operand("B", checks));
            let (a, b) = (a?, b?);
            run.check()?;
            let start = Instant::now();
            let r = f(&a, &b);
            // A call cancelled on the way leaves no result.
            run.check()?;
            Ok((r, start.elapsed().as_secs_f64()))
        })?
    }
}
