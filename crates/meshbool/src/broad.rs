//! Broad phase between two meshes: every pair of triangles, one from each mesh, whose boxes
//! overlap, found by cutting up the region where both meshes are.
//!
//! First a coarse grid over the common box of the two meshes: each mesh marks the cells its
//! triangles' boxes reach (one streaming pass over its triangles), and only the cells both
//! meshes reach are kept. Where two surfaces cross along a curve, that is a thin band of
//! cells around the curve, so the rest of both meshes is never touched again; a tree over
//! each whole mesh ([`crate::bvh`]) sorts and stores every triangle instead. The triangles
//! in kept cells are then sorted out per cell by halving it across its longest side again
//! and again; each half keeps the triangles of both meshes whose boxes meet it and shrinks
//! to the box both of its lists still cover, and a half that holds triangles of only one
//! mesh is dropped.
//!
//! Exactness: cells and cuts only route triangles, by boxes that contain the exact ones
//! (outward-rounded `f32`), so no triangle is lost on the way to a piece it meets; every
//! reported pair is confirmed on the exact `f64` boxes. A pair whose boxes overlap is
//! reported once: in the grid cell that holds the lowest corner of the boxes'
//! intersection (cells partition space by a monotone function of the coordinates) and there
//! in the one final piece whose half-open region (closed below, open above along every cut)
//! holds that corner.

use crate::par::Grain;
use rayon::prelude::*;

use crate::bvh::{overlaps, round_out, tri_box, Box3, Box3f};
use crate::Mesh;

/// Stop cutting when a piece has at most this many candidate pairs.
const LEAF_PAIRS: usize = 64;

/// Stop cutting after this many cuts (a guard; pieces that do not separate stop earlier).
const MAX_DEPTH: u32 = 60;

/// Pieces with more triangles than this are cut on both threads.
const PARALLEL: usize = 1 << 12;

/// At most this many grid cells along an axis (below 2¹⁰: ranges pack into 10-bit fields).
const MAX_CELLS: f64 = 128.0;

/// Grid cells are about this many typical triangle sizes wide.
const CELL_TRIANGLES: f64 = 2.0;

/// The typical size of a triangle of `a` and `b`: the median longest box side of a sample
/// of both.
pub(crate) fn typical_size(a: &Mesh, b: &Mesh) -> f64 {
    let mut sizes: Vec<f64> = [a, b]
        .iter()
        .flat_map(|m| {
            let n = m.triangles.len();
            let step = (n / 512).max(1);
            (0..n)
                .step_by(step)
                .map(move |t| longest_side(&tri_box(m, t as u32)))
        })
        .collect();
    sizes.sort_by(f64::total_cmp);
    sizes.get(sizes.len() / 2).copied().unwrap_or(0.0)
}

fn longest_side(b: &Box3) -> f64 {
    (0..3).map(|k| b[1][k] - b[0][k]).fold(0.0, f64::max)
}

/// A triangle is covered by pieces when its box is over this many piece widths long.
const LARGE: f64 = 4.0;

/// Pieces of a large triangle are at most this many typical sizes wide.
const PIECE: f64 = 2.0;

/// Pieces of a sliver are about this many times its width (its least altitude) wide.
const SLIVER: f64 = 16.0;

/// Large triangles are covered by pieces only when their boxes sweep at least this share
/// of what all boxes sweep.
const WORTH: f64 = 0.05;

/// Meshes of more triangles than this are judged on a sample of about this many first
/// (see [`cover_large`]).
const SAMPLE: u32 = 1 << 12;

/// At most this many pieces along a large triangle's side (this squared in all).
const MAX_PIECES: usize = 32;

/// The width of the pieces that cover triangle `t` of `m` in the broad phase, or `None`
/// when it is used whole: pieces are at most [`PIECE`] typical sizes wide, and for a
/// sliver about [`SLIVER`] times its own width; a triangle is cut when its box is over
/// [`LARGE`] piece widths long.
fn piece_width(m: &Mesh, t: u32, typical: f64) -> Option<f64> {
    if clearly_whole(m, t, typical) {
        return None;
    }
    piece_width_in_full(m, t, typical)
}

/// True when triangle `t` is certainly not cut into pieces ([`piece_width`] is `None`),
/// told without roots. The box is over LARGE widths long exactly when it is over
/// LARGE · PIECE typical sizes long or over LARGE · SLIVER altitudes (altitude = twice
/// the area over the longest edge). Most triangles are clearly neither: told from
/// squares, with a margin far above their rounding (and only where the squares neither
/// overflow nor underflow); `false` leaves the answer to [`piece_width_in_full`].
fn clearly_whole(m: &Mesh, t: u32, typical: f64) -> bool {
    let long = longest_side(&tri_box(m, t));
    let [a, b, c] = m.corners(t as usize);
    let (u, v, w) = (
        crate::vec3::sub(&b, &a),
        crate::vec3::sub(&c, &a),
        crate::vec3::sub(&c, &b),
    );
    let squared = |x: &[f64; 3]| crate::vec3::dot(x, x);
    let (edge2, area2) = (
        squared(&u).max(squared(&v)).max(squared(&w)),
        squared(&crate::vec3::cross(&u, &v)),
    );
    let (k, lhs) = (LARGE * SLIVER, long * long * edge2);
    long <= 0.999 * LARGE * PIECE * typical
        && area2.is_normal()
        && lhs.is_finite()
        && lhs <= 0.998 * k * k * area2
}

/// [`piece_width`] by its definition, with roots.
fn piece_width_in_full(m: &Mesh, t: u32, typical: f64) -> Option<f64> {
    let long = longest_side(&tri_box(m, t));
    if !long.is_finite() {
        return None;
    }
    let [a, b, c] = m.corners(t as usize);
    let (u, v, w) = (
        crate::vec3::sub(&b, &a),
        crate::vec3::sub(&c, &a),
        crate::vec3::sub(&c, &b),
    );
    let twice_area = crate::vec3::norm(&crate::vec3::cross(&u, &v));
    let edge = crate::vec3::norm(&u)
        .max(crate::vec3::norm(&v))
        .max(crate::vec3::norm(&w));
    let altitude = if edge > 0.0 { twice_area / edge } else { 0.0 };
    let width = (PIECE * typical).min((SLIVER * altitude).max(long / MAX_PIECES as f64));
    (width > 0.0 && long > LARGE * width).then_some(width)
}

/// What the broad phase's cover of large triangles needs to know of one mesh, whatever
/// the other mesh: kept by an operand ([`crate::kept::Keeps`]), so that a boolean with it
/// spares the pass over all its triangles (about 100 µs, 3 %, of the 5k spheres' union on
/// one thread).
///
/// Triangle `t` is cut at typical size `s` when its box is over 4 widths long, the width
/// being the smaller of twice `s` and a part that does not depend on `s`. So a triangle
/// cut at some `s` is either cut at every size (as at `s = ∞`: the slivers, kept here) or
/// longer than `8 s`, which no triangle is when the longest of all is not.
#[derive(Clone, Debug, Default)]
pub struct Slivers {
    /// The triangles cut at every typical size, ascending.
    ids: Vec<u32>,
    /// The longest box side of any triangle.
    longest: f64,
    /// The squares of the longest box sides summed over all triangles, and (in order)
    /// over the sample the cover weighs first.
    swept_all: f64,
    swept_sample: f64,
}

impl Slivers {
    /// The slivers and sums of `m`.
    pub fn of(m: &Mesh) -> Slivers {
        let n = m.triangles.len() as u32;
        let long = |t: u32| longest_side(&tri_box(m, t));
        let step = (n / SAMPLE).max(1);
        // The longest side and the swept sum in one pass over the triangles.
        let (longest, swept_all) = (0..n)
            .into_par_iter()
            .grained()
            .map(|t| {
                let l = long(t);
                (l, l.powi(2))
            })
            .reduce(|| (0.0, 0.0), |x, y| (x.0.max(y.0), x.1 + y.1));
        Slivers {
            ids: (0..n)
                .into_par_iter()
                .grained()
                .filter(|&t| piece_width(m, t, f64::INFINITY).is_some())
                .collect(),
            longest,
            swept_all,
            swept_sample: (0..n)
                .step_by(step as usize)
                .fold(0.0, |sum, t| sum + long(t).powi(2)),
        }
    }
}

/// A stand-in for `m` in the broad phase when some of its triangles are large next to the
/// typical size `typical` (long slivers of CAD tessellations, one triangle under a fine
/// mesh): each large triangle is cut into strips across its longest extent (parallel to
/// its shortest side), each strip into pieces along it where it is wide, and every piece
/// becomes a box carrier, a degenerate triangle whose corners are its box `[lo, hi, hi]`;
/// the other triangles stay as they are. The boxes of a large triangle together hold it:
/// each is its piece's computed box widened by more than the rounding error of the
/// pieces' corners. Returns the stand-in and, per triangle of it, the triangle of `m` it
/// stands for; `None` when no triangle is large, or the large ones' boxes are a small part
/// of all boxes ([`large_triangles`]).
///
/// A box around a long diagonal sliver holds a large region the sliver is nowhere near,
/// and every triangle of the other mesh there became a candidate pair; with the pieces,
/// the pairs are those near the sliver.
pub(crate) fn cover_large(
    m: &Mesh,
    typical: f64,
    slivers: Option<&Slivers>,
) -> Option<(Mesh, Vec<u32>)> {
    large_triangles(m, typical, slivers).map(|large| cut_large(m, &large))
}

/// The triangles of `m` that [`cover_large`] cuts into pieces, ascending, each with the
/// width of its pieces; `None` where the cover is not worth it (the large triangles' boxes
/// are a small part of all boxes) or no triangle is large.
pub(crate) fn large_triangles(
    m: &Mesh,
    typical: f64,
    slivers: Option<&Slivers>,
) -> Option<Vec<(u32, f64)>> {
    if !(typical.is_finite() && typical > 0.0) {
        return None;
    }
    // Worth it where the large triangles' boxes are a good part of all boxes (by the
    // square of their longest side, what a box sweeps of a surface): not for the few
    // slivers at the poles of a UV sphere. Judged first on an even sample (a full pass
    // over a 2M-triangle mesh costs a tenth of its boolean), then on every triangle.
    // With the mesh's slivers at hand, the large triangles are among them (when no
    // triangle is long next to `typical`), and the sums over all triangles are known.
    let n = m.triangles.len() as u32;
    let swept = |t: u32| longest_side(&tri_box(m, t)).powi(2);
    let step = (n / SAMPLE).max(1);
    let known = slivers.filter(|s| s.longest <= LARGE * (PIECE * typical));
    let large_among = |ids: &[u32]| -> Vec<(u32, f64)> {
        ids.iter()
            .filter_map(|&t| Some((t, piece_width(m, t, typical)?)))
            .collect()
    };
    let known_large = known.map(|s| large_among(&s.ids));
    if step > 1 {
        let (all, large) = match (known, &known_large) {
            (Some(s), Some(large)) => (
                s.swept_sample,
                large
                    .iter()
                    .filter(|&&(t, _)| t % step == 0)
                    .fold(0.0, |sum, &(t, _)| sum + swept(t)),
            ),
            _ => {
                let (mut all, mut large) = (0.0, 0.0);
                for t in (0..n).step_by(step as usize) {
                    let s = swept(t);
                    all += s;
                    if piece_width(m, t, typical).is_some() {
                        large += s;
                    }
                }
                (all, large)
            }
        };
        if large < WORTH * all {
            return None;
        }
    }
    let large: Vec<(u32, f64)> = known_large.unwrap_or_else(|| {
        (0..n)
            .into_par_iter()
            .grained()
            .filter_map(|t| Some((t, piece_width(m, t, typical)?)))
            .collect()
    });
    if large.is_empty() {
        return None;
    }
    let of_large: f64 = large.par_iter().grained().map(|&(t, _)| swept(t)).sum();
    let all = known.map_or_else(
        || (0..n).into_par_iter().grained().map(swept).sum(),
        |s| s.swept_all,
    );
    if of_large < WORTH * all {
        return None;
    }
    Some(large)
}

/// The stand-in of [`cover_large`] for the triangles `large` (ascending, each with the
/// width of its pieces) cut into pieces, and per triangle of it the triangle of `m` it
/// stands for.
pub(crate) fn cut_large(m: &Mesh, large: &[(u32, f64)]) -> (Mesh, Vec<u32>) {
    let mut positions = m.positions.clone();
    let mut triangles = Vec::with_capacity(m.triangles.len() + 8 * large.len());
    let mut parent = Vec::with_capacity(m.triangles.len() + 8 * large.len());
    let mut next = 0usize;
    for &(t, width) in large {
        let t = t as usize;
        triangles.extend_from_slice(&m.triangles[next..t]);
        parent.extend(next as u32..t as u32);
        next = t + 1;
        let corners = m.corners(t);
        // `a` opposite the shortest side `b c`.
        let len = |k: usize| {
            let (p, q) = (corners[(k + 1) % 3], corners[(k + 2) % 3]);
            (0..3).map(|x| (p[x] - q[x]).abs()).fold(0.0, f64::max)
        };
        let k = (0..3)
            .min_by(|&x, &y| len(x).total_cmp(&len(y)))
            .unwrap_or(0);
        let (a, b, c) = (corners[k], corners[(k + 1) % 3], corners[(k + 2) % 3]);
        let big = a
            .iter()
            .chain(&b)
            .chain(&c)
            .fold(0.0f64, |s, x| s.max(x.abs()));
        // Each corner below is within about 10 ulps of `big` of the exact one.
        let pad = 32.0 * f64::EPSILON * big + 1e-320;
        let ab: [f64; 3] = std::array::from_fn(|x| b[x] - a[x]);
        let bc: [f64; 3] = std::array::from_fn(|x| c[x] - b[x]);
        // The point at `t` of the way from `a` to side `b c`, `u` of the way along it.
        let at = |t: f64, u: f64| -> [f64; 3] {
            std::array::from_fn(|x| a[x] + t * ab[x] + (t * u) * bc[x])
        };
        let extent = |v: [f64; 3]| v.iter().fold(0.0f64, |s, x| s.max(x.abs()));
        let strips = ((extent(ab).max(extent(std::array::from_fn(|x| c[x] - a[x]))) / width).ceil()
            as usize)
            .clamp(1, MAX_PIECES);
        let across = extent(bc);
        for i in 0..strips {
            let (t0, t1) = (i as f64 / strips as f64, (i + 1) as f64 / strips as f64);
            let pieces = ((across * t1 / width).ceil() as usize).clamp(1, MAX_PIECES);
            for j in 0..pieces {
                let (u0, u1) = (j as f64 / pieces as f64, (j + 1) as f64 / pieces as f64);
                let q = [at(t0, u0), at(t0, u1), at(t1, u0), at(t1, u1)];
                let lo: [f64; 3] = std::array::from_fn(|x| {
                    q.iter().map(|p| p[x]).fold(f64::INFINITY, f64::min) - pad
                });
                let hi: [f64; 3] = std::array::from_fn(|x| {
                    q.iter().map(|p| p[x]).fold(f64::NEG_INFINITY, f64::max) + pad
                });
                let v = positions.len() as u32;
                positions.push(lo);
                positions.push(hi);
                triangles.push([v, v + 1, v + 1]);
                parent.push(t as u32);
            }
        }
    }
    triangles.extend_from_slice(&m.triangles[next..]);
    parent.extend(next as u32..m.triangles.len() as u32);
    (Mesh::new_unchecked(positions, triangles), parent)
}

/// A grid over the common box. Cell `c` along axis `k` holds the coordinates `x` with
/// `index(x, k) == c`, a monotone function of `x`, so the cells partition space (points
/// outside the box belong to the outermost cells) and a box `[lo, hi]` meets exactly the
/// cells `index(lo)..=index(hi)`.
struct Grid {
    lo: [f64; 3],
    scale: [f64; 3],
    dims: [u32; 3],
}

impl Grid {
    /// A grid over `common` with cells about [`CELL_TRIANGLES`] times as wide as the
    /// typical triangle of `a` and `b` (the median longest box side of a sample), at most
    /// [`MAX_CELLS`] per axis.
    fn new(common: &Box3, a: &Mesh, b: &Mesh) -> Grid {
        let ext: [f64; 3] = std::array::from_fn(|k| common[1][k] - common[0][k]);
        let longest = ext.iter().copied().fold(0.0, f64::max);
        let typical = typical_size(a, b);
        let width = (CELL_TRIANGLES * typical).max(longest / MAX_CELLS);
        // Extents that overflow to infinity get one cell (and scale 0: every coordinate
        // then has index 0, as `NaN.max(0.0)` is 0).
        let dims = std::array::from_fn(|k| {
            let n = ext[k] / width;
            if n.is_finite() && n > 0.0 {
                n.ceil().clamp(1.0, MAX_CELLS) as u32
            } else {
                1
            }
        });
        Grid {
            lo: common[0],
            scale: std::array::from_fn(|k| {
                if ext[k].is_finite() && ext[k] > 0.0 {
                    f64::from(dims[k]) / ext[k]
                } else {
                    0.0
                }
            }),
            dims,
        }
    }

    #[inline]
    fn index(&self, x: f64, k: usize) -> u32 {
        // Truncation of a non-negative value is its floor; `as` saturates (and takes the
        // NaN that finite input never gives to 0).
        let c = ((x - self.lo[k]) * self.scale[k]).max(0.0);
        (c as u32).min(self.dims[k] - 1)
    }

    /// The cells a box meets, per axis as `[first, last]`.
    #[inline]
    fn range(&self, b: &Box3) -> [[u32; 2]; 3] {
        [0, 1, 2].map(|k| [self.index(b[0][k], k), self.index(b[1][k], k)])
    }

    /// A range in one word, 10 bits per bound.
    #[inline]
    fn pack(r: &[[u32; 2]; 3]) -> u64 {
        r.iter().flatten().fold(0, |w, &c| (w << 10) | u64::from(c))
    }

    /// The range [`Grid::pack`] packed.
    #[inline]
    fn unpack(w: u64) -> [[u32; 2]; 3] {
        let at = |i: u32| ((w >> (10 * (5 - i))) & 0x3ff) as u32;
        [[at(0), at(1)], [at(2), at(3)], [at(4), at(5)]]
    }

    fn cells(&self) -> usize {
        self.dims.iter().map(|&d| d as usize).product()
    }

    #[inline]
    fn id(&self, c: [u32; 3]) -> usize {
        let [x, y, z] = c.map(|v| v as usize);
        let [nx, ny, _] = self.dims.map(|v| v as usize);
        x + nx * (y + ny * z)
    }

    /// Calls `f` with every cell id of `range`.
    #[inline]
    fn each(&self, range: &[[u32; 2]; 3], mut f: impl FnMut(usize)) {
        for z in range[2][0]..=range[2][1] {
            for y in range[1][0]..=range[1][1] {
                for x in range[0][0]..=range[0][1] {
                    f(self.id([x, y, z]));
                }
            }
        }
    }

    /// The cell holding `p`.
    fn cell_of(&self, p: &[f64; 3]) -> usize {
        self.id(std::array::from_fn(|k| self.index(p[k], k)))
    }
}

/// No cell: the triangle's box misses the common box.
const NOWHERE: u64 = u64::MAX;

/// The cells each triangle of `m` reaches, packed ([`Grid::pack`]; [`NOWHERE`] for a
/// triangle whose box misses `common`), and the set of all of them as bits.
fn reached(m: &Mesh, common: &Box3, grid: &Grid) -> (Vec<u64>, Vec<u64>) {
    let ranges: Vec<u64> = (0..m.triangles.len() as u32)
        .into_par_iter()
        .grained()
        .map(|t| {
            let e = tri_box(m, t);
            if overlaps(&e, common) {
                Grid::pack(&grid.range(&e))
            } else {
                NOWHERE
            }
        })
        .collect();
    let words = grid.cells().div_ceil(64);
    let bits = ranges
        .par_iter()
        .grained()
        .with_min_len(1 << 14)
        .fold(
            || (vec![0u64; words], NOWHERE),
            |(mut bits, last), &r| {
                // Neighbouring triangles mostly reach the same cells.
                if r != NOWHERE && r != last {
                    grid.each(&Grid::unpack(r), |c| bits[c / 64] |= 1 << (c % 64));
                }
                (bits, r)
            },
        )
        .map(|(bits, _)| bits)
        .reduce(
            || vec![0u64; words],
            |mut x, y| {
                x.iter_mut().zip(y).for_each(|(w, v)| *w |= v);
                x
            },
        );
    (ranges, bits)
}

/// One mesh's part in the search: the triangles that reach a kept cell, with their
/// rounded boxes (local index `i` is triangle `ids[i]`, ids ascending), and the pairs
/// `(cell, local index)` sorted.
struct Part<'a> {
    mesh: &'a Mesh,
    ids: Vec<u32>,
    boxes: Vec<Box3f>,
    items: Vec<(u32, u32)>,
}

impl<'a> Part<'a> {
    /// The triangles of `mesh` that reach a cell of `keep` (`ranges` from [`reached`]).
    fn new(mesh: &'a Mesh, ranges: &[u64], grid: &Grid, keep: &[u64]) -> Self {
        let kept = |c: usize| keep[c / 64] >> (c % 64) & 1 == 1;
        let mut found: Vec<(u32, u32)> = ranges
            .par_iter()
            .grained()
            .enumerate()
            .with_min_len(1 << 12)
            .fold(Vec::new, |mut out, (t, &r)| {
                if r != NOWHERE {
                    grid.each(&Grid::unpack(r), |c| {
                        if kept(c) {
                            out.push((c as u32, t as u32));
                        }
                    });
                }
                out
            })
            .reduce(Vec::new, |mut x, mut y| {
                x.append(&mut y);
                x
            });
        let mut ids: Vec<u32> = found.iter().map(|&(_, t)| t).collect();
        ids.par_sort_unstable();
        ids.dedup();
        let boxes = ids
            .par_iter()
            .grained()
            .map(|&t| round_out(&tri_box(mesh, t)))
            .collect();
        for f in &mut found {
            f.1 = ids.binary_search(&f.1).unwrap_or_default() as u32;
        }
        found.par_sort_unstable();
        Part {
            mesh,
            ids,
            boxes,
            items: found,
        }
    }

    /// The union of the rounded boxes of the triangles `list`.
    fn bound(&self, list: &[u32]) -> Box3 {
        let mut b = [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]];
        for &i in list {
            let c = &self.boxes[i as usize];
            for k in 0..3 {
                b[0][k] = b[0][k].min(f64::from(c[0][k]));
                b[1][k] = b[1][k].max(f64::from(c[1][k]));
            }
        }
        b
    }

    /// The triangles of `list` whose rounded boxes meet `lo..=hi` along `axis`.
    fn within(&self, list: &[u32], axis: usize, lo: f64, hi: f64) -> Vec<u32> {
        list.iter()
            .copied()
            .filter(|&i| {
                let c = &self.boxes[i as usize];
                f64::from(c[0][axis]) <= hi && f64::from(c[1][axis]) >= lo
            })
            .collect()
    }

    /// The local indices of the triangles in cell `c`.
    fn in_cell(&self, c: u32) -> Vec<u32> {
        let from = self.items.partition_point(|&(x, _)| x < c);
        self.items[from..]
            .iter()
            .take_while(|&&(x, _)| x == c)
            .map(|&(_, i)| i)
            .collect()
    }
}

/// The box of the positions of `m` (unreferenced vertices included: a larger box only
/// lets more triangles take part, never fewer).
fn position_bounds(m: &Mesh) -> Option<Box3> {
    m.positions
        .par_iter()
        .grained()
        .fold(
            || None,
            |b: Option<Box3>, p| {
                Some(match b {
                    None => [*p, *p],
                    Some([lo, hi]) => [
                        std::array::from_fn(|k| lo[k].min(p[k])),
                        std::array::from_fn(|k| hi[k].max(p[k])),
                    ],
                })
            },
        )
        .reduce(
            || None,
            |x, y| match (x, y) {
                (None, b) | (b, None) => b,
                (Some([l0, h0]), Some([l1, h1])) => Some([
                    std::array::from_fn(|k| l0[k].min(l1[k])),
                    std::array::from_fn(|k| h0[k].max(h1[k])),
                ]),
            },
        )
}

/// Every pair `(triangle of a, triangle of b)` whose exact boxes overlap (closed boxes:
/// touching counts), sorted. Degenerate triangles take part like any other. Indices must be
/// in range. Parallel.
pub fn overlapping_pairs(a: &Mesh, b: &Mesh) -> Vec<(u32, u32)> {
    if a.triangles.is_empty() || b.triangles.is_empty() {
        return Vec::new();
    }
    let (Some(ba), Some(bb)) = crate::par::join(|| position_bounds(a), || position_bounds(b))
    else {
        return Vec::new();
    };
    let common: Box3 = [
        std::array::from_fn(|k| ba[0][k].max(bb[0][k])),
        std::array::from_fn(|k| ba[1][k].min(bb[1][k])),
    ];
    if (0..3).any(|k| common[0][k] > common[1][k]) {
        return Vec::new();
    }
    let grid = Grid::new(&common, a, b);
    let ((ra, bits_a), (rb, bits_b)) =
        crate::par::join(|| reached(a, &common, &grid), || reached(b, &common, &grid));
    let keep: Vec<u64> = bits_a.iter().zip(&bits_b).map(|(x, y)| x & y).collect();
    let (pa, pb) = crate::par::join(
        || Part::new(a, &ra, &grid, &keep),
        || Part::new(b, &rb, &grid, &keep),
    );
    let mut cells: Vec<u32> = pa.items.iter().map(|&(c, _)| c).collect();
    cells.dedup();
    let own = [[f64::NEG_INFINITY; 3], [f64::INFINITY; 3]];
    let pairs: Vec<(u32, u32)> = cells
        .par_iter()
        .grained()
        .flat_map_iter(|&c| {
            let (la, lb) = (pa.in_cell(c), pb.in_cell(c));
            let at = Place {
                grid: &grid,
                cell: c as usize,
                own,
            };
            // Searched within the common box, not the cell's own box: rounding may put a
            // corner the cell holds just outside the box its bounds describe.
            let mut out = Vec::new();
            cut(&pa, &la, &pb, &lb, common, at, 0, &mut out);
            out
        })
        .collect();
    crate::bvh::sort_pairs(pairs, a.triangles.len(), false)
}

/// Which corner points a piece reports pairs for: those in grid cell `cell` and in `own`
/// (closed below, open above).
#[derive(Clone, Copy)]
struct Place<'g> {
    grid: &'g Grid,
    cell: usize,
    own: Box3,
}

impl Place<'_> {
    fn holds(&self, p: &[f64; 3]) -> bool {
        (0..3).all(|k| self.own[0][k] <= p[k] && p[k] < self.own[1][k])
            && self.grid.cell_of(p) == self.cell
    }
}

/// The pairs of triangles `la` of `a` and `lb` of `b` (local indices) whose exact boxes
/// overlap, the lowest corner of their intersection lying in `at`, searched within the
/// closed box `cell` (which holds every such corner), added to `out`.
#[allow(clippy::too_many_arguments)]
fn cut(
    a: &Part,
    la: &[u32],
    b: &Part,
    lb: &[u32],
    cell: Box3,
    at: Place,
    depth: u32,
    out: &mut Vec<(u32, u32)>,
) {
    if la.is_empty() || lb.is_empty() {
        return;
    }
    // Shrink to what both lists cover.
    let (ca, cb) = (a.bound(la), b.bound(lb));
    let cell: Box3 = [
        std::array::from_fn(|k| cell[0][k].max(ca[0][k]).max(cb[0][k])),
        std::array::from_fn(|k| cell[1][k].min(ca[1][k]).min(cb[1][k])),
    ];
    if (0..3).any(|k| cell[0][k] > cell[1][k]) {
        return;
    }
    let axis = (0..3)
        .max_by(|&i, &j| (cell[1][i] - cell[0][i]).total_cmp(&(cell[1][j] - cell[0][j])))
        .unwrap_or(0);
    let (lo, hi) = (cell[0][axis], cell[1][axis]);
    let mid = lo + (hi - lo) / 2.0;
    if la.len() * lb.len() <= LEAF_PAIRS || depth >= MAX_DEPTH || !(lo < mid && mid < hi) {
        return leaf(a, la, b, lb, &at, out);
    }
    let lists = |from: f64, to: f64| (a.within(la, axis, from, to), b.within(lb, axis, from, to));
    let (below, above) = (lists(lo, mid), lists(mid, hi));
    // A cut that leaves more pairs to test than it started with separates nothing (many
    // triangles of both meshes through one spot): test the pairs here.
    if below.0.len() * below.1.len() + above.0.len() * above.1.len() > la.len() * lb.len() {
        return leaf(a, la, b, lb, &at, out);
    }
    let half = |(ha, hb): (Vec<u32>, Vec<u32>), is_below: bool, out: &mut Vec<(u32, u32)>| {
        let (mut c, mut o) = (cell, at);
        if is_below {
            c[1][axis] = mid;
            o.own[1][axis] = mid;
        } else {
            c[0][axis] = mid;
            o.own[0][axis] = mid;
        }
        cut(a, &ha, b, &hb, c, o, depth + 1, out);
    };
    if la.len() + lb.len() > PARALLEL {
        let mut more = Vec::new();
        crate::par::join(|| half(below, true, out), || half(above, false, &mut more));
        out.append(&mut more);
    } else {
        half(below, true, out);
        half(above, false, out);
    }
}

/// Every pair of `la × lb` whose exact boxes overlap with the lowest corner of their
/// intersection in `at`, as triangle ids, added to `out`.
fn leaf(a: &Part, la: &[u32], b: &Part, lb: &[u32], at: &Place, out: &mut Vec<(u32, u32)>) {
    let exact_b: Vec<Box3> = lb
        .iter()
        .map(|&j| tri_box(b.mesh, b.ids[j as usize]))
        .collect();
    for &i in la {
        let ra = &a.boxes[i as usize];
        let mut ea: Option<Box3> = None;
        for (&j, eb) in lb.iter().zip(&exact_b) {
            let rb = &b.boxes[j as usize];
            if !(0..3).all(|k| ra[0][k] <= rb[1][k] && rb[0][k] <= ra[1][k]) {
                continue;
            }
            let ea = ea.get_or_insert_with(|| tri_box(a.mesh, a.ids[i as usize]));
            if !overlaps(ea, eb) {
                continue;
            }
            let corner = std::array::from_fn(|k| ea[0][k].max(eb[0][k]));
            if at.holds(&corner) {
                out.push((a.ids[i as usize], b.ids[j as usize]));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    /// The cover from a mesh's kept slivers is the cover of the full pass, at typical
    /// sizes where the slivers decide and where a triangle is long next to the size (the
    /// full pass then), on meshes judged whole and judged on a sample first.
    #[test]
    fn kept_slivers_give_the_cover_of_a_full_pass() {
        // A fan of `n` slivers of radius `r` around `c`.
        let fan = |c: [f64; 3], r: f64, n: u32| {
            let mut positions = vec![c];
            for k in 0..n {
                let a = std::f64::consts::TAU * f64::from(k) / f64::from(n);
                positions.push([c[0] + r * a.cos(), c[1] + r * a.sin(), c[2]]);
            }
            let triangles = (0..n).map(|k| [0, 1 + k, 1 + (k + 1) % n]).collect();
            Mesh::new(positions, triangles).unwrap()
        };
        let sphere = shapes::uv_sphere([0.0; 3], 1.0, 71, 36);
        let mut slivers = fan([0.0; 3], 1.0, 800);
        slivers.append(&fan([0.0, 0.0, 1e-3], 1.0, 800)).unwrap();
        // 20,000 small triangles (a sample first) with a fan of short slivers, or with
        // the fan and one long triangle.
        let ground = shapes::heightfield([-5.0, -5.0], [5.0, 5.0], 100, 100, |x, y| {
            0.1 * (x * y).sin()
        });
        let mut with_fan = ground.clone();
        with_fan.append(&fan([1.0, 1.0, 0.5], 0.5, 800)).unwrap();
        let mut with_long = with_fan.clone();
        let long = Mesh::new(
            vec![[-5.0, -5.0, 1.0], [5.0, -5.0, 1.0], [0.0, 5.0, 1.0]],
            vec![[0, 1, 2]],
        )
        .unwrap();
        with_long.append(&long).unwrap();
        // Near the share at which slivers are worth covering: 100 slivers among the
        // 20,000 (a share of about a tenth), and 30 placed where the sample looks (a
        // third of the sample's share, a thirtieth of the whole mesh's).
        let fan_part = |k: u32| {
            let mut f = fan([1.0, 1.0, 0.5], 0.5, 800);
            f.triangles.truncate(k as usize);
            f
        };
        let mut hundred = ground.clone();
        hundred.append(&fan_part(100)).unwrap();
        let sampled = {
            let mut m = ground.clone();
            m.append(&fan_part(30)).unwrap();
            let (n, g) = (m.triangles.len(), ground.triangles.len());
            let step = (n / SAMPLE as usize).max(1);
            let (mut plain, mut thin) = (m.triangles[..g].iter(), m.triangles[g..].iter());
            let mut order = Vec::with_capacity(n);
            while order.len() < n {
                let next = if order.len() % step == 0 {
                    thin.next()
                } else {
                    None
                };
                order.push(
                    *next
                        .or_else(|| plain.next())
                        .or_else(|| thin.next())
                        .unwrap(),
                );
            }
            m.triangles = order;
            m
        };
        let (mut kept, mut full, mut covered) = (0, 0, 0);
        for m in [
            &sphere, &slivers, &ground, &with_fan, &with_long, &hundred, &sampled,
        ] {
            let known = Slivers::of(m);
            let typical = typical_size(m, m);
            for t in [typical, 0.01 * typical, 100.0 * typical, 0.0, f64::INFINITY] {
                let want = cover_large(m, t, None);
                assert!(cover_large(m, t, Some(&known)) == want, "typical {t}");
                if known.longest > LARGE * (PIECE * t) {
                    full += 1;
                } else {
                    kept += 1;
                }
                covered += usize::from(want.is_some());
            }
        }
        assert!(
            kept >= 10 && full >= 5 && covered >= 4,
            "{kept} {full} {covered}"
        );
        // The two near the share: the first covered, the second judged on all its
        // triangles after its sample.
        let at = |m: &Mesh| cover_large(m, typical_size(m, m), Some(&Slivers::of(m)));
        assert!(at(&hundred).is_some() && at(&sampled).is_none());
        // The fans' slivers are cut at every size; the sphere's triangles (those at the
        // poles too) and the ground's at none.
        assert_eq!(Slivers::of(&slivers).ids.len(), 1600);
        assert_eq!(Slivers::of(&with_long).ids.len(), 800);
        assert!(Slivers::of(&sphere).ids.is_empty());
        assert!(Slivers::of(&ground).ids.is_empty());
    }

    fn brute(a: &Mesh, b: &Mesh) -> Vec<(u32, u32)> {
        let mut out = Vec::new();
        for i in 0..a.triangles.len() as u32 {
            let ea = tri_box(a, i);
            for j in 0..b.triangles.len() as u32 {
                if overlaps(&ea, &tri_box(b, j)) {
                    out.push((i, j));
                }
            }
        }
        out
    }

    /// The pairs equal brute force; returns how many there are.
    fn check(a: &Mesh, b: &Mesh) -> usize {
        let got = overlapping_pairs(a, b);
        let want = brute(a, b);
        assert_eq!(got.len(), want.len());
        assert!(got == want);
        got.len()
    }

    #[test]
    fn pairs_are_the_brute_force_pairs_under_rigid_motions() {
        let ball = shapes::uv_sphere([0.0; 3], 1.0, 24, 12);
        let ring = shapes::torus([0.0; 3], 1.0, 0.3, 24, 10);
        let mut found = 0;
        for k in 0..12 {
            let t = f64::from(k);
            let moved = shapes::rigid_motion(
                &ball,
                [t.sin(), 1.0, t.cos()],
                0.37 * t,
                [0.1 * t - 0.6, 0.05 * t, -0.03 * t],
            );
            found += check(&ball, &moved);
            found += check(&ring, &moved);
        }
        assert!(found > 1000, "{found}");
    }

    #[test]
    fn the_shortcut_for_small_triangles_keeps_every_piece_width() {
        // Regular triangles, slivers and needles of every aspect, around the two limits
        // (8 typical sizes long, 64 altitudes long), collinear and repeated corners, at
        // unit size and at 2^±300 (squares that underflow or overflow).
        let mut rng = crate::test_util::Rng(0x91ec);
        let mut m = Mesh::default();
        for _ in 0..20_000 {
            let scale = [1.0, 2f64.powi(-300), 2f64.powi(300)][(rng.next() % 3) as usize];
            let long = scale * 16.0 * rng.unit();
            let thin = long
                * [1.0, 1.0 / 64.0, 1.0 / 60.0, 1.0 / 70.0, 0.0][(rng.next() % 5) as usize]
                * (0.9 + 0.2 * rng.unit());
            let a = [scale * rng.unit(), scale * rng.unit(), scale * rng.unit()];
            let b = [a[0] + long, a[1], a[2]];
            let c = [
                a[0] + long * rng.unit(),
                a[1] + thin,
                a[2] + thin * rng.unit(),
            ];
            let v = m.positions.len() as u32;
            m.positions.extend([a, b, c]);
            m.triangles
                .push([v, v + 1, if rng.next() % 50 == 0 { v } else { v + 2 }]);
        }
        let mut large = 0;
        for typical in [1.0, 2f64.powi(-300), 2f64.powi(300), 0.9, 2.1] {
            for t in 0..m.triangles.len() as u32 {
                let want = piece_width_in_full(&m, t, typical);
                assert_eq!(piece_width(&m, t, typical), want, "{t} {typical}");
                large += usize::from(want.is_some());
            }
        }
        assert!(large > 10_000 && large < 90_000, "{large}");
    }

    #[test]
    fn touching_identical_and_coplanar_meshes() {
        let cube = Mesh::unit_cube();
        // Touching along a face (closed boxes), identical, shifted on a face, apart.
        let touching = Mesh::cuboid([1.0, 0.2, 0.2], [2.0, 0.8, 0.8]);
        assert!(check(&cube, &touching) > 0);
        assert!(check(&cube, &cube) > 12);
        let grid = shapes::heightfield([0.0, 0.0], [1.0, 1.0], 16, 16, |_, _| 0.0);
        let shifted = shapes::rigid_motion(&grid, [0.0, 0.0, 1.0], 0.0, [0.25, 0.125, 0.0]);
        assert!(check(&grid, &grid) > 2 * 16 * 16);
        assert!(check(&grid, &shifted) > 0);
        let apart = shapes::rigid_motion(&grid, [0.0, 0.0, 1.0], 0.0, [0.0, 0.0, 1e-9]);
        assert_eq!(check(&grid, &apart), 0);
        assert!(overlapping_pairs(&grid, &Mesh::default()).is_empty());
    }

    #[test]
    fn shared_fans_and_utm_coordinates() {
        // Both meshes have a fan of 200 triangles around the same poles: pieces there
        // never separate and end at the depth limit.
        let a = shapes::uv_sphere([0.0; 3], 1.0, 200, 6);
        let b = shapes::rigid_motion(&a, [0.0, 0.0, 1.0], 0.01, [0.0; 3]);
        assert!(check(&a, &b) > 2 * 200 * 200);
        // Far from the origin the rounded boxes are much larger than the triangles.
        let at = [512_345.5, 7_123_456.25, 250.0];
        let terrain = shapes::heightfield(
            [at[0] - 50.0, at[1] - 50.0],
            [at[0] + 50.0, at[1] + 50.0],
            40,
            40,
            |x, y| at[2] + ((x - at[0]) * 0.1).sin() * ((y - at[1]) * 0.1).cos(),
        );
        let ball = shapes::uv_sphere(at, 20.0, 16, 8);
        assert!(check(&terrain, &ball) > 0);
    }

    #[test]
    fn large_inputs_give_the_trees_pairs() {
        // Above the size where `intersect` switches from trees to the grid: the same
        // sorted pairs, for crossing and for identical meshes.
        use crate::bvh::Bvh;
        let a = shapes::uv_sphere([0.0; 3], 1.0, 300, 200);
        let b = shapes::rigid_motion(&a, [0.0, 0.0, 1.0], 0.1, [0.5, 0.0, 0.0]);
        assert!(a.triangles.len() + b.triangles.len() >= 100_000);
        for (x, y) in [(&a, &b), (&a, &a)] {
            let trees = Bvh::new(x).overlapping_pairs(x, &Bvh::new(y), y);
            let got = overlapping_pairs(x, y);
            assert!(!got.is_empty());
            assert!(got == trees);
        }
    }

    #[test]
    fn extents_beyond_f64_range() {
        // The common box is wider than the largest f64: one cell per axis, no panic.
        let tri = |x: f64| {
            Mesh::new_unchecked(
                vec![[x, 0.0, 0.0], [0.0, x, 0.0], [0.0, 0.0, x]],
                vec![[0, 1, 2]],
            )
        };
        let (a, b) = (tri(1e308), tri(-1e308));
        let mut both = a.clone();
        both.positions.extend(&b.positions);
        both.triangles.push([3, 4, 5]);
        assert_eq!(check(&both, &both), 4);
    }

    #[test]
    fn degenerate_triangles_take_part() {
        let cube = Mesh::unit_cube();
        let mut flat = Mesh::cuboid([0.5, 0.5, 0.5], [1.5, 1.5, 1.5]);
        let p = flat.positions.len() as u32;
        flat.positions.push([0.5, 0.5, 1.0]);
        flat.positions.push([0.7, 0.5, 1.0]);
        // A zero-area sliver and a point triangle, both on the cube's top face.
        flat.triangles.push([p, p + 1, p + 1]);
        flat.triangles.push([p, p, p]);
        assert!(check(&cube, &flat) > 0);
    }
}
