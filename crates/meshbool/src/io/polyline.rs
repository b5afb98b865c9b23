//! Writing polylines (intersection curves): OBJ `l` elements, DXF 3D `POLYLINE`s, JSON.

use std::io::Write;

use super::{Format, Out};
use crate::error::{Error, Location, Result};
use crate::intersect::PolylineXyz;

/// Writes `lines` in `format`: OBJ (`v` and `l`; a closed line repeats its first index),
/// DXF (3D `POLYLINE`, flag 1 when closed) or JSON (`[{"closed":..,"points":[[x,y,z],..]}]`).
/// Coordinates use the shortest text that reads back to the same `f64`. Any other format
/// (a mesh format) is [`Error::InvalidParameter`].
pub fn write_polylines(out: &mut impl Write, lines: &[PolylineXyz], format: Format) -> Result<()> {
    check_finite(lines)?;
    let mut o = Out::new(out);
    match format {
        Format::Obj => write_obj(&mut o, lines)?,
        Format::Dxf => write_dxf(&mut o, lines)?,
        Format::JsonSoup | Format::JsonKirra => write_json(&mut o, lines)?,
        other => {
            return Err(Error::InvalidParameter(format!(
                "polylines cannot be written as {other}, only as OBJ (.obj), DXF (.dxf) or \
                 JSON (.json)"
            )))
        }
    }
    o.finish()
}

/// An error naming the first line with a non-finite coordinate, if any.
fn check_finite(lines: &[PolylineXyz]) -> Result<()> {
    match lines
        .iter()
        .position(|l| l.points.iter().flatten().any(|x| !x.is_finite()))
    {
        Some(i) => Err(Error::invalid(
            Location::Triangle(i),
            "non-finite polyline coordinate",
        )),
        None => Ok(()),
    }
}

/// OBJ: every line's points as `v` records, then one `l` record per line (a closed line
/// repeats its first index).
fn write_obj<W: Write>(o: &mut Out<'_, W>, lines: &[PolylineXyz]) -> Result<()> {
    o.bytes(b"# meshbool polylines\n");
    for l in lines {
        for p in &l.points {
            o.obj_vertex(p);
            o.record_done()?;
        }
    }
    let mut base = 1u64;
    for l in lines {
        o.bytes(b"l");
        let n = l.points.len() as u64;
        for k in 0..n {
            o.bytes(b" ").int(base + k);
        }
        if l.closed && n > 0 {
            o.bytes(b" ").int(base);
        }
        o.bytes(b"\n").record_done()?;
        base += n;
    }
    Ok(())
}

/// DXF (R12): one 3D `POLYLINE` per line (flag 8, plus 1 when closed) with its `VERTEX`
/// records, in the `ENTITIES` section.
fn write_dxf<W: Write>(o: &mut Out<'_, W>, lines: &[PolylineXyz]) -> Result<()> {
    o.bytes(b"0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1009\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n");
    for l in lines {
        o.bytes(b"0\nPOLYLINE\n8\n0\n66\n1\n10\n0\n20\n0\n30\n0\n70\n")
            .int(8 + u64::from(l.closed))
            .bytes(b"\n");
        for p in &l.points {
            o.bytes(b"0\nVERTEX\n8\n0\n10\n")
                .f64(p[0])
                .bytes(b"\n20\n")
                .f64(p[1]);
            o.bytes(b"\n30\n").f64(p[2]).bytes(b"\n70\n32\n");
            o.record_done()?;
        }
        o.bytes(b"0\nSEQEND\n8\n0\n");
    }
    o.bytes(b"0\nENDSEC\n0\nEOF\n");
    Ok(())
}

/// JSON: `[{"closed":..,"points":[[x,y,z],..]}, ..]`, one line per polyline.
fn write_json<W: Write>(o: &mut Out<'_, W>, lines: &[PolylineXyz]) -> Result<()> {
    o.bytes(b"[");
    for (i, l) in lines.iter().enumerate() {
        o.bytes(if i == 0 { b"\n" } else { b",\n" });
        o.bytes(if l.closed {
            b"{\"closed\":true,\"points\":["
        } else {
            b"{\"closed\":false,\"points\":["
        });
        for (k, p) in l.points.iter().enumerate() {
            o.bytes(if k == 0 { b"[" } else { b",[" });
            o.coords(p, b",").bytes(b"]");
            o.record_done()?;
        }
        o.bytes(b"]}");
    }
    o.bytes(b"\n]\n");
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines() -> Vec<PolylineXyz> {
        vec![
            PolylineXyz {
                points: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.1]],
                closed: true,
            },
            PolylineXyz {
                points: vec![[478_614.7, 6_772_313.84, 0.1 + 0.2], [5.0, 6.0, 7.0]],
                closed: false,
            },
        ]
    }

    fn text(f: Format) -> String {
        let mut out = Vec::new();
        write_polylines(&mut out, &lines(), f).unwrap();
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn obj_lines_close_by_repeating_the_first_index() {
        let t = text(Format::Obj);
        assert!(t.contains("\nl 1 2 3 1\nl 4 5\n"), "{t}");
        assert!(t.contains("v 478614.7 6772313.84 0.30000000000000004\n"));
    }

    #[test]
    fn json_round_trips_coordinates() {
        let v: serde_json::Value = serde_json::from_str(&text(Format::JsonSoup)).unwrap();
        assert_eq!(v[0]["closed"], true);
        assert_eq!(v[1]["points"][0][2].as_f64(), Some(0.1 + 0.2));
    }

    #[test]
    fn dxf_has_closed_flag_and_vertices() {
        let t = text(Format::Dxf);
        assert_eq!(t.matches("0\nPOLYLINE\n").count(), 2);
        assert_eq!(t.matches("0\nVERTEX\n").count(), 5);
        assert!(t.contains("70\n9\n") && t.contains("70\n8\n"));
        assert!(t.ends_with("0\nEOF\n"));
        assert!(write_polylines(&mut Vec::new(), &lines(), Format::StlBinary).is_err());
    }
}
