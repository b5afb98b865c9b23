//! Duplicate triangles: the same three vertices used more than once
//! ([`remove_duplicates`]), or, with a tolerance, three corners each within a distance of
//! another triangle's ([`remove_overlapping`]).

use rustc_hash::FxHashMap;
use serde::Serialize;

use super::weld::{clamp_tolerance, within, NearGrid};
use crate::Mesh;

/// What [`remove_duplicates`] and [`remove_overlapping`] did.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct DuplicateReport {
    /// Extra copies with the same orientation, removed.
    pub same_orientation_removed: usize,
    /// Triangles removed in anti-parallel pairs (same vertices, opposite orientation: a
    /// zero-thickness double wall).
    pub anti_parallel_removed: usize,
    /// The largest distance between corresponding corners of a removed triangle and the
    /// triangle it was matched with ([`remove_overlapping`]); 0 when every match was exact.
    pub largest_distance: f64,
}

/// Removes duplicate triangles. Per set of three vertices, copies of opposite orientation
/// cancel pairwise (anti-parallel pairs); of what remains, one copy is kept. Other triangles
/// keep their order.
pub fn remove_duplicates(mesh: &Mesh) -> (Mesh, DuplicateReport) {
    // Per vertex set and orientation: the first triangle and how many there are.
    #[derive(Default)]
    struct Group {
        first: [Option<usize>; 2],
        count: [usize; 2],
    }
    let mut groups: FxHashMap<[u32; 3], Group> = FxHashMap::default();
    for (i, t) in mesh.triangles.iter().enumerate() {
        let mut key = *t;
        key.sort_unstable();
        let g = groups.entry(key).or_default();
        let p = parity(t);
        g.first[p].get_or_insert(i);
        g.count[p] += 1;
    }
    let mut keep = vec![false; mesh.triangles.len()];
    let mut report = DuplicateReport::default();
    for Group { first, count } in groups.values() {
        let pairs = count[0].min(count[1]);
        report.anti_parallel_removed += 2 * pairs;
        let (rest, side) = if count[0] > count[1] {
            (count[0] - pairs, 0)
        } else {
            (count[1] - pairs, 1)
        };
        if rest > 0 {
            keep[first[side].expect("a counted orientation has a first triangle")] = true;
            report.same_orientation_removed += rest - 1;
        }
    }
    (kept(mesh, &keep), report)
}

/// Which way round a triangle runs: rotated to start at its smallest vertex, it runs the
/// sorted order (parity 0) exactly when its other two vertices are ascending.
fn parity(t: &[u32; 3]) -> usize {
    let k = (0..3).min_by_key(|&i| t[i]).unwrap_or(0);
    usize::from(t[(k + 1) % 3] > t[(k + 2) % 3])
}

/// The unnormalised normal of triangle `t`.
fn normal(mesh: &Mesh, t: &[u32; 3]) -> [f64; 3] {
    let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
    let (u, w) = (
        [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
        [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
    );
    [
        u[1] * w[2] - u[2] * w[1],
        u[2] * w[0] - u[0] * w[2],
        u[0] * w[1] - u[1] * w[0],
    ]
}

/// How triangle `s` matches triangle `t` within `tol`: `Some((0, d))` for the same
/// orientation, `Some((1, d))` for the opposite one, with `d` the largest distance between
/// corresponding corners. Triangles on the same three vertices always match (exactly, as
/// [`remove_duplicates`] takes them). Others match when neither has an edge of length at
/// most `2 tol`, for some rotation of `s` (reversed for the opposite orientation)
/// corresponding corners are within `tol`, a vertex both use corresponds to itself (so
/// neighbours sharing an edge never match), and the normals point the same way (opposite
/// ways for the opposite orientation; a zero normal matches nothing).
fn matching(mesh: &Mesh, t: &[u32; 3], s: &[u32; 3], tol: f64) -> Option<(usize, f64)> {
    let (mut ts, mut ss) = (*t, *s);
    ts.sort_unstable();
    ss.sort_unstable();
    if ts == ss {
        return Some((usize::from(parity(t) != parity(s)), 0.0));
    }
    let pos = |v: u32| &mesh.positions[v as usize];
    // Corners closer than twice the tolerance could pair up either way: too small to
    // tell a copy from a neighbour.
    let small = |x: &[u32; 3]| (0..3).any(|k| within(pos(x[k]), pos(x[(k + 1) % 3]), 2.0 * tol));
    if small(t) || small(s) {
        return None;
    }
    let (nt, ns) = (normal(mesh, t), normal(mesh, s));
    let dot = nt[0] * ns[0] + nt[1] * ns[1] + nt[2] * ns[2];
    let distance = |p: &[f64; 3], q: &[f64; 3]| {
        ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
    };
    for (side, turned) in [(0, *s), (1, [s[0], s[2], s[1]])] {
        let facing = if side == 0 { dot > 0.0 } else { dot < 0.0 };
        if !facing {
            continue;
        }
        for r in 0..3 {
            let u = [turned[r], turned[(r + 1) % 3], turned[(r + 2) % 3]];
            let corresponds = (0..3).all(|k| {
                t[k] == u[k]
                    || (!s.contains(&t[k])
                        && !t.contains(&u[k])
                        && within(pos(t[k]), pos(u[k]), tol))
            });
            if corresponds {
                let d = (0..3)
                    .map(|k| distance(pos(t[k]), pos(u[k])))
                    .fold(0.0, f64::max);
                return Some((side, d.min(tol)));
            }
        }
    }
    None
}

/// Removes triangles that overlap another within `tolerance`: as [`remove_duplicates`]
/// does for triangles on the same three vertices, with triangles whose corresponding
/// corners are each within `tolerance` of each other taken as copies too (a double wall
/// that is not exactly coincident, or a copy moved a little).
///
/// Deterministic and without chaining, as [`weld_within`](super::weld_within): triangles
/// are visited in index order; each one not yet taken starts a group and takes every later
/// triangle not yet taken that matches *it*, the same way round or the opposite way. In
/// each group, copies of opposite orientation cancel pairwise (anti-parallel pairs, both
/// removed); of what remains, the first is kept. Two triangles match when, for some
/// rotation of one (reversed for the opposite orientation), corresponding corners are
/// within `tolerance`, a vertex both use corresponds to itself (neighbours sharing an edge
/// never match), and their normals point the same way (opposite ways for an anti-parallel
/// pair). A triangle with an edge of at most twice `tolerance` is too small for its
/// corners to be told apart at that distance: it matches only triangles on its own three
/// vertices, as without a tolerance. Triangles keep their order; positions are not moved.
/// `tolerance` must be finite and ≥ 0; 0 is [`remove_duplicates`].
pub fn remove_overlapping(mesh: &Mesh, tolerance: f64) -> (Mesh, DuplicateReport) {
    let tol = clamp_tolerance(tolerance);
    if tol == 0.0 {
        return remove_duplicates(mesh);
    }
    let nt = mesh.triangles.len();
    let nv = mesh.positions.len();
    // The triangles at each vertex (compressed rows).
    let mut start = vec![0u32; nv + 1];
    for t in &mesh.triangles {
        for &v in t {
            start[v as usize + 1] += 1;
        }
    }
    for v in 0..nv {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut at = vec![0u32; start[nv] as usize];
    for (i, t) in mesh.triangles.iter().enumerate() {
        for &v in t {
            at[fill[v as usize] as usize] = i as u32;
            fill[v as usize] += 1;
        }
    }
    let incident = |v: u32| &at[start[v as usize] as usize..start[v as usize + 1] as usize];
    let grid = NearGrid::new(&mesh.positions, 0..nv as u32, tol);
    // Per triangle: its group's first triangle, its side (0: as the first, 1: reversed),
    // its distance from the first.
    let mut group = vec![u32::MAX; nt];
    let mut side = vec![0u8; nt];
    let mut dist = vec![0.0f64; nt];
    let mut candidates = Vec::new();
    for i in 0..nt {
        if group[i] != u32::MAX {
            continue;
        }
        group[i] = i as u32;
        let t = mesh.triangles[i];
        let p = mesh.positions[t[0] as usize];
        candidates.clear();
        candidates.extend_from_slice(incident(t[0]));
        for w in grid.near(&p) {
            if w != t[0] && within(&p, &mesh.positions[w as usize], tol) {
                candidates.extend_from_slice(incident(w));
            }
        }
        candidates.sort_unstable();
        candidates.dedup();
        for &j in &candidates {
            let j = j as usize;
            if j <= i || group[j] != u32::MAX {
                continue;
            }
            if let Some((s, d)) = matching(mesh, &t, &mesh.triangles[j], tol) {
                group[j] = i as u32;
                side[j] = s as u8;
                dist[j] = d;
            }
        }
    }
    // Per group: how many on each side, and the first on each side.
    let mut count = vec![[0usize; 2]; nt];
    let mut first = vec![[u32::MAX; 2]; nt];
    for j in 0..nt {
        let (g, s) = (group[j] as usize, side[j] as usize);
        count[g][s] += 1;
        if first[g][s] == u32::MAX {
            first[g][s] = j as u32;
        }
    }
    let mut keep = vec![false; nt];
    let mut report = DuplicateReport::default();
    for g in 0..nt {
        let c = count[g];
        let pairs = c[0].min(c[1]);
        report.anti_parallel_removed += 2 * pairs;
        let surplus = usize::from(c[1] > c[0]);
        let rest = c[surplus] - pairs;
        if rest > 0 {
            keep[first[g][surplus] as usize] = true;
            report.same_orientation_removed += rest - 1;
        }
    }
    // A removed triangle is in a group of two or more: its distance from the group's
    // first triangle is one it was matched with.
    for j in (0..nt).filter(|&j| !keep[j]) {
        report.largest_distance = report.largest_distance.max(dist[j]);
    }
    (kept(mesh, &keep), report)
}

/// The triangles of `mesh` whose `keep` flag is set, on the same vertices.
fn kept(mesh: &Mesh, keep: &[bool]) -> Mesh {
    let triangles = mesh
        .triangles
        .iter()
        .zip(keep)
        .filter(|(_, &k)| k)
        .map(|(t, _)| *t)
        .collect();
    Mesh::new_unchecked(mesh.positions.clone(), triangles)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::mesh_stats;

    #[test]
    fn duplicates_and_anti_parallel_pairs() {
        let mut m = Mesh::unit_cube();
        m.triangles.push(m.triangles[3]); // same orientation copy
        let [a, b, c] = m.triangles[5];
        m.triangles.push([b, c, a]); // same orientation, rotated
        assert!(mesh_stats(&m).non_manifold_edges > 0);
        // An internal double wall: the diagonal square x = y as two anti-parallel pairs.
        m.triangles
            .extend([[0, 3, 7], [0, 7, 3], [0, 7, 4], [0, 4, 7]]);
        let (f, r) = remove_duplicates(&m);
        assert_eq!(
            (r.same_orientation_removed, r.anti_parallel_removed),
            (2, 4)
        );
        assert_eq!(f.triangles, Mesh::unit_cube().triangles);
        let s = mesh_stats(&f);
        assert_eq!((s.non_manifold_edges, s.volume), (0, 1.0));
        // Three copies, two one way and one the other: one survives, the surplus way.
        let tri = Mesh::new_unchecked(
            vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            vec![[0, 1, 2], [2, 1, 0], [1, 2, 0]],
        );
        let (f, r) = remove_duplicates(&tri);
        assert_eq!(f.triangles, vec![[0, 1, 2]]);
        assert_eq!(
            (r.same_orientation_removed, r.anti_parallel_removed),
            (0, 2)
        );
    }

    /// The unit cube and a copy of its top face (own vertices 8..12) moved up by `dz`,
    /// facing up as the face does or, `reversed`, down.
    fn cube_and_face_copy(dz: f64, reversed: bool) -> Mesh {
        let mut m = Mesh::unit_cube();
        for v in 4..8 {
            let [x, y, z] = m.positions[v];
            m.positions.push([x, y, z + dz]);
        }
        // The top face is [4, 5, 6], [5, 7, 6].
        if reversed {
            m.triangles.extend([[8, 10, 9], [9, 10, 11]]);
        } else {
            m.triangles.extend([[8, 9, 10], [9, 11, 10]]);
        }
        m
    }

    #[test]
    fn a_near_copy_of_a_face_goes_within_the_tolerance_only() {
        let dz = (1.0f64 + 1e-4) - 1.0;
        let m = cube_and_face_copy(1e-4, false);
        assert_eq!(mesh_stats(&m).boundary_edges, 4);
        for (f, r) in [remove_duplicates(&m), remove_overlapping(&m, 1e-5)] {
            assert_eq!(
                (r.same_orientation_removed, r.anti_parallel_removed),
                (0, 0)
            );
            assert_eq!(f.triangles, m.triangles);
        }
        let (f, r) = remove_overlapping(&m, 1e-3);
        assert_eq!(
            (
                r.same_orientation_removed,
                r.anti_parallel_removed,
                r.largest_distance
            ),
            (2, 0, dz)
        );
        // The first of each pair stays: the cube, closed.
        assert_eq!(f.triangles, Mesh::unit_cube().triangles);
        let s = mesh_stats(&f);
        assert_eq!((s.boundary_edges, s.closed, s.volume), (0, true, 1.0));
    }

    #[test]
    fn a_near_reversed_copy_cancels_as_an_exact_one_does() {
        // Reversed, the copy and the face are a double wall 1e-4 thick: both go, as an
        // exactly coincident reversed copy and the face do without a tolerance.
        let m = cube_and_face_copy(1e-4, true);
        let (f, r) = remove_overlapping(&m, 1e-3);
        assert_eq!(
            (r.same_orientation_removed, r.anti_parallel_removed),
            (0, 4)
        );
        let mut exact = Mesh::unit_cube();
        exact.triangles.extend([[4, 6, 5], [5, 6, 7]]);
        let (g, e) = remove_duplicates(&exact);
        assert_eq!((e.anti_parallel_removed, &g.triangles), (4, &f.triangles));
        assert_eq!(f.triangles.len(), 10);
        assert_eq!(mesh_stats(&f).boundary_edges, 4);
        assert_eq!(remove_overlapping(&m, 1e-5).1.anti_parallel_removed, 0);
        // Exact duplicates go with a tolerance too, counted the same way.
        let (g2, e2) = remove_overlapping(&exact, 1e-3);
        assert_eq!((g2, e2), (g, e));
    }

    #[test]
    fn triangles_too_small_for_the_tolerance_are_never_copies() {
        // A grid of cells 0.1 across: with a tolerance of 0.05 or more, corners of
        // different triangles would pair up; no triangle is taken as a copy.
        let grid = crate::shapes::heightfield([0.0, 0.0], [1.0, 1.0], 10, 10, |_, _| 0.0);
        for tol in [0.04, 0.05, 0.3] {
            let (f, r) = remove_overlapping(&grid, tol);
            assert_eq!(
                (r.same_orientation_removed, r.anti_parallel_removed),
                (0, 0)
            );
            assert_eq!(f.triangles, grid.triangles);
        }
        // Exact copies still go.
        let mut twice = grid.clone();
        twice.triangles.extend(grid.triangles.clone());
        let (f, r) = remove_overlapping(&twice, 0.3);
        assert_eq!(
            (r.same_orientation_removed, f.triangles),
            (200, grid.triangles)
        );
    }

    #[test]
    fn neighbours_never_match_and_a_near_fin_does() {
        // Two triangles on the edge b c, their third corners 2e-4 apart on either side:
        // a flat strip, not a copy, however close the corners.
        let b = [0.0, 0.0, 0.0];
        let c = [0.0, 1.0, 0.0];
        let strip = Mesh::new_unchecked(
            vec![b, c, [-1e-4, 0.5, 0.0], [1e-4, 0.5, 0.0]],
            vec![[0, 1, 2], [1, 0, 3]],
        );
        let (f, r) = remove_overlapping(&strip, 1e-3);
        assert_eq!(
            (r.same_orientation_removed, r.anti_parallel_removed),
            (0, 0)
        );
        assert_eq!(f, strip);
        // The second folded back over the first (a fin 1e-4 wide): a near double wall.
        let fin = Mesh::new_unchecked(
            vec![b, c, [-1e-4, 0.5, 0.0], [-2e-4, 0.5, 0.0]],
            vec![[0, 1, 2], [1, 0, 3]],
        );
        let (f, r) = remove_overlapping(&fin, 1e-3);
        assert_eq!((r.anti_parallel_removed, f.triangles.len()), (2, 0));
    }
}
