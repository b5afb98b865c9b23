//! Cancellation ([`meshbool::ops::Cancel`]): a call asked to stop returns
//! `Error::Cancelled` at its next stage and reports no later stage; a flag never set
//! changes nothing.

use std::sync::{Arc, Mutex};

use meshbool::boolean::Stage;
use meshbool::ops::{
    self, BooleanOptions, Cancel, Progress, ResolveOptions, RunOptions, SplitOptions,
};
use meshbool::shapes::uv_sphere;
use meshbool::{Error, Op};

/// Run options that record the stages begun and cancel as `stop` begins.
fn recording(stop: Option<Stage>) -> (RunOptions, Arc<Mutex<Vec<Stage>>>, Cancel) {
    let cancel = Cancel::new();
    let seen = Arc::new(Mutex::new(Vec::new()));
    let (log, flag) = (seen.clone(), cancel.clone());
    let run = RunOptions {
        threads: Some(2),
        progress: Some(Progress::new(move |s| {
            log.lock().unwrap().push(s);
            if Some(s) == stop {
                flag.cancel();
            }
        })),
        cancel: Some(cancel.clone()),
    };
    (run, seen, cancel)
}

/// A call of the library under test: its run options in, a count of its output out.
type Call<'a> = Box<dyn Fn(RunOptions) -> meshbool::Result<usize> + 'a>;

#[test]
fn a_call_cancelled_at_a_stage_stops_there() {
    let a = uv_sphere([0.0; 3], 1.0, 64, 32);
    let b = uv_sphere([0.5, 0.0, 0.0], 1.0, 64, 32);
    for stop in [
        Stage::Check,
        Stage::Intersect,
        Stage::Arrange,
        Stage::Classify,
    ] {
        let (run, seen, cancel) = recording(Some(stop));
        let opts = BooleanOptions {
            run,
            ..BooleanOptions::default()
        };
        let err = ops::boolean(&a, &b, Op::Union, &opts).unwrap_err();
        assert!(matches!(err, Error::Cancelled), "{err}");
        assert_eq!(err.to_string(), "cancelled");
        assert!(cancel.is_cancelled());
        let seen = seen.lock().unwrap().clone();
        assert_eq!(seen.last(), Some(&stop), "{seen:?}");
        assert!(!seen.contains(&Stage::Merge), "{seen:?}");
    }
    // Split, n-ary booleans and resolve too, at every stage they report.
    let c = uv_sphere([0.0, 0.5, 0.0], 1.0, 64, 32);
    let mut two = a.clone();
    two.append(&b).unwrap();
    let calls: [(&str, Call); 3] = [
        (
            "split",
            Box::new(|run| {
                let opts = SplitOptions {
                    run,
                    ..SplitOptions::default()
                };
                ops::split(&a, &b, &opts).map(|o| o.groups.len())
            }),
        ),
        (
            "union of three",
            Box::new(|run| {
                let opts = BooleanOptions {
                    run,
                    ..BooleanOptions::default()
                };
                let inputs = [(&a).into(), (&b).into(), (&c).into()];
                ops::boolean_many(&inputs, Op::Union, &opts).map(|o| o.mesh.triangles().len())
            }),
        ),
        (
            "resolve",
            Box::new(|run| {
                let opts = ResolveOptions {
                    run,
                    ..ResolveOptions::default()
                };
                ops::resolve(&two, &opts).map(|o| o.mesh.triangles().len())
            }),
        ),
    ];
    for (name, call) in &calls {
        let (run, seen, _) = recording(None);
        assert!(call(run).unwrap() > 0, "{name}");
        let stages = seen.lock().unwrap().clone();
        assert!(stages.len() >= 2, "{name}: {stages:?}");
        for stop in stages {
            let (run, _, _) = recording(Some(stop));
            match call(run) {
                Err(Error::Cancelled) => {}
                other => panic!("{name} cancelled at {stop:?}: {other:?}"),
            }
        }
    }
}

#[test]
fn a_flag_set_before_the_call_stops_it_first_and_one_never_set_changes_nothing() {
    let a = uv_sphere([0.0; 3], 1.0, 32, 16);
    let b = uv_sphere([0.5, 0.0, 0.0], 1.0, 32, 16);
    let (run, seen, cancel) = recording(None);
    cancel.cancel();
    let opts = BooleanOptions {
        run,
        ..BooleanOptions::default()
    };
    assert!(matches!(
        ops::boolean(&a, &b, Op::Union, &opts),
        Err(Error::Cancelled)
    ));
    assert!(seen.lock().unwrap().is_empty());
    let (run, seen, _) = recording(None);
    let opts = BooleanOptions {
        run,
        ..BooleanOptions::default()
    };
    let with = ops::boolean(&a, &b, Op::Union, &opts).unwrap();
    let without = ops::boolean(&a, &b, Op::Union, &BooleanOptions::default()).unwrap();
    assert_eq!(with.mesh.triangles(), without.mesh.triangles());
    assert_eq!(with.mesh.positions(), without.mesh.positions());
    let seen = seen.lock().unwrap().clone();
    assert_eq!(
        seen,
        vec![
            Stage::Check,
            Stage::Intersect,
            Stage::Arrange,
            Stage::Classify,
            Stage::Merge
        ]
    );
}
