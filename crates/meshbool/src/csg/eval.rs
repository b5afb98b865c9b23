//! Evaluation of a scene: the nodes' keys, then the tree bottom-up, independent subtrees
//! in parallel, every result kept in the cache by key.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use rayon::prelude::*;
use serde::Serialize;
use web_time::Instant;

use super::cache::{Cache, Key, Source};
use super::scene::{CsgOp, Node, NodeKind, Role, Scene};
use crate::ops::{self, BooleanOptions, Input, Measures, SCHEMA};
use crate::{Error, Mesh, Result, Transform};

/// A callback told of each node as it is done (on the thread that did it), with the
/// number of nodes done so far.
#[derive(Clone)]
pub struct NodeProgress(Arc<NodeCallback>);

/// The callback of a [`NodeProgress`].
type NodeCallback = dyn Fn(&NodeReport, usize) + Send + Sync;

impl NodeProgress {
    /// A callback from a closure.
    pub fn new(f: impl Fn(&NodeReport, usize) + Send + Sync + 'static) -> Self {
        NodeProgress(Arc::new(f))
    }
}

impl std::fmt::Debug for NodeProgress {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("NodeProgress(..)")
    }
}

/// Options of [`evaluate`].
#[derive(Clone, Debug, Default)]
pub struct CsgOptions {
    /// The options of every boolean of the scene (checks, snapping, ...): part of every
    /// operation node's key. Its `run` gives the threads of the whole evaluation (not part
    /// of any key: the results are the same whatever the thread count) and cancellation;
    /// its stage progress is not used (see `progress`).
    pub boolean: BooleanOptions,
    /// Told of each node as it is done.
    pub progress: Option<NodeProgress>,
    /// Also give the result of every named node ([`CsgOutput::named`]), in the root's
    /// output coordinates (for one glTF node per named node: `meshbool csg --each`).
    pub named: bool,
}

/// The result of a named node ([`CsgOptions::named`]).
#[derive(Clone, Debug)]
pub struct NamedResult {
    /// Its path ([`NodeReport::path`]).
    pub path: String,
    /// Its name (the root's, or `root`, for the root).
    pub name: String,
    /// `union`, `intersection`, `difference`, `mesh` or the primitive's name.
    pub kind: &'static str,
    /// Its role in its parent.
    pub role: Role,
    /// Its result with its own transform and every ancestor's applied: where it lies in
    /// the root's result.
    pub mesh: Arc<Mesh>,
}

/// What [`evaluate`] found for one node it visited.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NodeReport {
    /// Where the node is in the document: `root`, `root.children[1]`, ...
    pub path: String,
    /// Its name, if it has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// `union`, `intersection`, `difference`, `mesh` or the primitive's name.
    pub kind: &'static str,
    /// Its role in its parent.
    pub role: Role,
    /// Its key (the hash of what determines its result, docs/csg.md).
    pub key: String,
    /// Where its result came from: an operation found in the cache is not computed
    /// again, and its subtree is not visited (its nodes are not reported).
    pub source: Source,
    /// Measures of its result (transformed); `None` when it failed.
    #[serde(flatten)]
    pub result: Option<Measures>,
    /// Time spent on the node itself (its boolean, reading, generating, transforming;
    /// not its children), in seconds.
    pub seconds: f64,
    /// What was assumed or skipped: cutters ignored outside a difference, empty operands,
    /// the booleans' `assumed` lines, cache entries recomputed or not written.
    pub notes: Vec<String>,
    /// Why the node has no result (its own failure, or a child's).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

/// The node whose result could not be computed (the first found), and why.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct NodeFailure {
    /// Its path ([`NodeReport::path`]).
    pub path: String,
    /// Why.
    pub error: String,
}

/// The result of [`evaluate`].
#[derive(Clone, Debug)]
pub struct CsgOutput {
    /// The root's result (an empty mesh is a valid result); `None` when a node failed.
    pub mesh: Option<Mesh>,
    /// The node that failed, if one did: its ancestors have no result either.
    pub failed: Option<NodeFailure>,
    /// Every node visited, children before their parents (in the document's order).
    pub nodes: Vec<NodeReport>,
    /// With [`CsgOptions::named`] and no failure: the root, then every named node in the
    /// document's order (a parent before its children).
    pub named: Vec<NamedResult>,
    /// Time of the whole evaluation, in seconds.
    pub seconds: f64,
}

/// The JSON of `meshbool csg --json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CsgReport {
    /// [`SCHEMA`].
    pub schema: u32,
    /// Measures of the root's result; absent when a node failed.
    #[serde(flatten)]
    pub result: Option<Measures>,
    /// The node that failed, if one did.
    pub failed: Option<NodeFailure>,
    /// Nodes computed in this evaluation.
    pub computed: usize,
    /// Nodes whose result came from the cache.
    pub cached: usize,
    /// Every node visited ([`CsgOutput::nodes`]).
    pub nodes: Vec<NodeReport>,
    /// [`CsgOutput::seconds`].
    pub seconds: f64,
}

impl CsgOutput {
    /// The report, with the root's measures.
    pub fn report(&self) -> CsgReport {
        let computed = self
            .nodes
            .iter()
            .filter(|n| n.source == Source::Computed)
            .count();
        CsgReport {
            schema: SCHEMA,
            result: self.mesh.as_ref().map(Measures::of),
            failed: self.failed.clone(),
            computed,
            cached: self.nodes.len() - computed,
            nodes: self.nodes.clone(),
            seconds: self.seconds,
        }
    }

    /// The paths of the nodes computed in this evaluation (not taken from the cache).
    pub fn computed(&self) -> Vec<&str> {
        self.nodes
            .iter()
            .filter(|n| n.source == Source::Computed)
            .map(|n| n.path.as_str())
            .collect()
    }
}

/// Evaluates `scene` bottom-up: each operation node's boolean of its children's results
/// (each child transformed by its own transform), n-ary unions and intersections in one
/// call ([`ops::boolean_many`]), a difference as the union of its base children less all
/// its cutters in one call ([`ops::difference_many`]). Independent subtrees run in
/// parallel; the results do not depend on the thread count or the order of evaluation.
///
/// Every node's result is kept in `cache` under its key (the hash of its operation,
/// parameters, transform and its children's keys; a mesh file's key hashes its content),
/// so that after an edit only the nodes whose key changed (the edited node and its
/// ancestors) are computed again; with a cache folder ([`Cache::in_dir`]) results also
/// outlive the process.
///
/// Failure is a value: a node whose result cannot be computed (a file that cannot be
/// read, a boolean refused) is reported in [`CsgOutput::failed`] and the scene has no
/// result. Errors only for options out of range and for cancellation.
///
/// ```
/// use meshbool::csg::{evaluate, Cache, CsgOptions, Node, Scene};
/// use meshbool::ops::Shape;
///
/// let block = Node::primitive(Shape::Cube { min: [0.0; 3], max: [4.0, 2.0, 2.0] });
/// let drill = Node::primitive(Shape::Cube { min: [1.0, -1.0, -1.0], max: [2.0, 3.0, 3.0] }).cutter();
/// let scene = Scene::new(Node::difference(vec![block, drill]).named("slotted"));
/// let cache = Cache::new();
/// let out = evaluate(&scene, &cache, &CsgOptions::default())?;
/// assert_eq!(meshbool::measure::signed_volume(out.mesh.as_ref().unwrap()), 12.0);
/// assert_eq!(out.computed(), ["root.children[0]", "root.children[1]", "root"]);
/// // Again: the root comes from the cache, its subtree is not visited.
/// let again = evaluate(&scene, &cache, &CsgOptions::default())?;
/// assert!(again.computed().is_empty());
/// # Ok::<(), meshbool::Error>(())
/// ```
pub fn evaluate(scene: &Scene, cache: &Cache, opts: &CsgOptions) -> Result<CsgOutput> {
    crate::repair::check_tolerance(opts.boolean.snap)?;
    let start = Instant::now();
    let fingerprint = fingerprint(&opts.boolean);
    let mut order = 0;
    let plan = plan(&scene.root, "root".to_string(), &fingerprint, &mut order);
    let inner = BooleanOptions {
        run: ops::RunOptions {
            threads: None,
            progress: None,
            cancel: opts.boolean.run.cancel.clone(),
        },
        ..opts.boolean.clone()
    };
    let cx = Cx {
        cache,
        opts: &inner,
        progress: opts.progress.as_ref(),
        reports: Mutex::new(vec![None; order]),
        done: AtomicUsize::new(0),
    };
    let result = ops::with_threads(opts.boolean.run.threads, || {
        let root = run(&plan, &cx)?;
        let mut named = Vec::new();
        if opts.named {
            named.push(NamedResult {
                path: plan.path.clone(),
                name: scene.root.name.clone().unwrap_or_else(|| "root".into()),
                kind: scene.root.kind_name(),
                role: scene.root.role,
                mesh: root.clone(),
            });
            for c in &plan.children {
                collect_named(c, &scene.root.transform, &cx, &mut named)?;
            }
        }
        Ok((root, named))
    })?;
    let mut reports = cx.reports.into_inner().unwrap_or_else(|e| e.into_inner());
    let nodes: Vec<NodeReport> = reports.iter_mut().filter_map(Option::take).collect();
    let mut named = Vec::new();
    let (mesh, failed) = match result {
        Ok((mesh, n)) => {
            named = n;
            (Some(Arc::unwrap_or_clone(mesh)), None)
        }
        Err(Failed::Cancelled) => return Err(Error::Cancelled),
        Err(Failed::At(path)) => {
            let error = nodes
                .iter()
                .find(|n| n.path == path)
                .and_then(|n| n.error.clone())
                .unwrap_or_default();
            (None, Some(NodeFailure { path, error }))
        }
    };
    Ok(CsgOutput {
        mesh,
        failed,
        nodes,
        named,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// Adds the named nodes of `plan`'s subtree to `out`, `above` the transform from `plan`'s
/// parent's frame to the root's output (each node's result from the cache, where the
/// evaluation put it, else computed).
fn collect_named(
    plan: &Plan<'_>,
    above: &Transform,
    cx: &Cx<'_>,
    out: &mut Vec<NamedResult>,
) -> std::result::Result<(), Failed> {
    let node = plan.node;
    if let Some(name) = &node.name {
        let mesh = match plan
            .key
            .as_ref()
            .ok()
            .and_then(|k| cx.cached(k, &mut Vec::new()))
        {
            Some((m, _)) => m,
            None => run(plan, cx)?,
        };
        let mesh = if *above == Transform::IDENTITY || mesh.is_empty() {
            mesh
        } else {
            match ops::transform(&mesh, above) {
                Ok(t) => Arc::new(t.mesh),
                Err(_) => return Err(Failed::At(plan.path.clone())),
            }
        };
        out.push(NamedResult {
            path: plan.path.clone(),
            name: name.clone(),
            kind: node.kind_name(),
            role: node.role,
            mesh,
        });
    }
    let below = node.transform.then(above);
    for c in &plan.children {
        collect_named(c, &below, cx, out)?;
    }
    Ok(())
}

/// A node with its path, keys and place among the reports.
struct Plan<'s> {
    node: &'s Node,
    path: String,
    /// Its place in the reports (children before parents).
    order: usize,
    /// The key of its (transformed) result; `Err` for a mesh file that cannot be read.
    key: std::result::Result<Key, String>,
    /// An operation's key before its own transform.
    op_key: Option<Key>,
    children: Vec<Plan<'s>>,
}

/// The hash of the boolean options that change results (not the threads).
fn fingerprint(o: &BooleanOptions) -> Vec<u8> {
    let c = &o.checks;
    let flags = [
        c.edges,
        c.self_intersections,
        c.orient,
        c.resolve,
        c.force,
        c.rounding_noise,
        o.keep_nonmanifold,
        o.keep_seam_points,
        o.one_arrangement,
        o.sliver_guard,
    ];
    let mut v: Vec<u8> = flags.iter().map(|&f| u8::from(f)).collect();
    v.extend_from_slice(&o.snap.to_bits().to_le_bytes());
    v
}

/// A hasher for keys of this library version.
fn hasher(kind: &[u8]) -> blake3::Hasher {
    let mut h = blake3::Hasher::new();
    h.update(b"meshbool csg ");
    h.update(env!("CARGO_PKG_VERSION").as_bytes());
    h.update(b"\0");
    h.update(kind);
    h.update(b"\0");
    h
}

fn finish(h: &blake3::Hasher) -> Key {
    Key(*h.finalize().as_bytes())
}

/// The transform's part of a key.
fn hash_transform(h: &mut blake3::Hasher, t: &Transform) {
    for x in t.to_row_major() {
        h.update(&x.to_bits().to_le_bytes());
    }
}

/// The plan of `node` at `path`: its children's first (their places numbered in order).
fn plan<'s>(node: &'s Node, path: String, fingerprint: &[u8], order: &mut usize) -> Plan<'s> {
    let children: Vec<Plan<'s>> = match &node.kind {
        NodeKind::Op { children, .. } => children
            .iter()
            .enumerate()
            .map(|(k, c)| plan(c, format!("{path}.children[{k}]"), fingerprint, order))
            .collect(),
        _ => Vec::new(),
    };
    let (key, op_key) = match &node.kind {
        NodeKind::Op { op, .. } => {
            let mut h = hasher(b"op");
            h.update(fingerprint);
            h.update(op.name().as_bytes());
            h.update(&(children.len() as u64).to_le_bytes());
            let mut missing = None;
            for c in &children {
                h.update(&[u8::from(c.node.role == Role::Cutter)]);
                match &c.key {
                    Ok(k) => {
                        h.update(&k.0);
                    }
                    Err(_) => missing = Some(()),
                }
            }
            let op_key = finish(&h);
            let key = if node.transform == Transform::IDENTITY {
                op_key
            } else {
                let mut h = hasher(b"moved");
                h.update(&op_key.0);
                hash_transform(&mut h, &node.transform);
                finish(&h)
            };
            let key = match missing {
                Some(()) => Err("a child has no key".to_string()),
                None => Ok(key),
            };
            (key, Some(op_key))
        }
        leaf => {
            let mut h = hasher(b"leaf");
            let content = match leaf {
                NodeKind::File(path) => file_content(path).map(|c| {
                    h.update(b"file");
                    h.update(c.as_bytes());
                }),
                NodeKind::Mesh(m) => {
                    h.update(b"mesh");
                    h.update(&(m.positions().len() as u64).to_le_bytes());
                    for x in m.positions().iter().flatten() {
                        h.update(&x.to_bits().to_le_bytes());
                    }
                    for v in m.triangles().iter().flatten() {
                        h.update(&v.to_le_bytes());
                    }
                    Ok(())
                }
                NodeKind::Primitive(s) => {
                    // Debug prints every f64 so that it reads back exactly.
                    h.update(format!("{s:?}").as_bytes());
                    Ok(())
                }
                NodeKind::Op { .. } => unreachable!("an operation is not a leaf"),
            };
            hash_transform(&mut h, &node.transform);
            (content.map(|()| finish(&h)), None)
        }
    };
    let me = *order;
    *order += 1;
    Plan {
        node,
        path,
        order: me,
        key,
        op_key,
        children,
    }
}

/// The hash of a mesh file's content (a Surpac DTM's string file beside it included).
fn file_content(path: &std::path::Path) -> std::result::Result<blake3::Hash, String> {
    let read = |p: &std::path::Path| {
        std::fs::read(p).map_err(|e| format!("cannot read {}: {e}", p.display()))
    };
    let mut h = blake3::Hasher::new();
    h.update(&read(path)?);
    if crate::Format::for_path(path) == Some(crate::Format::SurpacDtm) {
        if let Ok(strings) = std::fs::read(path.with_extension("str")) {
            h.update(&strings);
        }
    }
    Ok(h.finalize())
}

/// What an evaluation shares between its threads.
struct Cx<'a> {
    cache: &'a Cache,
    /// The booleans' options (in the evaluation's pool, without stage progress).
    opts: &'a BooleanOptions,
    progress: Option<&'a NodeProgress>,
    reports: Mutex<Vec<Option<NodeReport>>>,
    done: AtomicUsize,
}

/// Why a node has no result.
enum Failed {
    /// The node at this path failed (it, or a node below it).
    At(String),
    /// The evaluation was cancelled.
    Cancelled,
}

impl Cx<'_> {
    /// The result of `key` from the cache's memory, else from its folder (then kept in
    /// memory too); a damaged entry is noted and not used.
    fn cached(&self, key: &Key, notes: &mut Vec<String>) -> Option<(Arc<Mesh>, Source)> {
        if let Some(m) = self.cache.get(key) {
            return Some((m, Source::Memory));
        }
        match self.cache.load(key) {
            Ok(Some(m)) => {
                let m = Arc::new(m);
                self.cache.put(*key, m.clone());
                Some((m, Source::Disk))
            }
            Ok(None) => None,
            Err(why) => {
                notes.push(format!("cache entry {why}; recomputed"));
                None
            }
        }
    }

    /// Keeps `mesh` as `key`'s result, in memory and in the folder (a failed write is
    /// noted: the result stands).
    fn keep(&self, key: &Key, mesh: &Arc<Mesh>, notes: &mut Vec<String>) {
        self.cache.put(*key, mesh.clone());
        if let Err(why) = self.cache.store(key, mesh) {
            notes.push(format!("cache entry not written: {why}"));
        }
    }

    /// Files `report` and tells the progress callback.
    fn finish(&self, order: usize, report: NodeReport) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        if let Some(p) = self.progress {
            (p.0)(&report, done);
        }
        let mut reports = self.reports.lock().unwrap_or_else(|e| e.into_inner());
        reports[order] = Some(report);
    }
}

/// The result of `plan`'s node: from the cache, or computed (its children first, in
/// parallel).
fn run(plan: &Plan<'_>, cx: &Cx<'_>) -> std::result::Result<Arc<Mesh>, Failed> {
    let node = plan.node;
    let mut report = NodeReport {
        path: plan.path.clone(),
        name: node.name.clone(),
        kind: node.kind_name(),
        role: node.role,
        key: plan.key.as_ref().map(Key::hex).unwrap_or_default(),
        source: Source::Computed,
        result: None,
        seconds: 0.0,
        notes: Vec::new(),
        error: None,
    };
    let fail = |mut report: NodeReport, error: String, at: String| {
        report.error = Some(error);
        cx.finish(plan.order, report);
        Err(Failed::At(at))
    };
    if let Ok(key) = &plan.key {
        if let Some((mesh, source)) = cx.cached(key, &mut report.notes) {
            report.source = source;
            report.result = Some(Measures::of(&mesh));
            cx.finish(plan.order, report);
            return Ok(mesh);
        }
    }
    let start;
    let untransformed: Arc<Mesh> = match &node.kind {
        NodeKind::Op { op, .. } => {
            let op_key = plan.op_key.expect("an operation has an op key");
            // A node moved by a new transform: its boolean as it was.
            let moved = (node.transform != Transform::IDENTITY)
                .then(|| cx.cached(&op_key, &mut report.notes))
                .flatten();
            match moved {
                Some((m, source)) => {
                    report.source = source;
                    start = Instant::now();
                    m
                }
                None => {
                    let results: Vec<_> = plan.children.par_iter().map(|c| run(c, cx)).collect();
                    let mut children = Vec::with_capacity(results.len());
                    for (c, r) in plan.children.iter().zip(results) {
                        match r {
                            Ok(m) => children.push((c, m)),
                            Err(Failed::Cancelled) => return Err(Failed::Cancelled),
                            Err(Failed::At(at)) => {
                                return fail(report, format!("{} failed", c.path), at)
                            }
                        }
                    }
                    start = Instant::now();
                    match combine(*op, &children, cx.opts, &mut report.notes) {
                        Ok(m) => {
                            let m = Arc::new(m);
                            if node.transform != Transform::IDENTITY {
                                cx.keep(&op_key, &m, &mut report.notes);
                            }
                            m
                        }
                        Err(Error::Cancelled) => return Err(Failed::Cancelled),
                        Err(e) => return fail(report, e.to_string(), plan.path.clone()),
                    }
                }
            }
        }
        leaf => {
            start = Instant::now();
            let mesh = match leaf {
                NodeKind::File(path) => match &plan.key {
                    Err(why) => return fail(report, why.clone(), plan.path.clone()),
                    Ok(_) => ops::read(path, None).map(|(m, _)| Arc::new(m)),
                },
                NodeKind::Mesh(m) => Ok(m.clone()),
                NodeKind::Primitive(s) => s.mesh().map(Arc::new),
                NodeKind::Op { .. } => unreachable!("an operation is not a leaf"),
            };
            match mesh {
                Ok(m) => m,
                Err(e) => return fail(report, e.to_string(), plan.path.clone()),
            }
        }
    };
    let mesh = if node.transform == Transform::IDENTITY || untransformed.is_empty() {
        untransformed
    } else {
        match ops::transform(&untransformed, &node.transform) {
            Ok(out) => Arc::new(out.mesh),
            Err(e) => return fail(report, e.to_string(), plan.path.clone()),
        }
    };
    if let Ok(key) = &plan.key {
        cx.keep(key, &mesh, &mut report.notes);
    }
    report.result = Some(Measures::of(&mesh));
    report.seconds = start.elapsed().as_secs_f64();
    cx.finish(plan.order, report);
    Ok(mesh)
}

/// The boolean `op` of `children` (their results, transformed), with what it assumed
/// added to `notes`.
fn combine(
    op: CsgOp,
    children: &[(&Plan<'_>, Arc<Mesh>)],
    opts: &BooleanOptions,
    notes: &mut Vec<String>,
) -> Result<Mesh> {
    let (mut bases, mut cutters): (Vec<_>, Vec<_>) = children
        .iter()
        .partition(|(c, _)| c.node.role == Role::Base);
    if op != CsgOp::Difference {
        for (c, _) in &cutters {
            notes.push(format!(
                "{} is a cutter: ignored in {} (a cutter acts in a difference)",
                c.path,
                match op {
                    CsgOp::Union => "a union",
                    _ => "an intersection",
                }
            ));
        }
        cutters.clear();
    } else if cutters.is_empty() && !bases.is_empty() {
        // Without cutters: the first child less the others.
        cutters = bases.split_off(1);
    }
    let mut empty = |list: &mut Vec<&(&Plan<'_>, Arc<Mesh>)>| {
        let before = list.len();
        let paths: Vec<String> = list
            .iter()
            .filter(|(_, m)| m.is_empty())
            .map(|(c, _)| c.path.clone())
            .collect();
        list.retain(|(_, m)| !m.is_empty());
        if list.len() < before {
            notes.push(format!("empty operands: {}", paths.join(", ")));
        }
        list.len() < before
    };
    let base_had_empty = empty(&mut bases);
    if op == CsgOp::Intersection && base_had_empty {
        return Ok(Mesh::default());
    }
    empty(&mut cutters);
    let meshes = |list: &[&(&Plan<'_>, Arc<Mesh>)]| -> Vec<Arc<Mesh>> {
        list.iter().map(|(_, m)| m.clone()).collect()
    };
    let mut assumed = Vec::new();
    let base = match op {
        CsgOp::Intersection => many(&meshes(&bases), crate::Op::Intersection, opts, &mut assumed)?,
        _ => many(&meshes(&bases), crate::Op::Union, opts, &mut assumed)?,
    };
    let result = if cutters.is_empty() || base.is_empty() {
        base
    } else {
        let mut all = vec![Arc::new(base)];
        all.extend(meshes(&cutters));
        let inputs: Vec<Input> = all.iter().map(|m| Input::from(&**m)).collect();
        let out = ops::difference_many(&inputs, opts)?;
        assumed.extend(out.report().assumed);
        out.mesh
    };
    notes.extend(assumed);
    Ok(result)
}

/// The union or intersection of `meshes`: none gives an empty mesh, one itself.
fn many(
    meshes: &[Arc<Mesh>],
    op: crate::Op,
    opts: &BooleanOptions,
    assumed: &mut Vec<String>,
) -> Result<Mesh> {
    match meshes {
        [] => Ok(Mesh::default()),
        [one] => Ok((**one).clone()),
        _ => {
            let inputs: Vec<Input> = meshes.iter().map(|m| Input::from(&**m)).collect();
            let out = ops::boolean_many(&inputs, op, opts)?;
            assumed.extend(out.report().assumed);
            Ok(out.mesh)
        }
    }
}
