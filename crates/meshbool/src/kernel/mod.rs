//! The exact kernel: points (explicit input coordinates and implicit intersection points)
//! and the predicates that every topological decision of the pipeline goes through.
//!
//! Nothing outside this module compares floats to decide topology. Every point has exact
//! homogeneous coordinates `(X, Y, Z, W)`, polynomials in input `f64` coordinates without
//! division. A predicate is the sign of a polynomial in those; it is evaluated first in
//! `f64` with a bound on its rounding error (`bounded`), where that cannot decide in
//! interval arithmetic (`interval`), and only where the interval contains zero again with
//! exact dyadic numbers (`exact`). The answer is always the exact sign.
//!
//! Conventions: `orient3d(a, b, c, d)` is positive when `d` lies on the side of the plane
//! `abc` that its normal `(b − a) × (c − a)` points to; `orient2d(a, b, c, axis)` is positive
//! when `a, b, c` turn counter-clockwise in the projection that drops coordinate `axis`,
//! keeping the other two in cyclic order (`axis` 2 → (x, y), 0 → (y, z), 1 → (z, x)), so a
//! triangle facing `+axis` is counter-clockwise in its projection.

use std::cmp::Ordering;

mod bounded;
mod exact;
mod filter;
mod incircle;
pub(crate) use incircle::incircle_canonical;
#[cfg(test)]
use incircle::incircle_clear;
mod interval;
#[cfg(test)]
mod tests;
mod triangle;

use bounded::Bounded;
use exact::Dyadic;
pub use filter::{
    certainly_apart_beyond_corner, certainly_apart_projected, certainly_separated,
    certainly_unfolded, FloatPlane,
};
use interval::Interval;
pub use triangle::{planes_line_axis, Triangle};

/// The sign of an exact value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sign {
    /// Less than zero.
    Negative = -1,
    /// Exactly zero.
    Zero = 0,
    /// Greater than zero.
    Positive = 1,
}

impl Sign {
    /// The sign of a product.
    pub fn times(self, o: Sign) -> Sign {
        // The product of two of -1, 0, 1 is one of them: with the other values ruled
        // out, the compiler sees that the match maps each to itself and leaves a single
        // multiplication (the unreachable arm is not in the binary).
        match (self as i8) * (o as i8) {
            1 => Sign::Positive,
            -1 => Sign::Negative,
            0 => Sign::Zero,
            _ => unreachable!("a product of signs is a sign"),
        }
    }

    /// The opposite sign.
    pub fn reversed(self) -> Sign {
        self.times(Sign::Negative)
    }

    /// The sign of `x − y`, exact (a comparison, no subtraction); zero when either is
    /// NaN.
    pub(crate) fn of_difference(x: f64, y: f64) -> Sign {
        match x.partial_cmp(&y) {
            Some(Ordering::Greater) => Sign::Positive,
            Some(Ordering::Less) => Sign::Negative,
            _ => Sign::Zero,
        }
    }

    fn of_f64(x: f64) -> Sign {
        if x > 0.0 {
            Sign::Positive
        } else if x < 0.0 {
            Sign::Negative
        } else {
            Sign::Zero
        }
    }
}

/// Number types the predicates are evaluated in: ring operations and a sign that may be
/// undecided (intervals) or always known (exact).
pub(crate) trait Num: Clone {
    fn from_f64(x: f64) -> Self;
    fn add(&self, o: &Self) -> Self;
    fn sub(&self, o: &Self) -> Self;
    fn mul(&self, o: &Self) -> Self;
    fn sign(&self) -> Option<Sign>;
}

/// A point: an input vertex, or an intersection point defined by input vertices and kept
/// in that form (never rounded) for every decision.
#[derive(Clone, Debug, PartialEq)]
pub enum Point {
    /// An input vertex.
    Explicit([f64; 3]),
    /// Where segment `p q` crosses the plane of triangle `a b c`. Precondition: `p` and `q`
    /// lie strictly on opposite sides of that plane (so the point exists and is unique).
    Lpi {
        /// Segment start.
        p: [f64; 3],
        /// Segment end.
        q: [f64; 3],
        /// Plane's first point.
        a: [f64; 3],
        /// Plane's second point.
        b: [f64; 3],
        /// Plane's third point.
        c: [f64; 3],
    },
    /// Where segments `p q` and `r s`, lying in one plane, cross. Precondition: their
    /// projections dropping coordinate `axis` are not parallel (the plane's normal must
    /// have a non-zero `axis` component, e.g. its largest one).
    Ssi {
        /// First segment's start.
        p: [f64; 3],
        /// First segment's end.
        q: [f64; 3],
        /// Second segment's start.
        r: [f64; 3],
        /// Second segment's end.
        s: [f64; 3],
        /// The dropped coordinate of the projection used to intersect the lines.
        axis: u8,
    },
    /// Where three planes meet, each given by three points (a triangle's corners): the
    /// point where three triangles of a self-crossing mesh meet. Precondition: the planes'
    /// normals are independent (the point exists and is unique). Boxed: the nine corners
    /// would triple the size of every point.
    Tpi(Box<[[[f64; 3]; 3]; 3]>),
}

fn lift<T: Num>(p: &[f64; 3]) -> [T; 3] {
    p.map(T::from_f64)
}

fn vsub<T: Num>(a: &[T; 3], b: &[T; 3]) -> [T; 3] {
    [a[0].sub(&b[0]), a[1].sub(&b[1]), a[2].sub(&b[2])]
}

fn cross<T: Num>(a: &[T; 3], b: &[T; 3]) -> [T; 3] {
    [
        a[1].mul(&b[2]).sub(&a[2].mul(&b[1])),
        a[2].mul(&b[0]).sub(&a[0].mul(&b[2])),
        a[0].mul(&b[1]).sub(&a[1].mul(&b[0])),
    ]
}

fn dot<T: Num>(a: &[T; 3], b: &[T; 3]) -> T {
    a[0].mul(&b[0]).add(&a[1].mul(&b[1])).add(&a[2].mul(&b[2]))
}

/// `u × v` restricted to the projection dropping `axis` (cyclic order of the others).
fn cross2<T: Num>(u: &[T; 3], v: &[T; 3], axis: usize) -> T {
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    u[i].mul(&v[j]).sub(&u[j].mul(&v[i]))
}

/// `p · w + d · t` per coordinate: the homogeneous point `p + (t / w) d`.
fn along<T: Num>(p: &[T; 3], d: &[T; 3], t: &T, w: &T) -> [T; 4] {
    [
        p[0].mul(w).add(&d[0].mul(t)),
        p[1].mul(w).add(&d[1].mul(t)),
        p[2].mul(w).add(&d[2].mul(t)),
        w.clone(),
    ]
}

impl Point {
    /// Homogeneous coordinates `(X, Y, Z, W)`: the point is `(X/W, Y/W, Z/W)`, `W ≠ 0`.
    fn homogeneous<T: Num>(&self) -> [T; 4] {
        match self {
            Point::Explicit(p) => {
                let [x, y, z] = lift(p);
                [x, y, z, T::from_f64(1.0)]
            }
            Point::Lpi { p, q, a, b, c } => {
                let (p, q, a, b, c) = (lift(p), lift(q), lift(a), lift(b), lift(c));
                let n = cross(&vsub(&b, &a), &vsub(&c, &a));
                let d = vsub(&q, &p);
                along(&p, &d, &dot(&n, &vsub(&a, &p)), &dot(&n, &d))
            }
            Point::Tpi(planes) => {
                // n_i · x = d_i for each plane: x = Σ d_i (n_j × n_k) / (n_1 · (n_2 × n_3)).
                let plane = |[a, b, c]: &[[f64; 3]; 3]| {
                    let (a, b, c) = (lift::<T>(a), lift(b), lift(c));
                    let n = cross(&vsub(&b, &a), &vsub(&c, &a));
                    let d = dot(&n, &a);
                    (n, d)
                };
                let [(n1, d1), (n2, d2), (n3, d3)] = [0, 1, 2].map(|i| plane(&planes[i]));
                let (c23, c31, c12) = (cross(&n2, &n3), cross(&n3, &n1), cross(&n1, &n2));
                let w = dot(&n1, &c23);
                let x: [T; 3] = std::array::from_fn(|k| {
                    d1.mul(&c23[k]).add(&d2.mul(&c31[k])).add(&d3.mul(&c12[k]))
                });
                let [x, y, z] = x;
                [x, y, z, w]
            }
            Point::Ssi { p, q, r, s, axis } => {
                let (p, q, r, s) = (lift(p), lift(q), lift(r), lift(s));
                let (d, e) = (vsub(&q, &p), vsub(&s, &r));
                let axis = *axis as usize;
                along(
                    &p,
                    &d,
                    &cross2(&vsub(&r, &p), &e, axis),
                    &cross2(&d, &e, axis),
                )
            }
        }
    }

    /// The nearest-ish `f64` coordinates (a few ulps off for implicit points): for output,
    /// hashing and bounding boxes, never for decisions. Evaluated in `f64` where interval
    /// arithmetic shows that close (to 2^-40 of the point's size); otherwise — a segment
    /// almost parallel to the plane it crosses, where `f64` can lose every digit and even
    /// divide zero by zero — from the exact homogeneous coordinates.
    #[cfg(any(test, feature = "internals"))]
    pub fn approx(&self) -> [f64; 3] {
        match self {
            Point::Explicit(p) => *p,
            _ => self.approx_within(&Enclosure::of(self)),
        }
    }

    /// [`Point::approx`] given the point's enclosure (evaluated once for both).
    pub(crate) fn approx_within(&self, e: &Enclosure) -> [f64; 3] {
        /// 2^-40: how close, relative to the point's size, the `f64` evaluation must be shown
        /// to be.
        const CLOSE: f64 = 1.0 / (1u64 << 40) as f64;
        if let Point::Explicit(p) = self {
            return *p;
        }
        let [x, y, z, w] = self.homogeneous::<F64>();
        let fast = [x.0 / w.0, y.0 / w.0, z.0 / w.0];
        let close = match &e.coords {
            Some(c) => {
                let size = c
                    .iter()
                    .fold(0.0f64, |m, c| m.max(c.lo().abs()).max(c.hi().abs()));
                c.iter().all(|c| c.hi() - c.lo() <= size * CLOSE)
            }
            None => false,
        };
        if close {
            return fast;
        }
        let [x, y, z, w] = self.homogeneous::<Dyadic>();
        let exact = [x, y, z].map(|c| c.div_f64(&w));
        match exact {
            [Some(x), Some(y), Some(z)] => [x, y, z],
            _ => fast,
        }
    }

    /// Where segment `p q` crosses the plane of `a b c` ([`Point::Lpi`], same
    /// precondition), as an explicit point when its coordinates are `f64` numbers known
    /// exactly: a coordinate in which the segment is constant, or the plane square to an
    /// axis, and the rest found along the segment in exact `f64` steps
    /// ([`on_segment_exact`]). The faces and edges of boxes and CAD parts meet in such
    /// points, and every later predicate on an explicit point is the cheap one.
    pub fn lpi(p: [f64; 3], q: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> Point {
        let known = std::array::from_fn(|k| {
            if p[k] == q[k] {
                Some(p[k])
            } else if a[k] == b[k] && b[k] == c[k] {
                Some(a[k])
            } else {
                None
            }
        });
        match on_segment_exact(&p, &q, known) {
            Some(x) => Point::Explicit(x),
            None => Point::Lpi { p, q, a, b, c },
        }
    }

    /// Where segments `p q` and `r s` cross ([`Point::Ssi`], same precondition), as an
    /// explicit point when its coordinates are known exactly: a coordinate in which either
    /// segment is constant, the rest found along one of them ([`Point::lpi`]).
    pub fn ssi(p: [f64; 3], q: [f64; 3], r: [f64; 3], s: [f64; 3], axis: u8) -> Point {
        let known = std::array::from_fn(|k| {
            if p[k] == q[k] {
                Some(p[k])
            } else if r[k] == s[k] {
                Some(r[k])
            } else {
                None
            }
        });
        match on_segment_exact(&p, &q, known).or_else(|| on_segment_exact(&r, &s, known)) {
            Some(x) => Point::Explicit(x),
            None => Point::Ssi { p, q, r, s, axis },
        }
    }

    /// The input coordinates if the point is explicit.
    pub fn explicit(&self) -> Option<[f64; 3]> {
        match self {
            Point::Explicit(p) => Some(*p),
            _ => None,
        }
    }
}

/// The point of the line through `p` and `q` (distinct) whose coordinates `known` are
/// given, when all three are `f64` numbers found exactly: each unknown coordinate `i` is
/// `p[i] + (x[j] − p[j]) (q[i] − p[i]) / (q[j] − p[j])` for a known `x[j]` in which the
/// line is not constant, every step checked exact (error-free transformations: a sum's
/// rounding error, a product's and a quotient's residual by a fused multiply-add, all
/// zero, and no underflow). `None` when a step rounds, or nothing fixes the point.
pub(crate) fn on_segment_exact(
    p: &[f64; 3],
    q: &[f64; 3],
    known: [Option<f64>; 3],
) -> Option<[f64; 3]> {
    if let [Some(x), Some(y), Some(z)] = known {
        return Some([x, y, z]);
    }
    let j = (0..3).find(|&j| known[j].is_some() && p[j] != q[j])?;
    let (run, from) = (sub_exact(q[j], p[j])?, sub_exact(known[j]?, p[j])?);
    let mut out = [0.0; 3];
    for i in 0..3 {
        out[i] = match known[i] {
            Some(x) => x,
            None => {
                let step = div_exact(mul_exact(from, sub_exact(q[i], p[i])?)?, run)?;
                sub_exact(p[i], -step)?
            }
        };
    }
    Some(out)
}

/// `a − b` when it is exact in `f64`: Knuth's two-sum error is zero (exact for any
/// finite operands) and there is no overflow.
fn sub_exact(a: f64, b: f64) -> Option<f64> {
    let nb = -b;
    let s = a + nb;
    let bb = s - a;
    let err = (a - (s - bb)) + (nb - bb);
    (s.is_finite() && err == 0.0).then_some(s)
}

/// Whether `x` is zero or of magnitude in `[2^-200, 2^200]` ([`robust_safe`]'s range):
/// products of two such numbers are multiples of `2^-504`, so a fused residual that is
/// not exactly zero cannot round to zero. Without branches, so that the checks of many
/// coordinates run side by side.
fn in_safe_range(x: f64) -> bool {
    const LO: f64 = 6.223_015_277_861_142e-61; // 2^-200
    const HI: f64 = 1.606_938_044_258_990_3e60; // 2^200
    (x == 0.0) | (LO..=HI).contains(&x.abs())
}

/// `a · b` when it is exact in `f64`: operands and product in [`in_safe_range`] and the
/// fused residual `a · b − m` zero.
fn mul_exact(a: f64, b: f64) -> Option<f64> {
    let m = a * b;
    ([a, b, m].into_iter().all(in_safe_range) && a.mul_add(b, -m) == 0.0).then_some(m)
}

/// `a / b` (`b ≠ 0`) when it is exact in `f64`: operands and quotient in
/// [`in_safe_range`] and the fused residual `m · b − a` zero.
fn div_exact(a: f64, b: f64) -> Option<f64> {
    let m = a / b;
    ([a, b, m].into_iter().all(in_safe_range) && b != 0.0 && m.mul_add(b, -a) == 0.0).then_some(m)
}

/// Plain `f64` evaluation, used only for approximate coordinates.
#[derive(Clone, Copy)]
struct F64(f64);

impl Num for F64 {
    fn from_f64(x: f64) -> Self {
        F64(x)
    }
    fn add(&self, o: &Self) -> Self {
        F64(self.0 + o.0)
    }
    fn sub(&self, o: &Self) -> Self {
        F64(self.0 - o.0)
    }
    fn mul(&self, o: &Self) -> Self {
        F64(self.0 * o.0)
    }
    fn sign(&self) -> Option<Sign> {
        Some(Sign::of_f64(self.0))
    }
}

/// Sign of a polynomial given as a generic function: `f64` with an error bound first,
/// then intervals, exact if both are undecided.
macro_rules! decide {
    ($f:ident ( $($arg:expr),* )) => {{
        match $f::<Bounded>($($arg),*).sign() {
            Some(s) => s,
            None => match $f::<Interval>($($arg),*).sign() {
                Some(s) => s,
                None => $f::<Dyadic>($($arg),*)
                    .sign()
                    .expect("exact signs are always decided"),
            },
        }
    }};
}

fn sign_of_w(p: &Point) -> Sign {
    match p {
        Point::Explicit(_) => Sign::Positive,
        _ => decide!(w_of(p)),
    }
}

fn w_of<T: Num>(p: &Point) -> T {
    let [_, _, _, w] = p.homogeneous::<T>();
    w
}

/// `(b − a) × (c − a) · (P − a)`, times `W_P` (explicit plane, any point).
fn plane_side<T: Num>(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], p: &Point) -> T {
    let (a, b, c) = (lift::<T>(a), lift(b), lift(c));
    let n = cross(&vsub(&b, &a), &vsub(&c, &a));
    let [x, y, z, w] = p.homogeneous::<T>();
    let rel = [
        x.sub(&w.mul(&a[0])),
        y.sub(&w.mul(&a[1])),
        z.sub(&w.mul(&a[2])),
    ];
    dot(&n, &rel)
}

fn det3<T: Num>(m: [[T; 3]; 3]) -> T {
    let minor = |i: usize, j: usize| m[1][i].mul(&m[2][j]).sub(&m[1][j].mul(&m[2][i]));
    m[0][0]
        .mul(&minor(1, 2))
        .sub(&m[0][1].mul(&minor(0, 2)))
        .add(&m[0][2].mul(&minor(0, 1)))
}

fn det4_rows<T: Num>(a: &Point, b: &Point, c: &Point, d: &Point) -> T {
    let r = [a, b, c, d].map(|p| p.homogeneous::<T>());
    // Laplace expansion along the last column (W).
    let minor = |skip: usize| {
        let rows: Vec<&[T; 4]> = (0..4).filter(|&i| i != skip).map(|i| &r[i]).collect();
        det3([0, 1, 2].map(|k| [rows[k][0].clone(), rows[k][1].clone(), rows[k][2].clone()]))
    };
    let mut acc = T::from_f64(0.0);
    for (i, row) in r.iter().enumerate() {
        let term = row[3].mul(&minor(i));
        // Cofactor sign (−1)^(i+3).
        acc = if i % 2 == 1 {
            acc.add(&term)
        } else {
            acc.sub(&term)
        };
    }
    acc
}

fn orient2d_rows<T: Num>(a: &Point, b: &Point, c: &Point, axis: usize) -> T {
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    det3([a, b, c].map(|p| {
        let h = p.homogeneous::<T>();
        [h[i].clone(), h[j].clone(), h[3].clone()]
    }))
}

fn coord_diff<T: Num>(a: &Point, b: &Point, axis: usize) -> T {
    let (ha, hb) = (a.homogeneous::<T>(), b.homogeneous::<T>());
    ha[axis].mul(&hb[3]).sub(&hb[axis].mul(&ha[3]))
}

/// Exact orientation of `d` against the oriented plane through explicit points `a b c`:
/// positive on the side `(b − a) × (c − a)` points to, zero on the plane.
pub fn orient3d_plane(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &Point) -> Sign {
    match d {
        Point::Explicit(p) => orient3d_explicit(a, b, c, p),
        _ => decide!(plane_side(a, b, c, d)).times(sign_of_w(d)),
    }
}

/// True when Shewchuk's adaptive predicates (`robust`) are exact for these coordinates:
/// they assume no overflow or underflow. With every coordinate zero or of magnitude in
/// `[2^-200, 2^200]`, all differences and their error terms are multiples of `2^-252` and
/// below `2^201`, so products of three stay in the normal range.
pub(crate) fn robust_safe(points: &[&[f64; 3]]) -> bool {
    // Every coordinate checked (no early exit: almost all pass, and the checks of a point's
    // three run side by side).
    points.iter().fold(true, |ok, p| {
        ok & p.iter().fold(true, |ok, &x| ok & in_safe_range(x))
    })
}

fn plane_side_explicit<T: Num>(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> T {
    plane_side(a, b, c, &Point::Explicit(*d))
}

/// [`orient3d_plane`] for four input points: Shewchuk's adaptive exact predicate where its
/// assumptions hold, the kernel's interval/exact evaluation otherwise. Where the floating-
/// point filter cannot decide (points on or next to one plane), coordinates that are short
/// binary fractions of one scale (grids, CAD data) are decided in integer arithmetic
/// (`orient3d_fixed`) before Shewchuk's expansion arithmetic.
pub fn orient3d_explicit(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> Sign {
    orient3d_inputs(a, b, c, d, robust_safe(&[a, b, c, d]))
}

/// [`orient3d_explicit`] where whether the points meet [`robust_safe`] is known (from
/// their triangles: `safe`), not checked again.
pub(crate) fn orient3d_inputs(
    a: &[f64; 3],
    b: &[f64; 3],
    c: &[f64; 3],
    d: &[f64; 3],
    safe: bool,
) -> Sign {
    debug_assert!(!safe || robust_safe(&[a, b, c, d]));
    if !safe {
        return decide!(plane_side_explicit(a, b, c, d));
    }
    if let Some(s) = PlaneFilter::new(a, b, c).side(d) {
        return s;
    }
    if in_one_axis_plane(&[a, b, c, d]) {
        return Sign::Zero;
    }
    if let Some(s) = orient3d_fixed(a, b, c, d) {
        return s;
    }
    orient3d_robust(a, b, c, d)
}

/// The floating-point stage of Shewchuk's `orient3d` (its first error bound, for inputs
/// that meet [`robust_safe`]) for one plane `a b c` and any number of points: the plane's
/// products are computed once.
struct PlaneFilter {
    a: [f64; 3],
    /// `(b − a) × (c − a)` as rounded, grouped as Shewchuk groups it.
    n: [f64; 3],
    /// The permanents bounding each component's products.
    p: [f64; 3],
}

impl PlaneFilter {
    fn new(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3]) -> Self {
        let [u, v] = [b, c].map(|p| [p[0] - a[0], p[1] - a[1], p[2] - a[2]]);
        let (uyvz, uzvy) = (u[1] * v[2], u[2] * v[1]);
        let (uzvx, uxvz) = (u[2] * v[0], u[0] * v[2]);
        let (uxvy, uyvx) = (u[0] * v[1], u[1] * v[0]);
        PlaneFilter {
            a: *a,
            n: [uyvz - uzvy, uzvx - uxvz, uxvy - uyvx],
            p: [
                uyvz.abs() + uzvy.abs(),
                uzvx.abs() + uxvz.abs(),
                uxvy.abs() + uyvx.abs(),
            ],
        }
    }

    /// The sign of `((b − a) × (c − a)) · (d − a)` where the rounded value is certain.
    fn side(&self, d: &[f64; 3]) -> Option<Sign> {
        // Shewchuk's o3derrboundA = (7 + 56ε)ε with ε = 2⁻⁵³.
        const BOUND: f64 = (7.0 + 56.0 * f64::EPSILON / 2.0) * (f64::EPSILON / 2.0);
        let (a, n, p) = (&self.a, &self.n, &self.p);
        let w = [d[0] - a[0], d[1] - a[1], d[2] - a[2]];
        let det = w[0] * n[0] + w[1] * n[1] + w[2] * n[2];
        let bound = BOUND * (p[0] * w[0].abs() + p[1] * w[1].abs() + p[2] * w[2].abs());
        if det > bound {
            Some(Sign::Positive)
        } else if -det > bound {
            Some(Sign::Negative)
        } else {
            None
        }
    }
}

/// Shewchuk's adaptive `orient3d` (inputs meeting [`robust_safe`]) in this module's sign
/// convention.
fn orient3d_robust(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> Sign {
    let c3 = |p: &[f64; 3]| robust::Coord3D {
        x: p[0],
        y: p[1],
        z: p[2],
    };
    // robust's orient3d is positive when d is below (opposite to our convention).
    Sign::of_f64(robust::orient3d(c3(a), c3(b), c3(c), c3(d))).reversed()
}

/// Exact `orient3d` in integer arithmetic where the coordinates allow it: every
/// coordinate an integer multiple of one power of two `2^e`, below `2^(e + 62)`, and every
/// difference from `a` below `2^(e + 41)` in magnitude. Then the determinant, in units of
/// `2^(3e)`, is below 2¹²⁶ and computed exactly in `i128`. `None` otherwise. Coordinates of
/// grids and most CAD models qualify; this is the answer for points exactly on a plane,
/// which floating-point filters cannot give.
fn orient3d_fixed(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> Option<Sign> {
    orient3d_fixed_many(&[*a, *b, *c], std::slice::from_ref(d)).map(|s| s[0])
}

/// A normal `f64` as `(mantissa, e)` with `|x| = mantissa · 2^e`, the mantissa's implicit
/// leading bit included (53 bits).
fn split(x: f64) -> (u64, i32) {
    let bits = x.to_bits();
    let mantissa = (bits & ((1 << 52) - 1)) | (1 << 52);
    (mantissa, ((bits >> 52) & 0x7ff) as i32 - 1075)
}

/// [`orient3d_fixed`] of up to three points against one plane, with one common scale: all
/// of them or none (`None` when any coordinate does not fit).
fn orient3d_fixed_many(t: &[[f64; 3]; 3], ds: &[[f64; 3]]) -> Option<[Sign; 3]> {
    debug_assert!(ds.len() <= 3);
    let coords = || t.iter().chain(ds).flat_map(|p| p.iter().copied());
    // Exponents of the lowest set bit and of a bound on the magnitude.
    let (mut low, mut high) = (i32::MAX, i32::MIN);
    for x in coords() {
        if x == 0.0 {
            continue;
        }
        if !x.is_normal() {
            return None; // subnormal or not finite
        }
        let (mantissa, e) = split(x);
        low = low.min(e + mantissa.trailing_zeros() as i32);
        high = high.max(e + 53);
    }
    if low == i32::MAX {
        return Some([Sign::Zero; 3]); // all coordinates zero
    }
    if high - low > 62 {
        return None;
    }
    // Each coordinate as an integer in units of 2^low (exact shifts).
    let int = |x: f64| -> i64 {
        if x == 0.0 {
            return 0;
        }
        let (mantissa, e) = split(x);
        let mantissa = mantissa as i64;
        let shifted = if e >= low {
            mantissa << (e - low)
        } else {
            mantissa >> (low - e)
        };
        if x < 0.0 {
            -shifted
        } else {
            shifted
        }
    };
    const LIMIT: i64 = 1 << 41;
    let ia = t[0].map(int);
    // Differences from `a`, each below 2^41 (both ends below 2^62: no overflow).
    let diff = |p: &[f64; 3]| -> Option<[i128; 3]> {
        let mut out = [0i128; 3];
        for k in 0..3 {
            let x = int(p[k]) - ia[k];
            if x.abs() >= LIMIT {
                return None;
            }
            out[k] = i128::from(x);
        }
        Some(out)
    };
    let (u, v) = (diff(&t[1])?, diff(&t[2])?);
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let mut out = [Sign::Zero; 3];
    for (o, d) in out.iter_mut().zip(ds) {
        let w = diff(d)?;
        *o = match (n[0] * w[0] + n[1] * w[1] + n[2] * w[2]).cmp(&0) {
            Ordering::Greater => Sign::Positive,
            Ordering::Less => Sign::Negative,
            Ordering::Equal => Sign::Zero,
        };
    }
    Some(out)
}

/// [`orient3d_explicit`] of the three corners `ds` of one triangle against the plane of
/// another, `t`: the same exact signs, with the work the three share done once (the
/// filter's products of the plane's edges; one common scale for the integer path).
pub fn orient3d_sides(t: &[[f64; 3]; 3], ds: &[[f64; 3]; 3]) -> [Sign; 3] {
    let [a, b, c] = t;
    // Checked before the filter here: for a triangle against another, one such test
    // spares the three filters' failures. (The square plane below gives the same zeros,
    // but through an orientation: coplanar faces of boxes are most pairs of such meshes.)
    if in_one_axis_plane(&[a, b, c, &ds[0], &ds[1], &ds[2]]) {
        return [Sign::Zero; 3];
    }
    // A plane square to axis k (faces of boxes and CAD parts, where the filter fails for
    // every point on it): the normal points along k, with the sign of the triangle's
    // orientation in the projection dropping k; a point's side is the sign of its
    // coordinate's difference from the plane's, times that.
    if let Some(k) = (0..3).find(|&k| a[k] == b[k] && b[k] == c[k]) {
        let n = orient2d_inputs(a, b, c, k, robust_safe(&[a, b, c]));
        return ds.map(|d| Sign::of_difference(d[k], a[k]).times(n));
    }
    if !robust_safe(&[a, b, c, &ds[0], &ds[1], &ds[2]]) {
        return ds.map(|d| orient3d_explicit(a, b, c, &d));
    }
    let plane = PlaneFilter::new(a, b, c);
    let filtered = ds.map(|d| plane.side(&d));
    if let [Some(x), Some(y), Some(z)] = filtered {
        return [x, y, z];
    }
    if let Some(s) = orient3d_fixed_many(t, ds) {
        return s;
    }
    std::array::from_fn(|k| filtered[k].unwrap_or_else(|| orient3d_robust(a, b, c, &ds[k])))
}

/// Exact orientation of four points of any kind (see the module conventions).
pub fn orient3d(a: &Point, b: &Point, c: &Point, d: &Point) -> Sign {
    if let (Some(a), Some(b), Some(c)) = (a.explicit(), b.explicit(), c.explicit()) {
        return orient3d_plane(&a, &b, &c, d);
    }
    let w = [a, b, c, d]
        .iter()
        .fold(Sign::Positive, |s, p| s.times(sign_of_w(p)));
    decide!(det4_rows(a, b, c, d)).reversed().times(w)
}

/// Exact orientation of three points in the projection dropping coordinate `axis`
/// (0, 1 or 2): positive when counter-clockwise (see the module conventions).
pub fn orient2d(a: &Point, b: &Point, c: &Point, axis: usize) -> Sign {
    if let Some(s) = orient2d_shewchuk(a, b, c, axis) {
        return s;
    }
    let w = [a, b, c]
        .iter()
        .fold(Sign::Positive, |s, p| s.times(sign_of_w(p)));
    decide!(orient2d_rows(a, b, c, axis)).times(w)
}

/// A point with interval enclosures of its homogeneous coordinates, evaluated once: for
/// code that asks many predicates about the same points (a triangulation), so that the
/// interval filter does not rebuild an implicit point's coordinates for every test. The
/// exact evaluation, where the filter cannot decide, still starts from the point.
#[derive(Clone, Debug)]
pub(crate) struct Prepared {
    point: Point,
    enclosure: [Interval; 4],
    /// Enclosures of the point's coordinates themselves (`X/W`, ...), when `W`'s enclosure
    /// excludes zero: a point's coordinates are known to a few ulps of their own size,
    /// while its homogeneous coordinates carry the (large) scale of the planes that made
    /// it, so predicates on close points decide here where the homogeneous filter cannot.
    coords: Option<[Interval; 3]>,
    /// The exact homogeneous coordinates, computed on the first exact evaluation that
    /// needs them and kept: in a triangulation the same points meet the exact fallback
    /// again and again, and building an implicit point's coordinates is most of its cost.
    /// Boxed: most points never need them, and every prepared point is moved around.
    exact: std::cell::OnceCell<Box<[Dyadic; 4]>>,
}

/// Interval enclosures of a point's homogeneous coordinates and of its coordinates (when
/// `W`'s enclosure excludes zero): what [`Prepared`] keeps and [`Point::approx`] checks,
/// evaluated once for a seam point that several triangles take in.
#[derive(Clone, Debug)]
pub(crate) struct Enclosure {
    enclosure: [Interval; 4],
    coords: Option<[Interval; 3]>,
}

impl Enclosure {
    /// The enclosures of `point`.
    pub(crate) fn of(point: &Point) -> Enclosure {
        let enclosure = point.homogeneous::<Interval>();
        let coords = match point {
            Point::Explicit(p) => Some(p.map(Interval::from_f64)),
            _ => {
                let [x, y, z, w] = &enclosure;
                match (x.div(w), y.div(w), z.div(w)) {
                    (Some(x), Some(y), Some(z)) => Some([x, y, z]),
                    _ => None,
                }
            }
        };
        Enclosure { enclosure, coords }
    }

    /// A box that holds the point: `[low, high]` per coordinate; `None` where the
    /// enclosure of its `W` holds zero (no bound).
    pub(crate) fn bounds(&self) -> Option<[[f64; 2]; 3]> {
        self.coords.map(|c| c.map(|i| [i.lo(), i.hi()]))
    }
}

impl Prepared {
    /// Prepares `point`.
    pub(crate) fn new(point: Point) -> Prepared {
        let e = Enclosure::of(&point);
        Prepared::with(point, e)
    }

    /// Prepares `point` whose enclosure `e` ([`Enclosure::of`]) was evaluated before.
    pub(crate) fn with(point: Point, e: Enclosure) -> Prepared {
        Prepared {
            point,
            enclosure: e.enclosure,
            coords: e.coords,
            exact: std::cell::OnceCell::new(),
        }
    }

    /// The input coordinates if the point is explicit.
    #[cfg(test)]
    pub(crate) fn explicit(&self) -> Option<[f64; 3]> {
        self.point.explicit()
    }

    /// The exact homogeneous coordinates (computed once).
    fn exact(&self) -> &[Dyadic; 4] {
        self.exact
            .get_or_init(|| Box::new(self.point.homogeneous::<Dyadic>()))
    }

    /// The sign of `W` (positive for explicit points).
    fn sign_of_w(&self) -> Sign {
        match (&self.point, self.enclosure[3].sign()) {
            (Point::Explicit(_), _) => Sign::Positive,
            (_, Some(s)) => s,
            (p, None) => decide!(w_of(p)),
        }
    }
}

/// [`orient2d`] of prepared points: the same exact answer, the interval filter from the
/// stored enclosures.
pub(crate) fn orient2d_prepared(a: &Prepared, b: &Prepared, c: &Prepared, axis: usize) -> Sign {
    if let Some(s) = orient2d_shewchuk(&a.point, &b.point, &c.point, axis) {
        return s;
    }
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    // First on the coordinates themselves: (b − a) × (c − a).
    if let (Some(pa), Some(pb), Some(pc)) = (&a.coords, &b.coords, &c.coords) {
        let (u, v) = (
            [pb[i].sub(&pa[i]), pb[j].sub(&pa[j])],
            [pc[i].sub(&pa[i]), pc[j].sub(&pa[j])],
        );
        if let Some(s) = u[0].mul(&v[1]).sub(&u[1].mul(&v[0])).sign() {
            return s;
        }
    }
    let rows = [a, b, c].map(|p| [p.enclosure[i], p.enclosure[j], p.enclosure[3]]);
    let det = match det3(rows).sign() {
        Some(s) => s,
        None => det3([a, b, c].map(|p| {
            let h = p.exact();
            [h[i].clone(), h[j].clone(), h[3].clone()]
        }))
        .sign()
        .expect("exact signs are always decided"),
    };
    [a, b, c].iter().fold(det, |s, p| s.times(p.sign_of_w()))
}

/// [`cmp_coord`] of prepared points: the same exact answer, the interval filter from the
/// stored enclosures.
pub(crate) fn cmp_coord_prepared(a: &Prepared, b: &Prepared, axis: usize) -> Ordering {
    if let (Some(pa), Some(pb)) = (a.point.explicit(), b.point.explicit()) {
        return pa[axis].partial_cmp(&pb[axis]).unwrap_or(Ordering::Equal);
    }
    if let (Some(ca), Some(cb)) = (&a.coords, &b.coords) {
        if ca[axis].disjoint(&cb[axis]) {
            return if ca[axis].lo() < cb[axis].lo() {
                Ordering::Less
            } else {
                Ordering::Greater
            };
        }
    }
    let (ea, eb) = (&a.enclosure, &b.enclosure);
    let diff = match ea[axis].mul(&eb[3]).sub(&eb[axis].mul(&ea[3])).sign() {
        Some(s) => s,
        None => {
            let (ha, hb) = (a.exact(), b.exact());
            ha[axis]
                .mul(&hb[3])
                .sub(&hb[axis].mul(&ha[3]))
                .sign()
                .expect("exact signs are always decided")
        }
    };
    (diff.times(a.sign_of_w()).times(b.sign_of_w()) as i8).cmp(&0)
}

/// [`same_point`] of prepared points.
#[cfg(test)]
pub(crate) fn same_point_prepared(a: &Prepared, b: &Prepared) -> bool {
    (0..3).all(|k| cmp_coord_prepared(a, b, k) == Ordering::Equal)
}

/// Shewchuk's adaptive `orient2d` where it is exact: three explicit points whose
/// coordinates meet [`robust_safe`]; `None` otherwise.
fn orient2d_shewchuk(a: &Point, b: &Point, c: &Point, axis: usize) -> Option<Sign> {
    let (pa, pb, pc) = (a.explicit()?, b.explicit()?, c.explicit()?);
    robust_safe(&[&pa, &pb, &pc]).then(|| orient2d_safe(&pa, &pb, &pc, axis))
}

/// [`orient2d`] of three input points whose coordinates are known to meet [`robust_safe`]
/// (checked once per triangle by callers that ask many orientations of the same corners):
/// Shewchuk's adaptive predicate without the per-call checks.
#[inline]
pub(crate) fn orient2d_safe(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], axis: usize) -> Sign {
    debug_assert!(robust_safe(&[a, b, c]));
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    // On one line square to an axis of the projection (edges of boxes and grids):
    // collinear, where the adaptive predicate would take its slowest path to zero.
    if (a[i] == b[i] && b[i] == c[i]) || (a[j] == b[j] && b[j] == c[j]) {
        return Sign::Zero;
    }
    let c2 = |p: &[f64; 3]| robust::Coord { x: p[i], y: p[j] };
    Sign::of_f64(robust::orient2d(c2(a), c2(b), c2(c)))
}

/// [`orient2d`] of three input points, with [`orient2d_safe`] where the caller has found
/// them to meet [`robust_safe`] (`safe`: checked once for points asked about many times).
#[inline]
pub(crate) fn orient2d_inputs(
    a: &[f64; 3],
    b: &[f64; 3],
    c: &[f64; 3],
    axis: usize,
    safe: bool,
) -> Sign {
    if safe {
        orient2d_safe(a, b, c, axis)
    } else {
        let e = |p: &[f64; 3]| Point::Explicit(*p);
        orient2d(&e(a), &e(b), &e(c), axis)
    }
}

/// Whether the points all lie in one plane square to a coordinate axis: then they are
/// exactly coplanar (faces of boxes and CAD parts), where floating-point filters can only
/// fail.
fn in_one_axis_plane(points: &[&[f64; 3]]) -> bool {
    (0..3).any(|k| points.iter().all(|p| p[k] == points[0][k]))
}

/// Exact comparison of coordinate `axis` of two points.
pub fn cmp_coord(a: &Point, b: &Point, axis: usize) -> Ordering {
    if let (Some(pa), Some(pb)) = (a.explicit(), b.explicit()) {
        // Inputs are finite (validated meshes), so the comparison is total.
        return pa[axis].partial_cmp(&pb[axis]).unwrap_or(Ordering::Equal);
    }
    let s = decide!(coord_diff(a, b, axis))
        .times(sign_of_w(a))
        .times(sign_of_w(b));
    (s as i8).cmp(&0)
}

/// The coordinate in which `b − a` is largest in magnitude: the axis to order points along
/// the segment `a b` by [`cmp_coord`]. For distinct input points the difference there is
/// non-zero (distinct floats never subtract to zero), so the order is strict.
pub fn longest_axis(a: &[f64; 3], b: &[f64; 3]) -> usize {
    (0..3)
        .max_by(|&i, &j| (b[i] - a[i]).abs().total_cmp(&(b[j] - a[j]).abs()))
        .unwrap_or(0)
}

/// Exactly whether two points coincide.
pub fn same_point(a: &Point, b: &Point) -> bool {
    if let (Some(pa), Some(pb)) = (a.explicit(), b.explicit()) {
        return pa == pb;
    }
    (0..3).all(|k| decide!(coord_diff(a, b, k)) == Sign::Zero)
}

fn cross_component<T: Num>(
    p: &[f64; 3],
    q: &[f64; 3],
    r: &[f64; 3],
    s: &[f64; 3],
    axis: usize,
) -> T {
    let (p, q, r, s) = (lift::<T>(p), lift(q), lift(r), lift(s));
    cross2(&vsub(&q, &p), &vsub(&s, &r), axis)
}

/// Exact sign of component `axis` of `(q − p) × (s − r)` (for a triangle `a b c`:
/// `cross_sign(a, b, a, c, axis)` is its normal's component).
pub fn cross_sign(p: &[f64; 3], q: &[f64; 3], r: &[f64; 3], s: &[f64; 3], axis: usize) -> Sign {
    decide!(cross_component(p, q, r, s, axis))
}

fn normals_cross_component<T: Num>(t: &[[f64; 3]; 3], u: &[[f64; 3]; 3], axis: usize) -> T {
    let normal = |t: &[[f64; 3]; 3]| {
        let [a, b, c] = t.map(|p| lift::<T>(&p));
        cross(&vsub(&b, &a), &vsub(&c, &a))
    };
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let (n, m) = (normal(t), normal(u));
    n[i].mul(&m[j]).sub(&n[j].mul(&m[i]))
}

/// Exact sign of component `axis` of `n_t × n_u`, the direction of the line where the
/// planes of triangles `t` and `u` meet.
pub fn normals_cross_sign(t: &[[f64; 3]; 3], u: &[[f64; 3]; 3], axis: usize) -> Sign {
    // A floating-point filter first, as in `normals_dot_sign`: the rounded component is
    // within some 30ε·S_t·S_u of the exact one (a difference of two products of normal
    // components, each within 4ε·S of its exact value and at most S).
    let ((n, sn), (m, sm)) = (normal_and_size(t), normal_and_size(u));
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let d = n[i] * m[j] - n[j] * m[i];
    let bound = 1e-12 * sn * sm;
    if bound.is_finite() && bound > 1e-250 && d.abs() > bound {
        return Sign::of_f64(d);
    }
    decide!(normals_cross_component(t, u, axis))
}

/// A triangle's normal `(b − a) × (c − a)` in `f64`, and the product of the L1 norms of
/// its two edge vectors: a bound on the normal's components that its rounding errors are
/// measured against (each within about 4ε of it, ε = 2⁻⁵³).
fn normal_and_size(p: &[[f64; 3]; 3]) -> ([f64; 3], f64) {
    let (e1, e2) = (
        [p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]],
        [p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]],
    );
    let l1 = |e: &[f64; 3]| e[0].abs() + e[1].abs() + e[2].abs();
    (crate::vec3::cross(&e1, &e2), l1(&e1) * l1(&e2))
}

fn normals_dot_value<T: Num>(t: &[[f64; 3]; 3], u: &[[f64; 3]; 3]) -> T {
    let normal = |t: &[[f64; 3]; 3]| {
        let [a, b, c] = t.map(|p| lift::<T>(&p));
        cross(&vsub(&b, &a), &vsub(&c, &a))
    };
    dot(&normal(t), &normal(u))
}

/// Whether triangles `t` and `u` lie in one plane and face the same way (exact). A corner
/// of `u` at a corner of `t` is in its plane without a predicate: triangles that share an
/// edge need one `orient3d`, not the exact zeros that take its slowest path.
pub(crate) fn same_plane_same_facing(t: &[[f64; 3]; 3], u: &[[f64; 3]; 3]) -> bool {
    u.iter()
        .all(|x| t.contains(x) || orient3d_explicit(&t[0], &t[1], &t[2], x) == Sign::Zero)
        && normals_dot_sign(t, u) == Sign::Positive
}

/// Exact sign of `n_t · n_u`, the dot product of the normals `(b − a) × (c − a)` of
/// triangles `t` and `u`: positive when they face the same side (less than a right angle
/// apart), zero when either is degenerate or they are perpendicular. Decides whether
/// moving a vertex turns a triangle over.
pub fn normals_dot_sign(t: &[[f64; 3]; 3], u: &[[f64; 3]; 3]) -> Sign {
    // A floating-point filter first: each rounded difference is within ε of the exact
    // one per coordinate, each cross-product component within about 4ε·|e₁|₁·|e₂|₁ of
    // its exact value, and the dot product then within about 30ε·S_t·S_u, where S is
    // that product of a triangle's edge norms (ε = 2⁻⁵³; 30ε ≈ 3.4e-15). The answer
    // needs the value beyond 1e-12·S_t·S_u, some 300 times that; anything closer (and any
    // bound that overflows or underflows) goes to the exact evaluation.
    let ((n, sn), (m, sm)) = (normal_and_size(t), normal_and_size(u));
    let d = crate::vec3::dot(&n, &m);
    let bound = 1e-12 * sn * sm;
    if bound.is_finite() && bound > 1e-250 && d.abs() > bound {
        return Sign::of_f64(d);
    }
    decide!(normals_dot_value(t, u))
}

/// What a (generalized, fast-summed) winding number's distance to a threshold loses, beyond its error bound, to
/// the rounding of the sums (a few units in the last place per term, over up to
/// millions of terms): the side of a value `w` with bound `e` is certain where
/// `|w − threshold| > e + SUM_ROUNDING`.
pub(crate) const SUM_ROUNDING: f64 = 1e-9;

/// How far a winding number `w` with error bound `e` clears `threshold` beyond that bound
/// and [`SUM_ROUNDING`]: its side of the threshold is certain where this is positive (NaN
/// where `w` or `e` is, which no comparison takes for certain).
pub(crate) fn side_margin(w: f64, e: f64, threshold: f64) -> f64 {
    (w - threshold).abs() - e - SUM_ROUNDING
}
