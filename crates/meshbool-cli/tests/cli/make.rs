//! `make` and `transform`: every shape's report, transforms in command-line order, bad
//! arguments.

use crate::common::*;

#[test]
fn make_cube_then_transform_scales_and_mirrors_volume_exactly() {
    let cube = tmp("tf_cube.ply");
    let sc = cube.to_str().unwrap();
    let v = report(&["make", "cube", "-o", sc, "--json"]);
    assert_eq!(
        (&v["shape"], &v["volume"], &v["closed"]),
        (&"cube".into(), &1.0.into(), &true.into())
    );
    assert_eq!(v["bbox"]["min"], serde_json::json!([-0.5, -0.5, -0.5]));

    let out = tmp("tf_out.ply");
    let so = out.to_str().unwrap();
    let v = report(&["transform", sc, "-o", so, "--scale", "2", "--json"]);
    assert_eq!(
        (v["volume"].as_f64(), v["determinant"].as_f64()),
        (Some(8.0), Some(8.0))
    );
    assert_eq!(v["reversed"], false);
    let info = report(&["info", so, "--json"]);
    assert_eq!(
        (info["volume"].as_f64(), info["closed"].as_bool()),
        (Some(8.0), Some(true))
    );

    // A mirror: the same volume, positive, triangles reversed, still consistently oriented.
    let v = report(&["transform", sc, "-o", so, "--scale", "-1,1,1", "--json"]);
    assert_eq!(v["volume"].as_f64(), Some(1.0));
    assert_eq!(
        (&v["reversed"], &v["determinant"]),
        (&true.into(), &(-1.0).into())
    );
    let info = report(&["info", so, "--json"]);
    assert_eq!(info["inconsistent_edges"], 0);
    assert_eq!(info["volume"].as_f64(), Some(1.0));

    // The CLI prints exactly the library's report.
    use meshbool::ops;
    let mesh = ops::read(&cube, None).unwrap().0;
    let t = meshbool::Transform::scaling_xyz([-1.0, 1.0, 1.0]);
    assert_eq!(v, json(&ops::transform(&mesh, &t).unwrap().report()));
}

#[test]
fn transform_applies_operations_in_command_line_order() {
    let cube = write_cube("tf_order.ply", [0.0; 3], [1.0; 3]);
    let sc = cube.to_str().unwrap();
    let out = tmp("tf_order_out.ply");
    let so = out.to_str().unwrap();
    let bbox = |ops: &[&str]| {
        let v = report(&[&["transform", sc, "-o", so, "--json"], ops].concat());
        (v["bbox"]["min"].clone(), v["bbox"]["max"].clone())
    };
    use serde_json::json as j;
    assert_eq!(
        bbox(&["--scale", "2", "--translate", "1,0,0"]),
        (j!([1.0, 0.0, 0.0]), j!([3.0, 2.0, 2.0]))
    );
    assert_eq!(
        bbox(&["--translate", "1,0,0", "--scale", "2"]),
        (j!([2.0, 0.0, 0.0]), j!([4.0, 2.0, 2.0]))
    );
    // A quarter turn about z, exact; negative numbers as values.
    assert_eq!(
        bbox(&["--rotate", "z,90", "--translate", "-0.5,0,0"]),
        (j!([-1.5, 0.0, 0.0]), j!([-0.5, 1.0, 1.0]))
    );
    assert_eq!(
        bbox(&["--rotate", "0,0,-1,-90"]),
        (j!([-1.0, 0.0, 0.0]), j!([0.0, 1.0, 1.0]))
    );
    // --matrix (row-major, translation in the last column) is the same transform as the
    // options, bit for bit.
    let by_ops = report(&[
        "transform",
        sc,
        "-o",
        so,
        "--scale",
        "2",
        "--translate",
        "1,2,3",
        "--json",
    ]);
    let by_ops_file = std::fs::read(&out).unwrap();
    let by_matrix = report(&[
        "transform",
        sc,
        "-o",
        so,
        "--matrix",
        "2,0,0,1, 0,2,0,2, 0,0,2,3, 0,0,0,1",
        "--json",
    ]);
    assert_eq!(by_ops, by_matrix);
    assert_eq!(std::fs::read(&out).unwrap(), by_ops_file);
    assert_eq!(
        by_ops["matrix"],
        j!([2.0, 0.0, 0.0, 1.0, 0.0, 2.0, 0.0, 2.0, 0.0, 0.0, 2.0, 3.0, 0.0, 0.0, 0.0, 1.0])
    );
    // UTM-sized moves stay exact: there and back again gives the input bit for bit.
    let far = tmp("tf_far.ply");
    let sf = far.to_str().unwrap();
    let v = report(&[
        "transform",
        sc,
        "-o",
        sf,
        "--translate",
        "512345.25,7012345.5,120",
        "--json",
    ]);
    assert_eq!(v["bbox"]["min"], j!([512345.25, 7012345.5, 120.0]));
    assert_eq!(v["volume"].as_f64(), Some(1.0));
    report(&[
        "transform",
        sf,
        "-o",
        so,
        "--translate",
        "-512345.25,-7012345.5,-120",
        "--json",
    ]);
    assert_eq!(
        meshbool::ops::read(&out, None).unwrap().0,
        meshbool::ops::read(&cube, None).unwrap().0
    );
}

#[test]
fn make_every_shape_prints_the_library_report() {
    use meshbool::ops::{self, Shape};
    let out = tmp("mk_shape.ply");
    let so = out.to_str().unwrap();
    let cases: [(&[&str], Shape); 9] = [
        (
            &["cube", "--min", "-1,0,0", "--max", "1,2,0.5"],
            Shape::Cube {
                min: [-1.0, 0.0, 0.0],
                max: [1.0, 2.0, 0.5],
            },
        ),
        (
            &[
                "sphere",
                "--center",
                "1,2,3",
                "--radius",
                "2",
                "--segments",
                "24",
                "--rings",
                "12",
            ],
            Shape::Sphere {
                center: [1.0, 2.0, 3.0],
                radius: 2.0,
                segments: 24,
                rings: 12,
            },
        ),
        (
            &["cylinder"],
            Shape::Cylinder {
                base: [0.0; 3],
                radius: 1.0,
                height: 1.0,
                segments: 32,
            },
        ),
        (
            &[
                "cone",
                "--radius",
                "2",
                "--top-radius",
                "1",
                "--height",
                "3",
                "--segments",
                "4",
            ],
            Shape::Cone {
                base: [0.0; 3],
                radius: 2.0,
                top_radius: 1.0,
                height: 3.0,
                segments: 4,
            },
        ),
        (
            &[
                "plane", "--width", "4", "--depth", "2", "--nx", "4", "--ny", "2",
            ],
            Shape::Plane {
                center: [0.0; 3],
                width: 4.0,
                depth: 2.0,
                nx: 4,
                ny: 2,
            },
        ),
        // The defaults the library documents for the command line.
        (
            &["terrain"],
            Shape::Terrain {
                center: [0.0; 3],
                size: [1000.0; 2],
                cells: [100; 2],
                relief: 40.0,
                seed: 1,
            },
        ),
        (
            &[
                "terrain",
                "--center",
                "478600,6772300,400",
                "--size",
                "300,200",
                "--cells",
                "30,20",
                "--relief",
                "12.5",
                "--seed",
                "18446744073709551615",
            ],
            Shape::Terrain {
                center: [478600.0, 6772300.0, 400.0],
                size: [300.0, 200.0],
                cells: [30, 20],
                relief: 12.5,
                seed: u64::MAX,
            },
        ),
        (
            &["pit"],
            Shape::Pit {
                center: [0.0, 0.0, 60.0],
                radius: [220.0, 160.0],
                depth: 140.0,
                benches: 5,
                berm: 8.0,
                segments: 64,
            },
        ),
        (
            &[
                "pit",
                "--center",
                "1,2,-3",
                "--radius",
                "50",
                "--depth",
                "30",
                "--benches",
                "3",
                "--berm",
                "0",
                "--segments",
                "12",
            ],
            Shape::Pit {
                center: [1.0, 2.0, -3.0],
                radius: [50.0; 2],
                depth: 30.0,
                benches: 3,
                berm: 0.0,
                segments: 12,
            },
        ),
    ];
    for (args, shape) in cases {
        let cli = report(&[&["make"], args, &["-o", so, "--json"]].concat());
        let lib = ops::make(&shape).unwrap();
        assert_eq!(cli, json(&lib.report()), "{args:?}");
        // The file holds the mesh, bit for bit.
        assert_eq!(ops::read(&out, None).unwrap().0, lib.mesh, "{args:?}");
        let info = report(&["info", so, "--json"]);
        assert_eq!(
            (
                info["inconsistent_edges"].as_u64(),
                info["degenerate_triangles"].as_u64(),
                info["non_manifold_edges"].as_u64()
            ),
            (Some(0), Some(0), Some(0)),
            "{args:?}"
        );
        let open = ["plane", "terrain", "pit"].contains(&shape.name());
        assert_eq!(info["closed"], !open, "{args:?}");
    }
    // The figures the defaults give (quoted in the README).
    let t = report(&["make", "terrain", "-o", so, "--json"]);
    let p = report(&["make", "pit", "-o", so, "--json"]);
    let counts = |v: &serde_json::Value| {
        ["triangles", "vertices", "boundary_edges"].map(|k| v[k].as_u64().unwrap())
    };
    assert_eq!(
        (counts(&t), counts(&p)),
        ([20000, 10201, 400], [1216, 641, 64])
    );
    assert_eq!(
        (&t["bbox"]["min"], &t["bbox"]["max"]),
        (
            &serde_json::json!([-500.0, -500.0, -20.0]),
            &serde_json::json!([500.0, 500.0, 20.0])
        )
    );
    assert_eq!(
        (&p["bbox"]["min"], &p["bbox"]["max"]),
        (
            &serde_json::json!([-220.0, -160.0, -80.0]),
            &serde_json::json!([220.0, 160.0, 60.0])
        )
    );
    // Frustum of squares with corners on the axes (areas 8 and 2): h/3 (8 + 4 + 2) = 14.
    let v = report(&[
        "make",
        "cone",
        "--radius",
        "2",
        "--top-radius",
        "1",
        "--height",
        "3",
        "--segments",
        "4",
        "-o",
        so,
        "--json",
    ]);
    assert_eq!(v["volume"].as_f64(), Some(14.0));
}

#[test]
fn transform_and_make_refuse_bad_arguments_with_usage_errors() {
    let cube = write_cube("tf_bad.ply", [0.0; 3], [1.0; 3]);
    let (sc, so) = (cube.to_str().unwrap(), tmp("tf_bad_out.ply"));
    let so = so.to_str().unwrap();
    let t = |extra: &[&str], needle: &str| {
        usage_error(&[&["transform", sc, "-o", so], extra].concat(), needle)
    };
    t(&["--rotate", "q,45"], "unknown axis `q`");
    t(&["--rotate", "x"], "--rotate");
    t(&["--rotate", "0,0,0,45"], "not zero");
    t(
        &["--matrix", "1,0,0,0,0,1,0,0,0,0,1,0,0,0,0"],
        "expected 16 numbers",
    );
    t(&["--matrix", "1,0,0,0,0,1,0,0,0,0,1,0,0,0,1,1"], "last row");
    t(&["--matrix", "1,0,0,0,0,0,0,0,0,0,1,0,0,0,0,1"], "singular");
    t(&["--scale", "0"], "flatten");
    t(&["--scale", "1,2"], "three");
    t(&["--translate", "1,2,nan"], "finite");
    t(&["--translate", "a,b,c"], "not a number");
    t(&[], "required");
    let m =
        |args: &[&str], needle: &str| usage_error(&[&["make"], args, &["-o", so]].concat(), needle);
    m(&["cylinder", "--radius", "-1"], "must be positive");
    m(&["cylinder", "--segments", "0"], "--segments");
    m(&["sphere", "--segments", "0"], "--segments");
    m(&["sphere", "--rings", "1"], "--rings");
    m(&["cone", "--top-radius", "-1"], "0 or positive");
    m(&["cone", "--height", "0"], "must be positive");
    m(&["plane", "--nx", "0"], "--nx");
    m(&["cube", "--size", "1,0,1"], "positive");
    m(
        &["cube", "--min", "0,0,0", "--max", "1,0,1"],
        "min must be below its max",
    );
    m(&["cube", "--min", "0,0,0"], "--max");
    m(
        &["cube", "--size", "1", "--min", "0,0,0", "--max", "1,1,1"],
        "cannot be used",
    );
    m(
        &[
            "sphere",
            "--radius",
            "1e-12",
            "--center",
            "1e6,0,0",
            "--segments",
            "64",
        ],
        "too small",
    );
    m(&["terrain", "--size", "0"], "must be positive");
    m(&["terrain", "--size", "1,2,3"], "one number or two");
    m(&["terrain", "--cells", "0"], "at least 1");
    m(&["terrain", "--cells", "4,x"], "not a whole number");
    m(&["terrain", "--relief", "-1"], "0 or positive");
    m(&["terrain", "--relief", "inf"], "finite");
    m(&["terrain", "--seed=-1"], "--seed");
    m(&["terrain", "--cells", "20000"], "more than");
    m(&["pit", "--radius", "0,1"], "must be positive");
    m(&["pit", "--depth", "0"], "must be positive");
    m(&["pit", "--benches", "0"], "--benches");
    m(&["pit", "--berm", "-1"], "0 or positive");
    m(&["pit", "--segments", "2"], "--segments");
    m(&["pit", "--radius", "100"], "reach 102 in from the rim");
    m(&["torus"], "torus");
    assert!(!tmp("tf_bad_out.ply").exists());
}
