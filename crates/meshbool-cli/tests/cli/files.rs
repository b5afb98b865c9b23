//! `info`, `convert` and the readers and writers: measures, round trips, malformed files, outputs
//! that fail or are interrupted.

use std::path::PathBuf;
use std::process::Command;

use crate::common::*;

#[test]
fn info_json_reports_terrain_counts() {
    let Some(terrain) = shared_data("kirra_terrain.obj") else {
        return;
    };
    let out = meshbool(&["info", "--json", terrain.to_str().unwrap()]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["triangles"], 11200);
    assert_eq!(v["vertices"], 5881);
    assert_eq!(v["boundary_edges"], 560);
    assert_eq!(v["non_manifold_edges"], 0);
    assert_eq!(v["inconsistent_edges"], 46);
    assert_eq!(v["degenerate_triangles"], 0);
    assert_eq!(v["components"], 1);
    assert_eq!(v["closed"], false);
    assert!(v["area"].as_f64().unwrap() > 0.0);
    assert_eq!(v["bbox"]["max"][2], 23.516);
}

#[test]
fn info_json_several_files_is_an_array() {
    let out = meshbool(&[
        "info",
        "--json",
        drill(O).to_str().unwrap(),
        bowl(O).to_str().unwrap(),
    ]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v[0]["closed"], true);
    assert_eq!(v[1]["boundary_edges"], 16);
}

#[test]
fn convert_round_trip_keeps_measures() {
    let (input, ply) = (wound_terrain(UTM), tmp("t.ply"));
    let out = meshbool(&["convert", input.to_str().unwrap(), ply.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let dxf = tmp("t.dxf");
    assert!(
        meshbool(&["convert", ply.to_str().unwrap(), dxf.to_str().unwrap()])
            .status
            .success()
    );
    let info = |p: &PathBuf| -> serde_json::Value {
        serde_json::from_slice(&meshbool(&["info", "--json", p.to_str().unwrap()]).stdout).unwrap()
    };
    let (a, b) = (info(&input), info(&dxf));
    for k in [
        "triangles",
        "vertices",
        "boundary_edges",
        "inconsistent_edges",
        "volume",
        "area",
        "bbox",
    ] {
        assert_eq!(a[k], b[k], "{k}");
    }
}

#[test]
fn convert_to_glb_keeps_triangles_and_volume() {
    let (cylinder, glb) = (drill(O), tmp("cylinder.glb"));
    let out = meshbool(&["convert", cylinder.to_str().unwrap(), glb.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(std::fs::read(&glb).unwrap()[..4], *b"glTF");
    let info = |p: &PathBuf| -> serde_json::Value {
        let out = meshbool(&["info", p.to_str().unwrap(), "--json"]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let (a, b) = (info(&cylinder), info(&glb));
    assert_eq!(a["triangles"], b["triangles"]);
    assert_eq!(a["vertices"], b["vertices"]);
    let (va, vb) = (a["volume"].as_f64().unwrap(), b["volume"].as_f64().unwrap());
    assert!(va > 0.0 && (va - vb).abs() <= 1e-6 * va, "{va} {vb}");
}

#[test]
fn bad_input_exits_1_naming_file_and_line() {
    let bad = tmp("bad.obj");
    std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n").unwrap();
    let out = meshbool(&["info", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("bad.obj") && err.contains("line 3") && err.contains("non-finite"),
        "{err}"
    );

    let stl = tmp("short.stl");
    std::fs::write(&stl, [0u8; 40]).unwrap();
    let out = meshbool(&["info", stl.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("byte 40"));

    let out = meshbool(&["info", tmp("missing.obj").to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
}

#[test]
fn convert_to_mining_formats_and_back_keeps_triangles_and_volume() {
    let info = |p: &PathBuf| -> serde_json::Value {
        let out = meshbool(&["info", "--json", p.to_str().unwrap()]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let input = terrain(UTM);
    let want = info(&input);
    for ext in ["ts", "xml", "dtm"] {
        let written = tmp(&format!("mining.{ext}"));
        let back = tmp(&format!("mining-{ext}.obj"));
        for (from, to) in [(&input, &written), (&written, &back)] {
            let out = meshbool(&["convert", from.to_str().unwrap(), to.to_str().unwrap()]);
            assert!(
                out.status.success(),
                "{ext}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
        }
        if ext == "dtm" {
            assert!(written.with_extension("str").exists());
        }
        for p in [&written, &back] {
            let got = info(p);
            for k in ["triangles", "vertices", "volume", "area", "bbox"] {
                assert_eq!(got[k], want[k], "{ext} {k}");
            }
        }
        // The same triangles, vertex for vertex.
        assert_eq!(
            std::fs::read_to_string(&back).unwrap(),
            std::fs::read_to_string(tmp(&format!("mining-{}.obj", "ts"))).unwrap(),
            "{ext}"
        );
    }
    // A DTM without its string file: the error names the missing file.
    let lonely = tmp("lonely.dtm");
    std::fs::copy(tmp("mining.dtm"), &lonely).unwrap();
    let out = meshbool(&["info", lonely.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("lonely.str"), "{err}");
}

#[test]
fn a_failing_standard_output_is_an_error_or_a_quiet_end_never_a_panic() {
    let terrain = terrain(O);
    // A full disk: exit 1 with a message naming standard output.
    if let Ok(full) = std::fs::File::create("/dev/full") {
        let out = Command::new(env!("CARGO_BIN_EXE_meshbool"))
            .args(["info", "--json", terrain.to_str().unwrap()])
            .stdout(full)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{err}");
        assert!(
            err.contains("writing standard output") && !err.contains("panicked"),
            "{err}"
        );
    }
    // A reader that closes the pipe at once: a quiet end, exit 0.
    let mut child = Command::new(env!("CARGO_BIN_EXE_meshbool"))
        .args(["info", terrain.to_str().unwrap(), terrain.to_str().unwrap()])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn killing_a_large_write_leaves_the_earlier_file_or_the_whole_new_one() {
    // A 2M-triangle sphere written as OBJ over an earlier file, the process killed at
    // moments spread over the write: the path holds the earlier file or the whole new one.
    let big = tmp("kill_big.ply");
    let made = meshbool(&[
        "make",
        "sphere",
        "--segments",
        "1024",
        "--rings",
        "1024",
        "-o",
        big.to_str().unwrap(),
    ]);
    assert!(
        made.status.success(),
        "{}",
        String::from_utf8_lossy(&made.stderr)
    );
    let want = meshbool::io::read_path(&big).unwrap().triangle_count();
    assert!(want > 2_000_000);
    let out = tmp("kill_out.obj");
    let (mut earlier, mut whole) = (0, 0);
    // The last run is not killed: its whole result is checked too.
    for delay_ms in [0u64, 30, 80, 150, 250, 400, 600, 900, 1300, 2000, u64::MAX] {
        meshbool::io::write_path(&out, &meshbool::Mesh::unit_cube()).unwrap();
        let mut child = Command::new(env!("CARGO_BIN_EXE_meshbool"))
            .args(["convert", big.to_str().unwrap(), out.to_str().unwrap()])
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        if delay_ms == u64::MAX {
            assert!(child.wait().unwrap().success());
        } else {
            std::thread::sleep(std::time::Duration::from_millis(delay_ms));
            let _ = child.kill();
            let _ = child.wait();
        }
        let n = meshbool::io::read_path(&out).unwrap().triangle_count();
        assert!(n == 12 || n == want, "after {delay_ms} ms: {n} triangles");
        if n == 12 {
            earlier += 1;
        } else {
            whole += 1;
        }
    }
    // Both outcomes happened (the first kill falls long before the rename).
    assert!(earlier > 0 && whole > 0, "{earlier} earlier, {whole} whole");
    for f in std::fs::read_dir(out.parent().unwrap()).unwrap() {
        let name = f.unwrap().path();
        if name.to_string_lossy().ends_with(".meshbool-tmp") {
            let _ = std::fs::remove_file(name); // left by the kills
        }
    }
}

#[test]
fn readers_refuse_content_beyond_the_format_and_say_what_is_wrong() {
    // Issue 17: a binary STL whose header starts with "solid" and whose count is wrong was
    // "malformed ASCII STL"; extra PLY lines and junk after an OBJ vertex were read as if
    // absent; a bad JSON triangle was "did not match any variant of untagged enum Tri".
    let mut stl = Vec::from(&b"solid cube"[..]);
    stl.resize(80, b' ');
    stl.extend_from_slice(&13u32.to_le_bytes());
    stl.resize(84 + 50 * 12, 0);
    let p = "{\"x\":0,\"y\":0,\"z\":0}";
    for (name, content, says) in [
        (
            "wrong_count.stl",
            stl,
            "malformed binary STL at byte 80: header announces 13 triangles (734 bytes) but the \
             file has 684 bytes",
        ),
        (
            "extra_face.ply",
            b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
              property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
              end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n"
                .to_vec(),
            "malformed ASCII PLY at line 14: data beyond what the header declares",
        ),
        (
            "junk.obj",
            b"v 0 0 0 junk\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec(),
            "malformed OBJ at line 1: expected a number, found \"junk\"",
        ),
        (
            "bad_triangle.json",
            format!("[{{\"v0\":{p},\"v1\":{p}}}]").into_bytes(),
            "malformed JSON soup at line 1: array element 0 (0-based): missing \"v2\"; each \
             element must be a triangle:",
        ),
    ] {
        let path = tmp(name);
        std::fs::write(&path, content).unwrap();
        let r = meshbool(&["info", path.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(1), "{name}: {err}");
        assert!(err.contains(says), "{name}: {err}");
    }
}
