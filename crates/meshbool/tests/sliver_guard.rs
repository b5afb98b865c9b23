//! The sliver guard ([`meshbool::ops::SplitOptions::sliver_guard`]): a floor of two
//! triangles crossed by a fine fence is cut into pieces of bounded shape, the split's
//! groups keep their areas, and every fence segment is still an edge of the floor's
//! pieces; off, the floor's pieces are needles.

use meshbool::measure::mesh_stats;
use meshbool::ops::{self, SplitOptions};
use meshbool::Mesh;

/// The floor [0, 100]² at z = 0 (two triangles, facing up).
fn floor() -> Mesh {
    Mesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [100.0, 0.0, 0.0],
            [100.0, 100.0, 0.0],
            [0.0, 100.0, 0.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
    .unwrap()
}

/// A vertical fence at x = 50 from y = 10 to 90, z from −1 to 1, in strips 0.5 wide.
fn fence() -> Mesh {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    let strips = 160;
    for i in 0..=strips {
        let y = 10.0 + 0.5 * f64::from(i);
        positions.push([50.0, y, -1.0]);
        positions.push([50.0, y, 1.0]);
    }
    for i in 0..strips {
        let (a, b, c, d) = (2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3);
        triangles.push([a, c, d]);
        triangles.push([a, d, b]);
    }
    Mesh::new(positions, triangles).unwrap()
}

/// Longest edge² / (2 · area), over that of the equilateral triangle (1/√3·2 = 1.1547):
/// 1 for an equilateral triangle, large for a needle.
fn aspect(m: &Mesh, t: usize) -> f64 {
    let [a, b, c] = m.corners(t);
    let e = |p: [f64; 3], q: [f64; 3]| {
        ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
    };
    let longest = e(a, b).max(e(b, c)).max(e(c, a));
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let twice = ((u[1] * v[2] - u[2] * v[1]).powi(2)
        + (u[2] * v[0] - u[0] * v[2]).powi(2)
        + (u[0] * v[1] - u[1] * v[0]).powi(2))
    .sqrt();
    longest * longest / twice / (2.0 / 3f64.sqrt())
}

/// The floor's pieces (groups of A) as one mesh.
fn floor_pieces(out: &ops::SplitOutput) -> Vec<Mesh> {
    out.groups
        .iter()
        .filter(|g| g.group.name().starts_with("a_"))
        .map(|g| g.mesh.clone())
        .collect()
}

#[test]
fn a_floor_cut_by_a_fine_fence_gets_pieces_of_bounded_shape() {
    let (a, b) = (floor(), fence());
    let count = |out: &ops::SplitOutput| {
        let pieces = floor_pieces(out);
        let total: usize = pieces.iter().map(|m| m.triangles().len()).sum();
        let needles: usize = pieces
            .iter()
            .map(|m| {
                (0..m.triangles().len())
                    .filter(|&t| aspect(m, t) > 100.0)
                    .count()
            })
            .sum();
        let area: f64 = pieces.iter().map(|m| mesh_stats(m).area).sum();
        (total, needles, area)
    };
    let plain = ops::split(
        &a,
        &b,
        &SplitOptions {
            keep_seam_points: true,
            ..SplitOptions::default()
        },
    )
    .unwrap();
    let (total, needles, area) = count(&plain);
    assert!(
        needles > total / 2,
        "without the guard: {needles} needles of {total}"
    );
    assert!((area - 10_000.0).abs() < 1e-9, "{area}");
    let guarded = ops::split(
        &a,
        &b,
        &SplitOptions {
            keep_seam_points: true,
            sliver_guard: true,
            ..SplitOptions::default()
        },
    )
    .unwrap();
    let (total, needles, area) = count(&guarded);
    assert!(total > 10, "{total}");
    assert!(needles < 10, "with the guard: {needles} needles of {total}");
    assert!((area - 10_000.0).abs() < 1e-9, "{area}");
    // The fence's crossing is still cut into the floor: edges of the floor's pieces
    // along x = 50 run from y = 10 to 90 without a gap (the strips' diagonals cross the
    // floor half-way, so the seam's points are 0.25 apart).
    let mut along: Vec<(f64, f64)> = Vec::new();
    for m in floor_pieces(&guarded) {
        let p = m.positions();
        for t in m.triangles() {
            for k in 0..3 {
                let (u, v) = (p[t[k] as usize], p[t[(k + 1) % 3] as usize]);
                if u[0] == 50.0 && v[0] == 50.0 {
                    along.push((u[1].min(v[1]), u[1].max(v[1])));
                }
            }
        }
    }
    along.sort_by(|x, y| x.partial_cmp(y).unwrap());
    along.dedup();
    assert_eq!(along.len(), 320, "{:?}", &along[..along.len().min(8)]);
    let mut reach = 10.0;
    for &(lo, hi) in &along {
        assert_eq!(lo, reach, "a gap at y = {reach}");
        reach = hi;
    }
    assert_eq!(reach, 90.0);
    // The fence's own pieces are untouched by the guard (its triangles are small).
    let fence_triangles = |out: &ops::SplitOutput| -> usize {
        out.groups
            .iter()
            .filter(|g| g.group.name().starts_with("b_"))
            .map(|g| g.mesh.triangles().len())
            .sum()
    };
    assert_eq!(fence_triangles(&guarded), fence_triangles(&plain));
}

/// A box whose faces are two triangles each, minus a fine sphere poking through its top
/// face: with the guard the worst-shaped piece is better, and the difference is the same
/// solid (closed, manifold, the same volume to rounding).
#[test]
fn a_guarded_boolean_is_the_same_solid() {
    let cube = Mesh::cuboid([-5.0, -5.0, -5.0], [5.0, 5.0, 5.0]);
    let ball = meshbool::shapes::uv_sphere([0.3, 0.2, 5.0], 3.0, 128, 64);
    let run = |guard: bool| {
        let opts = ops::BooleanOptions {
            sliver_guard: guard,
            keep_seam_points: true,
            ..ops::BooleanOptions::default()
        };
        ops::boolean(&cube, &ball, meshbool::Op::Difference, &opts).unwrap()
    };
    let (plain, guarded) = (run(false), run(true));
    let (p, g) = (mesh_stats(&plain.mesh), mesh_stats(&guarded.mesh));
    assert!(
        g.closed && g.boundary_edges == 0 && g.non_manifold_edges == 0,
        "{g:?}"
    );
    assert!(
        (g.volume - p.volume).abs() < 1e-9 * p.volume,
        "{} vs {}",
        g.volume,
        p.volume
    );
    assert!(guarded.mesh.triangles().len() > plain.mesh.triangles().len());
    let worst = |m: &Mesh| {
        (0..m.triangles().len())
            .map(|t| aspect(m, t))
            .fold(0.0, f64::max)
    };
    assert!(
        worst(&guarded.mesh) < worst(&plain.mesh),
        "worst aspect {} guarded, {} plain",
        worst(&guarded.mesh),
        worst(&plain.mesh)
    );
}
