//! Every reader on arbitrary bytes: no panic, no hang; whatever reads must measure, and must
//! round-trip exactly through OBJ and binary PLY.
//!
//! Run: `cd crates/meshbool && cargo +nightly fuzz run read_any -- -max_len=8192`
#![no_main]

use libfuzzer_sys::fuzz_target;
use meshbool::io::{self, Format};

fuzz_target!(|data: &[u8]| {
    let _ = io::detect_format(data, None);
    for (_, f) in Format::NAMES {
        let Ok(mesh) = io::read_bytes(data, f) else { continue };
        let _ = meshbool::measure::mesh_stats(&mesh);
        for g in [Format::Obj, Format::PlyBinaryLe] {
            let mut out = Vec::new();
            io::write(&mut out, &mesh, g).expect("a mesh that was read must be writable");
            if mesh.positions().is_empty() || mesh.triangles().is_empty() {
                continue;
            }
            let back = io::read_bytes(&out, g).expect("written output must read back");
            assert_eq!(back.triangles(), mesh.triangles());
            let bits = |m: &meshbool::Mesh| -> Vec<[u64; 3]> {
                m.positions().iter().map(|p| p.map(f64::to_bits)).collect()
            };
            assert_eq!(bits(&back), bits(&mesh));
        }
    }
});
