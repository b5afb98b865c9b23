//! Inputs shared by the benches: pairs of UV spheres of radius 1, the second rotated
//! 0.1 rad about z and shifted 0.5 along x (so the tessellations do not line up).

use std::sync::LazyLock;

use meshbool::shapes::{rigid_motion, uv_sphere};
use meshbool::Mesh;

/// A sphere pair with 2 · segments · (rings − 1) triangles per sphere.
fn pair(segments: u32, rings: u32) -> (Mesh, Mesh) {
    let a = uv_sphere([0.0; 3], 1.0, segments, rings);
    let b = rigid_motion(&a, [0.0, 0.0, 1.0], 0.1, [0.5, 0.0, 0.0]);
    (a, b)
}

/// 200,340 triangles per sphere.
pub static P200K: LazyLock<(Mesh, Mesh)> = LazyLock::new(|| pair(632, 159));
/// 2,000,000 triangles per sphere.
pub static P2M: LazyLock<(Mesh, Mesh)> = LazyLock::new(|| pair(2000, 501));
