//! Exact arithmetic on dyadic numbers `m · 2^e` (big-integer mantissa). Every `f64` is one,
//! and sums, differences and products of dyadic numbers are dyadic, so the kernel's
//! division-free expressions are evaluated without any rounding.
//!
//! Written here rather than taken from a big-float crate because only exact `+ − ×` and
//! the sign are needed: no precision contexts, no rounding modes, nothing to misconfigure.

use dashu_int::IBig;

use super::{Num, Sign};

/// An exact dyadic number `m · 2^e`.
#[derive(Clone, Debug)]
pub struct Dyadic {
    m: IBig,
    e: i64,
}

impl Dyadic {
    /// `self · 2^(self.e − e)` as a mantissa for exponent `e ≤ self.e`.
    fn mantissa_at(&self, e: i64) -> IBig {
        &self.m << (self.e - e) as usize
    }
}

impl Num for Dyadic {
    fn from_f64(x: f64) -> Self {
        debug_assert!(x.is_finite());
        let bits = x.to_bits();
        let exp = ((bits >> 52) & 0x7ff) as i64;
        let frac = (bits & ((1 << 52) - 1)) as i64;
        let (m, e) = if exp == 0 {
            (frac, -1074)
        } else {
            (frac | (1 << 52), exp - 1075)
        };
        let m = if bits >> 63 == 1 { -m } else { m };
        Dyadic {
            m: IBig::from(m),
            e,
        }
    }

    fn add(&self, o: &Self) -> Self {
        let e = self.e.min(o.e);
        Dyadic {
            m: self.mantissa_at(e) + o.mantissa_at(e),
            e,
        }
    }

    fn sub(&self, o: &Self) -> Self {
        let e = self.e.min(o.e);
        Dyadic {
            m: self.mantissa_at(e) - o.mantissa_at(e),
            e,
        }
    }

    fn mul(&self, o: &Self) -> Self {
        Dyadic {
            m: &self.m * &o.m,
            e: self.e + o.e,
        }
    }

    fn sign(&self) -> Option<Sign> {
        Some(match self.m.signum() {
            s if s > IBig::ZERO => Sign::Positive,
            s if s < IBig::ZERO => Sign::Negative,
            _ => Sign::Zero,
        })
    }
}
