//! The booleans (`union`, `intersection`, `difference`): volumes, many inputs, timings, the
//! door's checks and refusals, reports, cancellation, thread counts, usage errors.

use std::process::Command;

use crate::common::*;

#[test]
fn usage_errors_exit_2() {
    assert_eq!(meshbool(&["info"]).status.code(), Some(2));
    assert_eq!(
        meshbool(&["convert", "a.obj", "b.obj", "--to", "gltf"])
            .status
            .code(),
        Some(2)
    );
    assert_eq!(meshbool(&["frobnicate"]).status.code(), Some(2));
}

#[test]
fn boolean_commands_give_exact_cube_volumes() {
    let a = write_cube("ba.stl", [0.0; 3], [1.0; 3]);
    let b = write_cube("bb.obj", [0.5, 0.0, 0.0], [1.5, 1.0, 1.0]);
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
    let out = tmp("r.ply");
    let out = out.to_str().unwrap();
    for (cmd, extra, vol) in [
        ("union", None, 1.5),
        ("intersection", None, 0.5),
        ("intersect", None, 0.5),
        ("difference", None, 0.5),
        ("subtract", Some("--reverse"), 0.5),
    ] {
        let mut args = vec![cmd, a, b, "-o", out, "--json"];
        args.extend(extra);
        let r = report(&args);
        assert_eq!(r["volume"], vol, "{cmd}");
        assert_eq!(r["boundary_edges"], 0, "{cmd}");
        assert_eq!(r["closed"], true, "{cmd}");
        let info = report(&["info", "--json", out]);
        assert_eq!(info["volume"], vol, "{cmd}");
    }
}

/// Two 24-sided prisms on one base, the second turned by half a side, caps fanned from a
/// corner: the caps overlap in a regular 48-gon of inradius cos(π/24) where every fan
/// triangle of one crosses many of the other's. With `--coplanar-refinement` the shared
/// caps are cut along both fans (more triangles), the same closed solid either way;
/// `split` and `curves` take the flag too.
#[test]
fn coplanar_refinement_cuts_shared_caps_along_both_fans() {
    let n = 24;
    let a = fanned_prism("fanned_a.obj", n, 0.0);
    let b = fanned_prism("fanned_b.obj", n, std::f64::consts::PI / n as f64);
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
    let out = tmp("refined.ply");
    let out = out.to_str().unwrap();
    let r_in = (std::f64::consts::PI / n as f64).cos();
    let want = 2.0 * n as f64 * r_in * r_in * (std::f64::consts::PI / (2 * n) as f64).tan();
    let boolean = |extra: &[&str]| {
        let r = report(&[&["intersection", a, b, "-o", out, "--json"], extra].concat());
        assert_eq!(
            (r["closed"].clone(), r["boundary_edges"].clone()),
            (true.into(), 0.into())
        );
        assert_eq!(r["non_manifold_edges"], 0);
        let v = r["volume"].as_f64().unwrap();
        assert!((v - want).abs() < 1e-12, "{v} {want}");
        r["triangles"].as_u64().unwrap()
    };
    let lean = boolean(&["--keep-seam-points"]);
    let refined = boolean(&["--keep-seam-points", "--coplanar-refinement"]);
    assert!(refined > 2 * lean, "{refined} {lean}");
    assert!(boolean(&["--coplanar-refinement"]) < refined);
    let same = |dir: &str, extra: &[&str]| {
        let d = tmp(dir);
        let m = report(
            &[
                &[
                    "split",
                    a,
                    b,
                    "-o",
                    d.to_str().unwrap(),
                    "--overwrite",
                    "--json",
                ],
                extra,
            ]
            .concat(),
        );
        let group = m["groups"]
            .as_array()
            .unwrap()
            .iter()
            .find(|g| g["name"] == "a_on_b_same")
            .cloned()
            .unwrap();
        group["triangles"].as_u64().unwrap()
    };
    let split_lean = same("split_lean", &["--keep-seam-points"]);
    let split_refined = same(
        "split_refined",
        &["--keep-seam-points", "--coplanar-refinement"],
    );
    assert!(
        split_refined > 2 * split_lean && split_lean > 0,
        "{split_refined} {split_lean}"
    );
    let segments = |extra: &[&str]| {
        let r = report(&[&["curves", a, b, "--json", "--tagged"], extra].concat());
        r["tagged_segments"].as_array().unwrap().len()
    };
    assert!(segments(&["--coplanar-refinement"]) > 2 * segments(&[]));
}

/// Three boxes (two sharing a face, a third crossing both), united and intersected by
/// the pairwise tree and with `--one-arrangement`: the same exact volumes, closed, and the
/// report's `combined` naming the route; two inputs have no `combined`.
#[test]
fn many_inputs_in_one_arrangement_or_the_tree() {
    let a = write_cube("m1.stl", [0.0; 3], [1.0; 3]);
    let b = write_cube("m2.stl", [1.0, 0.0, 0.0], [2.0, 1.0, 1.0]);
    let c = write_cube("m3.obj", [0.5, 0.25, 0.5], [1.5, 0.75, 1.5]);
    let (a, b, c) = (
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        c.to_str().unwrap(),
    );
    let out = tmp("many.ply");
    let out = out.to_str().unwrap();
    for (cmd, vol) in [("union", 2.25), ("intersection", 0.0625)] {
        let c2 = write_cube("m4.stl", [0.75, 0.0, 0.0], [1.25, 1.0, 1.0]);
        let c2 = c2.to_str().unwrap();
        let inputs = if cmd == "union" {
            [a, b, c]
        } else {
            [a, c2, c]
        };
        for (flag, combined) in [
            (None, "pairwise_tree"),
            (Some("--one-arrangement"), "one_arrangement"),
        ] {
            let mut args = vec![cmd];
            args.extend(inputs);
            args.extend(["-o", out, "--json"]);
            args.extend(flag);
            let r = report(&args);
            assert_eq!(r["volume"], vol, "{cmd} {flag:?}");
            assert_eq!(r["closed"], true, "{cmd} {flag:?}");
            assert_eq!(r["combined"], combined, "{cmd} {flag:?}");
        }
    }
    let r = report(&["union", a, b, "-o", out, "--json", "--one-arrangement"]);
    assert_eq!((r["volume"].as_f64(), r.get("combined")), (Some(2.0), None));
}

#[test]
fn timings_name_every_stage_and_add_up() {
    let a = write_cube("ta.stl", [0.0; 3], [1.0; 3]);
    let b = write_cube("tb.stl", [0.5, 0.25, 0.0], [1.5, 1.0, 1.0]);
    let out = tmp("timed.stl");
    let r = meshbool(&[
        "union",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--timings",
    ]);
    assert!(r.status.success());
    let err = String::from_utf8_lossy(&r.stderr);
    // "   0.001 s  stage", one line per stage shown, then the whole.
    let lines: Vec<(f64, &str)> = err
        .lines()
        .filter_map(|l| {
            let (secs, stage) = l.trim_start().split_once(" s  ")?;
            Some((secs.parse().ok()?, stage))
        })
        .collect();
    let stages: Vec<&str> = lines.iter().map(|l| l.1).collect();
    assert_eq!(
        stages,
        [
            "reading the inputs, checking for self-intersections",
            "intersecting",
            "cutting along the seam",
            "classifying inside/outside",
            "merging the result",
            "writing",
            "in all"
        ],
        "{err}"
    );
    let parts: f64 = lines[..lines.len() - 1].iter().map(|l| l.0).sum();
    let all = lines[lines.len() - 1].0;
    assert!((parts - all).abs() <= 0.004 && all > 0.0, "{err}");
    // Without the flag, no timings.
    let plain = meshbool(&[
        "union",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(!String::from_utf8_lossy(&plain.stderr).contains(" s  in all"));
}

#[test]
fn boolean_orients_inconsistent_input_or_refuses_it_with_no_orient() {
    let (t, c) = (wound_terrain(O), drill(O));
    let out = tmp("forced.ply");
    let args = [
        "difference",
        t.to_str().unwrap(),
        c.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ];
    // Oriented at the door by default, with a line in `assumed`.
    let v = report(&[&args[..], &["--json"]].concat());
    assert_eq!(v["operands"][0]["reoriented_triangles"], 5);
    let assumed = v["assumed"].as_array().unwrap();
    assert_eq!(assumed.len(), 1);
    assert!(assumed[0].as_str().unwrap().contains("made consistent"));
    // Refused with --no-orient, taken as given with --force.
    let strict = [&args[..], &["--no-orient"]].concat();
    let r = meshbool(&strict);
    assert_eq!(r.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&r.stderr).contains("15 inconsistently oriented edges"));
    let mut forced = strict.to_vec();
    forced.extend(["--force", "--json"]);
    let v = report(&forced);
    assert_eq!(v["boundary_edges"], 240);
    assert_eq!(v["assumed"].as_array().unwrap().len(), 1);
}

#[test]
fn oriented_terrain_needs_no_force() {
    let oriented = tmp("oriented.ply");
    let r = report(&[
        "orient",
        wound_terrain(UTM).to_str().unwrap(),
        "-o",
        oriented.to_str().unwrap(),
        "--z-up",
        "--json",
    ]);
    assert_eq!(r["flipped"], 5);
    assert_eq!(r["conflicting_edges"], 0);
    let info = report(&["info", "--json", oriented.to_str().unwrap()]);
    assert_eq!(info["inconsistent_edges"], 0);
    assert_eq!(info["boundary_edges"], 240);
    let out = tmp("mined.ply");
    let v = report(&[
        "difference",
        oriented.to_str().unwrap(),
        drill(UTM).to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(v["boundary_edges"], 240);
    assert_eq!(v["assumed"].as_array().unwrap().len(), 0);
}

#[test]
fn self_intersecting_input_is_refused_with_a_location() {
    // A cube with a corner pushed through its bottom and a side triangle taken out (it
    // crosses itself and is open), with a closed box through it in the same file: the
    // box's inside is cut by the open part, so it cannot be resolved.
    let (mut positions, mut triangles) = meshbool::Mesh::unit_cube().into_parts();
    for p in &mut positions {
        if *p == [1.0; 3] {
            *p = [0.5, 0.5, -0.5];
        }
    }
    let side = triangles
        .iter()
        .position(|t| t.iter().all(|&v| positions[v as usize][0] == 0.0))
        .unwrap();
    triangles.remove(side);
    let open = meshbool::Mesh::new(positions, triangles).unwrap();
    let mut m = open.clone();
    m.append(&meshbool::Mesh::cuboid([0.25; 3], [0.75, 0.75, 1.5]))
        .unwrap();
    let bad = tmp("selfx.ply");
    meshbool::io::write_path(&bad, &m).unwrap();
    let c = write_cube("selfx_b.ply", [2.0; 3], [3.0; 3]);
    let out = tmp("selfx_out.ply");
    let union = |a: &std::path::Path| {
        meshbool(&[
            "union",
            a.to_str().unwrap(),
            c.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ])
    };
    // The open surface alone crossing itself is taken as given, with a warning.
    let alone = tmp("selfx_open.ply");
    meshbool::io::write_path(&alone, &open).unwrap();
    let r = union(&alone);
    assert_eq!(r.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&r.stderr).contains("of its open parts"));
    let r = union(&bad);
    assert_eq!(r.status.code(), Some(1));
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(
        err.contains("self-intersecting triangle pairs")
            && err.contains("near")
            && err.contains("cannot be resolved"),
        "{err}"
    );
}

#[test]
fn json_output_is_exactly_the_library_report() {
    use meshbool::ops::{self, Checks, Operand};
    let a = write_cube("ja.ply", [0.0; 3], [1.0; 3]);
    let b = write_cube("jb.obj", [0.5, 0.25, -0.5], [1.5, 0.75, 0.5]);
    let (sa, sb) = (a.to_str().unwrap(), b.to_str().unwrap());
    let out = tmp("j_out.ply");
    let so = out.to_str().unwrap();
    let (oa, ob) = Operand::read_pair(&a, &b, &Checks::default()).unwrap();

    let lib = ops::boolean(&oa, &ob, meshbool::Op::Difference, &Default::default()).unwrap();
    let cli = report(&["difference", sa, sb, "-o", so, "--json"]);
    assert_eq!(untimed(cli), json(&lib.report()));

    let dir = tmp("j_split");
    let split = ops::split(&oa, &ob, &Default::default()).unwrap();
    let cli = report(&["split", sa, sb, "-o", dir.to_str().unwrap(), "--json"]);
    assert_eq!(cli, json(&split.report(meshbool::Format::PlyBinaryLe)));
    let manifest: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("manifest.json")).unwrap()).unwrap();
    assert_eq!(manifest, cli);

    let keep = ["a_out_b".parse().unwrap(), "b_in_a:flip".parse().unwrap()];
    let cli = report(&[
        "pick",
        dir.to_str().unwrap(),
        "--keep",
        "a_out_b",
        "--keep",
        "b_in_a:flip",
        "-o",
        so,
        "--json",
    ]);
    assert_eq!(
        cli,
        json(&split.pick(&keep, &Default::default()).unwrap().report())
    );

    let curves = ops::curves(&oa, &ob, &Default::default()).unwrap();
    let cli = report(&["curves", sa, sb, "--json"]);
    assert_eq!(untimed(cli), json(&curves.report()));

    let mesh = ops::read(&a, None).unwrap().0;
    let cli = report(&["info", sa, "--json"]);
    assert_eq!(
        cli,
        json(&ops::InfoReport::new(sa, ops::info(&mesh).unwrap()))
    );
    let facing = meshbool::repair::Facing::Outward;
    let cli = report(&["orient", sa, "-o", so, "--outward", "--json"]);
    assert_eq!(cli, json(&ops::orient(&mesh, facing).unwrap().report()));
    let mode = meshbool::repair::CloseMode::Cap;
    let cli = report(&["close", sa, "-o", so, "--json"]);
    assert_eq!(
        cli,
        json(
            &ops::close(&mesh, mode, &Default::default())
                .unwrap()
                .report()
        )
    );
    let cli = report(&["repair", sa, "-o", so, "--json"]);
    assert_eq!(
        cli,
        json(&ops::repair(&mesh, &Default::default()).unwrap().report())
    );
}

#[test]
fn overlapping_parts_are_resolved_alone_and_as_operands() {
    // Two overlapping cubes in one file: their union, 2 - 1/8.
    let mut m = meshbool::Mesh::unit_cube();
    m.append(&meshbool::Mesh::cuboid([0.5; 3], [1.5; 3]))
        .unwrap();
    let two = tmp("two_cubes.ply");
    meshbool::io::write_path(&two, &m).unwrap();
    let out = tmp("two_cubes_resolved.obj");
    let v = report(&[
        "resolve",
        two.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(
        (v["volume"].as_f64(), v["closed"].as_bool()),
        (Some(1.875), Some(true))
    );
    assert_eq!(v["rule"], "positive");
    assert_eq!(v["resolve"]["united_components"], 2);
    let written = meshbool::io::read_path(&out).unwrap();
    assert_eq!(meshbool::measure::signed_volume(&written), 1.875);
    // As an operand of a union with a cube that touches nothing: 1.875 + 1.
    let far = write_cube("far_cube.ply", [3.0; 3], [4.0; 3]);
    let union_out = tmp("two_cubes_union.ply");
    let args = [
        "union",
        two.to_str().unwrap(),
        far.to_str().unwrap(),
        "-o",
        union_out.to_str().unwrap(),
        "--json",
    ];
    let v = report(&args);
    assert_eq!(
        (v["volume"].as_f64(), v["closed"].as_bool()),
        (Some(2.875), Some(true))
    );
    assert_eq!(v["operands"][0]["resolved"]["components"], 2);
    assert_eq!(v["operands"][1]["resolved"], serde_json::Value::Null);
    // --no-resolve refuses it as before.
    let r = meshbool(&[&args[..], &["--no-resolve"]].concat());
    assert_eq!(r.status.code(), Some(1));
    // An unknown rule is a usage error.
    let r = meshbool(&[
        "resolve",
        two.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--rule",
        "odd",
    ]);
    assert_eq!(r.status.code(), Some(2));
}

#[test]
fn union_and_intersection_take_more_than_two_inputs() {
    let a = write_cube("many_a.ply", [0.0; 3], [2.0; 3]);
    let b = write_cube("many_b.ply", [1.0; 3], [3.0; 3]);
    let c = write_cube("many_c.ply", [1.5, 1.5, -1.0], [2.5, 2.5, 4.0]);
    let out = tmp("many_out.ply");
    let run = |op: &str| {
        report(&[
            op,
            a.to_str().unwrap(),
            b.to_str().unwrap(),
            c.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--json",
        ])
    };
    // 8 + 8 + 5 - 1 (A∩B) - 0.5 (C∩A) - 2 (C∩B) + 0.25 (A∩B∩C) = 17.75
    let v = run("union");
    assert_eq!(
        (v["volume"].as_f64(), v["closed"].as_bool()),
        (Some(17.75), Some(true))
    );
    assert_eq!(v["operands"].as_array().unwrap().len(), 3);
    let v = run("intersection");
    assert_eq!(v["volume"].as_f64(), Some(0.25));
    let written = meshbool::io::read_path(&out).unwrap();
    assert_eq!(meshbool::measure::signed_volume(&written), 0.25);
    // A difference of three: A less B and C (8 - 1 - 0.5 + 0.25; more in cli_rules.rs).
    let v = run("difference");
    assert_eq!(v["volume"].as_f64(), Some(6.75));
}

#[test]
fn cube_minus_made_cylinder_is_closed_with_the_expected_volume() {
    let cube = tmp("mk_cube.obj");
    let cyl = tmp("mk_cyl.ply");
    let out = tmp("mk_drilled.ply");
    let (sc, sy, so) = (
        cube.to_str().unwrap(),
        cyl.to_str().unwrap(),
        out.to_str().unwrap(),
    );
    report(&["make", "cube", "--size", "2", "-o", sc, "--json"]);
    let c = report(&[
        "make",
        "cylinder",
        "--radius",
        "0.5",
        "--height",
        "4",
        "--base",
        "0,0,-2",
        "--segments",
        "48",
        "-o",
        sy,
        "--json",
    ]);
    assert_eq!(
        (c["triangles"].as_u64(), c["closed"].as_bool()),
        (Some(192), Some(true))
    );
    let (n, r) = (48.0, 0.5);
    let prism_area = n / 2.0 * (2.0 * std::f64::consts::PI / n).sin() * r * r;
    let cyl_volume = c["volume"].as_f64().unwrap();
    assert!((cyl_volume - 4.0 * prism_area).abs() < 1e-13);
    // The cylinder goes right through: the hole is its cross-section times the cube's height.
    let d = report(&["difference", sc, sy, "-o", so, "--json"]);
    assert_eq!(
        (d["closed"].as_bool(), d["boundary_edges"].as_u64()),
        (Some(true), Some(0))
    );
    let want = 8.0 - cyl_volume / 4.0 * 2.0;
    assert!((d["volume"].as_f64().unwrap() - want).abs() < 1e-12, "{d}");
    let info = report(&["info", so, "--json"]);
    assert_eq!(
        (
            info["inconsistent_edges"].as_u64(),
            info["components"].as_u64()
        ),
        (Some(0), Some(1))
    );
}

#[test]
fn thresholds_that_would_empty_or_overflow_a_mesh_are_refused() {
    let (cyl, terrain) = (drill(O), terrain(O));
    let out = tmp("refused.ply");
    let o = out.to_str().unwrap();
    for (args, says) in [
        (
            vec![
                "repair",
                cyl.to_str().unwrap(),
                "-o",
                o,
                "--remove-degenerate",
                "--max-aspect=-5",
            ],
            "maximum aspect",
        ),
        (
            vec![
                "repair",
                cyl.to_str().unwrap(),
                "-o",
                o,
                "--remove-degenerate",
                "--max-aspect=0",
            ],
            "maximum aspect",
        ),
        (
            vec![
                "repair",
                cyl.to_str().unwrap(),
                "-o",
                o,
                "--remove-degenerate",
                "--min-area=inf",
            ],
            "minimum area",
        ),
        (
            vec!["repair", cyl.to_str().unwrap(), "-o", o, "--weld", "-1"],
            "weld must be",
        ),
        (
            vec![
                "close",
                terrain.to_str().unwrap(),
                "-o",
                o,
                "--mode",
                "curtain",
                "--floor-offset",
                "1e308",
            ],
            "too large",
        ),
    ] {
        let r = meshbool(&args);
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(!out.exists(), "{args:?} wrote a file");
    }
}

/// Ctrl-C (SIGINT) during a long boolean: the command stops at the library's next stage,
/// says so, exits 130 and writes nothing (neither the output nor a temporary file).
#[cfg(unix)]
#[test]
fn ctrl_c_cancels_a_boolean_and_writes_nothing() {
    let dir = tmp("ctrl-c");
    std::fs::create_dir_all(&dir).unwrap();
    let (a, b, out) = (dir.join("a.ply"), dir.join("b.ply"), dir.join("union.ply"));
    for (path, x) in [(&a, "0"), (&b, "0.5")] {
        let made = meshbool(&[
            "make",
            "sphere",
            "--segments",
            "1000",
            "--rings",
            "500",
            "--center",
            &format!("{x},0,0"),
            "-o",
            path.to_str().unwrap(),
        ]);
        assert!(
            made.status.success(),
            "{}",
            String::from_utf8_lossy(&made.stderr)
        );
    }
    let child = Command::new(env!("CARGO_BIN_EXE_meshbool"))
        .args([
            "union",
            a.to_str().unwrap(),
            b.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ])
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(400));
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let done = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&done.stderr);
    assert_eq!(done.status.code(), Some(130), "{stderr}");
    assert!(stderr.contains("cancelled"), "{stderr}");
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    let mut left = left;
    left.sort();
    assert_eq!(left, ["a.ply", "b.ply"], "nothing but the inputs");
}

/// A thread count out of range is a usage error (exit 2, clap's message), found before
/// any file is read; in range it runs.
#[test]
fn a_thread_count_out_of_range_is_a_usage_error() {
    let out = tmp("threads.stl");
    let (a, b) = (drill(O), bowl(O));
    let (a, b, o) = (
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        out.to_str().unwrap(),
    );
    for args in [
        vec!["union", a, b, "-o", o, "--threads", "5000"],
        vec!["resolve", a, "-o", o, "--threads", "1025"],
        vec!["union", a, b, "-o", o, "--threads", "many"],
    ] {
        let r = meshbool(&args);
        assert_eq!(r.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(err.contains("--threads"), "{err}");
        assert!(!out.exists());
    }
    let r = meshbool(&["union", a, b, "-o", o, "--threads", "1024"]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
}
