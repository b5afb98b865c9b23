//! Wavefront OBJ: `v x y z [w | r g b]` (numbers, then at most a `#` comment) and `f` with
//! `i`, `i/t`, `i//n`, `i/t/n` references, 1-based or negative (relative) indices. Polygons
//! become triangle fans. Texture coordinates, normals, groups, materials, lines and any
//! other statements are skipped.

use std::io::Write;

use rayon::prelude::*;

use super::{lines, parse_f64, tokens, whole_lines, Format, Out};
use crate::error::{Error, Location, Result};
use crate::par::{concat, exclusive_sums};
use crate::Mesh;

/// Content sniffing: some line starts with `v ` and some with `f `.
pub(super) fn looks_like(bytes: &[u8]) -> bool {
    let head = &bytes[..bytes.len().min(1 << 16)];
    let starts = |p: &[u8]| lines(head).any(|(_, l)| l.trim_ascii_start().starts_with(p));
    // A large file's faces may come after the first 64 KiB of vertices: then every whole
    // line of the head must be one an OBJ file has.
    let obj_lines = || {
        let whole = match head.iter().rposition(|&b| b == b'\n') {
            Some(i) => &head[..i],
            None => head,
        };
        lines(whole).all(|(_, l)| {
            let keyword = tokens(l).next().unwrap_or(b"");
            keyword.is_empty()
                || keyword.starts_with(b"#")
                || [
                    &b"v"[..],
                    b"vn",
                    b"vt",
                    b"vp",
                    b"f",
                    b"l",
                    b"o",
                    b"g",
                    b"s",
                    b"usemtl",
                    b"mtllib",
                ]
                .contains(&keyword)
        })
    };
    starts(b"v ") && (starts(b"f ") || head.len() == bytes.len() || obj_lines())
}

pub(super) fn read(bytes: &[u8]) -> Result<Mesh> {
    read_in(bytes, super::pieces(bytes.len()))
}

/// [`read`] in about `pieces` pieces of whole lines, parsed side by side: vertices and
/// faces in file order, the same mesh and the same first error as one pass. A negative
/// (relative) reference needs the count of vertices before it: a piece that meets one is
/// parsed again once the pieces before it are counted.
pub(super) fn read_in(bytes: &[u8], pieces: usize) -> Result<Mesh> {
    let fmt = Format::Obj;
    let chunks = whole_lines(bytes, pieces.max(1));
    let mut parsed: Vec<std::result::Result<Piece, Stop>> = chunks
        .par_iter()
        .enumerate()
        .map(|(k, c)| Piece::parse(c, (k == 0).then_some(0)))
        .collect();
    if parsed.iter().any(|p| matches!(p, Err(Stop::Relative))) {
        let counts: Vec<usize> = chunks
            .par_iter()
            .zip(&parsed)
            .map(|(c, p)| match p {
                Ok(p) => p.positions.len(),
                Err(_) => vertex_lines(c),
            })
            .collect();
        let offsets = exclusive_sums(&counts);
        parsed
            .par_iter_mut()
            .zip(chunks.par_iter().zip(&offsets))
            .filter(|(p, _)| matches!(p, Err(Stop::Relative)))
            .for_each(|(p, (c, &o))| *p = Piece::parse(c, Some(o as u64)));
    }
    let mut ok = Vec::with_capacity(parsed.len());
    for (k, p) in parsed.into_iter().enumerate() {
        match p {
            Ok(p) => ok.push(p),
            Err(Stop::Error(line, message)) => {
                let line = line + lines_before(bytes, &chunks, k);
                return Err(Error::parse(fmt, Location::Line(line), message));
            }
            Err(Stop::Relative) => unreachable!("pieces with relative references are parsed again"),
        }
    }
    let n = ok.iter().map(|p| p.positions.len()).sum::<usize>() as u64;
    let beyond = ok.par_iter().map(|p| {
        p.triangles
            .iter()
            .position(|tri: &[u32; 3]| tri.iter().any(|&i| u64::from(i) >= n))
    });
    if let Some((k, t)) = beyond
        .collect::<Vec<_>>()
        .into_iter()
        .enumerate()
        .find_map(|(k, t)| Some((k, t?)))
    {
        let line = face_line(chunks[k], t) + lines_before(bytes, &chunks, k);
        return Err(Error::parse(
            fmt,
            Location::Line(line),
            format!("face references a vertex beyond the {n} defined"),
        ));
    }
    let (positions, triangles): (Vec<_>, Vec<_>) =
        ok.into_iter().map(|p| (p.positions, p.triangles)).unzip();
    let (positions, triangles) = rayon::join(|| concat(positions), || concat(triangles));
    Ok(Mesh::new_unchecked(positions, triangles))
}

/// The lines before piece `k` of `chunks` (cut from `bytes` by [`whole_lines`]).
fn lines_before(bytes: &[u8], chunks: &[&[u8]], k: usize) -> usize {
    let start: usize = chunks[..k].iter().map(|c| c.len()).sum();
    bytes[..start].iter().filter(|&&b| b == b'\n').count()
}

/// The lines that are vertices (`v` statements) in a piece, as [`Piece::parse`] reads them.
fn vertex_lines(chunk: &[u8]) -> usize {
    lines(chunk)
        .filter(|(_, l)| tokens(l).next() == Some(b"v"))
        .count()
}

/// The line (in `chunk`) of its face that made triangle `t` (counted in `chunk`).
fn face_line(chunk: &[u8], t: usize) -> usize {
    let mut made = 0;
    for (ln, line) in lines(chunk) {
        let mut tok = tokens(line);
        if tok.next() == Some(b"f") {
            made += tok.count().saturating_sub(2);
            if made > t {
                return ln;
            }
        }
    }
    0
}

/// What a piece of an OBJ file holds.
struct Piece {
    positions: Vec<[f64; 3]>,
    /// Faces as fans of triangles, with absolute 0-based references (range checked at
    /// the end: some writers reference vertices defined later in the file).
    triangles: Vec<[u32; 3]>,
}

/// Why a piece was not read.
enum Stop {
    /// A parse error: the line (in the piece) and the message.
    Error(usize, String),
    /// A relative reference, before the count of vertices ahead of the piece is known.
    Relative,
}

impl Piece {
    /// Parses `chunk` (whole lines) with `before` vertices ahead of it, where known.
    fn parse(chunk: &[u8], before: Option<u64>) -> std::result::Result<Piece, Stop> {
        let mut positions: Vec<[f64; 3]> = Vec::new();
        let mut triangles = Vec::new();
        let mut poly: Vec<u32> = Vec::new();
        let number = |t: &[u8], ln: usize| {
            parse_f64(t, Format::Obj, ln).map_err(|e| match e {
                Error::Parse { message, .. } => Stop::Error(ln, message),
                e => Stop::Error(ln, e.to_string()),
            })
        };
        for (ln, line) in lines(chunk) {
            let mut tok = tokens(line);
            match tok.next() {
                Some(b"v") => {
                    let mut p = [0.0; 3];
                    for c in &mut p {
                        let t = tok.next().ok_or_else(|| {
                            Stop::Error(ln, "vertex needs three coordinates".into())
                        })?;
                        *c = number(t, ln)?;
                    }
                    // A weight `w` or a colour `r g b` may follow (numbers too), then a
                    // comment.
                    let mut extra = 0;
                    for t in tok.by_ref().take_while(|t| !t.starts_with(b"#")) {
                        number(t, ln)?;
                        extra += 1;
                    }
                    if !matches!(extra, 0 | 1 | 3) {
                        return Err(Stop::Error(
                            ln,
                            format!(
                                "vertex has {} numbers: expected x y z, x y z w (a weight) or \
                                 x y z r g b (a colour)",
                                3 + extra
                            ),
                        ));
                    }
                    positions.push(p);
                }
                Some(b"f") => {
                    poly.clear();
                    for t in tok {
                        let idx = t.split(|&b| b == b'/').next().unwrap_or(t);
                        let bad = || {
                            Stop::Error(
                                ln,
                                format!("bad vertex reference {:?}", String::from_utf8_lossy(t)),
                            )
                        };
                        let i: i64 = std::str::from_utf8(idx)
                            .ok()
                            .and_then(|s| s.parse().ok())
                            .ok_or_else(bad)?;
                        let so_far = || before.map(|b| b as i64 + positions.len() as i64);
                        let abs = match i {
                            0 => return Err(bad()),
                            i if i > 0 => i - 1,
                            i => so_far().ok_or(Stop::Relative)? + i,
                        };
                        if abs < 0 || abs > i64::from(u32::MAX - 1) {
                            return Err(Stop::Error(
                                ln,
                                format!(
                                    "vertex reference {i} is out of range ({} vertices so far)",
                                    so_far().ok_or(Stop::Relative)?
                                ),
                            ));
                        }
                        poly.push(abs as u32);
                    }
                    if poly.len() < 3 {
                        return Err(Stop::Error(
                            ln,
                            format!("face has {} vertices, needs at least 3", poly.len()),
                        ));
                    }
                    super::push_fan(&poly, &mut triangles);
                }
                _ => {}
            }
        }
        Ok(Piece {
            positions,
            triangles,
        })
    }
}

pub(super) fn write(out: &mut impl Write, mesh: &Mesh) -> Result<()> {
    let mut o = Out::new(out);
    o.bytes(b"# meshbool\n");
    super::records(&mut o, mesh.positions.len(), |o, v| {
        o.obj_vertex(&mesh.positions[v]);
    })?;
    super::records(&mut o, mesh.triangles.len(), |o, t| {
        o.bytes(b"f");
        for &i in &mesh.triangles[t] {
            o.bytes(b" ").int(u64::from(i) + 1);
        }
        o.bytes(b"\n");
    })?;
    o.finish()
}
