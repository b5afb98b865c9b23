//! Manifold topology without moving anything: edges used by more than two triangles have
//! their triangles paired into sheets, and vertices whose triangles form several fans get
//! one copy per fan (same position). Two solids touching along an edge or at a vertex
//! come out as two closed, manifold surfaces that share positions but no vertex.
//!
//! Pairing is exact: the triangles around an edge are ordered by angle with `orient3d`
//! on their points — a boolean's seam points as the exact points they are, not as their
//! rounded coordinates, which can tie or swap the angles of thin triangles —, and each is
//! paired with its neighbour on its inside (the side its normal points away from), so
//! that every sheet bounds one solid wedge. Where the
//! orientation around an edge does not alternate (an inconsistently oriented or open
//! input), triangles without a partner are counted and left on a boundary there.

use crate::par::Grain;
use rayon::prelude::*;
use serde::Serialize;

use crate::edges::angular_order;
use crate::kernel::Point;
use crate::Mesh;

/// What [`split_nonmanifold`] did.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct NonManifoldReport {
    /// Edges used by more than two triangles, whose triangles were paired into sheets.
    pub edges_split: usize,
    /// Vertices added: one copy of a vertex for each of its fans beyond the first.
    pub vertices_added: usize,
    /// Triangles at split edges left without a partner (the orientation around the edge
    /// does not alternate); each leaves a boundary edge.
    pub unpaired: usize,
}

impl NonManifoldReport {
    /// Adds `other`'s counts to these (two splits of one mesh).
    pub fn add(&mut self, other: &NonManifoldReport) {
        self.edges_split += other.edges_split;
        self.vertices_added += other.vertices_added;
        self.unpaired += other.unpaired;
    }
}

/// Makes `mesh` manifold by splitting its topology (see the module doc): afterwards every
/// edge has at most two triangles and every vertex one fan. Positions are unchanged
/// (copies are appended after the existing vertices); triangles keep their order and
/// orientation.
pub fn split_nonmanifold(mesh: &Mesh) -> (Mesh, NonManifoldReport) {
    let all: Vec<u32> = (0..mesh.positions.len() as u32).collect();
    let (mesh, report, _) = split_at(mesh.clone(), &all, None);
    (mesh, report)
}

/// The exact point of the `i`th candidate of [`split_at`]; `None`: its position is exact.
pub(crate) type ExactPoint<'a> = &'a (dyn Fn(usize) -> Option<Point> + Sync);

/// [`split_nonmanifold`] looking only at the vertices `candidates` (sorted, distinct):
/// where a boolean glues its two inputs, the only places it can make the result
/// non-manifold. `exact(i)` is the exact point of `candidates[i]` where its position is
/// rounded (a seam point); `None`: positions are exact. Also returns, for each copy
/// appended, the vertex it copies.
pub(crate) fn split_at(
    mut mesh: Mesh,
    candidates: &[u32],
    exact: Option<ExactPoint>,
) -> (Mesh, NonManifoldReport, Vec<u32>) {
    let n = mesh.positions.len();
    // The corners (triangle, position in it) of each candidate vertex, in triangle order:
    // found in pieces of the triangles side by side (candidates are usually few), then
    // sorted by candidate.
    let mut slot = crate::par::filled(u32::MAX, n);
    for (i, &v) in candidates.iter().enumerate() {
        slot[v as usize] = i as u32;
    }
    const CHUNK: usize = 1 << 15;
    let found: Vec<Vec<(u32, u32, u8)>> = mesh
        .triangles
        .par_chunks(CHUNK)
        .grained()
        .enumerate()
        .map(|(c, tris)| {
            let mut out = Vec::new();
            for (j, tri) in tris.iter().enumerate() {
                for (k, &v) in tri.iter().enumerate() {
                    if slot[v as usize] != u32::MAX {
                        out.push((slot[v as usize], (c * CHUNK + j) as u32, k as u8));
                    }
                }
            }
            out
        })
        .collect();
    let mut start = vec![0u32; candidates.len() + 1];
    for &(s, _, _) in found.iter().flatten() {
        start[s as usize + 1] += 1;
    }
    for i in 0..candidates.len() {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut corners = vec![(0u32, 0u8); start[candidates.len()] as usize];
    for &(s, t, k) in found.iter().flatten() {
        corners[fill[s as usize] as usize] = (t, k);
        fill[s as usize] += 1;
    }
    // Each candidate's fans, worked out on its own.
    let fans: Vec<Fans> = (0..candidates.len())
        .into_par_iter()
        .grained()
        .map(|i| {
            let cs = &corners[start[i] as usize..start[i + 1] as usize];
            let counts_here =
                |other: u32| candidates[i] < other || slot[other as usize] == u32::MAX;
            let point = |v: u32| {
                match (exact, slot[v as usize]) {
                    (Some(exact), s) if s != u32::MAX => exact(s as usize),
                    _ => None,
                }
                .unwrap_or(Point::Explicit(mesh.positions[v as usize]))
            };
            fans_of(&mesh, candidates[i], cs, counts_here, point)
        })
        .collect();
    // Every fan but the first gets a new vertex at the same position.
    let mut report = NonManifoldReport::default();
    let mut copied = Vec::new();
    for (i, f) in fans.iter().enumerate() {
        let v = candidates[i];
        report.edges_split += f.split_edges;
        report.unpaired += f.unpaired;
        let cs = &corners[start[i] as usize..start[i + 1] as usize];
        for fan in 1..f.count {
            let copy = mesh.positions.len() as u32;
            mesh.positions.push(mesh.positions[v as usize]);
            copied.push(v);
            report.vertices_added += 1;
            for (c, &(t, k)) in cs.iter().enumerate() {
                if f.fan[c] == fan {
                    mesh.triangles[t as usize][k as usize] = copy;
                }
            }
        }
    }
    (mesh, report, copied)
}

/// A list of a vertex's corners or edge uses, in place up to a typical valence: no
/// allocation for most vertices (a boolean looks at every seam vertex).
type Around<T> = smallvec::SmallVec<[T; 16]>;

/// The fans of one vertex: `fan[c]` for each of its corners (0 for the fan holding its
/// first corner, then in order of first corners), their number, and the split edges at it.
struct Fans {
    fan: Around<u32>,
    count: u32,
    split_edges: usize,
    unpaired: usize,
}

/// The fans around vertex `v` whose corners are `cs`: corners are joined across each edge
/// at `v` that two triangles share, and across the pairs of an edge with more. Split
/// edges are counted where `counts_here(other end)` says (once per edge); `point(u)` is
/// vertex `u`'s exact point.
fn fans_of(
    mesh: &Mesh,
    v: u32,
    cs: &[(u32, u8)],
    counts_here: impl Fn(u32) -> bool,
    point: impl Fn(u32) -> Point,
) -> Fans {
    if one_closed_fan(mesh, v, cs) {
        return Fans {
            fan: smallvec::smallvec![0; cs.len()],
            count: 1,
            split_edges: 0,
            unpaired: 0,
        };
    }
    fans_by_edges(mesh, v, cs, counts_here, point)
}

/// [`fans_of`] worked out in full: the uses of the edges at `v` sorted by their other
/// end, corners joined across each edge.
fn fans_by_edges(
    mesh: &Mesh,
    v: u32,
    cs: &[(u32, u8)],
    counts_here: impl Fn(u32) -> bool,
    point: impl Fn(u32) -> Point,
) -> Fans {
    // The uses of each edge at v: (other end, corner, direction: true when v -> other).
    let mut uses: Around<(u32, u32, bool)> = Around::with_capacity(2 * cs.len());
    for (c, &(t, k)) in cs.iter().enumerate() {
        let tri = mesh.triangles[t as usize];
        let (next, prev) = (tri[(k as usize + 1) % 3], tri[(k as usize + 2) % 3]);
        if next != v {
            uses.push((next, c as u32, true));
        }
        if prev != v && prev != next {
            uses.push((prev, c as u32, false));
        }
    }
    uses.sort_unstable();
    let mut parent: Around<u32> = (0..cs.len() as u32).collect();
    let mut join = |a: u32, b: u32| {
        let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
        parent[ra.max(rb) as usize] = ra.min(rb);
    };
    let (mut split_edges, mut unpaired) = (0, 0);
    for edge in uses.chunk_by(|a, b| a.0 == b.0) {
        match edge {
            [_] => {}
            [a, b] => join(a.1, b.1),
            _ => {
                let sheets = pair_around(mesh, v, edge, cs, &point);
                if counts_here(edge[0].0) {
                    split_edges += 1;
                    unpaired += edge.len() - 2 * sheets.len();
                }
                for (a, b) in sheets {
                    join(a, b);
                }
            }
        }
    }
    let mut fan: Around<u32> = smallvec::smallvec![u32::MAX; cs.len()];
    let mut count = 0;
    for c in 0..cs.len() {
        let r = root(&mut parent, c as u32) as usize;
        if fan[r] == u32::MAX {
            fan[r] = count;
            count += 1;
        }
        fan[c] = fan[r];
    }
    Fans {
        fan,
        count,
        split_edges,
        unpaired,
    }
}

/// Whether the corners `cs` of vertex `v` form one closed fan with every edge at `v` used
/// twice, once each way (almost every vertex of a boolean's seam): then [`fans_of`] finds
/// one fan and no split edge, which this tells without sorting. The corners' next ends
/// must be distinct (so each edge has at most one use leaving `v`, and one entering) and
/// stepping from a corner to the one whose previous end is its next must visit them all.
/// Tried up to a typical valence (the test is quadratic); `false` means: work it out.
fn one_closed_fan(mesh: &Mesh, v: u32, cs: &[(u32, u8)]) -> bool {
    const UP_TO: usize = 16;
    let n = cs.len();
    if !(3..=UP_TO).contains(&n) {
        return false;
    }
    let mut next = [0u32; UP_TO];
    let mut prev = [0u32; UP_TO];
    for (c, &(t, k)) in cs.iter().enumerate() {
        let tri = mesh.triangles[t as usize];
        (next[c], prev[c]) = (tri[(k as usize + 1) % 3], tri[(k as usize + 2) % 3]);
        if next[c] == v || prev[c] == v || next[c] == prev[c] || next[..c].contains(&next[c]) {
            return false;
        }
    }
    // The walk: n steps back to the start, each to the first corner entering along the
    // edge the last one left by. Returning to the start only at step n, it visited every
    // corner once (a repeat before would be a loop without the start); so the previous
    // ends are the next ends, each once, and every edge has exactly its two uses.
    let mut c = 0;
    for step in 1..=n {
        let Some(d) = prev[..n].iter().position(|&p| p == next[c]) else {
            return false;
        };
        c = d;
        if c == 0 {
            return step == n;
        }
    }
    false
}

fn root(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let up = parent[parent[x as usize] as usize];
        parent[x as usize] = up;
        x = up;
    }
    x
}

/// Pairs the triangles around the edge from `v` to the other end of `uses` (more than two
/// uses: other end, corner of `v`, direction) into sheets, as pairs of corners. Both ends
/// of an edge pair it alike: the order depends only on the edge, taken from its lower to
/// its higher vertex id, and on its triangles. `point(u)` is vertex `u`'s exact point.
fn pair_around(
    mesh: &Mesh,
    v: u32,
    uses: &[(u32, u32, bool)],
    cs: &[(u32, u8)],
    point: &impl Fn(u32) -> Point,
) -> Vec<(u32, u32)> {
    let other = uses[0].0;
    let (lo, hi) = (v.min(other), v.max(other));
    let (p, q) = (point(lo), point(hi));
    // Per use: its corner, whether it runs lo -> hi, its far vertex.
    let items: Vec<(u32, bool, Point, u32)> = uses
        .iter()
        .map(|&(_, c, out)| {
            let (t, k) = cs[c as usize];
            let tri = mesh.triangles[t as usize];
            let far = tri[(k as usize + if out { 2 } else { 1 }) % 3];
            (c, out == (v == lo), point(far), t)
        })
        .collect();
    let order = angular_order(&p, &q, mesh.positions[lo as usize], &items);
    // Around the axis lo -> hi, angles increasing counter-clockwise (seen with the axis
    // pointing at the viewer): a triangle running hi -> lo faces backwards, so its inside
    // is towards the next triangle, which (oriented consistently) runs lo -> hi.
    // Such a pair opens a sheet's inside and closes it: they are matched as parentheses
    // around the circle, so that sheets nested in one another's wedge (parts that overlap
    // there, a part given twice) pair up too, innermost first. The pass starts just after
    // the lowest point of the running count (opens +1, closes −1), where no sheet is open.
    let m = order.len();
    let opens = |i: usize| !items[order[i]].1;
    let (mut count, mut lowest, mut start) = (0i64, 0i64, 0usize);
    for i in 0..m {
        count += if opens(i) { 1 } else { -1 };
        if count < lowest {
            (lowest, start) = (count, i + 1);
        }
    }
    let mut open = Vec::new();
    let mut sheets = Vec::new();
    for s in 0..m {
        let i = (start + s) % m;
        if opens(i) {
            open.push(i);
        } else if let Some(j) = open.pop() {
            sheets.push((items[order[j]].0, items[order[i]].0));
        }
    }
    sheets
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::edges::EdgeTopology;
    use crate::measure::{mesh_stats, signed_volume};

    fn two(a: Mesh, b: &Mesh) -> Mesh {
        let mut m = crate::weld_exact(&{
            let mut m = a;
            m.append(b).unwrap();
            m
        })
        .mesh;
        m.triangles.sort_unstable();
        m
    }

    fn assert_manifold_closed(m: &Mesh, components: usize, volume: f64) {
        let s = mesh_stats(m);
        assert_eq!(
            (s.boundary_edges, s.non_manifold_edges, s.inconsistent_edges),
            (0, 0, 0)
        );
        assert_eq!(s.components, components);
        assert_eq!(signed_volume(m), volume);
        // Vertex-manifold: every vertex's triangles form one fan.
        let all: Vec<u32> = (0..m.positions.len() as u32).collect();
        let (again, r, _) = split_at(m.clone(), &all, None);
        assert_eq!(r, NonManifoldReport::default());
        assert_eq!(&again, m);
    }

    #[test]
    fn the_quick_closed_fan_test_agrees_with_the_full_one() {
        // Closed, open, non-manifold at an edge and at a vertex, a flipped triangle, a
        // repeated triangle: every vertex, in two triangle orders.
        let sphere = crate::shapes::uv_sphere([0.0; 3], 1.0, 12, 7);
        let mut open = sphere.clone();
        open.triangles.truncate(open.triangles.len() - 5);
        let mut flipped = sphere.clone();
        flipped.triangles[3].swap(0, 1);
        let mut doubled = sphere.clone();
        doubled.triangles.push(sphere.triangles[7]);
        let edge = two(
            Mesh::unit_cube(),
            &Mesh::cuboid([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]),
        );
        let vertex = two(Mesh::unit_cube(), &Mesh::cuboid([1.0; 3], [2.0; 3]));
        let (mut quick, mut full) = (0, 0);
        for mesh in [sphere, open, flipped, doubled, edge, vertex] {
            for reversed in [false, true] {
                let mut m = mesh.clone();
                if reversed {
                    m.triangles.reverse();
                }
                for v in 0..m.positions.len() as u32 {
                    let cs: Vec<(u32, u8)> = (0..m.triangles.len())
                        .flat_map(|t| (0..3).map(move |k| (t as u32, k as u8)))
                        .filter(|&(t, k)| m.triangles[t as usize][k as usize] == v)
                        .collect();
                    let point = |u: u32| Point::Explicit(m.positions[u as usize]);
                    let want = fans_by_edges(&m, v, &cs, |_| true, point);
                    let got = fans_of(&m, v, &cs, |_| true, point);
                    assert_eq!(
                        (&got.fan, got.count, got.split_edges, got.unpaired),
                        (&want.fan, want.count, want.split_edges, want.unpaired),
                        "vertex {v}"
                    );
                    if one_closed_fan(&m, v, &cs) {
                        quick += 1;
                    } else {
                        full += 1;
                    }
                }
            }
        }
        // Both ways taken: every vertex of the closed sphere and the cubes' other corners
        // quickly; the open, flipped, doubled and shared ones in full.
        assert!(quick > 600 && full > 30, "{quick} quick, {full} full");
    }

    #[test]
    fn cubes_sharing_an_edge_become_two_closed_sheets() {
        let a = Mesh::unit_cube();
        let b = Mesh::cuboid([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]);
        let m = two(a, &b);
        assert_eq!(EdgeTopology::new(&m).kind_counts().non_manifold, 1);
        let (out, r) = split_nonmanifold(&m);
        assert_eq!(r.edges_split, 1);
        assert_eq!(r.vertices_added, 2);
        assert_eq!(r.unpaired, 0);
        assert_eq!(out.triangles.len(), m.triangles.len());
        assert_manifold_closed(&out, 2, 2.0);
    }

    #[test]
    fn cubes_sharing_a_vertex_get_two_copies_of_it() {
        let m = two(Mesh::unit_cube(), &Mesh::cuboid([1.0; 3], [2.0; 3]));
        let (out, r) = split_nonmanifold(&m);
        assert_eq!((r.edges_split, r.vertices_added, r.unpaired), (0, 1, 0));
        assert_manifold_closed(&out, 2, 2.0);
    }

    #[test]
    fn four_cubes_around_one_edge_pair_each_with_itself() {
        // Four unit cubes around the z axis: the axis edge has 8 triangles, four solid
        // wedges and no empty one, in every rotation of the triangle order.
        let mut m = Mesh::default();
        for (x, y) in [(0.0, 0.0), (-1.0, 0.0), (-1.0, -1.0), (0.0, -1.0)] {
            m.append(&Mesh::cuboid([x, y, 0.0], [x + 1.0, y + 1.0, 1.0]))
                .unwrap();
        }
        let m = crate::weld_exact(&m).mesh;
        for shift in 0..m.triangles.len() {
            let mut rotated = m.clone();
            rotated.triangles.rotate_left(shift);
            let (out, r) = split_nonmanifold(&rotated);
            assert_eq!(r.unpaired, 0);
            let s = mesh_stats(&out);
            assert_eq!((s.boundary_edges, s.non_manifold_edges), (0, 0));
            assert_eq!(s.components, 4, "shift {shift}");
            assert_eq!(signed_volume(&out), 4.0);
        }
    }

    #[test]
    fn a_cube_given_twice_becomes_its_two_copies() {
        // Welded: every edge has four triangles, two layers at each of its two faces.
        let mut m = Mesh::unit_cube();
        m.append(&Mesh::unit_cube()).unwrap();
        let m = crate::weld_exact(&m).mesh;
        assert_eq!(EdgeTopology::new(&m).kind_counts().non_manifold, 18);
        for shift in [0, 5, 12, 17] {
            let mut rotated = m.clone();
            rotated.triangles.rotate_left(shift);
            let (out, r) = split_nonmanifold(&rotated);
            assert_eq!((r.edges_split, r.vertices_added, r.unpaired), (18, 8, 0));
            let s = mesh_stats(&out);
            assert_eq!((s.boundary_edges, s.non_manifold_edges), (0, 0));
            assert_eq!(s.components, 2, "shift {shift}");
            assert_eq!(signed_volume(&out), 2.0);
            if shift > 0 {
                continue; // coincident layers pair by id: copies may mix, still closed
            }
            // In input order each copy is one sheet: the first copy's triangles share no
            // vertex with the second's.
            let first = |t: usize| t < 12;
            let mut side = vec![None; out.positions.len()];
            for (t, tri) in out.triangles.iter().enumerate() {
                for &v in tri {
                    assert_ne!(side[v as usize].replace(first(t)), Some(!first(t)));
                }
            }
        }
    }

    #[test]
    fn a_wedge_nested_in_another_pairs_inside_out() {
        // Two wedges around the z axis, the second inside the first: a box and a thinner
        // box turned about the shared edge. The uses alternate open, open, close, close.
        let outer = Mesh::cuboid([0.0, 0.0, 0.0], [2.0, 2.0, 1.0]);
        let inner = Mesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.2, 0.0],
                [0.2, 1.0, 0.0],
                [0.0, 0.0, 1.0],
                [1.0, 0.2, 1.0],
                [0.2, 1.0, 1.0],
            ],
            vec![
                [0, 2, 1],
                [3, 4, 5],
                [0, 1, 4],
                [0, 4, 3],
                [1, 2, 5],
                [1, 5, 4],
                [2, 0, 3],
                [2, 3, 5],
            ],
        )
        .unwrap();
        assert!(signed_volume(&inner) > 0.0);
        let m = two(outer, &inner);
        let (out, r) = split_nonmanifold(&m);
        assert_eq!((r.edges_split, r.unpaired), (1, 0));
        let s = mesh_stats(&out);
        assert_eq!((s.boundary_edges, s.non_manifold_edges), (0, 0));
        assert_eq!(s.components, 2);
    }

    #[test]
    fn manifold_meshes_are_left_as_they_are() {
        let sphere = crate::shapes::uv_sphere([0.0; 3], 1.0, 16, 8);
        let (out, r) = split_nonmanifold(&sphere);
        assert_eq!(r, NonManifoldReport::default());
        assert_eq!(out, sphere);
        let grid = crate::shapes::heightfield([0.0, 0.0], [1.0, 1.0], 4, 4, |x, y| x * y);
        assert_eq!(split_nonmanifold(&grid).0, grid);
    }

    #[test]
    fn inconsistent_orientation_leaves_unpaired_triangles_open() {
        // Three triangles on one edge, all running the same way: nothing pairs.
        let m = Mesh::new_unchecked(
            vec![
                [0.0, 0.0, 0.0],
                [0.0, 0.0, 1.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [-1.0, 0.0, 0.0],
            ],
            vec![[0, 1, 2], [0, 1, 3], [0, 1, 4]],
        );
        let (out, r) = split_nonmanifold(&m);
        assert_eq!((r.edges_split, r.unpaired), (1, 3));
        assert_eq!(mesh_stats(&out).non_manifold_edges, 0);
    }
}
