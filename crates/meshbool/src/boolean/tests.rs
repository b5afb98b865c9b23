use super::*;
use crate::measure::{mesh_stats, signed_volume};
use crate::shapes::rigid_motion;
use crate::shapes::{torus, uv_sphere};
use crate::test_util::{fanned_prism, Rng};

fn vol(m: &Mesh) -> f64 {
    signed_volume(m)
}

/// The pipeline's boolean with the default options.
fn boolean(a: &Mesh, b: &Mesh, op: Op) -> BooleanResult {
    super::boolean(a, b, op, &PipelineOptions::default())
}

/// The pipeline's split with the default options.
fn split(a: &Mesh, b: &Mesh) -> Split {
    super::split(a, b, &PipelineOptions::default())
}

/// The default options but for [`PipelineOptions::first_votes`].
fn first_votes() -> PipelineOptions<'static> {
    PipelineOptions {
        first_votes: true,
        ..PipelineOptions::default()
    }
}

/// Closed, manifold, consistently oriented (or empty).
fn assert_closed(m: &Mesh, what: &str) {
    if m.triangles.is_empty() {
        return;
    }
    let s = mesh_stats(m);
    assert_eq!(
        (s.boundary_edges, s.non_manifold_edges, s.inconsistent_edges),
        (0, 0, 0),
        "{what}: {} triangles",
        s.triangles
    );
}

/// All four operations, closed outputs, and the volume identities.
fn check(a: &Mesh, b: &Mesh, tol: f64) -> [f64; 4] {
    let ops = [
        Op::Union,
        Op::Intersection,
        Op::Difference,
        Op::ReverseDifference,
    ];
    let r = ops.map(|op| {
        let r = boolean(a, b, op);
        assert!(r.failed.is_empty(), "{op:?}: {:?}", r.failed);
        // Valid solids: each patch's first deciding vote is all its votes' answer.
        let first = super::boolean(a, b, op, &first_votes());
        assert_eq!(
            (&first.mesh, &first.provenance),
            (&r.mesh, &r.provenance),
            "{op:?}: first deciding votes"
        );
        assert_closed(&r.mesh, &format!("{op:?}"));
        vol(&r.mesh)
    });
    let [u, i, d, rd] = r;
    let (va, vb) = (vol(a), vol(b));
    let scale = va.abs().max(vb.abs());
    assert!(
        (u + i - va - vb).abs() <= tol * scale,
        "union+inter {u}+{i} vs {va}+{vb}"
    );
    assert!((d - (va - i)).abs() <= tol * scale, "A-B {d} vs {va}-{i}");
    assert!((rd - (vb - i)).abs() <= tol * scale, "B-A {rd} vs {vb}-{i}");
    r
}

#[test]
fn overlapping_cubes_exact_volumes() {
    let a = Mesh::unit_cube();
    let b = Mesh::cuboid([0.5, 0.25, -0.5], [1.5, 0.75, 0.5]);
    let [u, i, d, rd] = check(&a, &b, 0.0);
    assert_eq!(i, 0.5 * 0.5 * 0.5);
    assert_eq!(u, 1.0 + 0.5 - 0.125);
    assert_eq!(d, 1.0 - 0.125);
    assert_eq!(rd, 0.5 - 0.125);
}

#[test]
fn cubes_with_coplanar_faces_exact_volumes() {
    let a = Mesh::unit_cube();
    // Shares the planes y = 0, y = 1, z = 0, z = 1 with a.
    let b = Mesh::cuboid([0.5, 0.0, 0.0], [1.5, 1.0, 1.0]);
    let [u, i, d, rd] = check(&a, &b, 0.0);
    assert_eq!((u, i, d, rd), (1.5, 0.5, 0.5, 0.5));
    // A corner overlap sharing three planes.
    let c = Mesh::cuboid([0.5, 0.5, 0.5], [1.0, 1.0, 1.0]);
    let [u, i, d, rd] = check(&a, &c, 0.0);
    assert_eq!((u, i, d, rd), (1.0, 0.125, 0.875, 0.0));
}

/// The area of the intersection of two convex polygons (counter-clockwise), by clipping
/// one to each edge of the other: an independent reference for the prisms' volumes.
fn convex_overlap_area(p: &[[f64; 2]], q: &[[f64; 2]]) -> f64 {
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut poly = p.to_vec();
    for k in 0..q.len() {
        let (e0, e1) = (q[k], q[(k + 1) % q.len()]);
        let mut out = Vec::new();
        for i in 0..poly.len() {
            let (s, t) = (poly[i], poly[(i + 1) % poly.len()]);
            let (ds, dt) = (cross(e0, e1, s), cross(e0, e1, t));
            if ds >= 0.0 {
                out.push(s);
            }
            if (ds >= 0.0) != (dt >= 0.0) {
                let u = ds / (ds - dt);
                out.push([s[0] + u * (t[0] - s[0]), s[1] + u * (t[1] - s[1])]);
            }
        }
        poly = out;
    }
    (0..poly.len())
        .map(|i| cross([0.0, 0.0], poly[i], poly[(i + 1) % poly.len()]))
        .sum::<f64>()
        / 2.0
}

#[test]
fn fanned_caps_in_one_plane_cut_each_other_only_along_their_boundaries() {
    // Two ellipses of 96 sides, one turned by 0.3 radians, extruded between the same two
    // planes: each cap's fan crosses the other's in thousands of points, but inside the
    // overlap both caps are flat, so the seam is the caps' outlines and the walls.
    let ellipse = |n: usize, turn: f64| -> Vec<[f64; 2]> {
        (0..n)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / n as f64;
                let (x, y) = (2.0 * t.cos(), t.sin());
                [x * turn.cos() - y * turn.sin(), x * turn.sin() + y * turn.cos()]
            })
            .collect()
    };
    let (p, q) = (ellipse(96, 0.0), ellipse(96, 0.3));
    let (a, b) = (fanned_prism(&p, 1.0), fanned_prism(&q, 1.0));
    let seam = crate::intersect::intersect(&a, &b);
    // The outlines cross the other cap's fan edges: a few points per fan triangle.
    assert!(seam.points.len() <= 8 * 96, "{} seam points", seam.points.len());
    let [_, i, _, _] = check(&a, &b, 1e-12);
    let area = convex_overlap_area(&p, &q);
    assert!((i - area).abs() <= 1e-12 * area, "{i} vs {area}");
    let r = boolean(&a, &b, Op::Union);
    assert_closed(&r.mesh, "union");
    // Asked for, the common refinement: every fan edge of one cap cuts the other's fan
    // triangles.
    let refined = crate::intersect::intersect_coplanar(&a, &b, true);
    assert!(refined.points.len() > 4 * seam.points.len(), "{} refined seam points", refined.points.len());
    // Every seam point kept (no clean-up) to see them: the same solid, held by many
    // more triangles.
    let kept = |coplanar_refinement| PipelineOptions {
        coplanar_refinement,
        cleanup: false,
        ..Default::default()
    };
    let fine = super::boolean(&a, &b, Op::Intersection, &kept(true));
    let lean = super::boolean(&a, &b, Op::Intersection, &kept(false));
    for r in [&fine, &lean] {
        assert_closed(&r.mesh, "intersection, seam points kept");
        assert!((vol(&r.mesh) - area).abs() <= 1e-12 * area);
    }
    let (n, m) = (fine.mesh.triangles.len(), lean.mesh.triangles.len());
    assert!(n > 4 * m, "{n} vs {m} triangles");
}

#[test]
fn identical_meshes() {
    for m in [Mesh::unit_cube(), uv_sphere([0.0; 3], 1.0, 24, 12)] {
        let v = vol(&m);
        assert_eq!(vol(&boolean(&m, &m, Op::Union).mesh), v);
        assert_eq!(vol(&boolean(&m, &m, Op::Intersection).mesh), v);
        assert!(boolean(&m, &m, Op::Difference).mesh.triangles.is_empty());
        assert_eq!(
            boolean(&m, &m, Op::Union).mesh.triangles.len(),
            m.triangles.len()
        );
    }
}

#[test]
fn touching_cubes() {
    let a = Mesh::unit_cube();
    // Face to face.
    let b = Mesh::cuboid([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]);
    let [u, i, d, rd] = check(&a, &b, 0.0);
    assert_eq!((u, i, d, rd), (2.0, 0.0, 1.0, 1.0));
    // Union of face-to-face cubes: the shared face disappears, a 2x1x1 box remains.
    let un = boolean(&a, &b, Op::Union).mesh;
    assert_eq!(mesh_stats(&un).area, 10.0);
    // Edge to edge: the two solids share an edge with four faces (a non-manifold edge when
    // kept, split into two manifold sheets by default); vertex to vertex: manifold edges,
    // the vertex split by default. No boundary either way.
    for (b, non_manifold) in [
        (Mesh::cuboid([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]), 1),
        (Mesh::cuboid([1.0; 3], [2.0; 3]), 0),
    ] {
        let keep = PipelineOptions {
            keep_nonmanifold: true,
            ..PipelineOptions::default()
        };
        for (un, non_manifold) in [
            (super::boolean(&a, &b, Op::Union, &keep).mesh, non_manifold),
            (boolean(&a, &b, Op::Union).mesh, 0),
        ] {
            let s = mesh_stats(&un);
            assert_eq!(
                (
                    s.triangles,
                    s.boundary_edges,
                    s.non_manifold_edges,
                    s.inconsistent_edges
                ),
                (24, 0, non_manifold, 0)
            );
            assert_eq!(s.volume, 2.0);
        }
        assert!(boolean(&a, &b, Op::Intersection).mesh.triangles.is_empty());
        assert_eq!(vol(&boolean(&a, &b, Op::Difference).mesh), 1.0);
    }
}

#[test]
fn sphere_strictly_inside_cube() {
    let cube = Mesh::cuboid([-2.0; 3], [2.0; 3]);
    let s = uv_sphere([0.1, 0.2, 0.3], 1.0, 32, 16);
    let [u, i, d, rd] = check(&cube, &s, 1e-12);
    assert_eq!(i, vol(&s));
    assert_eq!(u, 64.0);
    assert!((d - (64.0 - vol(&s))).abs() < 1e-12);
    assert_eq!(rd, 0.0);
    let cavity = boolean(&cube, &s, Op::Difference).mesh;
    assert_eq!(mesh_stats(&cavity).components, 2);
}

#[test]
fn disjoint_meshes() {
    let a = Mesh::unit_cube();
    let b = uv_sphere([5.0; 3], 1.0, 16, 8);
    let [u, i, d, rd] = check(&a, &b, 1e-12);
    assert_eq!(i, 0.0);
    assert_eq!(d, 1.0);
    assert_eq!(rd, vol(&b));
    assert!((u - 1.0 - vol(&b)).abs() < 1e-12);
}

#[test]
fn volume_identities_over_random_rigid_motions() {
    let mut rng = Rng(0xdead_beef_1234_5678);
    let mut unit = || rng.unit();
    let shapes = [
        uv_sphere([0.0; 3], 1.0, 24, 12),
        torus([0.0; 3], 1.0, 0.35, 24, 12),
        Mesh::cuboid([-0.7; 3], [0.7; 3]),
    ];
    for k in 0..18 {
        let a = &shapes[k % 3];
        let b = &shapes[(k / 3) % 3];
        let axis = [unit() - 0.5, unit() - 0.5, unit() - 0.5];
        let shift = [unit() - 0.5, unit() - 0.5, unit() - 0.5];
        check(a, &rigid_motion(b, axis, 6.0 * unit(), shift), 1e-9);
    }
}

#[test]
fn near_degenerate_copies() {
    let a = uv_sphere([0.0; 3], 1.0, 24, 12);
    check(
        &a,
        &rigid_motion(&a, [0.3, 0.5, 0.8], 0.2, [1e-9, 0.0, 0.0]),
        1e-9,
    );
    check(
        &a,
        &rigid_motion(&a, [0.0, 0.0, 1.0], 1e-12, [0.0; 3]),
        1e-9,
    );
    let cube = Mesh::unit_cube();
    check(
        &cube,
        &rigid_motion(&cube, [1.0, 1.0, 1.0], 1e-12, [0.0; 3]),
        1e-9,
    );
}

#[test]
fn utm_offset_cubes_exact() {
    let o = [478_614.0, 6_772_313.0, 350.0];
    let a = Mesh::cuboid(o, [o[0] + 10.0, o[1] + 10.0, o[2] + 10.0]);
    let b = Mesh::cuboid(
        [o[0] + 5.0, o[1], o[2] + 2.5],
        [o[0] + 15.0, o[1] + 10.0, o[2] + 7.5],
    );
    let [u, i, d, rd] = check(&a, &b, 1e-12);
    assert_eq!(i, 250.0);
    assert_eq!(u, 1000.0 + 500.0 - 250.0);
    assert_eq!((d, rd), (750.0, 250.0));
}

#[test]
fn provenance_names_sources() {
    let a = Mesh::unit_cube();
    let b = Mesh::cuboid([0.5, 0.25, -0.5], [1.5, 0.75, 0.5]);
    let r = boolean(&a, &b, Op::Difference);
    assert_eq!(r.provenance.len(), r.mesh.triangles.len());
    assert!(r
        .provenance
        .iter()
        .any(|p| p.source == Source::A && !p.flipped));
    assert!(r
        .provenance
        .iter()
        .all(|p| (p.source == Source::B) == p.flipped));
    assert!(r.provenance.iter().all(|p| p.triangle < 12));
}

use crate::test_util::{bowl, terrain_and_drill, UTM};

/// Every seam edge of the split terrain has an inside triangle on one side and an outside
/// triangle on the other; the groups' areas add up to the terrain's area.
fn check_open_split(terrain: &Mesh, tool: &Mesh) -> Split {
    let s = split(terrain, tool);
    assert!(s.a.failed.is_empty() && s.b.failed.is_empty());
    let topo = crate::edges::EdgeTopology::new(&s.a.mesh);
    let mut seam_edges = 0;
    for e in &s.a.seam_edges {
        let id = topo.edges.binary_search(e).unwrap();
        let classes: Vec<Class> = topo
            .uses_of(id)
            .iter()
            .map(|u| s.class_a.class[u.triangle as usize])
            .collect();
        assert_eq!(classes.len(), 2, "{e:?}");
        assert!(
            classes.contains(&Class::Inside) && classes.contains(&Class::Outside),
            "{e:?}: {classes:?}"
        );
        seam_edges += 1;
    }
    assert!(seam_edges > 0);
    let area_of = |c: Class| {
        let tris: Vec<[u32; 3]> = (0..s.a.mesh.triangles.len())
            .filter(|&t| s.class_a.class[t] == c)
            .map(|t| s.a.mesh.triangles[t])
            .collect();
        crate::measure::area(&Mesh::new_unchecked(s.a.mesh.positions.clone(), tris))
    };
    let (ai, ao) = (area_of(Class::Inside), area_of(Class::Outside));
    let total = crate::measure::area(terrain);
    assert!(ai > 0.0 && ao > 0.0);
    assert!(
        (ai + ao - total).abs() < 1e-9 * total,
        "{ai} + {ao} vs {total}"
    );
    s
}

#[test]
fn terrain_split_by_cylinder_and_cup() {
    for center in [[0.0; 3], UTM] {
        let t = format!("{center:?}");
        let (terrain, cyl) = terrain_and_drill(center);
        check_open_split(&terrain, &cyl);
        // Terrain minus the cylinder: a hole whose boundary is the seam loop, less the seam
        // points the clean-up removed (where the loop is straight); all of them kept
        // without it.
        let seam_len = crate::intersect::chain(&crate::intersect::intersect(&terrain, &cyl), true)
            [0]
        .points
        .len();
        for cleanup in [false, true] {
            let opts = PipelineOptions {
                cleanup,
                ..Default::default()
            };
            let r = super::boolean(&terrain, &cyl, Op::Difference, &opts);
            let holed: Vec<[u32; 3]> = r
                .provenance
                .iter()
                .zip(&r.mesh.triangles)
                .filter(|(p, _)| p.source == Source::A)
                .map(|(_, t)| *t)
                .collect();
            let holed = Mesh::new_unchecked(r.mesh.positions.clone(), holed);
            let st = mesh_stats(&holed);
            let gone = r.cleanup.removed_points + r.cleanup.zero_length_edges;
            assert_eq!(st.boundary_edges, 240 + seam_len - gone, "{t}");
            assert_eq!(gone > 0, cleanup, "{t}: {:?}", r.cleanup);
        }
        check_open_split(&terrain, &bowl(center));
    }
}

#[test]
fn crossing_terrains_split_along_the_open_curve() {
    use crate::shapes::heightfield;
    let a = heightfield([0.0, 0.0], [10.0, 10.0], 23, 19, |x, y| {
        0.5 * (x * 0.7).sin() + 0.3 * (y * 0.9).cos()
    });
    let b = heightfield([-1.0, -1.0], [11.0, 11.0], 17, 29, |x, y| {
        0.08 * (x - 5.0) + 0.05 * (y - 5.0) + 0.1
    });
    let s = check_open_split(&a, &b);
    // And the other way round: b split by a.
    let topo = crate::edges::EdgeTopology::new(&s.b.mesh);
    for e in &s.b.seam_edges {
        let id = topo.edges.binary_search(e).unwrap();
        let classes: Vec<Class> = topo
            .uses_of(id)
            .iter()
            .map(|u| s.class_b.class[u.triangle as usize])
            .collect();
        assert!(
            classes.contains(&Class::Inside) && classes.contains(&Class::Outside),
            "{classes:?}"
        );
    }
    // Below a (behind its up-facing normals) is "inside": b's far-below corner is inside.
    let low = heightfield([-1.0, -1.0], [11.0, 11.0], 3, 3, |_, _| -50.0);
    let seam = crate::intersect::intersect(&a, &low);
    assert!(seam.segments.is_empty());
    let cls = split(&low, &a).class_a;
    assert!(cls.class.iter().all(|&c| c == Class::Inside));
}

#[test]
fn split_groups_pick_back_into_the_booleans() {
    let a = uv_sphere([0.0; 3], 1.0, 24, 12);
    let b = rigid_motion(
        &torus([0.0; 3], 1.0, 0.35, 24, 12),
        [1.0, 0.2, 0.1],
        0.7,
        [0.3, 0.1, 0.0],
    );
    let s = split(&a, &b);
    let g = |x: Group| s.group(x).0;
    let (a_out, b_out, a_in, b_in) = (
        g(Group::AOutB),
        g(Group::BOutA),
        g(Group::AInB),
        g(Group::BInA),
    );
    // Groups partition each arranged mesh.
    let n = |m: &Mesh| m.triangles.len();
    assert_eq!(
        n(&a_out) + n(&a_in) + n(&g(Group::AOnBSame)) + n(&g(Group::AOnBOpposite)),
        s.a.mesh.triangles.len()
    );
    let union = pick(&[(&a_out, false), (&b_out, false)]).unwrap();
    assert_closed(&union, "picked union");
    assert!((vol(&union) - vol(&boolean(&a, &b, Op::Union).mesh)).abs() < 1e-12);
    let diff = pick(&[(&a_out, false), (&b_in, true)]).unwrap();
    assert_closed(&diff, "picked difference");
    assert!((vol(&diff) - vol(&boolean(&a, &b, Op::Difference).mesh)).abs() < 1e-12);
    let inter = pick(&[(&a_in, false), (&b_in, false)]).unwrap();
    assert!((vol(&inter) + vol(&union) - vol(&a) - vol(&b)).abs() < 1e-9);
    assert_eq!("b_in_a".parse::<Group>().unwrap(), Group::BInA);
}

#[test]
fn progress_reports_every_stage_in_order() {
    let a = Mesh::unit_cube();
    let b = Mesh::cuboid([0.5; 3], [1.5; 3]);
    let seen = std::sync::Mutex::new(Vec::new());
    let progress = |s| seen.lock().unwrap().push(s);
    let opts = PipelineOptions {
        progress: Some(&progress),
        ..PipelineOptions::default()
    };
    let r = super::boolean(&a, &b, Op::Union, &opts);
    assert_eq!(
        *seen.lock().unwrap(),
        vec![
            Stage::Intersect,
            Stage::Arrange,
            Stage::Classify,
            Stage::Merge
        ]
    );
    assert_eq!(crate::measure::signed_volume(&r.mesh), 2.0 - 0.125);
}

/// A flat 10 x 10 grid at z = 0, and a vertical square in the plane y = 0.3 (facing +y),
/// |x| <= 1, |z| <= 1, whose seam on the grid stops inside the grid's single patch.
fn grid_and_square() -> (Mesh, Mesh) {
    let grid = crate::shapes::heightfield([-5.0, -5.0], [5.0, 5.0], 20, 20, |_, _| 0.0);
    let square = Mesh::new_unchecked(
        vec![
            [-1.0, 0.3, -1.0],
            [1.0, 0.3, -1.0],
            [1.0, 0.3, 1.0],
            [-1.0, 0.3, 1.0],
        ],
        // Facing +y: (2 - 0) x (1 - 0) = (2, 0, 2) x (2, 0, 0) has y = 4 > 0.
        vec![[0, 2, 1], [0, 3, 2]],
    );
    (grid, square)
}

#[test]
fn seam_stopping_inside_a_patch_is_classified_by_winding_number() {
    // A: a flat 10 x 10 grid at z = 0. B: a vertical square in the plane y = 0.3 (facing
    // +y), |x| <= 1, |z| <= 1: its seam on A is the segment from x = -1 to 1, which
    // stops inside A's single patch. For a flat B the winding number's sign is the side
    // of its plane, so every triangle of A is behind B (inside) exactly when y < 0.3 —
    // also far beyond the ends of the seam.
    let (a, b) = grid_and_square();
    let s = split(&a, &b);
    assert_eq!(s.class_a.patches, 1);
    assert_eq!(s.class_a.by_winding, 1);
    let mut counts = [0usize; 2];
    for (t, &c) in s.class_a.class.iter().enumerate() {
        let [p, q, r] = s.a.mesh.corners(t);
        let y = (p[1] + q[1] + r[1]) / 3.0;
        let want = if y < 0.3 {
            Class::Inside
        } else {
            Class::Outside
        };
        assert_eq!(c, want, "triangle {t} at y = {y}");
        counts[usize::from(c == Class::Inside)] += 1;
    }
    assert!(counts[0] > 100 && counts[1] > 100, "{counts:?}");
}

/// Output triangles whose rounded coordinates do not face like their input triangle (in
/// its projection), recomputed from the provenance alone.
fn count_rounding_flips(r: &BooleanResult, a: &Mesh, b: &Mesh) -> usize {
    use crate::kernel::{orient2d, Point};
    r.mesh
        .triangles
        .iter()
        .zip(&r.provenance)
        .filter(|(t, p)| {
            let src = if p.source == Source::A { a } else { b };
            let k = p.triangle as usize;
            let parent =
                crate::intersect::tritri::Tri::new(p.triangle, src.triangles[k], src.corners(k))
                    .expect("non-degenerate parent");
            let mut q = t.map(|v| Point::Explicit(r.mesh.positions[v as usize]));
            if p.flipped {
                q.swap(1, 2);
            }
            orient2d(&q[0], &q[1], &q[2], parent.axis()) != parent.sign()
        })
        .count()
}

#[test]
fn rounding_flips_are_counted_exactly() {
    // A copy turned by 1e-12 rad: the seam runs everywhere at a grazing angle and a
    // piece or two are thinner than f64 rounding of their seam points (measured: 2 in the
    // union, 0 in the intersection, with the seam points' coordinates within an ulp or so
    // of the exact points; their plain f64 evaluation, up to 5e-4 off here, gave 1 and 1).
    let a = uv_sphere([0.0; 3], 1.0, 64, 32);
    let b = rigid_motion(&a, [0.3, 0.5, 1.0], 1e-12, [0.0; 3]);
    for (op, flips) in [(Op::Union, 2), (Op::Intersection, 0)] {
        let r = boolean(&a, &b, op);
        assert_eq!(r.rounding_flips, flips, "{op:?}");
        assert_eq!(count_rounding_flips(&r, &a, &b), flips, "{op:?}");
    }
    // A generic crossing: none.
    let c = rigid_motion(&a, [0.0, 0.0, 1.0], 0.1, [0.5, 0.0, 0.0]);
    let r = boolean(&a, &c, Op::Union);
    assert_eq!((r.rounding_flips, count_rounding_flips(&r, &a, &c)), (0, 0));
}

#[test]
fn large_spheres_take_the_large_input_paths() {
    // Above the size where candidate pairs come from the grid broad phase, and many
    // merge pieces: the same closedness and volume identities; the intersection lies
    // between the two-sphere lens volume and each sphere.
    let a = uv_sphere([0.0; 3], 1.0, 300, 200);
    let b = rigid_motion(&a, [0.0, 0.0, 1.0], 0.1, [0.5, 0.0, 0.0]);
    assert!(a.triangles.len() + b.triangles.len() >= 200_000);
    let [u, i, _, _] = check(&a, &b, 1e-9);
    // Exact lens of two unit balls 0.5 apart: π (4 + d)(2 − d)² / 12.
    let lens = std::f64::consts::PI * 4.5 * 1.5 * 1.5 / 12.0;
    assert!((i - lens).abs() < 2e-3 * lens, "{i} vs {lens}");
    assert!(u > vol(&a) && i < vol(&a));
    let r = boolean(&a, &b, Op::Union);
    let s = split(&a, &b);
    assert!(r.seam_points > 1000 && s.a.mesh.triangles.len() > a.triangles.len());
}

#[test]
fn forced_paths_below_their_crossovers_give_the_same_results() {
    // The grid broad phase and the hierarchical winding numbers, forced on small inputs
    // (PipelineOptions' crossovers at 0), answer as the trees and the exact sums do.
    let sphere = uv_sphere([0.0; 3], 1.0, 24, 12);
    let moved = rigid_motion(&sphere, [0.3, 0.2, 1.0], 0.4, [0.6, 0.1, 0.0]);
    let mut inner = Mesh::cuboid([-0.2; 3], [0.2; 3]);
    inner
        .append(&rigid_motion(
            &sphere,
            [0.0, 0.0, 1.0],
            0.0,
            [1.5, 0.0, 0.0],
        ))
        .unwrap();
    let grid = crate::shapes::heightfield([-2.0, -2.0], [2.0, 2.0], 12, 12, |x, y| 0.1 * x * y);
    // A box below the grid, apart from everything: a piece without a seam.
    let mut moved_and_box = moved.clone();
    moved_and_box
        .append(&Mesh::cuboid([1.0, 1.0, -1.5], [1.4, 1.4, -1.1]))
        .unwrap();
    let forced = PipelineOptions {
        grid_from: 0,
        exact_winding_up_to: 0.0,
        ..PipelineOptions::default()
    };
    let mut by_winding = 0;
    let pairs = [
        (&sphere, &moved),
        (&sphere, &inner),
        (&grid, &moved_and_box),
        (&moved_and_box, &grid),
    ];
    for (a, b) in pairs {
        let (s, f) = (split(a, b), super::split(a, b, &forced));
        assert!(f.seam.from_grid && !s.seam.from_grid);
        assert_eq!(s.seam.points, f.seam.points);
        assert_eq!(s.seam.segments, f.seam.segments);
        assert_eq!(s.class_a.class, f.class_a.class);
        assert_eq!(s.class_b.class, f.class_b.class);
        for (cs, cf) in [(&s.class_a, &f.class_a), (&s.class_b, &f.class_b)] {
            assert!(!cs.approximate_winding);
            assert_eq!(cf.approximate_winding, cf.by_winding > 0);
            by_winding += cf.by_winding;
        }
        for op in Op::ALL {
            assert_eq!(
                boolean(a, b, op).mesh,
                super::boolean(a, b, op, &forced).mesh
            );
        }
    }
    assert!(by_winding >= 3, "{by_winding}");
}

/// Two open terrains, the second rotated and larger than the first: most of the second
/// lies outside the first's footprint, where the first's winding number is within
/// hundredths of 0 and the hierarchy's own error decides some sides wrongly. Its sides
/// are certified ([`crate::classify::FastWinding::sided_many`]): the classes and the
/// results are those of exact sums. So for two flat sheets in one plane, where the
/// winding numbers beside them are ties.
#[test]
fn terrains_classified_by_the_hierarchy_as_by_exact_sums() {
    use crate::shapes::heightfield;
    let a = heightfield([0.0, 0.0], [10.0, 10.0], 70, 70, |x, y| {
        0.6 * (0.9 * x).sin() * (0.7 * y).cos() + 0.25 * (2.3 * x + 1.1 * y + 0.4).sin()
    });
    let flat = heightfield([-7.5, -7.5], [7.5, 7.5], 45, 45, |_, _| 0.0);
    let mut b = rigid_motion(&flat, [0.0, 0.0, 1.0], 0.3, [5.0, 5.0, 0.0]);
    for p in &mut b.positions {
        let [x, y, _] = *p;
        p[2] = 0.22 * (x - 5.0)
            + 0.1 * (y - 5.0)
            + 0.35 * (1.3 * y + 0.2).cos() * (0.5 * x + 0.3).sin();
    }
    let fast = PipelineOptions {
        exact_winding_up_to: 0.0,
        ..PipelineOptions::default()
    };
    let exact = PipelineOptions {
        exact_winding_up_to: f64::INFINITY,
        ..PipelineOptions::default()
    };
    // Two flat sheets in one plane, the second turned: beside each other the winding
    // numbers are 0 term by term, ties that must stay on the threshold.
    let sheet = heightfield([0.0, 0.0], [10.0, 10.0], 40, 40, |_, _| 0.0);
    let turned = rigid_motion(
        &heightfield([0.0, 0.0], [10.0, 10.0], 32, 32, |_, _| 0.0),
        [0.0, 0.0, 1.0],
        0.3,
        [5.0, -3.0, 0.0],
    );
    for (x, y) in [(&a, &b), (&b, &a), (&sheet, &turned)] {
        let (f, e) = (super::split(x, y, &fast), super::split(x, y, &exact));
        for (cf, ce) in [(&f.class_a, &e.class_a), (&f.class_b, &e.class_b)] {
            assert!(!ce.approximate_winding);
            assert_eq!(cf.approximate_winding, cf.by_winding > 0);
            let differ = cf
                .class
                .iter()
                .zip(&ce.class)
                .filter(|(a, b)| a != b)
                .count();
            assert_eq!(differ, 0, "{differ} classes of {}", ce.class.len());
        }
        assert!(f.class_a.by_winding + f.class_b.by_winding > 0);
        for op in Op::ALL {
            assert_eq!(
                super::boolean(x, y, op, &fast).mesh,
                super::boolean(x, y, op, &exact).mesh
            );
        }
    }
}

/// Large meshes take the paths that run side by side (edge structure by vertex ranges and
/// a shared union-find, the reassembly in spans, the merge's parallel fills): the result,
/// its provenance and its seam are the same on any number of threads.
#[test]
fn large_booleans_are_the_same_on_any_number_of_threads() {
    let a = uv_sphere([0.0; 3], 1.0, 240, 150);
    let b = rigid_motion(&a, [1.0, 2.0, 3.0], 0.7, [0.3, 0.1, 0.05]);
    assert!(a.triangles.len() > 1 << 16);
    let on = |threads: usize, op: Op| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| boolean(&a, &b, op))
    };
    for op in [Op::Union, Op::Difference] {
        let one = on(1, op);
        assert!(one.seam_points > 500, "{}", one.seam_points);
        assert_closed(&one.mesh, "one thread");
        for threads in [3, 8] {
            let many = on(threads, op);
            assert_eq!(many.mesh.triangles, one.mesh.triangles, "{op:?} {threads}");
            let bits = |m: &Mesh| -> Vec<[u64; 3]> {
                m.positions.iter().map(|p| p.map(f64::to_bits)).collect()
            };
            assert_eq!(bits(&many.mesh), bits(&one.mesh), "{op:?} {threads}");
            assert_eq!(many.provenance, one.provenance, "{op:?} {threads}");
            assert_eq!(many.seam_vertices, one.seam_vertices, "{op:?} {threads}");
            assert_eq!(many.rounding_flips, one.rounding_flips, "{op:?} {threads}");
        }
    }
}

/// Against a closed mesh a patch's first deciding seam vote is the answer of all its votes
/// where the operands are valid: the classes of both meshes, and the patches left to
/// winding numbers, are those of every vote asked, for solids crossing, sharing faces,
/// touching along an edge, identical, and open surfaces against solids (whose own
/// classification, against an open mesh, asks every vote either way, as where an open
/// surface's seam stops inside a patch); on any number of threads for a large pair.
#[test]
fn first_deciding_votes_classify_as_every_vote() {
    let cube = Mesh::unit_cube();
    let sphere = uv_sphere([0.0; 3], 1.0, 24, 12);
    let moved = rigid_motion(&sphere, [1.0, 2.0, 3.0], 0.7, [0.3, 0.1, 0.05]);
    let grid = crate::shapes::heightfield([-2.0, -2.0], [2.0, 2.0], 12, 12, |x, y| 0.1 * x * y);
    // An open square whose seam stops inside the flat grid's patch (votes disagree there).
    let (flat, square) = grid_and_square();
    let large = uv_sphere([0.0; 3], 1.0, 240, 150);
    let large_moved = rigid_motion(&large, [1.0, 2.0, 3.0], 0.7, [0.3, 0.1, 0.05]);
    let pairs = [
        (&sphere, &moved, 1),
        (&cube, &Mesh::cuboid([0.5, 0.0, 0.0], [1.5, 1.0, 1.0]), 1),
        (&cube, &Mesh::cuboid([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]), 1),
        (&cube, &cube, 1),
        (&sphere, &sphere, 1),
        (&grid, &moved, 1),
        (&moved, &grid, 1),
        (&flat, &square, 1),
        (&large, &large_moved, 3),
    ];
    let on = |threads: usize, a: &Mesh, b: &Mesh, opts: &PipelineOptions| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| super::split(a, b, opts))
    };
    let (mut coplanar, mut by_winding) = (0, 0);
    for (k, (a, b, threads)) in pairs.into_iter().enumerate() {
        let all = on(1, a, b, &PipelineOptions::default());
        for threads in [1, threads] {
            let first = on(threads, a, b, &first_votes());
            for (f, e) in [
                (&first.class_a, &all.class_a),
                (&first.class_b, &all.class_b),
            ] {
                assert_eq!(f.class, e.class, "pair {k} on {threads} threads");
                assert_eq!(f.by_winding, e.by_winding, "pair {k} on {threads} threads");
            }
        }
        by_winding += all.class_a.by_winding + all.class_b.by_winding;
        coplanar += [&all.class_a, &all.class_b]
            .iter()
            .flat_map(|c| &c.class)
            .filter(|&&c| matches!(c, Class::CoplanarSame | Class::CoplanarOpposite))
            .count();
    }
    assert!(coplanar > 300, "{coplanar}");
    assert!(by_winding > 0, "{by_winding}");
}

/// Where the other mesh is closed but its parts cross (an operand taken as given), a
/// patch's votes can disagree: all votes ask winding numbers there, the first deciding
/// one answers alone. Two overlapping boxes given as one mesh, `[0, 2]^3` and `[1, 3]^3`,
/// and a box whose bottom face at `z = 1.5` crosses both: the L-shaped piece of that face
/// inside the first box only is bounded by the first box's seam (inside there) and the
/// second's (outside there). A boolean on such an operand, forced through its checks,
/// asks every vote.
#[test]
fn crossing_parts_of_a_closed_mesh_make_votes_disagree() {
    let mut boxes = Mesh::cuboid([0.0; 3], [2.0; 3]);
    boxes.append(&Mesh::cuboid([1.0; 3], [3.0; 3])).unwrap();
    let tool = Mesh::cuboid([0.5, 0.5, 1.5], [2.5, 2.5, 4.0]);
    let all = split(&tool, &boxes);
    let first = super::split(&tool, &boxes, &first_votes());
    assert!(all.class_a.by_winding > 0, "{}", all.class_a.by_winding);
    assert_eq!(first.class_a.by_winding, 0);
    assert_ne!(first.class_a.class, all.class_a.class);
    let forced = crate::ops::BooleanOptions {
        checks: crate::ops::Checks {
            resolve: false,
            force: true,
            ..crate::ops::Checks::default()
        },
        ..crate::ops::BooleanOptions::default()
    };
    for op in Op::ALL {
        let out = crate::ops::boolean(&tool, &boxes, op, &forced).unwrap();
        assert!(out.operands[1].forced);
        assert_eq!(out.mesh, boolean(&tool, &boxes, op).mesh, "{op:?}");
        let by_first = super::boolean(&tool, &boxes, op, &first_votes()).mesh;
        assert_ne!(out.mesh, by_first, "{op:?}");
    }
}
