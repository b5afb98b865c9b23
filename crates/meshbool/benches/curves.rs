//! Intersection curves of two UV spheres (radius 1, the second shifted by 0.5 along x and
//! rotated slightly so that the tessellations do not line up).
//! Run: `cargo bench -p meshbool --bench curves`.

use std::sync::LazyLock;

use meshbool::intersect::{chain, intersect};
use meshbool::shapes::{rigid_motion, uv_sphere};
use meshbool::Mesh;

/// Sphere pairs by triangle count per sphere: 2 · segments · (rings − 1).
fn pair(segments: u32, rings: u32) -> (Mesh, Mesh) {
    let a = uv_sphere([0.0; 3], 1.0, segments, rings);
    let b = rigid_motion(&a, [0.0, 0.0, 1.0], 0.1, [0.5, 0.0, 0.0]);
    (a, b)
}

static P200K: LazyLock<(Mesh, Mesh)> = LazyLock::new(|| pair(632, 159));
static P2M: LazyLock<(Mesh, Mesh)> = LazyLock::new(|| pair(2000, 501));

fn main() {
    divan::main();
}

#[divan::bench(sample_count = 10)]
fn curves_200k_spheres() -> usize {
    let (a, b) = &*P200K;
    chain(&intersect(a, b), true).len()
}

#[divan::bench(sample_count = 10)]
fn curves_2m_spheres() -> usize {
    let (a, b) = &*P2M;
    chain(&intersect(a, b), true).len()
}
