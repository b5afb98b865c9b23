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

/// A mesh of other projects' data in `../shared/data` beside the checkout (the Kirra
/// surfaces of the reference JS library, kept out of the repository), or `None`, saying
/// the test is skipped, where that folder is absent.
pub(crate) fn shared_data(name: &str) -> Option<crate::Mesh> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data");
    if !dir.is_dir() {
        eprintln!("skipped: ../shared/data not found");
        return None;
    }
    Some(crate::io::read_path(dir.join(name)).expect("a shared data file reads"))
}

/// A centre at UTM-like coordinates (metres east and north, elevation).
pub(crate) const UTM: [f64; 3] = [478_600.0, 6_772_300.0, 400.0];

/// A generated survey and a drill hole through it, about `center`: a
/// [`crate::shapes::terrain`] of 600 m × 600 m in 60 × 60 cells (7200 triangles, 240
/// boundary edges, heights `center.z ± 20`), and a [`crate::shapes::cylinder`] of radius
/// 35 (30 sides, 120 triangles) from 60 below to 60 above it, 20 m east and 10 m south
/// of the centre: they cross in one closed loop.
pub(crate) fn terrain_and_drill(center: [f64; 3]) -> (crate::Mesh, crate::Mesh) {
    let [x, y, z] = center;
    let terrain = crate::shapes::terrain(center, [600.0; 2], [60; 2], 40.0, 1).unwrap();
    let drill = crate::shapes::cylinder([x + 20.0, y - 10.0, z - 60.0], 35.0, 120.0, 30);
    (terrain, drill.unwrap())
}

/// An open bowl crossing [`terrain_and_drill`]'s terrain: a [`crate::shapes::pit`] of
/// radius 60 and two benches (112 triangles), its rim 30 above `center.z` (above the
/// ground) and its floor 40 below (under it), 100 m west and 80 m north of the centre.
pub(crate) fn bowl(center: [f64; 3]) -> crate::Mesh {
    let [x, y, z] = center;
    crate::shapes::pit([x - 100.0, y + 80.0, z + 30.0], [60.0; 2], 70.0, 2, 5.0, 16).unwrap()
}

/// [`terrain_and_drill`]'s terrain badly wound, as surveys often are: five triangles far
/// from the drill and from one another reversed (15 inconsistently oriented edges).
pub(crate) fn wound_badly(terrain: &crate::Mesh) -> crate::Mesh {
    let mut m = terrain.clone();
    for (i, j) in [(5, 5), (5, 50), (50, 5), (50, 50), (10, 30)] {
        m.triangles[2 * (j * 60 + i)].swap(1, 2);
    }
    m
}

/// `f` run in a pool of its own with `threads` threads (what a result must not depend on).
pub(crate) fn on_threads<R: Send>(threads: usize, f: impl FnOnce() -> R + Send) -> R {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool")
        .install(f)
}

/// A prism of height `h` over the polygon `ring` (counter-clockwise in xy) with
/// both caps fanned from the ring's first vertex: long thin triangles that span the cap,
/// as CAD exports triangulate extruded profiles.
pub(crate) fn fanned_prism(ring: &[[f64; 2]], h: f64) -> crate::Mesh {
    let n = ring.len() as u32;
    let positions = [0.0, h]
        .iter()
        .flat_map(|&z| ring.iter().map(move |p| [p[0], p[1], z]))
        .collect();
    let mut triangles = Vec::new();
    for i in 0..n {
        let j = (i + 1) % n;
        triangles.extend([[i, j, n + j], [i, n + j, n + i]]);
    }
    for i in 1..n - 1 {
        triangles.extend([[0, i + 1, i], [n, n + i, n + i + 1]]);
    }
    crate::Mesh::new(positions, triangles).unwrap()
}
