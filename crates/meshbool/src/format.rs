//! File formats: the [`Format`] enum, its names and how a file name maps to one. Below
//! both [`crate::io`] (which reads and writes them) and [`crate::Error`] (which names the
//! format of malformed content), so that neither depends on the other. It uses nothing
//! of the library: its [`FromStr`](std::str::FromStr), whose error is the library's, is
//! in `error.rs`.

use std::fmt;
use std::path::Path;

/// A file format (with its encoding, where a format has several).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Format {
    /// Binary STL (`f32` coordinates).
    StlBinary,
    /// ASCII STL.
    StlAscii,
    /// Wavefront OBJ (`v`/`f`; polygons are triangulated as fans on read).
    Obj,
    /// ASCII PLY.
    PlyAscii,
    /// Binary little-endian PLY (written with `double` positions).
    PlyBinaryLe,
    /// Binary big-endian PLY.
    PlyBinaryBe,
    /// ASCII DXF: read 3DFACE entities and polyface meshes, written as 3DFACE.
    Dxf,
    /// JSON soup `[{"v0":{"x":..,"y":..,"z":..},"v1":..,"v2":..}, ..]`.
    JsonSoup,
    /// Kirra's JSON: `[{"vertices":[{"x":..,"y":..,"z":..}, x3]}, ..]`.
    JsonKirra,
    /// glTF 2.0 binary (`.glb`): `f32` positions written relative to a local origin that
    /// the node's translation holds in `f64`.
    Glb,
    /// GOCAD TSurf (`.ts`, ASCII): `VRTX`/`PVRTX`/`ATOM`/`PATOM` vertices and `TRGL`
    /// triangles, several face sets and surfaces per file; `ZPOSITIVE Depth` surfaces have
    /// `z` negated on read so that up is `+z`.
    GocadTs,
    /// Surpac DTM: triangles in the `.dtm` file referring to the points of the string file
    /// (`.str`) of the same name beside it, points as `y, x, z` (northing first). Two
    /// files: read and written by path ([`crate::io::read_file`],
    /// [`crate::io::write_path_as`]) or with [`crate::io::read_surpac_dtm`] and
    /// [`crate::io::write_surpac_dtm`].
    SurpacDtm,
    /// LandXML 1.2 TIN surfaces (`.xml`): `<P id="..">northing easting elevation</P>`
    /// points and `<F>` faces; invisible faces (`i="1"`) are skipped.
    LandXml,
    /// Object File Format (`.off`, ASCII): `OFF`, the counts, vertex lines and face lines
    /// (0-based polygons, triangulated as fans on read); the `C`, `N` and `ST` variants'
    /// extra numbers are skipped.
    Off,
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Format::StlBinary => "binary STL",
            Format::StlAscii => "ASCII STL",
            Format::Obj => "OBJ",
            Format::PlyAscii => "ASCII PLY",
            Format::PlyBinaryLe => "binary little-endian PLY",
            Format::PlyBinaryBe => "binary big-endian PLY",
            Format::Dxf => "DXF",
            Format::JsonSoup => "JSON soup",
            Format::JsonKirra => "Kirra JSON",
            Format::Glb => "binary glTF",
            Format::GocadTs => "GOCAD TSurf",
            Format::SurpacDtm => "Surpac DTM",
            Format::LandXml => "LandXML",
            Format::Off => "OFF",
        })
    }
}

impl Format {
    /// All formats, with the names they are read by ([`FromStr`](std::str::FromStr)) and
    /// written as.
    pub const NAMES: [(&'static str, Format); 14] = [
        ("stl", Format::StlBinary),
        ("stl-ascii", Format::StlAscii),
        ("obj", Format::Obj),
        ("ply", Format::PlyBinaryLe),
        ("ply-ascii", Format::PlyAscii),
        ("ply-be", Format::PlyBinaryBe),
        ("dxf", Format::Dxf),
        ("json", Format::JsonSoup),
        ("kirra-json", Format::JsonKirra),
        ("glb", Format::Glb),
        ("gocad-ts", Format::GocadTs),
        ("surpac-dtm", Format::SurpacDtm),
        ("landxml", Format::LandXml),
        ("off", Format::Off),
    ];

    /// The format's name in [`Format::NAMES`] (`stl`, `stl-ascii`, `obj`, ...).
    pub fn name(self) -> &'static str {
        Format::NAMES
            .iter()
            .find(|(_, f)| *f == self)
            .map_or("", |(n, _)| n)
    }

    /// True when reading this format already merges exactly equal positions into one
    /// vertex (formats that store triangles as corner coordinates: STL, DXF 3DFACE, JSON
    /// soups), so [`crate::weld_exact`] after reading would change nothing.
    pub fn welds_on_read(self) -> bool {
        matches!(
            self,
            Format::StlBinary
                | Format::StlAscii
                | Format::Dxf
                | Format::JsonSoup
                | Format::JsonKirra
        )
    }

    /// The file name extension of the format: `stl`, `obj`, `ply`, `dxf`, `json`, `glb`,
    /// `ts` (GOCAD TSurf), `dtm` (Surpac DTM, whose points go in a `.str` beside it), `xml`
    /// (LandXML), `off`.
    pub fn extension(self) -> &'static str {
        match self {
            Format::StlBinary | Format::StlAscii => "stl",
            Format::Obj => "obj",
            Format::PlyAscii | Format::PlyBinaryLe | Format::PlyBinaryBe => "ply",
            Format::Dxf => "dxf",
            Format::JsonSoup | Format::JsonKirra => "json",
            Format::Glb => "glb",
            Format::GocadTs => "ts",
            Format::SurpacDtm => "dtm",
            Format::LandXml => "xml",
            Format::Off => "off",
        }
    }

    /// The format written for a file name's extension: `.stl` binary STL, `.obj`, `.ply`
    /// binary little-endian, `.dxf`, `.json` JSON soup, `.glb` binary glTF, `.ts` GOCAD
    /// TSurf, `.dtm` Surpac DTM, `.xml` LandXML, `.off` OFF. `None` for other extensions.
    pub fn for_path(path: impl AsRef<Path>) -> Option<Format> {
        let ext = path.as_ref().extension()?.to_str()?.to_ascii_lowercase();
        Some(match ext.as_str() {
            "stl" => Format::StlBinary,
            "obj" => Format::Obj,
            "ply" => Format::PlyBinaryLe,
            "dxf" => Format::Dxf,
            "json" => Format::JsonSoup,
            "glb" => Format::Glb,
            "ts" => Format::GocadTs,
            "dtm" => Format::SurpacDtm,
            "xml" => Format::LandXml,
            "off" => Format::Off,
            _ => return None,
        })
    }
}
