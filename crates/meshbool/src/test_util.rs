//! Helpers shared by the unit tests.

/// A small deterministic generator (xorshift64): the same seed gives the same cases.
pub(crate) struct Rng(pub(crate) u64);

impl Rng {
    pub(crate) fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// Uniform in [0, 1).
    pub(crate) fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Reads a mesh shipped in the repository's `data/` folder.
pub(crate) fn data(name: &str) -> crate::Mesh {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data");
    crate::io::read_path(dir.join(name)).expect("data file reads")
}

/// `f` run in a pool of its own with `threads` threads (what a result must not depend on).
pub(crate) fn on_threads<R: Send>(threads: usize, f: impl FnOnce() -> R + Send) -> R {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool")
        .install(f)
}
