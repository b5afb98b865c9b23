//! Reading speed: a 2M-triangle binary STL (UV sphere, 100 MB) against a plain memory copy
//! of the same bytes; reading and writing a 500k-triangle sphere as OBJ and PLY (binary and
//! ASCII), in memory. Run: `cargo bench -p meshbool --bench io`.

use std::sync::LazyLock;

use meshbool::io::{self, Format};
use meshbool::shapes::uv_sphere;

/// 2 · 2000 · 500 = 2,000,000 triangles.
static STL: LazyLock<Vec<u8>> = LazyLock::new(|| {
    let mut out = Vec::new();
    io::write(
        &mut out,
        &uv_sphere([0.0; 3], 1.0, 2000, 501),
        Format::StlBinary,
    )
    .unwrap();
    out
});

fn main() {
    LazyLock::force(&STL);
    divan::main();
}

/// The baseline: copy the file's bytes into a new buffer.
#[divan::bench(sample_count = 20)]
fn memcpy_2m_stl_bytes() -> Vec<u8> {
    divan::black_box(&*STL).to_vec()
}

/// Parse and weld into an indexed `Mesh` (what `io::read_path` does after reading the file).
#[divan::bench(sample_count = 20)]
fn read_2m_binary_stl() -> meshbool::Mesh {
    io::read_bytes(divan::black_box(&STL), Format::StlBinary).unwrap()
}

/// The same file with its triangles in a scrambled order: no locality between a vertex's
/// uses, the worst case for welding.
static SHUFFLED: LazyLock<Vec<u8>> = LazyLock::new(|| {
    let (positions, triangles) = uv_sphere([0.0; 3], 1.0, 2000, 501).into_parts();
    let n = triangles.len();
    // A fixed permutation: multiplication by an odd constant modulo a power of two, folded.
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by_key(|&i| (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 11);
    let scrambled = order.iter().map(|&i| triangles[i]).collect();
    let m = meshbool::Mesh::new(positions, scrambled).unwrap();
    let mut out = Vec::new();
    io::write(&mut out, &m, Format::StlBinary).unwrap();
    out
});

/// Parse and weld the scrambled file.
#[divan::bench(sample_count = 10)]
fn read_2m_binary_stl_scrambled() -> meshbool::Mesh {
    io::read_bytes(divan::black_box(&SHUFFLED), Format::StlBinary).unwrap()
}

/// 2 · 500 · 500 = 499,000 triangles.
static SPHERE_500K: LazyLock<meshbool::Mesh> = LazyLock::new(|| uv_sphere([0.0; 3], 1.0, 500, 500));

/// The 500k sphere written in `format`.
fn written(format: Format) -> Vec<u8> {
    let mut out = Vec::new();
    io::write(&mut out, &SPHERE_500K, format).unwrap();
    out
}

static OBJ: LazyLock<Vec<u8>> = LazyLock::new(|| written(Format::Obj));
static PLY: LazyLock<Vec<u8>> = LazyLock::new(|| written(Format::PlyBinaryLe));
static PLY_ASCII: LazyLock<Vec<u8>> = LazyLock::new(|| written(Format::PlyAscii));

#[divan::bench(sample_count = 20)]
fn read_500k_obj() -> meshbool::Mesh {
    io::read_bytes(divan::black_box(&OBJ), Format::Obj).unwrap()
}

#[divan::bench(sample_count = 20)]
fn read_500k_ply() -> meshbool::Mesh {
    io::read_bytes(divan::black_box(&PLY), Format::PlyBinaryLe).unwrap()
}

#[divan::bench(sample_count = 20)]
fn read_500k_ply_ascii() -> meshbool::Mesh {
    io::read_bytes(divan::black_box(&PLY_ASCII), Format::PlyAscii).unwrap()
}

/// Writing into memory (the buffer reserved before the timing).
fn write_500k(bencher: divan::Bencher, format: Format) {
    let m = &*SPHERE_500K;
    bencher
        .with_inputs(|| Vec::with_capacity(64 << 20))
        .bench_values(|mut out: Vec<u8>| {
            io::write(&mut out, m, format).unwrap();
            out
        });
}

#[divan::bench(sample_count = 20)]
fn write_500k_obj(bencher: divan::Bencher) {
    write_500k(bencher, Format::Obj);
}

#[divan::bench(sample_count = 20)]
fn write_500k_ply(bencher: divan::Bencher) {
    write_500k(bencher, Format::PlyBinaryLe);
}

#[divan::bench(sample_count = 20)]
fn write_500k_ply_ascii(bencher: divan::Bencher) {
    write_500k(bencher, Format::PlyAscii);
}
