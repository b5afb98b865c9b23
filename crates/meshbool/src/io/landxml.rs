//! LandXML 1.2 TIN surfaces (`.xml`), the exchange format of civil and survey software.
//!
//! Read: every `LandXML/Surfaces/Surface/Definition` (any `surfType`), concatenated in file
//! order. Its `Pnts/P` elements are points `<P id="7">northing easting elevation</P>`:
//! **the standard's order is northing (`y`) first, then easting (`x`)**, so `x` is the
//! second number and `y` the first. Ids are integers of the writer's choosing, local to
//! their surface, and each point becomes a vertex in file order. Its `Faces/F` elements are
//! triangles by point ids (`<F>7 3 9</F>`; four ids make a quad, split into two
//! triangles); a face with `i="1"` (or `i="true"`) is invisible (a hole, or outside the
//! surface's boundary) and skipped; other attributes (`n` neighbours, `b` boundary) are
//! ignored. Everything else (units, alignments, breaklines, source data, feature
//! elements) is skipped. Element names are matched without their namespace prefix.
//!
//! Errors name the line: a point without three numbers or without an integer `id`, a face
//! naming an id its surface does not define, an id defined twice, non-finite numbers,
//! malformed XML, and a file that ends before its elements are closed (truncated).
//!
//! Written as LandXML 1.2 with one `Surface` named `meshbool` (`surfType="TIN"`): every
//! vertex a `P` with id = index + 1 in northing easting elevation order, every triangle an
//! `F`, numbers in the shortest form that reads back to the same `f64`. The root carries
//! the date and time of writing (UTC), as the schema asks, and metric units: meshbool's
//! coordinates carry no unit, and metres are what mining and survey data mostly use.
//!
//! The XML is parsed with `quick-xml` (a pull parser: no tree is built).

use std::io::Write;

use quick_xml::events::{BytesStart, Event};
use quick_xml::Reader;
use rustc_hash::FxHashMap;

use super::{parse_f64, tokens, Format, Out};
use crate::error::{Error, Location, Result};
use crate::Mesh;

const FMT: Format = Format::LandXml;

/// Content sniffing: an XML text with a `<LandXML` element near its start.
pub(super) fn looks_like(text: &[u8]) -> bool {
    let text = text.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(text);
    let head = &text[..text.len().min(4096)];
    head.trim_ascii_start().starts_with(b"<") && head.windows(8).any(|w| w == b"<LandXML")
}

/// What a read met besides the mesh (for the tests; nothing of it is public).
#[derive(Debug, Default, PartialEq)]
pub(super) struct Counts {
    /// `Surface` elements read.
    pub surfaces: usize,
    /// Faces skipped as invisible (`i="1"`).
    pub invisible_faces: usize,
}

/// The elements that matter, by where they are.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Tag {
    LandXml,
    Surfaces,
    Surface,
    Definition,
    Pnts,
    P,
    Faces,
    F,
    Other,
}

impl Tag {
    fn child(self, name: &str) -> Tag {
        match (self, name) {
            (Tag::LandXml, "Surfaces") => Tag::Surfaces,
            (Tag::Surfaces, "Surface") => Tag::Surface,
            (Tag::Surface, "Definition") => Tag::Definition,
            (Tag::Definition, "Pnts") => Tag::Pnts,
            (Tag::Definition, "Faces") => Tag::Faces,
            (Tag::Pnts, "P") => Tag::P,
            (Tag::Faces, "F") => Tag::F,
            _ => Tag::Other,
        }
    }
}

fn err(line: usize, message: impl Into<String>) -> Error {
    Error::parse(FMT, Location::Line(line), message)
}

fn lossy(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// Line numbers of byte offsets, counted forward from the last one asked for.
struct Lines<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: usize,
}

impl Lines<'_> {
    fn at(&mut self, pos: u64) -> usize {
        let pos = (pos as usize).min(self.bytes.len());
        if pos < self.pos {
            self.pos = 0;
            self.line = 1;
        }
        self.line += self.bytes[self.pos..pos]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        self.pos = pos;
        self.line
    }
}

/// The reader's state: the mesh so far and the surface being read.
struct Tin {
    positions: Vec<[f64; 3]>,
    triangles: Vec<[u32; 3]>,
    counts: Counts,
    /// Open elements with the line each starts on.
    stack: Vec<(Tag, usize)>,
    /// The text of the open `P` or `F`.
    text: Vec<u8>,
    /// The open `P`'s id.
    id: i64,
    /// Whether the open `F` is invisible.
    invisible: bool,
    /// The surface's point ids and its faces (ids, how many, line), resolved at its end.
    ids: FxHashMap<i64, u32>,
    faces: Vec<([i64; 4], usize, usize)>,
}

impl Tin {
    fn open(&mut self, e: &BytesStart<'_>, line: usize) -> Result<()> {
        let name = e.local_name();
        let name = name.as_ref();
        let tag = match self.stack.last() {
            Some(&(parent, _)) => parent.child(name),
            None if name == "LandXML" => Tag::LandXml,
            None => {
                return Err(err(
                    line,
                    format!("the root element is <{name}>, not <LandXML>"),
                ))
            }
        };
        match tag {
            Tag::Surface => {
                self.ids.clear();
                self.faces.clear();
                self.counts.surfaces += 1;
            }
            Tag::P => {
                let id =
                    attribute(e, "id", line)?.ok_or_else(|| err(line, "a point <P> has no id"))?;
                self.id = id.trim().parse().map_err(|_| {
                    err(
                        line,
                        format!("a point's id must be an integer, found {id:?}"),
                    )
                })?;
                self.text.clear();
            }
            Tag::F => {
                self.invisible =
                    attribute(e, "i", line)?.is_some_and(|i| matches!(i.trim(), "1" | "true"));
                self.text.clear();
            }
            _ => {}
        }
        self.stack.push((tag, line));
        Ok(())
    }

    fn close(&mut self) -> Result<()> {
        let Some((tag, line)) = self.stack.pop() else {
            return Ok(());
        };
        match tag {
            Tag::P => {
                let mut nez = [0.0; 3];
                let mut n = 0;
                for t in tokens(&self.text) {
                    if n < 3 {
                        nez[n] = parse_f64(t, FMT, line)?;
                    }
                    n += 1;
                }
                if n != 3 {
                    return Err(err(
                        line,
                        format!(
                            "point {} needs northing, easting and elevation; found {n} numbers in {:?}",
                            self.id,
                            lossy(self.text.trim_ascii())
                        ),
                    ));
                }
                let index = u32::try_from(self.positions.len())
                    .ok()
                    .filter(|&i| i < u32::MAX)
                    .ok_or_else(|| err(line, "more points than a mesh can index"))?;
                if self.ids.insert(self.id, index).is_some() {
                    return Err(err(
                        line,
                        format!("point id {} is defined twice in this surface", self.id),
                    ));
                }
                self.positions.push([nez[1], nez[0], nez[2]]);
            }
            Tag::F => {
                let mut ids = [0i64; 4];
                let mut n = 0;
                for t in tokens(&self.text) {
                    let id = std::str::from_utf8(t)
                        .ok()
                        .and_then(|s| s.parse().ok())
                        .ok_or_else(|| {
                            err(
                                line,
                                format!(
                                    "a face's point id must be an integer, found {:?}",
                                    lossy(t)
                                ),
                            )
                        })?;
                    if n < 4 {
                        ids[n] = id;
                    }
                    n += 1;
                }
                if n != 3 && n != 4 {
                    return Err(err(
                        line,
                        format!("a face needs 3 point ids (or 4 for a quad), found {n}"),
                    ));
                }
                if self.invisible {
                    self.counts.invisible_faces += 1;
                } else {
                    self.faces.push((ids, n, line));
                }
            }
            Tag::Surface => {
                for &(ids, n, at) in &self.faces {
                    let mut poly = [0u32; 4];
                    for (v, id) in poly.iter_mut().zip(&ids[..n]) {
                        *v = *self.ids.get(id).ok_or_else(|| {
                            err(
                                at,
                                format!("face refers to point id {id}, which this surface does not define"),
                            )
                        })?;
                    }
                    super::push_fan(&poly[..n], &mut self.triangles);
                }
            }
            _ => {}
        }
        Ok(())
    }

    /// True inside a `P` or `F`, whose text is collected.
    fn in_text(&self) -> bool {
        matches!(self.stack.last(), Some((Tag::P | Tag::F, _)))
    }
}

/// The value of attribute `key` (without namespace prefix) of `e`.
fn attribute(e: &BytesStart<'_>, key: &str, line: usize) -> Result<Option<String>> {
    for a in e.attributes() {
        let a = a.map_err(|x| err(line, format!("malformed attribute: {x}")))?;
        if a.key.local_name().as_ref() == key {
            return Ok(Some(a.value.into_owned()));
        }
    }
    Ok(None)
}

pub(super) fn read(bytes: &[u8]) -> Result<Mesh> {
    Ok(read_counted(bytes)?.0)
}

pub(super) fn read_counted(bytes: &[u8]) -> Result<(Mesh, Counts)> {
    let mut reader = Reader::from_reader(bytes);
    let mut lines = Lines {
        bytes,
        pos: 0,
        line: 1,
    };
    let mut tin = Tin {
        positions: Vec::new(),
        triangles: Vec::new(),
        counts: Counts::default(),
        stack: Vec::new(),
        text: Vec::new(),
        id: 0,
        invisible: false,
        ids: FxHashMap::default(),
        faces: Vec::new(),
    };
    let mut seen_root = false;
    loop {
        let start = reader.buffer_position();
        let event = reader.read_event().map_err(|e| {
            let at = Lines {
                bytes,
                pos: 0,
                line: 1,
            }
            .at(reader.error_position());
            err(at, format!("malformed XML: {e}"))
        })?;
        match event {
            Event::Start(e) => {
                let line = lines.at(start);
                tin.open(&e, line)?;
                seen_root = true;
            }
            Event::Empty(e) => {
                let line = lines.at(start);
                tin.open(&e, line)?;
                seen_root = true;
                tin.close()?;
            }
            Event::End(_) => tin.close()?,
            Event::Text(t) if tin.in_text() => tin.text.extend_from_slice(t.as_bytes()),
            Event::CData(t) if tin.in_text() => tin.text.extend_from_slice(t.as_bytes()),
            Event::GeneralRef(r) if tin.in_text() => {
                let line = lines.at(start);
                return Err(err(
                    line,
                    format!("unexpected entity reference &{}; among numbers", &*r),
                ));
            }
            Event::Eof => break,
            _ => {}
        }
    }
    if let Some(&(_, line)) = tin.stack.first() {
        let &(_, inner) = tin.stack.last().unwrap_or(&(Tag::Other, line));
        return Err(err(
            lines.at(bytes.len() as u64),
            format!(
                "the file ends before the element opened at line {inner} is closed: truncated?"
            ),
        ));
    }
    if !seen_root {
        return Err(Error::parse(FMT, Location::Whole, "no <LandXML> element"));
    }
    if tin.counts.surfaces == 0 {
        return Err(Error::parse(
            FMT,
            Location::Whole,
            "no <Surface> in <Surfaces>: nothing to read",
        ));
    }
    Ok((
        Mesh::new_unchecked(tin.positions, tin.triangles),
        tin.counts,
    ))
}

pub(super) fn write(out: &mut impl Write, mesh: &Mesh) -> Result<()> {
    let now = utc_now();
    let mut o = Out::new(out);
    o.bytes(
        b"<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
          <LandXML xmlns=\"http://www.landxml.org/schema/LandXML-1.2\" \
          xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" \
          xsi:schemaLocation=\"http://www.landxml.org/schema/LandXML-1.2 \
          http://www.landxml.org/schema/LandXML-1.2/LandXML-1.2.xsd\" \
          version=\"1.2\" date=\"",
    )
    .bytes(now.iso_date().as_bytes())
    .bytes(b"\" time=\"")
    .bytes(now.iso_time().as_bytes())
    .bytes(
        b"\">\n\
          \x20 <Units>\n\
          \x20   <Metric linearUnit=\"meter\" areaUnit=\"squareMeter\" volumeUnit=\"cubicMeter\" \
          temperatureUnit=\"celsius\" pressureUnit=\"milliBars\"/>\n\
          \x20 </Units>\n\
          \x20 <Application name=\"meshbool\" version=\"",
    )
    .bytes(env!("CARGO_PKG_VERSION").as_bytes())
    .bytes(
        b"\"/>\n\
          \x20 <Surfaces>\n\
          \x20   <Surface name=\"meshbool\">\n\
          \x20     <Definition surfType=\"TIN\">\n\
          \x20       <Pnts>\n",
    );
    for (i, p) in mesh.positions.iter().enumerate() {
        o.bytes(b"          <P id=\"")
            .int(i as u64 + 1)
            .bytes(b"\">")
            .f64(p[1])
            .bytes(b" ")
            .f64(p[0])
            .bytes(b" ")
            .f64(p[2])
            .bytes(b"</P>\n")
            .record_done()?;
    }
    o.bytes(b"        </Pnts>\n        <Faces>\n");
    for t in &mesh.triangles {
        o.bytes(b"          <F>");
        for (k, &i) in t.iter().enumerate() {
            if k > 0 {
                o.bytes(b" ");
            }
            o.int(u64::from(i) + 1);
        }
        o.bytes(b"</F>\n").record_done()?;
    }
    o.bytes(
        b"        </Faces>\n\
          \x20     </Definition>\n\
          \x20   </Surface>\n\
          \x20 </Surfaces>\n\
          </LandXML>\n",
    );
    o.finish()
}

/// A UTC date and time, to the second.
pub(super) struct UtcNow {
    year: i64,
    month: u32,
    day: u32,
    seconds_of_day: u32,
}

/// The current date and time (UTC); the epoch when the clock is before it.
pub(super) fn utc_now() -> UtcNow {
    let secs = web_time::SystemTime::now()
        .duration_since(web_time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    utc_from_unix(secs)
}

/// The UTC date and time `secs` seconds after 1970-01-01T00:00:00.
pub(super) fn utc_from_unix(secs: u64) -> UtcNow {
    let days = (secs / 86_400) as i64;
    // Days since 0000-03-01 in the proleptic Gregorian calendar, whose 400-year cycles
    // have 146_097 days; counting years from March puts the leap day last.
    let z = days + 719_468;
    let cycle = z.div_euclid(146_097);
    let day_of_cycle = z.rem_euclid(146_097);
    let year_of_cycle =
        (day_of_cycle - day_of_cycle / 1460 + day_of_cycle / 36_524 - day_of_cycle / 146_096) / 365;
    let day_of_year =
        day_of_cycle - (365 * year_of_cycle + year_of_cycle / 4 - year_of_cycle / 100);
    let month_from_march = (5 * day_of_year + 2) / 153;
    let day = (day_of_year - (153 * month_from_march + 2) / 5 + 1) as u32;
    let month = if month_from_march < 10 {
        month_from_march + 3
    } else {
        month_from_march - 9
    } as u32;
    let year = year_of_cycle + cycle * 400 + i64::from(month <= 2);
    UtcNow {
        year,
        month,
        day,
        seconds_of_day: (secs % 86_400) as u32,
    }
}

impl UtcNow {
    /// `YYYY-MM-DD` (`xs:date`).
    pub(super) fn iso_date(&self) -> String {
        format!("{:04}-{:02}-{:02}", self.year, self.month, self.day)
    }

    /// `hh:mm:ss` (`xs:time`).
    pub(super) fn iso_time(&self) -> String {
        let s = self.seconds_of_day;
        format!("{:02}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
    }

    /// `dd-Mmm-yy`, as Surpac writes dates.
    pub(super) fn surpac_date(&self) -> String {
        const MONTHS: [&str; 12] = [
            "Jan", "Feb", "Mar", "Apr", "May", "Jun", "Jul", "Aug", "Sep", "Oct", "Nov", "Dec",
        ];
        let month = MONTHS[(self.month as usize).clamp(1, 12) - 1];
        format!("{:02}-{month}-{:02}", self.day, self.year.rem_euclid(100))
    }
}
