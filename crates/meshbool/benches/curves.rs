//! Intersection curves of the sphere pairs in `common` (broad phase, exact tests, seam
//! assembly, chaining) and the self-intersection input check (on the 2M sphere and on real
//! models). Run: `cargo bench -p meshbool --bench curves`.

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

/// Candidate pairs of the 2M spheres from the grid broad phase (what `intersect` uses for
/// inputs this large).
#[divan::bench(sample_count = 10)]
fn broad_phase_2m_spheres_grid() -> usize {
    let (a, b) = &*P2M;
    meshbool::broad::overlapping_pairs(a, b).len()
}

/// The same pairs from two trees, each over the triangles meeting the other mesh's box
/// (what `intersect` uses for small inputs).
#[divan::bench(sample_count = 10)]
fn broad_phase_2m_spheres_trees() -> usize {
    use meshbool::bvh::Bvh;
    let (a, b) = &*P2M;
    let (box_a, box_b) = (a.bounds().unwrap(), b.bounds().unwrap());
    let (ta, tb) = rayon::join(|| Bvh::new_within(a, &box_b), || Bvh::new_within(b, &box_a));
    ta.overlapping_pairs(a, &tb, b).len()
}

/// The input check on real models beside the repository (`../shared/data`): CAD parts of
/// long slivers side by side (thingi 73416, 908460; 79741's around slanted cylinders),
/// CAD parts of flat faces
/// (a multi-body part, a sensor housing, seven gears, a wing), and two scans.
/// A model that is not there is timed as nothing.
#[divan::bench(sample_count = 7, args = [
    "real/thingi_79741.obj",
    "real/thingi_73416.obj",
    "real/thingi_908460.obj",
    "corpus/cad_abc5_multibody.stl",
    "corpus/cad_gears.stl",
    "corpus/print_wing.stl",
    "corpus/cad_adis16480.stl",
    "corpus/scan_hammer.obj",
    "corpus/scan_armadillo.obj",
])]
fn self_intersections_real(bencher: divan::Bencher, file: &str) {
    let path = format!("{}/../../../shared/data/{file}", env!("CARGO_MANIFEST_DIR"));
    let mesh = std::fs::read(&path).ok().and_then(|bytes| {
        let format = meshbool::io::detect_format(&bytes, None)?;
        meshbool::io::read_bytes(&bytes, format).ok()
    });
    bencher.bench(|| {
        mesh.as_ref()
            .map_or(0, |m| meshbool::intersect::self_intersections(m).len())
    });
}
