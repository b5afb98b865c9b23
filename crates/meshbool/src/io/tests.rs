use super::*;
use crate::measure::mesh_stats;

/// A mesh whose coordinates exercise number formatting: UTM offsets, tiny and huge
/// magnitudes, negative zero, values with 17 significant digits.
fn awkward_mesh() -> Mesh {
    let mut m = Mesh::cuboid(
        [478_614.7, 6_772_313.84, -0.1],
        [478_624.700_000_000_1, 6_772_333.123_456_789, 1e-300],
    );
    m.positions.push([1e300, -2.5e-310, 0.1 + 0.2]);
    m.positions.push([-0.0, std::f64::consts::PI, -1.0 / 3.0]);
    m.positions.push([7.0, 8.0, 9.0]);
    m.triangles.push([8, 9, 10]);
    m
}

fn write_to_vec(mesh: &Mesh, format: Format) -> Vec<u8> {
    let mut out = Vec::new();
    if format == Format::SurpacDtm {
        // Two files: the .dtm (its string file is left out; see `read_back`).
        write_surpac_dtm(&mut out, &mut Vec::new(), mesh, "t").unwrap();
        return out;
    }
    write(&mut out, mesh, format).unwrap();
    out
}

/// `mesh` written in `format` and read back (a Surpac DTM through both of its files).
fn read_back(mesh: &Mesh, format: Format) -> Mesh {
    if format == Format::SurpacDtm {
        let (mut dtm, mut strings) = (Vec::new(), Vec::new());
        write_surpac_dtm(&mut dtm, &mut strings, mesh, "t").unwrap();
        return read_surpac_dtm(&dtm, &strings).unwrap();
    }
    read_bytes(&write_to_vec(mesh, format), format).unwrap()
}

fn round_trip(mesh: &Mesh, format: Format) -> Mesh {
    let bytes = write_to_vec(mesh, format);
    assert_eq!(
        detect_format(&bytes, None)
            .map(|f| f == format || matches!((f, format), (Format::JsonSoup, Format::JsonKirra))),
        Some(true),
        "{format}"
    );
    read_bytes(&bytes, detect_format(&bytes, None).unwrap()).unwrap()
}

/// Corner positions compared as bit patterns, with -0.0 taken as 0.0 (welding merges them).
fn soup_bits(m: &Mesh) -> Vec<[[u64; 3]; 3]> {
    m.to_soup()
        .iter()
        .map(|t| t.map(|p| p.map(|x| (x + 0.0).to_bits())))
        .collect()
}

#[test]
fn indexed_formats_round_trip_bit_exact() {
    let m = awkward_mesh();
    for f in [
        Format::Obj,
        Format::PlyAscii,
        Format::PlyBinaryLe,
        Format::PlyBinaryBe,
    ] {
        let back = round_trip(&m, f);
        assert_eq!(back.triangles, m.triangles, "{f}");
        let bits = |m: &Mesh| {
            m.positions
                .iter()
                .map(|p| p.map(f64::to_bits))
                .collect::<Vec<_>>()
        };
        assert_eq!(bits(&back), bits(&m), "{f}");
    }
}

#[test]
fn soup_formats_round_trip_bit_exact_and_weld() {
    let m = awkward_mesh();
    for f in [
        Format::StlAscii,
        Format::Dxf,
        Format::JsonSoup,
        Format::JsonKirra,
    ] {
        let back = round_trip(&m, f);
        assert_eq!(soup_bits(&back), soup_bits(&m), "{f}");
        // Welded on read: the cube's 8 corners + 3 others.
        assert_eq!(back.vertex_count(), 11, "{f}");
        let (a, b) = (mesh_stats(&back), mesh_stats(&m));
        assert_eq!(
            (a.edges, a.boundary_edges, a.components),
            (b.edges, b.boundary_edges, b.components),
            "{f}"
        );
    }
}

#[test]
fn binary_stl_round_trips_through_f32() {
    let m = Mesh::cuboid([-1.5, 2.25, 3.0], [4.0, 5.5, 6.125]);
    let back = round_trip(&m, Format::StlBinary);
    assert_eq!(back.to_soup(), m.to_soup());
    let s = mesh_stats(&back);
    assert_eq!(
        (s.vertices, s.boundary_edges, s.volume),
        (8, 0, 5.5 * 3.25 * 3.125)
    );
    // Awkward values come back as their f32 roundings.
    let a = awkward_mesh();
    let back = round_trip(
        &Mesh::new_unchecked(a.positions.clone(), a.triangles[..12].to_vec()),
        Format::StlBinary,
    );
    let want: Vec<_> = a.to_soup()[..12]
        .iter()
        .map(|t| t.map(|p| p.map(|x| f64::from(x as f32))))
        .collect();
    assert_eq!(back.to_soup(), want);
}

fn binary_stl_of(mesh: &Mesh) -> Vec<u8> {
    write_to_vec(mesh, Format::StlBinary)
}

fn parse_err(bytes: &[u8], format: Format) -> (Location, String) {
    match read_bytes(bytes, format) {
        Err(Error::Parse {
            location, message, ..
        }) => (location, message),
        other => panic!("expected a parse error, got {other:?}"),
    }
}

#[test]
fn binary_stl_with_solid_header_is_binary() {
    let mut bytes = binary_stl_of(&Mesh::unit_cube());
    bytes[..12].copy_from_slice(b"solid cube  ");
    assert_eq!(
        detect_format(&bytes, Some(Format::StlBinary)),
        Some(Format::StlBinary)
    );
    let m = read_bytes(&bytes, Format::StlBinary).unwrap();
    assert_eq!(mesh_stats(&m).volume, 1.0);
}

#[test]
fn truncated_binary_stl_is_an_error() {
    let bytes = binary_stl_of(&Mesh::unit_cube());
    let (loc, msg) = parse_err(&bytes[..bytes.len() - 10], Format::StlBinary);
    assert_eq!(loc, Location::Byte(80));
    assert!(
        msg.contains("announces 12 triangles") && msg.contains("room for 11"),
        "{msg}"
    );
    let (loc, _) = parse_err(&bytes[..50], Format::StlBinary);
    assert_eq!(loc, Location::Byte(50));
}

#[test]
fn wrong_triangle_count_is_an_error() {
    let mut bytes = binary_stl_of(&Mesh::unit_cube());
    bytes[80..84].copy_from_slice(&13u32.to_le_bytes());
    let (_, msg) = parse_err(&bytes, Format::StlBinary);
    assert!(msg.contains("announces 13"), "{msg}");
}

#[test]
fn nan_in_binary_stl_names_the_byte() {
    let mut bytes = binary_stl_of(&Mesh::unit_cube());
    let at = 84 + 50 * 3 + 12 + 12 + 4; // triangle 3, corner 1, y
    bytes[at..at + 4].copy_from_slice(&f32::NAN.to_le_bytes());
    assert_eq!(
        parse_err(&bytes, Format::StlBinary).0,
        Location::Byte(at as u64)
    );
}

#[test]
fn empty_input_is_an_error_in_every_format() {
    for (_, f) in Format::NAMES {
        assert_eq!(parse_err(b"", f).0, Location::Whole, "{f}");
        assert_eq!(parse_err(b" \n", f).0, Location::Whole, "{f}");
    }
}

#[test]
fn ascii_stl_several_solids_and_polygons() {
    let text = b"solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\nendfacet\nendsolid a\n\
                 solid b with spaces\n  facet normal 0 0 0\n  outer loop\n  vertex 0 0 0\n  vertex 1 1 0\n vertex 0 1 0\n vertex -1 1 0\n  endloop\n  endfacet\nendsolid\n";
    let m = read_bytes(text, Format::StlAscii).unwrap();
    assert_eq!((m.triangle_count(), m.vertex_count()), (3, 5));
}

#[test]
fn ascii_stl_errors_name_the_line() {
    let good = b"solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\nendfacet\nendsolid a\n";
    // Cut inside a vertex line: that line; cut after a vertex: the facet that stays open.
    assert_eq!(
        parse_err(&good[..60], Format::StlAscii).0,
        Location::Line(5)
    );
    assert_eq!(
        parse_err(&good[..64], Format::StlAscii).0,
        Location::Line(2)
    );
    let bad = String::from_utf8_lossy(good).replace("vertex 1 0 0", "vertex 1 zero 0");
    assert_eq!(
        parse_err(bad.as_bytes(), Format::StlAscii).0,
        Location::Line(5)
    );
    let nan = String::from_utf8_lossy(good).replace("vertex 1 0 0", "vertex 1 NaN 0");
    let (loc, msg) = parse_err(nan.as_bytes(), Format::StlAscii);
    assert_eq!(loc, Location::Line(5));
    assert!(msg.contains("non-finite"), "{msg}");
    let cut = String::from_utf8_lossy(good).replace("endsolid a\n", "");
    assert!(parse_err(cut.as_bytes(), Format::StlAscii)
        .1
        .contains("endsolid"));
}

#[test]
fn obj_polygons_negative_indices_and_extras() {
    let text = b"# comment\nmtllib x.mtl\no thing\nv 0 0 0\nv 1 0 0 1.0\nv 1 1 0 0.5 0.5 0.5\nv 0 1 0\nvt 0 0\nvn 0 0 1\n\
                 g group\nusemtl m\ns off\nf 1/1/1 2/1/1 3/1/1 4/1/1\nf -4//1 -2//1 -1//1\nl 1 2\n";
    let m = read_bytes(text, Format::Obj).unwrap();
    assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3], [0, 2, 3]]);
    assert_eq!(m.positions[1], [1.0, 0.0, 0.0]);
}

#[test]
fn obj_bad_indices_name_the_line() {
    for (text, line) in [
        (&b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"[..], 4),
        (b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", 4),
        (b"v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 -7\n", 5),
        (b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", 4),
        (b"v 0 0 0\nv 1 0 0\nf 1 2\n", 3),
        (b"v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n", 2),
        (b"v 0 0\n", 1),
    ] {
        assert_eq!(
            parse_err(text, Format::Obj).0,
            Location::Line(line),
            "{}",
            String::from_utf8_lossy(text)
        );
    }
}

#[test]
fn ply_with_extra_properties_elements_and_types() {
    let header = "ply\r\nformat binary_big_endian 1.0\r\ncomment x\r\nelement vertex 4\r\nproperty float x\r\nproperty float y\r\n\
                  property float z\r\nproperty uchar red\r\nproperty list uchar int extra\r\nelement face 1\r\n\
                  property list uchar uint vertex_indices\r\nproperty float quality\r\nelement edge 1\r\nproperty int a\r\nend_header\r\n";
    let mut b = header.as_bytes().to_vec();
    for (i, p) in [
        [0.0f32, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.5],
        [0.0, 1.0, 0.0],
    ]
    .iter()
    .enumerate()
    {
        for x in p {
            b.extend_from_slice(&x.to_be_bytes());
        }
        b.push(200);
        b.push(i as u8); // list of i ints
        for _ in 0..i {
            b.extend_from_slice(&7i32.to_be_bytes());
        }
    }
    b.push(4);
    for i in [0u32, 1, 2, 3] {
        b.extend_from_slice(&i.to_be_bytes());
    }
    b.extend_from_slice(&1.5f32.to_be_bytes());
    b.extend_from_slice(&9i32.to_be_bytes());
    let m = read_bytes(&b, detect_format(&b, None).unwrap()).unwrap();
    assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    assert_eq!(m.positions[2], [1.0, 1.0, 0.5]);
    // Truncated body: the byte where it ran out.
    assert!(matches!(
        parse_err(&b[..b.len() - 3], Format::PlyBinaryBe).0,
        Location::Byte(_)
    ));
}

#[test]
fn ply_ascii_errors() {
    let ok = "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n\
              element face 1\nproperty list uchar int vertex_index\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    assert_eq!(
        read_bytes(ok.as_bytes(), Format::PlyAscii)
            .unwrap()
            .triangles,
        vec![[0, 1, 2]]
    );
    assert_eq!(
        parse_err(
            ok.replace("3 0 1 2", "3 0 1 3").as_bytes(),
            Format::PlyAscii
        )
        .0,
        Location::Line(13)
    );
    assert_eq!(
        parse_err(ok.replace("1 0 0", "1 nan 0").as_bytes(), Format::PlyAscii).0,
        Location::Line(11)
    );
    assert_eq!(
        parse_err(&ok.as_bytes()[..ok.len() - 4], Format::PlyAscii).0,
        Location::Line(13)
    );
    assert_eq!(
        parse_err(
            ok.replace("double y", "quad y").as_bytes(),
            Format::PlyAscii
        )
        .0,
        Location::Line(5)
    );
    assert_eq!(
        parse_err(ok.replace("end_header\n", "").as_bytes(), Format::PlyAscii).0,
        Location::Line(9)
    );
    assert!(parse_err(b"ply\nformat ascii 1.0\n", Format::PlyAscii)
        .1
        .contains("end_header"));
}

#[test]
fn dxf_quads_and_polyface_meshes() {
    // A quad 3DFACE, a triangle 3DFACE (4th corner = 3rd), a polyface mesh with one quad
    // face, and a 3DFACE inside BLOCKS that must not be read.
    let face = |pts: [[f64; 3]; 4]| {
        let mut s = String::from("0\n3DFACE\n8\nlayer\n");
        for (k, p) in pts.iter().enumerate() {
            for (a, x) in p.iter().enumerate() {
                s += &format!("{}\n{x}\n", 10 * (a + 1) + k);
            }
        }
        s
    };
    let mut s = String::from("999\nmade by hand\n0\nSECTION\n2\nBLOCKS\n");
    s += &face([[9.0; 3], [8.0; 3], [7.0, 0.0, 0.0], [7.0, 0.0, 0.0]]);
    s += "0\nENDSEC\n0\nSECTION\n2\nENTITIES\n";
    s += &face([
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ]);
    s += &face([
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, 1.0],
    ]);
    s += "0\nPOLYLINE\n8\n0\n66\n1\n70\n64\n71\n4\n72\n1\n";
    for p in [
        [5.0, 0.0, 0.0],
        [6.0, 0.0, 0.0],
        [6.0, 1.0, 0.0],
        [5.0, 1.0, 0.0],
    ] {
        s += &format!(
            "0\nVERTEX\n8\n0\n10\n{}\n20\n{}\n30\n{}\n70\n192\n",
            p[0], p[1], p[2]
        );
    }
    s += "0\nVERTEX\n8\n0\n10\n0\n20\n0\n30\n0\n70\n128\n71\n1\n72\n-2\n73\n3\n74\n4\n0\nSEQEND\n0\nENDSEC\n0\nEOF\n";
    let m = read_bytes(s.as_bytes(), detect_format(s.as_bytes(), None).unwrap()).unwrap();
    assert_eq!(m.triangle_count(), 5);
    assert_eq!(m.vertex_count(), 9);
    assert_eq!(crate::measure::area(&m), 1.0 + 0.5 + 1.0);
    // Truncated: no EOF.
    let cut = &s[..s.len() - 8];
    assert!(parse_err(cut.as_bytes(), Format::Dxf).1.contains("EOF"));
    // A face record pointing past the vertices.
    let bad = s.replace("74\n4\n", "74\n9\n");
    assert!(parse_err(bad.as_bytes(), Format::Dxf)
        .1
        .contains("vertex 9"));
    // A mesh vertex without its z (or without x and y): an error naming the codes, not a
    // vertex at 0 (the face record, flag 128, needs no coordinates).
    let no_z = s.replacen("10\n6\n20\n0\n30\n0\n", "10\n6\n20\n0\n", 1);
    assert_eq!(no_z.len(), s.len() - 5);
    let (_, msg) = parse_err(no_z.as_bytes(), Format::Dxf);
    assert!(
        msg.contains("VERTEX") && msg.contains("group code 30"),
        "{msg}"
    );
    let no_xy = s.replacen("10\n6\n20\n0\n", "", 1);
    assert!(parse_err(no_xy.as_bytes(), Format::Dxf)
        .1
        .contains("group codes 10, 20"));
    assert!(parse_err(b"AutoCAD Binary DXF\r\n\x1a\0", Format::Dxf)
        .1
        .contains("binary DXF"));
}

#[test]
fn json_layouts_and_errors() {
    let soup = br#"[{"v0":{"x":0,"y":0,"z":0},"v1":{"x":1,"y":0,"z":0},"v2":{"x":0,"y":1,"z":0},"id":"t1"}]"#;
    let kirra = br#"[{"vertices":[{"x":0,"y":0,"z":0},{"x":1,"y":0,"z":0},{"x":0,"y":1,"z":0},{"x":-1,"y":0,"z":0}],"color":3}]"#;
    assert_eq!(
        read_bytes(soup, Format::JsonSoup).unwrap().triangle_count(),
        1
    );
    assert_eq!(
        read_bytes(kirra, Format::JsonSoup)
            .unwrap()
            .triangle_count(),
        2
    );
    let (loc, msg) = parse_err(b"[\n{\"v0\":{\"x\":0,\"y\":0}}]", Format::JsonSoup);
    assert_eq!(loc, Location::Line(2));
    assert!(msg.contains("v0"), "{msg}");
    assert_eq!(parse_err(b"[\n\n{", Format::JsonSoup).0, Location::Line(3));
    assert!(
        parse_err(br#"[{"vertices":[{"x":0,"y":0,"z":0}]}]"#, Format::JsonSoup)
            .1
            .contains("needs at least 3")
    );
    assert!(matches!(
        parse_err(br#"[{"v0":{"x":1e999,"y":0,"z":0}}]"#, Format::JsonSoup).0,
        Location::Line(1)
    ));
}

#[test]
fn detection_by_name_and_content() {
    let cube = Mesh::unit_cube();
    for (_, f) in Format::NAMES {
        let bytes = write_to_vec(&cube, f);
        let seen = detect_format(&bytes, None).unwrap();
        let want = if f == Format::JsonKirra {
            Format::JsonSoup
        } else {
            f
        };
        assert_eq!(seen, want, "{f}");
        assert_eq!(
            detect_format(&bytes, Some(f)).map(|g| g == want || f == Format::PlyAscii),
            Some(true)
        );
    }
    assert_eq!(Format::for_path("a/b.STL"), Some(Format::StlBinary));
    assert_eq!(Format::for_path("x.txt"), None);
    assert_eq!("PLY-ascii".parse::<Format>().unwrap(), Format::PlyAscii);
    assert_eq!(detect_format(b"hello world", None), None);
}

#[test]
fn a_large_obj_whose_faces_start_after_the_first_64_kib_is_detected() {
    let s = crate::shapes::uv_sphere([0.0; 3], 1.0, 64, 48);
    let bytes = write_to_vec(&s, Format::Obj);
    let first_face = bytes.windows(3).position(|w| w == b"\nf ").unwrap();
    assert!(first_face > 1 << 16, "{first_face}");
    assert_eq!(detect_format(&bytes, None), Some(Format::Obj));
    // A text that is not OBJ past its vertex-like lines is still not taken for one.
    let mut other = b"v 1 2 3\n".repeat(7000);
    other.extend_from_slice(b"hello world\n");
    assert!(other.len() < 1 << 16);
    other.extend(b"v 1 2 3\n".repeat(9000));
    assert_eq!(detect_format(&other, None), None);
}

#[test]
fn writing_invalid_mesh_is_an_error() {
    let mut m = Mesh::unit_cube();
    m.positions[0][0] = f64::INFINITY;
    for (_, f) in Format::NAMES {
        assert!(
            matches!(
                write(&mut Vec::new(), &m, f),
                Err(Error::InvalidMesh { .. })
            ),
            "{f}"
        );
    }
}

#[test]
fn binary_stl_refuses_coordinates_beyond_or_below_f32() {
    for x in [1e39, -3.5e38] {
        let mut m = Mesh::unit_cube();
        m.positions[3][1] = x;
        let e = write(&mut Vec::new(), &m, Format::StlBinary).unwrap_err();
        assert!(
            matches!(
                &e,
                Error::InvalidMesh {
                    location: Location::Vertex(3),
                    ..
                }
            ),
            "{x}: {e}"
        );
        assert!(e.to_string().contains("32-bit"), "{e}");
        // Formats in f64 keep it.
        let back = read_bytes(&write_to_vec(&m, Format::PlyBinaryLe), Format::PlyBinaryLe);
        assert_eq!(back.unwrap().positions[3][1], x);
    }
    // A cube of side 1e-50 would collapse to a point: refused, naming a triangle.
    let tiny = Mesh::cuboid([0.0; 3], [1e-50; 3]);
    let e = write(&mut Vec::new(), &tiny, Format::StlBinary).unwrap_err();
    assert!(
        matches!(
            &e,
            Error::InvalidMesh {
                location: Location::Triangle(_),
                ..
            }
        ),
        "{e}"
    );
    // A tiny coordinate that only rounds to zero, collapsing nothing, is written (and
    // f32's extremes themselves are fine).
    let mut m = Mesh::unit_cube();
    m.positions[0][1] = 1e-50; // (0, 1e-50, 0): rounds to the origin, no other corner is there
    m.positions[4][1] = f64::from(f32::MAX);
    m.positions[5][1] = f64::from(f32::from_bits(1)); // the smallest subnormal
    assert!(write(&mut Vec::new(), &m, Format::StlBinary).is_ok());
}

#[test]
fn a_failed_write_leaves_the_earlier_file_and_no_temporary_file() {
    let dir = std::env::temp_dir().join(format!("meshbool-atomic-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("result.stl");
    std::fs::write(&path, b"earlier content").unwrap();
    // A writer that fails halfway (after writing some bytes).
    let r = write_file(&path, |out| {
        out.write_all(&[7u8; 100_000])?;
        Err(Error::InvalidParameter("stop".into()))
    });
    assert!(r.is_err());
    assert_eq!(std::fs::read(&path).unwrap(), b"earlier content");
    // A mesh that cannot be written in the format asked (binary STL range) likewise.
    let mut m = Mesh::unit_cube();
    m.positions[0][0] = 1e300;
    assert!(write_path(&path, &m).is_err());
    assert_eq!(std::fs::read(&path).unwrap(), b"earlier content");
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left, [std::ffi::OsString::from("result.stl")]);
    // A successful write replaces it whole.
    write_path(&path, &Mesh::unit_cube()).unwrap();
    assert_eq!(read_path(&path).unwrap().triangle_count(), 12);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn welds_on_read_says_exactly_which_readers_weld() {
    // The unit cube as an unwelded soup (36 vertices): readers that weld give 8.
    let soup = Mesh::from_soup_unwelded(&Mesh::unit_cube().to_soup());
    assert_eq!(soup.vertex_count(), 36);
    for (_, f) in Format::NAMES {
        let back = read_back(&soup, f);
        let welded = crate::weld_exact(&back).mesh.vertex_count() == back.vertex_count();
        assert_eq!(f.welds_on_read(), welded, "{f}");
        assert_eq!(welded, back.vertex_count() == 8, "{f}");
    }
}

// Issue 17, items 7 and 8: readers that took too much, and messages that said it badly.

const PLY_TRIANGLE: &str =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n\
    property double z\nelement face 1\nproperty list uchar int vertex_index\nend_header\n\
    0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

#[test]
fn ply_ascii_lines_beyond_the_declared_counts_are_an_error() {
    // Whitespace after the last element is fine.
    for tail in ["", "\n", "\n\n  \t\r\n", "   "] {
        let text = format!("{PLY_TRIANGLE}{tail}");
        assert_eq!(
            read_bytes(text.as_bytes(), Format::PlyAscii)
                .unwrap()
                .triangle_count(),
            1,
            "{tail:?}"
        );
    }
    // A face, or a vertex, more than the header declares: the line where it starts.
    for (tail, line) in [("3 0 2 1\n", 14), ("\n\n0 0 1\n", 16), ("x", 14)] {
        let text = format!("{PLY_TRIANGLE}{tail}");
        let (loc, msg) = parse_err(text.as_bytes(), Format::PlyAscii);
        assert_eq!(loc, Location::Line(line), "{tail:?}: {msg}");
        assert!(msg.contains("header declares"), "{msg}");
    }
    // Extra text on the last line itself.
    let text = PLY_TRIANGLE.replace("3 0 1 2\n", "3 0 1 2 7\n");
    assert_eq!(
        parse_err(text.as_bytes(), Format::PlyAscii).0,
        Location::Line(13)
    );
}

#[test]
fn ply_binary_bytes_beyond_the_declared_data_are_an_error() {
    for f in [Format::PlyBinaryLe, Format::PlyBinaryBe] {
        let bytes = write_to_vec(&Mesh::unit_cube(), f);
        let mut longer = bytes.clone();
        longer.extend_from_slice(&[3, 0, 0, 0, 0]);
        let (loc, msg) = parse_err(&longer, f);
        assert_eq!(loc, Location::Byte(bytes.len() as u64), "{f}: {msg}");
        assert!(
            msg.contains("5 bytes") && msg.contains("header declares"),
            "{msg}"
        );
        // A single trailing newline is trailing content too in a binary body.
        longer.truncate(bytes.len() + 1);
        assert_eq!(parse_err(&longer, f).0, Location::Byte(bytes.len() as u64));
    }
}

#[test]
fn ply_list_count_must_be_an_integer_type() {
    for ty in ["float", "double", "float32"] {
        let text = PLY_TRIANGLE.replace("list uchar int", &format!("list {ty} int"));
        let (loc, msg) = parse_err(text.as_bytes(), Format::PlyAscii);
        assert_eq!(loc, Location::Line(8), "{ty}");
        assert!(
            msg.contains(&format!("list length type {ty}")) && msg.contains("integer"),
            "{msg}"
        );
    }
    // Every integer type is fine.
    for ty in [
        "char", "uchar", "int8", "uint8", "short", "ushort", "int", "uint32",
    ] {
        let text = PLY_TRIANGLE.replace("list uchar int", &format!("list {ty} int"));
        assert!(
            read_bytes(text.as_bytes(), Format::PlyAscii).is_ok(),
            "{ty}"
        );
    }
}

#[test]
fn dxf_3dface_with_missing_coordinates_is_an_error() {
    // A 3DFACE at line 5 with the given group codes (value: the code squared).
    let dxf = |codes: &[u32]| {
        let mut s = String::from("0\nSECTION\n2\nENTITIES\n0\n3DFACE\n8\n0\n");
        for c in codes {
            s += &format!("{c}\n{}\n", c * c);
        }
        s + "0\nENDSEC\n0\nEOF\n"
    };
    let three = [10, 20, 30, 11, 21, 31, 12, 22, 32];
    let four = [10, 20, 30, 11, 21, 31, 12, 22, 32, 13, 23, 33];
    // Absent 4th corner, or a 4th corner equal to the 3rd: a triangle.
    assert_eq!(
        read_bytes(dxf(&three).as_bytes(), Format::Dxf)
            .unwrap()
            .triangle_count(),
        1
    );
    let same = dxf(&four).replace(
        "13\n169\n23\n529\n33\n1089\n",
        "13\n144\n23\n484\n33\n1024\n",
    );
    assert_eq!(
        read_bytes(same.as_bytes(), Format::Dxf)
            .unwrap()
            .triangle_count(),
        1
    );
    // A coordinate of corners 1-3 missing, or a partial 4th corner: the entity's line.
    for (missing, all) in [(32, &three[..]), (21, &three), (10, &three), (33, &four)] {
        let codes: Vec<u32> = all.iter().copied().filter(|&c| c != missing).collect();
        let (loc, msg) = parse_err(dxf(&codes).as_bytes(), Format::Dxf);
        assert_eq!(loc, Location::Line(5), "{missing}: {msg}");
        assert!(
            msg.contains("3DFACE") && msg.contains(&format!("group code {missing}")),
            "{msg}"
        );
    }
    // Several missing: all named.
    let (_, msg) = parse_err(dxf(&[10, 20, 30, 11, 21, 31]).as_bytes(), Format::Dxf);
    assert!(msg.contains("group codes 12, 22, 32"), "{msg}");
}

#[test]
fn obj_vertex_takes_3_4_or_6_numbers() {
    let face = "v 1 0 0\nv 0 1 0\nf 1 2 3\n";
    for first in [
        "v 0 0 0",
        "v 0 0 0 1.0",
        "v 0 0 0 0.5 0.25 1",
        "  v\t0 0 0  ",
        "v 0 0 0 # a comment",
        "v 0 0 0 0.5 0.25 1 #comment",
    ] {
        let text = format!("{first}\n{face}");
        let m = read_bytes(text.as_bytes(), Format::Obj);
        assert_eq!(m.unwrap().positions[0], [0.0; 3], "{first}");
    }
    for first in [
        "v 0 0 0 junk",
        "v 0 0 0 1 2",
        "v 0 0 0 1 2 3 4",
        "v 0 0 0 0.5 0.25 x",
        "v 0 0 0 1 2 #3",
    ] {
        let text = format!("{face}{first}\n");
        let (loc, msg) = parse_err(text.as_bytes(), Format::Obj);
        assert_eq!(loc, Location::Line(4), "{first}: {msg}");
    }
    let (_, msg) = parse_err(b"v 0 0 0 junk\n", Format::Obj);
    assert!(msg.contains("\"junk\""), "{msg}");
    let (_, msg) = parse_err(b"v 0 0 0 1 2\n", Format::Obj);
    assert!(
        msg.contains("5 numbers") && msg.contains("x y z w"),
        "{msg}"
    );
}

#[test]
fn polylines_in_a_mesh_format_is_one_clear_sentence() {
    let lines = [crate::intersect::PolylineXyz {
        points: vec![[0.0; 3], [1.0; 3]],
        closed: false,
    }];
    let e = write_polylines(&mut Vec::new(), &lines, Format::StlBinary).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid parameter: polylines cannot be written as binary STL, only as OBJ (.obj), \
         DXF (.dxf) or JSON (.json)"
    );
    // Through the curves' writer, with the file named first.
    let a = Mesh::unit_cube();
    let b = Mesh::cuboid([0.5; 3], [1.5; 3]);
    let curves = crate::ops::curves(&a, &b, &Default::default()).unwrap();
    let dir = std::env::temp_dir().join(format!("meshbool-polystl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("c.stl");
    let e = curves.write(&path).unwrap_err().to_string();
    assert_eq!(
        e,
        format!(
            "writing {}: invalid parameter: polylines cannot be written as binary STL, only as \
             OBJ (.obj), DXF (.dxf) or JSON (.json)",
            path.display()
        )
    );
    assert!(!path.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn json_bad_triangle_says_which_and_what_shape() {
    let p = r#"{"x":0,"y":0,"z":0}"#;
    let ok = format!(r#"{{"v0":{p},"v1":{p},"v2":{p}}}"#);
    let shape = r#"{"v0": {"x":..,"y":..,"z":..}, "v1": .., "v2": ..} or Kirra's {"vertices": [..3 or more points..]}"#;
    for (text, line, says) in [
        (
            format!("[{ok},\n{ok},\n{{\"v0\":{p},\"v1\":{p}}}]"),
            3,
            "array element 2 (0-based): missing \"v2\"",
        ),
        (
            format!("[{ok},{{\"v0\":{p},\"v1\":{p},\"v2\":{{\"x\":0,\"y\":0}}}}]"),
            1,
            "array element 1 (0-based), \"v2\": missing field `z`",
        ),
        (
            format!("[{{\"vertices\":[{p},{p},{{\"x\":0,\"y\":\"a\",\"z\":0}}]}}]"),
            1,
            "array element 0 (0-based), \"vertices\" point 2: invalid type: string \"a\", expected f64",
        ),
        (
            format!("[{ok},{{\"a\":1}}]"),
            1,
            "array element 1 (0-based): neither \"v0\", \"v1\", \"v2\" nor \"vertices\"",
        ),
        (
            format!("[{ok},\n7]"),
            2,
            "array element 1 (0-based): invalid type: integer `7`, expected a triangle object",
        ),
        (
            ok.clone(),
            1,
            "invalid type: map, expected an array of triangle objects",
        ),
    ] {
        let (loc, msg) = parse_err(text.as_bytes(), Format::JsonSoup);
        assert_eq!(loc, Location::Line(line), "{text}: {msg}");
        assert!(msg.starts_with(says), "{text}: {msg}");
        assert!(msg.ends_with(shape), "{msg}");
        assert!(!msg.contains("untagged") && !msg.contains("column"), "{msg}");
    }
    // Both layouts in one array, other keys ignored.
    let mixed = format!(r#"[{ok},{{"id":[1,{{"v0":2}}],"vertices":[{p},{p},{p}]}}]"#);
    assert_eq!(
        read_bytes(mixed.as_bytes(), Format::JsonSoup)
            .unwrap()
            .triangle_count(),
        2
    );
}

#[test]
fn binary_stl_with_solid_header_and_wrong_count_is_reported_as_binary() {
    let good = binary_stl_of(&Mesh::unit_cube());
    let mut solid = good.clone();
    solid[..12].copy_from_slice(b"solid cube  ");
    for (bytes, n) in [
        (solid.clone(), 13u32),
        (solid[..solid.len() - 3].to_vec(), 12),
        ([&solid[..], &[0u8; 4][..]].concat(), 12),
    ] {
        let mut bytes = bytes;
        bytes[80..84].copy_from_slice(&n.to_le_bytes());
        for f in [Some(Format::StlBinary), None] {
            let f = detect_format(&bytes, f).unwrap();
            let e = read_bytes(&bytes, f).unwrap_err();
            let msg = e.to_string();
            assert!(
                msg.starts_with("malformed binary STL at byte 80: header announces")
                    && msg.contains(&format!("announces {n} triangles"))
                    && msg.contains(&format!("the file has {} bytes", bytes.len())),
                "{msg}"
            );
        }
    }
    // A count that is text too, but a size within a record of what it announces.
    let n = u64::from(u32::from_le_bytes(*b"abcd"));
    assert!(super::stl::size_is_near(n, 84 + 50 * n - 3));
    assert!(super::stl::size_is_near(n, 84 + 50 * n + 49));
    assert!(!super::stl::size_is_near(n, 84 + 50 * n - 50));
    assert!(!super::stl::size_is_near(n, 684));
    // ASCII STL stays ASCII: a solid name in UTF-8, and a truncated one.
    let ascii = "solid café\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\nendfacet\nendsolid\n";
    assert_eq!(
        detect_format(ascii.as_bytes(), None),
        Some(Format::StlAscii)
    );
    assert_eq!(
        read_bytes(ascii.as_bytes(), Format::StlBinary)
            .unwrap()
            .triangle_count(),
        1
    );
    let (loc, _) = parse_err(&ascii.as_bytes()[..70], Format::StlBinary);
    assert_eq!(loc, Location::Line(6));
}

/// Files of more than the write-back step in the formats written in order (their
/// write-back started every few megabytes) hold the bytes written to memory.
#[test]
fn large_files_written_in_order_are_the_bytes_written_to_memory() {
    let dir = std::env::temp_dir().join(format!("meshbool-writeback-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let m = crate::shapes::uv_sphere([1_000.5, -2_000.25, 12.5], 40.0, 400, 260);
    let larger = crate::shapes::uv_sphere([1_000.5, -2_000.25, 12.5], 40.0, 640, 400);
    for (format, name, m) in [
        (Format::Obj, "big.obj", &m),
        (Format::PlyAscii, "big.ply", &m),
        (Format::PlyBinaryLe, "bin.ply", &larger),
        (Format::StlAscii, "big.stl", &m),
    ] {
        let want = write_to_vec(m, format);
        assert!(want.len() as u64 > 8 << 20, "{format:?}: {}", want.len());
        let path = dir.join(name);
        write_path_as(&path, m, format).unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), want, "{format:?}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A large binary STL written to a file on any number of threads (blocks written at their
/// offsets, their write-back started as they go) and read on many (the file read in
/// pieces, the corners welded in shards) is byte for byte the file streamed in order, and
/// reads back to the same mesh, vertex numbering included; a mesh that cannot be stored
/// is refused on that path too, leaving nothing behind.
#[test]
fn large_binary_stl_on_many_threads_is_the_file_of_one() {
    let dir = std::env::temp_dir().join(format!("meshbool-parallel-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("big.stl");
    let mut m = crate::shapes::uv_sphere([1_000.5, -2_000.25, 12.5], 40.0, 360, 200);
    // Negative zeros and far coordinates among the corners.
    m.positions[7][0] = -0.0;
    m.positions[8] = [1e30, -2.5e-30, 0.0];
    assert!(m.triangles.len() > 4 * (1 << 14) && m.triangles.len() % (1 << 13) != 0);
    let one = write_to_vec(&m, Format::StlBinary);
    let on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
    };
    let serial = on(1).install(|| read_bytes(&one, Format::StlBinary).unwrap());
    for threads in [1, 2, 3, 8] {
        let pool = on(threads);
        pool.install(|| write_path(&path, &m)).unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), one, "{threads} threads");
        let back = pool.install(|| read_path(&path)).unwrap();
        assert_eq!(back.triangles, serial.triangles, "{threads} threads");
        assert_eq!(soup_bits(&back), soup_bits(&serial), "{threads} threads");
    }
    assert_eq!(serial.triangle_count(), m.triangle_count());
    // Non-finite coordinates far into the file: the first is named, on any thread count.
    let mut nan = one.clone();
    for (t, o) in [(70_000, 40), (50_000, 28)] {
        let at = 84 + 50 * t + o;
        nan[at..at + 4].copy_from_slice(&f32::INFINITY.to_le_bytes());
    }
    for threads in [1, 8] {
        let e = on(threads).install(|| read_bytes(&nan, Format::StlBinary));
        assert!(
            matches!(&e, Err(Error::Parse { location: Location::Byte(b), .. }) if *b == 84 + 50 * 50_000 + 28),
            "{e:?}"
        );
    }
    let mut bad = m.clone();
    bad.positions[12_345][2] = 1e300;
    let e = on(8).install(|| write_path(dir.join("bad.stl"), &bad));
    assert!(matches!(e, Err(Error::InvalidMesh { .. })), "{e:?}");
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left, [std::ffi::OsString::from("big.stl")]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A named pipe is read to its end from one opening (a second opening would wait for a
/// writer that has gone); its format is told from its content.
#[cfg(unix)]
#[test]
fn a_named_pipe_is_read_once_to_its_end() {
    let dir = std::env::temp_dir().join(format!("meshbool-fifo-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let fifo = dir.join("pipe.stl");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        std::fs::remove_dir_all(&dir).unwrap();
        return; // no mkfifo here: nothing to test
    }
    let bytes = write_to_vec(&Mesh::unit_cube(), Format::StlBinary);
    let writer = {
        let (fifo, bytes) = (fifo.clone(), bytes.clone());
        std::thread::spawn(move || std::fs::write(fifo, bytes).unwrap())
    };
    let (tx, rx) = std::sync::mpsc::channel();
    let reader = fifo.clone();
    std::thread::spawn(move || tx.send(read_file(&reader, None).map(|(m, _)| m)));
    let got = rx
        .recv_timeout(std::time::Duration::from_secs(20))
        .expect("reading the pipe finished");
    writer.join().unwrap();
    assert_eq!(got.unwrap().triangle_count(), 12);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// An OBJ file read in pieces side by side is the file read in one pass: the same mesh,
/// or the same first error (message and line), for relative and forward references,
/// polygons, statements that are skipped, CRLF lines, and an error anywhere.
#[test]
fn obj_in_pieces_reads_as_in_one_pass() {
    let mut rng = crate::test_util::Rng(11);
    for case in 0..300 {
        let (mut text, mut defined) = (String::new(), 0i64);
        let lines = 5 + rng.next() % 60;
        let error_at = (case % 3 != 0).then(|| rng.next() % lines);
        for l in 0..lines {
            let end = if rng.next() % 4 == 0 { "\r\n" } else { "\n" };
            if error_at == Some(l) {
                let bad = [
                    "v 0 x 0",
                    "v 1 2",
                    "f 1 2 0",
                    "f 1 2",
                    "f -999 1 2",
                    "f 1 2 99999",
                    "v 0 0 0 1 2",
                    "f 1 2 a/b",
                ];
                text += bad[(rng.next() % bad.len() as u64) as usize];
                text += end;
                continue;
            }
            match rng.next() % 6 {
                0..=2 => {
                    let c = [0, 1, 2].map(|_| (rng.next() % 1000) as f64 / 7.0);
                    text += &format!("v {} {} {}", c[0], c[1], c[2]);
                    defined += 1;
                }
                3 | 4 if defined >= 3 => {
                    let n = 3 + rng.next() % 3;
                    text += "f";
                    for _ in 0..n {
                        let v = 1 + (rng.next() % defined as u64) as i64;
                        // Relative, absolute, or with texture and normal references.
                        match rng.next() % 3 {
                            0 => text += &format!(" {}", v - defined - 1),
                            1 => text += &format!(" {v}"),
                            _ => text += &format!(" {v}/1/1"),
                        }
                    }
                }
                _ => text += ["# c", "vt 0 0", "vn 0 0 1", "g x", ""][(rng.next() % 5) as usize],
            }
            text += end;
        }
        let bytes = text.as_bytes();
        let whole = obj::read_in(bytes, 1).map_err(|e| e.to_string());
        for pieces in [2, 3, 5, 8, 40] {
            let split = obj::read_in(bytes, pieces).map_err(|e| e.to_string());
            assert_eq!(split, whole, "case {case}, {pieces} pieces:\n{text}");
        }
    }
}

/// PLY files of the usual shape (a vertex element of scalars, a face element of one index
/// list) are read side by side; the result is the general reader's, and whatever is out
/// of the ordinary (a polygon, an index out of range, a non-finite coordinate, a body
/// longer or shorter than declared, blank lines or extra values in ASCII) goes to the
/// general reader, which names the problem. Every encoding, coordinate, length and index
/// type, extra properties around `x y z`, CRLF lines, ASCII bodies in many pieces.
#[test]
fn ply_triangles_side_by_side_read_as_the_general_reader() {
    let mut rng = crate::test_util::Rng(5);
    let types: [(&str, usize); 8] = [
        ("char", 1),
        ("uchar", 1),
        ("short", 2),
        ("ushort", 2),
        ("int", 4),
        ("uint", 4),
        ("float", 4),
        ("double", 8),
    ];
    let mut fast = 0;
    for case in 0..400 {
        let enc = ["ascii", "binary_little_endian", "binary_big_endian"][case % 3];
        let be = enc == "binary_big_endian";
        let nl = if enc == "ascii" && rng.next() % 3 == 0 {
            "\r\n"
        } else {
            "\n"
        };
        let nv = 3 + (rng.next() % 30) as usize;
        let nf = (rng.next() % 40) as usize;
        // Vertex properties: x, y, z (signed or floating types) among extras.
        let mut props: Vec<(String, usize)> = ["x", "y", "z"]
            .iter()
            .map(|a| (a.to_string(), [0, 2, 4, 6, 7][(rng.next() % 5) as usize]))
            .collect();
        for e in 0..rng.next() % 3 {
            let at = (rng.next() % (props.len() as u64 + 1)) as usize;
            props.insert(at, (format!("extra{e}"), (rng.next() % 8) as usize));
        }
        let ct = [1, 3, 4, 5][(rng.next() % 4) as usize];
        let it = [1, 2, 3, 4, 5][(rng.next() % 5) as usize];
        let mut head = format!("ply{nl}format {enc} 1.0{nl}element vertex {nv}{nl}");
        for (name, t) in &props {
            head += &format!("property {} {name}{nl}", types[*t].0);
        }
        head += &format!(
            "element face {nf}{nl}property list {} {} vertex_indices{nl}end_header{nl}",
            types[ct].0, types[it].0
        );
        let flaw = rng.next() % 12;
        let mut body: Vec<u8> = Vec::new();
        let value = |body: &mut Vec<u8>, t: usize, x: f64| {
            if enc == "ascii" {
                body.extend(format!("{x} ").as_bytes());
                return;
            }
            let mut b: Vec<u8> = match t {
                0 => vec![x as i8 as u8],
                1 => vec![x as u8],
                2 => (x as i16).to_le_bytes().to_vec(),
                3 => (x as u16).to_le_bytes().to_vec(),
                4 => (x as i32).to_le_bytes().to_vec(),
                5 => (x as u32).to_le_bytes().to_vec(),
                6 => (x as f32).to_le_bytes().to_vec(),
                _ => x.to_le_bytes().to_vec(),
            };
            if be {
                b.reverse();
            }
            body.extend(b);
        };
        let end = |body: &mut Vec<u8>| {
            if enc == "ascii" {
                body.pop();
                body.extend(nl.as_bytes());
            }
        };
        for v in 0..nv {
            for (name, t) in &props {
                let mut x = (rng.next() % 100) as f64
                    - if *t == 1 || *t == 3 || *t == 5 {
                        0.0
                    } else {
                        50.0
                    };
                if *t >= 6 {
                    x += 0.25;
                }
                if flaw == 0 && v == nv / 2 && name == "y" && *t >= 6 {
                    x = f64::NAN;
                }
                value(&mut body, *t, x);
            }
            end(&mut body);
        }
        for f in 0..nf {
            let n = if flaw == 1 && f == nf / 2 { 4 } else { 3 };
            // A count that says 4 before three indices (ASCII: the next line's first
            // value would be the fourth).
            let said = if flaw == 7 && enc == "ascii" && f == 0 {
                4
            } else {
                n
            };
            value(&mut body, ct, said as f64);
            for k in 0..n {
                let mut i = (rng.next() % nv as u64) as f64;
                if flaw == 2 && f == nf / 2 && k == 1 {
                    i = nv as f64 + (case % 2) as f64;
                }
                value(&mut body, it, i);
            }
            end(&mut body);
            if flaw == 3 && enc == "ascii" && f == 0 {
                body.extend(nl.as_bytes());
            }
        }
        match flaw {
            4 => body.extend(b"7"),
            5 => {
                body.truncate(body.len().saturating_sub(2));
            }
            6 if enc == "ascii" => body.extend(format!("{nl}{nl}  {nl}").as_bytes()),
            _ => {}
        }
        let mut bytes = head.into_bytes();
        bytes.extend(body);
        let general = ply::both_readers(&bytes, 1).1.map_err(|e| e.to_string());
        for pieces in [1, 2, 3, 7] {
            let (side, _) = ply::both_readers(&bytes, pieces);
            if let Some(m) = &side {
                assert_eq!(Ok(m), general.as_ref(), "case {case}, {pieces} pieces");
                fast += 1;
            }
        }
        let read = read_bytes(&bytes, Format::PlyAscii).map_err(|e| e.to_string());
        assert_eq!(read, general, "case {case}");
        // Files without a flaw are read side by side.
        if flaw > 7 && nf > 0 {
            assert!(ply::both_readers(&bytes, 3).0.is_some(), "case {case}");
        }
    }
    assert!(fast > 400, "{fast} side by side");
}

/// Text and PLY records formatted side by side are written in order: the same bytes on
/// one thread and on several, across block and batch boundaries.
#[test]
fn records_written_side_by_side_are_the_bytes_of_one_thread() {
    // 2 · 300 · 150 = 89,400 triangles, 44,702 vertices: several batches of 3 threads.
    let m = crate::shapes::uv_sphere([0.0; 3], 1.0, 300, 151);
    for format in [
        Format::Obj,
        Format::PlyAscii,
        Format::PlyBinaryLe,
        Format::PlyBinaryBe,
    ] {
        let on = |threads: usize| {
            crate::test_util::on_threads(threads, || {
                let mut out = Vec::new();
                write(&mut out, &m, format).unwrap();
                out
            })
        };
        let one = on(1);
        assert_eq!(on(3), one, "{format:?}");
        assert_eq!(on(8), one, "{format:?}");
        assert_eq!(read_bytes(&one, format).unwrap(), m, "{format:?}");
    }
}
