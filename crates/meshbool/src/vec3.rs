//! Plain floating-point vector helpers for measures and filters. Nothing here decides
//! topology: exact decisions go through [`crate::kernel`].

/// `a - b`.
pub(crate) fn sub(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `a × b`.
pub(crate) fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a · b`.
pub(crate) fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `|a|`: finite for every finite `a`, also where the squares of its components overflow
/// (lengths above about 1e154: areas of meshes at coordinates above 1e77).
pub(crate) fn norm(a: &[f64; 3]) -> f64 {
    let n = dot(a, a).sqrt();
    if n.is_finite() || !a.iter().all(|x| x.is_finite()) {
        return n;
    }
    // The squares overflowed: the length of `a` over its largest component, times it.
    let m = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let s = a.map(|x| x / m);
    m * dot(&s, &s).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn norm_is_finite_where_the_squares_overflow() {
        assert_eq!(norm(&[3.0, 4.0, 0.0]), 5.0);
        let big = 2f64.powi(600);
        assert_eq!(norm(&[3.0 * big, 4.0 * big, 0.0]), 5.0 * big);
        assert_eq!(norm(&[f64::MAX, 0.0, 0.0]), f64::MAX);
        assert!(norm(&[f64::INFINITY, 0.0, 0.0]).is_infinite());
        assert!(norm(&[f64::NAN, 1.0, 0.0]).is_nan());
    }
}
