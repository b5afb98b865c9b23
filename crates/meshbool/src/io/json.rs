//! JSON triangle soups: the seed library's `[{"v0":{"x":..,"y":..,"z":..},"v1":..,"v2":..}]`
//! and Kirra's `[{"vertices":[{"x":..,"y":..,"z":..}, ..]}]` (polygons become fans). Other
//! keys in a triangle object are ignored. Corners are welded where exactly equal.

use std::io::Write;

use serde::Deserialize;

use super::{Format, Out};
use crate::error::{Error, Location, Result};
use crate::{Mesh, Welder};

#[derive(Deserialize)]
struct P {
    x: f64,
    y: f64,
    z: f64,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum Tri {
    Soup { v0: P, v1: P, v2: P },
    Kirra { vertices: Vec<P> },
}

pub(super) fn read(bytes: &[u8]) -> Result<Mesh> {
    let tris: Vec<Tri> = serde_json::from_slice(bytes).map_err(|e| {
        let msg = if e.is_data() {
            format!("{e}: expected an array of {{\"v0\",\"v1\",\"v2\"}} or {{\"vertices\"}} triangle objects with x, y, z numbers")
        } else {
            e.to_string()
        };
        Error::parse(Format::JsonSoup, Location::Line(e.line()), msg)
    })?;
    let mut welder = Welder::with_capacity(tris.len() * 3);
    let mut triangles = Vec::with_capacity(tris.len());
    let mut poly = Vec::new();
    for (t, tri) in tris.iter().enumerate() {
        poly.clear();
        match tri {
            Tri::Soup { v0, v1, v2 } => {
                poly.extend([v0, v1, v2].map(|p| welder.index([p.x, p.y, p.z])))
            }
            Tri::Kirra { vertices } => {
                poly.extend(vertices.iter().map(|p| welder.index([p.x, p.y, p.z])))
            }
        }
        if poly.len() < 3 {
            return Err(Error::parse(
                Format::JsonKirra,
                Location::Triangle(t),
                format!("polygon has {} vertices, needs at least 3", poly.len()),
            ));
        }
        super::push_fan(&poly, &mut triangles);
    }
    Ok(Mesh::new_unchecked(welder.into_positions(), triangles))
}

pub(super) fn write(out: &mut impl Write, mesh: &Mesh, format: Format) -> Result<()> {
    let mut o = Out::new(out);
    o.bytes(b"[");
    for t in 0..mesh.triangles.len() {
        o.bytes(if t == 0 { b"\n" } else { b",\n" });
        o.bytes(if format == Format::JsonKirra {
            b"{\"vertices\":["
        } else {
            b"{"
        });
        for (k, p) in mesh.corners(t).iter().enumerate() {
            if format == Format::JsonKirra {
                o.bytes(if k == 0 { b"" } else { b"," });
            } else {
                o.bytes(match k {
                    0 => b"\"v0\":",
                    1 => b",\"v1\":",
                    _ => b",\"v2\":",
                });
            }
            o.bytes(b"{\"x\":")
                .f64(p[0])
                .bytes(b",\"y\":")
                .f64(p[1])
                .bytes(b",\"z\":")
                .f64(p[2])
                .bytes(b"}");
        }
        o.bytes(if format == Format::JsonKirra {
            b"]}"
        } else {
            b"}"
        });
        o.record_done()?;
    }
    o.bytes(b"\n]\n");
    o.finish()
}
