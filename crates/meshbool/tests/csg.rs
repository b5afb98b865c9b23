//! CSG documents (`meshbool::csg`): a scene evaluates to the booleans chained by hand,
//! edits recompute only their path, the cache folder returns the same bytes and survives
//! damage, failures are values.

use std::path::PathBuf;

use meshbool::csg::{evaluate, Cache, CsgOptions, Scene, Source};
use meshbool::measure::{mesh_stats, signed_volume};
use meshbool::ops::{self, boolean_many, difference_many, BooleanOptions, Input, RunOptions};
use meshbool::{shapes, Mesh, Op, Transform};

/// A fresh scratch folder for `name`.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("meshbool-csg-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The area of the 64-gon of circumradius 3 that `cylinder` tessellates.
fn polygon_area() -> f64 {
    0.5 * 64.0 * 9.0 * (std::f64::consts::TAU / 64.0).sin()
}

/// A housing of depth 4: (cube ∩ box) ∪ a mesh file, less a drilled cylinder and
/// everything behind a plane at z = 4. `big` is the half size of the box.
fn housing(big: [f64; 3]) -> String {
    format!(
        r#"{{ "root": {{ "op": "difference", "name": "housing", "children": [
        {{ "op": "union", "name": "body", "children": [
            {{ "op": "intersection", "children": [
                {{ "primitive": "cube", "size": [40, 20, 10] }},
                {{ "primitive": "cube", "min": [{}, {}, {}], "max": [{}, {}, {}] }} ] }},
            {{ "mesh": "parts/tower.ply", "transform": [{{ "rotate": ["z", 90] }}, {{ "translate": [0, 0, 10] }}] }} ] }},
        {{ "primitive": "cylinder", "radius": 3, "height": 30, "base": [0, 0, -15], "segments": 64, "role": "cutter" }},
        {{ "primitive": "plane", "width": 100, "depth": 100, "transform": {{ "translate": [0, 0, 4] }}, "role": "cutter" }} ] }} }}"#,
        -big[0], -big[1], -big[2], big[0], big[1], big[2]
    )
}

/// Writes the housing's mesh file (a 10 × 10 × 10 cube about the origin) under `dir`.
fn write_tower(dir: &std::path::Path) {
    std::fs::create_dir_all(dir.join("parts")).unwrap();
    ops::write(
        dir.join("parts/tower.ply"),
        &shapes::cube([0.0; 3], 10.0).unwrap(),
        None,
    )
    .unwrap();
}

#[test]
fn a_deep_scene_is_the_booleans_chained_by_hand() {
    let dir = scratch("deep");
    write_tower(&dir);
    let scene = Scene::from_json(&housing([19.0, 11.0, 6.0]), &dir).unwrap();
    let out = evaluate(&scene, &Cache::new(), &CsgOptions::default()).unwrap();
    assert!(out.failed.is_none(), "{:?}", out.failed);
    let mesh = out.mesh.clone().unwrap();

    // By hand, with the same calls.
    let o = BooleanOptions::default();
    let cube = shapes::cuboid([-20.0, -10.0, -5.0], [20.0, 10.0, 5.0]).unwrap();
    let bigbox = shapes::cuboid([-19.0, -11.0, -6.0], [19.0, 11.0, 6.0]).unwrap();
    let i = boolean_many(
        &[Input::from(&cube), Input::from(&bigbox)],
        Op::Intersection,
        &o,
    )
    .unwrap();
    let tower = ops::read(dir.join("parts/tower.ply"), None).unwrap().0;
    let t = Transform::rotation_z(90.0).translate([0.0, 0.0, 10.0]);
    let tower = ops::transform(&tower, &t).unwrap().mesh;
    let u = boolean_many(&[Input::from(&i.mesh), Input::from(&tower)], Op::Union, &o).unwrap();
    let cyl = shapes::cylinder([0.0, 0.0, -15.0], 3.0, 30.0, 64).unwrap();
    let plane = shapes::plane([0.0; 3], 100.0, 100.0, 1, 1).unwrap();
    let plane = ops::transform(&plane, &Transform::translation([0.0, 0.0, 4.0]))
        .unwrap()
        .mesh;
    let by_hand = difference_many(
        &[Input::from(&u.mesh), Input::from(&cyl), Input::from(&plane)],
        &o,
    )
    .unwrap();
    assert_eq!(mesh, by_hand.mesh);

    // The geometry: above z = 4, the slab 38 × 20 × 1 and the tower 10 × 10 × 10, less
    // the drill's 11 units of length; closed.
    let s = mesh_stats(&mesh);
    assert_eq!((s.boundary_edges, s.non_manifold_edges), (0, 0));
    let expected = 760.0 + 1000.0 - 11.0 * polygon_area();
    assert!(
        (s.volume - expected).abs() < 1e-9 * expected,
        "{} vs {expected}",
        s.volume
    );
    assert!(mesh.bounds().unwrap().min[2] == 4.0);

    // The report: every node, children first; the intersection's measures.
    let paths: Vec<&str> = out.nodes.iter().map(|n| n.path.as_str()).collect();
    assert_eq!(
        paths,
        [
            "root.children[0].children[0].children[0]",
            "root.children[0].children[0].children[1]",
            "root.children[0].children[0]",
            "root.children[0].children[1]",
            "root.children[0]",
            "root.children[1]",
            "root.children[2]",
            "root",
        ]
    );
    let inter = out.nodes[2].result.unwrap();
    assert_eq!(inter.volume, 7600.0);
    assert_eq!(out.nodes[4].name.as_deref(), Some("body"));
    assert_eq!(out.nodes[4].result.unwrap().volume, 8600.0);
    assert!(out.nodes.iter().all(|n| n.source == Source::Computed));
}

#[test]
fn an_edit_recomputes_only_its_path() {
    let dir = scratch("edit");
    write_tower(&dir);
    let cache = Cache::new();
    let opts = CsgOptions::default();
    let first = evaluate(
        &Scene::from_json(&housing([19.0, 11.0, 6.0]), &dir).unwrap(),
        &cache,
        &opts,
    )
    .unwrap();
    assert_eq!(first.computed().len(), 8);
    // The same scene again: the root from memory, nothing below it visited.
    let again = evaluate(
        &Scene::from_json(&housing([19.0, 11.0, 6.0]), &dir).unwrap(),
        &cache,
        &opts,
    )
    .unwrap();
    assert!(again.computed().is_empty());
    assert_eq!(again.nodes.len(), 1);
    assert_eq!(again.mesh, first.mesh);
    // One leaf edited: it and its three ancestors are computed; the siblings on the way
    // come from memory.
    let edited = evaluate(
        &Scene::from_json(&housing([18.0, 11.0, 6.0]), &dir).unwrap(),
        &cache,
        &opts,
    )
    .unwrap();
    assert_eq!(
        edited.computed(),
        [
            "root.children[0].children[0].children[1]",
            "root.children[0].children[0]",
            "root.children[0]",
            "root",
        ]
    );
    let from_memory: Vec<&str> = edited
        .nodes
        .iter()
        .filter(|n| n.source == Source::Memory)
        .map(|n| n.path.as_str())
        .collect();
    assert_eq!(
        from_memory,
        [
            "root.children[0].children[0].children[0]",
            "root.children[0].children[1]",
            "root.children[1]",
            "root.children[2]",
        ]
    );
    let v = signed_volume(edited.mesh.as_ref().unwrap());
    let expected = 36.0 * 20.0 + 1000.0 - 11.0 * polygon_area();
    assert!((v - expected).abs() < 1e-9 * expected, "{v} vs {expected}");
    // A changed mesh file changes its leaf's key: that path only.
    ops::write(
        dir.join("parts/tower.ply"),
        &shapes::cube([0.0; 3], 8.0).unwrap(),
        None,
    )
    .unwrap();
    let moved = evaluate(
        &Scene::from_json(&housing([18.0, 11.0, 6.0]), &dir).unwrap(),
        &cache,
        &opts,
    )
    .unwrap();
    assert_eq!(
        moved.computed(),
        ["root.children[0].children[1]", "root.children[0]", "root"]
    );
}

#[test]
fn the_cache_folder_returns_the_same_bytes_and_survives_damage() {
    let dir = scratch("folder");
    write_tower(&dir);
    let store = dir.join("cache");
    let scene = Scene::from_json(&housing([19.0, 11.0, 6.0]), &dir).unwrap();
    let opts = CsgOptions::default();
    let cold = evaluate(&scene, &Cache::in_dir(&store).unwrap(), &opts).unwrap();
    // One entry per node.
    let entries = std::fs::read_dir(&store).unwrap().count();
    assert_eq!(entries, 8);
    // A new process (a new cache on the same folder): the root from disk.
    let warm = evaluate(&scene, &Cache::in_dir(&store).unwrap(), &opts).unwrap();
    assert_eq!(warm.nodes.len(), 1);
    assert_eq!(warm.nodes[0].source, Source::Disk);
    assert_eq!(warm.mesh, cold.mesh);
    let bits = |m: &Mesh| -> Vec<u64> {
        m.positions()
            .iter()
            .flatten()
            .map(|x| x.to_bits())
            .collect()
    };
    assert_eq!(
        bits(warm.mesh.as_ref().unwrap()),
        bits(cold.mesh.as_ref().unwrap())
    );
    // The root's entry truncated: recomputed (its children from disk), noted, rewritten.
    let root = store.join(format!("{}.mbcsg", cold.nodes.last().unwrap().key));
    let whole = std::fs::metadata(&root).unwrap().len();
    let bytes = std::fs::read(&root).unwrap();
    std::fs::write(&root, &bytes[..bytes.len() / 2]).unwrap();
    let repaired = evaluate(&scene, &Cache::in_dir(&store).unwrap(), &opts).unwrap();
    assert_eq!(repaired.mesh, cold.mesh);
    let top = repaired.nodes.last().unwrap();
    assert_eq!(top.source, Source::Computed);
    assert!(
        top.notes.iter().any(|n| n.contains("recomputed")),
        "{:?}",
        top.notes
    );
    // Below it: its children from disk (the body's subtree not visited).
    let below: Vec<(&str, Source)> = repaired.nodes[..repaired.nodes.len() - 1]
        .iter()
        .map(|n| (n.path.as_str(), n.source))
        .collect();
    assert_eq!(
        below,
        [
            ("root.children[0]", Source::Disk),
            ("root.children[1]", Source::Disk),
            ("root.children[2]", Source::Disk),
        ]
    );
    assert_eq!(std::fs::metadata(&root).unwrap().len(), whole);
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let dir = scratch("threads");
    write_tower(&dir);
    let scene = Scene::from_json(&housing([19.0, 11.0, 6.0]), &dir).unwrap();
    let with = |n| {
        let opts = CsgOptions {
            boolean: BooleanOptions {
                run: RunOptions {
                    threads: Some(n),
                    ..RunOptions::default()
                },
                ..BooleanOptions::default()
            },
            ..CsgOptions::default()
        };
        evaluate(&scene, &Cache::new(), &opts)
            .unwrap()
            .mesh
            .unwrap()
    };
    assert_eq!(with(1), with(3));
}

#[test]
fn failures_are_values_and_cutters_outside_a_difference_are_noted() {
    let dir = scratch("fail");
    let scene = Scene::from_json(
        r#"{ "root": { "op": "union", "children": [
            { "primitive": "cube" },
            { "mesh": "missing.stl" },
            { "primitive": "sphere", "role": "cutter" } ] } }"#,
        &dir,
    )
    .unwrap();
    let out = evaluate(&scene, &Cache::new(), &CsgOptions::default()).unwrap();
    assert!(out.mesh.is_none());
    let failed = out.failed.unwrap();
    assert_eq!(failed.path, "root.children[1]");
    assert!(failed.error.contains("missing.stl"), "{}", failed.error);
    let root = out.nodes.last().unwrap();
    assert_eq!(root.error.as_deref(), Some("root.children[1] failed"));

    // The cutter in a union: ignored, with a note; the union of the cube alone.
    let scene = Scene::from_json(
        r#"{ "root": { "op": "union", "children": [
            { "primitive": "cube", "size": 2 },
            { "primitive": "sphere", "role": "cutter" } ] } }"#,
        &dir,
    )
    .unwrap();
    let out = evaluate(&scene, &Cache::new(), &CsgOptions::default()).unwrap();
    assert_eq!(signed_volume(out.mesh.as_ref().unwrap()), 8.0);
    let notes = &out.nodes.last().unwrap().notes;
    assert!(
        notes
            .iter()
            .any(|n| n.contains("root.children[1] is a cutter: ignored in a union")),
        "{notes:?}"
    );

    // Empty results are results: an intersection of disjoint cubes, less a cutter.
    let scene = Scene::from_json(
        r#"{ "root": { "op": "difference", "children": [
            { "op": "intersection", "children": [
                { "primitive": "cube" }, { "primitive": "cube", "center": [5, 0, 0] } ] },
            { "primitive": "sphere", "role": "cutter" } ] } }"#,
        &dir,
    )
    .unwrap();
    let out = evaluate(&scene, &Cache::new(), &CsgOptions::default()).unwrap();
    assert!(out.failed.is_none());
    assert_eq!(out.mesh.unwrap().triangle_count(), 0);
}

#[test]
fn mesh_leaves_may_name_meshes_given_beside_the_document() {
    let meshes = [std::sync::Arc::new(Mesh::cuboid([0.0; 3], [2.0; 3]))];
    let text = r#"{ "root": { "op": "difference", "children": [
        { "mesh": 0 }, { "primitive": "cube", "min": [1, 1, 1], "max": [3, 3, 3] } ] } }"#;
    let scene = Scene::from_json_with(text, std::path::Path::new("."), &meshes).unwrap();
    let out = evaluate(&scene, &Cache::new(), &CsgOptions::default()).unwrap();
    assert_eq!(signed_volume(out.mesh.as_ref().unwrap()), 7.0);
    let e = Scene::from_json_with(
        text.replace("0 }", "1 }").as_str(),
        std::path::Path::new("."),
        &meshes,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("root.children[0].mesh: mesh 1 is not one of the 1 meshes"),
        "{e}"
    );
    assert!(Scene::from_json(text, std::path::Path::new(".")).is_err());
}

#[test]
fn named_nodes_are_given_where_they_lie_in_the_root() {
    let dir = scratch("named");
    write_tower(&dir);
    // The body moved up by 100 as a whole: its named result lies there too.
    let text = housing([19.0, 11.0, 6.0]).replacen(
        r#""name": "body","#,
        r#""name": "body", "transform": { "translate": [0, 0, 100] },"#,
        1,
    );
    let scene = Scene::from_json(&text, &dir).unwrap();
    let opts = CsgOptions {
        named: true,
        ..CsgOptions::default()
    };
    let cache = Cache::new();
    for round in 0..2 {
        // The second time the root comes from the cache: the named results too.
        let out = evaluate(&scene, &cache, &opts).unwrap();
        let names: Vec<(&str, &str)> = out
            .named
            .iter()
            .map(|n| (n.name.as_str(), n.path.as_str()))
            .collect();
        assert_eq!(
            names,
            [("housing", "root"), ("body", "root.children[0]")],
            "round {round}"
        );
        assert_eq!(*out.named[0].mesh, out.mesh.clone().unwrap());
        let body = &out.named[1].mesh;
        assert_eq!(signed_volume(body), 8600.0);
        assert_eq!(body.bounds().unwrap().min[2], 95.0);
    }
}

#[test]
fn malformed_documents_say_where() {
    let dir = std::path::Path::new(".");
    let err = |text: &str| Scene::from_json(text, dir).unwrap_err().to_string();
    let cases = [
        (
            r#"{ "root": { "op": "union", "children": [ { "primitive": "sphere", "radus": 2 } ] } }"#,
            "root.children[0].radus: unknown key",
        ),
        (
            r#"{ "root": { "op": "carve", "children": [] } }"#,
            "root.op: unknown operation `carve`",
        ),
        (
            r#"{ "root": { "primitive": "sphere", "radius": -1 } }"#,
            "root: ",
        ),
        (
            r#"{ "root": { "primitive": "cube", "transform": { "scale": 0 } } }"#,
            "root.transform.scale: a scale factor of 0",
        ),
        (
            r#"{ "root": { "primitive": "cube", "transform": [ { "rotate": ["w", 3] } ] } }"#,
            "root.transform[0].rotate[0]: unknown axis `w`",
        ),
        (
            r#"{ "root": { "primitive": "cube", "transform": { "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 1] } } }"#,
            "root.transform.matrix: the matrix's last row must be 0 0 0 1",
        ),
        (
            r#"{ "root": { "mesh": "a.stl", "primitive": "cube" } }"#,
            "root: a node is one of op, mesh, primitive; got mesh and primitive",
        ),
        (
            r#"{ "root": { "op": "union" } }"#,
            "root: an operation needs children",
        ),
        (
            r#"{ "root": { "primitive": "cube", "role": "drill" } }"#,
            "root.role: unknown role `drill`",
        ),
        (r#"{ "roots": {} }"#, "roots: unknown key"),
        ("{ \"root\": ", "line 1 column 10: not JSON"),
    ];
    for (text, expected) in cases {
        let e = err(text);
        assert!(
            e.contains(expected),
            "{text}\n  gave: {e}\n  expected: {expected}"
        );
    }
}

/// A molecule: `atoms` spheres on a helix, each bonded to the next by a cylinder.
fn molecule(atoms: usize) -> String {
    let mut children = Vec::new();
    for k in 0..atoms {
        let a = k as f64 * 0.7;
        let (x, y, z) = (4.0 * a.cos(), 4.0 * a.sin(), k as f64 * 0.9);
        children.push(format!(
            r#"{{ "primitive": "sphere", "center": [{x}, {y}, {z}], "radius": 1.1, "segments": 12, "rings": 6 }}"#
        ));
        if k + 1 < atoms {
            // A bond along z, turned toward the next atom: ranged as a segment of the helix.
            let b = (k + 1) as f64 * 0.7;
            let d = [4.0 * b.cos() - x, 4.0 * b.sin() - y, 0.9];
            let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let axis = [-d[1], d[0], 0.0];
            let angle = (d[2] / len).acos().to_degrees();
            children.push(format!(
                r#"{{ "primitive": "cylinder", "radius": 0.35, "height": {len}, "segments": 8,
                     "transform": [ {{ "rotate": [{}, {}, {}, {angle}] }}, {{ "translate": [{x}, {y}, {z}] }} ] }}"#,
                axis[0], axis[1], axis[2]
            ));
        }
    }
    format!(
        r#"{{ "root": {{ "op": "union", "children": [ {} ] }} }}"#,
        children.join(",\n")
    )
}

#[test]
fn a_molecule_unites_in_one_call_closed() {
    let scene = Scene::from_json(&molecule(1000), std::path::Path::new(".")).unwrap();
    let out = evaluate(&scene, &Cache::new(), &CsgOptions::default()).unwrap();
    let mesh = out.mesh.unwrap();
    let s = mesh_stats(&mesh);
    assert_eq!((s.boundary_edges, s.non_manifold_edges), (0, 0));
    assert_eq!(out.nodes.len(), 2000);
    // Less than the parts' volumes (they overlap), more than the spheres' alone less
    // their overlaps' bound (each sphere shares at most two caps with bonds and
    // neighbours).
    let parts: f64 = out.nodes[..1999]
        .iter()
        .map(|n| n.result.unwrap().volume)
        .sum();
    assert!(
        s.volume < parts && s.volume > 0.5 * parts,
        "{} of {parts}",
        s.volume
    );
}

/// docs/csg.schema.json and the parser agree: every property the schema gives a node
/// kind is read (a sample value of its type), and a property it does not give is refused.
#[test]
fn the_schema_names_what_the_parser_reads() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../docs/csg.schema.json"
    ))
    .unwrap();
    let schema: serde_json::Value = serde_json::from_str(&text).unwrap();
    let defs = &schema["$defs"];
    let sample = |prop: &serde_json::Value| -> serde_json::Value {
        let r = prop["$ref"].as_str().unwrap_or("");
        match r.rsplit('/').next().unwrap() {
            "point" => serde_json::json!([0.25, 0.5, 0.75]),
            "count" => serde_json::json!(3),
            "number" | "triple" => serde_json::json!(0.5),
            "pair" => serde_json::json!([300, 250]),
            "name" => serde_json::json!("part"),
            "role" => serde_json::json!("cutter"),
            "transform" => {
                serde_json::json!([{ "scale": 2, "rotate": ["x", 30] }, { "matrix": [1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] }])
            }
            _ => match prop.get("type").and_then(|t| t.as_str()) {
                Some("integer") => serde_json::json!(7),
                Some("string") => serde_json::json!("tower.ply"),
                _ => serde_json::json!(4),
            },
        }
    };
    let kinds = defs["node"]["oneOf"].as_array().unwrap();
    for k in kinds {
        let name = k["$ref"].as_str().unwrap().rsplit('/').next().unwrap();
        let def = &defs[name];
        let props = def["properties"].as_object().unwrap();
        let required: Vec<&str> = def["required"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| r.as_str().unwrap())
            .collect();
        let mut base = serde_json::Map::new();
        for r in &required {
            let v = match (name, *r) {
                ("op", "op") => serde_json::json!("union"),
                ("op", "children") => serde_json::json!([{ "primitive": "cube" }]),
                ("mesh", "mesh") => serde_json::json!("tower.ply"),
                (_, "primitive") => props["primitive"]["const"].clone(),
                _ => sample(&props[*r]),
            };
            base.insert(r.to_string(), v);
        }
        for (p, schema_of) in props {
            if required.contains(&p.as_str()) {
                continue;
            }
            let mut node = base.clone();
            node.insert(p.clone(), sample(schema_of));
            if name == "cube" && (p == "min" || p == "max") {
                node.insert("min".into(), serde_json::json!([0, 0, 0]));
                node.insert("max".into(), serde_json::json!([1, 2, 3]));
            }
            let doc = serde_json::json!({ "root": node });
            Scene::from_value(&doc, std::path::Path::new("."))
                .unwrap_or_else(|e| panic!("{name}.{p}: {e}"));
        }
        let mut extra = base.clone();
        extra.insert("colour".into(), serde_json::json!(1));
        let e = Scene::from_value(
            &serde_json::json!({ "root": extra }),
            std::path::Path::new("."),
        )
        .unwrap_err();
        assert!(
            e.to_string().contains("root.colour: unknown key"),
            "{name}: {e}"
        );
    }
}
