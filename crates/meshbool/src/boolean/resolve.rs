//! Resolving a self-overlapping mesh: the solid it encloses under a fill rule, as a clean
//! closed mesh.
//!
//! What is built today: meshes made of closed, consistently oriented components that
//! overlap or nest one another (CAD exports of touching parts, models made of overlapping
//! primitives). Components that cross are united with exact booleans, in a balanced tree
//! (`log2 k` rounds, pairs of a round in parallel); a component or united cluster that
//! crosses nothing is kept or dropped by the winding number of the others at one of its
//! points. A component that crosses *itself* needs the self-arrangement (cutting a mesh
//! along its own seams, `DESIGN.md`), which is not built yet: such meshes are refused
//! with the reason.

use rayon::prelude::*;
use serde::Serialize;

use super::nary::{reduce, Part, Reduced};
use super::{Op, PipelineOptions};
use crate::classify::winding_number;
use crate::edges::{EdgeKind, EdgeTopology};
use crate::measure::signed_volume;
use crate::repair::{split_nonmanifold, NonManifoldReport};
use crate::vec3::{cross, norm, sub};
use crate::{Aabb, Mesh};

/// Which points a self-overlapping mesh encloses, by their winding number `w` (how many
/// times the surface wraps around the point, counting inward-facing parts negatively).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FillRule {
    /// Inside where `w ≥ 1`: the union of the overlapping parts (inward-facing parts cut
    /// cavities). The default.
    #[default]
    Positive,
    /// Inside where `w ≠ 0`.
    NonZero,
    /// Inside where `w` is odd.
    EvenOdd,
}

impl FillRule {
    /// Every rule, in the order of [`FillRule::name`]s listed in help texts.
    pub const ALL: [FillRule; 3] = [FillRule::Positive, FillRule::NonZero, FillRule::EvenOdd];

    /// The rule's name: `positive`, `nonzero`, `evenodd`.
    pub fn name(self) -> &'static str {
        match self {
            FillRule::Positive => "positive",
            FillRule::NonZero => "nonzero",
            FillRule::EvenOdd => "evenodd",
        }
    }

    /// Whether a point of winding number `w` is inside.
    pub fn inside(self, w: i64) -> bool {
        match self {
            FillRule::Positive => w >= 1,
            FillRule::NonZero => w != 0,
            FillRule::EvenOdd => w % 2 != 0,
        }
    }
}

by_name!(FillRule, "fill rule");

/// What [`resolve`] found and did.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ResolveReport {
    /// Edge-connected components of the input.
    pub components: usize,
    /// Pairs of triangles of different components that cross or touch.
    pub crossing_pairs: usize,
    /// Components united with others they cross.
    pub united_components: usize,
    /// Components (or united clusters of them) dropped because they do not bound the
    /// solid under the rule (a part nested inside another).
    pub dropped_components: usize,
    /// Components (or united clusters) kept with their orientation reversed, to face away
    /// from the solid (a part nested in another under the even-odd rule).
    pub flipped_components: usize,
    /// Points of the intersection curves of the unions.
    pub seam_points: usize,
    /// Input triangles that could not be cut along a seam and were kept whole (empty for
    /// valid inputs); triangle ids of the input.
    pub failed_triangles: usize,
    /// Result triangles that turned over when seam points were rounded to `f64`.
    pub rounding_flips: usize,
    /// Where the result was not manifold and was split.
    pub split_nonmanifold: NonManifoldReport,
}

/// The resolved solid: a mesh, the input triangle each of its triangles is part of, and
/// the report.
#[derive(Clone, Debug)]
pub struct Resolved {
    /// The surface of the solid the input encloses (orientation kept: outward where the
    /// input faced outward).
    pub mesh: Mesh,
    /// For every triangle of `mesh`, the input triangle it is part of.
    pub parent: Vec<u32>,
    /// What was found and done.
    pub report: ResolveReport,
}

/// A part of the resolved solid: a mesh with the input triangle of each of its triangles.
struct Piece {
    mesh: Mesh,
    parent: Vec<u32>,
    /// +1 facing outward (positive volume), −1 inward.
    facing: i64,
    components: usize,
}

/// Resolves `mesh` (valid, exactly welded) whose crossing triangle pairs are `pairs` (as
/// [`crate::intersect::self_intersections`] finds them): the solid its winding number
/// encloses under `rule`, as a closed mesh (manifold unless `opts.keep_nonmanifold`).
///
/// Errors (the reason, one phrase): a component that crosses itself, a component that is
/// not closed and consistently oriented, a component of zero volume, an inward-facing
/// component crossing another, crossing components under [`FillRule::EvenOdd`].
pub fn resolve(
    mesh: &Mesh,
    pairs: &[(u32, u32)],
    rule: FillRule,
    opts: &PipelineOptions,
) -> Result<Resolved, String> {
    let topo = EdgeTopology::new(mesh);
    let (count, component) = topo.components();
    let mut report = ResolveReport {
        components: count,
        ..ResolveReport::default()
    };
    // Components whose edges are not all used twice in opposite directions.
    let mut bad = vec![false; count];
    for e in 0..topo.edge_count() {
        if topo.kind(e) != EdgeKind::Manifold {
            bad[component[topo.uses_of(e)[0].triangle as usize] as usize] = true;
        }
    }
    if let Some(c) = bad.iter().position(|&b| b) {
        return Err(format!(
            "component {c} is not closed and consistently oriented (resolving needs closed components)"
        ));
    }
    // Clusters of crossing components (union-find, the lowest id the root).
    let mut root: Vec<usize> = (0..count).collect();
    fn find(root: &mut [usize], mut x: usize) -> usize {
        while root[x] != x {
            root[x] = root[root[x]];
            x = root[x];
        }
        x
    }
    for &(i, j) in pairs {
        let (ci, cj) = (
            component[i as usize] as usize,
            component[j as usize] as usize,
        );
        if ci == cj {
            return Err(format!(
                "component {ci} crosses itself (triangles {i} and {j}): resolving a self-crossing component needs the self-arrangement, not built yet"
            ));
        }
        report.crossing_pairs += 1;
        let (ri, rj) = (find(&mut root, ci), find(&mut root, cj));
        root[ri.max(rj)] = ri.min(rj);
    }
    let mut members: Vec<Vec<u32>> = vec![Vec::new(); count];
    for t in 0..mesh.triangles.len() as u32 {
        members[component[t as usize] as usize].push(t);
    }
    let mut clusters: Vec<Vec<usize>> = vec![Vec::new(); count];
    for c in 0..count {
        let r = find(&mut root, c);
        clusters[r].push(c);
    }
    clusters.retain(|c| !c.is_empty());
    if rule == FillRule::EvenOdd && clusters.iter().any(|c| c.len() > 1) {
        return Err(
            "crossing components under the even-odd rule need the self-arrangement, not built yet"
                .into(),
        );
    }
    let components: Vec<Piece> = members
        .par_iter()
        .map(|tris| {
            let m = mesh.subset(tris);
            let v = signed_volume(&m);
            Piece {
                facing: if v > 0.0 { 1 } else { -1 },
                mesh: m,
                parent: tris.clone(),
                components: 1,
            }
        })
        .collect();
    if let Some(c) = components
        .iter()
        .position(|p| signed_volume(&p.mesh) == 0.0)
    {
        return Err(format!("component {c} encloses no volume"));
    }
    for cluster in clusters.iter().filter(|c| c.len() > 1) {
        if let Some(&c) = cluster.iter().find(|&&c| components[c].facing < 0) {
            return Err(format!(
                "component {c} faces inward and crosses another component"
            ));
        }
        report.united_components += cluster.len();
    }
    // Unite each cluster, clusters and the pairs of each round in parallel.
    let mut slots: Vec<Option<Piece>> = components.into_iter().map(Some).collect();
    let grouped: Vec<Vec<Piece>> = clusters
        .iter()
        .map(|c| c.iter().map(|&i| slots[i].take().expect("once")).collect())
        .collect();
    let pipeline = PipelineOptions {
        keep_nonmanifold: true,
        ..*opts
    };
    let united: Vec<(Piece, Reduced)> = grouped
        .into_par_iter()
        .map(|mut pieces| {
            if pieces.len() == 1 {
                return (pieces.pop().expect("one"), Reduced::default());
            }
            let components = pieces.len();
            let parts = pieces
                .into_iter()
                .map(|p| Part {
                    mesh: p.mesh,
                    parent: p.parent,
                })
                .collect();
            let mut r = reduce(parts, Op::Union, &pipeline);
            let part = std::mem::take(&mut r.part);
            let piece = Piece {
                mesh: part.mesh,
                parent: part.parent,
                facing: 1,
                components,
            };
            (piece, r)
        })
        .collect();
    // Keep a piece where the rule's inside changes across it, facing away from the inside.
    let boxes: Vec<Option<Aabb>> = united.par_iter().map(|(p, _)| p.mesh.bounds()).collect();
    let keep: Vec<Option<bool>> = (0..united.len())
        .into_par_iter()
        .map(|i| {
            let p = &united[i].0;
            let at = probe(&p.mesh);
            let others: i64 = (0..united.len())
                .filter(|&j| j != i && boxes[j].is_some_and(|b| b.contains(&at)))
                .map(|j| winding_number(&united[j].0.mesh, at).round() as i64)
                .sum();
            // The piece's enclosed side has winding `others + facing`, its outside `others`;
            // the enclosed side is behind an outward-facing piece, in front of an inward one.
            let (behind, front) = if p.facing > 0 {
                (others + p.facing, others)
            } else {
                (others, others + p.facing)
            };
            (rule.inside(behind) != rule.inside(front)).then(|| !rule.inside(behind))
        })
        .collect();
    let mut mesh_out = Mesh::default();
    let mut parent = Vec::new();
    for ((p, stats), keep) in united.into_iter().zip(keep) {
        report.seam_points += stats.seam_points;
        report.failed_triangles += stats.failed.len();
        report.rounding_flips += stats.rounding_flips;
        let Some(flip) = keep else {
            report.dropped_components += p.components;
            continue;
        };
        if flip {
            report.flipped_components += p.components;
            mesh_out.append(&p.mesh.flipped())
        } else {
            mesh_out.append(&p.mesh)
        }
        .map_err(|e| e.to_string())?;
        parent.extend(p.parent);
    }
    let mesh_out = if opts.keep_nonmanifold {
        mesh_out
    } else {
        let (m, r) = split_nonmanifold(&mesh_out);
        report.split_nonmanifold = r;
        m
    };
    Ok(Resolved {
        mesh: mesh_out,
        parent,
        report,
    })
}

/// A point of `mesh` away from its vertices (the centroid of its largest triangle), where
/// the winding number of the other pieces, which it does not touch, is evaluated.
fn probe(mesh: &Mesh) -> [f64; 3] {
    let t = (0..mesh.triangles.len())
        .max_by(|&i, &j| {
            let twice_area = |t: usize| {
                let [a, b, c] = mesh.corners(t);
                norm(&cross(&sub(&b, &a), &sub(&c, &a)))
            };
            twice_area(i).total_cmp(&twice_area(j))
        })
        .expect("a piece has triangles");
    let [a, b, c] = mesh.corners(t);
    std::array::from_fn(|k| (a[k] + b[k] + c[k]) / 3.0)
}
