//! Arrangement: every triangle cut by the seam is re-triangulated in its own plane with its
//! seam points and seam segments as constraints, so that both meshes become conforming
//! along the seam: one vertex per seam point, shared (by number within each mesh, by exact
//! position across the two), and every seam segment an edge of both.
//!
//! Pipeline position: after [`crate::intersect`], before classification. Seam points on a
//! triangle's edge are inserted into both triangles of that edge, so no T-junctions appear.

use crate::par::Grain;
use rayon::prelude::*;
use rustc_hash::FxHashMap;

use crate::intersect::{Feature, Seam, Source};
use crate::kernel::{orient2d_inputs, robust_safe, Enclosure, Point, Prepared, Sign, Triangle};
use crate::Mesh;

mod guard;
mod local;
mod own;

pub use own::arrange_self;
pub(crate) use own::coplanar;

/// Why a cut triangle could not be re-triangulated (the inputs broke an assumption of the
/// arrangement, as a self-intersecting mesh does); the triangle is then kept whole.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FailReason {
    /// The triangle has zero area.
    DegenerateTriangle,
    /// A seam segment ends outside the triangle.
    ConstraintEndOutside,
    /// Walking to a seam point's triangle did not end.
    PointLocationDidNotConverge,
    /// A seam point lies outside its triangle.
    PointOutside,
    /// The triangulation met a zero-area triangle.
    DegenerateInTriangulation,
    /// Two seam segments cross each other.
    ConstraintsCross,
    /// Inserting a seam segment did not end.
    ConstraintInsertionDidNotConverge,
    /// A seam segment is not an edge after its insertion.
    ConstraintMissing,
}

impl std::fmt::Display for FailReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            FailReason::DegenerateTriangle => "degenerate triangle",
            FailReason::ConstraintEndOutside => "constraint end not in the triangle",
            FailReason::PointLocationDidNotConverge => "point location did not converge",
            FailReason::PointOutside => "point outside its triangle",
            FailReason::DegenerateInTriangulation => "degenerate triangle in the triangulation",
            FailReason::ConstraintsCross => "a constraint crosses another constraint",
            FailReason::ConstraintInsertionDidNotConverge => {
                "constraint insertion did not converge"
            }
            FailReason::ConstraintMissing => "constraint missing after insertion",
        })
    }
}

/// One mesh cut along the seam.
#[derive(Clone, Debug, Default)]
pub struct Arranged {
    /// The conforming mesh: the input vertices first (same ids), then one vertex per seam
    /// point that is not an input vertex of this mesh (approximate coordinates).
    pub mesh: Mesh,
    /// Vertices below this id are the input's (exact as they are); the others were added
    /// for seam points.
    pub input_vertices: usize,
    /// The exact point of every added vertex: vertex `input_vertices + i` is
    /// `added_points[i]` (see [`Arranged::point`]).
    pub added_points: Vec<Point>,
    /// For every output triangle, the input triangle it is part of.
    pub parent: Vec<u32>,
    /// For every seam point, its vertex in [`Arranged::mesh`].
    pub seam_vertex: Vec<u32>,
    /// The seam segments as vertex pairs `[lo, hi]` of [`Arranged::mesh`] (sorted), each
    /// an edge of the mesh.
    pub seam_edges: Vec<[u32; 2]>,
    /// Input triangles that could not be re-triangulated, with the reason (inconsistent
    /// input, such as a self-intersecting mesh), kept uncut; empty for valid inputs.
    pub failed: Vec<(u32, FailReason)>,
    /// Triangles of [`Arranged::mesh`] (sorted ids) that are correct with their exact
    /// points but, with seam points rounded to `f64` coordinates, turn over or collapse
    /// in their input triangle's plane (a sliver thinner than the rounding): the output
    /// is only as exact as `f64` coordinates allow there.
    pub rounding_flips: Vec<u32>,
    /// The projection of every re-triangulated input triangle, sorted by triangle: the
    /// coordinate its [`Triangle`] drops and its orientation there, for the
    /// classification's tests in the planes of these triangles ([`Arranged::projection`]).
    pub(crate) projections: Vec<(u32, Projection)>,
}

/// A triangle's projection: the coordinate dropped ([`Triangle::axis`]) and the
/// triangle's orientation there ([`Triangle::sign`]).
pub(crate) type Projection = (u8, Sign);

impl Arranged {
    /// The projection of input triangle `t` when the arrangement re-triangulated it (as
    /// [`Triangle::new`] of its corners gives it); `None` for the others.
    pub(crate) fn projection(&self, t: u32) -> Option<(usize, Sign)> {
        let i = self
            .projections
            .binary_search_by_key(&t, |&(u, _)| u)
            .ok()?;
        let (axis, sign) = self.projections[i].1;
        Some((usize::from(axis), sign))
    }

    /// [`Arranged::point`] without copying an added vertex's point (those of seam points
    /// are large).
    pub(crate) fn point_ref(&self, v: u32) -> std::borrow::Cow<'_, Point> {
        let v = v as usize;
        match v.checked_sub(self.input_vertices) {
            Some(i) => std::borrow::Cow::Borrowed(&self.added_points[i]),
            None => std::borrow::Cow::Owned(Point::Explicit(self.mesh.positions[v])),
        }
    }

    /// The exact point of vertex `v`.
    pub fn point(&self, v: u32) -> Point {
        self.point_ref(v).into_owned()
    }
}

/// Cuts `mesh` (side `side` of `seam`) along the seam. `mesh` must be the mesh the seam was
/// computed from on that side.
#[cfg(test)]
pub fn arrange(mesh: &Mesh, seam: &Seam, side: Source) -> Arranged {
    arrange_with(mesh, seam, side, false)
}

/// [`arrange`], with the sliver guard where `sliver_guard` asks for it: a large triangle
/// cut by a dense seam (at least 16 seam points, its inradius at least 4 of its seam
/// segments) gets points inside it and along its edges, clear of the seam, so that its
/// pieces are not needles from its corners. The added points are vertices of this mesh
/// only (inside one face, or on an edge and then in both of its triangles), after the
/// seam points.
pub fn arrange_with(mesh: &Mesh, seam: &Seam, side: Source, sliver_guard: bool) -> Arranged {
    let mut points = index_seam_points(mesh, seam, side);
    let seam_edges = seam_edges(seam, &points.seam_vertex);
    let constraints = constraints(seam, side, &seam_edges);
    let mut edges_guarded = false;
    if sliver_guard {
        // Triangles coplanar with the other mesh keep the pieces the other's match.
        let coplanar: rustc_hash::FxHashSet<u32> = seam
            .sources
            .iter()
            .filter(|s| seam.segments[s.segment as usize].coplanar)
            .map(|s| match side {
                Source::A => s.tri_a,
                Source::B => s.tri_b,
            })
            .collect();
        edges_guarded = guard::add_interior_points(mesh, &mut points, &constraints, &coplanar);
    }
    // Points the guard put on edges reach triangles the seam's candidates may not name
    // (a guarded triangle's neighbour): then every triangle is looked at.
    let near = seam
        .near
        .as_ref()
        .filter(|_| !edges_guarded)
        .map(|n| match side {
            Source::A => &n[0][..],
            Source::B => &n[1][..],
        });
    let cut = cut_triangles(mesh, &points, &constraints, near);
    let results: Vec<(u32, CutResult)> = cut
        .par_iter()
        .grained()
        .map_init(Lent::take, |s, &t| {
            (t, cut_triangle(mesh, t, &points, &constraints, &mut s.0))
        })
        .collect();
    Arranged::assemble(points, seam_edges, reassemble(mesh, results))
}

/// Memory that [`cut_triangle`] reuses from one triangle to the next (one per parallel
/// task): most cut triangles hold a few points, and allocating their triangulation's
/// arrays for each was a good part of the arrangement of small inputs.
#[derive(Default)]
pub(crate) struct Scratch {
    local: Option<local::Local>,
    mine: Vec<(u32, Option<usize>)>,
    to_local: Vec<(u32, u32)>,
    ids: Vec<u32>,
    chains: Chains,
}

/// A [`Scratch`] kept for the next task on a thread up to this many points (the room
/// of its triangulation): a few hundred kilobytes a thread at most, while a triangle
/// crossed by a fine mesh (thousands of points) frees its arrays.
const KEEP_UP_TO: usize = 1024;

thread_local! {
    /// The scratch a thread's last arrangement task left ([`Lent`]).
    static KEPT: std::cell::Cell<Option<Scratch>> = const { std::cell::Cell::new(None) };
}

/// A [`Scratch`] lent by the thread's kept one, given back to the thread that drops it: a
/// boolean on small inputs, one arrangement task per mesh, finds its arrays already grown
/// by the call before (their allocation and growth were a tenth of a two-cube boolean's
/// arrangement).
struct Lent(Scratch);

impl Lent {
    fn take() -> Lent {
        Lent(KEPT.take().unwrap_or_default())
    }
}

impl Drop for Lent {
    fn drop(&mut self) {
        let s = std::mem::take(&mut self.0);
        if s.local.as_ref().is_none_or(|l| l.room() <= KEEP_UP_TO) {
            // (A thread being torn down has no slot left: the scratch is dropped.)
            let _ = KEPT.try_with(|k| k.set(Some(s)));
        }
    }
}

impl Arranged {
    /// The arranged mesh from the seam points' vertices and the reassembled triangles.
    fn assemble(points: SeamPoints, seam_edges: Vec<[u32; 2]>, out: Reassembled) -> Arranged {
        Arranged {
            mesh: Mesh::new_unchecked(points.positions, out.triangles),
            input_vertices: points.input_vertices,
            added_points: points.added,
            parent: out.parent,
            seam_vertex: points.seam_vertex,
            seam_edges,
            failed: out.failed,
            rounding_flips: out.rounding_flips,
            projections: out.projections,
        }
    }
}

/// A short list kept in place (most triangles and edges hold a few seam points and seam
/// edges): no allocation per entry of the maps below.
type List<T> = smallvec::SmallVec<[T; 4]>;

/// Per input triangle, its constraints: the seam edges in it, in order.
type Constraints = FxHashMap<u32, List<[u32; 2]>>;

/// The seam points as vertices of one mesh ([`index_seam_points`]).
struct SeamPoints {
    /// The input positions, then one per added vertex.
    positions: Vec<[f64; 3]>,
    /// Number of input vertices: added vertices start here.
    input_vertices: usize,
    /// The exact point of every added vertex.
    added: Vec<Point>,
    /// Its enclosures when the seam had them (same order).
    enclosed: Vec<Option<Enclosure>>,
    /// Added vertices inside each input triangle's face.
    on_face: FxHashMap<u32, List<u32>>,
    /// Added vertices on each input edge `(lo, hi)`.
    on_edge: FxHashMap<(u32, u32), List<u32>>,
    /// For every seam point, its vertex.
    seam_vertex: Vec<u32>,
}

impl SeamPoints {
    /// The exact point of vertex `v` (an input vertex of `mesh`, or an added one).
    fn exact(&self, mesh: &Mesh, v: u32) -> Point {
        match (v as usize).checked_sub(self.input_vertices) {
            Some(i) => self.added[i].clone(),
            None => Point::Explicit(mesh.positions[v as usize]),
        }
    }
}

/// Gives every seam point a vertex of `mesh` (side `side`): a seam point at an input
/// vertex is that vertex; every other one becomes a new vertex after the input's, noted
/// with the face or edge of the input it lies on.
fn index_seam_points(mesh: &Mesh, seam: &Seam, side: Source) -> SeamPoints {
    // Copied side by side: on large meshes a serial copy into fresh memory is this
    // step's serial part.
    let mut positions = Vec::with_capacity(mesh.positions.len() + seam.points.len());
    positions.par_extend(mesh.positions.par_iter().grained().copied());
    let input_vertices = positions.len();
    // Sized for the most there can be (every seam point added; each on its own face or
    // edge): most seams are small, and growing these was a tenth of a small
    // arrangement.
    let n = seam.points.len();
    let mut added: Vec<Point> = Vec::with_capacity(n);
    let mut enclosed = Vec::with_capacity(n);
    let mut on_face: FxHashMap<u32, List<u32>> = FxHashMap::default();
    let mut on_edge: FxHashMap<(u32, u32), List<u32>> = FxHashMap::default();
    on_face.reserve(n);
    on_edge.reserve(n);
    let seam_vertex: Vec<u32> = seam
        .points
        .iter()
        .enumerate()
        .map(|(s, l)| match l.feature(side) {
            Feature::Vertex(v) => v,
            f => {
                let id = positions.len() as u32;
                positions.push(seam.positions[s]);
                added.push(seam.exact[s].clone());
                enclosed.push(seam.enclosure(s));
                match f {
                    Feature::Face(t) => on_face.entry(t).or_default().push(id),
                    Feature::Edge(u, v) => on_edge.entry((u, v)).or_default().push(id),
                    Feature::Vertex(_) => unreachable!(),
                }
                id
            }
        })
        .collect();
    SeamPoints {
        positions,
        input_vertices,
        added,
        enclosed,
        on_face,
        on_edge,
        seam_vertex,
    }
}

/// The seam segments as sorted vertex pairs, given every seam point's vertex.
fn seam_edges(seam: &Seam, seam_vertex: &[u32]) -> Vec<[u32; 2]> {
    seam.segments
        .iter()
        .map(|s| {
            let (x, y) = (
                seam_vertex[s.ends[0] as usize],
                seam_vertex[s.ends[1] as usize],
            );
            [x.min(y), x.max(y)]
        })
        .collect()
}

/// Per input triangle of side `side`, the seam edges found in it: the constraints of its
/// re-triangulation.
fn constraints(seam: &Seam, side: Source, seam_edges: &[[u32; 2]]) -> Constraints {
    let mut cons = Constraints::default();
    cons.reserve(seam.sources.len());
    for src in &seam.sources {
        let t = match side {
            Source::A => src.tri_a,
            Source::B => src.tri_b,
        };
        cons.entry(t)
            .or_default()
            .push(seam_edges[src.segment as usize]);
    }
    cons
}

/// The input triangles to re-triangulate, sorted: those with a seam point in their face
/// or on one of their edges, or a seam edge. `near`: where known, triangles among which
/// are all those with a seam point on an edge (the seam's broad-phase candidates).
fn cut_triangles(
    mesh: &Mesh,
    points: &SeamPoints,
    cons: &Constraints,
    near: Option<&[u32]>,
) -> Vec<u32> {
    let mut cut: Vec<u32> = points.on_face.keys().chain(cons.keys()).copied().collect();
    if !points.on_edge.is_empty() {
        // Only a triangle with two corners on such edges can have one: check that first.
        let mut ends = vec![false; points.positions.len()];
        for &(u, v) in points.on_edge.keys() {
            ends[u as usize] = true;
            ends[v as usize] = true;
        }
        let holds = |&t: &u32| {
            let tri = mesh.triangles[t as usize];
            tri.iter().filter(|&&v| ends[v as usize]).count() >= 2
                && (0..3).any(|k| {
                    let (u, v) = (tri[k], tri[(k + 1) % 3]);
                    points.on_edge.contains_key(&(u.min(v), u.max(v)))
                })
        };
        match near {
            Some(near) => cut.par_extend(near.par_iter().grained().copied().filter(holds)),
            None => cut.par_extend(
                (0..mesh.triangles.len() as u32)
                    .into_par_iter()
                    .grained()
                    .filter(holds),
            ),
        }
    }
    cut.par_sort_unstable();
    cut.dedup();
    cut
}

/// One cut triangle re-triangulated: its pieces (vertex ids of the arranged mesh), the
/// pieces that rounding their seam points turns over (by their place among the pieces;
/// almost always none), and the triangle's projection; or why it failed.
type CutResult = Result<(Pieces, Vec<u32>, Projection), local::Failed>;

/// A cut triangle's pieces, in place for the few of most (no allocation per triangle).
type Pieces = smallvec::SmallVec<[[u32; 3]; 8]>;

/// Re-triangulates input triangle `t` with the seam points on it (`points`) and its seam
/// edges (`cons`) as constraints, then improves the shape of the pieces; and marks the
/// pieces that their rounded seam points turn over ([`turned_by_rounding`]).
fn cut_triangle(
    mesh: &Mesh,
    t: u32,
    points: &SeamPoints,
    cons: &Constraints,
    scratch: &mut Scratch,
) -> CutResult {
    let tri = mesh.triangles[t as usize];
    let corners = mesh.corners(t as usize);
    let Some(shape) = Triangle::new(corners) else {
        return Err(local::Failed(FailReason::DegenerateTriangle));
    };
    // Seam points with the outer edge they lie on, if any.
    let Scratch {
        local,
        mine,
        to_local,
        ids,
        chains,
    } = scratch;
    mine.clear();
    if let Some(p) = points.on_face.get(&t) {
        mine.extend(p.iter().map(|&g| (g, None)));
    }
    for k in 0..3 {
        let (u, v) = (tri[k], tri[(k + 1) % 3]);
        if let Some(p) = points.on_edge.get(&(u.min(v), u.max(v))) {
            mine.extend(p.iter().map(|&g| (g, Some(k))));
        }
    }
    let cons_t = cons.get(&t).map(List::as_slice).unwrap_or(&[]);
    let (axis, sign) = (shape.axis(), shape.sign());
    let projection = (axis as u8, sign);
    // Nothing inside and only its own edges as seam edges (a face the other mesh shares):
    // the triangle is its own only piece, as the triangulation below would leave it.
    if mine.is_empty() && cons_t.iter().all(|c| c.iter().all(|v| tri.contains(v))) {
        return Ok((smallvec::smallvec![tri], Vec::new(), projection));
    }
    let lt = match local {
        Some(lt) => {
            lt.reset(corners, axis, sign, mine.len());
            lt
        }
        None => local.insert(local::Local::new(corners, axis, sign, mine.len())),
    };
    // Mesh vertex to local vertex, as pairs sorted once all are in (a few per triangle,
    // thousands under a fine mesh): where a vertex is named twice, the later pair holds.
    to_local.clear();
    to_local.extend(tri.iter().enumerate().map(|(k, &v)| (v, k as u32)));
    ids.clear();
    ids.extend_from_slice(&tri);
    chain_order(mine, cons_t, chains);
    for &(g, on_edge) in mine.iter() {
        // An input vertex here is one of the mesh's own lying on this triangle (the
        // self-arrangement); the rest are constructed seam points.
        let exact = match (g as usize).checked_sub(points.input_vertices) {
            Some(i) => match &points.enclosed[i] {
                Some(e) => Prepared::with(points.added[i].clone(), e.clone()),
                None => Prepared::new(points.added[i].clone()),
            },
            None => Prepared::new(Point::Explicit(mesh.positions[g as usize])),
        };
        let l = lt.insert(exact, points.positions[g as usize], on_edge)?;
        if l as usize == ids.len() {
            ids.push(g);
        }
        to_local.push((g, l));
    }
    // The few of most triangles scanned from the end; many sorted (stably) and searched.
    let few = to_local.len() <= LOCAL_SCAN_UP_TO;
    if !few {
        to_local.sort_by_key(|&(g, _)| g);
    }
    let local_of = |g: u32| {
        if few {
            return to_local
                .iter()
                .rev()
                .find(|&&(h, _)| h == g)
                .map(|&(_, l)| l);
        }
        let end = to_local.partition_point(|&(h, _)| h <= g);
        to_local[..end]
            .last()
            .filter(|&&(h, _)| h == g)
            .map(|&(_, l)| l)
    };
    for (i, c) in cons_t.iter().enumerate() {
        // A seam segment is listed once for each pair of triangles it lies in: inserted
        // again, it would find itself an edge already (checked among the few).
        if few && i < LOCAL_SCAN_UP_TO && cons_t[..i].iter().any(|d| d == c || [d[1], d[0]] == *c) {
            continue;
        }
        let (Some(p), Some(q)) = (local_of(c[0]), local_of(c[1])) else {
            return Err(local::Failed(FailReason::ConstraintEndOutside));
        };
        lt.constrain(p, q)?;
    }
    lt.improve();
    let pieces: Pieces = lt.tris.iter().map(|v| v.map(|l| ids[l as usize])).collect();
    let flipped = turned_by_rounding(&pieces, points, &shape);
    Ok((pieces, flipped, projection))
}

/// Orders a triangle's seam points along the chains its constraints form, so that each
/// point is inserted next to the one before (the point location walk then takes a step or
/// two instead of crossing the triangulation); points on no constraint go last. `work`:
/// arrays reused from one triangle to the next.
fn chain_order(mine: &mut [(u32, Option<usize>)], cons: &[[u32; 2]], work: &mut Chains) {
    if mine.len() < CHAIN_FROM || cons.is_empty() {
        return;
    }
    let Chains {
        ends,
        local,
        next,
        rank,
        stack,
        keyed,
        sorted,
    } = work;
    // The constraints' ends, numbered; each end's rank in a depth-first walk of the
    // graph of the constraints, a vertex's neighbours taken in the constraints' order:
    // found by scanning the constraints for the few of most triangles, by a list sorted
    // by end (stably) for many.
    ends.clear();
    ends.extend(cons.iter().flatten().copied());
    ends.sort_unstable();
    ends.dedup();
    // (Every end is in the list: its place there is its number.)
    let number = |v: u32| {
        if ends.len() <= CHAIN_SCAN_UP_TO {
            ends.iter().take_while(|&&e| e < v).count() as u32
        } else {
            ends.partition_point(|&e| e < v) as u32
        }
    };
    local.clear();
    local.extend(cons.iter().map(|c| c.map(number)));
    next.clear();
    if cons.len() > CHAIN_SCAN_UP_TO {
        next.reserve(2 * cons.len());
        for &[a, b] in local.iter() {
            next.extend([(a, b), (b, a)]);
        }
        next.sort_by_key(|&(v, _)| v);
    }
    rank.clear();
    rank.resize(ends.len(), u32::MAX);
    let mut ranked = 0;
    stack.clear();
    for &[a, _] in local.iter() {
        stack.push(a);
        while let Some(v) = stack.pop() {
            if rank[v as usize] != u32::MAX {
                continue;
            }
            rank[v as usize] = ranked;
            ranked += 1;
            let unranked = |w: u32| rank[w as usize] == u32::MAX;
            if next.is_empty() {
                for &[x, y] in local.iter() {
                    if x == v && unranked(y) {
                        stack.push(y);
                    }
                    if y == v && unranked(x) {
                        stack.push(x);
                    }
                }
            } else {
                let from = next.partition_point(|&(u, _)| u < v);
                let to = next.partition_point(|&(u, _)| u <= v);
                stack.extend(
                    next[from..to]
                        .iter()
                        .map(|&(_, w)| w)
                        .filter(|&w| unranked(w)),
                );
            }
        }
    }
    // A stable sort by rank: each point's rank found once, ties kept in order.
    let at = |v: u32| ends.binary_search(&v).ok();
    keyed.clear();
    keyed.extend(
        mine.iter()
            .zip(0..)
            .map(|(&(g, _), k)| (at(g).map_or(u32::MAX, |i| rank[i]), k)),
    );
    keyed.sort_unstable();
    sorted.clear();
    sorted.extend(keyed.iter().map(|&(_, k)| mine[k as usize]));
    mine.copy_from_slice(sorted);
}

/// The arrays of [`chain_order`], kept in a [`Scratch`]: the constraints' ends, the
/// constraints by end number, the ends' neighbours (many constraints), ranks, the walk's
/// stack, the points by rank and in their new order.
#[derive(Default)]
pub(crate) struct Chains {
    ends: Vec<u32>,
    local: Vec<[u32; 2]>,
    next: Vec<(u32, u32)>,
    rank: Vec<u32>,
    stack: Vec<u32>,
    keyed: Vec<(u32, u32)>,
    sorted: Vec<(u32, Option<usize>)>,
}

/// From this many seam points on, [`chain_order`] orders a cut triangle's points along
/// its constraints; fewer are inserted as they come (a walk across a few triangles costs
/// less than the ordering; the triangulation does not depend on the order).
const CHAIN_FROM: usize = 8;

/// Up to this many vertices (corners and seam points), [`cut_triangle`] finds a mesh
/// vertex's local vertex by scanning the pairs (cheaper than sorting them for a
/// triangle's few).
const LOCAL_SCAN_UP_TO: usize = 16;

/// Up to this many constraints, [`chain_order`] finds a vertex's neighbours by scanning
/// them all (cheaper than sorting a list for a triangle's few).
const CHAIN_SCAN_UP_TO: usize = 16;

/// [`chain_order`] as first written (a list sorted by end for every size, the points
/// sorted by a key searched at every comparison): the reference of its test.
#[cfg(test)]
fn chain_order_reference(mine: &mut [(u32, Option<usize>)], cons: &[[u32; 2]]) {
    if mine.len() < CHAIN_FROM || cons.is_empty() {
        return;
    }
    // Each end's neighbours along the constraints, in the constraints' order (a stable
    // sort by end), and each end's rank in a depth-first walk of that graph.
    let mut next: Vec<(u32, u32)> = Vec::with_capacity(2 * cons.len());
    for &[a, b] in cons {
        next.extend([(a, b), (b, a)]);
    }
    next.sort_by_key(|&(v, _)| v);
    let mut ends: Vec<u32> = next.iter().map(|&(v, _)| v).collect();
    ends.dedup();
    let at = |v: u32| ends.binary_search(&v).ok();
    let mut rank = vec![u32::MAX; ends.len()];
    let mut ranked = 0;
    let mut stack = Vec::new();
    for &[a, _] in cons {
        stack.push(a);
        while let Some(v) = stack.pop() {
            let Some(i) = at(v).filter(|&i| rank[i] == u32::MAX) else {
                continue;
            };
            rank[i] = ranked;
            ranked += 1;
            let from = next.partition_point(|&(u, _)| u < v);
            let to = next.partition_point(|&(u, _)| u <= v);
            stack.extend(
                next[from..to]
                    .iter()
                    .map(|&(_, w)| w)
                    .filter(|&w| at(w).is_some_and(|j| rank[j] == u32::MAX)),
            );
        }
    }
    mine.sort_by_key(|&(g, _)| at(g).map_or(u32::MAX, |i| rank[i]));
}

/// The pieces of `parent` (their places in `pieces`) that hold a seam point and, with the
/// seam points rounded to their `f64` coordinates, no longer face like `parent` (exact
/// test on the rounded coordinates). A piece whose seam points all have `f64` coordinates
/// (input vertices of the other mesh) is as the triangulation made it, facing like
/// `parent`.
fn turned_by_rounding(pieces: &[[u32; 3]], points: &SeamPoints, parent: &Triangle) -> Vec<u32> {
    let rounded = |v: u32| {
        (v as usize)
            .checked_sub(points.input_vertices)
            .is_some_and(|i| !matches!(points.added[i], Point::Explicit(_)))
    };
    (0..)
        .zip(pieces)
        .filter(|(_, p)| {
            p.iter().any(|&v| rounded(v)) && {
                let [a, b, c] = p.map(|v| points.positions[v as usize]);
                let safe = robust_safe(&[&a, &b, &c]);
                orient2d_inputs(&a, &b, &c, parent.axis(), safe) != parent.sign()
            }
        })
        .map(|(i, _)| i)
        .collect()
}

/// The arranged triangles with their bookkeeping ([`reassemble`]).
struct Reassembled {
    triangles: Vec<[u32; 3]>,
    parent: Vec<u32>,
    failed: Vec<(u32, FailReason)>,
    rounding_flips: Vec<u32>,
    projections: Vec<(u32, Projection)>,
}

/// The output in input order: runs of uncut triangles copied as they are, each cut one
/// replaced by its pieces (`results` in increasing triangle order), or kept whole where
/// it failed; each output triangle's parent, and the failures and pieces turned by
/// rounding by their ids. Large meshes are filled in spans side by side: each span of
/// input triangles (from one cut triangle to the next span's first) knows its place in
/// the output from the sizes of the spans before it.
fn reassemble(mesh: &Mesh, results: Vec<(u32, CutResult)>) -> Reassembled {
    let n = mesh.triangles.len();
    let size = |r: &CutResult| r.as_ref().map_or(1, |(p, _, _)| p.len());
    let projections = results
        .iter()
        .filter_map(|(t, r)| r.as_ref().ok().map(|&(_, _, p)| (*t, p)))
        .collect();
    // Spans of cut triangles; span k covers input triangles from its first cut one (0 for
    // the first span) to the next span's first cut one (n for the last).
    let spans = if n < 1 << 16 {
        1
    } else {
        (4 * rayon::current_num_threads()).min(results.len()).max(1)
    };
    let per = results.len().div_ceil(spans).max(1);
    let groups: Vec<&[(u32, CutResult)]> = results.chunks(per).collect();
    let bounds: Vec<(usize, usize)> = (0..groups.len().max(1))
        .map(|k| {
            let start = if k == 0 { 0 } else { groups[k][0].0 as usize };
            let end = groups.get(k + 1).map_or(n, |g| g[0].0 as usize);
            (start, end)
        })
        .collect();
    let sizes: Vec<usize> = bounds
        .iter()
        .enumerate()
        .map(|(k, &(start, end))| {
            let g = groups.get(k).copied().unwrap_or(&[]);
            end - start - g.len() + g.iter().map(|(_, r)| size(r)).sum::<usize>()
        })
        .collect();
    let total = sizes.iter().sum();
    let mut triangles = crate::par::filled([0u32; 3], total);
    let mut parent = crate::par::filled(0u32, total);
    let firsts = crate::par::exclusive_sums(&sizes);
    // Per span: its failures and its pieces turned by rounding.
    type Found = (Vec<(u32, FailReason)>, Vec<u32>);
    let lists: Vec<Found> = crate::par::split_by(&mut triangles, &sizes)
        .into_par_iter()
        .grained()
        .zip(crate::par::split_by(&mut parent, &sizes))
        .enumerate()
        .map(|(k, (tris, par))| {
            let (start, end) = bounds[k];
            let g = groups.get(k).copied().unwrap_or(&[]);
            let (mut failed, mut flips) = (Vec::new(), Vec::new());
            let mut at = 0usize;
            // The uncut triangles `from..to`, copied at `at`.
            let copy =
                |tris: &mut [[u32; 3]], par: &mut [u32], from: usize, to: usize, at: usize| {
                    tris[at..at + to - from].copy_from_slice(&mesh.triangles[from..to]);
                    for (p, t) in par[at..at + to - from].iter_mut().zip(from as u32..) {
                        *p = t;
                    }
                    to - from
                };
            let mut next = start;
            for (t, r) in g {
                let t = *t as usize;
                at += copy(tris, par, next, t, at);
                match r {
                    Ok((sub, flipped, _)) => {
                        flips.extend(flipped.iter().map(|&i| (firsts[k] + at) as u32 + i));
                        tris[at..at + sub.len()].copy_from_slice(sub);
                        par[at..at + sub.len()].fill(t as u32);
                        at += sub.len();
                    }
                    Err(local::Failed(why)) => {
                        failed.push((t as u32, *why));
                        tris[at] = mesh.triangles[t];
                        par[at] = t as u32;
                        at += 1;
                    }
                }
                next = t + 1;
            }
            copy(tris, par, next, end, at);
            (failed, flips)
        })
        .collect();
    let (mut failed, mut rounding_flips) = (Vec::new(), Vec::new());
    for (f, r) in lists {
        failed.extend(f);
        rounding_flips.extend(r);
    }
    Reassembled {
        triangles,
        parent,
        failed,
        rounding_flips,
        projections,
    }
}

#[cfg(test)]
mod tests;
