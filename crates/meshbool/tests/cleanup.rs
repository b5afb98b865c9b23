//! The exact clean-up of booleans' results (on by default; `keep_seam_points` turns it
//! off): seam points where the result is flat or straight go, zero-area triangles made
//! by rounding go, and the surface does not move — same volume, every vertex left at a
//! position the arrangement gave, every triangle in its parent's plane.

use meshbool::intersect::self_intersections;
use meshbool::measure::{degenerate_triangles, mesh_stats, signed_volume};
use meshbool::ops::{self, BooleanOptions, BooleanOutput};
use meshbool::shapes::rigid_motion;
use meshbool::{Mesh, Op};

mod common;
use common::{assert_in_parent_faces, cube_and_cutter};

fn boolean(a: &Mesh, b: &Mesh, op: Op, keep_seam_points: bool) -> BooleanOutput {
    let opts = BooleanOptions {
        keep_seam_points,
        ..BooleanOptions::default()
    };
    ops::boolean(a, b, op, &opts).unwrap()
}

/// What the clean-up must keep of the result `raw` it starts from: closed (and manifold)
/// where it was, the same open and non-manifold edges at most, every vertex at one of
/// `raw`'s positions (nothing moved), the same volume, no zero-area triangle but those
/// counted, no self-intersection where `raw` had none, fewer or as many triangles, the
/// counts in the report right, provenance for every triangle.
fn check(raw: &BooleanOutput, clean: &BooleanOutput, what: &str) {
    let (r, c) = (mesh_stats(&raw.mesh), mesh_stats(&clean.mesh));
    assert!(c.closed || !r.closed, "{what}");
    assert!(c.boundary_edges <= r.boundary_edges, "{what}");
    assert!(c.non_manifold_edges <= r.non_manifold_edges, "{what}");
    assert_eq!(c.inconsistent_edges, 0, "{what}");
    let mut at: Vec<[u64; 3]> = raw
        .mesh
        .positions()
        .iter()
        .map(|p| p.map(f64::to_bits))
        .collect();
    at.sort_unstable();
    for p in clean.mesh.positions() {
        assert!(
            at.binary_search(&p.map(f64::to_bits)).is_ok(),
            "{what}: moved"
        );
    }
    let (v0, v1) = (signed_volume(&raw.mesh), signed_volume(&clean.mesh));
    assert!(
        (v1 - v0).abs() <= 1e-12 * v0.abs().max(1.0),
        "{what}: {v0} {v1}"
    );
    let s = clean.cleanup;
    assert_eq!(
        degenerate_triangles(&clean.mesh),
        s.zero_area_left,
        "{what}"
    );
    assert_eq!(s.zero_area_left, 0, "{what}");
    if self_intersections(&raw.mesh).is_empty() {
        assert!(self_intersections(&clean.mesh).is_empty(), "{what}");
    }
    assert_eq!(
        raw.mesh.triangle_count() - clean.mesh.triangle_count(),
        s.triangles_removed,
        "{what}"
    );
    assert_eq!(
        raw.mesh.vertex_count() - clean.mesh.vertex_count(),
        s.removed_points + s.zero_length_edges,
        "{what}"
    );
    // Each collapse takes two triangles, a flip none.
    assert_eq!(
        s.triangles_removed,
        2 * (s.removed_points + s.zero_length_edges),
        "{what}"
    );
    assert_eq!(clean.provenance.len(), clean.mesh.triangle_count());
    assert_eq!(raw.cleanup, Default::default(), "{what}");
}

/// Axis-aligned: every removable seam point goes and the results are the coarsest
/// meshes of their shapes (an L-shaped prism: 2 × 4 + 6 × 2 triangles; a box: 12), at
/// exactly the volumes, each triangle in the face of the input triangle it names.
#[test]
fn straight_seam_points_go_and_the_shape_stays() {
    let (a, b) = cube_and_cutter();
    for (op, triangles, volume) in [
        (Op::Difference, 20, 0.75),
        (Op::Intersection, 12, 0.25),
        (Op::Union, 0, 0.0),
        (Op::ReverseDifference, 0, 0.0),
    ] {
        let raw = boolean(&a, &b, op, true);
        let clean = boolean(&a, &b, op, false);
        check(&raw, &clean, &op.to_string());
        assert!(clean.cleanup.removed_points > 0, "{op}");
        if triangles > 0 {
            assert_eq!(clean.mesh.triangle_count(), triangles, "{op}");
            assert_eq!(signed_volume(&clean.mesh), volume, "{op}");
            assert!(raw.mesh.triangle_count() > triangles, "{op}");
        }
        assert_in_parent_faces(&clean.mesh, &clean.provenance, &a, &b, &op.to_string());
    }
}

/// Turned about skew axes, the cube's faces are no longer exactly flat (their corners were
/// rounded): the clean-up only removes what stays exactly flat or straight, and where two
/// seam points round to one position (seed 2) the zero-area triangles between them go.
#[test]
fn rigid_motions_keep_every_guarantee() {
    let (a0, b0) = cube_and_cutter();
    let mut zero_length = 0;
    for seed in 0..6u64 {
        let f = |k: u64| ((seed * 7919 + k * 104_729) % 1000) as f64 / 1000.0;
        let axis = [f(1) - 0.5, f(2) - 0.5, f(3) + 0.1];
        let (angle, shift) = (6.0 * f(4), [10.0 * f(5), -3.0 * f(6), 100.0 * f(7)]);
        let (a, b) = (
            rigid_motion(&a0, axis, angle, shift),
            rigid_motion(&b0, axis, angle, shift),
        );
        for op in Op::ALL {
            let raw = boolean(&a, &b, op, true);
            let clean = boolean(&a, &b, op, false);
            let what = format!("seed {seed} {op}");
            check(&raw, &clean, &what);
            if seed == 2 && matches!(op, Op::Difference | Op::Intersection) {
                assert!(degenerate_triangles(&raw.mesh) > 0, "{what}");
            }
            zero_length += clean.cleanup.zero_length_edges;
        }
    }
    assert!(zero_length > 0);
}

/// Spheres and a torus crossing at an angle (curved: no seam point is removable) and an
/// open terrain cut by a cylinder (straight walls: the hole's rim loses its straight
/// points): the guarantees hold; the volume identity holds with the clean-up.
#[test]
fn curved_and_open_inputs() {
    let s1 = meshbool::shapes::uv_sphere([0.0; 3], 1.0, 48, 24);
    let s2 = rigid_motion(
        &meshbool::shapes::uv_sphere([0.4, 0.1, 0.2], 0.9, 40, 20),
        [0.3, 0.2, 1.0],
        0.7,
        [0.0; 3],
    );
    let mut v = [0.0; 4];
    for (k, op) in Op::ALL.into_iter().enumerate() {
        let (raw, clean) = (boolean(&s1, &s2, op, true), boolean(&s1, &s2, op, false));
        check(&raw, &clean, &format!("spheres {op}"));
        v[k] = signed_volume(&clean.mesh);
    }
    let (va, vb) = (signed_volume(&s1), signed_volume(&s2));
    assert!((v[0] + v[1] - va - vb).abs() < 1e-9, "{v:?}");
    assert!((v[2] + v[1] - va).abs() < 1e-9, "{v:?}");
    let data = |n: &str| {
        let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../data")
            .join(n);
        meshbool::io::read_path(&p).unwrap()
    };
    let (terrain, cylinder) = (data("kirra_terrain.obj"), data("kirra_cylinder.obj"));
    for op in Op::ALL {
        let (raw, clean) = (
            boolean(&terrain, &cylinder, op, true),
            boolean(&terrain, &cylinder, op, false),
        );
        check(&raw, &clean, &format!("terrain {op}"));
    }
    let clean = boolean(&terrain, &cylinder, Op::Difference, false);
    assert_eq!(clean.cleanup.removed_points, 16);
}

/// Many inputs: the clean-ups of the pairwise booleans add up in the report, and the
/// result is the same solid as without them.
#[test]
fn many_inputs_add_up() {
    let boxes: Vec<Mesh> = (0..4)
        .map(|k| {
            let o = 0.3 * k as f64;
            Mesh::cuboid(
                [o, 0.1 * k as f64, 0.0],
                [o + 1.0, 1.0, 1.0 + 0.2 * k as f64],
            )
        })
        .collect();
    let inputs: Vec<ops::Input> = boxes.iter().map(ops::Input::from).collect();
    let run = |keep_seam_points| {
        let opts = BooleanOptions {
            keep_seam_points,
            ..BooleanOptions::default()
        };
        ops::boolean_many(&inputs, Op::Union, &opts).unwrap()
    };
    let (raw, clean) = (run(true), run(false));
    assert!(clean.cleanup.removed_points > 0);
    assert_eq!(raw.cleanup, Default::default());
    assert!(mesh_stats(&clean.mesh).closed);
    assert!(clean.mesh.triangle_count() < raw.mesh.triangle_count());
    assert_eq!(signed_volume(&clean.mesh), signed_volume(&raw.mesh));
    assert_eq!(clean.report().cleanup, clean.cleanup);
}
