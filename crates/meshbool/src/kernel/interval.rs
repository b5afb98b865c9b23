//! Interval arithmetic without changing the rounding mode: every rounded result is widened
//! by one unit in the last place on each side (`next_down`/`next_up`). Under
//! round-to-nearest the exact value is within half an ulp of the rounded one, so the
//! widened interval always contains it. Overflow to infinity and NaN make the interval
//! undecided, never wrong.

use super::{Num, Sign};

/// A closed interval `[lo, hi]` known to contain an exact real value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    lo: f64,
    hi: f64,
}

impl Interval {
    const EVERYTHING: Interval = Interval {
        lo: f64::NEG_INFINITY,
        hi: f64::INFINITY,
    };

    /// The quotient `self / o`, or `None` when `o` may be zero. IEEE division is
    /// correctly rounded, so widening by an ulp encloses the exact quotient.
    pub(crate) fn div(&self, o: &Interval) -> Option<Interval> {
        if !(o.lo > 0.0 || o.hi < 0.0) {
            return None;
        }
        let q = [
            self.lo / o.lo,
            self.lo / o.hi,
            self.hi / o.lo,
            self.hi / o.hi,
        ];
        if q.iter().any(|x| !x.is_finite()) {
            return None;
        }
        Some(Self::widened(
            q.iter().copied().fold(f64::INFINITY, f64::min),
            q.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        ))
    }

    /// The lower end.
    pub(crate) fn lo(&self) -> f64 {
        self.lo
    }

    /// The upper end.
    pub(crate) fn hi(&self) -> f64 {
        self.hi
    }

    /// Whether the two intervals share no point.
    pub(crate) fn disjoint(&self, o: &Interval) -> bool {
        self.hi < o.lo || o.hi < self.lo
    }

    fn widened(lo: f64, hi: f64) -> Interval {
        if lo.is_nan() || hi.is_nan() {
            return Self::EVERYTHING;
        }
        Interval {
            lo: lo.next_down(),
            hi: hi.next_up(),
        }
    }
}

impl Num for Interval {
    #[inline]
    fn from_f64(x: f64) -> Self {
        Interval { lo: x, hi: x }
    }

    #[inline]
    fn add(&self, o: &Self) -> Self {
        Self::widened(self.lo + o.lo, self.hi + o.hi)
    }

    #[inline]
    fn sub(&self, o: &Self) -> Self {
        Self::widened(self.lo - o.hi, self.hi - o.lo)
    }

    #[inline]
    fn mul(&self, o: &Self) -> Self {
        let p = [
            self.lo * o.lo,
            self.lo * o.hi,
            self.hi * o.lo,
            self.hi * o.hi,
        ];
        if p.iter().any(|x| x.is_nan()) {
            return Self::EVERYTHING;
        }
        Self::widened(
            p.iter().copied().fold(f64::INFINITY, f64::min),
            p.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        )
    }

    #[inline]
    fn sign(&self) -> Option<Sign> {
        if self.lo > 0.0 {
            Some(Sign::Positive)
        } else if self.hi < 0.0 {
            Some(Sign::Negative)
        } else if self.lo == 0.0 && self.hi == 0.0 {
            Some(Sign::Zero)
        } else {
            None
        }
    }
}
