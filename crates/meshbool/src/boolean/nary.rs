//! Booleans of many meshes: union or intersection, pairwise in a balanced tree.
//!
//! Both operations are associative and commutative, so `k` meshes take `⌈log2 k⌉` rounds
//! of pairwise booleans, the pairs of a round in parallel: `k − 1` booleans as a chain
//! would do, but each mesh goes through `log2 k` of them instead of up to `k − 1`, and a
//! round uses every core. Shared topology (solids touching along an edge or at a vertex)
//! is kept between rounds and split once at the end.

use rayon::prelude::*;

use super::{boolean, CleanupReport, Op, PipelineOptions, Source};
use crate::arrange::FailReason;
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
}

/// `op` ([`Op::Union`] or [`Op::Intersection`]) of `parts`, pairwise in a balanced tree.
/// The result is split where it is not manifold unless `opts.keep_nonmanifold`.
///
/// # Panics
/// When `op` is a difference or `parts` is empty (callers check both).
pub fn reduce(mut parts: Vec<Part>, op: Op, opts: &PipelineOptions) -> Reduced {
    assert!(matches!(op, Op::Union | Op::Intersection) && !parts.is_empty());
    let pipeline = PipelineOptions {
        progress: None,
        keep_nonmanifold: true,
        ..*opts
    };
    let mut out = Reduced::default();
    while parts.len() > 1 {
        let odd = (parts.len() % 2 == 1).then(|| parts.pop().expect("non-empty"));
        let mut pairs = Vec::with_capacity(parts.len() / 2);
        let mut it = parts.into_iter();
        while let (Some(a), Some(b)) = (it.next(), it.next()) {
            pairs.push((a, b));
        }
        let done: Vec<_> = pairs
            .into_par_iter()
            .map(|(a, b)| {
                let r = boolean(&a.mesh, &b.mesh, op, &pipeline);
                let of = |s: Source, t: u32| match s {
                    Source::A => a.parent[t as usize],
                    Source::B => b.parent[t as usize],
                };
                let parent = r.provenance.iter().map(|p| of(p.source, p.triangle));
                let part = Part {
                    parent: parent.collect(),
                    mesh: r.mesh,
                };
                let failed: Vec<_> = r
                    .failed
                    .iter()
                    .map(|f| (of(f.source, f.triangle), f.reason))
                    .collect();
                (part, r.seam_points, failed, r.rounding_flips, r.cleanup)
            })
            .collect();
        parts = Vec::with_capacity(done.len() + 1);
        for (part, seam_points, failed, flips, cleanup) in done {
            out.cleanup.add(&cleanup);
            out.seam_points += seam_points;
            out.failed.extend(failed);
            out.rounding_flips += flips;
            parts.push(part);
        }
        parts.extend(odd);
    }
    out.part = parts.pop().expect("one part left");
    if !opts.keep_nonmanifold {
        let (mesh, report) = split_nonmanifold(&out.part.mesh);
        out.part.mesh = mesh;
        out.nonmanifold = report;
    }
    out
}
