//! Boolean operations on two meshes: the pipeline end to end.
//!
//! `boolean()` reads like the pipeline: intersect → arrange both → classify both → select
//! by the operation's rules → merge into one mesh (seam vertices shared), with the source
//! of every output triangle.
//!
//! Notation used here and in the stages:
//! - **seam**: where the two surfaces meet — seam points (named by the smallest feature of
//!   each mesh holding them, [`crate::intersect::Label`]) and seam segments between them.
//! - **arranged mesh**: an input cut along the seam, re-triangulated so that every seam
//!   point is a vertex and every seam segment an edge ([`Arranged`]); its triangles keep
//!   their **parent** (the input triangle they lie in).
//! - **patch**: a connected piece of an arranged mesh between seam edges.
//! - **class**: where a triangle lies against the other mesh: inside, outside, or on one of
//!   its faces facing the same or the opposite way ([`Class`]); one per patch, except where
//!   an open surface's seam stops inside a patch.
//! - **rule**: the classes of A and of B an operation keeps, and which it flips
//!   ([`Op::rule`]).
//! - **group**: one mesh's triangles of one class, the unit of split-and-pick ([`Group`]).
//! - **provenance**: for each output triangle, its input, parent triangle and whether it
//!   was flipped ([`Provenance`]).

use std::fmt;
use std::str::FromStr;

use crate::par::Grain;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::arrange::{arrange_with, Arranged, FailReason};
use crate::classify::{classify_with, Class, Classified, CutMesh, Votes};
use crate::edges::SeamTopology;
pub use crate::intersect::Source;
use crate::intersect::{intersect_with, Seam};
use crate::kept::Keeps;
use crate::par::{exclusive_sums, filled, split_by};
use crate::repair::nonmanifold::split_at;
use crate::repair::NonManifoldReport;
pub use crate::stage::Stage;
use crate::Mesh;

mod cleanup;
pub mod nary;
pub mod resolve;
mod sides;
mod snap;
pub use cleanup::CleanupReport;
pub use resolve::{resolve, FillRule, ResolveReport};
pub use snap::{snap_result, snap_split, GroupMesh};

/// A boolean operation. Written (and parsed, [`FromStr`]) as `union`, `intersection`,
/// `difference`, `reverse-difference`; parsing also takes the reference library's
/// `intersect` and `subtract`, and `_` for `-`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Op {
    /// A ∪ B.
    Union,
    /// A ∩ B.
    Intersection,
    /// A − B.
    Difference,
    /// B − A.
    ReverseDifference,
}

impl Op {
    /// Every operation.
    pub const ALL: [Op; 4] = [
        Op::Union,
        Op::Intersection,
        Op::Difference,
        Op::ReverseDifference,
    ];

    /// The operation's name (`union`, `intersection`, `difference`, `reverse-difference`).
    pub fn name(self) -> &'static str {
        match self {
            Op::Union => "union",
            Op::Intersection => "intersection",
            Op::Difference => "difference",
            Op::ReverseDifference => "reverse-difference",
        }
    }
}

impl fmt::Display for Op {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Op {
    type Err = crate::Error;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_lowercase().replace('_', "-").as_str() {
            "intersect" => Ok(Op::Intersection),
            "subtract" => Ok(Op::Difference),
            name => crate::error::parse_name(name, &Op::ALL, Op::name, "operation"),
        }
    }
}

/// Where an output triangle comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Provenance {
    /// The input mesh.
    pub source: Source,
    /// The input triangle it is part of.
    pub triangle: u32,
    /// True when its orientation was reversed (the subtracted mesh's inside part).
    pub flipped: bool,
}

/// The result of [`boolean`].
#[derive(Clone, Debug)]
pub struct BooleanResult {
    /// The result mesh (seam vertices shared between the parts from A and from B;
    /// unreferenced vertices removed).
    pub mesh: Mesh,
    /// The origin of every triangle of `mesh`.
    pub provenance: Vec<Provenance>,
    /// Where the result was non-manifold and how it was split (nothing with
    /// [`PipelineOptions::keep_nonmanifold`]).
    pub nonmanifold: NonManifoldReport,
    /// Seam points, for statistics.
    pub seam_points: usize,
    /// Degenerate (zero-area) triangles of A and B where the meshes meet, left out of the
    /// intersection test (see [`Seam::degenerate`]).
    pub degenerate: [usize; 2],
    /// Triangles that could not be re-triangulated (invalid input), kept uncut. Empty for
    /// valid inputs.
    pub failed: Vec<FailedTriangle>,
    /// Result triangles that turned over or collapsed when their seam points were rounded
    /// to `f64` coordinates ([`Arranged::rounding_flips`]); 0 in almost every case.
    pub rounding_flips: usize,
    /// The vertices of `mesh` at seam points (sorted; copies made by the non-manifold
    /// split included): the vertices the boolean made rather than took from an input.
    pub seam_vertices: Vec<u32>,
    /// What the exact clean-up did ([`PipelineOptions::cleanup`]; all zero when off).
    pub cleanup: CleanupReport,
}

/// An input triangle that could not be cut along the seam (inconsistent input, such as a
/// self-intersecting mesh taken as given) and was kept whole.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct FailedTriangle {
    /// The input it belongs to.
    pub source: Source,
    /// Its index in that input.
    pub triangle: u32,
    /// Why.
    pub reason: FailReason,
}

/// What a selection does with one triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Keep {
    /// Left out.
    Drop,
    /// Kept as it is.
    AsIs,
    /// Kept with its orientation reversed.
    Flipped,
}

/// The classes of one mesh that an operation keeps, and whether they are flipped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Selection {
    /// The classes kept.
    pub classes: &'static [Class],
    /// Kept triangles are flipped (the subtrahend's inside, which bounds the result from
    /// the other side).
    pub flip: bool,
}

impl Selection {
    /// What happens to a triangle of class `c`.
    pub fn of(&self, c: Class) -> Keep {
        match (self.classes.contains(&c), self.flip) {
            (false, _) => Keep::Drop,
            (true, false) => Keep::AsIs,
            (true, true) => Keep::Flipped,
        }
    }
}

/// The rule of an operation: what it keeps of A and of B. Where the two meshes share a
/// face (coplanar pieces, present in both), one copy is kept: A's for union and
/// intersection, the minuend's for a difference.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rule {
    /// A's triangles, by their class against B.
    pub a: Selection,
    /// B's triangles, by their class against A.
    pub b: Selection,
}

impl Op {
    /// The operation's rule (see [`Rule`]).
    pub fn rule(self) -> Rule {
        use Class::{CoplanarOpposite, CoplanarSame, Inside, Outside};
        let (a, flip_a, b, flip_b): (&[Class], bool, &[Class], bool) = match self {
            Op::Union => (&[Outside, CoplanarSame], false, &[Outside], false),
            Op::Intersection => (&[Inside, CoplanarSame], false, &[Inside], false),
            Op::Difference => (&[Outside, CoplanarOpposite], false, &[Inside], true),
            Op::ReverseDifference => (&[Inside], true, &[Outside, CoplanarOpposite], false),
        };
        Rule {
            a: Selection {
                classes: a,
                flip: flip_a,
            },
            b: Selection {
                classes: b,
                flip: flip_b,
            },
        }
    }
}

/// Everything the pipeline computes before selection: the seam, both arrangements and
/// both classifications. The basis of booleans and of split-and-pick.
#[derive(Clone, Debug)]
pub struct Split {
    /// The intersection of the inputs.
    pub(crate) seam: Seam,
    /// A cut along the seam.
    pub(crate) a: Arranged,
    /// B cut along the seam.
    pub(crate) b: Arranged,
    /// Classes of A's triangles relative to B.
    pub(crate) class_a: Classified,
    /// Classes of B's triangles relative to A.
    pub(crate) class_b: Classified,
}

/// How the pipeline runs: progress reporting, and the two measured crossovers between
/// algorithms (public so that tests can force either path on small inputs).
#[derive(Clone, Copy)]
pub struct PipelineOptions<'p> {
    /// Called with each stage as it begins, on the thread running the call (a worker of
    /// the pool, or the calling thread for a small call: [`crate::ops::SERIAL_BELOW`]).
    pub progress: Option<&'p (dyn Fn(Stage) + Sync)>,
    /// Set when the call is cancelled ([`crate::ops::Cancel`]): the pipeline stops at its
    /// next stage with nothing computed (an empty split, an empty result), which the
    /// caller discards.
    pub cancel: Option<&'p crate::stage::Cancel>,
    /// Candidate pairs from the grid from this many triangles in both meshes together
    /// ([`crate::intersect::GRID_FROM`]), below from two trees.
    pub grid_from: usize,
    /// Exact winding-number sums up to this many triangle × query products
    /// ([`crate::classify::EXACT_WINDING_UP_TO`]), the hierarchical approximation beyond.
    pub exact_winding_up_to: f64,
    /// Keep the result's topology where it is not manifold (solids touching along an edge
    /// or at a vertex share that edge or vertex) instead of splitting it
    /// ([`crate::repair::split_nonmanifold`], at the seam only).
    pub keep_nonmanifold: bool,
    /// The exact clean-up of the result (on by default): seam points where the result is
    /// flat or straight removed, zero-area triangles made by rounding seam points
    /// collapsed or flipped away, no surface moved ([`CleanupReport`]). Off, the result
    /// keeps every seam point of the arrangement.
    pub cleanup: bool,
    /// Split the result's topology at every vertex where it is not manifold, not only at
    /// the seam: for an input that is not manifold itself (an operand resolved at the
    /// door whose parts touch along an edge or at a vertex). Ignored with
    /// `keep_nonmanifold`.
    pub split_everywhere: bool,
    /// What A and B keep between calls ([`Keeps`]; an operand's): the broad phase takes
    /// a mesh's whole tree below [`crate::intersect::GRID_FROM`] triangles, in place of a
    /// tree of its triangles near the other mesh. Each must be kept for the very mesh it
    /// is given with.
    pub kept: [Option<&'p Keeps>; 2],
    /// Interior points for a large triangle cut by a dense seam
    /// ([`crate::arrange::arrange_with`]): its pieces are not needles from its corners.
    /// Off by default (it adds vertices inside flat faces).
    pub sliver_guard: bool,
    /// Classify each patch by its first deciding seam vote against a closed other mesh
    /// ([`Votes::FirstDeciding`]) instead of asking every vote ([`Votes::All`]): for
    /// operands that are valid solids, checked or known to be clean, where all of a
    /// patch's votes agree. Off (the default) for meshes that may not be (an operand
    /// with problems taken as given, the parts of an operand being resolved).
    pub first_votes: bool,
    /// Cut coplanar overlaps along every edge of either mesh that crosses them, as
    /// [`crate::intersect::intersect_coplanar`] does with `refinement`: the groups of a
    /// split then hold the common refinement of both triangulations there. Off (the
    /// default), coplanar regions meet along their boundaries only.
    pub coplanar_refinement: bool,
}

impl Default for PipelineOptions<'_> {
    fn default() -> Self {
        PipelineOptions {
            split_everywhere: false,
            progress: None,
            cancel: None,
            grid_from: crate::intersect::GRID_FROM,
            exact_winding_up_to: crate::classify::EXACT_WINDING_UP_TO,
            keep_nonmanifold: false,
            cleanup: true,
            kept: [None, None],
            first_votes: false,
            sliver_guard: false,
            coplanar_refinement: false,
        }
    }
}

impl PipelineOptions<'_> {
    /// Tells the progress callback that `stage` begins (not once the call is cancelled:
    /// what runs after that is discarded).
    fn stage(&self, stage: Stage) {
        if let Some(p) = self.progress.filter(|_| !self.cancelled()) {
            p(stage);
        }
    }

    /// Whether the call was cancelled.
    fn cancelled(&self) -> bool {
        self.cancel.is_some_and(crate::stage::Cancel::is_cancelled)
    }
}

/// Runs intersection, arrangement and classification of `a` against `b` (both valid and
/// exactly welded; see [`crate::weld_exact`]). Threads as [`boolean`]'s.
pub fn split(a: &Mesh, b: &Mesh, opts: &PipelineOptions) -> Split {
    let triangles = a.triangles.len() + b.triangles.len();
    crate::par::run_for(triangles, || split_in_pool(a, b, opts))
}

/// [`split`] on the thread it is called on.
fn split_in_pool(a: &Mesh, b: &Mesh, opts: &PipelineOptions) -> Split {
    // Cancelled, the call stops at the next stage with nothing computed (the caller
    // discards what it gets).
    let nothing = || Split {
        seam: Seam::default(),
        a: Arranged::default(),
        b: Arranged::default(),
        class_a: Classified::default(),
        class_b: Classified::default(),
    };
    opts.stage(Stage::Intersect);
    if opts.cancelled() {
        return nothing();
    }
    let seam = intersect_with(a, b, opts.grid_from, opts.kept, opts.coplanar_refinement);
    opts.stage(Stage::Arrange);
    if opts.cancelled() {
        return nothing();
    }
    let (arr_a, arr_b) = crate::par::join(
        || arrange_with(a, &seam, Source::A, opts.sliver_guard),
        || arrange_with(b, &seam, Source::B, opts.sliver_guard),
    );
    // Closedness picks the winding-number threshold (of the input's winding number); the
    // arranged mesh is closed exactly when its input is (cutting keeps every edge's use
    // count) where the input does not cross itself. An input taken as given whose parts
    // cross may be cut into an arrangement with a few open edges: its own edges say
    // whether it is closed then (with threshold 0 the winding numbers of a closed input,
    // 0 outside it, all stood on the threshold: slow, and the side their rounding's).
    let (topo_a, topo_b) = crate::par::join(
        || SeamTopology::new(&arr_a.mesh, &arr_a.seam_edges),
        || SeamTopology::new(&arr_b.mesh, &arr_b.seam_edges),
    );
    let closed = |topo: &SeamTopology, input: &Mesh| {
        topo.is_closed() || (!input.triangles.is_empty() && nary::closed_sheets(input))
    };
    let (closed_a, closed_b) = crate::par::join(|| closed(&topo_a, a), || closed(&topo_b, b));
    let oa = CutMesh {
        input: a,
        arranged: &arr_a,
        topology: &topo_a,
        seam: Some((&seam.points, Source::A)),
    };
    let ob = CutMesh {
        input: b,
        arranged: &arr_b,
        topology: &topo_b,
        seam: Some((&seam.points, Source::B)),
    };
    opts.stage(Stage::Classify);
    if opts.cancelled() {
        return nothing();
    }
    let votes = match opts.first_votes {
        true => Votes::FirstDeciding,
        false => Votes::All,
    };
    let (class_a, class_b) = crate::par::join(
        || classify_with(&oa, &ob, closed_b, opts.exact_winding_up_to, votes),
        || classify_with(&ob, &oa, closed_a, opts.exact_winding_up_to, votes),
    );
    Split {
        seam,
        a: arr_a,
        b: arr_b,
        class_a,
        class_b,
    }
}

/// What [`merge`] makes.
#[derive(Clone, Debug)]
pub struct Merged {
    /// The chosen triangles as one mesh.
    pub mesh: Mesh,
    /// The origin of each of its triangles.
    pub provenance: Vec<Provenance>,
    /// Its vertices at seam points (sorted): where the two inputs' parts are glued, the
    /// only places a merge can make a mesh non-manifold.
    pub seam_vertices: Vec<u32>,
    /// The vertex of A's arrangement of each of `seam_vertices` (same order), whose exact
    /// point it is ([`Arranged::point`]).
    pub seam_origin: Vec<u32>,
}

/// Merges chosen triangles of both arrangements into one mesh. `keep_a(t)` / `keep_b(t)`
/// say whether a triangle is kept and whether it is flipped. Triangles come in order (A's,
/// then B's); vertices are the used ones, A's in A's order, then B's own in B's order.
pub fn merge(
    s: &Split,
    keep_a: impl Fn(usize) -> Keep + Sync,
    keep_b: impl Fn(usize) -> Keep + Sync,
) -> Merged {
    use std::sync::atomic::{AtomicBool, Ordering::Relaxed};
    /// Triangles (and vertices) per piece of parallel work.
    const CHUNK: usize = 1 << 14;
    let (na, nb) = (s.a.mesh.positions.len(), s.b.mesh.positions.len());
    // B's vertex ids in the merged numbering: seam vertices are A's, others follow A's.
    let mut b_to_merged: Vec<u32> = (na as u32..(na + nb) as u32)
        .into_par_iter()
        .grained()
        .collect();
    for (sp, &vb) in s.b.seam_vertex.iter().enumerate() {
        b_to_merged[vb as usize] = s.a.seam_vertex[sp];
    }
    type Choice<'k> = &'k (dyn Fn(usize) -> Keep + Sync);
    let sides: [(&Arranged, Choice, Source, Option<&[u32]>); 2] = [
        (&s.a, &keep_a, Source::A, None),
        (&s.b, &keep_b, Source::B, Some(&b_to_merged)),
    ];
    // Pieces of both meshes in output order; each writes its kept triangles into its own
    // slice of the output, found from the counts of the pieces before it.
    let pieces: Vec<(usize, std::ops::Range<usize>)> = sides
        .iter()
        .enumerate()
        .flat_map(|(k, side)| {
            let n = side.0.mesh.triangles.len();
            (0..n)
                .step_by(CHUNK)
                .map(move |t| (k, t..(t + CHUNK).min(n)))
        })
        .collect();
    let counts: Vec<usize> = pieces
        .par_iter()
        .grained()
        .map(|(k, r)| {
            r.clone()
                .filter(|&t| (sides[*k].1)(t) != Keep::Drop)
                .count()
        })
        .collect();
    let total: usize = counts.iter().sum();
    let mut triangles = filled([0u32; 3], total);
    let none = Provenance {
        source: Source::A,
        triangle: 0,
        flipped: false,
    };
    let mut provenance = filled(none, total);
    let used: Vec<AtomicBool> = (0..na + nb)
        .into_par_iter()
        .grained()
        .map(|_| AtomicBool::new(false))
        .collect();
    split_by(&mut triangles, &counts)
        .into_par_iter()
        .grained()
        .zip(split_by(&mut provenance, &counts))
        .zip(&pieces)
        .for_each(|((tris, prov), (k, range))| {
            let (arr, keep, source, map) = sides[*k];
            let kept = range.clone().filter_map(|t| match keep(t) {
                Keep::Drop => None,
                k => Some((t, k == Keep::Flipped)),
            });
            for ((t, flip), (out, p)) in kept.zip(tris.iter_mut().zip(prov.iter_mut())) {
                let tri = arr.mesh.triangles[t];
                let mut v = match map {
                    None => tri,
                    Some(m) => tri.map(|i| m[i as usize]),
                };
                if flip {
                    v.swap(1, 2);
                }
                for &i in &v {
                    used[i as usize].store(true, Relaxed);
                }
                *out = v;
                *p = Provenance {
                    source,
                    triangle: arr.parent[t],
                    flipped: flip,
                };
            }
        });
    // Compact: only referenced vertices, in merged-id order (the same two-pass split).
    let position = |v: usize| {
        if v < na {
            s.a.mesh.positions[v]
        } else {
            s.b.mesh.positions[v - na]
        }
    };
    let used_in: Vec<usize> = used
        .par_chunks(CHUNK)
        .grained()
        .map(|c| c.iter().filter(|u| u.load(Relaxed)).count())
        .collect();
    let mut positions = filled([0.0; 3], used_in.iter().sum());
    let starts = exclusive_sums(&used_in);
    let mut new_id = filled(0u32, na + nb);
    new_id
        .par_chunks_mut(CHUNK)
        .grained()
        .zip(split_by(&mut positions, &used_in))
        .enumerate()
        .for_each(|(c, (ids, pos))| {
            let mut next = 0;
            for (j, id) in ids.iter_mut().enumerate() {
                let v = c * CHUNK + j;
                *id = if used[v].load(Relaxed) {
                    pos[next] = position(v);
                    next += 1;
                    (starts[c] + next - 1) as u32
                } else {
                    u32::MAX
                };
            }
        });
    triangles
        .par_iter_mut()
        .grained()
        .for_each(|t| *t = t.map(|v| new_id[v as usize]));
    // Seam vertices are numbered by A's arrangement in the merged numbering.
    let mut seam: Vec<(u32, u32)> =
        s.a.seam_vertex
            .iter()
            .map(|&v| (new_id[v as usize], v))
            .filter(|&(m, _)| m != u32::MAX)
            .collect();
    seam.par_sort_unstable();
    seam.dedup();
    let (seam_vertices, seam_origin) = seam.into_iter().unzip();
    Merged {
        mesh: Mesh::new_unchecked(positions, triangles),
        provenance,
        seam_vertices,
        seam_origin,
    }
}

/// Of the merged mesh's `seam_vertices` (with the vertex of A's arrangement each is,
/// `seam_origin`), those the arrangement added: neither A's vertex nor B's.
fn added_points(s: &Split, seam_origin: &[u32], seam_vertices: &[u32]) -> Vec<u32> {
    let mut b_vertex = vec![false; s.a.mesh.positions.len()];
    for (&va, &vb) in s.a.seam_vertex.iter().zip(&s.b.seam_vertex) {
        if (vb as usize) < s.b.input_vertices {
            b_vertex[va as usize] = true;
        }
    }
    (seam_origin.iter().zip(seam_vertices))
        .filter(|&(&o, _)| o as usize >= s.a.input_vertices && !b_vertex[o as usize])
        .map(|(_, &v)| v)
        .collect()
}

/// The boolean `op` of `a` and `b` (both valid, exactly welded, consistently oriented;
/// closed meshes facing outward, open surfaces with "inside" behind them).
///
/// Called from outside a thread pool, it moves into the current one once (a small call
/// runs serially on the calling thread instead: [`crate::ops::SERIAL_BELOW`]).
pub fn boolean(a: &Mesh, b: &Mesh, op: Op, opts: &PipelineOptions) -> BooleanResult {
    let triangles = a.triangles.len() + b.triangles.len();
    crate::par::run_for(triangles, || boolean_in_pool(a, b, op, opts))
}

/// [`boolean`] on the thread it is called on.
fn boolean_in_pool(a: &Mesh, b: &Mesh, op: Op, opts: &PipelineOptions) -> BooleanResult {
    let s = split_in_pool(a, b, opts);
    opts.stage(Stage::Merge);
    let rule = op.rule();
    let merged = merge(
        &s,
        |t| rule.a.of(s.class_a.class[t]),
        |t| rule.b.of(s.class_b.class[t]),
    );
    let merged_vertices = merged.mesh.positions.len() as u32;
    let (mesh, nonmanifold, copied) = if opts.keep_nonmanifold {
        (merged.mesh, NonManifoldReport::default(), Vec::new())
    } else if opts.split_everywhere {
        // Every vertex, the seam's at their exact points.
        let mut seam_index = vec![u32::MAX; merged.mesh.positions.len()];
        for (i, &v) in merged.seam_vertices.iter().enumerate() {
            seam_index[v as usize] = i as u32;
        }
        let exact = |v: usize| match seam_index[v] {
            u32::MAX => None,
            i => Some(s.a.point(merged.seam_origin[i as usize])),
        };
        let all: Vec<u32> = (0..merged_vertices).collect();
        let (mesh, report, copied) = split_at(merged.mesh, &all, Some(&exact));
        let copied = copied
            .into_iter()
            .map(|v| seam_index[v as usize] != u32::MAX)
            .collect();
        (mesh, report, copied)
    } else {
        // Pairing at the seam's exact points: rounded, thin triangles there can tie or
        // swap angles around an edge.
        let exact = |i: usize| Some(s.a.point(merged.seam_origin[i]));
        let (mesh, report, copied) = split_at(merged.mesh, &merged.seam_vertices, Some(&exact));
        (mesh, report, vec![true; copied.len()])
    };
    // The split's copies come after the merged vertices; those of seam vertices are seam
    // vertices too.
    let mut seam_vertices = merged.seam_vertices;
    seam_vertices.extend(
        (merged_vertices..mesh.positions.len() as u32)
            .zip(copied)
            .filter_map(|(v, seam)| seam.then_some(v)),
    );
    let (mut mesh, mut provenance) = (mesh, merged.provenance);
    let cleanup = if opts.cleanup {
        let added = added_points(&s, &merged.seam_origin, &seam_vertices);
        cleanup::clean_up(
            &mut mesh,
            &mut provenance,
            &mut seam_vertices,
            &added,
            [a, b],
        )
    } else {
        CleanupReport::default()
    };
    let kept = |arr: &Arranged, cls: &Classified, keep: &Selection| {
        arr.rounding_flips
            .iter()
            .filter(|&&t| keep.of(cls.class[t as usize]) != Keep::Drop)
            .count()
    };
    let rounding_flips = kept(&s.a, &s.class_a, &rule.a) + kept(&s.b, &s.class_b, &rule.b);
    let failed = [(Source::A, &s.a), (Source::B, &s.b)]
        .into_iter()
        .flat_map(|(source, arr)| {
            arr.failed
                .iter()
                .map(move |&(triangle, reason)| FailedTriangle {
                    source,
                    triangle,
                    reason,
                })
        })
        .collect();
    BooleanResult {
        mesh,
        provenance,
        nonmanifold,
        seam_points: s.seam.points.len(),
        degenerate: s.seam.degenerate,
        failed,
        rounding_flips,
        seam_vertices,
        cleanup,
    }
}

/// The groups of split-and-pick: each mesh's triangles by their class against the other.
/// Written (and parsed, [`FromStr`]) by [`Group::name`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Group {
    /// A's part inside B (behind B for an open B).
    AInB,
    /// A's part outside B.
    AOutB,
    /// B's part inside A.
    BInA,
    /// B's part outside A.
    BOutA,
    /// A's part on B's faces, facing the same way.
    AOnBSame,
    /// A's part on B's faces, facing the opposite way.
    AOnBOpposite,
    /// B's part on A's faces, facing the same way.
    BOnASame,
    /// B's part on A's faces, facing the opposite way.
    BOnAOpposite,
}

impl Group {
    /// All groups, in a fixed order.
    pub const ALL: [Group; 8] = [
        Group::AInB,
        Group::AOutB,
        Group::BInA,
        Group::BOutA,
        Group::AOnBSame,
        Group::AOnBOpposite,
        Group::BOnASame,
        Group::BOnAOpposite,
    ];

    /// The group's name as used in file names and on the command line (`a_in_b`, ...).
    pub fn name(self) -> &'static str {
        match self {
            Group::AInB => "a_in_b",
            Group::AOutB => "a_out_b",
            Group::BInA => "b_in_a",
            Group::BOutA => "b_out_a",
            Group::AOnBSame => "a_on_b_same",
            Group::AOnBOpposite => "a_on_b_opposite",
            Group::BOnASame => "b_on_a_same",
            Group::BOnAOpposite => "b_on_a_opposite",
        }
    }

    /// The side and class of the group's triangles.
    pub fn side_and_class(self) -> (Source, Class) {
        match self {
            Group::AInB => (Source::A, Class::Inside),
            Group::AOutB => (Source::A, Class::Outside),
            Group::BInA => (Source::B, Class::Inside),
            Group::BOutA => (Source::B, Class::Outside),
            Group::AOnBSame => (Source::A, Class::CoplanarSame),
            Group::AOnBOpposite => (Source::A, Class::CoplanarOpposite),
            Group::BOnASame => (Source::B, Class::CoplanarSame),
            Group::BOnAOpposite => (Source::B, Class::CoplanarOpposite),
        }
    }
}

by_name!(Group, "group");

impl Split {
    /// Every non-empty group of the split ([`Split::group`]), in the order of
    /// [`Group::ALL`], made from one mesh of all of them; with `cleanup`, what the
    /// arrangement added and the groups do not need goes first, the groups kept
    /// conforming and each of its shape ([`PipelineOptions::cleanup`] for splits: a seam
    /// point goes only where the seam runs straight through it and both meshes are flat
    /// around it). `a` and `b` are the split's inputs.
    pub(crate) fn groups(
        &self,
        a: &Mesh,
        b: &Mesh,
        cleanup: bool,
    ) -> (Vec<GroupMesh>, CleanupReport) {
        let mut all = merge(self, |_| Keep::AsIs, |_| Keep::AsIs);
        let mut labels = self.group_labels(all.mesh.triangles.len());
        let report = if cleanup {
            let added = added_points(self, &all.seam_origin, &all.seam_vertices);
            cleanup::clean_up_sheets(
                &mut all.mesh,
                &mut all.provenance,
                &mut labels,
                &mut all.seam_vertices,
                &added,
                [a, b],
            )
        } else {
            CleanupReport::default()
        };
        (snap::groups_of(&all.mesh, &all.provenance, &labels), report)
    }

    /// Each triangle's group (its index in [`Group::ALL`]) in the merge of all of them:
    /// A's triangles, then B's.
    pub(crate) fn group_labels(&self, n: usize) -> Vec<u32> {
        let na = self.a.mesh.triangles.len();
        let group_of = |k: usize| {
            let (source, class) = if k < na {
                (Source::A, self.class_a.class[k])
            } else {
                (Source::B, self.class_b.class[k - na])
            };
            Group::ALL
                .iter()
                .position(|g| g.side_and_class() == (source, class))
                .map_or(u32::MAX, |i| i as u32)
        };
        (0..n).into_par_iter().grained().map(group_of).collect()
    }

    /// The triangles of one group as a mesh (vertices compacted), with their provenance.
    #[cfg(test)]
    pub fn group(&self, g: Group) -> (Mesh, Vec<Provenance>) {
        let (side, class) = g.side_and_class();
        let pick = |cls: &Classified, t: usize| {
            if cls.class[t] == class {
                Keep::AsIs
            } else {
                Keep::Drop
            }
        };
        let merged = match side {
            Source::A => merge(self, |t| pick(&self.class_a, t), |_| Keep::Drop),
            Source::B => merge(self, |_| Keep::Drop, |t| pick(&self.class_b, t)),
        };
        (merged.mesh, merged.provenance)
    }
}

/// Merges meshes into one, each optionally flipped, welding exactly equal positions: the
/// "pick" of split-and-pick (pieces written by a split share their seam vertices bit for
/// bit). Errors when the pieces together have more than `u32::MAX` vertices.
pub fn pick(pieces: &[(&Mesh, bool)]) -> crate::Result<Mesh> {
    let mut all = Mesh::default();
    for &(m, flip) in pieces {
        if flip {
            all.append(&m.flipped())?;
        } else {
            all.append(m)?;
        }
    }
    Ok(crate::weld_exact(&all).mesh.without_unreferenced().0)
}

#[cfg(test)]
mod tests;
