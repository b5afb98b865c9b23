//! JSON triangle soups: the seed library's `[{"v0":{"x":..,"y":..,"z":..},"v1":..,"v2":..}]`
//! and Kirra's `[{"vertices":[{"x":..,"y":..,"z":..}, ..]}]` (polygons become fans). Other
//! keys in a triangle object are ignored. Corners are welded where exactly equal. A
//! malformed triangle is an error naming its array element and what a triangle looks like.

use std::cell::Cell;
use std::fmt;
use std::io::Write;

use serde::de::{self, DeserializeSeed, Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};
use serde::Deserialize;

use super::{Format, Out};
use crate::error::{Error, Location, Result};
use crate::{Mesh, Welder};

#[derive(Deserialize)]
#[serde(expecting = "a point {\"x\":..,\"y\":..,\"z\":..}")]
struct P {
    x: f64,
    y: f64,
    z: f64,
}

enum Tri {
    Soup { v0: P, v1: P, v2: P },
    Kirra { vertices: Vec<P> },
}

/// What a triangle looks like, for error messages.
const SHAPE: &str = "each element must be a triangle: \
    {\"v0\": {\"x\":..,\"y\":..,\"z\":..}, \"v1\": .., \"v2\": ..} or Kirra's \
    {\"vertices\": [..3 or more points..]}";

/// Where the reader is, for error messages: the array element, the key in it, the point
/// of its `"vertices"`.
#[derive(Default)]
struct At {
    element: Cell<Option<usize>>,
    key: Cell<Option<&'static str>>,
    point: Cell<Option<usize>>,
}

impl At {
    /// `array element 3 (0-based), "vertices" point 1: ` or nothing, outside the elements.
    fn prefix(&self) -> String {
        let Some(i) = self.element.get() else {
            return String::new();
        };
        let mut s = format!("array element {i} (0-based)");
        if let Some(k) = self.key.get() {
            s += &format!(", \"{k}\"");
            if let Some(p) = self.point.get() {
                s += &format!(" point {p}");
            }
        }
        s + ": "
    }
}

/// The top-level array of triangles.
struct Tris<'a>(&'a At);

impl<'de> DeserializeSeed<'de> for Tris<'_> {
    type Value = Vec<Tri>;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Vec<Tri>, D::Error> {
        d.deserialize_seq(self)
    }
}

impl<'de> Visitor<'de> for Tris<'_> {
    type Value = Vec<Tri>;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("an array of triangle objects")
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<Tri>, A::Error> {
        let mut tris = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(1 << 20));
        loop {
            self.0.element.set(Some(tris.len()));
            match seq.next_element_seed(OneTri(self.0))? {
                Some(t) => tris.push(t),
                None => break,
            }
        }
        self.0.element.set(None);
        Ok(tris)
    }
}

/// One triangle object: `v0`, `v1`, `v2`, or `vertices`; other keys are skipped.
struct OneTri<'a>(&'a At);

/// A key of a triangle object.
enum Key {
    Corner(usize),
    Vertices,
    Other,
}

impl<'de> Deserialize<'de> for Key {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Key, D::Error> {
        struct KeyVisitor;
        impl Visitor<'_> for KeyVisitor {
            type Value = Key;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a key")
            }
            fn visit_str<E: de::Error>(self, s: &str) -> Result<Key, E> {
                Ok(match s {
                    "v0" => Key::Corner(0),
                    "v1" => Key::Corner(1),
                    "v2" => Key::Corner(2),
                    "vertices" => Key::Vertices,
                    _ => Key::Other,
                })
            }
        }
        d.deserialize_identifier(KeyVisitor)
    }
}

impl<'de> DeserializeSeed<'de> for OneTri<'_> {
    type Value = Tri;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Tri, D::Error> {
        d.deserialize_map(self)
    }
}

impl<'de> Visitor<'de> for OneTri<'_> {
    type Value = Tri;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a triangle object")
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Tri, A::Error> {
        const CORNERS: [&str; 3] = ["v0", "v1", "v2"];
        let mut v: [Option<P>; 3] = [None, None, None];
        let mut vertices = None;
        while let Some(key) = map.next_key::<Key>()? {
            match key {
                Key::Corner(k) => {
                    self.0.key.set(Some(CORNERS[k]));
                    v[k] = Some(map.next_value()?);
                }
                Key::Vertices => {
                    self.0.key.set(Some("vertices"));
                    vertices = Some(map.next_value_seed(Points(self.0))?);
                }
                Key::Other => {
                    map.next_value::<IgnoredAny>()?;
                }
            }
            self.0.key.set(None);
        }
        match (v, vertices) {
            ([Some(v0), Some(v1), Some(v2)], _) => Ok(Tri::Soup { v0, v1, v2 }),
            ([None, None, None], Some(vertices)) => Ok(Tri::Kirra { vertices }),
            ([None, None, None], None) => Err(de::Error::custom(
                "neither \"v0\", \"v1\", \"v2\" nor \"vertices\"",
            )),
            (v, _) => {
                let missing: Vec<String> = (0..3)
                    .filter(|&k| v[k].is_none())
                    .map(|k| format!("\"{}\"", CORNERS[k]))
                    .collect();
                Err(de::Error::custom(format!("missing {}", missing.join(", "))))
            }
        }
    }
}

/// The points of a `"vertices"` array.
struct Points<'a>(&'a At);

impl<'de> DeserializeSeed<'de> for Points<'_> {
    type Value = Vec<P>;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<Vec<P>, D::Error> {
        d.deserialize_seq(self)
    }
}

impl<'de> Visitor<'de> for Points<'_> {
    type Value = Vec<P>;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("an array of points")
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<P>, A::Error> {
        let mut points = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(64));
        loop {
            self.0.point.set(Some(points.len()));
            match seq.next_element()? {
                Some(p) => points.push(p),
                None => break,
            }
        }
        self.0.point.set(None);
        Ok(points)
    }
}

pub(super) fn read(bytes: &[u8]) -> Result<Mesh> {
    let at = At::default();
    let mut de = serde_json::Deserializer::from_slice(bytes);
    let tris = Tris(&at)
        .deserialize(&mut de)
        .and_then(|tris| de.end().map(|()| tris))
        .map_err(|e| {
            let msg = if e.is_data() {
                // The message without serde's " at line L column C" (the location says it).
                let full = e.to_string();
                let end = format!(" at line {} column {}", e.line(), e.column());
                let inner = full.strip_suffix(&end).unwrap_or(&full);
                format!("{}{inner}; {SHAPE}", at.prefix())
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
