//! Exact arithmetic on dyadic numbers `m · 2^e` (big-integer mantissa). Every `f64` is one,
//! and sums, differences and products of dyadic numbers are dyadic, so the kernel's
//! division-free expressions are evaluated without any rounding.
//!
//! Written here rather than taken from a big-float crate because only exact `+ − ×` and
//! the sign are needed: no precision contexts, no rounding modes, nothing to misconfigure.

use dashu_int::ops::BitTest;
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

    /// The quotient `self / d` in `f64`, within an ulp or two; `None` when `d` is zero.
    pub(crate) fn div_f64(&self, d: &Dyadic) -> Option<f64> {
        if d.m == IBig::ZERO {
            return None;
        }
        // The numerator shifted so that the integer quotient has 64 or 65 bits: truncating
        // it (and the numerator, when shifted right) costs less than 2^-63 relative.
        let k = 64 + d.m.bit_len() as i64 - self.m.bit_len() as i64;
        let n = if k >= 0 {
            &self.m << k as usize
        } else {
            &self.m >> (-k) as usize
        };
        let q = (n / &d.m).to_f64().value();
        Some(times_power_of_two(q, self.e - d.e - k))
    }
}

/// `x · 2^e`, in steps that keep every factor a normal `f64`.
fn times_power_of_two(mut x: f64, mut e: i64) -> f64 {
    while e > 1000 && x.is_finite() && x != 0.0 {
        x *= 2f64.powi(1000);
        e -= 1000;
    }
    while e < -1000 && x != 0.0 {
        x *= 2f64.powi(-1000);
        e += 1000;
    }
    x * 2f64.powi(e.clamp(-1100, 1100) as i32)
}

impl Num for Dyadic {
    /// Exact for finite `x`. A non-finite `x` (only from a public caller's unvalidated
    /// mesh: every operation validates its inputs) is read by its bits as a large finite
    /// number: a defined, meaningless answer rather than a panic.
    fn from_f64(x: f64) -> Self {
        let bits = x.to_bits();
        let exp = ((bits >> 52) & 0x7ff) as i64;
        let frac = (bits & ((1 << 52) - 1)) as i64;
        let (m, e) = if exp == 0 {
            (frac, -1074)
        } else {
            (frac | (1 << 52), exp - 1075)
        };
        // Trailing zero bits moved into the exponent: short binary fractions (grids, CAD
        // data) then have short mantissas, and their products stay in a machine word or two.
        let (m, e) = if m == 0 {
            (0, 0)
        } else {
            let tz = m.trailing_zeros();
            (m >> tz, e + i64::from(tz))
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
