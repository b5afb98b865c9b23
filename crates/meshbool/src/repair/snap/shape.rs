//! A triangle's measures in floating point (edge lengths, altitude, area, swept volume,
//! box): what decides which triangles are bad at the tolerance, never topology.

use crate::bvh::Box3;
use crate::vec3::{cross, dot, norm, sub};

/// The smallest edge length and the smallest altitude (twice the area over the longest
/// edge) of a triangle, and twice its area.
pub(super) fn shape(p: &[[f64; 3]; 3]) -> (f64, f64, f64) {
    let l = [0, 1, 2].map(|k| norm(&sub(&p[(k + 1) % 3], &p[k])));
    let twice = norm(&cross(&sub(&p[1], &p[0]), &sub(&p[2], &p[0])));
    let longest = l[0].max(l[1]).max(l[2]);
    let h = if longest > 0.0 { twice / longest } else { 0.0 };
    (l[0].min(l[1]).min(l[2]), h, twice)
}

/// Whether a triangle is bad at tolerance `d`: its key (smallest altitude, or shortest
/// edge where smaller: worst first), `None` when it is not bad.
pub(super) fn badness(p: &[[f64; 3]; 3], d: f64) -> Option<f64> {
    let (e, h, _) = shape(p);
    (e < d || h < d).then_some(h.min(e))
}

/// The smallest altitude of a triangle.
pub(super) fn altitude(p: &[[f64; 3]; 3]) -> f64 {
    shape(p).1
}

/// Six times the signed volume of the tetrahedron of a triangle and `o`.
pub(super) fn volume6(p: &[[f64; 3]; 3], o: &[f64; 3]) -> f64 {
    let [a, b, c] = p.map(|x| sub(&x, o));
    dot(&a, &cross(&b, &c))
}

/// The smaller of two numbers that are not NaN (`f64::min` also orders NaN, in more
/// instructions: this runs for every triangle).
#[inline]
pub(super) fn min(a: f64, b: f64) -> f64 {
    if a < b {
        a
    } else {
        b
    }
}

/// The larger of two numbers that are not NaN.
#[inline]
pub(super) fn max(a: f64, b: f64) -> f64 {
    if a > b {
        a
    } else {
        b
    }
}

#[inline]
pub(super) fn tri_box(p: &[[f64; 3]; 3]) -> Box3 {
    let lo = |k: usize| min(min(p[0][k], p[1][k]), p[2][k]);
    let hi = |k: usize| max(max(p[0][k], p[1][k]), p[2][k]);
    [[lo(0), lo(1), lo(2)], [hi(0), hi(1), hi(2)]]
}

pub(super) fn grown(b: &Box3, by: f64) -> Box3 {
    [b[0].map(|x| x - by), b[1].map(|x| x + by)]
}
