//! Helpers of the command-line tests: running the binary, scratch files, meshes made with
//! `meshbool make`, shared data.

use std::path::PathBuf;
use std::process::{Command, Output};

/// A file of other projects' data in `../shared/data` beside the checkout (the Kirra
/// surfaces of the reference JS library, kept out of the repository), or `None`, saying
/// the test is skipped, where that folder is absent.
pub(crate) fn shared_data(name: &str) -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data");
    if dir.is_dir() {
        Some(dir.join(name))
    } else {
        eprintln!("skipped: ../shared/data not found");
        None
    }
}

/// A mesh made by `meshbool make ARGS`, in a file of its own.
pub(crate) fn made(args: &[&str]) -> PathBuf {
    static MADE: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = MADE.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let path = tmp(&format!("made_{n}.ply"));
    let r = meshbool(&[&["make"], args, &["-o", path.to_str().unwrap()]].concat());
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    path
}

/// A centre at UTM-like coordinates (metres east and north, elevation).
pub(crate) const UTM: [f64; 3] = [478_600.0, 6_772_300.0, 400.0];

/// `center` moved by `d`, as `X,Y,Z`.
pub(crate) fn at(center: [f64; 3], d: [f64; 3]) -> String {
    format!(
        "{},{},{}",
        center[0] + d[0],
        center[1] + d[1],
        center[2] + d[2]
    )
}

/// A generated survey about `center`: 600 m square in 60 × 60 cells (7200 triangles, 240
/// boundary edges), heights `center.z ± 20`.
pub(crate) fn terrain(center: [f64; 3]) -> PathBuf {
    let c = at(center, [0.0; 3]);
    made(&["terrain", "--center", &c, "--size", "600", "--cells", "60"])
}

/// [`terrain`] badly wound, as surveys often are: five triangles far from [`drill`] and
/// from one another reversed (15 inconsistently oriented edges).
pub(crate) fn wound_terrain(center: [f64; 3]) -> PathBuf {
    let path = terrain(center);
    let (positions, mut triangles) = meshbool::io::read_path(&path).unwrap().into_parts();
    for (i, j) in [(5, 5), (5, 50), (50, 5), (50, 50), (10, 30)] {
        triangles[2 * (j * 60 + i)].swap(1, 2);
    }
    let m = meshbool::Mesh::new(positions, triangles).unwrap();
    meshbool::io::write_path(&path, &m).unwrap();
    path
}

/// A drill hole through [`terrain`]: a cylinder of radius 35 and 30 sides (120
/// triangles) from 60 below to 60 above the centre, 20 m east and 10 m south of it.
pub(crate) fn drill(center: [f64; 3]) -> PathBuf {
    let base = at(center, [20.0, -10.0, -60.0]);
    made(&[
        "cylinder",
        "--base",
        &base,
        "--radius",
        "35",
        "--height",
        "120",
        "--segments",
        "30",
    ])
}

/// An open bowl crossing [`terrain`]: a pit of radius 60 in 16 segments (16 boundary
/// edges), its rim above the ground and its floor below, 100 m west and 80 m north.
pub(crate) fn bowl(center: [f64; 3]) -> PathBuf {
    let c = at(center, [-100.0, 80.0, 30.0]);
    made(&[
        "pit",
        "--center",
        &c,
        "--radius",
        "60",
        "--depth",
        "70",
        "--benches",
        "2",
        "--berm",
        "5",
        "--segments",
        "16",
    ])
}

pub(crate) const O: [f64; 3] = [0.0; 3];

pub(crate) fn meshbool(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_meshbool"))
        .args(args)
        .output()
        .unwrap()
}

pub(crate) fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("meshbool-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// A fresh, empty directory for one test (`test`: a name no other test uses).
pub(crate) fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("meshbool-cli-{}-dir-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// An OBJ file of a prism of height 1 on a regular `n`-gon of circumradius 1 turned by
/// `turn` radians, both caps fanned from its first vertex (as CAD exporters fan caps).
pub(crate) fn fanned_prism(name: &str, n: usize, turn: f64) -> PathBuf {
    let mut obj = String::new();
    for z in [0.0, 1.0] {
        for i in 0..n {
            let a = turn + std::f64::consts::TAU * i as f64 / n as f64;
            obj += &format!("v {} {} {z}\n", a.cos(), a.sin());
        }
    }
    for i in 1..n - 1 {
        obj += &format!("f 1 {} {}\n", i + 2, i + 1);
        obj += &format!("f {} {} {}\n", n + 1, n + i + 1, n + i + 2);
    }
    for i in 0..n {
        let j = (i + 1) % n;
        obj += &format!("f {} {} {}\n", i + 1, j + 1, n + j + 1);
        obj += &format!("f {} {} {}\n", i + 1, n + j + 1, n + i + 1);
    }
    let path = tmp(name);
    std::fs::write(&path, obj).unwrap();
    path
}

pub(crate) fn write_cube(name: &str, min: [f64; 3], max: [f64; 3]) -> PathBuf {
    let p = tmp(name);
    meshbool::io::write_path(&p, &meshbool::Mesh::cuboid(min, max)).unwrap();
    p
}

pub(crate) fn report(args: &[&str]) -> serde_json::Value {
    let out = meshbool(args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// Runs `repair` on `mesh` (written as OBJ under `name`) with `flags`: the JSON report.
pub(crate) fn repair_json(mesh: &meshbool::Mesh, name: &str, flags: &[&str]) -> serde_json::Value {
    let input = tmp(&format!("{name}.obj"));
    meshbool::io::write_path(&input, mesh).unwrap();
    let out = tmp(&format!("{name}_fixed.obj"));
    let mut args = vec![
        "repair",
        input.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--json",
    ];
    args.extend(flags);
    report(&args)
}

/// The unit cube as two closed boxes stacked at z = 0.5, the upper one's bottom face
/// (its own vertices, facing down) lifted by 1e-4: a double wall 1e-4 thick.
pub(crate) fn stacked_boxes() -> meshbool::Mesh {
    let mut m = meshbool::Mesh::cuboid([0.0; 3], [1.0, 1.0, 0.5]);
    let (mut positions, triangles) = meshbool::Mesh::unit_cube().into_parts();
    for p in &mut positions {
        if p[2] == 0.0 {
            p[2] = 0.5001;
        }
    }
    m.append(&meshbool::Mesh::new(positions, triangles).unwrap())
        .unwrap();
    m
}

/// A box over `[0, 1]² × [z0, z1]` with its top (`top = false`) or bottom face missing.
pub(crate) fn open_box(z0: f64, z1: f64, drop_top: bool) -> meshbool::Mesh {
    let m = meshbool::Mesh::cuboid([0.0, 0.0, z0], [1.0, 1.0, z1]);
    let z = if drop_top { z1 } else { z0 };
    let triangles = (0..m.triangle_count())
        .filter(|&t| !m.corners(t).iter().all(|p| p[2] == z))
        .map(|t| m.triangles()[t])
        .collect();
    meshbool::Mesh::new(m.positions().to_vec(), triangles).unwrap()
}

/// A report as JSON without its timing, which differs from run to run.
pub(crate) fn untimed(mut v: serde_json::Value) -> serde_json::Value {
    if let Some(m) = v.as_object_mut() {
        m.remove("seconds");
    }
    v
}

/// A library report as the CLI should print it, without its timing.
pub(crate) fn json(report: &impl serde::Serialize) -> serde_json::Value {
    untimed(serde_json::to_value(report).unwrap())
}

/// Runs `meshbool` expecting a usage error: exit 2, a message naming `needle`, no panic.
pub(crate) fn usage_error(args: &[&str], needle: &str) {
    let r = meshbool(args);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{args:?}: {err}");
    assert!(err.contains(needle), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
}
