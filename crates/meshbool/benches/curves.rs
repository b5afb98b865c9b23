//! Intersection curves of the sphere pairs in `common` (broad phase, exact tests, seam
//! assembly, chaining) and the self-intersection input check. Run: `cargo bench -p meshbool --bench curves`.

mod common;

use common::{P200K, P2M};
use meshbool::intersect::{chain, intersect};

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

/// The input check run before a boolean: exact self-intersections of one 2M sphere.
#[divan::bench(sample_count = 5)]
fn self_intersections_2m_sphere() -> usize {
    let (a, _) = &*P2M;
    meshbool::intersect::self_intersections(a).len()
}
