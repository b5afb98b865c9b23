//! `split` and `pick`: the four groups, picks that rebuild the booleans, merged components,
//! snapping.

use crate::common::*;

#[test]
fn split_then_pick_rebuilds_the_difference() {
    let a = write_cube("sa.ply", [0.0; 3], [1.0; 3]);
    let b = write_cube("sb.ply", [0.5, 0.25, -0.5], [1.5, 0.75, 0.5]);
    let dir = tmp("split");
    let m = report(&[
        "split",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "-o",
        dir.to_str().unwrap(),
        "--json",
    ]);
    let names: Vec<&str> = m["groups"]
        .as_array()
        .unwrap()
        .iter()
        .map(|g| g["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["a_in_b", "a_out_b", "b_in_a", "b_out_a"]);
    let area: f64 = m["groups"].as_array().unwrap()[..2]
        .iter()
        .map(|g| g["area"].as_f64().unwrap())
        .sum();
    assert!((area - 6.0).abs() < 1e-12);
    let out = tmp("picked.obj");
    let v = report(&[
        "pick",
        dir.to_str().unwrap(),
        "--keep",
        "a_out_b",
        "--keep",
        "b_in_a:flip",
        "-o",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(v["volume"], 1.0 - 0.125);
    assert_eq!(v["boundary_edges"], 0);
    let bad = meshbool(&[
        "pick",
        dir.to_str().unwrap(),
        "--keep",
        "a_on_b_same",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(bad.status.code(), Some(2));
}

#[test]
fn split_merge_small_joins_stray_components() {
    // A: a cube. B: a sphere poking out of its top face and a thin box poking out
    // next to it: B outside A has two components, the sphere cap (many triangles) and
    // the box top (a handful).
    let a = write_cube("ms_a.ply", [0.0; 3], [3.0; 3]);
    let mut b = meshbool::shapes::uv_sphere([1.2, 1.5, 3.0], 0.8, 24, 12);
    b.append(&meshbool::Mesh::cuboid([2.5, 2.5, 2.5], [2.7, 2.7, 3.3]))
        .unwrap();
    let bp = tmp("ms_b.ply");
    meshbool::io::write_path(&bp, &b).unwrap();
    let group = |m: &serde_json::Value, name: &str| -> serde_json::Value {
        m["groups"]
            .as_array()
            .unwrap()
            .iter()
            .find(|g| g["name"] == name)
            .unwrap()
            .clone()
    };
    let split = |dir: &str, extra: &[&str]| {
        let dir = tmp(dir);
        let mut args = vec![
            "split",
            a.to_str().unwrap(),
            bp.to_str().unwrap(),
            "-o",
            dir.to_str().unwrap(),
            "--json",
        ];
        args.extend(extra);
        report(&args)
    };
    let plain = group(&split("ms_plain", &[]), "b_out_a");
    let parts = plain["components"].as_array().unwrap();
    assert_eq!(parts.len(), 2);
    // Largest first.
    let (big, small) = (
        parts[0]["triangles"].as_u64().unwrap(),
        parts[1]["triangles"].as_u64().unwrap(),
    );
    assert!(big > 100 && small < 20, "{big} {small}");
    assert_eq!(plain["merged_small_components"], 0);
    let merged = group(&split("ms_merged", &["--merge-small", "20"]), "b_out_a");
    assert_eq!(merged["components"].as_array().unwrap().len(), 0);
    assert_eq!(merged["merged_small_components"], 1);
    assert_eq!(merged["triangles"].as_u64().unwrap(), big + small);
}

#[test]
fn pick_by_op_gives_the_boolean() {
    let a = write_cube("pickop_a.ply", [0.0; 3], [1.0; 3]);
    let b = write_cube("pickop_b.ply", [0.5; 3], [1.5; 3]);
    let dir = tmp("pickop_split");
    let r = meshbool(&[
        "split",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "-o",
        dir.to_str().unwrap(),
    ]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let out = tmp("pickop.ply");
    for (op, volume) in [
        ("union", 1.875),
        ("intersection", 0.125),
        ("difference", 0.875),
    ] {
        report(&[
            "pick",
            dir.to_str().unwrap(),
            "--op",
            op,
            "-o",
            out.to_str().unwrap(),
            "--json",
        ]);
        let m = meshbool::io::read_path(&out).unwrap();
        assert_eq!(meshbool::measure::signed_volume(&m), volume, "{op}");
    }
    // --op and --keep together: a usage error.
    let r = meshbool(&[
        "pick",
        dir.to_str().unwrap(),
        "--op",
        "union",
        "--keep",
        "a_out_b",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(r.status.code(), Some(2));
}

#[test]
fn split_and_pick_snap() {
    // The pair of `snap_cleans_needles_and_refuses_bad_tolerances`, split with `--snap`:
    // four groups, each one piece, no edge under the tolerance; the difference picked
    // from them closed, with the volume of the exact one. Then `pick --snap` from the
    // exact split's directory: the same difference as `difference --snap`.
    let a = write_cube("split_snap_a.obj", [0.0; 3], [1.0; 3]);
    let b = write_cube(
        "split_snap_b.obj",
        [0.5, -0.001, 0.5],
        [1.001, 1.001, 1.001],
    );
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
    let (dir, exact_dir) = (tmp("split_snap_dir"), tmp("split_exact_dir"));
    let (dir, exact_dir) = (dir.to_str().unwrap(), exact_dir.to_str().unwrap());
    let m = report(&[
        "split", a, b, "-o", dir, "--format", "obj", "--snap", "0.01", "--json",
    ]);
    assert_eq!(m["snap"]["left"], 0);
    assert!(m["snap"]["collapsed"].as_u64().unwrap() > 0);
    let groups = m["groups"].as_array().unwrap();
    assert_eq!(groups.len(), 4);
    for g in groups {
        assert_eq!(g["components"].as_array().unwrap().len(), 0, "{g}");
    }
    let manifest: serde_json::Value =
        serde_json::from_slice(&std::fs::read(format!("{dir}/manifest.json")).unwrap()).unwrap();
    assert_eq!(manifest["snap"], m["snap"]);
    let out = tmp("split_snap_diff.obj");
    let r = report(&[
        "pick",
        dir,
        "--op",
        "difference",
        "-o",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(
        (r["closed"].clone(), r["non_manifold_edges"].clone()),
        (true.into(), 0.into())
    );
    assert!((r["volume"].as_f64().unwrap() - 0.75).abs() <= 0.01 * r["area"].as_f64().unwrap());
    assert!(r.get("snap").is_none());
    let mesh = meshbool::io::read_path(&out).unwrap();
    let p = mesh.positions();
    for t in mesh.triangles() {
        for k in 0..3 {
            let (u, v) = (p[t[k] as usize], p[t[(k + 1) % 3] as usize]);
            let d = ((u[0] - v[0]).powi(2) + (u[1] - v[1]).powi(2) + (u[2] - v[2]).powi(2)).sqrt();
            assert!(d >= 0.01, "edge of {d}");
        }
    }
    report(&[
        "split",
        a,
        b,
        "-o",
        exact_dir,
        "--format",
        "obj",
        "--keep-seam-points",
        "--json",
    ]);
    let r = report(&[
        "pick",
        exact_dir,
        "--op",
        "difference",
        "-o",
        tmp("split_snap_pick.obj").to_str().unwrap(),
        "--snap",
        "0.01",
        "--json",
    ]);
    assert_eq!(r["snap"]["left"], 0);
    assert_eq!(
        (r["triangles"].clone(), r["volume"].clone()),
        (24.into(), 0.75.into())
    );
    assert_eq!(r["closed"], true);
    // The split's own exact clean-up (on by default) already leaves the coarsest
    // difference, the boolean's: 20 triangles, closed, without a tolerance.
    let clean_dir = tmp("split_clean_dir");
    let clean_dir = clean_dir.to_str().unwrap();
    let m = report(&["split", a, b, "-o", clean_dir, "--format", "obj", "--json"]);
    assert_eq!(m["cleanup"]["removed_points"], 6);
    let r = report(&[
        "pick",
        clean_dir,
        "--op",
        "difference",
        "-o",
        tmp("split_clean_pick.obj").to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(
        (
            r["triangles"].clone(),
            r["volume"].clone(),
            r["closed"].clone()
        ),
        (20.into(), 0.75.into(), true.into())
    );
}
