//! `docs/json.md` lists every key of every report, and nothing else: the reports of real
//! runs are checked against its tables both ways (each key written is documented; each
//! documented key is written by some run).

use std::collections::{BTreeMap, BTreeSet};

// Only its cube with corners that differ by rounding is used here.
#[allow(dead_code)]
mod common;

use meshbool::ops::{self, BooleanOptions, Checks, CurvesOptions, PieceSpec, SplitOptions};
use meshbool::repair::{CloseMode, CloseOptions, DegenerateOptions, Facing, RepairConfig};
use meshbool::shapes::heightfield;
use meshbool::{Format, Mesh, Op};
use serde_json::Value;

/// The tables of `docs/json.md`: section name → rows (key, type column).
fn doc_tables() -> BTreeMap<String, Vec<(String, String)>> {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/json.md"))
        .unwrap();
    let mut tables = BTreeMap::new();
    let mut section: Option<String> = None;
    for line in text.lines() {
        if let Some(name) = line.strip_prefix("### ") {
            section = Some(name.trim().to_lowercase());
            tables.insert(name.trim().to_lowercase(), Vec::new());
        } else if line.starts_with("## ") {
            section = None;
        } else if let (Some(s), Some(row)) = (&section, line.strip_prefix("| ")) {
            let cells: Vec<&str> = row.split(" | ").collect();
            if cells.len() < 2 || cells[0] == "key" || cells[0].starts_with("---") {
                continue;
            }
            let key = cells[0].trim_matches('`').to_string();
            tables.get_mut(s).unwrap().push((key, cells[1].to_string()));
        }
    }
    tables
}

/// The key paths a section documents, below `prefix`: `a`, `a.b` for objects, `a[].b` for
/// arrays of objects; a row referring to another section (`[Name](#name)`) takes that
/// section's keys, a row "*(the keys of [Name](#name))*" takes them at the same level.
fn documented(
    tables: &BTreeMap<String, Vec<(String, String)>>,
    section: &str,
    prefix: &str,
    out: &mut BTreeSet<String>,
) {
    let link = |s: &str| {
        let start = s.find("](#")? + 3;
        Some(s[start..start + s[start..].find(')')?].to_string())
    };
    for (key, ty) in &tables[section] {
        if key.starts_with("*(the keys of") {
            documented(tables, &link(key).unwrap(), prefix, out);
            continue;
        }
        out.insert(format!("{prefix}{key}"));
        if let Some(sub) = link(ty) {
            let sep = if ty.starts_with("array of") {
                "[]."
            } else {
                "."
            };
            documented(tables, &sub, &format!("{prefix}{key}{sep}"), out);
        }
    }
}

/// The key paths of a JSON value, in the same notation.
fn written(v: &Value, prefix: &str, out: &mut BTreeSet<String>) {
    let Value::Object(map) = v else { return };
    for (k, x) in map {
        let path = format!("{prefix}{k}");
        out.insert(path.clone());
        match x {
            Value::Object(_) => written(x, &format!("{path}."), out),
            Value::Array(items) => {
                for item in items {
                    written(item, &format!("{path}[]."), out);
                }
            }
            _ => {}
        }
    }
}

fn json(report: &impl serde::Serialize) -> Value {
    serde_json::to_value(report).unwrap()
}

/// A slab crossed by two separate boxes: groups with several components.
fn slab_and_posts() -> (Mesh, Mesh) {
    let a = Mesh::cuboid([0.0; 3], [4.0, 2.0, 1.0]);
    let mut b = Mesh::cuboid([0.5, 0.5, 0.5], [1.5, 1.5, 2.0]);
    b.append(&Mesh::cuboid([2.5, 0.5, 0.5], [3.5, 1.5, 2.0]))
        .unwrap();
    (a, b)
}

/// A terrain with a hole in the middle, a fold, a duplicate, a T-junction crack and a
/// needle: something for every repair step.
fn rough_terrain() -> Mesh {
    let m = heightfield([0.0, 0.0], [10.0, 10.0], 10, 10, |x, y| 0.1 * x * y);
    let (positions, mut triangles) = m.into_parts();
    triangles.swap_remove(100);
    triangles.push(triangles[3]);
    triangles[50].swap(1, 2);
    Mesh::new(positions, triangles).unwrap()
}

/// Each report's runs, as JSON.
fn samples() -> BTreeMap<&'static str, Vec<Value>> {
    let mut s: BTreeMap<&str, Vec<Value>> = BTreeMap::new();
    let cube = Mesh::unit_cube();
    let other = Mesh::cuboid([0.5; 3], [1.5; 3]);
    let union = ops::boolean(&cube, &other, Op::Union, &BooleanOptions::default()).unwrap();
    s.entry("boolean").or_default().push(json(&union.report()));
    // Two overlapping cubes in one mesh: resolved into their union on the way in.
    let mut two = Mesh::unit_cube();
    two.append(&other).unwrap();
    let far = Mesh::cuboid([3.0; 3], [4.0; 3]);
    let resolved = ops::boolean(&two, &far, Op::Union, &BooleanOptions::default()).unwrap();
    assert!(resolved.operands[0].resolved.is_some());
    s.entry("boolean")
        .or_default()
        .push(json(&resolved.report()));
    // More than two inputs: the `combined` key.
    let three = [&cube, &other, &far].map(ops::Input::from);
    let many = ops::boolean_many(&three, Op::Union, &BooleanOptions::default()).unwrap();
    s.entry("boolean").or_default().push(json(&many.report()));
    let r = ops::resolve(&two, &ops::ResolveOptions::default()).unwrap();
    s.entry("resolve").or_default().push(json(&r.report()));
    // Snapping at a tolerance: the `snap` keys.
    let snap = ops::ResolveOptions {
        snap: 1e-3,
        ..Default::default()
    };
    let r = ops::resolve(&two, &snap).unwrap();
    assert!(r.snap.is_some());
    s.entry("resolve").or_default().push(json(&r.report()));
    let cutter = Mesh::cuboid([0.5, -0.001, 0.5], [1.001, 1.001, 1.001]);
    // (On the arrangement as it is: the exact clean-up leaves this result nothing to snap.)
    let snapped = BooleanOptions {
        snap: 0.01,
        keep_seam_points: true,
        ..BooleanOptions::default()
    };
    let d = ops::boolean(&cube, &cutter, Op::Difference, &snapped).unwrap();
    assert!(d.snap.as_ref().is_some_and(|s| s.collapsed > 0));
    s.entry("boolean").or_default().push(json(&d.report()));
    // Shared corners one unit in the last place apart: merged at the door.
    let noisy = common::cube_off_by_an_ulp();
    // A non-manifold open sheet taken as given: where its first such edge is.
    let finned = common::finned_sheet();
    let forced = BooleanOptions {
        checks: ops::Checks {
            force: true,
            ..ops::Checks::default()
        },
        ..BooleanOptions::default()
    };
    let fin = ops::boolean(&finned, &other, Op::Union, &forced).unwrap();
    s.entry("boolean").or_default().push(json(&fin.report()));
    // A cube with one triangle wound the wrong way, not oriented at the door but taken as
    // given: where its first inconsistent edge is.
    let (positions, mut triangles) = Mesh::unit_cube().into_parts();
    triangles[0].swap(1, 2);
    let flipped = Mesh::new(positions, triangles).unwrap();
    let unoriented = BooleanOptions {
        checks: ops::Checks {
            force: true,
            orient: false,
            ..ops::Checks::default()
        },
        ..BooleanOptions::default()
    };
    let wound = ops::boolean(&flipped, &other, Op::Union, &unoriented).unwrap();
    assert!(wound.report().operands[0].inconsistent_near.is_some());
    s.entry("boolean").or_default().push(json(&wound.report()));
    let merged = ops::boolean(&noisy, &other, Op::Union, &BooleanOptions::default()).unwrap();
    assert!(merged.report().operands[0].rounding_noise.is_some());
    s.entry("boolean").or_default().push(json(&merged.report()));
    let snapped_split = SplitOptions {
        snap: 0.01,
        ..SplitOptions::default()
    };
    let sp = ops::split(&cube, &cutter, &snapped_split).unwrap();
    assert!(sp.snap.is_some());
    s.entry("split")
        .or_default()
        .push(json(&sp.report(Format::Obj)));
    let snapped_pick = ops::PickOptions {
        snap: 0.01,
        ..Default::default()
    };
    let p = ops::split(&cube, &cutter, &SplitOptions::default())
        .unwrap()
        .pick_op(Op::Difference, &snapped_pick)
        .unwrap();
    assert!(p.snap.is_some());
    s.entry("pick").or_default().push(json(&p.report()));

    let (slab, posts) = slab_and_posts();
    let split = ops::split(&slab, &posts, &SplitOptions::default()).unwrap();
    let report = split.report(Format::Obj);
    assert!(report.groups.iter().any(|g| g.components.len() == 2));
    s.entry("split").or_default().push(json(&report));
    let keep: Vec<PieceSpec> = vec!["a_out_b".parse().unwrap(), "b_in_a:flip".parse().unwrap()];
    s.entry("pick").or_default().push(json(
        &split.pick(&keep, &Default::default()).unwrap().report(),
    ));

    let curves = ops::curves(&cube, &other, &CurvesOptions::default()).unwrap();
    s.entry("curves").or_default().push(json(&curves.report()));
    let full = CurvesOptions {
        simplify: Some(0.1),
        tagged: true,
        ..CurvesOptions::default()
    };
    let curves = ops::curves(&cube, &other, &full).unwrap();
    s.entry("curves").or_default().push(json(&curves.report()));
    let points = [[0.5; 3], [2.0; 3], [1.0, 0.5, 0.5]];
    let c = ops::classify_points(&cube, &points, &Default::default()).unwrap();
    s.entry("classify").or_default().push(json(&c.report(true)));
    let ground = heightfield([0.0, 0.0], [4.0, 4.0], 2, 2, |_, _| 0.0);
    let slope = heightfield([0.0, 0.0], [4.0, 4.0], 2, 2, |x, _| x - 2.0);
    let cf = ops::cutfill(&ground, &slope, &Default::default()).unwrap();
    s.entry("cutfill").or_default().push(json(&cf.report()));
    s.entry("info")
        .or_default()
        .push(json(&ops::InfoReport::new(
            "cube",
            ops::info(&cube).unwrap(),
        )));
    s.entry("orient")
        .or_default()
        .push(json(&ops::orient(&cube, Facing::Outward).unwrap().report()));
    let mirror = meshbool::Transform::scaling_xyz([-1.0, 1.0, 1.0]).translate([5.0, 0.0, 0.0]);
    s.entry("transform")
        .or_default()
        .push(json(&ops::transform(&cube, &mirror).unwrap().report()));
    let plane = ops::Shape::Plane {
        center: [0.0; 3],
        width: 2.0,
        depth: 1.0,
        nx: 2,
        ny: 1,
    };
    s.entry("make")
        .or_default()
        .push(json(&ops::make(&plane).unwrap().report()));

    // A CSG scene with a name and a note (a cutter in a union), and one that fails.
    for text in [
        r#"{"root": {"op": "union", "name": "u", "children": [{"primitive": "cube"}, {"primitive": "sphere", "role": "cutter"}]}}"#,
        r#"{"root": {"op": "union", "children": [{"primitive": "cube"}, {"mesh": "no such file.stl"}]}}"#,
    ] {
        let scene = meshbool::csg::Scene::from_json(text, std::path::Path::new(".")).unwrap();
        let out =
            meshbool::csg::evaluate(&scene, &meshbool::csg::Cache::new(), &Default::default())
                .unwrap();
        s.entry("csg").or_default().push(json(&out.report()));
    }

    // A grid with one vertex pushed over its neighbours and raised: folded triangles.
    let (mut positions, triangles) =
        heightfield([0.0, 0.0], [4.0, 4.0], 4, 4, |x, y| 0.1 * x + 0.05 * y).into_parts();
    positions[12] = [3.6, 2.0, 1.5];
    let folded = Mesh::new(positions, triangles).unwrap();
    let env = ops::envelope(&folded, &Default::default()).unwrap();
    assert!(env.report.folded_triangles > 0 && env.report.jump_walls > 0);
    s.entry("envelope").or_default().push(json(&env.report()));

    let terrain = rough_terrain();
    let (positions, mut triangles) = Mesh::unit_cube().into_parts();
    triangles.truncate(10);
    let open_box = Mesh::new(positions, triangles).unwrap();
    for (mesh, mode) in [
        (&open_box, CloseMode::Cap),
        (&terrain, CloseMode::StitchCurtain),
    ] {
        let out = ops::close(mesh, mode, &CloseOptions::default()).unwrap();
        s.entry("close").or_default().push(json(&out.report()));
    }
    for (close, tolerance) in [
        (CloseMode::StitchCurtain, None),
        (CloseMode::Cap, Some(1e-9)),
    ] {
        let config = RepairConfig {
            weld: Some(1e-9),
            remove_duplicates: true,
            remove_overlapping: tolerance,
            weld_boundary: Some(1e-9),
            tjunctions: true,
            tjunction_tolerance: tolerance,
            degenerate: Some(DegenerateOptions::default()),
            snap: Some(1e-3),
            orient: Some(Facing::ZUp),
            remove_folds: true,
            close,
            close_gaps: Some(1.0),
            ..RepairConfig::default()
        };
        let out = ops::repair(&terrain, &config).unwrap();
        s.entry("repair").or_default().push(json(&out.report()));
    }
    // Two cubes 1e-5 apart: a weld at 1e-4 would make their facing sides one, and is
    // undone.
    let mut pair = Mesh::unit_cube();
    pair.append(&Mesh::cuboid([1.0 + 1e-5, 0.0, 0.0], [2.0, 1.0, 1.0]))
        .unwrap();
    let config = RepairConfig {
        weld: Some(1e-4),
        ..RepairConfig::default()
    };
    let out = ops::repair(&pair, &config).unwrap();
    assert_eq!(out.repair.undone.len(), 1);
    s.entry("repair").or_default().push(json(&out.report()));
    s
}

#[test]
fn docs_list_every_key_of_every_report_and_no_other() {
    let tables = doc_tables();
    let samples = samples();
    assert_eq!(samples.len(), 15);
    for (report, runs) in &samples {
        let mut doc = BTreeSet::new();
        documented(&tables, report, "", &mut doc);
        let mut all = BTreeSet::new();
        for run in runs {
            assert_eq!(run["schema"], ops::SCHEMA, "{report}");
            let mut keys = BTreeSet::new();
            written(run, "", &mut keys);
            let undocumented: Vec<_> = keys.difference(&doc).collect();
            assert!(
                undocumented.is_empty(),
                "{report}: undocumented keys {undocumented:?}"
            );
            all.extend(keys);
        }
        let unwritten: Vec<_> = doc.difference(&all).collect();
        assert!(
            unwritten.is_empty(),
            "{report}: documented, never written {unwritten:?}"
        );
    }
}

#[test]
fn operand_report_keys_are_documented_when_a_check_finds_something() {
    // A cube with a corner pushed through its bottom and a side triangle taken out:
    // self-intersections that cannot be resolved (not closed), of an open surface: taken
    // as given without forcing.
    let (mut positions, mut triangles) = Mesh::unit_cube().into_parts();
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
    let m = Mesh::new(positions, triangles).unwrap();
    let opts = BooleanOptions {
        checks: Checks {
            force: true,
            ..Checks::default()
        },
        ..BooleanOptions::default()
    };
    let far = Mesh::cuboid([3.0; 3], [4.0; 3]);
    let out = ops::boolean(&m, &far, Op::Union, &opts).unwrap();
    let v = json(&out.report());
    let s = &v["operands"][0]["self_intersections"];
    assert_eq!(s["first"].as_array().unwrap().len(), 2);
    assert_eq!(s["near"].as_array().unwrap().len(), 3);
    assert!(s["unresolved"].as_str().unwrap().contains("not closed"));
    assert_eq!(s["open_kept"], true);
    assert_eq!(v["operands"][0]["forced"], false);
    let tables = doc_tables();
    let mut doc = BTreeSet::new();
    documented(&tables, "boolean", "", &mut doc);
    let mut keys = BTreeSet::new();
    written(&v, "", &mut keys);
    assert!(keys.is_subset(&doc), "{:?}", keys.difference(&doc));
}

#[test]
fn docs_list_every_key_of_the_repair_configuration() {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/json.md"))
        .unwrap();
    let section = text
        .split("\n## ")
        .find(|s| s.starts_with("Repair configuration"))
        .expect("a section on the repair configuration");
    let documented: BTreeSet<String> = section
        .lines()
        .filter_map(|l| l.strip_prefix("| `"))
        .map(|l| l[..l.find('`').unwrap()].to_string())
        .collect();
    let Value::Object(keys) = json(&RepairConfig::default()) else {
        panic!("an object")
    };
    let keys: BTreeSet<String> = keys.keys().cloned().collect();
    assert_eq!(documented, keys);
    // The defaults the table gives.
    let c: RepairConfig = serde_json::from_str("{}").unwrap();
    assert_eq!(c, RepairConfig::default());
    assert_eq!(json(&c)["orient"], "majority");
    assert_eq!(json(&c)["close"], "none");
    assert_eq!(
        json(&c)["close_options"],
        serde_json::json!({"stitch_max_gap": null, "floor_offset": 10.0})
    );
    assert_eq!(
        json(&DegenerateOptions::default()),
        serde_json::json!({"min_area": 0.0, "max_aspect": null})
    );
}
