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

/// `|a|`, to the rounding of its components' squares also where those squares would
/// overflow or underflow `f64` (lengths above 1e145 or below 1e-145: areas of meshes at
/// coordinates beyond 1e72 or within 1e-72 of zero).
pub(crate) fn norm(a: &[f64; 3]) -> f64 {
    let d = dot(a, a);
    if (1e-290..=1e290).contains(&d) || !a.iter().all(|x| x.is_finite()) {
        return d.sqrt();
    }
    // The squares are out of range: the length of `a` over its largest component, times
    // it.
    let m = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if m == 0.0 {
        return 0.0;
    }
    let s = a.map(|x| x / m);
    m * dot(&s, &s).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn norm_holds_where_the_squares_overflow_or_underflow() {
        assert_eq!(norm(&[3.0, 4.0, 0.0]), 5.0);
        let big = 2f64.powi(600);
        assert_eq!(norm(&[3.0 * big, 4.0 * big, 0.0]), 5.0 * big);
        assert_eq!(norm(&[f64::MAX, 0.0, 0.0]), f64::MAX);
        assert!(norm(&[f64::INFINITY, 0.0, 0.0]).is_infinite());
        assert!(norm(&[f64::NAN, 1.0, 0.0]).is_nan());
        let tiny = 2f64.powi(-600);
        assert_eq!(norm(&[3.0 * tiny, 0.0, 4.0 * tiny]), 5.0 * tiny);
        assert_eq!(norm(&[0.0; 3]), 0.0);
        assert_eq!(
            norm(&[f64::MIN_POSITIVE / 8.0, 0.0, 0.0]),
            f64::MIN_POSITIVE / 8.0
        );
    }
}
