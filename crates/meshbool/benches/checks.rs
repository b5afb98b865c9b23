//! The input checks' inside-out test (`repair::inside_out`) on meshes of many closed
//! parts, half of them inside out: its cost per inward part. Run:
//! `cargo bench -p meshbool --bench checks`.

use std::sync::LazyLock;

use meshbool::shapes::uv_sphere;
use meshbool::Mesh;

fn main() {
    divan::main();
}

/// `k` UV spheres of 224 triangles on a grid, every other one inside out.
fn spheres(k: usize) -> Mesh {
    let mut m = Mesh::default();
    for i in 0..k {
        let c = [3.0 * (i % 50) as f64, 3.0 * (i / 50) as f64, 0.0];
        let s = uv_sphere(c, 1.0, 16, 8);
        m.append(&if i % 2 == 0 { s.flipped() } else { s })
            .expect("parts append");
    }
    m
}

static S200: LazyLock<Mesh> = LazyLock::new(|| spheres(200));
static S2000: LazyLock<Mesh> = LazyLock::new(|| spheres(2000));

/// 100 inside-out parts among 200 (44,800 triangles).
#[divan::bench(sample_count = 10)]
fn inside_out_200_parts() -> usize {
    meshbool::repair::inside_out(&S200).1
}

/// 1,000 inside-out parts among 2,000 (448,000 triangles).
#[divan::bench(sample_count = 10)]
fn inside_out_2000_parts() -> usize {
    meshbool::repair::inside_out(&S2000).1
}
