use serde_json::json;

use super::super::{detect_format, read_bytes, write};
use super::*;
use crate::measure::signed_volume;

fn to_glb(mesh: &Mesh) -> Vec<u8> {
    let mut out = Vec::new();
    write(&mut out, mesh, Format::Glb).unwrap();
    out
}

/// A GLB by hand: `json` padded with spaces, then `bin` (if any) padded with zeros.
fn assemble(json: &serde_json::Value, bin: Option<&[u8]>) -> Vec<u8> {
    let mut j = serde_json::to_vec(json).unwrap();
    j.resize(j.len().next_multiple_of(4), b' ');
    let mut chunks = Vec::new();
    chunks.extend_from_slice(&(j.len() as u32).to_le_bytes());
    chunks.extend_from_slice(&CHUNK_JSON.to_le_bytes());
    chunks.extend_from_slice(&j);
    if let Some(bin) = bin {
        let mut b = bin.to_vec();
        b.resize(b.len().next_multiple_of(4), 0);
        chunks.extend_from_slice(&(b.len() as u32).to_le_bytes());
        chunks.extend_from_slice(&CHUNK_BIN.to_le_bytes());
        chunks.extend_from_slice(&b);
    }
    let mut out = b"glTF".to_vec();
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&((12 + chunks.len()) as u32).to_le_bytes());
    out.extend(chunks);
    out
}

fn f32s(values: &[f32]) -> Vec<u8> {
    values.iter().flat_map(|x| x.to_le_bytes()).collect()
}

/// The message of the parse error reading `bytes` gives, and its byte.
fn glb_err(bytes: &[u8]) -> (u64, String) {
    match read_bytes(bytes, Format::Glb) {
        Err(Error::Parse {
            format: Format::Glb,
            location: Location::Byte(at),
            message,
        }) => (at, message),
        other => panic!("expected a GLB parse error, got {other:?}"),
    }
}

/// One triangle (1,0,0), (0,1,0), (0,0,1) with `u16` indices 0 1 2: 36 + 6 bytes.
fn triangle_bin() -> Vec<u8> {
    let mut bin = f32s(&[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]);
    for i in [0u16, 1, 2] {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    bin
}

/// The glTF of [`triangle_bin`] with `nodes` and the rest given.
fn triangle_gltf(extra: serde_json::Value) -> serde_json::Value {
    let mut g = json!({
        "asset": {"version": "2.0"},
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "accessors": [
            {"bufferView": 0, "componentType": FLOAT, "count": 3, "type": "VEC3"},
            {"bufferView": 1, "componentType": UNSIGNED_SHORT, "count": 3, "type": "SCALAR"},
        ],
        "bufferViews": [
            {"buffer": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 6},
        ],
        "buffers": [{"byteLength": 42}],
    });
    for (k, v) in extra.as_object().unwrap() {
        g[k] = v.clone();
    }
    g
}

#[test]
fn glb_cube_round_trips_exactly() {
    let m = Mesh::cuboid([-1.5, 2.25, 3.0], [4.0, 5.5, 6.125]);
    let bytes = to_glb(&m);
    assert_eq!(bytes.len() % 4, 0);
    assert_eq!(detect_format(&bytes, None), Some(Format::Glb));
    let back = read_bytes(&bytes, Format::Glb).unwrap();
    // Offsets from the centre are small dyadic numbers: exact in f32.
    assert_eq!(back, m);
    assert_eq!(signed_volume(&back), 5.5 * 3.25 * 3.125);
}

#[test]
fn glb_writes_what_the_specification_asks() {
    let m = Mesh::cuboid(
        [478_600.0, 6_772_300.0, 350.0],
        [478_610.0, 6_772_320.0, 380.5],
    );
    let bytes = to_glb(&m);
    assert_eq!(&bytes[..4], b"glTF");
    assert_eq!(u32_at(&bytes, 4), 2);
    assert_eq!(u32_at(&bytes, 8) as usize, bytes.len());
    let json_len = u32_at(&bytes, 12) as usize;
    assert_eq!(json_len % 4, 0);
    assert_eq!(u32_at(&bytes, 16), CHUNK_JSON);
    let text = &bytes[20..20 + json_len];
    let g: serde_json::Value = serde_json::from_slice(text).unwrap();
    assert_eq!(u32_at(&bytes, 20 + json_len + 4), CHUNK_BIN);
    let bin_len = u32_at(&bytes, 20 + json_len) as usize;
    assert_eq!(bin_len, 8 * 12 + 12 * 12);
    assert_eq!(bytes.len(), 28 + json_len + bin_len);
    assert_eq!(
        g["asset"],
        json!({"version": "2.0", "generator": "meshbool"})
    );
    assert_eq!(g["scenes"], json!([{"nodes": [0]}]));
    assert_eq!(
        g["nodes"][0]["translation"],
        json!([478_605.0, 6_772_310.0, 365.25])
    );
    let prim = &g["meshes"][0]["primitives"][0];
    assert_eq!(prim["mode"], 4);
    let pos = &g["accessors"][prim["attributes"]["POSITION"].as_u64().unwrap() as usize];
    assert_eq!(
        (&pos["componentType"], &pos["type"], &pos["count"]),
        (&json!(FLOAT), &json!("VEC3"), &json!(8))
    );
    assert_eq!(pos["min"], json!([-5.0, -10.0, -15.25]));
    assert_eq!(pos["max"], json!([5.0, 10.0, 15.25]));
    let idx = &g["accessors"][prim["indices"].as_u64().unwrap() as usize];
    assert_eq!(
        (&idx["componentType"], &idx["type"], &idx["count"]),
        (&json!(UNSIGNED_INT), &json!("SCALAR"), &json!(36))
    );
}

#[test]
fn glb_keeps_utm_coordinates_to_the_f32_rounding_of_local_offsets() {
    let centre = [478_600.0, 6_772_300.0, 350.0];
    let m = crate::shapes::uv_sphere(centre, 25.0, 64, 48);
    let back = read_bytes(&to_glb(&m), Format::Glb).unwrap();
    assert_eq!(back.triangles, m.triangles);
    assert_eq!(back.positions.len(), m.positions.len());
    // Bound per coordinate: the offset from the origin (at most half the box's size h)
    // rounded to f32, relative error 2^-24, plus the f64 roundings of taking the origin
    // off and adding it back (each at most half an ulp of the coordinate: 2^-53 |p|).
    let b = m.bounds().unwrap();
    let half = b.size().map(|s| s / 2.0);
    let (mut worst, mut worst_f32) = (0.0f64, 0.0f64);
    for (p, q) in m.positions.iter().zip(&back.positions) {
        for k in 0..3 {
            let e = (p[k] - q[k]).abs();
            let bound = half[k] * 2f64.powi(-24) + p[k].abs() * 2f64.powi(-52);
            assert!(e <= bound, "{p:?} came back as {q:?}: {e} > {bound}");
            worst = worst.max(e);
            worst_f32 = worst_f32.max((p[k] - f64::from(p[k] as f32)).abs());
        }
    }
    eprintln!("UTM sphere: largest coordinate error {worst:e} m (absolute f32: {worst_f32:e} m)");
    assert!(worst < 2e-6, "{worst}");
    // Absolute f32 coordinates would be off by up to a quarter metre in y.
    assert!(
        worst_f32 > 0.1 && worst < worst_f32 * 1e-5,
        "{worst} {worst_f32}"
    );
    // Volume: each coordinate within 2^-24 of the radius, relatively, so the volume
    // within about 3 · 2^-24.
    let (v, w) = (signed_volume(&m), signed_volume(&back));
    let rel = (w - v).abs() / v;
    eprintln!("UTM sphere: relative volume change {rel:e}");
    assert!(rel <= 3.0 * 2f64.powi(-24), "{rel}");
}

#[test]
fn glb_node_hierarchy_applies_transforms() {
    let nodes = json!([
        {"translation": [10.0, 20.0, 30.0], "children": [1]},
        {"scale": [2.0, 3.0, 4.0], "mesh": 0},
        // 90 degrees about z, then 5 along x, column-major.
        {"matrix": [0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1], "mesh": 0},
        // 180 degrees about z, then down 1.
        {"rotation": [0.0, 0.0, 1.0, 0.0], "translation": [0.0, 0.0, -1.0], "mesh": 0},
        // A mirror: the triangle is turned over to keep facing the same way.
        {"scale": [-1.0, 1.0, 1.0], "mesh": 0},
        // Not in the scene.
        {"translation": [100.0, 0.0, 0.0], "mesh": 0},
    ]);
    let want_positions = vec![
        [12.0, 20.0, 30.0],
        [10.0, 23.0, 30.0],
        [10.0, 20.0, 34.0],
        [5.0, 1.0, 0.0],
        [4.0, 0.0, 0.0],
        [5.0, 0.0, 1.0],
        [-1.0, 0.0, -1.0],
        [0.0, -1.0, -1.0],
        [0.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let want_triangles = vec![[0, 1, 2], [3, 4, 5], [6, 7, 8], [9, 11, 10]];
    let g = triangle_gltf(json!({
        "nodes": nodes,
        "scenes": [{"nodes": [5]}, {"nodes": [0, 2, 3, 4]}],
        "scene": 1,
    }));
    let m = read_bytes(&assemble(&g, Some(&triangle_bin())), Format::Glb).unwrap();
    // -0.0 and 0.0 compare equal here, as they should.
    assert_eq!(m.positions, want_positions);
    assert_eq!(m.triangles, want_triangles);

    // Without scenes: every root node (0, 2, 3, 4, 5), in order.
    let g = triangle_gltf(json!({ "nodes": nodes }));
    let m = read_bytes(&assemble(&g, Some(&triangle_bin())), Format::Glb).unwrap();
    assert_eq!(m.triangle_count(), 5);
    assert_eq!(m.positions[..12], want_positions[..]);
    assert_eq!(m.positions[12], [101.0, 0.0, 0.0]);

    // With scenes but no `scene`: the first.
    let g = triangle_gltf(json!({ "nodes": nodes, "scenes": [{"nodes": [5]}] }));
    let m = read_bytes(&assemble(&g, Some(&triangle_bin())), Format::Glb).unwrap();
    assert_eq!(
        m.positions,
        vec![[101.0, 0.0, 0.0], [100.0, 1.0, 0.0], [100.0, 0.0, 1.0]]
    );

    // Without nodes: each mesh as it is.
    let m = read_bytes(
        &assemble(&triangle_gltf(json!({})), Some(&triangle_bin())),
        Format::Glb,
    )
    .unwrap();
    assert_eq!(
        m.positions,
        vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    );
    assert_eq!(m.triangles, vec![[0, 1, 2]]);
}

#[test]
fn glb_u8_indices_byte_stride_offsets_strips_and_fans() {
    // 8 bytes of something else, then four vertices interleaved with a 4-byte attribute
    // (stride 16), then u8 indices.
    let mut bin = vec![0xAB; 8];
    let square = [
        [0.0f32, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    for p in square {
        bin.extend_from_slice(&[0xCD; 4]);
        bin.extend(f32s(&p));
    }
    let indices_at = bin.len();
    bin.extend_from_slice(&[0u8, 1, 2, 0, 2, 3]);
    let g = json!({
        "asset": {"version": "2.0"},
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [
            {"attributes": {"POSITION": 0}, "indices": 1, "mode": 4},
            {"attributes": {"POSITION": 0}, "mode": 1},
            {"attributes": {"POSITION": 0}, "indices": 2, "mode": 5},
            {"attributes": {"POSITION": 0}, "mode": 6},
            {"attributes": {"POSITION": 3}},
        ]}],
        "accessors": [
            {"bufferView": 0, "byteOffset": 4, "componentType": FLOAT, "count": 4, "type": "VEC3"},
            {"bufferView": 1, "componentType": UNSIGNED_BYTE, "count": 6, "type": "SCALAR"},
            // Strip 0 1 3 2: triangles (0 1 3) and (1 2 3), wound alike.
            {"bufferView": 2, "componentType": UNSIGNED_INT, "count": 4, "type": "SCALAR"},
            // The first three vertices, no indices.
            {"bufferView": 0, "byteOffset": 4, "componentType": FLOAT, "count": 3, "type": "VEC3"},
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 8, "byteLength": 64, "byteStride": 16},
            {"buffer": 0, "byteOffset": indices_at, "byteLength": 6},
            {"buffer": 0, "byteOffset": indices_at + 8, "byteLength": 16},
        ],
        "buffers": [{"byteLength": indices_at + 24}],
    });
    bin.extend_from_slice(&[0, 0]);
    for i in [0u32, 1, 3, 2] {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    let m = read_bytes(&assemble(&g, Some(&bin)), Format::Glb).unwrap();
    let sq: Vec<[f64; 3]> = square.iter().map(|p| p.map(f64::from)).collect();
    assert_eq!(m.positions[..4], sq[..]);
    assert_eq!(m.positions.len(), 4 + 4 + 4 + 3);
    assert_eq!(
        m.triangles,
        vec![
            [0, 1, 2],
            [0, 2, 3],
            [4, 5, 7],
            [5, 6, 7],
            [9, 10, 8],
            [10, 11, 8],
            [12, 13, 14]
        ]
    );
    // Every triangle faces +z.
    let normal_z = |t: &[u32; 3]| {
        let [a, b, c] = t.map(|i| m.positions[i as usize]);
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    };
    assert!(m.triangles.iter().all(|t| normal_z(t) > 0.0));

    // A stride shorter than a vertex.
    let mut short = g.clone();
    short["bufferViews"][0]["byteStride"] = json!(8);
    assert!(glb_err(&assemble(&short, Some(&bin)))
        .1
        .contains("byteStride 8"));
    // Elements running past the view.
    let mut long = g.clone();
    long["accessors"][0]["count"] = json!(5);
    assert!(glb_err(&assemble(&long, Some(&bin)))
        .1
        .contains("do not fit"));
    // An index past the vertices: its byte.
    let mut bad = bin.clone();
    bad[indices_at + 2] = 4;
    let (at, msg) = glb_err(&assemble(&g, Some(&bad)));
    assert!(
        msg.contains("index 4") && msg.contains("out of range"),
        "{msg}"
    );
    let json_len = u32_at(&assemble(&g, Some(&bin)), 12) as u64;
    assert_eq!(at, 28 + json_len + indices_at as u64 + 2);
}

#[test]
fn glb_u16_indices_and_mode_defaults() {
    let g = triangle_gltf(json!({"nodes": [{"mesh": 0}]}));
    let m = read_bytes(&assemble(&g, Some(&triangle_bin())), Format::Glb).unwrap();
    assert_eq!(m.triangles, vec![[0, 1, 2]]);
    assert_eq!(m.positions[2], [0.0, 0.0, 1.0]);
}

#[test]
fn glb_truncated_at_every_cut_is_an_error() {
    let bytes = to_glb(&Mesh::cuboid(
        [478_600.0, 6_772_300.0, 0.0],
        [478_601.0, 6_772_302.0, 3.0],
    ));
    for cut in 0..bytes.len() {
        let part = &bytes[..cut];
        assert!(read_bytes(part, Format::Glb).is_err(), "cut at {cut}");
        if cut >= 4 {
            assert_eq!(detect_format(part, None), Some(Format::Glb));
        }
        // The same with the header's length made to agree: the chunks must be found short.
        if cut >= 12 {
            let mut fixed = part.to_vec();
            fixed[8..12].copy_from_slice(&(cut as u32).to_le_bytes());
            assert!(read_bytes(&fixed, Format::Glb).is_err(), "cut at {cut}");
        }
    }
    // Any byte changed: an error or a mesh, never a panic.
    for at in 0..bytes.len() {
        for v in [0x00, 0x7F, 0xFF] {
            let mut b = bytes.clone();
            b[at] = v;
            let _ = read_bytes(&b, Format::Glb);
        }
    }
    let (at, msg) = glb_err(&bytes[..7]);
    assert_eq!(at, 7);
    assert!(msg.contains("header"), "{msg}");
    let (at, msg) = glb_err(&bytes[..100]);
    assert_eq!(at, 8);
    assert!(msg.contains("truncated"), "{msg}");
}

#[test]
fn glb_errors_name_the_problem() {
    let good = assemble(&triangle_gltf(json!({})), Some(&triangle_bin()));
    assert!(read_bytes(&good, Format::Glb).is_ok());

    let mut b = good.clone();
    b[..4].copy_from_slice(b"glTf");
    let (at, msg) = glb_err(&b);
    assert!(at == 0 && msg.contains("magic"), "{msg}");

    let mut b = good.clone();
    b[4] = 1;
    let (at, msg) = glb_err(&b);
    assert!(at == 4 && msg.contains("version 1"), "{msg}");

    // No BIN chunk.
    let (at, msg) = glb_err(&assemble(&triangle_gltf(json!({})), None));
    assert!(at == 20 && msg.contains("no BIN chunk"), "{msg}");

    // Buffers elsewhere.
    let ext = triangle_gltf(json!({"buffers": [{"byteLength": 42, "uri": "mesh.bin"}]}));
    let msg = glb_err(&assemble(&ext, Some(&triangle_bin()))).1;
    assert!(msg.contains("external file \"mesh.bin\""), "{msg}");
    let data = triangle_gltf(
        json!({"buffers": [{"byteLength": 42, "uri": "data:application/octet-stream;base64,AAAA"}]}),
    );
    assert!(glb_err(&assemble(&data, Some(&triangle_bin())))
        .1
        .contains("data URI"));

    // Sparse accessors.
    let mut sparse = triangle_gltf(json!({}));
    sparse["accessors"][0]["sparse"] = json!({"count": 1, "indices": {}, "values": {}});
    assert!(glb_err(&assemble(&sparse, Some(&triangle_bin())))
        .1
        .contains("sparse"));

    // Only lines and points.
    let mut lines = triangle_gltf(json!({}));
    lines["meshes"][0]["primitives"][0]["mode"] = json!(1);
    let msg = glb_err(&assemble(&lines, Some(&triangle_bin()))).1;
    assert!(
        msg.contains("no triangle primitives") && msg.contains("[1]"),
        "{msg}"
    );

    // Wrong position type.
    let mut ints = triangle_gltf(json!({}));
    ints["accessors"][0]["componentType"] = json!(UNSIGNED_SHORT);
    assert!(glb_err(&assemble(&ints, Some(&triangle_bin())))
        .1
        .contains("componentType 5123"));

    // Draco and friends.
    let draco = triangle_gltf(json!({"extensionsRequired": ["KHR_draco_mesh_compression"]}));
    assert!(glb_err(&assemble(&draco, Some(&triangle_bin())))
        .1
        .contains("KHR_draco_mesh_compression"));

    // A cycle among the nodes.
    let cycle = triangle_gltf(
        json!({"nodes": [{"children": [1]}, {"children": [0], "mesh": 0}], "scenes": [{"nodes": [0]}]}),
    );
    assert!(glb_err(&assemble(&cycle, Some(&triangle_bin())))
        .1
        .contains("not a tree"));

    // Missing references.
    let dangling = triangle_gltf(json!({"nodes": [{"mesh": 3}]}));
    assert!(glb_err(&assemble(&dangling, Some(&triangle_bin())))
        .1
        .contains("meshes[3]"));

    // A buffer longer than the BIN chunk.
    let long = triangle_gltf(json!({"buffers": [{"byteLength": 400}]}));
    assert!(glb_err(&assemble(&long, Some(&triangle_bin())))
        .1
        .contains("BIN chunk has 44"));

    // A JSON syntax error: its byte.
    let mut b = good.clone();
    b[20] = b'x';
    let (at, msg) = glb_err(&b);
    assert!(at == 20 && msg.contains("JSON"), "{at} {msg}");
    let mut b = good.clone();
    let quote = 20 + b[20..].iter().position(|&c| c == b':').unwrap();
    b[quote] = b'!';
    assert_eq!(glb_err(&b).0, quote as u64);

    // A non-finite coordinate: its byte.
    let mut bin = triangle_bin();
    bin[16..20].copy_from_slice(&f32::NAN.to_le_bytes());
    let json_len = u32_at(&good, 12) as u64;
    let (at, msg) = glb_err(&assemble(&triangle_gltf(json!({})), Some(&bin)));
    assert!(msg.contains("non-finite"), "{msg}");
    assert_eq!(at, 28 + json_len + 16);
}

#[test]
fn glb_refuses_meshes_it_cannot_hold() {
    let invalid = |m: &Mesh| {
        matches!(
            write(&mut Vec::new(), m, Format::Glb),
            Err(Error::InvalidMesh { .. })
        )
    };
    assert!(invalid(&Mesh::default()));
    let (positions, _) = Mesh::unit_cube().into_parts();
    assert!(invalid(&Mesh::new(positions, vec![]).unwrap()));
    let mut far = Mesh::unit_cube();
    far.positions[0] = [1e300, 0.0, 0.0];
    assert!(invalid(&far));
}

#[test]
fn glb_is_detected_and_named() {
    let bytes = to_glb(&Mesh::unit_cube());
    assert_eq!(detect_format(&bytes, None), Some(Format::Glb));
    assert_eq!(detect_format(&bytes, Some(Format::Obj)), Some(Format::Glb));
    assert_eq!(Format::for_path("site/pit.GLB"), Some(Format::Glb));
    assert_eq!("glb".parse::<Format>().unwrap(), Format::Glb);
    assert_eq!(
        (Format::Glb.name(), Format::Glb.extension()),
        ("glb", "glb")
    );
    assert!(!Format::Glb.welds_on_read());
}
