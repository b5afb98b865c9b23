//! Boolean union of two UV spheres (the second rotated 0.1 rad about z and shifted 0.5
//! along x), in memory: intersection, arrangement, classification, selection, merge.
//! Run: `cargo bench -p meshbool --bench boolean`.

use std::sync::LazyLock;

use meshbool::boolean::{boolean, Op};
use meshbool::shapes::{rigid_motion, uv_sphere};
use meshbool::Mesh;

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
fn union_200k_spheres() -> usize {
    let (a, b) = &*P200K;
    boolean(a, b, Op::Union).mesh.triangles.len()
}

#[divan::bench(sample_count = 5)]
fn union_2m_spheres() -> usize {
    let (a, b) = &*P2M;
    boolean(a, b, Op::Union).mesh.triangles.len()
}
