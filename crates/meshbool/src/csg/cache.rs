//! The content-addressed cache of node results: in memory, and optionally in a folder
//! of files named by key.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use crate::{Error, Mesh, Result};

/// A node's key: the BLAKE3 hash of what determines its result (docs/csg.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Key(pub [u8; 32]);

impl Key {
    /// The key in hexadecimal (64 digits).
    pub fn hex(&self) -> String {
        self.0.iter().map(|b| format!("{b:02x}")).collect()
    }
}

impl std::fmt::Display for Key {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.hex())
    }
}

/// Results of nodes by key, kept between evaluations ([`super::evaluate`]): in memory,
/// and with [`Cache::in_dir`] also as files in a folder, so that they outlive the process.
///
/// The memory holds every result computed or read since the cache was made (or
/// [`Cache::clear`]ed). A file entry is written beside its final name and renamed into
/// place (never half written); one that does not read back whole and matching its
/// checksum is recomputed and replaced, never trusted.
#[derive(Debug, Default)]
pub struct Cache {
    memory: Mutex<HashMap<Key, Arc<Mesh>>>,
    dir: Option<PathBuf>,
}

/// Where a result came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Source {
    /// Computed in this evaluation.
    Computed,
    /// From the cache's memory.
    Memory,
    /// From the cache's folder.
    Disk,
}

/// The first bytes of an entry file: a name and the format's version.
const MAGIC: &[u8; 8] = b"MBCSG\x00\x00\x01";

impl Cache {
    /// An empty cache in memory only.
    pub fn new() -> Cache {
        Cache::default()
    }

    /// A cache that also keeps results as files in `dir` (created if missing), one file
    /// per node's result, named by its key (`KEY.mbcsg`).
    pub fn in_dir(dir: impl Into<PathBuf>) -> Result<Cache> {
        let dir = dir.into();
        std::fs::create_dir_all(&dir).map_err(|e| Error::from(e).in_file("creating", &dir))?;
        Ok(Cache {
            memory: Mutex::default(),
            dir: Some(dir),
        })
    }

    /// The folder of the file entries, if any.
    pub fn dir(&self) -> Option<&Path> {
        self.dir.as_deref()
    }

    /// The results held in memory.
    pub fn len(&self) -> usize {
        self.lock().len()
    }

    /// Whether the memory holds no result.
    pub fn is_empty(&self) -> bool {
        self.lock().is_empty()
    }

    /// Forgets the results held in memory (the folder's files stay).
    pub fn clear(&self) {
        self.lock().clear();
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, HashMap<Key, Arc<Mesh>>> {
        // A panic elsewhere cannot leave the map half changed: insert and get only.
        self.memory.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The result of `key` in memory.
    pub(super) fn get(&self, key: &Key) -> Option<Arc<Mesh>> {
        self.lock().get(key).cloned()
    }

    /// Keeps `mesh` as the result of `key` in memory.
    pub(super) fn put(&self, key: Key, mesh: Arc<Mesh>) {
        self.lock().insert(key, mesh);
    }

    /// The path of `key`'s file entry.
    fn entry(&self, key: &Key) -> Option<PathBuf> {
        self.dir
            .as_ref()
            .map(|d| d.join(format!("{}.mbcsg", key.hex())))
    }

    /// The result of `key` from the folder: `Ok(None)` without a folder or an entry,
    /// `Err(why)` for an entry that does not read back whole (it is then recomputed).
    pub(super) fn load(&self, key: &Key) -> std::result::Result<Option<Mesh>, String> {
        let Some(path) = self.entry(key) else {
            return Ok(None);
        };
        let bytes = match std::fs::read(&path) {
            Ok(b) => b,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
            Err(e) => return Err(format!("cannot read {}: {e}", path.display())),
        };
        decode(&bytes, key)
            .map(Some)
            .map_err(|why| format!("{} {why}", path.display()))
    }

    /// Writes `mesh` as `key`'s file entry (nothing without a folder); the error says why
    /// it could not be written.
    pub(super) fn store(&self, key: &Key, mesh: &Mesh) -> std::result::Result<(), String> {
        let Some(path) = self.entry(key) else {
            return Ok(());
        };
        // Written beside its name, then renamed over it: a reader sees a whole entry or
        // none. Not synced: an entry lost or damaged by a crash fails its checksum and is
        // computed again.
        static WRITES: AtomicUsize = AtomicUsize::new(0);
        let n = WRITES.fetch_add(1, Ordering::Relaxed);
        let part = path.with_extension(format!("part-{}-{n}", std::process::id()));
        let written =
            std::fs::write(&part, encode(key, mesh)).and_then(|()| std::fs::rename(&part, &path));
        if let Err(e) = written {
            let _ = std::fs::remove_file(&part);
            return Err(format!("cannot write {}: {e}", path.display()));
        }
        Ok(())
    }
}

/// An entry: [`MAGIC`], the key, the vertex and triangle counts (`u64`), the positions
/// (`f64`) and the triangles' corners (`u32`), all little-endian, then the BLAKE3 hash of
/// everything before it.
fn encode(key: &Key, mesh: &Mesh) -> Vec<u8> {
    let (p, t) = (mesh.positions(), mesh.triangles());
    let mut out = Vec::with_capacity(8 + 32 + 16 + p.len() * 24 + t.len() * 12 + 32);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&key.0);
    out.extend_from_slice(&(p.len() as u64).to_le_bytes());
    out.extend_from_slice(&(t.len() as u64).to_le_bytes());
    for x in p.iter().flatten() {
        out.extend_from_slice(&x.to_le_bytes());
    }
    for v in t.iter().flatten() {
        out.extend_from_slice(&v.to_le_bytes());
    }
    let sum = blake3::hash(&out);
    out.extend_from_slice(sum.as_bytes());
    out
}

/// The mesh of an entry ([`encode`]), or why it is not one for `key`.
fn decode(bytes: &[u8], key: &Key) -> std::result::Result<Mesh, String> {
    const HEAD: usize = 8 + 32 + 16;
    if bytes.len() < HEAD + 32 || &bytes[..8] != MAGIC {
        return Err("is not a cache entry of this version".into());
    }
    let (body, sum) = bytes.split_at(bytes.len() - 32);
    if blake3::hash(body).as_bytes() != sum {
        return Err("is damaged (its checksum does not match)".into());
    }
    if body[8..40] != key.0 {
        return Err("holds another key".into());
    }
    let word = |at: usize| u64::from_le_bytes(body[at..at + 8].try_into().expect("8 bytes"));
    let (nv, nt) = (word(40), word(48));
    let expected = nv
        .checked_mul(24)
        .zip(nt.checked_mul(12))
        .and_then(|(a, b)| a.checked_add(b))
        .and_then(|n| n.checked_add(HEAD as u64));
    if expected != Some(body.len() as u64) {
        return Err("has the wrong length".into());
    }
    let (nv, nt) = (nv as usize, nt as usize);
    let f = |at: usize| f64::from_le_bytes(body[at..at + 8].try_into().expect("8 bytes"));
    let u = |at: usize| u32::from_le_bytes(body[at..at + 4].try_into().expect("4 bytes"));
    let positions = (0..nv)
        .map(|i| std::array::from_fn(|k| f(HEAD + 24 * i + 8 * k)))
        .collect();
    let first = HEAD + 24 * nv;
    let triangles = (0..nt)
        .map(|i| std::array::from_fn(|k| u(first + 12 * i + 4 * k)))
        .collect();
    Mesh::new(positions, triangles).map_err(|e| format!("is not a valid mesh: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entries_round_trip_and_damage_is_seen() {
        let mesh = Mesh::unit_cube();
        let key = Key([7; 32]);
        let bytes = encode(&key, &mesh);
        assert_eq!(decode(&bytes, &key).unwrap(), mesh);
        assert!(decode(&bytes, &Key([8; 32]))
            .unwrap_err()
            .contains("another key"));
        assert!(decode(&bytes[..bytes.len() - 1], &key).is_err());
        let mut flipped = bytes.clone();
        flipped[70] ^= 1;
        assert!(decode(&flipped, &key).unwrap_err().contains("checksum"));
        assert!(decode(b"nonsense", &key).is_err());
    }
}
