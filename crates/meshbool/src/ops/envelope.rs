//! The upper or lower envelope of an open surface that folds over itself: the single-valued
//! surface a folded terrain stands for (`meshbool resolve --envelope upper|lower`).
//!
//! With the surface `S` faced up, the solid `E` of every point below some point of `S`
//! (down to a floor) is the union of exact solids: the curtain solid `C(S)` (walls from
//! `S`'s boundary down to the floor, the floor capped) resolved under the positive
//! rule, and a prism under each patch of `S`'s triangles that face down (the folds,
//! turned up and curtained). A point below `S` whose winding number in `C(S)` is not
//! positive has, on its way up, a down-facing sheet to cross (an up-facing one lowers
//! the count), so it lies in that sheet's prism. The prisms stand on a floor halfway
//! between `C(S)`'s and the surface, inside `C(S)`, so that no two floors overlap;
//! above the surface's lowest point `E` is exact either way. `E` is computed with the
//! exact n-ary union; its boundary is the floors, vertical walls and, on top, exactly
//! the points of `S` that nothing of `S` lies above: the upper envelope. The walls
//! whose connected pieces stay above the surface's lowest point are the jumps between a
//! sheet and the sheet under it (an overhang's edge): they are kept, so that the
//! envelope is connected there; walls reaching down are the outline's curtain and are
//! dropped. The lower envelope is the upper one of the surface mirrored in z.

use serde::Serialize;
use web_time::Instant;

use super::{BooleanOptions, Checks, Input, Measures, RunOptions, SCHEMA};
use crate::boolean::Op;
use crate::edges::{EdgeCounts, EdgeKind, EdgeTopology};
use crate::repair::{curtain_to, orient, Facing};
use crate::{Error, Mesh, Result};

/// Which envelope of a surface: what is seen from above or from below.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Envelope {
    /// The highest sheet at each plan position (the terrain's surface over a fold).
    #[default]
    Upper,
    /// The lowest sheet at each plan position.
    Lower,
}

impl Envelope {
    /// Both envelopes, in the order of [`Envelope::name`]s listed in help texts.
    pub const ALL: [Envelope; 2] = [Envelope::Upper, Envelope::Lower];

    /// The envelope's name: `upper`, `lower`.
    pub fn name(self) -> &'static str {
        match self {
            Envelope::Upper => "upper",
            Envelope::Lower => "lower",
        }
    }
}

by_name!(Envelope, "envelope");

/// Options of [`envelope()`].
#[derive(Clone, Debug, Default)]
pub struct EnvelopeOptions {
    /// Which envelope.
    pub side: Envelope,
    /// Threads and progress.
    pub run: RunOptions,
}

/// What [`envelope()`] found and did.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct EnvelopeReport {
    /// Which envelope.
    pub side: Envelope,
    /// Input triangles facing the other way once the surface is oriented consistently
    /// (away from the envelope's side: the folds), each given a prism.
    pub folded_triangles: usize,
    /// Edge-connected patches of those (one prism solid each).
    pub fold_patches: usize,
    /// Input triangles of which no part is on the envelope (hidden under another sheet).
    pub hidden_triangles: usize,
    /// Vertical wall triangles kept where the envelope jumps from a sheet to the sheet
    /// under it (an overhang's edge), so that it stays connected.
    pub jump_walls: usize,
    /// Points of the intersection curves of the exact union.
    pub seam_points: usize,
    /// Input triangles that could not be cut along a seam and were kept whole (empty for
    /// valid inputs).
    pub failed_triangles: usize,
}

/// The result of [`envelope()`].
#[derive(Clone, Debug)]
pub struct EnvelopeOutput {
    /// The envelope, faced up (towards `+z`) whichever side it is.
    pub mesh: Mesh,
    /// For every triangle of `mesh`, the triangle of the (welded) input it is part of; for
    /// a jump wall, the input triangle whose edge it hangs from.
    pub parent: Vec<u32>,
    /// What was found and done.
    pub report: EnvelopeReport,
    /// Time of the whole call, in seconds.
    pub seconds: f64,
}

/// The JSON of `meshbool resolve --envelope SIDE --json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EnvelopeCommandReport {
    /// [`SCHEMA`].
    pub schema: u32,
    /// Measures of the result.
    #[serde(flatten)]
    pub result: Measures,
    /// What was found and done.
    pub envelope: EnvelopeReport,
    /// [`EnvelopeOutput::seconds`].
    pub seconds: f64,
}

impl EnvelopeOutput {
    /// The report, with the result's measures.
    pub fn report(&self) -> EnvelopeCommandReport {
        EnvelopeCommandReport {
            schema: SCHEMA,
            result: Measures::of(&self.mesh),
            envelope: self.report.clone(),
            seconds: self.seconds,
        }
    }
}

/// The upper or lower envelope of an open surface that may fold over itself (see the
/// module doc): exact, every inside/outside decision made by the exact n-ary union.
/// Errors ([`Error::Unresolvable`]): a closed mesh (it has no single-valued envelope
/// here: use its top faces), a surface that cannot be oriented consistently, or one
/// with edges of more than two triangles.
pub fn envelope<'a>(mesh: impl Into<Input<'a>>, opts: &EnvelopeOptions) -> Result<EnvelopeOutput> {
    let start = Instant::now();
    let input = mesh.into().operand("mesh", &Checks::NONE)?;
    let name = input.name().to_string();
    let refuse = |reason: &str| Error::Unresolvable {
        name: name.clone(),
        reason: reason.to_string(),
    };
    let mirror = opts.side == Envelope::Lower;
    let mirrored = |m: &Mesh| {
        let mut m = m.clone();
        for p in &mut m.positions {
            p[2] = -p[2];
        }
        m
    };
    let given = mirror.then(|| mirrored(input.mesh()));
    let (surface, _) = orient(given.as_ref().unwrap_or(input.mesh()), Facing::ZUp);
    let counts = EdgeCounts::of(&surface);
    if counts.boundary == 0 {
        return Err(refuse(
            "an envelope is taken of an open surface, and this mesh is closed",
        ));
    }
    if counts.inconsistent > 0 || counts.non_manifold > 0 {
        // Where the first such edge is, in the input's coordinates (not the mirror's).
        let topo = EdgeTopology::new(&surface);
        let near = [EdgeKind::NonManifold, EdgeKind::Inconsistent]
            .into_iter()
            .find_map(|kind| topo.first_of(kind))
            .map(|e| {
                let [x, y, z] = topo.midpoint(&surface, e);
                format!("; the first near {:?}", [x, y, if mirror { -z } else { z }])
            })
            .unwrap_or_default();
        return Err(refuse(&format!(
            "the surface cannot be oriented consistently ({} inconsistent, {} non-manifold edges{near})",
            counts.inconsistent, counts.non_manifold
        )));
    }
    let n = surface.triangles.len();
    let b = surface
        .bounds()
        .ok_or_else(|| refuse("the mesh is empty"))?;
    // Any plane below the surface will do; one its own height lower keeps walls sound.
    let floor = b.min[2] - (b.max[2] - b.min[2]).max(1.0);
    if !floor.is_finite() {
        return Err(refuse("the surface is too tall to put a floor under it"));
    }
    // Triangles facing down in plan (exact): the folds.
    let folded: Vec<u32> = (0..n as u32)
        .filter(|&t| {
            let [p, q, r] = surface.corners(t as usize);
            crate::kernel::orient2d_inputs(&p, &q, &r, 2, false) == crate::kernel::Sign::Negative
        })
        .collect();
    // The folds' prisms, one solid per edge-connected patch of folded triangles (the patch
    // turned up, curtained), standing on a floor halfway to the surface: inside the
    // curtain solid, so that no face of theirs lies on its floor.
    // Every input of the union: the curtain solid of the whole surface, then the prisms;
    // each a solid whose first triangles are surface triangles `tops`, then its walls,
    // `walls[w]` the index in `tops` of the triangle wall `w` hangs from, then its floor.
    let mid = floor + (b.min[2] - floor) / 2.0;
    let patches = fold_patches(&surface, &folded);
    let curtained = |top: &Mesh, tops: Vec<u32>, floor: f64| {
        let (solid, c) = curtain_to(top, floor);
        let walls = owners(top, &solid, c.wall_triangles);
        (solid, tops, walls)
    };
    let mut parts = vec![curtained(&surface, (0..n as u32).collect(), floor)];
    parts.extend(
        patches
            .iter()
            .map(|ids| curtained(&surface.subset(ids).flipped(), ids.clone(), mid)),
    );
    // The exact n-ary union (each input checked and, crossing itself, resolved at the
    // door); provenance names an input and its triangle.
    let inputs: Vec<Input> = parts.iter().map(|(m, _, _)| Input::from(m)).collect();
    let bopts = BooleanOptions {
        run: opts.run.clone(),
        ..BooleanOptions::default()
    };
    let union = super::boolean_many(&inputs, Op::Union, &bopts)?;
    // Each result triangle: Some((surface triangle, is a wall)), or None for a floor.
    let role: Vec<Option<(u32, bool)>> = union
        .provenance
        .iter()
        .map(|&[i, t]| {
            let (_, tops, walls) = &parts[i as usize];
            let t = t as usize;
            match t.checked_sub(tops.len()) {
                None => Some((tops[t], false)),
                Some(w) => walls.get(w).map(|&k| (tops[k as usize], true)),
            }
        })
        .collect();
    // Walls: connected pieces that reach a floor are the outline's curtain.
    let wall_ids: Vec<u32> = (0..role.len() as u32)
        .filter(|&t| matches!(role[t as usize], Some((_, true))))
        .collect();
    let wall_mesh = union.mesh.subset(&wall_ids);
    let (pieces, piece) = EdgeTopology::new(&wall_mesh).components();
    let mut grounded = vec![false; pieces];
    for (k, tri) in wall_mesh.triangles.iter().enumerate() {
        // Below the surface's lowest point lie only the floors.
        if tri
            .iter()
            .any(|&v| wall_mesh.positions[v as usize][2] < b.min[2])
        {
            grounded[piece[k] as usize] = true;
        }
    }
    let mut keep = vec![false; role.len()];
    let mut jump_walls = 0;
    for (t, r) in role.iter().enumerate() {
        keep[t] = matches!(r, Some((_, false)));
    }
    for (k, &t) in wall_ids.iter().enumerate() {
        if !grounded[piece[k] as usize] {
            keep[t as usize] = true;
            jump_walls += 1;
        }
    }
    let kept: Vec<u32> = (0..role.len() as u32)
        .filter(|&t| keep[t as usize])
        .collect();
    let mut out = union.mesh.subset(&kept);
    let parent: Vec<u32> = kept
        .iter()
        .map(|&t| role[t as usize].expect("kept").0)
        .collect();
    let mut seen = vec![false; n];
    for &t in &kept {
        if let Some((p, false)) = role[t as usize] {
            seen[p as usize] = true;
        }
    }
    if mirror {
        // A mirror in z keeps the z of every normal: mirrored back, it still faces up.
        out = mirrored(&out);
    }
    let report = EnvelopeReport {
        side: opts.side,
        folded_triangles: folded.len(),
        fold_patches: patches.len(),
        hidden_triangles: seen.iter().filter(|&&s| !s).count(),
        jump_walls,
        seam_points: union.seam_points,
        failed_triangles: union.failed.len(),
    };
    Ok(EnvelopeOutput {
        mesh: out,
        parent,
        report,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// For each wall triangle of `solid` (`curtain_to(top, ..)`, whose walls of `count`
/// triangles follow `top`'s triangles, a pair per boundary edge starting `[b, a, floor]`
/// for the edge `a -> b`), the triangle of `top` that edge belongs to.
fn owners(top: &Mesh, solid: &Mesh, count: usize) -> Vec<u32> {
    let n = top.triangles.len();
    let mut owner = rustc_hash::FxHashMap::default();
    for (t, tri) in top.triangles.iter().enumerate() {
        for k in 0..3 {
            owner.insert((tri[k], tri[(k + 1) % 3]), t as u32);
        }
    }
    (0..count)
        .map(|w| {
            let first = solid.triangles[n + w / 2 * 2];
            owner[&(first[1], first[0])]
        })
        .collect()
}

/// The edge-connected patches of the triangles `folded` (sorted) of `mesh`, each sorted.
fn fold_patches(mesh: &Mesh, folded: &[u32]) -> Vec<Vec<u32>> {
    let sub = mesh.subset(folded);
    let (count, component) = EdgeTopology::new(&sub).components();
    let mut patches = vec![Vec::new(); count];
    for (k, &t) in folded.iter().enumerate() {
        patches[component[k] as usize].push(t);
    }
    patches
}
