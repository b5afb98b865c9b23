//! What the tests share: the cube-and-cutter of snapping and the exact clean-up, a cube
//! whose shared corners differ by rounding, and the way to other projects' data.

use meshbool::boolean::Provenance;
use meshbool::{Mesh, Source};

/// The unit cube, and a box cutting off the part x > 0.5, z > 0.5 whose other walls lie
/// 1e-3 outside the cube's faces (a cutter drawn "a little larger"): its faces' diagonals
/// cross the cube's faces a millimetre from the cube's edges, 5e-4 from the cut's corners.
pub fn cube_and_cutter() -> (Mesh, Mesh) {
    (
        Mesh::unit_cube(),
        Mesh::cuboid([0.5, -0.001, 0.5], [1.001, 1.001, 1.001]),
    )
}

/// Asserts that every triangle of `mesh` lies in the face (an axis plane) of the input
/// triangle its provenance names, in `a` or `b` (axis-aligned boxes).
pub fn assert_in_parent_faces(
    mesh: &Mesh,
    provenance: &[Provenance],
    a: &Mesh,
    b: &Mesh,
    what: &str,
) {
    for (t, p) in mesh.triangles().iter().zip(provenance) {
        let source = if p.source == Source::A { a } else { b };
        let face = source.triangles()[p.triangle as usize].map(|v| source.positions()[v as usize]);
        let axis = (0..3)
            .find(|&k| face[0][k] == face[1][k] && face[1][k] == face[2][k])
            .unwrap();
        for v in t {
            assert_eq!(mesh.positions()[*v as usize][axis], face[0][axis], "{what}");
        }
    }
}

/// `a` and `b` moved together by a rotation about a skew axis and a translation, different
/// for every `seed` (faces no longer exactly axis-aligned: their corners are rounded).
pub fn skew_motion(seed: u64, a: &Mesh, b: &Mesh) -> (Mesh, Mesh) {
    use meshbool::shapes::rigid_motion;
    let f = |k: u64| ((seed * 7919 + k * 104_729) % 1000) as f64 / 1000.0;
    let axis = [f(1) - 0.5, f(2) - 0.5, f(3) + 0.1];
    let (angle, shift) = (6.0 * f(4), [10.0 * f(5), -3.0 * f(6), 100.0 * f(7)]);
    (
        rigid_motion(a, axis, angle, shift),
        rigid_motion(b, axis, angle, shift),
    )
}

/// The unit cube as a soup whose odd triangles' corners are one unit in the last place
/// off (each coordinate raised to the next `f64`): shared corners that differ in the last
/// bits, as floating-point exports write them. Exactly welded it is open along every
/// edge between an odd and an even triangle.
// Used by the door and report tests, not by the others that include this module.
#[allow(dead_code)]
pub fn cube_off_by_an_ulp() -> Mesh {
    let cube = Mesh::unit_cube();
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for (t, tri) in cube.triangles().iter().enumerate() {
        let base = positions.len() as u32;
        for &v in tri {
            let p = cube.positions()[v as usize];
            positions.push(if t % 2 == 1 { p.map(f64::next_up) } else { p });
        }
        triangles.push([base, base + 1, base + 2]);
    }
    Mesh::new(positions, triangles).unwrap()
}

/// An open unit square (two triangles) with a fin along its diagonal: the edge
/// (0.5, 0.5, 0) is used by three triangles.
#[allow(dead_code)]
pub fn finned_sheet() -> Mesh {
    Mesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.5, 1.0],
        ],
        vec![[0, 1, 2], [0, 2, 3], [0, 2, 4]],
    )
    .unwrap()
}

/// A file of other projects' data in `../shared/data` beside the checkout (the Kirra
/// surfaces of the reference JS library, kept out of the repository), or `None`, saying
/// the test is skipped, where that folder is absent.
#[allow(dead_code)]
pub fn shared_data(name: &str) -> Option<std::path::PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data");
    if dir.is_dir() {
        Some(dir.join(name))
    } else {
        eprintln!("skipped: ../shared/data not found");
        None
    }
}
