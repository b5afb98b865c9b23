//! Mining workflows: cut and fill, badly wound blocks cut by a terrain.

use crate::common::*;

#[test]
fn cutfill_of_a_slope_against_flat_ground() {
    // Ground z = 0 and a slope z = x − 2 over [0, 4]²: cut and fill 4 · 2 · 2 / 2 = 8 each,
    // meeting along x = 2 (length 4).
    let ground = tmp("cf_ground.ply");
    let slope = tmp("cf_slope.ply");
    let flat = meshbool::shapes::heightfield([0.0, 0.0], [4.0, 4.0], 2, 2, |_, _| 0.0);
    let tilted = meshbool::shapes::heightfield([0.0, 0.0], [4.0, 4.0], 2, 2, |x, _| x - 2.0);
    meshbool::io::write_path(&ground, &flat).unwrap();
    meshbool::io::write_path(&slope, &tilted).unwrap();
    let lines = tmp("cf_lines.json");
    let v = report(&[
        "cutfill",
        ground.to_str().unwrap(),
        slope.to_str().unwrap(),
        "-o",
        lines.to_str().unwrap(),
        "--json",
    ]);
    for (k, want) in [
        ("cut", 8.0),
        ("fill", 8.0),
        ("net", 0.0),
        ("common_plan_area", 16.0),
    ] {
        let got = v[k].as_f64().unwrap();
        assert!((got - want).abs() < 1e-12, "{k}: {got}");
    }
    assert_eq!(v["zero_lines"], 1);
    let written: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&lines).unwrap()).unwrap();
    assert_eq!(written.as_array().unwrap().len(), 1);
    // A missing file is a clear error, exit 1.
    let out = meshbool(&["cutfill", ground.to_str().unwrap(), "nope.obj"]);
    assert_eq!(out.status.code(), Some(1));
}

#[test]
fn a_badly_wound_block_is_oriented_and_cut_by_the_terrain() {
    // A closed block through the terrain, two of its triangles (on its bottom and its top:
    // no edge in common) reversed, 6 inconsistent edges: the door orients it; the parts
    // above and below the terrain add up to the oriented block.
    let block = tmp("wound_block.ply");
    let (positions, mut triangles) =
        meshbool::Mesh::cuboid([-47.5, -38.75, -60.0], [71.25, 52.5, 60.0]).into_parts();
    triangles[0].swap(1, 2);
    triangles[3].swap(1, 2);
    let wound = meshbool::Mesh::new(positions, triangles).unwrap();
    meshbool::io::write_path(&block, &wound).unwrap();
    let terrain = terrain(O);
    let info = report(&["info", "--json", block.to_str().unwrap()]);
    assert_eq!(
        (&info["inconsistent_edges"], &info["closed"]),
        (&6.into(), &true.into())
    );
    let oriented = tmp("conv_oriented.ply");
    let o = report(&[
        "orient",
        block.to_str().unwrap(),
        "-o",
        oriented.to_str().unwrap(),
        "--outward",
        "--json",
    ]);
    assert_eq!(
        (&o["conflicting_edges"], &o["flipped"]),
        (&0.into(), &2.into())
    );
    let whole = report(&["info", "--json", oriented.to_str().unwrap()])["volume"]
        .as_f64()
        .unwrap();
    assert_eq!(whole, 118.75 * 91.25 * 120.0);
    let part = |op: &str| {
        let out = tmp(&format!("conv_{op}.ply"));
        let v = report(&[
            op,
            block.to_str().unwrap(),
            terrain.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--json",
        ]);
        assert_eq!(v["closed"], true, "{op}");
        v["volume"].as_f64().unwrap()
    };
    let (above, below) = (part("difference"), part("intersection"));
    assert!(above > 0.0 && below > 0.0);
    assert!(
        (above + below - whole).abs() < 1e-9 * whole,
        "{above} + {below} vs {whole}"
    );
}
