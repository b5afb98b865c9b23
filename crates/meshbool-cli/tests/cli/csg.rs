//! `meshbool csg`: the document evaluated to the library's result, a cache folder shared
//! by runs computing only what an edit changed, the report per node.

use std::path::Path;
use std::process::Command;

use meshbool::csg::{evaluate, Cache, CsgOptions, Scene};

use crate::common::scratch;

/// `meshbool csg ARGS --json`, which must succeed: its report.
fn csg(dir: &Path, args: &[&str]) -> serde_json::Value {
    let out = Command::new(env!("CARGO_BIN_EXE_meshbool"))
        .current_dir(dir)
        .arg("csg")
        .args(args)
        .arg("--json")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// The paths of the nodes a report says were computed.
fn computed(report: &serde_json::Value) -> Vec<String> {
    report["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|n| n["source"] == "computed")
        .map(|n| n["path"].as_str().unwrap().to_string())
        .collect()
}

const SCENE: &str = r#"{ "root": { "op": "difference", "name": "housing", "children": [
    { "op": "union", "name": "body", "children": [
        { "primitive": "cube", "size": [40, 20, 10] },
        { "mesh": "parts/tower.ply", "transform": { "rotate": ["z", 30], "translate": [0, 0, 10] } } ] },
    { "primitive": "cylinder", "radius": 3, "height": 30, "base": [0, 0, -15], "segments": 64, "role": "cutter" },
    { "primitive": "plane", "width": 100, "depth": 100, "transform": { "translate": [0, 0, -2] }, "role": "cutter" } ] } }"#;

#[test]
fn runs_share_a_cache_folder_and_compute_only_an_edits_path() {
    let dir = scratch("cache");
    std::fs::create_dir_all(dir.join("parts")).unwrap();
    let tower = |size: f64| {
        meshbool::ops::write(
            dir.join("parts/tower.ply"),
            &meshbool::shapes::cube([0.0; 3], size).unwrap(),
            None,
        )
        .unwrap()
    };
    tower(10.0);
    std::fs::write(dir.join("housing.json"), SCENE).unwrap();
    let args = ["housing.json", "-o", "out/housing.ply", "--cache", "cache"];

    let cold = csg(&dir, &args);
    assert_eq!(
        (cold["computed"].as_u64(), cold["cached"].as_u64()),
        (Some(6), Some(0))
    );
    assert_eq!(cold["closed"], true);
    assert_eq!(std::fs::read_dir(dir.join("cache")).unwrap().count(), 6);
    // The file written is the library's result, bit for bit (PLY keeps f64).
    let scene = Scene::read(dir.join("housing.json")).unwrap();
    let lib = evaluate(&scene, &Cache::new(), &CsgOptions::default())
        .unwrap()
        .mesh
        .unwrap();
    let written = meshbool::ops::read(dir.join("out/housing.ply"), None)
        .unwrap()
        .0;
    assert_eq!(written, lib);
    assert_eq!(
        cold["volume"].as_f64(),
        Some(meshbool::measure::signed_volume(&lib))
    );

    let warm = csg(&dir, &args);
    assert_eq!(
        (warm["computed"].as_u64(), warm["cached"].as_u64()),
        (Some(0), Some(1))
    );
    assert_eq!(warm["nodes"][0]["source"], "disk");
    assert_eq!(warm["volume"], cold["volume"]);

    tower(12.0);
    let edited = csg(&dir, &args);
    assert_eq!(
        computed(&edited),
        ["root.children[0].children[1]", "root.children[0]", "root"]
    );
    assert_eq!(edited["cached"].as_u64(), Some(3));
    let names: Vec<&str> = edited["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|n| n["name"].as_str())
        .collect();
    assert_eq!(names, ["body", "housing"]);
}

/// The JSON chunk of a GLB file.
fn glb_json(bytes: &[u8]) -> serde_json::Value {
    let len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    serde_json::from_slice(&bytes[20..20 + len]).unwrap()
}

#[test]
fn each_writes_one_gltf_node_per_named_node() {
    let dir = scratch("each");
    std::fs::create_dir_all(dir.join("parts")).unwrap();
    meshbool::ops::write(
        dir.join("parts/tower.ply"),
        &meshbool::shapes::cube([0.0; 3], 10.0).unwrap(),
        None,
    )
    .unwrap();
    std::fs::write(dir.join("housing.json"), SCENE).unwrap();
    let report = csg(&dir, &["housing.json", "-o", "housing.glb", "--each"]);
    let bytes = std::fs::read(dir.join("housing.glb")).unwrap();
    let json = glb_json(&bytes);
    let nodes = json["nodes"].as_array().unwrap();
    let names: Vec<&str> = nodes.iter().map(|n| n["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["housing", "body"]);
    assert_eq!(
        nodes[1]["extensions"]["KHR_node_visibility"]["visible"],
        false
    );
    assert!(nodes[0].get("extensions").is_none());
    assert_eq!(nodes[1]["extras"]["csg"]["path"], "root.children[0]");
    assert_eq!(nodes[1]["extras"]["csg"]["kind"], "union");
    assert_eq!(json["extensionsUsed"][0], "KHR_node_visibility");
    // Read back: the shown node only (the root), to glTF's f32 offsets.
    let back = meshbool::ops::read(dir.join("housing.glb"), None)
        .unwrap()
        .0;
    let v = meshbool::measure::signed_volume(&back);
    let want = report["volume"].as_f64().unwrap();
    assert!((v - want).abs() < 1e-4 * want, "{v} vs {want}");
    assert_eq!(json["meshes"].as_array().unwrap().len(), 2);
    // --each needs a .glb output: a usage error.
    let out = Command::new(env!("CARGO_BIN_EXE_meshbool"))
        .current_dir(&dir)
        .args(["csg", "housing.json", "-o", "housing.stl", "--each"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("must be a .glb file"));
}
