//! The editor: the working mesh (triangles killed and made, never edited), its rounds of
//! gathering neighbourhoods around the bad triangles, the queue, and the changes it hands
//! back ([`Edit`]).

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use rayon::prelude::*;
use rustc_hash::{FxHashMap, FxHashSet};

use super::grid::Grid;
use super::refusal::{Gate, Refusal, Refusal::*, Stop};
use super::scan::{Keyed, Scan};
use super::shape::{badness, grown, tri_box};
use super::{Edit, Labels, SnapOptions, SnapReport};
use crate::bvh::{overlaps as overlap, Box3};
use crate::par::Grain;
use crate::Mesh;

/// A bad triangle waiting in the queue, smallest key first.
#[derive(Clone, Copy, Debug)]
pub(super) struct Item {
    pub(super) key: f64,
    pub(super) t: u32,
}

impl PartialEq for Item {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}

impl Eq for Item {}

impl PartialOrd for Item {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for Item {
    fn cmp(&self, o: &Self) -> Ordering {
        // Reversed: the max-heap pops the smallest key (then the lowest id).
        o.key.total_cmp(&self.key).then(o.t.cmp(&self.t))
    }
}

/// What is known of the mesh near the work: the live triangles touching the marked
/// cells, gathered at the start of a round, sorted by their [`Grid::key`]s (the grid is
/// their spatial index: a box's triangles are found row by row of its cells), and the
/// triangles around each of their vertices; the triangles made since by grid cell.
#[derive(Default)]
pub(super) struct Near {
    /// The gathered triangles spanning at most two cells along each axis, as ([`Grid::key`],
    /// id), sorted.
    pub(super) keyed: Vec<(u32, u32)>,
    /// The boxes of the triangles of `keyed`, in its order, and its rows
    /// ([`Grid::rows_of_keys`]).
    pub(super) boxes: Vec<Box3>,
    pub(super) rows: FxHashMap<u32, (u32, u32)>,
    /// The gathered triangles spanning more ([`Grid::WIDE`]).
    pub(super) wide_in: Vec<u32>,
    /// Each vertex's id among the gathered triangles' vertices plus one (0: none; zeroed
    /// memory, whose pages the system maps only where written), and those vertices (to
    /// clear `local` for the next gathering without a new buffer).
    pub(super) local: Vec<u32>,
    pub(super) verts: Vec<u32>,
    /// The triangles (ids) around local vertex `l`: `around[start[l]..start[l + 1]]`.
    pub(super) start: Vec<u32>,
    pub(super) around: Vec<u32>,
    /// The triangles indexed since (made, or gathered by [`Editor::extend`]), in `later`
    /// and by the blocks ([`Grid::blocks`]) their boxes meet, or in `wide` where they meet
    /// many.
    pub(super) later: Vec<u32>,
    pub(super) blocks: FxHashMap<u32, Vec<u32>>,
    pub(super) wide: Vec<u32>,
    /// Whether the index was built ([`Editor::index`]).
    pub(super) built: bool,
}

impl Near {
    /// The triangles around vertex `v` in the index as built (none where `v` is not a
    /// corner of a gathered triangle).
    pub(super) fn indexed_around(&self, v: u32) -> &[u32] {
        match self.local.get(v as usize).filter(|&&l| l != 0) {
            Some(&l) => {
                let l = l - 1;
                &self.around[self.start[l as usize] as usize..self.start[l as usize + 1] as usize]
            }
            None => &[],
        }
    }
}

/// The working mesh. Triangles are never edited, only killed and made anew (so the
/// index's boxes stay true): ids below the input's triangle count are the input's,
/// those above are made, each in the place (`slot`) of an input triangle, which holds
/// at most one live triangle at a time.
pub(super) struct Editor<'a> {
    pub(super) mesh: &'a Mesh,
    pub(super) d: f64,
    pub(super) seam: &'a [u32],
    pub(super) labels: Labels<'a>,
    pub(super) sheets: Option<&'a [u32]>,
    /// The input's triangle count: the first made triangle's id.
    pub(super) base: u32,
    pub(super) killed: Vec<bool>,
    /// The input triangles killed, in order.
    pub(super) killed_list: Vec<u32>,
    pub(super) made: Vec<[u32; 3]>,
    pub(super) made_alive: Vec<bool>,
    pub(super) made_slot: Vec<u32>,
    /// The live triangle made in each slot whose input triangle was killed.
    pub(super) in_slot: FxHashMap<u32, u32>,
    /// The triangles around vertices changed since the round began (dead ones dropped
    /// lazily); the others' are in `near`.
    pub(super) stars: FxHashMap<u32, Vec<u32>>,
    /// Vertices collapsed away.
    pub(super) dead: FxHashSet<u32>,
    /// For a vertex that others were collapsed into: those (input) vertices.
    pub(super) absorbed: FxHashMap<u32, Vec<u32>>,
    /// Changes made so far, and for each vertex the count when it last changed.
    pub(super) changes: u32,
    /// A bound on the changes (each collapse removes a triangle and each flip makes two
    /// better, so the work ends anyway; this keeps it in proportion to what was found).
    pub(super) max_changes: u32,
    pub(super) touched: FxHashMap<u32, u32>,
    pub(super) grid: Grid,
    /// Cells around the marked ones (by [`Editor::HALO`] cells, marked at each full
    /// pass, or around the seam's points from the start), and the input triangles
    /// touching them at the last full pass (or the scan) with their [`Grid::key`]s.
    pub(super) halo: Grid,
    pub(super) candidates: Vec<(u32, u32)>,
    /// Each vertex's cell ([`Grid::packed`]), made at the first pass over all triangles
    /// (empty before).
    pub(super) cells: Vec<u32>,
    pub(super) near: Near,
    pub(super) budget: f64,
    /// Whether `budget` is `D` times the whole area (else times a part of it).
    pub(super) budget_whole: bool,
    pub(super) spent: f64,
    pub(super) heap: BinaryHeap<Item>,
    /// Every triangle found bad (to count those left).
    pub(super) ever_bad: Vec<u32>,
    /// The refusal of the last attempt to fix a triangle.
    pub(super) refusal: FxHashMap<u32, Refusal>,
    pub(super) report: SnapReport,
}

/// Rounds of gathering neighbourhoods and fixing.
pub(super) const MAX_ROUNDS: usize = 8;

/// In a list of triangles met ([`Editor::crossings`]): a meeting of two of the triangles
/// tested, rather than of one of them and a live triangle.
pub(super) const AMONG: u32 = u32::MAX;

impl<'a> Editor<'a> {
    /// Made triangles meeting at most this many blocks are indexed by block.
    pub(super) const FEW_BLOCKS: usize = 8;
    /// The halo's margin around the boxes marked at a full pass, in cells.
    pub(super) const HALO: f64 = 3.0;

    pub(super) fn new(
        mesh: &'a Mesh,
        opts: &SnapOptions<'a>,
        labels: Labels<'a>,
        scan: Scan,
        grid: Grid,
        halo: Grid,
    ) -> Self {
        let n = mesh.triangles.len();
        Editor {
            mesh,
            d: opts.tolerance,
            seam: opts.seam,
            labels,
            sheets: opts.sheets,
            base: n as u32,
            killed: vec![false; n],
            killed_list: Vec::new(),
            made: Vec::new(),
            made_alive: Vec::new(),
            made_slot: Vec::new(),
            in_slot: FxHashMap::default(),
            stars: FxHashMap::default(),
            dead: FxHashSet::default(),
            absorbed: FxHashMap::default(),
            changes: 0,
            max_changes: u32::try_from(16 * scan.bad.len() + 1024).unwrap_or(u32::MAX),
            touched: FxHashMap::default(),
            candidates: scan.candidates,
            cells: Vec::new(),
            halo,
            grid,
            near: Near::default(),
            budget: opts.tolerance * scan.area,
            budget_whole: !opts.seam_only,
            spent: 0.0,
            heap: BinaryHeap::new(),
            ever_bad: scan.bad.iter().map(|&(_, t)| t).collect(),
            refusal: FxHashMap::default(),
            report: SnapReport::default(),
        }
    }

    pub(super) fn tri(&self, t: u32) -> [u32; 3] {
        if t < self.base {
            self.mesh.triangles[t as usize]
        } else {
            self.made[(t - self.base) as usize]
        }
    }

    pub(super) fn alive(&self, t: u32) -> bool {
        if t < self.base {
            !self.killed[t as usize]
        } else {
            self.made_alive[(t - self.base) as usize]
        }
    }

    pub(super) fn kill(&mut self, t: u32) {
        if t < self.base {
            self.killed[t as usize] = true;
            self.killed_list.push(t);
        } else {
            self.made_alive[(t - self.base) as usize] = false;
        }
    }

    pub(super) fn slot(&self, t: u32) -> u32 {
        if t < self.base {
            t
        } else {
            self.made_slot[(t - self.base) as usize]
        }
    }

    pub(super) fn label(&self, t: u32) -> Option<u32> {
        let slot = self.slot(t);
        match self.labels {
            Labels::Given(l) => l.map(|l| l[slot as usize]),
            Labels::Of(f) => Some(f(slot)),
        }
    }

    pub(super) fn sheet(&self, t: u32) -> u32 {
        self.sheets.map_or(0, |s| s[self.slot(t) as usize])
    }

    pub(super) fn corners(&self, t: &[u32; 3]) -> [[f64; 3]; 3] {
        t.map(|v| self.mesh.positions[v as usize])
    }

    pub(super) fn pos(&self, v: u32) -> [f64; 3] {
        self.mesh.positions[v as usize]
    }

    pub(super) fn bad_key(&self, t: u32) -> Option<f64> {
        badness(&self.corners(&self.tri(t)), self.d)
    }

    /// The live triangles around `v`; `Later` when they are not all gathered (`v` is not
    /// in a marked cell: then some of its triangles may not touch one).
    pub(super) fn star(&self, v: u32) -> Gate<Vec<u32>> {
        let all: &[u32] = match self.stars.get(&v) {
            Some(s) => s,
            None => {
                if !self
                    .grid
                    .get(self.grid.unpacked(self.grid.packed(&self.pos(v))))
                {
                    return Err(Stop::Later);
                }
                self.near.indexed_around(v)
            }
        };
        // One allocation (a filter's `collect` would grow from nothing).
        let mut live = Vec::with_capacity(all.len());
        live.extend(all.iter().copied().filter(|&t| self.alive(t)));
        Ok(live)
    }

    /// Fixes bad triangles in rounds, starting from `seeds`.
    pub(super) fn run(&mut self, mut seeds: Vec<u32>) {
        for _ in 0..MAX_ROUNDS {
            if seeds.is_empty() {
                break;
            }
            let gathered = self.gather(&seeds);
            let before = self.changes;
            self.queue(&seeds);
            let mut later = Vec::new();
            let mut failed: Vec<(u32, u32)> = Vec::new();
            while let Some(Item { t, .. }) = self.heap.pop() {
                if self.changes >= self.max_changes {
                    self.heap.clear();
                    break;
                }
                if !self.alive(t) || self.bad_key(t).is_none() {
                    continue;
                }
                match self.fix(t) {
                    Ok(()) => {}
                    Err(Stop::Later) => later.push(t),
                    Err(Stop::Refused(r)) => {
                        self.refusal.insert(t, r);
                        failed.push((t, self.changes));
                    }
                }
            }
            if self.changes == before && !gathered {
                break;
            }
            // Next: what waited for its neighbourhood, and what was refused before
            // something around it changed.
            let touched_since = |w: &Self, t: u32, at: u32| {
                w.tri(t)
                    .iter()
                    .any(|v| w.touched.get(v).is_some_and(|&c| c > at))
            };
            later.extend(
                failed
                    .into_iter()
                    .filter(|&(t, at)| self.alive(t) && touched_since(self, t, at))
                    .map(|(t, _)| t),
            );
            later.sort_unstable();
            later.dedup();
            later.retain(|&t| self.alive(t));
            seeds = later;
        }
    }

    /// Marks the cells around `seeds` (their boxes grown by a cell and a few tolerances,
    /// and the boxes of the triangles around their vertices where those are known) and
    /// gathers every live triangle touching a marked cell; whether anything new was
    /// marked. A change at a seed then finds everything it needs: the triangles around
    /// its vertices (in marked cells), and every triangle its new triangles could meet.
    pub(super) fn gather(&mut self, seeds: &[u32]) -> bool {
        let by = self.grid.size() + 4.0 * self.d;
        let mut boxes: Vec<Box3> = Vec::new();
        let mut around: Vec<u32> = Vec::new();
        for &t in seeds {
            let tri = self.tri(t);
            boxes.push(grown(&tri_box(&self.corners(&tri)), by));
            for v in tri {
                around.extend(self.star(v).unwrap_or_default());
            }
        }
        // Each triangle once (a large one is around many seeds).
        around.sort_unstable();
        around.dedup();
        boxes.extend(
            around
                .iter()
                .map(|&s| grown(&tri_box(&self.corners(&self.tri(s))), 4.0 * self.d)),
        );
        let (mut marked, mut set) = (false, Vec::new());
        for b in &boxes {
            marked |= self.grid.mark_noting(b, &mut set);
        }
        if marked {
            // Within the halo the last full pass (or the scan) gathered its candidates
            // from, a pass over those finds every triangle (only those touching no cell
            // marked before, once there is an index); else the halo grows and all are
            // passed over.
            if boxes.iter().all(|b| self.halo.covers(b)) {
                if self.near.built {
                    let mut before = self.grid.clone();
                    for (w, bits) in set {
                        before.bits[w] &= !bits;
                    }
                    self.extend(&before);
                } else {
                    self.pass(false);
                }
            } else {
                let margin = Self::HALO * self.grid.size();
                for b in &boxes {
                    self.halo.mark(&grown(b, margin));
                }
                self.pass(true);
            }
        }
        marked
    }

    /// One pass over the triangles: every live one touching a marked cell, indexed (a
    /// tree, and the triangles around each vertex). `full`: over all of them, keeping
    /// those touching the halo as the candidates of the next passes; else over the
    /// candidates (the marked cells are all in the halo).
    pub(super) fn pass(&mut self, full: bool) {
        const PIECE: usize = 1 << 13;
        if full && self.cells.is_empty() {
            let grid = &self.grid;
            self.cells = (self.mesh.positions.par_iter().grained().with_min_len(PIECE))
                .map(|p| grid.packed(p))
                .collect();
        }
        let w = &*self;
        let mut keyed: Vec<(u32, u32)> = if full {
            let pieces: Vec<(Keyed, Keyed)> = self
                .mesh
                .triangles
                .par_chunks(PIECE)
                .grained()
                .enumerate()
                .map(|(k, tris)| {
                    let (mut ids, mut halo) = (Vec::new(), Vec::new());
                    for (i, tri) in tris.iter().enumerate() {
                        let t = (k * PIECE + i) as u32;
                        let p = || w.corners(tri);
                        let key = w.grid.key(tri.map(|v| w.cells[v as usize]));
                        if w.halo.touches_key(key, p) && w.alive(t) {
                            halo.push((t, key));
                            if w.grid.touches_key(key, p) {
                                ids.push((t, key));
                            }
                        }
                    }
                    (ids, halo)
                })
                .collect();
            let (ids, halo): (Vec<Keyed>, Vec<Keyed>) = pieces.into_iter().unzip();
            self.candidates = halo.concat();
            ids.concat()
        } else {
            self.candidates
                .par_iter()
                .grained()
                .with_min_len(PIECE)
                .filter(|&&(t, key)| {
                    // The corners only for a triangle spanning many cells (read at
                    // random, they would cost more than the rest).
                    w.grid
                        .touches_key(key, || w.corners(&w.mesh.triangles[t as usize]))
                        && w.alive(t)
                })
                .copied()
                .collect()
        };
        for i in 0..self.made.len() {
            let t = self.base + i as u32;
            let tri = self.made[i];
            if self.made_alive[i] && self.grid.touches(&tri_box(&self.corners(&tri))) {
                keyed.push((
                    t,
                    self.grid.key(tri.map(|v| self.grid.packed(&self.pos(v)))),
                ));
            }
        }
        self.index(keyed);
    }

    /// Adds to the index the live triangles touching the cells marked since `before` and
    /// none marked in it (candidates: the marked cells are all in the halo). The vertices
    /// in the newly marked cells get their stars: the triangles around them in the index
    /// as built, and those indexed since ([`Near::later`]: made, or added here or by an
    /// earlier extension). None of those vertices had one: a triangle around a vertex in
    /// a cell marked before touches that cell, so it was indexed.
    pub(super) fn extend(&mut self, before: &Grid) {
        const PIECE: usize = 1 << 13;
        let w = &*self;
        // The corners only for a triangle spanning many cells (read at random, they would
        // cost more than the rest).
        let newly = |key: u32, t: u32| {
            let p = || w.corners(&w.mesh.triangles[t as usize]);
            w.grid.touches_key(key, p) && !before.touches_key(key, p)
        };
        // (Every live triangle made before the index was built touches a cell marked
        // then: one of its corners is a changed vertex, whose star was known. So only
        // the candidates are new.)
        let added: Vec<u32> = self
            .candidates
            .par_iter()
            .grained()
            .with_min_len(PIECE)
            .filter(|&&(t, key)| newly(key, t) && w.alive(t))
            .map(|&(t, _)| t)
            .collect();
        for &t in &added {
            self.index_later(t);
        }
        // The vertices in newly marked cells, with the triangles indexed since around
        // them.
        let is_new = |v: u32| {
            let c = self.grid.unpacked(self.grid.packed(&self.pos(v)));
            self.grid.get(c) && !before.get(c)
        };
        let mut new_around: Vec<(u32, u32)> = (self.near.later.iter())
            .filter(|&&t| self.alive(t))
            .flat_map(|&t| self.tri(t).map(|v| (v, t)))
            .filter(|&(v, _)| is_new(v))
            .collect();
        new_around.sort_unstable();
        new_around.dedup();
        for run in new_around.chunk_by(|a, b| a.0 == b.0) {
            let v = run[0].0;
            let mut star = self.near.indexed_around(v).to_vec();
            for &(_, t) in run {
                if !star.contains(&t) {
                    star.push(t);
                }
            }
            debug_assert!(!self.stars.contains_key(&v));
            self.stars.insert(v, star);
        }
    }

    /// The index over the triangles `keyed` ((id, [`Grid::key`])): sorted by key, each
    /// vertex's triangles; the made triangles' cells and the changed stars start anew.
    pub(super) fn index(&mut self, keyed: Keyed) {
        let old = std::mem::take(&mut self.near);
        let mut local = old.local;
        if local.len() == self.mesh.positions.len() {
            for &v in &old.verts {
                local[v as usize] = 0;
            }
        } else {
            local = vec![0; self.mesh.positions.len()];
        }
        let mut verts = old.verts;
        verts.clear();
        let triangles: Vec<[u32; 3]> = keyed
            .iter()
            .map(|&(t, _)| {
                self.tri(t).map(|v| {
                    let l = &mut local[v as usize];
                    if *l == 0 {
                        verts.push(v);
                        *l = verts.len() as u32;
                    }
                    *l - 1
                })
            })
            .collect();
        // The triangles around each local vertex (a counting sort).
        let mut start = vec![0u32; verts.len() + 1];
        for tri in &triangles {
            for (j, &l) in tri.iter().enumerate() {
                if !tri[..j].contains(&l) {
                    start[l as usize + 1] += 1;
                }
            }
        }
        for i in 0..verts.len() {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut around = vec![0u32; start[verts.len()] as usize];
        for (tri, &(t, _)) in triangles.iter().zip(&keyed) {
            for (j, &l) in tri.iter().enumerate() {
                if !tri[..j].contains(&l) {
                    around[fill[l as usize] as usize] = t;
                    fill[l as usize] += 1;
                }
            }
        }
        let wide_in: Vec<u32> = keyed
            .iter()
            .filter(|&&(_, key)| key == Grid::WIDE)
            .map(|&(t, _)| t)
            .collect();
        let mut keyed: Vec<(u32, u32)> = keyed
            .into_iter()
            .filter(|&(_, key)| key != Grid::WIDE)
            .map(|(t, key)| (key, t))
            .collect();
        keyed.par_sort_unstable();
        let boxes = keyed
            .par_iter()
            .grained()
            .with_min_len(1 << 12)
            .map(|&(_, t)| tri_box(&self.corners(&self.tri(t))))
            .collect();
        let rows = self.grid.rows_of_keys(&keyed);
        self.near = Near {
            keyed,
            boxes,
            rows,
            wide_in,
            local,
            verts,
            start,
            around,
            later: Vec::new(),
            blocks: FxHashMap::default(),
            wide: Vec::new(),
            built: true,
        };
        self.stars.clear();
    }

    /// The live triangles whose boxes meet `b`, which the grid must cover.
    pub(super) fn near_triangles(&self, b: &Box3) -> Vec<u32> {
        let meets = |t: u32| self.alive(t) && overlap(&tri_box(&self.corners(&self.tri(t))), b);
        let mut out: Vec<u32> = Vec::with_capacity(64);
        let near = &self.near;
        self.grid.keyed_near(&near.keyed, &near.rows, b, |i| {
            let t = near.keyed[i].1;
            if overlap(&near.boxes[i], b) && self.alive(t) {
                out.push(t);
            }
        });
        out.extend(near.wide_in.iter().copied().filter(|&t| meets(t)));
        // Those indexed since: by block where the box meets few, else all of them.
        let r = self.grid.blocks(&self.grid.range(b));
        let later = if Grid::cells(&r) <= 4 * Self::FEW_BLOCKS {
            let mut later = near.wide.clone();
            self.grid.all_blocks(&r, |i| {
                if let Some(ids) = near.blocks.get(&i) {
                    later.extend(ids);
                }
            });
            later.sort_unstable();
            later.dedup();
            later
        } else {
            near.later.clone()
        };
        out.extend(later.into_iter().filter(|&t| meets(t)));
        out
    }

    /// A new triangle in the place of input triangle `slot`, indexed; its id.
    pub(super) fn make(&mut self, tri: [u32; 3], slot: u32) -> u32 {
        let id = self.base + self.made.len() as u32;
        self.made.push(tri);
        self.made_alive.push(true);
        self.made_slot.push(slot);
        self.in_slot.insert(slot, id);
        self.index_later(id);
        id
    }

    /// Indexes triangle `t` after the gathering (in [`Near::later`]).
    pub(super) fn index_later(&mut self, t: u32) {
        let r = self
            .grid
            .blocks(&self.grid.range(&tri_box(&self.corners(&self.tri(t)))));
        let near = &mut self.near;
        near.later.push(t);
        if Grid::cells(&r) <= Self::FEW_BLOCKS {
            let blocks = &mut near.blocks;
            self.grid
                .all_blocks(&r, |i| blocks.entry(i).or_default().push(t));
        } else {
            near.wide.push(t);
        }
    }

    /// After a change: the stars of the vertices of the new triangles `made` take them in,
    /// the vertices `around` are marked changed, bad new triangles are queued.
    pub(super) fn changed(&mut self, around: &[u32], made: &[u32]) {
        self.changes += 1;
        for &v in around {
            self.touched.insert(v, self.changes);
        }
        for &m in made {
            for v in self.tri(m) {
                self.touched.insert(v, self.changes);
                // Only vertices whose triangles are all known keep a list (the dead ones
                // in it are dropped when it is read).
                if let Some(s) = self.stars.get_mut(&v) {
                    if !s.contains(&m) {
                        s.push(m);
                    }
                } else if let Ok(mut s) = self.star(v) {
                    if !s.contains(&m) {
                        s.push(m);
                    }
                    self.stars.insert(v, s);
                }
            }
        }
        for &m in made {
            if self.bad_key(m).is_some() {
                self.ever_bad.push(m);
            }
        }
        self.queue(made);
    }

    /// Queues the bad ones of `ts`.
    pub(super) fn queue(&mut self, ts: &[u32]) {
        for &t in ts {
            if let Some(key) = self.bad_key(t) {
                self.heap.push(Item { key, t });
            }
        }
    }

    /// The report with the bad triangles left, counted by the refusal of their last fix.
    pub(super) fn finish_report(&mut self) -> SnapReport {
        let mut r = std::mem::take(&mut self.report);
        self.ever_bad.sort_unstable();
        self.ever_bad.dedup();
        for &t in &self.ever_bad {
            if !self.alive(t) || self.bad_key(t).is_none() {
                continue;
            }
            r.left += 1;
            match self.refusal.get(&t) {
                Some(Manifold) => r.refused_manifold += 1,
                Some(Inversion) => r.refused_inversion += 1,
                Some(SelfIntersection) => r.refused_self_intersection += 1,
                Some(Distance) => r.refused_distance += 1,
                Some(Volume) => r.refused_volume += 1,
                Some(Seam) => r.refused_seam += 1,
                Some(NoGain) => r.refused_no_gain += 1,
                None => r.not_reached += 1,
            }
        }
        r
    }

    /// The changes made: dead vertices, slots left empty, slots with a new triangle.
    pub(super) fn edit(&self) -> Edit {
        let mut dead: Vec<u32> = self.dead.iter().copied().collect();
        dead.sort_unstable();
        let (mut removed, mut replaced) = (Vec::new(), Vec::new());
        for &s in &self.killed_list {
            match self.in_slot.get(&s) {
                Some(&m) if self.alive(m) => replaced.push((s, self.tri(m))),
                _ => removed.push(s),
            }
        }
        removed.sort_unstable();
        Edit {
            dead,
            removed,
            replaced,
        }
    }
}
