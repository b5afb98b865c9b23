//! The bit grid: a uniform grid of cells over the mesh's box, marking where the editor's
//! spatial index is complete, and keying triangles by their cells.

use rayon::prelude::*;
use rustc_hash::FxHashMap;

use super::shape::tri_box;
use crate::bvh::Box3;
use crate::par::Grain;
use crate::Mesh;

/// A uniform grid of cells over the mesh's box, some of them marked: the region where
/// the spatial index of the work is complete. A box's range of cells is monotone in its
/// coordinates, so a triangle whose box meets a box whose cells are all marked has a
/// marked cell in its own range.
#[derive(Clone)]
pub(super) struct Grid {
    pub(super) lo: [f64; 3],
    /// `1 / cell size` (0 for a mesh in one point).
    pub(super) inv: f64,
    pub(super) n: [usize; 3],
    /// Where each axis's cell sits in a [`Grid::packed`] cell, and its bits there.
    pub(super) shift: [u32; 3],
    pub(super) mask: [u32; 3],
    pub(super) bits: Vec<u64>,
}

impl Grid {
    /// At most this many cells.
    pub(super) const CELLS: usize = 1 << 24;
    /// At most this many cells along an axis.
    pub(super) const AXIS: usize = 1 << 21;
    /// [`Grid::key`] of a box spanning more than two cells along an axis.
    pub(super) const WIDE: u32 = u32::MAX;
    /// A bit of a [`Grid::packed`] cell that the packing leaves free (31: the three axes
    /// take at most 27 bits, as there are at most 2^24 cells), which [`Grid::key`] and
    /// [`Grid::unpacked`] ignore: the scan's mark of a vertex near the halo.
    pub(super) const NEAR_BIT: u32 = 31;
    /// What a row's look-up costs in [`Grid::keyed_near`], in entries looked at.
    pub(super) const ROW_COST: usize = 8;

    /// A grid over the mesh's vertices, with cells about the size of its triangles (so
    /// that most span one or two along each axis) and at most [`Grid::CELLS`].
    pub(super) fn new(mesh: &Mesh, d: f64) -> Grid {
        let (lo, hi) = mesh
            .positions
            .par_chunks(1 << 14)
            .grained()
            .map(|ps| {
                ps.iter().fold(
                    ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
                    |(lo, hi), p| {
                        (
                            std::array::from_fn(|k| lo[k].min(p[k])),
                            std::array::from_fn(|k| hi[k].max(p[k])),
                        )
                    },
                )
            })
            .reduce(
                || ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
                |a, b| {
                    (
                        std::array::from_fn(|k| a.0[k].min(b.0[k])),
                        std::array::from_fn(|k| a.1[k].max(b.1[k])),
                    )
                },
            );
        let ext: [f64; 3] = std::array::from_fn(|k| (hi[k] - lo[k]).max(0.0));
        // A typical triangle's longest edge, from a sample.
        let step = (mesh.triangles.len() / 256).max(1);
        let mut sample: Vec<f64> = mesh
            .triangles
            .iter()
            .step_by(step)
            .map(|t| {
                let p = t.map(|v| mesh.positions[v as usize]);
                let b = tri_box(&p);
                (0..3).map(|k| b[1][k] - b[0][k]).fold(0.0, f64::max)
            })
            .collect();
        sample.sort_by(f64::total_cmp);
        let typical = sample.get(sample.len() / 2).copied().unwrap_or(0.0);
        let count = |h: f64| -> [usize; 3] {
            ext.map(|e| {
                if h > 0.0 {
                    ((e / h) as usize).saturating_add(1)
                } else {
                    1
                }
            })
        };
        let fits = |n: [usize; 3]| {
            n.iter().all(|&c| c <= Self::AXIS)
                && n[0].saturating_mul(n[1]).saturating_mul(n[2]) <= Self::CELLS
        };
        let largest = ext[0].max(ext[1]).max(ext[2]);
        let mut h = typical.max(4.0 * d).max(largest / (1 << 23) as f64);
        while h > 0.0 && !fits(count(h)) {
            h *= 1.25;
        }
        let n = count(h);
        // Each axis packs in the bits its largest cell needs.
        let width = n.map(|c| usize::BITS - (c - 1).leading_zeros());
        debug_assert!(width.iter().sum::<u32>() <= Self::NEAR_BIT);
        Grid {
            lo,
            inv: if h > 0.0 { 1.0 / h } else { 0.0 },
            n,
            shift: [0, width[0], width[0] + width[1]],
            mask: width.map(|w| (1u32 << w) - 1),
            bits: vec![0; (n[0] * n[1] * n[2]).div_ceil(64)],
        }
    }

    /// The same grid with no cell marked.
    pub(super) fn empty(&self) -> Grid {
        Grid {
            bits: vec![0; self.bits.len()],
            ..*self
        }
    }

    /// Whether a triangle with [`Grid::key`] `key` touches a marked cell; `p` gives its
    /// corners, asked only for a triangle spanning many cells.
    #[inline]
    pub(super) fn touches_key(&self, key: u32, p: impl FnOnce() -> [[f64; 3]; 3]) -> bool {
        if key == Self::WIDE {
            self.touches(&tri_box(&p()))
        } else {
            self.key_touches(key)
        }
    }

    /// The cells' edge length.
    pub(super) fn size(&self) -> f64 {
        if self.inv > 0.0 {
            1.0 / self.inv
        } else {
            0.0
        }
    }

    /// The cell of coordinate `x` along axis `k`, clamped to the grid. Monotone in `x`.
    #[inline]
    pub(super) fn cell(&self, x: f64, k: usize) -> usize {
        // `as` saturates: below the grid → 0.
        let c = ((x - self.lo[k]) * self.inv) as usize;
        if c < self.n[k] {
            c
        } else {
            self.n[k] - 1
        }
    }

    /// The cells a box meets: `[lo, hi]` per axis.
    #[inline]
    pub(super) fn range(&self, b: &Box3) -> [[usize; 3]; 2] {
        let c = |i: usize, k: usize| self.cell(b[i][k], k);
        [[c(0, 0), c(0, 1), c(0, 2)], [c(1, 0), c(1, 1), c(1, 2)]]
    }

    pub(super) fn index(&self, c: [usize; 3]) -> usize {
        Self::index_of(self.n, c)
    }

    /// The index of cell `c` in a grid of `n` cells a side.
    #[inline]
    pub(super) fn index_of(n: [usize; 3], c: [usize; 3]) -> usize {
        (c[2] * n[1] + c[1]) * n[0] + c[0]
    }

    /// A point's cell, packed: each axis in its [`Grid::shift`] and [`Grid::mask`].
    #[inline]
    pub(super) fn packed(&self, p: &[f64; 3]) -> u32 {
        self.pack([0, 1, 2].map(|k| self.cell(p[k], k)))
    }

    /// A cell's coordinates, packed as in [`Grid::packed`].
    #[inline]
    pub(super) fn pack(&self, c: [usize; 3]) -> u32 {
        c[0] as u32 | (c[1] as u32) << self.shift[1] | (c[2] as u32) << self.shift[2]
    }

    /// A triangle's cells in 32 bits, from its corners' [`Grid::packed`] cells (the range
    /// of its box: cells are monotone): its lowest cell's index times 8, plus a bit per
    /// axis along which it spans two cells; [`Grid::WIDE`] when it spans more.
    #[inline]
    pub(super) fn key(&self, c: [u32; 3]) -> u32 {
        let mut low = [0usize; 3];
        let mut span = 0;
        for (k, low) in low.iter_mut().enumerate() {
            let [a, b, d] = c.map(|x| x >> self.shift[k] & self.mask[k]);
            let (lo, hi) = (a.min(b).min(d), a.max(b).max(d));
            match hi - lo {
                0 => {}
                1 => span |= 1 << k,
                _ => return Self::WIDE,
            }
            *low = lo as usize;
        }
        (self.index(low) as u32) << 3 | span
    }

    /// A box that a box meets if and only if the range of its cells meets `r` (the cells
    /// are monotone: the range of a box's cells is that of its corners).
    pub(super) fn enclosing(&self, r: &[[usize; 3]; 2]) -> Box3 {
        [
            std::array::from_fn(|k| self.first_at_least(k, r[0][k])),
            std::array::from_fn(|k| self.first_at_least(k, r[1][k] + 1)),
        ]
    }

    /// The least coordinate along axis `k` whose cell is `c` or more (a bisection over the
    /// doubles in order; `∞` where no cell is).
    pub(super) fn first_at_least(&self, k: usize, c: usize) -> f64 {
        // The doubles in order as integers (an involution, as in `f64::total_cmp`).
        let ord = |x: i64| x ^ (((x >> 63) as u64) >> 1) as i64;
        let at = |i: i64| f64::from_bits(ord(i) as u64);
        if c == 0 {
            return f64::NEG_INFINITY;
        }
        if c >= self.n[k] {
            return f64::INFINITY;
        }
        // cell(−∞) = 0 < c ≤ n − 1 = cell(∞).
        let (mut below, mut above) = (
            ord(f64::NEG_INFINITY.to_bits() as i64),
            ord(f64::INFINITY.to_bits() as i64),
        );
        while below < above - 1 {
            let mid = ((i128::from(below) + i128::from(above)) >> 1) as i64;
            if self.cell(at(mid), k) >= c {
                above = mid;
            } else {
                below = mid;
            }
        }
        at(above)
    }

    /// Whether a triangle with corners in the [`Grid::packed`] cells `c` spans more than
    /// two cells along an axis (its [`Grid::key`] is [`Grid::WIDE`]).
    #[inline]
    pub(super) fn wide(&self, c: [u32; 3]) -> bool {
        let mut wide = false;
        for k in 0..3 {
            let [a, b, d] = c.map(|x| x >> self.shift[k] & self.mask[k]);
            wide |= a.max(b).max(d) - a.min(b).min(d) > 1;
        }
        wide
    }

    /// The index of a [`Grid::packed`] cell.
    #[inline]
    pub(super) fn unpacked(&self, c: u32) -> usize {
        self.index(self.coordinates(c))
    }

    /// The coordinates of a [`Grid::packed`] cell.
    #[inline]
    pub(super) fn coordinates(&self, c: u32) -> [usize; 3] {
        [0, 1, 2].map(|k| (c >> self.shift[k] & self.mask[k]) as usize)
    }

    #[inline]
    pub(super) fn get(&self, i: usize) -> bool {
        self.bits[i / 64] >> (i % 64) & 1 == 1
    }

    /// Whether any cell of a [`Grid::key`] (not [`Grid::WIDE`]) is marked.
    #[inline]
    pub(super) fn key_touches(&self, key: u32) -> bool {
        let (base, span) = ((key >> 3) as usize, key & 7);
        if span == 0 {
            return self.get(base);
        }
        let (sy, sz) = (self.n[0], self.n[0] * self.n[1]);
        let (nx, ny, nz) = (span & 1, span >> 1 & 1, span >> 2 & 1);
        for z in 0..=nz {
            for y in 0..=ny {
                for x in 0..=nx {
                    if self.get(base + x as usize + y as usize * sy + z as usize * sz) {
                        return true;
                    }
                }
            }
        }
        false
    }

    /// The rows (along x) of a [`Grid::key`]-sorted list `keyed`: for each row that holds
    /// a key's lowest cell, the run of `keyed` there (`start`, `end`).
    pub(super) fn rows_of_keys(&self, keyed: &[(u32, u32)]) -> FxHashMap<u32, (u32, u32)> {
        let mut rows = FxHashMap::default();
        for (run, i) in keyed
            .chunk_by(|a, b| (a.0 >> 3) / self.n[0] as u32 == (b.0 >> 3) / self.n[0] as u32)
            .scan(0u32, |i, run| {
                let start = *i;
                *i += run.len() as u32;
                Some((run, start))
            })
        {
            rows.insert(
                (run[0].0 >> 3) / self.n[0] as u32,
                (i, i + run.len() as u32),
            );
        }
        rows
    }

    /// Calls `f` with the position in `keyed` ((key, id) sorted, no [`Grid::WIDE`] key,
    /// its rows `rows` ([`Grid::rows_of_keys`])) of every entry whose cells meet those of
    /// box `b` (a superset of the triangles whose boxes meet `b`), each once; of every
    /// entry where the rows would cost more than the whole list.
    pub(super) fn keyed_near(
        &self,
        keyed: &[(u32, u32)],
        rows: &FxHashMap<u32, (u32, u32)>,
        b: &Box3,
        mut f: impl FnMut(usize),
    ) {
        let r = self.range(b);
        // A triangle's cells along an axis are its key's lowest cell and perhaps the next:
        // those meeting the range have their lowest cell in it, or just below it and the
        // key's bit for that axis set. Row by row (along x, one run of keys each), or all
        // of them where the rows would cost more.
        let [x0, y0, z0] = r[0].map(|c| c.saturating_sub(1));
        let count = (r[1][1] - y0 + 1) * (r[1][2] - z0 + 1);
        if count.saturating_mul(Self::ROW_COST) > keyed.len() {
            (0..keyed.len()).for_each(f);
            return;
        }
        for z in z0..=r[1][2] {
            for y in y0..=r[1][1] {
                let Some(&(start, end)) = rows.get(&((z * self.n[1] + y) as u32)) else {
                    continue;
                };
                let run = &keyed[start as usize..end as usize];
                // The bits a key of this row must have.
                let need = u32::from(y < r[0][1]) << 1 | u32::from(z < r[0][2]) << 2;
                let lo = (self.index([x0, y, z]) as u32) << 3;
                let mid = (self.index([r[0][0], y, z]) as u32) << 3;
                let hi = (self.index([r[1][0], y, z]) as u32) << 3 | 7;
                let first = run.partition_point(|&(k, _)| k < lo);
                let last = first + run[first..].partition_point(|&(k, _)| k <= hi);
                let from = start as usize + first;
                for (i, &(k, _)) in (from..).zip(&run[first..last]) {
                    let need = need | u32::from(k < mid);
                    if k & need == need {
                        f(i);
                    }
                }
            }
        }
    }

    /// The blocks (of 4 × 4 × 4 cells) of the cells of a range, as a range.
    pub(super) fn blocks(&self, r: &[[usize; 3]; 2]) -> [[usize; 3]; 2] {
        r.map(|c| c.map(|x| x / 4))
    }

    /// Calls `f` with the id of each block of the range of blocks `r`.
    pub(super) fn all_blocks(&self, r: &[[usize; 3]; 2], mut f: impl FnMut(u32)) {
        let nb = self.n.map(|c| c.div_ceil(4));
        for z in r[0][2]..=r[1][2] {
            for y in r[0][1]..=r[1][1] {
                for x in r[0][0]..=r[1][0] {
                    f(Self::index_of(nb, [x, y, z]) as u32);
                }
            }
        }
    }

    /// The number of cells in a range.
    pub(super) fn cells(r: &[[usize; 3]; 2]) -> usize {
        (0..3).map(|k| r[1][k] - r[0][k] + 1).product()
    }

    /// Calls `f(word, mask)` for the bits of every row (along x) of the cells of `r`, a
    /// word at a time, until it says stop; whether it went through all of them.
    pub(super) fn rows(&self, r: &[[usize; 3]; 2], f: impl FnMut(usize, u64) -> bool) -> bool {
        Self::rows_of(self.n, r, f)
    }

    /// [`Grid::rows`] of a grid of `n` cells a side (without borrowing one, so that `f`
    /// may change its bits).
    pub(super) fn rows_of(
        n: [usize; 3],
        r: &[[usize; 3]; 2],
        mut f: impl FnMut(usize, u64) -> bool,
    ) -> bool {
        let index = |c: [usize; 3]| Self::index_of(n, c);
        for z in r[0][2]..=r[1][2] {
            for y in r[0][1]..=r[1][1] {
                let (first, last) = (index([r[0][0], y, z]), index([r[1][0], y, z]));
                for w in first / 64..=last / 64 {
                    let lo = if w == first / 64 { first % 64 } else { 0 };
                    let hi = if w == last / 64 { last % 64 } else { 63 };
                    let mask = (u64::MAX >> (63 - hi)) & (u64::MAX << lo);
                    if !f(w, mask) {
                        return false;
                    }
                }
            }
        }
        true
    }

    /// Marks the cells of `b`; whether any was new.
    pub(super) fn mark(&mut self, b: &Box3) -> bool {
        self.mark_range(&self.range(b))
    }

    /// [`Grid::mark`], noting the bits it set: (word, bits).
    pub(super) fn mark_noting(&mut self, b: &Box3, set: &mut Vec<(usize, u64)>) -> bool {
        let r = self.range(b);
        self.mark_range_with(&r, |w, fresh| set.push((w, fresh)))
    }

    /// Marks the cells of the range `r`; whether any was new.
    pub(super) fn mark_range(&mut self, r: &[[usize; 3]; 2]) -> bool {
        self.mark_range_with(r, |_, _| {})
    }

    /// [`Grid::mark_range`], telling `note` the bits newly set in each word.
    pub(super) fn mark_range_with(
        &mut self,
        r: &[[usize; 3]; 2],
        mut note: impl FnMut(usize, u64),
    ) -> bool {
        let (bits, mut new) = (&mut self.bits, false);
        Self::rows_of(self.n, r, |w, mask| {
            let fresh = mask & !bits[w];
            if fresh != 0 {
                new = true;
                bits[w] |= fresh;
                note(w, fresh);
            }
            true
        });
        new
    }

    /// Whether every cell of `b` is marked.
    pub(super) fn covers(&self, b: &Box3) -> bool {
        self.rows(&self.range(b), |w, mask| self.bits[w] & mask == mask)
    }

    /// Whether some cell of `b` is marked.
    pub(super) fn touches(&self, b: &Box3) -> bool {
        !self.rows(&self.range(b), |w, mask| self.bits[w] & mask == 0)
    }
}
