//! Generalized winding numbers (Jacobson et al. 2013), exact sum and a fast hierarchical
//! approximation (Barill et al. 2018, to the third term): far from a cluster of triangles,
//! the cluster's solid angle is expanded about its area-weighted centroid using its
//! area-weighted normal (dipole), the moment of the normals about the centroid and the
//! symmetric part of the normals' third moment.
//!
//! Winding numbers decide only what the exact seam-local tests cannot (pieces without a
//! seam, open surfaces whose seam stops inside a piece); they are measures, not
//! predicates, and are documented as such. The hierarchy bounds its own error (the far
//! field's Taylor remainder, [`far_error`]), and where a value's bound straddles the
//! threshold asked, [`FastWinding::sided_many`] completes it through the mesh's boundary
//! ([`Cone`]) or sums it exactly: the side it gives is the exact sum's.

use crate::par::Grain;
use rayon::prelude::*;
use std::cmp::Ordering::{Greater, Less};

use crate::bvh::morton_order_cube as morton_order;
use crate::vec3::{cross, dot, norm, sub};
use crate::Mesh;

/// `atan2` of van Oosterom–Strackee's formula for the solid angle of triangle `abc` seen
/// from `p`: the solid angle is twice this; positive when `p` is behind the triangle (its
/// normal points away from `p`).
#[inline]
fn half_solid_angle(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], p: &[f64; 3]) -> f64 {
    let (det, den, _) = solid_angle_vector(a, b, c, p);
    det.atan2(den)
}

/// The vector whose angle is [`half_solid_angle`]: van Oosterom–Strackee's triple
/// product and denominator, and the product of the corners' distances from `p`, which
/// scales both's rounding ([`Cone::at`]).
#[inline]
fn solid_angle_vector(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], p: &[f64; 3]) -> (f64, f64, f64) {
    let (a, b, c) = (sub(a, p), sub(b, p), sub(c, p));
    let (la, lb, lc) = (norm(&a), norm(&b), norm(&c));
    let lengths = la * lb * lc;
    let det = dot(&a, &cross(&b, &c));
    let den = lengths + dot(&a, &b) * lc + dot(&b, &c) * la + dot(&c, &a) * lb;
    (det, den, lengths)
}

/// Half solid angles summed, to a winding number: Ω / 4π = 2 · half / 4π.
const HALF_ANGLE_TO_WINDING: f64 = 1.0 / (2.0 * std::f64::consts::PI);

/// Generalized winding number of `mesh` at `p`: 1 inside a closed, outward-facing mesh, 0
/// outside; ±1/2 on either side of a large open surface (positive behind it, where its
/// normals point away). Exact sum over all triangles (in floating point), in parallel,
/// the same value bit for bit whatever the threads (fixed chunks summed in order).
pub fn winding_number(mesh: &Mesh, p: [f64; 3]) -> f64 {
    half_angles(mesh, &p, |_| true) * HALF_ANGLE_TO_WINDING
}

/// [`winding_number`] of `mesh` at `p` without triangle `skip`: at a point on `skip`
/// itself, whose own solid angle there is a half sphere of either sign, the other
/// triangles' sum is `w + 1/2` with `w` the winding number just in front of `skip`.
pub(crate) fn winding_number_without(mesh: &Mesh, p: [f64; 3], skip: usize) -> f64 {
    half_angles(mesh, &p, |t| t != skip) * HALF_ANGLE_TO_WINDING
}

/// [`winding_number`] of the triangles `t` of `mesh` with `keep(t)` at `p`: the same sum
/// over a subset without copying it.
pub(crate) fn winding_number_of(
    mesh: &Mesh,
    p: [f64; 3],
    keep: impl Fn(usize) -> bool + Sync,
) -> f64 {
    half_angles(mesh, &p, keep) * HALF_ANGLE_TO_WINDING
}

/// The half solid angles at `p` of the triangles `t` of `mesh` with `keep(t)`, summed in
/// order within fixed chunks side by side and the chunks' sums then in order: a sum
/// whose rounding does not depend on how the threads split the work (a parallel `sum`
/// splits where work is stolen), so that sides decided by exact sums are too.
fn half_angles(mesh: &Mesh, p: &[f64; 3], keep: impl Fn(usize) -> bool + Sync) -> f64 {
    const CHUNK: usize = 1 << 10;
    let n = mesh.triangles.len();
    let chunks: Vec<f64> = (0..n.div_ceil(CHUNK))
        .into_par_iter()
        .grained()
        .map(|c| {
            (c * CHUNK..(n.min((c + 1) * CHUNK)))
                .filter(|&t| keep(t))
                .map(|t| {
                    let [a, b, c] = mesh.corners(t);
                    half_solid_angle(&a, &b, &c, p)
                })
                .sum::<f64>()
        })
        .collect();
    chunks.iter().sum()
}

/// Triangle `abc`'s term of a winding number at `p` (what [`winding_number`] and the near
/// field of [`FastWinding`] add for it, computed the same way).
pub(crate) fn winding_term(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], p: &[f64; 3]) -> f64 {
    half_solid_angle(a, b, c, p) * HALF_ANGLE_TO_WINDING
}

/// A group's winding numbers and their error bounds ([`FastWinding::group`]).
type GroupValues = ([f64; 64], [f64; 64]);

/// Triangles per leaf of [`FastWinding`]. Four would save nothing on terrain ∪ terrain
/// (2.66G instructions for the run against 2.65G) for twice the nodes' memory; before
/// the expansion's third term they saved 6 %, but the raw values then erred by 0.033
/// at a sphere's centre, beyond the 0.03 documented for [`FastWinding::at`].
const LEAF: usize = 8;

/// Far-field criterion: a cluster is approximated when the query is farther from its
/// centre than `BETA` times its radius (Barill et al. use 2). Measured: within 0.03 of the
/// exact sum at random points around spheres, tori and height fields (tests; the error
/// is largest inside strongly curved closed meshes, where every cluster errs the same
/// way), some 180 times faster than the exact sum per query on 2M triangles; each value
/// comes with a bound on its error, 13 to 20 times the largest error seen (tests).
/// It only ever decides a threshold (1/2 closed, 0 open), never topology. Measured on
/// terrain ∪ terrain with the third term: 2 costs 5 % more instructions, 2.25 the same,
/// 2.75 1 % more (without it, 2 cost 10 % more, 4 and 5 10 and 23 %).
const BETA: f64 = 2.5;

/// A cluster as the queries read it, kept small (136 bytes) because every query walks
/// hundreds of them: the centre in `f64` (queries subtract it from input coordinates,
/// which may be UTM-sized), the expansion's coefficients in `f32` (each far-field term is
/// itself an approximation good to a fraction of a per cent; `f32` adds 1e-7 of it), the
/// bound on ∫ |y|³ in `f64` (it grows with the fifth power of the size: `f32` would
/// overflow or vanish on meshes a few billion or a hundred-billionth of a unit across).
#[derive(Clone, Copy, Debug, Default)]
struct Node {
    /// Area-weighted centroid.
    centre: [f64; 3],
    /// `(BETA · radius)²`: the query is in the far field beyond this squared distance.
    far2: f64,
    /// Area-weighted normal sum (half the cross products).
    normal: [f32; 3],
    /// Symmetric part of the second moment about `centre` (Σ area-normal ⊗ (triangle
    /// centroid − centre)): xx, yy, zz, xy, xz, yz. Only it enters the expansion.
    moment: [f32; 6],
    /// Fully symmetric part of the third moment about `centre` (Σ area-normal ⊗ ∫ y ⊗ y
    /// over the triangle, y = x − centre): xxx, yyy, zzz, xxy, xxz, xyy, yyz, xzz, yzz,
    /// xyz. Only it enters the expansion's third term.
    third: [f32; 10],
    /// The cluster's radius (the distance from `centre` to its farthest corner) and its
    /// total area, rounded up: what bounds the far field's error ([`far_error`]).
    radius: f32,
    area: f32,
    /// A bound on ∫ |x − centre|³ over the cluster's area (Cauchy–Schwarz over the
    /// second and fourth moments, [`Sums`]).
    cube: f64,
    /// Range of the cluster in `order`.
    start: u32,
    end: u32,
    /// Right child (left child follows the node); 0 for a leaf.
    right: u32,
}

/// What building a subtree needs from its children: the full-precision sums and bounds.
#[derive(Clone, Copy, Debug)]
struct Sums {
    normal: [f64; 3],
    centre: [f64; 3],
    area: f64,
    /// Σ area-normal ⊗ (triangle centroid − centre).
    moment: [[f64; 3]; 3],
    /// Fully symmetric part of Σ area-normal ⊗ ∫ y ⊗ y over each triangle / its area
    /// (y = x − centre), in the order of [`THIRD`].
    third: [f64; 10],
    /// A bound on the distance from `centre` to any corner in the cluster.
    radius: f64,
    /// ∫ y ⊗ y, ∫ |y|² y and ∫ |y|⁴ over the cluster's area (y = x − centre): what
    /// bounds ∫ |y|³ and moves to a parent's centre exactly ([`Sums::moved_area_moments`]).
    second: [[f64; 3]; 3],
    skew: [f64; 3],
    fourth: f64,
    /// Bounding box of the corners.
    bbox: [[f64; 3]; 2],
}

impl Sums {
    /// ∫ y ⊗ y, ∫ |y|² y and ∫ |y|⁴ of the cluster about `centre` instead of its own
    /// centre (its area-weighted centroid, about which ∫ y vanishes): with δ = own centre
    /// − `centre`, C + A δ ⊗ δ; V + tr C δ + 2 C δ + A |δ|² δ; Q + 4 δ·V + 2 |δ|² tr C +
    /// 4 δᵀ C δ + A |δ|⁴ (from |y + δ|² = |y|² + 2 y·δ + |δ|²).
    fn moved_area_moments(&self, centre: &[f64; 3]) -> ([[f64; 3]; 3], [f64; 3], f64) {
        let (c, a) = (&self.second, self.area);
        let d = sub(&self.centre, centre);
        let dd = dot(&d, &d);
        let trace = c[0][0] + c[1][1] + c[2][2];
        let cd: [f64; 3] = std::array::from_fn(|j| dot(&c[j], &d));
        let second = std::array::from_fn(|j| std::array::from_fn(|k| c[j][k] + a * d[j] * d[k]));
        let skew = std::array::from_fn(|j| self.skew[j] + (trace + a * dd) * d[j] + 2.0 * cd[j]);
        let fourth = self.fourth
            + 4.0 * dot(&d, &self.skew)
            + 2.0 * dd * trace
            + 4.0 * dot(&d, &cd)
            + a * dd * dd;
        (second, skew, fourth)
    }

    /// A bound on ∫ |y|³ over the cluster: ∫ |y| |y|² ≤ (∫ |y|² ∫ |y|⁴)^½.
    fn cube(&self) -> f64 {
        let trace = self.second[0][0] + self.second[1][1] + self.second[2][2];
        (trace.max(0.0) * self.fourth.max(0.0)).sqrt()
    }
}

/// The index triples of the symmetric third moment's ten components, as [`Node`] keeps
/// them.
const THIRD: [[usize; 3]; 10] = [
    [0, 0, 0],
    [1, 1, 1],
    [2, 2, 2],
    [0, 0, 1],
    [0, 0, 2],
    [0, 1, 1],
    [1, 1, 2],
    [0, 2, 2],
    [1, 2, 2],
    [0, 1, 2],
];

/// Nodes of the subtree over `n` triangles.
fn subtree_nodes(n: usize) -> usize {
    if n <= LEAF {
        1
    } else {
        1 + subtree_nodes(n / 2) + subtree_nodes(n - n / 2)
    }
}

/// A hierarchy for fast winding-number queries against one mesh: cost grows with the log
/// of the triangle count far from the surface, exact sums near it (within `BETA`
/// cluster radii).
pub struct FastWinding<'a> {
    mesh: &'a Mesh,
    order: Vec<u32>,
    nodes: Vec<Node>,
    /// The cone over the mesh's boundary, built when first asked ([`Cone`]).
    cone: std::sync::OnceLock<Cone>,
}

impl<'a> FastWinding<'a> {
    /// Builds the hierarchy over `mesh`'s triangles (Morton order, balanced, parallel).
    pub fn new(mesh: &'a Mesh) -> Self {
        let order = morton_order(mesh);
        let mut nodes = vec![Node::default(); subtree_nodes(order.len()).max(1)];
        if !order.is_empty() {
            Self::build(mesh, &order, 0, order.len(), 0, &mut nodes);
        } else {
            nodes.clear();
        }
        FastWinding {
            mesh,
            order,
            nodes,
            cone: std::sync::OnceLock::new(),
        }
    }

    /// The hierarchy with the cone of [`FastWinding::sided_many`] built over `boundary`,
    /// which must be the mesh's [`crate::edges::unbalanced_edges`] (for a caller that has
    /// them already: they are not found again).
    pub(crate) fn with_boundary(mut self, boundary: &[([u32; 2], i32)]) -> Self {
        self.cone = std::sync::OnceLock::from(Cone::over(self.mesh, boundary));
        self
    }

    /// Fills `nodes` (the pre-order subtree over `order[start..end]`, its first node having
    /// index `base`) and returns the sums of its root.
    fn build(
        mesh: &Mesh,
        order: &[u32],
        start: usize,
        end: usize,
        base: usize,
        nodes: &mut [Node],
    ) -> Sums {
        let n = end - start;
        let (sums, right) = if n <= LEAF {
            // One pass for each triangle's half cross product, area and centroid (kept
            // for the second), the sums and the box; the centre is then known, and one
            // pass more takes the moments about it and the radius.
            let tris = &order[start..end];
            let (mut nts, mut ars) = ([[0.0; 3]; LEAF], [0.0; LEAF]);
            let mut centroids = [[0.0; 3]; LEAF];
            let (mut normal, mut weighted, mut area) = ([0.0; 3], [0.0; 3], 0.0);
            let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
            for (j, &t) in tris.iter().enumerate() {
                let [a, b, c] = mesh.corners(t as usize);
                let nt = cross(&sub(&b, &a), &sub(&c, &a)).map(|x| x / 2.0);
                let centroid: [f64; 3] = std::array::from_fn(|k| (a[k] + b[k] + c[k]) / 3.0);
                let ar = norm(&nt);
                for k in 0..3 {
                    normal[k] += nt[k];
                    weighted[k] += ar * centroid[k];
                    lo[k] = lo[k].min(a[k]).min(b[k]).min(c[k]);
                    hi[k] = hi[k].max(a[k]).max(b[k]).max(c[k]);
                }
                area += ar;
                (nts[j], ars[j], centroids[j]) = (nt, ar, centroid);
            }
            let centre = if area > 0.0 {
                weighted.map(|x| x / area)
            } else {
                mesh.corners(order[start] as usize)[0]
            };
            let (mut moment, mut third) = ([[0.0; 3]; 3], [0.0; 10]);
            let (mut second, mut skew, mut fourth) = ([[0.0; 3]; 3], [0.0; 3], 0.0);
            let mut radius2: f64 = 0.0;
            let kept = nts.iter().zip(ars).zip(&centroids);
            for (&t, ((nt, ar), centroid)) in tris.iter().zip(kept) {
                for i in 0..3 {
                    for j in 0..3 {
                        moment[i][j] += nt[i] * (centroid[j] - centre[j]);
                    }
                }
                // ∫ y ⊗ y over a triangle is its area over 12 times Σ v ⊗ v + s ⊗ s (v its
                // corners from the centre, s their sum).
                let vs = mesh.corners(t as usize).map(|v| sub(&v, &centre));
                let sum: [f64; 3] = std::array::from_fn(|k| vs[0][k] + vs[1][k] + vs[2][k]);
                let mut yy = [[0.0; 3]; 3];
                for j in 0..3 {
                    for k in j..3 {
                        let v = vs[0][j] * vs[0][k] + vs[1][j] * vs[1][k] + vs[2][j] * vs[2][k];
                        yy[j][k] = (v + sum[j] * sum[k]) / 12.0;
                        yy[k][j] = yy[j][k];
                    }
                }
                // Symmetrized: n ⊗ Y averaged over the three places of n.
                for (s, &[i, j, k]) in third.iter_mut().zip(&THIRD) {
                    *s += (nt[i] * yy[j][k] + nt[j] * yy[i][k] + nt[k] * yy[i][j]) / 3.0;
                }
                // The triangle's ∫ y ⊗ y, ∫ |y|² y and ∫ |y|⁴: its area times the
                // moments of the barycentric coordinates (Dirichlet(1, 1, 1): E[λ^α] =
                // 2 α! / (|α| + 2)!) summed over the corners' products.
                let mut g = [[0.0; 3]; 3];
                for i in 0..3 {
                    for j in i..3 {
                        g[i][j] = dot(&vs[i], &vs[j]);
                        g[j][i] = g[i][j];
                    }
                    // The farthest corner from the centre: the radius.
                    radius2 = radius2.max(g[i][i]);
                }
                let ss = dot(&sum, &sum);
                let p = g[0][0] + g[1][1] + g[2][2];
                let at_s: [f64; 3] = std::array::from_fn(|i| dot(&vs[i], &sum));
                for j in 0..3 {
                    for k in 0..3 {
                        second[j][k] += ar * yy[j][k];
                    }
                    let cubic = (ss + p) * sum[j]
                        + 2.0
                            * ((at_s[0] + g[0][0]) * vs[0][j]
                                + (at_s[1] + g[1][1]) * vs[1][j]
                                + (at_s[2] + g[2][2]) * vs[2][j]);
                    skew[j] += ar * cubic / 60.0;
                }
                let r = dot(&at_s, &at_s);
                let t = g[0][0] * at_s[0] + g[1][1] * at_s[1] + g[2][2] * at_s[2];
                let f: f64 = g.iter().flatten().map(|x| x * x).sum();
                let u = g[0][0] * g[0][0] + g[1][1] * g[1][1] + g[2][2] * g[2][2];
                let quartic =
                    ss * ss + 2.0 * p * ss + 4.0 * r + 8.0 * t + p * p + 2.0 * f + 6.0 * u;
                fourth += ar * quartic / 360.0;
            }
            let sums = Sums {
                normal,
                centre,
                area,
                moment,
                third,
                radius: radius2.sqrt(),
                second,
                skew,
                fourth,
                bbox: [lo, hi],
            };
            (sums, 0)
        } else {
            let mid = start + n / 2;
            let (_, rest) = nodes.split_at_mut(1);
            let (left, right) = rest.split_at_mut(subtree_nodes(n / 2));
            let right_base = base + 1 + left.len();
            let (l, r) = if n > 1 << 14 {
                crate::par::join(
                    || Self::build(mesh, order, start, mid, base + 1, left),
                    || Self::build(mesh, order, mid, end, right_base, right),
                )
            } else {
                (
                    Self::build(mesh, order, start, mid, base + 1, left),
                    Self::build(mesh, order, mid, end, right_base, right),
                )
            };
            let area = l.area + r.area;
            let centre = if area > 0.0 {
                std::array::from_fn(|k| (l.area * l.centre[k] + r.area * r.centre[k]) / area)
            } else {
                l.centre
            };
            // Every corner lies within a child's radius of the child's centre, and in the
            // box of both children's boxes: the smaller of the two bounds.
            let lo: [f64; 3] = std::array::from_fn(|k| l.bbox[0][k].min(r.bbox[0][k]));
            let hi: [f64; 3] = std::array::from_fn(|k| l.bbox[1][k].max(r.bbox[1][k]));
            let far: [f64; 3] = std::array::from_fn(|k| (centre[k] - lo[k]).max(hi[k] - centre[k]));
            let radius = (norm(&sub(&l.centre, &centre)) + l.radius)
                .max(norm(&sub(&r.centre, &centre)) + r.radius)
                .min(norm(&far));
            // Moments moved to the new centre: M + N ⊗ (child centre − centre).
            let moment = std::array::from_fn(|i| {
                std::array::from_fn(|j| {
                    l.moment[i][j]
                        + r.moment[i][j]
                        + l.normal[i] * (l.centre[j] - centre[j])
                        + r.normal[i] * (r.centre[j] - centre[j])
                })
            });
            // Third moments moved: H + M ⊗ δ + (M ⊗ δ, its last two indices swapped) +
            // N ⊗ δ ⊗ δ, δ = child centre − centre; symmetrized, with P = M + Mᵀ, S +
            // (P_ij δ_k + P_ik δ_j + P_jk δ_i + N_i δ_j δ_k + N_j δ_i δ_k + N_k δ_i δ_j) / 3.
            let moved_third = |c: &Sums| -> [f64; 10] {
                let dl = sub(&c.centre, &centre);
                let (m, n) = (&c.moment, &c.normal);
                let p = |i: usize, j: usize| m[i][j] + m[j][i];
                std::array::from_fn(|x| {
                    let [i, j, k] = THIRD[x];
                    c.third[x]
                        + (p(i, j) * dl[k]
                            + p(i, k) * dl[j]
                            + p(j, k) * dl[i]
                            + n[i] * dl[j] * dl[k]
                            + n[j] * dl[i] * dl[k]
                            + n[k] * dl[i] * dl[j])
                            / 3.0
                })
            };
            let (tl, tr) = (moved_third(&l), moved_third(&r));
            let third = std::array::from_fn(|x| tl[x] + tr[x]);
            let (ml, mr) = (l.moved_area_moments(&centre), r.moved_area_moments(&centre));
            let sums = Sums {
                normal: std::array::from_fn(|k| l.normal[k] + r.normal[k]),
                centre,
                area,
                moment,
                third,
                radius,
                second: std::array::from_fn(|j| std::array::from_fn(|k| ml.0[j][k] + mr.0[j][k])),
                skew: std::array::from_fn(|j| ml.1[j] + mr.1[j]),
                fourth: ml.2 + mr.2,
                bbox: [lo, hi],
            };
            (sums, right_base as u32)
        };
        let m = &sums.moment;
        let sym = |i: usize, j: usize| ((m[i][j] + m[j][i]) / 2.0) as f32;
        nodes[0] = Node {
            centre: sums.centre,
            far2: (BETA * sums.radius).powi(2),
            normal: sums.normal.map(|x| x as f32),
            moment: [
                sym(0, 0),
                sym(1, 1),
                sym(2, 2),
                sym(0, 1),
                sym(0, 2),
                sym(1, 2),
            ],
            third: sums.third.map(|x| x as f32),
            radius: up_f32(sums.radius),
            area: up_f32(sums.area),
            cube: sums.cube(),
            start: start as u32,
            end: end as u32,
            right,
        };
        sums
    }

    /// The winding number at `p`, approximated far from the surface (relative error of
    /// the far field about (1/β)³ per cluster), exact per triangle near it.
    #[cfg(test)]
    pub fn at(&self, p: [f64; 3]) -> f64 {
        if self.nodes.is_empty() {
            return 0.0;
        }
        self.group(&[p], 1.0).0[0]
    }

    /// [`FastWinding::at`] of many points, the same values bit for bit. Points are taken
    /// in groups of up to 64 neighbours (Morton order) that walk the tree together: each
    /// node is read once per group, every point of the group still decides near or far by
    /// its own distance (a bit mask of the points still descending), and its terms are
    /// added in the same order as a walk of its own (a group of one). Reading a node is
    /// what a lone walk waits on; the group shares it. Parallel over groups.
    pub fn at_many(&self, points: &[[f64; 3]]) -> Vec<f64> {
        self.walk_many(points, 1.0)
            .into_iter()
            .map(|(w, _)| w)
            .collect()
    }

    /// [`FastWinding::at_many`] with a bound on each value's error: the far field's
    /// truncation and the rounding of its stored coefficients, summed over the clusters
    /// taken far ([`far_error`]). The triangles taken near are summed as
    /// [`winding_number`] sums them; the bound does not cover their rounding (a few
    /// units in the last place of each term, except at points within rounding of the
    /// surface, where no floating-point sum is decisive).
    pub fn at_many_bounded(&self, points: &[[f64; 3]]) -> Vec<(f64, f64)> {
        self.walk_many(points, 1.0)
    }

    /// Winding numbers on a known side of `threshold`, each with a bound on its error
    /// below its distance to `threshold` where that can be had: the side is then the
    /// exact winding number's.
    ///
    /// First [`FastWinding::at_many_bounded`]. Where its bound leaves the side unsure,
    /// the value is completed through the mesh's boundary ([`Cone`]): the mesh less the
    /// cone over its boundary is closed, so their winding numbers differ by an integer,
    /// which the hierarchy's value fixes when its bound and the cone's rounding are
    /// below ½; the cone's value plus that integer is then good to the cone's rounding
    /// (against a closed mesh, the cone is empty and the value an integer). A completed
    /// value within its bound, below [`TIE`], of the threshold is a tie: it becomes the
    /// threshold itself, not above it (a point in the plane of a flat sheet, beside it,
    /// where the exact sum is 0 term by term). Where the completion fails (a point
    /// within rounding of the cone's edges), the exact sum, [`winding_number`] (bound 0).
    /// So the side is the exact sum's wherever that is clear of rounding. A mesh with a
    /// long boundary gets more walks, the far field farther, before its cone is asked
    /// ([`LONG_BOUNDARY`]).
    pub fn sided_many(&self, points: &[[f64; 3]], threshold: f64) -> Vec<(f64, f64)> {
        let mut out = self.walk_many(points, 1.0);
        // Unsure unless clear of the threshold by more than the bound (NaN: unsure).
        let unsure = |(w, e): (f64, f64)| (w - threshold).abs().partial_cmp(&e) != Some(Greater);
        let mut open: Vec<usize> = (0..points.len()).filter(|&i| unsure(out[i])).collect();
        if open.is_empty() {
            return out;
        }
        let cone = self
            .cone
            .get_or_init(|| Cone::over(self.mesh, &crate::edges::unbalanced_edges(self.mesh)));
        for (widen, long) in [(2.0, LONG_BOUNDARY), (16.0, 16 * LONG_BOUNDARY)] {
            if cone.ends.len() <= long || open.is_empty() {
                break;
            }
            let pts: Vec<[f64; 3]> = open.iter().map(|&i| points[i]).collect();
            for (&i, we) in open.iter().zip(self.walk_many(&pts, widen)) {
                out[i] = we;
            }
            open.retain(|&i| unsure(out[i]));
        }
        let completed: Vec<Option<(f64, f64)>> = open
            .par_iter()
            .grained()
            .map(|&i| {
                let (w, e) = out[i];
                let (wc, ec) = cone.at(&points[i]);
                // Both bounds below ½ between them: the integer is certain.
                (e + ec < 0.4).then(|| (wc + (w - wc).round(), ec))
            })
            .collect();
        for (&i, c) in open.iter().zip(completed) {
            if let Some(we) = c {
                out[i] = we;
            }
        }
        // A completed value within `TIE` of the threshold is a tie that no sum breaks
        // better than its rounding: it counts as on the threshold (not above it), as
        // exact sums have it where every term vanishes (a point in the plane of a flat
        // sheet, beside it), with no sum over the whole mesh.
        for &i in &open {
            let (w, e) = out[i];
            if e <= TIE && (w - threshold).abs() <= e {
                out[i] = (threshold, e);
            }
        }
        open.retain(|&i| unsure(out[i]) && out[i].1 > TIE);
        let exact: Vec<f64> = open
            .par_iter()
            .map(|&i| winding_number(self.mesh, points[i]))
            .collect();
        for (&i, w) in open.iter().zip(exact) {
            out[i] = (w, 0.0);
        }
        out
    }

    /// Values and error bounds at `points` (see [`FastWinding::at_many`]), a cluster
    /// taken far beyond `widen` times its usual squared far distance.
    fn walk_many(&self, points: &[[f64; 3]], widen: f64) -> Vec<(f64, f64)> {
        const GROUP: usize = 64;
        // The bound's coefficient term assumes clusters at least `BETA` radii away.
        debug_assert!(widen >= 1.0);
        if self.nodes.is_empty() {
            return vec![(0.0, 0.0); points.len()];
        }
        let order = morton_order_of_points(points, false);
        let groups: Vec<(usize, GroupValues)> = order
            .par_chunks(GROUP)
            .grained()
            .enumerate()
            .map(|(g, ids)| {
                let mut pts = [[0.0; 3]; GROUP];
                for (p, &i) in pts.iter_mut().zip(ids) {
                    *p = points[i as usize];
                }
                (g, self.group(&pts[..ids.len()], widen))
            })
            .collect();
        let mut out = vec![(0.0, 0.0); points.len()];
        for (g, (values, errors)) in groups {
            for (k, &i) in order[g * GROUP..].iter().take(GROUP).enumerate() {
                out[i as usize] = (values[k], errors[k]);
            }
        }
        out
    }

    /// Winding numbers of up to 64 points in one walk (see [`FastWinding::at_many`]), and
    /// bounds on their errors; a cluster is far beyond `widen` times its `far2`.
    fn group(&self, pts: &[[f64; 3]], widen: f64) -> GroupValues {
        let (mut far, mut half, mut error) = ([0.0f64; 64], [0.0f64; 64], [0.0f64; 64]);
        let all = if pts.len() == 64 {
            u64::MAX
        } else {
            (1u64 << pts.len()) - 1
        };
        // Depth-first as in `at`: at most one pending right child per level.
        let mut stack = [(0u32, 0u64); 64];
        stack[0] = (0, all);
        let mut depth = 1;
        // Per cluster: the points taking it far and their offsets from its centre, then
        // their terms and bounds.
        let mut ids = [0u8; 64];
        let (mut xs, mut ys, mut zs, mut d2s) = ([0.0; 64], [0.0; 64], [0.0; 64], [0.0; 64]);
        let (mut terms, mut bounds) = ([0.0; 64], [0.0; 64]);
        while depth > 0 {
            depth -= 1;
            let (i, mask) = stack[depth];
            let n = &self.nodes[i as usize];
            let [xx, yy, zz, xy, xz, yz] = n.moment.map(f64::from);
            let [xxx, yyy, zzz, xxy, xxz, xyy, yyz, xzz, yzz, xyz] = n.third.map(f64::from);
            // τ_k = Σ_i S_iik.
            let tau = [xxx + xyy + xzz, xxy + yyy + yzz, xxz + yyz + zzz];
            let normal = n.normal.map(f64::from);
            let far2 = widen * n.far2;
            let (radius, area, cube) = (f64::from(n.radius), f64::from(n.area), n.cube);
            // The points that take this cluster far, as columns (the far terms below are
            // then one loop the compiler vectorizes), and those that descend.
            let (mut near, mut m, mut nf) = (0u64, mask, 0);
            while m != 0 {
                let k = m.trailing_zeros() as usize;
                m &= m - 1;
                let d = sub(&n.centre, &pts[k]);
                let d2 = dot(&d, &d);
                // Without a branch (which way it goes is a coin toss): the point is
                // written in the next free column, which counts only if it is far.
                let is_far = d2 > far2;
                ids[nf] = k as u8;
                (xs[nf], ys[nf], zs[nf], d2s[nf]) = (d[0], d[1], d[2], d2);
                nf += usize::from(is_far);
                near |= u64::from(!is_far) << k;
            }
            let trace = xx + yy + zz;
            for j in 0..nf.min(64) {
                // Far field of ∫ n · (x − p) / |x − p|³ with x = c + y, d = c − p, to the
                // third term: (N·d + tr M) / |d|³ − 3 dᵀM d / |d|⁵ + 15/2 S[d,d,d] / |d|⁷
                // − 9/2 τ·d / |d|⁵ (only the symmetric parts of M and of the third
                // moment, S, enter; τ_k = Σ_i S_iik); times 4π, scaled at the end.
                let (x, y, z) = (xs[j], ys[j], zs[j]);
                let dmd = x * x * xx
                    + y * y * yy
                    + z * z * zz
                    + 2.0 * (x * y * xy + x * z * xz + y * z * yz);
                let sddd = x * x * (xxx * x + 3.0 * (xxy * y + xxz * z))
                    + y * y * (yyy * y + 3.0 * (xyy * x + yyz * z))
                    + z * z * (zzz * z + 3.0 * (xzz * x + yzz * y))
                    + 6.0 * xyz * x * y * z;
                let r = 1.0 / d2s[j].sqrt();
                let (r2, inv3) = (r * r, r * r * r);
                let tau_d = tau[0] * x + tau[1] * y + tau[2] * z;
                let third = (7.5 * sddd * r2 - 4.5 * tau_d) * r2;
                let nd = normal[0] * x + normal[1] * y + normal[2] * z;
                terms[j] = ((nd + trace) - 3.0 * dmd * r2 + third) * inv3;
                bounds[j] = far_error(radius, area, cube, r);
            }
            for j in 0..nf.min(64) {
                let k = ids[j] as usize;
                far[k] += terms[j];
                error[k] += bounds[j];
            }
            if near == 0 {
                continue;
            }
            if n.right == 0 {
                for &t in &self.order[n.start as usize..n.end as usize] {
                    let [a, b, c] = self.mesh.corners(t as usize);
                    let mut m = near;
                    while m != 0 {
                        let k = m.trailing_zeros() as usize;
                        m &= m - 1;
                        half[k] += half_solid_angle(&a, &b, &c, &pts[k]);
                    }
                }
            } else {
                stack[depth] = (n.right, near);
                stack[depth + 1] = (i + 1, near);
                depth += 2;
            }
        }
        let four_pi = 4.0 * std::f64::consts::PI;
        (
            std::array::from_fn(|k| far[k] / four_pi + half[k] * HALF_ANGLE_TO_WINDING),
            std::array::from_fn(|k| error[k] / four_pi),
        )
    }
}

/// What the far field's coefficients lose to `f32`, per unit of area over the squared
/// distance: each coefficient is within 2⁻²⁴ of itself, `|N| ≤ A`, `|M| ≤ A r` and
/// `|S| ≤ A r²`, so the term moves by at most 2⁻²⁴ (√3 + 12 r / |d| + (7.5 · 3√3 + 4.5
/// · 3√3) r² / |d|²) A / |d|² ≤ 2⁻²⁴ (√3 + 12 / β + 62.4 / β²) A / |d|², under 1e-6 ·
/// A / |d|² at β = 2.5.
const F32_COEFFICIENTS: f64 = 1e-6;

/// A bound on one far cluster's error (in the units of the far sum, 4π times a winding
/// number): radius `r`, total area `a`, `cube` ≥ ∫ |y|³ over its area, its centre at
/// distance `1 / inv` from the query, beyond [`BETA`] times `r`.
///
/// The far term is the second-order Taylor expansion, in `x = c + y`, of
/// `g(y) = n · (x − p) / |x − p|³ = −DG(d + y)[n]` (`G = 1/|v|`, `d = c − p`), integrated
/// exactly; the remainder is `½ ∫₀¹ (1 − t)² D⁴G(d + t y)[n, y, y, y] dt`. The k-th
/// derivative of `G` along a unit direction is `k! P_k(cos θ) / |v|^(k+1)` with
/// `|P_k| ≤ 1`, and a symmetric form is largest on its diagonal, so
/// `|D⁴G(v)[n, y, y, y]| ≤ 24 |y|³ / |v|⁵`, with `|d + t y| ≥ |d| (1 − t u)`,
/// `u = |y| / |d|`. Then `12 ∫₀¹ (1 − t)² / (1 − t u)⁵ dt = Σ_k (k + 4) u^k =
/// (4 − 3u) / (1 − u)²`, so the remainder is at most `|y|³ (4 − 3u) / ((1 − u)² |d|⁵)`,
/// increasing in `|y| ≤ r`: integrated, `cube · f(u) / |d|⁵` with `u = r / |d| < 1` and
/// `cube` a bound on ∫ |y|³ over the cluster's area. Plus the rounding of the stored
/// coefficients, [`F32_COEFFICIENTS`] `· a / |d|²`.
#[inline]
fn far_error(r: f64, a: f64, cube: f64, inv: f64) -> f64 {
    let (inv2, u) = (inv * inv, r * inv);
    (cube * inv * (4.0 - 3.0 * u) / ((1.0 - u) * (1.0 - u)) * inv2 + F32_COEFFICIENTS * a) * inv2
}

/// How near the threshold a completed value may lie, its bound below this, and stand:
/// the rounding of an exact sum over ten million terms.
const TIE: f64 = 1e-9;

/// Boundary edges beyond which [`FastWinding::sided_many`] walks a second time (the far
/// field √2 times as far) before it asks the cone, whose cost per point grows with the
/// boundary; beyond 16 times as many, a third time (four times as far). Terrain ∪
/// terrain (800 boundary edges): 3.09G instructions for the run without the second
/// walk, 2.65G with it (2.70G and 2.78G with the far field √3 and 2 times as far).
const LONG_BOUNDARY: usize = 256;

/// The cone over a mesh's boundary from an apex far off in a generic direction: the
/// triangles (apex, a, b), each boundary edge `a → b` taken as many times as its uses
/// fail to cancel ([`crate::edges::unbalanced_edges`]). Its boundary is the mesh's, so
/// the mesh less the cone is closed and their winding numbers differ by an integer
/// wherever both are defined.
#[derive(Debug, Default)]
struct Cone {
    apex: [f64; 3],
    /// Each boundary edge's ends and its count.
    ends: Vec<([f64; 3], [f64; 3], f64)>,
}

impl Cone {
    /// The cone over `mesh`'s boundary `boundary`, its
    /// [`crate::edges::unbalanced_edges`] (empty for a closed, consistently oriented
    /// mesh).
    fn over(mesh: &Mesh, boundary: &[([u32; 2], i32)]) -> Cone {
        let ends: Vec<([f64; 3], [f64; 3], f64)> = boundary
            .iter()
            .map(|&([a, b], n)| {
                let at = |v: u32| mesh.positions[v as usize];
                (at(a), at(b), f64::from(n))
            })
            .collect();
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for (a, b, _) in &ends {
            for k in 0..3 {
                lo[k] = lo[k].min(a[k]).min(b[k]);
                hi[k] = hi[k].max(a[k]).max(b[k]);
            }
        }
        let apex = match ends.is_empty() {
            true => [0.0; 3],
            false => {
                // Twice the box's diagonal away, along a direction no grid lines up with.
                let reach = 2.0 * norm(&sub(&hi, &lo)) + 1.0;
                let dir = [0.267_261_24, 0.534_522_48, 0.801_783_73];
                std::array::from_fn(|k| (lo[k] + hi[k]) / 2.0 + reach * dir[k])
            }
        };
        Cone { apex, ends }
    }

    /// The cone's winding number at `p` and a bound on its rounding, up to a whole number
    /// (within rounding of a cone triangle's plane, inside it, `atan2` may take either
    /// side's value, ½ apart in winding; completion rounds such a step away): per
    /// triangle, the corners' differences from `p` and the triple product and denominator
    /// of [`half_solid_angle`] are each within a few units in the last place of
    /// `|a| |b| |c|` (the corners from `p`), so the vector `atan2` reads is within
    /// `64 u |a| |b| |c|` of the true one and its angle within π/2 times that over the
    /// vector's length; infinite where that is not below the length. The length is a
    /// plain square root (`hypot` costs 2 % of a terrain ∪ terrain), `hypot` only where
    /// the squares overflow; where they underflow it comes out short, which only widens
    /// the bound.
    fn at(&self, p: &[f64; 3]) -> (f64, f64) {
        let (mut half, mut error, mut sizes) = (0.0, 0.0, 0.0);
        for (a, b, n) in &self.ends {
            let (det, den, lengths) = solid_angle_vector(&self.apex, a, b, p);
            let length = match (det * det + den * den).sqrt() {
                l if l.is_finite() => l,
                _ => det.hypot(den),
            };
            let slack = 64.0 * f64::EPSILON / 2.0 * lengths;
            if slack.partial_cmp(&length) != Some(Less) {
                return (0.0, f64::INFINITY);
            }
            let term = n * det.atan2(den);
            half += term;
            sizes += term.abs();
            error += n.abs() * (std::f64::consts::FRAC_PI_2 * slack / length + 4.0 * f64::EPSILON);
        }
        let terms = self.ends.len() as f64;
        (
            half * HALF_ANGLE_TO_WINDING,
            (error + terms * f64::EPSILON * sizes) * HALF_ANGLE_TO_WINDING,
        )
    }
}

/// `x` as an `f32` no smaller than it (a bound stays a bound).
fn up_f32(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) < x {
        f.next_up()
    } else {
        f
    }
}

/// Indices of `points` in Morton order of their positions (10 bits per axis over their
/// bounding box; with `cube`, over the cube on its longest side, so that a flat set, a
/// terrain's boundary, keeps its few bits of height from splitting neighbours apart):
/// neighbours in space become neighbours in the list.
pub(super) fn morton_order_of_points(points: &[[f64; 3]], cube: bool) -> Vec<u32> {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let longest = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    let scale: [f64; 3] = std::array::from_fn(|k| {
        let ext = if cube { longest } else { hi[k] - lo[k] };
        if ext > 0.0 {
            1023.0 / ext
        } else {
            0.0
        }
    });
    let spread = |x: u32| -> u32 {
        let mut x = x & 0x3ff;
        x = (x | x << 16) & 0x0300_00ff;
        x = (x | x << 8) & 0x0300_f00f;
        x = (x | x << 4) & 0x030c_30c3;
        (x | x << 2) & 0x0924_9249
    };
    let mut keyed: Vec<(u32, u32)> = points
        .par_iter()
        .grained()
        .enumerate()
        .map(|(i, p)| {
            let cell = |k: usize| (((p[k] - lo[k]) * scale[k]).max(0.0) as u32).min(1023);
            (
                spread(cell(0)) | spread(cell(1)) << 1 | spread(cell(2)) << 2,
                i as u32,
            )
        })
        .collect();
    keyed.par_sort_unstable();
    keyed.into_iter().map(|(_, i)| i).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::{heightfield, torus, uv_sphere};
    use crate::test_util::Rng;

    /// `scattered` random points in the cube of side 6 about the origin, then `near`
    /// points a hair (10⁻³) off random triangles of `m`.
    fn scattered_and_near(m: &Mesh, scattered: usize, near: usize, rng: &mut Rng) -> Vec<[f64; 3]> {
        let mut pts: Vec<[f64; 3]> = (0..scattered)
            .map(|_| std::array::from_fn(|_| 6.0 * (rng.unit() - 0.5)))
            .collect();
        pts.extend((0..near).map(|_| {
            let [a, b, c] = m.corners((rng.next() % m.triangles.len() as u64) as usize);
            let (u, v) = (rng.unit() / 2.0, rng.unit() / 2.0);
            std::array::from_fn(|k| a[k] + u * (b[k] - a[k]) + v * (c[k] - a[k]) + 1e-3)
        }));
        pts
    }

    /// A sphere, a torus and an open height field: the shapes the hierarchy is held to.
    fn three_shapes() -> [Mesh; 3] {
        [
            uv_sphere([0.1, -0.2, 0.3], 1.0, 64, 32),
            torus([0.0; 3], 2.0, 0.6, 48, 24),
            heightfield([-2.0, -2.0], [2.0, 2.0], 30, 30, |x, y| 0.2 * x * y),
        ]
    }

    /// Exact sums do not depend on the threads: the same bits on one thread and on
    /// three (a parallel `sum` rounds as its splits fall), with and without a triangle.
    #[test]
    fn exact_sums_are_the_same_bits_on_any_number_of_threads() {
        let m = uv_sphere([0.1, 0.2, 0.3], 1.0, 120, 60);
        let mut rng = Rng(0x7e57_5a3e_b175);
        let pts: Vec<[f64; 3]> = (0..200)
            .map(|_| std::array::from_fn(|_| 3.0 * (rng.unit() - 0.5)))
            .collect();
        let on = |threads: usize| {
            crate::test_util::on_threads(threads, || {
                (pts.iter().enumerate())
                    .map(|(i, &p)| {
                        let without = winding_number_without(&m, p, 7 * i);
                        [winding_number(&m, p).to_bits(), without.to_bits()]
                    })
                    .collect::<Vec<_>>()
            })
        };
        let (one, three) = (on(1), on(3));
        let differ = one.iter().zip(&three).filter(|(a, b)| a != b).count();
        assert_eq!(differ, 0, "{differ} of {} points", pts.len());
    }

    /// A cluster's moments are the integrals they stand for: the root's sums over a
    /// small bumpy height field (four leaves, so moved between centres twice) against a
    /// quadrature exact to degree five (Radon's seven points), about the root's centre.
    #[test]
    fn moments_are_the_integrals() {
        let m = heightfield([-0.5, -0.4], [0.6, 0.5], 4, 3, |x, y| {
            0.3 * (3.0 * x).sin() * y
        });
        let order = morton_order(&m);
        let mut nodes = vec![Node::default(); subtree_nodes(order.len())];
        let sums = FastWinding::build(&m, &order, 0, order.len(), 0, &mut nodes);
        assert!(nodes.len() >= 3, "{} nodes", nodes.len());
        let c = sums.centre;
        let r15 = 15f64.sqrt();
        let (a1, a2) = ((6.0 - r15) / 21.0, (6.0 + r15) / 21.0);
        let (w1, w2) = ((155.0 - r15) / 1200.0, (155.0 + r15) / 1200.0);
        let mut rule = vec![([1.0 / 3.0; 3], 9.0 / 40.0)];
        for (a, w) in [(a1, w1), (a2, w2)] {
            let b = 1.0 - 2.0 * a;
            rule.extend([([a, a, b], w), ([a, b, a], w), ([b, a, a], w)]);
        }
        let (mut second, mut skew, mut fourth) = ([[0.0; 3]; 3], [0.0; 3], 0.0);
        let mut third = [[[0.0; 3]; 3]; 3];
        for t in 0..m.triangles.len() {
            let [a, b, cc] = m.corners(t);
            let n = cross(&sub(&b, &a), &sub(&cc, &a)).map(|x| x / 2.0);
            let area = norm(&n);
            for &(l, w) in &rule {
                let y: [f64; 3] =
                    std::array::from_fn(|k| l[0] * a[k] + l[1] * b[k] + l[2] * cc[k] - c[k]);
                let yy = dot(&y, &y);
                for j in 0..3 {
                    for k in 0..3 {
                        second[j][k] += area * w * y[j] * y[k];
                        for i in 0..3 {
                            third[i][j][k] += n[i] * w * y[j] * y[k];
                        }
                    }
                    skew[j] += area * w * yy * y[j];
                }
                fourth += area * w * yy * yy;
            }
        }
        let close = |got: f64, want: f64, scale: f64| (got - want).abs() <= 1e-12 * scale;
        let s2 = second[0][0] + second[1][1] + second[2][2];
        for (j, (got, want)) in sums.second.iter().zip(&second).enumerate() {
            for k in 0..3 {
                assert!(close(got[k], want[k], s2), "C {j}{k}");
            }
            assert!(close(sums.skew[j], skew[j], s2 * sums.radius), "V {j}");
        }
        // H is symmetric in its last two indices: its symmetric part averages the three
        // choices of the first.
        for (x, &[i, j, k]) in THIRD.iter().enumerate() {
            let want = (third[i][j][k] + third[j][i][k] + third[k][i][j]) / 3.0;
            assert!(close(sums.third[x], want, s2), "S {i}{j}{k}");
        }
        assert!(
            close(sums.fourth, fourth, fourth),
            "Q {} {fourth}",
            sums.fourth
        );
    }

    /// The far field is the expansion to its third term: taken far, a lone cluster's
    /// error falls with the fifth power of the distance (the fourth without the third
    /// term), and stays within its bound.
    #[test]
    fn the_far_field_errs_with_the_fifth_power_of_the_distance() {
        let m = heightfield([-0.5, -0.4], [0.6, 0.5], 2, 2, |x, y| {
            0.3 * (3.0 * x).sin() * y
        });
        let fast = FastWinding::new(&m);
        assert_eq!(fast.nodes.len(), 1);
        let (c, r) = (fast.nodes[0].centre, f64::from(fast.nodes[0].radius));
        let dir = [0.3, 0.5, 0.8].map(|x| x / norm(&[0.3, 0.5, 0.8]));
        let err = |distance: f64| {
            let p = std::array::from_fn(|k| c[k] + distance * r * dir[k]);
            let (w, e) = fast.at_many_bounded(&[p])[0];
            let off = (w - winding_number(&m, p)).abs();
            assert!(off <= e, "{distance}: {off} beyond {e}");
            off
        };
        for distance in [3.0, 5.0, 8.0] {
            let ratio = err(distance) / err(2.0 * distance);
            assert!(ratio > 26.0 && ratio < 40.0, "{distance}: ratio {ratio}");
        }
    }

    #[test]
    fn fast_agrees_with_the_exact_sum() {
        let mut rng = Rng(77);
        let meshes = three_shapes();
        let mut worst: f64 = 0.0;
        for m in &meshes {
            let fast = FastWinding::new(m);
            for _ in 0..300 {
                let p = std::array::from_fn(|_| 6.0 * (rng.unit() - 0.5));
                let (w, f) = (winding_number(m, p), fast.at(p));
                worst = worst.max((w - f).abs());
            }
        }
        assert!(worst < 0.03, "worst difference {worst}");
    }

    /// The error bound of [`FastWinding::at_many_bounded`] holds at random points around
    /// a sphere, a torus and a height field, also points within a hair of the surface.
    /// It is not idle (somewhere the error uses a fair part of it), and it shrinks when
    /// the far field is taken farther.
    #[test]
    fn the_error_bound_holds() {
        let mut rng = Rng(0xb0_0d);
        let meshes = three_shapes();
        for m in &meshes {
            let fast = FastWinding::new(m);
            let pts = scattered_and_near(m, 400, 100, &mut rng);
            let bounded = fast.at_many_bounded(&pts);
            let (mut used, mut mean_bound) = (0.0f64, 0.0);
            for (p, &(w, e)) in pts.iter().zip(&bounded) {
                let exact = winding_number(m, *p);
                assert!((w - exact).abs() <= e + 1e-12, "{p:?}: {w} {exact} {e}");
                used = used.max((w - exact).abs() / e);
                mean_bound += e / pts.len() as f64;
                assert_eq!(w.to_bits(), fast.at(*p).to_bits());
            }
            assert!(used > 0.05, "the bound is looser than it was ({used})");
            // With the expansion's third term and ∫ |y|³ bounded by the fourth moment, the
            // mean bound is 0.011, 0.018 and 0.009 here (0.039, 0.068, 0.033 without).
            assert!(
                mean_bound < 0.02,
                "the bound is looser than it was ({mean_bound})"
            );
            // Farther far fields: a tighter bound, still holding.
            let mut mean_before = mean_bound;
            for widen in [4.0, 16.0] {
                let wider = fast.walk_many(&pts, widen);
                let mean: f64 = wider.iter().map(|&(_, e)| e).sum::<f64>() / pts.len() as f64;
                assert!(mean < mean_before / 3.0, "{widen}: {mean} {mean_before}");
                for (p, &(w, e)) in pts.iter().zip(&wider) {
                    assert!((w - winding_number(m, *p)).abs() <= e + 1e-12, "{p:?}");
                }
                mean_before = mean;
            }
        }
    }

    /// A mesh less the cone over its boundary is closed: their winding numbers differ by
    /// an integer, to within the cone's rounding bound, at random points around an open
    /// height field, a torus with a hole cut and a triangle flipped, and a closed sphere
    /// (no cone at all).
    #[test]
    fn the_cone_over_the_boundary_differs_by_an_integer() {
        let mut rng = Rng(0xc0_0e);
        let field = heightfield([-2.0, -2.0], [2.0, 2.0], 30, 30, |x, y| 0.2 * x * y);
        let mut holed = torus([0.0; 3], 2.0, 0.6, 48, 24);
        holed.triangles.drain(100..140);
        holed.triangles[500].swap(0, 1);
        let sphere = uv_sphere([0.1, -0.2, 0.3], 1.0, 32, 16);
        for (m, edges) in [(&field, 120), (&holed, 0), (&sphere, 0)] {
            let cone = Cone::over(m, &crate::edges::unbalanced_edges(m));
            if edges > 0 {
                assert_eq!(cone.ends.len(), edges);
            }
            let mut fractions = 0.0f64;
            for _ in 0..300 {
                let p: [f64; 3] = std::array::from_fn(|_| 6.0 * (rng.unit() - 0.5));
                let (wc, ec) = cone.at(&p);
                assert!(ec < 1e-9, "{p:?}: {ec}");
                let diff = winding_number(m, p) - wc;
                assert!((diff - diff.round()).abs() < 1e-9 + ec, "{p:?}: {diff}");
                fractions = fractions.max((wc - wc.round()).abs());
            }
            match std::ptr::eq(m, &sphere) {
                true => assert!(cone.ends.is_empty() && fractions == 0.0),
                // The cone's own values are not integers: it carries the fractions.
                false => assert!(fractions > 0.1, "{fractions}"),
            }
        }
    }

    /// Sided values take the exact sum's side of the threshold, also where the
    /// hierarchy's own value is within its error of it: beside an open height field,
    /// near the plane it would extend into (the winding number within hundredths of 0),
    /// and just off a closed sphere (threshold ½). There, some hierarchy values alone
    /// are on the wrong side.
    #[test]
    fn sided_values_take_the_exact_side() {
        let mut rng = Rng(0x51_de);
        let field = heightfield([0.0, 0.0], [10.0, 10.0], 60, 60, |x, y| {
            0.6 * (0.9 * x).sin() * (0.7 * y).cos()
        });
        let sphere = uv_sphere([0.0; 3], 1.0, 48, 24);
        let (mut unsure, mut wrong_alone) = (0, 0);
        for (m, threshold) in [(&field, 0.0), (&sphere, 0.5)] {
            let fast = FastWinding::new(m);
            let pts: Vec<[f64; 3]> = (0..3000)
                .map(|_| match threshold == 0.0 {
                    // Around the field, mostly outside its footprint, near its height.
                    true => [
                        14.0 * rng.unit() - 2.0,
                        14.0 * rng.unit() - 2.0,
                        0.4 * (rng.unit() - 0.5),
                    ],
                    // Within 1/100 of the sphere.
                    false => {
                        let d: [f64; 3] = std::array::from_fn(|_| rng.unit() - 0.5);
                        let r = 1.0 + 0.02 * (rng.unit() - 0.5);
                        d.map(|c| c * r / norm(&d))
                    }
                })
                .collect();
            let alone = fast.at_many_bounded(&pts);
            let sided = fast.sided_many(&pts, threshold);
            for ((p, &(w, e)), &(ws, es)) in pts.iter().zip(&alone).zip(&sided) {
                let exact = winding_number(m, *p);
                if (exact - threshold).abs() < 1e-9 {
                    continue;
                }
                assert_eq!(ws > threshold, exact > threshold, "{p:?}: {ws} {exact}");
                assert!((ws - threshold).abs() > es && (ws - exact).abs() <= es + 1e-9);
                if (w - threshold).abs() <= e {
                    unsure += 1;
                    // Completed, not summed: through the cone beside the field (a bound
                    // of rounding), to an integer against the sphere.
                    match threshold == 0.0 {
                        true => assert!(es > 0.0 && es < 1e-9, "{p:?}: {es}"),
                        false => assert!(es == 0.0 && ws == ws.round(), "{p:?}: {ws}"),
                    }
                }
                wrong_alone += usize::from((w > threshold) != (exact > threshold));
            }
        }
        assert!(unsure > 100 && wrong_alone > 0, "{unsure} {wrong_alone}");
        // In the plane of a flat open square, beside it, the winding number is 0 term by
        // term: no bound decides, and the tie is the threshold itself (not above it).
        let flat = heightfield([0.0, 0.0], [1.0, 1.0], 20, 20, |_, _| 0.0);
        let fast = FastWinding::new(&flat);
        let beside: Vec<[f64; 3]> = (0..40)
            .map(|i| [1.5 + 0.1 * f64::from(i), 0.3 + 0.01 * f64::from(i), 0.0])
            .collect();
        for (p, (w, e)) in beside.iter().zip(fast.sided_many(&beside, 0.0)) {
            assert_eq!(winding_number(&flat, *p), 0.0);
            assert!(e <= TIE && w == 0.0, "{p:?}: {w} {e}");
        }
    }

    #[test]
    fn many_points_at_once_give_the_same_values_bit_for_bit() {
        let mut rng = Rng(13);
        let meshes = [
            torus([0.0; 3], 2.0, 0.6, 48, 24),
            heightfield([-2.0, -2.0], [2.0, 2.0], 30, 30, |x, y| 0.2 * x * y),
        ];
        for m in &meshes {
            let fast = FastWinding::new(m);
            // Scattered points, points clustered near the surface, and a count that
            // leaves a partial last group.
            let pts = scattered_and_near(m, 300, 157, &mut rng);
            let many = fast.at_many(&pts);
            assert_eq!(many.len(), pts.len());
            for (p, w) in pts.iter().zip(&many) {
                assert_eq!(w.to_bits(), fast.at(*p).to_bits(), "{p:?}");
            }
        }
        assert!(FastWinding::new(&meshes[0]).at_many(&[]).is_empty());
        assert_eq!(
            FastWinding::new(&Mesh::default()).at_many(&[[0.0; 3]]),
            vec![0.0]
        );
    }

    #[test]
    fn closed_meshes_give_one_inside_and_zero_outside() {
        let s = uv_sphere([0.0; 3], 1.0, 32, 16);
        let fast = FastWinding::new(&s);
        for (p, want) in [
            ([0.0; 3], 1.0),
            ([0.5, 0.2, -0.3], 1.0),
            ([3.0, 0.0, 0.0], 0.0),
            ([0.0, 0.0, -1.5], 0.0),
        ] {
            assert!((winding_number(&s, p) - want).abs() < 1e-9, "{p:?}");
            assert!((fast.at(p) - want).abs() < 0.03, "{p:?}: {}", fast.at(p));
        }
        // Inside/outside decided as the exact sum decides it, away from the surface.
        let mut rng = Rng(5);
        for _ in 0..500 {
            let p: [f64; 3] = std::array::from_fn(|_| 3.0 * (rng.unit() - 0.5));
            let r = norm(&p);
            if (r - 1.0).abs() > 0.05 {
                assert_eq!(fast.at(p) > 0.5, r < 1.0, "{p:?}");
            }
        }
        // Far away: every cluster is a dipole, and the sum vanishes.
        assert!(fast.at([1e6, 0.0, 0.0]).abs() < 1e-12);
        assert_eq!(FastWinding::new(&Mesh::default()).at([0.0; 3]), 0.0);
    }
}
