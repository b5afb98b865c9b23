//! Booleans of small inputs, where fixed costs and the exact kernel's slow paths (points
//! exactly on planes and edges) weigh most: the cube pairs of `../shared/bench/
//! gen_meshes.py` (faces split into g × g quads; the second cube shifted by half its size
//! along x, so that four face pairs are coplanar, or the same cube), its 5k sphere pair,
//! and its terrain pierced by a cylinder (a large mesh, a short seam).
//! Run: `cargo bench -p meshbool --bench small`.

use std::sync::LazyLock;

use meshbool::boolean::{boolean, Op};
use meshbool::shapes::{cylinder, heightfield, rigid_motion, uv_sphere};
use meshbool::Mesh;

fn main() {
    divan::main();
}

/// The box `[lo, hi]` with each face split into `g × g` quads of two triangles, welded,
/// facing out (`gen_meshes.py`'s `grid_cube`).
fn grid_cube(lo: [f64; 3], hi: [f64; 3], g: u32) -> Mesh {
    let mut ids = std::collections::HashMap::new();
    let mut positions = Vec::new();
    let mut vertex = |ijk: [u32; 3]| -> u32 {
        *ids.entry(ijk).or_insert_with(|| {
            positions.push(std::array::from_fn(|k| {
                lo[k] + (hi[k] - lo[k]) * f64::from(ijk[k]) / f64::from(g)
            }));
            (positions.len() - 1) as u32
        })
    };
    let mut triangles = Vec::new();
    for ax in 0..3 {
        let (u, v) = ((ax + 1) % 3, (ax + 2) % 3);
        for s in [0, g] {
            for a in 0..g {
                for b in 0..g {
                    let q = [(0, 0), (1, 0), (1, 1), (0, 1)].map(|(da, db)| {
                        let mut ijk = [0; 3];
                        (ijk[ax], ijk[u], ijk[v]) = (s, a + da, b + db);
                        vertex(ijk)
                    });
                    if s == g {
                        triangles.extend([[q[0], q[1], q[2]], [q[0], q[2], q[3]]]);
                    } else {
                        triangles.extend([[q[0], q[2], q[1]], [q[0], q[3], q[2]]]);
                    }
                }
            }
        }
    }
    Mesh::new(positions, triangles).expect("a valid grid cube")
}

/// The coplanar pair with `g × g` quads per face.
fn coplanar(g: u32) -> (Mesh, Mesh) {
    (
        grid_cube([0.0; 3], [1.0; 3], g),
        grid_cube([0.5, 0.0, 0.0], [1.5, 1.0, 1.0], g),
    )
}

static SINGLE: LazyLock<(Mesh, Mesh)> = LazyLock::new(|| coplanar(1));
static GRID16: LazyLock<(Mesh, Mesh)> = LazyLock::new(|| coplanar(16));
/// 5,040 triangles per sphere, the second rotated 0.7 rad about (1, 2, 3) and shifted by
/// 0.3 of the radius along that axis.
static SPHERES_5K: LazyLock<(Mesh, Mesh)> = LazyLock::new(|| {
    let a = uv_sphere([0.0; 3], 1.0, 72, 36);
    let axis = [1.0, 2.0, 3.0];
    let len = 14f64.sqrt();
    let b = rigid_motion(&a, axis, 0.7, axis.map(|x| 0.3 * x / len));
    (a, b)
});

/// `gen_meshes.py`'s `terrain_cylinder`: an open 200 × 200 height field over 10 × 10
/// (80,000 triangles) and a closed 64-segment cylinder of radius 1 standing through it.
static TERRAIN_CYLINDER: LazyLock<(Mesh, Mesh)> = LazyLock::new(|| {
    let terrain = heightfield([0.0; 2], [10.0; 2], 200, 200, |x, y| {
        0.6 * (0.9 * x).sin() * (0.7 * y).cos() + 0.25 * (2.3 * x + 1.1 * y + 0.4).sin()
    });
    let cylinder = cylinder([5.0, 5.0, -3.0], 1.0, 7.0, 64).expect("a valid cylinder");
    (terrain, cylinder)
});

#[divan::bench(sample_count = 200)]
fn union_coplanar_cubes_g1() -> usize {
    let (a, b) = &*SINGLE;
    boolean(a, b, Op::Union, &Default::default())
        .mesh
        .triangle_count()
}

#[divan::bench(sample_count = 50)]
fn union_coplanar_cubes_g16() -> usize {
    let (a, b) = &*GRID16;
    boolean(a, b, Op::Union, &Default::default())
        .mesh
        .triangle_count()
}

#[divan::bench(sample_count = 50)]
fn union_identical_cubes_g16() -> usize {
    let a = &GRID16.0;
    boolean(a, a, Op::Union, &Default::default())
        .mesh
        .triangle_count()
}

#[divan::bench(sample_count = 50)]
fn union_spheres_5k() -> usize {
    let (a, b) = &*SPHERES_5K;
    boolean(a, b, Op::Union, &Default::default())
        .mesh
        .triangle_count()
}

#[divan::bench(sample_count = 50)]
fn union_terrain_cylinder() -> usize {
    let (a, b) = &*TERRAIN_CYLINDER;
    boolean(a, b, Op::Union, &Default::default())
        .mesh
        .triangle_count()
}
