//! Exact arithmetic on dyadic numbers `m · 2^e` (big-integer mantissa). Every `f64` is one,
//! and sums, differences and products of dyadic numbers are dyadic, so the kernel's
//! division-free expressions are evaluated without any rounding.
//!
//! Written here rather than taken from a big-float crate because only exact `+ − ×` and
//! the sign are needed: no precision contexts, no rounding modes, nothing to misconfigure.
//! Mantissas stay in an `i128` while they fit (checked operations) and move to a
//! big integer (`dashu-int`) when they would not.

use dashu_int::ops::BitTest;
use dashu_int::IBig;

use super::{Num, Sign};

/// An exact dyadic number `m · 2^e`.
#[derive(Clone, Debug)]
pub struct Dyadic {
    m: Mantissa,
    e: i64,
}

/// A mantissa in a machine word pair while it fits, a big integer beyond: the exact
/// fallback's values for short coordinates (grids, CAD data, points exactly on planes)
/// stay in `i128` and allocate nothing.
#[derive(Clone, Debug)]
enum Mantissa {
    Small(i128),
    Big(IBig),
}

impl Mantissa {
    fn big(&self) -> IBig {
        match self {
            Mantissa::Small(m) => IBig::from(*m),
            Mantissa::Big(m) => m.clone(),
        }
    }

    fn into_big(self) -> IBig {
        match self {
            Mantissa::Small(m) => IBig::from(m),
            Mantissa::Big(m) => m,
        }
    }

    /// `self · 2^k`.
    fn shifted(&self, k: u64) -> Mantissa {
        match self {
            // Fits when the magnitude keeps a sign bit to spare.
            Mantissa::Small(m) if k < 127 && u64::from(m.unsigned_abs().leading_zeros()) > k => {
                Mantissa::Small(m << k)
            }
            Mantissa::Small(m) => Mantissa::Big(IBig::from(*m) << k as usize),
            Mantissa::Big(m) => Mantissa::Big(m << k as usize),
        }
    }
}

impl Dyadic {
    /// `self · 2^(self.e − e)` as a mantissa for exponent `e ≤ self.e`.
    fn mantissa_at(&self, e: i64) -> Mantissa {
        if self.e == e {
            self.m.clone()
        } else {
            self.m.shifted((self.e - e) as u64)
        }
    }

    /// The sum or difference of two mantissas at one exponent.
    fn combine(a: Mantissa, b: Mantissa, subtract: bool, e: i64) -> Dyadic {
        if let (Mantissa::Small(x), Mantissa::Small(y)) = (&a, &b) {
            let r = if subtract {
                x.checked_sub(*y)
            } else {
                x.checked_add(*y)
            };
            if let Some(r) = r {
                return Dyadic {
                    m: Mantissa::Small(r),
                    e,
                };
            }
        }
        let (x, y) = (a.into_big(), b.into_big());
        Dyadic {
            m: Mantissa::Big(if subtract { x - y } else { x + y }),
            e,
        }
    }

    /// Whether the mantissa is held in an `i128`.
    #[cfg(test)]
    pub(crate) fn is_small(&self) -> bool {
        matches!(self.m, Mantissa::Small(_))
    }

    /// The quotient `self / d` in `f64`, within an ulp or two; `None` when `d` is zero.
    pub(crate) fn div_f64(&self, d: &Dyadic) -> Option<f64> {
        let (m, dm) = (self.m.big(), d.m.big());
        if dm == IBig::ZERO {
            return None;
        }
        // The numerator shifted so that the integer quotient has 64 or 65 bits: truncating
        // it (and the numerator, when shifted right) costs less than 2^-63 relative.
        let k = 64 + dm.bit_len() as i64 - m.bit_len() as i64;
        let n = if k >= 0 {
            &m << k as usize
        } else {
            &m >> (-k) as usize
        };
        let q = (n / &dm).to_f64().value();
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
            m: Mantissa::Small(i128::from(m)),
            e,
        }
    }

    fn add(&self, o: &Self) -> Self {
        let e = self.e.min(o.e);
        Self::combine(self.mantissa_at(e), o.mantissa_at(e), false, e)
    }

    fn sub(&self, o: &Self) -> Self {
        let e = self.e.min(o.e);
        Self::combine(self.mantissa_at(e), o.mantissa_at(e), true, e)
    }

    fn mul(&self, o: &Self) -> Self {
        let m = match (&self.m, &o.m) {
            (Mantissa::Small(x), Mantissa::Small(y)) => match x.checked_mul(*y) {
                Some(p) => Mantissa::Small(p),
                None => Mantissa::Big(IBig::from(*x) * IBig::from(*y)),
            },
            (Mantissa::Big(x), Mantissa::Big(y)) => Mantissa::Big(x * y),
            (Mantissa::Big(x), Mantissa::Small(y)) | (Mantissa::Small(y), Mantissa::Big(x)) => {
                Mantissa::Big(x * IBig::from(*y))
            }
        };
        Dyadic { m, e: self.e + o.e }
    }

    fn sign(&self) -> Option<Sign> {
        let s = match &self.m {
            Mantissa::Small(m) => m.signum(),
            Mantissa::Big(m) => match m.signum() {
                s if s > IBig::ZERO => 1,
                s if s < IBig::ZERO => -1,
                _ => 0,
            },
        };
        Some(match s {
            1 => Sign::Positive,
            -1 => Sign::Negative,
            _ => Sign::Zero,
        })
    }
}
