//! Snapping results at a tolerance (`BooleanOptions::snap`, `ResolveOptions::snap`,
//! `RepairConfig::snap`, `repair::snap`): the short edges and needles of exact results go,
//! and nothing the result had is lost: closed stays closed, manifold stays manifold, no
//! self-intersection appears, no vertex moves more than the tolerance, the volume changes
//! by at most the tolerance times the area.

use meshbool::intersect::self_intersections;
use meshbool::measure::{area, signed_volume};
use meshbool::ops::{self, BooleanOptions, BooleanOutput, ResolveOptions};
use meshbool::repair::{RepairConfig, SnapReport};
use meshbool::shapes::{heightfield, rigid_motion};
use meshbool::{Error, Mesh, Op};

mod common;
use common::{assert_in_parent_faces, cube_and_cutter, skew_motion};

const D: f64 = 0.01;

/// The shortest edge and the smallest altitude of a mesh's triangles.
fn worst(m: &Mesh) -> (f64, f64) {
    let (pos, tris) = (m.positions(), m.triangles());
    let mut worst = (f64::INFINITY, f64::INFINITY);
    for t in tris {
        let p = t.map(|v| pos[v as usize]);
        let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let len = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let l = [0, 1, 2].map(|k| len(sub(p[(k + 1) % 3], p[k])));
        let (u, v) = (sub(p[1], p[0]), sub(p[2], p[0]));
        let c = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let altitude = len(c) / l[0].max(l[1]).max(l[2]);
        worst.0 = worst.0.min(l[0].min(l[1]).min(l[2]));
        worst.1 = worst.1.min(altitude);
    }
    worst
}

/// The boolean snapped at `snap`, on the arrangement as it is (`keep_seam_points`: the
/// exact clean-up, on by default, already removes the straight seam points that make
/// most needles here; these tests are about what snapping does on its own).
fn boolean(a: &Mesh, b: &Mesh, op: Op, snap: f64) -> BooleanOutput {
    let opts = BooleanOptions {
        snap,
        keep_seam_points: true,
        ..BooleanOptions::default()
    };
    ops::boolean(a, b, op, &opts).unwrap()
}

/// What every snapped closed result must be, compared with the exact one: closed and
/// manifold, no edge shorter and no altitude smaller than `D` (the inputs have none), the
/// volume within `D × area` of the exact one (and as reported), no vertex moved more
/// than `D`, no more self-intersections than the exact result, provenance for every
/// triangle.
fn check_closed(exact: &BooleanOutput, snapped: &BooleanOutput, what: &str) -> SnapReport {
    let r = snapped.report();
    let s = r.snap.clone().expect("a snap report");
    assert!(r.result.closed, "{what}");
    assert_eq!(r.result.non_manifold_edges, 0, "{what}");
    let (edge, height) = worst(&snapped.mesh);
    assert!(edge >= D && height >= D, "{what}: {edge} {height}");
    let (v0, v1) = (signed_volume(&exact.mesh), signed_volume(&snapped.mesh));
    let bound = D * area(&exact.mesh);
    assert!((v1 - v0).abs() <= bound, "{what}: {v0} -> {v1}");
    assert!(s.volume_change.abs() <= bound, "{what}");
    assert!((s.volume_change - (v1 - v0)).abs() < 1e-12, "{what}");
    assert!((s.area_change - (area(&snapped.mesh) - area(&exact.mesh))).abs() < 1e-12);
    assert!(s.max_move <= D, "{what}");
    assert_eq!(
        (s.triangles_removed, s.vertices_removed),
        (
            exact.mesh.triangle_count() - snapped.mesh.triangle_count(),
            exact.mesh.vertex_count() - snapped.mesh.vertex_count()
        ),
        "{what}"
    );
    assert_eq!(
        (s.left, s.found > 0, s.collapsed > 0),
        (0, true, true),
        "{what}"
    );
    assert!(
        self_intersections(&snapped.mesh).len() <= self_intersections(&exact.mesh).len(),
        "{what}"
    );
    assert_eq!(
        snapped.provenance.len(),
        snapped.mesh.triangle_count(),
        "{what}"
    );
    s
}

#[test]
fn snapping_a_cube_cut_by_a_slightly_larger_box_removes_every_needle() {
    let (a, b) = cube_and_cutter();
    for (op, triangles, volume) in [(Op::Difference, 24, 0.75), (Op::Intersection, 16, 0.25)] {
        let exact = boolean(&a, &b, op, 0.0);
        let (edge, height) = worst(&exact.mesh);
        assert!(
            edge < 1e-3 && height < 1e-3,
            "{op}: the exact result has needles"
        );
        let snapped = boolean(&a, &b, op, D);
        let s = check_closed(&exact, &snapped, &op.to_string());
        // Seam points went into the cut's corners along the creases: the shape is the
        // exact one, the volume too; no self-intersection.
        assert_eq!(snapped.mesh.triangle_count(), triangles, "{op}");
        assert_eq!(
            (s.volume_change, signed_volume(&snapped.mesh)),
            (0.0, volume)
        );
        assert!(self_intersections(&snapped.mesh).is_empty());
        // Provenance follows: every triangle lies in the face (an axis plane) of the
        // input triangle it names.
        assert_in_parent_faces(&snapped.mesh, &snapped.provenance, &a, &b, &op.to_string());
    }
}

#[test]
fn without_a_tolerance_the_result_is_the_exact_one() {
    let (a, b) = cube_and_cutter();
    for op in Op::ALL {
        let raw = BooleanOptions {
            keep_seam_points: true,
            ..BooleanOptions::default()
        };
        let plain = ops::boolean(&a, &b, op, &raw).unwrap();
        let zero = boolean(&a, &b, op, 0.0);
        assert_eq!(plain.mesh, zero.mesh, "{op}");
        assert_eq!(plain.provenance, zero.provenance, "{op}");
        // Nothing was cleaned: the exact result's needles are there.
        let (edge, height) = worst(&plain.mesh);
        assert!(edge.min(height) < 1e-3, "{op}: {edge} {height}");
        assert!(zero.snap.is_none());
        let json = serde_json::to_value(zero.report()).unwrap();
        assert!(json.get("snap").is_none());
    }
}

#[test]
fn rigid_motions_snap_the_same() {
    let (a, b) = cube_and_cutter();
    for seed in 0..6u64 {
        let (a, b) = skew_motion(seed, &a, &b);
        for (op, triangles) in [(Op::Difference, 24), (Op::Intersection, 16)] {
            let exact = boolean(&a, &b, op, 0.0);
            let snapped = boolean(&a, &b, op, D);
            let what = format!("seed {seed} {op}");
            check_closed(&exact, &snapped, &what);
            assert_eq!(snapped.mesh.triangle_count(), triangles, "{what}");
            // Rounding the seam points of the rotated exact result can make slivers cross;
            // snapping takes them away.
            assert!(self_intersections(&snapped.mesh).is_empty(), "{what}");
        }
    }
}

#[test]
fn snapping_an_open_terrain_keeps_its_boundary() {
    // A terrain (grid of 1) cut by a box whose walls pass 1e-3 from grid lines, crossing
    // the terrain's edge 1e-3 from a boundary vertex.
    let terrain = heightfield([0.0, 0.0], [10.0, 10.0], 10, 10, |x, y| {
        0.1 * x + 0.05 * y + 0.02 * (x * y).sin()
    });
    let cutter = Mesh::cuboid([2.001, -1.0, -5.0], [6.999, 5.0005, 0.5]);
    for op in [Op::Difference, Op::Intersection, Op::Union] {
        let exact = boolean(&terrain, &cutter, op, 0.0);
        let snapped = boolean(&terrain, &cutter, op, D);
        let (e, r) = (exact.report(), snapped.report());
        let s = r.snap.expect("a snap report");
        assert!(worst(&exact.mesh).1 < 1e-3);
        assert!(r.result.boundary_edges <= e.result.boundary_edges, "{op}");
        assert_eq!(r.result.non_manifold_edges, 0, "{op}");
        let (edge, height) = worst(&snapped.mesh);
        assert!(edge >= D && height >= D, "{op}: {edge} {height}");
        assert_eq!(s.left, 0, "{op}");
        assert!(s.max_move <= D);
        assert!(self_intersections(&snapped.mesh).is_empty(), "{op}");
    }
}

#[test]
fn resolve_and_repair_snap_too() {
    // Two overlapping cubes in one mesh, the second a little larger than the first's
    // half: resolved into their union, with needles where the faces nearly meet.
    let mut two = Mesh::unit_cube();
    two.append(&Mesh::cuboid([0.5, -0.001, 0.5], [1.001, 1.001, 1.001]))
        .unwrap();
    let exact = ops::resolve(&two, &ResolveOptions::default()).unwrap();
    let opts = ResolveOptions {
        snap: D,
        ..ResolveOptions::default()
    };
    let snapped = ops::resolve(&two, &opts).unwrap();
    let s = snapped.snap.clone().expect("a snap report");
    assert!(s.collapsed > 0 && s.left == 0);
    assert_eq!(snapped.parent.len(), snapped.mesh.triangle_count());
    let r = snapped.report();
    assert!(r.result.closed);
    assert!((r.result.volume - signed_volume(&exact.mesh)).abs() <= D * area(&exact.mesh));
    assert!(worst(&snapped.mesh).1 >= D);
    // The same as a repair step on the exact result.
    let config = RepairConfig {
        snap: Some(D),
        ..RepairConfig::default()
    };
    let repaired = ops::repair(&exact.mesh, &config).unwrap();
    let rs = repaired.repair.snap.clone().expect("the step ran");
    assert_eq!(rs.left, 0);
    assert!(repaired.repair.after.closed);
    assert!(worst(&repaired.mesh).1 >= D);
}

#[test]
fn tolerances_must_be_finite_and_not_negative() {
    let (a, b) = cube_and_cutter();
    for bad in [f64::NAN, -1.0, -0.0001, f64::INFINITY, f64::NEG_INFINITY] {
        let opts = BooleanOptions {
            snap: bad,
            ..BooleanOptions::default()
        };
        let refused = |r: Result<(), Error>| matches!(r, Err(Error::InvalidParameter(m)) if m.contains("snap"));
        assert!(
            refused(ops::boolean(&a, &b, Op::Union, &opts).map(drop)),
            "{bad}"
        );
        let inputs = [(&a).into(), (&b).into()];
        assert!(refused(
            ops::boolean_many(&inputs, Op::Union, &opts).map(drop)
        ));
        let resolve = ResolveOptions {
            snap: bad,
            ..ResolveOptions::default()
        };
        assert!(refused(ops::resolve(&a, &resolve).map(drop)));
        let config = RepairConfig {
            snap: Some(bad),
            ..RepairConfig::default()
        };
        assert!(refused(ops::repair(&a, &config).map(drop)));
        assert!(refused(meshbool::repair::snap(&a, bad).map(drop)));
    }
}

#[test]
fn many_inputs_snap_with_provenance() {
    let (a, b) = cube_and_cutter();
    let c = Mesh::cuboid([-0.001, 0.5, -0.001], [0.5, 1.001, 0.5]);
    let opts = BooleanOptions {
        snap: D,
        ..BooleanOptions::default()
    };
    let inputs = [(&a).into(), (&b).into(), (&c).into()];
    let exact = ops::boolean_many(&inputs, Op::Union, &BooleanOptions::default()).unwrap();
    let out = ops::boolean_many(&inputs, Op::Union, &opts).unwrap();
    let s = out.snap.clone().expect("a snap report");
    assert!(s.collapsed > 0 && s.left == 0);
    assert_eq!(out.provenance.len(), out.mesh.triangle_count());
    let r = out.report();
    assert!(r.result.closed && r.result.non_manifold_edges == 0);
    assert!((r.result.volume - signed_volume(&exact.mesh)).abs() <= D * area(&exact.mesh));
    assert!(worst(&out.mesh).0 >= D);
}

#[test]
fn extreme_scales_snap_as_at_unit_size() {
    let (a, b) = cube_and_cutter();
    let unit = boolean(&a, &b, Op::Difference, D);
    let s0 = unit.snap.clone().expect("a snap report");
    for e in [-600, 500] {
        let k = 2f64.powi(e);
        let scaled = |m: &Mesh| {
            let (p, t) = m.clone().into_parts();
            Mesh::new(p.into_iter().map(|q| q.map(|x| x * k)).collect(), t).unwrap()
        };
        let out = boolean(&scaled(&a), &scaled(&b), Op::Difference, D * k);
        let s = out.snap.clone().expect("a snap report");
        assert_eq!(
            out.mesh.triangle_count(),
            unit.mesh.triangle_count(),
            "2^{e}"
        );
        assert_eq!(
            (s.collapsed, s.flipped, s.left),
            (s0.collapsed, s0.flipped, 0)
        );
        assert_eq!(s.tolerance, D * k);
        assert_eq!(s.max_move, s0.max_move * k);
        for (p, q) in out.mesh.positions().iter().zip(unit.mesh.positions()) {
            assert_eq!(*p, q.map(|x| x * k), "2^{e}");
        }
    }
}

/// `boolean::snap_result` keeps the result's seam vertices in step with its vertices (the
/// ones collapsed away gone, the others renumbered) and refuses a bad tolerance.
#[test]
fn snapping_a_pipeline_result_renumbers_its_seam_vertices() {
    let (a, b) = cube_and_cutter();
    let raw = meshbool::boolean::PipelineOptions {
        cleanup: false,
        ..Default::default()
    };
    let mut r = meshbool::boolean::boolean(&a, &b, Op::Difference, &raw);
    let at = |r: &meshbool::boolean::BooleanResult, v: u32| r.mesh.positions()[v as usize];
    let seam: Vec<[f64; 3]> = r.seam_vertices.iter().map(|&v| at(&r, v)).collect();
    assert!(meshbool::boolean::snap_result(&mut r, -1.0).is_err());
    let report = meshbool::boolean::snap_result(&mut r, D).unwrap();
    assert!(report.vertices_removed > 0);
    assert_eq!(r.provenance.len(), r.mesh.triangle_count());
    // Exactly the vertices still at seam points are listed.
    let listed: Vec<u32> = (0..r.mesh.vertex_count() as u32)
        .filter(|&v| seam.contains(&at(&r, v)))
        .collect();
    assert_eq!(r.seam_vertices, listed);
    assert!(listed.len() < seam.len());
}

/// A boolean snaps where it cut, not the inputs' own needles elsewhere: a UV sphere's
/// pole fans (altitudes about 2e-3) stay as they were, `repair --snap` would take them.
#[test]
fn a_boolean_snaps_where_it_cut_and_leaves_the_inputs_needles() {
    let sphere = meshbool::shapes::uv_sphere([0.0; 3], 1.0, 200, 50);
    let pole_fan = |m: &Mesh| {
        let (pos, tris) = (m.positions(), m.triangles());
        tris.iter()
            .filter(|t| t.iter().any(|&v| pos[v as usize] == [0.0, 0.0, 1.0]))
            .count()
    };
    assert_eq!(pole_fan(&sphere), 200);
    // A box across the equator, 1e-3 beyond the sphere on one side.
    let cutter = Mesh::cuboid([0.5, -0.3, -0.3], [1.001, 0.3, 0.3]);
    let exact = boolean(&sphere, &cutter, Op::Difference, 0.0);
    let snapped = boolean(&sphere, &cutter, Op::Difference, D);
    let s = snapped.snap.clone().unwrap();
    assert!(s.collapsed + s.flipped > 0, "{s:?}");
    assert_eq!(pole_fan(&snapped.mesh), 200);
    let r = snapped.report();
    assert!(r.result.closed);
    assert_eq!(r.result.non_manifold_edges, 0);
    assert!(
        (signed_volume(&snapped.mesh) - signed_volume(&exact.mesh)).abs() <= D * area(&exact.mesh)
    );
    // The whole mesh snapped by repair takes the pole fans too.
    let config = RepairConfig {
        snap: Some(D),
        ..RepairConfig::default()
    };
    let repaired = ops::repair(&exact.mesh, &config).unwrap();
    assert!(pole_fan(&repaired.mesh) < 200);
}

/// The triangles of `m` with an edge shorter than `D` or an altitude below it.
fn needles(m: &Mesh) -> usize {
    m.triangles()
        .iter()
        .filter(|t| {
            let one = Mesh::new(m.positions().to_vec(), vec![**t]).unwrap();
            let (edge, height) = worst(&one);
            edge < D || height < D
        })
        .count()
}

/// The split at `snap`; with 0, the exact arrangement's groups with every seam point (the
/// baseline the snap's counts are measured against, as a boolean's raw result).
fn split(a: &Mesh, b: &Mesh, snap: f64) -> ops::SplitOutput {
    let opts = ops::SplitOptions {
        snap,
        keep_seam_points: true,
        ..ops::SplitOptions::default()
    };
    ops::split(a, b, &opts).unwrap()
}

/// Every pick of the four main groups (each subset, as is and with B's parts flipped)
/// from the exact split and the snapped one: (closed, boundary edges, non-manifold edges,
/// volume).
fn picks(s: &ops::SplitOutput) -> Vec<(bool, usize, usize, f64)> {
    use meshbool::Group;
    let main = [Group::AInB, Group::AOutB, Group::BInA, Group::BOutA];
    let mut out = Vec::new();
    for subset in 1..16u32 {
        for flip_b in [false, true] {
            let specs: Vec<ops::PieceSpec> = (0..4)
                .filter(|k| subset & (1 << k) != 0)
                .map(|k| ops::PieceSpec {
                    group: main[k],
                    component: None,
                    flip: flip_b && k >= 2,
                })
                .collect();
            let m = s.pick(&specs, &ops::PickOptions::default()).unwrap().mesh;
            let st = meshbool::measure::mesh_stats(&m);
            out.push((
                st.closed,
                st.boundary_edges,
                st.non_manifold_edges,
                st.volume,
            ));
        }
    }
    out
}

/// A split with `--snap` cleans all four groups together: each stays one component, no
/// needle is left, and every pick of them is closed exactly where the exact pick is, its
/// volume within `D × area` of the exact pick's, without self-intersections.
#[test]
fn a_snapped_split_keeps_its_groups_conforming() {
    let (a0, b0) = cube_and_cutter();
    for seed in 0..4u64 {
        let f = |k: u64| ((seed * 7919 + k * 104_729) % 1000) as f64 / 1000.0;
        let (axis, angle, shift) = (
            [f(1) - 0.5, f(2) - 0.5, f(3) + 0.1],
            6.0 * f(4),
            [10.0 * f(5), -3.0 * f(6), 100.0 * f(7)],
        );
        let (a, b) = if seed == 0 {
            (a0.clone(), b0.clone())
        } else {
            (
                rigid_motion(&a0, axis, angle, shift),
                rigid_motion(&b0, axis, angle, shift),
            )
        };
        let exact = split(&a, &b, 0.0);
        let snapped = split(&a, &b, D);
        let what = format!("seed {seed}");
        assert!(exact.snap.is_none());
        let s = snapped.snap.clone().expect("a snap report");
        assert!(s.collapsed > 0 && s.not_reached == 0, "{what}: {s:?}");
        // Each needle left has its refusal counted: here, where a collapse would lay A's
        // part inside B onto B's part inside A (a pick of both would have them touch).
        assert_eq!(s.left, s.refused_manifold, "{what}: {s:?}");
        assert!(s.left * 8 <= s.found, "{what}: {s:?}");
        if seed == 0 {
            assert_eq!(s.left, 0);
        }
        assert!(s.max_move <= D, "{what}");
        let names = |o: &ops::SplitOutput| o.groups.iter().map(|g| g.group).collect::<Vec<_>>();
        assert_eq!(names(&snapped), names(&exact), "{what}");
        assert_eq!(snapped.groups.len(), 4, "{what}");
        let total_area: f64 = exact.groups.iter().map(|g| area(&g.mesh)).sum();
        let mut bad = 0;
        for (g, e) in snapped.groups.iter().zip(&exact.groups) {
            assert!(g.components.is_empty(), "{what}: {} in pieces", g.group);
            assert_eq!(g.provenance.len(), g.mesh.triangle_count());
            assert!(g.mesh.triangle_count() < e.mesh.triangle_count(), "{what}");
            bad += needles(&g.mesh);
        }
        // Every needle left is one the report counts (the inputs have none).
        assert_eq!(bad, s.left, "{what}");
        for ((c0, b0, n0, v0), (c1, b1, n1, v1)) in picks(&exact).into_iter().zip(picks(&snapped)) {
            // Closed stays closed, manifold stays manifold (a seam loop smaller than `D`
            // may go, closing a pick that was open).
            assert!(c1 || !c0, "{what}");
            assert!(
                b1 <= b0 && (n1 == 0 || n0 > 0),
                "{what}: {b0} {n0} -> {b1} {n1}"
            );
            if c0 {
                assert!((v1 - v0).abs() <= D * total_area, "{what}: {v0} -> {v1}");
            }
        }
        // The booleans picked from either split: closed, manifold; the snapped ones
        // without crossings. (Seed 2 has distinct seam points that round to one point:
        // the sliver between them goes when the pieces are welded, counted.)
        let mut by_weld = 0;
        for op in Op::ALL {
            let m = snapped
                .pick_op(op, &ops::PickOptions::default())
                .unwrap()
                .mesh;
            let e = exact.pick_op(op, &ops::PickOptions::default()).unwrap();
            by_weld += e.collapsed_by_weld;
            let st = meshbool::measure::mesh_stats(&e.mesh);
            assert!(
                st.closed && st.non_manifold_edges == 0,
                "{what} {op}: exact"
            );
            let e = e.mesh;
            assert!(meshbool::measure::mesh_stats(&m).closed, "{what} {op}");
            assert!(self_intersections(&m).is_empty(), "{what} {op}");
            let dv = signed_volume(&m) - signed_volume(&e);
            assert!(dv.abs() <= D * area(&e), "{what} {op}: {dv}");
        }
        assert_eq!(by_weld > 0, seed == 2, "{what}");
        // The manifest carries the report.
        let report = snapped.report(meshbool::Format::Obj);
        assert_eq!(report.snap.as_ref(), Some(&s));
        assert!(exact.report(meshbool::Format::Obj).snap.is_none());
    }
}

/// `pick --snap` cleans where the picked pieces meet, as the boolean's own snap does: the
/// boolean picked from an exact split and snapped is closed, manifold, without needles,
/// its volume within `D × area` of the exact one; at 2^-600 the same, scaled.
#[test]
fn a_pick_snaps_where_its_pieces_meet() {
    let (a, b) = cube_and_cutter();
    let exact = split(&a, &b, 0.0);
    let opts = ops::PickOptions {
        snap: D,
        ..ops::PickOptions::default()
    };
    for op in [Op::Difference, Op::Intersection, Op::ReverseDifference] {
        let e = exact.pick_op(op, &ops::PickOptions::default()).unwrap();
        let p = exact.pick_op(op, &opts).unwrap();
        assert!(e.snap.is_none());
        let s = p.snap.clone().expect("a snap report");
        assert!(s.collapsed > 0 && s.left == 0, "{op}: {s:?}");
        let r = p.report();
        assert!(r.stats.closed && r.stats.non_manifold_edges == 0, "{op}");
        assert_eq!(r.snap.as_ref(), Some(&s));
        assert_eq!(needles(&p.mesh), 0, "{op}");
        let dv = signed_volume(&p.mesh) - signed_volume(&e.mesh);
        assert!(dv.abs() <= D * area(&e.mesh), "{op}: {dv}");
        assert!((s.volume_change - dv).abs() < 1e-12, "{op}");
        assert!(self_intersections(&p.mesh).is_empty(), "{op}");
    }
    // At an extreme scale: the same picks, scaled exactly.
    let k = 2f64.powi(-600);
    let scaled = |m: &Mesh| {
        let (p, t) = m.clone().into_parts();
        Mesh::new(p.into_iter().map(|q| q.map(|x| x * k)).collect(), t).unwrap()
    };
    let unit = exact.pick_op(Op::Difference, &opts).unwrap();
    let tiny = split(&scaled(&a), &scaled(&b), 0.0);
    let tiny_opts = ops::PickOptions {
        snap: D * k,
        ..opts
    };
    let p = tiny.pick_op(Op::Difference, &tiny_opts).unwrap();
    assert_eq!(p.mesh, scaled(&unit.mesh));
    let s = p.snap.unwrap();
    assert_eq!(s.collapsed, unit.snap.as_ref().unwrap().collapsed);
    assert_eq!(s.max_move, unit.snap.unwrap().max_move * k);
    // A bad tolerance is refused.
    let bad = ops::PickOptions { snap: -1.0, ..opts };
    assert!(exact.pick_op(Op::Union, &bad).is_err());
}

/// `boolean::snap_result` fills the slots it empties from the end (few moves) but makes
/// the same mesh as the order-keeping `repair::snap_with` with the same options: the same
/// triangles at the same corners, with the same provenance, and the seam vertices at the
/// same points.
#[test]
fn snapping_a_result_out_of_order_makes_the_ordered_mesh() {
    use meshbool::boolean::{PipelineOptions, Provenance, Source};
    use meshbool::repair::{snap_with, SnapOptions};
    let (a, b) = cube_and_cutter();
    for op in [Op::Difference, Op::Union, Op::Intersection] {
        let raw = PipelineOptions {
            cleanup: false,
            ..Default::default()
        };
        let r = meshbool::boolean::boolean(&a, &b, op, &raw);
        let labels: Vec<u32> = r
            .provenance
            .iter()
            .map(|p| u32::from(p.source == Source::B))
            .collect();
        let opts = SnapOptions {
            tolerance: D,
            seam: &r.seam_vertices,
            labels: Some(&labels),
            seam_only: true,
            sheets: None,
        };
        let ordered = snap_with(&r.mesh, &opts).unwrap();
        let mut filled = r.clone();
        let report = meshbool::boolean::snap_result(&mut filled, D).unwrap();
        assert_eq!(report, ordered.report, "{op:?}");
        assert!(
            report.collapsed > 0,
            "{op:?}: the case must change something"
        );
        // Triangles as (corners from the lowest, provenance), sorted.
        type Key = ([[u64; 3]; 3], (bool, u32, bool));
        let keys = |m: &Mesh, prov: &mut dyn Iterator<Item = Provenance>| -> Vec<Key> {
            let mut k: Vec<Key> = m
                .triangles()
                .iter()
                .zip(prov)
                .map(|(t, p)| {
                    let c = t.map(|v| m.positions()[v as usize].map(f64::to_bits));
                    let low = (0..3).min_by_key(|&i| c[i]).unwrap();
                    let c = [c[low], c[(low + 1) % 3], c[(low + 2) % 3]];
                    (c, (p.source == Source::B, p.triangle, p.flipped))
                })
                .collect();
            k.sort_unstable();
            k
        };
        let parent_prov = ordered.parent.iter().map(|&t| r.provenance[t as usize]);
        assert_eq!(
            keys(&filled.mesh, &mut filled.provenance.iter().copied()),
            keys(&ordered.mesh, &mut parent_prov.into_iter()),
            "{op:?}"
        );
        assert_eq!(filled.mesh.vertex_count(), ordered.mesh.vertex_count());
        let points = |m: &Mesh, vs: &[u32]| {
            let mut p: Vec<[u64; 3]> = vs
                .iter()
                .map(|&v| m.positions()[v as usize].map(f64::to_bits))
                .collect();
            p.sort_unstable();
            p
        };
        let seam_left: Vec<u32> = (0..ordered.mesh.vertex_count() as u32)
            .filter(|&v| {
                let p = ordered.mesh.positions()[v as usize];
                r.seam_vertices
                    .iter()
                    .any(|&s| r.mesh.positions()[s as usize] == p)
            })
            .collect();
        assert_eq!(
            points(&filled.mesh, &filled.seam_vertices),
            points(&ordered.mesh, &seam_left),
            "{op:?}"
        );
        assert!(filled.seam_vertices.windows(2).all(|w| w[0] < w[1]));
    }
}

/// `boolean::snap_result` labels every triangle by the input it comes from (read from
/// its provenance), so that no edge is flipped across the seam: the same snap as
/// `repair::snap_with` given those labels, on a case whose snap depends on them (flips
/// across the seam refused; without labels the snap differs).
#[test]
fn a_boolean_snap_labels_its_triangles_by_input() {
    use meshbool::boolean::Source;
    use meshbool::repair::{snap_with, SnapOptions};
    let a = meshbool::shapes::uv_sphere([0.0; 3], 1.0, 100, 31);
    let b = rigid_motion(&a, [0.0, 0.0, 1.0], 0.1, [0.5, 0.0, 0.0]);
    let r = meshbool::boolean::boolean(&a, &b, Op::Union, &Default::default());
    let by_input: Vec<u32> = r
        .provenance
        .iter()
        .map(|p| u32::from(p.source == Source::B))
        .collect();
    let snapped = |labels: Option<&[u32]>| {
        let opts = SnapOptions {
            tolerance: D,
            seam: &r.seam_vertices,
            labels,
            seam_only: true,
            sheets: None,
        };
        snap_with(&r.mesh, &opts).unwrap()
    };
    let (with, without) = (snapped(Some(&by_input)), snapped(None));
    assert!(
        with.report.refused_seam > 0 && without.report != with.report,
        "the case must depend on the labels: {:?}",
        with.report
    );
    let mut s = r.clone();
    let report = meshbool::boolean::snap_result(&mut s, D).unwrap();
    assert_eq!(report, with.report);
    assert_eq!(s.mesh.triangle_count(), with.mesh.triangle_count());
    assert_eq!(s.mesh.vertex_count(), with.mesh.vertex_count());
}
