//! Reading and writing meshes: STL (binary and ASCII), OBJ, PLY (ASCII, binary little and
//! big endian), OFF, DXF (3DFACE and polyface meshes), JSON triangle soups, binary glTF
//! (`.glb`), and the surface formats of mining and geology software: GOCAD TSurf (`.ts`),
//! Surpac DTM (`.dtm` with its string file `.str`) and LandXML 1.2 TIN surfaces (`.xml`).
//!
//! Everything is read into `f64`. Formats that store corners per triangle (STL, DXF 3DFACE,
//! JSON soups) are welded on read where positions are exactly equal ([`crate::weld_exact`]).
//! Readers never panic: malformed content gives [`Error::Parse`] with the line or byte
//! where it went wrong; NaN/infinite coordinates and out-of-range indices are errors.
//!
//! Writers use the shortest decimal form that reads back to the same `f64` (text formats)
//! or `f64` fields (PLY), so positions round-trip bit-exactly, except binary STL, which
//! stores `f32` by definition, and glTF, which stores `f32` offsets from an `f64` origin.

use std::fs;
use std::io::{BufWriter, Write};
use std::path::Path;

use crate::error::{Error, Location, Result};
use crate::Mesh;

mod dxf;
mod glb;
#[cfg(feature = "mining-formats")]
mod gocad;
mod json;
#[cfg(feature = "mining-formats")]
mod landxml;
mod obj;
mod off;
mod ply;
mod points;
mod polyline;
mod stl;
#[cfg(feature = "mining-formats")]
mod surpac;

#[doc(no_inline)]
pub use crate::format::Format;
pub use points::read_points;
pub use polyline::write_polylines;
#[cfg(feature = "mining-formats")]
pub use surpac::{read_surpac_dtm, write_surpac_dtm};

/// The format of `bytes`, from the content, with `hint` (a format from the file name)
/// deciding between families the content cannot tell apart. STL's binary/ASCII encoding
/// and PLY's encoding always come from the content, and so does glTF's binary container
/// (its magic `glTF`). `None` when nothing fits.
pub fn detect_format(bytes: &[u8], hint: Option<Format>) -> Option<Format> {
    if glb::looks_like(bytes) {
        return Some(Format::Glb);
    }
    if bytes.starts_with(b"ply") {
        return ply::encoding(bytes).or(Some(Format::PlyAscii));
    }
    match hint {
        Some(family) => Some(format_in_family(bytes, family)),
        None => format_from_content(bytes),
    }
}

/// The format of `bytes` within the family of `hint` (STL, OBJ, PLY, DXF, JSON or glTF): STL's
/// encoding from the content, the family's first format otherwise.
fn format_in_family(bytes: &[u8], hint: Format) -> Format {
    match hint {
        Format::StlBinary | Format::StlAscii => stl::encoding(bytes),
        Format::Obj => Format::Obj,
        Format::PlyAscii | Format::PlyBinaryLe | Format::PlyBinaryBe => Format::PlyAscii,
        Format::Dxf => Format::Dxf,
        Format::JsonSoup | Format::JsonKirra => Format::JsonSoup,
        Format::Glb => Format::Glb,
        Format::GocadTs => Format::GocadTs,
        Format::SurpacDtm => Format::SurpacDtm,
        Format::LandXml => Format::LandXml,
        Format::Off => Format::Off,
    }
}

/// The format of `bytes` from the content alone (no PLY header): binary STL by its
/// size, then by the first text: `solid` (ASCII STL), a JSON bracket, `GOCAD TSurf`, a
/// `<LandXML` element, Surpac's `OBJECT`/`TRISOLATION` lines, an `OFF` header, DXF group
/// codes, OBJ records. `None` when nothing fits.
fn format_from_content(bytes: &[u8]) -> Option<Format> {
    if stl::is_binary(bytes) {
        return Some(Format::StlBinary);
    }
    let text = bytes.trim_ascii_start();
    if text.starts_with(b"solid") {
        return Some(stl::encoding(bytes)); // binary when a wrong count is all that is wrong
    }
    if text.starts_with(b"[") || text.starts_with(b"{") {
        return Some(Format::JsonSoup);
    }
    #[cfg(feature = "mining-formats")]
    {
        if gocad::looks_like(text) {
            return Some(Format::GocadTs);
        }
        if landxml::looks_like(text) {
            return Some(Format::LandXml);
        }
        if surpac::looks_like(text) {
            return Some(Format::SurpacDtm);
        }
    }
    if off::looks_like(text) {
        return Some(Format::Off);
    }
    if dxf::looks_like(text) {
        return Some(Format::Dxf);
    }
    if obj::looks_like(bytes) {
        return Some(Format::Obj);
    }
    None
}

/// The error for a format left out of this build (the `mining-formats` feature, off in
/// the WebAssembly package to keep it small).
#[cfg(not(feature = "mining-formats"))]
fn not_built(format: Format) -> Error {
    Error::InvalidParameter(format!(
        "{} is not built into this build of meshbool (the mining-formats feature)",
        format.name()
    ))
}

/// Reads a mesh from bytes in the given format (for STL and PLY the encoding is taken from
/// the content; for JSON both soup layouts are accepted). A Surpac DTM cannot be read from
/// its `.dtm` alone, which holds no points: that is an error saying so (read it by path,
/// or with [`read_surpac_dtm`]).
pub fn read_bytes(bytes: &[u8], format: Format) -> Result<Mesh> {
    if bytes.trim_ascii().is_empty() {
        return Err(Error::parse(format, Location::Whole, "the file is empty"));
    }
    let mesh = match format {
        Format::StlBinary | Format::StlAscii => stl::read(bytes)?,
        Format::Obj => obj::read(bytes)?,
        Format::Off => off::read(bytes)?,
        Format::PlyAscii | Format::PlyBinaryLe | Format::PlyBinaryBe => ply::read(bytes)?,
        Format::Dxf => dxf::read(bytes)?,
        Format::JsonSoup | Format::JsonKirra => json::read(bytes)?,
        Format::Glb => glb::read(bytes)?,
        #[cfg(feature = "mining-formats")]
        Format::GocadTs => gocad::read(bytes)?,
        #[cfg(feature = "mining-formats")]
        Format::LandXml => landxml::read(bytes)?,
        #[cfg(feature = "mining-formats")]
        Format::SurpacDtm => {
            return Err(Error::parse(format, Location::Whole, surpac::NEEDS_STRINGS))
        }
        #[cfg(not(feature = "mining-formats"))]
        Format::GocadTs | Format::LandXml | Format::SurpacDtm => return Err(not_built(format)),
    };
    mesh.validate()?;
    Ok(mesh)
}

/// Reads a mesh file, telling the format from the extension and the content.
pub fn read_path(path: impl AsRef<Path>) -> Result<Mesh> {
    Ok(read_file(path, None)?.0)
}

/// The bytes of the file at `path`, opened once. A large regular file, with more than two
/// threads, is read in pieces at their offsets on all of them (the copies out of the page
/// cache, and the page faults of the new buffer, run side by side); anything else (small
/// files, pipes, devices) is read to its end from the handle.
fn read_all(path: &Path) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let mut file = fs::File::open(path)?;
    let meta = file.metadata()?;
    let mut bytes = Vec::new();
    if meta.is_file() {
        let len = usize::try_from(meta.len()).map_err(std::io::Error::other)?;
        bytes
            .try_reserve_exact(len)
            .map_err(std::io::Error::other)?;
        #[cfg(unix)]
        if rayon::current_num_threads() > 2 && len >= 1 << 24 {
            use rayon::prelude::*;
            use std::os::unix::fs::FileExt;
            const PIECE: usize = 1 << 22;
            // Zeroed side by side too (the first touch of fresh pages is what costs).
            bytes.par_extend(rayon::iter::repeat_n(0u8, len));
            bytes
                .par_chunks_mut(PIECE)
                .enumerate()
                .try_for_each(|(i, piece)| file.read_exact_at(piece, (i * PIECE) as u64))?;
            return Ok(bytes);
        }
    }
    file.read_to_end(&mut bytes)?;
    Ok(bytes)
}

/// Reads a mesh file as `from`, or as the format its name and content say
/// ([`detect_format`]); also gives the format it was read as. A Surpac DTM is read with
/// the string file of the same name beside it (extension `str`): an error names that file
/// when it cannot be read.
pub fn read_file(path: impl AsRef<Path>, from: Option<Format>) -> Result<(Mesh, Format)> {
    let path = path.as_ref();
    let bytes = read_all(path)?;
    let format = detect_format(&bytes, from.or_else(|| Format::for_path(path)))
        .ok_or_else(|| Error::UnknownFormat(path.display().to_string()))?;
    #[cfg(feature = "mining-formats")]
    if format == Format::SurpacDtm && !bytes.trim_ascii().is_empty() {
        return Ok((surpac::read_path(path, &bytes)?, format));
    }
    Ok((read_bytes(&bytes, format)?, format))
}

/// Writes `mesh` to `out` in `format`. Non-finite coordinates are an error
/// ([`Mesh::validate`]); so are, in [`Format::Glb`], a mesh without triangles and
/// coordinates too far from the mesh's centre for `f32` offsets. [`Format::SurpacDtm`] is
/// two files and cannot go to one writer: [`Error::InvalidParameter`] (write it by path,
/// or with [`write_surpac_dtm`]).
pub fn write(out: &mut impl Write, mesh: &Mesh, format: Format) -> Result<()> {
    mesh.validate()?;
    match format {
        Format::StlBinary => stl::write_binary(out, mesh),
        Format::StlAscii => stl::write_ascii(out, mesh),
        Format::Obj => obj::write(out, mesh),
        Format::Off => off::write(out, mesh),
        Format::PlyAscii | Format::PlyBinaryLe | Format::PlyBinaryBe => {
            ply::write(out, mesh, format)
        }
        Format::Dxf => dxf::write(out, mesh),
        Format::JsonSoup | Format::JsonKirra => json::write(out, mesh, format),
        Format::Glb => glb::write(out, mesh),
        #[cfg(feature = "mining-formats")]
        Format::GocadTs => gocad::write(out, mesh),
        #[cfg(feature = "mining-formats")]
        Format::LandXml => landxml::write(out, mesh),
        #[cfg(not(feature = "mining-formats"))]
        Format::GocadTs | Format::LandXml => Err(not_built(format)),
        Format::SurpacDtm => Err(Error::InvalidParameter(
            "a Surpac DTM is two files, the .dtm and its string file .str: write it by path \
             (io::write_path_as) or with io::write_surpac_dtm"
                .into(),
        )),
    }?;
    Ok(())
}

pub use glb::GlbPart;

/// Writes a glTF binary of several meshes, one node each, in the order given (names,
/// visibility, `extras`: [`GlbPart`]); as [`write()`] writes one mesh in [`Format::Glb`].
/// Errors for non-finite coordinates and coordinates too far from their mesh's centre
/// for `f32` offsets.
pub fn write_glb(out: &mut impl Write, parts: &[GlbPart<'_>]) -> Result<()> {
    for p in parts {
        p.mesh.validate()?;
    }
    glb::write_parts(out, parts)
}

/// Writes `mesh` to a file in the format its extension names ([`Format::for_path`]).
pub fn write_path(path: impl AsRef<Path>, mesh: &Mesh) -> Result<()> {
    let path = path.as_ref();
    let format =
        Format::for_path(path).ok_or_else(|| Error::UnknownFormat(path.display().to_string()))?;
    write_path_as(path, mesh, format)
}

/// Writes `mesh` to a file in `format`. A Surpac DTM's string file is written beside it:
/// the same name with extension `str`.
pub fn write_path_as(path: impl AsRef<Path>, mesh: &Mesh, format: Format) -> Result<()> {
    #[cfg(feature = "mining-formats")]
    if format == Format::SurpacDtm {
        return surpac::write_path(path.as_ref(), mesh);
    }
    write_file(path.as_ref(), |out| {
        // A large binary STL is written by all threads, each block at its offset, its
        // write-back started as it goes (faster on one and two threads too).
        #[cfg(unix)]
        if format == Format::StlBinary && mesh.triangles.len() >= 1 << 16 {
            mesh.validate()?;
            return stl::write_binary_at(out.get_ref(), mesh);
        }
        // Other formats are written in order, their write-back started as they go.
        #[cfg(unix)]
        {
            let mut back = BufWriter::new(WritingBack {
                file: out.get_ref(),
                written: 0,
                started: 0,
            });
            write(&mut back, mesh, format)?;
            back.flush()?;
            Ok(())
        }
        #[cfg(not(unix))]
        write(out, mesh, format)
    })
}

/// A new file written in order from its start, whose write-back to disk is started every
/// [`WritingBack::STEP`] bytes ([`start_writeback`]), so that the final sync waits for
/// little.
#[cfg(unix)]
struct WritingBack<'f> {
    file: &'f fs::File,
    /// Bytes written so far, and up to where the write-back was started.
    written: u64,
    started: u64,
}

#[cfg(unix)]
impl WritingBack<'_> {
    const STEP: u64 = 8 << 20;
}

#[cfg(unix)]
impl Write for WritingBack<'_> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let mut file = self.file;
        let n = file.write(buf)?;
        self.written += n as u64;
        if self.written - self.started >= Self::STEP {
            start_writeback(
                self.file,
                self.started,
                (self.written - self.started) as usize,
            );
            self.started = self.written;
        }
        Ok(n)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        let mut file = self.file;
        file.flush()
    }
}

/// Writes the file at `path` through `fill`, so that it is never seen half-written: the
/// one way files are written. The content goes to a new temporary file beside `path`
/// (same directory, hidden name), is synced to disk, and the temporary file is renamed
/// over `path` (atomic on POSIX file systems). On any failure the temporary file is
/// removed and whatever was at `path` before is untouched — an input named as the output
/// included.
pub fn write_file(
    path: &Path,
    fill: impl FnOnce(&mut BufWriter<fs::File>) -> Result<()>,
) -> Result<()> {
    static COUNT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let name = path
        .file_name()
        .ok_or_else(|| Error::InvalidParameter(format!("{} is not a file name", path.display())))?;
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let n = COUNT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let tmp = dir.join(format!(
        ".{}.{}-{n}.meshbool-tmp",
        name.to_string_lossy(),
        std::process::id()
    ));
    let result = (|| {
        let file = fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)?;
        let mut out = BufWriter::new(file);
        fill(&mut out)?;
        let file = out.into_inner().map_err(|e| Error::Io(e.into_error()))?;
        file.sync_all()?;
        fs::rename(&tmp, path)?;
        Ok(())
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result
}

/// Starts writing the whole pages among `len` bytes of `file` from `at` back to disk
/// without waiting. On Linux through `posix_fadvise(POSIX_FADV_DONTNEED)`, the one way to
/// it without unsafe code: the kernel starts the write-back of the range's dirty pages and
/// drops its clean ones, but pages dirty or being written are never dropped (so just
/// written data stay cached, only moved to the inactive list; each call also drains the
/// per-CPU page lists, a cost that the measurements include). Only whole pages are
/// advised, so that a page a neighbouring block is still writing is left to the sync.
/// [`write_file`]'s final sync then waits for little: for a 117 MB binary STL written on
/// 16 threads, write and sync took 56–67 ms instead of 98–104 ms (BENCHMARKS.md, "Measured
/// settings"). A hint
/// only: on other systems, on file systems without write-back (tmpfs), or where it
/// fails, nothing happens and the sync does all the work.
#[cfg(unix)]
fn start_writeback(file: &fs::File, at: u64, len: usize) {
    const PAGE: u64 = 4096;
    let (start, end) = (at.div_ceil(PAGE) * PAGE, (at + len as u64) / PAGE * PAGE);
    #[cfg(target_os = "linux")]
    if let Some(len) = end.checked_sub(start).and_then(std::num::NonZeroU64::new) {
        // Ignored on failure: the data are written either way and synced later.
        let _ = rustix::fs::fadvise(file, start, Some(len), rustix::fs::Advice::DontNeed);
    }
    #[cfg(not(target_os = "linux"))]
    let _ = (file, start, end);
}

/// Writes `bytes` to `path` as [`write_file`] does (never half-written, nothing lost on
/// failure), the error naming the file.
pub fn write_bytes(path: impl AsRef<Path>, bytes: &[u8]) -> Result<()> {
    let path = path.as_ref();
    write_file(path, |out| Ok(out.write_all(bytes)?)).map_err(|e| e.in_file("writing", path))
}

/// Output assembled in a buffer and handed to the writer in pieces of about 64 KiB, with
/// number formatting that round-trips (`ryu` for `f64`, `itoa` for integers).
struct Out<'a, W: Write> {
    w: &'a mut W,
    buf: Vec<u8>,
    num: ryu::Buffer,
    int: itoa::Buffer,
}

impl<'a, W: Write> Out<'a, W> {
    const CHUNK: usize = 1 << 16;

    fn new(w: &'a mut W) -> Self {
        Self::with_buffer(w, Vec::with_capacity(Self::CHUNK + 1024))
    }

    /// An `Out` that formats into `buf` (emptied first).
    fn with_buffer(w: &'a mut W, mut buf: Vec<u8>) -> Self {
        buf.clear();
        Out {
            w,
            buf,
            num: ryu::Buffer::new(),
            int: itoa::Buffer::new(),
        }
    }

    fn bytes(&mut self, b: &[u8]) -> &mut Self {
        self.buf.extend_from_slice(b);
        self
    }

    /// The shortest decimal text that parses back to exactly `x` (`x` must be finite).
    fn f64(&mut self, x: f64) -> &mut Self {
        self.buf
            .extend_from_slice(self.num.format_finite(x).as_bytes());
        self
    }

    /// The three coordinates of `p` ([`Out::f64`]) with `sep` between them.
    fn coords(&mut self, p: &[f64; 3], sep: &[u8]) -> &mut Self {
        self.f64(p[0]).bytes(sep).f64(p[1]).bytes(sep).f64(p[2])
    }

    /// An OBJ vertex line `v x y z`.
    fn obj_vertex(&mut self, p: &[f64; 3]) -> &mut Self {
        self.bytes(b"v ").coords(p, b" ").bytes(b"\n")
    }

    fn int(&mut self, x: u64) -> &mut Self {
        self.buf.extend_from_slice(self.int.format(x).as_bytes());
        self
    }

    /// Call after each record: passes the buffer on once it is full.
    fn record_done(&mut self) -> std::io::Result<()> {
        if self.buf.len() >= Self::CHUNK {
            self.w.write_all(&self.buf)?;
            self.buf.clear();
        }
        Ok(())
    }

    fn finish(mut self) -> Result<()> {
        self.w.write_all(&self.buf)?;
        self.buf.clear();
        Ok(())
    }
}

/// Writes records `0..n`, each formatted by `record` into an [`Out`] of its own: on one
/// thread straight through, passed on as its buffer fills; on more, blocks of records
/// are formatted side by side and written in order (a batch of blocks at a time, so
/// that little is held).
fn records<W: Write>(
    o: &mut Out<'_, W>,
    n: usize,
    record: impl Fn(&mut Out<'_, std::io::Sink>, usize) + Sync,
) -> std::io::Result<()> {
    use rayon::prelude::*;
    const BLOCK: usize = 1 << 13;
    // What `o` holds goes first.
    o.w.write_all(&o.buf)?;
    o.buf.clear();
    let mut sink = std::io::sink();
    let mut t = Out::new(&mut sink);
    let threads = rayon::current_num_threads();
    if threads == 1 || n < 2 * BLOCK {
        for i in 0..n {
            record(&mut t, i);
            if t.buf.len() >= Out::<W>::CHUNK {
                o.w.write_all(&t.buf)?;
                t.buf.clear();
            }
        }
        o.w.write_all(&t.buf)?;
        return Ok(());
    }
    // A buffer per block of a batch, kept from batch to batch.
    let mut blocks: Vec<Vec<u8>> = vec![Vec::new(); 4 * threads];
    for start in (0..n).step_by(BLOCK * blocks.len()) {
        blocks.par_iter_mut().enumerate().for_each(|(k, buf)| {
            let mut sink = std::io::sink();
            let mut t = Out::with_buffer(&mut sink, std::mem::take(buf));
            let first = (start + k * BLOCK).min(n);
            for i in first..(first + BLOCK).min(n) {
                record(&mut t, i);
            }
            *buf = t.buf;
        });
        for b in &blocks {
            o.w.write_all(b)?;
        }
    }
    Ok(())
}

/// Parses a decimal number from a text format; non-finite values are errors.
fn parse_f64(token: &[u8], format: Format, line: usize) -> Result<f64> {
    let bad = || {
        Error::parse(
            format,
            Location::Line(line),
            format!(
                "expected a number, found {:?}",
                String::from_utf8_lossy(token)
            ),
        )
    };
    let x: f64 = std::str::from_utf8(token)
        .map_err(|_| bad())?
        .parse()
        .map_err(|_| bad())?;
    if !x.is_finite() {
        return Err(Error::parse(
            format,
            Location::Line(line),
            format!("non-finite coordinate {:?}", String::from_utf8_lossy(token)),
        ));
    }
    Ok(x)
}

/// Lines of a text file with their 1-based numbers, without line terminators.
fn lines(bytes: &[u8]) -> impl Iterator<Item = (usize, &[u8])> {
    bytes
        .split(|&b| b == b'\n')
        .enumerate()
        .map(|(i, l)| (i + 1, l.strip_suffix(b"\r").unwrap_or(l)))
}

/// Whitespace-separated tokens of a line.
fn tokens(line: &[u8]) -> impl Iterator<Item = &[u8]> {
    line.split(|b| b.is_ascii_whitespace())
        .filter(|t| !t.is_empty())
}

/// Text files are parsed in pieces of about this many bytes side by side ([`pieces`]).
const PIECE: usize = 1 << 20;

/// How many pieces of whole lines a text file of `len` bytes is parsed in: one per
/// [`PIECE`], at most eight per thread; one on one thread.
fn pieces(len: usize) -> usize {
    let threads = rayon::current_num_threads();
    if threads > 1 {
        (len / PIECE).clamp(1, 8 * threads)
    } else {
        1
    }
}

/// `bytes` cut into about `pieces` pieces, each ending just after a line's end (the last
/// at the end).
fn whole_lines(bytes: &[u8], pieces: usize) -> Vec<&[u8]> {
    let mut out = Vec::with_capacity(pieces);
    let mut rest = bytes;
    for k in (1..pieces).rev() {
        let target = rest.len() / (k + 1);
        match rest[target..].iter().position(|&b| b == b'\n') {
            Some(i) => {
                let (head, tail) = rest.split_at(target + i + 1);
                out.push(head);
                rest = tail;
            }
            None => break,
        }
    }
    out.push(rest);
    out
}

/// Splits polygon `poly` (vertex indices, in order) into a fan of triangles.
fn push_fan(poly: &[u32], out: &mut Vec<[u32; 3]>) {
    for k in 1..poly.len().saturating_sub(1) {
        out.push([poly[0], poly[k], poly[k + 1]]);
    }
}

#[cfg(test)]
mod tests;

#[cfg(all(test, feature = "mining-formats"))]
mod mining_tests;
