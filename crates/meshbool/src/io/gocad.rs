//! GOCAD TSurf (`.ts`), the ASCII surface format of GOCAD/SKUA and of the geological
//! modelling packages that exchange with it.
//!
//! A file holds one or more objects, each from a `GOCAD <type> <version>` line to its `END`
//! line. Every `GOCAD TSurf` object is read and the surfaces are concatenated; objects of
//! other types (`PLine`, `VSet`, ...) are skipped. In a surface:
//!
//! - `HEADER { ... }` and any other block opened by a line ending in `{` (such as
//!   `PROPERTY_CLASS_HEADER`) is skipped up to its `}`; `HEADER {name:x}` on one line too.
//! - `TFACE` starts a face set; a surface may have several. Vertex ids belong to the
//!   surface, so a triangle of one face set may use a vertex of another.
//! - `VRTX id x y z` and `PVRTX id x y z [property values]`: a vertex with an integer id
//!   of the writer's choosing. Property values are skipped.
//! - `ATOM id vid` and `PATOM id vid [property values]`: a second id for vertex `vid`
//!   (the same point, so the same vertex of the mesh).
//! - `TRGL a b c`: a triangle by vertex or atom ids, kept in the order written.
//! - `ZPOSITIVE Elevation` (the default) or `ZPOSITIVE Depth`, usually inside
//!   `GOCAD_ORIGINAL_COORDINATE_SYSTEM`: with `Depth`, `z` grows downwards, so the surface's
//!   `z` values are negated on read and up is `+z` in the mesh. The triangles keep their
//!   vertex order: a surface written from a `z`-up model to a depth file and read back
//!   faces as it did in the model.
//! - `PROPERTIES`, `PROPERTY_CLASSES`, `BSTONE`, `BORDER`, `#` comments and any other line
//!   are skipped.
//!
//! Errors name the line: a surface without `END` (a truncated file), a triangle or atom
//! naming an id the surface does not define, an id defined twice, non-finite or malformed
//! numbers.
//!
//! Written as one surface: `GOCAD TSurf 1`, a header named `meshbool`, `ZPOSITIVE
//! Elevation`, one `TFACE` with `VRTX` ids from 1 and the `TRGL`s, then `END`, numbers in
//! the shortest form that reads back to the same `f64`.

use std::io::Write;

use rustc_hash::FxHashMap;

use super::{lines, parse_f64, tokens, Format, Out};
use crate::error::{Error, Location, Result};
use crate::Mesh;

const FMT: Format = Format::GocadTs;

/// Content sniffing: the first line is `GOCAD TSurf ...`.
pub(super) fn looks_like(text: &[u8]) -> bool {
    let first = lines(text).next().map_or(&b""[..], |(_, l)| l);
    let mut t = tokens(first);
    t.next() == Some(b"GOCAD") && t.next().is_some_and(|k| k.eq_ignore_ascii_case(b"TSurf"))
}

/// What a read met besides the mesh (for the tests; nothing of it is public).
#[derive(Debug, Default, PartialEq)]
pub(super) struct Counts {
    /// `GOCAD TSurf` objects read.
    pub surfaces: usize,
    /// `TFACE` lines.
    pub face_sets: usize,
    /// Property values skipped on `PVRTX` and `PATOM` lines.
    pub property_values: usize,
    /// Objects of other types skipped.
    pub other_objects: usize,
}

pub(super) fn read(bytes: &[u8]) -> Result<Mesh> {
    Ok(read_counted(bytes)?.0)
}

fn err(line: usize, message: impl Into<String>) -> Error {
    Error::parse(FMT, Location::Line(line), message)
}

fn lossy(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// An integer vertex id.
fn id(token: Option<&[u8]>, what: &str, line: usize) -> Result<i64> {
    let t = token.ok_or_else(|| err(line, format!("{what} is missing")))?;
    std::str::from_utf8(t)
        .ok()
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| {
            err(
                line,
                format!("{what} must be an integer, found {:?}", lossy(t)),
            )
        })
}

/// True when `line` opens a `{ ... }` block that goes on over the following lines.
fn opens_block(line: &[u8]) -> bool {
    match line.iter().rposition(|&b| b == b'{') {
        Some(at) => !line[at..].contains(&b'}'),
        None => false,
    }
}

/// Where the reader is.
#[derive(Clone, Copy, PartialEq)]
enum State {
    /// Between objects.
    Outside,
    /// In a `GOCAD TSurf` object that began on this line.
    Surface(usize),
    /// In an object of another type that began on this line.
    Other(usize),
}

pub(super) fn read_counted(bytes: &[u8]) -> Result<(Mesh, Counts)> {
    let mut positions: Vec<[f64; 3]> = Vec::new();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    let mut counts = Counts::default();
    let mut state = State::Outside;
    // The surface being read: its ids, its triangles by id (resolved at its END), its first
    // vertex and its z convention.
    let mut ids: FxHashMap<i64, u32> = FxHashMap::default();
    let mut pending: Vec<([i64; 3], usize)> = Vec::new();
    let mut first_vertex = 0;
    let mut depth = false;
    // The line of the `{` whose block is being skipped.
    let mut block: Option<usize> = None;
    let mut last_line = 0;

    for (ln, line) in lines(bytes) {
        last_line = ln;
        if block.is_some() {
            if line.contains(&b'}') {
                block = None;
            }
            continue;
        }
        let mut tok = tokens(line);
        let Some(key) = tok.next() else { continue };
        if key.starts_with(b"#") {
            continue;
        }
        let start = match state {
            State::Outside => {
                if key != b"GOCAD" {
                    return Err(err(
                        ln,
                        format!(
                            "expected an object header such as `GOCAD TSurf 1`, found {:?}",
                            lossy(line)
                        ),
                    ));
                }
                if tok.next().is_some_and(|k| k.eq_ignore_ascii_case(b"TSurf")) {
                    state = State::Surface(ln);
                    ids.clear();
                    pending.clear();
                    first_vertex = positions.len();
                    depth = false;
                } else {
                    state = State::Other(ln);
                    counts.other_objects += 1;
                }
                continue;
            }
            State::Other(_) => {
                if opens_block(line) {
                    block = Some(ln);
                } else if key == b"END" {
                    state = State::Outside;
                }
                continue;
            }
            State::Surface(start) => start,
        };
        if opens_block(line) {
            block = Some(ln);
            continue;
        }
        match key {
            b"VRTX" | b"PVRTX" => {
                let v = id(tok.next(), "the vertex id", ln)?;
                let mut p = [0.0; 3];
                for (c, axis) in p.iter_mut().zip(["x", "y", "z"]) {
                    let t = tok.next().ok_or_else(|| {
                        err(
                            ln,
                            format!("a vertex needs an id and x y z; {axis} is missing"),
                        )
                    })?;
                    *c = parse_f64(t, FMT, ln)?;
                }
                if key == b"PVRTX" {
                    counts.property_values += tok.count();
                }
                let index = u32::try_from(positions.len())
                    .ok()
                    .filter(|&i| i < u32::MAX)
                    .ok_or_else(|| err(ln, "more vertices than a mesh can index"))?;
                if ids.insert(v, index).is_some() {
                    return Err(err(ln, format!("vertex id {v} is defined twice")));
                }
                positions.push(p);
            }
            b"ATOM" | b"PATOM" => {
                let a = id(tok.next(), "the atom id", ln)?;
                let of = id(tok.next(), "the vertex an atom stands for", ln)?;
                let &v = ids.get(&of).ok_or_else(|| {
                    err(
                        ln,
                        format!("atom {a} refers to vertex {of}, which is not defined before it"),
                    )
                })?;
                if key == b"PATOM" {
                    counts.property_values += tok.count();
                }
                if ids.insert(a, v).is_some() {
                    return Err(err(ln, format!("vertex id {a} is defined twice")));
                }
            }
            b"TRGL" => {
                let mut t = [0; 3];
                for c in &mut t {
                    *c = id(tok.next(), "a triangle's vertex id", ln)?;
                }
                pending.push((t, ln));
            }
            b"TFACE" => counts.face_sets += 1,
            b"ZPOSITIVE" => match tok.next() {
                Some(v) if v.eq_ignore_ascii_case(b"Elevation") => depth = false,
                Some(v) if v.eq_ignore_ascii_case(b"Depth") => depth = true,
                v => {
                    return Err(err(
                        ln,
                        format!(
                            "ZPOSITIVE must be Elevation or Depth, found {:?}",
                            lossy(v.unwrap_or(b""))
                        ),
                    ))
                }
            },
            b"GOCAD" => {
                return Err(err(
                    ln,
                    format!(
                        "a new object starts before the END of the TSurf begun at line {start}"
                    ),
                ));
            }
            b"END" => {
                triangles.reserve(pending.len());
                for (t, at) in pending.drain(..) {
                    let mut tri = [0; 3];
                    for (c, v) in tri.iter_mut().zip(t) {
                        *c = *ids.get(&v).ok_or_else(|| {
                            err(
                                at,
                                format!("triangle refers to vertex id {v}, which this surface does not define"),
                            )
                        })?;
                    }
                    triangles.push(tri);
                }
                if depth {
                    for p in &mut positions[first_vertex..] {
                        p[2] = -p[2];
                    }
                }
                counts.surfaces += 1;
                state = State::Outside;
            }
            _ => {}
        }
    }
    if let Some(at) = block {
        return Err(err(
            at,
            "the block opened here is not closed by `}`: truncated?",
        ));
    }
    match state {
        State::Outside => {}
        State::Surface(start) | State::Other(start) => {
            return Err(err(
                last_line,
                format!("the object begun at line {start} has no END: truncated?"),
            ))
        }
    }
    if counts.surfaces == 0 {
        return Err(Error::parse(
            FMT,
            Location::Whole,
            "no `GOCAD TSurf` object in the file",
        ));
    }
    Ok((Mesh::new_unchecked(positions, triangles), counts))
}

pub(super) fn write(out: &mut impl Write, mesh: &Mesh) -> Result<()> {
    let mut o = Out::new(out);
    o.bytes(
        b"GOCAD TSurf 1\n\
          HEADER {\n\
          name:meshbool\n\
          }\n\
          GOCAD_ORIGINAL_COORDINATE_SYSTEM\n\
          NAME Default\n\
          AXIS_NAME \"X\" \"Y\" \"Z\"\n\
          ZPOSITIVE Elevation\n\
          END_ORIGINAL_COORDINATE_SYSTEM\n\
          TFACE\n",
    );
    for (i, p) in mesh.positions.iter().enumerate() {
        o.bytes(b"VRTX ")
            .int(i as u64 + 1)
            .bytes(b" ")
            .coords(p, b" ")
            .bytes(b"\n")
            .record_done()?;
    }
    for t in &mesh.triangles {
        o.bytes(b"TRGL");
        for &i in t {
            o.bytes(b" ").int(u64::from(i) + 1);
        }
        o.bytes(b"\n").record_done()?;
    }
    o.bytes(b"END\n");
    o.finish()
}
