//! Editing a mesh in place: compaction that moves few (removed slots taken by the last
//! live elements), removal keeping the order, and the vertex stars and neighbour lists of
//! local edits. Used by the snap, the boolean's clean-up and the split.

use rayon::prelude::*;

use crate::par::Grain;
use crate::Mesh;

/// What [`snap_filling`] did to the vertices: the dead ones, and the last ones moved
/// into their slots.
#[derive(Default)]
pub(crate) struct Filled {
    /// Vertices collapsed away (sorted ids in the mesh as it was).
    pub(crate) dead: Vec<u32>,
    /// The vertex count after.
    pub(crate) count: usize,
    /// (from, to) of the vertices moved into dead slots, sorted.
    pub(crate) moves: Vec<(u32, u32)>,
}

impl Filled {
    /// The new id of vertex `v` of the mesh as it was; `None` when it was collapsed away.
    pub(crate) fn renamed(&self, v: u32) -> Option<u32> {
        if self.dead.binary_search(&v).is_ok() {
            None
        } else if (v as usize) < self.count || self.moves.is_empty() {
            Some(v)
        } else {
            Some(moved(&self.moves, v))
        }
    }
}

/// Where vertex `v` (one of the moved ones) went: `moves` sorted by source.
#[inline]
fn moved(moves: &[(u32, u32)], v: u32) -> u32 {
    moves[moves.partition_point(|&(f, _)| f < v)].1
}

/// Removes the triangles `dead_triangles` and the unreferenced vertices `dead_vertices`
/// (both sorted, distinct) from `mesh`, each slot below the new counts taken by the last
/// live one, so that nothing else moves: `carry(from, to)` is told of every triangle moved
/// (what is kept per triangle follows it; truncate it to the new count after), and the
/// triangles' corners follow the vertices moved (one pass, only where vertices moved).
/// Returns what became of the vertices.
pub(crate) fn compact_from_end(
    mesh: &mut Mesh,
    dead_triangles: &[u32],
    dead_vertices: Vec<u32>,
    mut carry: impl FnMut(usize, usize),
) -> Filled {
    debug_assert!(dead_triangles.windows(2).all(|w| w[0] < w[1]));
    debug_assert!(dead_vertices.windows(2).all(|w| w[0] < w[1]));
    let (n, moves) = filled_from_end(dead_triangles, mesh.triangles.len());
    for &(from, to) in &moves {
        mesh.triangles[to as usize] = mesh.triangles[from as usize];
        carry(from as usize, to as usize);
    }
    mesh.triangles.truncate(n);
    let (count, moves) = filled_from_end(&dead_vertices, mesh.positions.len());
    for &(from, to) in &moves {
        mesh.positions[to as usize] = mesh.positions[from as usize];
    }
    mesh.positions.truncate(count);
    if !moves.is_empty() {
        let last = count as u32;
        mesh.triangles
            .par_iter_mut()
            .grained()
            .with_min_len(1 << 12)
            .for_each(|t| {
                if t.iter().any(|&v| v >= last) {
                    *t = t.map(|v| if v < last { v } else { moved(&moves, v) });
                }
            });
    }
    Filled {
        dead: dead_vertices,
        count,
        moves,
    }
}

/// Compaction that moves few: of `len` slots, `dead` (sorted, distinct) go, and each dead
/// slot below the new count takes a live one from the end. Returns the new count and the
/// moves (from, to), sorted by source.
fn filled_from_end(dead: &[u32], len: usize) -> (usize, Vec<(u32, u32)>) {
    let n = len - dead.len();
    let split = dead.partition_point(|&k| (k as usize) < n);
    let (holes, tail) = dead.split_at(split);
    let mut tail = tail.iter().peekable();
    let live_tail = (n as u32..len as u32).filter(|&k| {
        if tail.peek() == Some(&&k) {
            tail.next();
            false
        } else {
            true
        }
    });
    (n, live_tail.zip(holes.iter().copied()).collect())
}

/// Removes the elements at the sorted, distinct positions `removed` from `v`, keeping the
/// order of the others (a few block moves).
pub(crate) fn remove_sorted<T: Copy>(v: &mut Vec<T>, removed: &[u32]) {
    let mut to = match removed.first() {
        Some(&r) => r as usize,
        None => return,
    };
    for (j, &r) in removed.iter().enumerate() {
        let end = removed.get(j + 1).map_or(v.len(), |&n| n as usize);
        let from = r as usize + 1;
        v.copy_within(from..end, to);
        to += end - from;
    }
    v.truncate(to);
}

/// Vertex or triangle ids around one vertex (its star, its neighbours): held inline up
/// to 16, almost always enough, so that the many small lists of the clean-ups do not each
/// go to the allocator.
pub(crate) type Ids = smallvec::SmallVec<[u32; 16]>;

/// The neighbours of `v` in the triangles `star` (all containing `v`), sorted.
pub(crate) fn neighbours(star: impl IntoIterator<Item = [u32; 3]>, v: u32) -> Ids {
    let mut n: Ids = star.into_iter().flatten().filter(|&x| x != v).collect();
    n.sort_unstable();
    n.dedup();
    n
}

/// The elements of sorted `a` that are in sorted `b`.
pub(crate) fn common(a: &[u32], b: &[u32]) -> Ids {
    a.iter()
        .copied()
        .filter(|x| b.binary_search(x).is_ok())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Compaction from the end: the dead go, the last live ones fill the holes below the new
    /// count, and every survivor is accounted for exactly once.
    #[test]
    fn filling_from_the_end_moves_only_the_last_ones() {
        assert_eq!(filled_from_end(&[], 5), (5, vec![]));
        // Dead at the end: nothing moves.
        assert_eq!(filled_from_end(&[3, 4], 5), (3, vec![]));
        // Holes 0 and 2 take 5 and 6 (4 is dead too).
        assert_eq!(filled_from_end(&[0, 2, 4], 7), (4, vec![(5, 0), (6, 2)]));
        assert_eq!(filled_from_end(&[0, 1, 2], 3), (0, vec![]));
        let mut rng = crate::test_util::Rng(7);
        for _ in 0..200 {
            let len = 1 + (rng.next() % 40) as usize;
            let dead: Vec<u32> = (0..len as u32).filter(|_| rng.next() % 3 == 0).collect();
            let (n, moves) = filled_from_end(&dead, len);
            assert_eq!(n, len - dead.len());
            let mut slot: Vec<Option<u32>> = (0..len as u32).map(Some).collect();
            for &d in &dead {
                slot[d as usize] = None;
            }
            for &(from, to) in &moves {
                assert!(from as usize >= n && (to as usize) < n && slot[to as usize].is_none());
                slot[to as usize] = slot[from as usize].take();
            }
            assert!(slot[n..].iter().all(Option::is_none));
            let mut kept: Vec<u32> = slot[..n].iter().map(|s| s.expect("filled")).collect();
            kept.sort_unstable();
            let live: Vec<u32> = (0..len as u32).filter(|v| !dead.contains(v)).collect();
            assert_eq!(kept, live);
            assert!(moves.windows(2).all(|w| w[0].0 < w[1].0));
        }
    }
}
