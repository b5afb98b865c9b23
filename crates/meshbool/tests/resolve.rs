//! Self-overlapping meshes resolved into the solid they enclose, alone (`ops::resolve`)
//! and as operands of booleans: volumes, volume identities, closed and manifold results.

use meshbool::measure::{mesh_stats, signed_volume};
use meshbool::ops::{self, BooleanOptions, Checks, ResolveOptions};
use meshbool::shapes::uv_sphere;
use meshbool::{Error, FillRule, Mesh, Op};

/// Meshes given as one.
fn joined(parts: &[Mesh]) -> Mesh {
    let mut m = Mesh::default();
    for p in parts {
        m.append(p).unwrap();
    }
    m
}

fn resolve(m: &Mesh, rule: FillRule) -> ops::ResolveOutput {
    let opts = ResolveOptions {
        rule,
        ..ResolveOptions::default()
    };
    ops::resolve(m, &opts).unwrap()
}

/// Closed, no non-manifold edge, no vertex with two fans; the volume.
fn closed_manifold_volume(m: &Mesh) -> f64 {
    let s = mesh_stats(m);
    assert!(s.closed, "{s:?}");
    assert_eq!(
        (s.boundary_edges, s.non_manifold_edges, s.inconsistent_edges),
        (0, 0, 0)
    );
    let (_, split) = meshbool::repair::split_nonmanifold(m);
    assert_eq!(split.vertices_added, 0, "a vertex with several fans");
    s.volume
}

/// A cube with its corner (1,1,1) pushed through its bottom face: one closed component
/// that crosses itself.
fn folded_cube() -> Mesh {
    let (mut positions, triangles) = Mesh::unit_cube().into_parts();
    for p in &mut positions {
        if *p == [1.0; 3] {
            *p = [0.5, 0.5, -0.5];
        }
    }
    Mesh::new(positions, triangles).unwrap()
}

#[test]
fn two_overlapping_cubes_in_one_mesh_resolve_to_their_union() {
    let m = joined(&[Mesh::unit_cube(), Mesh::cuboid([0.5; 3], [1.5; 3])]);
    let out = resolve(&m, FillRule::Positive);
    assert_eq!(closed_manifold_volume(&out.mesh), 2.0 - 0.125);
    assert!(out.self_intersections > 0);
    let r = &out.resolve;
    assert_eq!(
        (r.components, r.united_components, r.dropped_components),
        (2, 2, 0)
    );
    assert_eq!(r.crossing_pairs, out.self_intersections);
    assert_eq!(out.parent.len(), out.mesh.triangles().len());
    assert!(out
        .parent
        .iter()
        .all(|&t| (t as usize) < m.triangles().len()));
    // Both parts are represented in the result.
    assert!(out.parent.iter().any(|&t| t < 12) && out.parent.iter().any(|&t| t >= 12));
    // Non-zero gives the same here (every winding number is 0, 1 or 2).
    assert_eq!(
        signed_volume(&resolve(&m, FillRule::NonZero).mesh),
        signed_volume(&out.mesh)
    );
    let report = out.report();
    assert_eq!(report.result.volume, signed_volume(&out.mesh));
    assert!(report.result.closed);
    // The unions' exact clean-up is counted, and the result is the boolean's union: here
    // the parts share face planes, so seam points lie where the result is flat.
    let side = Mesh::cuboid([0.5, 0.0, 0.0], [1.5, 1.0, 1.0]);
    let out = resolve(
        &joined(&[Mesh::unit_cube(), side.clone()]),
        FillRule::Positive,
    );
    let union = ops::boolean(
        &Mesh::unit_cube(),
        &side,
        Op::Union,
        &BooleanOptions::default(),
    )
    .unwrap();
    assert_eq!(closed_manifold_volume(&out.mesh), 1.5);
    assert_eq!(out.mesh.triangles().len(), union.mesh.triangles().len());
    assert_eq!(out.resolve.cleanup, union.cleanup);
    assert!(out.resolve.cleanup.removed_points > 0);
}

#[test]
fn nested_parts_follow_the_fill_rule() {
    let outer = Mesh::cuboid([0.0; 3], [3.0; 3]);
    let inner = Mesh::cuboid([1.0; 3], [2.0; 3]);
    // Outward inside outward: winding 2 inside the inner cube.
    let nested = joined(&[outer.clone(), inner.clone()]);
    let pos = resolve(&nested, FillRule::Positive);
    assert_eq!(closed_manifold_volume(&pos.mesh), 27.0);
    assert_eq!(pos.resolve.dropped_components, 1);
    assert_eq!(pos.self_intersections, 0);
    let even = resolve(&nested, FillRule::EvenOdd);
    assert_eq!(signed_volume(&even.mesh), 26.0);
    assert_eq!(even.mesh.triangles().len(), 24);
    assert_eq!(even.resolve.flipped_components, 1);
    // An inward-facing inner cube is a cavity under every rule.
    let hollow = joined(&[outer, inner.flipped()]);
    for rule in FillRule::ALL {
        let r = resolve(&hollow, rule);
        assert_eq!(signed_volume(&r.mesh), 26.0, "{rule}");
        assert_eq!(r.resolve.dropped_components, 0, "{rule}");
    }
}

/// `n` spheres of random centres and radii (a fixed linear congruential sequence), many
/// overlapping.
fn random_spheres(n: usize) -> Vec<Mesh> {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n)
        .map(|_| {
            let c = [4.0 * next(), 4.0 * next(), 4.0 * next()];
            uv_sphere(c, 0.5 + next(), 24, 12)
        })
        .collect()
}

#[test]
fn forty_overlapping_spheres_resolve_like_their_pairwise_union() {
    let spheres = random_spheres(40);
    let m = joined(&spheres);
    let out = resolve(&m, FillRule::Positive);
    let v = closed_manifold_volume(&out.mesh);
    assert!(out.resolve.united_components >= 30, "{:?}", out.resolve);
    assert_eq!(out.resolve.failed_triangles, 0);
    // The same solid, united one sphere at a time in the reverse order.
    let opts = BooleanOptions {
        checks: Checks {
            self_intersections: false,
            ..Checks::default()
        },
        ..BooleanOptions::default()
    };
    let mut chain = spheres[39].clone();
    for s in spheres[..39].iter().rev() {
        chain = ops::boolean(&chain, s, Op::Union, &opts).unwrap().mesh;
    }
    let w = signed_volume(&chain);
    assert!((v - w).abs() <= 1e-9 * w, "{v} vs {w}");
    let largest = spheres.iter().map(signed_volume).fold(0.0, f64::max);
    let sum: f64 = spheres.iter().map(signed_volume).sum();
    assert!(v > largest && v < sum);
}

#[test]
fn booleans_take_self_overlapping_operands_without_force() {
    let a = joined(&[Mesh::unit_cube(), Mesh::cuboid([0.5; 3], [1.5; 3])]);
    let va = signed_volume(&resolve(&a, FillRule::Positive).mesh);
    let b = uv_sphere([1.2, 1.1, 0.9], 0.6, 32, 16);
    let vb = signed_volume(&b);
    let opts = BooleanOptions::default();
    let vol = |op| {
        let out = ops::boolean(&a, &b, op, &opts).unwrap();
        let r = out.report();
        assert!(r.operands[0].resolved.is_some());
        assert!(!r.operands[0].forced);
        assert!(
            r.assumed.iter().any(|l| l.contains("resolved")),
            "{:?}",
            r.assumed
        );
        assert!(out
            .provenance
            .iter()
            .all(|p| (p.triangle as usize) < a.triangles().len().max(b.triangles().len())));
        closed_manifold_volume(&out.mesh)
    };
    let (u, i) = (vol(Op::Union), vol(Op::Intersection));
    assert!(
        (u + i - va - vb).abs() <= 1e-9 * (va + vb),
        "{u} + {i} vs {va} + {vb}"
    );
    let d = vol(Op::Difference);
    assert!((d - (va - i)).abs() <= 1e-9 * va);
    let rd = vol(Op::ReverseDifference);
    assert!((rd - (vb - i)).abs() <= 1e-9 * va);
    // Asked not to resolve, the operand is refused as before.
    let strict = BooleanOptions {
        checks: Checks {
            resolve: false,
            ..Checks::default()
        },
        ..BooleanOptions::default()
    };
    let err = ops::boolean(&a, &b, Op::Union, &strict).unwrap_err();
    assert!(
        err.to_string().contains("self-intersecting triangle pairs"),
        "{err}"
    );
}

#[test]
fn what_cannot_be_resolved_is_refused_with_the_reason() {
    // An open part crossing another.
    let (positions, mut triangles) = Mesh::unit_cube().into_parts();
    triangles.truncate(10);
    let open = joined(&[
        Mesh::new(positions, triangles).unwrap(),
        Mesh::cuboid([0.5; 3], [1.5; 3]),
    ]);
    let err = ops::resolve(&open, &ResolveOptions::default()).unwrap_err();
    assert!(matches!(err, Error::Unresolvable { .. }), "{err}");
    assert!(err.to_string().contains("not closed"), "{err}");
}

#[test]
fn crossing_parts_under_even_odd_keep_their_symmetric_difference() {
    // Two overlapping cubes: odd winding outside their common part, 2 - 2/8.
    let two = joined(&[Mesh::unit_cube(), Mesh::cuboid([0.5; 3], [1.5; 3])]);
    let out = resolve(&two, FillRule::EvenOdd);
    assert_eq!(closed_manifold_volume(&out.mesh), 1.75);
    let r = &out.resolve;
    assert!(
        r.patches >= 4 && r.patches_flipped >= 2 && r.patches_dropped == 0,
        "{r:?}"
    );
    assert_eq!(r.failed_triangles, 0);
}

#[test]
fn an_inward_part_crossing_an_outward_one_cuts_it() {
    // [0,2]³ facing out and [1,3]³ facing in, as one mesh: winding 1 in A − B, 0 in
    // A ∩ B, −1 in B − A.
    let m = joined(&[
        Mesh::cuboid([0.0; 3], [2.0; 3]),
        Mesh::cuboid([1.0; 3], [3.0; 3]).flipped(),
    ]);
    for (rule, want) in [
        (FillRule::Positive, 7.0),
        (FillRule::NonZero, 14.0),
        (FillRule::EvenOdd, 14.0),
    ] {
        let out = resolve(&m, rule);
        assert_eq!(closed_manifold_volume(&out.mesh), want, "{rule}");
        assert!(out.resolve.patches > 0, "{rule}: {:?}", out.resolve);
    }
}

#[test]
fn a_component_crossing_itself_is_cut_along_its_own_seam() {
    // The folded cube's dent passes through its bottom: winding 1 in the cube, 0 in the
    // dent inside it, -1 in the tip outside. Positive keeps w = 1, non-zero and even-odd
    // w = ±1, and the signed volume is vol(w = 1) - vol(w = -1), so
    // vol(nonzero) + signed = 2 vol(positive).
    let m = folded_cube();
    let signed = signed_volume(&m);
    let pos = resolve(&m, FillRule::Positive);
    let nonzero = resolve(&m, FillRule::NonZero);
    let even = resolve(&m, FillRule::EvenOdd);
    let (vp, vn) = (
        closed_manifold_volume(&pos.mesh),
        closed_manifold_volume(&nonzero.mesh),
    );
    assert_eq!(closed_manifold_volume(&even.mesh), vn);
    assert!(vp > signed && vn > vp, "{signed} {vp} {vn}");
    assert!((vn + signed - 2.0 * vp).abs() < 1e-12, "{signed} {vp} {vn}");
    assert!(pos.resolve.patches >= 3, "{:?}", pos.resolve);
    assert_eq!(pos.resolve.failed_triangles, 0);
    // As a boolean operand it is resolved on the way in too.
    let b = Mesh::cuboid([2.0; 3], [3.0; 3]);
    let u = ops::boolean(&m, &b, Op::Union, &BooleanOptions::default()).unwrap();
    let vu = closed_manifold_volume(&u.mesh);
    assert!((vu - (vp + 1.0)).abs() < 1e-12, "{vu} vs {vp} + 1");
    assert!(u.operands[0].resolved.as_ref().unwrap().patches > 0);
}

#[test]
fn fill_rules_read_and_write_by_name() {
    for rule in FillRule::ALL {
        assert_eq!(rule.to_string().parse::<FillRule>().unwrap(), rule);
    }
    assert!("odd".parse::<FillRule>().is_err());
    assert!(FillRule::Positive.inside(2) && !FillRule::Positive.inside(-1));
    assert!(FillRule::NonZero.inside(-1) && !FillRule::NonZero.inside(0));
    assert!(FillRule::EvenOdd.inside(-3) && !FillRule::EvenOdd.inside(2));
}

/// The union or intersection of `meshes` one at a time, left to right.
fn chained(meshes: &[Mesh], op: Op) -> Mesh {
    let opts = BooleanOptions::default();
    let mut acc = meshes[0].clone();
    for m in &meshes[1..] {
        acc = ops::boolean(&acc, m, op, &opts).unwrap().mesh;
    }
    acc
}

#[test]
fn union_of_ten_spheres_in_one_call_equals_the_chain() {
    let spheres = random_spheres(10);
    let inputs: Vec<ops::Input> = spheres.iter().map(ops::Input::from).collect();
    let out = ops::boolean_many(&inputs, Op::Union, &BooleanOptions::default()).unwrap();
    let v = closed_manifold_volume(&out.mesh);
    let w = signed_volume(&chained(&spheres, Op::Union));
    assert!((v - w).abs() <= 1e-9 * w, "{v} vs {w}");
    // Provenance names an input and one of its triangles; every sphere that reaches the
    // surface of the union is there.
    assert_eq!(out.provenance.len(), out.mesh.triangles().len());
    for &[i, t] in &out.provenance {
        assert!((t as usize) < spheres[i as usize].triangles().len());
    }
    let mut seen: Vec<u32> = out.provenance.iter().map(|p| p[0]).collect();
    seen.dedup();
    seen.sort_unstable();
    seen.dedup();
    assert!(seen.len() >= 8, "{seen:?}");
    let r = out.report();
    assert_eq!(r.operands.len(), 10);
    assert_eq!(r.operands[3].name, "4");
    assert!(r.result.closed && r.assumed.is_empty(), "{:?}", r.assumed);
}

#[test]
fn intersection_of_many_equals_the_chain_and_differences_are_refused() {
    let spheres: Vec<Mesh> = [[0.0, 0.0, 0.0], [0.7, 0.1, 0.0], [0.3, 0.6, 0.2]]
        .iter()
        .map(|&c| uv_sphere(c, 1.0, 48, 24))
        .collect();
    let inputs: Vec<ops::Input> = spheres.iter().map(ops::Input::from).collect();
    let out = ops::boolean_many(&inputs, Op::Intersection, &BooleanOptions::default()).unwrap();
    let v = closed_manifold_volume(&out.mesh);
    let w = signed_volume(&chained(&spheres, Op::Intersection));
    assert!((v - w).abs() <= 1e-9 * w, "{v} vs {w}");
    assert!(v > 0.0 && v < signed_volume(&spheres[0]));
    for op in [Op::Difference, Op::ReverseDifference] {
        let err = ops::boolean_many(&inputs, op, &BooleanOptions::default()).unwrap_err();
        assert!(matches!(err, Error::InvalidParameter(_)), "{err}");
    }
    assert!(ops::boolean_many(&[], Op::Union, &BooleanOptions::default()).is_err());
    // One input: itself.
    let one = ops::boolean_many(&inputs[..1], Op::Union, &BooleanOptions::default()).unwrap();
    assert_eq!(signed_volume(&one.mesh), signed_volume(&spheres[0]));
    // A self-overlapping input is resolved first; provenance maps to its own triangles.
    let two = joined(&[Mesh::unit_cube(), Mesh::cuboid([0.5; 3], [1.5; 3])]);
    let far = Mesh::cuboid([3.0; 3], [4.0; 3]);
    let inputs = [
        ops::Input::from(&far),
        ops::Input::from(&two),
        ops::Input::from(&far),
    ];
    let out = ops::boolean_many(&inputs, Op::Union, &BooleanOptions::default()).unwrap();
    assert_eq!(closed_manifold_volume(&out.mesh), 1.0 + 1.875);
    assert!(out.operands[1].resolved.is_some());
    assert!(out.provenance.iter().any(|&[i, t]| i == 1 && t >= 12));
}

/// Two unit cubes sharing the edge x = y = 1 (welded there: an edge of four triangles).
fn cubes_sharing_an_edge() -> Mesh {
    joined(&[
        Mesh::unit_cube(),
        Mesh::cuboid([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]),
    ])
}

#[test]
fn parts_glued_along_edges_or_given_twice_resolve() {
    // A cube given twice: one copy where w = 2 is inside, nothing under even-odd.
    let twice = joined(&[Mesh::unit_cube(), Mesh::unit_cube()]);
    for rule in [FillRule::Positive, FillRule::NonZero] {
        let out = resolve(&twice, rule);
        assert_eq!(closed_manifold_volume(&out.mesh), 1.0);
        assert_eq!(out.mesh.triangles().len(), 12);
        let s = &out.resolve.separated_input;
        assert_eq!((s.edges_split, s.unpaired), (18, 0));
    }
    assert!(resolve(&twice, FillRule::EvenOdd).mesh.is_empty());
    // Sharing an edge: both kept under every rule, the edge's ends duplicated.
    for rule in FillRule::ALL {
        let out = resolve(&cubes_sharing_an_edge(), rule);
        assert_eq!(closed_manifold_volume(&out.mesh), 2.0);
        assert_eq!(out.mesh.positions().len(), 16);
        assert_eq!(out.resolve.separated_input.edges_split, 1);
    }
}

#[test]
fn booleans_take_glued_operands_and_boxes_lying_on_the_glued_edge() {
    let glued = cubes_sharing_an_edge();
    let twice = joined(&[Mesh::unit_cube(), Mesh::unit_cube()]);
    // Boxes: lying on the shared edge (its top face holds the edge, coplanar with a face
    // of each cube, facing with one and against the other), crossing the edge, away.
    let boxes = [
        Mesh::cuboid([0.5, 0.0, 0.0], [1.5, 1.0, 1.0]),
        Mesh::cuboid([0.5; 3], [1.5; 3]),
        Mesh::cuboid([-0.5, 0.0, 0.5], [0.5, 1.0, 1.5]),
    ];
    let opts = BooleanOptions::default();
    let mut exact = Vec::new();
    for (a, va) in [(&glued, 2.0), (&twice, 1.0)] {
        for b in &boxes {
            let vb = signed_volume(b);
            let vol = |op| {
                let out = ops::boolean(a, b, op, &opts).unwrap();
                let r = out.report();
                assert!(r.operands[0].resolved.is_some() && !r.operands[0].forced);
                assert!(r
                    .assumed
                    .iter()
                    .any(|l| l.contains("separated into sheets")));
                closed_manifold_volume(&out.mesh)
            };
            let (u, i) = (vol(Op::Union), vol(Op::Intersection));
            assert!((u + i - va - vb).abs() <= 1e-12, "{u} + {i} vs {va} + {vb}");
            assert_eq!(vol(Op::Difference), va - i);
            assert_eq!(vol(Op::ReverseDifference), vb - i);
            exact.push((u, i));
        }
    }
    assert_eq!(exact[0], (2.5, 0.5));
    assert_eq!(exact[1], (2.75, 0.25));
    assert_eq!(exact[3], (1.5, 0.5));
    // Without resolving at the door, the glued operand is refused as before.
    let strict = BooleanOptions {
        checks: Checks {
            resolve: false,
            ..Checks::default()
        },
        ..BooleanOptions::default()
    };
    let err = ops::boolean(&glued, &boxes[0], Op::Union, &strict).unwrap_err();
    assert!(err.to_string().contains("non-manifold edges"), "{err}");
}

#[test]
fn union_of_cubes_sharing_an_edge_and_a_box_on_it_is_closed_in_any_order() {
    // The pairwise tree first unites two of them; the third meets the result's edge of
    // four triangles (this was open: the box's face lying on the edge was classified by a
    // winding number measured on the surface itself).
    let parts = [
        Mesh::unit_cube(),
        Mesh::cuboid([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]),
        Mesh::cuboid([0.5, 0.0, 0.0], [1.5, 1.0, 1.0]),
    ];
    for order in [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ] {
        let inputs: Vec<ops::Input> = order.iter().map(|&k| ops::Input::from(&parts[k])).collect();
        let out = ops::boolean_many(&inputs, Op::Union, &BooleanOptions::default()).unwrap();
        assert_eq!(closed_manifold_volume(&out.mesh), 2.5, "{order:?}");
    }
}

#[test]
fn split_of_a_glued_operand_gives_edge_manifold_groups_and_closed_picks() {
    let glued = cubes_sharing_an_edge();
    // A box crossing the shared edge: the edge's piece in each of A's groups has four
    // triangles unless split.
    let b = Mesh::cuboid([0.5; 3], [1.5; 3]);
    let s = ops::split(&glued, &b, &ops::SplitOptions::default()).unwrap();
    for g in &s.groups {
        let st = mesh_stats(&g.mesh);
        assert_eq!(st.non_manifold_edges, 0, "{:?}", g.group);
        assert_eq!(st.boundary_edges, 12, "{:?}", g.group);
    }
    let a_groups = s.groups.iter().filter(|g| {
        matches!(
            g.group,
            meshbool::boolean::Group::AInB | meshbool::boolean::Group::AOutB
        )
    });
    // Each of A's groups holds a piece of both cubes, now two sheets.
    assert!(a_groups.map(|g| g.components.len()).all(|n| n == 2));
    for (op, want) in [
        (Op::Union, 2.75),
        (Op::Intersection, 0.25),
        (Op::Difference, 1.75),
        (Op::ReverseDifference, 0.75),
    ] {
        let p = s.pick_op(op, &ops::PickOptions::default()).unwrap();
        assert_eq!(closed_manifold_volume(&p.mesh), want, "{op:?}");
    }
}

/// [`ops::boolean_many`] in one arrangement of all inputs, and by the pairwise tree.
fn many_both_ways(inputs: &[&Mesh], op: Op) -> (ops::BooleanManyOutput, ops::BooleanManyOutput) {
    let inputs: Vec<ops::Input> = inputs.iter().map(|&m| ops::Input::from(m)).collect();
    let one = BooleanOptions {
        one_arrangement: true,
        ..BooleanOptions::default()
    };
    let in_one = ops::boolean_many(&inputs, op, &one).unwrap();
    let tree = ops::boolean_many(&inputs, op, &BooleanOptions::default()).unwrap();
    assert_eq!(tree.combined, ops::Combined::PairwiseTree);
    (in_one, tree)
}

/// Overlapping spheres united and intersected in one arrangement (every sphere cut along
/// all the others at once, pieces kept by exact winding numbers): the solid of the
/// pairwise tree (volume to 1e-9), closed and manifold, every triangle traced to its
/// input, and the report saying how it was combined.
#[test]
fn many_in_one_arrangement_equal_the_pairwise_tree() {
    let spheres = random_spheres(10);
    let three: Vec<Mesh> = [[0.0, 0.0, 0.0], [0.7, 0.1, 0.0], [0.3, 0.6, 0.2]]
        .iter()
        .map(|&c| uv_sphere(c, 1.0, 48, 24))
        .collect();
    for (meshes, op) in [(&spheres, Op::Union), (&three, Op::Intersection)] {
        let refs: Vec<&Mesh> = meshes.iter().collect();
        let (one, tree) = many_both_ways(&refs, op);
        assert_eq!(one.combined, ops::Combined::OneArrangement, "{op:?}");
        let (v, w) = (
            closed_manifold_volume(&one.mesh),
            closed_manifold_volume(&tree.mesh),
        );
        assert!((v - w).abs() <= 1e-9 * w, "{op:?}: {v} vs {w}");
        assert!(v > 0.0, "{op:?}");
        assert!(one.failed.is_empty() && one.rounding_flips == 0, "{op:?}");
        assert_eq!(one.provenance.len(), one.mesh.triangles().len());
        for &[i, t] in &one.provenance {
            assert!((t as usize) < meshes[i as usize].triangles().len());
        }
        let json = serde_json::to_value(one.report()).unwrap();
        assert_eq!(json["combined"], "one_arrangement");
    }
}

/// Coincident and touching inputs in one arrangement: the same cube three times (one
/// copy of each face kept), two cubes sharing a face with a third crossing it where they
/// meet (the shared face cancels inside the union), cubes sharing only an edge (the result
/// split there); each the pairwise tree's volume, closed and manifold. An open input is
/// left to the tree.
#[test]
fn coincident_and_touching_inputs_in_one_arrangement() {
    let cube = Mesh::unit_cube();
    let next = Mesh::cuboid([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]);
    let across = Mesh::cuboid([0.5, 0.25, 0.5], [1.5, 0.75, 1.5]);
    let on_edge = Mesh::cuboid([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]);
    for (meshes, op, volume) in [
        (vec![&cube, &cube, &cube], Op::Union, 1.0),
        (vec![&cube, &cube, &cube], Op::Intersection, 1.0),
        (vec![&cube, &next, &across], Op::Union, 2.25),
        (vec![&cube, &across, &on_edge], Op::Union, 2.375),
        (vec![&cube, &across, &next], Op::Intersection, 0.0),
    ] {
        let (one, tree) = many_both_ways(&meshes, op);
        assert_eq!(
            one.combined,
            ops::Combined::OneArrangement,
            "{op:?} {volume}"
        );
        if volume > 0.0 {
            assert_eq!(closed_manifold_volume(&tree.mesh), volume, "{op:?}");
            assert_eq!(closed_manifold_volume(&one.mesh), volume, "{op:?}");
        } else {
            assert!(tree.mesh.is_empty() && one.mesh.is_empty(), "{op:?}");
        }
        assert!(one.failed.is_empty(), "{op:?} {volume}");
    }
    // The cube given three times keeps its twelve triangles.
    let (one, _) = many_both_ways(&[&cube, &cube, &cube], Op::Union);
    assert_eq!(one.mesh.triangles().len(), 12);
    // An open surface has no winding number: the tree.
    let sheet = meshbool::shapes::plane([0.5, 0.5, 0.5], 3.0, 3.0, 2, 2).unwrap();
    let (one, _) = many_both_ways(&[&cube, &next, &sheet], Op::Union);
    assert_eq!(one.combined, ops::Combined::PairwiseTree);
}

/// Overlapping and touching boxes in one mesh, turned off the coordinate lattice (the
/// crossings' points then round when written): a multi-body CAD export.
fn overlapping_boxes(degrees: f64, shift: [f64; 3]) -> Mesh {
    let parts = [
        Mesh::cuboid([0.0; 3], [2.0, 1.0, 1.0]),
        Mesh::cuboid([1.5, 0.25, 0.25], [3.0, 0.75, 1.5]),
        // Touches the first box on part of its face x = 0 (no vertex or edge shared).
        Mesh::cuboid([-1.0, 0.2, 0.1], [0.0, 0.8, 0.5]),
        Mesh::cuboid([0.5, -0.5, 0.5], [1.0, 1.5, 0.75]),
    ];
    let t = meshbool::Transform::rotation([1.0, 2.0, 3.0], degrees)
        .unwrap()
        .translate(shift);
    joined(&parts).transformed(&t)
}

#[test]
fn self_overlapping_operands_give_closed_results_with_nothing_rounded_in_between() {
    // Each operand crosses itself; resolved and combined in one arrangement, the result
    // is closed and the volume identities hold with the operands' volumes as resolved at
    // the door. (Resolving first and combining the rounded surfaces left holes here.)
    let opts = BooleanOptions::default();
    for (k, degrees) in [17.0, 23.5, 41.0].into_iter().enumerate() {
        let a = overlapping_boxes(degrees, [0.0; 3]);
        let b = overlapping_boxes(degrees + 13.0, [0.3, -0.2, 0.1 * k as f64]);
        let mut vols = Vec::new();
        for op in Op::ALL {
            let out = ops::boolean(&a, &b, op, &opts).unwrap();
            let r = out.report();
            assert!(r.operands.iter().all(|o| o.resolved.is_some()), "{op}");
            assert!(r.result.closed, "{degrees} {op}: {:?}", r.result);
            let v = closed_manifold_volume(&out.mesh);
            assert_eq!(out.provenance.len(), out.mesh.triangles().len());
            assert!(out.provenance.iter().all(|p| {
                let n = match p.source {
                    meshbool::Source::A => a.triangles().len(),
                    meshbool::Source::B => b.triangles().len(),
                };
                (p.triangle as usize) < n
            }));
            vols.push((v, r.operands[0].volume, r.operands[1].volume));
        }
        let (u, va, vb) = vols[0];
        let (i, d, rd) = (vols[1].0, vols[2].0, vols[3].0);
        let tol = 1e-9 * (va + vb);
        assert!(
            (u + i - va - vb).abs() <= tol,
            "{degrees}: {u} + {i} vs {va} + {vb}"
        );
        assert!((d + i - va).abs() <= tol, "{degrees}: {d} + {i} vs {va}");
        assert!((rd + i - vb).abs() <= tol, "{degrees}: {rd} + {i} vs {vb}");
        // The resolved operands' volumes are those of the boxes' union.
        let alone = closed_manifold_volume(&resolve(&a, FillRule::Positive).mesh);
        assert!((va - alone).abs() <= 1e-12 * alone, "{va} vs {alone}");
    }
}
