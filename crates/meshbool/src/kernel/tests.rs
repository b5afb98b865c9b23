//! The kernel against an independent oracle: every point constructed explicitly in big
//! rationals (`num-rational`), every predicate a rational determinant.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, Zero};

use super::*;

type Q = BigRational;

fn q(x: f64) -> Q {
    Q::from_float(x).unwrap()
}

fn qv(p: &[f64; 3]) -> [Q; 3] {
    p.map(q)
}

fn sub(a: &[Q; 3], b: &[Q; 3]) -> [Q; 3] {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

fn crs(a: &[Q; 3], b: &[Q; 3]) -> [Q; 3] {
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

fn dt(a: &[Q; 3], b: &[Q; 3]) -> Q {
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

/// The point as exact rational coordinates, computed the textbook way (with division).
fn oracle_point(p: &Point) -> [Q; 3] {
    match p {
        Point::Explicit(p) => qv(p),
        Point::Lpi { p, q: qq, a, b, c } => {
            let (p, qq, a, b, c) = (qv(p), qv(qq), qv(a), qv(b), qv(c));
            let n = crs(&sub(&b, &a), &sub(&c, &a));
            let d = sub(&qq, &p);
            let t = dt(&n, &sub(&a, &p)) / dt(&n, &d);
            [&p[0] + &t * &d[0], &p[1] + &t * &d[1], &p[2] + &t * &d[2]]
        }
        Point::Ssi {
            p,
            q: qq,
            r,
            s,
            axis,
        } => {
            let (p, qq, r, s) = (qv(p), qv(qq), qv(r), qv(s));
            let (i, j) = ((*axis as usize + 1) % 3, (*axis as usize + 2) % 3);
            let (d, e, f) = (sub(&qq, &p), sub(&s, &r), sub(&r, &p));
            let c2 = |u: &[Q; 3], v: &[Q; 3]| &u[i] * &v[j] - &u[j] * &v[i];
            let t = c2(&f, &e) / c2(&d, &e);
            [&p[0] + &t * &d[0], &p[1] + &t * &d[1], &p[2] + &t * &d[2]]
        }
        Point::Tpi(planes) => oracle_tpi(planes),
    }
}

/// Where three planes meet, by Cramer's rule in rationals.
fn oracle_tpi(planes: &[[[f64; 3]; 3]; 3]) -> [Q; 3] {
    let pl = |t: &[[f64; 3]; 3]| {
        let (a, b, c) = (qv(&t[0]), qv(&t[1]), qv(&t[2]));
        let n = crs(&sub(&b, &a), &sub(&c, &a));
        let d = dt(&n, &a);
        (n, d)
    };
    let [(n1, d1), (n2, d2), (n3, d3)] = [0, 1, 2].map(|i| pl(&planes[i]));
    let w = dt(&n1, &crs(&n2, &n3));
    let (c23, c31, c12) = (crs(&n2, &n3), crs(&n3, &n1), crs(&n1, &n2));
    std::array::from_fn(|k| (&d1 * &c23[k] + &d2 * &c31[k] + &d3 * &c12[k]) / &w)
}

fn sign_q(x: &Q) -> Sign {
    if x.is_zero() {
        Sign::Zero
    } else if x.is_positive() {
        Sign::Positive
    } else {
        Sign::Negative
    }
}

fn oracle_orient3d(a: &Point, b: &Point, c: &Point, d: &Point) -> Sign {
    let [a, b, c, d] = [a, b, c, d].map(oracle_point);
    sign_q(&dt(&crs(&sub(&b, &a), &sub(&c, &a)), &sub(&d, &a)))
}

fn oracle_orient2d(a: &Point, b: &Point, c: &Point, axis: usize) -> Sign {
    let [a, b, c] = [a, b, c].map(oracle_point);
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let (u, v) = (sub(&b, &a), sub(&c, &a));
    sign_q(&(&u[i] * &v[j] - &u[j] * &v[i]))
}

/// The kernel and the rational oracle both give `want` for `x` against the plane `a b c`.
fn assert_plane_side(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], x: &Point, want: Sign) {
    assert_eq!(orient3d_plane(a, b, c, x), want, "kernel: {x:?}");
    let e = |p: &[f64; 3]| Point::Explicit(*p);
    assert_eq!(
        oracle_orient3d(&e(a), &e(b), &e(c), x),
        want,
        "oracle: {x:?}"
    );
}

/// Small deterministic generator (xorshift64*).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn point(&mut self, offset: [f64; 3], scale: f64) -> [f64; 3] {
        std::array::from_fn(|k| offset[k] + scale * (self.unit() - 0.5))
    }
}

const UTM: [f64; 3] = [478_614.7, 6_772_313.84, 412.5];

/// An LPI whose segment really crosses the plane (the constructor's precondition).
fn random_lpi(rng: &mut Rng, offset: [f64; 3], scale: f64) -> Point {
    loop {
        let [p, q, a, b, c] = [0; 5].map(|_| rng.point(offset, scale));
        let (sp, sq) = (
            orient3d_explicit(&a, &b, &c, &p),
            orient3d_explicit(&a, &b, &c, &q),
        );
        if sp != Sign::Zero && sq == sp.reversed() {
            return Point::Lpi { p, q, a, b, c };
        }
    }
}

/// Three random planes meeting in one point (independent normals).
fn random_tpi(rng: &mut Rng, offset: [f64; 3], scale: f64) -> Point {
    loop {
        let planes: [[[f64; 3]; 3]; 3] =
            std::array::from_fn(|_| std::array::from_fn(|_| rng.point(offset, scale)));
        if oracle_det(&planes) != Sign::Zero {
            return Point::Tpi(Box::new(planes));
        }
    }
}

/// The sign of the determinant of the three planes' normals.
fn oracle_det(planes: &[[[f64; 3]; 3]; 3]) -> Sign {
    let n = planes.map(|t| {
        let (a, b, c) = (qv(&t[0]), qv(&t[1]), qv(&t[2]));
        crs(&sub(&b, &a), &sub(&c, &a))
    });
    sign_q(&dt(&n[0], &crs(&n[1], &n[2])))
}

fn random_point(rng: &mut Rng, offset: [f64; 3], scale: f64) -> Point {
    match rng.next() % 3 {
        0 => Point::Explicit(rng.point(offset, scale)),
        1 => random_lpi(rng, offset, scale),
        _ => random_tpi(rng, offset, scale),
    }
}

/// A three-plane point lies exactly on each of its planes, and equals the same point
/// built from the planes in another order, or from other points of the same planes.
#[test]
fn three_plane_points_lie_on_their_planes() {
    let mut rng = Rng(7);
    for offset in [[0.0; 3], UTM] {
        for _ in 0..100 {
            let tpi = random_tpi(&mut rng, offset, 10.0);
            let Point::Tpi(planes) = &tpi else {
                unreachable!()
            };
            for [a, b, c] in planes.iter() {
                assert_plane_side(a, b, c, &tpi, Sign::Zero);
            }
            let [p1, p2, p3] = **planes;
            let again = Point::Tpi(Box::new([p3, [p2[1], p2[2], p2[0]], p1]));
            assert!(same_point(&tpi, &again));
            // The approximation is close to the exact point (a few ulps of the scale).
            let exact = oracle_point(&tpi);
            let got = tpi.approx();
            for k in 0..3 {
                let err = (q(got[k]) - &exact[k]).abs();
                assert!(err < q(1e-6 * (1.0 + offset[k].abs())), "{k}: {got:?}");
            }
        }
    }
    // Axis planes x = 1, y = 2, z = 3: the explicit point (1, 2, 3).
    let x = [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [1.0, 0.0, 1.0]];
    let y = [[0.0, 2.0, 0.0], [0.0, 2.0, 1.0], [1.0, 2.0, 0.0]];
    let z = [[0.0, 0.0, 3.0], [1.0, 0.0, 3.0], [0.0, 1.0, 3.0]];
    let tpi = Point::Tpi(Box::new([x, y, z]));
    assert!(same_point(&tpi, &Point::Explicit([1.0, 2.0, 3.0])));
    assert_eq!(tpi.approx(), [1.0, 2.0, 3.0]);
    assert!(!same_point(
        &tpi,
        &Point::Explicit([1.0, 2.0, 3.0f64.next_up()])
    ));
}

#[test]
fn predicates_agree_with_rationals_on_random_points() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for offset in [[0.0; 3], UTM] {
        for _ in 0..300 {
            let pts: Vec<Point> = (0..4)
                .map(|_| random_point(&mut rng, offset, 10.0))
                .collect();
            assert_eq!(
                orient3d(&pts[0], &pts[1], &pts[2], &pts[3]),
                oracle_orient3d(&pts[0], &pts[1], &pts[2], &pts[3])
            );
            let prepared: Vec<Prepared> = pts.iter().cloned().map(Prepared::new).collect();
            for axis in 0..3 {
                let want = oracle_orient2d(&pts[0], &pts[1], &pts[2], axis);
                assert_eq!(orient2d(&pts[0], &pts[1], &pts[2], axis), want);
                let got = orient2d_prepared(&prepared[0], &prepared[1], &prepared[2], axis);
                assert_eq!(got, want);
                let want = oracle_point(&pts[0])[axis].cmp(&oracle_point(&pts[1])[axis]);
                assert_eq!(cmp_coord(&pts[0], &pts[1], axis), want);
                assert_eq!(cmp_coord_prepared(&prepared[0], &prepared[1], axis), want);
            }
            assert!(same_point_prepared(&prepared[2], &prepared[2]));
            assert_eq!(
                same_point_prepared(&prepared[0], &prepared[1]),
                oracle_point(&pts[0]) == oracle_point(&pts[1])
            );
        }
    }
}

/// An LPI of a segment crossing the plane of a triangle `t`: the point lies exactly on
/// that plane, so orient3d against `t` (and against any triangle of the same plane) is
/// exactly zero; the interval filter cannot decide this, the exact path must.
#[test]
fn implicit_point_on_its_own_plane_is_exactly_zero() {
    let mut rng = Rng(42);
    for offset in [[0.0; 3], UTM] {
        for _ in 0..200 {
            let lpi = random_lpi(&mut rng, offset, 10.0);
            let Point::Lpi { a, b, c, p, q } = lpi.clone() else {
                unreachable!()
            };
            assert_plane_side(&a, &b, &c, &lpi, Sign::Zero);
            // On the segment too: collinear with p and q in every projection.
            for axis in 0..3 {
                assert_eq!(
                    orient2d(&Point::Explicit(p), &Point::Explicit(q), &lpi, axis),
                    Sign::Zero
                );
            }
            // The same geometric point from the plane spanned differently (b, c, a).
            let again = Point::Lpi {
                p: q,
                q: p,
                a: b,
                b: c,
                c: a,
            };
            assert!(same_point(&lpi, &again));
            for axis in 0..3 {
                assert_eq!(cmp_coord(&lpi, &again, axis), Ordering::Equal);
            }
        }
    }
}

/// Points one ulp off a plane: the exact sign is that of the ulp.
#[test]
fn one_ulp_off_an_axis_plane() {
    for offset in [0.0, UTM[2]] {
        let z = offset + 0.1;
        let (a, b, c) = (
            [UTM[0], UTM[1], z],
            [UTM[0] + 3.0, UTM[1], z],
            [UTM[0], UTM[1] + 2.0, z],
        );
        let at = |zz: f64| Point::Explicit([UTM[0] + 0.7, UTM[1] + 0.3, zz]);
        assert_eq!(orient3d_plane(&a, &b, &c, &at(z)), Sign::Zero);
        assert_eq!(orient3d_plane(&a, &b, &c, &at(z.next_up())), Sign::Positive);
        assert_eq!(
            orient3d_plane(&a, &b, &c, &at(z.next_down())),
            Sign::Negative
        );
        // An implicit point whose segment crosses z one ulp above: strictly above the plane.
        let lpi = Point::Lpi {
            p: [UTM[0] + 1.0, UTM[1] + 1.0, z - 1.0],
            q: [UTM[0] + 1.5, UTM[1] + 0.5, z + 1.0],
            a: [UTM[0], UTM[1], z.next_up()],
            b: [UTM[0] + 1.0, UTM[1], z.next_up()],
            c: [UTM[0], UTM[1] + 1.0, z.next_up()],
        };
        assert_plane_side(&a, &b, &c, &lpi, Sign::Positive);
    }
}

/// A tilted plane through UTM-sized coordinates: an LPI on it against a second triangle
/// spanning the same plane (exactly coplanar: integer-valued points) is zero.
#[test]
fn implicit_point_on_another_triangle_of_the_same_plane() {
    // Plane x + 2y + 4z = k through integer points (exactly representable).
    let k = 478_614.0 + 2.0 * 6_772_313.0 + 4.0 * 100.0;
    let on = |x: f64, y: f64| [x, y, (k - x - 2.0 * y) / 4.0];
    let (a, b, c) = (
        on(478_614.0, 6_772_313.0),
        on(478_618.0, 6_772_313.0),
        on(478_614.0, 6_772_317.0),
    );
    let (d, e, f) = (
        on(478_610.0, 6_772_309.0),
        on(478_630.0, 6_772_321.0),
        on(478_602.0, 6_772_333.0),
    );
    for p in [a, b, c, d, e, f] {
        assert_eq!(p[0] + 2.0 * p[1] + 4.0 * p[2], k); // representable exactly
    }
    let lpi = Point::Lpi {
        p: [478_615.3, 6_772_314.1, 0.0],
        q: [478_615.1, 6_772_314.9, 300.0],
        a,
        b,
        c,
    };
    assert_eq!(orient3d_plane(&d, &e, &f, &lpi), Sign::Zero);
    let nudged = [f[0], f[1], f[2].next_up()];
    assert_eq!(
        orient3d_plane(&d, &e, &nudged, &lpi),
        oracle_orient3d(
            &Point::Explicit(d),
            &Point::Explicit(e),
            &Point::Explicit(nudged),
            &lpi
        )
    );
    assert_ne!(orient3d_plane(&d, &e, &nudged, &lpi), Sign::Zero);
}

/// Coplanar segment crossings: the point is on both segments' lines, equal to the LPI of
/// one segment with a plane through the other, and ordered correctly along an axis.
#[test]
fn coplanar_segment_crossings() {
    let mut rng = Rng(7);
    for offset in [[0.0; 3], UTM] {
        for _ in 0..200 {
            // Four points in the plane z = 0.25 x + 0.5 y + c (exact: dyadic coefficients on a grid).
            let pt = |rng: &mut Rng| {
                let (x, y) = (
                    (rng.next() % 1000) as f64 * 0.125,
                    (rng.next() % 1000) as f64 * 0.125,
                );
                [offset[0] + x, offset[1] + y, offset[2] + 0.25 * x + 0.5 * y]
            };
            let [p, q, r, s] = [0; 4].map(|_| pt(&mut rng));
            let e = |x| Point::Explicit(x);
            // Only crossing lines: non-parallel in the (x, y) projection.
            if orient2d(&e(p), &e(q), &e(r), 2) == orient2d(&e(p), &e(q), &e(s), 2) {
                continue;
            }
            if orient2d(&e(r), &e(s), &e(p), 2) == Sign::Zero {
                continue;
            }
            let x = Point::Ssi {
                p,
                q,
                r,
                s,
                axis: 2,
            };
            let pre = |x: &Point| Prepared::new(x.clone());
            for axis in 0..3 {
                assert_eq!(orient2d(&e(p), &e(q), &x, axis), Sign::Zero);
                assert_eq!(orient2d(&e(r), &e(s), &x, axis), Sign::Zero);
                // Exactly zero: the stored enclosures cannot decide, the exact path must.
                let z = orient2d_prepared(&pre(&e(p)), &pre(&e(q)), &pre(&x), axis);
                assert_eq!(z, Sign::Zero);
            }
            // The same point as the crossing of p q with the vertical plane through r s.
            let up = [r[0], r[1], r[2] + 1.0];
            let lpi = Point::Lpi {
                p,
                q,
                a: r,
                b: s,
                c: up,
            };
            assert!(same_point(&x, &lpi), "{x:?}");
            // The same point by two constructions: every coordinate exactly equal, which
            // the stored enclosures cannot decide either.
            assert!(same_point_prepared(&pre(&x), &pre(&lpi)), "{x:?}");
            assert_eq!(oracle_point(&x), oracle_point(&lpi));
            let other = Point::Explicit(pt(&mut rng));
            for axis in 0..3 {
                let want = oracle_point(&x)[axis].cmp(&oracle_point(&other)[axis]);
                assert_eq!(cmp_coord(&x, &other, axis), want);
                assert_eq!(cmp_coord_prepared(&pre(&x), &pre(&other), axis), want);
                assert_eq!(
                    cmp_coord_prepared(&pre(&other), &pre(&x), axis),
                    want.reverse()
                );
            }
        }
    }
}

#[test]
fn approx_is_close_to_exact() {
    let mut rng = Rng(99);
    for _ in 0..200 {
        let lpi = random_lpi(&mut rng, UTM, 10.0);
        let exact = oracle_point(&lpi);
        let approx = lpi.approx();
        for k in 0..3 {
            let err = (&exact[k] - q(approx[k])).abs();
            // Within 1e-6 m at UTM magnitude for well-conditioned random crossings.
            assert!(
                err < Q::new(BigInt::from(1), BigInt::from(1_000_000)),
                "{k}: {err}"
            );
        }
    }
}

#[test]
fn extreme_magnitudes_fall_back_to_exact() {
    // Products overflow f64: intervals become unbounded, the exact path decides.
    let big = 1e200;
    let (a, b, c) = ([0.0, 0.0, 0.0], [big, 0.0, 0.0], [0.0, big, 0.0]);
    let lpi = Point::Lpi {
        p: [1.0, 1.0, -big],
        q: [1.0, 1.0, big],
        a,
        b,
        c,
    };
    assert_eq!(orient3d_plane(&a, &b, &c, &lpi), Sign::Zero);
    let above = Point::Explicit([1.0, 1.0, 1e-300]);
    assert_eq!(
        orient3d(
            &Point::Explicit(a),
            &Point::Explicit(b),
            &Point::Explicit(c),
            &above
        ),
        Sign::Positive
    );
    assert_eq!(cmp_coord(&lpi, &above, 2), Ordering::Less);
    // Shewchuk's predicate alone gets this wrong (its error bound overflows).
    let on_line = [2e200, 2e200, 2e200];
    assert!(crate::measure::is_degenerate([0.0; 3], [1e200; 3], on_line));
    assert!(!crate::measure::is_degenerate(
        [0.0; 3],
        [1e200; 3],
        [on_line[0], on_line[1], on_line[2].next_up()]
    ));
    assert!(!crate::measure::is_degenerate(
        [0.0; 3],
        [1e-300, 0.0, 0.0],
        [0.0, 1e-300, 0.0]
    ));
}

#[test]
fn float_plane_filter_never_contradicts_the_exact_sign() {
    let mut rng = Rng(0x1234_5678_9abc_def1);
    let e = |p: &[f64; 3]| Point::Explicit(*p);
    let (mut answered, mut asked) = (0, 0);
    for offset in [[0.0; 3], UTM] {
        for scale in [1e-3, 1.0, 1e3] {
            for _ in 0..200 {
                let t = [0, 1, 2].map(|_| rng.point(offset, scale));
                let plane = FloatPlane::new(&t);
                // A random point, one rounded onto the plane (a + s·u + t·v in floats)
                // and the latter moved one ulp in each direction.
                let (s, r) = (rng.unit(), rng.unit());
                let on: [f64; 3] = std::array::from_fn(|k| {
                    t[0][k] + s * (t[1][k] - t[0][k]) + r * (t[2][k] - t[0][k])
                });
                let mut qs = vec![rng.point(offset, scale), on];
                for k in 0..3 {
                    let (mut up, mut down) = (on, on);
                    up[k] = up[k].next_up();
                    down[k] = down[k].next_down();
                    qs.extend([up, down]);
                }
                for q in &qs {
                    let want = oracle_orient3d(&e(&t[0]), &e(&t[1]), &e(&t[2]), &e(q));
                    asked += 1;
                    if let Some(got) = plane.side(q) {
                        answered += 1;
                        assert_eq!(got, want, "filter: {t:?} {q:?}");
                    }
                    assert_eq!(plane.side_exact(&t, q), want, "{t:?} {q:?}");
                }
            }
        }
    }
    // Random points are clear-cut: the filter must answer them (1 of every 8 asked).
    assert!(answered * 8 >= asked, "{answered} of {asked}");
    // Exactly on an axis plane: never answered, always zero.
    let t = [[0.0, 0.0, 5.0], [1.0, 0.0, 5.0], [0.0, 1.0, 5.0]];
    assert_eq!(FloatPlane::new(&t).side(&[0.3, 0.7, 5.0]), None);
    assert_eq!(
        FloatPlane::new(&t).side_exact(&t, &[0.3, 0.7, 5.0]),
        Sign::Zero
    );
    // Magnitudes where the bound underflows or overflows: left to the exact test.
    let tiny = t.map(|p| p.map(|x| x * 1e-200));
    assert_eq!(FloatPlane::new(&tiny).side(&[0.0, 0.0, 1e-190]), None);
    let huge = t.map(|p| p.map(|x| x * 1e200));
    assert_eq!(FloatPlane::new(&huge).side(&[0.0, 0.0, 1e210]), None);
    assert_eq!(
        FloatPlane::new(&huge).side_exact(&huge, &[0.0, 0.0, 1e210]),
        Sign::Positive
    );
}

/// The integer path of `orient3d_explicit` on grid points (short binary fractions, also
/// offset to UTM-sized dyadic coordinates): decided exactly, exact zeros included (points
/// built on the plane of the first three), and refused where the coordinates do not fit.
#[test]
fn fixed_point_orient3d_agrees_with_rationals() {
    let mut rng = Rng(0x5eed);
    for (offset, step) in [(0.0, 1.0 / 16.0), (524_288.0, 1.0 / 64.0), (-3.0, 0.25)] {
        let grid = |rng: &mut Rng| -> [f64; 3] {
            std::array::from_fn(|_| offset + step * ((rng.next() % 2001) as f64 - 1000.0))
        };
        let (mut zeros, mut decided) = (0, 0);
        for i in 0..2000 {
            let (a, b, c) = (grid(&mut rng), grid(&mut rng), grid(&mut rng));
            let d = if i % 2 == 0 {
                // On the plane of a b c: a + s (b − a) + t (c − a), s and t small integers.
                let (s, t) = ((rng.next() % 7) as f64 - 3.0, (rng.next() % 7) as f64 - 3.0);
                std::array::from_fn(|k| a[k] + s * (b[k] - a[k]) + t * (c[k] - a[k]))
            } else {
                grid(&mut rng)
            };
            let e = |p: [f64; 3]| Point::Explicit(p);
            let want = oracle_orient3d(&e(a), &e(b), &e(c), &e(d));
            let got = orient3d_fixed(&a, &b, &c, &d).expect("grid coordinates fit");
            assert_eq!(got, want, "{a:?} {b:?} {c:?} {d:?}");
            assert_eq!(orient3d_explicit(&a, &b, &c, &d), want);
            if let Some(s) = PlaneFilter::new(&a, &b, &c).side(&d) {
                assert_eq!(s, want);
                decided += 1;
            }
            zeros += usize::from(want == Sign::Zero);
        }
        assert!(zeros >= 1000, "{zeros}");
        assert!(decided > 0 && decided <= 2000 - zeros);
    }
    // Full-precision coordinates do not fit: left to the expansion arithmetic.
    let p = |x: f64| [x, 2.0 * x, 0.1];
    assert_eq!(
        orient3d_fixed(&p(0.1), &p(0.3), &p(0.7), &[1.0, 1.0, 1.0]),
        None
    );
    // Spans wider than 2^41 between differences: refused, not wrong.
    let far = [2f64.powi(45), 0.0, 0.0];
    let unit = [1.0 / 1024.0, 0.0, 0.0];
    assert_eq!(
        orient3d_fixed(&[0.0; 3], &far, &unit, &[0.0, 1.0, 0.0]),
        None
    );
    assert_eq!(
        orient3d_fixed(&[0.0; 3], &[0.0; 3], &[0.0; 3], &[0.0; 3]),
        Some(Sign::Zero)
    );
}

/// Three corners against one plane at once: the same exact signs as one at a time, on
/// grid points (integer path, exact zeros), random UTM points (Shewchuk), coordinates out
/// of Shewchuk's range (interval/exact path), and mixtures.
#[test]
fn sides_of_three_points_agree_with_single_tests() {
    let mut rng = Rng(0xface);
    let grid = |rng: &mut Rng, offset: f64| -> [f64; 3] {
        std::array::from_fn(|_| offset + ((rng.next() % 33) as f64 - 16.0) / 8.0)
    };
    let mut zeros = 0;
    for i in 0..4000 {
        let (t, ds): ([[f64; 3]; 3], [[f64; 3]; 3]) = match i % 5 {
            0 => (
                std::array::from_fn(|_| grid(&mut rng, 0.0)),
                std::array::from_fn(|_| grid(&mut rng, 0.0)),
            ),
            1 => {
                // Coplanar corners: on the plane z = x / 2 - y / 4 + offset.
                let on = |rng: &mut Rng| {
                    let [x, y, _] = grid(rng, 1024.0);
                    [x, y, x / 2.0 - y / 4.0 + 3.0]
                };
                (
                    std::array::from_fn(|_| on(&mut rng)),
                    std::array::from_fn(|_| on(&mut rng)),
                )
            }
            2 => (
                std::array::from_fn(|_| rng.point(UTM, 10.0)),
                std::array::from_fn(|_| rng.point(UTM, 10.0)),
            ),
            3 => {
                // A face in an axis plane (UTM-sized coordinates), the points in it or an
                // eighth above or below it (on the shortcuts for all in one axis plane
                // and for a triangle in one).
                let k = (rng.next() % 3) as usize;
                let at = |rng: &mut Rng, off: f64| {
                    let mut p = grid(rng, UTM[k]);
                    p[k] = UTM[k] + off;
                    p
                };
                let some_off = rng.next() % 2 == 0;
                let t = std::array::from_fn(|_| at(&mut rng, 0.0));
                let ds = std::array::from_fn(|j| {
                    let off = match (some_off, j) {
                        (true, 1) => 0.125,
                        (true, 2) => -0.125,
                        _ => 0.0,
                    };
                    at(&mut rng, off)
                });
                (t, ds)
            }
            _ => (
                std::array::from_fn(|_| rng.point([0.0; 3], 1e-210)),
                std::array::from_fn(|k| {
                    if k == 0 {
                        [0.0; 3]
                    } else {
                        rng.point([0.0; 3], 1e-210)
                    }
                }),
            ),
        };
        let want = ds.map(|d| orient3d_explicit(&t[0], &t[1], &t[2], &d));
        let e = |p: [f64; 3]| Point::Explicit(p);
        for k in 0..3 {
            assert_eq!(
                want[k],
                oracle_orient3d(&e(t[0]), &e(t[1]), &e(t[2]), &e(ds[k]))
            );
        }
        assert_eq!(orient3d_sides(&t, &ds), want, "{t:?} {ds:?}");
        zeros += want.iter().filter(|s| **s == Sign::Zero).count();
    }
    assert!(zeros > 3500, "{zeros}");
}

/// Seam points of a fine mesh crossing one huge triangle: close edge-plane points whose
/// homogeneous coordinates carry the huge plane's scale. The prepared predicates (which
/// first look at enclosures of the coordinates themselves) agree with the oracle.
#[test]
fn close_points_on_a_huge_plane_agree_with_the_oracle() {
    let mut rng = Rng(0xfeed_5eed);
    for offset in [[0.0; 3], UTM] {
        let big = [
            rng.point(offset, 4000.0),
            rng.point(offset, 4000.0),
            rng.point(offset, 4000.0),
        ];
        let n = {
            let (u, v) = (
                std::array::from_fn::<f64, 3, _>(|k| big[1][k] - big[0][k]),
                std::array::from_fn::<f64, 3, _>(|k| big[2][k] - big[0][k]),
            );
            [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ]
        };
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let centre: [f64; 3] = std::array::from_fn(|k| (big[0][k] + big[1][k] + big[2][k]) / 3.0);
        let mut pts = Vec::new();
        while pts.len() < 40 {
            // Short segments straddling the plane near its centre.
            let c = rng.point(centre, 0.01);
            let d: [f64; 3] =
                std::array::from_fn(|k| 1e-3 * n[k] / len + 1e-4 * (rng.unit() - 0.5));
            let (p, q) = (
                std::array::from_fn(|k| c[k] + d[k]),
                std::array::from_fn(|k| c[k] - d[k]),
            );
            let (sp, sq) = (
                orient3d_explicit(&big[0], &big[1], &big[2], &p),
                orient3d_explicit(&big[0], &big[1], &big[2], &q),
            );
            if sp != Sign::Zero && sq == sp.reversed() {
                pts.push(Point::Lpi {
                    p,
                    q,
                    a: big[0],
                    b: big[1],
                    c: big[2],
                });
            }
        }
        let prepared: Vec<Prepared> = pts.iter().cloned().map(Prepared::new).collect();
        for i in 0..pts.len() - 2 {
            let (a, b, c) = (i, i + 1, i + 2);
            for axis in 0..3 {
                assert_eq!(
                    orient2d_prepared(&prepared[a], &prepared[b], &prepared[c], axis),
                    oracle_orient2d(&pts[a], &pts[b], &pts[c], axis)
                );
                let want = oracle_point(&pts[a])[axis].cmp(&oracle_point(&pts[b])[axis]);
                assert_eq!(cmp_coord_prepared(&prepared[a], &prepared[b], axis), want);
            }
            assert!(!same_point_prepared(&prepared[a], &prepared[b]));
        }
    }
}

/// The signs of the components of `n_t × n_u` and of `n_t · n_u` (the planes' line and
/// whether two triangles face alike) against rationals: random triangles, nearly parallel
/// ones (a copy with one corner moved an ulp or a little more), exactly parallel and
/// exactly perpendicular ones on a grid (exact zeros), at unit size, UTM-like offsets and
/// extreme scales (where the floating-point filters must stand aside).
#[test]
fn normal_predicates_agree_with_rationals() {
    let mut rng = Rng(0x0a11_6e55_1234_4321);
    let normal = |t: &[[f64; 3]; 3]| {
        let [a, b, c] = t.map(|p| qv(&p));
        crs(&sub(&b, &a), &sub(&c, &a))
    };
    let check = |t: &[[f64; 3]; 3], u: &[[f64; 3]; 3]| -> usize {
        let (n, m) = (normal(t), normal(u));
        let d = crs(&n, &m);
        for (k, dk) in d.iter().enumerate() {
            assert_eq!(normals_cross_sign(t, u, k), sign_q(dk), "{t:?} {u:?} {k}");
        }
        assert_eq!(normals_dot_sign(t, u), sign_q(&dt(&n, &m)), "{t:?} {u:?}");
        d.iter().filter(|x| x.is_zero()).count()
    };
    let mut zeros = 0;
    for offset in [[0.0; 3], UTM] {
        for scale in [1e-3, 1.0, 1e3, 1e-150, 1e150] {
            for _ in 0..300 {
                let t = [0, 1, 2].map(|_| rng.point(offset, scale));
                let u = [0, 1, 2].map(|_| rng.point(offset, scale));
                check(&t, &u);
                // Nearly parallel: one corner moved by an ulp, or by a relative 1e-13.
                let mut v = t;
                let k = (rng.next() % 3) as usize;
                v[k][0] = v[k][0].next_up();
                check(&t, &v);
                v[k][1] *= 1.0 + 1e-13;
                check(&t, &v);
            }
        }
    }
    // Grid triangles: parallel and perpendicular planes are common, and exact.
    for _ in 0..3000 {
        let mut grid = || std::array::from_fn(|_| (rng.next() % 3) as f64);
        let (t, u): ([[f64; 3]; 3], [[f64; 3]; 3]) = (
            std::array::from_fn(|_| grid()),
            std::array::from_fn(|_| grid()),
        );
        zeros += check(&t, &u);
    }
    assert!(zeros > 1000, "{zeros}");
}

/// The bounded `f64` stage never gives a sign the exact evaluation contradicts, on the
/// predicates' polynomials of explicit and implicit points near and on degeneracies: grid
/// points (exact zeros), grid points one ulp off, implicit points on (and one ulp beside)
/// the planes that made them; at unit size, UTM-shifted, scaled to 2^±60 and to 1e±150
/// (products there underflow or overflow: no answer). And it decides many of them.
#[test]
fn bounded_filter_never_contradicts_the_exact_sign() {
    let mut rng = Rng(0x0b0d_ed5e_ed11);
    let (mut asked, mut decided) = (0usize, 0usize);
    let mut check = |bounded: Option<Sign>, exact: Option<Sign>, what: &dyn Fn() -> String| {
        let exact = exact.expect("exact signs are always decided");
        asked += 1;
        if let Some(s) = bounded {
            decided += 1;
            assert_eq!(s, exact, "{}", what());
        }
    };
    for round in 0..6000 {
        let (offset, scale) = match round % 6 {
            0 => (0.0, 1.0),
            1 => (UTM[0], 1.0),
            2 => (0.0, 2f64.powi(-60)),
            3 => (0.0, 2f64.powi(60)),
            4 => (0.0, 1e-150),
            _ => (0.0, 1e150),
        };
        let mut grid = || -> [f64; 3] {
            std::array::from_fn(|_| {
                let x = offset + scale * (rng.next() % 5) as f64;
                match rng.next() % 4 {
                    0 => x.next_up(),
                    1 => x.next_down(),
                    _ => x,
                }
            })
        };
        let [a, b, c, p, q, r, s] = [(); 7].map(|_| grid());
        let mut points = vec![Point::Explicit(p), Point::Explicit(q)];
        if orient3d_explicit(&a, &b, &c, &p) == orient3d_explicit(&a, &b, &c, &q).reversed()
            && orient3d_explicit(&a, &b, &c, &p) != Sign::Zero
        {
            points.push(Point::Lpi { p, q, a, b, c });
        }
        for axis in 0..3 {
            if cross_sign(&p, &q, &r, &s, axis) != Sign::Zero {
                points.push(Point::Ssi {
                    p,
                    q,
                    r,
                    s,
                    axis: axis as u8,
                });
                break;
            }
        }
        for x in &points {
            let what = || format!("{a:?} {b:?} {c:?} {x:?}");
            check(
                plane_side::<Bounded>(&a, &b, &c, x).sign(),
                plane_side::<Dyadic>(&a, &b, &c, x).sign(),
                &what,
            );
            check(w_of::<Bounded>(x).sign(), w_of::<Dyadic>(x).sign(), &what);
            for y in &points {
                for axis in 0..3 {
                    check(
                        coord_diff::<Bounded>(x, y, axis).sign(),
                        coord_diff::<Dyadic>(x, y, axis).sign(),
                        &what,
                    );
                    let z = &points[0];
                    check(
                        orient2d_rows::<Bounded>(x, y, z, axis).sign(),
                        orient2d_rows::<Dyadic>(x, y, z, axis).sign(),
                        &what,
                    );
                }
            }
        }
    }
    // Most of these are exact zeros (repeated points, grid-aligned planes): no filter
    // decides those.
    assert!(asked > 200_000 && decided > 50_000, "{asked} {decided}");
}

/// Exact dyadic arithmetic gives the rational value's sign, and exact zeros, on random
/// sums and products of short and full-length binary fractions of many magnitudes, on
/// both sides of the move from `i128` mantissas to big integers (both are reached often).
#[test]
fn dyadic_arithmetic_agrees_with_rationals_across_the_small_mantissa_limit() {
    let mut rng = Rng(0x00d1_ad1c_0b16);
    let (mut small, mut big) = (0, 0);
    for _ in 0..20_000 {
        let mut value = || -> f64 {
            let x = match rng.next() % 4 {
                0 => (rng.next() % 9) as f64 - 4.0,
                1 => ((rng.next() % 64) as f64 - 32.0) / 8.0,
                2 => rng.unit() - 0.5,
                _ => (rng.unit() - 0.5) * 2f64.powi((rng.next() % 120) as i32 - 60),
            };
            if rng.next() % 3 == 0 {
                x + UTM[0]
            } else {
                x
            }
        };
        let v: Vec<f64> = (0..8).map(|_| value()).collect();
        // ((v0·v1 − v2·v3) · (v4 + v5) − v6) · v7, and the same regrouped: equal exactly.
        let d = |x: f64| Dyadic::from_f64(x);
        let dy = d(v[0])
            .mul(&d(v[1]))
            .sub(&d(v[2]).mul(&d(v[3])))
            .mul(&d(v[4]).add(&d(v[5])))
            .sub(&d(v[6]))
            .mul(&d(v[7]));
        let again = d(v[7])
            .mul(&d(v[4]).add(&d(v[5])))
            .mul(&d(v[1]).mul(&d(v[0])))
            .sub(
                &d(v[7])
                    .mul(&d(v[5]).add(&d(v[4])))
                    .mul(&d(v[3]).mul(&d(v[2]))),
            )
            .sub(&d(v[6]).mul(&d(v[7])));
        let r = (q(v[0]) * q(v[1]) - q(v[2]) * q(v[3])) * (q(v[4]) + q(v[5])) - q(v[6]);
        let r = r * q(v[7]);
        assert_eq!(dy.sign(), Some(sign_q(&r)), "{v:?}");
        assert_eq!(dy.sub(&again).sign(), Some(Sign::Zero), "{v:?}");
        if dy.is_small() {
            small += 1;
        } else {
            big += 1;
        }
    }
    assert!(small > 1000 && big > 3000, "{small} {big}");
}

/// Seam points of boxes and grids (segments constant in a coordinate, planes square to an
/// axis, coordinates on a grid of quarters; at unit size, UTM-shifted and scaled by
/// 2^-30) and of random data: where the constructors give an explicit point it is the
/// implicit point exactly (rational coordinates), and on the grids many are explicit.
#[test]
fn seam_points_with_exact_coordinates_are_made_explicit() {
    let mut rng = Rng(0xe4ac7);
    let mut explicit = [0usize; 2];
    let grid = |rng: &mut Rng, offset: [f64; 3], scale: f64| -> [f64; 3] {
        std::array::from_fn(|k| offset[k] + scale * ((rng.next() % 17) as f64 - 8.0) / 4.0)
    };
    for (offset, scale) in [([0.0; 3], 1.0), (UTM, 1.0), ([0.0; 3], 2f64.powi(-30))] {
        let mut lpis = 0;
        while lpis < 400 {
            let [p, mut q, mut a, mut b, mut c] = [0; 5].map(|_| grid(&mut rng, offset, scale));
            // A plane square to an axis, and a segment constant in one or two coordinates.
            let (k, m) = ((rng.next() % 3) as usize, (rng.next() % 3) as usize);
            if rng.next() % 2 == 0 {
                (b[k], c[k]) = (a[k], a[k]);
            }
            match rng.next() % 3 {
                0 => q[m] = p[m],
                1 => (q[m], q[(m + 1) % 3]) = (p[m], p[(m + 1) % 3]),
                _ => {}
            }
            if rng.next() % 4 == 0 {
                a = rng.point(offset, scale);
            }
            let (sp, sq) = (
                orient3d_explicit(&a, &b, &c, &p),
                orient3d_explicit(&a, &b, &c, &q),
            );
            if sp == Sign::Zero || sq != sp.reversed() {
                continue;
            }
            lpis += 1;
            let implicit = Point::Lpi { p, q, a, b, c };
            if let Point::Explicit(x) = Point::lpi(p, q, a, b, c) {
                assert_eq!(qv(&x), oracle_point(&implicit), "{implicit:?}");
                explicit[0] += 1;
            }
        }
        let mut ssis = 0;
        while ssis < 400 {
            // Four points of one plane: square to an axis, or spanned by grid vectors.
            let k = (rng.next() % 3) as usize;
            let [p, q, r, s] = if rng.next() % 2 == 0 {
                let level = grid(&mut rng, offset, scale)[k];
                [0; 4].map(|_| {
                    let mut x = grid(&mut rng, offset, scale);
                    x[k] = level;
                    x
                })
            } else {
                let (o, u, v) = (
                    grid(&mut rng, offset, scale),
                    grid(&mut rng, [0.0; 3], scale),
                    grid(&mut rng, [0.0; 3], scale),
                );
                [0; 4].map(|_| {
                    let (i, j) = ((rng.next() % 3) as f64, (rng.next() % 3) as f64);
                    std::array::from_fn(|x| o[x] + i * u[x] + j * v[x])
                })
            };
            let Some(axis) = (0..3).find(|&ax| cross_sign(&p, &q, &r, &s, ax) != Sign::Zero) else {
                continue;
            };
            if orient3d_explicit(&p, &q, &r, &s) != Sign::Zero {
                continue; // the spanned points rounded off their plane
            }
            ssis += 1;
            let implicit = Point::Ssi {
                p,
                q,
                r,
                s,
                axis: axis as u8,
            };
            if let Point::Explicit(x) = Point::ssi(p, q, r, s, axis as u8) {
                assert_eq!(qv(&x), oracle_point(&implicit), "{implicit:?}");
                explicit[1] += 1;
            }
        }
    }
    assert!(explicit[0] > 100 && explicit[1] > 100, "{explicit:?}");
    // Random data: the same, wherever a step happens to be exact.
    for _ in 0..2000 {
        let implicit = random_lpi(&mut rng, [0.0; 3], 1.0);
        let Point::Lpi { p, q, a, b, c } = implicit.clone() else {
            unreachable!()
        };
        if let Point::Explicit(x) = Point::lpi(p, q, a, b, c) {
            assert_eq!(qv(&x), oracle_point(&implicit));
        }
    }
}

/// The exact steps of [`on_segment_exact`] answer exactly when the rounded result is the
/// exact one (rationals), for operands from grids, UTM coordinates and random doubles of
/// many sizes.
#[test]
fn exact_steps_are_taken_only_when_exact() {
    let mut rng = Rng(0x57e9);
    let value = |rng: &mut Rng| -> f64 {
        match rng.next() % 4 {
            0 => ((rng.next() % 33) as f64 - 16.0) / 8.0,
            1 => UTM[(rng.next() % 3) as usize] + ((rng.next() % 9) as f64 - 4.0) / 4.0,
            2 => (rng.unit() - 0.5) * 2f64.powi((rng.next() % 60) as i32 - 30),
            _ => 3.0 * ((rng.next() % 11) as f64 - 5.0),
        }
    };
    let mut taken = [0usize; 3];
    for _ in 0..20_000 {
        let (a, b) = (value(&mut rng), value(&mut rng));
        let want = q(a) - q(b);
        assert_eq!(sub_exact(a, b).is_some(), q(a - b) == want, "{a} - {b}");
        taken[0] += usize::from(sub_exact(a, b).is_some());
        let want = q(a) * q(b);
        assert_eq!(mul_exact(a, b).is_some(), q(a * b) == want, "{a} * {b}");
        taken[1] += usize::from(mul_exact(a, b).is_some());
        if b != 0.0 {
            let want = q(a) / q(b);
            assert_eq!(div_exact(a, b).is_some(), q(a / b) == want, "{a} / {b}");
            taken[2] += usize::from(div_exact(a, b).is_some());
        }
    }
    assert!(taken.iter().all(|&t| t > 2000 && t < 19_000), "{taken:?}");
}

/// Orientations of input points on a small grid (many on lines square to an axis, where
/// `orient2d_safe` answers zero before Shewchuk's predicate), UTM-shifted too: the
/// rational orientation in every projection.
#[test]
fn grid_orientations_agree_with_rationals() {
    let mut rng = Rng(0x0219);
    let mut zeros = 0;
    for offset in [[0.0; 3], UTM] {
        for _ in 0..3000 {
            let [a, b, c] = [0; 3].map(|_| -> [f64; 3] {
                std::array::from_fn(|k| offset[k] + (rng.next() % 3) as f64 * 0.5)
            });
            for axis in 0..3 {
                let (pa, pb, pc) = (Point::Explicit(a), Point::Explicit(b), Point::Explicit(c));
                let want = oracle_orient2d(&pa, &pb, &pc, axis);
                assert_eq!(
                    orient2d_safe(&a, &b, &c, axis),
                    want,
                    "{a:?} {b:?} {c:?} {axis}"
                );
                zeros += usize::from(want == Sign::Zero);
            }
        }
    }
    assert!(zeros > 2000 && zeros < 17_000, "{zeros}");
}

/// The safe range is what it names: zero (either sign) and magnitudes in
/// `[2^-200, 2^200]`, at and beside both ends (its constants are decimal literals); not
/// NaN, the infinities or subnormals.
#[test]
fn the_safe_range_is_zero_and_two_to_the_minus_200_to_200() {
    use super::in_safe_range;
    let (lo, hi) = (2f64.powi(-200), 2f64.powi(200));
    let below = |x: f64| f64::from_bits(x.to_bits() - 1);
    let above = |x: f64| f64::from_bits(x.to_bits() + 1);
    for (x, want) in [
        (0.0, true),
        (-0.0, true),
        (lo, true),
        (-lo, true),
        (hi, true),
        (-hi, true),
        (below(lo), false),
        (-below(lo), false),
        (above(hi), false),
        (-above(hi), false),
        (above(lo), true),
        (below(hi), true),
        (1.0, true),
        (f64::MIN_POSITIVE / 2.0, false),
        (f64::NAN, false),
        (-f64::NAN, false),
        (f64::INFINITY, false),
        (f64::NEG_INFINITY, false),
        (f64::MAX, false),
    ] {
        assert_eq!(in_safe_range(x), want, "{x:e}");
    }
}

/// The Delaunay flips' in-circle test: the sign of the exact test wherever it answers,
/// zero for four points on one circle (the corners of squares and rectangles, at any
/// offset), and zero only within the error bound of `f64` (points near a circle).
#[test]
fn the_flips_in_circle_test_has_the_exact_sign_or_none() {
    let c = |x: f64, y: f64| [x, y];
    let r = |p: [f64; 2]| robust::Coord { x: p[0], y: p[1] };
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let mut next = || rng.unit();
    let (mut signed, mut zero) = (0, 0);
    for k in 0..20_000 {
        // Random points, points on a lattice (many on one circle), near-cocircular.
        let p: [[f64; 2]; 4] = match k % 3 {
            0 => std::array::from_fn(|_| c(next() * 10.0 - 5.0, next() * 10.0 - 5.0)),
            1 => std::array::from_fn(|_| c((next() * 4.0).floor(), (next() * 4.0).floor())),
            _ => {
                let scale = if k % 2 == 0 { 0.0 } else { 1e6 };
                let (r, off) = (1.0 + next(), [scale * next(), scale * next()]);
                std::array::from_fn(|_| {
                    let t = next() * std::f64::consts::TAU;
                    c(off[0] + r * t.cos(), off[1] + r * t.sin())
                })
            }
        };
        let exact = robust::incircle(r(p[0]), r(p[1]), r(p[2]), r(p[3]));
        let got = incircle_clear(p[0], p[1], p[2], p[3]);
        if got == 0.0 {
            zero += 1;
        } else {
            signed += 1;
            assert_eq!(got > 0.0, exact > 0.0, "{p:?}");
            assert!(exact != 0.0, "{p:?}");
        }
    }
    assert!(signed > 10_000 && zero > 1_000, "{signed} {zero}");
    // Squares' and rectangles' corners, anywhere: on one circle.
    for off in [[0.0, 0.0], [0.5, -3.25], [512_345.5, 7_001_234.25]] {
        let q = |x: f64, y: f64| c(off[0] + x, off[1] + y);
        for (w, h) in [(1.0, 1.0), (2.0, 0.5), (0.125, 3.0)] {
            let r = incircle_clear(q(0.0, 0.0), q(w, 0.0), q(w, h), q(0.0, h));
            assert_eq!(r, 0.0);
            assert!(incircle_clear(q(0.0, 0.0), q(w, 0.0), q(w, h), q(w / 2.0, h / 2.0)) > 0.0);
        }
    }
}

/// The flips' canonical in-circle choice: for every order of four points, the same
/// answer up to the order's sign (so the two diagonals of a quad never both ask for a
/// flip, and the flips end where they would for any insertion order); the clear test's
/// sign where it has one; on one circle, the sign of the determinant with the lexicographically
/// first point's lift raised a little (a lifting, so the triangulation is a regular one).
#[test]
fn the_flips_canonical_choice_is_one_for_every_order() {
    let c = |x: f64, y: f64| [x, y];
    let r = |p: [f64; 2]| robust::Coord { x: p[0], y: p[1] };
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut next = || rng.unit();
    let perms: Vec<([usize; 4], bool)> = (0..24)
        .map(|mut n| {
            let mut rest = vec![0, 1, 2, 3];
            let mut p = [0; 4];
            for (i, slot) in p.iter_mut().enumerate() {
                *slot = rest.remove(n % (4 - i));
                n /= 4 - i;
            }
            let odd = (0..4)
                .flat_map(|i| (i + 1..4).map(move |j| (i, j)))
                .filter(|&(i, j)| p[i] > p[j])
                .count()
                % 2
                == 1;
            (p, odd)
        })
        .collect();
    let (mut tied, mut clear) = (0, 0);
    for k in 0..6_000 {
        let p: [[f64; 2]; 4] = match k % 2 {
            0 => std::array::from_fn(|_| c(next() * 10.0 - 5.0, next() * 10.0 - 5.0)),
            _ => std::array::from_fn(|_| c((next() * 4.0).floor(), (next() * 4.0).floor())),
        };
        let distinct = (0..4).all(|i| (i + 1..4).all(|j| (p[i][0], p[i][1]) != (p[j][0], p[j][1])));
        if !distinct {
            continue;
        }
        let base = incircle_canonical(p);
        for (perm, odd) in &perms {
            let got = incircle_canonical(perm.map(|i| p[i]));
            let want = if *odd { -base } else { base };
            assert_eq!(
                got.partial_cmp(&0.0),
                want.partial_cmp(&0.0),
                "{p:?} {perm:?}"
            );
        }
        let collinear = robust::orient2d(r(p[0]), r(p[1]), r(p[2])) == 0.0
            && robust::orient2d(r(p[0]), r(p[1]), r(p[3])) == 0.0;
        assert_eq!(base == 0.0, collinear, "{p:?}");
        if incircle_clear(p[0], p[1], p[2], p[3]) != 0.0 {
            clear += 1;
            assert_eq!(
                base > 0.0,
                robust::incircle(r(p[0]), r(p[1]), r(p[2]), r(p[3])) > 0.0
            );
        } else if robust::incircle(r(p[0]), r(p[1]), r(p[2]), r(p[3])) == 0.0 && !collinear {
            tied += 1;
            // The lexicographically first point's lift raised by a small step (exact
            // here: small integers), the others' by far less.
            let mut order = [0usize, 1, 2, 3];
            order.sort_by(|&i, &j| (p[i][0], p[i][1]).partial_cmp(&(p[j][0], p[j][1])).unwrap());
            let mut lift = [0.0f64; 4];
            for (r, &i) in order.iter().enumerate() {
                lift[i] = p[i][0] * p[i][0]
                    + p[i][1] * p[i][1]
                    + [1.0 / 64.0, 1.0 / 4096.0, 1.0 / 262_144.0, 0.0][r];
            }
            let d = 3;
            let row = |i: usize| [p[i][0] - p[d][0], p[i][1] - p[d][1], lift[i] - lift[d]];
            let (r0, r1, r2) = (row(0), row(1), row(2));
            let det = r0[0] * (r1[1] * r2[2] - r1[2] * r2[1])
                - r0[1] * (r1[0] * r2[2] - r1[2] * r2[0])
                + r0[2] * (r1[0] * r2[1] - r1[1] * r2[0]);
            assert!(
                det != 0.0 && (det > 0.0) == (base > 0.0),
                "{p:?}: {det} {base}"
            );
        }
    }
    assert!(tied > 100 && clear > 2_000, "{tied} {clear}");
}
