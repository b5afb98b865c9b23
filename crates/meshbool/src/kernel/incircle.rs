//! The in-circle test of the local triangulation's Delaunay flips: a floating-point
//! filter that answers only where it is sure, and a canonical choice for four points on
//! one circle, so that the triangulation does not depend on the order of its points.

/// The in-circle choice of `p[3]` against `p[0] p[1] p[2]` (positive inside for them
/// counter-clockwise), the same for every order of the four points up to the order's
/// sign, so that the Delaunay flips of the local triangulation (`arrange::local`) end in the same triangulation whatever
/// order the points and constraints came in (cocircular points, on grids and boxes, are
/// the rule): [`incircle_clear`] of the points in lexicographic order, and where that is
/// unsure, the sign of the in-circle determinant with each point's lift raised by `ε^r`
/// (`r` its rank in that order, `ε` infinitesimal: the first point's raise dominates),
/// from exact orientations of the others (`robust::orient2d` on the same coordinates).
/// Zero only where all four are collinear (or two coincide).
pub(crate) fn incircle_canonical(p: [[f64; 2]; 4]) -> f64 {
    let mut q = p.map(|[x, y]| robust::Coord { x, y });
    // Insertion sort by (x, y), counting swaps for the permutation's sign.
    let mut odd = false;
    for i in 1..4 {
        let mut j = i;
        while j > 0 && (q[j].x, q[j].y) < (q[j - 1].x, q[j - 1].y) {
            q.swap(j, j - 1);
            odd = !odd;
            j -= 1;
        }
    }
    let signed = |x: f64| if odd { -x } else { x };
    let det = clear(q[0], q[1], q[2], q[3]);
    if det != 0.0 {
        return signed(det);
    }
    let [a, b, c, d] = q;
    // d det / d lift of a, b, c, d in turn (the cofactors of the lifted column).
    for o in [
        robust::orient2d(b, c, d),
        robust::orient2d(a, d, c),
        robust::orient2d(a, b, d),
        -robust::orient2d(a, b, c),
    ] {
        if o != 0.0 {
            return signed(o);
        }
    }
    0.0
}

/// The in-circle determinant of `d` against `a b c` (positive inside for `a b c`
/// counter-clockwise) where its `f64` evaluation is sure of its sign, else zero: the
/// first stage of Shewchuk's `incircle`, with his error bound, without the adaptive
/// stages. For the Delaunay flips of the local triangulation, which only choose among
/// valid triangulations: a flip is made where a point is clearly inside a circle, and none for
/// points on one circle or too close to it to tell (the corners of squares, on grids and
/// boxes, where the adaptive stages ran to their end only to find zero).
#[cfg(test)]
pub(crate) fn incircle_clear(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> f64 {
    let c2 = |p: [f64; 2]| robust::Coord { x: p[0], y: p[1] };
    clear(c2(a), c2(b), c2(c), c2(d))
}

/// [`incircle_clear`] of `robust`'s points.
fn clear(
    a: robust::Coord<f64>,
    b: robust::Coord<f64>,
    c: robust::Coord<f64>,
    d: robust::Coord<f64>,
) -> f64 {
    const ERR: f64 = (10.0 + 96.0 * f64::EPSILON / 2.0) * f64::EPSILON / 2.0;
    let (adx, ady) = (a.x - d.x, a.y - d.y);
    let (bdx, bdy) = (b.x - d.x, b.y - d.y);
    let (cdx, cdy) = (c.x - d.x, c.y - d.y);
    let (bdxcdy, cdxbdy) = (bdx * cdy, cdx * bdy);
    let (cdxady, adxcdy) = (cdx * ady, adx * cdy);
    let (adxbdy, bdxady) = (adx * bdy, bdx * ady);
    let alift = adx * adx + ady * ady;
    let blift = bdx * bdx + bdy * bdy;
    let clift = cdx * cdx + cdy * cdy;
    let det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
    let permanent = (bdxcdy.abs() + cdxbdy.abs()) * alift
        + (cdxady.abs() + adxcdy.abs()) * blift
        + (adxbdy.abs() + bdxady.abs()) * clift;
    if det.abs() > ERR * permanent {
        det
    } else {
        0.0
    }
}
