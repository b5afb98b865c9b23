//! Edge adjacency: which triangles use each undirected edge, and in which direction.
//! The basis of the edge statistics in [`crate::measure`], of edge-connected components,
//! and of patch flood fills in the boolean pipeline; and the exact order of the
//! triangles around an edge (`angular_order`), which pairs the sheets of a non-manifold
//! edge in repair and the classification at one.

use crate::kernel::{orient3d, Point, Sign};
use crate::par::Grain;
use crate::Mesh;

/// One triangle's use of an edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EdgeUse {
    /// The triangle.
    pub triangle: u32,
    /// Which of the triangle's edges: corner `k` to corner `(k+1) % 3`.
    pub corner: u8,
    /// True when the triangle runs along the edge from its lower vertex index to its higher.
    pub forward: bool,
}

impl EdgeUse {
    /// The use by half-edge `h` (`3 · triangle + corner`) of `mesh` of an edge whose lower
    /// vertex is `lo`.
    fn of(mesh: &Mesh, lo: usize, h: u32) -> EdgeUse {
        let (t, k) = (h / 3, (h % 3) as usize);
        EdgeUse {
            triangle: t,
            corner: k as u8,
            forward: mesh.triangles[t as usize][k] as usize == lo,
        }
    }
}

/// Undirected edges of a mesh and the triangles incident to each (compressed rows).
///
/// Edges are sorted by their vertex pair. Edges from a triangle to itself that repeats a
/// vertex index (`[a, a, b]` has the loop `a–a`) are left out; [`EdgeTopology::triangle_edges`]
/// marks them with [`EdgeTopology::NO_EDGE`].
#[derive(Clone, Debug, Default)]
pub struct EdgeTopology {
    /// The edges as vertex pairs `[lo, hi]` with `lo < hi`, sorted.
    pub edges: Vec<[u32; 2]>,
    /// `uses[offsets[e]..offsets[e + 1]]` are the uses of edge `e`.
    pub offsets: Vec<u32>,
    /// All edge uses, grouped by edge, in triangle order within an edge.
    pub uses: Vec<EdgeUse>,
    /// For every triangle, the edge id of its edge `k` (corner `k` to `k+1`).
    pub triangle_edges: Vec<[u32; 3]>,
}

impl EdgeTopology {
    /// Marks a triangle edge that joins a vertex to itself.
    pub const NO_EDGE: u32 = u32::MAX;

    /// Builds the adjacency of `mesh`. Linear time: half-edges
    /// are bucketed by their lower vertex (a counting sort), then each small bucket is sorted
    /// by the higher vertex.
    pub fn new(mesh: &Mesh) -> Self {
        let nv = mesh.positions.len();
        // (higher vertex, half-edge id) per lower vertex, in triangle order.
        let (start, mut half) = bucket_by_lower(mesh, 0, nv as u32, |a, b, h| (a.max(b), h));
        let mut edges = Vec::with_capacity(half.len() / 2 + 1);
        let mut offsets = Vec::with_capacity(half.len() / 2 + 2);
        let mut uses = Vec::with_capacity(half.len());
        let mut triangle_edges = vec![[Self::NO_EDGE; 3]; mesh.triangles.len()];
        for lo in 0..nv {
            let bucket = &mut half[start[lo] as usize..start[lo + 1] as usize];
            bucket.sort_unstable();
            let mut prev = None;
            for &(hi, h) in bucket.iter() {
                if prev != Some(hi) {
                    prev = Some(hi);
                    offsets.push(uses.len() as u32);
                    edges.push([lo as u32, hi]);
                }
                let u = EdgeUse::of(mesh, lo, h);
                triangle_edges[u.triangle as usize][u.corner as usize] = (edges.len() - 1) as u32;
                uses.push(u);
            }
        }
        offsets.push(uses.len() as u32);
        EdgeTopology {
            edges,
            offsets,
            uses,
            triangle_edges,
        }
    }

    /// Number of undirected edges.
    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }

    /// The uses of edge `e`.
    #[inline]
    pub fn uses_of(&self, e: usize) -> &[EdgeUse] {
        &self.uses[self.offsets[e] as usize..self.offsets[e + 1] as usize]
    }

    /// Classifies edge `e` by how it is used.
    pub fn kind(&self, e: usize) -> EdgeKind {
        match self.uses_of(e) {
            [_] => EdgeKind::Boundary,
            [a, b] if a.forward != b.forward => EdgeKind::Manifold,
            [_, _] => EdgeKind::Inconsistent,
            _ => EdgeKind::NonManifold,
        }
    }

    /// The first edge of `kind` (edges in the order of their vertices), if any.
    pub fn first_of(&self, kind: EdgeKind) -> Option<usize> {
        (0..self.edge_count()).find(|&e| self.kind(e) == kind)
    }

    /// The midpoint of edge `e` of `mesh` (the mesh of this adjacency): where to find it,
    /// in a message.
    pub fn midpoint(&self, mesh: &Mesh, e: usize) -> [f64; 3] {
        let [u, v] = self.edges[e].map(|i| mesh.positions[i as usize]);
        std::array::from_fn(|k| 0.5 * (u[k] + v[k]))
    }

    /// How many edges there are of each [`EdgeKind`].
    pub fn kind_counts(&self) -> EdgeCounts {
        let mut c = EdgeCounts::default();
        for e in 0..self.edge_count() {
            *match self.kind(e) {
                EdgeKind::Boundary => &mut c.boundary,
                EdgeKind::Manifold => &mut c.manifold,
                EdgeKind::Inconsistent => &mut c.inconsistent,
                EdgeKind::NonManifold => &mut c.non_manifold,
            } += 1;
        }
        c
    }

    /// True when every edge has exactly two uses (no boundary, no non-manifold edge) and
    /// there is at least one edge.
    pub fn is_closed(&self) -> bool {
        !self.edges.is_empty() && self.offsets.windows(2).all(|w| w[1] - w[0] == 2)
    }

    /// True when every edge is used as often in one direction as in the other (none on a
    /// boundary, none inconsistent; edges of four, six, ... triangles allowed): the
    /// surface is a cycle, and its winding number is an integer defined at every point
    /// off it, even where it is not manifold (closed parts glued along an edge or face
    /// to face, a face given twice in opposite directions).
    pub fn is_balanced(&self) -> bool {
        (0..self.edge_count()).all(|e| {
            let uses = self.uses_of(e);
            2 * uses.iter().filter(|u| u.forward).count() == uses.len()
        })
    }

    /// Edge-connected components: triangles sharing an edge (of any kind) are in the same
    /// component. Returns the number of components and each triangle's component id;
    /// ids are numbered in order of each component's first triangle.
    pub fn components(&self) -> (usize, Vec<u32>) {
        self.components_across(|_| true)
    }

    /// [`EdgeTopology::components`] joining triangles only across the edges `e` for which
    /// `join(e)` holds (e.g. not across seam edges). Union-find streaming over the edges:
    /// cache-friendly even when triangles are not stored in spatial order.
    pub fn components_across(&self, join: impl Fn(usize) -> bool) -> (usize, Vec<u32>) {
        let mut roots = Roots::new(self.triangle_edges.len());
        for e in 0..self.edges.len() {
            if join(e) {
                roots.join_all(self.uses_of(e));
            }
        }
        roots.labels()
    }
}

/// Union-find over triangles, or any ids (path halving; the lower id stays the root, so
/// that labels can follow triangle order).
pub(crate) struct Roots {
    parent: Vec<u32>,
}

impl Roots {
    pub(crate) fn new(n: usize) -> Self {
        Roots {
            parent: (0..n as u32).collect(),
        }
    }

    pub(crate) fn find(&mut self, mut x: u32) -> u32 {
        let parent = &mut self.parent;
        while parent[x as usize] != x {
            let up = parent[parent[x as usize] as usize];
            parent[x as usize] = up;
            x = up;
        }
        x
    }

    /// Puts the triangles of all `uses` into one component.
    fn join_all(&mut self, uses: &[EdgeUse]) {
        for w in uses.windows(2) {
            self.join(w[0].triangle, w[1].triangle);
        }
    }

    /// Puts `a` and `b` into one component: Rem's algorithm with splicing (the two paths
    /// to the roots climbed together, the higher parent always spliced onto the lower),
    /// which stops as soon as the paths meet and shortens them as it goes; every parent
    /// stays below its child, so each root is its set's lowest triangle.
    pub(crate) fn join(&mut self, a: u32, b: u32) {
        splice(&mut self.parent, 0, a, b);
    }

    /// The number of components and each triangle's component, numbered in order of each
    /// component's first triangle.
    fn labels(mut self) -> (usize, Vec<u32>) {
        let n = self.parent.len();
        let mut label = vec![u32::MAX; n];
        let mut count = 0u32;
        let out = (0..n as u32)
            .map(|t| {
                let r = self.find(t) as usize;
                if label[r] == u32::MAX {
                    label[r] = count;
                    count += 1;
                }
                label[r]
            })
            .collect();
        (count as usize, out)
    }
}

/// [`Roots::join`] on the ids `base..` whose parents are `parent` (each id's parent at
/// `id - base`; `a` and `b` and every parent on their paths in that range).
fn splice(parent: &mut [u32], base: u32, mut a: u32, mut b: u32) {
    let at = |x: u32| (x - base) as usize;
    loop {
        let (pa, pb) = (parent[at(a)], parent[at(b)]);
        if pa == pb {
            return;
        }
        if pa < pb {
            (a, b) = (b, a);
            continue;
        }
        // parent(a) > parent(b): splice `a` onto `b`'s parent.
        parent[at(a)] = pb;
        if pa == a {
            return; // `a` was a root: now linked
        }
        a = pa;
    }
}

/// Each triangle's component (triangles connected through shared vertices) as the
/// component's lowest vertex, for `triangles` over `n` vertices; the same on any number
/// of threads. Consecutive chunks of triangles are joined side by side, each in its own
/// range of vertices: those above every vertex the chunks before it name, up to the
/// highest it names. Edges with an end outside its range are joined afterwards: on one
/// thread where they are few, as vertices numbered in order of first use (as the
/// readers' weld numbers them) leave them (those reaching back across a chunk's start);
/// side by side in the shared union-find where they are many (another numbering). The
/// components are the same either way.
pub(crate) fn vertex_components(triangles: &[[u32; 3]], n: usize) -> Vec<u32> {
    use rayon::prelude::*;
    let threads = rayon::current_num_threads();
    let chunk = if threads == 1 {
        triangles.len().max(1)
    } else {
        triangles.len().div_ceil(4 * threads).max(1 << 12)
    };
    // Range k ends past the highest vertex chunks 0..=k name (the last at `n`).
    let highest: Vec<usize> = if chunk >= triangles.len() {
        vec![n]
    } else {
        triangles
            .par_chunks(chunk)
            .grained()
            .map(|c| c.iter().flatten().max().map_or(0, |&m| m as usize + 1))
            .collect()
    };
    let mut ends: Vec<usize> = highest
        .iter()
        .scan(0, |end, &h| {
            *end = h.max(*end).min(n);
            Some(*end)
        })
        .collect();
    if let Some(last) = ends.last_mut() {
        *last = n;
    }
    let starts: Vec<usize> = std::iter::once(0).chain(ends.iter().copied()).collect();
    let lengths: Vec<usize> = ends.iter().zip(&starts).map(|(e, s)| e - s).collect();
    let mut parent: Vec<u32> = (0..n as u32).into_par_iter().grained().collect();
    let across: Vec<Vec<[u32; 2]>> = crate::par::split_by(&mut parent, &lengths)
        .into_par_iter()
        .grained()
        .zip(triangles.par_chunks(chunk).grained())
        .zip(&starts)
        .map(|((range, tris), &start)| {
            let (lo, hi) = (start as u32, (start + range.len()) as u32);
            let mut across = Vec::new();
            for &[a, b, c] in tris {
                for (x, y) in [(a, b), (a, c)] {
                    if (lo..hi).contains(&x) && (lo..hi).contains(&y) {
                        splice(range, lo, x, y);
                    } else {
                        across.push([x, y]);
                    }
                }
            }
            across
        })
        .collect();
    // The edges across ranges: on one thread where few (numbering by first use); where
    // many (a numbering that puts far vertices in early chunks), side by side in the
    // shared union-find, which also keeps every parent below its child.
    let count: usize = across.iter().map(Vec::len).sum();
    let mut parent = if threads > 2 && count > triangles.len() / 4 {
        let shared = SharedRoots {
            parent: parent
                .into_par_iter()
                .grained()
                .map(std::sync::atomic::AtomicU32::new)
                .collect(),
        };
        across.par_iter().grained().for_each(|pairs| {
            pairs
                .par_chunks(1 << 12)
                .grained()
                .for_each(|c| c.iter().for_each(|&[x, y]| shared.join(x, y)))
        });
        shared
            .parent
            .into_par_iter()
            .grained()
            .map(std::sync::atomic::AtomicU32::into_inner)
            .collect()
    } else {
        let mut roots = Roots { parent };
        for [x, y] in across.into_iter().flatten() {
            roots.join(x, y);
        }
        roots.parent
    };
    // Every parent is below its child: in increasing order, each vertex's parent is
    // already its root.
    for x in 0..n {
        parent[x] = parent[parent[x] as usize];
    }
    triangles
        .par_iter()
        .grained()
        .map(|t| parent[t[0] as usize])
        .collect()
}

/// A half-edge `a → b` with id `h` as [`SeamTopology::new`] buckets it: higher vertex and
/// id in one sortable word.
fn seam_word(a: u32, b: u32, h: u32) -> u64 {
    (u64::from(a.max(b)) << 32) | u64::from(h)
}

/// Edge `[lo, hi]` as one word that sorts as the pair does.
pub(crate) fn edge_word(lo: u32, hi: u32) -> u64 {
    (u64::from(lo) << 32) | u64::from(hi)
}

/// The edges whose lower vertex lies in one range, as [`SeamTopology::new`] needs them.
struct SeamPiece {
    /// The seam edges in the range, in order, with the start of each one's uses.
    edges: Vec<[u32; 2]>,
    offsets: Vec<u32>,
    uses: Vec<EdgeUse>,
    /// Whether the range has an edge, and whether every one of its edges is closed.
    any: bool,
    closed: bool,
}

impl SeamPiece {
    /// Scans the edges whose lower vertex is in `v0..v1`: those on the `seam` (sorted
    /// [`edge_word`]s; `on_seam` marks their lower vertices) are listed with their uses,
    /// and the triangles around every other edge are handed to `join`, pair by pair
    /// (consecutive uses).
    fn scan(
        mesh: &Mesh,
        v0: u32,
        v1: u32,
        seam: &[u64],
        on_seam: &[bool],
        join: impl FnMut(u32, u32),
    ) -> SeamPiece {
        let (start, half) = bucket_by_lower(mesh, v0, v1, seam_word);
        SeamPiece::of_buckets(mesh, v0, &start, half, seam, on_seam, join)
    }

    /// [`SeamPiece::scan`] of the half-edges already bucketed by lower vertex from `v0`
    /// on, as [`seam_word`]s.
    fn of_buckets(
        mesh: &Mesh,
        v0: u32,
        start: &[u32],
        mut half: Vec<u64>,
        seam: &[u64],
        on_seam: &[bool],
        mut join: impl FnMut(u32, u32),
    ) -> SeamPiece {
        // Room for the seam edges whose lower vertex is in this range (`seam` is sorted)
        // and their two uses each.
        let v1 = v0 + (start.len() - 1) as u32;
        let below = |v: u32| seam.partition_point(|&w| (w >> 32) < u64::from(v));
        let room = below(v1) - below(v0);
        let mut out = SeamPiece {
            edges: Vec::with_capacity(room),
            offsets: Vec::with_capacity(room + 1),
            uses: Vec::with_capacity(2 * room),
            any: !half.is_empty(),
            closed: true,
        };
        let mut run: Vec<EdgeUse> = Vec::new();
        for i in 0..start.len() - 1 {
            let lo = v0 as usize + i;
            let bucket = &mut half[start[i] as usize..start[i + 1] as usize];
            bucket.sort_unstable();
            let mut rest = &*bucket;
            while let Some(&first) = rest.first() {
                let hi = (first >> 32) as u32;
                let n = rest.iter().take_while(|&&w| (w >> 32) as u32 == hi).count();
                let edge = [lo as u32, hi];
                let on = on_seam[lo] && seam.binary_search(&edge_word(lo as u32, hi)).is_ok();
                if n == 2 && !on {
                    // Most edges: two triangles joined, whichever way they run (closed).
                    join(rest[0] as u32 / 3, rest[1] as u32 / 3);
                    rest = &rest[n..];
                    continue;
                }
                run.clear();
                run.extend(rest[..n].iter().map(|&w| EdgeUse::of(mesh, lo, w as u32)));
                // Two uses, or more in as many pairs of opposite directions (closed
                // parts glued along the edge): the winding number is an integer.
                out.closed &=
                    n == 2 || (n > 2 && 2 * run.iter().filter(|u| u.forward).count() == n);
                if on {
                    out.edges.push(edge);
                    out.offsets.push(out.uses.len() as u32);
                    out.uses.extend_from_slice(&run);
                } else {
                    for w in run.windows(2) {
                        join(w[0].triangle, w[1].triangle);
                    }
                }
                rest = &rest[n..];
            }
        }
        out
    }
}

/// Union-find over triangles (or any ids) that threads join into together: the
/// concurrent form of [`Roots`]. A parent only ever moves to a lower id, and a root is linked, by
/// compare-and-swap, only under a lower root; so each root is its set's lowest triangle
/// whatever order the joins came in, and [`SharedRoots::labels`] equals [`Roots::labels`].
pub(crate) struct SharedRoots {
    parent: Vec<std::sync::atomic::AtomicU32>,
}

impl SharedRoots {
    pub(crate) fn new(n: usize) -> Self {
        use rayon::prelude::*;
        SharedRoots {
            parent: (0..n as u32)
                .into_par_iter()
                .grained()
                .map(std::sync::atomic::AtomicU32::new)
                .collect(),
        }
    }

    /// The root of `x`, halving the path on the way (a parent is replaced by its own
    /// parent where no other thread changed it meanwhile).
    pub(crate) fn find(&self, mut x: u32) -> u32 {
        use std::sync::atomic::Ordering::Relaxed;
        loop {
            let p = self.parent[x as usize].load(Relaxed);
            if p == x {
                return x;
            }
            let g = self.parent[p as usize].load(Relaxed);
            if g != p {
                let _ = self.parent[x as usize].compare_exchange_weak(p, g, Relaxed, Relaxed);
            }
            x = g;
        }
    }

    /// Puts `a` and `b` into one component: the higher root is linked under the lower,
    /// again from the roots if another thread linked it first.
    pub(crate) fn join(&self, a: u32, b: u32) {
        use std::sync::atomic::Ordering::{AcqRel, Relaxed};
        let (mut a, mut b) = (a, b);
        loop {
            (a, b) = (self.find(a), self.find(b));
            if a == b {
                return;
            }
            let (lo, hi) = (a.min(b), a.max(b));
            if self.parent[hi as usize]
                .compare_exchange(hi, lo, AcqRel, Relaxed)
                .is_ok()
            {
                return;
            }
        }
    }

    /// [`Roots::labels`]: a triangle is the first of its component exactly when it is
    /// its root, so a component's number is its root's rank among the roots.
    fn labels(self) -> (usize, Vec<u32>) {
        use rayon::prelude::*;
        const CHUNK: usize = 1 << 16;
        let roots: Vec<u32> = (0..self.parent.len() as u32)
            .into_par_iter()
            .grained()
            .map(|t| self.find(t))
            .collect();
        let firsts: Vec<u32> = roots
            .par_chunks(CHUNK)
            .grained()
            .enumerate()
            .map(|(c, r)| {
                let base = (c * CHUNK) as u32;
                r.iter()
                    .enumerate()
                    .filter(|&(i, &x)| x == base + i as u32)
                    .count() as u32
            })
            .collect();
        let mut base = Vec::with_capacity(firsts.len());
        let mut count = 0u32;
        for f in firsts {
            base.push(count);
            count += f;
        }
        let mut rank = vec![0u32; roots.len()];
        rank.par_chunks_mut(CHUNK)
            .grained()
            .zip(roots.par_chunks(CHUNK).grained())
            .enumerate()
            .for_each(|(c, (rank, r))| {
                let (mut next, first) = (base[c], (c * CHUNK) as u32);
                for (i, (k, &x)) in rank.iter_mut().zip(r).enumerate() {
                    if x == first + i as u32 {
                        *k = next;
                        next += 1;
                    }
                }
            });
        let label = roots
            .par_iter()
            .grained()
            .map(|&r| rank[r as usize])
            .collect();
        (count as usize, label)
    }
}

/// What the boolean's classification needs of an arranged mesh's edges, without the full
/// adjacency of [`EdgeTopology`] (a fraction of its memory and time on large meshes): the
/// patches (components joined across every edge but the seam edges), the uses of the seam
/// edges, and whether the mesh is closed. Part of the pipeline, not of the public surface.
#[doc(hidden)]
#[derive(Clone, Debug, Default)]
pub struct SeamTopology {
    /// The seam edges that are edges of the mesh, as `[lo, hi]` (`lo < hi`), sorted.
    pub edges: Vec<[u32; 2]>,
    offsets: Vec<u32>,
    uses: Vec<EdgeUse>,
    /// Number of patches.
    pub patches: usize,
    /// Patch of every triangle, numbered in order of each patch's first triangle (the
    /// numbering of [`EdgeTopology::components_across`]).
    pub patch: Vec<u32>,
    closed: bool,
}

impl SeamTopology {
    /// The seam structure of `mesh` cut along `seam` (vertex
    /// pairs, in any order; pairs that are not edges of the mesh are ignored).
    pub fn new(mesh: &Mesh, seam: &[[u32; 2]]) -> Self {
        use rayon::prelude::*;
        let nv = mesh.positions.len();
        // One word per edge (sorted faster than pairs).
        let mut seam: Vec<u64> = seam
            .iter()
            .map(|&[u, v]| edge_word(u.min(v), u.max(v)))
            .collect();
        seam.sort_unstable();
        seam.dedup();
        let mut on_seam = vec![false; nv];
        for &w in &seam {
            on_seam[(w >> 32) as usize] = true;
        }
        let threads = rayon::current_num_threads();
        let (pieces, (patches, patch)) = if threads <= 2 || mesh.triangles.len() < 1 << 16 {
            let mut roots = Roots::new(mesh.triangles.len());
            let piece =
                SeamPiece::scan(mesh, 0, nv as u32, &seam, &on_seam, |a, b| roots.join(a, b));
            (vec![piece], roots.labels())
        } else {
            // Vertex ranges side by side, joining into one shared union-find.
            let roots = SharedRoots::new(mesh.triangles.len());
            let step = nv.div_ceil(4 * threads.min(64)) as u32;
            let pieces = bucket_ranges(mesh, step, seam_word)
                .into_par_iter()
                .grained()
                .map(|(v0, _, start, half)| {
                    SeamPiece::of_buckets(mesh, v0, &start, half, &seam, &on_seam, |a, b| {
                        roots.join(a, b)
                    })
                })
                .collect();
            (pieces, roots.labels())
        };
        let mut out = SeamTopology {
            closed: pieces.iter().any(|p| p.any) && pieces.iter().all(|p| p.closed),
            patches,
            patch,
            ..SeamTopology::default()
        };
        match <[SeamPiece; 1]>::try_from(pieces) {
            // One piece (a serial scan): its arrays as they are.
            Ok([p]) => (out.edges, out.offsets, out.uses) = (p.edges, p.offsets, p.uses),
            Err(pieces) => {
                for p in pieces {
                    let base = out.uses.len() as u32;
                    out.edges.extend(p.edges);
                    out.offsets.extend(p.offsets.iter().map(|&o| o + base));
                    out.uses.extend(p.uses);
                }
            }
        }
        out.offsets.push(out.uses.len() as u32);
        out
    }

    /// The uses of seam edge `e` (an index into [`SeamTopology::edges`]), in triangle order.
    pub fn uses_of(&self, e: usize) -> &[EdgeUse] {
        &self.uses[self.offsets[e] as usize..self.offsets[e + 1] as usize]
    }

    /// True when there is at least one edge and every edge has exactly two uses, or
    /// more with as many running each way (closed parts glued along it, as in a union
    /// kept non-manifold): the mesh bounds a solid, its winding number an integer off it.
    /// (Not [`EdgeTopology::is_closed`], which wants two uses everywhere.)
    pub fn is_closed(&self) -> bool {
        self.closed
    }
}

/// The components of a mesh as triangle lists ([`components_merged`]).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Components {
    /// Triangle ids of each component, largest component first (ties: the one whose first
    /// triangle comes first); ids ascending within a component.
    pub parts: Vec<Vec<u32>>,
    /// Components below the size limit that were merged into a larger one.
    pub merged: usize,
}

/// The edge-connected components of `mesh`, largest first, with every component of fewer
/// than `min_triangles` triangles merged into the nearest component that is not small:
/// the one with a vertex closest to the small component's centroid (the seed library's
/// stray-fragment clean-up after a split; merged parts are no longer connected). With no
/// component at or over the limit, nothing is merged. `min_triangles = 0` only sorts.
pub fn components_merged(mesh: &Mesh, min_triangles: usize) -> Components {
    let (count, ids) = EdgeTopology::new(mesh).components();
    let mut parts: Vec<Vec<u32>> = vec![Vec::new(); count];
    for (t, &c) in ids.iter().enumerate() {
        parts[c as usize].push(t as u32);
    }
    // Stable: equal sizes keep the order of their first triangles.
    parts.sort_by_key(|p| std::cmp::Reverse(p.len()));
    let big = parts
        .iter()
        .take_while(|p| p.len() >= min_triangles)
        .count();
    if big == 0 || big == parts.len() {
        return Components { parts, merged: 0 };
    }
    // Nearest big component to each small one's centroid, by its closest vertex.
    let small = parts.split_off(big);
    let vertices_of = |p: &[u32]| {
        let mut v: Vec<u32> = p.iter().flat_map(|&t| mesh.triangles[t as usize]).collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let big_vertices: Vec<Vec<u32>> = parts.iter().map(|p| vertices_of(p)).collect();
    let merged = small.len();
    for p in small {
        let vs = vertices_of(&p);
        let c: [f64; 3] = std::array::from_fn(|k| {
            vs.iter()
                .map(|&v| mesh.positions[v as usize][k])
                .sum::<f64>()
                / vs.len() as f64
        });
        let d2 = |v: u32| {
            let q = mesh.positions[v as usize];
            (0..3).map(|k| (q[k] - c[k]) * (q[k] - c[k])).sum::<f64>()
        };
        let nearest = (0..big)
            .map(|i| {
                let d = big_vertices[i]
                    .iter()
                    .map(|&v| d2(v))
                    .fold(f64::INFINITY, f64::min);
                (d, i)
            })
            .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)))
            .map_or(0, |(_, i)| i);
        parts[nearest].extend(p);
    }
    for p in &mut parts {
        p.sort_unstable();
    }
    Components { parts, merged }
}

/// Edge counts by kind ([`EdgeTopology::kind_counts`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EdgeCounts {
    /// Edges used by one triangle.
    pub boundary: usize,
    /// Edges used by two triangles in opposite directions.
    pub manifold: usize,
    /// Edges used by two triangles in the same direction.
    pub inconsistent: usize,
    /// Edges used by more than two triangles.
    pub non_manifold: usize,
}

impl EdgeCounts {
    /// Counts the edges of `mesh` by kind, the same counts as
    /// [`EdgeTopology::kind_counts`] without building the adjacency: what the input checks
    /// and result reports need, in a fraction of the memory. The half-edges are bucketed
    /// by lower vertex (a counting sort, in vertex ranges side by side on several threads)
    /// and the runs of each small bucket sorted by higher vertex are counted.
    pub fn of(mesh: &Mesh) -> EdgeCounts {
        use rayon::prelude::*;
        let nv = mesh.positions.len();
        let threads = rayon::current_num_threads();
        let add = |a: EdgeCounts, b: EdgeCounts| EdgeCounts {
            boundary: a.boundary + b.boundary,
            manifold: a.manifold + b.manifold,
            inconsistent: a.inconsistent + b.inconsistent,
            non_manifold: a.non_manifold + b.non_manifold,
        };
        if mesh.triangles.len() < 1 << 16 || threads == 1 {
            return counts_in_range(mesh, 0, nv as u32);
        }
        if threads == 2 {
            // Two ranges, each scanning every triangle: less memory traffic than listing
            // the half-edges first, which pays from more threads on.
            let half = (nv / 2) as u32;
            let (a, b) = crate::par::join(
                || counts_in_range(mesh, 0, half),
                || counts_in_range(mesh, half, nv as u32),
            );
            return add(a, b);
        }
        let step = nv.div_ceil(4 * threads.min(64)) as u32;
        bucket_ranges(mesh, step, count_word)
            .into_par_iter()
            .grained()
            .map(|(v0, v1, start, mut half)| count_buckets(v1 - v0, &start, &mut half))
            .reduce(EdgeCounts::default, add)
    }
}

/// The edges of `mesh` whose uses do not cancel: `([lo, hi], n)` with `n` the number of
/// uses running `lo → hi` less those running back, where not zero. Together they are the
/// boundary of the triangles as a chain (each triangle's edges added with its
/// orientation): empty for a closed, consistently oriented mesh; an open surface's
/// boundary loops; twice an edge whose two uses run the same way. In edge order.
pub(crate) fn unbalanced_edges(mesh: &Mesh) -> Vec<([u32; 2], i32)> {
    let nv = mesh.positions.len() as u32;
    // One word per half-edge: the higher vertex, and whether the half-edge runs up.
    let (start, mut half) = bucket_by_lower(mesh, 0, nv, |a, b, _| {
        (u64::from(a.max(b)) << 1) | u64::from(a < b)
    });
    let mut out = Vec::new();
    for lo in 0..nv as usize {
        let bucket = &mut half[start[lo] as usize..start[lo + 1] as usize];
        bucket.sort_unstable();
        let mut rest = &*bucket;
        while let Some(&first) = rest.first() {
            let n = rest.iter().take_while(|&&w| w >> 1 == first >> 1).count();
            let up = rest[..n].iter().filter(|&&w| w & 1 == 1).count() as i32;
            let net = 2 * up - n as i32;
            if net != 0 {
                out.push(([lo as u32, (first >> 1) as u32], net));
            }
            rest = &rest[n..];
        }
    }
    out
}

/// The half-edges of `mesh` whose lower vertex lies in `v0..v1`, bucketed by that vertex
/// (a counting sort; triangle order within a bucket): `half[start[i]..start[i + 1]]` holds
/// `entry(a, b, id)` for each half-edge `a → b` with lower vertex `v0 + i`, `id` being
/// `3 · triangle + corner`. Half-edges from a vertex to itself are left out.
fn bucket_by_lower<T: Copy + Default>(
    mesh: &Mesh,
    v0: u32,
    v1: u32,
    entry: impl Fn(u32, u32, u32) -> T,
) -> (Vec<u32>, Vec<T>) {
    bucket_by_lower_of(mesh.triangles.len(), |t| mesh.triangles[t], v0, v1, entry)
}

/// [`bucket_by_lower`] of the triangles `triangle(0)`, …, `triangle(count − 1)` (a subset
/// of a mesh's, or any), `id` being `3 · i + corner` for the `i`-th.
pub(crate) fn bucket_by_lower_of<T: Copy + Default>(
    count: usize,
    triangle: impl Fn(usize) -> [u32; 3],
    v0: u32,
    v1: u32,
    entry: impl Fn(u32, u32, u32) -> T,
) -> (Vec<u32>, Vec<T>) {
    let n = v1.saturating_sub(v0) as usize;
    let lower =
        |a: u32, b: u32| (a != b && (v0..v1).contains(&a.min(b))).then(|| (a.min(b) - v0) as usize);
    let mut start = vec![0u32; n + 1];
    for t in 0..count {
        let tri = triangle(t);
        for k in 0..3 {
            if let Some(lo) = lower(tri[k], tri[(k + 1) % 3]) {
                start[lo + 1] += 1;
            }
        }
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut half = vec![T::default(); start[n] as usize];
    for t in 0..count {
        let tri = triangle(t);
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            if let Some(lo) = lower(a, b) {
                half[fill[lo] as usize] = entry(a, b, (t as u32) * 3 + k as u32);
                fill[lo] += 1;
            }
        }
    }
    (start, half)
}

/// The half-edges bucketed as [`bucket_by_lower`] buckets them, for every range of
/// vertices (`[p · step, (p + 1) · step)`, the last one clipped; `step` rounded down to
/// a power of two, so that a vertex's range is a shift), on all threads: per chunk of
/// triangles, each range's half-edges are counted, then listed in place (each chunk into
/// its own slice of every range's list: no list grows), one word each: the lower vertex's
/// offset in its range above the corner; then per range, its list is bucketed by lower
/// vertex, each entry made from its corner's triangle. Each range's `(v0, v1, start,
/// half)` is what `bucket_by_lower(mesh, v0, v1, entry)` gives.
fn bucket_ranges<T: Copy + Default + Send + Sync>(
    mesh: &Mesh,
    step: u32,
    entry: impl Fn(u32, u32, u32) -> T + Sync,
) -> Vec<(u32, u32, Vec<u32>, Vec<T>)> {
    use crate::par::split_by;
    use rayon::prelude::*;
    const CHUNK: usize = 1 << 15;
    let nv = mesh.positions.len() as u32;
    // The largest power of two not above `step` (at most 2^31).
    let shift = 31 - step.max(1).leading_zeros();
    let mask = (1u32 << shift) - 1;
    let parts = nv.div_ceil(1 << shift).max(1) as usize;
    // The lower vertex of each half-edge of triangle `tri` that is not a loop, with the
    // half-edge's corner.
    let lower = |tri: [u32; 3]| {
        (0..3).filter_map(move |k| {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            (a != b).then(|| (a.min(b), k))
        })
    };
    let counts: Vec<Vec<u32>> = mesh
        .triangles
        .par_chunks(CHUNK)
        .grained()
        .map(|tris| {
            let mut c = vec![0u32; parts];
            for &tri in tris {
                for (lo, _) in lower(tri) {
                    c[(lo >> shift) as usize] += 1;
                }
            }
            c
        })
        .collect();
    // Per range, its half-edges chunk after chunk: the lower vertex's offset in the range
    // (below 2^31) in the high half of a word, the corner (`3t + k`) in the low half.
    let mut lists: Vec<Vec<u64>> = (0..parts)
        .into_par_iter()
        .grained()
        .map(|p| vec![0u64; counts.iter().map(|c| c[p] as usize).sum()])
        .collect();
    let mut slices: Vec<Vec<&mut [u64]>> =
        counts.iter().map(|_| Vec::with_capacity(parts)).collect();
    for (p, words) in lists.iter_mut().enumerate() {
        let lengths: Vec<usize> = counts.iter().map(|c| c[p] as usize).collect();
        for (chunk, piece) in slices.iter_mut().zip(split_by(words, &lengths)) {
            chunk.push(piece);
        }
    }
    mesh.triangles
        .par_chunks(CHUNK)
        .grained()
        .zip(slices)
        .enumerate()
        .for_each(|(c, (tris, mut slices))| {
            let mut at = vec![0usize; parts];
            for (i, &tri) in tris.iter().enumerate() {
                let t = (c * CHUNK + i) as u32;
                for (lo, k) in lower(tri) {
                    let p = (lo >> shift) as usize;
                    slices[p][at[p]] = (u64::from(lo & mask) << 32) | u64::from(3 * t + k as u32);
                    at[p] += 1;
                }
            }
        });
    lists
        .into_par_iter()
        .grained()
        .enumerate()
        .map(|(p, words)| {
            let v0 = ((p as u64) << shift).min(u64::from(nv)) as u32;
            let v1 = ((p as u64 + 1) << shift).min(u64::from(nv)) as u32;
            let n = (v1 - v0) as usize;
            let mut start = vec![0u32; n + 1];
            for &w in &words {
                start[(w >> 32) as usize + 1] += 1;
            }
            for i in 0..n {
                start[i + 1] += start[i];
            }
            let mut fill = start.clone();
            let mut half = vec![T::default(); words.len()];
            for &w in &words {
                let (i, h) = ((w >> 32) as usize, w as u32);
                let tri = mesh.triangles[(h / 3) as usize];
                let k = (h % 3) as usize;
                half[fill[i] as usize] = entry(tri[k], tri[(k + 1) % 3], h);
                fill[i] += 1;
            }
            (v0, v1, start, half)
        })
        .collect()
}

/// [`EdgeCounts::of`] for the edges whose lower vertex lies in `v0..v1`.
fn counts_in_range(mesh: &Mesh, v0: u32, v1: u32) -> EdgeCounts {
    if v0 >= v1 {
        return EdgeCounts::default();
    }
    let (start, mut half) = bucket_by_lower(mesh, v0, v1, count_word);
    count_buckets(v1 - v0, &start, &mut half)
}

/// A half-edge `a → b` as [`EdgeCounts`] buckets it: higher vertex and direction in one
/// key, so that a bucket sorts by edge.
fn count_word(a: u32, b: u32, _: u32) -> u64 {
    (u64::from(a.max(b)) << 1) | u64::from(a < b)
}

/// The edge counts of `n` buckets of [`count_word`]s, each bucket sorted here.
fn count_buckets(n: u32, start: &[u32], half: &mut [u64]) -> EdgeCounts {
    let mut c = EdgeCounts::default();
    for lo in 0..n as usize {
        let bucket = &mut half[start[lo] as usize..start[lo + 1] as usize];
        bucket.sort_unstable();
        for run in bucket.chunk_by(|x, y| x >> 1 == y >> 1) {
            *match run {
                [_] => &mut c.boundary,
                [x, y] if x != y => &mut c.manifold,
                [_, _] => &mut c.inconsistent,
                _ => &mut c.non_manifold,
            } += 1;
        }
    }
    c
}

/// How an undirected edge is used by the triangles around it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeKind {
    /// Used by exactly one triangle: on the mesh boundary.
    Boundary,
    /// Used by two triangles in opposite directions: a consistently oriented interior edge.
    Manifold,
    /// Used by two triangles in the same direction: their orientations disagree.
    Inconsistent,
    /// Used by more than two triangles.
    NonManifold,
}

/// The uses' indices ordered by the angle of their far vertices around the axis `p -> q`,
/// counter-clockwise, starting at the first use's far vertex; at equal angles those
/// running `p -> q` (whose inside is before them) first, by increasing triangle, then the
/// others by decreasing triangle.
/// Exact (`orient3d` on the points). Far vertices on the axis itself (zero-area
/// triangles) come first. `near` is `p`'s position (its coordinates when explicit).
pub(crate) fn angular_order(
    p: &Point,
    q: &Point,
    near: [f64; 3],
    items: &[(u32, bool, Point, u32)],
) -> Vec<usize> {
    // Four explicit points no plane holds all of: `near` and three moved along one axis
    // each (to a different, finite value).
    let probes: [Point; 4] = std::array::from_fn(|k| {
        let mut x = near;
        if k < 3 {
            x[k] = if x[k] > 0.0 {
                x[k] / 2.0 - 1.0
            } else {
                x[k] / 2.0 + 1.0
            };
        }
        Point::Explicit(x)
    });
    // A reference direction: a far vertex off the axis, and a point off the plane through
    // the axis and it (to tell its ray from the opposite one).
    let off_axis = |w: &Point| {
        probes
            .iter()
            .find(|aux| orient3d(p, q, w, aux) != Sign::Zero)
    };
    // Non-finite coordinates (a public caller's broken mesh) have no angles: the order by
    // triangle, as for far vertices all on the axis.
    let finite = |x: &Point| !matches!(x, Point::Explicit(c) if !c.iter().all(|v| v.is_finite()));
    let all_finite = finite(p) && finite(q) && near.iter().all(|v| v.is_finite());
    let reference = || items.iter().find_map(|it| Some((&it.2, off_axis(&it.2)?)));
    let usable = all_finite && items.iter().all(|it| finite(&it.2));
    let Some((w0, aux)) = usable.then(reference).flatten() else {
        let mut all: Vec<usize> = (0..items.len()).collect();
        all.sort_by_key(|&i| items[i].3);
        return all;
    };
    let side0 = orient3d(p, q, aux, w0);
    // Half-turn 0: angles in [0, π); 1: [π, 2π); rank 0 within a half for its first ray.
    let key = |w: &Point| -> (u8, u8) {
        match orient3d(p, q, w0, w) {
            Sign::Positive => (0, 1),
            Sign::Negative => (1, 1),
            Sign::Zero => match orient3d(p, q, aux, w) {
                s if s == side0 => (0, 0),
                Sign::Zero => (0, 0),
                _ => (1, 0),
            },
        }
    };
    let keys: Vec<(u8, u8)> = items.iter().map(|it| key(&it.2)).collect();
    let mut order: Vec<usize> = (0..items.len()).collect();
    order.sort_by(|&i, &j| {
        keys[i].cmp(&keys[j]).then_with(|| {
            let by_angle = if keys[i].1 == 1 {
                // Same open half-turn: j comes later when it lies counter-clockwise of i.
                match orient3d(p, q, &items[i].2, &items[j].2) {
                    Sign::Positive => std::cmp::Ordering::Less,
                    Sign::Negative => std::cmp::Ordering::Greater,
                    Sign::Zero => std::cmp::Ordering::Equal,
                }
            } else {
                std::cmp::Ordering::Equal
            };
            // At one angle (faces on faces), the one bounding the wedge before it first;
            // coincident layers by triangle, closes up and opens down, so that the
            // matching pairs the k-th lowest open with the k-th lowest close (a part given
            // twice pairs each copy with itself at every edge).
            by_angle.then(items[j].1.cmp(&items[i].1)).then_with(|| {
                if items[i].1 {
                    items[i].3.cmp(&items[j].3)
                } else {
                    items[j].3.cmp(&items[i].3)
                }
            })
        })
    });
    order
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_has_18_manifold_edges_and_one_component() {
        let topo = EdgeTopology::new(&Mesh::unit_cube());
        assert_eq!(topo.edge_count(), 18);
        assert!((0..18).all(|e| topo.kind(e) == EdgeKind::Manifold));
        assert_eq!(topo.components(), (1, vec![0; 12]));
        for (t, te) in topo.triangle_edges.iter().enumerate() {
            for &e in te {
                assert!(topo
                    .uses_of(e as usize)
                    .iter()
                    .any(|u| u.triangle == t as u32));
            }
        }
    }

    #[test]
    fn kinds_of_edges() {
        // Two triangles sharing edge 0-1 in the same direction, a third sharing it too.
        let m = Mesh::new_unchecked(
            vec![
                [0.0; 3],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, -1.0, 0.0],
                [0.0, 0.0, 1.0],
            ],
            vec![[0, 1, 2], [0, 1, 3]],
        );
        let topo = EdgeTopology::new(&m);
        let e01 = topo.edges.iter().position(|&e| e == [0, 1]).unwrap();
        assert_eq!(topo.kind(e01), EdgeKind::Inconsistent);
        let mut m3 = m.clone();
        m3.triangles.push([1, 0, 4]);
        let topo = EdgeTopology::new(&m3);
        assert_eq!(topo.kind(e01), EdgeKind::NonManifold);
        assert_eq!(topo.components().0, 1);
    }

    #[test]
    fn components_in_first_triangle_order() {
        let mut a = Mesh::cuboid([5.0; 3], [6.0; 3]);
        let b = Mesh::unit_cube();
        let off = a.positions.len() as u32;
        a.positions.extend(&b.positions);
        // Interleave the triangles of the two cubes.
        let tris_a = a.triangles.clone();
        a.triangles.clear();
        for (ta, tb) in tris_a.iter().zip(&b.triangles) {
            a.triangles.push(tb.map(|i| i + off));
            a.triangles.push(*ta);
        }
        let (n, ids) = EdgeTopology::new(&a).components();
        assert_eq!(n, 2);
        assert_eq!(&ids[..4], &[0, 1, 0, 1]);
    }

    #[test]
    fn lean_counts_agree_with_the_topology() {
        // A large sphere (split among threads) broken in every way: a hole (boundary),
        // flipped triangles (inconsistent), a triangle repeated three times
        // (non-manifold), a repeated-vertex triangle (its loop edge is not an edge).
        let mut m = crate::shapes::uv_sphere([0.0; 3], 1.0, 300, 150);
        assert!(m.triangles.len() > 1 << 16);
        m.triangles.remove(1000);
        for t in [5000, 20000, 60000] {
            let [a, b, c] = m.triangles[t];
            m.triangles[t] = [a, c, b];
        }
        let t = m.triangles[30000];
        m.triangles.extend([t, t]);
        m.triangles.push([7, 7, 9]);
        let want = EdgeTopology::new(&m).kind_counts();
        assert!(want.boundary > 0 && want.inconsistent > 0 && want.non_manifold > 0);
        assert_eq!(EdgeCounts::of(&m), want);
        // The same mesh with its vertices numbered far from their triangles' order.
        let nv = m.positions.len() as u64;
        assert!(nv % 7919 != 0);
        let mut spread = m.clone();
        for t in &mut spread.triangles {
            *t = t.map(|v| (u64::from(v) * 7919 % nv) as u32);
        }
        let cube = EdgeCounts::of(&Mesh::unit_cube());
        assert_eq!((cube.manifold, cube.boundary), (18, 0));
        assert_eq!(EdgeCounts::of(&Mesh::default()), EdgeCounts::default());
        for threads in [1, 3, 7] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build();
            let pool = pool.expect("pool");
            assert_eq!(
                pool.install(|| EdgeCounts::of(&m)),
                want,
                "{threads} threads"
            );
            let got = pool.install(|| EdgeCounts::of(&spread));
            assert_eq!(got, want, "{threads} threads, spread");
        }
    }

    /// [`SeamTopology`] of `m` cut along `seam` against the same from the full adjacency.
    fn seam_topology_matches(m: &Mesh, seam: &[[u32; 2]]) -> SeamTopology {
        let full = EdgeTopology::new(m);
        let is_seam = |e: usize| {
            let [u, v] = full.edges[e];
            seam.iter().any(|s| *s == [u, v] || *s == [v, u])
        };
        let got = SeamTopology::new(m, seam);
        let (n, patch) = full.components_across(|e| !is_seam(e));
        assert_eq!((got.patches, &got.patch), (n, &patch));
        let edges: Vec<usize> = (0..full.edge_count()).filter(|&e| is_seam(e)).collect();
        assert_eq!(got.edges.len(), edges.len());
        for (k, &e) in edges.iter().enumerate() {
            assert_eq!(got.edges[k], full.edges[e]);
            assert_eq!(got.uses_of(k), full.uses_of(e));
        }
        assert_eq!(got.is_closed(), full.is_closed());
        got
    }

    #[test]
    fn union_find_gives_the_connected_components() {
        // Random joins (chains, stars, repeats, self-joins) against labels spread to a
        // fixed point: the same sets, numbered in order of their first element.
        let mut rng = crate::test_util::Rng(0x5e75);
        for (n, joins) in [(1usize, 3usize), (50, 30), (2000, 1500), (2000, 5000)] {
            let pairs: Vec<(u32, u32)> = (0..joins)
                .map(|_| {
                    let a = (rng.next() % n as u64) as u32;
                    (a, (rng.next() % n as u64) as u32)
                })
                .collect();
            let mut roots = Roots::new(n);
            for &(a, b) in &pairs {
                roots.join(a, b);
            }
            let mut least: Vec<u32> = (0..n as u32).collect();
            let mut changed = true;
            while changed {
                changed = false;
                for &(a, b) in &pairs {
                    let m = least[a as usize].min(least[b as usize]);
                    for x in [a, b] {
                        if least[x as usize] != m {
                            least[x as usize] = m;
                            changed = true;
                        }
                    }
                }
            }
            let mut number = vec![u32::MAX; n];
            let mut count = 0;
            let want: Vec<u32> = least
                .iter()
                .map(|&r| {
                    if number[r as usize] == u32::MAX {
                        number[r as usize] = count;
                        count += 1;
                    }
                    number[r as usize]
                })
                .collect();
            assert_eq!(
                roots.labels(),
                (count as usize, want.clone()),
                "{n} {joins}"
            );
            // The shared union-find, joined from several threads at once.
            use rayon::prelude::*;
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(4)
                .build()
                .unwrap();
            let shared = SharedRoots::new(n);
            pool.install(|| {
                pairs
                    .par_iter()
                    .with_max_len(8)
                    .for_each(|&(a, b)| shared.join(a, b))
            });
            assert_eq!(shared.labels(), (count as usize, want), "{n} {joins}");
        }
    }

    /// Components through shared vertices, from chunks of triangles joined side by side:
    /// each triangle's component is its lowest vertex, as one union-find over every edge
    /// gives, for vertices numbered in order of first use and at random, on 1 to 8 threads.
    #[test]
    fn vertex_components_are_those_of_one_union_find() {
        let mut rng = crate::test_util::Rng(0xc0_ffee);
        // Many small strips (numbered in order of first use), a few long ones; each
        // triangle joins the strip's next vertex and one of its own, so that no join is
        // redundant.
        let mut triangles: Vec<[u32; 3]> = Vec::new();
        let mut next = 0u32;
        for strip in 0..400 {
            let len = if strip % 100 == 0 {
                5000
            } else {
                1 + rng.next() as u32 % 60
            };
            let base = next;
            for i in 0..len {
                triangles.push([base + 2 * i, base + 2 * i + 2, base + 2 * i + 1]);
            }
            next = base + 2 * len + 1;
        }
        let n = next as usize + 10; // a few vertices no triangle names
        let mut shuffled: Vec<u32> = (0..n as u32).collect();
        for i in (1..n).rev() {
            shuffled.swap(i, rng.next() as usize % (i + 1));
        }
        let renumbered: Vec<[u32; 3]> = triangles
            .iter()
            .map(|t| t.map(|v| shuffled[v as usize]))
            .collect();
        // Strips joined through a shared vertex far down the numbering.
        let mut joined = triangles.clone();
        joined.push([0, next - 1, next / 2]);
        assert!(triangles.len() > 1 << 14);
        for tris in [&triangles, &renumbered, &joined] {
            let mut roots = Roots::new(n);
            for &[a, b, c] in tris.iter() {
                roots.join(a, b);
                roots.join(a, c);
            }
            let want: Vec<u32> = tris.iter().map(|t| roots.find(t[0])).collect();
            for threads in [1, 3, 8] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                let got = pool.install(|| vertex_components(tris, n));
                assert_eq!(got, want, "{threads} threads");
            }
        }
    }

    /// The seam structure of a large mesh, cut into several patches, is the same from
    /// vertex ranges side by side (many threads) as from one scan.
    #[test]
    fn seam_topology_is_the_same_on_many_threads() {
        let sphere = |c: f64| crate::shapes::uv_sphere([c, 0.0, 0.0], 1.0, 160, 120);
        // Two spheres, the second's vertices numbered first for some triangles.
        let (a, b) = (sphere(0.0), sphere(5.0));
        let mut m = a.clone();
        let off = a.positions.len() as u32;
        m.positions.extend(&b.positions);
        m.triangles
            .extend(b.triangles.iter().map(|t| t.map(|v| v + off)));
        assert!(m.triangles.len() > 1 << 16);
        let full = EdgeTopology::new(&m);
        // Seam: three latitude rings of the first sphere, every 7th edge of the second.
        let z = |v: u32| m.positions[v as usize][2];
        let seam: Vec<[u32; 2]> = full
            .edges
            .iter()
            .enumerate()
            .filter(|&(e, &[u, v])| {
                (u < off
                    && z(u) == z(v)
                    && [0.0, 0.5, -0.5].iter().any(|h| (z(u) - h).abs() < 0.02))
                    || (u >= off && e % 7 == 0)
            })
            .map(|(_, &[u, v])| [v, u])
            .collect();
        let on = |m: &Mesh, seam: &[[u32; 2]], threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| SeamTopology::new(m, seam))
        };
        let one = on(&m, &seam, 1);
        assert!(one.patches > 4, "{}", one.patches);
        assert!(one.is_closed());
        // Vertices numbered far from their triangles' order too: each vertex range's
        // half-edges then come from every chunk of triangles.
        let nv = m.positions.len() as u64;
        assert!(nv % 7919 != 0);
        let spread = |v: u32| (u64::from(v) * 7919 % nv) as u32;
        let mut spread_m = m.clone();
        for (v, p) in m.positions.iter().enumerate() {
            spread_m.positions[spread(v as u32) as usize] = *p;
        }
        for t in &mut spread_m.triangles {
            *t = t.map(spread);
        }
        let spread_seam: Vec<[u32; 2]> = seam.iter().map(|e| e.map(spread)).collect();
        let spread_one = on(&spread_m, &spread_seam, 1);
        assert_eq!(
            (spread_one.patches, &spread_one.patch),
            (one.patches, &one.patch)
        );
        for threads in [3, 8] {
            for (m, seam, one) in [(&m, &seam, &one), (&spread_m, &spread_seam, &spread_one)] {
                let many = on(m, seam, threads);
                assert_eq!(many.edges, one.edges);
                assert_eq!(many.offsets, one.offsets);
                assert_eq!(many.uses, one.uses);
                assert_eq!((many.patches, &many.patch), (one.patches, &one.patch));
                assert_eq!(many.closed, one.closed);
            }
        }
    }

    #[test]
    fn seam_topology_agrees_with_the_full_adjacency() {
        // A closed sphere cut along a ring of edges (two patches), given in both
        // directions, twice, and with pairs that are not edges.
        let m = crate::shapes::uv_sphere([0.0; 3], 1.0, 24, 12);
        let full = EdgeTopology::new(&m);
        let z = |v: u32| m.positions[v as usize][2];
        let ring: Vec<[u32; 2]> = full
            .edges
            .iter()
            .filter(|&&[u, v]| z(u) == z(v) && z(u).abs() < 1e-12)
            .map(|&[u, v]| [v, u])
            .collect();
        assert_eq!(ring.len(), 24);
        let mut seam = ring.clone();
        seam.extend(&ring);
        seam.extend([[0, 0], [3, 200]]);
        let cut = seam_topology_matches(&m, &seam);
        assert_eq!((cut.patches, cut.is_closed()), (2, true));
        assert_eq!(seam_topology_matches(&m, &[]).patches, 1);
        // Broken: a hole, flipped triangles, a triangle used three times (its edges are
        // non-manifold), a repeated-vertex triangle; seam edges among them.
        let mut b = m.clone();
        b.triangles.remove(100);
        b.triangles[50].swap(1, 2);
        let t = b.triangles[200];
        b.triangles.extend([t, t]);
        b.triangles.push([7, 7, 9]);
        let mut seam = ring;
        seam.extend([
            [t[0], t[1]],
            [7, 9],
            [b.triangles[50][0], b.triangles[50][1]],
        ]);
        let open = seam_topology_matches(&b, &seam);
        assert!(!open.is_closed());
        assert!(!seam_topology_matches(&Mesh::default(), &[]).is_closed());
    }

    #[test]
    fn closed_parts_glued_along_an_edge_are_closed_for_the_seam() {
        // Two cubes welded along a shared edge: four uses there, two each way. A boolean
        // on such an operand (a union kept non-manifold) must take it as a solid: as an
        // open surface a part far from it was classified by the sign of a winding number
        // that is zero up to rounding (the n-ary union dropped a prism of the Kirra
        // terrain's envelope for one order of its inputs).
        let mut m = Mesh::unit_cube();
        m.append(&Mesh::cuboid([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]))
            .unwrap();
        let m = crate::weld_exact(&m).mesh;
        assert_eq!(EdgeTopology::new(&m).kind_counts().non_manifold, 1);
        assert!(!EdgeTopology::new(&m).is_closed());
        assert!(SeamTopology::new(&m, &[]).is_closed());
        // Three uses (a cube with one extra triangle on an edge): not closed.
        let mut three = m.clone();
        three.triangles.push(m.triangles[0]);
        assert!(!SeamTopology::new(&three, &[]).is_closed());
        // Four uses, three running one way (a triangle at the shared edge turned over):
        // not closed.
        let topo = EdgeTopology::new(&m);
        let shared = (0..topo.edge_count())
            .find(|&e| topo.kind(e) == EdgeKind::NonManifold)
            .unwrap();
        let mut turned = m.clone();
        turned.triangles[topo.uses_of(shared)[0].triangle as usize].swap(1, 2);
        assert!(!SeamTopology::new(&turned, &[]).is_closed());
    }
}

#[cfg(test)]
mod merge_tests {
    use super::*;
    use crate::shapes::uv_sphere;

    /// `m` with `other`'s triangles appended (vertices offset).
    fn with(mut m: Mesh, other: &Mesh) -> Mesh {
        m.append(other).unwrap();
        m
    }

    fn stray(at: [f64; 3]) -> Mesh {
        Mesh::new_unchecked(
            vec![at, [at[0] + 0.1, at[1], at[2]], [at[0], at[1] + 0.1, at[2]]],
            vec![[0, 1, 2]],
        )
    }

    #[test]
    fn small_components_join_the_nearest_large_one() {
        let near = uv_sphere([0.0; 3], 1.0, 8, 4); // 48 triangles
        let far = uv_sphere([10.0, 0.0, 0.0], 2.0, 10, 5); // 80 triangles
                                                           // Strays: one just outside the near sphere, one beside the far one.
        let m = with(
            with(with(near, &stray([1.2, 0.0, 0.0])), &far),
            &stray([12.5, 0.0, 0.0]),
        );
        let c = components_merged(&m, 0);
        assert_eq!(
            c.parts.iter().map(Vec::len).collect::<Vec<_>>(),
            vec![80, 48, 1, 1]
        );
        assert_eq!(c.merged, 0);
        let c = components_merged(&m, 5);
        assert_eq!(c.merged, 2);
        assert_eq!(
            c.parts.iter().map(Vec::len).collect::<Vec<_>>(),
            vec![81, 49]
        );
        // The near sphere's part holds the stray at x = 1.2 (triangle 48), the far
        // sphere's the one at x = 12.5 (the last triangle).
        assert!(c.parts[1].contains(&48));
        assert!(c.parts[0].contains(&(m.triangles.len() as u32 - 1)));
        // Every triangle exactly once.
        let mut all: Vec<u32> = c.parts.concat();
        all.sort_unstable();
        assert_eq!(all, (0..m.triangles.len() as u32).collect::<Vec<_>>());
        // Everything small: nothing to merge into.
        let c = components_merged(&m, 1000);
        assert_eq!((c.parts.len(), c.merged), (4, 0));
    }
}
