//! The scene tree ([`Scene`], [`Node`]) and its JSON form (docs/csg.md,
//! docs/csg.schema.json).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use serde_json::{Map, Value};

use crate::ops::{Shape, ShapeJsonError, ShapeKeys};
use crate::{Error, Mesh, Result, Transform};

/// A CSG document: a tree of booleans over meshes and primitives.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The tree's root; its result is the scene's.
    pub root: Node,
}

/// The boolean of an operation node ([`NodeKind::Op`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CsgOp {
    /// The union of the base children.
    Union,
    /// The intersection of the base children.
    Intersection,
    /// The union of the base children less the union of the cutters; without cutters,
    /// the first child less the others.
    Difference,
}

impl CsgOp {
    /// Every operation, in the order of their names.
    pub const ALL: [CsgOp; 3] = [CsgOp::Union, CsgOp::Intersection, CsgOp::Difference];

    /// `union`, `intersection` or `difference`.
    pub fn name(self) -> &'static str {
        match self {
            CsgOp::Union => "union",
            CsgOp::Intersection => "intersection",
            CsgOp::Difference => "difference",
        }
    }
}

by_name!(CsgOp, "CSG operation");

/// What a child does in its parent's boolean.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Role {
    /// An operand of the parent's operation (the default).
    #[default]
    Base,
    /// Subtracted in a difference (the cutters are united, then taken from the union of
    /// the base children); ignored, with a note, in a union or an intersection.
    Cutter,
}

/// What a node is: an operation on its children, or a leaf.
#[derive(Clone, Debug, PartialEq)]
pub enum NodeKind {
    /// A boolean of the children, each with its own transform and role.
    Op {
        /// The operation.
        op: CsgOp,
        /// Its operands.
        children: Vec<Node>,
    },
    /// A mesh file, read as [`crate::ops::read`] reads it (any readable format).
    File(PathBuf),
    /// A mesh given in memory.
    Mesh(Arc<Mesh>),
    /// A primitive of `meshbool make` ([`crate::ops::make`]).
    Primitive(Shape),
}

/// A node of the tree: what it is, its transform, its role in its parent and its name.
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    /// An operation or a leaf.
    pub kind: NodeKind,
    /// Applied to the node's result (a leaf's mesh, an operation's boolean) before its
    /// parent uses it.
    pub transform: Transform,
    /// Base operand or cutter in the parent's operation.
    pub role: Role,
    /// A name for reports (and, in a document, for the reader).
    pub name: Option<String>,
}

impl Node {
    /// A node of `kind`, untransformed, a base operand, unnamed.
    pub fn new(kind: NodeKind) -> Node {
        Node {
            kind,
            transform: Transform::IDENTITY,
            role: Role::Base,
            name: None,
        }
    }

    /// The operation `op` of `children`.
    pub fn op(op: CsgOp, children: Vec<Node>) -> Node {
        Node::new(NodeKind::Op { op, children })
    }

    /// The union of `children`.
    pub fn union(children: Vec<Node>) -> Node {
        Node::op(CsgOp::Union, children)
    }

    /// The intersection of `children`.
    pub fn intersection(children: Vec<Node>) -> Node {
        Node::op(CsgOp::Intersection, children)
    }

    /// The difference of `children` (the base children less the cutters; without
    /// cutters, the first less the others).
    pub fn difference(children: Vec<Node>) -> Node {
        Node::op(CsgOp::Difference, children)
    }

    /// A primitive leaf.
    pub fn primitive(shape: Shape) -> Node {
        Node::new(NodeKind::Primitive(shape))
    }

    /// A mesh-file leaf.
    pub fn file(path: impl Into<PathBuf>) -> Node {
        Node::new(NodeKind::File(path.into()))
    }

    /// An in-memory mesh leaf.
    pub fn mesh(mesh: impl Into<Arc<Mesh>>) -> Node {
        Node::new(NodeKind::Mesh(mesh.into()))
    }

    /// This node, named.
    pub fn named(mut self, name: impl Into<String>) -> Node {
        self.name = Some(name.into());
        self
    }

    /// This node as a cutter of its parent ([`Role::Cutter`]).
    pub fn cutter(mut self) -> Node {
        self.role = Role::Cutter;
        self
    }

    /// This node with `t` applied after its transform.
    pub fn transformed(mut self, t: &Transform) -> Node {
        self.transform = self.transform.then(t);
        self
    }

    /// What the node is, for reports: the operation, `mesh`, or the primitive's name.
    pub fn kind_name(&self) -> &'static str {
        match &self.kind {
            NodeKind::Op { op, .. } => op.name(),
            NodeKind::File(_) | NodeKind::Mesh(_) => "mesh",
            NodeKind::Primitive(s) => s.name(),
        }
    }
}

/// The error of a malformed document, at `at` (a JSON path such as
/// `root.children[1].radius`).
fn malformed(at: &str, message: impl std::fmt::Display) -> Error {
    Error::Malformed {
        what: "CSG scene",
        message: format!("{at}: {message}"),
    }
}

impl Scene {
    /// A scene of one root.
    pub fn new(root: Node) -> Scene {
        Scene { root }
    }

    /// Reads a scene document; its mesh paths are relative to the document's folder.
    /// Errors name the file; a malformed document's error says where (`root.children[2]`).
    pub fn read(path: impl AsRef<Path>) -> Result<Scene> {
        let path = path.as_ref();
        let text =
            std::fs::read_to_string(path).map_err(|e| Error::from(e).in_file("reading", path))?;
        let base = path.parent().unwrap_or(Path::new(""));
        Scene::from_json(&text, base).map_err(|e| e.in_file("reading", path))
    }

    /// A scene from its JSON text; relative mesh paths are taken from `base`.
    pub fn from_json(text: &str, base: &Path) -> Result<Scene> {
        Scene::from_json_with(text, base, &[])
    }

    /// A scene from its JSON text whose mesh leaves may also name, by a whole number `k`
    /// (`{"mesh": 0}`), the `k`-th of `meshes`: meshes in memory, as the Python and
    /// JavaScript packages pass them.
    pub fn from_json_with(text: &str, base: &Path, meshes: &[Arc<Mesh>]) -> Result<Scene> {
        let value: Value = serde_json::from_str(text).map_err(|e| {
            malformed(
                &format!("line {} column {}", e.line(), e.column()),
                format!("not JSON: {e}"),
            )
        })?;
        Scene::from_value_with(&value, base, meshes)
    }

    /// A scene from a parsed JSON document ([`Scene::from_json`]).
    pub fn from_value(value: &Value, base: &Path) -> Result<Scene> {
        Scene::from_value_with(value, base, &[])
    }

    /// A scene from a parsed JSON document with meshes in memory
    /// ([`Scene::from_json_with`]).
    pub fn from_value_with(value: &Value, base: &Path, meshes: &[Arc<Mesh>]) -> Result<Scene> {
        let doc = object(value, "the document")?;
        for key in doc.keys() {
            if !matches!(key.as_str(), "root" | "version" | "$schema" | "description") {
                return Err(malformed(
                    key,
                    "unknown key (a document has root, and may have version, $schema, description)",
                ));
            }
        }
        if let Some(v) = doc.get("version") {
            if v.as_u64() != Some(1) {
                return Err(malformed(
                    "version",
                    format!("only version 1 is known, got {v}"),
                ));
            }
        }
        let root = doc
            .get("root")
            .ok_or_else(|| malformed("the document", "no root node"))?;
        Ok(Scene {
            root: node(root, "root", &Inputs { base, meshes })?,
        })
    }
}

/// `value` as an object, or the error at `at`.
fn object<'v>(value: &'v Value, at: &str) -> Result<&'v Map<String, Value>> {
    value
        .as_object()
        .ok_or_else(|| malformed(at, format!("expected an object, got {}", type_of(value))))
}

/// A JSON value's type, for messages.
fn type_of(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "a list",
        Value::Object(_) => "an object",
    }
}

/// The keys every node may have beside what makes it a node.
const COMMON: [&str; 3] = ["name", "transform", "role"];

/// Where a document's mesh leaves are found: files relative to `base`, meshes in memory
/// by index.
struct Inputs<'a> {
    base: &'a Path,
    meshes: &'a [Arc<Mesh>],
}

/// The node at `at`.
fn node(value: &Value, at: &str, inputs: &Inputs<'_>) -> Result<Node> {
    let obj = object(value, at)?;
    let kinds: Vec<&str> = ["op", "mesh", "primitive"]
        .into_iter()
        .filter(|k| obj.contains_key(*k))
        .collect();
    let kind = match kinds[..] {
        ["op"] => {
            allow_keys(obj, at, &["op", "children"])?;
            let op = string(&obj["op"], &format!("{at}.op"))?;
            let op: CsgOp = op.parse().map_err(|_| {
                malformed(
                    &format!("{at}.op"),
                    format!("unknown operation `{op}` (union, intersection or difference)"),
                )
            })?;
            let list_at = format!("{at}.children");
            let list = obj
                .get("children")
                .ok_or_else(|| malformed(at, "an operation needs children (a list of nodes)"))?
                .as_array()
                .ok_or_else(|| malformed(&list_at, "expected a list of nodes"))?;
            let children = list
                .iter()
                .enumerate()
                .map(|(k, c)| node(c, &format!("{list_at}[{k}]"), inputs))
                .collect::<Result<_>>()?;
            NodeKind::Op { op, children }
        }
        ["mesh"] => {
            allow_keys(obj, at, &["mesh"])?;
            let mesh_at = format!("{at}.mesh");
            match &obj["mesh"] {
                Value::Number(n) => {
                    let m = n
                        .as_u64()
                        .and_then(|k| inputs.meshes.get(usize::try_from(k).ok()?))
                        .ok_or_else(|| {
                            malformed(
                                &mesh_at,
                                format!(
                                    "mesh {n} is not one of the {} meshes given beside the document",
                                    inputs.meshes.len()
                                ),
                            )
                        })?;
                    NodeKind::Mesh(m.clone())
                }
                v => {
                    let path = PathBuf::from(string(v, &mesh_at)?);
                    NodeKind::File(if path.is_relative() {
                        inputs.base.join(path)
                    } else {
                        path
                    })
                }
            }
        }
        ["primitive"] => NodeKind::Primitive(primitive(obj, at)?),
        [] => {
            return Err(malformed(
                at,
                "a node is an operation (op), a mesh file (mesh) or a primitive (primitive)",
            ))
        }
        _ => {
            return Err(malformed(
                at,
                format!(
                    "a node is one of op, mesh, primitive; got {}",
                    kinds.join(" and ")
                ),
            ))
        }
    };
    let name = match obj.get("name") {
        None => None,
        Some(v) => Some(string(v, &format!("{at}.name"))?.to_string()),
    };
    let role = match obj.get("role") {
        None => Role::Base,
        Some(v) => match string(v, &format!("{at}.role"))? {
            "cutter" => Role::Cutter,
            "base" => Role::Base,
            other => {
                return Err(malformed(
                    &format!("{at}.role"),
                    format!("unknown role `{other}` (cutter or base)"),
                ))
            }
        },
    };
    let transform = match obj.get("transform") {
        None => Transform::IDENTITY,
        Some(v) => transform(v, &format!("{at}.transform"))?,
    };
    Ok(Node {
        kind,
        transform,
        role,
        name,
    })
}

/// Errors for a key of `obj` that is neither in `own` nor common to every node.
fn allow_keys(obj: &Map<String, Value>, at: &str, own: &[&str]) -> Result<()> {
    match obj
        .keys()
        .find(|k| !own.contains(&k.as_str()) && !COMMON.contains(&k.as_str()))
    {
        Some(k) => Err(malformed(
            &format!("{at}.{k}"),
            format!(
                "unknown key (this node takes {})",
                [own, &COMMON[..]].concat().join(", ")
            ),
        )),
        None => Ok(()),
    }
}

fn string<'v>(v: &'v Value, at: &str) -> Result<&'v str> {
    v.as_str()
        .ok_or_else(|| malformed(at, format!("expected a string, got {}", type_of(v))))
}

fn number(v: &Value, at: &str) -> Result<f64> {
    match v.as_f64() {
        Some(x) if x.is_finite() => Ok(x),
        _ => Err(malformed(at, format!("expected a finite number, got {v}"))),
    }
}

/// `n` numbers.
fn numbers(v: &Value, at: &str, n: usize) -> Result<Vec<f64>> {
    let list = v
        .as_array()
        .filter(|l| l.len() == n)
        .ok_or_else(|| malformed(at, format!("expected a list of {n} numbers, got {v}")))?;
    list.iter()
        .enumerate()
        .map(|(k, x)| number(x, &format!("{at}[{k}]")))
        .collect()
}

fn point(v: &Value, at: &str) -> Result<[f64; 3]> {
    let p = numbers(v, at, 3)?;
    Ok([p[0], p[1], p[2]])
}

/// One number for all `N` components or a list of `N`.
fn one_or<const N: usize>(v: &Value, at: &str) -> Result<[f64; N]> {
    if v.is_number() {
        return Ok([number(v, at)?; N]);
    }
    let p = numbers(v, at, N).map_err(|_| {
        malformed(
            at,
            format!("expected a number or a list of {N} numbers, got {v}"),
        )
    })?;
    Ok(std::array::from_fn(|k| p[k]))
}

/// A node's `transform`: one step object or a list of them, applied in order.
fn transform(v: &Value, at: &str) -> Result<Transform> {
    match v {
        Value::Array(steps) => steps
            .iter()
            .enumerate()
            .try_fold(Transform::IDENTITY, |t, (k, s)| {
                Ok(t.then(&step(s, &format!("{at}[{k}]"))?))
            }),
        _ => step(v, at),
    }
}

/// One transform object: `scale`, `rotate` and `translate` (applied in that order, each
/// optional), or `matrix` alone.
fn step(v: &Value, at: &str) -> Result<Transform> {
    let obj = object(v, at)?;
    let invalid = |key: &str, e: Error| match e {
        Error::InvalidParameter(m) => malformed(&format!("{at}.{key}"), m),
        e => e,
    };
    if let Some(m) = obj.get("matrix") {
        if obj.len() > 1 {
            return Err(malformed(
                at,
                "matrix stands alone in its object (put other steps before or after it in a list)",
            ));
        }
        let m = numbers(m, &format!("{at}.matrix"), 16)?;
        let t = Transform::from_row_major(std::array::from_fn(|k| m[k]))
            .map_err(|e| invalid("matrix", e))?;
        if t.determinant() == 0.0 {
            return Err(malformed(
                &format!("{at}.matrix"),
                "the matrix is singular (determinant 0)",
            ));
        }
        return Ok(t);
    }
    if let Some(k) = obj
        .keys()
        .find(|k| !matches!(k.as_str(), "scale" | "rotate" | "translate"))
    {
        return Err(malformed(
            &format!("{at}.{k}"),
            "unknown transform step (scale, rotate, translate, or matrix alone)",
        ));
    }
    let mut t = Transform::IDENTITY;
    if let Some(s) = obj.get("scale") {
        let f = one_or::<3>(s, &format!("{at}.scale"))?;
        if f.contains(&0.0) {
            return Err(malformed(
                &format!("{at}.scale"),
                "a scale factor of 0 would flatten the mesh",
            ));
        }
        t = t.then(&Transform::scaling_xyz(f));
    }
    if let Some(r) = obj.get("rotate") {
        t = t.then(&rotation(r, &format!("{at}.rotate"))?);
    }
    if let Some(p) = obj.get("translate") {
        t = t.then(&Transform::translation(point(
            p,
            &format!("{at}.translate"),
        )?));
    }
    Ok(t)
}

/// `["z", 30]` or `[ax, ay, az, degrees]`.
fn rotation(v: &Value, at: &str) -> Result<Transform> {
    const USE: &str =
        "expected [AXIS, DEGREES] with AXIS \"x\", \"y\" or \"z\", or [AX, AY, AZ, DEGREES]";
    let list = v.as_array().ok_or_else(|| malformed(at, USE))?;
    let (axis, degrees) = match &list[..] {
        [Value::String(name), d] => {
            let axis = match name.to_ascii_lowercase().as_str() {
                "x" => [1.0, 0.0, 0.0],
                "y" => [0.0, 1.0, 0.0],
                "z" => [0.0, 0.0, 1.0],
                _ => {
                    return Err(malformed(
                        &format!("{at}[0]"),
                        format!("unknown axis `{name}`: {USE}"),
                    ))
                }
            };
            (axis, number(d, &format!("{at}[1]"))?)
        }
        [_, _, _, _] => {
            let n = numbers(v, at, 4)?;
            ([n[0], n[1], n[2]], n[3])
        }
        _ => return Err(malformed(at, USE)),
    };
    Transform::rotation(axis, degrees).map_err(|e| match e {
        Error::InvalidParameter(m) => malformed(at, m),
        e => e,
    })
}

/// A primitive leaf's shape: the parameters of `meshbool make`, with its defaults.
fn primitive(obj: &Map<String, Value>, at: &str) -> Result<Shape> {
    let name = string(&obj["primitive"], &format!("{at}.primitive"))?;
    let others = [&["primitive"][..], &COMMON[..]].concat();
    let shape = Shape::from_json(name, obj, ShapeKeys::Document, &others).map_err(|e| match e {
        ShapeJsonError::UnknownShape(_) => malformed(&format!("{at}.primitive"), e),
        ShapeJsonError::UnknownKey { key, known } => malformed(
            &format!("{at}.{key}"),
            format!(
                "unknown key (this node takes {})",
                [&others[..1], &known, &others[1..]].concat().join(", ")
            ),
        ),
        ShapeJsonError::Value { key, message } => malformed(&format!("{at}.{key}"), message),
        ShapeJsonError::Keys(message) => malformed(at, message),
    })?;
    // The parameters' ranges, checked here so that the error says where.
    shape.mesh().map_err(|e| match e {
        Error::InvalidParameter(m) => malformed(at, m),
        e => e,
    })?;
    Ok(shape)
}
