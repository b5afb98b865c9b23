//! The self-arrangement: a mesh cut along where it crosses itself
//! ([`crate::intersect::self_seam`]), so that every sheet that passes through another is
//! split along the crossing and the two share its vertices and edges.
//!
//! Differences from cutting one mesh along another's seam: a seam point lies on two
//! features of the same mesh and is inserted into the triangles of both; a seam segment is
//! a constraint of both its triangles; and two constraints of one triangle can cross,
//! where three of the mesh's triangles meet: the crossing becomes a three-plane point
//! ([`Point::Tpi`]), named by the sorted triangle triple so that the three triangles share
//! one vertex, and inserted into all three (each splits its constraints there).

use crate::par::Grain;
use rayon::prelude::*;
use rustc_hash::FxHashMap;

use super::{cut_triangle, cut_triangles, reassemble, seam_edges, Arranged, SeamPoints};
use crate::edges::Roots;
use crate::intersect::{Feature, Seam};
use crate::kernel::{orient2d, orient3d_explicit, same_point, Enclosure, Point, Sign, Triangle};
use crate::Mesh;

/// Per triangle: its constraints (seam edges), each with the triangle it comes from
/// (`None` for coplanar overlaps, which cross nothing at a three-plane point).
type Sourced = FxHashMap<u32, Vec<([u32; 2], Option<u32>)>>;

/// Cuts `mesh` along its own seam `seam` (from [`crate::intersect::self_seam`] on the
/// same mesh). Degenerate coincidences (four planes through one point, a crossing exactly
/// at another seam point) may leave triangles that do not share a vertex where they
/// should; such triangles are kept uncut and listed in [`Arranged::failed`] when their
/// re-triangulation fails.
pub fn arrange_self(mesh: &Mesh, seam: &Seam) -> Arranged {
    match weld_seam_vertices(mesh, seam) {
        Some((welded, seam)) => arrange_welded(&welded, &seam),
        None => arrange_welded(mesh, seam),
    }
}

/// [`arrange_self`] of a mesh with no two seam vertices at one position.
fn arrange_welded(mesh: &Mesh, seam: &Seam) -> Arranged {
    let mut points = index_own_points(mesh, seam);
    let seam_edges = seam_edges(seam, &points.seam_vertex);
    let mut with_other: Sourced = FxHashMap::default();
    // Each triangle's coplanar partners (sorted, unique).
    let mut partners: FxHashMap<u32, Vec<u32>> = FxHashMap::default();
    for src in &seam.sources {
        let e = seam_edges[src.segment as usize];
        for (t, o) in [(src.tri_a, src.tri_b), (src.tri_b, src.tri_a)] {
            // The triangle a segment crosses `t` with, where one does: a segment found
            // both by a coplanar pair and by a crossing one (an edge of a face shared
            // with `t`) crosses with the latter.
            let other = (!coplanar(mesh, t, o)).then_some(o);
            if other.is_none() {
                partners.entry(t).or_default().push(o);
            }
            let list = with_other.entry(t).or_default();
            match list.iter_mut().find(|(x, _)| *x == e) {
                Some(known) => {
                    known.1 = known.1.or(other);
                }
                None => list.push((e, other)),
            }
        }
    }
    add_crossings(mesh, &mut points, &with_other);
    add_coplanar_edge_points(mesh, &mut points, partners);
    // One vertex per point: the same point named by different features (on a line where
    // two coplanar faces meet a third, on four planes) or made again as a three-plane
    // point.
    let canon = merge_equal_points(mesh, &mut points);
    let seam_edges: Vec<[u32; 2]> = seam_edges
        .into_iter()
        .map(|[a, b]| {
            let (a, b) = (canon(a), canon(b));
            [a.min(b), a.max(b)]
        })
        .collect();
    let constraints: super::Constraints = with_other
        .into_iter()
        .map(|(t, list)| {
            // In their order (which the triangulation follows), each once.
            let mut cons = super::List::with_capacity(list.len());
            for ([a, b], _) in list {
                let (a, b) = (canon(a), canon(b));
                let e = [a.min(b), a.max(b)];
                if a != b && !cons.contains(&e) {
                    cons.push(e);
                }
            }
            (t, cons)
        })
        .collect();
    let cut = cut_triangles(mesh, &points, &constraints, None);
    let results: Vec<_> = cut
        .par_iter()
        .grained()
        .map_init(super::Scratch::default, |s, &t| {
            (t, cut_triangle(mesh, t, &points, &constraints, s))
        })
        .collect();
    Arranged::assemble(points, seam_edges, reassemble(mesh, results))
}

/// Input vertices of the seam at exactly the same position (the copies of a part given
/// twice, parts touching at corners they do not share): each replaced by the lowest id
/// among them in the triangles and in the seam, so that the arrangement gives the point
/// one vertex and the sheets through it share their edges there, as the sheets of a
/// crossing do. `None` where no two coincide (the usual case, nothing copied).
fn weld_seam_vertices(mesh: &Mesh, seam: &Seam) -> Option<(Mesh, Seam)> {
    let mut ids: Vec<u32> = Vec::new();
    let mut add = |f: Feature| match f {
        Feature::Vertex(v) => ids.push(v),
        Feature::Edge(u, v) => ids.extend([u, v]),
        Feature::Face(_) => {}
    };
    for l in &seam.points {
        add(l.a);
        add(l.b);
    }
    for &(v, f) in &seam.vertex_on {
        add(Feature::Vertex(v));
        add(f);
    }
    // The seam names a point by one of the vertices there: the corners of the triangles
    // it cuts are the others.
    for src in &seam.sources {
        for t in [src.tri_a, src.tri_b] {
            ids.extend(mesh.triangles[t as usize]);
        }
    }
    // Adding zero makes -0.0 equal to 0.0 under the total order.
    let key = |v: u32| mesh.positions[v as usize].map(|x| x + 0.0);
    let order = |a: &u32, b: &u32| {
        let (p, q) = (key(*a), key(*b));
        (0..3)
            .map(|k| p[k].total_cmp(&q[k]))
            .find(|o| o.is_ne())
            .unwrap_or(std::cmp::Ordering::Equal)
            .then(a.cmp(b))
    };
    // Each vertex once (most appear in many seam points and triangles), then by position.
    let mut seen = vec![false; mesh.positions.len()];
    ids.retain(|&v| !std::mem::replace(&mut seen[v as usize], true));
    ids.par_sort_unstable_by(order);
    let mut canon: FxHashMap<u32, u32> = FxHashMap::default();
    for same in ids.chunk_by(|&a, &b| key(a) == key(b)) {
        canon.extend(same[1..].iter().map(|&v| (v, same[0])));
    }
    if canon.is_empty() {
        return None;
    }
    let c = |v: u32| canon.get(&v).copied().unwrap_or(v);
    let feature = |f: Feature| match f {
        Feature::Vertex(v) => Feature::Vertex(c(v)),
        Feature::Edge(u, v) => crate::intersect::tritri::edge(c(u), c(v)),
        Feature::Face(t) => Feature::Face(t),
    };
    let mut welded = mesh.clone();
    for t in &mut welded.triangles {
        *t = t.map(c);
    }
    let mut seam = seam.clone();
    for l in &mut seam.points {
        l.a = feature(l.a);
        l.b = feature(l.b);
    }
    for (v, f) in &mut seam.vertex_on {
        *v = c(*v);
        *f = feature(*f);
    }
    seam.vertex_on.sort_unstable();
    seam.vertex_on.dedup();
    Some((welded, seam))
}

/// Whether triangles `t` and `o` of `mesh` lie in one plane (exact).
pub(crate) fn coplanar(mesh: &Mesh, t: u32, o: u32) -> bool {
    let [a, b, c] = mesh.corners(t as usize);
    mesh.corners(o as usize)
        .iter()
        .all(|d| orient3d_explicit(&a, &b, &c, d) == Sign::Zero)
}

/// Gives exactly equal points one vertex: each added vertex equal to an input vertex of
/// the seam, or to an added vertex of lower id, is replaced by it in `points`' lists of
/// the points on faces and edges and in its seam vertices (the replaced vertex stays,
/// unused). Candidates are found by their approximate positions (sorted along x, within
/// a relative 1e-9 on every axis) and compared exactly. Returns the replacement of every
/// vertex id (itself where kept).
fn merge_equal_points(mesh: &Mesh, points: &mut SeamPoints) -> impl Fn(u32) -> u32 {
    let n = points.positions.len();
    let first_added = points.input_vertices as u32;
    // The input vertices that are seam points, and every added vertex, along x (the
    // copies of an id next to each other).
    let pos = &points.positions;
    let mut ids: Vec<u32> = points
        .seam_vertex
        .iter()
        .copied()
        .filter(|&v| v < first_added)
        .chain(first_added..n as u32)
        .collect();
    ids.par_sort_unstable_by(|&a, &b| {
        pos[a as usize][0]
            .total_cmp(&pos[b as usize][0])
            .then(a.cmp(&b))
    });
    ids.dedup();
    let near = |a: &[f64; 3], b: &[f64; 3], k: usize| {
        (a[k] - b[k]).abs() <= 1e-9 * (1.0 + a[k].abs().max(b[k].abs()))
    };
    // The lowest id stays the root (an input vertex before any added one).
    let mut roots = Roots::new(n);
    let mut merged = false;
    for i in 0..ids.len() {
        let a = ids[i];
        let pa = pos[a as usize];
        for &b in &ids[i + 1..] {
            let pb = pos[b as usize];
            if !near(&pa, &pb, 0) {
                break;
            }
            if near(&pa, &pb, 1)
                && near(&pa, &pb, 2)
                && same_point(&points.exact(mesh, a), &points.exact(mesh, b))
            {
                roots.join(a, b);
                merged = true;
            }
        }
    }
    let canon: Vec<u32> = if merged {
        (0..n as u32).map(|v| roots.find(v)).collect()
    } else {
        Vec::new()
    };
    if merged {
        let map = |list: &mut super::List<u32>| {
            for v in list.iter_mut() {
                *v = canon[*v as usize];
            }
            list.sort_unstable();
            list.dedup();
        };
        points.on_face.values_mut().for_each(map);
        points.on_edge.values_mut().for_each(map);
        for v in &mut points.seam_vertex {
            *v = canon[*v as usize];
        }
    }
    move |v: u32| canon.get(v as usize).copied().unwrap_or(v)
}

/// Every seam point as a vertex: an input vertex as itself, any other point new, noted on
/// both features of the mesh it lies on.
fn index_own_points(mesh: &Mesh, seam: &Seam) -> SeamPoints {
    let mut points = SeamPoints {
        positions: mesh.positions.clone(),
        input_vertices: mesh.positions.len(),
        added: Vec::new(),
        enclosed: Vec::new(),
        on_face: FxHashMap::default(),
        on_edge: FxHashMap::default(),
        seam_vertex: Vec::with_capacity(seam.points.len()),
    };
    for (s, l) in seam.points.iter().enumerate() {
        if let Feature::Vertex(v) = l.a {
            points.seam_vertex.push(v);
            continue;
        }
        let id = points.positions.len() as u32;
        points.positions.push(seam.positions[s]);
        points.added.push(seam.exact[s].clone());
        points.enclosed.push(seam.enclosure(s));
        for (k, f) in [l.a, l.b].into_iter().enumerate() {
            if k == 1 && f == l.a {
                break;
            }
            match f {
                Feature::Face(t) => points.on_face.entry(t).or_default().push(id),
                Feature::Edge(u, v) => points.on_edge.entry((u, v)).or_default().push(id),
                Feature::Vertex(_) => {}
            }
        }
        points.seam_vertex.push(id);
    }
    // A vertex on another triangle's edge or face is a point of that feature too.
    for &(v, f) in &seam.vertex_on {
        match f {
            Feature::Face(t) => points.on_face.entry(t).or_default().push(v),
            Feature::Edge(u, w) => points.on_edge.entry((u, w)).or_default().push(v),
            Feature::Vertex(_) => {}
        }
    }
    points
}

/// Inserts into the face of each triangle `t` the seam points on the edges of its coplanar
/// `partners` that lie strictly inside it. Where such an edge runs inside `t` it bounds
/// their overlap, a constraint of `t`; another constraint crosses it at the point where
/// the edge meets the other's triangle, a seam point of that pair (no three-plane point
/// names it, as no crossing triangle bounds the overlap), which `t` must have too.
fn add_coplanar_edge_points(
    mesh: &Mesh,
    points: &mut SeamPoints,
    partners: FxHashMap<u32, Vec<u32>>,
) {
    let found: Vec<(u32, Vec<u32>)> = partners
        .into_par_iter()
        .filter_map(|(t, mut others)| {
            others.sort_unstable();
            others.dedup();
            let shape = Triangle::new(mesh.corners(t as usize))?;
            let axis = shape.axis();
            let corners = mesh.corners(t as usize).map(Point::Explicit);
            let mut inside = Vec::new();
            for o in others {
                let [a, b, c] = mesh.triangles[o as usize];
                for (u, v) in [(a, b), (b, c), (c, a)] {
                    let Some(list) = points.on_edge.get(&(u.min(v), u.max(v))) else {
                        continue;
                    };
                    for &p in list {
                        let q = points.exact(mesh, p);
                        let strictly = (0..3).all(|i| {
                            orient2d(&corners[i], &corners[(i + 1) % 3], &q, axis) == shape.sign()
                        });
                        if strictly {
                            inside.push(p);
                        }
                    }
                }
            }
            (!inside.is_empty()).then_some((t, inside))
        })
        .collect();
    for (t, inside) in found {
        let list = points.on_face.entry(t).or_default();
        list.extend(inside);
        list.sort_unstable();
        list.dedup();
    }
}

/// A box that holds vertex `v`'s exact point: its position for an input vertex, its
/// enclosure for an added one (everything where it has none).
fn point_box(points: &SeamPoints, v: u32) -> [[f64; 2]; 3] {
    let v = v as usize;
    if v < points.input_vertices {
        return points.positions[v].map(|c| [c, c]);
    }
    points.enclosed[v - points.input_vertices]
        .as_ref()
        .and_then(|e| e.bounds())
        .unwrap_or([[f64::NEG_INFINITY, f64::INFINITY]; 3])
}

/// Finds, in every triangle, the constraints that cross each other in their interiors;
/// each crossing becomes a three-plane point shared by the three triangles, inserted in
/// their faces.
fn add_crossings(mesh: &Mesh, points: &mut SeamPoints, cons: &Sourced) {
    let exact = |v: u32| points.exact(mesh, v);
    let mut triples: Vec<[u32; 3]> = cons
        .par_iter()
        .filter(|(_, list)| list.len() > 1)
        .flat_map_iter(|(&t, list)| {
            let mut found = Vec::new();
            let Some(shape) = Triangle::new(mesh.corners(t as usize)) else {
                return found;
            };
            let axis = shape.axis();
            let ends: Vec<[Point; 2]> = list.iter().map(|(e, _)| e.map(exact)).collect();
            // Pairs whose boxes in the projection overlap (boxes certain to hold the exact
            // points), by a sweep along the first of the two coordinates: a triangle
            // crossed by thousands of constraints is not tested pair by pair.
            let (x, y) = ((axis + 1) % 3, (axis + 2) % 3);
            let boxes: Vec<[[f64; 2]; 2]> = list
                .iter()
                .map(|([a, b], _)| {
                    let (p, q) = (point_box(points, *a), point_box(points, *b));
                    [x, y].map(|k| [p[k][0].min(q[k][0]), p[k][1].max(q[k][1])])
                })
                .collect();
            let mut order: Vec<usize> = (0..list.len()).collect();
            order.sort_unstable_by(|&i, &j| boxes[i][0][0].total_cmp(&boxes[j][0][0]));
            let mut candidates = Vec::new();
            for (n, &i) in order.iter().enumerate() {
                for &j in &order[n + 1..] {
                    if boxes[j][0][0] > boxes[i][0][1] {
                        break;
                    }
                    if boxes[j][1][0] <= boxes[i][1][1] && boxes[i][1][0] <= boxes[j][1][1] {
                        candidates.push((i.min(j), i.max(j)));
                    }
                }
            }
            for (i, j) in candidates {
                let ((e, Some(u)), (f, Some(w))) = (list[i], list[j]) else {
                    continue;
                };
                if u == w || e.iter().any(|v| f.contains(v)) {
                    continue;
                }
                let ([p, q], [r, s]) = (&ends[i], &ends[j]);
                let apart = |a: &Point, b: &Point, c: &Point, d: &Point| {
                    orient2d(a, b, c, axis).times(orient2d(a, b, d, axis)) == Sign::Negative
                };
                if apart(p, q, r, s) && apart(r, s, p, q) {
                    let mut tri = [t, u, w];
                    tri.sort_unstable();
                    found.push(tri);
                }
            }
            found
        })
        .collect();
    triples.par_sort_unstable();
    triples.dedup();
    for tri in triples {
        let id = points.positions.len() as u32;
        let planes = tri.map(|t| mesh.corners(t as usize));
        let p = Point::Tpi(Box::new(planes));
        let e = Enclosure::of(&p);
        points.positions.push(p.approx_within(&e));
        points.added.push(p);
        points.enclosed.push(Some(e));
        for t in tri {
            points.on_face.entry(t).or_default().push(id);
        }
    }
}
