//! No public function panics on any `Mesh` value: random broken meshes (any coordinates:
//! NaN, infinities, the extremes of `f64`, subnormals, UTM-sized offsets; repeated,
//! degenerate, duplicate, flipped and non-manifold triangles) through every function of
//! the public surface. Errors are fine; panics are not.

use meshbool::ops::{self, BooleanOptions, Checks, CurvesOptions, Operand, SplitOptions};
use meshbool::repair::{self, CloseMode, CloseOptions, DegenerateOptions, Facing, RepairConfig};
use meshbool::{edges, intersect, io, measure, Format, Mesh, Op};
use proptest::prelude::*;

/// Coordinates: mostly small integers (so that triangles meet, touch and overlap often),
/// sometimes a value at the edge of `f64`.
fn coordinate() -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => (-2i32..=2).prop_map(f64::from),
        1 => prop::sample::select(vec![
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            5e-324,
            -0.0,
            1e-300,
            1e300,
            4.5e6,
            0.5,
            1.0 / 3.0,
        ]),
    ]
}

/// Positions and triangles: up to 9 vertices and 14 triangles, indices now and then one
/// past the last vertex.
fn parts() -> impl Strategy<Value = (Vec<[f64; 3]>, Vec<[u32; 3]>)> {
    (1usize..9).prop_flat_map(|n| {
        let index = prop_oneof![12 => 0..n as u32, 1 => Just(n as u32)];
        (
            prop::collection::vec([coordinate(), coordinate(), coordinate()], n),
            prop::collection::vec([index.clone(), index.clone(), index], 0..14),
        )
    })
}

/// A mesh: the parts whose indices are in range ([`Mesh::new`] refuses the others).
fn mesh() -> impl Strategy<Value = Mesh> {
    parts().prop_filter_map("an index out of range", |(p, t)| Mesh::new(p, t).ok())
}

/// Every function of the public surface that takes a mesh, on `m` (and `other` where it
/// takes two).
fn exercise(m: &Mesh, other: &Mesh) {
    let forced = Checks {
        force: true,
        ..Checks::default()
    };
    for op in Op::ALL {
        let _ = ops::boolean(m, other, op, &BooleanOptions::default());
        let opts = BooleanOptions {
            checks: forced,
            ..BooleanOptions::default()
        };
        if let Ok(out) = ops::boolean(m, other, op, &opts) {
            let _ = out.report();
        }
        let snapped = BooleanOptions { snap: 0.5, ..opts };
        if let Ok(out) = ops::boolean(m, other, op, &snapped) {
            let _ = out.report();
        }
    }
    let opts = SplitOptions {
        checks: forced,
        merge_small: 2,
        ..SplitOptions::default()
    };
    if let Ok(s) = ops::split(m, other, &opts) {
        let _ = s.report(Format::Obj);
        let specs = ["a_in_b", "a_out_b#0", "b_in_a:flip", "b_out_a#1"];
        let _ = s.pick(&specs.map(|t| t.parse().unwrap()), &Default::default());
    }
    if let Ok(c) = ops::curves(m, other, &CurvesOptions::default()) {
        let _ = c.report();
    }
    let _ = Operand::new("m", m, &Checks::default());
    let _ = ops::info(m);
    for facing in Facing::ALL {
        let _ = ops::orient(m, facing);
        let _ = repair::orient(m, facing);
    }
    for mode in CloseMode::ALL {
        let _ = ops::close(m, mode, &CloseOptions::default());
        let _ = repair::close(m, mode, &CloseOptions::default());
    }
    let all_steps = RepairConfig {
        weld: Some(0.5),
        remove_duplicates: true,
        tjunctions: true,
        degenerate: Some(DegenerateOptions {
            min_area: 0.1,
            max_aspect: Some(4.0),
        }),
        orient: Some(Facing::ZUp),
        remove_folds: true,
        close: CloseMode::StitchCurtain,
        close_gaps: Some(2.0),
        snap: Some(0.5),
        ..RepairConfig::default()
    };
    let _ = ops::repair(m, &all_steps);
    let _ = repair::repair(m, &all_steps);
    let toleranced = RepairConfig {
        remove_overlapping: Some(0.5),
        weld_boundary: Some(0.5),
        tjunction_tolerance: Some(0.5),
        ..all_steps
    };
    let _ = repair::repair(m, &toleranced);
    let _ = ops::pick(&[(m, false), (other, true)], &Default::default());
    let _ = repair::split_nonmanifold(m);
    let _ = repair::snap(m, 0.5);

    let _ = measure::mesh_stats(m);
    let _ = measure::signed_volume(m);
    let _ = measure::area(m);
    for plane in [measure::Plane::XY, measure::Plane::YZ, measure::Plane::XZ] {
        let _ = measure::projected_area(m, plane);
    }
    let _ = measure::degenerate_triangles(m);
    let _ = measure::duplicate_triangles(m);
    let topo = edges::EdgeTopology::new(m);
    let _ = (topo.kind_counts(), topo.is_closed(), topo.components());
    let _ = edges::EdgeCounts::of(m);
    let _ = edges::components_merged(m, 3);

    let _ = repair::boundary_loops(m);
    let _ = repair::cap_holes(m);
    let _ = repair::cap_small_holes(m, 1.0);
    let _ = repair::curtain(m, 1.0);
    let _ = repair::remove_degenerates(m, &DegenerateOptions::default());
    let _ = repair::remove_duplicates(m);
    let _ = repair::remove_folds(m);
    let _ = repair::stitch(m, 1.0);
    let _ = repair::resolve_t_junctions(m);
    let _ = repair::weld_within(m, 0.25);
    for tol in [0.0, 1e-300, 0.25, 3.0, 1e300] {
        let _ = repair::resolve_t_junctions_within(m, tol);
        let _ = repair::remove_overlapping(m, tol);
        let _ = repair::weld_boundary(m, tol);
        let _ = repair::weld_within(m, tol);
    }

    let _ = meshbool::weld_exact(m);
    let _ = (
        m.bounds(),
        m.flipped(),
        m.to_soup(),
        m.clone().without_unreferenced(),
    );
    let _ = intersect::self_intersections(m);
    let _ = intersect::chain(&intersect::intersect(m, other), true);
    for (_, format) in Format::NAMES {
        let _ = io::write(&mut Vec::new(), m, format);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn meshes_are_made_only_with_indices_in_range((positions, triangles) in parts()) {
        let n = positions.len() as u32;
        let valid = triangles.iter().flatten().all(|&i| i < n);
        let made = Mesh::new(positions, triangles);
        prop_assert_eq!(made.is_ok(), valid);
        if let Ok(m) = made {
            exercise(&m, &m);
        }
    }

    #[test]
    fn no_public_function_panics_on_any_mesh(a in mesh(), b in mesh()) {
        exercise(&a, &b);
        exercise(&a, &a);
    }
}
