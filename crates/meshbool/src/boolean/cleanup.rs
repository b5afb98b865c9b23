//! The exact clean-up of a boolean's result: what the arrangement added and the result
//! does not need goes, and no surface moves.
//!
//! An exact arrangement keeps every seam point, also where the result is straight or flat
//! through it (the seam crossing a flat diagonal of the other mesh, a coplanar contact),
//! and rounding seam points to `f64` can make zero-area triangles (two seam points that
//! round to one point, or three onto one line). Only seam vertices and the triangles at
//! them are looked at; input vertices never move. Three edits, each changing no geometry:
//!
//! - **zero-length edges** (two seam vertices at one position) are collapsed;
//! - a **removable seam point** — its triangles lie in one plane (the same plane and
//!   facing, decided exactly on their parent input triangles), or in two planes that meet
//!   in a line with the point between its two neighbours along that line — is collapsed
//!   onto a neighbour (onto one of the two on the line for the second kind), where no
//!   triangle of its star turns over or degenerates at the written coordinates (exact
//!   sign of its normal against its parent's);
//! - **caps** (three distinct corners exactly on one line) are flipped into the
//!   neighbour across their longest edge, which is split at the middle corner.
//!
//! Every edit keeps the mesh manifold (the link condition: the two ends of a collapsed
//! edge share no neighbour but the edge's far corners; a flip makes no edge twice).

use crate::par::Grain;
use rayon::prelude::*;
use rustc_hash::FxHashMap;
use serde::{Deserialize, Serialize};
use smallvec::SmallVec;

use super::{Provenance, Source};
use crate::kernel::{normals_dot_sign, planes_line_axis, Sign};
use crate::measure::is_degenerate;
use crate::mesh_edit::{common, compact_from_end, neighbours, Ids};
use crate::Mesh;

/// What the exact clean-up of a boolean's result did (`BooleanOptions::keep_seam_points`
/// turns it off).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct CleanupReport {
    /// Seam points removed where the result is flat or straight through them: each a
    /// collapse onto a neighbour in the same plane or on the same line.
    pub removed_points: usize,
    /// Edges of zero length (two seam points rounded to one position) collapsed.
    pub zero_length_edges: usize,
    /// Zero-area triangles with three distinct corners on one line, flipped into their
    /// neighbour across the longest edge.
    pub flipped_caps: usize,
    /// Zero-area triangles at seam points left (no collapse or flip kept the mesh
    /// manifold): normally 0.
    pub zero_area_left: usize,
    /// Triangles fewer than before.
    pub triangles_removed: usize,
}

impl CleanupReport {
    /// Adds `o`'s counts to these (the clean-ups of several booleans).
    pub fn add(&mut self, o: &CleanupReport) {
        self.removed_points += o.removed_points;
        self.zero_length_edges += o.zero_length_edges;
        self.flipped_caps += o.flipped_caps;
        self.zero_area_left += o.zero_area_left;
        self.triangles_removed += o.triangles_removed;
    }
}

/// The mesh under clean-up: its triangles (dead ones kept in place until the end), the
/// stars of the vertices at and next to seam points, and where each triangle came from.
struct Cleanup<'a> {
    positions: &'a [[f64; 3]],
    triangles: Vec<[u32; 3]>,
    alive: Vec<bool>,
    provenance: Vec<Provenance>,
    inputs: [&'a Mesh; 2],
    /// Per vertex: its slot in `stars`, or `u32::MAX` for one no edit touches.
    slot: Vec<u32>,
    /// Per slot: triangles that contained the vertex at some time (check before use).
    stars: Vec<SmallVec<[u32; 8]>>,
    /// Slots below this hold every triangle of their vertex (those made at the start);
    /// later ones only the triangles edits gave it.
    complete_slots: usize,
    /// Per vertex: whether it is one the clean-up may remove (a seam point that is not
    /// an input vertex).
    seam: Vec<bool>,
    dead_vertex: Vec<bool>,
    /// The dead triangles and vertices, as they died.
    dead_triangles: Vec<u32>,
    dead_vertices: Vec<u32>,
    report: CleanupReport,
    /// A split's groups: each triangle's group, where A's pieces and B's are two sheets
    /// glued along the seam ([`clean_up_sheets`]); `None` for a boolean's result.
    labels: Option<Vec<u32>>,
}

/// What [`Cleanup::plan`] finds: a vertex's neighbours, and those to try moving it onto.
type Plan = (Ids, Option<Ids>);

/// What a seam point's first star says ([`Cleanup::first`]).
enum First {
    /// Not looked at (a split's groups, a star not known whole), or looked at already.
    Unknown,
    /// [`Cleanup::remove`] fails whatever its neighbours' stars are: the star rules it out
    /// and no neighbour lies at its position.
    RuledOut,
    /// [`Cleanup::plan`]'s answer, for [`Cleanup::remove`] to start from.
    Plan(Plan),
}

/// A closed fan of triangles around a vertex: its neighbours (sorted), and for each the
/// triangle whose edge runs out of the vertex to it and the one whose edge runs in.
struct ClosedFan {
    neighbours: Ids,
    out: Ids,
    into: Ids,
}

impl Cleanup<'_> {
    /// The live triangles at `v` (empty for a vertex without a slot).
    fn star(&self, v: u32) -> Ids {
        let s = self.slot[v as usize];
        if s == u32::MAX {
            return Ids::new();
        }
        let mut star: Ids = self.stars[s as usize]
            .iter()
            .copied()
            .filter(|&t| self.alive[t as usize] && self.triangles[t as usize].contains(&v))
            .collect();
        star.sort_unstable();
        star.dedup();
        star
    }

    fn complete(&self, v: u32) -> bool {
        let s = self.slot[v as usize];
        (s as usize) < self.complete_slots
    }

    fn add(&mut self, v: u32, t: u32) {
        if self.slot[v as usize] == u32::MAX {
            self.slot[v as usize] = self.stars.len() as u32;
            self.stars.push(SmallVec::new());
        }
        self.stars[self.slot[v as usize] as usize].push(t);
    }

    fn corners(&self, t: [u32; 3]) -> [[f64; 3]; 3] {
        t.map(|v| self.positions[v as usize])
    }

    /// The parent input triangle of `t`, turned as `t` faces.
    fn parent(&self, t: u32) -> [[f64; 3]; 3] {
        let p = self.provenance[t as usize];
        let m = self.inputs[usize::from(p.source == Source::B)];
        let [a, b, c] = m.corners(p.triangle as usize);
        if p.flipped {
            [a, c, b]
        } else {
            [a, b, c]
        }
    }

    /// Whether triangles `t` and `u` lie in one plane facing the same way (exact, on their
    /// parents).
    fn flat(&self, t: u32, u: u32) -> bool {
        let (p, q) = (self.provenance[t as usize], self.provenance[u as usize]);
        if p.source == q.source && p.triangle == q.triangle {
            return p.flipped == q.flipped;
        }
        crate::kernel::same_plane_same_facing(&self.parent(t), &self.parent(u))
    }

    /// The neighbours of `v` in the triangles `star` (sorted).
    fn neighbours(&self, star: &[u32], v: u32) -> Ids {
        neighbours(star.iter().map(|&t| self.triangles[t as usize]), v)
    }

    /// Whether collapsing `p` onto `q` keeps the mesh manifold: `q`'s star is known,
    /// exactly two triangles hold the edge, and the ends share no other neighbour.
    /// `np`: `p`'s neighbours in `star_p` (sorted).
    fn link_ok(&self, p: u32, q: u32, star_p: &[u32], np: &[u32]) -> bool {
        self.complete(q) && self.link_ok_with(p, q, star_p, np, &self.star(q))
    }

    /// [`Cleanup::link_ok`] with `q`'s star given (`q`'s star known).
    fn link_ok_with(&self, p: u32, q: u32, star_p: &[u32], np: &[u32], star_q: &[u32]) -> bool {
        if !self.complete(q) {
            return false;
        }
        let mut on_edge = star_p
            .iter()
            .copied()
            .filter(|&t| self.triangles[t as usize].contains(&q));
        let (Some(e), Some(f), None) = (on_edge.next(), on_edge.next(), on_edge.next()) else {
            return false;
        };
        let nq = self.neighbours(star_q, q);
        let shared = common(np, &nq).len();
        let far = |t: u32| {
            let tri = self.triangles[t as usize];
            tri.into_iter().find(|&x| x != p && x != q).unwrap_or(p)
        };
        far(e) != far(f) && shared == 2
    }

    /// Collapses `p` onto `q` (checked by the caller): the triangles on the edge die, the
    /// others take `q` for `p`.
    fn collapse(&mut self, p: u32, q: u32, star_p: &[u32]) {
        for &t in star_p {
            let tri = &mut self.triangles[t as usize];
            if tri.contains(&q) {
                self.alive[t as usize] = false;
                self.dead_triangles.push(t);
                self.report.triangles_removed += 1;
            } else {
                for v in tri.iter_mut() {
                    if *v == p {
                        *v = q;
                    }
                }
                self.add(q, t);
            }
        }
        self.dead_vertex[p as usize] = true;
        self.dead_vertices.push(p);
    }

    /// Whether no triangle of `star_p` but those on the edge to `q` turns over or
    /// degenerates when `p` moves to `q`'s position (exact, at the written coordinates).
    fn keeps_facing(&self, p: u32, q: u32, star_p: &[u32]) -> bool {
        star_p.iter().all(|&t| {
            let tri = self.triangles[t as usize];
            if tri.contains(&q) {
                return true;
            }
            let moved = tri.map(|v| if v == p { q } else { v });
            normals_dot_sign(&self.corners(moved), &self.parent(t)) == Sign::Positive
        })
    }

    /// The triangles `star` around `p` as a closed fan: every neighbour starts exactly
    /// one triangle's edge out of `p` and ends exactly one; `None` otherwise.
    fn closed_fan(&self, p: u32, star: &[u32]) -> Option<ClosedFan> {
        let mut fan: SmallVec<[(u32, u32, u32); 16]> = SmallVec::new(); // (next, prev, t)
        for &t in star {
            let tri = self.triangles[t as usize];
            let i = tri.iter().position(|&v| v == p)?;
            fan.push((tri[(i + 1) % 3], tri[(i + 2) % 3], t));
        }
        // Closed: the edges' far ends `next` are distinct and are the ends `prev` (each
        // once), so they are the neighbours: sorted, they are the sorted neighbours.
        let mut neighbours: Ids = fan.iter().map(|&(next, _, _)| next).collect();
        neighbours.sort_unstable();
        if neighbours.windows(2).any(|w| w[0] == w[1]) || neighbours.binary_search(&p).is_ok() {
            return None;
        }
        let mut out: Ids = smallvec::smallvec![u32::MAX; neighbours.len()];
        let mut into: Ids = smallvec::smallvec![u32::MAX; neighbours.len()];
        for &(next, prev, t) in &fan {
            let (i, j) = (
                neighbours.binary_search(&next).ok()?,
                neighbours.binary_search(&prev).ok()?,
            );
            if into[j] != u32::MAX {
                return None;
            }
            out[i] = t;
            into[j] = t;
        }
        Some(ClosedFan {
            neighbours,
            out,
            into,
        })
    }

    /// The sheet of triangle `t` in a split's groups: 0 for A's pieces, 1 for B's.
    fn sheet(&self, t: u32) -> usize {
        usize::from(self.provenance[t as usize].source == Source::B)
    }

    /// Whether `p` lies strictly between `q` and `r` along some coordinate (of three
    /// points known to be on one line: rounding, monotone, keeps it).
    fn between(&self, q: u32, p: u32, r: u32) -> bool {
        let [q, x, r] = [q, p, r].map(|v| self.positions[v as usize]);
        (0..3).any(|k| (q[k] < x[k] && x[k] < r[k]) || (q[k] > x[k] && x[k] > r[k]))
    }

    /// [`Cleanup::remove`] in a split's groups: `p` goes only where each sheet is a closed
    /// fan in one plane around it, the two planes cross, and `p` lies between its two
    /// seam neighbours (on the line where the planes meet), by one collapse onto one of
    /// them in both sheets: the seam stays a straight line through where `p` was, so no
    /// group changes shape and the groups stay conforming. Two seam points at one
    /// position joined by a seam edge collapse the same way.
    fn remove_across_sheets(&mut self, p: u32) -> Option<(u32, Ids)> {
        let star = self.star(p);
        let mut sides: [Ids; 2] = [Ids::new(), Ids::new()];
        for &t in &star {
            sides[self.sheet(t)].push(t);
        }
        let fans = [
            self.closed_fan(p, &sides[0])?,
            self.closed_fan(p, &sides[1])?,
        ];
        let seam = common(&fans[0].neighbours, &fans[1].neighbours);
        let [q, r] = seam[..] else {
            return None;
        };
        let mut neighbours = fans[0].neighbours.clone();
        neighbours.extend(fans[1].neighbours.iter().copied());
        neighbours.sort_unstable();
        neighbours.dedup();
        let link = |w: &Self, q: u32| {
            (0..2).all(|s| {
                let star_q: Ids = w.star(q).into_iter().filter(|&t| w.sheet(t) == s).collect();
                w.link_ok_with(p, q, &sides[s], &fans[s].neighbours, &star_q)
            })
        };
        let position = |v: u32| self.positions[v as usize];
        for target in [q, r] {
            if position(target) == position(p) && link(self, target) {
                self.collapse(p, target, &star);
                self.report.zero_length_edges += 1;
                return Some((target, neighbours));
            }
        }
        let flat = |w: &Self, f: &ClosedFan| (0..f.out.len()).all(|i| w.flat(f.out[i], f.into[i]));
        if !(flat(self, &fans[0]) && flat(self, &fans[1])) {
            return None;
        }
        let (pa, pb) = (self.parent(sides[0][0]), self.parent(sides[1][0]));
        if planes_line_axis(&pa, &pb).is_none() || !self.between(q, p, r) {
            return None;
        }
        for target in [q, r] {
            if link(self, target) && self.keeps_facing(p, target, &star) {
                self.collapse(p, target, &star);
                self.report.removed_points += 1;
                return Some((target, neighbours));
            }
        }
        None
    }

    /// Tries to remove seam vertex `p`; returns the vertex it went onto and `p`'s
    /// neighbours before. `first`: what [`Cleanup::plan`] said of `p`'s star, where that star
    /// has not changed since.
    fn remove(&mut self, p: u32, first: Option<Plan>) -> Option<(u32, Ids)> {
        if self.dead_vertex[p as usize] || !self.complete(p) {
            return None;
        }
        if self.labels.is_some() {
            return self.remove_across_sheets(p);
        }
        let star = self.star(p);
        debug_assert!(first.is_none() || first == self.plan(p, &star));
        let (neighbours, targets) = match first {
            Some(plan) => plan,
            None => self.plan(p, &star)?,
        };
        let position = |v: u32| self.positions[v as usize];
        // Zero-length edges first: the same position, nothing to check but the link.
        for &q in &neighbours {
            if position(q) == position(p) && self.link_ok(p, q, &star, &neighbours) {
                self.collapse(p, q, &star);
                self.report.zero_length_edges += 1;
                return Some((q, neighbours));
            }
        }
        for q in targets.unwrap_or_default() {
            if self.link_ok(p, q, &star, &neighbours) && self.keeps_facing(p, q, &star) {
                self.collapse(p, q, &star);
                self.report.removed_points += 1;
                return Some((q, neighbours));
            }
        }
        None
    }

    /// What `p`'s star alone says of removing `p` (reading, not changing anything): `None`
    /// where the star is no closed fan; else `p`'s neighbours, and the neighbours to try
    /// moving `p` onto (after any at `p`'s position), `None` where the star rules that out.
    fn plan(&self, p: u32, star: &[u32]) -> Option<Plan> {
        let ClosedFan {
            neighbours,
            out,
            into,
        } = self.closed_fan(p, star)?;
        let creases: SmallVec<[usize; 4]> = (0..neighbours.len())
            .filter(|&i| !self.flat(out[i], into[i]))
            .collect();
        let targets: Option<Ids> = match creases[..] {
            [] => {
                // Input vertices (exact points) first.
                let mut t = neighbours.clone();
                t.sort_by_key(|&v| self.seam[v as usize]);
                Some(t)
            }
            [i, j] => {
                // Two planes that meet in a line (not one plane folded back): p and its
                // two neighbours on the crease lie on that line, exactly; p must be
                // strictly between them, which rounding (monotone) keeps per coordinate.
                let (pt, pu) = (self.parent(out[i]), self.parent(into[i]));
                // (The largest component of the line's direction first: its sign is
                // clear at once, where a zero one takes the slowest exact path.)
                let crossing = planes_line_axis(&pt, &pu).is_some();
                (crossing && self.between(neighbours[i], p, neighbours[j]))
                    .then(|| smallvec::smallvec![neighbours[i], neighbours[j]])
            }
            _ => None,
        };
        Some((neighbours, targets))
    }

    /// What the boolean's seam point `p`'s first star says of removing it. Both answers
    /// hold until `p`'s star changes (a removal next to it).
    fn first(&self, p: u32) -> First {
        if self.labels.is_some() || !self.complete(p) {
            return First::Unknown;
        }
        match self.plan(p, &self.star(p)) {
            None => First::RuledOut,
            Some((neighbours, None))
                if neighbours
                    .iter()
                    .all(|&q| self.positions[q as usize] != self.positions[p as usize]) =>
            {
                First::RuledOut
            }
            Some(plan) => First::Plan(plan),
        }
    }

    /// Flips the cap `t` (three distinct corners on one line) into the neighbour across
    /// its longest edge, split at the middle corner. Returns whether it did.
    fn flip_cap(&mut self, t: u32) -> bool {
        let tri = self.triangles[t as usize];
        let p = self.corners(tri);
        // The middle corner: strictly between the other two on some coordinate.
        let Some(k) = (0..3).find(|&k| {
            let (m, a, b) = (p[k], p[(k + 1) % 3], p[(k + 2) % 3]);
            (0..3).any(|x| (a[x] < m[x] && m[x] < b[x]) || (a[x] > m[x] && m[x] > b[x]))
        }) else {
            return false;
        };
        // The cap is (a, b, c) with c on a → b; the neighbour is (b, a, d).
        let (c, a, b) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
        if !(self.complete(a) && self.complete(b) && self.complete(c)) {
            return false;
        }
        let star_a = self.star(a);
        let label = |u: u32| self.labels.as_ref().map(|l| l[u as usize]);
        let across: Ids = star_a
            .iter()
            .copied()
            .filter(|&u| u != t && self.triangles[u as usize].contains(&b))
            .filter(|&u| label(u) == label(t))
            .collect();
        let [n] = across[..] else {
            return false;
        };
        let nt = self.triangles[n as usize];
        let i = nt.iter().position(|&v| v == b).unwrap_or(0);
        if nt[(i + 1) % 3] != a {
            return false; // not oriented as the cap: the surface is not consistent here
        }
        let d = nt[(i + 2) % 3];
        if self.neighbours(&self.star(c), c).binary_search(&d).is_ok() {
            return false; // the new edge c–d exists
        }
        let (new_t, new_n) = ([c, a, d], [b, c, d]);
        for x in [new_t, new_n] {
            let q = self.corners(x);
            if is_degenerate(q[0], q[1], q[2]) {
                return false;
            }
        }
        self.triangles[t as usize] = new_t;
        self.triangles[n as usize] = new_n;
        self.provenance[t as usize] = self.provenance[n as usize];
        self.add(c, n);
        self.add(d, t);
        self.report.flipped_caps += 1;
        true
    }

    fn zero_area(&self, t: u32) -> bool {
        let q = self.corners(self.triangles[t as usize]);
        is_degenerate(q[0], q[1], q[2])
    }
}

/// The exact clean-up of `mesh` (a boolean's result: valid, with `provenance` naming its
/// triangles' parents in `a` and `b`, and `seam_vertices` sorted): see the module's text.
/// Only the vertices `added` (seam points that are neither input's vertex) are removed.
/// Dead triangles and vertices are removed, each slot filled by the last live one (the
/// others keep their places); `provenance` and `seam_vertices` (sorted) follow.
pub(crate) fn clean_up(
    mesh: &mut Mesh,
    provenance: &mut Vec<Provenance>,
    seam_vertices: &mut Vec<u32>,
    added: &[u32],
    inputs: [&Mesh; 2],
) -> CleanupReport {
    clean_up_labelled(mesh, provenance, None, seam_vertices, added, inputs)
}

/// [`clean_up`] of a split's groups merged into one mesh (A's pieces and B's: two sheets
/// glued along the seam, whose edges have four triangles), `labels` naming each
/// triangle's group (and following it): a seam point goes only where the seam runs
/// straight through it and each sheet is flat around it ([`Cleanup::remove_across_sheets`]),
/// caps flip only within their group, so that no group changes shape and the groups
/// stay conforming.
pub(crate) fn clean_up_sheets(
    mesh: &mut Mesh,
    provenance: &mut Vec<Provenance>,
    labels: &mut Vec<u32>,
    seam_vertices: &mut Vec<u32>,
    added: &[u32],
    inputs: [&Mesh; 2],
) -> CleanupReport {
    clean_up_labelled(mesh, provenance, Some(labels), seam_vertices, added, inputs)
}

fn clean_up_labelled(
    mesh: &mut Mesh,
    provenance: &mut Vec<Provenance>,
    mut labels: Option<&mut Vec<u32>>,
    seam_vertices: &mut Vec<u32>,
    added: &[u32],
    [a, b]: [&Mesh; 2],
) -> CleanupReport {
    if added.is_empty() {
        return CleanupReport::default();
    }
    let nv = mesh.positions.len();
    let mut seam = vec![false; nv];
    for &v in added {
        seam[v as usize] = true;
    }
    // The stars of the seam vertices and of their neighbours: two passes over the
    // triangles (the second picks every triangle at a vertex of the first's).
    let touching = |marked: &[bool]| -> Vec<u32> {
        const CHUNK: usize = 1 << 15;
        let found: Vec<Vec<u32>> = mesh
            .triangles
            .par_chunks(CHUNK)
            .grained()
            .enumerate()
            .map(|(c, tris)| {
                let mut out = Vec::new();
                for (k, t) in tris.iter().enumerate() {
                    if marked[t[0] as usize] | marked[t[1] as usize] | marked[t[2] as usize] {
                        out.push((c * CHUNK + k) as u32);
                    }
                }
                out
            })
            .collect();
        found.concat()
    };
    let mut ring = seam.clone();
    for &t in &touching(&seam) {
        for v in mesh.triangles[t as usize] {
            ring[v as usize] = true;
        }
    }
    let around = touching(&ring);
    let mut slot = crate::par::filled(u32::MAX, nv);
    let mut stars: Vec<SmallVec<[u32; 8]>> = Vec::new();
    for &t in &around {
        for v in mesh.triangles[t as usize] {
            if ring[v as usize] {
                if slot[v as usize] == u32::MAX {
                    slot[v as usize] = stars.len() as u32;
                    stars.push(SmallVec::new());
                }
                stars[slot[v as usize] as usize].push(t);
            }
        }
    }
    let complete_slots = stars.len();
    let mut w = Cleanup {
        positions: &mesh.positions,
        triangles: std::mem::take(&mut mesh.triangles),
        alive: vec![true; provenance.len()],
        provenance: std::mem::take(provenance),
        inputs: [a, b],
        slot,
        stars,
        complete_slots,
        seam,
        dead_vertex: vec![false; nv],
        dead_triangles: Vec::new(),
        dead_vertices: Vec::new(),
        report: CleanupReport::default(),
        labels: labels.as_mut().map(|l| std::mem::take(&mut **l)),
    };
    // Seam points, then again those next to a removed one (its removal can make theirs
    // possible), until nothing changes.
    // What each one's own star says is found side by side first and used while its
    // star stays as it was: those it rules out are skipped, the others start from it
    // (the same outcome, the same order).
    let mut queue: Vec<u32> = added.iter().rev().copied().collect();
    let mut queued = w.seam.clone();
    let mut firsts: Vec<First> = added.par_iter().grained().map(|&p| w.first(p)).collect();
    // Per vertex: its place in `firsts` while its star is the first one.
    let mut first_of = vec![u32::MAX; nv];
    for (i, &p) in added.iter().enumerate() {
        first_of[p as usize] = i as u32;
    }
    let ruled_out = |firsts: &[First], first_of: &[u32], p: u32| {
        let i = first_of[p as usize];
        i != u32::MAX && matches!(firsts[i as usize], First::RuledOut)
    };
    // Checked in debug builds and the library's tests: a point is skipped only with the
    // star it was ruled out with.
    let check = cfg!(any(test, debug_assertions));
    let star_of = |w: &Cleanup, p: u32| -> Vec<[u32; 3]> {
        w.star(p).iter().map(|&t| w.triangles[t as usize]).collect()
    };
    let first_stars: FxHashMap<u32, Vec<[u32; 3]>> = added
        .iter()
        .filter(|&&p| check && ruled_out(&firsts, &first_of, p))
        .map(|&p| (p, star_of(&w, p)))
        .collect();
    while let Some(p) = queue.pop() {
        queued[p as usize] = false;
        if ruled_out(&firsts, &first_of, p) {
            assert!(
                !check || star_of(&w, p) == first_stars[&p],
                "star of {p} changed"
            );
            continue;
        }
        // A plan is used once: `p` comes back only when its star changes.
        let plan = match first_of[p as usize] {
            u32::MAX => None,
            i => match std::mem::replace(&mut firsts[i as usize], First::Unknown) {
                First::Plan(plan) => Some(plan),
                _ => None,
            },
        };
        if let Some((q, neighbours)) = w.remove(p, plan) {
            for x in neighbours.into_iter().chain([q]) {
                first_of[x as usize] = u32::MAX;
                if w.seam[x as usize] && !w.dead_vertex[x as usize] && !queued[x as usize] {
                    queued[x as usize] = true;
                    queue.push(x);
                }
            }
        }
    }
    // Caps left at the seam.
    let mut caps: Vec<u32> = added
        .par_iter()
        .grained()
        .filter(|&&v| !w.dead_vertex[v as usize])
        .flat_map_iter(|&v| w.star(v))
        .collect();
    caps.par_sort_unstable();
    caps.dedup();
    let caps: Vec<u32> = caps
        .into_par_iter()
        .grained()
        .filter(|&t| w.zero_area(t))
        .collect();
    for &t in &caps {
        if w.alive[t as usize] && w.zero_area(t) && !w.flip_cap(t) {
            w.report.zero_area_left += 1;
        }
    }
    let Cleanup {
        triangles,
        provenance: mut provenance_in,
        mut dead_triangles,
        mut dead_vertices,
        report,
        labels: labels_in,
        ..
    } = w;
    let mut labels_in = labels_in.unwrap_or_default();
    if report.triangles_removed == 0 {
        // Flips only: nothing to compact.
        mesh.triangles = triangles;
        *provenance = provenance_in;
        if let Some(l) = labels {
            *l = labels_in;
        }
        return report;
    }
    // Compact without moving what stays in place (few go): each dead triangle's and
    // dead vertex's slot below the new count takes the live one from the end (dead
    // vertices were collapsed, so they are unreferenced); ids follow.
    dead_triangles.sort_unstable();
    dead_vertices.sort_unstable();
    mesh.triangles = triangles;
    let filled = compact_from_end(mesh, &dead_triangles, dead_vertices, |from, to| {
        provenance_in[to] = provenance_in[from];
        if let Some(l) = labels_in.get(from).copied() {
            labels_in[to] = l;
        }
    });
    let nt = mesh.triangles.len();
    provenance_in.truncate(nt);
    labels_in.truncate(nt);
    if let Some(l) = labels {
        *l = labels_in;
    }
    *provenance = provenance_in;
    *seam_vertices = seam_vertices
        .iter()
        .filter_map(|&v| filled.renamed(v))
        .collect();
    seam_vertices.sort_unstable();
    report
}
