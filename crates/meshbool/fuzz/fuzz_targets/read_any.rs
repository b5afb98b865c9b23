//! Every reader on arbitrary bytes: never a panic or a hang; whatever reads must measure,
//! and must round-trip bit for bit through OBJ and binary PLY.
//!
//! The first byte picks the reader, so that each input exercises one reader and libFuzzer's
//! coverage feedback tells the formats apart: `0x10`…`0x19` one reader each ([`READERS`])
//! on the bytes after it; any other first byte: the command-line tool's path on the whole
//! input — the format detected from the content ([`io::detect_format`]), then read.
//!
//! Run (docs/fuzzing.md): `cd crates/meshbool/fuzz && cargo +nightly fuzz run read_any
//! corpus/read_any seeds/read_any -- -max_len=8192`
#![no_main]

use libfuzzer_sys::fuzz_target;
use meshbool::io::{self, Format};
use meshbool::Mesh;

/// What a selector byte reads.
#[derive(Clone, Copy)]
enum Reader {
    /// [`io::read_bytes`] in a format (STL's and PLY's encodings come from the content).
    Mesh(Format),
    /// [`io::read_surpac_dtm`]: the `.dtm` up to the first NUL byte, the string file after it.
    Surpac,
    /// [`io::read_points`]: text or JSON points.
    Points,
}

/// The readers picked by first bytes `0x10`, `0x11`, … in order.
const READERS: [Reader; 10] = [
    Reader::Mesh(Format::StlBinary),
    Reader::Mesh(Format::Obj),
    Reader::Mesh(Format::PlyAscii),
    Reader::Mesh(Format::Dxf),
    Reader::Mesh(Format::JsonSoup),
    Reader::Mesh(Format::Glb),
    Reader::Mesh(Format::GocadTs),
    Reader::Mesh(Format::LandXml),
    Reader::Surpac,
    Reader::Points,
];

fuzz_target!(|data: &[u8]| {
    let picked = data
        .first()
        .and_then(|&b| READERS.get(usize::from(b.wrapping_sub(0x10))));
    match (picked, data.get(1..).unwrap_or_default()) {
        (Some(Reader::Mesh(format)), body) => check(io::read_bytes(body, *format)),
        (Some(Reader::Surpac), body) => {
            let cut = body.iter().position(|&b| b == 0).unwrap_or(body.len());
            let strings = body.get(cut + 1..).unwrap_or_default();
            check(io::read_surpac_dtm(&body[..cut], strings));
        }
        (Some(Reader::Points), body) => {
            if let Ok(points) = io::read_points(body) {
                assert!(points.iter().flatten().all(|x| x.is_finite()));
            }
        }
        (None, _) => {
            if let Some(format) = io::detect_format(data, None) {
                check(io::read_bytes(data, format));
            }
        }
    }
});

/// What was read must measure, be written as OBJ and binary PLY, and read back from them
/// bit for bit.
fn check(read: meshbool::Result<Mesh>) {
    let Ok(mesh) = read else { return };
    let _ = meshbool::measure::mesh_stats(&mesh);
    for format in [Format::Obj, Format::PlyBinaryLe] {
        let mut out = Vec::new();
        io::write(&mut out, &mesh, format).expect("a mesh that was read must be writable");
        if mesh.positions().is_empty() || mesh.triangles().is_empty() {
            continue;
        }
        let back = io::read_bytes(&out, format).expect("written output must read back");
        assert_eq!(back.triangles(), mesh.triangles());
        let bits = |m: &Mesh| -> Vec<[u64; 3]> {
            m.positions().iter().map(|p| p.map(f64::to_bits)).collect()
        };
        assert_eq!(bits(&back), bits(&mesh));
    }
}
