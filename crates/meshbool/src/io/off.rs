//! Object File Format (`.off`, ASCII), as Geomview, MeshLab, CGAL and mcut write it: a
//! header keyword (`OFF`, or `COFF`, `NOFF`, `CNOFF`, `STOFF`, ... saying that colours,
//! normals or texture coordinates follow each vertex), the counts `vertices faces edges`
//! (on the header's line or the next), then one vertex per line (`x y z` and whatever the
//! keyword adds) and one face per line (`n i0 .. i(n-1)`, 0-based, an optional colour
//! after). Polygons become triangle fans; `#` starts a comment anywhere. The binary
//! variant (`OFF BINARY`) and higher dimensions (`4OFF`, `nOFF`) are refused by name.

use std::io::Write;

use super::{lines, parse_f64, tokens, Format, Out};
use crate::error::{Error, Location, Result};
use crate::Mesh;

/// Content sniffing: the first token (after comments and blank lines) is an OFF keyword.
pub(super) fn looks_like(text: &[u8]) -> bool {
    let head = &text[..text.len().min(4096)];
    meaningful(head)
        .next()
        .and_then(|(_, l)| tokens(l).next())
        .is_some_and(keyword)
}

/// Whether `t` is an OFF header keyword: `OFF` with any of the prefixes `ST`, `C`, `N`,
/// `4`, `n` (in that order), the ones this reader refuses included, so that they get
/// their own error rather than "unknown format".
fn keyword(t: &[u8]) -> bool {
    let Some(mut rest) = t.strip_suffix(b"OFF") else {
        return false;
    };
    for prefix in [&b"n"[..], b"4", b"N", b"C", b"ST"] {
        rest = rest.strip_suffix(prefix).unwrap_or(rest);
    }
    rest.is_empty()
}

/// Lines with their numbers, comments cut off, blank ones left out.
fn meaningful(bytes: &[u8]) -> impl Iterator<Item = (usize, &[u8])> {
    lines(bytes)
        .map(|(n, l)| (n, l.split(|&b| b == b'#').next().unwrap_or(l)))
        .filter(|(_, l)| tokens(l).next().is_some())
}

pub(super) fn read(bytes: &[u8]) -> Result<Mesh> {
    let fmt = Format::Off;
    let err = |line: usize, message: String| Error::parse(fmt, Location::Line(line), message);
    let mut it = meaningful(bytes);
    let (ln, header) = it.next().ok_or_else(|| err(1, "no OFF header".into()))?;
    let mut tok = tokens(header);
    let key = tok.next().unwrap_or(b"");
    if !keyword(key) {
        return Err(err(
            ln,
            format!(
                "expected the header OFF, found {:?}",
                String::from_utf8_lossy(key)
            ),
        ));
    }
    let key_text = String::from_utf8_lossy(key).into_owned();
    if key.contains(&b'4') || key.starts_with(b"n") {
        return Err(err(
            ln,
            format!("{key_text}: only three-dimensional OFF files are read"),
        ));
    }
    // Numbers each vertex line has after x y z: normals (N), colours (C, 3 or 4 numbers),
    // texture coordinates (ST).
    let key_body = &key[..key.len() - 3];
    let normals = key_body.contains(&b'N');
    let colours = key_body.contains(&b'C');
    let texture = key_body.starts_with(b"ST");
    let mut rest: Vec<&[u8]> = tok.collect();
    if rest.first() == Some(&&b"BINARY"[..]) {
        return Err(err(
            ln,
            "binary OFF is not read: write it as ASCII OFF".into(),
        ));
    }
    // The counts: on the header's line, else on the next.
    let mut count_line = ln;
    if rest.is_empty() {
        let (n, l) = it
            .next()
            .ok_or_else(|| err(ln, "the counts (vertices faces edges) are missing".into()))?;
        count_line = n;
        rest = tokens(l).collect();
    }
    let count = |k: usize, what: &str| -> Result<usize> {
        let t = rest
            .get(k)
            .ok_or_else(|| err(count_line, format!("the count of {what} is missing")))?;
        std::str::from_utf8(t)
            .ok()
            .and_then(|s| s.parse::<usize>().ok())
            .ok_or_else(|| {
                err(
                    count_line,
                    format!("bad count of {what}: {:?}", String::from_utf8_lossy(t)),
                )
            })
    };
    let (nv, nf) = (count(0, "vertices")?, count(1, "faces")?);
    if nv > u32::MAX as usize - 1 {
        return Err(err(
            count_line,
            format!("{nv} vertices: at most 2^32 − 2 are read"),
        ));
    }
    // Reserved within what the file can hold, a vertex line being at least 6 bytes and a
    // face line 8 (a count larger than the file is an error found below, not an
    // allocation).
    let mut positions = Vec::with_capacity(nv.min(bytes.len() / 6));
    let mut triangles = Vec::with_capacity(nf.min(bytes.len() / 8));
    let mut last = count_line;
    for k in 0..nv {
        let (n, l) = it.next().ok_or_else(|| {
            err(
                last,
                format!("the file ends after {k} of its {nv} vertices"),
            )
        })?;
        last = n;
        let mut tok = tokens(l);
        let mut p = [0.0; 3];
        for c in &mut p {
            let t = tok
                .next()
                .ok_or_else(|| err(n, "vertex needs three coordinates".into()))?;
            *c = parse_f64(t, fmt, n)?;
        }
        let mut extra = 0;
        for t in tok {
            parse_f64(t, fmt, n)?;
            extra += 1;
        }
        let wanted = 3 * usize::from(normals) + 2 * usize::from(texture);
        // A colour is 1 (an index), 3 or 4 numbers: taken as it comes.
        if !colours && extra != wanted {
            return Err(err(
                n,
                format!(
                    "vertex has {} numbers; {key_text} vertices have {}",
                    3 + extra,
                    3 + wanted
                ),
            ));
        }
        positions.push(p);
    }
    let mut poly: Vec<u32> = Vec::new();
    for k in 0..nf {
        let (n, l) = it
            .next()
            .ok_or_else(|| err(last, format!("the file ends after {k} of its {nf} faces")))?;
        last = n;
        let mut tok = tokens(l);
        let bad = |t: &[u8]| {
            err(
                n,
                format!("bad face entry {:?}", String::from_utf8_lossy(t)),
            )
        };
        let first = tok.next().unwrap_or(b"");
        let size: usize = std::str::from_utf8(first)
            .ok()
            .and_then(|s| s.parse().ok())
            .ok_or_else(|| bad(first))?;
        if size < 3 {
            return Err(err(
                n,
                format!("face has {size} vertices, needs at least 3"),
            ));
        }
        poly.clear();
        for _ in 0..size {
            let t = tok
                .next()
                .ok_or_else(|| err(n, format!("face of {size} vertices lists fewer")))?;
            let i: u64 = std::str::from_utf8(t)
                .ok()
                .and_then(|s| s.parse().ok())
                .ok_or_else(|| bad(t))?;
            if i >= nv as u64 {
                return Err(err(
                    n,
                    format!("face references vertex {i}; the file has {nv} (numbered from 0)"),
                ));
            }
            poly.push(i as u32);
        }
        // A colour may follow (numbers); anything else is an error.
        for t in tok {
            parse_f64(t, fmt, n)?;
        }
        super::push_fan(&poly, &mut triangles);
    }
    Ok(Mesh::new_unchecked(positions, triangles))
}

pub(super) fn write(out: &mut impl Write, mesh: &Mesh) -> Result<()> {
    let mut o = Out::new(out);
    o.bytes(b"OFF\n")
        .int(mesh.positions.len() as u64)
        .bytes(b" ")
        .int(mesh.triangles.len() as u64)
        .bytes(b" 0\n");
    super::records(&mut o, mesh.positions.len(), |o, v| {
        o.coords(&mesh.positions[v], b" ").bytes(b"\n");
    })?;
    super::records(&mut o, mesh.triangles.len(), |o, t| {
        o.bytes(b"3");
        for &i in &mesh.triangles[t] {
            o.bytes(b" ").int(u64::from(i));
        }
        o.bytes(b"\n");
    })?;
    o.finish()
}

#[cfg(test)]
mod tests {
    use super::super::{detect_format, read_bytes, write};
    use super::*;

    fn read_text(s: &str) -> Result<Mesh> {
        read_bytes(s.as_bytes(), Format::Off)
    }

    #[test]
    fn a_tetrahedron_with_comments_quads_and_colours() {
        let text = "# a comment\nOFF\n# another\n5 2 0\n0 0 0\n1 0 0\n1 1 0 # c\n0 1 0\n\n0.5 0.5 1\n4 0 1 2 3 255 0 0\n3 0 1 4\n";
        let m = read_text(text).unwrap();
        assert_eq!(m.positions.len(), 5);
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3], [0, 1, 4]]);
        assert_eq!(detect_format(text.as_bytes(), None), Some(Format::Off));
    }

    #[test]
    fn counts_on_the_header_line_and_coloured_vertices() {
        let m = read_text("COFF 3 1 0\n0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n0 1 0 0 0 1 1\n3 0 1 2\n")
            .unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2]]);
        assert_eq!(m.positions[1], [1.0, 0.0, 0.0]);
    }

    #[test]
    fn round_trips_bit_exactly() {
        let m = Mesh::new_unchecked(
            vec![
                [689195.4, 7361624.0, -1.141297e-10],
                [0.1, 0.2, 0.3],
                [1e-300, -2.5, 3.0],
            ],
            vec![[0, 1, 2]],
        );
        let mut bytes = Vec::new();
        write(&mut bytes, &m, Format::Off).unwrap();
        assert_eq!(read_bytes(&bytes, Format::Off).unwrap(), m);
    }

    #[test]
    fn malformed_files_are_errors_with_lines() {
        let cases = [
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n",
                "ends after 2 of its 3 vertices",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
                "references vertex 3",
            ),
            ("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 nan\n3 0 1 2\n", "non-finite"),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
                "needs at least 3",
            ),
            ("OFF\nx 1 0\n", "bad count of vertices"),
            (
                "COFF\n3 1 0\n0 0 0 red\n1 0 0\n0 1 0\n3 0 1 2\n",
                "expected a number",
            ),
            (
                "OFF\n3 1 0\n0 0 0 1\n1 0 0\n0 1 0\n3 0 1 2\n",
                "vertex has 4 numbers",
            ),
            ("OFF BINARY\n", "binary OFF"),
            ("4OFF\n1 0 0\n", "three-dimensional"),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 x\n",
                "expected a number",
            ),
            (
                "OFF\n3 9999999999 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                "ends after 1 of its",
            ),
        ];
        for (text, wanted) in cases {
            let e = read_text(text).unwrap_err().to_string();
            assert!(e.contains(wanted), "{text:?}: {e}");
            assert!(e.contains("line"), "{text:?}: {e}");
        }
    }
}
