//! Boolean operations on two meshes: the pipeline end to end.
//!
//! `boolean()` reads like the pipeline: intersect → arrange both → classify both → select
//! by the operation's rules → merge into one mesh (seam vertices shared), with the source
//! of every output triangle.

use crate::arrange::{arrange, Arranged, Side};
use crate::classify::{classify, Class, Classified};
use crate::intersect::{intersect, Seam};
use crate::measure::mesh_stats;
use crate::Mesh;

/// A boolean operation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
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

/// Which input an output triangle comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Source {
    /// The first operand.
    A,
    /// The second operand.
    B,
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
    /// Seam points, for statistics.
    pub seam_points: usize,
    /// Triangles that could not be re-triangulated (invalid input), kept uncut: each is
    /// `(source, triangle, reason)`. Empty for valid inputs.
    pub failed: Vec<(Source, u32, &'static str)>,
}

/// Which classes of A and of B an operation keeps, and whether B's are flipped.
fn rule(op: Op) -> (&'static [Class], &'static [Class], bool) {
    match op {
        Op::Union => (
            &[Class::Outside, Class::CoplanarSame],
            &[Class::Outside],
            false,
        ),
        Op::Intersection => (
            &[Class::Inside, Class::CoplanarSame],
            &[Class::Inside],
            false,
        ),
        Op::Difference => (
            &[Class::Outside, Class::CoplanarOpposite],
            &[Class::Inside],
            true,
        ),
        Op::ReverseDifference => unreachable!("handled by swapping the operands"),
    }
}

/// Everything the pipeline computes before selection: the seam, both arrangements and
/// both classifications. The basis of booleans and of split-and-pick.
#[derive(Clone, Debug)]
pub struct Split {
    /// The intersection of the inputs.
    pub seam: Seam,
    /// A cut along the seam.
    pub a: Arranged,
    /// B cut along the seam.
    pub b: Arranged,
    /// Classes of A's triangles relative to B.
    pub class_a: Classified,
    /// Classes of B's triangles relative to A.
    pub class_b: Classified,
}

/// Runs intersection, arrangement and classification of `a` against `b` (both valid and
/// exactly welded; see [`crate::weld_exact`]).
pub fn split(a: &Mesh, b: &Mesh) -> Split {
    let seam = intersect(a, b);
    let (arr_a, arr_b) = rayon::join(|| arrange(a, &seam, Side::A), || arrange(b, &seam, Side::B));
    let (closed_a, closed_b) = rayon::join(|| mesh_stats(a).closed, || mesh_stats(b).closed);
    let (class_a, class_b) = rayon::join(
        || classify(&arr_a, a, &arr_b, b, closed_b),
        || classify(&arr_b, b, &arr_a, a, closed_a),
    );
    Split {
        seam,
        a: arr_a,
        b: arr_b,
        class_a,
        class_b,
    }
}

/// Merges chosen triangles of both arrangements into one mesh. `keep_a(t)` / `keep_b(t)`
/// say whether a triangle is kept and whether it is flipped.
pub fn merge(
    s: &Split,
    keep_a: impl Fn(usize) -> Option<bool>,
    keep_b: impl Fn(usize) -> Option<bool>,
) -> (Mesh, Vec<Provenance>) {
    let na = s.a.mesh.positions.len() as u32;
    // B's vertex ids in the merged numbering: seam vertices are A's, others follow A's.
    let mut b_to_merged: Vec<u32> = (0..s.b.mesh.positions.len() as u32)
        .map(|v| na + v)
        .collect();
    for (sp, &vb) in s.b.seam_vertex.iter().enumerate() {
        b_to_merged[vb as usize] = s.a.seam_vertex[sp];
    }
    let mut triangles = Vec::new();
    let mut provenance = Vec::new();
    for (arr, keep, source, map) in [
        (
            &s.a,
            &keep_a as &dyn Fn(usize) -> Option<bool>,
            Source::A,
            None,
        ),
        (
            &s.b,
            &keep_b as &dyn Fn(usize) -> Option<bool>,
            Source::B,
            Some(&b_to_merged),
        ),
    ] {
        for (t, tri) in arr.mesh.triangles.iter().enumerate() {
            let Some(flip) = keep(t) else { continue };
            let mut v = match map {
                None => *tri,
                Some(m) => tri.map(|i| m[i as usize]),
            };
            if flip {
                v.swap(1, 2);
            }
            triangles.push(v);
            provenance.push(Provenance {
                source,
                triangle: arr.parent[t],
                flipped: flip,
            });
        }
    }
    // Compact: only referenced vertices, in order of first use.
    let mut positions_all = s.a.mesh.positions.clone();
    positions_all.extend_from_slice(&s.b.mesh.positions);
    let mut new_id = vec![u32::MAX; positions_all.len()];
    let mut positions = Vec::new();
    for tri in &mut triangles {
        for v in tri.iter_mut() {
            if new_id[*v as usize] == u32::MAX {
                new_id[*v as usize] = positions.len() as u32;
                positions.push(positions_all[*v as usize]);
            }
            *v = new_id[*v as usize];
        }
    }
    (Mesh::new(positions, triangles), provenance)
}

/// The boolean `op` of `a` and `b` (both valid, exactly welded, consistently oriented;
/// closed meshes facing outward, open surfaces with "inside" behind them).
pub fn boolean(a: &Mesh, b: &Mesh, op: Op) -> BooleanResult {
    if op == Op::ReverseDifference {
        let mut r = boolean(b, a, Op::Difference);
        for p in &mut r.provenance {
            p.source = match p.source {
                Source::A => Source::B,
                Source::B => Source::A,
            };
        }
        for f in &mut r.failed {
            f.0 = match f.0 {
                Source::A => Source::B,
                Source::B => Source::A,
            };
        }
        return r;
    }
    let s = split(a, b);
    let (keep_a, keep_b, flip_b) = rule(op);
    let (mesh, provenance) = merge(
        &s,
        |t| keep_a.contains(&s.class_a.class[t]).then_some(false),
        |t| keep_b.contains(&s.class_b.class[t]).then_some(flip_b),
    );
    let failed =
        s.a.failed
            .iter()
            .map(|&(t, w)| (Source::A, t, w))
            .chain(s.b.failed.iter().map(|&(t, w)| (Source::B, t, w)))
            .collect();
    BooleanResult {
        mesh,
        provenance,
        seam_points: s.seam.points.len(),
        failed,
    }
}

#[cfg(test)]
mod tests;
