//! Bounding-volume hierarchy over triangle boxes and the broad phase: all pairs of
//! triangles (one from each mesh) whose boxes overlap.
//!
//! Build: triangles are sorted by the Morton code of their box centres, then the sorted
//! range is split at its middle recursively, so the tree is balanced by construction and
//! spatially coherent; leaf boxes are the exact min/max of input coordinates, inner boxes
//! their unions. O(n log n) for the (parallel) sort, O(n) for the rest.
//! Queries compare input coordinates only (closed boxes: touching counts as overlapping),
//! so they are exact and conservative.

use rayon::prelude::*;

use crate::Mesh;

/// Triangles per leaf.
const LEAF: usize = 4;

/// An axis-aligned box as `[min, max]`.
type Box3 = [[f64; 3]; 2];

fn union(a: &Box3, b: &Box3) -> Box3 {
    [
        std::array::from_fn(|k| a[0][k].min(b[0][k])),
        std::array::from_fn(|k| a[1][k].max(b[1][k])),
    ]
}

#[inline]
fn overlaps(a: &Box3, b: &Box3) -> bool {
    (0..3).all(|k| a[0][k] <= b[1][k] && b[0][k] <= a[1][k])
}

/// A node: its box and either two children or a range of `order`.
#[derive(Clone, Copy, Debug)]
struct Node {
    bbox: Box3,
    /// Leaf: first index into `order`; inner: index of the left child (right = left + 1).
    start: u32,
    /// Leaf: number of triangles (> 0); inner: 0.
    count: u32,
}

/// A BVH over the triangles of one mesh.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    /// Triangle ids in leaf order.
    order: Vec<u32>,
    /// Their boxes, in the same order.
    boxes: Vec<Box3>,
}

/// Spreads the low 21 bits of `x` to every third bit.
fn spread(x: u64) -> u64 {
    let mut x = x & 0x1f_ffff;
    x = (x | x << 32) & 0x1f_0000_0000_ffff;
    x = (x | x << 16) & 0x1f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    (x | x << 2) & 0x1249_2492_4924_9249
}

impl Bvh {
    /// Builds the hierarchy of `mesh` (indices must be in range).
    pub fn new(mesh: &Mesh) -> Self {
        let n = mesh.triangles.len();
        if n == 0 {
            return Bvh::default();
        }
        let boxes: Vec<Box3> = (0..n)
            .into_par_iter()
            .map(|t| {
                let [a, b, c] = mesh.corners(t);
                [
                    std::array::from_fn(|k| a[k].min(b[k]).min(c[k])),
                    std::array::from_fn(|k| a[k].max(b[k]).max(c[k])),
                ]
            })
            .collect();
        let all = boxes
            .par_iter()
            .copied()
            .reduce(|| boxes[0], |a, b| union(&a, &b));
        let scale: [f64; 3] = std::array::from_fn(|k| {
            let ext = all[1][k] - all[0][k];
            if ext > 0.0 {
                ((1u64 << 21) - 1) as f64 / ext
            } else {
                0.0
            }
        });
        let mut keyed: Vec<(u64, u32)> = boxes
            .par_iter()
            .enumerate()
            .map(|(t, b)| {
                let cell = |k: usize| {
                    let c = 0.5 * (b[0][k] + b[1][k]) - all[0][k];
                    ((c * scale[k]) as u64).min((1 << 21) - 1)
                };
                (
                    spread(cell(0)) | spread(cell(1)) << 1 | spread(cell(2)) << 2,
                    t as u32,
                )
            })
            .collect();
        keyed.par_sort_unstable();
        let order: Vec<u32> = keyed.into_iter().map(|(_, t)| t).collect();
        let mut nodes = Vec::with_capacity(2 * n.div_ceil(LEAF));
        nodes.push(Node {
            bbox: all,
            start: 0,
            count: 0,
        });
        Self::build(&mut nodes, 0, 0, n, &order, &boxes);
        let boxes = order.iter().map(|&t| boxes[t as usize]).collect();
        Bvh {
            nodes,
            order,
            boxes,
        }
    }

    /// Fills node `at` for `order[lo..hi]`.
    fn build(
        nodes: &mut Vec<Node>,
        at: usize,
        lo: usize,
        hi: usize,
        order: &[u32],
        boxes: &[Box3],
    ) {
        if hi - lo <= LEAF {
            let bbox = order[lo + 1..hi]
                .iter()
                .fold(boxes[order[lo] as usize], |b, &t| {
                    union(&b, &boxes[t as usize])
                });
            nodes[at] = Node {
                bbox,
                start: lo as u32,
                count: (hi - lo) as u32,
            };
            return;
        }
        let left = nodes.len();
        let empty = Node {
            bbox: [[0.0; 3]; 2],
            start: 0,
            count: 0,
        };
        nodes.push(empty);
        nodes.push(empty);
        // Leaf-aligned middle keeps leaves full.
        let mid = lo + ((hi - lo).div_ceil(LEAF) / 2) * LEAF;
        Self::build(nodes, left, lo, mid, order, boxes);
        Self::build(nodes, left + 1, mid, hi, order, boxes);
        nodes[at] = Node {
            bbox: union(&nodes[left].bbox, &nodes[left + 1].bbox),
            start: left as u32,
            count: 0,
        };
    }

    /// Number of triangles indexed.
    pub fn len(&self) -> usize {
        self.order.len()
    }

    /// True when no triangle is indexed.
    pub fn is_empty(&self) -> bool {
        self.order.is_empty()
    }

    /// Every pair `(triangle of self, triangle of other)` whose boxes overlap (closed
    /// boxes: touching counts). Parallel; the pairs come sorted.
    pub fn overlapping_pairs(&self, other: &Bvh) -> Vec<(u32, u32)> {
        if self.is_empty() || other.is_empty() {
            return Vec::new();
        }
        let mut pairs = self.pairs_below(other, 0, 0, 0);
        pairs.par_sort_unstable();
        pairs
    }

    fn pairs_below(&self, other: &Bvh, a: usize, b: usize, depth: u32) -> Vec<(u32, u32)> {
        let (na, nb) = (&self.nodes[a], &other.nodes[b]);
        if !overlaps(&na.bbox, &nb.bbox) {
            return Vec::new();
        }
        match (na.count > 0, nb.count > 0) {
            (true, true) => {
                let mut out = Vec::new();
                self.leaf_pairs(other, na, nb, &mut out);
                out
            }
            // Descend into the inner node, or the larger box when both are inner.
            (false, true) => self.split(other, a, b, true, depth),
            (true, false) => self.split(other, a, b, false, depth),
            (false, false) => {
                let vol = |n: &Node| (0..3).map(|k| n.bbox[1][k] - n.bbox[0][k]).product::<f64>();
                self.split(other, a, b, vol(na) >= vol(nb), depth)
            }
        }
    }

    fn split(
        &self,
        other: &Bvh,
        a: usize,
        b: usize,
        left_side: bool,
        depth: u32,
    ) -> Vec<(u32, u32)> {
        let (x, y) = if left_side {
            let c = self.nodes[a].start as usize;
            ((c, b), (c + 1, b))
        } else {
            let c = other.nodes[b].start as usize;
            ((a, c), (a, c + 1))
        };
        if depth < 12 {
            let (mut l, r) = rayon::join(
                || self.pairs_below(other, x.0, x.1, depth + 1),
                || self.pairs_below(other, y.0, y.1, depth + 1),
            );
            l.extend(r);
            l
        } else {
            let mut l = self.pairs_below(other, x.0, x.1, depth + 1);
            l.extend(self.pairs_below(other, y.0, y.1, depth + 1));
            l
        }
    }

    fn leaf_pairs(&self, other: &Bvh, na: &Node, nb: &Node, out: &mut Vec<(u32, u32)>) {
        let (ra, rb) = (
            na.start as usize..(na.start + na.count) as usize,
            nb.start as usize..(nb.start + nb.count) as usize,
        );
        for i in ra {
            for j in rb.clone() {
                if overlaps(&self.boxes[i], &other.boxes[j]) {
                    out.push((self.order[i], other.order[j]));
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::uv_sphere;

    fn tri_box(m: &Mesh, t: usize) -> Box3 {
        let [a, b, c] = m.corners(t);
        [
            std::array::from_fn(|k| a[k].min(b[k]).min(c[k])),
            std::array::from_fn(|k| a[k].max(b[k]).max(c[k])),
        ]
    }

    #[test]
    fn broad_phase_finds_exactly_the_brute_force_pairs() {
        let a = uv_sphere([0.0; 3], 1.0, 24, 12);
        let b = uv_sphere([0.5, 0.1, 0.0], 1.0, 20, 10);
        let pairs = Bvh::new(&a).overlapping_pairs(&Bvh::new(&b));
        let mut want = Vec::new();
        for i in 0..a.triangles.len() {
            for j in 0..b.triangles.len() {
                if overlaps(&tri_box(&a, i), &tri_box(&b, j)) {
                    want.push((i as u32, j as u32));
                }
            }
        }
        assert!(!want.is_empty());
        assert_eq!(pairs.len(), want.len());
        assert!(pairs == want);
    }

    #[test]
    fn box_leaves_cover_every_triangle_once() {
        let m = uv_sphere([3.0; 3], 2.0, 33, 17);
        let bvh = Bvh::new(&m);
        let mut seen = bvh.order.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..m.triangles.len() as u32).collect::<Vec<_>>());
        assert!(Bvh::new(&Mesh::default())
            .overlapping_pairs(&bvh)
            .is_empty());
    }

    #[test]
    fn touching_boxes_count() {
        let a = Mesh::cuboid([0.0; 3], [1.0; 3]);
        let b = Mesh::cuboid([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]);
        let pairs = Bvh::new(&a).overlapping_pairs(&Bvh::new(&b));
        // a's x = 1 face (triangles 10, 11) touches b's x = 1 face (triangles 8, 9).
        for p in [(10, 8), (10, 9), (11, 8), (11, 9)] {
            assert!(pairs.contains(&p), "{p:?}");
        }
    }
}
