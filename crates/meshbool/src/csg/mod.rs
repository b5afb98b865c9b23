//! CSG documents: trees of booleans over meshes and primitives, each node with its own
//! transform, evaluated bottom-up with a cache that recomputes only what changed.
//!
//! A [`Scene`] is a tree of [`Node`]s: operations ([`CsgOp`]: union, intersection,
//! difference) over their children, and leaves (mesh files, meshes in memory, the
//! primitives of `meshbool make`). Every node may carry a [`Transform`](crate::Transform),
//! applied to its result, and a [`Role`]: a cutter is subtracted in a difference (the
//! cutters united, then taken from the union of the base children) and ignored, with a
//! note, in a union or an intersection. Open surfaces are operands like any other: a
//! plane cutter removes what lies behind it (the side its normal points away from) and
//! caps the cut.
//!
//! [`evaluate`] computes the root with the library's n-ary booleans, independent subtrees
//! in parallel, and keeps every node's result in a [`Cache`] under a key that hashes
//! everything the result depends on ([`Key`]), so that after an edit only the edited node
//! and its ancestors are computed again. The JSON form of a scene ([`Scene::read`],
//! [`Scene::from_json`]) is documented in docs/csg.md, with a JSON schema in
//! docs/csg.schema.json.

mod cache;
mod eval;
mod scene;

pub use cache::{Cache, Key, Source};
pub use eval::{
    evaluate, CsgOptions, CsgOutput, CsgReport, NamedResult, NodeFailure, NodeProgress, NodeReport,
};
pub use scene::{CsgOp, Node, NodeKind, Role, Scene};
