//! A triangle of input points with the 2D projection its predicates use: the coordinate
//! axis to drop, chosen so that the triangle is not degenerate in that projection, and
//! its orientation there.

use super::{normals_cross_sign, orient2d_inputs, robust_safe, Sign};
use crate::vec3::{cross, sub};

/// A non-degenerate triangle of input points, with a projection in which it is not
/// degenerate: [`Triangle::axis`] (the coordinate dropped) and [`Triangle::sign`] (its
/// orientation there, as given). Classifying a point of the triangle's plane against its
/// edges, re-triangulating it, or comparing another triangle's orientation with it are
/// then exact `orient2d` questions in that projection.
#[derive(Clone, Copy, Debug)]
pub struct Triangle {
    corners: [[f64; 3]; 3],
    axis: usize,
    sign: Sign,
    /// The corners meet the conditions of Shewchuk's predicates ([`robust_safe`]), so
    /// orientations of them can skip the per-call checks.
    safe: bool,
}

impl Triangle {
    /// The triangle `corners`; `None` when it is degenerate (zero area: collinear or
    /// repeated corners). The projection is the first, in order of the approximate
    /// normal's components from largest to smallest, in which the corners' exact
    /// orientation is non-zero: the dominant axis, unless rounding hides a sliver there.
    pub fn new(corners: [[f64; 3]; 3]) -> Option<Triangle> {
        let n = approx_normal(&corners);
        let mut axes = [0, 1, 2];
        axes.sort_by(|&i, &j| n[j].abs().total_cmp(&n[i].abs()));
        let safe = robust_safe(&[&corners[0], &corners[1], &corners[2]]);
        let [a, b, c] = &corners;
        axes.into_iter().find_map(|axis| {
            let sign = orient2d_inputs(a, b, c, axis, safe);
            (sign != Sign::Zero).then_some(Triangle {
                corners,
                axis,
                sign,
                safe,
            })
        })
    }

    /// The corner coordinates, as given.
    #[inline]
    pub fn corners(&self) -> &[[f64; 3]; 3] {
        &self.corners
    }

    /// The coordinate dropped by the projection in which the triangle is not degenerate.
    #[inline]
    pub fn axis(&self) -> usize {
        self.axis
    }

    /// The triangle's orientation (corners as given) in the projection dropping
    /// [`Triangle::axis`]: positive when counter-clockwise; never zero.
    #[inline]
    pub fn sign(&self) -> Sign {
        self.sign
    }

    /// Whether the corners meet the conditions of Shewchuk's predicates ([`robust_safe`]):
    /// then `orient2d_safe` decides orientations of them exactly.
    #[inline]
    pub(crate) fn robust_safe(&self) -> bool {
        self.safe
    }
}

/// `(b − a) × (c − a)` in plain `f64`: only to choose an order of trying axes.
fn approx_normal(p: &[[f64; 3]; 3]) -> [f64; 3] {
    cross(&sub(&p[1], &p[0]), &sub(&p[2], &p[0]))
}

/// An axis in which the direction of the line where the planes of triangles `t` and `u`
/// meet is exactly non-zero ([`normals_cross_sign`]), so that points on that line are
/// ordered along it by that coordinate. Axes are tried from the largest component of the
/// approximate direction to the smallest; with the axis, the sign of that component.
/// `None` for parallel (or degenerate) planes.
pub fn planes_line_axis(t: &[[f64; 3]; 3], u: &[[f64; 3]; 3]) -> Option<(usize, Sign)> {
    let d = cross(&approx_normal(t), &approx_normal(u));
    let mut axes = [0, 1, 2];
    axes.sort_by(|&i, &j| d[j].abs().total_cmp(&d[i].abs()));
    axes.into_iter()
        .map(|k| (k, normals_cross_sign(t, u, k)))
        .find(|&(_, s)| s != Sign::Zero)
}
