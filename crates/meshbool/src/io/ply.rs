//! PLY, ASCII and binary (little and big endian): `vertex` elements with scalar `x y z`
//! properties of any type, `face` elements with a `vertex_indices` (or `vertex_index`) list
//! of any integer type; every other element and property is skipped. A list's length type
//! must be an integer type, and the body must end where the header's counts say (only
//! whitespace may follow in ASCII). Written as binary little-endian (or the encoding asked
//! for) with `double` positions.

use std::io::Write;

use rayon::prelude::*;

use super::{lines, parse_f64, tokens, whole_lines, Format, Out};
use crate::error::{Error, Location, Result};
use crate::par::{concat, exclusive_sums};
use crate::Mesh;

#[derive(Clone, Copy, Debug, PartialEq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(name: &[u8]) -> Option<Scalar> {
        Some(match name {
            b"char" | b"int8" => Scalar::I8,
            b"uchar" | b"uint8" => Scalar::U8,
            b"short" | b"int16" => Scalar::I16,
            b"ushort" | b"uint16" => Scalar::U16,
            b"int" | b"int32" => Scalar::I32,
            b"uint" | b"uint32" => Scalar::U32,
            b"float" | b"float32" => Scalar::F32,
            b"double" | b"float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }
}

enum Prop {
    Scalar(Scalar, Vec<u8>),
    List(Scalar, Scalar, Vec<u8>),
}

struct Element {
    name: Vec<u8>,
    count: u64,
    props: Vec<Prop>,
}

/// The encoding named in the header, when there is a readable `format` line.
pub(super) fn encoding(bytes: &[u8]) -> Option<Format> {
    let line = super::lines(&bytes[..bytes.len().min(4096)])
        .find(|(_, l)| l.starts_with(b"format"))?
        .1;
    match tokens(line).nth(1)? {
        b"ascii" => Some(Format::PlyAscii),
        b"binary_little_endian" => Some(Format::PlyBinaryLe),
        b"binary_big_endian" => Some(Format::PlyBinaryBe),
        _ => None,
    }
}

/// Parses the header: the encoding, the elements and the byte offset where the body starts.
fn header(bytes: &[u8]) -> Result<(Format, Vec<Element>, usize, usize)> {
    let err = |ln: usize, msg: &str| Error::parse(Format::PlyAscii, Location::Line(ln), msg);
    let mut pos = 0;
    let mut ln = 0;
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        ln += 1;
        let Some(len) = bytes[pos..].iter().position(|&b| b == b'\n') else {
            return Err(err(ln, "header ends without end_header"));
        };
        let line = &bytes[pos..pos + len];
        let line = line.strip_suffix(b"\r").unwrap_or(line);
        pos += len + 1;
        let t: Vec<&[u8]> = tokens(line).collect();
        match t.as_slice() {
            [b"ply"] if ln == 1 => {}
            _ if ln == 1 => return Err(err(1, "missing the 'ply' magic line")),
            [] | [b"comment", ..] | [b"obj_info", ..] => {}
            [b"format", enc, _version] => {
                format = Some(match *enc {
                    b"ascii" => Format::PlyAscii,
                    b"binary_little_endian" => Format::PlyBinaryLe,
                    b"binary_big_endian" => Format::PlyBinaryBe,
                    _ => return Err(err(ln, "unknown PLY encoding")),
                })
            }
            [b"element", name, count] => {
                let count = std::str::from_utf8(count)
                    .ok()
                    .and_then(|c| c.parse().ok())
                    .ok_or_else(|| err(ln, "element count is not a number"))?;
                elements.push(Element {
                    name: name.to_vec(),
                    count,
                    props: Vec::new(),
                });
            }
            [b"property", b"list", ct_name, it, name] => {
                let (Some(ct), Some(it)) = (Scalar::parse(ct_name), Scalar::parse(it)) else {
                    return Err(err(ln, "unknown property type"));
                };
                if matches!(ct, Scalar::F32 | Scalar::F64) {
                    return Err(err(
                        ln,
                        &format!(
                            "list length type {} of property {} is not an integer type: a list's \
                             length must be char, uchar, short, ushort, int or uint",
                            String::from_utf8_lossy(ct_name),
                            String::from_utf8_lossy(name)
                        ),
                    ));
                }
                let e = elements
                    .last_mut()
                    .ok_or_else(|| err(ln, "property before any element"))?;
                e.props.push(Prop::List(ct, it, name.to_vec()));
            }
            [b"property", ty, name] => {
                let ty = Scalar::parse(ty).ok_or_else(|| err(ln, "unknown property type"))?;
                let e = elements
                    .last_mut()
                    .ok_or_else(|| err(ln, "property before any element"))?;
                e.props.push(Prop::Scalar(ty, name.to_vec()));
            }
            [b"end_header"] => break,
            _ => return Err(err(ln, "unrecognised header line")),
        }
    }
    let format = format.ok_or_else(|| err(ln, "header has no format line"))?;
    Ok((format, elements, pos, ln))
}

/// Reads values one at a time from an ASCII or binary body, knowing where it is for errors.
struct Body<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: usize,
    format: Format,
}

impl Body<'_> {
    fn err(&self, msg: impl Into<String>) -> Error {
        let loc = match self.format {
            Format::PlyAscii => Location::Line(self.line),
            _ => Location::Byte(self.pos as u64),
        };
        Error::parse(self.format, loc, msg)
    }

    /// After the last declared element: the end of the input, or (ASCII) only whitespace
    /// before it. Anything else means the header's counts are smaller than the body: an
    /// error at the line or byte where the rest starts.
    fn finish(&mut self, elements: &[Element]) -> Result<()> {
        if self.format == Format::PlyAscii {
            while self.pos < self.bytes.len() && self.bytes[self.pos].is_ascii_whitespace() {
                if self.bytes[self.pos] == b'\n' {
                    self.line += 1;
                }
                self.pos += 1;
            }
        }
        if self.pos == self.bytes.len() {
            return Ok(());
        }
        let declared: Vec<String> = elements
            .iter()
            .map(|e| format!("{} {}", e.count, String::from_utf8_lossy(&e.name)))
            .collect();
        let what = match self.format {
            Format::PlyAscii => "data".to_string(),
            _ => format!("{} bytes", self.bytes.len() - self.pos),
        };
        Err(self.err(format!(
            "{what} beyond what the header declares ({}): are its element counts too small?",
            declared.join(", ")
        )))
    }

    fn next(&mut self, ty: Scalar) -> Result<f64> {
        match self.format {
            Format::PlyAscii => {
                while self.pos < self.bytes.len() && self.bytes[self.pos].is_ascii_whitespace() {
                    if self.bytes[self.pos] == b'\n' {
                        self.line += 1;
                    }
                    self.pos += 1;
                }
                let start = self.pos;
                while self.pos < self.bytes.len() && !self.bytes[self.pos].is_ascii_whitespace() {
                    self.pos += 1;
                }
                if start == self.pos {
                    return Err(self.err("file ends before all elements are read: truncated?"));
                }
                parse_f64(&self.bytes[start..self.pos], self.format, self.line)
            }
            _ => {
                let n = ty.size();
                let Some(raw) = self.bytes.get(self.pos..self.pos + n) else {
                    return Err(self.err("file ends before all elements are read: truncated?"));
                };
                self.pos += n;
                Ok(value(raw, ty, self.format == Format::PlyBinaryBe))
            }
        }
    }
}

/// A binary value of type `ty` from the first bytes of `raw` (at least its size), big
/// endian where `be`.
#[inline]
fn value(raw: &[u8], ty: Scalar, be: bool) -> f64 {
    let word = |n: usize| {
        let mut b = [0u8; 8];
        b[..n].copy_from_slice(&raw[..n]);
        if be {
            b[..n].reverse();
        }
        b
    };
    match ty {
        Scalar::F32 => {
            let b = word(4);
            f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        }
        Scalar::F64 => f64::from_le_bytes(word(8)),
        // Exact: integers of at most 32 bits.
        _ => integer(raw, ty, be) as f64,
    }
}

/// The usual shape of a mesh file, which [`triangles_side_by_side`] reads: a `vertex`
/// element of scalar properties only (`x`, `y` and `z` among them: their offsets in a
/// record and types, the last of a name as the general reader takes it), then a `face`
/// element whose one property is its index list (its length and index types).
struct Usual {
    vertices: usize,
    props: Vec<Scalar>,
    xyz: [(usize, Scalar); 3],
    /// The same properties' places in the record.
    xyz_index: [usize; 3],
    faces: usize,
    list: (Scalar, Scalar),
}

impl Usual {
    fn of(elements: &[Element]) -> Option<Usual> {
        let [v, f] = elements else { return None };
        if v.name != b"vertex" || f.name != b"face" {
            return None;
        }
        let mut props = Vec::new();
        let mut xyz = [None; 3];
        let mut xyz_index = [0; 3];
        let mut offset = 0;
        for (j, p) in v.props.iter().enumerate() {
            let Prop::Scalar(ty, name) = p else {
                return None;
            };
            if let Some(k) = [&b"x"[..], b"y", b"z"].iter().position(|a| a == name) {
                xyz[k] = Some((offset, *ty));
                xyz_index[k] = j;
            }
            props.push(*ty);
            offset += ty.size();
        }
        let [Prop::List(ct, it, name)] = f.props.as_slice() else {
            return None;
        };
        let integer = |t: &Scalar| !matches!(t, Scalar::F32 | Scalar::F64);
        if !(name == b"vertex_indices" || name == b"vertex_index") || !integer(ct) || !integer(it) {
            return None;
        }
        Some(Usual {
            vertices: usize::try_from(v.count)
                .ok()
                .filter(|&n| n as u64 <= u64::from(u32::MAX))?,
            props,
            xyz: [xyz[0]?, xyz[1]?, xyz[2]?],
            xyz_index,
            faces: usize::try_from(f.count).ok()?,
            list: (*ct, *it),
        })
    }

    /// A triangle's corners from its list's length and three indices, if it is one
    /// (length 3, whole indices of vertices that exist).
    #[inline]
    fn triangle(&self, n: f64, idx: [f64; 3]) -> Option<[u32; 3]> {
        let nv = self.vertices as f64;
        (n == 3.0 && idx.iter().all(|&i| i >= 0.0 && i.fract() == 0.0 && i < nv))
            .then(|| idx.map(|i| i as u32))
    }
}

/// Vertex records (or face records) per piece of work.
const RECORDS: usize = 1 << 12;

/// The body of a file of the [`Usual`] shape with every face a triangle, decoded side by
/// side: `None` where anything is out of the ordinary (a polygon, an index out of range, a
/// non-finite coordinate, a body longer or shorter than declared, blank lines in ASCII),
/// for the general reader to read or to name the error.
fn triangles_side_by_side(
    bytes: &[u8],
    format: Format,
    elements: &[Element],
    start: usize,
) -> Option<Mesh> {
    triangles_in_pieces(bytes, format, elements, start, super::pieces(bytes.len()))
}

/// [`triangles_side_by_side`], an ASCII body in about `pieces` pieces of whole lines.
fn triangles_in_pieces(
    bytes: &[u8],
    format: Format,
    elements: &[Element],
    start: usize,
    pieces: usize,
) -> Option<Mesh> {
    let u = Usual::of(elements)?;
    let body = &bytes[start..];
    let (positions, triangles) = if format == Format::PlyAscii {
        ascii_body(body, &u, pieces)?
    } else {
        binary_body(body, &u, format == Format::PlyBinaryBe)?
    };
    Some(Mesh::new_unchecked(positions, triangles))
}

type Decoded = (Vec<[f64; 3]>, Vec<[u32; 3]>);

fn binary_body(body: &[u8], u: &Usual, be: bool) -> Option<Decoded> {
    let vsize: usize = u.props.iter().map(|t| t.size()).sum();
    let (ct, it) = u.list;
    let fsize = ct.size() + 3 * it.size();
    let split = u.vertices.checked_mul(vsize)?;
    if body.len() != split.checked_add(u.faces.checked_mul(fsize)?)? {
        return None;
    }
    let (vb, fb) = body.split_at(split);
    let mut positions = vec![[0.0; 3]; u.vertices];
    let mut triangles = vec![[0u32; 3]; u.faces];
    let nv = u.vertices as i64;
    let (finite, in_range) = rayon::join(
        || {
            decode(&mut positions, vb, vsize, |r| {
                let p = u.xyz.map(|(o, ty)| value(&r[o..], ty, be));
                p.iter().all(|x| x.is_finite()).then_some(p)
            })
        },
        || {
            decode(&mut triangles, fb, fsize, |r| {
                let at = |k: usize| integer(&r[ct.size() + k * it.size()..], it, be);
                let tri = [at(0), at(1), at(2)];
                (integer(r, ct, be) == 3 && tri.iter().all(|i| (0..nv).contains(i)))
                    .then(|| tri.map(|i| i as u32))
            })
        },
    );
    (finite && in_range).then_some((positions, triangles))
}

/// Fills `out` side by side from the records of `size` bytes of `raw` by `f`; whether
/// every record gave a value.
fn decode<T: Send>(
    out: &mut [T],
    raw: &[u8],
    size: usize,
    f: impl Fn(&[u8]) -> Option<T> + Sync,
) -> bool {
    out.par_chunks_mut(RECORDS)
        .zip(raw.par_chunks(RECORDS * size))
        .all(|(out, raw)| {
            out.iter_mut()
                .zip(raw.chunks_exact(size))
                .all(|(o, r)| f(r).map(|v| *o = v).is_some())
        })
}

/// A binary value of the integer type `ty` (as [`value`], without going through `f64`).
#[inline]
fn integer(raw: &[u8], ty: Scalar, be: bool) -> i64 {
    let n = ty.size();
    let mut b = [0u8; 4];
    b[..n].copy_from_slice(&raw[..n]);
    if be {
        b[..n].reverse();
    }
    match ty {
        Scalar::I8 => i64::from(b[0] as i8),
        Scalar::U8 => i64::from(b[0]),
        Scalar::I16 => i64::from(i16::from_le_bytes([b[0], b[1]])),
        Scalar::U16 => i64::from(u16::from_le_bytes([b[0], b[1]])),
        Scalar::I32 => i64::from(i32::from_le_bytes(b)),
        Scalar::U32 => i64::from(u32::from_le_bytes(b)),
        // Not an integer type: never a length or an index of the usual shape.
        Scalar::F32 | Scalar::F64 => -1,
    }
}

fn ascii_body(body: &[u8], u: &Usual, pieces: usize) -> Option<Decoded> {
    let records = u.vertices.checked_add(u.faces)?;
    let pieces = whole_lines(body, pieces);
    let last = pieces.len() - 1;
    // A piece's lines: those its newlines end, and the last piece's tail too.
    let text = |k: usize| match pieces[k] {
        [head @ .., b'\n'] if k < last => head,
        p => p,
    };
    // Each piece's first record: the lines before it (nothing to count for one piece).
    let firsts = if pieces.len() == 1 {
        vec![0]
    } else {
        let counts: Vec<usize> = (0..pieces.len())
            .into_par_iter()
            .map(|k| text(k).iter().filter(|&&b| b == b'\n').count() + 1)
            .collect();
        exclusive_sums(&counts)
    };
    // A finite number, as the general reader takes it (anything else goes to it).
    let number = |t: &[u8]| parse_f64(t, Format::PlyAscii, 0).ok();
    let parts = (0..pieces.len())
        .into_par_iter()
        .zip(firsts)
        .map(|(k, first)| {
            let (mut positions, mut triangles) = (Vec::new(), Vec::new());
            for (i, (_, line)) in lines(text(k)).enumerate() {
                let r = first + i;
                let mut tok = tokens(line);
                if r < u.vertices {
                    let mut p = [0.0; 3];
                    for j in 0..u.props.len() {
                        let v = number(tok.next()?)?;
                        for (x, &at) in p.iter_mut().zip(&u.xyz_index) {
                            if at == j {
                                *x = v;
                            }
                        }
                    }
                    positions.push(p);
                } else if r < records {
                    let n = number(tok.next()?)?;
                    let idx = [(); 3].map(|_| tok.next().and_then(number));
                    triangles.push(u.triangle(n, [idx[0]?, idx[1]?, idx[2]?])?);
                }
                // Past the records only blank lines.
                if tok.next().is_some() {
                    return None;
                }
            }
            Some((positions, triangles))
        })
        .collect::<Option<Vec<Decoded>>>()?;
    let (positions, triangles): (Vec<_>, Vec<_>) = parts.into_iter().unzip();
    let (positions, triangles) = rayon::join(|| concat(positions), || concat(triangles));
    // Fewer lines than records: truncated.
    (positions.len() == u.vertices && triangles.len() == u.faces).then_some((positions, triangles))
}

pub(super) fn read(bytes: &[u8]) -> Result<Mesh> {
    let (format, elements, start, header_lines) = header(bytes)?;
    if let Some(mesh) = triangles_side_by_side(bytes, format, &elements, start) {
        return Ok(mesh);
    }
    read_general(bytes, format, &elements, start, header_lines)
}

/// Reads the body value by value, whatever its shape, and names the first problem.
fn read_general(
    bytes: &[u8],
    format: Format,
    elements: &[Element],
    start: usize,
    header_lines: usize,
) -> Result<Mesh> {
    let mut body = Body {
        bytes,
        pos: start,
        line: header_lines + 1,
        format,
    };
    let nverts = elements
        .iter()
        .find(|e| e.name == b"vertex")
        .map_or(0, |e| e.count);
    if nverts > u64::from(u32::MAX) {
        return Err(body.err("more vertices than 2^32-1"));
    }
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    let mut poly: Vec<u32> = Vec::new();
    for e in elements {
        let is_vertex = e.name == b"vertex";
        let is_face = e.name == b"face";
        if is_vertex {
            for axis in [&b"x"[..], b"y", b"z"] {
                if !e
                    .props
                    .iter()
                    .any(|p| matches!(p, Prop::Scalar(_, n) if n == axis))
                {
                    return Err(body.err(format!(
                        "vertex element has no scalar property {}",
                        String::from_utf8_lossy(axis)
                    )));
                }
            }
            positions.reserve(e.count.min(1 << 24) as usize);
        }
        if e.props.is_empty() {
            continue; // nothing to read, whatever the count says
        }
        for _ in 0..e.count {
            let mut p = [0.0; 3];
            for prop in &e.props {
                match prop {
                    Prop::Scalar(ty, name) => {
                        let v = body.next(*ty)?;
                        if is_vertex {
                            let k = match name.as_slice() {
                                b"x" => 0,
                                b"y" => 1,
                                b"z" => 2,
                                _ => continue,
                            };
                            if !v.is_finite() {
                                return Err(body.err("non-finite vertex coordinate"));
                            }
                            p[k] = v;
                        }
                    }
                    Prop::List(ct, it, name) => {
                        let n = body.next(*ct)?;
                        if n < 0.0 || n.fract() != 0.0 {
                            return Err(body.err(format!("bad list length {n}")));
                        }
                        let indices =
                            is_face && (name == b"vertex_indices" || name == b"vertex_index");
                        poly.clear();
                        for _ in 0..n as u64 {
                            let i = body.next(*it)?;
                            if indices {
                                if i < 0.0 || i.fract() != 0.0 || i >= nverts as f64 {
                                    return Err(body.err(format!(
                                        "vertex index {i} out of range ({nverts} vertices)"
                                    )));
                                }
                                poly.push(i as u32);
                            }
                        }
                        if indices {
                            if poly.len() < 3 {
                                return Err(body.err(format!(
                                    "face has {} vertices, needs at least 3",
                                    poly.len()
                                )));
                            }
                            super::push_fan(&poly, &mut triangles);
                        }
                    }
                }
            }
            if is_vertex {
                positions.push(p);
            }
        }
    }
    body.finish(elements)?;
    Ok(Mesh::new_unchecked(positions, triangles))
}

/// The mesh of a PLY file as the reader side by side makes it (in `pieces` pieces where
/// ASCII), if the file is of its shape, and as the general reader makes it (for tests).
#[cfg(test)]
pub(super) fn both_readers(bytes: &[u8], pieces: usize) -> (Option<Mesh>, Result<Mesh>) {
    match header(bytes) {
        Ok((format, elements, start, lines)) => (
            triangles_in_pieces(bytes, format, &elements, start, pieces),
            read_general(bytes, format, &elements, start, lines),
        ),
        Err(e) => (None, Err(e)),
    }
}

pub(super) fn write(out: &mut impl Write, mesh: &Mesh, format: Format) -> Result<()> {
    let (enc, be) = match format {
        Format::PlyAscii => ("ascii", false),
        Format::PlyBinaryBe => ("binary_big_endian", true),
        _ => ("binary_little_endian", false),
    };
    let index_type = if mesh.positions.len() > i32::MAX as usize {
        "uint"
    } else {
        "int"
    };
    let head = format!(
        "ply\nformat {enc} 1.0\ncomment meshbool\nelement vertex {}\nproperty double x\n\
         property double y\nproperty double z\nelement face {}\n\
         property list uchar {index_type} vertex_indices\nend_header\n",
        mesh.positions.len(),
        mesh.triangles.len()
    );
    let mut o = Out::new(out);
    o.bytes(head.as_bytes());
    let f = |x: f64| if be { x.to_be_bytes() } else { x.to_le_bytes() };
    let u = |x: u32| if be { x.to_be_bytes() } else { x.to_le_bytes() };
    super::records(&mut o, mesh.positions.len(), |o, v| {
        let p = &mesh.positions[v];
        if format == Format::PlyAscii {
            o.coords(p, b" ").bytes(b"\n");
        } else {
            o.bytes(&f(p[0])).bytes(&f(p[1])).bytes(&f(p[2]));
        }
    })?;
    super::records(&mut o, mesh.triangles.len(), |o, t| {
        if format == Format::PlyAscii {
            o.bytes(b"3");
            for &i in &mesh.triangles[t] {
                o.bytes(b" ").int(u64::from(i));
            }
            o.bytes(b"\n");
        } else {
            o.bytes(&[3]);
            for &i in &mesh.triangles[t] {
                o.bytes(&u(i));
            }
        }
    })?;
    o.finish()
}
