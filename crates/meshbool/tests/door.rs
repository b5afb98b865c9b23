//! What the door makes of real data before a boolean: triangles that collapse when their
//! corners are welded (distinct vertices at one position, as UV-seamed models and
//! exports with duplicate vertices have them).

// Only part of it is used here.
#[allow(dead_code)]
mod common;

use meshbool::measure::mesh_stats;
use meshbool::ops::{self, BooleanOptions};
use meshbool::{Mesh, Op};

/// The unit cube given as a UV-seamed export would give it: triangle `t`'s third corner
/// is a second vertex at the same position, and a zero-area triangle joins the two
/// copies across the edge before it. As indexed it is open; welded, the extra triangle
/// has two equal corners and its edge four triangles.
fn cube_with_a_collapsed_triangle(t: usize) -> (Mesh, usize) {
    let (mut positions, mut triangles) = Mesh::unit_cube().into_parts();
    let [a, b, c] = triangles[t];
    let d = positions.len() as u32;
    positions.push(positions[c as usize]);
    triangles[t] = [a, b, d];
    let collapsed = triangles.len();
    triangles.push([b, c, d]);
    (Mesh::new(positions, triangles).unwrap(), collapsed)
}

#[test]
fn collapsed_triangles_are_removed_at_the_door_and_provenance_names_the_input() {
    let b = Mesh::cuboid([0.5, -0.25, 0.5], [1.5, 0.75, 1.5]);
    for t in [0, 5, 11] {
        let (a, collapsed) = cube_with_a_collapsed_triangle(t);
        let welded = meshbool::weld_exact(&a).mesh;
        assert_eq!(
            mesh_stats(&welded).non_manifold_edges,
            1,
            "the edge of four"
        );
        let opts = BooleanOptions::default();
        let mut vols = Vec::new();
        for op in Op::ALL {
            let out = ops::boolean(&a, &b, op, &opts).unwrap();
            let r = out.report();
            assert_eq!(r.operands[0].collapsed_triangles, 1, "{t} {op}");
            assert_eq!(r.operands[1].collapsed_triangles, 0);
            assert!(r.operands[0].resolved.is_none());
            assert!(
                r.assumed.iter().any(|l| l.contains("two equal corners")),
                "{:?}",
                r.assumed
            );
            let s = mesh_stats(&out.mesh);
            assert!(s.closed, "{t} {op}: {s:?}");
            assert_eq!((s.boundary_edges, s.non_manifold_edges), (0, 0));
            // Every result triangle lies in the face of the input triangle named.
            assert!(out
                .provenance
                .iter()
                .all(|p| p.source == meshbool::Source::B || p.triangle as usize != collapsed));
            common::assert_in_parent_faces(&out.mesh, &out.provenance, &a, &b, "collapsed");
            vols.push(s.volume);
        }
        // The boxes share 0.5 × 0.75 × 0.5: exact on these boxes.
        assert_eq!(vols, vec![1.8125, 0.1875, 0.8125, 0.8125], "{t}");
    }
}

#[test]
fn positions_that_differ_by_rounding_are_one_vertex() {
    let a = common::cube_off_by_an_ulp();
    let open = mesh_stats(&meshbool::weld_exact(&a).mesh);
    assert!(open.boundary_edges > 0, "{open:?}");
    let b = Mesh::cuboid([0.5, -0.25, 0.5], [1.5, 0.75, 1.5]);
    let opts = BooleanOptions::default();
    for (op, exact) in Op::ALL.into_iter().zip([1.8125, 0.1875, 0.8125, 0.8125]) {
        let out = ops::boolean(&a, &b, op, &opts).unwrap();
        let r = out.report();
        let noise = r.operands[0].rounding_noise.as_ref().expect("merged");
        assert_eq!(noise.boundary_edges, [open.boundary_edges, 0]);
        assert_eq!(noise.precision, "f64");
        assert!(noise.tolerance <= 1e-15, "{}", noise.tolerance);
        assert!(r.assumed.iter().any(|l| l.contains("rounding noise")));
        let s = mesh_stats(&out.mesh);
        assert!(s.closed, "{op}: {s:?}");
        assert!(
            (s.volume - exact).abs() <= 1e-14,
            "{op}: {} vs {exact}",
            s.volume
        );
    }
    // Taken exactly as written, the cube is an open surface with cracks whose sheets
    // cross by an ulp: refused (or, forced, open).
    let mut exact = BooleanOptions {
        checks: meshbool::ops::Checks {
            rounding_noise: false,
            ..meshbool::ops::Checks::default()
        },
        ..BooleanOptions::default()
    };
    let err = ops::boolean(&a, &b, Op::Union, &exact).unwrap_err();
    assert!(err.to_string().contains("not closed"), "{err}");
    // The refusal says what would close the cracks.
    assert!(err.to_string().contains("close at a weld of 2e-9"), "{err}");
    exact.checks.force = true;
    let out = ops::boolean(&a, &b, Op::Union, &exact).unwrap();
    assert!(out.report().operands[0].rounding_noise.is_none());
    assert!(!mesh_stats(&out.mesh).closed);
}

#[test]
fn real_holes_and_gaps_beyond_rounding_stay_open() {
    // A cube without one triangle, and the ulp cube with one corner moved 1e-9 (far more
    // than rounding): the hole is not merged; the gapped cube's other cracks are, the
    // moved corner's stay open.
    let forced = meshbool::ops::Checks {
        force: true,
        ..meshbool::ops::Checks::default()
    };
    let (positions, mut triangles) = Mesh::unit_cube().into_parts();
    triangles.pop();
    let holed = Mesh::new(positions, triangles).unwrap();
    let op = ops::Operand::new("holed", &holed, &forced).unwrap();
    assert!(op.report().rounding_noise.is_none());
    assert_eq!(mesh_stats(op.mesh()).boundary_edges, 3);
    let (mut positions, triangles) = common::cube_off_by_an_ulp().into_parts();
    positions[3][0] += 1e-9;
    let gapped = Mesh::new(positions, triangles).unwrap();
    let before = mesh_stats(&meshbool::weld_exact(&gapped).mesh).boundary_edges;
    let op = ops::Operand::new("gapped", &gapped, &forced).unwrap();
    let n = op
        .report()
        .rounding_noise
        .as_ref()
        .expect("the other cracks");
    assert_eq!(n.boundary_edges[0], before);
    assert!(n.boundary_edges[1] > 0, "{n:?}");
    assert_eq!(mesh_stats(op.mesh()).boundary_edges, n.boundary_edges[1]);
}

/// Ten squares of side 2.4 laid corner to corner along the diagonal, centres 2.4 apart in
/// x and y, each corner computed from its own centre: the shared corners differ in the
/// last bits (an overlap or a gap of ~1e-15).
fn diagonal_sheet() -> Mesh {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for i in 0..10 {
        let c = 12.0 * (-1.0 + 0.2 * f64::from(i));
        let v = positions.len() as u32;
        for (dx, dy) in [(-1.2, -1.2), (1.2, -1.2), (1.2, 1.2), (-1.2, 1.2)] {
            positions.push([c + dx, c + dy, 0.0]);
        }
        triangles.push([v, v + 1, v + 2]);
        triangles.push([v, v + 2, v + 3]);
    }
    Mesh::new(positions, triangles).unwrap()
}

#[test]
fn corners_that_touch_at_rounding_level_are_shared_not_crossing() {
    let sheet = diagonal_sheet();
    let exact = meshbool::weld_exact(&sheet).mesh;
    assert!(
        exact.positions().len() > 31,
        "some corners differ in the last bits: {}",
        exact.positions().len()
    );
    let b = Mesh::cuboid([-5.0, -5.0, -5.0], [5.0, 5.0, 5.0]);
    let out = ops::boolean(&sheet, &b, Op::Intersection, &BooleanOptions::default()).unwrap();
    let r = out.report();
    let noise = r.operands[0]
        .rounding_noise
        .as_ref()
        .expect("corners merged");
    // No edge closes: the boundary stays the squares' outlines.
    assert_eq!(noise.boundary_edges, [40, 40]);
    assert_eq!(
        r.operands[0]
            .self_intersections
            .as_ref()
            .map_or(0, |s| s.pairs),
        0
    );
    // The sheet's part inside the box: the squares centred at −2.4, 0 and 2.4 whole, and
    // the corners [3.6, 5]² of the two centred at ±4.8: 3 · 2.4² + 2 · 1.4² = 21.2.
    let p = out.mesh.positions();
    let area: f64 = out
        .mesh
        .triangles()
        .iter()
        .zip(&out.provenance)
        .filter(|(_, s)| s.source == meshbool::Source::A)
        .map(|(t, _)| {
            let [a, b, c] = t.map(|v| p[v as usize]);
            // The sheet lies in z = 0: the area is half the cross product's z.
            0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])).abs()
        })
        .sum();
    assert!((area - 21.2).abs() < 1e-12, "{area}");
    // Taken exactly as written, the corners overlap by an ulp: an open surface crossing
    // itself, taken as given and said so, its part inside the box the same.
    let exact_opts = BooleanOptions {
        checks: meshbool::ops::Checks {
            rounding_noise: false,
            ..meshbool::ops::Checks::default()
        },
        ..BooleanOptions::default()
    };
    let out = ops::boolean(&sheet, &b, Op::Intersection, &exact_opts).unwrap();
    let si = out.report().operands[0].self_intersections.clone().unwrap();
    assert!(si.pairs > 0 && si.open_kept, "{si:?}");
    assert!(out.failed.is_empty());
}

/// A non-manifold operand that cannot be resolved (an open sheet with a fin along one of
/// its edges) is refused with the count and where the first such edge is.
#[test]
fn a_non_manifold_refusal_says_where() {
    let sheet = common::finned_sheet();
    let b = Mesh::cuboid([0.2, 0.2, -1.0], [0.8, 0.8, 1.0]);
    let err = ops::boolean(&sheet, &b, Op::Union, &BooleanOptions::default()).unwrap_err();
    let text = err.to_string();
    assert!(
        text.contains("1 non-manifold edges (the first near [0.5, 0.5, 0.0])"),
        "{text}"
    );
    let forced = BooleanOptions {
        checks: meshbool::ops::Checks {
            force: true,
            ..meshbool::ops::Checks::default()
        },
        ..BooleanOptions::default()
    };
    let out = ops::boolean(&sheet, &b, Op::Union, &forced).unwrap();
    assert_eq!(
        out.report().operands[0].non_manifold_near,
        Some([0.5, 0.5, 0.0])
    );
}

/// Two unit cubes sharing their edge on the z axis, the second turned 30° about it into
/// the first: they overlap, and around the shared edge the faces alternate (first cube,
/// second, first, second), so no pairing of its four triangles into two closed sheets
/// keeps each cube's fan at the edge's ends apart. Every edge is still used as often in
/// each direction, so the winding number is defined everywhere off the surface.
fn cubes_crossing_at_a_shared_edge() -> Mesh {
    let mut m = Mesh::unit_cube();
    m.append(&Mesh::unit_cube().transformed(&meshbool::Transform::rotation_z(30.0)))
        .unwrap();
    m
}

/// A non-manifold operand whose winding number is defined (every edge used as often in
/// one direction as in the other) is resolved through its self-arrangement, not refused,
/// and gives closed, manifold results whose volumes add up.
#[test]
fn a_balanced_non_manifold_operand_is_resolved() {
    let a = cubes_crossing_at_a_shared_edge();
    let welded = meshbool::weld_exact(&a).mesh;
    let s = mesh_stats(&welded);
    assert_eq!((s.boundary_edges, s.non_manifold_edges), (0, 1), "{s:?}");
    // Two unit cubes less the overlap of two unit squares turned 30° about a corner
    // (the quadrilateral (0,0), (cos 30°, sin 30°), (1/√3, 1), (0, 1): area 1/√3).
    let expected = 2.0 - 1.0 / 3f64.sqrt();
    let resolved = ops::resolve(&a, &ops::ResolveOptions::default()).unwrap();
    let s = mesh_stats(&resolved.mesh);
    assert!(s.closed, "{s:?}");
    assert_eq!((s.boundary_edges, s.non_manifold_edges), (0, 0));
    assert!(
        (s.volume - expected).abs() < 1e-12,
        "{} {expected}",
        s.volume
    );
    // The same solid as the two cubes united by a boolean.
    let one = Mesh::unit_cube();
    let two = one.transformed(&meshbool::Transform::rotation_z(30.0));
    let united = ops::boolean(&one, &two, Op::Union, &BooleanOptions::default()).unwrap();
    assert!((mesh_stats(&united.mesh).volume - s.volume).abs() < 1e-14);
    // Against a box through both cubes: every operation answered, closed and manifold.
    let b = Mesh::cuboid([-0.4, 0.3, 0.25], [0.6, 1.6, 0.75]);
    let mut vols = std::collections::HashMap::new();
    for op in Op::ALL {
        let out = ops::boolean(&a, &b, op, &BooleanOptions::default()).unwrap();
        let s = mesh_stats(&out.mesh);
        assert!(s.closed, "{op}: {s:?}");
        assert_eq!((s.boundary_edges, s.non_manifold_edges), (0, 0), "{op}");
        let r = out.report();
        assert!((r.operands[0].volume - expected).abs() < 1e-12);
        assert!(r.operands[0].resolved.is_some(), "{op}");
        assert_faces_as_parents(&out.mesh, &out.provenance, &a, &b);
        vols.insert(op, s.volume);
    }
    let (va, vb) = (expected, 1.0 * 1.3 * 0.5);
    let sum = vols[&Op::Union] + vols[&Op::Intersection];
    assert!((sum - va - vb).abs() < 1e-12, "{vols:?}");
    assert!((vols[&Op::Difference] + vols[&Op::Intersection] - va).abs() < 1e-12);
    assert!((vols[&Op::ReverseDifference] + vols[&Op::Intersection] - vb).abs() < 1e-12);
}

/// Asserts that every triangle of `mesh` of positive area faces as the input triangle its
/// provenance names (reversed where the provenance says so).
fn assert_faces_as_parents(mesh: &Mesh, provenance: &[meshbool::Provenance], a: &Mesh, b: &Mesh) {
    fn normal(m: &Mesh, t: [u32; 3]) -> [f64; 3] {
        let [p, q, r] = t.map(|v| m.positions()[v as usize]);
        let (u, w) = (
            [0, 1, 2].map(|k| q[k] - p[k]),
            [0, 1, 2].map(|k| r[k] - p[k]),
        );
        [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ]
    }
    assert_eq!(mesh.triangles().len(), provenance.len());
    for (t, p) in mesh.triangles().iter().zip(provenance) {
        let source = if p.source == meshbool::Source::A {
            a
        } else {
            b
        };
        let (n, m) = (
            normal(mesh, *t),
            normal(source, source.triangles()[p.triangle as usize]),
        );
        let len = |v: [f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if len(n) < 1e-9 {
            continue;
        }
        let cos = n.iter().zip(m).map(|(x, y)| x * y).sum::<f64>() / (len(n) * len(m));
        let cos = if p.flipped { -cos } else { cos };
        assert!(cos > 1.0 - 1e-9, "{t:?} {p:?}: {cos}");
    }
}

/// An open surface that crosses itself (two square sheets crossing in an X, as fault
/// strands do) has no inside of its own to be ambiguous: it is taken as given, said in
/// the report, and its pieces inside a closed operand are exactly the parts of its sheets
/// there.
#[test]
fn an_open_surface_crossing_itself_is_taken_as_given() {
    let flat = Mesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
    .unwrap();
    let upright = Mesh::new(
        vec![
            [1.0, 0.0, -1.0],
            [1.0, 2.0, -1.0],
            [1.0, 2.0, 1.0],
            [1.0, 0.0, 1.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
    .unwrap();
    let mut a = flat;
    a.append(&upright).unwrap();
    let b = Mesh::cuboid([0.5, 0.5, -0.5], [1.5, 1.5, 0.5]);
    let out = ops::boolean(&a, &b, Op::Intersection, &BooleanOptions::default()).unwrap();
    let r = out.report();
    let si = r.operands[0].self_intersections.clone().unwrap();
    assert!(
        si.open_kept && si.pairs > 0 && !r.operands[0].forced,
        "{si:?}"
    );
    assert!(
        r.assumed.iter().any(|l| l.contains("of its open parts")),
        "{:?}",
        r.assumed
    );
    // A's pieces inside the box: a unit square of each sheet.
    let from_a: Vec<[u32; 3]> = out
        .provenance
        .iter()
        .zip(out.mesh.triangles())
        .filter(|(p, _)| p.source == meshbool::Source::A)
        .map(|(_, t)| *t)
        .collect();
    let pieces = Mesh::new(out.mesh.positions().to_vec(), from_a).unwrap();
    let area = meshbool::measure::area(&pieces);
    assert!((area - 2.0).abs() < 1e-12, "{area}");
    // Closed parts crossing each other are still resolved, not taken as given.
    let mut two = Mesh::unit_cube();
    two.append(&Mesh::cuboid([0.5; 3], [1.5; 3])).unwrap();
    let out = ops::boolean(&two, &b, Op::Union, &BooleanOptions::default()).unwrap();
    let o = &out.report().operands[0];
    assert!(o.resolved.is_some() && !o.self_intersections.as_ref().unwrap().open_kept);
}
