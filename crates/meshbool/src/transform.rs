//! Affine transforms: [`Transform`] (translations, rotations by degrees, scalings, any
//! affine matrix), composed in the order they are applied, and [`Mesh::transformed`].
//!
//! Matrices act on column vectors and are written **row-major**: a point `p` maps to
//! `M p`, the 16 numbers are the four rows one after another, the translation is the last
//! column (numbers 4, 8 and 12, counting from 1) and the last row is `0 0 0 1`.
//!
//! ```
//! use meshbool::{Mesh, Transform};
//!
//! // Scale by 2, then turn a quarter about z, then move: applied in this order.
//! let t = Transform::scaling(2.0).rotate_z(90.0).translate([10.0, 0.0, 0.0]);
//! assert_eq!(t.apply([1.0, 0.0, 0.0]), [10.0, 2.0, 0.0]);
//! let moved = Mesh::unit_cube().transformed(&t);
//! let b = moved.bounds().unwrap();
//! assert_eq!((b.min, b.max), ([8.0, 0.0, 0.0], [10.0, 2.0, 2.0]));
//!
//! // A mirror reverses every triangle: the solid still faces outward.
//! let mirrored = Mesh::unit_cube().transformed(&Transform::scaling_xyz([-1.0, 1.0, 1.0]));
//! assert_eq!(meshbool::measure::signed_volume(&mirrored), 1.0);
//! ```
//!
//! Rotations are by degrees; multiples of 90° are exact (their sines and cosines are
//! exactly 0 and ±1), as are 30°, 60° and their multiples' 0.5 values. Applying a transform
//! rounds each coordinate once per multiplication and addition in `f64`: a translation
//! alone adds exactly where the sum is representable (UTM-sized coordinates included),
//! and a scaling by a power of two is exact.

use std::ops::Mul;

use crate::{Error, Mesh, Result};

/// An affine transform of 3D space in `f64`: a 4×4 matrix whose last row is `0 0 0 1`,
/// acting on column vectors (`p ↦ M p`).
///
/// Build one from the constructors ([`Transform::translation`], [`Transform::rotation_z`],
/// [`Transform::scaling`], [`Transform::from_row_major`], ...) and compose with the
/// builder methods, each applied **after** what is there already:
/// `Transform::scaling(2.0).translate([1.0, 0.0, 0.0])` scales, then moves.
/// [`Transform::then`] composes two transforms in that order; `a * b` is the matrix
/// product (`b` first, then `a`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    /// The first three rows; the fourth is `0 0 0 1`.
    rows: [[f64; 4]; 3],
}

impl Default for Transform {
    fn default() -> Self {
        Transform::IDENTITY
    }
}

/// `sin` and `cos` of an angle in degrees: exact at multiples of 90° (0 and ±1, never
/// `-0.0`) and at ±30°, ±60° from them (±0.5), the other values from `f64::sin_cos` on
/// the angle reduced to `[0°, 45°]` (so that symmetric angles give symmetric values).
/// Non-finite angles give NaN.
pub(crate) fn sin_cos_deg(degrees: f64) -> (f64, f64) {
    // `rem_euclid` is exact (it may give 360 for tiny negative angles: quadrant 4 = 0).
    let r = degrees.rem_euclid(360.0);
    let q = (r / 90.0).floor();
    // Exact (Sterbenz) for q ≥ 1; may be a tiny negative when r / 90 rounded up.
    let rest = r - 90.0 * q;
    let (s, c) = if rest == 0.0 {
        (0.0, 1.0)
    } else if rest == 30.0 {
        (0.5, 0.75f64.sqrt())
    } else if rest == 45.0 {
        (
            std::f64::consts::FRAC_1_SQRT_2,
            std::f64::consts::FRAC_1_SQRT_2,
        )
    } else if rest == 60.0 {
        (0.75f64.sqrt(), 0.5)
    } else if rest > 45.0 {
        // 90 − rest is exact (Sterbenz): sin(90° − a) and cos(90° − a) of the same a.
        let (s, c) = (90.0 - rest).to_radians().sin_cos();
        (c, s)
    } else {
        rest.to_radians().sin_cos()
    };
    // `+ 0.0` turns -0.0 into 0.0. NaN quadrants cast to 0.
    let (s, c) = match (q as u32) % 4 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    };
    (s + 0.0, c + 0.0)
}

impl Transform {
    /// The transform that changes nothing.
    pub const IDENTITY: Transform = Transform {
        rows: [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
        ],
    };

    /// From the linear part (rows) and the translation.
    fn from_parts(l: [[f64; 3]; 3], t: [f64; 3]) -> Transform {
        Transform {
            rows: std::array::from_fn(|i| [l[i][0], l[i][1], l[i][2], t[i]]),
        }
    }

    /// A move by `offset`.
    pub fn translation(offset: [f64; 3]) -> Transform {
        let mut t = Transform::IDENTITY;
        for (i, row) in t.rows.iter_mut().enumerate() {
            row[3] = offset[i];
        }
        t
    }

    /// A uniform scaling by `factor` about the origin (negative: a point reflection).
    pub fn scaling(factor: f64) -> Transform {
        Transform::scaling_xyz([factor; 3])
    }

    /// A scaling about the origin by `factors[k]` along axis `k`; a negative factor
    /// mirrors (`[-1.0, 1.0, 1.0]`: the mirror in the plane x = 0).
    pub fn scaling_xyz(factors: [f64; 3]) -> Transform {
        let mut t = Transform::IDENTITY;
        for (k, row) in t.rows.iter_mut().enumerate() {
            row[k] = factors[k];
        }
        t
    }

    /// A rotation by `degrees` about the x axis (right-handed: y turns toward z).
    pub fn rotation_x(degrees: f64) -> Transform {
        let (s, c) = sin_cos_deg(degrees);
        Transform::from_parts([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]], [0.0; 3])
    }

    /// A rotation by `degrees` about the y axis (right-handed: z turns toward x).
    pub fn rotation_y(degrees: f64) -> Transform {
        let (s, c) = sin_cos_deg(degrees);
        Transform::from_parts([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]], [0.0; 3])
    }

    /// A rotation by `degrees` about the z axis (right-handed: x turns toward y, so 90°
    /// maps `(1, 0, 0)` to `(0, 1, 0)`).
    pub fn rotation_z(degrees: f64) -> Transform {
        let (s, c) = sin_cos_deg(degrees);
        Transform::from_parts([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]], [0.0; 3])
    }

    /// A rotation by `degrees` about the axis through the origin along `axis` (any
    /// non-zero length), right-handed (counter-clockwise seen from the tip of `axis`).
    /// An axis along a coordinate axis gives exactly [`Transform::rotation_x`] (`_y`,
    /// `_z`; the negative axis turns the other way). Errors when `axis` is zero or not
    /// finite.
    pub fn rotation(axis: [f64; 3], degrees: f64) -> Result<Transform> {
        let len = axis.iter().map(|a| a * a).sum::<f64>().sqrt();
        if !(len.is_finite() && len > 0.0) {
            return Err(Error::InvalidParameter(format!(
                "a rotation axis must be finite and not zero, got {axis:?}"
            )));
        }
        let zeros = axis.iter().filter(|&&a| a == 0.0).count();
        if zeros == 2 {
            let k = axis.iter().position(|&a| a != 0.0).unwrap_or(2);
            let d = if axis[k] < 0.0 { -degrees } else { degrees };
            return Ok(match k {
                0 => Transform::rotation_x(d),
                1 => Transform::rotation_y(d),
                _ => Transform::rotation_z(d),
            });
        }
        let [x, y, z] = axis.map(|a| a / len);
        let (s, c) = sin_cos_deg(degrees);
        let v = 1.0 - c;
        Ok(Transform::from_parts(
            [
                [c + x * x * v, x * y * v - z * s, x * z * v + y * s],
                [y * x * v + z * s, c + y * y * v, y * z * v - x * s],
                [z * x * v - y * s, z * y * v + x * s, c + z * z * v],
            ],
            [0.0; 3],
        ))
    }

    /// The transform of 16 numbers in row-major order (four rows of four; the translation
    /// in numbers 4, 8 and 12 counting from 1), acting on column vectors. Errors when a
    /// number is not finite or the last row is not `0 0 0 1` (projective transforms are
    /// not affine).
    pub fn from_row_major(m: [f64; 16]) -> Result<Transform> {
        if let Some(i) = m.iter().position(|v| !v.is_finite()) {
            return Err(Error::InvalidParameter(format!(
                "matrix element {} (row {}, column {}) is not finite: {}",
                i + 1,
                i / 4 + 1,
                i % 4 + 1,
                m[i]
            )));
        }
        if m[12..] != [0.0, 0.0, 0.0, 1.0] {
            return Err(Error::InvalidParameter(format!(
                "the matrix's last row must be 0 0 0 1 (an affine transform; row-major, translation in the last column), got {:?}",
                &m[12..]
            )));
        }
        Ok(Transform {
            rows: std::array::from_fn(|i| std::array::from_fn(|j| m[4 * i + j])),
        })
    }

    /// The 16 numbers of the matrix in row-major order, last row `0 0 0 1` included.
    pub fn to_row_major(&self) -> [f64; 16] {
        std::array::from_fn(|k| {
            let (i, j) = (k / 4, k % 4);
            if i < 3 {
                self.rows[i][j]
            } else if j == 3 {
                1.0
            } else {
                0.0
            }
        })
    }

    /// The matrix as four rows.
    pub fn rows(&self) -> [[f64; 4]; 4] {
        let [a, b, c] = self.rows;
        [a, b, c, [0.0, 0.0, 0.0, 1.0]]
    }

    /// `self`, then `next`: the matrix product `next · self`.
    pub fn then(&self, next: &Transform) -> Transform {
        let (n, s) = (&next.rows, &self.rows);
        Transform {
            rows: std::array::from_fn(|i| {
                std::array::from_fn(|j| {
                    let sum = n[i][0] * s[0][j] + n[i][1] * s[1][j] + n[i][2] * s[2][j];
                    if j == 3 {
                        sum + n[i][3]
                    } else {
                        sum
                    }
                })
            }),
        }
    }

    /// This transform, then a move by `offset`.
    pub fn translate(&self, offset: [f64; 3]) -> Transform {
        self.then(&Transform::translation(offset))
    }

    /// This transform, then a uniform scaling about the origin.
    pub fn scale(&self, factor: f64) -> Transform {
        self.then(&Transform::scaling(factor))
    }

    /// This transform, then a scaling about the origin by `factors` per axis.
    pub fn scale_xyz(&self, factors: [f64; 3]) -> Transform {
        self.then(&Transform::scaling_xyz(factors))
    }

    /// This transform, then a rotation by `degrees` about the x axis.
    pub fn rotate_x(&self, degrees: f64) -> Transform {
        self.then(&Transform::rotation_x(degrees))
    }

    /// This transform, then a rotation by `degrees` about the y axis.
    pub fn rotate_y(&self, degrees: f64) -> Transform {
        self.then(&Transform::rotation_y(degrees))
    }

    /// This transform, then a rotation by `degrees` about the z axis.
    pub fn rotate_z(&self, degrees: f64) -> Transform {
        self.then(&Transform::rotation_z(degrees))
    }

    /// This transform, then a rotation by `degrees` about `axis` through the origin
    /// ([`Transform::rotation`]; errors as it does).
    pub fn rotate(&self, axis: [f64; 3], degrees: f64) -> Result<Transform> {
        Ok(self.then(&Transform::rotation(axis, degrees)?))
    }

    /// The image of the point `p`: `M p`.
    pub fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|i| {
            let r = &self.rows[i];
            r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + r[3]
        })
    }

    /// The image of the direction `v` (the linear part only, no translation).
    pub fn apply_vector(&self, v: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|i| {
            let r = &self.rows[i];
            r[0] * v[0] + r[1] * v[1] + r[2] * v[2]
        })
    }

    /// The determinant of the linear part (the volume factor): negative for a transform
    /// that mirrors, zero for one that flattens.
    pub fn determinant(&self) -> f64 {
        let m = &self.rows;
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    }

    /// Whether the transform mirrors (negative determinant): [`Mesh::transformed`]
    /// then reverses every triangle.
    pub fn reverses_orientation(&self) -> bool {
        self.determinant() < 0.0
    }

    /// Whether every number of the matrix is finite.
    pub fn is_finite(&self) -> bool {
        self.rows.iter().flatten().all(|v| v.is_finite())
    }
}

impl Mul for Transform {
    type Output = Transform;

    /// The matrix product `self · rhs`: `rhs` first, then `self`.
    fn mul(self, rhs: Transform) -> Transform {
        rhs.then(&self)
    }
}

impl Mesh {
    /// The mesh with every vertex mapped by `t` ([`Transform::apply`]); the triangles
    /// keep their vertices. When `t` mirrors (negative [`Transform::determinant`]) every
    /// triangle is reversed, so that a solid facing outward still faces outward (its
    /// signed volume stays positive) and a surface keeps facing the image of the side it
    /// faced. A singular `t` (determinant 0) flattens the mesh into degenerate triangles;
    /// non-finite numbers give non-finite coordinates ([`crate::ops::transform`] refuses
    /// both).
    pub fn transformed(&self, t: &Transform) -> Mesh {
        let positions = self.positions.iter().map(|&p| t.apply(p)).collect();
        let triangles = if t.reverses_orientation() {
            self.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect()
        } else {
            self.triangles.clone()
        };
        Mesh::new_unchecked(positions, triangles)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::{mesh_stats, signed_volume};

    #[test]
    fn quarter_turns_are_exact() {
        let r = Transform::rotation_z(90.0);
        let p = r.apply([1.0, 0.0, 0.0]);
        assert_eq!(p, [0.0, 1.0, 0.0]);
        assert!((p[0] - 0.0).abs() <= 1e-15 && (p[1] - 1.0).abs() <= 1e-15);
        assert_eq!(
            Transform::rotation_x(90.0).apply([0.0, 1.0, 0.0]),
            [0.0, 0.0, 1.0]
        );
        assert_eq!(
            Transform::rotation_y(90.0).apply([0.0, 0.0, 1.0]),
            [1.0, 0.0, 0.0]
        );
        for (deg, s, c) in [
            (0.0, 0.0, 1.0),
            (90.0, 1.0, 0.0),
            (180.0, 0.0, -1.0),
            (270.0, -1.0, 0.0),
            (-90.0, -1.0, 0.0),
            (450.0, 1.0, 0.0),
            (-720.0, 0.0, 1.0),
            (30.0, 0.5, 0.75f64.sqrt()),
            (150.0, 0.5, -(0.75f64.sqrt())),
            (-60.0, -(0.75f64.sqrt()), 0.5),
        ] {
            let (gs, gc) = sin_cos_deg(deg);
            assert_eq!((gs, gc), (s, c), "{deg}");
            assert!(gs.is_sign_positive() || gs != 0.0);
        }
        // Symmetric angles give symmetric values; general angles agree with sin_cos.
        assert_eq!(sin_cos_deg(10.0).0, sin_cos_deg(170.0).0);
        let (s, c) = sin_cos_deg(37.0);
        let (rs, rc) = 37f64.to_radians().sin_cos();
        assert!((s - rs).abs() < 1e-15 && (c - rc).abs() < 1e-15);
        assert!(sin_cos_deg(f64::NAN).0.is_nan());
    }

    #[test]
    fn any_axis_rotation() {
        // About the negative z axis: the other way round.
        let r = Transform::rotation([0.0, 0.0, -3.0], 90.0).unwrap();
        assert_eq!(r, Transform::rotation_z(-90.0));
        // A third of a turn about the diagonal cycles the axes.
        let r = Transform::rotation([1.0, 1.0, 1.0], 120.0).unwrap();
        let p = r.apply([1.0, 0.0, 0.0]);
        for (k, want) in [0.0, 1.0, 0.0].into_iter().enumerate() {
            assert!((p[k] - want).abs() < 1e-15, "{p:?}");
        }
        assert!((r.determinant() - 1.0).abs() < 1e-15);
        assert!(Transform::rotation([0.0; 3], 10.0).is_err());
        assert!(Transform::rotation([f64::NAN, 0.0, 1.0], 10.0).is_err());
    }

    #[test]
    fn composition_applies_in_order() {
        let scale_then_move = Transform::scaling(2.0).translate([1.0, 0.0, 0.0]);
        let move_then_scale = Transform::translation([1.0, 0.0, 0.0]).scale(2.0);
        assert_eq!(scale_then_move.apply([1.0, 1.0, 1.0]), [3.0, 2.0, 2.0]);
        assert_eq!(move_then_scale.apply([1.0, 1.0, 1.0]), [4.0, 2.0, 2.0]);
        // then and * agree.
        let (a, b) = (
            Transform::rotation_z(90.0),
            Transform::translation([5.0, 0.0, 0.0]),
        );
        assert_eq!(a.then(&b), b * a);
        assert_eq!(a.then(&b).apply([1.0, 0.0, 0.0]), [5.0, 1.0, 0.0]);
        assert_eq!(b.then(&a).apply([1.0, 0.0, 0.0]), [0.0, 6.0, 0.0]);
        // Composing equals applying one after the other.
        let p = [0.3, -1.7, 2.5];
        let t = Transform::rotation([1.0, 2.0, 3.0], 33.0)
            .unwrap()
            .translate([4.0, 5.0, 6.0]);
        let (one, two) = (
            t.apply(p),
            Transform::translation([4.0, 5.0, 6.0])
                .apply(Transform::rotation([1.0, 2.0, 3.0], 33.0).unwrap().apply(p)),
        );
        for k in 0..3 {
            assert!((one[k] - two[k]).abs() < 1e-14);
        }
        assert_eq!(Transform::IDENTITY.then(&t), t);
        assert_eq!(Transform::default(), Transform::IDENTITY);
    }

    #[test]
    fn row_major_matrix_round_trips_and_matches_builders() {
        let m = [
            2.0, 0.0, 0.0, 1.0, //
            0.0, 2.0, 0.0, 2.0, //
            0.0, 0.0, 2.0, 3.0, //
            0.0, 0.0, 0.0, 1.0,
        ];
        let t = Transform::from_row_major(m).unwrap();
        assert_eq!(t, Transform::scaling(2.0).translate([1.0, 2.0, 3.0]));
        assert_eq!(t.to_row_major(), m);
        assert_eq!(t.rows()[3], [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(t.determinant(), 8.0);
        let mut projective = m;
        projective[12] = 0.5;
        assert!(Transform::from_row_major(projective).is_err());
        let mut nan = m;
        nan[5] = f64::NAN;
        let e = Transform::from_row_major(nan).unwrap_err().to_string();
        assert!(e.contains("row 2, column 2"), "{e}");
        assert_eq!(t.apply_vector([1.0, 1.0, 1.0]), [2.0, 2.0, 2.0]);
    }

    #[test]
    fn mirror_reverses_triangles_and_keeps_volume_positive() {
        let cube = Mesh::cuboid([0.0; 3], [1.0, 2.0, 3.0]);
        for t in [
            Transform::scaling_xyz([-1.0, 1.0, 1.0]),
            Transform::scaling_xyz([1.0, -2.0, 1.0]),
            Transform::scaling(-1.0),
        ] {
            assert!(t.reverses_orientation());
            let m = cube.transformed(&t);
            let s = mesh_stats(&m);
            assert!(s.closed && s.inconsistent_edges == 0);
            assert_eq!(s.volume, 6.0 * t.determinant().abs());
        }
        // Point reflection of a cube: the same triangles reversed.
        let m = cube.transformed(&Transform::scaling(-1.0));
        assert_eq!(m.triangles, cube.flipped().triangles);
        // A proper transform keeps the triangles.
        let m = cube.transformed(&Transform::scaling(2.0));
        assert_eq!(m.triangles, cube.triangles);
        assert_eq!(signed_volume(&m), 48.0);
    }

    #[test]
    fn utm_translation_is_exact() {
        let cube = Mesh::cuboid([-0.5; 3], [0.5; 3]);
        let offset = [512_345.25, 7_012_345.5, 1_234.125];
        let there = cube.transformed(&Transform::translation(offset));
        for (p, q) in cube.positions.iter().zip(&there.positions) {
            assert_eq!(*q, std::array::from_fn(|k| p[k] + offset[k]));
        }
        assert_eq!(signed_volume(&there), 1.0);
        let back = there.transformed(&Transform::translation(offset.map(|v| -v)));
        assert_eq!(back.positions, cube.positions);
        // Turned a quarter about a vertical axis through the origin, still exact.
        let turned = there.transformed(&Transform::rotation_z(90.0));
        assert_eq!(turned.positions[0], [-7_012_345.0, 512_344.75, 1_233.625]);
        assert_eq!(signed_volume(&turned), 1.0);
    }
}
