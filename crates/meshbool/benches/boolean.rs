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

/// The same union without the exact clean-up (`PipelineOptions::cleanup` off): the
/// clean-up's cost is the difference to `union_2m_spheres`.
#[divan::bench(sample_count = 5)]
fn union_2m_spheres_raw() -> usize {
    let (a, b) = &*P2M;
    let raw = meshbool::boolean::PipelineOptions {
        cleanup: false,
        ..Default::default()
    };
    boolean(a, b, Op::Union, &raw).mesh.triangle_count()
}

/// The same union snapped at 1e-4 (about a hundredth of the spheres' triangle size), as
/// the front door does with `snap: 1e-4`: the cost of snapping over the boolean.
#[divan::bench(sample_count = 10)]
fn union_200k_spheres_snap() -> usize {
    let (a, b) = &*P200K;
    let mut r = boolean(a, b, Op::Union, &Default::default());
    meshbool::boolean::snap_result(&mut r, 1e-4).expect("a valid tolerance");
    r.mesh.triangle_count()
}

#[divan::bench(sample_count = 10)]
fn union_2m_spheres() -> usize {
    let (a, b) = &*P2M;
    boolean(a, b, Op::Union, &Default::default())
        .mesh
        .triangle_count()
}

/// The same union snapped at 1e-4 (a thirtieth of the spheres' triangle size): the cost
/// of snapping on a large result (issue 21's target: under 15 % over the union).
#[divan::bench(sample_count = 10)]
fn union_2m_spheres_snap() -> usize {
    let (a, b) = &*P2M;
    let mut r = boolean(a, b, Op::Union, &Default::default());
    meshbool::boolean::snap_result(&mut r, 1e-4).expect("a valid tolerance");
    r.mesh.triangle_count()
}

/// Snapping alone, on the 2M-sphere union's result (made once; each sample snaps a copy):
/// the cost the two benches above differ by, without their noise.
#[divan::bench(sample_count = 10)]
fn snap_2m_union_result(bencher: divan::Bencher) {
    let (a, b) = &*P2M;
    let r = boolean(a, b, Op::Union, &Default::default());
    // The snapped result is returned, so that it is dropped outside the timing.
    bencher.with_inputs(|| r.clone()).bench_values(|mut r| {
        let report = meshbool::boolean::snap_result(&mut r, 1e-4).expect("a valid tolerance");
        (r, report)
    });
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

/// A flat 200 × 200 grid and one of bumps that touches it only at 10,201 isolated
/// vertices (80k triangles each): a seam of touching points and no segment.
static TOUCHING: std::sync::LazyLock<(meshbool::Mesh, meshbool::Mesh)> =
    std::sync::LazyLock::new(|| {
        use meshbool::shapes::heightfield;
        let flat = heightfield([0.0, 0.0], [200.0, 200.0], 200, 200, |_, _| 0.0);
        let bumps = heightfield([0.0, 0.0], [200.0, 200.0], 200, 200, |x, y| {
            if x % 2.0 == 0.0 && y % 2.0 == 0.0 {
                0.0
            } else {
                1.0
            }
        });
        (flat, bumps)
    });

#[divan::bench(sample_count = 10)]
fn union_grids_touching_at_points() -> usize {
    let (a, b) = &*TOUCHING;
    boolean(a, b, Op::Union, &Default::default())
        .mesh
        .triangle_count()
}

/// Ten overlapping 20k-triangle spheres (a ring of centres, each crossing its neighbours
/// and the middle one).
static TEN: std::sync::LazyLock<Vec<meshbool::Mesh>> = std::sync::LazyLock::new(|| {
    use meshbool::shapes::uv_sphere;
    (0..10)
        .map(|k| {
            let a = k as f64 * std::f64::consts::TAU / 9.0;
            let c = if k == 9 {
                [0.0; 3]
            } else {
                [1.6 * a.cos(), 1.6 * a.sin(), 0.1 * k as f64]
            };
            uv_sphere(c, 1.0, 142, 71)
        })
        .collect()
});

/// Ten 20k-triangle spheres that all overlap one another (centres within 0.3 of the
/// axis, a spiral): most of each sphere's crossings lie inside the union.
static TEN_DENSE: std::sync::LazyLock<Vec<meshbool::Mesh>> = std::sync::LazyLock::new(|| {
    use meshbool::shapes::uv_sphere;
    (0..10)
        .map(|k| {
            let a = k as f64 * 2.4;
            uv_sphere(
                [0.3 * a.cos(), 0.3 * a.sin(), 0.05 * k as f64],
                1.0,
                142,
                71,
            )
        })
        .collect()
});

/// Meshes as parts of an n-ary boolean.
fn parts_of(meshes: &[meshbool::Mesh]) -> Vec<meshbool::boolean::nary::Part> {
    meshes
        .iter()
        .enumerate()
        .map(|(k, m)| meshbool::boolean::nary::Part {
            mesh: m.clone(),
            parent: vec![k as u32; m.triangle_count()],
        })
        .collect()
}

/// The dense ten united in one arrangement.
#[divan::bench(sample_count = 10)]
fn union_10_dense_spheres_one() -> usize {
    let parts = parts_of(&TEN_DENSE);
    let r = meshbool::boolean::nary::reduce_in_one(&parts, Op::Union, &Default::default());
    r.expect("one arrangement").part.mesh.triangle_count()
}

/// The dense ten united pairwise in a balanced tree.
#[divan::bench(sample_count = 10)]
fn union_10_dense_spheres_tree() -> usize {
    meshbool::boolean::nary::reduce(parts_of(&TEN_DENSE), Op::Union, &Default::default())
        .part
        .mesh
        .triangle_count()
}

/// The ten spheres as parts of an n-ary boolean.
fn ten_parts() -> Vec<meshbool::boolean::nary::Part> {
    parts_of(&TEN)
}

/// Union of the ten spheres in one call: one arrangement of all of them.
#[divan::bench(sample_count = 10)]
fn union_10_spheres_one() -> usize {
    let parts = ten_parts();
    let r = meshbool::boolean::nary::reduce_in_one(&parts, Op::Union, &Default::default());
    r.expect("one arrangement").part.mesh.triangle_count()
}

/// Union of the ten spheres in one call: pairwise in a balanced tree, a round in parallel.
#[divan::bench(sample_count = 10)]
fn union_10_spheres_tree() -> usize {
    meshbool::boolean::nary::reduce(ten_parts(), Op::Union, &Default::default())
        .part
        .mesh
        .triangle_count()
}

/// The same union as a chain of nine pairwise unions.
#[divan::bench(sample_count = 10)]
fn union_10_spheres_chain() -> usize {
    let mut acc = TEN[0].clone();
    for m in &TEN[1..] {
        acc = boolean(&acc, m, Op::Union, &Default::default()).mesh;
    }
    acc.triangle_count()
}

/// A real model pair from `../shared/data/real/` (read once, welded), or `None` with a
/// message when the shared data is not there.
fn real_pair(a: &str, b: &str) -> Option<(meshbool::Mesh, meshbool::Mesh)> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/data/real");
    let read = |f: &str| {
        let m = meshbool::io::read_path(format!("{dir}/{f}")).ok()?;
        Some(meshbool::weld_exact(&m).mesh)
    };
    let pair = read(a).zip(read(b));
    if pair.is_none() {
        eprintln!("skipped: {dir}/{a} and {b} not found (shared data)");
    }
    pair
}

static THINGI_79741_65004: std::sync::LazyLock<Option<(meshbool::Mesh, meshbool::Mesh)>> =
    std::sync::LazyLock::new(|| real_pair("thingi_79741.obj", "thingi_65004.obj"));
static THINGI_908460_73416: std::sync::LazyLock<Option<(meshbool::Mesh, meshbool::Mesh)>> =
    std::sync::LazyLock::new(|| real_pair("thingi_908460.obj", "thingi_73416.obj"));

/// 79741 − 65004: huge triangles of B each crossed by thousands of A's seam points (the
/// exact fallback storm of issue 16).
#[divan::bench(sample_count = 5)]
fn difference_thingi_79741_65004() -> usize {
    THINGI_79741_65004.as_ref().map_or(0, |(a, b)| {
        boolean(a, b, Op::Difference, &Default::default())
            .mesh
            .triangle_count()
    })
}

/// 908460 − 73416: dense overlap.
#[divan::bench(sample_count = 5)]
fn difference_thingi_908460_73416() -> usize {
    THINGI_908460_73416.as_ref().map_or(0, |(a, b)| {
        boolean(a, b, Op::Difference, &Default::default())
            .mesh
            .triangle_count()
    })
}

/// The fallback storm without the shared files: a fine sphere (about 200k triangles)
/// minus a box turned a little, whose faces (two triangles each) cut the sphere: each of
/// the box's large triangles carries a seam loop of thousands of points, and the sphere's
/// triangles along it are slivers crossing the box's faces at a grazing angle.
#[divan::bench(sample_count = 5)]
fn difference_sphere_minus_large_triangles() -> usize {
    static PAIR: std::sync::LazyLock<(meshbool::Mesh, meshbool::Mesh)> =
        std::sync::LazyLock::new(|| {
            use meshbool::shapes::{cuboid, rigid_motion, uv_sphere};
            let sphere = uv_sphere([0.0; 3], 1.0, 500, 200);
            let b = cuboid([-0.6, -0.7, -0.8], [2.0, 2.0, 2.0]).expect("a box");
            (sphere, rigid_motion(&b, [1.0, 0.3, 0.1], 0.02, [0.0; 3]))
        });
    let (a, b) = &*PAIR;
    boolean(a, b, Op::Difference, &Default::default())
        .mesh
        .triangle_count()
}
