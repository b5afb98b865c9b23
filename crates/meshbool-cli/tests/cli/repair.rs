//! `repair`, `close`, `resolve`: each step, the pipeline and its config file, capping,
//! stitching, curtains, snapping, envelopes.

use crate::common::*;

#[test]
fn close_cap_turns_an_open_box_into_a_unit_cube() {
    let (positions, mut triangles) = meshbool::Mesh::unit_cube().into_parts();
    triangles.drain(4..6);
    let m = meshbool::Mesh::new(positions, triangles).unwrap();
    let open = tmp("openbox.obj");
    meshbool::io::write_path(&open, &m).unwrap();
    let out = tmp("closedbox.ply");
    let r = report(&[
        "close",
        open.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--mode",
        "cap",
        "--json",
    ]);
    assert_eq!(
        (
            r["cap"]["loops"].as_u64(),
            r["cap"]["capped"].as_u64(),
            r["cap"]["triangles_added"].as_u64()
        ),
        (Some(1), Some(1), Some(2))
    );
    let info = report(&["info", "--json", out.to_str().unwrap()]);
    assert_eq!(info["volume"], 1.0);
    assert_eq!(info["closed"], true);
    assert_eq!(info["inconsistent_edges"], 0);
}

#[test]
fn oriented_terrain_curtained_is_a_closed_solid() {
    let oriented = tmp("curt_oriented.ply");
    report(&[
        "orient",
        wound_terrain(UTM).to_str().unwrap(),
        "-o",
        oriented.to_str().unwrap(),
        "--z-up",
        "--json",
    ]);
    let out = tmp("curtained.ply");
    let r = report(&[
        "close",
        oriented.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--mode",
        "curtain",
        "--floor-offset",
        "10",
        "--json",
    ]);
    assert_eq!(r["closed"], true);
    assert_eq!(r["boundary_edges"], 0);
    assert_eq!(r["curtain"]["wall_triangles"], 2 * 240);
    assert!(r["volume"].as_f64().unwrap() > 0.0);
    let info = report(&["info", "--json", out.to_str().unwrap()]);
    assert_eq!(info["inconsistent_edges"], 0);
    assert_eq!(info["volume"], r["volume"]);
}

#[test]
fn repair_weld_closes_a_crack() {
    let m = meshbool::Mesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0001, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [1.0001, 1.0, 0.0],
        ],
        vec![[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]],
    )
    .unwrap();
    let input = tmp("crack.obj");
    meshbool::io::write_path(&input, &m).unwrap();
    let out = tmp("crack_fixed.obj");
    let r = report(&[
        "repair",
        input.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--weld",
        "0.001",
        "--json",
    ]);
    assert_eq!(r["weld"]["merged_vertices"], 2);
    assert_eq!(r["weld"]["collapsed_triangles"], 0);
    assert_eq!(r["after"]["boundary_edges"], 6);
    assert_eq!(r["after"]["triangles"], 4);
}

#[test]
fn repair_tjunctions_closes_a_cube_crack() {
    let (mut positions, mut triangles) = meshbool::Mesh::unit_cube().into_parts();
    positions.push([1.0, 0.5, 0.0]);
    triangles.truncate(10);
    triangles.extend([[1, 8, 5], [8, 3, 7], [8, 7, 5]]);
    let m = meshbool::Mesh::new(positions, triangles).unwrap();
    let input = tmp("tj.ply");
    meshbool::io::write_path(&input, &m).unwrap();
    let out = tmp("tj_fixed.ply");
    let r = report(&[
        "repair",
        input.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--tjunctions",
        "--json",
    ]);
    assert_eq!(r["tjunctions"]["edges_split"], 1);
    assert_eq!(r["after"]["boundary_edges"], 0);
    assert_eq!(
        report(&["info", "--json", out.to_str().unwrap()])["volume"],
        1.0
    );
}

#[test]
fn repair_tjunctions_with_a_distance_closes_a_near_t_junction() {
    // Two unit squares side by side; the right one is fanned around a vertex 1e-4 to the
    // right of the middle of the left one's right edge: a T-junction 1e-4 off the edge.
    let m = meshbool::Mesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [1.0001, 0.5, 0.0],
        ],
        vec![[0, 1, 2], [0, 2, 3], [6, 1, 4], [6, 4, 5], [6, 5, 2]],
    )
    .unwrap();
    // Exact (also with a distance of 0, or one below the gap): the seam stays open, four
    // edges around each square and the right one's left edge in two.
    for flags in [
        &["--tjunctions"][..],
        &["--tjunctions", "0"],
        &["--tjunctions", "1e-5"],
    ] {
        let r = repair_json(&m, "near_t", flags);
        assert_eq!(r["before"]["boundary_edges"], 9, "{flags:?}");
        assert_eq!(r["tjunctions"]["edges_split"], 0, "{flags:?}");
        assert_eq!(r["tjunctions"]["largest_distance"], 0.0, "{flags:?}");
        assert_eq!(r["after"]["boundary_edges"], 9, "{flags:?}");
    }
    // Within 1e-3: the left square's edge is split through the vertex; only the outline
    // of the two squares is left open.
    let r = repair_json(&m, "near_t", &["--tjunctions", "1e-3"]);
    assert_eq!(r["tjunctions"]["edges_split"], 1);
    assert_eq!(r["tjunctions"]["vertices_inserted"], 1);
    assert_eq!(r["tjunctions"]["largest_distance"], 1.0001 - 1.0);
    let a = &r["after"];
    assert_eq!(
        (
            &a["boundary_edges"],
            &a["inconsistent_edges"],
            &a["triangles"]
        ),
        (&6.into(), &0.into(), &6.into())
    );
    // The same from a configuration file.
    let cfg = tmp("near_t.json");
    std::fs::write(&cfg, r#"{"tjunction_tolerance": 0.001}"#).unwrap();
    let r = repair_json(&m, "near_t", &["--config", cfg.to_str().unwrap()]);
    assert_eq!(r["after"]["boundary_edges"], 6);
}

#[test]
fn repair_remove_overlapping_removes_near_copies_and_near_double_walls() {
    // A closed unit cube and a copy of its top face lifted by 1e-4, facing up too: the
    // copy goes (the first of each pair stays), the cube is closed.
    let (mut positions, mut triangles) = meshbool::Mesh::unit_cube().into_parts();
    let top: Vec<[u32; 3]> = triangles
        .iter()
        .filter(|t| t.iter().all(|&v| positions[v as usize][2] == 1.0))
        .copied()
        .collect();
    assert_eq!(top.len(), 2);
    for t in top {
        for v in t {
            let [x, y, _] = positions[v as usize];
            positions.push([x, y, 1.0001]);
        }
        let n = positions.len() as u32;
        triangles.push([n - 3, n - 2, n - 1]);
    }
    let m = meshbool::Mesh::new(positions, triangles).unwrap();
    let r = repair_json(&m, "near_copy", &["--remove-overlapping", "1e-3"]);
    let d = &r["duplicates"];
    assert_eq!(
        (&d["same_orientation_removed"], &d["anti_parallel_removed"]),
        (&2.into(), &0.into())
    );
    assert_eq!(d["largest_distance"], 1.0001 - 1.0);
    let a = &r["after"];
    assert_eq!(
        (
            &a["triangles"],
            &a["boundary_edges"],
            &a["closed"],
            &a["volume"]
        ),
        (&12.into(), &0.into(), &true.into(), &1.0.into())
    );
    // Exactly, nothing is a copy: the sheet stays, its four edges open.
    let r = repair_json(&m, "near_copy", &["--remove-duplicates"]);
    assert_eq!(r["duplicates"]["same_orientation_removed"], 0);
    assert_eq!(r["after"]["boundary_edges"], 4);

    // The near double wall between two stacked boxes: both walls go, and the boundary
    // weld (after the duplicates step) closes the cut: the unit cube.
    let m = stacked_boxes();
    let flags = ["--remove-overlapping", "1e-3", "--weld-boundary", "1e-3"];
    let r = repair_json(&m, "double_wall", &flags);
    assert_eq!(r["duplicates"]["anti_parallel_removed"], 4);
    assert_eq!(r["weld_boundary"]["merged_vertices"], 4);
    let a = &r["after"];
    assert_eq!(
        (
            &a["triangles"],
            &a["boundary_edges"],
            &a["closed"],
            &a["volume"]
        ),
        (&20.into(), &0.into(), &true.into(), &1.0.into())
    );
    // Exactly: the walls are 1e-4 apart, not removed; two closed boxes.
    let r = repair_json(&m, "double_wall", &["--remove-duplicates"]);
    assert_eq!(r["duplicates"]["anti_parallel_removed"], 0);
    let a = &r["after"];
    assert_eq!((&a["triangles"], &a["closed"]), (&24.into(), &true.into()));
    assert!((a["volume"].as_f64().unwrap() - 0.9999).abs() < 1e-12);
}

#[test]
fn repair_weld_boundary_closes_two_open_halves_and_keeps_interior_vertices() {
    // The unit cube cut at z = 0.5 into two open boxes, the upper one lifted by 1e-4.
    // The lower one's bottom is fanned around two interior vertices 5e-4 apart.
    let low = open_box(0.0, 0.5, true);
    let (mut positions, triangles) = low.into_parts();
    let corner = |p: [f64; 3]| positions.iter().position(|q| *q == p).unwrap() as u32;
    let c = [
        corner([0.0, 0.0, 0.0]),
        corner([1.0, 0.0, 0.0]),
        corner([1.0, 1.0, 0.0]),
        corner([0.0, 1.0, 0.0]),
    ];
    let mut triangles: Vec<[u32; 3]> = triangles
        .into_iter()
        .filter(|t| t.iter().any(|&v| positions[v as usize][2] != 0.0))
        .collect();
    let (p, q) = (positions.len() as u32, positions.len() as u32 + 1);
    positions.extend([[0.5, 0.5, 0.0], [0.5005, 0.5, 0.0]]);
    // Facing down: the fan of the square c0 c1 c2 c3 around p (left) and q (right).
    triangles.extend([
        [c[0], q, c[1]],
        [c[1], q, c[2]],
        [c[2], p, c[3]],
        [c[3], p, c[0]],
        [c[0], p, q],
        [q, p, c[2]],
    ]);
    let mut m = meshbool::Mesh::new(positions, triangles).unwrap();
    m.append(&open_box(0.5001, 1.0, false)).unwrap();
    let r = repair_json(&m, "halves", &["--weld-boundary", "1e-3"]);
    assert_eq!(r["before"]["boundary_edges"], 8);
    assert_eq!(r["weld_boundary"]["merged_vertices"], 4);
    assert_eq!(r["weld_boundary"]["collapsed_triangles"], 0);
    let a = &r["after"];
    assert_eq!(
        (
            &a["boundary_edges"],
            &a["inconsistent_edges"],
            &a["closed"],
            &a["volume"]
        ),
        (&0.into(), &0.into(), &true.into(), &1.0.into())
    );
    // The interior pair is as close as the rims but stays two vertices: the cube's 8
    // corners, the 4 of the cut, the 2 interior ones.
    assert_eq!(a["vertices"], 14);
    let (fixed, _) = meshbool::ops::read(tmp("halves_fixed.obj"), None).unwrap();
    assert!(fixed.positions().contains(&[0.5, 0.5, 0.0]));
    assert!(fixed.positions().contains(&[0.5005, 0.5, 0.0]));
    // A weld of every vertex takes the pair as well (its two triangles between them go).
    let r = repair_json(&m, "halves", &["--weld", "1e-3"]);
    assert_eq!(r["weld"]["merged_vertices"], 5);
    assert_eq!(r["weld"]["collapsed_triangles"], 2);
    // Below the gap: nothing merges, the cut stays open.
    let r = repair_json(&m, "halves", &["--weld-boundary", "1e-5"]);
    assert_eq!(r["after"]["boundary_edges"], 8);
}

#[test]
fn repair_refuses_negative_and_non_finite_distances() {
    let cube = write_cube("bad_d.obj", [0.0; 3], [1.0; 3]);
    let out = tmp("bad_d_out.obj");
    let cfg = tmp("bad_d.json");
    std::fs::write(&cfg, r#"{"weld_boundary": -2}"#).unwrap();
    for (flags, says) in [
        (
            &["--tjunctions=-1"][..],
            "tjunction_tolerance must be a finite distance >= 0, got -1",
        ),
        (
            &["--tjunctions", "-0.001"],
            "tjunction_tolerance must be a finite distance >= 0",
        ),
        (
            &["--tjunctions", "inf"],
            "tjunction_tolerance must be a finite distance >= 0, got inf",
        ),
        (
            &["--remove-overlapping", "nan"],
            "remove_overlapping must be a finite distance >= 0, got NaN",
        ),
        (
            &["--remove-overlapping=-0.5"],
            "remove_overlapping must be a finite distance >= 0",
        ),
        (
            &["--weld-boundary", "-1"],
            "weld_boundary must be a finite distance >= 0, got -1",
        ),
        (
            &["--config", cfg.to_str().unwrap()],
            "weld_boundary must be a finite distance >= 0, got -2",
        ),
    ] {
        let mut args = vec![
            "repair",
            cube.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ];
        args.extend(flags);
        let r = meshbool(&args);
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(2), "{flags:?}: {err}");
        assert!(err.contains(says), "{flags:?}: {err}");
        assert!(!out.exists(), "{flags:?} wrote a file");
    }
}

#[test]
fn close_stitch_joins_two_open_boxes_into_one_cuboid() {
    let mut m = open_box(0.0, 1.0, true);
    m.append(&open_box(2.0, 3.0, false)).unwrap();
    let input = tmp("two_boxes.obj");
    meshbool::io::write_path(&input, &m).unwrap();
    let out = tmp("stitched.obj");
    let r = report(&[
        "close",
        input.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--mode",
        "stitch",
        "--json",
    ]);
    assert_eq!(r["stitch"]["pairs"], 1);
    assert_eq!(r["stitch"]["triangles_added"], 8);
    assert_eq!(r["stitch"]["largest_gap"], 1.0);
    assert_eq!(r["closed"], true);
    assert_eq!(r["volume"], 3.0);
    let info = report(&["info", "--json", out.to_str().unwrap()]);
    assert_eq!(info["inconsistent_edges"], 0);
    // Too far apart for the limit: nothing stitched, still open.
    let r = report(&[
        "close",
        input.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--mode",
        "stitch",
        "--max-gap",
        "0.5",
        "--json",
    ]);
    assert_eq!(r["stitch"]["unpaired_loops"], 2);
    assert_eq!(r["closed"], false);
}

#[test]
fn repair_pipeline_orients_and_curtains_the_terrain() {
    let Some(terrain) = shared_data("kap_terrain.obj") else {
        return;
    };
    let out = tmp("terrain_solid.ply");
    let r = report(&[
        "repair",
        terrain.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--z-up",
        "--remove-folds",
        "--remove-degenerate",
        "--close",
        "curtain",
        "--floor-offset",
        "10",
        "--json",
    ]);
    assert_eq!(r["before"]["inconsistent_edges"], 46);
    assert_eq!(r["orient"]["flipped"], 22);
    // The 22 turned down by orientation are folds: 16 vertices out, every triangle up.
    assert_eq!(r["folds"]["vertices_removed"], 16);
    assert_eq!(r["folds"]["left"], 0);
    assert_eq!(r["degenerate"]["found"], 0);
    assert_eq!(r["curtain"], serde_json::Value::Null);
    assert_eq!(r["close"]["curtain"]["wall_triangles"], 1120);
    let a = &r["after"];
    assert_eq!(
        (
            &a["boundary_edges"],
            &a["non_manifold_edges"],
            &a["inconsistent_edges"],
            &a["closed"]
        ),
        (&0.into(), &0.into(), &0.into(), &true.into())
    );
    let floor = r["close"]["curtain"]["floor_triangles"].as_u64().unwrap();
    assert_eq!(a["triangles"], 11200 - 102 + 70 + 1120 + floor);
    assert!(a["volume"].as_f64().unwrap() > 0.0);
}

#[test]
fn repair_config_file_with_flags_overriding() {
    // A box missing its top, with a duplicated triangle: the config asks for duplicate
    // removal, outward orientation and capping; a flag adds an exact weld.
    let (positions, mut triangles) = open_box(0.0, 1.0, true).into_parts();
    triangles.push(triangles[0]);
    let m = meshbool::Mesh::new(positions, triangles).unwrap();
    let input = tmp("cfg_in.obj");
    meshbool::io::write_path(&input, &m).unwrap();
    let cfg = tmp("repair.json");
    std::fs::write(
        &cfg,
        r#"{"remove_duplicates": true, "close": "cap", "orient": "outward"}"#,
    )
    .unwrap();
    let out = tmp("cfg_out.obj");
    let r = report(&[
        "repair",
        input.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--config",
        cfg.to_str().unwrap(),
        "--weld",
        "0",
        "--json",
    ]);
    assert_eq!(r["duplicates"]["same_orientation_removed"], 1);
    assert_eq!(r["weld"]["merged_vertices"], 0);
    assert_eq!(r["close"]["cap"]["capped"], 1);
    assert_eq!(r["after"]["volume"], 1.0);
    assert_eq!(r["after"]["closed"], true);
    // A misspelt field is an error naming the file, exit 1.
    std::fs::write(&cfg, r#"{"remove_duplicate": true}"#).unwrap();
    let bad = meshbool(&[
        "repair",
        input.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--config",
        cfg.to_str().unwrap(),
    ]);
    assert_eq!(bad.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("repair.json"));
    // A negative distance is refused.
    let bad = meshbool(&[
        "repair",
        input.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--weld=-1",
    ]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("weld"));
}

#[test]
fn snap_cleans_needles_and_refuses_bad_tolerances() {
    // The unit cube less a box a millimetre larger than its corner part: the exact
    // difference has needles a millimetre wide along the cut.
    let a = write_cube("snap_a.obj", [0.0; 3], [1.0; 3]);
    let b = write_cube("snap_b.obj", [0.5, -0.001, 0.5], [1.001, 1.001, 1.001]);
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
    let (exact, zero, snapped) = (
        tmp("snap_exact.obj"),
        tmp("snap_zero.obj"),
        tmp("snap_d.obj"),
    );
    let r = report(&["difference", a, b, "-o", exact.to_str().unwrap(), "--json"]);
    assert!(r.get("snap").is_none());
    let r0 = report(&[
        "difference",
        a,
        b,
        "-o",
        zero.to_str().unwrap(),
        "--snap",
        "0",
        "--json",
    ]);
    assert!(r0.get("snap").is_none());
    assert_eq!(
        std::fs::read(&exact).unwrap(),
        std::fs::read(&zero).unwrap()
    );
    let r = report(&[
        "difference",
        a,
        b,
        "-o",
        snapped.to_str().unwrap(),
        "--snap",
        "0.01",
        "--json",
    ]);
    assert_eq!(r["closed"], true);
    // The exact clean-up already took the straight seam points (the fewest triangles an
    // L-shaped prism can have: 2 × 4 + 6 × 2), so snapping finds nothing left to do.
    assert_eq!(r["triangles"], 20);
    assert_eq!(r["volume"], 0.75);
    assert_eq!(r["cleanup"]["removed_points"], 6);
    assert_eq!(r["snap"]["tolerance"], 0.01);
    assert_eq!(r["snap"]["left"], 0);
    assert_eq!(r["snap"]["found"], 0);
    // On the arrangement as it is, snapping collapses the needles itself.
    let raw = report(&[
        "difference",
        a,
        b,
        "-o",
        snapped.to_str().unwrap(),
        "--snap",
        "0.01",
        "--keep-seam-points",
        "--json",
    ]);
    assert_eq!(raw["closed"], true);
    assert_eq!(raw["triangles"], 24);
    assert_eq!(raw["volume"], 0.75);
    assert_eq!(raw["cleanup"]["removed_points"], 0);
    assert_eq!(raw["snap"]["left"], 0);
    assert!(raw["snap"]["collapsed"].as_u64().unwrap() > 0);
    // The written mesh: no edge shorter than the tolerance.
    let m = meshbool::io::read_path(&snapped).unwrap();
    let p = m.positions();
    for t in m.triangles() {
        for k in 0..3 {
            let (u, v) = (p[t[k] as usize], p[t[(k + 1) % 3] as usize]);
            let d = ((u[0] - v[0]).powi(2) + (u[1] - v[1]).powi(2) + (u[2] - v[2]).powi(2)).sqrt();
            assert!(d >= 0.01, "edge of {d}");
        }
    }
    // The exact result snapped by `repair --snap`, and `resolve --snap`.
    let rep = report(&[
        "repair",
        exact.to_str().unwrap(),
        "-o",
        tmp("snap_rep.obj").to_str().unwrap(),
        "--snap",
        "0.01",
        "--json",
    ]);
    assert_eq!(rep["snap"]["left"], 0);
    assert_eq!(rep["after"]["closed"], true);
    let res = report(&[
        "resolve",
        exact.to_str().unwrap(),
        "-o",
        tmp("snap_res.obj").to_str().unwrap(),
        "--snap",
        "0.01",
        "--json",
    ]);
    assert_eq!(res["snap"]["left"], 0);
    // Not a distance: a usage error, before any work.
    for bad in ["-1", "nan", "inf", "x", "1,2"] {
        for cmd in [
            vec!["difference", a, b, "-o", "never.obj", "--snap", bad],
            vec!["union", a, b, a, "-o", "never.obj", "--snap", bad],
            vec!["resolve", a, "-o", "never.obj", "--snap", bad],
            vec!["repair", a, "-o", "never.obj", "--snap", bad],
            vec!["split", a, b, "-o", "never_dir", "--snap", bad],
            vec![
                "pick",
                "never_dir",
                "--op",
                "union",
                "-o",
                "never.obj",
                "--snap",
                bad,
            ],
        ] {
            let out = meshbool(&cmd);
            let err = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{cmd:?}: {err}");
            assert!(err.contains("--snap"), "{cmd:?}: {err}");
        }
    }
    assert!(!std::path::Path::new("never.obj").exists());
    assert!(!std::path::Path::new("never_dir").exists());
}

#[test]
fn resolve_envelope_of_a_terrain_keeps_its_outline() {
    // A generated terrain has no folds: its envelopes are itself. The real one folds over
    // itself in one place: 22 triangles under (over) another sheet.
    let terrain = terrain(O);
    let mut cases = vec![(terrain.clone(), 0, 240)];
    cases.extend(shared_data("kirra_terrain.obj").map(|t| (t, 22, 560)));
    for ((input, folded, boundary), side) in cases
        .iter()
        .flat_map(|c| ["upper", "lower"].map(|side| (c, side)))
    {
        let out_path = tmp(&format!("envelope_{side}_{folded}.ply"));
        let out = meshbool(&[
            "resolve",
            input.to_str().unwrap(),
            "--envelope",
            side,
            "-o",
            out_path.to_str().unwrap(),
            "--json",
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(v["envelope"]["side"], side);
        assert_eq!(v["envelope"]["folded_triangles"], *folded);
        assert_eq!(v["envelope"]["hidden_triangles"], *folded);
        assert_eq!(v["boundary_edges"], *boundary);
        assert_eq!(v["non_manifold_edges"], 0);
        // Written as reported, and no longer folded: every edge consistent.
        let info = meshbool(&["info", "--json", out_path.to_str().unwrap()]);
        let w: serde_json::Value = serde_json::from_slice(&info.stdout).unwrap();
        assert_eq!(w["triangles"], v["triangles"]);
        assert_eq!(w["inconsistent_edges"], 0);
    }
    // A fill rule, keeping non-manifold edges or snapping mean nothing for an envelope: a
    // usage error before any work (snapping was once accepted and ignored: its conflict
    // named an argument id that does not exist, which clap checks only in debug builds).
    for extra in [
        &["--rule", "evenodd"][..],
        &["--keep-nonmanifold"],
        &["--snap", "0.1"],
    ] {
        let never = tmp("never.ply");
        let _ = std::fs::remove_file(&never);
        let mut args = vec![
            "resolve",
            terrain.to_str().unwrap(),
            "--envelope",
            "upper",
            "-o",
            never.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let out = meshbool(&args);
        assert_eq!(out.status.code(), Some(2), "{extra:?}");
        assert!(
            String::from_utf8_lossy(&out.stderr).contains("cannot be used with"),
            "{extra:?}"
        );
        assert!(!never.exists(), "{extra:?}");
    }
    // A closed mesh: a clear error.
    let out = meshbool(&[
        "resolve",
        drill(O).to_str().unwrap(),
        "--envelope",
        "lower",
        "-o",
        tmp("never.ply").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("closed"));
}
