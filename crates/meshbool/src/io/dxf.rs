//! ASCII DXF, the exchange format of mining packages: `3DFACE` entities (a triangle, or a
//! quad as two triangles; a 3DFACE lacking a coordinate of its first three corners is an
//! error) and polyface meshes (`POLYLINE` with flag 64 and its `VERTEX` records; a mesh
//! vertex lacking a coordinate is an error) in the ENTITIES section are read; written as R12-style `3DFACE`s.
//!
//! Written by hand rather than with a DXF crate: only group-code pairs and two entity kinds
//! are needed, and coordinates must round-trip exactly, which the general crates do not
//! promise.

use std::io::Write;

use super::{parse_f64, Format, Out};
use crate::error::{Error, Location, Result};
use crate::{Mesh, Welder};

/// Content sniffing: the file opens with a group code 0 (or a 999 comment) and has a SECTION.
pub(super) fn looks_like(text: &[u8]) -> bool {
    let mut it = super::lines(text)
        .map(|(_, l)| l.trim_ascii())
        .filter(|l| !l.is_empty());
    matches!(it.next(), Some(b"0") | Some(b"999"))
        && text[..text.len().min(2048)]
            .windows(7)
            .any(|w| w == b"SECTION")
}

/// One group: its code, its value and the line of the code.
struct Group<'a> {
    code: i32,
    value: &'a [u8],
    line: usize,
}

fn groups(bytes: &[u8]) -> impl Iterator<Item = Result<Group<'_>>> {
    let mut lines = super::lines(bytes);
    std::iter::from_fn(move || {
        let (line, code) = loop {
            let (ln, l) = lines.next()?;
            if !l.trim_ascii().is_empty() {
                break (ln, l.trim_ascii());
            }
        };
        let Some(code) = std::str::from_utf8(code).ok().and_then(|c| c.parse().ok()) else {
            return Some(Err(Error::parse(
                Format::Dxf,
                Location::Line(line),
                format!(
                    "expected a group code, found {:?}",
                    String::from_utf8_lossy(code)
                ),
            )));
        };
        let value = match lines.next() {
            Some((_, v)) => v.trim_ascii(),
            None => {
                return Some(Err(Error::parse(
                    Format::Dxf,
                    Location::Line(line),
                    "group code without a value: truncated?",
                )))
            }
        };
        Some(Ok(Group { code, value, line }))
    })
}

/// An entity being collected: its type, line, and the groups that matter here.
#[derive(Default)]
struct Entity {
    kind: Vec<u8>,
    line: usize,
    /// Coordinates by group code 10..=13, 20..=23, 30..=33 as [corner][axis].
    xyz: [[f64; 3]; 4],
    /// Which of those group codes were present, as [corner][axis].
    seen: [[bool; 3]; 4],
    flags: i64,
    /// Face record indices, groups 71..=74.
    refs: [i64; 4],
}

pub(super) fn read(bytes: &[u8]) -> Result<Mesh> {
    if bytes.starts_with(b"AutoCAD Binary DXF") {
        return Err(Error::parse(
            Format::Dxf,
            Location::Whole,
            "binary DXF is not supported: save as ASCII DXF",
        ));
    }
    let mut welder = Welder::with_capacity(bytes.len() / 40);
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    let mut in_entities = false;
    let mut section_name_next = false;
    let mut ent = Entity::default();
    // Polyface mesh state: inside a polyface POLYLINE, its vertices (welded indices).
    let mut polyface: Option<Vec<u32>> = None;
    let mut in_polyline = false;
    let mut ended = false;

    let mut finish = |ent: &Entity,
                      polyface: &mut Option<Vec<u32>>,
                      in_polyline: &mut bool,
                      triangles: &mut Vec<[u32; 3]>|
     -> Result<()> {
        let err = |msg: String| Error::parse(Format::Dxf, Location::Line(ent.line), msg);
        match ent.kind.as_slice() {
            b"3DFACE" => {
                // Corners 1 to 3 need x, y and z; the 4th is all there or absent.
                let fourth = ent.seen[3].contains(&true);
                let complete = |k: usize| (k == 3 && !fourth) || ent.seen[k] == [true; 3];
                if !(0..4).all(complete) {
                    let missing: Vec<String> = (0..4)
                        .filter(|&k| !complete(k))
                        .flat_map(|k| (0..3).map(move |a| (k, a)))
                        .filter(|&(k, a)| !ent.seen[k][a])
                        .map(|(k, a)| (10 * (a + 1) + k).to_string())
                        .collect();
                    return Err(err(format!(
                        "3DFACE without group code{} {}: corners 1 to 3 need all of 10/20/30, \
                         11/21/31 and 12/22/32, and the 4th corner (13/23/33) is all there or \
                         absent",
                        if missing.len() == 1 { "" } else { "s" },
                        missing.join(", ")
                    )));
                }
                let mut c = ent.xyz;
                if !fourth {
                    c[3] = c[2];
                }
                let idx = c.map(|p| welder.index(p));
                triangles.push([idx[0], idx[1], idx[2]]);
                if c[3] != c[2] && c[3] != c[0] {
                    triangles.push([idx[0], idx[2], idx[3]]);
                }
            }
            b"POLYLINE" => {
                *in_polyline = true;
                *polyface = (ent.flags & 64 != 0).then(Vec::new);
            }
            b"VERTEX" if *in_polyline => {
                if let Some(verts) = polyface {
                    if ent.flags & 64 != 0 {
                        if ent.seen[0] != [true; 3] {
                            let missing: Vec<&str> = ["10", "20", "30"]
                                .into_iter()
                                .zip(ent.seen[0])
                                .filter(|&(_, seen)| !seen)
                                .map(|(code, _)| code)
                                .collect();
                            return Err(err(format!(
                                "polyface mesh VERTEX without group code{} {}: a mesh vertex \
                                 needs x, y and z (10/20/30)",
                                if missing.len() == 1 { "" } else { "s" },
                                missing.join(", ")
                            )));
                        }
                        verts.push(welder.index(ent.xyz[0]));
                    } else if ent.flags & 128 != 0 {
                        let mut poly = Vec::with_capacity(4);
                        for &r in &ent.refs {
                            if r == 0 {
                                continue;
                            }
                            let i = r.unsigned_abs() as usize;
                            let v = *verts.get(i - 1).ok_or_else(|| {
                                err(format!(
                                    "face record refers to vertex {i}, the mesh has {} so far",
                                    verts.len()
                                ))
                            })?;
                            poly.push(v);
                        }
                        if poly.len() < 3 {
                            return Err(err(format!(
                                "face record has {} vertices, needs at least 3",
                                poly.len()
                            )));
                        }
                        super::push_fan(&poly, triangles);
                    }
                }
            }
            b"SEQEND" => {
                *in_polyline = false;
                *polyface = None;
            }
            _ => {}
        }
        Ok(())
    };

    for g in groups(bytes) {
        let g = g?;
        if g.code == 0 {
            if in_entities {
                finish(&ent, &mut polyface, &mut in_polyline, &mut triangles)?;
            }
            ent = Entity {
                kind: g.value.to_vec(),
                line: g.line,
                ..Entity::default()
            };
            match g.value {
                b"SECTION" => section_name_next = true,
                b"ENDSEC" => in_entities = false,
                b"EOF" => {
                    ended = true;
                    break;
                }
                _ => {}
            }
            continue;
        }
        if section_name_next && g.code == 2 {
            in_entities = g.value == b"ENTITIES";
            section_name_next = false;
            continue;
        }
        if !in_entities {
            continue;
        }
        match g.code {
            10..=13 | 20..=23 | 30..=33 => {
                let (axis, corner) = ((g.code / 10 - 1) as usize, (g.code % 10) as usize);
                ent.xyz[corner][axis] = parse_f64(g.value, Format::Dxf, g.line + 1)?;
                ent.seen[corner][axis] = true;
            }
            70..=74 => {
                let v: i64 = std::str::from_utf8(g.value)
                    .ok()
                    .and_then(|s| s.parse().ok())
                    .ok_or_else(|| {
                        Error::parse(
                            Format::Dxf,
                            Location::Line(g.line + 1),
                            "expected an integer",
                        )
                    })?;
                if g.code == 70 {
                    ent.flags = v;
                } else {
                    ent.refs[(g.code - 71) as usize] = v;
                }
            }
            _ => {}
        }
    }
    if !ended {
        return Err(Error::parse(
            Format::Dxf,
            Location::Line(super::lines(bytes).count()),
            "missing EOF marker: truncated?",
        ));
    }
    Ok(Mesh::new_unchecked(welder.into_positions(), triangles))
}

pub(super) fn write(out: &mut impl Write, mesh: &Mesh) -> Result<()> {
    let mut o = Out::new(out);
    o.bytes(b"0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1009\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n");
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.corners(t);
        o.bytes(b"0\n3DFACE\n8\n0\n");
        for (k, p) in [a, b, c, c].iter().enumerate() {
            for (axis, &x) in p.iter().enumerate() {
                o.int((10 * (axis + 1) + k) as u64)
                    .bytes(b"\n")
                    .f64(x)
                    .bytes(b"\n");
            }
        }
        o.record_done()?;
    }
    o.bytes(b"0\nENDSEC\n0\nEOF\n");
    o.finish()
}
