//! Boolean union of the sphere pairs in `common` and of two crossing terrains, in memory:
//! intersection, arrangement, classification, selection, merge.
//! Run: `cargo bench -p meshbool --bench boolean`.

mod common;

use common::{P200K, P2M};
use meshbool::boolean::{boolean, Op};

fn main() {
    divan::main();
}

#[divan::bench(sample_count = 10)]
fn union_200k_spheres() -> usize {
    let (a, b) = &*P200K;
    boolean(a, b, Op::Union, &Default::default())
        .mesh
        .triangle_count()
}

#[divan::bench(sample_count = 5)]
fn union_2m_spheres() -> usize {
    let (a, b) = &*P2M;
    boolean(a, b, Op::Union, &Default::default())
        .mesh
        .triangle_count()
}

/// Two crossing open terrains (80k and 34k triangles): the seam stops inside both, so
/// both are classified triangle by triangle by winding number (the open-surface case of
/// the peer benchmark's terrain × terrain).
static TERRAINS: std::sync::LazyLock<(meshbool::Mesh, meshbool::Mesh)> =
    std::sync::LazyLock::new(|| {
        use meshbool::shapes::{heightfield, rigid_motion};
        let a = heightfield([0.0, 0.0], [10.0, 10.0], 200, 200, |x, y| {
            0.3 * (0.7 * x).sin() * (0.5 * y).cos()
        });
        let b = heightfield([-2.0, -2.0], [12.0, 6.0], 140, 120, |x, y| {
            0.15 * (x - 5.0) + 0.1 * y.sin()
        });
        (a, rigid_motion(&b, [0.0, 0.0, 1.0], 0.3, [0.5, 0.2, 0.0]))
    });

#[divan::bench(sample_count = 10)]
fn union_crossing_terrains() -> usize {
    let (a, b) = &*TERRAINS;
    boolean(a, b, Op::Union, &Default::default())
        .mesh
        .triangle_count()
}
