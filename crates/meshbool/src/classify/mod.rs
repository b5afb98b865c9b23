//! Classification: which parts of one arranged mesh lie inside, outside, or on (coplanar
//! with) the other mesh.
//!
//! Pipeline position: after [`crate::arrange`]. Patches are the connected pieces of the
//! arranged mesh between seam edges. A patch's side comes from the other mesh's local fan at
//! a seam edge it touches (exact `orient3d` of the patch triangle's far vertex against the
//! fan's planes, with the dihedral wedge's convexity deciding how the two sides combine).
//! Patches touching no seam, or whose seam edges disagree (an open surface whose seam
//! stops inside the patch), use the generalized winding number of the other mesh.

use std::borrow::Cow;
use std::cell::OnceCell;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering::Relaxed};

use crate::par::Grain;
use rayon::prelude::*;
use rustc_hash::FxHashMap;

use crate::arrange::Arranged;
use crate::edges::SeamTopology;
use crate::intersect::{Feature, Label, Source};
use crate::kernel::{
    orient2d, orient2d_inputs, orient3d_plane, robust_safe, Point, Sign, Triangle,
};
use crate::Mesh;

mod reach;
mod winding;
pub(crate) use crate::kernel::side_margin;
pub use winding::{winding_number, FastWinding};
pub(crate) use winding::{winding_number_of, winding_number_without, winding_term};

/// Where a triangle of one mesh lies relative to the other mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Class {
    /// Inside the other (closed) mesh, or behind the other (open) surface.
    Inside,
    /// Outside, or in front.
    Outside,
    /// On a face of the other mesh, facing the same way.
    CoplanarSame,
    /// On a face of the other mesh, facing the opposite way.
    CoplanarOpposite,
}

/// The classification of one arranged mesh.
#[derive(Clone, Debug, Default)]
pub struct Classified {
    /// Class of every triangle of the arranged mesh.
    pub class: Vec<Class>,
    /// Number of patches (read by the tests, as the next two).
    #[cfg_attr(not(test), allow(dead_code))]
    pub patches: usize,
    /// Patches classified by winding number (no seam edge, or disagreeing seam edges).
    #[cfg_attr(not(test), allow(dead_code))]
    pub by_winding: usize,
    /// True when winding numbers were asked for and came from the hierarchical
    /// approximation rather than exact sums.
    #[cfg_attr(not(test), allow(dead_code))]
    pub approximate_winding: bool,
}

/// One triangle of the other mesh's fan around a seam edge: its plane (an input triangle,
/// explicit) and its far vertex (exact).
struct FanFace<'a> {
    plane: [[f64; 3]; 3],
    /// The input triangle of the plane: its id and its corners' vertex ids.
    parent: (u32, [u32; 3]),
    far: Cow<'a, Point>,
    /// Whether its triangle runs from the edge's first end to its second.
    forward: bool,
    /// The projection of the face's input triangle ([`Arranged::projection`]: the
    /// arrangement found it), taken when first needed (a point in the face's plane) and
    /// kept for the edge's other uses; `None` inside when degenerate.
    projection: OnceCell<Option<(usize, Sign)>>,
    /// The side of the edge its far vertex lies on in that projection, found when first
    /// needed and kept for the edge's other uses.
    far_side: OnceCell<Sign>,
}

impl FanFace<'_> {
    /// The side of the face's plane that `w` is on, exactly: zero without arithmetic
    /// where `w` is a seam point on the face's input triangle (`w_on`: the feature of
    /// that input it lies on, known from the seam), else by `orient3d`. A point on a
    /// triangle's vertex, edge or face lies in its plane; most seam points lie on the
    /// faces of the fans they are classified against, where `orient3d` is zero and only
    /// its exact stage decides (an implicit point's exact coordinates built for that).
    fn side(&self, w: &Point, w_on: Option<Feature>) -> Sign {
        let (t, corners) = self.parent;
        let on = match w_on {
            Some(Feature::Vertex(v)) => corners.contains(&v),
            Some(Feature::Edge(u, v)) => corners.contains(&u) && corners.contains(&v),
            Some(Feature::Face(f)) => f == t,
            None => false,
        };
        if on {
            return Sign::Zero;
        }
        orient3d_plane(&self.plane[0], &self.plane[1], &self.plane[2], w)
    }

    /// The projection of the face's input triangle (its [`Triangle`]'s axis and sign);
    /// `None` when degenerate. `arranged`: the arrangement of the face's mesh.
    fn projection(&self, arranged: &Arranged) -> Option<(usize, Sign)> {
        *self.projection.get_or_init(|| {
            arranged
                .projection(self.parent.0)
                .or_else(|| Triangle::new(self.plane).map(|t| (t.axis(), t.sign())))
        })
    }
}

/// The input triangle a classified triangle comes from: its id, its mesh and the
/// arrangement of that mesh (which knows its projection).
struct Own<'a> {
    parent: u32,
    input: &'a Mesh,
    arranged: &'a Arranged,
}

impl Own<'_> {
    /// The triangle's orientation in the projection dropping `axis`: its own
    /// projection's sign where that drops `axis` too (coplanar faces mostly share the
    /// axis), else exact `orient2d`.
    fn sign_in(&self, axis: usize) -> Sign {
        match self.arranged.projection(self.parent) {
            Some((a, s)) if a == axis => s,
            _ => {
                let [a, b, c] = &self.input.corners(self.parent as usize);
                orient2d_inputs(a, b, c, axis, robust_safe(&[a, b, c]))
            }
        }
    }
}

/// The other mesh's fan around a seam edge, and whether the wedge of a two-face fan is
/// convex (the sign of the second face's far vertex against the first face's plane),
/// found when first needed and kept for the edge's other uses.
struct Fan<'a> {
    faces: &'a [FanFace<'a>],
    convex: OnceCell<Sign>,
}

/// The class of a triangle with far vertex `w` at seam edge `e0 e1` against the fan of
/// the other mesh (arranged as `other`). `own` is the input triangle the classified
/// triangle comes from. An edge of more than two faces (closed parts glued along it) goes
/// to [`glued_class`]. `None` when the fan does not decide (a boundary edge of the other
/// mesh).
fn local_class(
    own: &Own<'_>,
    (w, w_on): (&Point, Option<Feature>),
    e: [&Point; 2],
    near: [f64; 3],
    (fan, other): (&Fan<'_>, &Arranged),
) -> Option<Class> {
    let [f0, f1] = fan.faces else {
        return glued_class(own, (w, w_on), e, near, (fan.faces, other));
    };
    let s = [f0, f1].map(|f| f.side(w, w_on));
    for (k, f) in [f0, f1].iter().enumerate() {
        if s[k] != Sign::Zero {
            continue;
        }
        // In the plane of this face: overlapping it when on the same side of the edge.
        if let Some(c) = on_face(own, w, e, f, f.projection(other)?) {
            return Some(c);
        }
    }
    // Two pieces of one input triangle: a flat fan, `f1`'s far vertex in `f0`'s plane.
    let convex = *fan.convex.get_or_init(|| match f0.parent.0 == f1.parent.0 {
        true => Sign::Zero,
        false => orient3d_plane(&f0.plane[0], &f0.plane[1], &f0.plane[2], &f1.far),
    });
    let behind = |x: Sign| x == Sign::Negative;
    let inside = match convex {
        Sign::Negative => behind(s[0]) && behind(s[1]),
        Sign::Positive => behind(s[0]) || behind(s[1]),
        Sign::Zero => behind(s[0]) || behind(s[1]),
    };
    Some(if inside {
        Class::Inside
    } else {
        Class::Outside
    })
}

/// Whether `w`, seen from edge `e`, lies on face `f` (in its plane, on its side of the
/// edge); then the class by the facing of `own` (the classified triangle's input
/// triangle) against it. `(axis, sign)`: the projection of `f`'s input triangle.
fn on_face(
    own: &Own<'_>,
    w: &Point,
    e: [&Point; 2],
    f: &FanFace<'_>,
    (axis, sign): (usize, Sign),
) -> Option<Class> {
    let ow = orient2d(e[0], e[1], w, axis);
    if ow == Sign::Zero
        || ow
            != *f
                .far_side
                .get_or_init(|| orient2d(e[0], e[1], &f.far, axis))
    {
        return None;
    }
    Some(if own.sign_in(axis) == sign {
        Class::CoplanarSame
    } else {
        Class::CoplanarOpposite
    })
}

/// [`local_class`] at an edge of more than two faces of the other mesh (closed parts
/// glued along it, an operand resolved at the door whose parts touch): on a face where
/// `w` lies on one (all such faces agreeing), else inside where the fan wraps around
/// `w`'s side: the sectors between the faces, taken in angular order around the edge,
/// each gain one crossing a face that opens an inside and lose one crossing a face
/// that closes it; the fan of a solid's boundary wraps the sectors with the least count
/// zero times. `None` for fewer than three faces or an odd count (a boundary), and where
/// faces `w` lies on disagree. `near` is the position of `e[0]`.
fn glued_class(
    own: &Own<'_>,
    (w, w_on): (&Point, Option<Feature>),
    e: [&Point; 2],
    near: [f64; 3],
    (fan, other): (&[FanFace<'_>], &Arranged),
) -> Option<Class> {
    if fan.len() < 3 || fan.len() % 2 == 1 {
        return None;
    }
    let mut found = None;
    for f in fan {
        if f.side(w, w_on) != Sign::Zero {
            continue;
        }
        let Some(plane) = f.projection(other) else {
            continue;
        };
        if let Some(c) = on_face(own, w, e, f, plane) {
            if found.is_some_and(|d| d != c) {
                return None;
            }
            found = Some(c);
        }
    }
    if found.is_some() {
        return found;
    }
    // The faces and `w` in angular order around e[0] -> e[1]; `w` is the last item.
    let mut items: Vec<(u32, bool, Point, u32)> = fan
        .iter()
        .enumerate()
        .map(|(i, f)| (i as u32, f.forward, f.far.clone().into_owned(), i as u32))
        .collect();
    items.push((fan.len() as u32, true, w.clone(), fan.len() as u32));
    let order = crate::edges::angular_order(e[0], e[1], near, &items);
    // Counter-clockwise past a face running e1 -> e0 enters its inside, past one running
    // e0 -> e1 leaves it.
    let (mut count, mut lowest, mut at_w) = (0i64, 0i64, None);
    for &i in &order {
        if i == fan.len() {
            at_w = Some(count);
            continue;
        }
        count += if fan[i].forward { -1 } else { 1 };
        lowest = lowest.min(count);
    }
    // The sectors before the first face continue the last (the circle closes at zero).
    if count != 0 {
        return None;
    }
    let at_w = at_w?;
    Some(if at_w - lowest >= 1 {
        Class::Inside
    } else {
        Class::Outside
    })
}

/// One side of a classification: an input mesh, its arrangement and the arrangement's
/// edge topology.
pub struct CutMesh<'a> {
    /// The input mesh.
    pub input: &'a Mesh,
    /// Its arrangement along the seam.
    pub arranged: &'a Arranged,
    /// `SeamTopology::new(&arranged.mesh, &arranged.seam_edges)`.
    pub topology: &'a SeamTopology,
    /// The seam's points (their labels, [`crate::intersect::Seam::points`]) and the
    /// side of [`CutMesh::input`] in them, when known: each label's feature on that side
    /// is where the point lies on the input, so the other mesh's classification knows
    /// without arithmetic which seam points lie in this mesh's faces' planes.
    pub seam: Option<(&'a [Label], Source)>,
}

/// Up to this many triangle × query products, winding numbers are exact sums; beyond, the
/// hierarchical approximation (a measured crossover).
pub const EXACT_WINDING_UP_TO: f64 = 2e7;

/// How many of a patch's seam votes [`classify_with`] asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Votes {
    /// Every use of every seam edge votes; a patch whose votes disagree (an open
    /// surface's seam stopping inside it, or an operand taken as given whose parts
    /// cross) keeps the triangles' own agreeing votes and asks winding numbers for the
    /// rest.
    All,
    /// Against a closed other mesh, each patch takes the first vote that decides it, in
    /// the order of the seam edges and their uses, and no other vote is asked: a patch
    /// does not cross the other mesh's surface, so all its deciding votes agree where the
    /// operands are valid solids (checked, or known to be clean). Against an open mesh
    /// as [`Votes::All`]. Deterministic whatever the threads.
    FirstDeciding,
}

/// Classifies the triangles of `x` against the other mesh `y` (both arranged along the same
/// seam). `y_closed` picks the winding-number threshold (1/2 for closed, 0 for open);
/// winding numbers are exact sums up to `exact_winding_up_to` triangle × query products
/// ([`EXACT_WINDING_UP_TO`] by default), asking the seam votes that `votes` says.
pub fn classify_with(
    x: &CutMesh,
    y: &CutMesh,
    y_closed: bool,
    exact_winding_up_to: f64,
    votes: Votes,
) -> Classified {
    // Patches: components of the triangles joined across edges that are not seam edges,
    // numbered in the order of each patch's first triangle.
    let (patches, patch) = (x.topology.patches, &x.topology.patch);
    let resolved = match votes {
        Votes::FirstDeciding if y_closed => first_votes(x, y),
        _ => resolve_patches(seam_votes(x, y), patch, patches),
    };
    let (answers, approximate_winding) = winding_fallback(
        &x.arranged.mesh,
        &x.topology.edges,
        y.input,
        y_closed,
        &resolved.queries,
        exact_winding_up_to,
    );
    let by_winding = resolved.by_winding;
    Classified {
        class: settle(resolved, answers, patch, patches),
        patches,
        by_winding,
        approximate_winding,
    }
}

/// One use of a seam edge: the patch and triangle using it, and the triangle's class
/// from the other mesh's fan there (`None`: the fan does not decide).
type Vote = (u32, u32, Option<Class>);

/// Asks the votes at the seam edges of `x`: each from the other mesh's fan around the
/// edge ([`local_class`]).
struct Voter<'a> {
    x: &'a CutMesh<'a>,
    y: &'a CutMesh<'a>,
    seam_of_vertex: SeamOf,
}

impl<'a> Voter<'a> {
    fn new(x: &'a CutMesh<'a>, y: &'a CutMesh<'a>) -> Self {
        Voter {
            x,
            y,
            seam_of_vertex: SeamOf::new(x.arranged),
        }
    }

    /// The votes of the uses of seam edge `e` that `wanted(k, patch)` asks for (`k`: the
    /// use's place among the edge's uses), given to `out(k, vote)` in the uses' order.
    /// `faces`: room for the fan, reused edge by edge. The fan is not built where no use
    /// is wanted.
    fn votes_at(
        &self,
        e: usize,
        faces: &mut Vec<FanFace<'a>>,
        wanted: impl Fn(usize, u32) -> bool,
        mut out: impl FnMut(usize, Vote),
    ) {
        let (x_in, topo, y_in, ytopo) =
            (self.x.input, self.x.topology, self.y.input, self.y.topology);
        let (x, y) = (self.x.arranged, self.y.arranged);
        let patch = &topo.patch;
        let uses = topo.uses_of(e);
        if !(0..)
            .zip(uses)
            .any(|(k, u)| wanted(k, patch[u.triangle as usize]))
        {
            return;
        }
        let seam_of_vertex = &self.seam_of_vertex;
        let [u, v] = topo.edges[e];
        let (Some(su), Some(sv)) = (seam_of_vertex.get(u), seam_of_vertex.get(v)) else {
            unreachable!("a seam edge's ends are seam points");
        };
        let (yu, yv) = (y.seam_vertex[su as usize], y.seam_vertex[sv as usize]);
        faces.clear();
        if let Ok(ye) = ytopo.edges.binary_search(&[yu.min(yv), yu.max(yv)]) {
            faces.extend(ytopo.uses_of(ye).iter().map(|use_| {
                let tri = y.mesh.triangles[use_.triangle as usize];
                let parent = y.parent[use_.triangle as usize];
                FanFace {
                    plane: y_in.corners(parent as usize),
                    parent: (parent, y_in.triangles[parent as usize]),
                    far: y.point_ref(tri[(use_.corner as usize + 2) % 3]),
                    forward: tri[use_.corner as usize] == yu,
                    projection: OnceCell::new(),
                    far_side: OnceCell::new(),
                }
            }));
        }
        let fan = Fan {
            faces,
            convex: OnceCell::new(),
        };
        let (pu, pv) = (x.point_ref(u), x.point_ref(v));
        let ends = [&*pu, &*pv];
        for (k, use_) in uses.iter().enumerate() {
            let t = use_.triangle as usize;
            if !wanted(k, patch[t]) {
                continue;
            }
            let wv = x.mesh.triangles[t][(use_.corner as usize + 2) % 3];
            let w = &*x.point_ref(wv);
            // Where `w` is a seam point: the feature of `y`'s input it lies on.
            let w_on = self
                .y
                .seam
                .zip(seam_of_vertex.get(wv))
                .map(|((labels, side), s)| labels[s as usize].feature(side));
            let own = Own {
                parent: x.parent[t],
                input: x_in,
                arranged: x,
            };
            let near = x.mesh.positions[u as usize];
            let c = local_class(&own, (w, w_on), ends, near, (&fan, y));
            out(k, (patch[t], t as u32, c));
        }
    }
}

/// The votes of every use of every seam edge of `x`, each from the other mesh's fan around
/// that edge ([`local_class`]), in the order of `x`'s seam edges.
fn seam_votes(x: &CutMesh, y: &CutMesh) -> Vec<Vote> {
    let voter = Voter::new(x, y);
    // Each task's votes in one vector, and one vector of fan faces reused edge by edge.
    let votes: Vec<Vec<Vote>> = (0..x.topology.edges.len())
        .into_par_iter()
        .grained()
        .fold(
            || (Vec::new(), Vec::new()),
            |(mut votes, mut faces): (Vec<Vote>, Vec<FanFace>), e| {
                voter.votes_at(e, &mut faces, |_, _| true, |_, vote| votes.push(vote));
                (votes, faces)
            },
        )
        .map(|(votes, _)| votes)
        .collect();
    votes.concat()
}

/// The classes of [`Votes::FirstDeciding`]: each patch's first deciding vote in the order
/// of `x`'s seam edges and their uses. A use is asked only while its patch has no deciding
/// vote before it in that order: on one thread, each patch's votes up to its first
/// deciding one; on several, a few more, and the first in the order still wins (kept as
/// the smallest key of order and class per patch). A patch whose votes all fail to decide
/// (a degenerate fan) asks winding numbers for its triangles, as [`resolve_patches`] does.
fn first_votes(x: &CutMesh, y: &CutMesh) -> Resolved {
    use std::sync::atomic::AtomicU64;
    let topo = x.topology;
    let (patches, patch) = (topo.patches, &topo.patch);
    // Key of the vote of use `k` of edge `e`: edge, use (its place among the edge's uses;
    // more than 2^30 uses of one edge share the last key), class below.
    let key = |e: usize, k: usize| (e as u64) << 32 | (k.min((1 << 30) - 1) as u64) << 2;
    const CLASSES: [Class; 4] = [
        Class::Inside,
        Class::Outside,
        Class::CoplanarSame,
        Class::CoplanarOpposite,
    ];
    let code = |c: Class| CLASSES.iter().position(|&d| d == c).unwrap_or(0) as u64;
    let first: Vec<AtomicU64> = (0..patches).map(|_| AtomicU64::new(u64::MAX)).collect();
    // Patches with a use that voted (possibly without deciding).
    let voted: Vec<AtomicBool> = (0..patches).map(|_| AtomicBool::new(false)).collect();
    let voter = Voter::new(x, y);
    (0..topo.edges.len())
        .into_par_iter()
        .grained()
        .for_each_init(Vec::new, |faces, e| {
            voter.votes_at(
                e,
                faces,
                |k, p| first[p as usize].load(Relaxed) > key(e, k),
                |k, (p, _, c)| {
                    voted[p as usize].store(true, Relaxed);
                    if let Some(c) = c {
                        first[p as usize].fetch_min(key(e, k) | code(c), Relaxed);
                    }
                },
            );
        });
    let decided: Vec<Option<Option<Class>>> = first
        .iter()
        .zip(&voted)
        .map(|(f, v)| match f.load(Relaxed) {
            u64::MAX if v.load(Relaxed) => Some(None),
            u64::MAX => None,
            k => Some(Some(CLASSES[(k & 3) as usize])),
        })
        .collect();
    // An undecided patch's votes were all asked, and none decided: no triangle there has
    // its own answer.
    resolved(decided, patch, patches, &FxHashMap::default())
}

/// The seam point at each vertex of an arranged mesh that is one: by place for the added
/// vertices (all seam points), through a map for the input vertices that are (few in
/// most booleans; every one where faces are shared).
struct SeamOf {
    input_vertices: u32,
    added: Vec<u32>,
    inputs: FxHashMap<u32, u32>,
}

impl SeamOf {
    fn new(x: &Arranged) -> SeamOf {
        let input_vertices = x.input_vertices as u32;
        let mut added = vec![u32::MAX; x.added_points.len()];
        let mut inputs = FxHashMap::default();
        for (s, &v) in (0..).zip(&x.seam_vertex) {
            match v.checked_sub(input_vertices) {
                Some(i) => added[i as usize] = s,
                // (The last of several seam points at one input vertex.)
                None => _ = inputs.insert(v, s),
            }
        }
        SeamOf {
            input_vertices,
            added,
            inputs,
        }
    }

    /// The seam point at vertex `v`, if any.
    fn get(&self, v: u32) -> Option<u32> {
        match v.checked_sub(self.input_vertices) {
            Some(i) => Some(self.added[i as usize]).filter(|&s| s != u32::MAX),
            None => self.inputs.get(&v).copied(),
        }
    }
}

/// What the seam decided ([`resolve_patches`]), and what is left to winding numbers.
struct Resolved {
    /// Per patch: `None` without seam edges, `Some(None)` where its votes disagree or do
    /// not decide, `Some(Some(c))` where they all say `c`.
    decided: Vec<Option<Option<Class>>>,
    /// Per triangle, its class where the seam decides it.
    class: Vec<Option<Class>>,
    /// Triangles whose centroid needs a winding number: the first triangle of a patch
    /// without seam edges (for the whole patch), every triangle without its own answer in
    /// a patch whose votes disagree.
    queries: Vec<usize>,
    /// Patches left to winding numbers.
    by_winding: usize,
}

/// Combines the votes per patch: a patch whose votes all agree takes their class. In a
/// patch whose votes disagree (an open surface's seam stops inside it), the triangles
/// along the seam keep their own agreeing votes, and the others are queued for a winding
/// number each; a patch without votes is queued once, by its first triangle.
fn resolve_patches(votes: Vec<Vote>, patch: &[u32], patches: usize) -> Resolved {
    // None: no vote yet; Some(None): undecided or disagreeing.
    fn combine(d: Option<Option<Class>>, c: Option<Class>) -> Option<Option<Class>> {
        match (d, c) {
            (_, None) | (Some(None), _) => Some(None),
            (None, Some(c)) => Some(Some(c)),
            (Some(Some(a)), Some(b)) if a == b => Some(Some(a)),
            (Some(Some(_)), Some(_)) => Some(None),
        }
    }
    let mut decided: Vec<Option<Option<Class>>> = vec![None; patches];
    // Per triangle too: where a patch's votes disagree (the seam stops inside it), the
    // triangles along the seam keep their own local answer.
    let mut own_vote: FxHashMap<u32, Option<Class>> = FxHashMap::default();
    own_vote.reserve(votes.len());
    for (p, t, c) in votes {
        decided[p as usize] = combine(decided[p as usize], c);
        let v = own_vote.get(&t).copied();
        own_vote.insert(t, combine(v, c).flatten());
    }
    resolved(decided, patch, patches, &own_vote)
}

/// What the patches' combined votes `decided` leave: each triangle's class where its
/// patch, or its own vote (`own_vote`, for a patch whose votes disagree), decides it,
/// and the triangles to ask winding numbers for.
fn resolved(
    decided: Vec<Option<Option<Class>>>,
    patch: &[u32],
    patches: usize,
    own_vote: &FxHashMap<u32, Option<Class>>,
) -> Resolved {
    // The per-triangle passes run side by side (they are this stage's serial part on
    // large meshes otherwise); those for patches left to winding numbers only where
    // there are such patches.
    let by_winding = decided
        .iter()
        .filter(|d| !matches!(d, Some(Some(_))))
        .count();
    const CHUNK: usize = 1 << 15;
    // The first triangle of each patch without votes.
    let first: Vec<AtomicU32> = (0..patches)
        .into_par_iter()
        .grained()
        .map(|_| AtomicU32::new(u32::MAX))
        .collect();
    if decided.contains(&None) {
        patch
            .par_chunks(CHUNK)
            .grained()
            .enumerate()
            .for_each(|(c, ps)| {
                for (j, &p) in ps.iter().enumerate() {
                    let t = (c * CHUNK + j) as u32;
                    let f = &first[p as usize];
                    if decided[p as usize].is_none() && f.load(Relaxed) > t {
                        f.fetch_min(t, Relaxed);
                    }
                }
            });
    }
    let class: Vec<Option<Class>> = patch
        .par_iter()
        .grained()
        .enumerate()
        .map(|(t, &p)| match decided[p as usize] {
            Some(Some(c)) => Some(c),
            None => None,
            Some(None) => own_vote.get(&(t as u32)).copied().flatten(),
        })
        .collect();
    let queries: Vec<usize> = if by_winding == 0 {
        Vec::new()
    } else {
        (0..patch.len())
            .into_par_iter()
            .grained()
            .filter(|&t| {
                let p = patch[t] as usize;
                match decided[p] {
                    Some(Some(_)) => false,
                    None => first[p].load(Relaxed) == t as u32,
                    Some(None) => class[t].is_none(),
                }
            })
            .collect()
    };
    Resolved {
        decided,
        class,
        queries,
        by_winding,
    }
}

/// The class of each queried triangle of `x` from the generalized winding number of `y`
/// at its centroid: inside above the threshold (1/2 for a closed `y`, 0 for an open one).
/// Exact sums up to `exact_up_to` triangle × query products, the hierarchy beyond, its
/// sides of the threshold certified ([`FastWinding::sided_many`]), so the classes are
/// the exact sums' either way, whatever the threads (exact sums round the same on any
/// number of them, [`winding_number`]); also whether the hierarchy answered. From
/// [`reach::REACH_FROM`] queries on, a winding number clear of the threshold also settles
/// the queried triangles within reach of it (`seam`: the seam edges of `x`, which no
/// such reach crosses; see [`reach`]).
fn winding_fallback(
    x: &Mesh,
    seam: &[[u32; 2]],
    y: &Mesh,
    y_closed: bool,
    queries: &[usize],
    exact_up_to: f64,
) -> (Vec<Class>, bool) {
    let threshold = if y_closed { 0.5 } else { 0.0 };
    let by_reach = queries.len() >= reach::REACH_FROM;
    // The reach's chain and the hierarchy's cone are both over `y`'s boundary: found
    // once, beside the hierarchy's build.
    let (fast, boundary) = crate::par::join(
        || {
            (queries.len() as f64 * y.triangles.len() as f64 > exact_up_to)
                .then(|| FastWinding::new(y))
        },
        || match by_reach {
            true => crate::edges::unbalanced_edges(y),
            false => Vec::new(),
        },
    );
    let fast = fast.map(|f| match by_reach {
        true => f.with_boundary(&boundary),
        false => f,
    });
    let points: Vec<[f64; 3]> = queries.iter().map(|&t| x.centroid(t)).collect();
    let eval = |points: &[[f64; 3]]| -> Vec<(f64, f64)> {
        match &fast {
            Some(f) => f.sided_many(points, threshold),
            None => points
                .iter()
                .map(|&p| (winding_number(y, p), 0.0))
                .collect(),
        }
    };
    let classes = if by_reach {
        reach::classes_by_reach(x, queries, &points, seam, y, &boundary, threshold, eval)
    } else {
        eval(&points)
            .into_iter()
            .map(|(w, _)| class_of_winding(w, threshold))
            .collect()
    };
    (classes, fast.is_some())
}

/// The class a winding number `w` gives: inside above `threshold`, outside otherwise.
fn class_of_winding(w: f64, threshold: f64) -> Class {
    match w > threshold {
        true => Class::Inside,
        false => Class::Outside,
    }
}

/// Every triangle's class: its seam answer, or the winding answer (`answers`, one per
/// query) for its patch (a patch without seam edges) or for itself.
fn settle(r: Resolved, answers: Vec<Class>, patch: &[u32], patches: usize) -> Vec<Class> {
    let mut class = r.class;
    let mut patch_answer: Vec<Option<Class>> = vec![None; patches];
    for (&t, c) in r.queries.iter().zip(answers) {
        match r.decided[patch[t] as usize] {
            None => patch_answer[patch[t] as usize] = Some(c),
            _ => class[t] = Some(c),
        }
    }
    class
        .into_par_iter()
        .grained()
        .enumerate()
        .map(|(t, c)| {
            c.or(patch_answer[patch[t] as usize])
                .expect("every triangle is decided: by its patch, its seam or a winding number")
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::Rng;

    /// A classified triangle's orientation in a fan face's projection is exact
    /// `orient2d` in that projection, whichever axis its own projection (kept by the
    /// arrangement) drops: random triangles, whose normals' components differ in sign,
    /// each asked in all three projections, with and without a kept projection.
    #[test]
    fn an_own_triangle_is_oriented_in_any_projection() {
        let mut rng = Rng(0x0a11_a2e5);
        let mut differing = 0;
        for round in 0..2000 {
            let corners: [[f64; 3]; 3] =
                std::array::from_fn(|_| std::array::from_fn(|_| rng.unit() - 0.5));
            let Some(shape) = Triangle::new(corners) else {
                continue;
            };
            let input = Mesh::new_unchecked(corners.to_vec(), vec![[0, 1, 2]]);
            let mut arranged = Arranged::default();
            if round % 4 != 0 {
                arranged.projections = vec![(0, (shape.axis() as u8, shape.sign()))];
            }
            let own = Own {
                parent: 0,
                input: &input,
                arranged: &arranged,
            };
            let e = |p: [f64; 3]| Point::Explicit(p);
            let [a, b, c] = corners.map(e);
            let signs: Vec<Sign> = (0..3).map(|axis| orient2d(&a, &b, &c, axis)).collect();
            for (axis, &s) in signs.iter().enumerate() {
                assert_eq!(own.sign_in(axis), s, "{corners:?} {axis}");
            }
            differing += usize::from(signs.iter().any(|&s| s != shape.sign()));
        }
        assert!(differing > 1000, "{differing}");
    }
}
