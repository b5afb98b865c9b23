use std::sync::{Arc, Mutex};

use super::*;
use crate::boolean::{Group, Op};
use crate::measure::signed_volume;
use crate::repair::{CloseMode, CloseOptions, Facing};
use crate::test_util::shared_data;

fn cubes() -> (Mesh, Mesh) {
    (Mesh::unit_cube(), Mesh::cuboid([0.5; 3], [1.5; 3]))
}

/// A cube with a corner pushed through its bottom: one component crossing itself.
fn folded_cube() -> Mesh {
    let (mut positions, triangles) = Mesh::unit_cube().into_parts();
    for p in &mut positions {
        if *p == [1.0; 3] {
            *p = [0.5, 0.5, -0.5];
        }
    }
    Mesh::new(positions, triangles).unwrap()
}

/// The folded cube with a triangle of its face x = 0 taken out: it crosses itself and
/// is open, so it cannot be resolved into a solid.
fn self_intersecting() -> Mesh {
    let m = folded_cube();
    let (positions, mut triangles) = m.clone().into_parts();
    let t = (0..triangles.len())
        .find(|&t| m.corners(t).iter().all(|p| p[0] == 0.0))
        .unwrap();
    triangles.remove(t);
    Mesh::new(positions, triangles).unwrap()
}

#[test]
fn boolean_of_meshes_satisfies_the_volume_identities() {
    let (a, b) = cubes();
    let vol = |op| {
        let out = boolean(&a, &b, op, &BooleanOptions::default()).unwrap();
        let r = out.report();
        assert!(r.result.closed, "{op}");
        assert_eq!(r.result.volume, signed_volume(&out.mesh));
        assert_eq!(r.operation, op);
        assert!(r.assumed.is_empty(), "{op}: {:?}", r.assumed);
        r.result.volume
    };
    let (u, i, d, rd) = (
        vol(Op::Union),
        vol(Op::Intersection),
        vol(Op::Difference),
        vol(Op::ReverseDifference),
    );
    assert_eq!(u + i, 2.0);
    assert_eq!(d, 1.0 - i);
    assert_eq!(rd, 1.0 - i);
    assert_eq!(i, 0.125);
}

#[test]
fn invalid_meshes_are_errors_at_the_door() {
    let (a, _) = cubes();
    // Indices out of range cannot make a mesh at all.
    let (positions, mut triangles) = a.clone().into_parts();
    triangles[3][1] = 99;
    assert!(matches!(
        Mesh::new(positions, triangles),
        Err(Error::InvalidMesh { .. })
    ));
    let mut nan = a.clone();
    nan.positions_mut()[2][0] = f64::NAN;
    let bad = &nan;
    let opts = BooleanOptions::default();
    assert!(matches!(
        boolean(bad, &a, Op::Union, &opts),
        Err(Error::InvalidMesh { .. })
    ));
    assert!(matches!(
        boolean(&a, bad, Op::Union, &opts),
        Err(Error::InvalidMesh { .. })
    ));
    assert!(split(bad, &a, &SplitOptions::default()).is_err());
    assert!(curves(&a, bad, &CurvesOptions::default()).is_err());
    assert!(info(bad).is_err());
    assert!(orient(bad, Facing::Majority).is_err());
    assert!(close(bad, CloseMode::Cap, &Default::default()).is_err());
    assert!(repair(bad, &Default::default()).is_err());
    assert!(Operand::new("x", bad, &Checks::NONE).is_err());
}

#[test]
fn operands_with_problems_are_refused_unless_forced() {
    let terrain = shared_data("kirra_terrain.obj");
    let (Some(terrain), Some(cylinder)) = (terrain, shared_data("kirra_cylinder.obj")) else {
        return;
    };
    // By default the terrain's orientation is made consistent at the door: the same
    // result as orienting it first.
    let out = boolean(
        &terrain,
        &cylinder,
        Op::Difference,
        &BooleanOptions::default(),
    )
    .unwrap();
    assert_eq!(out.operands[0].inconsistent_edges, Some(46));
    assert_eq!(out.operands[0].reoriented_triangles, 22);
    assert_eq!(
        out.assumed(),
        ["A: 46 inconsistently oriented edges made consistent: 22 triangles reversed (each component faces as most of its triangles did)"]
    );
    let up = crate::repair::orient(&terrain, Facing::ZUp).0;
    let first = boolean(&up, &cylinder, Op::Difference, &BooleanOptions::default()).unwrap();
    assert_eq!(out.mesh, first.mesh);
    // Reversed triangles face against their input triangles in the provenance.
    let flipped_a = out
        .provenance
        .iter()
        .filter(|p| p.source == crate::Source::A && p.flipped)
        .count();
    assert!(flipped_a > 0);
    // Asked not to orient, the inconsistent operand is a problem.
    let strict = Checks {
        orient: false,
        ..Checks::default()
    };
    let err = boolean(
        &terrain,
        &cylinder,
        Op::Difference,
        &BooleanOptions {
            checks: strict,
            ..BooleanOptions::default()
        },
    )
    .unwrap_err();
    let Error::Operand { name, problems } = &err else {
        panic!("{err}")
    };
    assert_eq!(name, "A");
    assert_eq!(problems.len(), 1);
    assert!(
        problems[0].starts_with("46 inconsistently oriented edges (the first near ["),
        "{problems:?}"
    );
    let opts = BooleanOptions {
        checks: Checks {
            force: true,
            ..strict
        },
        ..BooleanOptions::default()
    };
    let out = boolean(&terrain, &cylinder, Op::Difference, &opts).unwrap();
    assert!(out.operands[0].forced);
    assert!(!out.operands[1].forced);
    let near = out.operands[0].inconsistent_near.unwrap();
    assert_eq!(
        out.assumed(),
        [format!(
            "A: 46 inconsistently oriented edges (the first near {near:?}) (input taken as given)"
        )]
    );
    assert_eq!(out.report().result.boundary_edges, 560);

    // A self-intersecting operand that is not resolved names its first pair: closed
    // parts crossing each other, with the resolve turned off.
    let (a, b) = cubes();
    let mut two = a.clone();
    two.append(&b).unwrap();
    let no_resolve = Checks {
        resolve: false,
        ..Checks::default()
    };
    let err = Operand::new("two cubes", &two, &no_resolve).unwrap_err();
    let pairs = crate::intersect::self_intersections(&two).len();
    assert!(pairs > 0);
    assert!(
        err.to_string().starts_with(&format!(
            "two cubes: {pairs} self-intersecting triangle pairs (first: triangles"
        )),
        "{err}"
    );
    // An open surface crossing itself has no inside of its own to be ambiguous: taken
    // as given, and said.
    let m = self_intersecting();
    let o = Operand::new("folded cube", &m, &Checks::default()).unwrap();
    let pairs = crate::intersect::self_intersections(&crate::weld_exact(&m).mesh).len();
    let si = o.report().self_intersections.clone().unwrap();
    assert!(pairs > 0 && si.open_kept && si.pairs == pairs, "{si:?}");
    assert!(!o.report().forced);
    assert_eq!(o.report().assumed().len(), 1);
    assert!(o.report().assumed()[0].starts_with(&format!(
        "folded cube: {pairs} self-intersecting triangle pairs of its open parts (the first near ["
    )));
    // Skipped checks are assumptions too.
    let unchecked = Checks {
        self_intersections: false,
        ..Checks::default()
    };
    let o = Operand::new("folded cube", &m, &unchecked).unwrap();
    assert_eq!(
        o.report().assumed(),
        ["folded cube: not checked for self-intersections"]
    );
    assert!(Operand::new("none", &m, &Checks::NONE).is_ok());
}

#[test]
fn operands_are_welded_and_reusable() {
    let (a, b) = cubes();
    let soup = Mesh::from_soup_unwelded(&a.to_soup());
    let oa = Operand::new("soup", &soup, &Checks::default()).unwrap();
    assert_eq!(oa.mesh().positions.len(), 8);
    assert_eq!(oa.report().vertices, 8);
    let ob = Operand::new("b", &b, &Checks::default()).unwrap();
    let opts = BooleanOptions::default();
    let u = boolean(&oa, &ob, Op::Union, &opts).unwrap();
    let i = boolean(&oa, &ob, Op::Intersection, &opts).unwrap();
    assert_eq!(u.operands[0].name, "soup");
    assert_eq!(
        signed_volume(&u.mesh) + signed_volume(&i.mesh),
        2.0,
        "one operand, two operations"
    );
}

/// An operand met in a second boolean builds the whole tree of its triangles and keeps
/// it; every boolean and split of reused operands is the one of fresh meshes: spheres of
/// equal sizes, of unlike sizes (the larger's tree over the triangles near the smaller, or
/// kept whole), a cube whose large triangles the broad phase looks at through pieces
/// (its kept tree not taken), one operand as both inputs, and operands apart.
#[test]
fn reused_operands_keep_their_trees_and_give_the_same_results() {
    let sphere = |c: [f64; 3], r: f64, n: u32| crate::shapes::sphere(c, r, 2 * n, n).unwrap();
    let cases = [
        (sphere([0.0; 3], 1.0, 16), sphere([0.3, 0.2, 0.1], 0.9, 14)),
        (sphere([0.0; 3], 1.0, 40), sphere([0.9, 0.0, 0.0], 0.3, 6)),
        (Mesh::cuboid([-0.5; 3], [0.5; 3]), sphere([0.4; 3], 0.5, 24)),
        (sphere([0.0; 3], 1.0, 12), sphere([0.0; 3], 1.0, 12)),
        (sphere([0.0; 3], 1.0, 12), sphere([5.0; 3], 1.0, 12)),
    ];
    let checks = Checks::default();
    let opts = BooleanOptions::default();
    for (k, (a, b)) in cases.iter().enumerate() {
        let (oa, ob) = (
            Operand::new("A", a, &checks).unwrap(),
            Operand::new("B", b, &checks).unwrap(),
        );
        for (round, op) in [Op::Union, Op::Difference, Op::Intersection]
            .into_iter()
            .enumerate()
        {
            let fresh = boolean(a, b, op, &opts).unwrap();
            let reused = boolean(&oa, &ob, op, &opts).unwrap();
            assert_eq!(reused.mesh, fresh.mesh, "case {k}, {op}");
            assert_eq!(reused.provenance, fresh.provenance, "case {k}, {op}");
            assert_eq!(reused.seam_points, fresh.seam_points, "case {k}, {op}");
            let built = [oa.keeps().tree.is_built(), ob.keeps().tree.is_built()];
            // The cube (case 2) is looked at through pieces: its tree is never asked for.
            assert_eq!(built, [round > 0 && k != 2, round > 0], "case {k}, {op}");
        }
        let fresh = split(a, b, &SplitOptions::default()).unwrap();
        let reused = split(&oa, &ob, &SplitOptions::default()).unwrap();
        assert_eq!(reused.groups.len(), fresh.groups.len(), "case {k}");
        for (r, f) in reused.groups.iter().zip(&fresh.groups) {
            assert_eq!(r.mesh, f.mesh, "case {k}");
        }
    }
    // One operand as both inputs: its tree is asked for twice in the first boolean.
    let (a, _) = &cases[0];
    let oa = Operand::new("A", a, &checks).unwrap();
    let fresh = boolean(a, a, Op::Union, &opts).unwrap();
    let reused = boolean(&oa, &oa, Op::Union, &opts).unwrap();
    assert!(oa.keeps().tree.is_built());
    assert_eq!(reused.mesh, fresh.mesh);
    assert_eq!(
        boolean(&oa, &oa, Op::Union, &opts).unwrap().mesh,
        fresh.mesh
    );
}

#[test]
fn thread_counts_out_of_range_are_errors() {
    let (a, b) = cubes();
    for threads in [RunOptions::MAX_THREADS + 1, 100_000] {
        let opts = BooleanOptions {
            run: RunOptions {
                threads: Some(threads),
                ..RunOptions::default()
            },
            ..BooleanOptions::default()
        };
        assert!(matches!(
            boolean(&a, &b, Op::Union, &opts),
            Err(Error::InvalidParameter(_))
        ));
    }
    assert_eq!(
        with_threads(Some(0), || 7).unwrap(),
        7,
        "0: the current pool"
    );
    let counts = with_threads(Some(3), || {
        let inner = with_threads(Some(3), rayon::current_num_threads).unwrap();
        (rayon::current_num_threads(), inner)
    });
    assert_eq!(counts.unwrap(), (3, 3));
}

/// Calls that keep their pool's other workers awake ([`awake`]) give their results and
/// return: from several threads at once on the global pool, from inside parallel work on
/// it (nested calls), and in pools of their own, booleans among them (the same mesh
/// every time).
#[test]
fn calls_keeping_workers_awake_return_from_many_threads_and_nested_work() {
    use rayon::prelude::*;
    let sum = |n: u64| (0..n).into_par_iter().map(|x| x * x % 1009).sum::<u64>();
    let want = |n: u64| (0..n).map(|x| x * x % 1009).sum::<u64>();
    let (a, b) = cubes();
    let union = || {
        let out = boolean(&a, &b, Op::Union, &BooleanOptions::default()).unwrap();
        out.mesh.triangles.len()
    };
    let triangles = union();
    std::thread::scope(|s| {
        for k in 0..6u64 {
            s.spawn(move || {
                for i in 0..40u64 {
                    let n = 1000 + 40 * k + i;
                    assert_eq!(with_threads(None, || sum(n)).unwrap(), want(n));
                    let nested: Vec<u64> = with_threads(None, || {
                        (0..8u64)
                            .into_par_iter()
                            .map(|j| with_threads(None, || sum(n + j)).unwrap())
                            .collect()
                    })
                    .unwrap();
                    assert_eq!(nested, (0..8u64).map(|j| want(n + j)).collect::<Vec<_>>());
                    assert_eq!(with_threads(Some(3), || sum(n)).unwrap(), want(n));
                    assert_eq!(with_threads(None, union).unwrap(), triangles);
                }
            });
        }
    });
}

/// Where a boolean's stages ran: the thread and its index in a rayon pool, per stage.
fn stage_threads(
    a: &Mesh,
    b: &Mesh,
    threads: Option<usize>,
) -> (BooleanOutput, Vec<(std::thread::ThreadId, Option<usize>)>) {
    let seen = Arc::new(Mutex::new(Vec::new()));
    let log = seen.clone();
    let opts = BooleanOptions {
        run: RunOptions {
            threads,
            progress: Some(Progress::new(move |_| {
                let here = (std::thread::current().id(), rayon::current_thread_index());
                log.lock().unwrap().push(here);
            })),
            cancel: None,
        },
        ..BooleanOptions::default()
    };
    let out = boolean(a, b, Op::Union, &opts).unwrap();
    let seen = seen.lock().unwrap().clone();
    (out, seen)
}

/// A call on fewer than [`SERIAL_BELOW`] triangles runs every stage on the calling
/// thread, outside any pool, whatever threads it asks for; a larger one moves into the
/// pool. The small result is the right solid either way.
#[test]
fn small_calls_run_on_the_calling_thread() {
    let (a, b) = cubes();
    assert!(a.triangles.len() + b.triangles.len() < SERIAL_BELOW);
    let me = std::thread::current().id();
    for threads in [None, Some(0), Some(3)] {
        let (out, seen) = stage_threads(&a, &b, threads);
        assert!(seen.len() >= 4, "{seen:?}");
        assert!(
            seen.iter().all(|&s| s == (me, None)),
            "{threads:?}: {seen:?}"
        );
        let m = Measures::of(&out.mesh);
        assert!((m.volume - (2.0 - 0.125)).abs() < 1e-12, "{}", m.volume);
        assert_eq!((m.boundary_edges, m.non_manifold_edges), (0, 0));
    }
    let big = crate::shapes::uv_sphere([0.0; 3], 1.0, 24, 12);
    let other = crate::shapes::uv_sphere([0.5; 3], 1.0, 24, 12);
    assert!(big.triangles.len() + other.triangles.len() >= SERIAL_BELOW);
    let (_, seen) = stage_threads(&big, &other, None);
    assert!(seen.iter().all(|&(_, index)| index.is_some()), "{seen:?}");
    // The pipeline's boolean called directly from outside a pool: the small one on this
    // thread, the large one on a worker.
    for ((x, y), small) in [((&a, &b), true), ((&big, &other), false)] {
        let seen = Mutex::new(Vec::new());
        let log = |_: crate::boolean::Stage| {
            let here = (std::thread::current().id(), rayon::current_thread_index());
            seen.lock().unwrap().push(here);
        };
        let opts = crate::boolean::PipelineOptions {
            progress: Some(&log),
            ..Default::default()
        };
        crate::boolean::boolean(x, y, Op::Union, &opts);
        let seen = seen.into_inner().unwrap();
        assert!(seen.len() >= 2, "{seen:?}");
        match small {
            true => assert!(seen.iter().all(|&s| s == (me, None)), "{seen:?}"),
            false => assert!(seen.iter().all(|&(_, i)| i.is_some()), "{seen:?}"),
        }
    }
    // Inside a small call, a nested call stays on its thread.
    let nested = crate::par::serially(|| with_threads(Some(2), rayon::current_thread_index));
    assert_eq!(nested.unwrap(), None);
}

/// The pipeline run serially on a thread outside any pool ([`crate::par::serially`])
/// gives the same mesh, bit for bit, as in a pool of three threads: crossing spheres of
/// 5,040 triangles each, every operation.
#[test]
fn serial_steps_give_the_parallel_mesh() {
    let a = crate::shapes::uv_sphere([0.0; 3], 1.0, 72, 36);
    let b = crate::shapes::rigid_motion(&a, [1.0, 2.0, 3.0], 0.7, [0.1, 0.2, 0.3]);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(3)
        .build()
        .unwrap();
    let opts = crate::boolean::PipelineOptions::default();
    for op in [
        Op::Union,
        Op::Intersection,
        Op::Difference,
        Op::ReverseDifference,
    ] {
        let serial = crate::par::serially(|| crate::boolean::boolean(&a, &b, op, &opts));
        let parallel = pool.install(|| crate::boolean::boolean(&a, &b, op, &opts));
        assert!(serial.mesh.triangles.len() > 5000, "{op:?}");
        assert_eq!(serial.mesh, parallel.mesh, "{op:?}");
        assert_eq!(serial.provenance, parallel.provenance, "{op:?}");
    }
}

#[test]
fn progress_reports_every_stage_in_order() {
    let (a, b) = cubes();
    let seen = Arc::new(Mutex::new(Vec::new()));
    let log = seen.clone();
    let opts = BooleanOptions {
        run: RunOptions {
            progress: Some(Progress::new(move |s| log.lock().unwrap().push(s))),
            ..RunOptions::default()
        },
        ..BooleanOptions::default()
    };
    boolean(&a, &b, Op::Union, &opts).unwrap();
    assert_eq!(
        *seen.lock().unwrap(),
        [
            Stage::Check,
            Stage::Intersect,
            Stage::Arrange,
            Stage::Classify,
            Stage::Merge
        ]
    );
}

#[test]
fn repair_progress_reports_the_steps_that_run_in_order() {
    let (positions, mut triangles) = Mesh::cuboid([0.0; 3], [2.0, 2.0, 1.0]).into_parts();
    triangles.truncate(10); // open: the x = max face gone
    let open_box = Mesh::new(positions, triangles).unwrap();
    let stages = |config: &crate::repair::RepairConfig| {
        let seen = Arc::new(Mutex::new(Vec::new()));
        let log = seen.clone();
        let run = RunOptions {
            threads: Some(1),
            progress: Some(Progress::new(move |s| log.lock().unwrap().push(s))),
            cancel: None,
        };
        let out = repair_with(&open_box, config, &run).unwrap();
        let plain = repair(&open_box, config).unwrap();
        assert_eq!(out.mesh, plain.mesh);
        assert_eq!(out.report(), plain.report());
        let stages = seen.lock().unwrap().clone();
        stages
    };
    let every_step = crate::repair::RepairConfig {
        weld: Some(1e-9),
        remove_overlapping: Some(1e-9),
        weld_boundary: Some(1e-9),
        tjunction_tolerance: Some(1e-9),
        degenerate: Some(Default::default()),
        snap: Some(1e-9),
        orient: Some(Facing::ZUp),
        remove_folds: true,
        close: CloseMode::Cap,
        close_gaps: Some(1.0),
        ..Default::default()
    };
    assert_eq!(
        stages(&every_step),
        [
            Stage::Weld,
            Stage::Duplicates,
            Stage::WeldBoundary,
            Stage::TJunctions,
            Stage::Degenerate,
            Stage::Snap,
            Stage::Orient,
            Stage::Folds,
            Stage::Close,
            Stage::CloseGaps,
        ]
    );
    assert_eq!(&Stage::ALL[5..], &stages(&every_step)[..]);
    // Only the steps asked for; the default orients.
    let some = crate::repair::RepairConfig {
        tjunctions: true,
        close: CloseMode::Cap,
        ..Default::default()
    };
    assert_eq!(
        stages(&some),
        [Stage::TJunctions, Stage::Orient, Stage::Close]
    );
    for s in Stage::ALL {
        assert!(!s.describe().is_empty());
    }
}

#[test]
fn piece_specs_read_and_write_the_same_text() {
    for text in [
        "a_out_b",
        "a_in_b#2",
        "b_in_a:flip",
        "b_on_a_opposite#0:flip",
    ] {
        let spec: PieceSpec = text.parse().unwrap();
        assert_eq!(spec.to_string(), text);
    }
    let spec: PieceSpec = "a_in_b#3:flip".parse().unwrap();
    assert_eq!(
        spec,
        PieceSpec {
            group: Group::AInB,
            component: Some(3),
            flip: true
        }
    );
    for bad in ["a_in", "a_in_b#x", "a_in_b#", "#1", "a_in_b:flop"] {
        assert!(bad.parse::<PieceSpec>().is_err(), "{bad}");
    }
    for op in Op::ALL {
        assert_eq!(op.to_string().parse::<Op>().unwrap(), op);
    }
    assert_eq!("subtract".parse::<Op>().unwrap(), Op::Difference);
    assert_eq!(
        "reverse_difference".parse::<Op>().unwrap(),
        Op::ReverseDifference
    );
    for g in Group::ALL {
        assert_eq!(g.to_string().parse::<Group>().unwrap(), g);
    }
    for s in Stage::ALL {
        assert_eq!(s.to_string().parse::<Stage>().unwrap(), s);
    }
    for f in Format::NAMES.map(|(_, f)| f) {
        assert_eq!(f.name().parse::<Format>().unwrap(), f);
    }
    for m in CloseMode::ALL {
        assert_eq!(m.to_string().parse::<CloseMode>().unwrap(), m);
    }
    for f in Facing::ALL {
        assert_eq!(f.to_string().parse::<Facing>().unwrap(), f);
    }
}

#[test]
fn pick_takes_each_piece_once() {
    // A slab crossed by two separate posts: B's part inside A has two components.
    let a = Mesh::cuboid([0.0; 3], [4.0, 2.0, 1.0]);
    let mut b = Mesh::cuboid([0.5, 0.5, 0.5], [1.5, 1.5, 2.0]);
    b.append(&Mesh::cuboid([2.5, 0.5, 0.5], [3.5, 1.5, 2.0]))
        .unwrap();
    let s = split(&a, &b, &SplitOptions::default()).unwrap();
    let b_in = s.groups.iter().find(|g| g.group == Group::BInA).unwrap();
    assert_eq!(b_in.components.len(), 2);
    let specs =
        |list: &[&str]| -> Vec<PieceSpec> { list.iter().map(|t| t.parse().unwrap()).collect() };
    // The difference, picked: A outside B and B inside A flipped.
    let diff = s
        .pick(&specs(&["a_out_b", "b_in_a:flip"]), &PickOptions::default())
        .unwrap();
    assert_eq!(signed_volume(&diff.mesh), 8.0 - 2.0 * 0.5);
    assert!(diff.report().stats.closed);
    // One post's part only: A minus one post, open exactly along the other post's rim.
    let one = s
        .pick(
            &specs(&["a_out_b", "b_in_a#1:flip"]),
            &PickOptions::default(),
        )
        .unwrap();
    let rim = Measures::of(&b_in.components[0]).boundary_edges;
    assert!(rim >= 4);
    assert_eq!(one.report().stats.boundary_edges, rim);
    assert_eq!(one.report().stats.non_manifold_edges, 0);
    for twice in [
        &["a_out_b", "a_out_b"][..],
        &["b_in_a#0", "b_in_a#0:flip"],
        &["b_in_a", "b_in_a#1"],
        &["a_out_b#0", "a_out_b"],
    ] {
        let err = s.pick(&specs(twice), &PickOptions::default()).unwrap_err();
        assert!(
            err.to_string().contains("a piece may be picked once"),
            "{err}"
        );
    }
    assert!(s
        .pick(&specs(&["b_in_a#2"]), &PickOptions::default())
        .is_err());
    assert!(s
        .pick(&specs(&["a_out_b#1"]), &PickOptions::default())
        .is_err());
    assert!(s
        .pick(&specs(&["a_on_b_same"]), &PickOptions::default())
        .is_err());
    // The same from the directory the split writes.
    let dir = std::env::temp_dir().join(format!("meshbool-ops-pick-{}", std::process::id()));
    let manifest = s.write_dir(&dir, Format::Obj).unwrap();
    assert_eq!(manifest, s.report(Format::Obj));
    let from_dir = pick_dir(
        &dir,
        &specs(&["a_out_b", "b_in_a:flip"]),
        &PickOptions::default(),
    )
    .unwrap();
    assert_eq!(from_dir.mesh, diff.mesh);
    assert!(pick_dir(
        &dir,
        &specs(&["b_in_a", "b_in_a#0"]),
        &PickOptions::default()
    )
    .is_err());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn files_are_named_in_errors() {
    let missing = std::path::Path::new("/nonexistent/meshbool/x.obj");
    let err = read(missing, None).unwrap_err();
    assert!(
        err.to_string()
            .starts_with("reading /nonexistent/meshbool/x.obj: "),
        "{err}"
    );
    let err = Operand::read(missing, &Checks::default()).unwrap_err();
    assert!(
        matches!(
            err,
            Error::File {
                action: "reading",
                ..
            }
        ),
        "{err}"
    );
    let err = write("/nonexistent/meshbool/y.ply", &Mesh::unit_cube(), None).unwrap_err();
    assert!(
        err.to_string()
            .starts_with("writing /nonexistent/meshbool/y.ply: "),
        "{err}"
    );
}

#[test]
fn touching_solids_come_out_closed_and_manifold() {
    use crate::measure::mesh_stats;
    let a = Mesh::unit_cube();
    // B touches A along an edge, then at a vertex only.
    for (b, edges, copies) in [
        (Mesh::cuboid([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]), 1, 2),
        (Mesh::cuboid([1.0; 3], [2.0; 3]), 0, 1),
    ] {
        let out = boolean(&a, &b, Op::Union, &BooleanOptions::default()).unwrap();
        let s = mesh_stats(&out.mesh);
        assert_eq!(
            (s.boundary_edges, s.non_manifold_edges, s.inconsistent_edges),
            (0, 0, 0)
        );
        assert_eq!((s.components, s.volume), (2, 2.0));
        assert_eq!(out.nonmanifold.edges_split, edges);
        assert_eq!(out.nonmanifold.vertices_added, copies);
        assert_eq!(out.report().split_nonmanifold, out.nonmanifold);
        // Vertex-manifold too: nothing left to split anywhere.
        assert_eq!(
            crate::repair::split_nonmanifold(&out.mesh).1,
            Default::default()
        );
        // Kept as it is when asked: the touching edge (or vertex) is shared.
        let opts = BooleanOptions {
            keep_nonmanifold: true,
            ..BooleanOptions::default()
        };
        let kept = boolean(&a, &b, Op::Union, &opts).unwrap();
        let k = mesh_stats(&kept.mesh);
        assert_eq!(k.non_manifold_edges, edges);
        assert_eq!(k.vertices + copies, s.vertices);
        // The same triangles at the same positions, in the same order.
        assert_eq!(kept.mesh.to_soup(), out.mesh.to_soup());
        for (op, volume) in [(Op::Intersection, 0.0), (Op::Difference, 1.0)] {
            let r = boolean(&a, &b, op, &BooleanOptions::default()).unwrap();
            assert_eq!(signed_volume(&r.mesh), volume, "{op}");
        }
    }
    // Picking the same pieces gives the same manifold mesh.
    let b = Mesh::cuboid([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]);
    let s = split(&a, &b, &SplitOptions::default()).unwrap();
    let specs = ["a_out_b".parse().unwrap(), "b_out_a".parse().unwrap()];
    let picked = s.pick(&specs, &PickOptions::default()).unwrap();
    let p = picked.report().stats;
    assert_eq!((p.non_manifold_edges, p.components, p.volume), (0, 2, 2.0));
    assert_eq!(picked.nonmanifold.edges_split, 1);
}

#[test]
fn self_curves_are_the_curves_between_the_parts() {
    // Two overlapping cubes given as one mesh cross themselves where the two cubes cross.
    let (a, b) = cubes();
    let mut joined = a.clone();
    joined.append(&b).unwrap();
    let own = self_curves(&joined, &CurvesOptions::default()).unwrap();
    let two = curves(&a, &b, &CurvesOptions::default()).unwrap();
    let (r, s) = (own.report(), two.report());
    assert_eq!((r.loops, r.open_chains), (s.loops, s.open_chains));
    assert_eq!((r.points, r.segments), (s.points, s.segments));
    assert_eq!(r.total_length, s.total_length);
    assert_eq!(r.loops, 1);
    // Six segments of length 1/2 (the cubes are offset by 1/2 along every axis), split
    // where they run over the other cube's triangle diagonals.
    assert!((r.total_length - 3.0).abs() < 1e-12, "{}", r.total_length);
    // Every point of the loop lies on both cubes' surfaces.
    for p in &own.polylines[0].points {
        let on = |lo: f64, hi: f64| {
            p.iter().all(|&x| (lo..=hi).contains(&x)) && p.iter().any(|&x| x == lo || x == hi)
        };
        assert!(on(0.0, 1.0) && on(0.5, 1.5), "{p:?}");
    }

    // A cube with a corner pushed through its bottom: one closed loop where the three
    // faces at that corner pass through the bottom face.
    let folded = folded_cube();
    let r = self_curves(&folded, &CurvesOptions::default())
        .unwrap()
        .report();
    assert_eq!((r.loops, r.open_chains), (1, 0), "{r:?}");
    assert!(r.total_length > 0.0);
    // A clean mesh does not cross itself.
    let clean = self_curves(&a, &CurvesOptions::default()).unwrap().report();
    assert_eq!(
        (clean.points, clean.segments, clean.candidate_pairs),
        (0, 0, 0)
    );
}

#[test]
fn tagged_segments_lie_in_their_triangles_and_simplify_thins_the_lines() {
    let (a, b) = cubes();
    let opts = CurvesOptions {
        tagged: true,
        ..CurvesOptions::default()
    };
    let out = curves(&a, &b, &opts).unwrap();
    let tagged = out.report().tagged_segments.unwrap();
    assert_eq!(tagged.len(), out.seam.sources.len());
    // Every end lies exactly in the closure of both its triangles (the coordinates are
    // halves and ones: exact), so on both planes and in both boxes.
    let inside = |m: &Mesh, t: u32, p: &[f64; 3]| {
        let [x, y, z] = m.corners(t as usize);
        let on_plane = crate::kernel::orient3d_explicit(&x, &y, &z, p) == crate::kernel::Sign::Zero;
        let in_box = (0..3).all(|k| {
            let (lo, hi) = (x[k].min(y[k]).min(z[k]), x[k].max(y[k]).max(z[k]));
            (lo..=hi).contains(&p[k])
        });
        on_plane && in_box
    };
    for s in &tagged {
        for p in [&s.p0, &s.p1] {
            assert!(inside(&a, s.tri_a, p) && inside(&b, s.tri_b, p), "{s:?}");
        }
    }
    assert_eq!(out.report().simplified_points_removed, None);
    // A dense loop: two spheres crossing in a circle of radius sqrt(3)/2.
    let s1 = crate::shapes::uv_sphere([0.0; 3], 1.0, 96, 48);
    let s2 = crate::shapes::uv_sphere([1.0, 0.0, 0.0], 1.0, 96, 48);
    let full = curves(&s1, &s2, &CurvesOptions::default()).unwrap();
    let thin = curves(
        &s1,
        &s2,
        &CurvesOptions {
            simplify: Some(0.2),
            ..CurvesOptions::default()
        },
    )
    .unwrap();
    let (f, t) = (&full.polylines[0], &thin.polylines[0]);
    assert!(t.closed && t.points.len() >= 3 && t.points.len() < f.points.len() / 4);
    assert_eq!(t.points[0], f.points[0]);
    for w in t.points.windows(2) {
        let d = ((w[0][0] - w[1][0]).powi(2)
            + (w[0][1] - w[1][1]).powi(2)
            + (w[0][2] - w[1][2]).powi(2))
        .sqrt();
        assert!(d >= 0.2, "{d}");
    }
    assert_eq!(
        thin.report().simplified_points_removed,
        Some(f.points.len() - t.points.len())
    );
    // The thinned loop still goes around: its length is within 3 % of the full one's.
    assert!((t.length() - f.length()).abs() < 0.03 * f.length());
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let opts = CurvesOptions {
            simplify: Some(bad),
            ..CurvesOptions::default()
        };
        assert!(matches!(
            curves(&s1, &s2, &opts),
            Err(Error::InvalidParameter(_))
        ));
        assert!(self_curves(&s1, &opts).is_err());
    }
}

#[test]
fn inside_out_operands_are_reversed_with_a_line_in_assumed() {
    // Before: an inside-out cube was taken as its complement (the union came out with a
    // negative volume).
    let (a, b) = cubes();
    let out = boolean(&a.flipped(), &b, Op::Union, &BooleanOptions::default()).unwrap();
    let r = out.report();
    assert_eq!(r.result.volume, 1.875);
    assert!(r.result.closed);
    assert_eq!(r.operands[0].reversed_components, 1);
    assert_eq!(
        r.assumed,
        ["A: 1 closed components faced inward without enclosing anything (inside out) and were reversed"]
    );
    // A's triangles in the result face against their (reversed) input triangles.
    assert!(out
        .provenance
        .iter()
        .all(|p| p.flipped == (p.source == crate::Source::A)));
    let d = boolean(&b, &a.flipped(), Op::Difference, &BooleanOptions::default()).unwrap();
    assert_eq!(signed_volume(&d.mesh), 1.0 - 0.125);
    // A hollow box (outer outward, cavity inward) is left alone.
    let mut hollow = Mesh::cuboid([0.0; 3], [3.0; 3]);
    hollow
        .append(&Mesh::cuboid([1.0; 3], [2.0; 3]).flipped())
        .unwrap();
    let far = Mesh::cuboid([5.0; 3], [6.0; 3]);
    let out = boolean(&hollow, &far, Op::Union, &BooleanOptions::default()).unwrap();
    assert_eq!(out.operands[0].reversed_components, 0);
    assert_eq!(signed_volume(&out.mesh), 26.0 + 1.0);
}

/// A large operand on several threads: its inside-out components are looked for beside
/// the edge counts, and that early answer is dropped when the orientation is repaired
/// (here the repaired sphere faces outward, where the mesh as given had a negative volume).
#[test]
fn inside_out_parts_found_beside_the_edge_counts_follow_a_repaired_orientation() {
    let sphere = crate::shapes::uv_sphere([0.0; 3], 1.0, 200, 180);
    assert!(sphere.triangles.len() >= 1 << 16);
    // The band around the equator reversed: fewer triangles than the rest, more volume.
    let mut mixed = sphere.clone();
    let z = |m: &Mesh, t: &[u32; 3]| {
        t.iter()
            .map(|&v| m.positions[v as usize][2].abs())
            .fold(0.0, f64::max)
    };
    let mut band = 0;
    for t in 0..mixed.triangles.len() {
        if z(&sphere, &sphere.triangles[t]) < 0.55 {
            mixed.triangles[t].swap(1, 2);
            band += 1;
        }
    }
    assert!(2 * band < mixed.triangles.len());
    assert!(signed_volume(&mixed) < 0.0, "{}", signed_volume(&mixed));
    let far = Mesh::cuboid([5.0; 3], [6.0; 3]);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(4)
        .build()
        .unwrap();
    for (a, reoriented, reversed) in [
        (&mixed, band, 0),
        (&sphere.flipped(), 0, 1),
        (&sphere, 0, 0),
    ] {
        let out = pool
            .install(|| boolean(a, &far, Op::Union, &BooleanOptions::default()))
            .unwrap();
        assert_eq!(out.operands[0].reoriented_triangles, reoriented);
        assert_eq!(out.operands[0].reversed_components, reversed);
        // The union of disjoint parts: their volumes added (to rounding of the sums).
        let want = signed_volume(&sphere) + 1.0;
        assert!((signed_volume(&out.mesh) - want).abs() <= 1e-13 * want);
    }
}

#[test]
fn picking_the_pieces_of_an_op_gives_the_boolean() {
    let (a, b) = cubes();
    let split = split(&a, &b, &SplitOptions::default()).unwrap();
    for op in Op::ALL {
        let picked = split.pick_op(op, &PickOptions::default()).unwrap();
        let direct = boolean(&a, &b, op, &BooleanOptions::default()).unwrap();
        let (p, d) = (picked.report(), direct.report());
        assert!(p.stats.closed, "{op}");
        assert_eq!(p.stats.volume, d.result.volume, "{op}");
        assert_eq!(p.stats.triangles, d.result.triangles, "{op}");
    }
    // The rule's pieces: difference keeps A outside, B inside flipped, and one copy of
    // faces the two share facing opposite ways.
    let names: Vec<String> = PieceSpec::for_op(Op::Difference)
        .iter()
        .map(|s| s.to_string())
        .collect();
    assert_eq!(names, ["a_out_b", "b_in_a:flip", "a_on_b_opposite"]);
}

/// `m` with every coordinate multiplied by `2^k`.
fn scaled(m: &Mesh, k: i32) -> Mesh {
    let mut m = m.clone();
    super::scale_points(&mut m.positions, k);
    m
}

/// `m`'s triangles as corner triples, sorted: the same surface whatever the numbering.
fn sorted(m: &Mesh) -> Vec<[[f64; 3]; 3]> {
    let mut s = m.to_soup();
    s.sort_by(|x, y| x.partial_cmp(y).unwrap());
    s
}

#[test]
fn tiny_and_huge_inputs_give_the_unit_result_scaled_bit_for_bit() {
    // Before: at 2^-256 the union's vertices drifted, at 2^-270 the curves vanished.
    let a = crate::shapes::sphere([0.0; 3], 1.0, 16, 8).unwrap();
    let b = crate::shapes::sphere([0.3, 0.2, 0.1], 1.0, 16, 8).unwrap();
    let opts = BooleanOptions::default();
    let unit = boolean(&a, &b, Op::Union, &opts).unwrap();
    let unit_split = split(&a, &b, &SplitOptions::default()).unwrap();
    let unit_curves = curves(&a, &b, &CurvesOptions::default()).unwrap();
    let mut unit_joined = a.clone();
    unit_joined.append(&b).unwrap();
    let unit_resolved = resolve(&unit_joined, &ResolveOptions::default()).unwrap();
    let unit_probe = [[0.1, 0.1, 0.1], [0.0, 0.0, 1.0], [3.0, 0.0, 0.0]];
    let unit_classes = classify_points(&a, &unit_probe, &Default::default())
        .unwrap()
        .classes;
    assert_eq!(
        unit_classes,
        [PointClass::Inside, PointClass::On, PointClass::Outside]
    );
    for k in [-960, -700, -300, -256, 256, 270, 300, 700, 1000] {
        let (sa, sb) = (scaled(&a, k), scaled(&b, k));
        let out = boolean(&sa, &sb, Op::Union, &opts).unwrap();
        assert_eq!(sorted(&out.mesh), sorted(&scaled(&unit.mesh, k)), "2^{k}");
        assert!(out.report().result.closed);
        let s = split(&sa, &sb, &SplitOptions::default()).unwrap();
        for (g, u) in s.groups.iter().zip(&unit_split.groups) {
            assert_eq!(g.group, u.group);
            assert_eq!(g.mesh, scaled(&u.mesh, k), "2^{k} {:?}", g.group);
        }
        // Resolve (the two spheres as one self-overlapping mesh) and point classification.
        let mut joined = sa.clone();
        joined.append(&sb).unwrap();
        let r = resolve(&joined, &ResolveOptions::default()).unwrap();
        assert_eq!(
            sorted(&r.mesh),
            sorted(&scaled(&unit_resolved.mesh, k)),
            "2^{k}"
        );
        let mut probe = [[0.1, 0.1, 0.1], [0.0, 0.0, 1.0], [3.0, 0.0, 0.0]];
        super::scale_points(&mut probe, k);
        let classes = classify_points(&sa, &probe, &Default::default())
            .unwrap()
            .classes;
        assert_eq!(classes, unit_classes, "2^{k}");
        let c = curves(&sa, &sb, &CurvesOptions::default()).unwrap();
        assert_eq!(c.polylines.len(), unit_curves.polylines.len());
        for (l, u) in c.polylines.iter().zip(&unit_curves.polylines) {
            let mut want = u.points.clone();
            super::scale_points(&mut want, k);
            assert_eq!(l.points, want, "2^{k}");
        }
    }
}

/// The largest magnitude is found on large meshes too (read in chunks side by side),
/// wherever it lies and whatever its sign, and with a small mesh beside.
#[test]
fn extreme_scale_reads_every_coordinate_of_large_meshes() {
    let n = 70_000;
    let big = |last: [f64; 3]| {
        let mut positions: Vec<[f64; 3]> = (0..n)
            .map(|i| [f64::from(i) * 2f64.powi(230), 1.0, -2.0])
            .collect();
        positions[n as usize - 1] = last;
        Mesh::new_unchecked(positions, vec![[0, 1, 2]])
    };
    let huge = big([1.0, -1.5 * 2f64.powi(300), 0.0]);
    assert!(huge.positions.len() >= 1 << 16);
    assert_eq!(extreme_scale(&[&huge]), Some(-300));
    let small = Mesh::new_unchecked(vec![[0.0, 0.0, 2f64.powi(301)]; 3], vec![[0, 1, 2]]);
    assert_eq!(extreme_scale(&[&huge, &small]), Some(-301));
    assert_eq!(extreme_scale(&[&small, &huge]), Some(-301));
    // The largest among the first coordinates (69,998 · 2^230, about 2^246).
    assert_eq!(extreme_scale(&[&big([0.0; 3])]), Some(-246));
    let tiny: Vec<[f64; 3]> = (0..n)
        .map(|i| [f64::from(i + 1) * 2f64.powi(-300), 0.0, 0.0])
        .collect();
    let tiny = Mesh::new_unchecked(tiny, vec![[0, 1, 2]]);
    assert_eq!(extreme_scale(&[&tiny]), Some(284));
}

#[test]
fn closing_and_cut_fill_at_extreme_scales_are_the_unit_results_scaled() {
    // Before: capping an open box at 2^300 reversed the cap (a float product of its
    // normals overflowed), and cut and fill at 2^-300 built its curtains down to a floor
    // a fixed 1 unit below (walls 2^300 times longer than the surfaces were wide) and ran
    // out of memory.
    let cube = Mesh::cuboid([0.0; 3], [1.0; 3]);
    let open = Mesh::new(cube.positions.clone(), cube.triangles[..10].to_vec()).unwrap();
    let design = crate::shapes::heightfield([0.0, 0.0], [1.0, 1.0], 8, 8, |x, _| 0.3 * x);
    let topo = crate::shapes::heightfield([0.0, 0.0], [1.0, 1.0], 7, 7, |_, y| 0.1 + 0.05 * y);
    let opts = CloseOptions::default();
    let unit_cap = close(&open, CloseMode::Cap, &opts).unwrap();
    let unit_curtain = close(&design, CloseMode::Curtain, &opts).unwrap();
    let unit_cf = cutfill(&design, &topo, &CutFillOptions::default()).unwrap();
    assert!(unit_cf.cut > 0.02 && unit_cf.fill > 0.05);
    for k in [-330, -300, -256, 256, 300, 330] {
        let cap = close(&scaled(&open, k), CloseMode::Cap, &opts).unwrap();
        assert_eq!(cap.mesh, scaled(&unit_cap.mesh, k), "2^{k}");
        let offset = CloseOptions {
            floor_offset: super::scaled(opts.floor_offset, k),
            ..opts
        };
        let curtain = close(&scaled(&design, k), CloseMode::Curtain, &offset).unwrap();
        assert_eq!(curtain.mesh, scaled(&unit_curtain.mesh, k), "2^{k}");
        let cf = cutfill(&scaled(&design, k), &scaled(&topo, k), &Default::default()).unwrap();
        let cube = |v: f64| super::scaled(super::scaled(super::scaled(v, k), k), k);
        assert_eq!(
            (cf.cut, cf.fill),
            (cube(unit_cf.cut), cube(unit_cf.fill)),
            "2^{k}"
        );
        assert_eq!(cf.lines.len(), unit_cf.lines.len());
    }
}

/// A unit cube as a soup needing every repair step: corners jittered by up to 1e-4
/// (one weld at 1e-3 joins them), one triangle reversed, one given twice, one zero-area
/// sliver along an edge, and one triangle missing (a hole `close_gaps` caps).
fn broken_cube() -> Mesh {
    let cube = Mesh::unit_cube();
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for t in 1..cube.triangles.len() {
        let base = positions.len() as u32;
        for (k, p) in cube.corners(t).into_iter().enumerate() {
            let j = ((t * 3 + k) % 7) as f64 * 1.5e-5;
            positions.push([p[0] + j, p[1] - j / 2.0, p[2] + j / 3.0]);
        }
        triangles.push(if t == 3 {
            [base, base + 2, base + 1]
        } else {
            [base, base + 1, base + 2]
        });
        if t == 5 {
            triangles.push([base, base + 1, base + 2]);
        }
    }
    let base = positions.len() as u32;
    positions.extend([[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [1.0, 0.0, 0.0]]);
    triangles.push([base, base + 1, base + 2]);
    Mesh::new(positions, triangles).unwrap()
}

#[test]
fn repair_at_extreme_scales_is_the_unit_repair_scaled() {
    let config = |k: i32| crate::repair::RepairConfig {
        weld: Some(super::scaled(1e-3, k)),
        remove_duplicates: true,
        tjunctions: true,
        degenerate: Some(crate::repair::DegenerateOptions {
            // An area 2^2k is no f64 beyond |k| = 511: no threshold there.
            min_area: if k.abs() < 500 {
                super::scaled(1e-12, 2 * k)
            } else {
                0.0
            },
            max_aspect: Some(1e6),
        }),
        snap: Some(super::scaled(1e-3, k)),
        close_gaps: Some(super::scaled(2.0, k)),
        ..Default::default()
    };
    let input = broken_cube();
    let unit = repair(&input, &config(0)).unwrap();
    assert!(unit.repair.after.closed, "{:?}", unit.repair.after);
    assert_eq!(unit.repair.after.components, 1);
    assert!((unit.repair.after.volume - 1.0).abs() < 1e-3);
    for k in [-1000, -700, -330, -256, 256, 330, 700, 1000] {
        let out = repair(&scaled(&input, k), &config(k)).unwrap();
        assert_eq!(out.mesh, scaled(&unit.mesh, k), "2^{k}");
        let (after, unit_after) = (&out.repair.after, &unit.repair.after);
        assert!(after.closed && after.components == 1, "2^{k}");
        assert_eq!(
            (after.triangles, after.vertices),
            (unit_after.triangles, unit_after.vertices)
        );
        if k.abs() <= 330 {
            // The report's measures are the unit ones scaled (volumes 2^3k, areas 2^2k).
            let area = |x: f64| super::scaled(super::scaled(x, k), k);
            assert_eq!(after.volume, super::scaled(area(unit_after.volume), k));
            assert_eq!(after.area, area(unit_after.area), "2^{k}");
            let snap = out.repair.snap.as_ref().unwrap();
            let unit_snap = unit.repair.snap.as_ref().unwrap();
            assert_eq!(snap.max_move, super::scaled(unit_snap.max_move, k));
        }
    }
}

#[test]
fn prepared_operands_and_many_inputs_at_extreme_scales_are_the_unit_results_scaled() {
    // Before: an operand prepared at 2^-700 was checked and used at that size (its
    // self-overlap unresolved, the boolean's seam lost), and booleans of many inputs
    // were never brought to unit size.
    let a = crate::shapes::sphere([0.0; 3], 1.0, 16, 8).unwrap();
    let b = crate::shapes::sphere([0.3, 0.2, 0.1], 1.0, 16, 8).unwrap();
    let c = crate::shapes::sphere([-0.2, 0.4, 0.3], 0.8, 12, 6).unwrap();
    // A and C given as one self-overlapping mesh: resolved at the door.
    let mut ac = a.clone();
    ac.append(&c).unwrap();
    let opts = BooleanOptions::default();
    let checks = Checks::default();
    let unit = boolean(
        &Operand::new("AC", &ac, &checks).unwrap(),
        &Operand::new("B", &b, &checks).unwrap(),
        Op::Difference,
        &opts,
    )
    .unwrap();
    assert!(unit.operands[0].resolved.is_some());
    let unit_ac = Operand::new("AC", &ac, &checks).unwrap().into_mesh();
    let inputs = [&a, &b, &c];
    let unit_many = boolean_many(
        &inputs.map(Input::Mesh),
        Op::Union,
        &BooleanOptions::default(),
    )
    .unwrap();
    let probe = [[0.1, 0.1, 0.1], [0.0, 0.0, 1.0], [3.0, 0.0, 0.0]];
    let unit_classes = classify_points(&a, &probe, &Default::default()).unwrap();
    for k in [-960, -700, -300, 300, 700, 1000] {
        let (x, y) = (
            Operand::new("AC", &scaled(&ac, k), &checks).unwrap(),
            Operand::new("B", &scaled(&b, k), &checks).unwrap(),
        );
        assert_eq!(x.mesh(), &scaled(&unit_ac, k), "2^{k}");
        let near = x
            .report()
            .self_intersections
            .as_ref()
            .unwrap()
            .near
            .unwrap();
        let mut want = unit.operands[0]
            .self_intersections
            .as_ref()
            .unwrap()
            .near
            .unwrap();
        super::scale_points(std::slice::from_mut(&mut want), k);
        assert_eq!(near, want, "2^{k}");
        let out = boolean(&x, &y, Op::Difference, &opts).unwrap();
        assert_eq!(sorted(&out.mesh), sorted(&scaled(&unit.mesh, k)), "2^{k}");
        assert_eq!(out.provenance, unit.provenance, "2^{k}");
        // An operand with a mesh, and many inputs.
        let mixed = boolean(&x, &scaled(&b, k), Op::Difference, &opts).unwrap();
        assert_eq!(mixed.mesh, out.mesh, "2^{k}");
        let many = [scaled(&a, k), scaled(&b, k), scaled(&c, k)];
        let out = boolean_many(
            &[
                Input::Operand(&Operand::new("1", &many[0], &checks).unwrap()),
                Input::Mesh(&many[1]),
                Input::Mesh(&many[2]),
            ],
            Op::Union,
            &BooleanOptions::default(),
        )
        .unwrap();
        assert_eq!(
            sorted(&out.mesh),
            sorted(&scaled(&unit_many.mesh, k)),
            "2^{k}"
        );
        assert!(out.report().result.closed, "2^{k}");
        let mut pts = probe;
        super::scale_points(&mut pts, k);
        let prepared = Operand::new("A", &many[0], &checks).unwrap();
        let classes = classify_points(&prepared, &pts, &Default::default()).unwrap();
        assert_eq!(classes.classes, unit_classes.classes, "2^{k}");
    }
}
