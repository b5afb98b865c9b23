//! STL, binary and ASCII. Binary vs ASCII is decided by the file size first: a file of
//! exactly `84 + 50 n` bytes whose header announces `n` triangles is binary even when its
//! header starts with "solid" (many exporters write that). So is one that starts with
//! "solid" but whose first 84 bytes are not text, or whose size is within a record of its
//! count's: a binary file with a wrong count, reported as one (`encoding`).

use std::io::Write;

use super::{lines, parse_f64, tokens, Format, Out};
use crate::error::{Error, Location, Result};
use crate::welder::Hashed;
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

fn read_binary(bytes: &[u8]) -> Result<Mesh> {
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
    // Decode and hash block b+1 on one core while the other welds block b.
    const BLOCK: usize = 4096;
    let blocks: Vec<&[u8]> = body.chunks(RECORD * BLOCK).collect();
    let decode = |b: usize, out: &mut Hashed| -> Result<()> {
        out.positions.clear();
        for (r, rec) in blocks[b].chunks_exact(RECORD).enumerate() {
            let f = |k: usize| f32::from_le_bytes([rec[k], rec[k + 1], rec[k + 2], rec[k + 3]]);
            for o in [12, 24, 36] {
                let p = [f(o), f(o + 4), f(o + 8)];
                if let Some(k) = p.iter().position(|x| !x.is_finite()) {
                    let t = b * BLOCK + r;
                    return Err(err(
                        HEADER + 4 + t * RECORD + o + 4 * k,
                        format!("non-finite coordinate in triangle {t}"),
                    ));
                }
                out.positions.push(p.map(f64::from));
            }
        }
        out.hash();
        Ok(())
    };
    let mut welder = Welder::with_capacity(room * 3);
    let mut ids: Vec<u32> = Vec::with_capacity(room * 3);
    let (mut cur, mut next) = (Hashed::default(), Hashed::default());
    if !blocks.is_empty() {
        decode(0, &mut cur)?;
    }
    for b in 0..blocks.len() {
        let (decoded, ()) = rayon::join(
            || match b + 1 < blocks.len() {
                true => decode(b + 1, &mut next),
                false => Ok(()),
            },
            || welder.index_hashed(&cur, &mut ids),
        );
        decoded?;
        std::mem::swap(&mut cur, &mut next);
    }
    let triangles = ids.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    Ok(Mesh::new_unchecked(welder.into_positions(), triangles))
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

fn normal32(m: &Mesh, t: usize) -> [f32; 3] {
    let [a, b, c] = m.corners(t);
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

pub(super) fn write_binary(out: &mut impl Write, mesh: &Mesh) -> Result<()> {
    use rayon::prelude::*;
    let n = u32::try_from(mesh.triangles.len()).map_err(|_| {
        Error::invalid(Location::Whole, "binary STL holds at most 2^32-1 triangles")
    })?;
    // Never write what cannot be read back: a coordinate beyond f32's range would become
    // infinite, and a triangle whose corners differ only below f32's resolution would
    // collapse (tiny coordinates rounded to zero are kept where nothing collapses).
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let c64 = tri.map(|v| mesh.positions[v as usize]);
        let c32 = c64.map(|p| p.map(|x| x as f32));
        if let Some(k) = (0..3).find(|&k| c32[k].iter().any(|x| !x.is_finite())) {
            return Err(Error::invalid(
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
        if collapses {
            return Err(Error::invalid(
                Location::Triangle(t),
                "its corners differ only below the resolution of binary STL's 32-bit floats \
                 (it would collapse); write another format (PLY, OBJ and glb keep them)",
            ));
        }
    }
    let mut head = [b' '; HEADER + 4];
    let label = b"meshbool binary STL";
    head[..label.len()].copy_from_slice(label);
    head[HEADER..].copy_from_slice(&n.to_le_bytes());
    out.write_all(&head)?;
    // Records are independent: blocks are encoded side by side, a batch of them at a
    // time (memory stays bounded), and written in order.
    const BLOCK: usize = 1 << 13;
    let encode = |first: usize| -> Vec<u8> {
        let end = (first + BLOCK).min(mesh.triangles.len());
        let mut buf = Vec::with_capacity((end - first) * RECORD);
        for t in first..end {
            for x in normal32(mesh, t) {
                buf.extend_from_slice(&x.to_le_bytes());
            }
            for x in mesh.corners(t).into_iter().flatten() {
                buf.extend_from_slice(&(x as f32).to_le_bytes());
            }
            buf.extend_from_slice(&[0, 0]);
        }
        buf
    };
    let batch = BLOCK * 4 * rayon::current_num_threads().max(1);
    for start in (0..mesh.triangles.len()).step_by(batch) {
        let end = (start + batch).min(mesh.triangles.len());
        let blocks: Vec<Vec<u8>> = (start..end)
            .step_by(BLOCK)
            .collect::<Vec<_>>()
            .into_par_iter()
            .map(encode)
            .collect();
        for b in blocks {
            out.write_all(&b)?;
        }
    }
    Ok(())
}

pub(super) fn write_ascii(out: &mut impl Write, mesh: &Mesh) -> Result<()> {
    let mut o = Out::new(out);
    o.bytes(b"solid meshbool\n");
    for t in 0..mesh.triangles.len() {
        o.bytes(b"facet normal");
        for x in normal32(mesh, t) {
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
