//! The gates of a change: each collapse or flip is made only where the manifold,
//! inversion, self-intersection, distance and volume gates all pass (see the module
//! [`super`]), each decided exactly where it is a question of topology.

use std::cmp::Ordering;

use rayon::prelude::*;

use super::engine::{Editor, AMONG};
use super::link::collapse_topology;
use super::refusal::{refuse, Gate, Refusal, Refusal::*, Stop};
use super::shape::{altitude, max, min, shape, tri_box, volume6};
use crate::bvh::{overlaps as overlap, Box3};
use crate::intersect::corners_meet_beyond_shared;
use crate::kernel::{normals_dot_sign, orient3d_explicit, FloatPlane, Sign};
use crate::mesh_edit::{common, neighbours};
use crate::par::Grain;
use crate::vec3::{cross, dot, norm, sub};

impl Editor<'_> {
    /// Tries to fix bad triangle `t`: its short edges collapsed (shortest first, the
    /// better end kept first: the one that keeps the shape ([`Editor::offset`]), else the
    /// better ranked ([`Editor::rank`])), else its longest edge flipped.
    pub(super) fn fix(&mut self, t: u32) -> Gate<()> {
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
    pub(super) fn offset(&self, keep: u32, other: u32) -> Gate<f64> {
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
    pub(super) fn rank(&self, keep: u32) -> Gate<(u8, bool)> {
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
    pub(super) fn volume_gate(&mut self, dv: f64) -> Gate<()> {
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
    pub(super) fn clear_of(&self, new: &[[u32; 3]], killed: &[u32]) -> Gate<()> {
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
    pub(super) fn crossings(&self, tris: &[[u32; 3]], skip: &[u32]) -> Gate<Vec<u32>> {
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
    pub(super) fn collapse(&mut self, keep: u32, gone: u32) -> Gate<()> {
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
    pub(super) fn flip(&mut self, t: u32, k: usize) -> Gate<()> {
        self.flip_with(t, k, false)
    }

    /// Where collapsing `gone` onto `keep` fails the link condition only through
    /// neighbours `x` the two share beyond the edge's far corners: flips an edge
    /// `gone`–`x` (moving no vertex: the volume gate bounds it) so that the collapse may
    /// pass. Whether one was flipped.
    pub(super) fn unlock(&mut self, keep: u32, gone: u32) -> Gate<bool> {
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

    /// [`Editor::flip`]; `unlock`: for [`Editor::unlock`], without the gates on the cap's
    /// height and on the triangles' shape.
    pub(super) fn flip_with(&mut self, t: u32, k: usize, unlock: bool) -> Gate<()> {
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
}

/// Whether a triangle with corners `old` turns over (or becomes degenerate) when its
/// corners become `new`: the new normal is zero, or at a right angle or more to the old
/// one (exact signs). A degenerate `old` has no side to keep: only the first test applies.
pub(super) fn turns_over(old: &[[f64; 3]; 3], new: &[[f64; 3]; 3]) -> bool {
    if normals_dot_sign(new, new) == Sign::Zero {
        return true;
    }
    match normals_dot_sign(old, new) {
        Sign::Positive => false,
        Sign::Negative => true,
        Sign::Zero => normals_dot_sign(old, old) != Sign::Zero,
    }
}
