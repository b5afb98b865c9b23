//! glTF 2.0 binary (GLB): a 12-byte header, a JSON chunk that describes the scene and a BIN
//! chunk that holds the numbers.
//!
//! Written as one scene, one node and one mesh with one triangle primitive (or, by
//! [`super::write_glb`], one such node per mesh, named, hidden or not with
//! `KHR_node_visibility`, with `extras`): `POSITION` as
//! `FLOAT` `VEC3` (with its `min`/`max`) and `UNSIGNED_INT` indices. glTF stores positions as
//! `f32`, whose 24-bit significand would leave survey coordinates (UTM northings near
//! 6.8 million) with steps of 0.5: positions are therefore written relative to a local
//! origin, the centre of the bounding box, kept as the node's `translation` in full `f64`.
//! A coordinate then comes back within `2^-24` of half the box's size (plus the `f64`
//! rounding of adding the origin back). Axes are written as they are: glTF viewers take
//! `+y` as up, so Z-up data shows lying on its side.
//!
//! Read: every triangle primitive (modes 4, 5 and 6: triangles, strips, fans) of every mesh
//! a node of the scene references, its `POSITION` (`FLOAT` `VEC3`) and its indices
//! (`UNSIGNED_BYTE`, `UNSIGNED_SHORT` or `UNSIGNED_INT`, or none: the positions in order),
//! moved by the node's transform composed from the root down (translation, rotation, scale
//! or a column-major matrix), in `f64`; a node hidden by `KHR_node_visibility` is left
//! out with its subtree. A node whose transform mirrors has its triangles
//! turned over, so that they keep facing the way glTF says they face. Points and lines are
//! skipped. Only the file's own BIN chunk is read: buffers in external files or data URIs,
//! sparse accessors and required extensions (Draco, meshopt) are errors.
//!
//! Both directions are done by hand, with `serde_json` for the JSON chunk, rather than with
//! a glTF crate: the container is a header and two chunks, and the little JSON a mesh needs
//! is a handful of objects, where a glTF crate would bring in materials, textures, images,
//! animations and extension handling this library has no use for.

use std::io::Write;

use serde::de::IgnoredAny;
use serde::Deserialize;

use super::{Format, Out};
use crate::error::{Error, Location, Result};
use crate::Mesh;

const MAGIC: &[u8; 4] = b"glTF";
const HEADER: usize = 12;
const CHUNK_HEADER: usize = 8;
const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;

const UNSIGNED_BYTE: u32 = 5121;
const UNSIGNED_SHORT: u32 = 5123;
const UNSIGNED_INT: u32 = 5125;
const FLOAT: u32 = 5126;

const TRIANGLES: u32 = 4;
const TRIANGLE_STRIP: u32 = 5;
const TRIANGLE_FAN: u32 = 6;

/// Content sniffing: the GLB magic.
pub(super) fn looks_like(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

fn u32_at(bytes: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
}

// ---------------------------------------------------------------------------------------
// Writing
// ---------------------------------------------------------------------------------------

pub(super) fn write(out: &mut impl Write, mesh: &Mesh) -> Result<()> {
    if mesh.triangles.is_empty() {
        return Err(Error::invalid(
            Location::Whole,
            "a glTF mesh needs at least one triangle; this mesh has none",
        ));
    }
    write_parts(
        out,
        &[GlbPart {
            name: None,
            mesh,
            visible: true,
            extras: None,
        }],
    )
}

/// One node of a GLB written by [`super::write_glb`]: a mesh, and what the node says of it.
#[derive(Clone, Debug)]
pub struct GlbPart<'a> {
    /// The node's `name`.
    pub name: Option<String>,
    /// Its mesh (a node without a mesh where it has no triangles).
    pub mesh: &'a Mesh,
    /// False: the node is hidden (`KHR_node_visibility`, which viewers without the
    /// extension ignore, and which this library's reader honours).
    pub visible: bool,
    /// The node's `extras` (any JSON).
    pub extras: Option<serde_json::Value>,
}

/// A mesh's positions relative to the centre of its box, as `f32`, with that centre and
/// the positions' bounds; an error naming a vertex too far from the centre for `f32`.
struct Local {
    origin: [f64; 3],
    positions: Vec<[f32; 3]>,
    min: [f32; 3],
    max: [f32; 3],
}

fn local(mesh: &Mesh) -> Result<Local> {
    // The local origin: the centre of the box around every position (halves added, so
    // that the sum cannot overflow).
    let mut lo = mesh.positions.first().copied().unwrap_or([0.0; 3]);
    let mut hi = lo;
    for p in &mesh.positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let origin: [f64; 3] = std::array::from_fn(|k| lo[k] / 2.0 + hi[k] / 2.0);
    let mut min = [f32::INFINITY; 3];
    let mut max = [f32::NEG_INFINITY; 3];
    let mut positions = Vec::with_capacity(mesh.positions.len());
    for (v, p) in mesh.positions.iter().enumerate() {
        let q: [f32; 3] = std::array::from_fn(|k| (p[k] - origin[k]) as f32);
        if q.iter().any(|x| !x.is_finite()) {
            return Err(Error::invalid(
                Location::Vertex(v),
                format!(
                    "{p:?} lies too far from the mesh's centre {origin:?} for glTF's f32 positions"
                ),
            ));
        }
        for k in 0..3 {
            min[k] = min[k].min(q[k]);
            max[k] = max[k].max(q[k]);
        }
        positions.push(q);
    }
    Ok(Local {
        origin,
        positions,
        min,
        max,
    })
}

/// Writes one scene of `parts`, a root node each (in order), each mesh relative to its
/// own local origin (the node's `translation`, in full `f64`).
pub(super) fn write_parts(out: &mut impl Write, parts: &[GlbPart<'_>]) -> Result<()> {
    let mut nodes = Vec::new();
    let mut meshes = Vec::new();
    let mut accessors = Vec::new();
    let mut views = Vec::new();
    let mut locals = Vec::new();
    let mut offset = 0u64;
    let mut hidden = false;
    for part in parts {
        let mut node = serde_json::Map::new();
        if let Some(name) = &part.name {
            node.insert("name".into(), name.clone().into());
        }
        if !part.mesh.triangles.is_empty() {
            let l = local(part.mesh)?;
            let (n, indices) = (
                l.positions.len() as u64,
                3 * part.mesh.triangles.len() as u64,
            );
            let a = accessors.len();
            node.insert("mesh".into(), meshes.len().into());
            node.insert("translation".into(), serde_json::json!(l.origin));
            meshes.push(serde_json::json!({"primitives": [{
                "attributes": {"POSITION": a},
                "indices": a + 1,
                "mode": TRIANGLES,
            }]}));
            accessors.push(serde_json::json!({
                "bufferView": a,
                "componentType": FLOAT,
                "count": n,
                "type": "VEC3",
                "min": l.min.map(f64::from),
                "max": l.max.map(f64::from),
            }));
            accessors.push(serde_json::json!({
                "bufferView": a + 1,
                "componentType": UNSIGNED_INT,
                "count": indices,
                "type": "SCALAR",
            }));
            views.push(serde_json::json!({"buffer": 0, "byteOffset": offset, "byteLength": 12 * n, "target": 34962}));
            views.push(serde_json::json!({"buffer": 0, "byteOffset": offset + 12 * n, "byteLength": 4 * indices, "target": 34963}));
            offset += 12 * n + 4 * indices;
            locals.push((l, part.mesh));
        }
        if !part.visible {
            hidden = true;
            node.insert(
                "extensions".into(),
                serde_json::json!({"KHR_node_visibility": {"visible": false}}),
            );
        }
        if let Some(extras) = &part.extras {
            node.insert("extras".into(), extras.clone());
        }
        nodes.push(serde_json::Value::Object(node));
    }
    let bin_len = offset;
    let mut json = serde_json::json!({
        "asset": {"version": "2.0", "generator": "meshbool"},
        "scene": 0,
        "scenes": [{"nodes": (0..nodes.len()).collect::<Vec<_>>()}],
        "nodes": nodes,
        "meshes": meshes,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": bin_len}],
    });
    if hidden {
        json["extensionsUsed"] = serde_json::json!(["KHR_node_visibility"]);
    }
    let mut json = serde_json::to_vec(&json)
        .map_err(|e| Error::invalid(Location::Whole, format!("glTF JSON: {e}")))?;
    // Chunks start and end on 4-byte boundaries: JSON padded with spaces, BIN with zeros.
    json.resize(json.len().next_multiple_of(4), b' ');
    let bin_padded = bin_len.next_multiple_of(4);
    let total = (HEADER + 2 * CHUNK_HEADER + json.len()) as u64 + bin_padded;
    let too_big = || {
        Error::invalid(
            Location::Whole,
            format!("{total} bytes: a GLB file holds at most 2^32-1 bytes"),
        )
    };
    let total32 = u32::try_from(total).map_err(|_| too_big())?;
    let bin32 = u32::try_from(bin_padded).map_err(|_| too_big())?;

    let mut o = Out::new(out);
    o.bytes(MAGIC)
        .bytes(&2u32.to_le_bytes())
        .bytes(&total32.to_le_bytes());
    o.bytes(&(json.len() as u32).to_le_bytes())
        .bytes(&CHUNK_JSON.to_le_bytes())
        .bytes(&json);
    o.bytes(&bin32.to_le_bytes())
        .bytes(&CHUNK_BIN.to_le_bytes());
    for (l, mesh) in &locals {
        for q in &l.positions {
            for x in q {
                o.bytes(&x.to_le_bytes());
            }
            o.record_done()?;
        }
        for t in &mesh.triangles {
            for i in t {
                o.bytes(&i.to_le_bytes());
            }
            o.record_done()?;
        }
    }
    for _ in bin_len..bin_padded {
        o.bytes(&[0]);
    }
    o.finish()
}

// ---------------------------------------------------------------------------------------
// Reading
// ---------------------------------------------------------------------------------------

/// The parts of the glTF JSON that a mesh needs; everything else is ignored.
#[derive(Deserialize)]
struct Gltf {
    asset: Asset,
    scene: Option<usize>,
    #[serde(default)]
    scenes: Vec<Scene>,
    #[serde(default)]
    nodes: Vec<Node>,
    #[serde(default)]
    meshes: Vec<GltfMesh>,
    #[serde(default)]
    accessors: Vec<Accessor>,
    #[serde(default, rename = "bufferViews")]
    buffer_views: Vec<BufferView>,
    #[serde(default)]
    buffers: Vec<Buffer>,
    #[serde(default, rename = "extensionsRequired")]
    extensions_required: Vec<String>,
}

#[derive(Deserialize)]
struct Asset {
    version: String,
}

#[derive(Deserialize)]
struct Scene {
    #[serde(default)]
    nodes: Vec<usize>,
}

#[derive(Deserialize)]
struct Node {
    #[serde(default)]
    children: Vec<usize>,
    #[serde(default)]
    extensions: NodeExtensions,
    mesh: Option<usize>,
    matrix: Option<[f64; 16]>,
    translation: Option<[f64; 3]>,
    rotation: Option<[f64; 4]>,
    scale: Option<[f64; 3]>,
}

/// The node extensions read: `KHR_node_visibility` (a hidden node and its subtree are
/// not read).
#[derive(Deserialize, Default)]
struct NodeExtensions {
    #[serde(rename = "KHR_node_visibility")]
    visibility: Option<Visibility>,
}

#[derive(Deserialize)]
struct Visibility {
    #[serde(default = "visible")]
    visible: bool,
}

fn visible() -> bool {
    true
}

#[derive(Deserialize)]
struct GltfMesh {
    primitives: Vec<Primitive>,
}

#[derive(Deserialize)]
struct Primitive {
    attributes: Attributes,
    indices: Option<usize>,
    mode: Option<u32>,
}

#[derive(Deserialize)]
struct Attributes {
    #[serde(rename = "POSITION")]
    position: Option<usize>,
}

#[derive(Deserialize)]
struct Accessor {
    #[serde(rename = "bufferView")]
    buffer_view: Option<usize>,
    #[serde(default, rename = "byteOffset")]
    byte_offset: u64,
    #[serde(rename = "componentType")]
    component_type: u32,
    count: u64,
    #[serde(rename = "type")]
    kind: String,
    sparse: Option<IgnoredAny>,
}

#[derive(Deserialize)]
struct BufferView {
    buffer: usize,
    #[serde(default, rename = "byteOffset")]
    byte_offset: u64,
    #[serde(rename = "byteLength")]
    byte_length: u64,
    #[serde(rename = "byteStride")]
    byte_stride: Option<u64>,
}

#[derive(Deserialize)]
struct Buffer {
    uri: Option<String>,
    #[serde(rename = "byteLength")]
    byte_length: u64,
}

/// An affine transform: three rows of `[a, b, c, t]`, `p' = A p + t`.
#[derive(Clone, Copy)]
struct Affine([[f64; 4]; 3]);

impl Affine {
    const IDENTITY: Affine = Affine([
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
    ]);

    /// `self ∘ other`: `other` first, then `self`.
    fn then_after(&self, other: &Affine) -> Affine {
        let (a, b) = (&self.0, &other.0);
        Affine(std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                let lin = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
                if j == 3 {
                    lin + a[i][3]
                } else {
                    lin
                }
            })
        }))
    }

    /// The transformed point. The linear part is summed first and the translation added
    /// last, so that a pure translation adds exactly one rounding.
    fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|i| {
            let r = &self.0[i];
            (r[0] * p[0] + r[1] * p[1] + r[2] * p[2]) + r[3]
        })
    }

    /// True when the transform mirrors (negative determinant of the linear part).
    fn mirrors(&self) -> bool {
        let m = &self.0;
        let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        det < 0.0
    }
}

/// A run of accessor elements in the BIN chunk.
struct Elements<'a> {
    data: &'a [u8],
    /// File offset of `data[0]`.
    at: u64,
    stride: usize,
    count: usize,
    component_type: u32,
}

impl Elements<'_> {
    /// Element `i`'s bytes (at least one element's size) and their file offset.
    fn get(&self, i: usize) -> (&[u8], u64) {
        let start = i * self.stride;
        (&self.data[start..], self.at + start as u64)
    }
}

/// The decoded file: the JSON, the BIN chunk, and where both are for error locations.
struct Glb<'a> {
    gltf: Gltf,
    json_at: u64,
    bin: Option<(&'a [u8], u64)>,
}

fn err(at: u64, msg: impl Into<String>) -> Error {
    Error::parse(Format::Glb, Location::Byte(at), msg)
}

pub(super) fn read(bytes: &[u8]) -> Result<Mesh> {
    let glb = container(bytes)?;
    glb.mesh()
}

/// Parses the header and the chunks, and the JSON chunk into [`Gltf`].
fn container(bytes: &[u8]) -> Result<Glb<'_>> {
    let len = bytes.len();
    if len < HEADER {
        return Err(err(
            len as u64,
            format!("file ends after {len} bytes, inside the 12-byte GLB header"),
        ));
    }
    if !looks_like(bytes) {
        return Err(err(
            0,
            format!(
                "bad magic {:?}: not a binary glTF file (expected \"glTF\")",
                String::from_utf8_lossy(&bytes[..4])
            ),
        ));
    }
    let version = u32_at(bytes, 4);
    if version != 2 {
        return Err(err(
            4,
            format!("GLB version {version}; only version 2 (glTF 2.0) is read"),
        ));
    }
    let announced = u32_at(bytes, 8) as usize;
    if announced != len {
        let why = if announced > len {
            "truncated?"
        } else {
            "trailing bytes or a wrong length"
        };
        return Err(err(
            8,
            format!("header announces {announced} bytes but the file has {len}: {why}"),
        ));
    }
    let mut json = None;
    let mut bin = None;
    let mut pos = HEADER;
    while pos < len {
        if len - pos < CHUNK_HEADER {
            return Err(err(pos as u64, "file ends inside a chunk header"));
        }
        let size = u32_at(bytes, pos) as usize;
        let kind = u32_at(bytes, pos + 4);
        let start = pos + CHUNK_HEADER;
        if size > len - start {
            return Err(err(
                pos as u64,
                format!(
                    "chunk announces {size} bytes but only {} remain: truncated?",
                    len - start
                ),
            ));
        }
        let data = &bytes[start..start + size];
        if pos == HEADER && kind != CHUNK_JSON {
            return Err(err(
                (pos + 4) as u64,
                format!("the first chunk is of type {kind:#010x}; it must be JSON"),
            ));
        }
        match kind {
            CHUNK_JSON if json.is_none() => json = Some((data, start as u64)),
            CHUNK_BIN if bin.is_none() => bin = Some((data, start as u64)),
            CHUNK_JSON | CHUNK_BIN => {
                return Err(err(pos as u64, "a second JSON or BIN chunk"));
            }
            _ => {} // unknown chunk types are skipped, as the specification asks
        }
        pos = start + size;
    }
    let Some((json, json_at)) = json else {
        return Err(err(HEADER as u64, "file has no JSON chunk"));
    };
    // Some writers pad the JSON with zeros rather than spaces.
    let text = match json.iter().rposition(|&b| b != 0) {
        Some(last) => &json[..=last],
        None => &[][..],
    };
    let gltf: Gltf = serde_json::from_slice(text).map_err(|e| {
        let offset = json_offset(text, e.line(), e.column());
        err(json_at + offset, format!("glTF JSON: {e}"))
    })?;
    Ok(Glb { gltf, json_at, bin })
}

/// The byte offset in `text` of serde_json's 1-based line and column.
fn json_offset(text: &[u8], line: usize, column: usize) -> u64 {
    let mut offset = 0;
    for l in text.split(|&b| b == b'\n').take(line.saturating_sub(1)) {
        offset += l.len() + 1;
    }
    (offset + column.saturating_sub(1)).min(text.len()) as u64
}

impl Glb<'_> {
    /// An error about the JSON's content, located at the JSON chunk.
    fn bad(&self, msg: impl Into<String>) -> Error {
        err(self.json_at, msg)
    }

    fn mesh(&self) -> Result<Mesh> {
        let g = &self.gltf;
        if !g.asset.version.starts_with("2.") {
            return Err(self.bad(format!(
                "asset.version is {:?}; only glTF 2.x is read",
                g.asset.version
            )));
        }
        if !g.extensions_required.is_empty() {
            return Err(self.bad(format!(
                "the file requires extensions that are not supported: {}",
                g.extensions_required.join(", ")
            )));
        }
        let mut positions = Vec::new();
        let mut triangles = Vec::new();
        let mut other_modes = Vec::new();
        for (mesh, xf) in self.instances()? {
            let m = g.meshes.get(mesh).ok_or_else(|| {
                self.bad(format!(
                    "a node refers to meshes[{mesh}] but there are {} meshes",
                    g.meshes.len()
                ))
            })?;
            for (k, prim) in m.primitives.iter().enumerate() {
                let path = format!("meshes[{mesh}].primitives[{k}]");
                let mode = prim.mode.unwrap_or(TRIANGLES);
                if !matches!(mode, TRIANGLES | TRIANGLE_STRIP | TRIANGLE_FAN) {
                    other_modes.push(mode);
                    continue;
                }
                self.primitive(prim, mode, &path, &xf, &mut positions, &mut triangles)?;
            }
        }
        if triangles.is_empty() && !other_modes.is_empty() {
            other_modes.sort_unstable();
            other_modes.dedup();
            return Err(self.bad(format!(
                "no triangle primitives: only modes {other_modes:?} (points or lines)"
            )));
        }
        Ok(Mesh::new_unchecked(positions, triangles))
    }

    /// Every mesh the scene shows with its node's transform, in the order of a depth-first
    /// walk of the scene's nodes: the scene `scene` names, else the first scene, else every
    /// root node; a file without nodes gives each of its meshes untransformed.
    fn instances(&self) -> Result<Vec<(usize, Affine)>> {
        let g = &self.gltf;
        let nodes = g.nodes.len();
        if nodes == 0 {
            return Ok((0..g.meshes.len()).map(|m| (m, Affine::IDENTITY)).collect());
        }
        let roots: Vec<usize> = match (g.scene, g.scenes.first()) {
            (Some(s), _) => {
                let scene = g.scenes.get(s).ok_or_else(|| {
                    self.bad(format!(
                        "scene is {s} but there are {} scenes",
                        g.scenes.len()
                    ))
                })?;
                scene.nodes.clone()
            }
            (None, Some(first)) => first.nodes.clone(),
            (None, None) => {
                let mut child = vec![false; nodes];
                for n in &g.nodes {
                    for &c in &n.children {
                        if let Some(x) = child.get_mut(c) {
                            *x = true;
                        }
                    }
                }
                (0..nodes).filter(|&n| !child[n]).collect()
            }
        };
        let mut seen = vec![false; nodes];
        let mut out = Vec::new();
        let mut stack: Vec<(usize, Affine)> =
            roots.iter().rev().map(|&n| (n, Affine::IDENTITY)).collect();
        while let Some((n, parent)) = stack.pop() {
            let node = g.nodes.get(n).ok_or_else(|| {
                self.bad(format!(
                    "a scene or node refers to nodes[{n}] but there are {nodes} nodes"
                ))
            })?;
            if std::mem::replace(&mut seen[n], true) {
                return Err(self.bad(format!(
                    "nodes[{n}] is reached twice: the node hierarchy is not a tree"
                )));
            }
            if node
                .extensions
                .visibility
                .as_ref()
                .is_some_and(|v| !v.visible)
            {
                continue;
            }
            let world = parent.then_after(&self.local(n, node)?);
            if let Some(m) = node.mesh {
                out.push((m, world));
            }
            stack.extend(node.children.iter().rev().map(|&c| (c, world)));
        }
        Ok(out)
    }

    /// A node's own transform: its matrix, or translation · rotation · scale.
    fn local(&self, n: usize, node: &Node) -> Result<Affine> {
        if let Some(m) = node.matrix {
            // Column-major: element (row r, column c) is m[4c + r].
            if [m[3], m[7], m[11], m[15]] != [0.0, 0.0, 0.0, 1.0] {
                return Err(self.bad(format!(
                    "nodes[{n}].matrix is not affine (its last row is not 0 0 0 1)"
                )));
            }
            return Ok(Affine(std::array::from_fn(|r| {
                std::array::from_fn(|c| m[4 * c + r])
            })));
        }
        let t = node.translation.unwrap_or([0.0; 3]);
        let s = node.scale.unwrap_or([1.0; 3]);
        let [x, y, z, w] = node.rotation.unwrap_or([0.0, 0.0, 0.0, 1.0]);
        let norm = (x * x + y * y + z * z + w * w).sqrt();
        if !(norm > 0.0 && norm.is_finite()) {
            return Err(self.bad(format!(
                "nodes[{n}].rotation {:?} is not a rotation quaternion",
                [x, y, z, w]
            )));
        }
        let [x, y, z, w] = [x / norm, y / norm, z / norm, w / norm];
        let r = [
            [
                1.0 - 2.0 * (y * y + z * z),
                2.0 * (x * y - z * w),
                2.0 * (x * z + y * w),
            ],
            [
                2.0 * (x * y + z * w),
                1.0 - 2.0 * (x * x + z * z),
                2.0 * (y * z - x * w),
            ],
            [
                2.0 * (x * z - y * w),
                2.0 * (y * z + x * w),
                1.0 - 2.0 * (x * x + y * y),
            ],
        ];
        Ok(Affine(std::array::from_fn(|i| {
            [r[i][0] * s[0], r[i][1] * s[1], r[i][2] * s[2], t[i]]
        })))
    }

    /// The elements of accessor `a` (used as `what`), checked against its buffer view, its
    /// buffer and the BIN chunk; `kind` is the accessor type wanted (`VEC3`, `SCALAR`) and
    /// `types` the component types allowed.
    fn elements(&self, a: usize, what: &str, kind: &str, types: &[u32]) -> Result<Elements<'_>> {
        let g = &self.gltf;
        let acc = g.accessors.get(a).ok_or_else(|| {
            self.bad(format!(
                "{what} refers to accessors[{a}] but there are {} accessors",
                g.accessors.len()
            ))
        })?;
        let name = format!("accessors[{a}] ({what})");
        if acc.sparse.is_some() {
            return Err(self.bad(format!(
                "{name} is sparse: sparse accessors are not supported"
            )));
        }
        if acc.kind != kind {
            return Err(self.bad(format!("{name} has type {:?}; expected {kind:?}", acc.kind)));
        }
        let size = match acc.component_type {
            c if !types.contains(&c) => {
                return Err(self.bad(format!(
                    "{name} has componentType {c}; expected one of {types:?}"
                )))
            }
            UNSIGNED_BYTE => 1,
            UNSIGNED_SHORT => 2,
            _ => 4,
        } * if kind == "VEC3" { 3 } else { 1 };
        let Some(v) = acc.buffer_view else {
            return Err(self.bad(format!(
                "{name} has no bufferView: accessors without data are not supported"
            )));
        };
        let view = g.buffer_views.get(v).ok_or_else(|| {
            self.bad(format!(
                "{name} refers to bufferViews[{v}] but there are {} buffer views",
                g.buffer_views.len()
            ))
        })?;
        let b = view.buffer;
        let buffer = g.buffers.get(b).ok_or_else(|| {
            self.bad(format!(
                "bufferViews[{v}] refers to buffers[{b}] but there are {} buffers",
                g.buffers.len()
            ))
        })?;
        match &buffer.uri {
            Some(uri) if uri.starts_with("data:") => {
                return Err(self.bad(format!(
                    "buffers[{b}] ({what}) is a data URI: only the GLB's own BIN chunk is read"
                )))
            }
            Some(uri) => {
                return Err(self.bad(format!(
                    "buffers[{b}] ({what}) is the external file {uri:?}: only the GLB's own \
                     BIN chunk is read"
                )))
            }
            None if b != 0 => {
                return Err(self.bad(format!(
                    "buffers[{b}] has no uri, but only buffers[0] can be the BIN chunk"
                )))
            }
            None => {}
        }
        let Some((bin, bin_at)) = self.bin else {
            return Err(self.bad(format!(
                "the file has no BIN chunk, but {what} needs buffers[0]"
            )));
        };
        if buffer.byte_length > bin.len() as u64 {
            return Err(self.bad(format!(
                "buffers[0].byteLength is {} but the BIN chunk has {} bytes: truncated?",
                buffer.byte_length,
                bin.len()
            )));
        }
        let view_end = view.byte_offset.checked_add(view.byte_length);
        if view_end.is_none_or(|e| e > buffer.byte_length) {
            return Err(self.bad(format!(
                "bufferViews[{v}] (byteOffset {}, byteLength {}) lies outside buffers[0] \
                 ({} bytes)",
                view.byte_offset, view.byte_length, buffer.byte_length
            )));
        }
        let stride = view.byte_stride.unwrap_or(size as u64);
        if stride < size as u64 {
            return Err(self.bad(format!(
                "bufferViews[{v}].byteStride {stride} is less than the {size} bytes of an \
                 element of {name}"
            )));
        }
        let needed = match acc.count {
            0 => Some(acc.byte_offset),
            c => (c - 1)
                .checked_mul(stride)
                .and_then(|x| x.checked_add(size as u64))
                .and_then(|x| x.checked_add(acc.byte_offset)),
        };
        if needed.is_none_or(|n| n > view.byte_length) {
            return Err(self.bad(format!(
                "{name}: {} elements from byteOffset {} with stride {stride} do not fit in \
                 bufferViews[{v}] ({} bytes)",
                acc.count, acc.byte_offset, view.byte_length
            )));
        }
        // All of it lies within the BIN chunk, so these fit in usize.
        let start = (view.byte_offset + acc.byte_offset) as usize;
        let end = (view.byte_offset + view.byte_length) as usize;
        Ok(Elements {
            data: &bin[start..end],
            at: bin_at + start as u64,
            stride: stride as usize,
            count: acc.count as usize,
            component_type: acc.component_type,
        })
    }

    /// Appends a triangle primitive's vertices (moved by `xf`) and triangles.
    fn primitive(
        &self,
        prim: &Primitive,
        mode: u32,
        path: &str,
        xf: &Affine,
        positions: &mut Vec<[f64; 3]>,
        triangles: &mut Vec<[u32; 3]>,
    ) -> Result<()> {
        let Some(pa) = prim.attributes.position else {
            return Err(self.bad(format!("{path} has no POSITION attribute")));
        };
        let pos = self.elements(pa, &format!("POSITION of {path}"), "VEC3", &[FLOAT])?;
        let base = positions.len();
        if (base + pos.count) as u64 > u64::from(u32::MAX) {
            return Err(self.bad(format!("{path}: more than {} vertices in all", u32::MAX)));
        }
        positions.reserve(pos.count);
        for i in 0..pos.count {
            let (b, at) = pos.get(i);
            let mut p = [0.0; 3];
            for (k, c) in p.iter_mut().enumerate() {
                let x = f32::from_le_bytes([b[4 * k], b[4 * k + 1], b[4 * k + 2], b[4 * k + 3]]);
                if !x.is_finite() {
                    return Err(err(
                        at + 4 * k as u64,
                        format!("non-finite coordinate in vertex {i} of {path}"),
                    ));
                }
                *c = f64::from(x);
            }
            positions.push(xf.apply(p));
        }
        let corners: Vec<u32> = match prim.indices {
            None => (0..pos.count as u32).collect(),
            Some(ia) => {
                let ix = self.elements(
                    ia,
                    &format!("indices of {path}"),
                    "SCALAR",
                    &[UNSIGNED_BYTE, UNSIGNED_SHORT, UNSIGNED_INT],
                )?;
                let mut corners = Vec::with_capacity(ix.count);
                for i in 0..ix.count {
                    let (b, at) = ix.get(i);
                    let v = match ix.component_type {
                        UNSIGNED_BYTE => u32::from(b[0]),
                        UNSIGNED_SHORT => u32::from(u16::from_le_bytes([b[0], b[1]])),
                        _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
                    };
                    if v as usize >= pos.count {
                        return Err(err(
                            at,
                            format!(
                                "index {v} of {path} is out of range ({} vertices)",
                                pos.count
                            ),
                        ));
                    }
                    corners.push(v);
                }
                corners
            }
        };
        let first = triangles.len();
        let n = corners.len();
        match mode {
            TRIANGLES => {
                if n % 3 != 0 {
                    return Err(self.bad(format!("{path} has {n} corners, not a multiple of 3")));
                }
                triangles.extend(corners.chunks_exact(3).map(|c| [c[0], c[1], c[2]]));
            }
            // Strips and fans as the specification numbers them; the degenerate triangles
            // that join strips are dropped.
            TRIANGLE_STRIP => {
                for i in 0..n.saturating_sub(2) {
                    let (b, c) = if i % 2 == 0 {
                        (i + 1, i + 2)
                    } else {
                        (i + 2, i + 1)
                    };
                    push_proper(triangles, [corners[i], corners[b], corners[c]]);
                }
            }
            _ => {
                for i in 0..n.saturating_sub(2) {
                    push_proper(triangles, [corners[i + 1], corners[i + 2], corners[0]]);
                }
            }
        }
        let flip = xf.mirrors();
        let base = base as u32;
        for t in &mut triangles[first..] {
            *t = t.map(|i| i + base);
            if flip {
                t.swap(1, 2);
            }
        }
        Ok(())
    }
}

/// Pushes `t` unless two of its corners are the same vertex.
fn push_proper(triangles: &mut Vec<[u32; 3]>, t: [u32; 3]) {
    if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
        triangles.push(t);
    }
}

#[cfg(test)]
#[path = "glb_tests.rs"]
mod tests;
