//! Extreme scales: meshes whose coordinates are all tiny or all huge are computed at unit
//! size ([`extreme_scale`]), and the exact power-of-two scalings of points, lengths and
//! measures between the two sizes. Below the pipeline, repair and measures, whose
//! options and reports scale with their meshes; the front door decides when.

use crate::Mesh;

/// Inputs whose coordinates are all tiny or all huge (the largest below 2^-200 or above
/// 2^200) are computed at unit size: the exact kernel's filters and implicit points work
/// in products of several coordinates, which would underflow or overflow `f64` there.
/// Multiplying by a power of two is exact (for normal numbers), and every step commutes
/// with it, so the result is the unit-size result scaled back bit for bit.
///
/// The exponent `e` that brings the meshes' largest magnitude into `[1, 2)`, when outside
/// the safe range; `None` when they are computed as given.
pub(crate) fn extreme_scale(meshes: &[&Mesh]) -> Option<i32> {
    use rayon::prelude::*;
    // The largest magnitude, from the bits without the sign: for non-negative floats the
    // order of the bit patterns is the numeric one (infinity and NaN above every finite
    // one). Chunks side by side on large meshes.
    let most = |ps: &[[f64; 3]]| {
        ps.iter()
            .flatten()
            .map(|x| x.to_bits() & !(1 << 63))
            .max()
            .unwrap_or(0)
    };
    let bits = meshes
        .iter()
        .map(|m| match m.positions.len() {
            n if n >= 1 << 16 => m.positions.par_chunks(1 << 14).map(most).max().unwrap_or(0),
            _ => most(&m.positions),
        })
        .max()
        .unwrap_or(0);
    let largest = f64::from_bits(bits);
    if !(largest.is_finite() && largest > 0.0) {
        return None;
    }
    let e = largest.log2().floor() as i32;
    (!(-200..=200).contains(&e)).then_some(-e)
}

/// `m` with every coordinate multiplied by `2^e` (exact for normal numbers).
pub(crate) fn scaled_mesh(m: &Mesh, e: i32) -> Mesh {
    let mut out = m.clone();
    scale_points(&mut out.positions, e);
    out
}

/// `x · 2^e`, in two steps where `2^e` alone is not a normal `f64` (a length given with
/// meshes computed at unit size).
pub(crate) fn scaled(x: f64, e: i32) -> f64 {
    let (half, rest) = (e / 2, e - e / 2);
    x * 2f64.powi(half) * 2f64.powi(rest)
}

/// `x · 2^(n·e)`: a measure of dimension `n` (1 a length, 2 an area, 3 a volume) of a
/// mesh scaled by `2^e`, one [`scaled`] per dimension so that no step leaves `f64`'s range.
pub(crate) fn scaled_measure(x: f64, e: i32, n: u32) -> f64 {
    (0..n).fold(x, |x, _| scaled(x, e))
}

/// Multiplies every coordinate by `2^e`, in two steps where `2^e` alone is not a normal
/// `f64`.
pub(crate) fn scale_points(points: &mut [[f64; 3]], e: i32) {
    let (half, rest) = (e / 2, e - e / 2);
    let (f, g) = (2f64.powi(half), 2f64.powi(rest));
    for p in points {
        for x in p.iter_mut() {
            *x = *x * f * g;
        }
    }
}
