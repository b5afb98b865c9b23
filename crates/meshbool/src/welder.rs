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
/// Positions go through [`Welder::index_hashed`] in blocks: it first issues the table loads for a
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

/// Positions per batch in [`Welder::index_hashed`]: enough independent loads in flight to
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
        Welder::for_vertices(corners / 6)
    }

    /// A welder expecting about `vertices` distinct positions.
    pub(crate) fn for_vertices(vertices: usize) -> Self {
        let expected = vertices.max(16);
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
    #[cfg(test)]
    pub(crate) fn index_batch(&mut self, ps: &[[f64; 3]], out: &mut Vec<u32>) {
        let mut hashed = Hashed::default();
        // Cache-sized pieces: the keys and hashes of a piece stay in L2 until used.
        for piece in ps.chunks(4096) {
            hashed.fill(piece);
            self.index_hashed(&hashed, out);
        }
    }

    /// [`Welder::index`] of every position of `h` (hashed beforehand, possibly on another
    /// thread), appended to `out` in order.
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

/// Corners per part of [`weld_all`]'s parallel path: the unit of its phases that run in
/// corner order (a part's corner lists and ids stay in cache).
const PART: usize = 1 << 16;

/// One part's corners listed by shard ([`weld_all`], step 1), with their positions.
struct Listed {
    corners: Vec<Vec<u32>>,
    positions: Vec<Vec<[f64; 3]>>,
}

/// One shard welded ([`weld_all`], step 2): its distinct positions, each of its corners'
/// shard-local vertex id (in its corner order) and each of its vertices' first corner.
struct Shard {
    positions: Vec<[f64; 3]>,
    local: Vec<u32>,
    firsts: Vec<u32>,
}

/// The vertices first seen in one part ([`weld_all`], step 3): their positions in corner
/// order and, per shard, the rank in that order of each of its vertices seen first here
/// (in shard order).
struct FirstSeen {
    positions: Vec<[f64; 3]>,
    rank: Vec<Vec<u32>>,
}

/// Welds `n` corners, `fill(range, out)` appending the positions of the corners in
/// `range` to `out`: the distinct positions in order of first appearance and each
/// corner's vertex id, exactly as one [`Welder`] fed the corners in order would give
/// them, whatever the number of threads. `vertices` is the number of distinct positions
/// expected (the tables' size; they grow when it is exceeded).
///
/// With fewer than eight threads, one welder takes the corners in blocks, the next block
/// decoded and hashed on another thread meanwhile. With eight or more (measured on 16
/// cores: at four threads, two files read side by side, the shards cost more than they
/// save) and enough corners, the work is spread over shards (the top bits of a
/// position's hash pick its shard, so equal positions share one):
/// 1. in parallel over parts of the corners, each shard's corners are listed in order;
/// 2. in parallel over shards, a [`Welder`] per shard numbers its vertices in order of
///    first appearance within the shard;
/// 3. in parallel over parts, the shard vertices first seen in the part are merged in
///    corner order, which numbers them globally;
/// 4. in parallel over parts, each corner's id is its shard vertex's global number.
///
/// No atomics and no locks; the same result as the serial welder because a vertex's
/// global number is the rank of its first corner among all first corners.
pub(crate) fn weld_all<F>(n: usize, vertices: usize, fill: F) -> (Vec<[f64; 3]>, Vec<u32>)
where
    F: Fn(std::ops::Range<usize>, &mut Vec<[f64; 3]>) + Sync,
{
    use rayon::prelude::*;
    let threads = rayon::current_num_threads();
    // Corner ids are 32-bit in the shards' lists: more corners go the serial way.
    if threads < 8 || n < 4 * PART || n > u32::MAX as usize {
        // One welder; with two threads or more, the next block is decoded and hashed on
        // one while the welder works on this one.
        const BLOCK: usize = 3 << 12;
        let mut welder = Welder::for_vertices(vertices);
        let mut ids = Vec::with_capacity(n);
        let decode = |start: usize, out: &mut Hashed| {
            out.positions.clear();
            fill(start..(start + BLOCK).min(n), &mut out.positions);
            out.hash();
        };
        let (mut cur, mut next) = (Hashed::default(), Hashed::default());
        decode(0, &mut cur);
        for start in (0..n).step_by(BLOCK) {
            crate::par::join(
                || {
                    if start + BLOCK < n {
                        decode(start + BLOCK, &mut next)
                    }
                },
                || welder.index_hashed(&cur, &mut ids),
            );
            std::mem::swap(&mut cur, &mut next);
        }
        return (welder.into_positions(), ids);
    }
    // At least 8 shards (so `bits` > 0), at most 256 (a shard number fits a byte).
    let shards = (4 * threads).next_power_of_two().clamp(8, 256);
    let bits = shards.trailing_zeros();
    let parts = n.div_ceil(PART);
    let range = |k: usize| k * PART..((k + 1) * PART).min(n);
    // 1. Per part, per shard: the part's corners in that shard, in order.
    let lists: Vec<Listed> = (0..parts)
        .into_par_iter()
        .map(|k| {
            let mut out = Listed {
                corners: vec![Vec::with_capacity(PART / shards * 5 / 4); shards],
                positions: vec![Vec::with_capacity(PART / shards * 5 / 4); shards],
            };
            let r = range(k);
            let mut ps = Vec::with_capacity(r.len());
            fill(r.clone(), &mut ps);
            for (c, p) in r.zip(ps) {
                let s = (key_hash(position_key(&p)) >> (64 - bits)) as usize;
                out.corners[s].push(c as u32);
                out.positions[s].push(p);
            }
            out
        })
        .collect();
    // 2. Per shard: its vertices numbered in order of first appearance.
    let welded: Vec<Shard> = (0..shards)
        .into_par_iter()
        .map(|s| {
            let count: usize = lists.iter().map(|l| l.corners[s].len()).sum();
            let mut welder = Welder::for_vertices(vertices / shards * 9 / 8);
            let mut local = Vec::with_capacity(count);
            let mut firsts = Vec::new();
            let mut hashed = Hashed::default();
            for (piece, ps) in lists
                .iter()
                .flat_map(|l| l.corners[s].chunks(4096).zip(l.positions[s].chunks(4096)))
            {
                hashed.fill(ps);
                let before = local.len();
                welder.index_hashed(&hashed, &mut local);
                // Ids of new vertices come in order: a corner is its vertex's first
                // exactly when its id is the next one.
                for (&id, &c) in local[before..].iter().zip(piece) {
                    if id as usize == firsts.len() {
                        firsts.push(c);
                    }
                }
            }
            Shard {
                positions: welder.into_positions(),
                local,
                firsts,
            }
        })
        .collect();
    // 3. Per part: the vertices first seen in it, in corner order.
    let merged: Vec<FirstSeen> = (0..parts)
        .into_par_iter()
        .map(|k| {
            let r = range(k);
            let mut seen: Vec<u64> = Vec::new();
            let mut from = vec![0usize; shards];
            for (s, shard) in welded.iter().enumerate() {
                let firsts = &shard.firsts;
                let lo = firsts.partition_point(|&c| (c as usize) < r.start);
                let hi = firsts.partition_point(|&c| (c as usize) < r.end);
                from[s] = lo;
                seen.extend(
                    firsts[lo..hi]
                        .iter()
                        .map(|&c| (u64::from(c) << 8) | s as u64),
                );
            }
            seen.sort_unstable();
            let mut out = FirstSeen {
                positions: Vec::with_capacity(seen.len()),
                rank: vec![Vec::new(); shards],
            };
            for (i, &e) in seen.iter().enumerate() {
                let s = (e & 0xff) as usize;
                out.positions
                    .push(welded[s].positions[from[s] + out.rank[s].len()]);
                out.rank[s].push(i as u32);
            }
            out
        })
        .collect();
    let mut base = Vec::with_capacity(parts);
    let mut total = 0u32;
    for m in &merged {
        base.push(total);
        total += m.positions.len() as u32;
    }
    let global: Vec<Vec<u32>> = (0..shards)
        .into_par_iter()
        .map(|s| {
            merged
                .iter()
                .zip(&base)
                .flat_map(|(m, &b)| m.rank[s].iter().map(move |&i| b + i))
                .collect()
        })
        .collect();
    // 4. Every corner's global vertex number, part by part.
    // Where part k's corners of shard s start among the shard's corners.
    let mut offset: Vec<Vec<usize>> = Vec::with_capacity(parts);
    let mut next = vec![0usize; shards];
    for l in &lists {
        offset.push(next.clone());
        for (n, c) in next.iter_mut().zip(&l.corners) {
            *n += c.len();
        }
    }
    let mut ids = crate::par::filled(0u32, n);
    ids.par_chunks_mut(PART).enumerate().for_each(|(k, out)| {
        for (s, list) in lists[k].corners.iter().enumerate() {
            let local = &welded[s].local[offset[k][s]..offset[k][s] + list.len()];
            for (&c, &v) in list.iter().zip(local) {
                out[c as usize - k * PART] = global[s][v as usize];
            }
        }
    });
    let positions = crate::par::concat(merged.into_iter().map(|m| m.positions).collect());
    debug_assert_eq!(positions.len(), total as usize);
    (positions, ids)
}

/// Corner ids three by three: the triangles of a welded soup (on all threads).
pub(crate) fn triangles_of(ids: &[u32]) -> Vec<[u32; 3]> {
    use rayon::prelude::*;
    let mut triangles = crate::par::filled([0u32; 3], ids.len() / 3);
    triangles
        .par_chunks_mut(1 << 14)
        .zip(ids.par_chunks(3 << 14))
        .for_each(|(t, c)| {
            for (t, c) in t.iter_mut().zip(c.chunks_exact(3)) {
                *t = [c[0], c[1], c[2]];
            }
        });
    triangles
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

    /// The sharded weld of many threads numbers vertices exactly as one welder does
    /// (order of first appearance), on a soup large enough to take the sharded path,
    /// where positions repeat across parts and shards, and some differ only in the last
    /// bit or in the sign of zero.
    #[test]
    fn sharded_weld_numbers_vertices_as_one_welder_does() {
        let mut rng = crate::test_util::Rng(0x9e37_79b9_7f4a_7c15);
        let pool: Vec<[f64; 3]> = (0..60_000)
            .map(|i| {
                let j = i / 4;
                let base = [0.25 + (j % 53) as f64, (j / 53) as f64, 1e6 + j as f64];
                match i % 4 {
                    0 => [-0.0, base[1], base[2]],
                    1 => [0.0, base[1], base[2]],
                    2 => [f64::from_bits(base[0].to_bits() + 1), base[1], base[2]],
                    _ => base,
                }
            })
            .collect();
        let n = 6 * PART + 12_345;
        let corners: Vec<[f64; 3]> = (0..n)
            .map(|_| pool[(rng.next() % pool.len() as u64) as usize])
            .collect();
        let fill =
            |r: std::ops::Range<usize>, out: &mut Vec<[f64; 3]>| out.extend_from_slice(&corners[r]);
        let mut serial = Welder::with_capacity(n);
        let mut expected = Vec::new();
        serial.index_batch(&corners, &mut expected);
        let expected_positions = serial.into_positions();
        for threads in [1, 2, 4, 8, 13] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let (positions, ids) = pool.install(|| weld_all(n, 1000, fill));
            assert_eq!(ids, expected, "{threads} threads");
            let bits = |ps: &[[f64; 3]]| -> Vec<[u64; 3]> {
                ps.iter().map(|p| p.map(f64::to_bits)).collect()
            };
            assert_eq!(
                bits(&positions),
                bits(&expected_positions),
                "{threads} threads"
            );
        }
        // -0.0 and 0.0 share a vertex; the last-bit neighbours do not.
        let keys: std::collections::BTreeSet<[u64; 3]> = corners.iter().map(position_key).collect();
        let raw: std::collections::BTreeSet<[u64; 3]> =
            corners.iter().map(|p| p.map(f64::to_bits)).collect();
        assert_eq!(expected_positions.len(), keys.len());
        assert!(
            keys.len() < raw.len() && keys.len() > 40_000,
            "{}",
            keys.len()
        );
    }
}
