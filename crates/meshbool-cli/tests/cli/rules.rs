//! The rules every command follows: a difference of many inputs, one exit-code
//! rule (0 done, 1 an input or the work failed, 2 usage, 130 Ctrl-C), one rule for where
//! outputs go, and refusals that say where the problem is. Inputs are made here (the
//! library's meshes, or text written out), never read from `data/`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use meshbool::Mesh;

use crate::common::scratch;

fn meshbool(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_meshbool"))
        .args(args)
        .output()
        .unwrap()
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Writes `mesh` to `dir/name`.
fn write(dir: &Path, name: &str, mesh: &Mesh) -> PathBuf {
    let p = dir.join(name);
    meshbool::io::write_path(&p, mesh).unwrap();
    p
}

/// Writes `text` to `dir/name`.
fn text(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// Runs a command that must succeed and print a JSON report.
fn report(args: &[&str]) -> serde_json::Value {
    let out = meshbool(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// `meshbool info --json` of a file.
fn info(p: &Path) -> serde_json::Value {
    report(&["info", "--json", s(p)])
}

/// The sorted names in a directory.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// A box from `min` to `max`.
fn cuboid(min: [f64; 3], max: [f64; 3]) -> Mesh {
    Mesh::cuboid(min, max)
}

/// Two meshes as one (not welded).
fn both(a: &Mesh, b: &Mesh) -> Mesh {
    let mut m = a.clone();
    m.append(b).unwrap();
    m
}

/// A closed, manifold result: no boundary and no non-manifold edge.
fn assert_closed_manifold(v: &serde_json::Value, what: &str) {
    assert_eq!(v["boundary_edges"], 0, "{what}: {v}");
    assert_eq!(v["non_manifold_edges"], 0, "{what}: {v}");
    assert_eq!(v["closed"], true, "{what}: {v}");
}

// ---------------------------------------------------------------------------------------
// 1. difference A B C ...
// ---------------------------------------------------------------------------------------

#[test]
fn difference_of_many_is_the_first_less_the_union_of_the_others() {
    let dir = scratch("difference_many");
    // A 4 × 2 × 2 block (volume 16) and slabs through it across y and z.
    let block = write(&dir, "block.ply", &cuboid([0.0; 3], [4.0, 2.0, 2.0]));
    let slab =
        |name: &str, x0: f64, x1: f64| write(&dir, name, &cuboid([x0, -1.0, -1.0], [x1, 3.0, 3.0]));
    let c1 = slab("c1.ply", 0.5, 1.5); // 4 of the block
    let c2 = slab("c2.ply", 2.5, 3.0); // 2, apart from c1
    let c3 = slab("c3.ply", 1.0, 2.25); // overlaps c1: together 0.5 .. 2.25, 7
    let far = write(&dir, "far.ply", &cuboid([10.0; 3], [11.0; 3]));
    let out = dir.join("out.ply");
    for (cutters, volume) in [
        (vec![&c1, &c2], 16.0 - 4.0 - 2.0),
        (vec![&c1, &c3], 16.0 - 7.0),
        (vec![&c1, &c3, &c2], 16.0 - 7.0 - 2.0),
        (vec![&c2, &far], 16.0 - 2.0),
    ] {
        let mut args = vec!["difference", s(&block)];
        args.extend(cutters.iter().map(|p| s(p)));
        args.extend(["-o", s(&out), "--json"]);
        for extra in [&[][..], &["--one-arrangement"]] {
            let v = report(&[&args[..], extra].concat());
            let what = format!("{args:?} {extra:?}");
            assert_eq!(v["operation"], "difference", "{what}");
            let route = match extra {
                [] => "pairwise_tree",
                _ => "one_arrangement",
            };
            assert_eq!(v["combined"], route, "{what}");
            assert_eq!(v["volume"], volume, "{what}");
            assert_closed_manifold(&v, &what);
            // Every operand is listed, by its file, in the order given.
            let names: Vec<&str> = v["operands"]
                .as_array()
                .unwrap()
                .iter()
                .map(|o| o["name"].as_str().unwrap())
                .collect();
            let given: Vec<&str> = std::iter::once(s(&block))
                .chain(cutters.iter().map(|p| s(p)))
                .collect();
            assert_eq!(names, given, "{what}");
            // The file written is the result reported.
            let written = info(&out);
            assert_eq!(written["volume"], volume, "{what}");
            assert_eq!(written["boundary_edges"], 0, "{what}");
            assert_eq!(written["non_manifold_edges"], 0, "{what}");
        }
    }
    // The same as two differences chained.
    let once = dir.join("once.ply");
    let v = report(&[
        "difference",
        s(&block),
        s(&c1),
        s(&c3),
        "-o",
        s(&once),
        "--json",
    ]);
    let step = dir.join("step.ply");
    let chained = dir.join("chained.ply");
    report(&["difference", s(&block), s(&c1), "-o", s(&step), "--json"]);
    let w = report(&["difference", s(&step), s(&c3), "-o", s(&chained), "--json"]);
    assert_eq!(v["volume"], w["volume"]);
    assert_eq!(v["area"], w["area"]);
    assert_eq!(v["volume"], 9.0);
    let (a, b) = (info(&once), info(&chained));
    assert_eq!(a["bbox"], b["bbox"]);
    assert_eq!(a["components"], b["components"]);
}

#[test]
fn difference_reverse_takes_two_inputs() {
    let dir = scratch("difference_reverse");
    let big = write(&dir, "big.ply", &cuboid([0.0; 3], [2.0; 3]));
    let small = write(&dir, "small.ply", &cuboid([0.5; 3], [1.0; 3]));
    let out = dir.join("out.ply");
    // B − A with two inputs.
    let v = report(&[
        "difference",
        s(&small),
        s(&big),
        "--reverse",
        "-o",
        s(&out),
        "--json",
    ]);
    assert_eq!(v["volume"], 8.0 - 0.125);
    std::fs::remove_file(&out).unwrap();
    // With three: a usage error before any work, nothing written.
    let r = meshbool(&[
        "difference",
        s(&small),
        s(&big),
        s(&small),
        "--reverse",
        "-o",
        s(&out),
    ]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--reverse takes two inputs") && err.contains("got 3"),
        "{err}"
    );
    assert!(!out.exists());
}

// ---------------------------------------------------------------------------------------
// 2. One exit-code rule
// ---------------------------------------------------------------------------------------

/// Every command, each with a usage error (exit 2) and an input or processing error (exit
/// 1): the exact code, stderr naming the problem, and nothing written.
#[test]
fn every_command_exits_by_one_rule() {
    let dir = scratch("exit_codes");
    let cube = write(&dir, "cube.ply", &cuboid([0.0; 3], [1.0; 3]));
    let small = write(&dir, "small.ply", &cuboid([0.25; 3], [0.5; 3]));
    let plane = write(
        &dir,
        "plane.obj",
        &Mesh::new(
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            vec![[0, 1, 2]],
        )
        .unwrap(),
    );
    let no_triangles = text(&dir, "points_only.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    let missing = dir.join("missing.ply");
    let malformed = text(
        &dir,
        "malformed.obj",
        "v 0 0 0\nv 1 0 0\nv 0 x 0\nf 1 2 3\n",
    );
    let bad_points = text(&dir, "points.txt", "0 0 0\n1 2\n");
    let bad_config = text(&dir, "repair.json", r#"{"weld": 0.1, "wled": 1}"#);
    let scene = text(&dir, "scene.json", r#"{"root": {"primitive": "cube"}}"#);
    let bad_scene = text(
        &dir,
        "bad_scene.json",
        r#"{"root": {"op": "union", "children": [{"primitive": "sphere", "radus": 2}]}}"#,
    );
    let failing_scene = text(
        &dir,
        "failing_scene.json",
        r#"{"root": {"op": "union", "children": [{"primitive": "cube"}, {"mesh": "nowhere.stl"}]}}"#,
    );
    // A split to pick from.
    let split = dir.join("split");
    report(&["split", s(&cube), s(&small), "-o", s(&split), "--json"]);
    let out = dir.join("out.ply");
    let o = s(&out);
    let lines = dir.join("lines.obj");
    let (no_split, no_points) = (dir.join("nosplit"), dir.join("nopoints.txt"));
    let (c, sm, pl) = (s(&cube), s(&small), s(&plane));
    let cases: Vec<(Vec<&str>, i32, &str)> = vec![
        (vec!["info", s(&missing)], 1, "missing.ply"),
        (vec!["info", c, "--from", "nope"], 2, "'nope'"),
        (vec!["info", s(&malformed)], 1, "line 3"),
        (
            vec!["convert", c, "out.xyz"],
            2,
            "cannot tell the mesh format of out.xyz",
        ),
        (vec!["convert", c, o, "--to", "gltf"], 2, "'gltf'"),
        (vec!["convert", s(&missing), o], 1, "missing.ply"),
        (
            vec!["union", c, sm, "-o", o, "--threads", "5000"],
            2,
            "at most 1024",
        ),
        (
            vec!["union", c, sm, "-o", o, "--snap", "-1"],
            2,
            "snap tolerance",
        ),
        (
            vec!["union", c, sm, "-o", "out.xyz"],
            2,
            "cannot tell the mesh format",
        ),
        (vec!["union", c, s(&malformed), "-o", o], 1, "malformed.obj"),
        (vec!["intersection", c, "-o", o], 2, "2 values required"),
        (
            vec!["intersection", c, s(&missing), "-o", o],
            1,
            "missing.ply",
        ),
        (
            vec!["difference", c, sm, sm, "--reverse", "-o", o],
            2,
            "--reverse",
        ),
        (
            vec!["difference", c, s(&missing), sm, "-o", o],
            1,
            "missing.ply",
        ),
        (
            vec!["split", c, sm, "-o", o, "--merge-small", "-1"],
            2,
            "--merge-small",
        ),
        (vec!["split", c, s(&missing), "-o", o], 1, "missing.ply"),
        (
            vec!["pick", s(&split), "--keep", "a_in_c", "-o", o],
            2,
            "no group \"a_in_c\"",
        ),
        (
            vec!["pick", s(&split), "--keep", "b_out_a", "-o", o],
            2,
            "no group \"b_out_a\" in this split",
        ),
        (
            vec!["pick", s(&no_split), "--op", "union", "-o", o],
            1,
            "manifest.json",
        ),
        (
            vec![
                "close",
                pl,
                "-o",
                o,
                "--mode",
                "curtain",
                "--floor-offset",
                "-1",
            ],
            2,
            "floor offset",
        ),
        (
            vec!["close", pl, "-o", o, "--mode", "stitch", "--max-gap", "nan"],
            2,
            "stitch gap",
        ),
        (vec!["close", s(&missing), "-o", o], 1, "missing.ply"),
        (
            vec!["repair", c, "-o", o, "--weld", "nan"],
            2,
            "weld must be a finite distance",
        ),
        (vec!["repair", c, "-o", o, "--remove-folds"], 2, "z-up"),
        (
            vec!["repair", c, "-o", o, "--min-area", "1"],
            2,
            "--remove-degenerate",
        ),
        (
            vec!["repair", c, "-o", o, "--config", s(&bad_config)],
            1,
            "repair.json",
        ),
        (vec!["resolve", c, "-o", o, "--rule", "nope"], 2, "'nope'"),
        (
            vec!["resolve", c, "-o", o, "--envelope", "upper"],
            1,
            "closed",
        ),
        (
            vec!["orient", c, "-o", o, "--z-up", "--outward"],
            2,
            "cannot be used with",
        ),
        (vec!["orient", s(&malformed), "-o", o], 1, "line 3"),
        (
            vec!["transform", c, "-o", o, "--scale", "0"],
            2,
            "scale factor of 0",
        ),
        (
            vec!["transform", c, "-o", "out.xyz", "--scale", "2"],
            2,
            "cannot tell the mesh format",
        ),
        (
            vec!["transform", s(&missing), "-o", o, "--scale", "2"],
            1,
            "missing.ply",
        ),
        (vec!["make", "cube", "--size", "0", "-o", o], 2, "positive"),
        (
            vec!["make", "cube", "--min", "1,1,1", "--max", "0,0,0", "-o", o],
            2,
            "min must be below",
        ),
        (
            vec!["curves", c, sm, "-o", "c.stl"],
            2,
            ".obj, .dxf or .json",
        ),
        (
            vec!["curves", c, sm, "--simplify", "-1"],
            2,
            "simplification distance",
        ),
        (vec!["curves", c, s(&missing)], 1, "missing.ply"),
        (vec!["classify", c, s(&bad_points)], 1, "line 2"),
        (vec!["classify", c, s(&no_points)], 1, "nopoints.txt"),
        (
            vec!["classify", c, s(&bad_points), "--threads", "x"],
            2,
            "not a number of threads",
        ),
        (
            vec!["cutfill", pl, pl, "--threads", "2000"],
            2,
            "at most 1024",
        ),
        (
            vec!["cutfill", pl, s(&no_triangles), "-o", s(&lines)],
            1,
            "points_only.obj: no triangles",
        ),
        (vec!["csg", s(&scene), "-o", "out.xyz"], 2, "out.xyz"),
        (vec!["csg", s(&missing), "-o", o], 1, "missing.ply"),
        (
            vec!["csg", s(&bad_scene), "-o", o],
            1,
            "root.children[0].radus: unknown key",
        ),
        (
            vec!["csg", s(&failing_scene), "-o", o],
            1,
            "node root.children[1] failed",
        ),
        (vec!["frobnicate"], 2, "frobnicate"),
    ];
    for (args, code, says) in cases {
        let r = meshbool(&args);
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(code), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(
            !out.exists() && !lines.exists(),
            "{args:?} wrote its output"
        );
    }
}

// ---------------------------------------------------------------------------------------
// 3. One rule for outputs
// ---------------------------------------------------------------------------------------

/// Every command that writes a file: into directories that do not exist yet (made), and
/// again over the file it wrote (replaced).
#[test]
fn file_outputs_make_missing_directories_and_replace_files() {
    let dir = scratch("file_outputs");
    let cube = write(&dir, "cube.ply", &cuboid([0.0; 3], [1.0; 3]));
    let other = write(&dir, "other.ply", &cuboid([0.5; 3], [1.5; 3]));
    let plane = write(
        &dir,
        "plane.obj",
        &Mesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ],
            vec![[0, 1, 2], [0, 2, 3]],
        )
        .unwrap(),
    );
    let tilted = write(
        &dir,
        "tilted.obj",
        &Mesh::new(
            vec![
                [0.0, 0.0, -0.5],
                [1.0, 0.0, 0.5],
                [1.0, 1.0, 0.5],
                [0.0, 1.0, -0.5],
            ],
            vec![[0, 1, 2], [0, 2, 3]],
        )
        .unwrap(),
    );
    let points = text(&dir, "points.txt", "0.5 0.5 0.5\n5 5 5\n");
    let scene = text(
        &dir,
        "scene.json",
        r#"{"root": {"op": "difference", "children": [{"primitive": "cube"}, {"primitive": "sphere", "radius": 0.6, "role": "cutter"}]}}"#,
    );
    let split = dir.join("split");
    report(&["split", s(&cube), s(&other), "-o", s(&split), "--json"]);
    let (c, o, p) = (s(&cube), s(&other), s(&plane));
    let commands: Vec<(&str, Vec<&str>, &str)> = vec![
        ("union", vec!["union", c, o, "-o"], "ply"),
        ("intersection", vec!["intersection", c, o, "-o"], "obj"),
        ("difference", vec!["difference", c, o, "-o"], "stl"),
        (
            "pick",
            vec!["pick", s(&split), "--op", "union", "-o"],
            "ply",
        ),
        ("close", vec!["close", p, "--mode", "cap", "-o"], "ply"),
        ("orient", vec!["orient", c, "-o"], "ply"),
        ("repair", vec!["repair", c, "-o"], "ply"),
        ("resolve", vec!["resolve", c, "-o"], "ply"),
        (
            "transform",
            vec!["transform", c, "--scale", "2", "-o"],
            "ply",
        ),
        ("convert", vec!["convert", c], "off"),
        ("make", vec!["make", "sphere", "-o"], "ply"),
        ("curves", vec!["curves", c, o, "-o"], "json"),
        ("classify", vec!["classify", c, s(&points), "-o"], "csv"),
        ("cutfill", vec!["cutfill", p, s(&tilted), "-o"], "obj"),
        ("csg", vec!["csg", s(&scene), "-o"], "stl"),
    ];
    for (name, args, ext) in commands {
        let target = dir
            .join(name)
            .join("a")
            .join("b")
            .join(format!("out.{ext}"));
        for round in ["made", "replaced"] {
            if round == "replaced" {
                std::fs::write(&target, "an earlier file").unwrap();
            }
            let mut full = args.clone();
            full.push(s(&target));
            let r = meshbool(&full);
            let err = String::from_utf8_lossy(&r.stderr);
            assert_eq!(r.status.code(), Some(0), "{name} {round}: {err}");
            let written = std::fs::read(&target).unwrap();
            assert!(
                written.len() > 20 && written != b"an earlier file",
                "{name} {round}"
            );
            // Nothing but the file (no temporary file left beside it).
            assert_eq!(
                listing(target.parent().unwrap()),
                [format!("out.{ext}")],
                "{name} {round}"
            );
        }
    }
}

/// An output that is a directory, or under a file, is refused (exit 1, naming it) before
/// any work; a command that fails leaves no directory it made.
#[test]
fn output_paths_that_cannot_be_files_are_refused_and_failures_leave_no_directories() {
    let dir = scratch("bad_outputs");
    let cube = write(&dir, "cube.ply", &cuboid([0.0; 3], [1.0; 3]));
    let c = s(&cube);
    let a_dir = dir.join("already.ply");
    std::fs::create_dir(&a_dir).unwrap();
    let under_file = dir.join("cube.ply").join("x.ply");
    for (out, says) in [
        (s(&a_dir), "already.ply is a directory"),
        (s(&under_file), "cube.ply is a file"),
    ] {
        for args in [
            vec!["union", c, c, "-o", out],
            vec!["transform", c, "--scale", "2", "-o", out],
            vec!["convert", c, out],
            vec!["make", "cube", "-o", out],
        ] {
            let r = meshbool(&args);
            let err = String::from_utf8_lossy(&r.stderr);
            assert_eq!(r.status.code(), Some(1), "{args:?}: {err}");
            assert!(err.contains(says), "{args:?}: {err}");
        }
    }
    assert!(listing(&a_dir).is_empty());
    // A command that fails after its directories were made removes them.
    let nested = dir.join("new").join("deeper").join("u.ply");
    let r = meshbool(&["union", c, s(&dir.join("missing.ply")), "-o", s(&nested)]);
    assert_eq!(r.status.code(), Some(1));
    assert!(!dir.join("new").exists());
    let r = meshbool(&[
        "split",
        c,
        s(&dir.join("missing.ply")),
        "-o",
        s(&dir.join("new").join("split")),
    ]);
    assert_eq!(r.status.code(), Some(1));
    assert!(!dir.join("new").exists());
}

/// `split -o DIR`: made with its parents; a non-empty DIR refused without --overwrite;
/// with it, the earlier split's files removed first (no stale component left), and a
/// directory holding anything else still refused, nothing of it removed.
#[test]
fn split_directory_is_made_refused_when_not_empty_or_replaced_with_overwrite() {
    let dir = scratch("split_dir");
    let first = cuboid([0.0; 3], [1.0; 3]);
    let second = cuboid([3.0, 0.0, 0.0], [4.0, 1.0, 1.0]);
    // A's outside of B is two components the first time (a_out_b.0, a_out_b.1), one the
    // second.
    let two = write(&dir, "two.ply", &both(&first, &second));
    let one = write(&dir, "one.ply", &first);
    let b = write(&dir, "b.ply", &cuboid([0.5, -1.0, -1.0], [1.5, 2.0, 2.0]));
    let out = dir.join("made").join("on").join("demand");
    let split = |a: &Path, extra: &[&str]| {
        meshbool(&[&["split", s(a), s(&b), "-o", s(&out), "--json"][..], extra].concat())
    };
    // The manifest's files and the manifest: exactly what the directory holds.
    let listed = |manifest: &serde_json::Value| {
        let mut files = vec!["manifest.json".to_string()];
        for g in manifest["groups"].as_array().unwrap() {
            files.push(g["file"].as_str().unwrap().to_string());
            for c in g["components"].as_array().unwrap() {
                files.push(c["file"].as_str().unwrap().to_string());
            }
        }
        files.sort();
        files
    };
    let r = split(&two, &[]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let m: serde_json::Value = serde_json::from_slice(&r.stdout).unwrap();
    assert!(listing(&out).contains(&"a_out_b.1.ply".to_string()));
    assert_eq!(listing(&out), listed(&m));
    let before = listing(&out);
    // Again without --overwrite: refused before any work, naming the directory and the
    // flag; nothing changed.
    let r = split(&one, &[]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(1), "{err}");
    assert!(
        err.contains(s(&out)) && err.contains("not empty") && err.contains("--overwrite"),
        "{err}"
    );
    assert_eq!(listing(&out), before);
    // With --overwrite: the earlier split's files go, the new ones come.
    let r = split(&one, &["--overwrite"]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let m: serde_json::Value = serde_json::from_slice(&r.stdout).unwrap();
    assert_eq!(listing(&out), listed(&m));
    assert!(!out.join("a_out_b.1.ply").exists());
    assert!(!out.join("a_out_b.0.ply").exists());
    // Also in another format.
    let r = split(&two, &["--overwrite", "--format", "obj"]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let m: serde_json::Value = serde_json::from_slice(&r.stdout).unwrap();
    assert_eq!(listing(&out), listed(&m));
    assert!(listing(&out).iter().all(|f| !f.ends_with(".ply")));
    // A file the split did not write: refused with it, nothing removed.
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let before = listing(&out);
    let r = split(&one, &["--overwrite"]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(1), "{err}");
    assert!(err.contains("notes.txt") && err.contains(s(&out)), "{err}");
    assert_eq!(listing(&out), before);
    // No manifest: not a split's directory, refused.
    let other = dir.join("other");
    std::fs::create_dir(&other).unwrap();
    std::fs::write(other.join("a_in_b.ply"), "not ours").unwrap();
    let r = meshbool(&["split", s(&one), s(&b), "-o", s(&other), "--overwrite"]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(1), "{err}");
    assert!(err.contains("no manifest.json"), "{err}");
    assert_eq!(listing(&other), ["a_in_b.ply"]);
    // A file where the directory should be.
    let r = meshbool(&["split", s(&one), s(&b), "-o", s(&one)]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(1), "{err}");
    assert!(err.contains("is not a directory"), "{err}");
}

/// The rule is in the `--help` of every option that writes.
#[test]
fn help_of_every_output_states_the_rule() {
    for cmd in [
        &["union"][..],
        &["intersection"],
        &["difference"],
        &["pick"],
        &["close"],
        &["orient"],
        &["repair"],
        &["resolve"],
        &["transform"],
        &["convert"],
        &["curves"],
        &["classify"],
        &["cutfill"],
        &["csg"],
    ] {
        let r = meshbool(&[cmd, &["--help"]].concat());
        // Help is wrapped at the terminal's width: compare with the line breaks and their
        // indentation made single spaces.
        let help = String::from_utf8_lossy(&r.stdout)
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ");
        assert!(
            help.contains("Missing directories are created; an existing file is replaced whole"),
            "{cmd:?}: {help}"
        );
    }
    let r = meshbool(&["split", "--help"]);
    let help = String::from_utf8_lossy(&r.stdout)
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    assert!(
        help.contains("made with its missing parents")
            && help.contains("refused unless --overwrite")
            && help.contains("none is left stale"),
        "{help}"
    );
}

// ---------------------------------------------------------------------------------------
// 4. Every refusal says where
// ---------------------------------------------------------------------------------------

/// The point `[x, y, z]` printed after `after` in `text`.
fn point_after(text: &str, after: &str) -> [f64; 3] {
    let start = text
        .find(after)
        .unwrap_or_else(|| panic!("{after:?} in {text}"))
        + after.len();
    let end = start + text[start..].find(']').unwrap();
    let v: Vec<f64> = text[start..end]
        .trim_start_matches('[')
        .split(',')
        .map(|x| x.trim().parse().unwrap())
        .collect();
    [v[0], v[1], v[2]]
}

#[test]
fn mesh_refusals_name_where_the_problem_is() {
    let dir = scratch("mesh_refusals");
    let cube = write(&dir, "cube.ply", &cuboid([5.0; 3], [6.0; 3]));
    // One triangle of a box turned over: its three edges are inconsistent; the refusal
    // names the midpoint of one of them.
    let (positions, mut triangles) = cuboid([0.0; 3], [1.0, 2.0, 3.0]).into_parts();
    triangles[4].swap(1, 2);
    let corners = triangles[4].map(|v| positions[v as usize]);
    let flipped_path = write(
        &dir,
        "flipped.ply",
        &Mesh::new(positions, triangles).unwrap(),
    );
    let out = dir.join("out.ply");
    let r = meshbool(&[
        "union",
        s(&flipped_path),
        s(&cube),
        "--no-orient",
        "-o",
        s(&out),
    ]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(1), "{err}");
    assert!(
        err.contains("flipped.ply: 3 inconsistently oriented edges"),
        "{err}"
    );
    let near = point_after(&err, "inconsistently oriented edges (the first near ");
    let midpoints: Vec<[f64; 3]> = [(0, 1), (1, 2), (2, 0)]
        .map(|(i, j)| std::array::from_fn(|k| 0.5 * (corners[i][k] + corners[j][k])))
        .into();
    assert!(midpoints.contains(&near), "{near:?} not in {midpoints:?}");
    // The JSON report of a forced run carries it too.
    let v = report(&[
        "union",
        s(&flipped_path),
        s(&cube),
        "--no-orient",
        "--force",
        "-o",
        s(&out),
        "--json",
    ]);
    let json_near: Vec<f64> = v["operands"][0]["inconsistent_near"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(json_near, near);
    std::fs::remove_file(&out).unwrap();
    // Three triangles on one edge of an open fin: the edge's midpoint.
    let fin = text(
        &dir,
        "fin.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n",
    );
    let r = meshbool(&["union", s(&fin), s(&cube), "-o", s(&out)]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(1), "{err}");
    assert!(
        err.contains("1 non-manifold edges (the first near [0.5, 0.0, 0.0])"),
        "{err}"
    );
    // Its envelope: refused, at the same edge.
    let r = meshbool(&["resolve", s(&fin), "--envelope", "lower", "-o", s(&out)]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(1), "{err}");
    assert!(
        err.contains("cannot be oriented consistently")
            && err.contains("the first near [0.5, 0.0, 0.0]"),
        "{err}"
    );
    // An open surface crossing itself: taken as given, the warning says where it
    // crosses; resolving it alone names the open edge it stops at.
    let crossing = text(
        &dir,
        "crossing.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 -1\nv 0.5 0.5 1\nv 0.2 2 0\n\
         f 1 2 3\nf 1 3 4\nf 5 6 7\n",
    );
    let r = meshbool(&["union", s(&crossing), s(&cube), "-o", s(&out)]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(0), "{err}");
    assert!(
        err.contains("2 self-intersecting triangle pairs of its open parts (the first near ["),
        "{err}"
    );
    std::fs::remove_file(&out).unwrap();
    let r = meshbool(&["resolve", s(&crossing), "-o", s(&out)]);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(1), "{err}");
    assert!(
        err.contains("component 0 is not closed and consistently oriented (an open edge near [0.5, 0.0, 0.0]"),
        "{err}"
    );
    assert!(!out.exists());
}

#[test]
fn file_refusals_name_the_file_and_the_line_or_byte() {
    let dir = scratch("file_refusals");
    let cube = write(&dir, "cube.ply", &cuboid([0.0; 3], [1.0; 3]));
    let obj = text(&dir, "nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n");
    let ply = text(
        &dir,
        "short.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
         property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
         end_header\n0 0 0\n1 0 0\n0 x 0\n3 0 1 2\n",
    );
    // A binary STL whose second triangle has a NaN corner.
    let mut stl = vec![0u8; 80];
    stl.extend(2u32.to_le_bytes());
    for corner_y in [1.0f32, f32::NAN] {
        let floats = [
            0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, corner_y, 1.0,
        ];
        for f in floats {
            stl.extend(f.to_le_bytes());
        }
        stl.extend([0, 0]);
    }
    let stl_path = dir.join("nan.stl");
    std::fs::write(&stl_path, &stl).unwrap();
    let points = text(&dir, "points.csv", "x,y,z\n0 0 0\n\n4 inf 6\n");
    for (args, says) in [
        (
            vec!["info", s(&obj)],
            vec!["nan.obj", "line 3", "non-finite"],
        ),
        (vec!["info", s(&ply)], vec!["short.ply", "line 12"]),
        (
            vec!["info", s(&stl_path)],
            vec!["nan.stl", "byte 174", "triangle 1"],
        ),
        (
            vec!["classify", s(&cube), s(&points)],
            vec!["points.csv", "line 4: point 1 is not finite"],
        ),
    ] {
        let r = meshbool(&args);
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(1), "{args:?}: {err}");
        for say in says {
            assert!(err.contains(say), "{args:?}: {say:?} in {err}");
        }
    }
}
