//! Floating-point filters that only ever answer "certain": for tests asked of millions of
//! neighbouring pairs (the self-intersection check), where almost every answer is
//! clear-cut. Each computes a value in plain `f64` and answers only when it exceeds a
//! margin far above the value's worst rounding error; anything closer, and any margin
//! that overflows or underflows, is left to the exact predicates.

use super::{orient3d_explicit, Sign};
use crate::vec3::{cross, dot, norm, sub};

/// A triangle's plane prepared for many side tests against explicit points: a floating-
/// point filter that answers only where its rounding error cannot change the sign, and
/// leaves the rest to [`orient3d_explicit`]. Used by tests that look at millions of
/// neighbouring pairs (the self-intersection check), where most answers are clear-cut.
#[derive(Clone, Copy, Debug)]
pub struct FloatPlane {
    a: [f64; 3],
    n: [f64; 3],
    /// `|b − a|₁ · |c − a|₁`: bounds the size of the normal's rounding error.
    scale: f64,
}

impl FloatPlane {
    /// The plane through `a`, `b`, `c`, normal `(b − a) × (c − a)`.
    pub fn new(t: &[[f64; 3]; 3]) -> Self {
        let [a, b, c] = *t;
        let u: [f64; 3] = std::array::from_fn(|k| b[k] - a[k]);
        let v: [f64; 3] = std::array::from_fn(|k| c[k] - a[k]);
        let l1 = |x: &[f64; 3]| x[0].abs() + x[1].abs() + x[2].abs();
        FloatPlane {
            a,
            n: cross(&u, &v),
            scale: l1(&u) * l1(&v),
        }
    }

    /// The side of `q` (as [`orient3d_explicit`] with the plane's three points) when the
    /// floating-point value is certain: its magnitude is over 1e-12 of the bound on the
    /// terms, some 400 times the worst rounding error of the sum; `None` otherwise (and
    /// where the bound overflows or underflows).
    pub fn side(&self, q: &[f64; 3]) -> Option<Sign> {
        let d: [f64; 3] = std::array::from_fn(|k| q[k] - self.a[k]);
        let s = self.n[0] * d[0] + self.n[1] * d[1] + self.n[2] * d[2];
        certain_sign(
            s,
            1e-12 * self.scale * (d[0].abs() + d[1].abs() + d[2].abs()),
        )
    }

    /// The exact side of `q` relative to the plane through `t` (this plane's triangle).
    pub fn side_exact(&self, t: &[[f64; 3]; 3], q: &[f64; 3]) -> Sign {
        self.side(q)
            .unwrap_or_else(|| orient3d_explicit(&t[0], &t[1], &t[2], q))
    }
}

/// Whether the triangles `a b u` and `a b v`, which share the edge `a b`, certainly lie
/// in different half-planes bounded by the edge's line, so that they meet in that edge at
/// most (coplanar or not): the normals `(b − a) × (u − a)` and `(b − a) × (v − a)` point
/// more than a right angle apart, i.e. seen along the edge, `u` and `v` lie more than a
/// right angle apart around it. With `e = b − a` and ε = 2⁻⁵³: each computed difference
/// is within a factor 1 ± ε of the exact one per coordinate, each cross-product component
/// within about 4ε·|e|·|u − a| (resp. `|v − a|`), and their dot product then within about
/// 20ε·|e|²·|u − a|·|v − a| ≈ 2.2e-15 of that product; the answer needs the value below
/// −1e-12 times the product, over 400 times that error. Margins that overflow or
/// underflow (below 1e-250, where subnormal products lose their relative accuracy)
/// answer `false`.
#[inline]
pub fn certainly_unfolded(a: &[f64; 3], b: &[f64; 3], u: &[f64; 3], v: &[f64; 3]) -> bool {
    let e = sub(b, a);
    let (u, v) = (sub(u, a), sub(v, a));
    let d = dot(&cross(&e, &u), &cross(&e, &v));
    let margin = 1e-12 * dot(&e, &e) * norm(&u) * norm(&v);
    margin.is_finite() && margin > 1e-250 && d < -margin
}

/// The axes of the separating-axis test of two triangles with edges `ep` and `eq` (each
/// triangle's normal is its first two edges' cross product), with the margin their
/// projections must clear, `1e-13 · |axis|₁ · scale` (axes whose margin overflows or
/// underflows left out): every edge of one crossed with every edge of the other, then
/// each normal crossed with its own edges, in its plane, square to an edge (what
/// separates coplanar triangles, whose edge-cross-edge axes all lie along the normal).
#[inline]
fn separating_axes(
    ep: [[f64; 3]; 3],
    eq: [[f64; 3]; 3],
    scale: f64,
) -> impl Iterator<Item = ([f64; 3], f64)> {
    let (np, nq) = (cross(&ep[0], &ep[1]), cross(&eq[0], &eq[1]));
    let across = (0..9).map(move |k| cross(&ep[k / 3], &eq[k % 3]));
    let in_plane = (0..3)
        .map(move |k| cross(&np, &ep[k]))
        .chain((0..3).map(move |k| cross(&nq, &eq[k])));
    across.chain(in_plane).filter_map(move |a| {
        let margin = 1e-13 * (a[0].abs() + a[1].abs() + a[2].abs()) * scale;
        (margin.is_finite() && margin > 1e-250).then_some((a, margin))
    })
}

/// Whether triangles `p` and `q`, whose corners `p[kp]` and `q[kq]` are one point (the
/// same coordinates: a shared vertex), certainly meet in that point alone: some
/// edge-cross-edge axis, or an axis in one triangle's plane square to one of its edges,
/// has `p`'s two other corners strictly on one side of the plane through the shared
/// point square to it and `q`'s two strictly on the other. Then each triangle meets that
/// plane in the shared point only. The separating-axis test of [`certainly_separated`]
/// with the shared point as origin (it projects to exactly zero) and the same margin.
/// For the pairs a vertex's planes do not settle: neighbours in a fan on either side of
/// a crease, where each leans over the other's plane.
#[inline]
pub fn certainly_apart_beyond_corner(
    p: &[[f64; 3]; 3],
    kp: usize,
    q: &[[f64; 3]; 3],
    kq: usize,
) -> bool {
    let o = p[kp];
    debug_assert_eq!(o, q[kq]);
    // The other corners, in order, relative to the shared one.
    let others = |t: &[[f64; 3]; 3], k: usize| [sub(&t[(k + 1) % 3], &o), sub(&t[(k + 2) % 3], &o)];
    let (p, q) = (others(p, kp), others(q, kq));
    let scale = p
        .iter()
        .chain(&q)
        .flat_map(|x| x.iter())
        .fold(0.0f64, |s, x| s.max(x.abs()));
    let edges = |t: &[[f64; 3]; 2]| [t[0], t[1], sub(&t[1], &t[0])];
    for (a, margin) in separating_axes(edges(&p), edges(&q), scale) {
        let (sp, sq) = (p.map(|x| dot(&a, &x)), q.map(|x| dot(&a, &x)));
        let above = |s: [f64; 2]| s[0] > margin && s[1] > margin;
        let below = |s: [f64; 2]| s[0] < -margin && s[1] < -margin;
        if (above(sp) && below(sq)) || (below(sp) && above(sq)) {
            return true;
        }
    }
    false
}

/// Whether an edge-cross-edge axis, or an axis in one triangle's plane square to one of
/// its edges, certainly separates triangles `p` and `q`: the separating-axis test in
/// floating point, answering only "certainly apart". Any vector
/// is a valid axis (the one computed from rounded edges is just some direction); what
/// must be certain is that the exact projections, onto it, of the corners (taken
/// relative to `p[0]`, which moves neither) leave a gap. Each computed projection is
/// within 4 ulp of |axis|₁ · (largest relative coordinate) of the exact one; the gap must
/// exceed 1e-13 times that product, over 50 times the two projections' errors together.
/// For pairs whose planes do not separate them: mostly neighbours across nearly planar
/// quads, where rounded coordinates put a corner of each a hair over the other's plane,
/// and coplanar triangles apart in their plane (the slivers of a CAD model's flat faces).
#[inline]
pub fn certainly_separated(p: &[[f64; 3]; 3], q: &[[f64; 3]; 3]) -> bool {
    let o = p[0];
    let (p, q) = (p.map(|x| sub(&x, &o)), q.map(|x| sub(&x, &o)));
    let scale = p
        .iter()
        .chain(&q)
        .flat_map(|x| x.iter())
        .fold(0.0f64, |s, x| s.max(x.abs()));
    let edges = |t: &[[f64; 3]; 3]| [sub(&t[1], &t[0]), sub(&t[2], &t[1]), sub(&t[0], &t[2])];
    for (a, margin) in separating_axes(edges(&p), edges(&q), scale) {
        let range = |t: &[[f64; 3]; 3]| {
            let s = t.map(|x| dot(&a, &x));
            (s[0].min(s[1]).min(s[2]), s[0].max(s[1]).max(s[2]))
        };
        let ((p_lo, p_hi), (q_lo, q_hi)) = (range(&p), range(&q));
        if p_hi + margin < q_lo || q_hi + margin < p_lo {
            return true;
        }
    }
    false
}

/// The sign of the orientation of `a b c` in the plane when the floating-point value is
/// certain: the determinant of the rounded differences `(b − a) × (c − a)`, whose error
/// is below 3.4e-16 times the sum of its two products' magnitudes (Shewchuk's
/// `ccwerrboundA`); answered only when it exceeds 1e-12 times that sum, and not where
/// that margin overflows or underflows.
#[inline]
fn certain_orient2d(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Option<Sign> {
    let l = (b[0] - a[0]) * (c[1] - a[1]);
    let r = (b[1] - a[1]) * (c[0] - a[0]);
    certain_sign(l - r, 1e-12 * (l.abs() + r.abs()))
}

/// The sign of a floating-point `value` whose error is known to be far below `margin`,
/// when its magnitude exceeds the margin; `None` otherwise, and where the margin
/// overflows or underflows (below 1e-250, where subnormal products lose their relative
/// accuracy).
#[inline]
fn certain_sign(value: f64, margin: f64) -> Option<Sign> {
    (margin.is_finite() && margin > 1e-250 && value.abs() > margin).then(|| Sign::of_f64(value))
}

/// Whether triangles `p` and `q` certainly meet at most in the shared corner `corner`
/// (`(kp, kq)`: `p[kp]` and `q[kq]` are one point), or (`None`) not at all, judged from
/// their shadows on the coordinate plane most square to `p`'s normal: an edge's line of
/// one shadow (through the shared corner, when there is one) with that shadow on one side
/// and the other's corners (but the shared one) certainly on the other. Shadows that meet
/// at most there come from triangles that do (a meeting point's shadow is in both, and a
/// triangle whose shadow is not flat is its shadow's only preimage of each point), for
/// any plane of projection; the one most square to `p` keeps coplanar pairs as they are.
/// Each orientation is trusted only where its floating-point determinant exceeds 1e-12
/// times the sum of its two products (its error is below 3.4e-16 times that, Shewchuk's
/// bound), and not where that margin overflows or underflows. For the pairs whose planes
/// do not separate them that are coplanar or nearly: the pieces of one cut face, side by
/// side.
#[inline]
pub fn certainly_apart_projected(
    p: &[[f64; 3]; 3],
    q: &[[f64; 3]; 3],
    corner: Option<(usize, usize)>,
) -> bool {
    let n = cross(&sub(&p[1], &p[0]), &sub(&p[2], &p[0]));
    let drop = if n[0].abs() >= n[1].abs() && n[0].abs() >= n[2].abs() {
        0
    } else if n[1].abs() >= n[2].abs() {
        1
    } else {
        2
    };
    let (u, v) = ((drop + 1) % 3, (drop + 2) % 3);
    let (p, q) = (p.map(|x| [x[u], x[v]]), q.map(|x| [x[u], x[v]]));
    // Each shadow's orientation, once: the exact sign is that of every rotation of it.
    let (Some(sp), Some(sq)) = (
        certain_orient2d(p[0], p[1], p[2]),
        certain_orient2d(q[0], q[1], q[2]),
    ) else {
        return false;
    };
    // Edge `a b` of a shadow oriented `s` (its third corner on side `s` of the line)
    // separates the `others` when they lie certainly on side `-s`.
    let beyond = |a: [f64; 2], b: [f64; 2], s: Sign, others: &[[f64; 2]]| {
        let opposite = s.reversed();
        others
            .iter()
            .all(|&x| certain_orient2d(a, b, x) == Some(opposite))
    };
    match corner {
        None => {
            (0..3).any(|k| beyond(p[k], p[(k + 1) % 3], sp, &q))
                || (0..3).any(|k| beyond(q[k], q[(k + 1) % 3], sq, &p))
        }
        Some((kp, kq)) => {
            // The edges through the shared corner `o`: `o → next` has the third corner on
            // the shadow's side, `o → previous` on the other.
            let o = p[kp];
            let (p1, p2) = (p[(kp + 1) % 3], p[(kp + 2) % 3]);
            let (q1, q2) = (q[(kq + 1) % 3], q[(kq + 2) % 3]);
            beyond(o, p1, sp, &[q1, q2])
                || beyond(o, p2, sp.reversed(), &[q1, q2])
                || beyond(o, q1, sq, &[p1, p2])
                || beyond(o, q2, sq.reversed(), &[p1, p2])
        }
    }
}
