//! Booleans of many meshes: union or intersection, or the first less all the others,
//! pairwise in a balanced tree or in one arrangement of all of them.
//!
//! **The tree** ([`reduce`], the default): both operations are associative and
//! commutative, so `k` meshes take `⌈log2 k⌉` rounds of pairwise booleans, the pairs of a
//! round in parallel: `k − 1` booleans as a chain would do, but each mesh goes through
//! `log2 k` of them instead of up to `k − 1`, and a round uses every core. Shared
//! topology (solids touching along an edge or at a vertex) is kept between rounds and
//! split once at the end. Each round's result has its seam points rounded to `f64`, and
//! the next round takes them as exact input vertices. A difference of many, the first
//! mesh less all the others, is the first less the tree's union of the others: one
//! difference at the end.
//!
//! **One arrangement** ([`reduce_in_one`], on request; closed meshes): the meshes'
//! triangles together are cut along every crossing at once
//! ([`crate::arrange::arrange_self`] on their concatenation), and each patch of the
//! result is kept where the operation's inside differs on its two sides, by the exact
//! winding number of each mesh there (`boolean::sides`). Nothing is rounded before the
//! result is written, and each triangle is cut once. It is not the default because it is
//! slower: it cuts every crossing, also those deep inside a union that the tree's early
//! rounds drop with the triangles around them (ten 20k-triangle spheres: 1.5× the
//! tree's time in a ring, 4.5× when all overlap one another; BENCHMARKS.md).

use crate::par::Grain;
use rayon::prelude::*;

use super::sides::{patch_sides, Inputs};
use super::{
    boolean, cleanup, BooleanResult, CleanupReport, Op, PipelineOptions, Provenance, Source,
};
use crate::arrange::{arrange_self, FailReason};
use crate::edges::{EdgeCounts, EdgeTopology};
use crate::intersect::{crossings_between, self_seam};
use crate::repair::nonmanifold::split_at;
use crate::repair::{split_nonmanifold, NonManifoldReport};
use crate::Mesh;

/// A mesh of the tree with, for each of its triangles, the input triangle it is part of
/// (numbered across all inputs).
#[derive(Clone, Debug, Default)]
pub struct Part {
    /// The mesh (valid, exactly welded).
    pub mesh: Mesh,
    /// For every triangle of `mesh`, its input triangle.
    pub parent: Vec<u32>,
}

/// The result of [`reduce`].
#[derive(Clone, Debug, Default)]
pub struct Reduced {
    /// The result, with the input triangle of each triangle.
    pub part: Part,
    /// Seam points of all the pairwise booleans.
    pub seam_points: usize,
    /// Input triangles that could not be cut along a seam and were kept whole, with the
    /// reason; empty for valid inputs.
    pub failed: Vec<(u32, FailReason)>,
    /// Result triangles that turned over when seam points were rounded to `f64`, over all
    /// the pairwise booleans.
    pub rounding_flips: usize,
    /// Where the result was not manifold and was split.
    pub nonmanifold: NonManifoldReport,
    /// What the exact clean-ups of all the pairwise booleans did, added up.
    pub cleanup: CleanupReport,
    /// Whether the result came from one arrangement of all the parts ([`reduce_in_one`]),
    /// else from the pairwise tree.
    pub one_arrangement: bool,
}

/// Patches times meshes beyond which [`reduce_in_one`] leaves the parts to the tree (the
/// winding numbers it keeps).
const MOST_WINDINGS: usize = 1 << 24;

/// `op` ([`Op::Union`], [`Op::Intersection`], or [`Op::Difference`]: the first part less
/// all the others) of `parts` (at least two) in one arrangement of all of them (see the
/// module's text); split where it is not manifold unless `opts.keep_nonmanifold`. A part
/// must not cross itself (as the operands of a pairwise boolean): only pairs of triangles
/// of different parts are cut.
///
/// `None`, for [`reduce`] to do it, where a part is not closed and edge-manifold, a
/// triangle could not be cut, the winding numbers are not decided exactly, or a part
/// winds around some point other than 0 or 1 times (its inside is then not what a
/// pairwise boolean takes it to be).
///
/// # Panics
/// When `op` is a reverse difference.
pub fn reduce_in_one(parts: &[Part], op: Op, opts: &PipelineOptions) -> Option<Reduced> {
    assert!(op != Op::ReverseDifference);
    if parts.len() < 2 {
        return None;
    }
    if !parts.par_iter().grained().all(|p| closed_sheets(&p.mesh)) {
        return None;
    }
    let mut all = Mesh::default();
    let mut starts = Vec::with_capacity(parts.len());
    for p in parts {
        starts.push(u32::try_from(all.triangles.len()).ok()?);
        all.append(&p.mesh).ok()?;
    }
    let inputs = Inputs::starting_at(&starts[1..]);
    // Pairs of different parts only: a part does not cross itself (a boolean's operands
    // are checked, resolved where they do; a pairwise boolean takes the same).
    let meshes: Vec<&Mesh> = parts.iter().map(|p| &p.mesh).collect();
    let pairs = crossings_between(&meshes, &all, &starts);
    let inside = |w: &[i64]| match op {
        Op::Union => w.iter().any(|&x| x >= 1),
        Op::Difference => w[0] >= 1 && w[1..].iter().all(|&x| x < 1),
        _ => w.iter().all(|&x| x >= 1),
    };
    let kept = keep_in_one(&all, &inputs, &pairs, Windings::ZeroOrOne, inside, opts)?;
    // Each triangle's part, and its input triangle there.
    let parent = kept
        .provenance
        .iter()
        .map(|p| {
            let k = inputs.of(p.triangle) as usize;
            parts[k].parent[(p.triangle - starts[k]) as usize]
        })
        .collect();
    Some(Reduced {
        part: Part {
            mesh: kept.mesh,
            parent,
        },
        seam_points: kept.seam_points,
        failed: Vec::new(),
        rounding_flips: kept.rounding_flips,
        nonmanifold: kept.nonmanifold,
        cleanup: kept.cleanup,
        one_arrangement: true,
    })
}

/// `op` of `a` and `b` (valid, exactly welded, each a cycle: every edge used as often in
/// one direction as in the other, closed sheets and parts glued along edges or face to
/// face alike) where either may cross or overlap itself: both cut along every crossing at once, their own included, in one arrangement
/// of the two, and each patch kept where the operation's inside differs on its two sides.
/// Inside a mesh is where its exact winding number is at least 1 (the fill rule
/// positive of [`super::resolve()`]), so the result is the boolean of the solids the two
/// enclose, with nothing rounded before the end: a self-overlapping operand is resolved
/// and combined in one step, and no rounding of its resolved surface can leave slivers or
/// crossings for the boolean to trip on.
///
/// `pairs_a` and `pairs_b` are each mesh's own crossing pairs (as
/// [`crate::intersect::self_intersections`] finds them).
///
/// `None` where the exact route does not decide (a mesh that is not a cycle,
/// a triangle the arrangement could not cut, winding numbers not decided exactly); the
/// caller then resolves and combines in two steps.
pub fn boolean_in_one(
    a: &Mesh,
    b: &Mesh,
    pairs_a: &[(u32, u32)],
    pairs_b: &[(u32, u32)],
    op: Op,
    opts: &PipelineOptions,
) -> Option<BooleanResult> {
    if !(balanced(a) && balanced(b)) {
        return None;
    }
    let na = u32::try_from(a.triangles.len()).ok()?;
    u32::try_from(a.triangles.len() + b.triangles.len()).ok()?;
    let mut all = a.clone();
    all.append(b).ok()?;
    let starts = [0, na];
    let inputs = Inputs::starting_at(&starts[1..]);
    let mut pairs = crossings_between(&[a, b], &all, &starts);
    pairs.extend_from_slice(pairs_a);
    pairs.extend(pairs_b.iter().map(|&(i, j)| (i + na, j + na)));
    pairs.par_sort_unstable();
    pairs.dedup();
    let inside = |w: &[i64]| {
        let (in_a, in_b) = (w[0] >= 1, w[1] >= 1);
        match op {
            Op::Union => in_a || in_b,
            Op::Intersection => in_a && in_b,
            Op::Difference => in_a && !in_b,
            Op::ReverseDifference => in_b && !in_a,
        }
    };
    let kept = keep_in_one(&all, &inputs, &pairs, Windings::Any, inside, opts)?;
    let provenance = kept
        .provenance
        .iter()
        .map(|p| {
            let (source, triangle) = if p.triangle < na {
                (Source::A, p.triangle)
            } else {
                (Source::B, p.triangle - na)
            };
            Provenance {
                source,
                triangle,
                flipped: p.flipped,
            }
        })
        .collect();
    Some(BooleanResult {
        mesh: kept.mesh,
        provenance,
        nonmanifold: kept.nonmanifold,
        seam_points: kept.seam_points,
        degenerate: [0, 0],
        failed: Vec::new(),
        rounding_flips: kept.rounding_flips,
        seam_vertices: kept.seam_vertices,
        cleanup: kept.cleanup,
    })
}

/// Whether `m` is made of closed, consistently oriented sheets with no edge of more than
/// two triangles: what one arrangement's winding numbers need (and a boolean's threshold
/// of an input's winding number).
pub(super) fn closed_sheets(m: &Mesh) -> bool {
    let c = EdgeCounts::of(m);
    c.boundary == 0 && c.inconsistent == 0 && c.non_manifold == 0
}

/// Whether every edge of `m` is used as often in each direction ([`EdgeTopology::is_balanced`]):
/// its winding number is defined off the surface, what [`boolean_in_one`] needs.
fn balanced(m: &Mesh) -> bool {
    let c = EdgeCounts::of(m);
    c.boundary == 0
        && c.inconsistent == 0
        && (c.non_manifold == 0 || crate::edges::EdgeTopology::new(m).is_balanced())
}

/// Which winding numbers [`keep_in_one`] takes: only 0 and 1 (meshes that do not cross
/// themselves, whose inside a pairwise boolean would take them to have), or any.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Windings {
    ZeroOrOne,
    Any,
}

/// What [`keep_in_one`] keeps of an arrangement.
struct Kept {
    /// The kept patches (split where not manifold unless asked to keep it, cleaned up
    /// unless asked not to; unreferenced vertices removed).
    mesh: Mesh,
    /// Each triangle's input triangle in the meshes given together (as [`Source::A`]),
    /// and whether it was reversed.
    provenance: Vec<Provenance>,
    /// The vertices of `mesh` at seam points (sorted).
    seam_vertices: Vec<u32>,
    seam_points: usize,
    rounding_flips: usize,
    nonmanifold: NonManifoldReport,
    cleanup: CleanupReport,
}

/// The meshes whose concatenation is `all` (`inputs` tells whose each triangle is), cut
/// along the crossings of the triangle pairs `pairs` in one arrangement; each patch is
/// kept where `inside` (of the meshes' winding numbers, one each) differs on its two
/// sides, facing away from the inside (the first of a stack of coincident patches only).
/// Then split where the meshes meet (the only places the result can be non-manifold),
/// the fans paired at the seam's exact points, and cleaned up exactly, as a pairwise
/// boolean does. `None` where a triangle could not be cut, the winding numbers are not
/// decided exactly, there are too many to keep, or one is other than `windings` takes.
fn keep_in_one(
    all: &Mesh,
    inputs: &Inputs,
    pairs: &[(u32, u32)],
    windings: Windings,
    inside: impl Fn(&[i64]) -> bool,
    opts: &PipelineOptions,
) -> Option<Kept> {
    let n = inputs.count();
    let seam = self_seam(all, pairs);
    let arr = arrange_self(all, &seam);
    if !arr.failed.is_empty() {
        return None;
    }
    let m = &arr.mesh;
    let topo = EdgeTopology::new(m);
    // Patches: pieces joined across edges of exactly two triangles.
    let (count, patch) = topo.components_across(|e| topo.uses_of(e).len() == 2);
    if count.saturating_mul(n) > MOST_WINDINGS {
        return None;
    }
    let best = largest_pieces(m, &patch, count);
    let sides = patch_sides(all, inputs, &arr, &topo, &patch, count, &best)?;
    let behind: Vec<i64> = sides
        .front
        .iter()
        .zip(&sides.net)
        .map(|(f, d)| f + d)
        .collect();
    if windings == Windings::ZeroOrOne
        && sides
            .front
            .iter()
            .chain(&behind)
            .any(|w| !(0..=1).contains(w))
    {
        return None;
    }
    // Per patch: None dropped, Some(flip) kept (the first of its stack only, where the
    // inside differs on its two sides, facing away from the inside). A patch of zero-area
    // pieces only (seam points rounding to one point) is kept where its group's values
    // decide it: dropping it would leave a hole of zero width in a closed result.
    let keep: Vec<Option<bool>> = (0..count)
        .map(|p| {
            let (f, b) = (
                inside(&sides.front[p * n..][..n]),
                inside(&behind[p * n..][..n]),
            );
            (f != b && sides.first[p] && sides.decided[p]).then_some(f)
        })
        .collect();
    let mut mesh = Mesh {
        positions: m.positions.clone(),
        triangles: Vec::new(),
    };
    let mut provenance = Vec::new();
    for (t, tri) in m.triangles.iter().enumerate() {
        if let Some(flip) = keep[patch[t] as usize] {
            let mut tri = *tri;
            if flip {
                tri.swap(1, 2);
            }
            mesh.triangles.push(tri);
            provenance.push(Provenance {
                source: Source::A,
                triangle: arr.parent[t],
                flipped: flip,
            });
        }
    }
    let rounding_flips = arr
        .rounding_flips
        .iter()
        .filter(|&&t| keep[patch[t as usize] as usize].is_some())
        .count();
    let mut seam_vertices = arr.seam_vertex.clone();
    seam_vertices.sort_unstable();
    seam_vertices.dedup();
    let before = mesh.positions.len() as u32;
    let (mut mesh, mut nonmanifold, mut copied) = if opts.keep_nonmanifold {
        (mesh, NonManifoldReport::default(), Vec::new())
    } else {
        let exact = |i: usize| Some(arr.point(seam_vertices[i]));
        split_at(mesh, &seam_vertices, Some(&exact))
    };
    if !opts.keep_nonmanifold {
        // Edges of more than two triangles away from the seam's vertices, where an input
        // was itself not manifold (parts glued face to face that no pairing into sheets
        // separated) and its pieces meet again: split there too, at their exact points.
        let left = nonmanifold_vertices(&mesh);
        if !left.is_empty() {
            let original = |v: u32| match (v as usize).checked_sub(before as usize) {
                Some(k) => copied[k],
                None => v,
            };
            let exact = |i: usize| Some(arr.point(original(left[i])));
            let (split, more, copies) = split_at(mesh, &left, Some(&exact));
            mesh = split;
            nonmanifold.add(&more);
            let copies: Vec<u32> = copies.into_iter().map(original).collect();
            copied.extend(copies);
        }
    }
    let is_added = |v: u32| v as usize >= arr.input_vertices;
    let mut added: Vec<u32> = seam_vertices
        .iter()
        .copied()
        .filter(|&v| is_added(v))
        .collect();
    for (k, &original) in copied.iter().enumerate() {
        let v = before + k as u32;
        seam_vertices.push(v);
        if is_added(original) {
            added.push(v);
        }
    }
    seam_vertices.sort_unstable();
    let cleanup = if opts.cleanup {
        cleanup::clean_up(
            &mut mesh,
            &mut provenance,
            &mut seam_vertices,
            &added,
            [all, all],
        )
    } else {
        CleanupReport::default()
    };
    let (mesh, seam_vertices) = without_unreferenced(mesh, &seam_vertices);
    Some(Kept {
        mesh,
        provenance,
        seam_vertices,
        seam_points: seam.points.len(),
        rounding_flips,
        nonmanifold,
        cleanup,
    })
}

/// The vertices of the edges of `m` used by more than two triangles (sorted, distinct;
/// empty for a manifold mesh, found without building the adjacency).
fn nonmanifold_vertices(m: &Mesh) -> Vec<u32> {
    if EdgeCounts::of(m).non_manifold == 0 {
        return Vec::new();
    }
    let topo = EdgeTopology::new(m);
    let mut v: Vec<u32> = (0..topo.edge_count())
        .filter(|&e| topo.uses_of(e).len() > 2)
        .flat_map(|e| topo.edges[e])
        .collect();
    v.sort_unstable();
    v.dedup();
    v
}

/// Each of the `count` patches' largest piece (`patch`: each triangle's patch) as (twice
/// its area, triangle); `(0, usize::MAX)` for a patch with no piece of positive area.
pub(super) fn largest_pieces(m: &Mesh, patch: &[u32], count: usize) -> Vec<(f64, usize)> {
    let mut best = vec![(0.0f64, usize::MAX); count];
    for (t, &p) in patch.iter().enumerate() {
        let a = m.twice_area(t);
        if a > best[p as usize].0 {
            best[p as usize] = (a, t);
        }
    }
    best
}

/// `mesh` without the vertices no triangle uses ([`Mesh::without_unreferenced`]), and
/// `seam_vertices` renamed to match (those left out dropped; sorted).
fn without_unreferenced(mesh: Mesh, seam_vertices: &[u32]) -> (Mesh, Vec<u32>) {
    let (mesh, new) = mesh.without_unreferenced_renumbered();
    let mut seam: Vec<u32> = seam_vertices
        .iter()
        .map(|&v| new[v as usize])
        .filter(|&v| v != u32::MAX)
        .collect();
    seam.sort_unstable();
    (mesh, seam)
}

/// `op` of `parts`, pairwise in a balanced tree: [`Op::Union`] or [`Op::Intersection`] of
/// them all, or [`Op::Difference`], the first part less the union of the others (their
/// tree, then one difference). The result is split where it is not manifold unless
/// `opts.keep_nonmanifold`.
///
/// # Panics
/// When `op` is a reverse difference or `parts` is empty (callers check both).
pub fn reduce(mut parts: Vec<Part>, op: Op, opts: &PipelineOptions) -> Reduced {
    assert!(op != Op::ReverseDifference && !parts.is_empty());
    let pipeline = PipelineOptions {
        progress: None,
        keep_nonmanifold: true,
        ..*opts
    };
    let mut out = Reduced::default();
    let minuend = (op == Op::Difference).then(|| parts.remove(0));
    let tree_op = if minuend.is_some() { Op::Union } else { op };
    while parts.len() > 1 {
        let odd = (parts.len() % 2 == 1).then(|| parts.pop().expect("non-empty"));
        let mut pairs = Vec::with_capacity(parts.len() / 2);
        let mut it = parts.into_iter();
        while let (Some(a), Some(b)) = (it.next(), it.next()) {
            pairs.push((a, b));
        }
        let done: Vec<Step> = pairs
            .into_par_iter()
            .grained()
            .map(|(a, b)| Step::of(&a, &b, tree_op, &pipeline))
            .collect();
        parts = Vec::with_capacity(done.len() + 1);
        for step in done {
            parts.push(out.add(step));
        }
        parts.extend(odd);
    }
    let mut last = parts.pop();
    if let Some(a) = minuend {
        last = Some(match last {
            Some(b) => out.add(Step::of(&a, &b, Op::Difference, &pipeline)),
            None => a,
        });
    }
    out.part = last.expect("one part left");
    if !opts.keep_nonmanifold {
        let (mesh, report) = split_nonmanifold(&out.part.mesh);
        out.part.mesh = mesh;
        out.nonmanifold = report;
    }
    out
}

/// One pairwise boolean of [`reduce`]: its result as a part (parents named across all
/// inputs) and what it found.
struct Step {
    part: Part,
    seam_points: usize,
    failed: Vec<(u32, FailReason)>,
    rounding_flips: usize,
    cleanup: CleanupReport,
}

impl Step {
    /// `op` of `a` and `b`.
    fn of(a: &Part, b: &Part, op: Op, pipeline: &PipelineOptions) -> Step {
        let r = boolean(&a.mesh, &b.mesh, op, pipeline);
        let of = |s: Source, t: u32| match s {
            Source::A => a.parent[t as usize],
            Source::B => b.parent[t as usize],
        };
        Step {
            part: Part {
                parent: r
                    .provenance
                    .iter()
                    .map(|p| of(p.source, p.triangle))
                    .collect(),
                mesh: r.mesh,
            },
            seam_points: r.seam_points,
            failed: r
                .failed
                .iter()
                .map(|f| (of(f.source, f.triangle), f.reason))
                .collect(),
            rounding_flips: r.rounding_flips,
            cleanup: r.cleanup,
        }
    }
}

impl Reduced {
    /// Adds what `step` found to the totals; its part.
    fn add(&mut self, step: Step) -> Part {
        self.cleanup.add(&step.cleanup);
        self.seam_points += step.seam_points;
        self.failed.extend(step.failed);
        self.rounding_flips += step.rounding_flips;
        step.part
    }
}
