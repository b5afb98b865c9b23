//! Duplicate triangles: the same three vertices used more than once.

use rustc_hash::FxHashMap;
use serde::Serialize;

use crate::Mesh;

/// What [`remove_duplicates`] did.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct DuplicateReport {
    /// Extra copies with the same orientation, removed.
    pub same_orientation_removed: usize,
    /// Triangles removed in anti-parallel pairs (same vertices, opposite orientation: a
    /// zero-thickness double wall).
    pub anti_parallel_removed: usize,
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
    let parity = |t: &[u32; 3]| -> usize {
        // Rotated to start at its smallest vertex, a triangle runs the sorted order (parity
        // 0) exactly when its other two vertices are ascending.
        let k = (0..3).min_by_key(|&i| t[i]).unwrap_or(0);
        usize::from(t[(k + 1) % 3] > t[(k + 2) % 3])
    };
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
    let triangles = mesh
        .triangles
        .iter()
        .zip(&keep)
        .filter(|(_, &k)| k)
        .map(|(t, _)| *t)
        .collect();
    (
        Mesh::new_unchecked(mesh.positions.clone(), triangles),
        report,
    )
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
}
