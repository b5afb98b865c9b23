//! Envelopes of folded open surfaces (`resolve --envelope`): single-valued, at the highest
//! (lowest) sheet everywhere, over the whole footprint, connected where the input was.

use meshbool::edges::EdgeCounts;
use meshbool::io;
use meshbool::ops::{self, Envelope, EnvelopeOptions};
use meshbool::repair::{orient, Facing};
use meshbool::{Error, Mesh};

#[allow(dead_code)]
mod common;

fn envelope(m: &Mesh, side: Envelope) -> ops::EnvelopeOutput {
    let opts = EnvelopeOptions {
        side,
        ..EnvelopeOptions::default()
    };
    ops::envelope(m, &opts).unwrap()
}

/// A 8 x 8 grid on a gentle slope with two interior vertices pushed over their
/// neighbours and raised: four triangles fold under the rest (an overhang), away from the
/// boundary.
fn folded_grid() -> Mesh {
    let n = 8;
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (mut x, y) = (i as f64, j as f64);
            let mut z = 0.1 * x + 0.05 * y;
            if (i, j) == (4, 4) {
                (x, z) = (5.6, z + 1.0);
            }
            if (i, j) == (4, 3) {
                (x, z) = (5.3, z + 0.5);
            }
            positions.push([x, y, z]);
        }
    }
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            let (b, c, d) = (a + 1, a + n + 2, a + n + 1);
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    Mesh::new(positions, triangles).unwrap()
}

/// Twice the signed area of a triangle projected on the plane z = 0.
fn plan_area2(m: &Mesh, tri: [u32; 3]) -> f64 {
    let [a, b, c] = tri.map(|v| m.positions()[v as usize]);
    (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
}

/// The heights of `m`'s triangles over plan point (x, y) (strictly inside them in plan;
/// `None` when the point is within `eps` of a triangle's edge in plan).
fn heights(m: &Mesh, x: f64, y: f64) -> Option<Vec<f64>> {
    let mut out = Vec::new();
    for &tri in m.triangles() {
        let [a, b, c] = tri.map(|v| m.positions()[v as usize]);
        let d = plan_area2(m, tri);
        if d.abs() < 1e-12 {
            continue; // vertical: no height of its own
        }
        let l1 = ((x - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (y - a[1])) / d;
        let l2 = ((b[0] - a[0]) * (y - a[1]) - (x - a[0]) * (b[1] - a[1])) / d;
        let l0 = 1.0 - l1 - l2;
        let least = l0.min(l1).min(l2);
        if least.abs() < 1e-7 {
            return None;
        }
        if least > 0.0 {
            out.push(l0 * a[2] + l1 * b[2] + l2 * c[2]);
        }
    }
    Some(out)
}

/// Checks `env` is the `side` envelope of `surface` at a grid of plan points over
/// `[lo, hi]`: exactly one sheet wherever the surface has one, at its highest (lowest)
/// height, at a third of the points at least (the others lie on an edge in plan).
fn assert_envelope_at(surface: &Mesh, env: &Mesh, side: Envelope, lo: [f64; 2], hi: [f64; 2]) {
    let mut compared = 0;
    let steps = 37;
    for i in 0..steps {
        for j in 0..steps {
            let x = lo[0] + (hi[0] - lo[0]) * (i as f64 + 0.37) / steps as f64;
            let y = lo[1] + (hi[1] - lo[1]) * (j as f64 + 0.61) / steps as f64;
            let (Some(s), Some(e)) = (heights(surface, x, y), heights(env, x, y)) else {
                continue;
            };
            if s.is_empty() {
                assert!(e.is_empty(), "({x}, {y}): outside the surface, {e:?}");
                continue;
            }
            let want = match side {
                Envelope::Upper => s.iter().copied().fold(f64::MIN, f64::max),
                Envelope::Lower => s.iter().copied().fold(f64::MAX, f64::min),
            };
            assert_eq!(e.len(), 1, "({x}, {y}): sheets {s:?}, envelope {e:?}");
            assert!(
                (e[0] - want).abs() <= 1e-9 * want.abs().max(1.0),
                "({x}, {y})"
            );
            compared += 1;
        }
    }
    assert!(compared > steps * steps / 3, "{compared}");
}

/// Faces up everywhere (vertical jump walls aside), and covers the plan area the surface
/// covers: its signed plan area (a fold's three layers count +1 −1 +1).
fn assert_faces_up_over(surface: &Mesh, env: &Mesh) {
    let (up, _) = orient(surface, Facing::ZUp);
    let signed: f64 = up.triangles().iter().map(|&t| plan_area2(&up, t)).sum();
    let mut area = 0.0;
    for &t in env.triangles() {
        let a = plan_area2(env, t);
        assert!(a > -1e-9, "a triangle faces down: {a}");
        area += a;
    }
    assert!((area - signed).abs() <= 1e-9 * signed, "{area} vs {signed}");
}

#[test]
fn a_folded_grid_gets_single_valued_envelopes() {
    let grid = folded_grid();
    assert_eq!(EdgeCounts::of(&grid).inconsistent, 0);
    for side in Envelope::ALL {
        let out = envelope(&grid, side);
        let r = &out.report;
        assert_eq!(r.folded_triangles, 4, "{side:?}");
        assert_eq!(r.fold_patches, 1);
        assert!(r.hidden_triangles >= 4, "{r:?}");
        assert!(r.jump_walls > 0, "{r:?}");
        assert_eq!(r.failed_triangles, 0);
        // The same outline: only the grid's 32 boundary edges, none where it jumps.
        let c = EdgeCounts::of(&out.mesh);
        assert_eq!((c.boundary, c.non_manifold, c.inconsistent), (32, 0, 0));
        assert_faces_up_over(&grid, &out.mesh);
        assert_eq!(
            out.mesh
                .triangles()
                .iter()
                .map(|&t| plan_area2(&out.mesh, t))
                .sum::<f64>(),
            2.0 * 64.0
        );
        assert_envelope_at(&grid, &out.mesh, side, [0.0, 0.0], [8.0, 8.0]);
        assert_eq!(out.parent.len(), out.mesh.triangles().len());
        assert!(out
            .parent
            .iter()
            .all(|&p| (p as usize) < grid.triangles().len()));
    }
}

#[test]
fn a_surface_without_folds_is_its_own_envelope() {
    let plane = meshbool::shapes::heightfield([0.0, 0.0], [4.0, 3.0], 4, 3, |x, y| x - y);
    for side in Envelope::ALL {
        let out = envelope(&plane, side);
        assert_eq!(out.report.folded_triangles, 0);
        assert_eq!(out.report.hidden_triangles, 0);
        assert_eq!(out.report.jump_walls, 0);
        assert_eq!(out.mesh.triangles().len(), plane.triangles().len());
        assert_faces_up_over(&plane, &out.mesh);
    }
}

#[test]
fn kirra_terrain_envelopes_keep_its_outline_and_hide_its_folds() {
    let Some(path) = common::shared_data("kirra_terrain.obj") else {
        return;
    };
    let terrain = io::read_path(path).unwrap();
    let b = terrain.bounds().unwrap();
    for side in Envelope::ALL {
        let out = envelope(&terrain, side);
        let r = &out.report;
        assert_eq!(r.folded_triangles, 22, "{side:?}");
        // Each fold triangle lies under (over) another sheet: none is on the envelope.
        assert_eq!(r.hidden_triangles, 22, "{r:?}");
        assert_eq!(r.failed_triangles, 0);
        let c = EdgeCounts::of(&out.mesh);
        assert_eq!((c.boundary, c.non_manifold, c.inconsistent), (560, 0, 0));
        assert_faces_up_over(&terrain, &out.mesh);
        assert_envelope_at(
            &terrain,
            &out.mesh,
            side,
            [b.min[0], b.min[1]],
            [b.max[0], b.max[1]],
        );
    }
}

#[test]
fn closed_meshes_have_no_envelope_here() {
    let err = ops::envelope(&Mesh::unit_cube(), &EnvelopeOptions::default()).unwrap_err();
    assert!(matches!(err, Error::Unresolvable { .. }), "{err}");
    assert!(err.to_string().contains("closed"), "{err}");
    assert_eq!(Envelope::Lower.name(), "lower");
    assert_eq!("UPPER".parse::<Envelope>().unwrap(), Envelope::Upper);
}
