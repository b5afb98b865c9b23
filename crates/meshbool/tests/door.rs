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
    // Taken exactly as written, the corners overlap by an ulp: refused.
    let exact_opts = BooleanOptions {
        checks: meshbool::ops::Checks {
            rounding_noise: false,
            ..meshbool::ops::Checks::default()
        },
        ..BooleanOptions::default()
    };
    let err = ops::boolean(&sheet, &b, Op::Intersection, &exact_opts).unwrap_err();
    assert!(err.to_string().contains("self-intersecting"), "{err}");
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
