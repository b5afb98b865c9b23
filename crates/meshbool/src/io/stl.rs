//! STL, binary and ASCII. Binary vs ASCII is decided by the file size first: a file of
//! exactly `84 + 50 n` bytes whose header announces `n` triangles is binary even when its
//! header starts with "solid" (many exporters write that). So is one that starts with
//! "solid" but whose first 84 bytes are not text, or whose size is within a record of its
//! count's: a binary file with a wrong count, reported as one (`encoding`).

use std::io::Write;

use super::{lines, parse_f64, tokens, Format, Out};
use crate::error::{Error, Location, Result};
use crate::{Mesh, Welder};

const HEADER: usize = 80;
const RECORD: usize = 50;

fn announced(bytes: &[u8]) -> Option<u64> {
    let n = bytes.get(HEADER..HEADER + 4)?;
    Some(u64::from(u32::from_le_bytes([n[0], n[1], n[2], n[3]])))
}

/// True when the size matches the triangle count in the binary header.
pub(super) fn is_binary(bytes: &[u8]) -> bool {
    announced(bytes).is_some_and(|n| (HEADER + 4) as u64 + RECORD as u64 * n == bytes.len() as u64)
}

/// True when a file of `len` bytes is within one record of the size of a binary STL of `n`
/// triangles: a binary file with a wrong count or a few bytes too many or too few.
pub(super) fn size_is_near(n: u64, len: u64) -> bool {
    ((HEADER + 4) as u64 + RECORD as u64 * n).abs_diff(len) < RECORD as u64
}

/// Which STL encoding `bytes` are in: ASCII when they start with "solid" and nothing says
/// binary was meant; binary otherwise, so that the binary reader reports what is wrong
/// (with the count and the size that disagree). Binary was meant when the size matches the
/// count or is within one record of it, or when the header and count hold a byte that no
/// text has (a control character other than whitespace: a count below 2^24 has a zero byte).
pub(super) fn encoding(bytes: &[u8]) -> Format {
    let text_head = bytes[..bytes.len().min(HEADER + 4)]
        .iter()
        .all(|&b| (b >= 0x20 && b != 0x7f) || b.is_ascii_whitespace() || b == 0x0b);
    let near = announced(bytes).is_some_and(|n| size_is_near(n, bytes.len() as u64));
    if text_head && !near && bytes.trim_ascii_start().starts_with(b"solid") {
        Format::StlAscii
    } else {
        Format::StlBinary
    }
}

pub(super) fn read(bytes: &[u8]) -> Result<Mesh> {
    match encoding(bytes) {
        Format::StlAscii => read_ascii(bytes),
        _ => read_binary(bytes),
    }
}

/// The little-endian `f32` at byte `at` of `bytes`.
fn f32_at(bytes: &[u8], at: usize) -> f32 {
    f32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
}

fn read_binary(bytes: &[u8]) -> Result<Mesh> {
    use rayon::prelude::*;
    let err =
        |at: usize, msg: String| Error::parse(Format::StlBinary, Location::Byte(at as u64), msg);
    let Some(n) = announced(bytes) else {
        return Err(err(
            bytes.len(),
            format!(
                "file ends after {} bytes, inside the 84-byte header",
                bytes.len()
            ),
        ));
    };
    let room = (bytes.len() - HEADER - 4) / RECORD;
    if n != room as u64 || (bytes.len() - HEADER - 4) % RECORD != 0 {
        return Err(err(
            HEADER,
            format!(
                "header announces {n} triangles ({} bytes) but the file has {} bytes \
                 (room for {room} triangles): truncated or wrong triangle count",
                (HEADER + 4) as u64 + RECORD as u64 * n,
                bytes.len()
            ),
        ));
    }
    let body = &bytes[HEADER + 4..];
    // Corners `3t + k` of triangle `t`, decoded record by record.
    let (positions, ids) = crate::welder::weld_all(room * 3, room / 2, |corners, out| {
        out.reserve(corners.len());
        for t in corners.start / 3..corners.end.div_ceil(3) {
            let rec = &body[t * RECORD..t * RECORD + RECORD];
            let f = |k: usize| f64::from(f32_at(rec, k));
            for (k, o) in [12, 24, 36].into_iter().enumerate() {
                if corners.contains(&(3 * t + k)) {
                    out.push([f(o), f(o + 4), f(o + 8)]);
                }
            }
        }
    });
    // Every welded position is some corner's: the corners are searched for the first
    // non-finite coordinate only when the (far fewer) positions hold one.
    let non_finite = positions
        .par_iter()
        .any(|p| p.iter().any(|x| !x.is_finite()));
    let first_bad = || {
        (0..room)
            .flat_map(|t| (12..48).step_by(4).map(move |o| (t, o)))
            .find(|&(t, o)| !f32_at(body, t * RECORD + o).is_finite())
    };
    if let Some((t, o)) = non_finite.then(first_bad).flatten() {
        return Err(err(
            HEADER + 4 + t * RECORD + o,
            format!("non-finite coordinate in triangle {t}"),
        ));
    }
    Ok(Mesh::new_unchecked(
        positions,
        crate::welder::triangles_of(&ids),
    ))
}

fn read_ascii(bytes: &[u8]) -> Result<Mesh> {
    let fmt = Format::StlAscii;
    let err = |line: usize, msg: String| Error::parse(fmt, Location::Line(line), msg);
    let mut welder = Welder::with_capacity(bytes.len() / 80);
    let mut triangles = Vec::new();
    let mut poly: Vec<u32> = Vec::new();
    // Where we are: outside a solid, in a solid, in a facet, in its loop.
    #[derive(PartialEq)]
    enum State {
        Top,
        Solid,
        Facet,
        Loop,
    }
    let mut state = State::Top;
    let mut opened = 0;
    for (ln, line) in lines(bytes) {
        let mut tok = tokens(line);
        let Some(key) = tok.next() else { continue };
        match (key, &state) {
            (b"solid", State::Top) => state = State::Solid,
            (b"facet", State::Solid) => {
                state = State::Facet;
                opened = ln;
            }
            (b"outer", State::Facet) => {
                state = State::Loop;
                poly.clear();
            }
            (b"vertex", State::Loop) => {
                let mut p = [0.0; 3];
                for c in &mut p {
                    let t = tok
                        .next()
                        .ok_or_else(|| err(ln, "vertex needs three coordinates".into()))?;
                    *c = parse_f64(t, fmt, ln)?;
                }
                poly.push(welder.index(p));
            }
            (b"endloop", State::Loop) => {
                if poly.len() < 3 {
                    return Err(err(
                        ln,
                        format!("facet has {} vertices, needs 3", poly.len()),
                    ));
                }
                super::push_fan(&poly, &mut triangles);
                state = State::Facet;
            }
            (b"endfacet", State::Facet) => state = State::Solid,
            (b"endsolid", State::Solid) => state = State::Top,
            _ => {
                return Err(err(
                    ln,
                    format!("unexpected {:?} here", String::from_utf8_lossy(key)),
                ))
            }
        }
    }
    match state {
        State::Top => Ok(Mesh::new_unchecked(welder.into_positions(), triangles)),
        State::Solid => Err(err(
            lines(bytes).count(),
            "missing endsolid: file truncated?".into(),
        )),
        _ => Err(err(
            opened,
            "facet not closed before end of file: truncated?".into(),
        )),
    }
}

/// The unit normal of a triangle with corners `[a, b, c]`, as binary STL stores it (zero
/// for a degenerate triangle).
fn normal32([a, b, c]: [[f64; 3]; 3]) -> [f32; 3] {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len > 0.0 && len.is_finite() {
        n.map(|x| (x / len) as f32)
    } else {
        [0.0; 3]
    }
}

/// Why triangle `t` of `mesh` cannot be stored in binary STL, if it cannot.
fn unwritable(mesh: &Mesh, t: usize) -> Option<Error> {
    let tri = mesh.triangles[t];
    let c64 = tri.map(|v| mesh.positions[v as usize]);
    let c32 = c64.map(|p| p.map(|x| x as f32));
    if let Some(k) = (0..3).find(|&k| c32[k].iter().any(|x| !x.is_finite())) {
        return Some(Error::invalid(
            Location::Vertex(tri[k] as usize),
            format!(
                "coordinates {:?} cannot be stored in binary STL's 32-bit floats (beyond \
                 their range); write another format (PLY, OBJ and glb keep them)",
                c64[k]
            ),
        ));
    }
    let collapses = (0..3).any(|k| {
        let j = (k + 1) % 3;
        c32[k] == c32[j] && c64[k] != c64[j]
    });
    collapses.then(|| {
        Error::invalid(
            Location::Triangle(t),
            "its corners differ only below the resolution of binary STL's 32-bit floats \
             (it would collapse); write another format (PLY, OBJ and glb keep them)",
        )
    })
}

/// Triangles per block of binary STL encoded at once.
const WRITE_BLOCK: usize = 1 << 13;

/// The header of a binary STL of `mesh`, once every triangle is known to be storable.
/// Never write what cannot be read back: a coordinate beyond f32's range would become
/// infinite, and a triangle whose corners differ only below f32's resolution would
/// collapse (tiny coordinates rounded to zero are kept where nothing collapses). Checked
/// on all threads before anything is written; the first such triangle is named.
fn binary_header(mesh: &Mesh) -> Result<[u8; HEADER + 4]> {
    use rayon::prelude::*;
    let n = u32::try_from(mesh.triangles.len()).map_err(|_| {
        Error::invalid(Location::Whole, "binary STL holds at most 2^32-1 triangles")
    })?;
    if let Some(e) = (0..mesh.triangles.len())
        .into_par_iter()
        .with_min_len(1 << 12)
        .find_map_first(|t| unwritable(mesh, t))
    {
        return Err(e);
    }
    let mut head = [b' '; HEADER + 4];
    let label = b"meshbool binary STL";
    head[..label.len()].copy_from_slice(label);
    head[HEADER..].copy_from_slice(&n.to_le_bytes());
    Ok(head)
}

/// The records of triangles `first..` (a block of [`WRITE_BLOCK`] at most).
fn encode_block(mesh: &Mesh, first: usize) -> Vec<u8> {
    let end = (first + WRITE_BLOCK).min(mesh.triangles.len());
    let mut buf = vec![0u8; (end - first) * RECORD];
    for (t, rec) in (first..end).zip(buf.chunks_exact_mut(RECORD)) {
        let corners = mesh.corners(t);
        let normal = normal32(corners);
        let values = normal
            .into_iter()
            .chain(corners.into_iter().flatten().map(|x| x as f32));
        // Twelve floats, then the two attribute bytes left zero.
        for (at, x) in rec.chunks_exact_mut(4).zip(values) {
            at.copy_from_slice(&x.to_le_bytes());
        }
    }
    buf
}

pub(super) fn write_binary(out: &mut impl Write, mesh: &Mesh) -> Result<()> {
    use rayon::prelude::*;
    out.write_all(&binary_header(mesh)?)?;
    // Records are independent: blocks are encoded side by side, a batch of them at a
    // time (memory stays bounded), and written in order.
    let batch = WRITE_BLOCK * 4 * rayon::current_num_threads().max(1);
    for start in (0..mesh.triangles.len()).step_by(batch) {
        let end = (start + batch).min(mesh.triangles.len());
        let blocks: Vec<Vec<u8>> = (start..end)
            .step_by(WRITE_BLOCK)
            .collect::<Vec<_>>()
            .into_par_iter()
            .map(|first| encode_block(mesh, first))
            .collect();
        for b in blocks {
            out.write_all(&b)?;
        }
    }
    Ok(())
}

/// [`write_binary`] into a file, each block written at its offset by the thread that
/// encoded it (the copies into the page cache run side by side), its write-back to disk
/// started at once ([`super::start_writeback`]).
#[cfg(unix)]
pub(super) fn write_binary_at(file: &std::fs::File, mesh: &Mesh) -> Result<()> {
    use rayon::prelude::*;
    use std::os::unix::fs::FileExt;
    file.write_all_at(&binary_header(mesh)?, 0)?;
    (0..mesh.triangles.len().div_ceil(WRITE_BLOCK))
        .into_par_iter()
        .try_for_each(|b| {
            let at = (HEADER + 4 + b * WRITE_BLOCK * RECORD) as u64;
            let block = encode_block(mesh, b * WRITE_BLOCK);
            file.write_all_at(&block, at)?;
            super::start_writeback(file, at, block.len());
            Ok::<(), std::io::Error>(())
        })?;
    Ok(())
}

pub(super) fn write_ascii(out: &mut impl Write, mesh: &Mesh) -> Result<()> {
    let mut o = Out::new(out);
    o.bytes(b"solid meshbool\n");
    for t in 0..mesh.triangles.len() {
        o.bytes(b"facet normal");
        for x in normal32(mesh.corners(t)) {
            o.bytes(b" ").f64(f64::from(x));
        }
        o.bytes(b"\n outer loop\n");
        for p in mesh.corners(t) {
            o.bytes(b"  vertex");
            for x in p {
                o.bytes(b" ").f64(x);
            }
            o.bytes(b"\n");
        }
        o.bytes(b" endloop\nendfacet\n").record_done()?;
    }
    o.bytes(b"endsolid meshbool\n");
    o.finish()
}
