//! The one data model: [`Mesh`] (positions + triangles), soup ↔ indexed conversion,
//! exact welding and bounds.

use crate::error::{Error, Location, Result};

/// A triangle mesh: vertex positions and triangles as triples of vertex indices
/// (counter-clockwise seen from the side the normal points to).
///
/// A triangle soup is a `Mesh` whose triangles share no vertices ([`Mesh::from_soup_unwelded`]).
/// Nothing about the mesh is assumed: it may be open, non-manifold, inconsistently oriented
/// or contain degenerate triangles; [`crate::measure::mesh_stats`] tells which.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions `[x, y, z]`.
    pub positions: Vec<[f64; 3]>,
    /// Triangles as indices into `positions`.
    pub triangles: Vec<[u32; 3]>,
}

/// An axis-aligned bounding box.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Aabb {
    /// Smallest coordinates.
    pub min: [f64; 3],
    /// Largest coordinates.
    pub max: [f64; 3],
}

impl Aabb {
    /// The box's centre.
    pub fn center(&self) -> [f64; 3] {
        std::array::from_fn(|i| 0.5 * (self.min[i] + self.max[i]))
    }

    /// The box's edge lengths.
    pub fn size(&self) -> [f64; 3] {
        std::array::from_fn(|i| self.max[i] - self.min[i])
    }
}

/// The result of [`weld_exact`]: the welded mesh and, for every input vertex, its new index.
#[derive(Clone, Debug, PartialEq)]
pub struct Welded {
    /// The mesh with every set of equal positions merged into one vertex.
    pub mesh: Mesh,
    /// `vertex_map[old] = new` for every input vertex.
    pub vertex_map: Vec<u32>,
}

impl Mesh {
    /// A mesh from positions and triangles, as given (no checks; see [`Mesh::validate`]).
    pub fn new(positions: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>) -> Self {
        Mesh {
            positions,
            triangles,
        }
    }

    /// The axis-aligned unit cube `[0,1]^3`, 8 vertices, 12 outward-facing triangles.
    pub fn unit_cube() -> Self {
        Self::cuboid([0.0; 3], [1.0; 3])
    }

    /// An axis-aligned box from `min` to `max`, 8 vertices, 12 outward-facing triangles.
    pub fn cuboid(min: [f64; 3], max: [f64; 3]) -> Self {
        let positions = (0..8)
            .map(|i| {
                [
                    if i & 1 == 0 { min[0] } else { max[0] },
                    if i & 2 == 0 { min[1] } else { max[1] },
                    if i & 4 == 0 { min[2] } else { max[2] },
                ]
            })
            .collect();
        let triangles = vec![
            [0, 2, 1],
            [1, 2, 3], // z = min
            [4, 5, 6],
            [5, 7, 6], // z = max
            [0, 1, 4],
            [1, 5, 4], // y = min
            [2, 6, 3],
            [3, 6, 7], // y = max
            [0, 4, 2],
            [2, 4, 6], // x = min
            [1, 3, 5],
            [3, 7, 5], // x = max
        ];
        Mesh {
            positions,
            triangles,
        }
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Number of vertices (including any that no triangle uses).
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// True when the mesh has no triangles.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// The three corner positions of triangle `t`. Panics if `t` or its indices are out of
    /// range; call [`Mesh::validate`] first on untrusted data.
    #[inline]
    pub fn corners(&self, t: usize) -> [[f64; 3]; 3] {
        let [a, b, c] = self.triangles[t];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }

    /// A mesh from a triangle soup (three corner positions per triangle), with corners at
    /// exactly equal positions welded into one vertex ([`weld_exact`]).
    pub fn from_soup(soup: &[[[f64; 3]; 3]]) -> Self {
        let mut welder = Welder::with_capacity(soup.len() * 3);
        let mut ids = Vec::with_capacity(soup.len() * 3);
        welder.index_batch(soup.as_flattened(), &mut ids);
        Mesh {
            positions: welder.into_positions(),
            triangles: ids.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
        }
    }

    /// A mesh from a triangle soup without welding: triangle `t` uses vertices `3t..3t+3`.
    pub fn from_soup_unwelded(soup: &[[[f64; 3]; 3]]) -> Self {
        let positions = soup.iter().flatten().copied().collect();
        let triangles = (0..soup.len() as u32)
            .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
            .collect();
        Mesh {
            positions,
            triangles,
        }
    }

    /// The triangle soup: three corner positions per triangle.
    /// Panics on out-of-range indices; call [`Mesh::validate`] first on untrusted data.
    pub fn to_soup(&self) -> Vec<[[f64; 3]; 3]> {
        (0..self.triangles.len()).map(|t| self.corners(t)).collect()
    }

    /// Checks the data model: every coordinate finite, every index in range, at most
    /// `u32::MAX` vertices. The error names the first offending vertex or triangle.
    pub fn validate(&self) -> Result<()> {
        if self.positions.len() > u32::MAX as usize {
            return Err(Error::invalid(
                Location::Whole,
                format!(
                    "{} vertices exceed the limit of {}",
                    self.positions.len(),
                    u32::MAX
                ),
            ));
        }
        if let Some(v) = self
            .positions
            .iter()
            .position(|p| p.iter().any(|c| !c.is_finite()))
        {
            return Err(Error::invalid(
                Location::Vertex(v),
                format!("non-finite coordinate {:?}", self.positions[v]),
            ));
        }
        let n = self.positions.len() as u64;
        if let Some(t) = self
            .triangles
            .iter()
            .position(|tri| tri.iter().any(|&i| u64::from(i) >= n))
        {
            return Err(Error::invalid(
                Location::Triangle(t),
                format!(
                    "vertex index out of range in {:?} (the mesh has {n} vertices)",
                    self.triangles[t]
                ),
            ));
        }
        Ok(())
    }

    /// The bounding box of the vertices that triangles use; `None` for a mesh without triangles.
    pub fn bounds(&self) -> Option<Aabb> {
        let mut it = self.triangles.iter().flatten();
        let first = self.positions[*it.next()? as usize];
        let mut b = Aabb {
            min: first,
            max: first,
        };
        for &i in it {
            let p = self.positions[i as usize];
            b.min = std::array::from_fn(|k| b.min[k].min(p[k]));
            b.max = std::array::from_fn(|k| b.max[k].max(p[k]));
        }
        Some(b)
    }

    /// The same mesh with every triangle's orientation reversed.
    pub fn flipped(&self) -> Mesh {
        Mesh {
            positions: self.positions.clone(),
            triangles: self.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect(),
        }
    }

    /// The same mesh without the vertices no triangle uses, the rest renumbered in order of
    /// first use; also returns how many were dropped. Triangle indices must be valid.
    pub fn without_unreferenced(self) -> (Mesh, usize) {
        let mut id = vec![u32::MAX; self.positions.len()];
        let mut positions = Vec::new();
        let triangles: Vec<[u32; 3]> = self
            .triangles
            .iter()
            .map(|t| {
                t.map(|v| {
                    if id[v as usize] == u32::MAX {
                        id[v as usize] = positions.len() as u32;
                        positions.push(self.positions[v as usize]);
                    }
                    id[v as usize]
                })
            })
            .collect();
        let dropped = self.positions.len() - positions.len();
        (Mesh::new(positions, triangles), dropped)
    }
}

/// Hash key of a position: its bit pattern, with `-0.0` folded onto `0.0` so that
/// positions that are equal as numbers share one key.
#[inline]
fn position_key(p: &[f64; 3]) -> [u64; 3] {
    [
        (p[0] + 0.0).to_bits(),
        (p[1] + 0.0).to_bits(),
        (p[2] + 0.0).to_bits(),
    ]
}

/// Assigns vertex indices to positions, one index per distinct position (exact equality,
/// `0.0 == -0.0`), in order of first appearance. The shared core of [`weld_exact`] and of
/// the readers of formats that store corners per triangle.
///
/// An open-addressing table of 8-byte slots (32-bit fingerprint, 32-bit vertex id + 1)
/// instead of a general hash map: for a million vertices it is 16 MB rather than ~64 MB of
/// buckets holding full keys, so it stays in cache, and welding a 2M-triangle STL is about
/// twice as fast. Equality is always confirmed on the stored position: exact, no false merges.
///
/// Large inputs go through [`Welder::index_batch`], which first issues the table loads for a
/// whole batch of positions, independent of each other so that the processor overlaps their
/// cache misses, and only then resolves them one by one.
pub(crate) struct Welder {
    slots: Vec<u64>,
    positions: Vec<[f64; 3]>,
}

/// Positions with their weld keys and hashes, computed apart from the table work so that a
/// reader can prepare the next block while the welder works on this one.
#[derive(Default)]
pub(crate) struct Hashed {
    pub(crate) positions: Vec<[f64; 3]>,
    keys: Vec<[u64; 3]>,
    hashes: Vec<u64>,
}

impl Hashed {
    /// Replaces the content with `ps` and their keys and hashes.
    pub(crate) fn fill(&mut self, ps: &[[f64; 3]]) {
        self.positions.clear();
        self.positions.extend_from_slice(ps);
        self.hash();
    }

    /// Computes keys and hashes of the current `positions`.
    pub(crate) fn hash(&mut self) {
        self.keys.clear();
        self.keys.extend(self.positions.iter().map(position_key));
        self.hashes.clear();
        self.hashes.extend(self.keys.iter().map(|&k| key_hash(k)));
    }
}

/// Positions per batch in [`Welder::index_batch`]: enough independent loads in flight to
/// hide memory latency, few enough to stay in L1.
const BATCH: usize = 64;

/// A 64-bit mix of a position key: every input bit reaches the low bits used as slot index
/// (float bit patterns often end in long runs of zeros, e.g. values read from `f32`).
#[inline]
fn key_hash(k: [u64; 3]) -> u64 {
    // Three independent multiplies (they overlap in the pipeline), then a fold and one more
    // multiply so that high and low bits of every coordinate reach every output bit.
    let h = k[0].wrapping_mul(0x9e37_79b9_7f4a_7c15)
        ^ k[1].wrapping_mul(0xc2b2_ae3d_27d4_eb4f).rotate_left(21)
        ^ k[2].wrapping_mul(0x1656_67b1_9e37_79f9).rotate_left(42);
    let h = (h ^ (h >> 32)).wrapping_mul(0xff51_afd7_ed55_8ccd);
    h ^ (h >> 29)
}

impl Welder {
    /// A welder expecting about `corners` positions.
    pub(crate) fn with_capacity(corners: usize) -> Self {
        // Typical closed meshes have about one vertex per two triangles (six corners).
        let expected = (corners / 6).max(16);
        Welder {
            slots: vec![0; (2 * expected).next_power_of_two()],
            positions: Vec::with_capacity(expected),
        }
    }

    /// The index of position `p`, new if no equal position was seen before.
    #[inline]
    pub(crate) fn index(&mut self, p: [f64; 3]) -> u32 {
        let key = position_key(&p);
        let h = key_hash(key);
        self.lookup_or_insert(p, key, h)
    }

    /// [`Welder::index`] of every position in `ps`, appended to `out` in order.
    pub(crate) fn index_batch(&mut self, ps: &[[f64; 3]], out: &mut Vec<u32>) {
        let mut hashed = Hashed::default();
        // Cache-sized pieces: the keys and hashes of a piece stay in L2 until used.
        for piece in ps.chunks(4096) {
            hashed.fill(piece);
            self.index_hashed(&hashed, out);
        }
    }

    /// [`Welder::index_batch`] of positions already hashed (possibly on another thread).
    pub(crate) fn index_hashed(&mut self, h: &Hashed, out: &mut Vec<u32>) {
        let mut first = [0u64; BATCH];
        for ((chunk, keys), hashes) in h
            .positions
            .chunks(BATCH)
            .zip(h.keys.chunks(BATCH))
            .zip(h.hashes.chunks(BATCH))
        {
            let mask = self.slots.len() - 1;
            // Independent loads: the processor keeps many of these misses in flight.
            for (f, &h) in first.iter_mut().zip(hashes) {
                *f = self.slots[h as usize & mask];
            }
            // A slot's id never changes once written (growing moves slots, not ids), so a
            // matching early load is a correct answer; checking it loads the stored
            // positions, again independently of each other.
            let mut found = [u32::MAX; BATCH];
            for i in 0..chunk.len() {
                let s = first[i];
                if s != 0 && s >> 32 == hashes[i] >> 32 {
                    let id = (s as u32) - 1;
                    if position_key(&self.positions[id as usize]) == keys[i] {
                        found[i] = id;
                    }
                }
            }
            for (i, &p) in chunk.iter().enumerate() {
                out.push(if found[i] != u32::MAX {
                    found[i]
                } else {
                    self.lookup_or_insert(p, keys[i], hashes[i])
                });
            }
        }
    }

    /// The table probe of [`Welder::index`].
    #[inline]
    fn lookup_or_insert(&mut self, p: [f64; 3], key: [u64; 3], h: u64) -> u32 {
        let fp = h >> 32;
        let mask = self.slots.len() - 1;
        let mut i = h as usize & mask;
        loop {
            let s = self.slots[i];
            if s == 0 {
                let id = self.positions.len() as u32;
                self.positions.push(p);
                self.slots[i] = (fp << 32) | u64::from(id + 1);
                if 2 * self.positions.len() > self.slots.len() {
                    self.grow();
                }
                return id;
            }
            if s >> 32 == fp {
                let id = (s as u32) - 1;
                if position_key(&self.positions[id as usize]) == key {
                    return id;
                }
            }
            i = (i + 1) & mask;
        }
    }

    /// Doubles the table, re-inserting every stored vertex.
    #[cold]
    fn grow(&mut self) {
        let mut slots = vec![0u64; 2 * self.slots.len()];
        let mask = slots.len() - 1;
        for (id, p) in self.positions.iter().enumerate() {
            let h = key_hash(position_key(p));
            let mut i = h as usize & mask;
            while slots[i] != 0 {
                i = (i + 1) & mask;
            }
            slots[i] = ((h >> 32) << 32) | (id as u64 + 1);
        }
        self.slots = slots;
    }

    /// The distinct positions, indexed as [`Welder::index`] returned them.
    pub(crate) fn into_positions(self) -> Vec<[f64; 3]> {
        self.positions
    }
}

/// Welds vertices whose positions are exactly equal (as `f64` numbers; `0.0` and `-0.0`
/// are equal). No tolerance: for welding within a distance use the repair tools.
///
/// Input: any mesh (indices must be in range). Output: the welded mesh, vertices in order
/// of first appearance in `positions`, triangles unchanged in number and order (a triangle
/// whose corners become equal stays, as a degenerate triangle), plus the old→new vertex map.
/// Deterministic.
pub fn weld_exact(mesh: &Mesh) -> Welded {
    let mut welder = Welder::with_capacity(mesh.positions.len() * 6);
    let mut vertex_map = Vec::with_capacity(mesh.positions.len());
    welder.index_batch(&mesh.positions, &mut vertex_map);
    let triangles = mesh
        .triangles
        .iter()
        .map(|t| t.map(|i| vertex_map[i as usize]))
        .collect();
    Welded {
        mesh: Mesh {
            positions: welder.into_positions(),
            triangles,
        },
        vertex_map,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn soup_round_trip_welds_shared_corners() {
        let cube = Mesh::unit_cube();
        let soup = cube.to_soup();
        assert_eq!(soup.len(), 12);
        let unwelded = Mesh::from_soup_unwelded(&soup);
        assert_eq!(unwelded.vertex_count(), 36);
        let welded = Mesh::from_soup(&soup);
        assert_eq!(welded.vertex_count(), 8);
        assert_eq!(welded.to_soup(), soup);
    }

    #[test]
    fn weld_merges_negative_zero_but_not_neighbours() {
        let m = Mesh::new(
            vec![
                [0.0, 0.0, 1.0],
                [-0.0, 0.0, 1.0],
                [0.0, 0.0, f64::from_bits(1.0f64.to_bits() + 1)],
            ],
            vec![[0, 1, 2]],
        );
        let w = weld_exact(&m);
        assert_eq!(w.vertex_map, vec![0, 0, 1]);
        assert_eq!(w.mesh.triangles, vec![[0, 0, 1]]);
    }

    /// The batched open-addressing welder against a plain ordered map, on a soup where most
    /// positions repeat, some differ only in the last bit or in the sign of zero, and far
    /// more distinct positions arrive than the table was sized for (it must grow).
    #[test]
    fn weld_matches_naive_reference() {
        let mut rng = crate::test_util::Rng(0x2545_f491_4f6c_dd1d);
        let mut next = || rng.next();
        let pool: Vec<[f64; 3]> = (0..30_000)
            .map(|i| {
                let base = [
                    (i % 37) as f64 * 0.1,
                    (i % 101) as f64 - 50.0,
                    478_614.7 + (i / 50) as f64,
                ];
                match i % 5 {
                    0 => [-0.0, base[1], base[2]],
                    1 => [f64::from_bits(base[0].to_bits() + 1), base[1], base[2]],
                    _ => base,
                }
            })
            .collect();
        let soup: Vec<[[f64; 3]; 3]> = (0..40_000)
            .map(|_| std::array::from_fn(|_| pool[(next() % pool.len() as u64) as usize]))
            .collect();
        let welded = Mesh::from_soup(&soup);
        let mut naive = std::collections::BTreeMap::new();
        let mut positions = Vec::new();
        let triangles: Vec<[u32; 3]> = soup
            .iter()
            .map(|t| {
                t.map(|p| {
                    *naive.entry(position_key(&p)).or_insert_with(|| {
                        positions.push(p);
                        positions.len() as u32 - 1
                    })
                })
            })
            .collect();
        assert_eq!(welded.triangles, triangles);
        assert_eq!(welded.positions.len(), positions.len());
        assert!(positions.len() > 20_000, "{}", positions.len());
        let w = weld_exact(&Mesh::from_soup_unwelded(&soup));
        assert_eq!(w.mesh.triangles, triangles);
    }

    #[test]
    fn validate_names_offender() {
        let mut m = Mesh::unit_cube();
        m.triangles[5] = [0, 1, 8];
        assert!(matches!(
            m.validate(),
            Err(Error::InvalidMesh {
                location: Location::Triangle(5),
                ..
            })
        ));
        let mut m = Mesh::unit_cube();
        m.positions[3][1] = f64::NAN;
        assert!(matches!(
            m.validate(),
            Err(Error::InvalidMesh {
                location: Location::Vertex(3),
                ..
            })
        ));
        assert!(Mesh::unit_cube().validate().is_ok());
    }

    #[test]
    fn bounds_of_cuboid() {
        let b = Mesh::cuboid([-1.0, 2.0, 3.0], [4.0, 5.0, 6.0])
            .bounds()
            .unwrap();
        assert_eq!(b.min, [-1.0, 2.0, 3.0]);
        assert_eq!(b.max, [4.0, 5.0, 6.0]);
        assert_eq!(Mesh::default().bounds(), None);
    }
}
