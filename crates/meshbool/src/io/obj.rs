//! Wavefront OBJ: `v x y z [w | r g b]` (numbers, then at most a `#` comment) and `f` with
//! `i`, `i/t`, `i//n`, `i/t/n` references, 1-based or negative (relative) indices. Polygons
//! become triangle fans. Texture coordinates, normals, groups, materials, lines and any
//! other statements are skipped.

use std::io::Write;

use super::{lines, parse_f64, tokens, Format, Out};
use crate::error::{Error, Location, Result};
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
    let fmt = Format::Obj;
    let mut positions: Vec<[f64; 3]> = Vec::new();
    let mut triangles = Vec::new();
    // Face corners as (absolute 0-based index, line) for the range check at the end, because
    // some writers reference vertices defined later in the file.
    let mut lines_of_tris: Vec<usize> = Vec::new();
    let mut poly: Vec<u32> = Vec::new();
    for (ln, line) in lines(bytes) {
        let mut tok = tokens(line);
        match tok.next() {
            Some(b"v") => {
                let mut p = [0.0; 3];
                for c in &mut p {
                    let t = tok.next().ok_or_else(|| {
                        Error::parse(fmt, Location::Line(ln), "vertex needs three coordinates")
                    })?;
                    *c = parse_f64(t, fmt, ln)?;
                }
                // A weight `w` or a colour `r g b` may follow (numbers too), then a comment.
                let mut extra = 0;
                for t in tok.by_ref().take_while(|t| !t.starts_with(b"#")) {
                    parse_f64(t, fmt, ln)?;
                    extra += 1;
                }
                if !matches!(extra, 0 | 1 | 3) {
                    return Err(Error::parse(
                        fmt,
                        Location::Line(ln),
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
                        Error::parse(
                            fmt,
                            Location::Line(ln),
                            format!("bad vertex reference {:?}", String::from_utf8_lossy(t)),
                        )
                    };
                    let i: i64 = std::str::from_utf8(idx)
                        .ok()
                        .and_then(|s| s.parse().ok())
                        .ok_or_else(bad)?;
                    let abs = match i {
                        0 => return Err(bad()),
                        i if i > 0 => i - 1,
                        i => positions.len() as i64 + i,
                    };
                    if abs < 0 || abs > i64::from(u32::MAX - 1) {
                        return Err(Error::parse(
                            fmt,
                            Location::Line(ln),
                            format!(
                                "vertex reference {i} is out of range ({} vertices so far)",
                                positions.len()
                            ),
                        ));
                    }
                    poly.push(abs as u32);
                }
                if poly.len() < 3 {
                    return Err(Error::parse(
                        fmt,
                        Location::Line(ln),
                        format!("face has {} vertices, needs at least 3", poly.len()),
                    ));
                }
                let before = triangles.len();
                super::push_fan(&poly, &mut triangles);
                lines_of_tris.resize(lines_of_tris.len() + triangles.len() - before, ln);
            }
            _ => {}
        }
    }
    let n = positions.len() as u64;
    if let Some(t) = triangles
        .iter()
        .position(|tri: &[u32; 3]| tri.iter().any(|&i| u64::from(i) >= n))
    {
        return Err(Error::parse(
            fmt,
            Location::Line(lines_of_tris[t]),
            format!("face references a vertex beyond the {n} defined"),
        ));
    }
    Ok(Mesh::new_unchecked(positions, triangles))
}

pub(super) fn write(out: &mut impl Write, mesh: &Mesh) -> Result<()> {
    let mut o = Out::new(out);
    o.bytes(b"# meshbool\n");
    for p in &mesh.positions {
        o.obj_vertex(p);
        o.record_done()?;
    }
    for t in &mesh.triangles {
        o.bytes(b"f");
        for &i in t {
            o.bytes(b" ").int(u64::from(i) + 1);
        }
        o.bytes(b"\n").record_done()?;
    }
    o.finish()
}
