//! Boolean union of the sphere pairs in `common`, in memory: intersection, arrangement,
//! classification, selection, merge. Run: `cargo bench -p meshbool --bench boolean`.

mod common;

use common::{P200K, P2M};
use meshbool::boolean::{boolean, Op};

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
