//! Surpac DTM: a text `.dtm` file of triangles whose corners are points of the string file
//! (`.str`) of the same name beside it.
//!
//! What this relies on (public descriptions of the text layout, chiefly Kirra's
//! documentation of its Surpac DTM/STR import and export, and Datamine's and Maptek's import
//! notes on Surpac strings; no Surpac specification is public):
//!
//! - The string file: a header line (`name, date, purpose, memo`), an axis line (string
//!   number 0 and six numbers), then records `string number, y, x, z[, description...]`:
//!   **northing (`y`) first, then easting (`x`), then elevation (`z`)**. A record with
//!   string number 0 ends a segment; `0, 0.000, 0.000, 0.000, END` ends the file.
//! - The DTM file: header lines (the string file's name, an axis-like line), then
//!   `OBJECT, n,` and `TRISOLATION, n, neighbours=..,validated=..,closed=..` lines, each
//!   followed by triangle records `triangle number, p1, p2, p3, n1, n2, n3, ...` whose
//!   `p` are 1-based numbers of the points of the string file, counted in file order
//!   without the segment and end records, and whose `n` are neighbouring triangles (0: none;
//!   ignored here). A record numbered 0 separates objects; `END` ends the file. Every
//!   object and trisolation is read into the one mesh.
//!
//! Both files must be complete: a missing `END`, a record with too few fields, a point
//! number beyond the string file's points and non-finite numbers are errors naming the file
//! and line. Binary DTM and string files (Surpac's other encoding) are not read.
//!
//! Written as one string (number 1) holding every vertex in order, so that point `k` is
//! vertex `k - 1` whether or not a reader counts segment records, and one object with one
//! trisolation: `neighbours=no` (the neighbour fields are 0), `validated=false` (Surpac's
//! own validation has not been run on it), and `closed=yes` when every edge has exactly two
//! triangles. Numbers are written in the shortest form that reads back to the same `f64`
//! (Surpac itself writes three decimals), and the header's date is today's (UTC).

use std::io::Write;

use super::{lines, parse_f64, Format, Out};
use crate::error::{Error, Location, Result};
use crate::Mesh;

const FMT: Format = Format::SurpacDtm;

/// The comma-separated fields of a line, trimmed.
fn fields(line: &[u8]) -> impl Iterator<Item = &[u8]> {
    line.split(|&b| b == b',').map(|f| f.trim_ascii())
}

fn lossy(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

fn integer(field: &[u8]) -> Option<i64> {
    std::str::from_utf8(field).ok()?.parse().ok()
}

/// Content sniffing: one of the first lines is an `OBJECT` or `TRISOLATION` record.
pub(super) fn looks_like(bytes: &[u8]) -> bool {
    let head = &bytes[..bytes.len().min(4096)];
    lines(head).take(16).any(|(_, l)| {
        let first = fields(l).next().unwrap_or(b"");
        first == b"OBJECT" || first.starts_with(b"TRISOLATION")
    })
}

/// The message for reading a DTM without its string file.
pub(super) const NEEDS_STRINGS: &str = "a Surpac DTM holds triangles only; its points are in the \
     string file (.str) of the same name: read it by path (io::read_file, which finds the .str \
     beside the .dtm) or with io::read_surpac_dtm";

/// The triangles of a DTM file as 1-based point numbers, each with its line.
fn triangles(dtm: &[u8]) -> Result<Vec<([u64; 3], usize)>> {
    let err = |ln, msg: String| Error::parse(FMT, Location::Line(ln), msg);
    let mut out = Vec::new();
    let mut started = false;
    let mut last_line = 0;
    for (ln, line) in lines(dtm) {
        last_line = ln;
        let mut f = fields(line);
        let first = f.next().unwrap_or(b"");
        if first.is_empty() {
            continue;
        }
        if first == b"OBJECT" || first.starts_with(b"TRISOLATION") {
            started = true;
            continue;
        }
        if !started {
            continue; // the header
        }
        if first == b"END" {
            return Ok(out);
        }
        if first[0].is_ascii_alphabetic() {
            continue; // a keyword line of some other section
        }
        let Some(number) = integer(first) else {
            return Err(err(
                ln,
                format!(
                    "expected a triangle record `number, p1, p2, p3, ...`, found {:?}",
                    lossy(line)
                ),
            ));
        };
        if number == 0 {
            continue; // between objects
        }
        let mut t = [0u64; 3];
        for c in &mut t {
            let p = f.next().unwrap_or(b"");
            *c = std::str::from_utf8(p)
                .ok()
                .and_then(|s| s.parse().ok())
                .filter(|&k| k > 0)
                .ok_or_else(|| {
                    err(
                        ln,
                        format!(
                            "triangle {number} needs three point numbers (1, 2, ...), found {:?}",
                            lossy(line)
                        ),
                    )
                })?;
        }
        out.push((t, ln));
    }
    Err(if started {
        err(last_line, "missing the END line: truncated?".into())
    } else {
        Error::parse(
            FMT,
            Location::Whole,
            "no OBJECT or TRISOLATION line: not a Surpac DTM",
        )
    })
}

/// The points of a string file, in order, as `[x, y, z]`.
fn points(strings: &[u8]) -> Result<Vec<[f64; 3]>> {
    let err =
        |ln, msg: String| Error::parse(FMT, Location::Line(ln), format!("string file: {msg}"));
    let mut out = Vec::new();
    let mut last_line = 0;
    for (ln, line) in lines(strings) {
        last_line = ln;
        if ln == 1 {
            continue; // name, date, purpose, memo
        }
        let mut f = fields(line);
        let first = f.next().unwrap_or(b"");
        if first.is_empty() && ln > 2 {
            continue;
        }
        let Some(number) = integer(first) else {
            return Err(err(
                ln,
                format!(
                    "expected a record `string number, y, x, z, ...`, found {:?}",
                    lossy(line)
                ),
            ));
        };
        if ln == 2 {
            if number != 0 {
                return Err(err(
                    ln,
                    "the second line must be the axis record `0, ...`".into(),
                ));
            }
            continue;
        }
        if number == 0 {
            if f.any(|x| x == b"END") {
                return Ok(out);
            }
            continue; // the end of a segment
        }
        let mut yxz = [0.0; 3];
        for (c, axis) in yxz.iter_mut().zip(["y", "x", "z"]) {
            let t = f.next().filter(|t| !t.is_empty()).ok_or_else(|| {
                err(
                    ln,
                    format!("a point record needs y, x and z; {axis} is missing"),
                )
            })?;
            *c = parse_f64(t, FMT, ln).map_err(|e| match e {
                Error::Parse { message, .. } => err(ln, message),
                e => e,
            })?;
        }
        out.push([yxz[1], yxz[0], yxz[2]]);
    }
    Err(err(
        last_line,
        "missing the END record `0, 0.000, 0.000, 0.000, END`: truncated?".into(),
    ))
}

/// The mesh of a DTM's triangles on its string file's points.
fn join(tris: Vec<([u64; 3], usize)>, positions: Vec<[f64; 3]>) -> Result<Mesh> {
    let n = positions.len() as u64;
    let mut triangles = Vec::with_capacity(tris.len());
    for (t, ln) in tris {
        if let Some(&k) = t.iter().find(|&&k| k > n) {
            return Err(Error::parse(
                FMT,
                Location::Line(ln),
                format!("triangle refers to point {k}; the string file has {n} points"),
            ));
        }
        triangles.push(t.map(|k| (k - 1) as u32));
    }
    let mesh = Mesh::new_unchecked(positions, triangles);
    mesh.validate()?;
    Ok(mesh)
}

/// Reads a Surpac DTM from the bytes of its `.dtm` file and of its string file (`.str`):
/// the triangles of every object and trisolation, on the string file's points (read as
/// `y, x, z`: northing first). Errors name the line, and for the string file say so.
pub fn read_surpac_dtm(dtm: &[u8], strings: &[u8]) -> Result<Mesh> {
    if dtm.trim_ascii().is_empty() {
        return Err(Error::parse(FMT, Location::Whole, "the DTM file is empty"));
    }
    let tris = triangles(dtm)?;
    join(tris, points(strings)?)
}

/// Reads the DTM at `path` with the string file beside it (the same name, extension `str`
/// or `STR`).
pub(super) fn read_path(path: &std::path::Path, dtm: &[u8]) -> Result<Mesh> {
    let tris = triangles(dtm)?;
    let lower = path.with_extension("str");
    let upper = path.with_extension("STR");
    let strings_path = if !lower.exists() && upper.exists() {
        upper
    } else {
        lower
    };
    let strings = std::fs::read(&strings_path)
        .map_err(|e| Error::from(e).in_file("reading the DTM's string file", &strings_path))?;
    join(tris, points(&strings)?)
}

/// `name` with what would break a comma-separated header line replaced.
fn header_name(name: &str) -> String {
    name.chars()
        .map(|c| if c == ',' || c.is_control() { '_' } else { c })
        .collect()
}

/// Writes `mesh` as a Surpac DTM: the triangles to `dtm`, the points to `strings` (the
/// string file, to be saved as `<name>.str` beside `<name>.dtm`; the DTM's header names it).
/// Positions are written `y, x, z` (northing first) in the shortest form that reads back
/// to the same `f64`. Non-finite coordinates are an error ([`Mesh::validate`]).
pub fn write_surpac_dtm(
    dtm: &mut impl Write,
    strings: &mut impl Write,
    mesh: &Mesh,
    name: &str,
) -> Result<()> {
    mesh.validate()?;
    let name = header_name(name);
    let date = super::landxml::utc_now().surpac_date();

    let mut o = Out::new(strings);
    o.bytes(name.as_bytes())
        .bytes(b",")
        .bytes(date.as_bytes())
        .bytes(b",,meshbool\n0, 0.000, 0.000, 0.000, 0.000, 0.000, 0.000\n");
    for p in &mesh.positions {
        o.bytes(b"1, ")
            .f64(p[1])
            .bytes(b", ")
            .f64(p[0])
            .bytes(b", ")
            .f64(p[2])
            .bytes(b",\n")
            .record_done()?;
    }
    o.bytes(b"0, 0.000, 0.000, 0.000,\n0, 0.000, 0.000, 0.000, END\n");
    o.finish()?;

    let counts = crate::edges::EdgeCounts::of(mesh);
    let closed = !mesh.triangles.is_empty() && counts.boundary == 0 && counts.non_manifold == 0;
    let mut o = Out::new(dtm);
    o.bytes(name.as_bytes())
        .bytes(b".str,\n0, 0.000, 0.000, 0.000, END\nOBJECT, 1,\nTRISOLATION, 1, neighbours=no,validated=false,closed=")
        .bytes(if closed { b"yes\n" } else { b"no\n" });
    for (k, t) in mesh.triangles.iter().enumerate() {
        o.int(k as u64 + 1);
        for &i in t {
            o.bytes(b", ").int(u64::from(i) + 1);
        }
        o.bytes(b", 0, 0, 0,\n").record_done()?;
    }
    o.bytes(b"END\n");
    o.finish()
}

/// Writes the DTM at `path` and its string file beside it (extension `str`).
pub(super) fn write_path(path: &std::path::Path, mesh: &Mesh) -> Result<()> {
    let is_str = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("str"));
    if is_str {
        return Err(Error::InvalidParameter(
            "a Surpac DTM cannot be named .str, the name its string file takes beside it: \
             name it .dtm"
                .into(),
        ));
    }
    mesh.validate()?;
    let strings_path = path.with_extension("str");
    let name = path
        .file_stem()
        .map_or_else(|| "meshbool".into(), |s| s.to_string_lossy().into_owned());
    // The string file first, then the DTM (each written whole or not at all): a DTM is
    // never beside a string file it does not belong to for longer than the two renames.
    let mut strings = Vec::new();
    let mut dtm = Vec::new();
    write_surpac_dtm(&mut dtm, &mut strings, mesh, &name)?;
    super::write_file(&strings_path, |out| Ok(out.write_all(&strings)?))
        .map_err(|e| e.in_file("writing the DTM's string file", &strings_path))?;
    super::write_file(path, |out| Ok(out.write_all(&dtm)?))
}
