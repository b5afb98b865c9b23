//! Lists of points for point queries (`meshbool classify`): text with three numbers per
//! line, or JSON.

use crate::error::{Error, Result};

fn bad(message: String) -> Error {
    Error::Malformed {
        what: "points",
        message,
    }
}

/// Points from text or JSON. Text: one point per line, three numbers separated by spaces,
/// tabs, commas or semicolons (`x y z`, `x,y,z`); blank lines and lines starting with `#`
/// are skipped, and a first line that is not numbers is taken for a header (CSV). JSON: an
/// array of `[x, y, z]` arrays or of `{"x": .., "y": .., "z": ..}` objects. Non-finite
/// numbers, lines of other than three numbers and text that is neither are errors naming
/// the line or the element.
pub fn read_points(bytes: &[u8]) -> Result<Vec<[f64; 3]>> {
    let text = std::str::from_utf8(bytes).map_err(|e| bad(format!("not UTF-8 text: {e}")))?;
    let trimmed = text.trim_start();
    if trimmed.starts_with('[') || trimmed.starts_with('{') {
        from_json(trimmed)
    } else {
        from_lines(text)
    }
}

/// Whether every coordinate of `p` is finite.
fn finite(p: &[f64; 3]) -> bool {
    p.iter().all(|x| x.is_finite())
}

fn from_json(text: &str) -> Result<Vec<[f64; 3]>> {
    let v: serde_json::Value =
        serde_json::from_str(text).map_err(|e| bad(format!("not JSON: {e}")))?;
    let items = v
        .as_array()
        .ok_or_else(|| bad("JSON points must be an array".into()))?;
    items
        .iter()
        .enumerate()
        .map(|(i, item)| {
            let num = |x: Option<&serde_json::Value>| x.and_then(serde_json::Value::as_f64);
            let p = match item {
                serde_json::Value::Array(a) if a.len() == 3 => {
                    [num(a.first()), num(a.get(1)), num(a.get(2))]
                }
                serde_json::Value::Object(o) => [num(o.get("x")), num(o.get("y")), num(o.get("z"))],
                _ => [None; 3],
            };
            match p {
                [Some(x), Some(y), Some(z)] if finite(&[x, y, z]) => Ok([x, y, z]),
                [Some(x), Some(y), Some(z)] => {
                    Err(bad(format!("element {i} is not finite: {:?}", [x, y, z])))
                }
                _ => Err(bad(format!(
                    "element {i} is not [x, y, z] nor {{\"x\", \"y\", \"z\"}}: {item}"
                ))),
            }
        })
        .collect()
}

fn from_lines(text: &str) -> Result<Vec<[f64; 3]>> {
    let mut points = Vec::new();
    let mut seen_data = false;
    for (n, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let tokens: Vec<&str> = line
            .split(|c: char| c.is_whitespace() || c == ',' || c == ';')
            .filter(|t| !t.is_empty())
            .collect();
        let numbers: Vec<Option<f64>> = tokens.iter().map(|t| t.parse().ok()).collect();
        if !seen_data && numbers.iter().any(Option::is_none) {
            seen_data = true; // a header
            continue;
        }
        seen_data = true;
        match numbers.as_slice() {
            [Some(x), Some(y), Some(z)] if finite(&[*x, *y, *z]) => points.push([*x, *y, *z]),
            [Some(_), Some(_), Some(_)] => {
                return Err(bad(format!(
                    "line {}: point {} is not finite: {line:?}",
                    n + 1,
                    points.len()
                )))
            }
            _ => {
                return Err(bad(format!(
                    "line {}: expected three numbers, found {line:?}",
                    n + 1
                )))
            }
        }
    }
    Ok(points)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_csv_and_json_points() {
        let text = b"# points\nx,y,z\n1,2,3\n\n4 5 6\n7\t8;9\n";
        assert_eq!(
            read_points(text).unwrap(),
            [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [7.0, 8.0, 9.0]]
        );
        let json = br#"[[1, 2, 3], {"x": 4, "y": 5.5, "z": -6}]"#;
        assert_eq!(
            read_points(json).unwrap(),
            [[1.0, 2.0, 3.0], [4.0, 5.5, -6.0]]
        );
        assert_eq!(read_points(b"").unwrap(), Vec::<[f64; 3]>::new());
        for (bad_input, says) in [
            (&b"1 2 3\n4 5\n"[..], "line 2"),
            (b"1 2 3\n4 5 x\n", "line 2"),
            (b"1 2 nan\n", "not finite"),
            (b"# x\n1 2 3\n\n4 inf 6\n", "line 4: point 1 is not finite"),
            (b"[[1, 2]]", "element 0"),
            (b"[1, 2", "not JSON"),
            (b"{\"x\": 1}", "must be an array"),
            (b"\xff\xfe", "UTF-8"),
        ] {
            let e = read_points(bad_input).unwrap_err().to_string();
            assert!(e.contains(says), "{e}");
        }
    }
}
