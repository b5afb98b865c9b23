//! `curves` and `classify`: intersection curves in every format, self-crossings, simplified and
//! tagged curves, points classified against a mesh.

use std::process::Command;

use crate::common::*;

#[test]
fn curves_of_terrain_and_cylinder_is_one_loop_in_every_format() {
    let (terrain, cylinder) = (terrain(UTM), drill(UTM));
    for ext in ["obj", "dxf", "json"] {
        let out = tmp(&format!("curve.{ext}"));
        let r = meshbool(&[
            "curves",
            terrain.to_str().unwrap(),
            cylinder.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--json",
        ]);
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        let v: serde_json::Value = serde_json::from_slice(&r.stdout).unwrap();
        assert_eq!(v["loops"], 1);
        assert_eq!(v["open_chains"], 0);
        let n = v["points"].as_u64().unwrap() as usize;
        let text = std::fs::read_to_string(&out).unwrap();
        match ext {
            "obj" => {
                assert_eq!(text.lines().filter(|l| l.starts_with("v ")).count(), n);
                let l: Vec<&str> = text.lines().filter(|l| l.starts_with("l ")).collect();
                assert_eq!(l.len(), 1);
                // Closed: the first index is repeated at the end.
                assert_eq!(l[0].split(' ').nth(1), l[0].split(' ').next_back());
            }
            "dxf" => assert_eq!(text.matches("\nVERTEX\n").count(), n),
            _ => {
                let j: serde_json::Value = serde_json::from_str(&text).unwrap();
                assert_eq!(j[0]["closed"], true);
                assert_eq!(j[0]["points"].as_array().unwrap().len(), n);
                // UTM coordinates survive in full.
                assert!(j[0]["points"][0][1].as_f64().unwrap() > 6_772_000.0);
            }
        }
    }
}

#[test]
fn curves_rejects_an_unknown_output_extension() {
    let r = meshbool(&[
        "curves",
        bowl(O).to_str().unwrap(),
        terrain(O).to_str().unwrap(),
        "-o",
        tmp("c.stl").to_str().unwrap(),
    ]);
    // A usage error, found before any work (issue 17: checked after the computation
    // before, with exit 1).
    assert_eq!(r.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&r.stderr).contains("polylines are written as .obj, .dxf or .json")
    );
    // Mesh outputs likewise: an unknown extension (a missing directory is made:
    // cli_rules.rs).
    let (a, b) = (bowl(O), drill(O));
    for (out, says) in [("u.xyz".to_string(), "cannot tell the mesh format")] {
        for cmd in [
            vec![
                "union",
                a.to_str().unwrap(),
                b.to_str().unwrap(),
                "-o",
                &out,
            ],
            vec!["repair", a.to_str().unwrap(), "-o", &out],
            vec!["orient", a.to_str().unwrap(), "-o", &out],
        ] {
            let r = meshbool(&cmd);
            let err = String::from_utf8_lossy(&r.stderr);
            assert_eq!(r.status.code(), Some(2), "{cmd:?}: {err}");
            assert!(err.contains(says), "{cmd:?}: {err}");
        }
    }
}

#[test]
fn curves_of_one_mesh_are_where_it_crosses_itself() {
    let mut m = meshbool::Mesh::unit_cube();
    m.append(&meshbool::Mesh::cuboid([0.5; 3], [1.5; 3]))
        .unwrap();
    let two = tmp("self_curves_in.ply");
    meshbool::io::write_path(&two, &m).unwrap();
    let out = tmp("self_curves.obj");
    let v = report(&[
        "curves",
        two.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(
        (v["loops"].as_u64(), v["open_chains"].as_u64()),
        (Some(1), Some(0))
    );
    assert!((v["total_length"].as_f64().unwrap() - 3.0).abs() < 1e-12);
    let text = std::fs::read_to_string(&out).unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with("l ")).count(), 1);
    // A clean mesh: nothing, and a length of 0 (not -0).
    let cube = write_cube("self_curves_clean.ply", [0.0; 3], [1.0; 3]);
    let v = report(&["curves", cube.to_str().unwrap(), "--json"]);
    assert_eq!(v["points"], 0);
    assert_eq!(v["total_length"].to_string(), "0.0");
}

#[test]
fn classify_points_from_a_file_and_stdin() {
    use std::io::Write;
    let cube = write_cube("classify_cube.stl", [0.0; 3], [1.0; 3]);
    let pts = tmp("classify_points.csv");
    std::fs::write(&pts, "x,y,z\n0.5,0.5,0.5\n2,2,2\n1,0.5,0.25\n").unwrap();
    let v = report(&[
        "classify",
        cube.to_str().unwrap(),
        pts.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(
        (
            &v["points"],
            &v["inside"],
            &v["outside"],
            &v["on"],
            &v["closed"]
        ),
        (&3.into(), &1.into(), &1.into(), &1.into(), &true.into())
    );
    let classes: Vec<&str> = v["results"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["class"].as_str().unwrap())
        .collect();
    assert_eq!(classes, ["inside", "outside", "on"]);
    // Standard input, lines out.
    let mut child = Command::new(env!("CARGO_BIN_EXE_meshbool"))
        .args(["classify", cube.to_str().unwrap(), "-"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(b"0.25 0.25 0.25\n5 5 5\n")
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 2);
    assert!(lines[0].starts_with("0.25,0.25,0.25,inside,"), "{text}");
    assert!(lines[1].starts_with("5,5,5,outside,"), "{text}");
    // -o .json: the per-point results in the file, the counts on stdout.
    let json = tmp("classify_out.json");
    let v = report(&[
        "classify",
        cube.to_str().unwrap(),
        pts.to_str().unwrap(),
        "-o",
        json.to_str().unwrap(),
        "--json",
    ]);
    assert!(v.get("results").is_none());
    let file: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    assert_eq!(file.as_array().unwrap().len(), 3);
    // A malformed points file names the line; exit code 1.
    std::fs::write(&pts, "0 0 0\n1 2\n").unwrap();
    let out = meshbool(&["classify", cube.to_str().unwrap(), pts.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("line 2"));
}

#[test]
fn curves_simplify_and_tagged_segments() {
    let a = write_cube("curves_a.stl", [0.0; 3], [1.0; 3]);
    let b = write_cube("curves_b.stl", [0.5; 3], [1.5; 3]);
    let v = report(&[
        "curves",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "--json",
        "--tagged",
    ]);
    let tagged = v["tagged_segments"].as_array().unwrap();
    assert!(tagged.len() >= v["segments"].as_u64().unwrap() as usize);
    assert!(tagged
        .iter()
        .all(|s| s["tri_a"].as_u64().unwrap() < 12 && s["tri_b"].as_u64().unwrap() < 12));
    let v = report(&[
        "curves",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "--json",
        "--simplify",
        "0.6",
    ]);
    assert!(v["simplified_points_removed"].as_u64().unwrap() > 0);
    // --tagged needs --json; a bad distance is refused.
    let out = meshbool(&[
        "curves",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "--tagged",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let out = meshbool(&[
        "curves",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "--simplify",
        "-1",
    ]);
    assert_ne!(out.status.code(), Some(0));
}
