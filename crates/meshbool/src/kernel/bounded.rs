//! The first stage of the predicates: plain `f64` evaluation with a running bound on its
//! rounding error (a dynamic version of the static filters of Shewchuk's predicates, in
//! the form of Higham's forward error bound for sums of products).
//!
//! Every value carries the computed `f64` value `v`, the same expression evaluated on the
//! inputs' absolute values with every subtraction made an addition (`m`, a bound on the
//! size of every term), and `n`, the most roundings any term went through. For the exact
//! value `E` and the exact magnitude `M`, `|v − E| ≤ γₙ·M` with `γₙ = n·u / (1 − n·u)`,
//! `u = 2⁻⁵³` (an addition: `γ_max(a, b) + 1`; a product: `γ_(a + b + 1)`), and `m`,
//! computed with roundings of non-negative numbers only, is at least `M·(1 − u)ⁿ`. The sign
//! of `v` is therefore the exact sign when `|v| > (n + 1)·u·m`, which covers both with a
//! margin. Two cheap operations per operation where intervals take four products and
//! two outward roundings.
//!
//! Underflow would break the relative error model: a product of non-zero magnitudes that
//! falls below 2⁻⁹⁶⁰ poisons the value (no answer). Above that, an underflowing value
//! product is off by at most 2⁻¹⁰⁷⁵, far inside the margin. Overflow makes `m` infinite:
//! no answer.

use super::{Num, Sign};

/// A value with a bound on its rounding error (see the module documentation).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bounded {
    v: f64,
    m: f64,
    /// Roundings along the deepest path; [`POISONED`] after a possible underflow.
    n: u32,
}

/// The roundings count of a value whose magnitude may have underflowed.
const POISONED: u32 = u32::MAX;

/// 2⁻⁹⁶⁰: a product of non-zero magnitudes below this may have lost its relative
/// accuracy to underflow.
const TINY: f64 = 1.0261342003245941e-289;

/// 2⁻⁵³, the unit roundoff.
const U: f64 = f64::EPSILON / 2.0;

impl Bounded {
    /// The sum or difference `v` (rounded) of `a` and `b`. Of two exact values it is the
    /// exact one rounded once, so its own magnitude bounds it (`|v − E| ≤ u·|E|`, `|v| ≥
    /// (1 − u)·|E|`): the differences of input coordinates that every predicate starts
    /// from keep their own small size, not that of the (possibly far larger, UTM-sized)
    /// coordinates.
    #[inline]
    fn sum(a: &Bounded, b: &Bounded, v: f64) -> Bounded {
        if a.n == 0 && b.n == 0 {
            Bounded {
                v,
                m: v.abs(),
                n: 1,
            }
        } else {
            Bounded {
                v,
                m: a.m + b.m,
                n: a.n.max(b.n).saturating_add(1),
            }
        }
    }
}

impl Num for Bounded {
    #[inline]
    fn from_f64(x: f64) -> Self {
        Bounded {
            v: x,
            m: x.abs(),
            n: 0,
        }
    }

    #[inline]
    fn add(&self, o: &Self) -> Self {
        Self::sum(self, o, self.v + o.v)
    }

    #[inline]
    fn sub(&self, o: &Self) -> Self {
        Self::sum(self, o, self.v - o.v)
    }

    #[inline]
    fn mul(&self, o: &Self) -> Self {
        let m = self.m * o.m;
        let n = if m < TINY && self.m != 0.0 && o.m != 0.0 {
            POISONED
        } else {
            self.n.saturating_add(o.n).saturating_add(1)
        };
        Bounded {
            v: self.v * o.v,
            m,
            n,
        }
    }

    #[inline]
    fn sign(&self) -> Option<Sign> {
        if self.n == POISONED || !self.m.is_finite() {
            return None;
        }
        if self.m == 0.0 {
            // Every term has a zero factor (no underflow: that would have poisoned it).
            return Some(Sign::Zero);
        }
        let bound = (f64::from(self.n) + 1.0) * U * self.m;
        if self.v > bound {
            Some(Sign::Positive)
        } else if -self.v > bound {
            Some(Sign::Negative)
        } else {
            None
        }
    }
}
