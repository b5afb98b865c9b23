//! Exact intersection of two triangles, one from each mesh, in every configuration:
//! proper crossing, vertex on plane, vertex on vertex, edge through edge, edge in plane,
//! coplanar overlap, touching at a point.
//!
//! Results are given as [`Label`]s: a point is named by the smallest feature (vertex,
//! edge, face) of each mesh that contains it, found with exact predicates. The same point
//! reached from different triangle pairs therefore gets the same label, and each label has
//! one canonical construction ([`super::label_point`]).

use std::cell::OnceCell;
use std::cmp::Ordering;

#[cfg(test)]
use crate::kernel::{
    cmp_coord_prepared, orient2d_prepared, robust_safe, same_point_prepared, Point, Prepared,
};
use crate::kernel::{
    longest_axis, orient2d_inputs, orient3d_inputs, orient3d_sides, planes_line_axis, Sign,
    Triangle,
};

/// A vertex, edge or face of one mesh, by its vertex / triangle ids (edges sorted).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Feature {
    /// A vertex.
    Vertex(u32),
    /// An edge `(lo, hi)` by its vertex ids.
    Edge(u32, u32),
    /// A triangle's interior.
    Face(u32),
}

/// The edge between vertices `u` and `v`.
pub fn edge(u: u32, v: u32) -> Feature {
    Feature::Edge(u.min(v), u.max(v))
}

/// A seam point named by the smallest feature of mesh A and of mesh B containing it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Label {
    /// Feature of mesh A.
    pub a: Feature,
    /// Feature of mesh B.
    pub b: Feature,
}

impl Label {
    /// The feature of one mesh.
    pub fn feature(&self, side: super::Source) -> Feature {
        match side {
            super::Source::A => self.a,
            super::Source::B => self.b,
        }
    }
}

/// A triangle with its ids and corner coordinates.
#[derive(Clone, Copy, Debug)]
pub struct Tri {
    /// Triangle id in its mesh.
    pub id: u32,
    /// Vertex ids.
    pub v: [u32; 3],
    /// The corners, with the projection in which the triangle is not degenerate.
    tri: Triangle,
    /// The corners' smallest and largest coordinates.
    lo: [f64; 3],
    hi: [f64; 3],
    /// Whether the triangle lies in a plane square to its axis (all corners share that
    /// coordinate: faces of boxes and CAD parts), where a point's side of its plane is the
    /// sign of a coordinate difference.
    square: bool,
}

impl Tri {
    /// `None` for a degenerate (zero-area) triangle.
    pub fn new(id: u32, v: [u32; 3], p: [[f64; 3]; 3]) -> Option<Tri> {
        let [lo, hi] = crate::bvh::corners_box(&p);
        Triangle::new(p).map(|tri| {
            let k = tri.axis();
            let square = p[0][k] == p[1][k] && p[1][k] == p[2][k];
            Tri {
                id,
                v,
                tri,
                lo,
                hi,
                square,
            }
        })
    }

    /// The exact sides of `other`'s corners against this triangle's plane: as
    /// [`orient3d_sides`] gives them, from a coordinate comparison where the plane is
    /// square to this triangle's axis (its normal points along the axis, with the sign of
    /// the triangle's orientation in the projection dropping it).
    pub(super) fn sides_of(&self, other: &Tri) -> [Sign; 3] {
        if self.square {
            let (k, at) = (self.axis(), self.corners()[0][self.axis()]);
            return other
                .corners()
                .map(|d| Sign::of_difference(d[k], at).times(self.sign()));
        }
        orient3d_sides(self.corners(), other.corners())
    }

    /// Corner coordinates.
    #[inline]
    pub fn corners(&self) -> &[[f64; 3]; 3] {
        self.tri.corners()
    }

    /// The projection axis in which the triangle is not degenerate ([`Triangle::axis`]).
    #[inline]
    pub fn axis(&self) -> usize {
        self.tri.axis()
    }

    /// The triangle's orientation (as given) in the projection dropping [`Tri::axis`].
    #[inline]
    pub fn sign(&self) -> Sign {
        self.tri.sign()
    }

    #[cfg(test)]
    fn corner(&self, k: usize) -> Point {
        Point::Explicit(self.corners()[k])
    }

    /// The smallest feature of this (closed) triangle containing `x`, which must lie in
    /// the triangle's plane; `None` when `x` is outside.
    #[cfg(test)]
    pub fn locate(&self, x: &Point) -> Option<Feature> {
        self.locate_prepared(&Prepared::new(x.clone()))
    }

    /// [`Tri::locate`] of a prepared point (its interval enclosure computed once for
    /// the three orientations).
    #[cfg(test)]
    fn locate_prepared(&self, x: &Prepared) -> Option<Feature> {
        if let Some(p) = x.explicit() {
            return self.locate_corner(&p, robust_safe(&[&p]));
        }
        let c = self.corners().map(|p| Prepared::new(Point::Explicit(p)));
        self.locate_by(std::array::from_fn(|k| {
            orient2d_prepared(&c[k], &c[(k + 1) % 3], x, self.axis())
        }))
    }

    /// [`Tri::locate`] of an input point (a corner of another triangle, on this one's
    /// plane): orientations of input points. `p_safe`: `p` is in the range of the
    /// fast predicates ([`robust_safe`]; known from its triangle).
    fn locate_corner(&self, p: &[f64; 3], p_safe: bool) -> Option<Feature> {
        let (c, safe) = (self.corners(), self.tri.robust_safe() && p_safe);
        self.locate_by(std::array::from_fn(|k| {
            orient2d_inputs(&c[k], &c[(k + 1) % 3], p, self.axis(), safe)
        }))
    }

    /// [`Tri::locate`] of the point where segment `p q` crosses this triangle's plane,
    /// `p` strictly on side `side` of it and `q` strictly on the other, from input points
    /// alone: the point lies on the inner side of edge `k` exactly when the tetrahedron
    /// `k, k + 1, q, p` is oriented as `side` says (three `orient3d`, no construction).
    /// `pq_safe`: `p` and `q` are in the range of the fast predicates ([`robust_safe`]).
    fn locate_crossing(
        &self,
        p: &[f64; 3],
        q: &[f64; 3],
        side: Sign,
        pq_safe: bool,
    ) -> Option<Feature> {
        let (c, safe) = (self.corners(), self.tri.robust_safe() && pq_safe);
        self.locate_inside(std::array::from_fn(|k| {
            orient3d_inputs(&c[k], &c[(k + 1) % 3], q, p, safe).times(side)
        }))
    }

    /// [`Tri::locate`] from the orientations of the point against the edges (edge `k`
    /// from corner `k` to `k + 1`, projected along [`Tri::axis`]).
    fn locate_by(&self, o: [Sign; 3]) -> Option<Feature> {
        self.locate_inside(o.map(|s| s.times(self.sign())))
    }

    /// [`Tri::locate`] from the side of each edge the point lies on, seen from the side
    /// the triangle's normal points to: positive on the inner side of edge `k` (from corner
    /// `k` to `k + 1`), zero on its line.
    fn locate_inside(&self, o: [Sign; 3]) -> Option<Feature> {
        if o.contains(&Sign::Negative) {
            return None;
        }
        // Edge k runs from corner k to corner k+1.
        match o.map(|s| s == Sign::Zero) {
            [false, false, false] => Some(Feature::Face(self.id)),
            [true, false, false] => Some(edge(self.v[0], self.v[1])),
            [false, true, false] => Some(edge(self.v[1], self.v[2])),
            [false, false, true] => Some(edge(self.v[2], self.v[0])),
            [true, true, false] => Some(Feature::Vertex(self.v[1])),
            [false, true, true] => Some(Feature::Vertex(self.v[2])),
            [true, false, true] => Some(Feature::Vertex(self.v[0])),
            [true, true, true] => None, // impossible for a non-degenerate triangle
        }
    }
}

/// What two triangles share.
#[derive(Clone, Debug, PartialEq)]
pub enum TriTri {
    /// Nothing.
    None,
    /// One point (touching).
    Point(Label),
    /// A segment between two distinct points (non-coplanar triangles).
    Segment([Label; 2]),
    /// Coplanar triangles: the parts of each triangle's edges inside the other (the
    /// boundary of their overlap and the edges crossing it), and isolated touching points.
    Coplanar {
        /// Segments, each between two distinct points.
        segments: Vec<[Label; 2]>,
        /// Points where the triangles only touch.
        points: Vec<Label>,
    },
}

/// A point on the other triangle's plane, with the feature of its own triangle it lies on.
/// Prepared: it is compared along the planes' line and located several times.
#[cfg(test)]
struct OnPlane {
    point: Prepared,
    own: Feature,
    /// For a crossing of an edge, the edge's ends and the side of the plane the first
    /// lies on: the point is located in the other triangle from these.
    crossing: Option<([f64; 3], [f64; 3], Sign)>,
}

#[cfg(test)]
impl OnPlane {
    /// The smallest feature of `t` (the triangle whose plane the point lies on) that
    /// contains the point.
    fn locate_in(&self, t: &Tri) -> Option<Feature> {
        match &self.crossing {
            Some((p, q, side)) => t.locate_crossing(p, q, *side, robust_safe(&[p, q])),
            None => t.locate_prepared(&self.point),
        }
    }
}

/// The points of `t` on the plane of `o`, given the sides `s` of `t`'s corners: corners on
/// the plane and crossings of edges whose ends are on opposite sides.
#[cfg(test)]
fn on_plane(t: &Tri, s: [Sign; 3], o: &Tri, out: &mut [Option<OnPlane>; 2]) {
    // At most two (in place): two corners on the plane (then the third is off it and no
    // edge crosses), or one and the crossing of the opposite edge, or two crossings.
    // Written where the caller keeps them (a point is a few hundred bytes).
    let mut free = 0;
    for (i, side) in s.iter().enumerate() {
        if *side == Sign::Zero {
            debug_assert!(free < 2, "a triangle meets a plane in two points");
            out[free] = Some(OnPlane {
                point: Prepared::new(t.corner(i)),
                own: Feature::Vertex(t.v[i]),
                crossing: None,
            });
            free += 1;
        }
    }
    for i in 0..3 {
        let j = (i + 1) % 3;
        if s[i].times(s[j]) == Sign::Negative {
            debug_assert!(free < 2, "a triangle meets a plane in two points");
            let (p, q) = (t.corners()[i], t.corners()[j]);
            let [x, y, z] = *o.corners();
            out[free] = Some(OnPlane {
                point: Prepared::new(Point::lpi(p, q, x, y, z)),
                own: edge(t.v[i], t.v[j]),
                crossing: Some((p, q, s[i])),
            });
            free += 1;
        }
    }
}

/// Intersects triangles `a` (mesh A) and `b` (mesh B) exactly.
pub fn intersect(a: &Tri, b: &Tri) -> TriTri {
    match against(a, b) {
        Against::Apart => TriTri::None,
        Against::Coplanar => coplanar_filtered(a, b, true).0,
        Against::Sides(sa) => crossing(a, b, sa),
    }
}

/// [`intersect`] with the points where each triangle meets the other's plane built and
/// compared along the planes' line ([`crossing_by_points`]): the tests' reference for
/// the orientations that decide it in [`crossing`].
#[cfg(test)]
pub(super) fn intersect_by_points(a: &Tri, b: &Tri) -> TriTri {
    match against(a, b) {
        Against::Apart => TriTri::None,
        Against::Coplanar => coplanar_filtered(a, b, true).0,
        Against::Sides(sa) => crossing_by_points(a, b, sa),
    }
}

/// How triangle `a` lies against the plane of `b`.
enum Against {
    /// Every corner strictly on one side.
    Apart,
    /// Every corner on the plane.
    Coplanar,
    /// Otherwise: the corners' sides.
    Sides([Sign; 3]),
}

/// [`planes_line_axis`] of the two triangles' planes: from their axes where both are
/// square to theirs (normals along two axes, signed by the triangles' orientations, so
/// that `d = n_a × n_b` lies along the third axis with the sign of the axes' order,
/// positive when cyclic, times the orientations).
pub(super) fn line_axis(a: &Tri, b: &Tri) -> Option<(usize, Sign)> {
    let (i, j) = (a.axis(), b.axis());
    if a.square && b.square && i != j {
        let cyclic = if j == (i + 1) % 3 {
            Sign::Positive
        } else {
            Sign::Negative
        };
        return Some((3 - i - j, cyclic.times(a.sign()).times(b.sign())));
    }
    planes_line_axis(a.corners(), b.corners())
}

/// How `a` lies against `b`'s plane, from the exact sides of its corners.
fn against(a: &Tri, b: &Tri) -> Against {
    let sa = b.sides_of(a);
    if sa[0] != Sign::Zero && sa[0] == sa[1] && sa[1] == sa[2] {
        Against::Apart
    } else if sa == [Sign::Zero; 3] {
        Against::Coplanar
    } else {
        Against::Sides(sa)
    }
}

/// One piece of what two triangles share, as the seam takes it in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Piece {
    /// A point where they only touch.
    Point(Label),
    /// A segment between two distinct points, and whether the triangles are coplanar.
    Segment([Label; 2], bool),
}

/// The pieces of `r`, in order: a coplanar pair's segments, then its points.
pub(super) fn pieces_of(r: &TriTri, mut f: impl FnMut(Piece)) {
    match r {
        TriTri::None => {}
        TriTri::Point(l) => f(Piece::Point(*l)),
        TriTri::Segment(s) => f(Piece::Segment(*s, false)),
        TriTri::Coplanar { segments, points } => coplanar_to(segments, points, f),
    }
}

/// A coplanar pair's pieces given to `f` in their order: its segments, then its points.
fn coplanar_to(segments: &[[Label; 2]], points: &[Label], mut f: impl FnMut(Piece)) {
    for &s in segments {
        f(Piece::Segment(s, true));
    }
    for &l in points {
        f(Piece::Point(l));
    }
}

/// The pieces of [`intersect`]`(a, b)`, in the same order ([`pieces_of`]), given to `f`
/// one by one: a coplanar pair's are made in place, with no allocation.
pub(super) fn meet(a: &Tri, b: &Tri, f: impl FnMut(Piece)) {
    meet_beyond_flat(a, b, [0, 0], f)
}

/// [`meet`], where a coplanar pair's segments along the edges that `flat` marks (per
/// triangle, bit `k` for its edge from corner `k` to `k + 1`) are not needed: those
/// edges are not clipped to the other triangle, and a pair whose six edges are marked
/// gives nothing (edges inside a planar region of their mesh: see the seam's sifting).
/// Segments along a marked edge may still come, from the shortcut of triangles side by
/// side or along an unmarked edge of the other triangle.
pub(super) fn meet_beyond_flat(a: &Tri, b: &Tri, flat: [u8; 2], mut f: impl FnMut(Piece)) {
    let skip_coplanar = flat == [0b111, 0b111];
    if let Some(touch) = touching(a, b) {
        if let Some(l) = touch {
            f(Piece::Point(l));
        }
        return;
    }
    if let Some(edges) = twins(a, b) {
        if !skip_coplanar {
            edges.into_iter().for_each(|s| f(Piece::Segment(s, true)));
        }
        return;
    }
    match against(a, b) {
        Against::Apart => {}
        Against::Coplanar => {
            if !skip_coplanar {
                coplanar_pieces(a, b, true, flat, &mut f);
            }
        }
        Against::Sides(sa) => pieces_of(&crossing(a, b, sa), f),
    }
}

/// Triangles with the same three corners (a face the two meshes share; every face of a
/// mesh against itself) share their three edges: the segments between the corners, each
/// corner named by its vertex in each mesh, in the order of [`coplanar_pieces`]
/// (each segment's ends sorted, the segments sorted). `None` for any other pair.
pub(super) fn twins(a: &Tri, b: &Tri) -> Option<[[Label; 2]; 3]> {
    if a.lo != b.lo || a.hi != b.hi {
        return None;
    }
    let (pa, pb) = (a.corners(), b.corners());
    // Distinct corners (the triangles are not degenerate): a match for each is a
    // one-to-one map.
    let mut at = [0usize; 3];
    for k in 0..3 {
        at[k] = (0..3).find(|&m| pb[m] == pa[k])?;
    }
    let corner = |k: usize| Label {
        a: Feature::Vertex(a.v[k]),
        b: Feature::Vertex(b.v[at[k]]),
    };
    let mut edges = [0, 1, 2].map(|k| {
        let (x, y) = (corner(k), corner((k + 1) % 3));
        [x.min(y), x.max(y)]
    });
    edges.sort_unstable();
    Some(edges)
}

/// Triangles whose boxes only touch, on a plane `x_i = c` square to an axis that both
/// cross (one on each side of it): neighbours on a grid, most candidate pairs of meshes
/// made on one (boxes, cubes, terrain grids, a mesh against itself). Each meets the plane
/// in its corners there, one or two, so they share what those corners share: nothing
/// when their boxes in the plane are apart, else a common corner, or a corner on the
/// other's edge there (one orientation, in the plane). Exact, from input coordinates
/// alone. `None` when the boxes do not touch so, or each has an edge on the plane (a
/// segment shared or crossed, left to the general test, which tells whether the
/// triangles are coplanar).
pub(super) fn touching(a: &Tri, b: &Tri) -> Option<Option<Label>> {
    let i = (0..3).find(|&i| {
        (a.hi[i] == b.lo[i] || b.hi[i] == a.lo[i]) && a.lo[i] < a.hi[i] && b.lo[i] < b.hi[i]
    })?;
    let c = if a.hi[i] == b.lo[i] { a.hi[i] } else { b.hi[i] };
    // Each triangle's corners on the plane: one, or the two ends of an edge (never three:
    // each crosses the plane).
    let on = |t: &Tri| -> ([usize; 2], usize) {
        let p = t.corners();
        match (p[0][i] == c, p[1][i] == c, p[2][i] == c) {
            (true, false, false) => ([0, 0], 1),
            (false, true, false) => ([1, 1], 1),
            (false, false, true) => ([2, 2], 1),
            (true, true, _) => ([0, 1], 2),
            (true, false, true) => ([0, 2], 2),
            _ => ([1, 2], 2),
        }
    };
    let ((ka, na), (kb, nb)) = (on(a), on(b));
    let (pa, pb) = (a.corners(), b.corners());
    let label = |x: Feature, y: Feature| Label { a: x, b: y };
    // Corner `m` of `p` against `s`'s edge `k` on the plane: a corner of it, a point
    // inside it (on its line, within its box), or apart.
    let corner_on_edge =
        |p: &Tri, m: usize, s: &Tri, k: [usize; 2]| -> Option<(Feature, Feature)> {
            let (x, [q, r]) = (&p.corners()[m], k.map(|m| &s.corners()[m]));
            let own = Feature::Vertex(p.v[m]);
            if x == q || x == r {
                let at = if x == q { k[0] } else { k[1] };
                return Some((own, Feature::Vertex(s.v[at])));
            }
            let within = (0..3).all(|j| x[j] >= q[j].min(r[j]) && x[j] <= q[j].max(r[j]));
            let safe = s.tri.robust_safe() && p.tri.robust_safe();
            (within && orient2d_inputs(q, r, x, i, safe) == Sign::Zero)
                .then(|| (own, edge(s.v[k[0]], s.v[k[1]])))
        };
    match (na, nb) {
        (1, 1) => Some(
            (pa[ka[0]] == pb[kb[0]])
                .then(|| label(Feature::Vertex(a.v[ka[0]]), Feature::Vertex(b.v[kb[0]]))),
        ),
        (1, _) => Some(corner_on_edge(a, ka[0], b, kb).map(|(x, y)| label(x, y))),
        (_, 1) => Some(corner_on_edge(b, kb[0], a, ka).map(|(y, x)| label(x, y))),
        _ => {
            // Two edges on the plane: apart when their boxes are, else left to the
            // general test.
            let span = |p: &[[f64; 3]; 3], k: [usize; 2], j: usize| {
                (p[k[0]][j].min(p[k[1]][j]), p[k[0]][j].max(p[k[1]][j]))
            };
            let apart = (0..3).any(|j| {
                let ((alo, ahi), (blo, bhi)) = (span(pa, ka, j), span(pb, kb, j));
                ahi < blo || bhi < alo
            });
            apart.then_some(None)
        }
    }
}

/// Triangles `a` and `b` that are not coplanar, with `a`'s corners' sides `sa` of `b`'s
/// plane (not all one non-zero side): each meets the line `L` where the planes cross in
/// a segment or a point, and they share the overlap of the two. The ends of each are
/// corners on the other's plane or crossings of edges with it, compared along `L` by
/// orientations of input corners alone ([`Line::cmp`]): no intersection point is built.
/// Pairs in general position cost four `orient3d` beyond the corners' sides, two of
/// them for pairs that are apart (the test of Devillers and Guigue, "Faster
/// triangle-triangle intersection tests", 2002, is this one in that configuration).
fn crossing(a: &Tri, b: &Tri, sa: [Sign; 3]) -> TriTri {
    let sb = a.sides_of(b);
    // All on one side: apart. All on `a`'s plane while `a` is not all on `b`'s: only with
    // non-finite corners (a public caller's unvalidated mesh).
    if sb[0] == sb[1] && sb[1] == sb[2] {
        return TriTri::None;
    }
    let line = Line {
        tris: [a, b],
        sides: [sa, sb],
        axis: OnceCell::new(),
    };
    line.overlap()
}

/// A point where a triangle meets the other's plane: on the line where the planes cross.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum OnLine {
    /// Corner `k` of triangle `t` (0: `a`, 1: `b`), on the other's plane.
    Corner { t: usize, k: usize },
    /// The crossing of the other's plane by edge `k l` of triangle `t`, whose ends are
    /// strictly on either side of it.
    Crossing { t: usize, k: usize, l: usize },
}

/// Two triangles that are not coplanar and both meet the other's plane ([`crossing`]).
/// Points on the line `L` where the planes cross are ordered along the direction
/// `d = n_a × n_b` (`n`: a triangle's normal `(c₁ − c₀) × (c₂ − c₀)`).
struct Line<'t> {
    tris: [&'t Tri; 2],
    /// The sides of each triangle's corners of the other's plane.
    sides: [[Sign; 3]; 2],
    /// An axis in which `d` is non-zero and the sign of `d` in it ([`planes_line_axis`]),
    /// found when first needed; `None` only for non-finite corners.
    axis: OnceCell<Option<(usize, Sign)>>,
}

impl Line<'_> {
    fn axis(&self) -> Option<(usize, Sign)> {
        *self
            .axis
            .get_or_init(|| line_axis(self.tris[0], self.tris[1]))
    }

    fn corner(&self, t: usize, k: usize) -> &[f64; 3] {
        &self.tris[t].corners()[k]
    }

    /// Triangle `t`'s points on the other's plane, ordered along `d`: two, or one twice.
    fn ends(&self, t: usize) -> Option<[OnLine; 2]> {
        let s = self.sides[t];
        let mut found = [None; 2];
        let mut push = |p: OnLine| {
            debug_assert!(found[1].is_none(), "a triangle meets a plane in two points");
            let free = usize::from(found[0].is_some());
            found[free] = Some(p);
        };
        for k in 0..3 {
            let l = (k + 1) % 3;
            if s[k] == Sign::Zero {
                push(OnLine::Corner { t, k });
            } else if s[k].times(s[l]) == Sign::Negative {
                push(OnLine::Crossing { t, k, l });
            }
        }
        match found {
            [Some(x), Some(y)] if self.cmp(x, y) == Sign::Negative => Some([y, x]),
            [Some(x), Some(y)] => Some([x, y]),
            [Some(x), None] => Some([x, x]),
            _ => None,
        }
    }

    /// The sign of `y − x` along `d`: positive when `y` lies beyond `x`, zero when they
    /// are one point.
    fn cmp(&self, x: OnLine, y: OnLine) -> Sign {
        match (x, y) {
            (OnLine::Crossing { t, k, l }, _) => self.beyond_crossing(t, k, l, y),
            (_, OnLine::Crossing { t, k, l }) => self.beyond_crossing(t, k, l, x).reversed(),
            (OnLine::Corner { t, k }, OnLine::Corner { t: u, k: m }) => {
                // Both on L, so their coordinates along an axis in which `d` is non-zero
                // come in the order of `d`'s sign there.
                let Some((axis, along)) = self.axis() else {
                    return Sign::Zero; // non-finite corners only
                };
                let (p, q) = (self.corner(t, k)[axis], self.corner(u, m)[axis]);
                Sign::of_difference(q, p).times(along)
            }
        }
    }

    /// [`Line::cmp`] of the crossing `x` of the other's plane by edge `k l` (`p q`) of
    /// triangle `t` and a point `z` on L. In `t`'s plane, `z` lies on the side of the line
    /// `p q` that `d` points to from `x` exactly when it lies beyond `x`: for `t = a`,
    /// the side `sign(n_a · ((q − p) × d)) = sign((q − p) · n_b)`, `q`'s side of `b`'s
    /// plane, and the opposite for `t = b` (`d` is `−n_b × n_a`). The side of `z` comes
    /// from `orient2d` for a corner (an input point in `t`'s plane), from `t`'s own
    /// orientation for its own points (they lie beyond the edge's third corner's side),
    /// and for the crossing of `t`'s plane by edge `r s` of the other triangle from
    /// `orient3d(p, q, r, s)`, which is minus the side of `z` times `r`'s side of `t`'s
    /// plane.
    fn beyond_crossing(&self, t: usize, k: usize, l: usize, z: OnLine) -> Sign {
        let tri = self.tris[t];
        let (p, q) = (self.corner(t, k), self.corner(t, l));
        // The side of edge k → l its third corner lies on: that of the triangle's own
        // points.
        let own = if l == (k + 1) % 3 {
            Sign::Positive
        } else {
            Sign::Negative
        };
        let side = match z {
            OnLine::Corner { t: u, .. } | OnLine::Crossing { t: u, .. } if u == t => own,
            OnLine::Corner { t: u, k: m } => {
                let z = self.corner(u, m);
                let safe = tri.tri.robust_safe() && self.tris[u].tri.robust_safe();
                orient2d_inputs(p, q, z, tri.axis(), safe).times(tri.sign())
            }
            OnLine::Crossing { t: u, k: r, l: s } => {
                let (r_at, s_at) = (self.corner(u, r), self.corner(u, s));
                let safe = tri.tri.robust_safe() && self.tris[u].tri.robust_safe();
                orient3d_inputs(p, q, r_at, s_at, safe)
                    .times(self.sides[u][r])
                    .reversed()
            }
        };
        let side = side.times(self.sides[t][l]);
        if t == 0 {
            side
        } else {
            side.reversed()
        }
    }

    /// The label of a point on L.
    fn label(&self, x: OnLine) -> Option<Label> {
        // The point's own feature in its triangle, and the feature of the other it lies in.
        let (t, own, other) = match x {
            OnLine::Corner { t, k } => {
                let at = self.corner(t, k);
                (
                    t,
                    Feature::Vertex(self.tris[t].v[k]),
                    self.tris[1 - t].locate_corner(at, self.tris[t].tri.robust_safe())?,
                )
            }
            OnLine::Crossing { t, k, l } => {
                let tri = self.tris[t];
                let (p, q) = (self.corner(t, k), self.corner(t, l));
                let other = self.tris[1 - t].locate_crossing(
                    p,
                    q,
                    self.sides[t][k],
                    tri.tri.robust_safe(),
                )?;
                (t, edge(tri.v[k], tri.v[l]), other)
            }
        };
        Some(if t == 0 {
            Label { a: own, b: other }
        } else {
            Label { a: other, b: own }
        })
    }

    /// The overlap of the two triangles' segments on L: nothing, a point or a segment,
    /// its ends in increasing coordinate along [`planes_line_axis`]'s axis.
    fn overlap(&self) -> TriTri {
        let (Some([a_lo, a_hi]), Some([b_lo, b_hi])) = (self.ends(0), self.ends(1)) else {
            return TriTri::None;
        };
        // Apart: one segment starts beyond the other's end.
        if self.cmp(a_hi, b_lo) == Sign::Positive || self.cmp(b_hi, a_lo) == Sign::Positive {
            return TriTri::None;
        }
        // The later start and the earlier end; ties (one point) go to `a`.
        let lo = if self.cmp(a_lo, b_lo) == Sign::Positive {
            b_lo
        } else {
            a_lo
        };
        let hi = if self.cmp(a_hi, b_hi) == Sign::Negative {
            b_hi
        } else {
            a_hi
        };
        let (Some(l0), Some(l1)) = (self.label(lo), self.label(hi)) else {
            // Only non-finite corners (a public caller's unvalidated mesh) get here.
            return TriTri::None;
        };
        if l0 == l1 {
            return TriTri::Point(l0);
        }
        match self.axis() {
            Some((_, Sign::Negative)) => TriTri::Segment([l1, l0]),
            Some(_) => TriTri::Segment([l0, l1]),
            None => TriTri::None,
        }
    }
}

/// [`crossing`] with each triangle's points on the other's plane built as implicit
/// points and compared by their coordinates: the reference the tests hold it to.
#[cfg(test)]
fn crossing_by_points(a: &Tri, b: &Tri, sa: [Sign; 3]) -> TriTri {
    let sb = orient3d_sides(a.corners(), b.corners());
    if sb[0] != Sign::Zero && sb[0] == sb[1] && sb[1] == sb[2] {
        return TriTri::None;
    }
    // Both triangles meet the line L where the planes cross; order points along an axis
    // in which L's direction is (exactly) non-zero.
    let Some((axis, _)) = planes_line_axis(a.corners(), b.corners()) else {
        return TriTri::None; // parallel distinct planes cannot get here; stay safe
    };
    // Each triangle's points on the other's plane, the first and the last along L.
    fn ends(v: &[Option<OnPlane>; 2], axis: usize) -> Option<(&OnPlane, &OnPlane)> {
        match v {
            [Some(x), Some(y)] => Some(
                if cmp_coord_prepared(&y.point, &x.point, axis) == Ordering::Less {
                    (y, x)
                } else {
                    (x, y)
                },
            ),
            [Some(x), None] => Some((x, x)),
            _ => None,
        }
    }
    let (mut pa, mut pb) = ([None, None], [None, None]);
    on_plane(a, sa, b, &mut pa);
    on_plane(b, sb, a, &mut pb);
    let (Some((a_lo, a_hi)), Some((b_lo, b_hi))) = (ends(&pa, axis), ends(&pb, axis)) else {
        return TriTri::None;
    };
    // Overlap of the two collinear intervals: [later start, earlier end].
    let lo_from_a = cmp_coord_prepared(&a_lo.point, &b_lo.point, axis) != Ordering::Less;
    let hi_from_a = cmp_coord_prepared(&a_hi.point, &b_hi.point, axis) != Ordering::Greater;
    let lo = if lo_from_a { a_lo } else { b_lo };
    let hi = if hi_from_a { a_hi } else { b_hi };
    if cmp_coord_prepared(&lo.point, &hi.point, axis) == Ordering::Greater {
        return TriTri::None;
    }
    let label = |x: &OnPlane, from_a: bool| -> Option<Label> {
        Some(if from_a {
            Label {
                a: x.own,
                b: x.locate_in(b)?,
            }
        } else {
            Label {
                a: x.locate_in(a)?,
                b: x.own,
            }
        })
    };
    // Non-finite corners come only from a public caller's unvalidated mesh.
    let finite = || {
        a.corners()
            .iter()
            .chain(b.corners())
            .flatten()
            .all(|x| x.is_finite())
    };
    let (Some(l0), Some(l1)) = (label(lo, lo_from_a), label(hi, hi_from_a)) else {
        debug_assert!(!finite(), "an overlap end lies outside a triangle");
        return TriTri::None;
    };
    // Labels are exact and canonical (the smallest feature of each closed triangle that
    // holds the point), so distinct labels name distinct points.
    debug_assert!(
        !finite() || (l0 == l1) == same_point_prepared(&lo.point, &hi.point),
        "distinct labels name one point"
    );
    if l0 == l1 {
        TriTri::Point(l0)
    } else {
        TriTri::Segment([l0, l1])
    }
}

/// Coplanar triangles, each edge clipped to the other triangle, with the shortcut for
/// triangles on either side of the line of one of their edges ([`beside`]) on or off (off
/// only in the tests that check it against the clipping); also whether the shortcut gave
/// the answer.
pub(super) fn coplanar_filtered(a: &Tri, b: &Tri, shortcut: bool) -> (TriTri, bool) {
    let (mut segments, mut points) = (Vec::new(), Vec::new());
    let short = coplanar_pieces(a, b, shortcut, [0, 0], &mut |p| match p {
        Piece::Segment(s, _) => segments.push(s),
        Piece::Point(l) => points.push(l),
    });
    let r = if segments.is_empty() && points.is_empty() {
        TriTri::None
    } else {
        TriTri::Coplanar { segments, points }
    };
    (r, short)
}

/// [`coplanar_filtered`]'s pieces given to `f` (segments, then points), made in place.
fn coplanar_pieces(
    a: &Tri,
    b: &Tri,
    shortcut: bool,
    flat: [u8; 2],
    f: &mut impl FnMut(Piece),
) -> bool {
    // Every orientation the clipping needs, once: `a`'s edges against `b`'s corners and
    // `b`'s edges against `a`'s corners, in the projection along `b`'s axis (for clipping
    // `a`'s edges) and along `a`'s (for `b`'s). When both triangles project along the
    // same axis, the second set asks the first one's questions with the roles swapped.
    // An edge's three orientations at a time: where they put the other triangle on or
    // beyond its line, the shortcut answers without the rest.
    let side = orientation(a, b);
    let mut for_a = Orients {
        other_edges: [[Sign::Zero; 3]; 3],
        own_edges: [[Sign::Zero; 3]; 3],
    };
    for m in 0..3 {
        for_a.other_edges[m] = std::array::from_fn(|k| side(b, m, a, k));
        if shortcut && beyond(for_a.other_edges[m], b.sign()) {
            beside(b, m, a, for_a.other_edges[m], false).map(f);
            return true;
        }
    }
    let mut sign_a = None;
    for i in 0..3 {
        for_a.own_edges[i] = std::array::from_fn(|m| side(a, i, b, m));
        if shortcut {
            // a's own orientation in the projection along b's axis.
            let inward = *sign_a.get_or_insert_with(|| {
                if a.axis() == b.axis() {
                    a.sign()
                } else {
                    let [p, q, r] = a.corners();
                    orient2d_inputs(p, q, r, b.axis(), a.tri.robust_safe())
                }
            });
            if beyond(for_a.own_edges[i], inward) {
                beside(a, i, b, for_a.own_edges[i], true).map(f);
                return true;
            }
        }
    }
    let for_b = if a.axis() == b.axis() {
        Orients {
            other_edges: for_a.own_edges,
            own_edges: for_a.other_edges,
        }
    } else {
        Orients::of(b, a)
    };
    // At most one clip per edge: six segments and six points at most.
    let mut segments = Six::new([FILLER; 2]);
    let mut points = Six::new(FILLER);
    for (own, other, own_is_a, o, flat) in [
        (a, b, true, &for_a, flat[0]),
        (b, a, false, &for_b, flat[1]),
    ] {
        for i in (0..3).filter(|i| flat & 1 << i == 0) {
            match clip_edge(own, i, other, own_is_a, o) {
                Clip::None => {}
                Clip::Point(l) => points.push(l),
                Clip::Segment(mut s) => {
                    s.sort();
                    segments.push(s);
                }
            }
        }
    }
    segments.sort_dedup();
    points.sort_dedup();
    points.retain(|p| !segments.as_slice().iter().any(|s| s.contains(p)));
    coplanar_to(segments.as_slice(), points.as_slice(), f);
    false
}

/// At most six items in place: the segments or the points of one coplanar pair (each
/// triangle's three edges clipped to the other give at most one of either each).
struct Six<T: Copy> {
    len: usize,
    items: [T; 6],
}

/// A label to fill the unused places of [`Six`].
const FILLER: Label = Label {
    a: Feature::Face(0),
    b: Feature::Face(0),
};

impl<T: Copy + Ord> Six<T> {
    fn new(filler: T) -> Self {
        Six {
            len: 0,
            items: [filler; 6],
        }
    }

    fn push(&mut self, x: T) {
        // Never more than six: see the type's comment.
        self.items[self.len] = x;
        self.len += 1;
    }

    fn as_slice(&self) -> &[T] {
        &self.items[..self.len]
    }

    /// Sorted, each item once.
    fn sort_dedup(&mut self) {
        let items = &mut self.items[..self.len];
        items.sort_unstable();
        let mut kept = 0;
        for r in 0..items.len() {
            if kept == 0 || items[r] != items[kept - 1] {
                items[kept] = items[r];
                kept += 1;
            }
        }
        self.len = kept;
    }

    fn retain(&mut self, keep: impl Fn(&T) -> bool) {
        let mut kept = 0;
        for r in 0..self.len {
            if keep(&self.items[r]) {
                self.items[kept] = self.items[r];
                kept += 1;
            }
        }
        self.len = kept;
    }
}

/// Whether the corners of a triangle, with orientations `sides` against an edge of a
/// coplanar triangle whose inner side is `inward`, all lie on the edge's line or beyond.
fn beyond(sides: [Sign; 3], inward: Sign) -> bool {
    // Never zero: both triangles are non-degenerate in the projection, being exactly
    // coplanar with a triangle that is.
    debug_assert_ne!(inward, Sign::Zero);
    sides.iter().all(|s| s.times(inward) != Sign::Positive)
}

/// Coplanar triangles on either side of the line of edge `e` of `s` (`other`'s corners,
/// with orientations `sides` against it, all on the line or beyond: neighbours of one
/// surface, most coplanar candidate pairs of meshes that share faces) meet only on that
/// line, where the edge overlaps `other`'s corners or edge there. That overlap, from input
/// coordinates along the line, is the whole answer. `s_is_a`: `s` is the triangle of A.
fn beside(s: &Tri, e: usize, other: &Tri, sides: [Sign; 3], s_is_a: bool) -> Option<Piece> {
    // Positions along the line by the coordinate in which the edge is longest (exact:
    // every point here is an input point on the line, where that coordinate is monotone).
    let (e0, e1) = (e, (e + 1) % 3);
    let axis = longest_axis(&s.corners()[e0], &s.corners()[e1]);
    let at = |t: &Tri, k: usize| t.corners()[k][axis];
    let (s_lo, s_hi) = (at(s, e0).min(at(s, e1)), at(s, e0).max(at(s, e1)));
    // `other`'s corners on the line: none, one, or the two ends of an edge.
    let mut z = [0usize; 2];
    let mut n = 0;
    for (k, side) in sides.iter().enumerate() {
        // (Three would be a degenerate triangle.)
        if *side == Sign::Zero && n < 2 {
            z[n] = k;
            n += 1;
        }
    }
    let z = &z[..n];
    let (z_lo, z_hi) = match *z {
        [k] => (at(other, k), at(other, k)),
        [k, l] => (
            at(other, k).min(at(other, l)),
            at(other, k).max(at(other, l)),
        ),
        _ => return None,
    };
    let (lo, hi) = (s_lo.max(z_lo), s_hi.min(z_hi));
    if lo > hi {
        return None;
    }
    // The point at `x` on the overlap: a corner of each triangle there, else its edge
    // on the line.
    let label = |x: f64| -> Label {
        let own = [e0, e1]
            .into_iter()
            .find(|&k| at(s, k) == x)
            .map_or(edge(s.v[e0], s.v[e1]), |k| Feature::Vertex(s.v[k]));
        let there = z.iter().find(|&&k| at(other, k) == x).map_or_else(
            || edge(other.v[z[0]], other.v[z[z.len() - 1]]),
            |&k| Feature::Vertex(other.v[k]),
        );
        if s_is_a {
            Label { a: own, b: there }
        } else {
            Label { a: there, b: own }
        }
    };
    Some(if lo == hi {
        Piece::Point(label(lo))
    } else {
        let (x, y) = (label(lo), label(hi));
        Piece::Segment([x.min(y), x.max(y)], true)
    })
}

/// The orientation, projected along `other`'s axis, of corner `k` of triangle `x`
/// against edge `m` (from corner `m` to `m + 1`) of triangle `e`, for `e` and `x` the two
/// coplanar triangles `own` and `other` in either role.
fn orientation<'t>(own: &Tri, other: &Tri) -> impl Fn(&Tri, usize, &Tri, usize) -> Sign + 't {
    let proj = other.axis();
    let safe = own.tri.robust_safe() && other.tri.robust_safe();
    move |e: &Tri, m: usize, x: &Tri, k: usize| {
        orient2d_inputs(
            &e.corners()[m],
            &e.corners()[(m + 1) % 3],
            &x.corners()[k],
            proj,
            safe,
        )
    }
}

/// Orientations for clipping `own`'s edges against `other` (projected along `other`'s
/// axis): `other_edges[m][k]` of `own`'s corner `k` against `other`'s edge `m`,
/// `own_edges[i][m]` of `other`'s corner `m` against `own`'s edge `i`.
#[derive(Clone, Copy)]
struct Orients {
    other_edges: [[Sign; 3]; 3],
    own_edges: [[Sign; 3]; 3],
}

impl Orients {
    /// Every orientation for clipping `own`'s edges against `other`, each asked once.
    fn of(own: &Tri, other: &Tri) -> Orients {
        let side = orientation(own, other);
        Orients {
            other_edges: std::array::from_fn(|m| std::array::from_fn(|k| side(other, m, own, k))),
            own_edges: std::array::from_fn(|i| std::array::from_fn(|m| side(own, i, other, m))),
        }
    }
}

/// What a clipped edge keeps: nothing, one point, or a segment between two distinct
/// points (named by labels, or by candidates while clipping).
enum Clip<T> {
    None,
    Point(T),
    Segment([T; 2]),
}

impl<T> Clip<T> {
    /// The same clip with each point named by `f`.
    fn map<U>(self, mut f: impl FnMut(T) -> U) -> Clip<U> {
        match self {
            Clip::None => Clip::None,
            Clip::Point(p) => Clip::Point(f(p)),
            Clip::Segment([p, q]) => Clip::Segment([f(p), f(q)]),
        }
    }
}

/// A point where a clipped edge may start or end: corner `k` of the clipped triangle, corner
/// `m` of the other one, or where the edge crosses edge `m` of the other triangle. Small (a
/// tag and an index): the coordinates and the label are looked up when needed.
#[derive(Clone, Copy)]
enum Cand {
    Own(u8),
    Other(u8),
    Crossing(u8),
}

/// The part of edge `i` of `own` inside the coplanar triangle `other`: the first and the
/// last of the candidate points along the edge (the corners of `own` inside `other`,
/// corners of `other` on the edge, crossings with `other`'s edges), ties going to the
/// earlier candidate for the first and the later for the last.
fn clip_edge(own: &Tri, i: usize, other: &Tri, own_is_a: bool, o: &Orients) -> Clip<Label> {
    let j = (i + 1) % 3;
    let along = Along::new(own, i, other, o);
    let mut ends = Ends::default();
    edge_candidates(own, i, other, o, &along, |c| ends.add(&along, c));
    let label = |c: Cand| -> Label {
        let (own_f, other_f) = match c {
            Cand::Own(k) => {
                let k = usize::from(k);
                let at = other.locate_by(std::array::from_fn(|m| o.other_edges[m][k]));
                (
                    Feature::Vertex(own.v[k]),
                    at.expect("a candidate corner lies in the other triangle"),
                )
            }
            Cand::Other(m) => (
                edge(own.v[i], own.v[j]),
                Feature::Vertex(other.v[usize::from(m)]),
            ),
            Cand::Crossing(m) => {
                let m = usize::from(m);
                (
                    edge(own.v[i], own.v[j]),
                    edge(other.v[m], other.v[(m + 1) % 3]),
                )
            }
        };
        if own_is_a {
            Label {
                a: own_f,
                b: other_f,
            }
        } else {
            Label {
                a: other_f,
                b: own_f,
            }
        }
    };
    ends.clip(&along).map(label)
}

/// Whether edge `i` of the clipped triangle crosses edge `m` of the coplanar other one
/// (each strictly crossing the other's line), for each `m`: no point is built (the
/// crossings are ordered along the edge by orientations already known, [`Along::cmp`]).
fn edge_crossings(i: usize, o: &Orients) -> [bool; 3] {
    let j = (i + 1) % 3;
    let crosses = |s: Sign, t: Sign| s.times(t) == Sign::Negative;
    std::array::from_fn(|m| {
        let n = (m + 1) % 3;
        crosses(o.other_edges[m][i], o.other_edges[m][j])
            && crosses(o.own_edges[i][m], o.own_edges[i][n])
    })
}

/// Calls `add` with every candidate end of the part of edge `i` of `own` inside `other`:
/// `own`'s two corners where they lie in `other`, `other`'s corners strictly inside the
/// edge, then the edge's crossings with `other`'s edges.
fn edge_candidates(
    own: &Tri,
    i: usize,
    other: &Tri,
    o: &Orients,
    along: &Along,
    mut add: impl FnMut(Cand),
) {
    let j = (i + 1) % 3;
    for k in [i, j] {
        let at = other.locate_by(std::array::from_fn(|m| o.other_edges[m][k]));
        if at.is_some() {
            add(Cand::Own(k as u8));
        }
    }
    let axis = along.axis;
    let (pa, qa) = (own.corners()[i][axis], own.corners()[j][axis]);
    for m in 0..3 {
        // On the edge's line and strictly between its ends.
        let w = other.corners()[m][axis];
        if o.own_edges[i][m] == Sign::Zero && ((pa < w && w < qa) || (qa < w && w < pa)) {
            add(Cand::Other(m as u8));
        }
    }
    for (m, &x) in along.crossing.iter().enumerate() {
        if x {
            add(Cand::Crossing(m as u8));
        }
    }
}

/// The order of candidates along edge `i` of `own` (from corner `i` to `i + 1`): by
/// coordinate `axis`, exactly. Corners by their coordinates; a crossing with edge `m` of
/// `other` (strictly inside both edges) by orientations already known, no point built:
/// along the edge, a point lies before the crossing exactly when it lies on corner `i`'s
/// side of edge `m`'s line. So the edge's own corners lie on either side of every
/// crossing; a corner of `other` on the edge (never an end of edge `m`, whose ends lie
/// strictly on either side of the edge's line) lies on the inner side of edge `m`, so
/// before the crossing when corner `i` does too; and of two crossings, with edges `m`
/// and `n`, the line enters `other` through the first and leaves through the second, so
/// the crossing with `m` is the first when corner `i` lies outside edge `m`.
struct Along<'a> {
    axis: usize,
    /// Coordinate `axis` grows from corner `i` to corner `i + 1`.
    rising: bool,
    own: &'a Tri,
    other: &'a Tri,
    i: usize,
    o: &'a Orients,
    /// The edge's crossings with `other`'s edges, for [`Cand::Crossing`].
    crossing: [bool; 3],
}

impl<'a> Along<'a> {
    /// The order along edge `i` of `own` clipped to `other`, with the orientations `o`.
    fn new(own: &'a Tri, i: usize, other: &'a Tri, o: &'a Orients) -> Self {
        let [p, q] = [i, (i + 1) % 3].map(|k| &own.corners()[k]);
        // Along the edge, by its longest coordinate (non-zero: the corners differ there).
        let axis = longest_axis(p, q);
        Along {
            axis,
            rising: p[axis] < q[axis],
            own,
            other,
            i,
            o,
            crossing: edge_crossings(i, o),
        }
    }

    /// The input coordinates of a corner candidate.
    fn corner(&self, c: Cand) -> Option<&[f64; 3]> {
        match c {
            Cand::Own(k) => Some(&self.own.corners()[usize::from(k)]),
            Cand::Other(m) => Some(&self.other.corners()[usize::from(m)]),
            Cand::Crossing(_) => None,
        }
    }

    /// Whether corner `i` of the edge lies on the inner side of `other`'s edge `m`.
    fn start_inside(&self, m: u8) -> bool {
        self.o.other_edges[usize::from(m)][self.i].times(self.other.sign()) == Sign::Positive
    }

    /// The order from corner `i` to corner `i + 1` of `x` against a crossing with edge
    /// `m`.
    fn against_crossing(&self, x: Cand, m: u8) -> Ordering {
        debug_assert!(self.crossing[usize::from(m)]);
        let before = match x {
            Cand::Own(k) => usize::from(k) == self.i,
            Cand::Other(_) => self.start_inside(m),
            Cand::Crossing(n) if n == m => return Ordering::Equal,
            Cand::Crossing(n) => !self.start_inside(n),
        };
        if before {
            Ordering::Less
        } else {
            Ordering::Greater
        }
    }

    fn cmp(&self, x: Cand, y: Cand) -> Ordering {
        let axis = self.axis;
        let along = match (self.corner(x), self.corner(y), x, y) {
            // Input coordinates are finite (validated meshes): the order is total.
            (Some(p), Some(q), _, _) => {
                return p[axis].partial_cmp(&q[axis]).unwrap_or(Ordering::Equal)
            }
            (_, _, _, Cand::Crossing(m)) => self.against_crossing(x, m),
            (_, _, Cand::Crossing(m), _) => self.against_crossing(y, m).reverse(),
            _ => unreachable!("a candidate without coordinates is a crossing"),
        };
        if self.rising {
            along
        } else {
            along.reverse()
        }
    }

    /// Whether two candidates are one point: a crossing is none of the others.
    fn same(&self, x: Cand, y: Cand) -> bool {
        match (self.corner(x), self.corner(y), x, y) {
            (Some(p), Some(q), _, _) => p == q,
            (_, _, Cand::Crossing(m), Cand::Crossing(n)) => m == n,
            _ => false,
        }
    }
}

/// The first and the last candidate seen along an edge, and how many there were.
#[derive(Default)]
struct Ends {
    ends: Option<(Cand, Cand)>,
    count: usize,
}

impl Ends {
    /// Takes candidate `c`: the new first when strictly before the first, the new last
    /// when not before the last.
    fn add(&mut self, along: &Along, c: Cand) {
        self.count += 1;
        match &mut self.ends {
            None => self.ends = Some((c, c)),
            Some((first, last)) => {
                if along.cmp(c, *first) == Ordering::Less {
                    *first = c;
                }
                if along.cmp(c, *last) != Ordering::Less {
                    *last = c;
                }
            }
        }
    }

    /// The clipped edge: nothing, a point (one candidate, or first and last the same
    /// point), or the segment from the first to the last.
    fn clip(self, along: &Along) -> Clip<Cand> {
        match (self.count, self.ends) {
            (_, None) => Clip::None,
            (1, Some((only, _))) => Clip::Point(only),
            (_, Some((first, last))) => {
                if along.same(first, last) {
                    Clip::Point(first)
                } else {
                    Clip::Segment([first, last])
                }
            }
        }
    }
}

#[cfg(test)]
mod along_tests {
    use super::*;

    /// Candidates along a clipped edge, crossings included, are ordered by orientations
    /// exactly as their points are by coordinate (the crossing built as a point, the
    /// reference): triangles with corners on a lattice in one plane (z = 0, a tilted
    /// plane through lattice points; as given, at UTM coordinates, scaled down), each
    /// edge of each triangle clipped to the other, every two candidates compared.
    #[test]
    fn crossings_are_ordered_along_an_edge_as_their_points_are() {
        let mut rng = crate::test_util::Rng(0xa10c_50e7);
        let (mut with_crossings, mut two_crossings) = (0usize, 0usize);
        for round in 0..60_000 {
            let mut point = || {
                let mut next = || (rng.next() % 5) as f64;
                let (x, y) = (next(), next());
                let z = if round % 2 == 0 { 0.0 } else { x + 2.0 * y };
                match (round / 2) % 3 {
                    0 => [x, y, z],
                    1 => [x + 4.5e6, y - 3.25e6, z + 1.0e3],
                    _ => [x, y, z].map(|c| c * 2f64.powi(-30)),
                }
            };
            let (pa, pb): ([[f64; 3]; 3], [[f64; 3]; 3]) = (
                std::array::from_fn(|_| point()),
                std::array::from_fn(|_| point()),
            );
            let (Some(a), Some(b)) = (Tri::new(0, [0, 1, 2], pa), Tri::new(1, [3, 4, 5], pb))
            else {
                continue;
            };
            for (own, other) in [(&a, &b), (&b, &a)] {
                let o = Orients::of(own, other);
                for i in 0..3 {
                    let j = (i + 1) % 3;
                    let along = Along::new(own, i, other, &o);
                    let axis = along.axis;
                    let mut cands = Vec::new();
                    edge_candidates(own, i, other, &o, &along, |c| cands.push(c));
                    let at = |c: Cand| {
                        Prepared::new(match c {
                            Cand::Own(k) => Point::Explicit(own.corners()[usize::from(k)]),
                            Cand::Other(m) => Point::Explicit(other.corners()[usize::from(m)]),
                            Cand::Crossing(m) => {
                                let m = usize::from(m);
                                let c = other.corners();
                                Point::ssi(
                                    own.corners()[i],
                                    own.corners()[j],
                                    c[m],
                                    c[(m + 1) % 3],
                                    other.axis() as u8,
                                )
                            }
                        })
                    };
                    let crossings = along.crossing.iter().filter(|&&x| x).count();
                    with_crossings += usize::from(crossings > 0);
                    two_crossings += usize::from(crossings > 1);
                    for &x in &cands {
                        for &y in &cands {
                            let (px, py) = (at(x), at(y));
                            assert_eq!(
                                along.cmp(x, y),
                                cmp_coord_prepared(&px, &py, axis),
                                "{pa:?} {pb:?} edge {i}"
                            );
                            assert_eq!(along.same(x, y), same_point_prepared(&px, &py));
                        }
                    }
                }
            }
        }
        assert!(
            with_crossings > 5000 && two_crossings > 2000,
            "{with_crossings} {two_crossings}"
        );
    }
}
