//! Split-and-pick at the front door: both inputs cut along their intersection into groups
//! (A in B, A out of B, B in A, B out of A, and the coplanar groups), each group into its
//! connected components; any set of pieces, each optionally flipped, merged back into one
//! welded mesh. A split can be written as a directory (one file per group and component
//! and a `manifest.json`, [`SplitReport`]) and picked from there later.

use std::fmt;
use std::path::Path;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use super::{Checks, Input, Operand, OperandReport, RunOptions, SCHEMA};
use crate::boolean::{CleanupReport, Group, Keep, Op, PipelineOptions, Provenance, Stage};
use crate::edges::components_merged;
use crate::measure::{area, mesh_stats, signed_volume, MeshStats};
use crate::repair::{split_nonmanifold, NonManifoldReport, SnapReport};
use crate::{Error, Format, Mesh, Result, Source};

/// Options of [`split`].
#[derive(Clone, Debug, Default)]
pub struct SplitOptions {
    /// Checks of inputs given as meshes.
    pub checks: Checks,
    /// Components of fewer triangles than this are merged into the nearest larger
    /// component of their group (stray fragments); 0 keeps every component.
    pub merge_small: usize,
    /// Snap tolerance `D` (a length; 0, the default: the exact split): with `D > 0` the
    /// groups are cleaned together where the split cut, as a boolean's result is
    /// ([`super::BooleanOptions::snap`]), so that they stay conforming: a pick of any
    /// set of them is closed where the exact pick is.
    pub snap: f64,
    /// Keep every seam point of the exact arrangement. Off (the default), the groups are
    /// cleaned together: seam points where the seam runs straight through flat faces of
    /// both meshes go (one collapse in all four groups), and zero-area triangles that
    /// rounding made flip within their group; no group changes shape and the groups stay
    /// conforming. As a boolean's [`super::BooleanOptions::keep_seam_points`].
    pub keep_seam_points: bool,
    /// Interior points for large triangles cut by a dense seam, as a boolean's
    /// [`super::BooleanOptions::sliver_guard`].
    pub sliver_guard: bool,
    /// Cut coplanar overlaps along every edge of either input that crosses them, as a
    /// boolean's [`super::BooleanOptions::coplanar_refinement`].
    pub coplanar_refinement: bool,
    /// Threads and progress.
    pub run: RunOptions,
}

/// One non-empty group of a split, with its connected components.
#[derive(Clone, Debug)]
pub struct GroupPieces {
    /// Which group.
    pub group: Group,
    /// The group's triangles (vertices compacted; seam vertices bit-identical to the other
    /// groups').
    pub mesh: Mesh,
    /// The origin of every triangle of `mesh`.
    pub provenance: Vec<Provenance>,
    /// The connected components, largest first, each its own mesh; empty when the group is
    /// one component (the group's mesh is then its component 0).
    pub components: Vec<Mesh>,
    /// Small components merged into larger ones ([`SplitOptions::merge_small`]).
    pub merged_small: usize,
}

/// The result of [`split`].
#[derive(Clone, Debug)]
pub struct SplitOutput {
    /// What the checks found in A and B.
    pub operands: [OperandReport; 2],
    /// Points of the intersection curves.
    pub seam_points: usize,
    /// The non-empty groups, in the order of [`Group::ALL`].
    pub groups: Vec<GroupPieces>,
    /// What snapping did ([`SplitOptions::snap`]); `None` without it.
    pub snap: Option<SnapReport>,
    /// What the exact clean-up did (all zero with [`SplitOptions::keep_seam_points`] or
    /// a snap tolerance, which cleans instead).
    pub cleanup: CleanupReport,
    /// Time of the split and the components, in seconds.
    pub seconds: f64,
}

/// A group's mesh or one of its components, in a [`SplitReport`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PieceInfo {
    /// The file it is written to, relative to the split's directory.
    pub file: String,
    /// Triangles.
    pub triangles: usize,
    /// Surface area.
    pub area: f64,
    /// Signed volume (of an open piece: relative to the piece's own box centre).
    pub volume: f64,
}

/// A group in a [`SplitReport`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GroupInfo {
    /// The group (`a_in_b`, ...).
    pub name: Group,
    /// The whole group.
    #[serde(flatten)]
    pub piece: PieceInfo,
    /// Its components, largest first; empty when it is one component.
    pub components: Vec<PieceInfo>,
    /// Small components merged into larger ones.
    #[serde(default)]
    pub merged_small_components: usize,
}

/// What a split holds: the JSON of `meshbool split --json`, and the `manifest.json` of a
/// split's directory.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SplitReport {
    /// [`SCHEMA`] (0 in manifests written before reports had a version).
    #[serde(default)]
    pub schema: u32,
    /// The name of A (its file).
    pub a: String,
    /// The name of B.
    pub b: String,
    /// Points of the intersection curves.
    pub seam_points: usize,
    /// The non-empty groups.
    pub groups: Vec<GroupInfo>,
    /// What the split assumes (skipped checks, problems taken as given), one line each.
    #[serde(default)]
    pub assumed: Vec<String>,
    /// What snapping did (only with a snap tolerance).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub snap: Option<SnapReport>,
    /// What the exact clean-up did ([`SplitOutput::cleanup`]).
    #[serde(default)]
    pub cleanup: CleanupReport,
}

/// Splits `a` and `b` along their intersection into groups and components. Inputs as for
/// [`super::boolean`].
pub fn split<'a>(
    a: impl Into<Input<'a>>,
    b: impl Into<Input<'a>>,
    opts: &SplitOptions,
) -> Result<SplitOutput> {
    let (a, b): (Input<'a>, Input<'a>) = (a.into(), b.into());
    crate::repair::check_tolerance(opts.snap)?;
    // At unit size the tolerance is scaled as the meshes are.
    let to_unit = (opts.snap > 0.0)
        .then(|| super::extreme_scale(&[a.mesh(), b.mesh()]))
        .flatten();
    let unit_opts = SplitOptions {
        snap: super::scaled(opts.snap, to_unit.unwrap_or(0)).min(f64::MAX),
        ..opts.clone()
    };
    let unit = |a: Input<'_>, b: Input<'_>| split(a, b, &unit_opts);
    if let Some(out) = super::at_unit_scale(a, b, unit, SplitOutput::scale_back) {
        return out;
    }
    let run = |a: &Operand, b: &Operand| {
        let pipeline = PipelineOptions {
            kept: [Some(a.keeps()), Some(b.keeps())],
            first_votes: a.clean() && b.clean(),
            sliver_guard: opts.sliver_guard,
            coplanar_refinement: opts.coplanar_refinement,
            ..opts.run.pipeline()
        };
        let s = crate::boolean::split(a.mesh(), b.mesh(), &pipeline);
        let (exact, snap, cleanup) = if opts.snap > 0.0 && !opts.run.cancelled() {
            opts.run.report(Stage::Snap);
            // The tolerance was checked above: never an error here.
            match crate::boolean::snap_split(&s, opts.snap) {
                Ok((groups, report)) => (groups, Some(report), CleanupReport::default()),
                Err(_) => (Vec::new(), None, CleanupReport::default()),
            }
        } else {
            opts.run.report(Stage::Merge);
            let (groups, cleanup) = s.groups(a.mesh(), b.mesh(), !opts.keep_seam_points);
            (groups, None, cleanup)
        };
        let groups = exact
            .into_iter()
            .filter(|(_, mesh, _)| !mesh.is_empty())
            .map(|(group, mesh, mut provenance)| {
                // An operand resolved at the door whose parts touch along an edge or at a
                // vertex stays welded there: its groups are split into edge-manifold
                // sheets (triangle order kept).
                let glued = match group.side_and_class().0 {
                    Source::A => a.glued(),
                    Source::B => b.glued(),
                };
                let mesh = if glued {
                    split_nonmanifold(&mesh).0
                } else {
                    mesh
                };
                Operand::to_input_triangles(&mut provenance, a, b);
                group_pieces(group, mesh, provenance, opts.merge_small)
            })
            .collect();
        (
            s.seam.points.len(),
            groups,
            (snap, cleanup),
            [a.report().clone(), b.report().clone()],
        )
    };
    let ((seam_points, groups, (snap, cleanup), operands), seconds) =
        Input::with_both(a, b, &opts.checks, &opts.run, run)?;
    Ok(SplitOutput {
        operands,
        seam_points,
        groups,
        snap,
        cleanup,
        seconds,
    })
}

/// A group's mesh with its components.
fn group_pieces(
    group: Group,
    mesh: Mesh,
    provenance: Vec<Provenance>,
    merge_small: usize,
) -> GroupPieces {
    let parts = components_merged(&mesh, merge_small);
    let components = if parts.parts.len() > 1 {
        parts.parts.iter().map(|part| mesh.subset(part)).collect()
    } else {
        Vec::new()
    };
    GroupPieces {
        group,
        mesh,
        provenance,
        components,
        merged_small: parts.merged,
    }
}

fn piece_info(file: String, m: &Mesh) -> PieceInfo {
    PieceInfo {
        file,
        triangles: m.triangles.len(),
        area: area(m),
        volume: signed_volume(m),
    }
}

impl SplitOutput {
    /// Multiplies the output's coordinates by `2^e` (for a computation done at unit size).
    fn scale_back(&mut self, e: i32) {
        for g in &mut self.groups {
            super::scale_points(&mut g.mesh.positions, e);
            for c in &mut g.components {
                super::scale_points(&mut c.positions, e);
            }
        }
        for o in &mut self.operands {
            o.scale_back(e);
        }
        if let Some(s) = &mut self.snap {
            s.scale_back(e);
        }
    }

    /// What the split holds, with the file names [`SplitOutput::write_dir`] gives the
    /// pieces in `format`.
    pub fn report(&self, format: Format) -> SplitReport {
        let ext = format.extension();
        SplitReport {
            schema: SCHEMA,
            a: self.operands[0].name.clone(),
            b: self.operands[1].name.clone(),
            seam_points: self.seam_points,
            groups: self
                .groups
                .iter()
                .map(|g| GroupInfo {
                    name: g.group,
                    piece: piece_info(format!("{}.{ext}", g.group), &g.mesh),
                    components: g
                        .components
                        .iter()
                        .enumerate()
                        .map(|(k, c)| piece_info(format!("{}.{k}.{ext}", g.group), c))
                        .collect(),
                    merged_small_components: g.merged_small,
                })
                .collect(),
            assumed: self.operands.iter().flat_map(|o| o.assumed()).collect(),
            snap: self.snap.clone(),
            cleanup: self.cleanup,
        }
    }

    /// Writes every group and component to `dir` (created if needed) in `format`, then
    /// `manifest.json` (the returned report). Each file is written whole or not at all;
    /// an earlier manifest is removed first and the new one written last, so a directory
    /// with a manifest always holds the pieces it lists.
    pub fn write_dir(&self, dir: impl AsRef<Path>, format: Format) -> Result<SplitReport> {
        let dir = dir.as_ref();
        std::fs::create_dir_all(dir).map_err(|e| Error::from(e).in_file("creating", dir))?;
        let manifest = dir.join("manifest.json");
        match std::fs::remove_file(&manifest) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                return Err(Error::from(e).in_file("removing the earlier", &manifest))
            }
            _ => {}
        }
        let report = self.report(format);
        for (g, info) in self.groups.iter().zip(&report.groups) {
            super::write(dir.join(&info.piece.file), &g.mesh, Some(format))?;
            for (c, ci) in g.components.iter().zip(&info.components) {
                super::write(dir.join(&ci.file), c, Some(format))?;
            }
        }
        let text = serde_json::to_string_pretty(&report)
            .map_err(|e| Error::InvalidParameter(e.to_string()))?;
        crate::io::write_bytes(&manifest, text.as_bytes())?;
        Ok(report)
    }

    /// The boolean `op` of the split's inputs from its pieces ([`PieceSpec::for_op`]).
    pub fn pick_op(&self, op: Op, opts: &PickOptions) -> Result<PickOutput> {
        let specs: Vec<PieceSpec> = PieceSpec::for_op(op)
            .into_iter()
            .filter(|s| self.groups.iter().any(|g| g.group == s.group))
            .collect();
        self.pick(&specs, opts)
    }

    /// Merges the pieces `specs` names, each flipped where it says so, into one welded
    /// mesh ([`pick`]). A piece may be named once.
    pub fn pick(&self, specs: &[PieceSpec], opts: &PickOptions) -> Result<PickOutput> {
        let pieces = resolve(specs, |group| {
            let g = self.groups.iter().find(|g| g.group == group)?;
            Some((&g.mesh, &g.components[..]))
        })?;
        pick(&pieces, opts)
    }
}

/// The pieces `specs` name, with their flips: `lookup` gives a group's whole piece and its
/// components (empty when the group is one component, which is then its component 0).
/// Refuses a group not in the split, a component out of range, and a list naming a piece
/// twice or a group and one of its components (their triangles would be doubled).
fn resolve<'g, T>(
    specs: &[PieceSpec],
    lookup: impl Fn(Group) -> Option<(&'g T, &'g [T])>,
) -> Result<Vec<(&'g T, bool)>> {
    let mut taken: Vec<(Group, Option<usize>, &PieceSpec)> = Vec::new();
    let mut pieces = Vec::new();
    for spec in specs {
        let (whole, components) = lookup(spec.group).ok_or_else(|| {
            Error::InvalidParameter(format!(
                "{:?}: no group {:?} in this split",
                spec.to_string(),
                spec.group.name()
            ))
        })?;
        // The component a spec names, `None` for the whole group.
        let key = spec.component.filter(|_| !components.is_empty());
        let piece = match key {
            None if spec.component.unwrap_or(0) == 0 => whole,
            None => return Err(few_components(spec, 1)),
            Some(k) => components
                .get(k)
                .ok_or_else(|| few_components(spec, components.len()))?,
        };
        if let Some((_, _, earlier)) = taken
            .iter()
            .find(|(g, k, _)| *g == spec.group && (*k == key || k.is_none() || key.is_none()))
        {
            return Err(Error::InvalidParameter(format!(
                "{:?} overlaps {:?}: a piece may be picked once",
                spec.to_string(),
                earlier.to_string()
            )));
        }
        taken.push((spec.group, key, spec));
        pieces.push((piece, spec.flip));
    }
    Ok(pieces)
}

fn few_components(spec: &PieceSpec, n: usize) -> Error {
    Error::InvalidParameter(format!(
        "{:?}: group {} has {} components",
        spec.to_string(),
        spec.group,
        n
    ))
}

/// A piece of a split to keep: a group, optionally one of its components, optionally
/// flipped. Written `GROUP[#COMPONENT][:flip]`, e.g. `a_out_b`, `a_in_b#2`, `b_in_a:flip`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PieceSpec {
    /// The group.
    pub group: Group,
    /// A component of the group (largest first); `None`: the whole group.
    pub component: Option<usize>,
    /// Reverse the piece's orientation.
    pub flip: bool,
}

impl PieceSpec {
    /// The pieces the boolean `op` keeps, by its [`Op::rule`]: whole groups, the
    /// subtrahend's inside flipped, one copy of shared faces. Picking them (those the
    /// split has) gives the boolean's result (the reference's `mergeSplitGroups`).
    pub fn for_op(op: Op) -> Vec<PieceSpec> {
        let rule = op.rule();
        Group::ALL
            .into_iter()
            .filter_map(|group| {
                let (side, class) = group.side_and_class();
                let keep = match side {
                    crate::Source::A => rule.a.of(class),
                    crate::Source::B => rule.b.of(class),
                };
                (keep != Keep::Drop).then_some(PieceSpec {
                    group,
                    component: None,
                    flip: keep == Keep::Flipped,
                })
            })
            .collect()
    }
}

impl fmt::Display for PieceSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.group)?;
        if let Some(k) = self.component {
            write!(f, "#{k}")?;
        }
        if self.flip {
            f.write_str(":flip")?;
        }
        Ok(())
    }
}

impl FromStr for PieceSpec {
    type Err = Error;

    fn from_str(spec: &str) -> Result<Self> {
        let (body, flip) = match spec.strip_suffix(":flip") {
            Some(b) => (b, true),
            None => (spec, false),
        };
        let (name, component) =
            match body.split_once('#') {
                Some((n, c)) => (
                    n,
                    Some(c.parse::<usize>().map_err(|_| {
                        Error::InvalidParameter(format!("bad component in {spec:?}"))
                    })?),
                ),
                None => (body, None),
            };
        let group = name.parse::<Group>().map_err(|_| {
            Error::InvalidParameter(format!(
                "{spec:?}: no group {name:?} (groups: {})",
                Group::ALL.map(Group::name).join(", ")
            ))
        })?;
        Ok(PieceSpec {
            group,
            component,
            flip,
        })
    }
}

/// Options of a pick.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PickOptions {
    /// Keep the merged mesh's topology where it is not manifold (pieces touching along an
    /// edge or at a vertex then share it). By default such edges and vertices are split
    /// ([`crate::repair::split_nonmanifold`]; positions unchanged).
    pub keep_nonmanifold: bool,
    /// Snap tolerance `D` (a length; 0, the default: the pieces as they are): with
    /// `D > 0` the merged mesh is cleaned where its pieces meet, as a boolean's result is
    /// ([`super::BooleanOptions::snap`]): the bad triangles with a corner shared by two
    /// pieces, no edge between two pieces flipped. (A split snapped with
    /// [`SplitOptions::snap`] has clean pieces already.)
    pub snap: f64,
}

/// The result of a pick: one welded mesh.
#[derive(Clone, Debug)]
pub struct PickOutput {
    /// The merged pieces, exactly equal positions welded, unreferenced vertices dropped,
    /// non-manifold edges and vertices split unless asked otherwise.
    pub mesh: Mesh,
    /// Where the merged mesh was not manifold and was split.
    pub nonmanifold: NonManifoldReport,
    /// Triangles removed because welding gave them two equal corners: where two seam
    /// points of the exact intersection are distinct but round to one `f64` point, a
    /// sliver between them has no area left once the pieces are welded (it would pinch
    /// its two other edges into one, used four times).
    pub collapsed_by_weld: usize,
    /// What snapping did ([`PickOptions::snap`]); `None` without it.
    pub snap: Option<SnapReport>,
}

/// The JSON of `meshbool pick --json`: the merged mesh's measures.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PickReport {
    /// [`SCHEMA`].
    pub schema: u32,
    /// Every measure of the result ([`mesh_stats`]).
    #[serde(flatten)]
    pub stats: MeshStats,
    /// Where the merged mesh was not manifold and was split.
    pub split_nonmanifold: NonManifoldReport,
    /// Triangles removed because welding gave them two equal corners
    /// ([`PickOutput::collapsed_by_weld`]).
    pub collapsed_by_weld: usize,
    /// What snapping did (only with a snap tolerance).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub snap: Option<SnapReport>,
}

impl PickOutput {
    /// The report: every measure of the merged mesh.
    pub fn report(&self) -> PickReport {
        PickReport {
            schema: SCHEMA,
            stats: mesh_stats(&self.mesh),
            split_nonmanifold: self.nonmanifold.clone(),
            collapsed_by_weld: self.collapsed_by_weld,
            snap: self.snap.clone(),
        }
    }
}

/// Merges meshes into one, each flipped where its flag says, welding exactly equal
/// positions: the "pick" of split-and-pick (pieces of one split share their seam vertices
/// bit for bit). Where the pieces touch along an edge or at a vertex, the merged mesh is
/// made manifold unless `opts` says otherwise.
/// Errors when a piece has non-finite coordinates, or all together more than
/// `u32::MAX` vertices; a bad snap tolerance.
pub fn pick(pieces: &[(&Mesh, bool)], opts: &PickOptions) -> Result<PickOutput> {
    crate::repair::check_tolerance(opts.snap)?;
    for (m, _) in pieces {
        m.validate()?;
    }
    let mut mesh = crate::boolean::pick(pieces)?;
    // Triangles keep their order through the weld and the split: piece by piece.
    let mut labels = Vec::with_capacity(mesh.triangles.len());
    for (k, (m, _)) in pieces.iter().enumerate() {
        labels.extend(std::iter::repeat_n(k as u32, m.triangles.len()));
    }
    let pinched: Vec<u32> = (0..mesh.triangles.len() as u32)
        .filter(|&t| {
            let [a, b, c] = mesh.triangles[t as usize];
            a == b || b == c || c == a
        })
        .collect();
    if !pinched.is_empty() {
        crate::mesh_edit::remove_sorted(&mut mesh.triangles, &pinched);
        crate::mesh_edit::remove_sorted(&mut labels, &pinched);
        mesh = mesh.without_unreferenced().0;
    }
    let (mut mesh, nonmanifold) = if opts.keep_nonmanifold {
        (mesh, NonManifoldReport::default())
    } else {
        split_nonmanifold(&mesh)
    };
    let snap = (opts.snap > 0.0).then(|| snap_pieces(&mut mesh, &labels, opts.snap));
    Ok(PickOutput {
        mesh,
        nonmanifold,
        collapsed_by_weld: pinched.len(),
        snap,
    })
}

/// Snaps a mesh of pieces (`labels`: each triangle's piece) at `tolerance` where pieces
/// meet: the vertices of triangles of two pieces are its seam. At unit size where the
/// mesh is of extreme magnitude ([`super::extreme_scale`]).
fn snap_pieces(mesh: &mut Mesh, labels: &[u32], tolerance: f64) -> SnapReport {
    let mut first = vec![u32::MAX; mesh.positions.len()];
    let mut seam = vec![false; mesh.positions.len()];
    for (t, &l) in mesh.triangles.iter().zip(labels) {
        for &v in t {
            let f = &mut first[v as usize];
            if *f == u32::MAX {
                *f = l;
            } else if *f != l {
                seam[v as usize] = true;
            }
        }
    }
    let seam: Vec<u32> = (0..seam.len() as u32)
        .filter(|&v| seam[v as usize])
        .collect();
    let Some(e) = super::extreme_scale(&[mesh]) else {
        return crate::repair::snap_unchecked(mesh, &snap_options(&seam, labels, tolerance)).0;
    };
    // Snapping moves no vertex (it only drops some): the positions kept are the input's,
    // bit for bit, whatever scaling did to them.
    let mut positions = mesh.positions.clone();
    super::scale_points(&mut mesh.positions, e);
    let tolerance = super::scaled(tolerance, e).min(f64::MAX);
    let (mut report, removed) =
        crate::repair::snap_unchecked(mesh, &snap_options(&seam, labels, tolerance));
    crate::mesh_edit::remove_sorted(&mut positions, &removed.vertices);
    mesh.positions = positions;
    report.scale_back(-e);
    report
}

/// The options of snapping where pieces meet.
fn snap_options<'a>(
    seam: &'a [u32],
    labels: &'a [u32],
    tolerance: f64,
) -> crate::repair::SnapOptions<'a> {
    crate::repair::SnapOptions {
        tolerance,
        seam,
        labels: Some(labels),
        seam_only: true,
        sheets: None,
    }
}

/// Picks from a split's directory ([`SplitOutput::write_dir`]): reads its manifest and the
/// pieces `specs` names, and merges them as [`SplitOutput::pick`] does.
pub fn pick_dir(
    dir: impl AsRef<Path>,
    specs: &[PieceSpec],
    opts: &PickOptions,
) -> Result<PickOutput> {
    pick_dir_with(dir.as_ref(), |_| specs.to_vec(), opts)
}

/// A boolean from a split's directory: the pieces `op` keeps ([`PieceSpec::for_op`]),
/// merged as [`pick_dir`] does — the same result as the boolean of the split's inputs.
pub fn pick_dir_op(dir: impl AsRef<Path>, op: Op, opts: &PickOptions) -> Result<PickOutput> {
    pick_dir_with(
        dir.as_ref(),
        |manifest| {
            PieceSpec::for_op(op)
                .into_iter()
                .filter(|s| manifest.groups.iter().any(|g| g.name == s.group))
                .collect()
        },
        opts,
    )
}

/// [`pick_dir`] of the pieces `specs` chooses from the split's manifest.
fn pick_dir_with(
    dir: &Path,
    specs: impl FnOnce(&SplitReport) -> Vec<PieceSpec>,
    opts: &PickOptions,
) -> Result<PickOutput> {
    let path = dir.join("manifest.json");
    let bytes = std::fs::read(&path).map_err(|e| Error::from(e).in_file("reading", &path))?;
    let manifest: SplitReport = serde_json::from_slice(&bytes).map_err(|e| {
        Error::Malformed {
            what: "split manifest",
            message: e.to_string(),
        }
        .in_file("reading", &path)
    })?;
    let specs = specs(&manifest);
    let files = resolve(&specs, |group| {
        let g = manifest.groups.iter().find(|g| g.name == group)?;
        Some((&g.piece, &g.components[..]))
    })?;
    let meshes = files
        .into_iter()
        .map(|(piece, flip)| Ok((super::read(dir.join(&piece.file), None)?.0, flip)))
        .collect::<Result<Vec<_>>>()?;
    let refs: Vec<(&Mesh, bool)> = meshes.iter().map(|(m, f)| (m, *f)).collect();
    pick(&refs, opts)
}
