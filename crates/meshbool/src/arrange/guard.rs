//! The sliver guard: interior points for a large triangle cut by a dense seam.
//!
//! A triangle whose seam is many short segments (a floor crossed by a fine fence) can
//! only be cut into needles from its own corners to the seam's points: nothing else lies
//! in it. With the guard, such a triangle gets a lattice of points inside it, kept clear
//! of its edges and of the seam, so that the pieces near the seam are about as wide as
//! the seam's segments are long and those farther out about as wide as the lattice's
//! step. Each point is exactly in the triangle's plane: it is where a short segment
//! through the lattice position, across the plane, meets it ([`Point::Lpi`]), so the
//! arrangement's predicates decide it exactly as they decide seam points. The points are
//! the mesh's own (not the other mesh's), inside one face: the arrangement stays
//! conforming along the seam.

use super::{Constraints, SeamPoints};
use crate::kernel::{orient3d_explicit, Point, Sign};
use crate::Mesh;

/// Seam points a triangle must hold before the guard looks at it: fewer give few needles.
pub const GUARD_FROM_POINTS: usize = 16;

/// The guard adds points only to a triangle whose inradius is at least this many times
/// the mean length of its seam segments (a triangle about as small as the seam's
/// segments is cut into pieces of that size anyway).
const GIANT: f64 = 4.0;

/// At most this many interior points per seam point of the triangle.
const POINTS_PER_SEAM_POINT: f64 = 4.0;

/// Adds interior points to the triangles of `mesh` that a dense seam cuts (see the module
/// documentation), but for those in `skip` (coplanar with the other mesh: their pieces
/// must match the other's): a lattice on the face, and points along the triangle's edges
/// at the same step (on an edge, for every triangle of that edge). True when it added
/// points on edges.
pub(super) fn add_interior_points(
    mesh: &Mesh,
    points: &mut SeamPoints,
    cons: &Constraints,
    skip: &rustc_hash::FxHashSet<u32>,
) -> bool {
    let mut cut: Vec<u32> = cons.keys().copied().filter(|t| !skip.contains(t)).collect();
    cut.sort_unstable();
    let mut done_edges = rustc_hash::FxHashSet::default();
    let mut on_edges = false;
    for t in cut {
        let segs = &cons[&t];
        let Some(plan) = plan_for(mesh, t, segs, &points.positions) else {
            continue;
        };
        for s in lattice(mesh, t, &plan) {
            let id = points.positions.len() as u32;
            points.positions.push(s.position);
            points.added.push(s.exact);
            points.enclosed.push(None);
            points.on_face.entry(t).or_default().push(id);
        }
        let tri = mesh.triangles[t as usize];
        for k in 0..3 {
            let (u, v) = (tri[k], tri[(k + 1) % 3]);
            let key = (u.min(v), u.max(v));
            if !done_edges.insert(key) {
                continue;
            }
            let taken: Vec<[f64; 3]> = points
                .on_edge
                .get(&key)
                .map(|l| l.iter().map(|&g| points.positions[g as usize]).collect())
                .unwrap_or_default();
            for s in along_edge(mesh, key, &plan, &taken) {
                let id = points.positions.len() as u32;
                points.positions.push(s.position);
                points.added.push(s.exact);
                points.enclosed.push(None);
                points.on_edge.entry(key).or_default().push(id);
                on_edges = true;
            }
        }
    }
    on_edges
}

/// How a triangle is guarded: the lattice step, the clearance kept from the seam, and
/// the seam's segments (positions).
struct Plan {
    step: f64,
    clear: f64,
    seam: Vec<[[f64; 3]; 2]>,
}

/// Points along input edge `key` (vertex ids, lower first) at about `plan.step` apart,
/// clear of the seam and of the points `taken` already on it; each exactly on the edge:
/// where the edge crosses a plane across it through the point ([`Point::Lpi`]).
fn along_edge(mesh: &Mesh, key: (u32, u32), plan: &Plan, taken: &[[f64; 3]]) -> Vec<Interior> {
    let (u, v) = (
        mesh.positions[key.0 as usize],
        mesh.positions[key.1 as usize],
    );
    let d = sub(v, u);
    let len = norm(d);
    let k = (len / plan.step).floor() as usize;
    if !(2..=1 << 12).contains(&k) {
        return Vec::new();
    }
    let e = [d[0] / len, d[1] / len, d[2] / len];
    // Two directions across the edge: a plane through the point, transversal to it.
    let any = if e[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let w1 = cross(e, any);
    let w1 = [
        w1[0] / norm(w1) * len,
        w1[1] / norm(w1) * len,
        w1[2] / norm(w1) * len,
    ];
    let w2 = cross(e, w1);
    let w2 = [
        w2[0] / norm(w2) * len,
        w2[1] / norm(w2) * len,
        w2[2] / norm(w2) * len,
    ];
    let mut out = Vec::new();
    for j in 1..k {
        let f = j as f64 / k as f64;
        let s = [u[0] + f * d[0], u[1] + f * d[1], u[2] + f * d[2]];
        if plan
            .seam
            .iter()
            .any(|&[p, q]| to_segment(s, p, q) < plan.clear)
            || taken.iter().any(|&p| norm(sub(s, p)) < plan.clear)
        {
            continue;
        }
        let (a, b, c) = (
            s,
            [s[0] + w1[0], s[1] + w1[1], s[2] + w1[2]],
            [s[0] + w2[0], s[1] + w2[1], s[2] + w2[2]],
        );
        let (su, sv) = (
            orient3d_explicit(&a, &b, &c, &u),
            orient3d_explicit(&a, &b, &c, &v),
        );
        if su == Sign::Zero || sv == Sign::Zero || su == sv {
            continue;
        }
        out.push(Interior {
            position: s,
            exact: Point::Lpi {
                p: u,
                q: v,
                a,
                b,
                c,
            },
        });
    }
    out
}

/// An interior point: where it is stored (its lattice position) and what it is exactly.
struct Interior {
    position: [f64; 3],
    exact: Point,
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// The distance from `p` to the segment `a b`.
fn to_segment(p: [f64; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let d = sub(b, a);
    let len2 = dot(d, d);
    let t = if len2 > 0.0 {
        (dot(sub(p, a), d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    norm(sub(p, [a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]]))
}

/// How triangle `t` (its seam segments `segs`, vertex ids into `positions`) is guarded;
/// `None` unless its seam is dense (at least [`GUARD_FROM_POINTS`] points) and the triangle
/// large against its segments ([`GIANT`]). Placement is a matter of shape only (floating
/// point); every point placed is checked exactly to be a valid construction.
fn plan_for(mesh: &Mesh, t: u32, segs: &[[u32; 2]], positions: &[[f64; 3]]) -> Option<Plan> {
    let mut ends: Vec<u32> = segs.iter().flatten().copied().collect();
    ends.sort_unstable();
    ends.dedup();
    if ends.len() < GUARD_FROM_POINTS {
        return None;
    }
    let [a, b, c] = mesh.corners(t as usize);
    let twice_area = norm(cross(sub(b, a), sub(c, a)));
    let perimeter = norm(sub(b, a)) + norm(sub(c, b)) + norm(sub(a, c));
    if !(twice_area > 0.0 && perimeter > 0.0) {
        return None;
    }
    let spacing = segs
        .iter()
        .map(|&[u, v]| norm(sub(positions[u as usize], positions[v as usize])))
        .sum::<f64>()
        / segs.len() as f64;
    if !(spacing > 0.0 && twice_area / perimeter >= GIANT * spacing) {
        return None;
    }
    // The lattice's step: three segment lengths, wider where that many would be more than
    // POINTS_PER_SEAM_POINT per seam point.
    let most = POINTS_PER_SEAM_POINT * ends.len() as f64;
    let step = (3.0 * spacing).max((0.5 * twice_area / most).sqrt());
    let seam = segs
        .iter()
        .map(|&[u, v]| [positions[u as usize], positions[v as usize]])
        .collect();
    Some(Plan {
        step,
        clear: 1.5 * spacing,
        seam,
    })
}

/// The interior points of triangle `t` under `plan`: a lattice at `plan.step`, half a
/// step clear of the triangle's edges and `plan.clear` of its seam.
fn lattice(mesh: &Mesh, t: u32, plan: &Plan) -> Vec<Interior> {
    let [a, b, c] = mesh.corners(t as usize);
    let n = cross(sub(b, a), sub(c, a));
    let twice_area = norm(n);
    let edges = [norm(sub(b, a)), norm(sub(c, b)), norm(sub(a, c))];
    let step = plan.step;
    let longest = edges.iter().fold(0.0f64, |m, &e| m.max(e));
    let m = (longest / step).ceil().max(2.0) as usize;
    if m > 1 << 12 {
        return Vec::new();
    }
    // Altitudes onto the edges opposite a, b and c, for the lattice points' distances
    // to them.
    let altitude = [
        twice_area / edges[1],
        twice_area / edges[2],
        twice_area / edges[0],
    ];
    let unit = [n[0] / twice_area, n[1] / twice_area, n[2] / twice_area];
    let mut out = Vec::new();
    for i in 1..m {
        for j in 1..m - i {
            // Barycentric (1 − u − v, u, v) on the corners a, b, c.
            let (u, v) = (i as f64 / m as f64, j as f64 / m as f64);
            let w = 1.0 - u - v;
            if w * altitude[0] < 0.5 * step
                || u * altitude[1] < 0.5 * step
                || v * altitude[2] < 0.5 * step
            {
                continue;
            }
            let s = [
                w * a[0] + u * b[0] + v * c[0],
                w * a[1] + u * b[1] + v * c[1],
                w * a[2] + u * b[2] + v * c[2],
            ];
            if plan
                .seam
                .iter()
                .any(|&[p, q]| to_segment(s, p, q) < plan.clear)
            {
                continue;
            }
            // A segment across the plane through `s`, as long as the triangle is wide.
            let p = [
                s[0] - longest * unit[0],
                s[1] - longest * unit[1],
                s[2] - longest * unit[2],
            ];
            let q = [
                s[0] + longest * unit[0],
                s[1] + longest * unit[1],
                s[2] + longest * unit[2],
            ];
            let (sp, sq) = (
                orient3d_explicit(&a, &b, &c, &p),
                orient3d_explicit(&a, &b, &c, &q),
            );
            if sp == Sign::Zero || sq == Sign::Zero || sp == sq {
                continue;
            }
            out.push(Interior {
                position: s,
                exact: Point::Lpi { p, q, a, b, c },
            });
        }
    }
    out
}
