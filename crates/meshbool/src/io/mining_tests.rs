//! GOCAD TSurf, Surpac DTM and LandXML: round trips, samples as other software writes
//! them, errors, truncation and detection.

use super::*;
use crate::measure::mesh_stats;
use crate::test_util::Rng;

/// A cuboid at UTM offsets plus vertices whose coordinates exercise number formatting:
/// huge, subnormal, negative zero, 17 significant digits, and one unreferenced vertex.
fn awkward() -> Mesh {
    let mut m = Mesh::cuboid(
        [478_614.7, 6_772_313.84, -0.1],
        [478_624.700_000_000_1, 6_772_333.123_456_789, 1e-300],
    );
    m.positions.push([1e300, -2.5e-310, 0.1 + 0.2]);
    m.positions.push([-0.0, std::f64::consts::PI, -1.0 / 3.0]);
    m.positions.push([7.0, 8.0, 9.0]);
    m.positions.push([5e-324, -1e-5, 123_456_789.012_345_67]);
    m.triangles.push([8, 9, 10]);
    m
}

/// `mesh` written in `format` and read back (a Surpac DTM through both of its files),
/// after checking that the written content is detected as `format`.
fn round_trip(mesh: &Mesh, format: Format) -> Mesh {
    if format == Format::SurpacDtm {
        let (mut dtm, mut strings) = (Vec::new(), Vec::new());
        write_surpac_dtm(&mut dtm, &mut strings, mesh, "t").unwrap();
        assert_eq!(detect_format(&dtm, None), Some(format));
        return read_surpac_dtm(&dtm, &strings).unwrap();
    }
    let mut bytes = Vec::new();
    write(&mut bytes, mesh, format).unwrap();
    assert_eq!(detect_format(&bytes, None), Some(format));
    read_bytes(&bytes, format).unwrap()
}

fn bits(m: &Mesh) -> Vec<[u64; 3]> {
    m.positions.iter().map(|p| p.map(f64::to_bits)).collect()
}

const MINING: [Format; 3] = [Format::GocadTs, Format::SurpacDtm, Format::LandXml];

#[test]
fn mining_formats_round_trip_bit_exact() {
    let terrain = crate::test_util::terrain_and_drill(crate::test_util::UTM).0;
    for mesh in [Mesh::unit_cube(), awkward(), terrain] {
        // Compared as text: the awkward mesh's area overflows to NaN.
        let want = format!("{:?}", mesh_stats(&mesh));
        for f in MINING {
            let back = round_trip(&mesh, f);
            assert_eq!(bits(&back), bits(&mesh), "{f}");
            assert_eq!(back.triangles, mesh.triangles, "{f}");
            assert_eq!(format!("{:?}", mesh_stats(&back)), want, "{f}");
        }
    }
    // An empty mesh and vertices without triangles come back as they were.
    let points = Mesh::new(vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]], vec![]).unwrap();
    for m in [Mesh::default(), points] {
        for f in MINING {
            assert_eq!(round_trip(&m, f), m, "{f}");
        }
    }
}

// ---------------------------------------------------------------------------------------
// GOCAD TSurf
// ---------------------------------------------------------------------------------------

/// Two surfaces with a polyline between them: the first in a depth frame with properties,
/// two face sets, `PATOM` and `ATOM` and a property class header; the second with a
/// one-line header.
const GOCAD_SAMPLE: &str = "GOCAD TSurf 1
HEADER {
name:fault_a
*solid*color:1 0 0 1
}
GOCAD_ORIGINAL_COORDINATE_SYSTEM
NAME Default
AXIS_NAME \"X\" \"Y\" \"Z\"
AXIS_UNIT \"m\" \"m\" \"m\"
ZPOSITIVE Depth
END_ORIGINAL_COORDINATE_SYSTEM
PROPERTIES Density Porosity
PROPERTY_CLASSES density porosity
PROPERTY_CLASS_HEADER density {
kind:Density
unit:g/cm3
}
# face set one
TFACE
PVRTX 10 478600.5 6772300.25 120.0 2.65 0.1
PVRTX 11 478610.5 6772300.25 121.5 2.70 0.12
PVRTX 12 478600.5 6772310.25 119 2.60 0.08
TRGL 10 11 12
TFACE
PATOM 20 11 2.70 0.12
VRTX 21 478612 6772311 118.25
ATOM 22 12
TRGL 20 21 22
BSTONE 10
BORDER 30 10 11
END
GOCAD PLine 1
HEADER {
name:trace
}
ILINE
VRTX 1 0 0 0
VRTX 2 1 1 1
SEG 1 2
END
GOCAD TSurf 1
HEADER {name:second}
VRTX -4 0 0 5
VRTX 2 1 0 5
VRTX 3 0 1 5
TFACE
TRGL -4 2 3
END
";

fn gocad_err(text: &str) -> (Location, String) {
    match read_bytes(text.as_bytes(), Format::GocadTs) {
        Err(Error::Parse {
            format: Format::GocadTs,
            location,
            message,
        }) => (location, message),
        other => panic!("expected a GOCAD parse error, got {other:?}"),
    }
}

#[test]
fn gocad_sample_reads_as_written_by_other_software() {
    let (m, counts) = gocad::read_counted(GOCAD_SAMPLE.as_bytes()).unwrap();
    assert_eq!(
        m.positions,
        vec![
            // ZPOSITIVE Depth: z negated.
            [478_600.5, 6_772_300.25, -120.0],
            [478_610.5, 6_772_300.25, -121.5],
            [478_600.5, 6_772_310.25, -119.0],
            [478_612.0, 6_772_311.0, -118.25],
            // The second surface: elevation.
            [0.0, 0.0, 5.0],
            [1.0, 0.0, 5.0],
            [0.0, 1.0, 5.0],
        ]
    );
    // Atoms are their vertices; ids are local to each surface.
    assert_eq!(m.triangles, vec![[0, 1, 2], [1, 3, 2], [4, 5, 6]]);
    assert_eq!(
        counts,
        gocad::Counts {
            surfaces: 2,
            face_sets: 3,
            property_values: 8,
            other_objects: 1,
        }
    );
    // CRLF line ends read the same.
    let crlf = GOCAD_SAMPLE.replace('\n', "\r\n");
    assert_eq!(read_bytes(crlf.as_bytes(), Format::GocadTs).unwrap(), m);
    assert_eq!(
        detect_format(GOCAD_SAMPLE.as_bytes(), None),
        Some(Format::GocadTs)
    );
}

#[test]
fn gocad_writes_one_surface_with_one_based_ids() {
    let m = Mesh::new(
        vec![[0.5, 1.0, -2.0], [3.0, 4.25, 5.0], [6.0, 7.0, 1e-7]],
        vec![[0, 1, 2]],
    )
    .unwrap();
    let mut out = Vec::new();
    write(&mut out, &m, Format::GocadTs).unwrap();
    let text = String::from_utf8(out).unwrap();
    assert_eq!(
        text,
        "GOCAD TSurf 1\nHEADER {\nname:meshbool\n}\nGOCAD_ORIGINAL_COORDINATE_SYSTEM\n\
         NAME Default\nAXIS_NAME \"X\" \"Y\" \"Z\"\nZPOSITIVE Elevation\n\
         END_ORIGINAL_COORDINATE_SYSTEM\nTFACE\nVRTX 1 0.5 1.0 -2.0\nVRTX 2 3.0 4.25 5.0\n\
         VRTX 3 6.0 7.0 1e-7\nTRGL 1 2 3\nEND\n"
    );
}

#[test]
fn gocad_errors_name_the_line() {
    let head = "GOCAD TSurf 1\nHEADER {\nname:x\n}\nTFACE\nVRTX 1 0 0 0\nVRTX 2 1 0 0\n";
    let (loc, msg) = gocad_err(&format!("{head}VRTX 3 0 1 0\nTRGL 1 2 7\nEND\n"));
    assert_eq!(loc, Location::Line(9));
    assert!(msg.contains("vertex id 7"), "{msg}");
    let (loc, msg) = gocad_err(&format!("{head}VRTX 2 0 1 0\nEND\n"));
    assert_eq!(loc, Location::Line(8));
    assert!(msg.contains("defined twice"), "{msg}");
    let (loc, msg) = gocad_err(&format!("{head}ATOM 3 9\nEND\n"));
    assert_eq!(loc, Location::Line(8));
    assert!(msg.contains("atom 3 refers to vertex 9"), "{msg}");
    for bad in ["nan", "inf", "-infinity", "1e999"] {
        let (loc, msg) = gocad_err(&format!("{head}VRTX 3 0 {bad} 0\nEND\n"));
        assert_eq!(loc, Location::Line(8), "{bad}");
        assert!(msg.contains("non-finite"), "{bad}: {msg}");
    }
    let (loc, msg) = gocad_err(&format!("{head}VRTX 3 0 x 0\nEND\n"));
    assert!(
        loc == Location::Line(8) && msg.contains("expected a number"),
        "{msg}"
    );
    let (loc, msg) = gocad_err(&format!("{head}VRTX 3 0 1\nEND\n"));
    assert!(
        loc == Location::Line(8) && msg.contains("z is missing"),
        "{msg}"
    );
    let (loc, msg) = gocad_err(&format!("{head}VRTX x 0 1 2\nEND\n"));
    assert!(loc == Location::Line(8) && msg.contains("integer"), "{msg}");
    let (loc, msg) = gocad_err(&format!("{head}TRGL 1 2\nEND\n"));
    assert!(loc == Location::Line(8) && msg.contains("missing"), "{msg}");
    let (loc, msg) = gocad_err(&format!("ZPOSITIVE Up\n{head}"));
    assert!(
        loc == Location::Line(1) && msg.contains("GOCAD TSurf 1"),
        "{msg}"
    );
    let (loc, msg) = gocad_err(&format!("{head}ZPOSITIVE Up\nEND\n"));
    assert!(
        loc == Location::Line(8) && msg.contains("Elevation or Depth"),
        "{msg}"
    );
    // Truncated: no END, an unclosed header, a new object inside a surface.
    let (loc, msg) = gocad_err(head);
    assert!(
        loc == Location::Line(8) && msg.contains("truncated"),
        "{msg}"
    );
    let (loc, msg) = gocad_err("GOCAD TSurf 1\nHEADER {\nname:x\n");
    assert!(
        loc == Location::Line(2) && msg.contains("truncated"),
        "{msg}"
    );
    let (loc, msg) = gocad_err(&format!("{head}GOCAD TSurf 1\nEND\n"));
    assert!(loc == Location::Line(8) && msg.contains("line 1"), "{msg}");
    // Only other objects.
    let (loc, msg) = gocad_err("GOCAD PLine 1\nVRTX 1 0 0 0\nEND\n");
    assert!(
        loc == Location::Whole && msg.contains("no `GOCAD TSurf`"),
        "{msg}"
    );
}

// ---------------------------------------------------------------------------------------
// LandXML
// ---------------------------------------------------------------------------------------

/// Two surfaces: the first with arbitrary ids, an invisible face, a neighbour attribute,
/// source data and points listed after a blank-padded one; the second compact.
const LANDXML_SAMPLE: &str = r#"<?xml version="1.0" encoding="UTF-8"?>
<LandXML xmlns="http://www.landxml.org/schema/LandXML-1.2" version="1.2" date="2024-05-01" time="10:00:00">
  <Units>
    <Metric linearUnit="meter" areaUnit="squareMeter" volumeUnit="cubicMeter" temperatureUnit="celsius" pressureUnit="milliBars"/>
  </Units>
  <Application name="Civil" manufacturer="Somebody"/>
  <!-- an existing ground surface -->
  <Surfaces>
    <Surface name="EG" desc="existing ground">
      <SourceData>
        <Breaklines><Breakline><PntList3D>1 2 3 4 5 6</PntList3D></Breakline></Breaklines>
      </SourceData>
      <Definition surfType="TIN" area2DSurf="100" elevMax="352" elevMin="350">
        <Pnts>
          <P id="101">6772300.5 478600.25 350.0</P>
          <P id="205">6772300.5 478610.25 351.5</P>
          <P id="7"> 6772310.5  478600.25
             352 </P>
          <P id="9">6772310.5 478610.25 351</P>
        </Pnts>
        <Faces>
          <F n="2 0 0">101 205 7</F>
          <F i="1">205 9 7</F>
        </Faces>
      </Definition>
    </Surface>
    <Surface name="Design">
      <Definition surfType="TIN"><Pnts><P id="1">10 20 30</P><P id="2">10 21 30</P><P id="3">11 20 30</P><P id="4">11 21 30</P></Pnts>
        <Faces><F>1 2 3</F><F i="0">2 4 3</F></Faces></Definition>
    </Surface>
  </Surfaces>
</LandXML>
"#;

fn landxml_err(text: &str) -> (Location, String) {
    match read_bytes(text.as_bytes(), Format::LandXml) {
        Err(Error::Parse {
            format: Format::LandXml,
            location,
            message,
        }) => (location, message),
        other => panic!("expected a LandXML parse error, got {other:?}"),
    }
}

#[test]
fn landxml_sample_reads_as_written_by_other_software() {
    let (m, counts) = landxml::read_counted(LANDXML_SAMPLE.as_bytes()).unwrap();
    // Northing first in the file: point 101 lies at easting (x) 478600.25, northing (y)
    // 6772300.5.
    assert_eq!(m.positions[0][0], 478_600.25);
    assert_eq!(m.positions[0][1], 6_772_300.5);
    assert_eq!(
        m.positions,
        vec![
            [478_600.25, 6_772_300.5, 350.0],
            [478_610.25, 6_772_300.5, 351.5],
            [478_600.25, 6_772_310.5, 352.0],
            [478_610.25, 6_772_310.5, 351.0],
            [20.0, 10.0, 30.0],
            [21.0, 10.0, 30.0],
            [20.0, 11.0, 30.0],
            [21.0, 11.0, 30.0],
        ]
    );
    assert_eq!(m.triangles, vec![[0, 1, 2], [4, 5, 6], [5, 7, 6]]);
    assert_eq!(
        counts,
        landxml::Counts {
            surfaces: 2,
            invisible_faces: 1,
        }
    );
    assert_eq!(
        detect_format(LANDXML_SAMPLE.as_bytes(), None),
        Some(Format::LandXml)
    );
    // A quad face is two triangles; a namespace prefix does not matter.
    let quad = r#"<x:LandXML xmlns:x="http://www.landxml.org/schema/LandXML-1.2"><x:Surfaces><x:Surface><x:Definition>
        <x:Pnts><x:P id="1">0 0 0</x:P><x:P id="2">0 1 0</x:P><x:P id="3">1 1 0</x:P><x:P id="4">1 0 0</x:P></x:Pnts>
        <x:Faces><x:F>1 2 3 4</x:F></x:Faces></x:Definition></x:Surface></x:Surfaces></x:LandXML>"#;
    let m = read_bytes(quad.as_bytes(), Format::LandXml).unwrap();
    assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    assert_eq!(m.positions[1], [1.0, 0.0, 0.0]);
}

#[test]
fn landxml_writes_northing_easting_elevation() {
    let m = Mesh::new(
        vec![
            [478_600.25, 6_772_300.5, 350.0],
            [1.0, 2.0, 3.0],
            [4.0, 5.0, 6.0],
        ],
        vec![[0, 1, 2]],
    )
    .unwrap();
    let mut out = Vec::new();
    write(&mut out, &m, Format::LandXml).unwrap();
    let text = String::from_utf8(out).unwrap();
    assert!(text.starts_with("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<LandXML "));
    assert!(text.contains(" version=\"1.2\" date=\""), "{text}");
    assert!(text.contains("<Surface name=\"meshbool\">"), "{text}");
    assert!(text.contains("<Definition surfType=\"TIN\">"), "{text}");
    assert!(
        text.contains("<P id=\"1\">6772300.5 478600.25 350.0</P>\n"),
        "{text}"
    );
    assert!(text.contains("<P id=\"3\">5.0 4.0 6.0</P>\n"), "{text}");
    assert!(text.contains("<F>1 2 3</F>\n"), "{text}");
    assert!(text.ends_with("</LandXML>\n"));
    // The date and time attributes are `xs:date` and `xs:time`.
    let date = text.split("date=\"").nth(1).unwrap();
    let time = text.split("time=\"").nth(1).unwrap();
    let digits = |s: &str, pattern: &str| {
        s.bytes().zip(pattern.bytes()).all(|(c, p)| {
            if p == b'9' {
                c.is_ascii_digit()
            } else {
                c == p
            }
        })
    };
    assert!(digits(date, "9999-99-99\""), "{date}");
    assert!(digits(time, "99:99:99\""), "{time}");
}

#[test]
fn landxml_errors_name_the_line() {
    let surface = |pnts: &str, faces: &str| {
        format!(
            "<LandXML>\n<Surfaces>\n<Surface>\n<Definition>\n<Pnts>\n{pnts}</Pnts>\n<Faces>\n{faces}</Faces>\n</Definition>\n</Surface>\n</Surfaces>\n</LandXML>\n"
        )
    };
    let three = "<P id=\"1\">0 0 0</P>\n<P id=\"2\">0 1 0</P>\n<P id=\"3\">1 0 0</P>\n";
    assert_eq!(
        read_bytes(surface(three, "<F>1 2 3</F>\n").as_bytes(), Format::LandXml)
            .unwrap()
            .triangles,
        vec![[0, 1, 2]]
    );
    let (loc, msg) = landxml_err(&surface("<P id=\"1\">0 0 0</P>\n<P id=\"2\">5 6</P>\n", ""));
    assert_eq!(loc, Location::Line(7));
    assert!(msg.contains("found 2 numbers"), "{msg}");
    let (loc, msg) = landxml_err(&surface(three, "<F>1 2 3</F>\n<F>1 2 44</F>\n"));
    assert_eq!(loc, Location::Line(12));
    assert!(msg.contains("point id 44"), "{msg}");
    let (loc, msg) = landxml_err(&surface(three, "<F>1 2</F>\n"));
    assert!(
        loc == Location::Line(11) && msg.contains("found 2"),
        "{msg}"
    );
    let (loc, msg) = landxml_err(&surface(three, "<F>1 2 x</F>\n"));
    assert!(
        loc == Location::Line(11) && msg.contains("integer"),
        "{msg}"
    );
    let (loc, msg) = landxml_err(&surface("<P>0 0 0</P>\n", ""));
    assert!(loc == Location::Line(6) && msg.contains("no id"), "{msg}");
    let (loc, msg) = landxml_err(&surface("<P id=\"a\">0 0 0</P>\n", ""));
    assert!(loc == Location::Line(6) && msg.contains("integer"), "{msg}");
    let (loc, msg) = landxml_err(&surface(
        "<P id=\"1\">0 0 0</P>\n<P id=\"1\">0 0 1</P>\n",
        "",
    ));
    assert!(loc == Location::Line(7) && msg.contains("twice"), "{msg}");
    for bad in ["NaN", "inf", "1e400"] {
        let (loc, msg) = landxml_err(&surface(&format!("<P id=\"1\">0 {bad} 0</P>\n"), ""));
        assert!(
            loc == Location::Line(6) && msg.contains("non-finite"),
            "{msg}"
        );
    }
    let (loc, msg) = landxml_err(&surface("<P id=\"1\">0 &amp; 0</P>\n", ""));
    assert!(loc == Location::Line(6) && msg.contains("entity"), "{msg}");
    // Malformed XML: the line of the problem.
    let (loc, msg) = landxml_err("<LandXML>\n<Surfaces>\n</Surface>\n</LandXML>\n");
    assert!(
        loc == Location::Line(3) && msg.contains("malformed XML"),
        "{msg}"
    );
    // Truncated.
    let whole = surface(three, "<F>1 2 3</F>\n");
    let (loc, msg) = landxml_err(&whole[..whole.find("<Faces>").unwrap()]);
    assert!(
        loc == Location::Line(10) && msg.contains("truncated"),
        "{loc} {msg}"
    );
    // Not LandXML, or no surface in it.
    let (loc, msg) = landxml_err("<?xml version=\"1.0\"?>\n<gml:Feature/>\n");
    assert!(
        loc == Location::Line(2) && msg.contains("<LandXML>"),
        "{msg}"
    );
    let (loc, msg) = landxml_err("<LandXML><Alignments/></LandXML>");
    assert!(
        loc == Location::Whole && msg.contains("no <Surface>"),
        "{msg}"
    );
    let (loc, _) = landxml_err("<?xml version=\"1.0\"?>\n");
    assert_eq!(loc, Location::Whole);
}

// ---------------------------------------------------------------------------------------
// Surpac DTM
// ---------------------------------------------------------------------------------------

/// A string file as Surpac writes one: two strings, padded numbers, descriptions.
const SURPAC_STR: &str = "pit_topo,01-May-24,,survey pickup
0,           0.000,           0.000,           0.000,           0.000,           0.000,           0.000
1, 6772300.500, 478600.250, 350.000,
1, 6772300.500, 478610.250, 351.500,
0, 0.000, 0.000, 0.000,
2, 6772310.500, 478600.250, 352.000, spot
2,   6772310.500,  478610.250,  351.000
0, 0.000, 0.000, 0.000,
0, 0.000, 0.000, 0.000, END
";

/// Its DTM: two objects, neighbour fields.
const SURPAC_DTM: &str = "pit_topo.str,01-May-24,,
0, 0.000, 0.000, 0.000, END
OBJECT, 1,
TRISOLATION, 1, neighbours=yes,validated=true,closed=no
1, 1, 2, 3, 0, 2, 0,
2, 2, 4, 3, 0, 0, 1,
OBJECT, 2,
TRISOLATION, 1, neighbours=no,validated=true,closed=no
1, 3, 4, 1, 0, 0, 0,
END
";

fn surpac_err(dtm: &str, strings: &str) -> (Location, String) {
    match read_surpac_dtm(dtm.as_bytes(), strings.as_bytes()) {
        Err(Error::Parse {
            format: Format::SurpacDtm,
            location,
            message,
        }) => (location, message),
        other => panic!("expected a Surpac parse error, got {other:?}"),
    }
}

fn tmp_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("meshbool-mining-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn surpac_pair_reads_as_written_by_surpac() {
    let m = read_surpac_dtm(SURPAC_DTM.as_bytes(), SURPAC_STR.as_bytes()).unwrap();
    // Y (northing) first in the string file: x is the third field.
    assert_eq!(m.positions[0][0], 478_600.25);
    assert_eq!(m.positions[0][1], 6_772_300.5);
    assert_eq!(
        m.positions,
        vec![
            [478_600.25, 6_772_300.5, 350.0],
            [478_610.25, 6_772_300.5, 351.5],
            [478_600.25, 6_772_310.5, 352.0],
            [478_610.25, 6_772_310.5, 351.0],
        ]
    );
    assert_eq!(m.triangles, vec![[0, 1, 2], [1, 3, 2], [2, 3, 0]]);
    assert_eq!(
        detect_format(SURPAC_DTM.as_bytes(), None),
        Some(Format::SurpacDtm)
    );

    // By path: the .str beside the .dtm.
    let dir = tmp_dir("pair");
    std::fs::write(dir.join("pit_topo.dtm"), SURPAC_DTM).unwrap();
    std::fs::write(dir.join("pit_topo.str"), SURPAC_STR).unwrap();
    let (by_path, f) = read_file(dir.join("pit_topo.dtm"), None).unwrap();
    assert_eq!((by_path, f), (m, Format::SurpacDtm));
    // Without it: an error naming the string file.
    std::fs::remove_file(dir.join("pit_topo.str")).unwrap();
    let e = read_path(dir.join("pit_topo.dtm")).unwrap_err();
    assert!(
        matches!(e, Error::File { ref path, .. } if path.ends_with("pit_topo.str")),
        "{e:?}"
    );
    assert!(e.to_string().contains("pit_topo.str"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();

    // The .dtm alone cannot be read, nor written to one writer.
    let (loc, msg) = match read_bytes(SURPAC_DTM.as_bytes(), Format::SurpacDtm) {
        Err(Error::Parse {
            location, message, ..
        }) => (location, message),
        other => panic!("{other:?}"),
    };
    assert!(
        loc == Location::Whole && msg.contains("string file (.str)"),
        "{msg}"
    );
    assert!(matches!(
        write(&mut Vec::new(), &Mesh::unit_cube(), Format::SurpacDtm),
        Err(Error::InvalidParameter(_))
    ));
}

#[test]
fn surpac_writes_both_files_beside_each_other() {
    let cube = Mesh::cuboid(
        [478_600.0, 6_772_300.0, 350.0],
        [478_601.0, 6_772_302.0, 353.0],
    );
    let (mut dtm, mut strings) = (Vec::new(), Vec::new());
    write_surpac_dtm(&mut dtm, &mut strings, &cube, "pit,1").unwrap();
    let (dtm, strings) = (
        String::from_utf8(dtm).unwrap(),
        String::from_utf8(strings).unwrap(),
    );
    let s: Vec<&str> = strings.lines().collect();
    assert!(
        s[0].starts_with("pit_1,") && s[0].ends_with(",,meshbool"),
        "{}",
        s[0]
    );
    assert_eq!(s[1], "0, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000");
    assert_eq!(s[2], "1, 6772300.0, 478600.0, 350.0,");
    assert_eq!(s.len(), 2 + 8 + 2);
    assert_eq!(
        s[10..],
        ["0, 0.000, 0.000, 0.000,", "0, 0.000, 0.000, 0.000, END"]
    );
    let d: Vec<&str> = dtm.lines().collect();
    assert_eq!(
        d[..4],
        [
            "pit_1.str,",
            "0, 0.000, 0.000, 0.000, END",
            "OBJECT, 1,",
            "TRISOLATION, 1, neighbours=no,validated=false,closed=yes",
        ]
    );
    let [a, b, c] = cube.triangles[0].map(|i| i + 1);
    assert_eq!(d[4], format!("1, {a}, {b}, {c}, 0, 0, 0,"));
    assert_eq!(d.len(), 4 + 12 + 1);
    assert_eq!(d[16], "END");
    // An open surface is not closed.
    let mut open = cube.clone();
    open.triangles.pop();
    let mut dtm = Vec::new();
    write_surpac_dtm(&mut dtm, &mut Vec::new(), &open, "o").unwrap();
    assert!(String::from_utf8(dtm).unwrap().contains("closed=no\n"));

    // By path: t.dtm and t.str; a .str name for the DTM is refused.
    let dir = tmp_dir("write");
    write_path(dir.join("t.dtm"), &cube).unwrap();
    assert!(std::fs::read_to_string(dir.join("t.str"))
        .unwrap()
        .starts_with("t,"));
    assert_eq!(read_path(dir.join("t.dtm")).unwrap(), cube);
    assert!(matches!(
        write_path_as(dir.join("u.STR"), &cube, Format::SurpacDtm),
        Err(Error::InvalidParameter(_))
    ));
    assert!(!dir.join("u.STR").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn surpac_errors_name_the_file_and_line() {
    let (loc, msg) = surpac_err(&SURPAC_DTM.replace("3, 4, 1,", "3, 5, 1,"), SURPAC_STR);
    assert!(
        loc == Location::Line(9) && msg.contains("point 5") && msg.contains("4 points"),
        "{msg}"
    );
    let (loc, msg) = surpac_err(&SURPAC_DTM.replace("2, 4, 3,", "2, 0, 3,"), SURPAC_STR);
    assert!(
        loc == Location::Line(6) && msg.contains("three point numbers"),
        "{msg}"
    );
    let (loc, msg) = surpac_err(
        &SURPAC_DTM.replace("2, 2, 4, 3, 0, 0, 1,", "2, 2, 4"),
        SURPAC_STR,
    );
    assert!(
        loc == Location::Line(6) && msg.contains("three point numbers"),
        "{msg}"
    );
    let (loc, msg) = surpac_err(&SURPAC_DTM.replace("2, 2, 4", "2.5, 2, 4"), SURPAC_STR);
    assert!(
        loc == Location::Line(6) && msg.contains("triangle record"),
        "{msg}"
    );
    let (loc, msg) = surpac_err(&SURPAC_DTM.replace("\nEND\n", "\n"), SURPAC_STR);
    assert!(
        loc == Location::Line(10) && msg.contains("truncated"),
        "{loc} {msg}"
    );
    let (loc, msg) = surpac_err("a.str,\n1, 2, 3, 4,\nEND\n", SURPAC_STR);
    assert!(
        loc == Location::Whole && msg.contains("not a Surpac DTM"),
        "{msg}"
    );

    let (loc, msg) = surpac_err(
        SURPAC_DTM,
        &SURPAC_STR.replace("478610.250, 351.500,", "478610.250"),
    );
    assert!(
        loc == Location::Line(4) && msg.starts_with("string file:") && msg.contains("z is missing"),
        "{msg}"
    );
    let (loc, msg) = surpac_err(SURPAC_DTM, &SURPAC_STR.replace("351.500", "nan"));
    assert!(
        loc == Location::Line(4) && msg.contains("string file") && msg.contains("non-finite"),
        "{msg}"
    );
    let (loc, msg) = surpac_err(
        SURPAC_DTM,
        &SURPAC_STR.replace("2, 6772310.500", "two, 6772310.500"),
    );
    assert!(
        loc == Location::Line(6) && msg.contains("string file"),
        "{msg}"
    );
    let (loc, msg) = surpac_err(SURPAC_DTM, &SURPAC_STR.replace(", END", ""));
    assert!(
        loc == Location::Line(10) && msg.contains("truncated"),
        "{loc} {msg}"
    );
    let (loc, msg) = surpac_err(SURPAC_DTM, "name\n1, 2, 3, 4\n0, 0, 0, 0, END\n");
    assert!(
        loc == Location::Line(2) && msg.contains("axis record"),
        "{msg}"
    );
    assert_eq!(surpac_err("", SURPAC_STR).0, Location::Whole);
}

// ---------------------------------------------------------------------------------------
// All three
// ---------------------------------------------------------------------------------------

/// Reads `bytes` in `format` (a Surpac DTM with `strings`), checking that it does not
/// panic; the mesh when it reads.
fn try_read(format: Format, bytes: &[u8], strings: &[u8]) -> Option<Mesh> {
    let read = if format == Format::SurpacDtm {
        read_surpac_dtm(bytes, strings)
    } else {
        read_bytes(bytes, format)
    };
    read.ok()
}

#[test]
fn truncation_at_every_byte_is_an_error_or_a_smaller_mesh() {
    let samples = [
        (Format::GocadTs, GOCAD_SAMPLE, ""),
        (Format::LandXml, LANDXML_SAMPLE, ""),
        (Format::SurpacDtm, SURPAC_DTM, SURPAC_STR),
    ];
    for (f, text, strings) in samples {
        let full = try_read(f, text.as_bytes(), strings.as_bytes()).unwrap();
        for cut in 0..text.len() {
            if let Some(m) = try_read(f, &text.as_bytes()[..cut], strings.as_bytes()) {
                assert!(
                    m.triangle_count() <= full.triangle_count()
                        && m.vertex_count() <= full.vertex_count(),
                    "{f} cut at {cut}"
                );
            }
        }
        if f == Format::SurpacDtm {
            for cut in 0..strings.trim_end().len() {
                // Cut anywhere before the end of its END record, the string file is an
                // error.
                let cut_str = &strings.as_bytes()[..cut];
                assert!(
                    try_read(f, text.as_bytes(), cut_str).is_none(),
                    "string file cut at {cut}"
                );
            }
        }
    }
}

#[test]
fn changed_bytes_give_an_error_or_a_mesh_never_a_panic() {
    let samples = [
        (Format::GocadTs, GOCAD_SAMPLE, ""),
        (Format::LandXml, LANDXML_SAMPLE, ""),
        (Format::SurpacDtm, SURPAC_DTM, SURPAC_STR),
    ];
    let mut rng = Rng(0x5eed_1234_abcd);
    let alphabet = b" \n\r\t0123456789-.,e<>/=\"&;{}#ABCENPTVXZ";
    for (f, text, strings) in samples {
        for at in 0..text.len() {
            for v in [b'0', b' ', b'\n', b'}', b'<', 0xFF] {
                let mut b = text.as_bytes().to_vec();
                b[at] = v;
                let _ = try_read(f, &b, strings.as_bytes());
            }
        }
        for _ in 0..2000 {
            let mut b = text.as_bytes().to_vec();
            let mut s = strings.as_bytes().to_vec();
            for _ in 0..1 + rng.next() % 4 {
                let c = alphabet[(rng.next() % alphabet.len() as u64) as usize];
                let target = if s.is_empty() || rng.next() % 2 == 0 {
                    &mut b
                } else {
                    &mut s
                };
                let at = (rng.next() % target.len() as u64) as usize;
                match rng.next() % 3 {
                    0 => target[at] = c,
                    1 => target.insert(at, c),
                    _ => {
                        target.remove(at);
                    }
                }
            }
            let _ = try_read(f, &b, &s);
            let _ = detect_format(&b, None);
        }
    }
}

#[test]
fn mining_formats_are_detected_and_named() {
    for (name, f, ext) in [
        ("gocad-ts", Format::GocadTs, "ts"),
        ("surpac-dtm", Format::SurpacDtm, "dtm"),
        ("landxml", Format::LandXml, "xml"),
    ] {
        assert_eq!(name.parse::<Format>().unwrap(), f);
        assert_eq!(name.to_uppercase().parse::<Format>().unwrap(), f);
        assert_eq!((f.name(), f.extension()), (name, ext));
        assert_eq!(
            Format::for_path(format!("site/pit.{}", ext.to_uppercase())),
            Some(f)
        );
        assert!(!f.welds_on_read());
        // The file name's format wins over the content's.
        assert_eq!(detect_format(b"solid x", Some(f)), Some(f));
    }
    assert_eq!(Format::GocadTs.to_string(), "GOCAD TSurf");
    assert_eq!(Format::SurpacDtm.to_string(), "Surpac DTM");
    assert_eq!(Format::LandXml.to_string(), "LandXML");
    // Content: with a byte-order mark, and not for look-alikes.
    assert_eq!(
        detect_format(format!("\u{feff}{LANDXML_SAMPLE}").as_bytes(), None),
        Some(Format::LandXml)
    );
    assert_eq!(detect_format(b"<svg></svg>", None), None);
    assert_eq!(detect_format(b"GOCAD PLine 1\nEND\n", None), None);
    assert_eq!(detect_format(SURPAC_STR.as_bytes(), None), None);
}

#[test]
fn utc_dates_are_civil_dates() {
    let at = |secs: u64| {
        let d = landxml::utc_from_unix(secs);
        (d.iso_date(), d.iso_time(), d.surpac_date())
    };
    let s = |a: &str, b: &str, c: &str| (a.to_string(), b.to_string(), c.to_string());
    assert_eq!(at(0), s("1970-01-01", "00:00:00", "01-Jan-70"));
    assert_eq!(at(951_782_400), s("2000-02-29", "00:00:00", "29-Feb-00"));
    assert_eq!(at(1_709_251_199), s("2024-02-29", "23:59:59", "29-Feb-24"));
    assert_eq!(at(1_735_689_600), s("2025-01-01", "00:00:00", "01-Jan-25"));
    assert_eq!(
        at(253_402_300_799),
        s("9999-12-31", "23:59:59", "31-Dec-99")
    );
}
