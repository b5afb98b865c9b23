//! The exact-weld table: one vertex id per distinct position (exact equality), shared by
//! [`crate::weld_exact`], [`crate::Mesh::from_soup`] and the readers of formats that store
//! corners per triangle (STL, DXF 3DFACE, JSON soups).

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
/// `0.0 == -0.0`), in order of first appearance. The shared core of [`crate::weld_exact`] and of
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{weld_exact, Mesh};

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
}
