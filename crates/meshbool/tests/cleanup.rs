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
use common::{assert_in_parent_faces, cube_and_cutter, skew_motion};

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
        let (a, b) = skew_motion(seed, &a0, &b0);
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
    let (s1, s2) = crossing_spheres();
    let mut v = [0.0; 4];
    for (k, op) in Op::ALL.into_iter().enumerate() {
        let (raw, clean) = (boolean(&s1, &s2, op, true), boolean(&s1, &s2, op, false));
        check(&raw, &clean, &format!("spheres {op}"));
        v[k] = signed_volume(&clean.mesh);
    }
    let (va, vb) = (signed_volume(&s1), signed_volume(&s2));
    assert!((v[0] + v[1] - va - vb).abs() < 1e-9, "{v:?}");
    assert!((v[2] + v[1] - va).abs() < 1e-9, "{v:?}");
    let (terrain, cylinder) = terrain_and_cylinder();
    for op in Op::ALL {
        let (raw, clean) = (
            boolean(&terrain, &cylinder, op, true),
            boolean(&terrain, &cylinder, op, false),
        );
        check(&raw, &clean, &format!("terrain {op}"));
    }
    // One on each of the cylinder's 30 flat sides: where the seam crosses its diagonal,
    // inside one terrain triangle.
    let clean = boolean(&terrain, &cylinder, Op::Difference, false);
    assert_eq!(clean.cleanup.removed_points, 30);
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

fn split(a: &Mesh, b: &Mesh, keep_seam_points: bool) -> ops::SplitOutput {
    let opts = ops::SplitOptions {
        keep_seam_points,
        ..ops::SplitOptions::default()
    };
    ops::split(a, b, &opts).unwrap()
}

/// The total length of the edges of one triangle.
fn boundary_length(m: &Mesh) -> f64 {
    edges_length(m, |n| n == 1)
}

/// The total length of the edges held by more than two triangles.
fn non_manifold_length(m: &Mesh) -> f64 {
    edges_length(m, |n| n > 2)
}

/// The total length of the edges of `m` held by a count of triangles that `counted` takes.
fn edges_length(m: &Mesh, counted: impl Fn(usize) -> bool) -> f64 {
    let mut uses = std::collections::HashMap::new();
    for t in m.triangles() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *uses.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    let p = m.positions();
    uses.iter()
        .filter(|&(_, &n)| counted(n))
        .map(|(&(a, b), _)| {
            let (x, y) = (p[a as usize], p[b as usize]);
            ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt()
        })
        .sum()
}

/// What the clean-up of a split must keep of the raw split: the same groups, each of the
/// same shape (area, volume, one component where it was one, every triangle in its
/// parent's plane for boxes, every vertex at a raw position) with as many triangles at
/// most and no zero-area triangle; the groups conforming ([`assert_same_picks`]); the
/// report's counts right. Returns the triangles removed.
fn check_split(raw: &ops::SplitOutput, clean: &ops::SplitOutput, what: &str) -> usize {
    let names = |o: &ops::SplitOutput| o.groups.iter().map(|g| g.group).collect::<Vec<_>>();
    assert_eq!(names(clean), names(raw), "{what}");
    let mut at: Vec<[u64; 3]> = raw
        .groups
        .iter()
        .flat_map(|g| g.mesh.positions().iter().map(|p| p.map(f64::to_bits)))
        .collect();
    at.sort_unstable();
    let mut removed = 0;
    for (c, r) in clean.groups.iter().zip(&raw.groups) {
        let w = format!("{what} {}", c.group);
        let (sc, sr) = (mesh_stats(&c.mesh), mesh_stats(&r.mesh));
        assert!(sc.triangles <= sr.triangles, "{w}");
        removed += sr.triangles - sc.triangles;
        assert!((sc.area - sr.area).abs() <= 1e-12 * sr.area.max(1.0), "{w}");
        let (v0, v1) = (signed_volume(&r.mesh), signed_volume(&c.mesh));
        assert!(
            (v1 - v0).abs() <= 1e-12 * v0.abs().max(1.0),
            "{w}: {v0} {v1}"
        );
        assert_eq!(c.components.len(), r.components.len(), "{w}");
        assert_eq!(degenerate_triangles(&c.mesh), 0, "{w}");
        assert_eq!(c.provenance.len(), c.mesh.triangle_count(), "{w}");
        for p in c.mesh.positions() {
            assert!(at.binary_search(&p.map(f64::to_bits)).is_ok(), "{w}: moved");
        }
    }
    assert_same_picks(clean, raw, what);
    let s = clean.cleanup;
    assert_eq!(s.triangles_removed, removed, "{what}");
    assert_eq!(
        s.triangles_removed,
        4 * (s.removed_points + s.zero_length_edges),
        "{what}"
    );
    assert_eq!(s.zero_area_left, 0, "{what}");
    assert_eq!(raw.cleanup, Default::default(), "{what}");
    removed
}

/// A split is cleaned as a boolean is, where the groups allow: the cube cut by a box a
/// hair larger has straight seams through flat faces, and their seam points go — four
/// triangles with each, one in each group — while every group keeps its shape and every
/// pick of them is closed where the raw pick is.
#[test]
fn a_split_loses_its_straight_seam_points_and_keeps_its_groups() {
    let (a, b) = cube_and_cutter();
    let (raw, clean) = (split(&a, &b, true), split(&a, &b, false));
    assert_eq!(check_split(&raw, &clean, "cube"), 24);
    assert_eq!(clean.cleanup.removed_points, 6);
    // The coarsest groups where the seam allows: the cube's part inside the box three
    // rectangles and two half-faces (8), the box's part inside the cube two rectangles (4).
    let counts = |o: &ops::SplitOutput| -> Vec<usize> {
        o.groups.iter().map(|g| g.mesh.triangle_count()).collect()
    };
    assert_eq!(counts(&raw), [14, 22, 10, 26]);
    assert_eq!(counts(&clean), [8, 16, 4, 20]);
    for g in &clean.groups {
        assert_in_parent_faces(&g.mesh, &g.provenance, &a, &b, &g.group.to_string());
    }
    // The report says so.
    let report = clean.report(meshbool::Format::PlyBinaryLe);
    assert_eq!(report.cleanup, clean.cleanup);
}

/// Turned about skew axes (faces no longer exactly flat, seam points rounding onto one
/// another), curved inputs (nothing to remove) and an open terrain cut by a cylinder:
/// every guarantee holds.
#[test]
fn split_clean_up_on_moved_curved_and_open_inputs() {
    let (a0, b0) = cube_and_cutter();
    for seed in 0..4u64 {
        let (a, b) = skew_motion(seed, &a0, &b0);
        check_split(
            &split(&a, &b, true),
            &split(&a, &b, false),
            &format!("seed {seed}"),
        );
    }
    let (s1, s2) = crossing_spheres();
    check_split(&split(&s1, &s2, true), &split(&s1, &s2, false), "spheres");
    let (terrain, cylinder) = terrain_and_cylinder();
    let removed = check_split(
        &split(&terrain, &cylinder, true),
        &split(&terrain, &cylinder, false),
        "terrain",
    );
    assert!(removed > 0);
}

/// Every pick of every group of a split (each subset, B's parts as they are and
/// flipped): its name, closed, the length of its non-manifold edges and of its boundary,
/// its volume.
fn all_picks(s: &ops::SplitOutput) -> Vec<(String, bool, f64, f64, f64)> {
    let groups: Vec<_> = s.groups.iter().map(|g| g.group).collect();
    let mut out = Vec::new();
    for subset in 1..(1u32 << groups.len()) {
        for flip_b in [false, true] {
            let specs: Vec<ops::PieceSpec> = (0..groups.len())
                .filter(|k| subset & (1 << k) != 0)
                .map(|k| ops::PieceSpec {
                    group: groups[k],
                    component: None,
                    flip: flip_b && groups[k].to_string().starts_with('b'),
                })
                .collect();
            let name: Vec<String> = specs.iter().map(|s| s.to_string()).collect();
            // As merged: a pick of three sheets at an edge has no manifold reading, and
            // its non-manifold split depends on the triangles there.
            let opts = ops::PickOptions {
                keep_nonmanifold: true,
                ..ops::PickOptions::default()
            };
            let m = s.pick(&specs, &opts).unwrap().mesh;
            let st = mesh_stats(&m);
            out.push((
                name.join(","),
                st.closed,
                non_manifold_length(&m),
                boundary_length(&m),
                st.volume,
            ));
        }
    }
    out
}

/// Faces that coincide or touch (B on A's top face, B's bottom in A's bottom face, a slab
/// through A), as given and turned about skew axes (rounded: caps and near-coincident
/// faces): every group of the cleaned split keeps its volume, and every pick of any of
/// the groups, the coplanar ones included, is closed where the raw pick is, with
/// boundaries and non-manifold edges of the same lengths and the same volume.
#[test]
fn split_clean_up_keeps_every_pick_of_touching_and_coplanar_parts() {
    let a = Mesh::unit_cube();
    let cases = [
        (
            "coplanar bottom",
            Mesh::cuboid([0.25, 0.25, 0.0], [0.75, 0.75, 1.5]),
        ),
        (
            "coplanar bottom and side",
            Mesh::cuboid([0.25, 0.0, 0.0], [1.5, 0.75, 0.5]),
        ),
        (
            "touching top",
            Mesh::cuboid([0.2, 0.3, 1.0], [0.8, 0.7, 2.0]),
        ),
        (
            "touching top offset",
            Mesh::cuboid([0.5, 0.5, 1.0], [1.5, 1.5, 2.0]),
        ),
        (
            "slab through",
            Mesh::cuboid([-0.5, 0.3, -0.5], [1.5, 0.7, 0.5]),
        ),
    ];
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * y.abs().max(1.0);
    for (name, b0) in &cases {
        for seed in 0..4u64 {
            let (a, b) = if seed == 0 {
                (a.clone(), b0.clone())
            } else {
                skew_motion(seed, &a, b0)
            };
            let what = format!("{name}, seed {seed}");
            let (raw, clean) = (split(&a, &b, true), split(&a, &b, false));
            for (c, r) in clean.groups.iter().zip(&raw.groups) {
                assert_eq!(c.group, r.group, "{what}");
                let (v0, v1) = (signed_volume(&r.mesh), signed_volume(&c.mesh));
                assert!(close(v1, v0), "{what} {}: {v0} {v1}", c.group);
            }
            assert_same_picks(&clean, &raw, &what);
        }
    }
}

/// Every pick of `clean`'s groups is the same pick of `raw`'s as a shape: closed where
/// it is, with boundaries and non-manifold edges of the same lengths (fewer points on
/// them) and the same volume.
fn assert_same_picks(clean: &ops::SplitOutput, raw: &ops::SplitOutput, what: &str) {
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * y.abs().max(1.0);
    let (pc, pr) = (all_picks(clean), all_picks(raw));
    assert_eq!(pc.len(), pr.len(), "{what}");
    for (c, r) in pc.iter().zip(&pr) {
        assert_eq!(c.0, r.0, "{what}");
        assert_eq!(c.1, r.1, "{what}: {}", c.0);
        assert!(
            close(c.2, r.2),
            "{what}: {} non-manifold {} {}",
            c.0,
            c.2,
            r.2
        );
        assert!(close(c.3, r.3), "{what}: {} boundary {} {}", c.0, c.3, r.3);
        assert!(close(c.4, r.4), "{what}: {} volume {} {}", c.0, c.4, r.4);
    }
}

/// A generated terrain (open, 7200 triangles) and a cylinder of 30 sides that pierces it.
fn terrain_and_cylinder() -> (Mesh, Mesh) {
    let terrain = meshbool::shapes::terrain([0.0; 3], [600.0; 2], [60; 2], 40.0, 1).unwrap();
    let cylinder = meshbool::shapes::cylinder([20.0, -10.0, -60.0], 35.0, 120.0, 30).unwrap();
    (terrain, cylinder)
}

/// Two UV spheres of unlike tessellations crossing at an angle (curved seams).
fn crossing_spheres() -> (Mesh, Mesh) {
    let s1 = meshbool::shapes::uv_sphere([0.0; 3], 1.0, 48, 24);
    let s2 = rigid_motion(
        &meshbool::shapes::uv_sphere([0.4, 0.1, 0.2], 0.9, 40, 20),
        [0.3, 0.2, 1.0],
        0.7,
        [0.0; 3],
    );
    (s1, s2)
}
