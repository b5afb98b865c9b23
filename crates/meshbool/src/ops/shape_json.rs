//! A [`Shape`] from a JSON object of its parameters: one reader for the CSG documents'
//! primitives and the JavaScript package's `make*` options, with the defaults of
//! `meshbool make`.

use serde_json::{Map, Value};

use super::Shape;

/// How [`Shape::from_json`] reads an object's keys.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShapeKeys {
    /// As CSG documents write them: snake case (`top_radius`), every key given a value.
    Document,
    /// As the JavaScript package takes options: camel case (`topRadius`) or snake case,
    /// `null` read as left out.
    Js,
}

/// Why [`Shape::from_json`] refused an object.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ShapeJsonError {
    /// No shape has this name.
    UnknownShape(String),
    /// The object has a key the shape does not take; `known` lists those it takes, as
    /// the object's spelling writes them.
    UnknownKey {
        /// The key.
        key: String,
        /// The shape's keys.
        known: Vec<&'static str>,
    },
    /// A value is not what its key takes.
    Value {
        /// The key, with an element's index for a list (`cells[1]`).
        key: String,
        /// What it must be, and what it is (`must be a whole number, got 2.5`).
        message: String,
    },
    /// The keys given do not go together (a cube's corners with its size).
    Keys(&'static str),
}

impl std::fmt::Display for ShapeJsonError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ShapeJsonError::UnknownShape(name) => {
                write!(f, "unknown shape `{name}` ({})", Shape::NAMES.join(", "))
            }
            ShapeJsonError::UnknownKey { key, known } => {
                write!(f, "{key}: unknown key (takes {})", known.join(", "))
            }
            ShapeJsonError::Value { key, message } => write!(f, "{key} {message}"),
            ShapeJsonError::Keys(message) => f.write_str(message),
        }
    }
}

impl std::error::Error for ShapeJsonError {}

/// The keys of each shape, as documents spell them.
const KEYS: [(&str, &[&str]); 7] = [
    ("cube", &["size", "center", "min", "max"]),
    ("sphere", &["center", "radius", "segments", "rings"]),
    ("cylinder", &["base", "radius", "height", "segments"]),
    (
        "cone",
        &["base", "radius", "top_radius", "height", "segments"],
    ),
    ("plane", &["center", "width", "depth", "nx", "ny"]),
    ("terrain", &["center", "size", "cells", "relief", "seed"]),
    (
        "pit",
        &["center", "radius", "depth", "benches", "berm", "segments"],
    ),
];

/// A document key as the JavaScript package spells it (`top_radius` → `topRadius`).
fn camel(key: &'static str) -> &'static str {
    match key {
        "top_radius" => "topRadius",
        k => k,
    }
}

/// The object being read, its spelling, and the keys it may hold besides the shape's.
struct Reader<'o> {
    obj: &'o Map<String, Value>,
    keys: ShapeKeys,
}

type Read<T> = std::result::Result<T, ShapeJsonError>;

impl<'o> Reader<'o> {
    /// The value of document key `key` and the key as the object wrote it; `None` when
    /// left out.
    fn get(&self, key: &'static str) -> Option<(&'static str, &'o Value)> {
        let found = |k: &'static str| self.obj.get(k).map(|v| (k, v));
        let v = match self.keys {
            ShapeKeys::Document => found(key),
            ShapeKeys::Js => found(camel(key)).or_else(|| found(key)),
        };
        v.filter(|(_, v)| !(self.keys == ShapeKeys::Js && v.is_null()))
    }

    fn number(&self, key: &'static str, default: f64) -> Read<f64> {
        match self.get(key) {
            None => Ok(default),
            Some((k, v)) => number(v).ok_or_else(|| wrong(k, "a number", v)),
        }
    }

    /// `N` numbers: a list of them, or, with `one`, one number for all.
    fn numbers<const N: usize>(
        &self,
        key: &'static str,
        default: [f64; N],
        one: bool,
    ) -> Read<[f64; N]> {
        let Some((k, v)) = self.get(key) else {
            return Ok(default);
        };
        if let Some(x) = number(v).filter(|_| one) {
            return Ok([x; N]);
        }
        let list = v.as_array().filter(|l| l.len() == N).ok_or_else(|| {
            let what = if one {
                format!("a number or an array of {N} numbers")
            } else {
                format!("an array of {N} numbers")
            };
            wrong(k, &what, v)
        })?;
        let mut out = [0.0; N];
        for (i, x) in list.iter().enumerate() {
            out[i] = number(x).ok_or_else(|| wrong(&format!("{k}[{i}]"), "a number", x))?;
        }
        Ok(out)
    }

    /// A whole number ≥ 0 that fits `T` (the `u32` counts, the `u64` seed).
    fn whole<T: TryFrom<u64>>(&self, key: &'static str, default: T) -> Read<T> {
        match self.get(key) {
            None => Ok(default),
            Some((k, v)) => whole(v).ok_or_else(|| wrong(k, "a whole number ≥ 0", v)),
        }
    }

    /// `N` whole numbers: a list of them, or one for all.
    fn wholes<const N: usize>(&self, key: &'static str, default: [u32; N]) -> Read<[u32; N]> {
        let Some((k, v)) = self.get(key) else {
            return Ok(default);
        };
        if let Some(n) = whole(v) {
            return Ok([n; N]);
        }
        let what = format!("a whole number ≥ 0 or an array of {N} of them");
        let list = v
            .as_array()
            .filter(|l| l.len() == N)
            .ok_or_else(|| wrong(k, &what, v))?;
        let mut out = [0; N];
        for (i, x) in list.iter().enumerate() {
            out[i] =
                whole(x).ok_or_else(|| wrong(&format!("{k}[{i}]"), "a whole number ≥ 0", x))?;
        }
        Ok(out)
    }
}

fn number(v: &Value) -> Option<f64> {
    v.as_f64().filter(|x| x.is_finite())
}

fn whole<T: TryFrom<u64>>(v: &Value) -> Option<T> {
    v.as_u64().and_then(|n| T::try_from(n).ok())
}

fn wrong(key: &str, what: &str, got: &Value) -> ShapeJsonError {
    ShapeJsonError::Value {
        key: key.to_string(),
        message: format!("must be {what}, got {got}"),
    }
}

impl Shape {
    /// The names [`Shape::from_json`] knows: `cube`, `sphere`, `cylinder`, `cone`, `plane`,
    /// `terrain`, `pit`.
    pub const NAMES: [&'static str; 7] = [
        "cube", "sphere", "cylinder", "cone", "plane", "terrain", "pit",
    ];

    /// The keys shape `name` takes, as documents spell them; `None` for an unknown name.
    pub fn keys(name: &str) -> Option<&'static [&'static str]> {
        KEYS.iter().find(|(n, _)| *n == name).map(|(_, k)| *k)
    }

    /// Shape `name` from the JSON object of its parameters, every one optional with the
    /// default of `meshbool make`: `cube` (`center` `[0, 0, 0]` and `size` 1, one number or
    /// three; or `min` and `max` together), `sphere` (`center` `[0, 0, 0]`, `radius` 1,
    /// `segments` 32, `rings` 16), `cylinder` (`base` `[0, 0, 0]`, `radius` 1, `height` 1,
    /// `segments` 32), `cone` (as the cylinder, with `top_radius` 0), `plane` (`center`
    /// `[0, 0, 0]`, `width` 1, `depth` 1, `nx` 1, `ny` 1), `terrain` and `pit` (the defaults
    /// of [`Shape::TERRAIN`] and [`Shape::PIT`]; `size`, `cells` and the pit's `radius`
    /// one number for both axes or two). Keys in `others` belong to the caller and are
    /// left alone (a CSG node's `name`, `role`, `transform`); any other key is refused.
    /// The parameters' ranges are checked where the shape is made ([`Shape::mesh`]).
    pub fn from_json(
        name: &str,
        obj: &Map<String, Value>,
        keys: ShapeKeys,
        others: &[&str],
    ) -> std::result::Result<Shape, ShapeJsonError> {
        let own =
            Shape::keys(name).ok_or_else(|| ShapeJsonError::UnknownShape(name.to_string()))?;
        let spelled: Vec<&'static str> = match keys {
            ShapeKeys::Document => own.to_vec(),
            ShapeKeys::Js => own.iter().map(|k| camel(k)).collect(),
        };
        let takes = |k: &str| own.contains(&k) || spelled.contains(&k) || others.contains(&k);
        if let Some(k) = obj.keys().find(|k| !takes(k)) {
            return Err(ShapeJsonError::UnknownKey {
                key: k.clone(),
                known: spelled,
            });
        }
        let r = Reader { obj, keys };
        let origin = [0.0; 3];
        Ok(match name {
            "cube" => {
                let (lo, hi) = (r.get("min"), r.get("max"));
                let (min, max) = if lo.is_some() || hi.is_some() {
                    if r.get("center").is_some() || r.get("size").is_some() {
                        return Err(ShapeJsonError::Keys(
                            "a cube takes min and max, or size and center, not both",
                        ));
                    }
                    if lo.is_none() || hi.is_none() {
                        return Err(ShapeJsonError::Keys("a cube's min and max go together"));
                    }
                    (
                        r.numbers("min", origin, false)?,
                        r.numbers("max", origin, false)?,
                    )
                } else {
                    let c = r.numbers("center", origin, false)?;
                    let s = r.numbers("size", [1.0; 3], true)?;
                    (
                        std::array::from_fn(|k| c[k] - s[k] / 2.0),
                        std::array::from_fn(|k| c[k] + s[k] / 2.0),
                    )
                };
                Shape::Cube { min, max }
            }
            "sphere" => Shape::Sphere {
                center: r.numbers("center", origin, false)?,
                radius: r.number("radius", 1.0)?,
                segments: r.whole("segments", 32)?,
                rings: r.whole("rings", 16)?,
            },
            "cylinder" => Shape::Cylinder {
                base: r.numbers("base", origin, false)?,
                radius: r.number("radius", 1.0)?,
                height: r.number("height", 1.0)?,
                segments: r.whole("segments", 32)?,
            },
            "cone" => Shape::Cone {
                base: r.numbers("base", origin, false)?,
                radius: r.number("radius", 1.0)?,
                top_radius: r.number("top_radius", 0.0)?,
                height: r.number("height", 1.0)?,
                segments: r.whole("segments", 32)?,
            },
            "plane" => Shape::Plane {
                center: r.numbers("center", origin, false)?,
                width: r.number("width", 1.0)?,
                depth: r.number("depth", 1.0)?,
                nx: r.whole("nx", 1)?,
                ny: r.whole("ny", 1)?,
            },
            "terrain" => match Shape::TERRAIN {
                Shape::Terrain {
                    center,
                    size,
                    cells,
                    relief,
                    seed,
                } => Shape::Terrain {
                    center: r.numbers("center", center, false)?,
                    size: r.numbers("size", size, true)?,
                    cells: r.wholes("cells", cells)?,
                    relief: r.number("relief", relief)?,
                    seed: r.whole("seed", seed)?,
                },
                other => other,
            },
            _ => match Shape::PIT {
                Shape::Pit {
                    center,
                    radius,
                    depth,
                    benches,
                    berm,
                    segments,
                } => Shape::Pit {
                    center: r.numbers("center", center, false)?,
                    radius: r.numbers("radius", radius, true)?,
                    depth: r.number("depth", depth)?,
                    benches: r.whole("benches", benches)?,
                    berm: r.number("berm", berm)?,
                    segments: r.whole("segments", segments)?,
                },
                other => other,
            },
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn obj(text: &str) -> Map<String, Value> {
        match serde_json::from_str(text) {
            Ok(Value::Object(m)) => m,
            other => panic!("not an object: {other:?}"),
        }
    }

    #[test]
    fn every_shape_takes_the_defaults_of_make() {
        let none = Map::new();
        let counts = Shape::NAMES.map(|n| {
            Shape::from_json(n, &none, ShapeKeys::Document, &[])
                .ok()
                .and_then(|s| s.mesh().ok())
                .map_or(0, |m| m.triangle_count())
        });
        assert_eq!(counts, [12, 960, 128, 64, 2, 20000, 1216]);
        let t = Shape::from_json("terrain", &none, ShapeKeys::Js, &[]);
        assert_eq!(t, Ok(Shape::TERRAIN));
        assert_eq!(
            Shape::from_json("pit", &none, ShapeKeys::Document, &[]),
            Ok(Shape::PIT)
        );
    }

    #[test]
    fn the_two_spellings_read_the_same_cone() {
        let cone = |text: &str, keys| Shape::from_json("cone", &obj(text), keys, &[]);
        let want = Ok(Shape::Cone {
            base: [0.0; 3],
            radius: 2.0,
            top_radius: 0.5,
            height: 1.0,
            segments: 8,
        });
        let snake = r#"{"radius": 2, "top_radius": 0.5, "segments": 8}"#;
        let camel = r#"{"radius": 2, "topRadius": 0.5, "segments": 8}"#;
        assert_eq!(cone(snake, ShapeKeys::Document), want);
        assert_eq!(cone(snake, ShapeKeys::Js), want);
        assert_eq!(cone(camel, ShapeKeys::Js), want);
        // Documents keep to their spelling.
        let e = cone(camel, ShapeKeys::Document).unwrap_err();
        assert_eq!(
            e.to_string(),
            "topRadius: unknown key (takes base, radius, top_radius, height, segments)"
        );
        // null: left out in JavaScript, a wrong value in a document.
        let null = r#"{"radius": null}"#;
        assert!(
            matches!(cone(null, ShapeKeys::Js), Ok(Shape::Cone { radius, .. }) if radius == 1.0)
        );
        assert_eq!(
            cone(null, ShapeKeys::Document).unwrap_err().to_string(),
            "radius must be a number, got null"
        );
    }

    #[test]
    fn errors_name_the_key_and_what_it_takes() {
        let read = |name: &str, text: &str| {
            Shape::from_json(name, &obj(text), ShapeKeys::Document, &["name"])
                .unwrap_err()
                .to_string()
        };
        assert_eq!(
            read("terrain", r#"{"cells": [4, 2.5]}"#),
            "cells[1] must be a whole number ≥ 0, got 2.5"
        );
        assert_eq!(
            read("terrain", r#"{"cells": "many"}"#),
            r#"cells must be a whole number ≥ 0 or an array of 2 of them, got "many""#
        );
        assert_eq!(
            read("pit", r#"{"radius": [1, 2, 3]}"#),
            "radius must be a number or an array of 2 numbers, got [1,2,3]"
        );
        assert_eq!(
            read("cylinder", r#"{"base": [0, "x", 0]}"#),
            r#"base[1] must be a number, got "x""#
        );
        assert_eq!(
            read("cube", r#"{"min": [0, 0, 0], "size": 2}"#),
            "a cube takes min and max, or size and center, not both"
        );
        assert_eq!(
            read("cube", r#"{"max": [1, 1, 1]}"#),
            "a cube's min and max go together"
        );
        assert_eq!(
            read("sphere", r#"{"radus": 2}"#),
            "radus: unknown key (takes center, radius, segments, rings)"
        );
        assert_eq!(
            read("torus", "{}"),
            "unknown shape `torus` (cube, sphere, cylinder, cone, plane, terrain, pit)"
        );
        // The caller's own keys pass.
        assert!(Shape::from_json(
            "sphere",
            &obj(r#"{"name": "ball"}"#),
            ShapeKeys::Document,
            &["name"]
        )
        .is_ok());
    }
}
