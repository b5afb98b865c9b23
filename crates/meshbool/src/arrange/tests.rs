use super::*;
use crate::edges::{EdgeKind, EdgeTopology};
use crate::intersect::intersect;
use crate::measure::{area, mesh_stats, signed_volume};
use crate::shapes::rigid_motion;
use crate::shapes::uv_sphere;
use crate::test_util::Rng;
use rustc_hash::FxHashSet;

fn edges_of(m: &Mesh) -> FxHashSet<[u32; 2]> {
    let topo = EdgeTopology::new(m);
    topo.edges.iter().copied().collect()
}

/// Both arranged meshes: closed inputs stay closed and manifold, area and volume are
/// preserved, and every seam segment is an edge of each.
fn check_closed_pair(a: &Mesh, b: &Mesh) {
    let seam = intersect(a, b);
    for (m, side) in [(a, Source::A), (b, Source::B)] {
        let arr = arrange(m, &seam, side);
        assert!(arr.failed.is_empty(), "{:?}", arr.failed);
        let s = mesh_stats(&arr.mesh);
        assert_eq!(
            (s.boundary_edges, s.non_manifold_edges, s.inconsistent_edges),
            (0, 0, 0),
            "{side:?}"
        );
        assert!(
            (area(&arr.mesh) - area(m)).abs() < 1e-9 * area(m),
            "{side:?}"
        );
        assert!(
            (signed_volume(&arr.mesh) - signed_volume(m)).abs() < 1e-9 * signed_volume(m).abs(),
            "{side:?}"
        );
        let edges = edges_of(&arr.mesh);
        for e in &arr.seam_edges {
            assert!(edges.contains(e), "{side:?}: seam edge {e:?} missing");
        }
        assert_eq!(arr.parent.len(), arr.mesh.triangles.len());
        // The seam's candidate triangles stand in for a pass over all triangles.
        let unknown = Seam {
            near: None,
            ..seam.clone()
        };
        let full = arrange(m, &unknown, side);
        assert_eq!(arr.mesh.triangles, full.mesh.triangles, "{side:?}");
        assert_eq!(arr.parent, full.parent, "{side:?}");
    }
}

/// Points on the outer edges (exact binary coordinates on a tilted plane), inserted in
/// many orders, some constrained: the first point on each edge, placed without a walk,
/// gives the triangulation the walk gives.
/// A triangulation reset for the next triangle ([`local::Local::reset`], as the
/// arrangement reuses one per task) is the one made fresh: one `Local` taken through 120
/// triangles in two planes, each with a random set of points, some on its edges, and
/// constraints among them, every time with the triangles a new one makes.
#[test]
fn a_reset_triangulation_is_a_fresh_one() {
    let planes: [fn(f64, f64) -> [f64; 3]; 2] = [
        |x, y| [x, y, 0.5 * x + 2.0 * y],
        |x, y| [0.25 * x - y, x + 0.5 * y, 3.0 - x],
    ];
    let points = [
        (1.0, 0.0, Some(0)),
        (6.0, 0.0, Some(0)),
        (5.0, 3.0, Some(1)),
        (0.0, 2.0, Some(2)),
        (1.0, 1.0, None),
        (2.0, 3.0, None),
        (4.0, 2.0, None),
        (1.5, 5.0, None),
    ];
    let mut rng = Rng(0x0dd_ba11_5eed);
    let mut reused: Option<local::Local> = None;
    for round in 0..120 {
        let plane = planes[round % 2];
        let scale = 1.0 + (round % 3) as f64;
        let at = |x: f64, y: f64| plane(scale * x, scale * y);
        let corners = [at(0.0, 0.0), at(8.0, 0.0), at(0.0, 8.0)];
        let shape = Triangle::new(corners).unwrap();
        let chosen: Vec<usize> = (0..points.len()).filter(|_| rng.next() % 3 != 0).collect();
        let run = |lt: &mut local::Local| {
            let ids: Vec<u32> = chosen
                .iter()
                .map(|&k| {
                    let (x, y, on) = points[k];
                    let p = at(x, y);
                    lt.insert(Prepared::new(Point::Explicit(p)), p, on).unwrap()
                })
                .collect();
            for w in ids.windows(2).step_by(2) {
                let (p, q) = (w[0], w[1]);
                // Only constraints that cross no earlier one: between consecutive
                // interior points (their segments lie apart).
                if chosen[ids.iter().position(|&i| i == p).unwrap()] >= 4 {
                    let _ = lt.constrain(p, q);
                }
            }
            lt.improve();
            lt.tris.clone()
        };
        let (axis, sign) = (shape.axis(), shape.sign());
        let mut fresh = local::Local::new(corners, axis, sign, chosen.len());
        let lt = match &mut reused {
            Some(lt) => {
                lt.reset(corners, axis, sign, chosen.len());
                lt
            }
            None => reused.insert(local::Local::new(corners, axis, sign, chosen.len())),
        };
        assert_eq!(run(lt), run(&mut fresh), "round {round}");
    }
}

/// The flips end where no edge wants one, in the same triangulation whatever order the
/// points came in: points of a lattice (cocircular fours everywhere) and off it, in a
/// tilted triangle (exact binary coordinates), each set in three orders.
#[test]
fn the_flips_end_where_no_edge_wants_one_whatever_the_order() {
    let at = |x: f64, y: f64| [x, y, 0.5 * x + 2.0 * y];
    let corners = [at(0.0, 0.0), at(16.0, 0.0), at(0.0, 16.0)];
    let shape = Triangle::new(corners).unwrap();
    let lattice: Vec<(f64, f64)> = (1..15)
        .flat_map(|x| (1..15 - x).map(move |y| (f64::from(x), f64::from(y))))
        .collect();
    let mut rng = Rng(0xf11b_5eed);
    let (mut flips, mut changed) = (0, 0);
    for round in 0..60 {
        let mut points: Vec<(f64, f64)> = lattice
            .iter()
            .copied()
            .filter(|_| rng.next() % 4 < 1 + round % 3)
            .collect();
        for _ in 0..round % 7 {
            // Off the lattice, inside the triangle: eighths, never on it.
            let (x, y) = (1 + rng.next() % 12, 1 + rng.next() % 12);
            let (x, y) = (x as f64 + 0.375, y.min(14 - x) as f64 + 0.125);
            if x + y < 15.5 && !points.contains(&(x, y)) {
                points.push((x, y));
            }
        }
        let triangulation = |order: &[usize]| {
            let mut lt = local::Local::new(corners, shape.axis(), shape.sign(), order.len());
            // Local vertex -> point (the corners: none).
            let mut of_local = vec![usize::MAX; 3];
            for &i in order {
                let (x, y) = points[i];
                let p = at(x, y);
                let l = lt
                    .insert(Prepared::new(Point::Explicit(p)), p, None)
                    .unwrap();
                assert_eq!(l as usize, of_local.len());
                of_local.push(i);
            }
            let before = lt.tris.clone();
            lt.improve();
            assert_eq!(lt.flips_left(), 0, "round {round}");
            let mut tris: Vec<[usize; 3]> = lt
                .tris
                .iter()
                .map(|t| {
                    let v = t.map(|l| match of_local[l as usize] {
                        usize::MAX => points.len() + l as usize,
                        i => i,
                    });
                    let k = (0..3).min_by_key(|&k| v[k]).unwrap();
                    [v[k], v[(k + 1) % 3], v[(k + 2) % 3]]
                })
                .collect();
            tris.sort_unstable();
            (tris, before != lt.tris)
        };
        let forward: Vec<usize> = (0..points.len()).collect();
        let mut shuffled = forward.clone();
        for i in (1..shuffled.len()).rev() {
            shuffled.swap(i, (rng.next() % (i as u64 + 1)) as usize);
        }
        let backward: Vec<usize> = forward.iter().rev().copied().collect();
        let (want, flipped) = triangulation(&forward);
        for order in [&shuffled, &backward] {
            assert_eq!(triangulation(order).0, want, "round {round}");
        }
        flips += usize::from(flipped);
        changed += usize::from(want.len() > 1);
    }
    // The flips had work to do in every round with points.
    assert_eq!(flips, changed);
}

#[test]
fn points_on_whole_edges_go_where_the_walk_takes_them() {
    let plane = |x: f64, y: f64| [x, y, 0.5 * x + 2.0 * y];
    let corners = [plane(0.0, 0.0), plane(8.0, 0.0), plane(0.0, 8.0)];
    // (x, y, outer edge): edge 0 from corner 0 to 1, 1 from 1 to 2, 2 from 2 to 0.
    let points = [
        (1.0, 0.0, Some(0)),
        (3.0, 0.0, Some(0)),
        (6.0, 0.0, Some(0)),
        (5.0, 3.0, Some(1)),
        (2.0, 6.0, Some(1)),
        (0.0, 2.0, Some(2)),
        (0.0, 7.0, Some(2)),
        (1.0, 1.0, None),
        (2.0, 3.0, None),
        (4.0, 2.0, None),
    ];
    let shape = Triangle::new(corners).unwrap();
    let mut rng = Rng(0x5eed_0fed_9e00);
    let mut fast_ones = 0;
    for round in 0..200 {
        let mut order: Vec<usize> = (0..points.len()).collect();
        for i in (1..order.len()).rev() {
            order.swap(i, (rng.next() % (i as u64 + 1)) as usize);
        }
        order.truncate(2 + round % (points.len() - 1));
        let run = |walk_only: bool| {
            let mut lt = local::Local::new(corners, shape.axis(), shape.sign(), order.len());
            if walk_only {
                lt.walk_only();
            }
            let ids: Vec<u32> = order
                .iter()
                .map(|&k| {
                    let (x, y, on) = points[k];
                    let p = plane(x, y);
                    lt.insert(Prepared::new(Point::Explicit(p)), p, on).unwrap()
                })
                .collect();
            // Two polylines across the triangle and three spurs (none cross), where both
            // ends are in.
            let local = |k: usize| order.iter().position(|&o| o == k).map(|i| ids[i]);
            for (k, l) in [
                (5, 7),
                (7, 8),
                (8, 4),
                (1, 9),
                (9, 3),
                (0, 7),
                (2, 3),
                (6, 4),
            ] {
                if let (Some(p), Some(q)) = (local(k), local(l)) {
                    lt.constrain(p, q).unwrap();
                }
            }
            lt.improve();
            lt.tris
        };
        let fast = run(false);
        assert_eq!(fast, run(true), "order {order:?}");
        fast_ones += usize::from(order.iter().any(|&k| points[k].2.is_some()));
    }
    assert!(fast_ones > 150);
}

#[test]
fn spheres_become_conforming_along_the_seam() {
    let a = uv_sphere([0.0; 3], 1.0, 32, 16);
    let b = uv_sphere([0.5, 0.1, 0.05], 0.8, 24, 12);
    check_closed_pair(&a, &b);
}

#[test]
fn aligned_spheres_with_coincident_rings() {
    // Same tessellation, shifted along x: ring vertices of one lie in the other's ring
    // planes, many edge-through-edge and vertex-on-face configurations.
    let a = uv_sphere([0.0; 3], 1.0, 32, 16);
    let b = uv_sphere([0.5, 0.0, 0.0], 1.0, 32, 16);
    check_closed_pair(&a, &b);
}

#[test]
fn cubes_with_coplanar_faces() {
    let a = Mesh::unit_cube();
    let b = Mesh::cuboid([0.5, 0.25, 0.0], [1.5, 0.75, 1.0]);
    check_closed_pair(&a, &b);
    let c = Mesh::cuboid([0.5, 0.5, 0.5], [1.5, 1.5, 1.5]);
    check_closed_pair(&a, &c);
}

#[test]
fn terrain_cut_by_cylinder_keeps_its_boundary() {
    use crate::test_util::{terrain_and_drill, wound_badly};
    // Badly wound as given: the arrangement keeps each triangle's winding.
    let (t, c) = terrain_and_drill([0.0; 3]);
    let t = wound_badly(&t);
    let seam = intersect(&t, &c);
    let arr = arrange(&t, &seam, Source::A);
    assert!(arr.failed.is_empty());
    let s = mesh_stats(&arr.mesh);
    assert_eq!((s.boundary_edges, s.non_manifold_edges), (240, 0));
    assert_eq!(s.inconsistent_edges, 15);
    assert!((s.area - area(&t)).abs() < 1e-9 * s.area);
    let edges = edges_of(&arr.mesh);
    assert!(arr.seam_edges.iter().all(|e| edges.contains(e)));
    let topo = EdgeTopology::new(&arr.mesh);
    for e in &arr.seam_edges {
        let id = topo.edges.binary_search(e).unwrap();
        assert_ne!(topo.kind(id), EdgeKind::Boundary);
    }
}

#[test]
fn random_rigid_motions_of_spheres_tori_and_cubes() {
    let mut rng = Rng(0x0123_4567_89ab_cdef);
    let mut unit = || rng.unit();
    let shapes = [
        uv_sphere([0.0; 3], 1.0, 24, 12),
        crate::shapes::torus([0.0; 3], 1.0, 0.35, 24, 12),
        Mesh::cuboid([-0.7; 3], [0.7; 3]),
    ];
    for i in 0..12 {
        let a = &shapes[i % 3];
        let b = &shapes[(i / 3) % 3];
        let axis = [unit() - 0.5, unit() - 0.5, unit() - 0.5];
        let shift = [unit() - 0.5, unit() - 0.5, unit() - 0.5];
        check_closed_pair(a, &rigid_motion(b, axis, 6.0 * unit(), shift));
    }
}

#[test]
fn near_identical_copies() {
    let a = uv_sphere([0.0; 3], 1.0, 24, 12);
    check_closed_pair(
        &a,
        &rigid_motion(&a, [0.3, 0.5, 0.8], 0.2, [1e-9, 0.0, 0.0]),
    );
    check_closed_pair(&a, &rigid_motion(&a, [0.0, 0.0, 1.0], 1e-12, [0.0; 3]));
    let cube = Mesh::unit_cube();
    check_closed_pair(
        &cube,
        &rigid_motion(&cube, [1.0, 1.0, 1.0], 1e-12, [0.0; 3]),
    );
}

#[test]
fn identical_meshes_need_no_cuts() {
    let a = uv_sphere([0.0; 3], 1.0, 24, 12);
    let seam = intersect(&a, &a);
    let arr = arrange(&a, &seam, Source::A);
    assert_eq!(arr.mesh.triangles, a.triangles);
    assert_eq!(arr.mesh.positions.len(), a.positions.len());
}

#[test]
fn utm_offset_pair() {
    let off = [478_614.7, 6_772_313.84, 350.0];
    let a = uv_sphere(off, 10.0, 24, 12);
    let b = rigid_motion(
        &uv_sphere([0.0; 3], 8.0, 20, 10),
        [0.2, 0.1, 1.0],
        0.3,
        [off[0] + 5.0, off[1] + 1.0, off[2]],
    );
    check_closed_pair(&a, &b);
}

/// A part given twice, its copies sharing no vertex (the self-seam names each common
/// corner by one copy's vertex): the arrangement gives each corner one vertex, so no
/// triangle fails and both copies' triangles meet at every edge, four to an edge.
#[test]
fn self_arrangement_of_a_part_given_twice() {
    let cube = rigid_motion(
        &Mesh::cuboid([0.0; 3], [1.0; 3]),
        [1.0, 2.0, 3.0],
        0.7,
        [0.5; 3],
    );
    for copy in [cube.clone(), cube.flipped()] {
        let mut twice = cube.clone();
        twice.append(&copy).unwrap();
        let seam =
            crate::intersect::self_seam(&twice, &crate::intersect::self_intersections(&twice));
        let arr = arrange_self(&twice, &seam);
        assert!(arr.failed.is_empty(), "{:?}", arr.failed);
        assert_eq!(arr.mesh.triangles.len(), 24);
        let topo = EdgeTopology::new(&arr.mesh);
        assert_eq!(topo.edge_count(), 18);
        assert!((0..18).all(|e| topo.uses_of(e).len() == 4));
    }
}

/// The Delaunay flips' in-circle test: the sign of the exact test wherever it answers,
/// zero for four points on one circle (the corners of squares and rectangles, at any
/// offset), and zero only within the error bound of `f64` (points near a circle).
#[test]
fn the_flips_in_circle_test_has_the_exact_sign_or_none() {
    use super::local::incircle_clear;
    let c = |x: f64, y: f64| robust::Coord { x, y };
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let mut next = || rng.unit();
    let (mut signed, mut zero) = (0, 0);
    for k in 0..20_000 {
        // Random points, points on a lattice (many on one circle), near-cocircular.
        let p: [robust::Coord<f64>; 4] = match k % 3 {
            0 => std::array::from_fn(|_| c(next() * 10.0 - 5.0, next() * 10.0 - 5.0)),
            1 => std::array::from_fn(|_| c((next() * 4.0).floor(), (next() * 4.0).floor())),
            _ => {
                let scale = if k % 2 == 0 { 0.0 } else { 1e6 };
                let (r, off) = (1.0 + next(), [scale * next(), scale * next()]);
                std::array::from_fn(|_| {
                    let t = next() * std::f64::consts::TAU;
                    c(off[0] + r * t.cos(), off[1] + r * t.sin())
                })
            }
        };
        let exact = robust::incircle(p[0], p[1], p[2], p[3]);
        let got = incircle_clear(p[0], p[1], p[2], p[3]);
        if got == 0.0 {
            zero += 1;
        } else {
            signed += 1;
            assert_eq!(got > 0.0, exact > 0.0, "{p:?}");
            assert!(exact != 0.0, "{p:?}");
        }
    }
    assert!(signed > 10_000 && zero > 1_000, "{signed} {zero}");
    // Squares' and rectangles' corners, anywhere: on one circle.
    for off in [[0.0, 0.0], [0.5, -3.25], [512_345.5, 7_001_234.25]] {
        let q = |x: f64, y: f64| c(off[0] + x, off[1] + y);
        for (w, h) in [(1.0, 1.0), (2.0, 0.5), (0.125, 3.0)] {
            let r = incircle_clear(q(0.0, 0.0), q(w, 0.0), q(w, h), q(0.0, h));
            assert_eq!(r, 0.0);
            assert!(incircle_clear(q(0.0, 0.0), q(w, 0.0), q(w, h), q(w / 2.0, h / 2.0)) > 0.0);
        }
    }
}

/// The flips' canonical in-circle choice: for every order of four points, the same
/// answer up to the order's sign (so the two diagonals of a quad never both ask for a
/// flip, and the flips end where they would for any insertion order); the clear test's
/// sign where it has one; on one circle, the sign of the determinant with the lexicographically
/// first point's lift raised a little (a lifting, so the triangulation is a regular one).
#[test]
fn the_flips_canonical_choice_is_one_for_every_order() {
    use super::local::{incircle_canonical, incircle_clear};
    let c = |x: f64, y: f64| robust::Coord { x, y };
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut next = || rng.unit();
    let perms: Vec<([usize; 4], bool)> = (0..24)
        .map(|mut n| {
            let mut rest = vec![0, 1, 2, 3];
            let mut p = [0; 4];
            for (i, slot) in p.iter_mut().enumerate() {
                *slot = rest.remove(n % (4 - i));
                n /= 4 - i;
            }
            let odd = (0..4)
                .flat_map(|i| (i + 1..4).map(move |j| (i, j)))
                .filter(|&(i, j)| p[i] > p[j])
                .count()
                % 2
                == 1;
            (p, odd)
        })
        .collect();
    let (mut tied, mut clear) = (0, 0);
    for k in 0..6_000 {
        let p: [robust::Coord<f64>; 4] = match k % 2 {
            0 => std::array::from_fn(|_| c(next() * 10.0 - 5.0, next() * 10.0 - 5.0)),
            _ => std::array::from_fn(|_| c((next() * 4.0).floor(), (next() * 4.0).floor())),
        };
        let distinct = (0..4).all(|i| (i + 1..4).all(|j| (p[i].x, p[i].y) != (p[j].x, p[j].y)));
        if !distinct {
            continue;
        }
        let base = incircle_canonical(p);
        for (perm, odd) in &perms {
            let got = incircle_canonical(perm.map(|i| p[i]));
            let want = if *odd { -base } else { base };
            assert_eq!(
                got.partial_cmp(&0.0),
                want.partial_cmp(&0.0),
                "{p:?} {perm:?}"
            );
        }
        let collinear =
            robust::orient2d(p[0], p[1], p[2]) == 0.0 && robust::orient2d(p[0], p[1], p[3]) == 0.0;
        assert_eq!(base == 0.0, collinear, "{p:?}");
        if incircle_clear(p[0], p[1], p[2], p[3]) != 0.0 {
            clear += 1;
            assert_eq!(base > 0.0, robust::incircle(p[0], p[1], p[2], p[3]) > 0.0);
        } else if robust::incircle(p[0], p[1], p[2], p[3]) == 0.0 && !collinear {
            tied += 1;
            // The lexicographically first point's lift raised by a small step (exact
            // here: small integers), the others' by far less.
            let mut order = [0usize, 1, 2, 3];
            order.sort_by(|&i, &j| (p[i].x, p[i].y).partial_cmp(&(p[j].x, p[j].y)).unwrap());
            let mut lift = [0.0f64; 4];
            for (r, &i) in order.iter().enumerate() {
                lift[i] = p[i].x * p[i].x
                    + p[i].y * p[i].y
                    + [1.0 / 64.0, 1.0 / 4096.0, 1.0 / 262_144.0, 0.0][r];
            }
            let d = 3;
            let row = |i: usize| [p[i].x - p[d].x, p[i].y - p[d].y, lift[i] - lift[d]];
            let (r0, r1, r2) = (row(0), row(1), row(2));
            let det = r0[0] * (r1[1] * r2[2] - r1[2] * r2[1])
                - r0[1] * (r1[0] * r2[2] - r1[2] * r2[0])
                + r0[2] * (r1[0] * r2[1] - r1[1] * r2[0]);
            assert!(
                det != 0.0 && (det > 0.0) == (base > 0.0),
                "{p:?}: {det} {base}"
            );
        }
    }
    assert!(tied > 100 && clear > 2_000, "{tied} {clear}");
}

/// The chain order numbers the constraints' ends once and walks them by number: the same
/// order as the first way (a list sorted by end, searched at every step and comparison),
/// on random triangles' points and constraints (chains, branches, repeated and
/// degenerate constraints, points on none), few (scanned) and many (sorted list).
#[test]
fn the_chain_order_is_the_one_of_the_first_way() {
    let mut rng = Rng(0xc4a1_0bde);
    let (mut moved, mut scanned, mut listed) = (0, 0, 0);
    // One set of arrays for every round, as a thread's triangles share it.
    let mut work = Chains::default();
    for round in 0..4000 {
        let vertices = 3 + (rng.next() % 40) as u32;
        let count = 1 + (rng.next() % if round % 3 == 0 { 60 } else { 12 }) as usize;
        let cons: Vec<[u32; 2]> = (0..count)
            .map(|_| {
                let a = 100 + (rng.next() % u64::from(vertices)) as u32;
                let b = match rng.next() % 8 {
                    0 => a,
                    _ => 100 + (rng.next() % u64::from(vertices)) as u32,
                };
                [a.min(b), a.max(b)]
            })
            .collect();
        let n = 3 + (rng.next() % u64::from(vertices + 5)) as usize;
        let mine: Vec<(u32, Option<usize>)> = (0..n)
            .map(|k| {
                let on_edge = (k % 4 == 0).then_some(k % 3);
                (100 + (rng.next() % u64::from(vertices + 5)) as u32, on_edge)
            })
            .collect();
        let (mut ours, mut first) = (mine.clone(), mine.clone());
        chain_order(&mut ours, &cons, &mut work);
        chain_order_reference(&mut first, &cons);
        assert_eq!(ours, first, "{cons:?}");
        moved += usize::from(ours != mine);
        if cons.len() > CHAIN_SCAN_UP_TO {
            listed += 1;
        } else {
            scanned += 1;
        }
    }
    assert!(
        moved > 2500 && scanned > 2000 && listed > 600,
        "{moved} {scanned} {listed}"
    );
}

/// The scratch a thread keeps between arrangements ([`Lent`]) changes no result: a small
/// pair arranged on a fresh thread, and again on that thread after a larger pair grew and
/// left its scratch, gives the same meshes; a scratch grown beyond [`KEEP_UP_TO`] points
/// (a triangle crossed by a fine sphere's equator) is not kept.
#[test]
fn a_kept_scratch_changes_no_arrangement() {
    let small = (
        Mesh::unit_cube(),
        Mesh::cuboid([0.5, 0.25, -0.5], [1.5, 0.75, 0.5]),
    );
    let sphere = uv_sphere([0.0; 3], 1.0, 48, 24);
    let large = (
        sphere.clone(),
        rigid_motion(&sphere, [1.0, 2.0, 3.0], 0.7, [0.3, 0.1, 0.05]),
    );
    let big_triangle = Mesh::new_unchecked(
        vec![[-3.0, -3.0, 0.01], [6.0, -3.0, 0.02], [-3.0, 6.0, 0.03]],
        vec![[0, 1, 2]],
    );
    let fine = (big_triangle, uv_sphere([0.0; 3], 1.0, 1200, 9));
    let arranged = |(a, b): &(Mesh, Mesh)| {
        let seam = intersect(a, b);
        [(a, Source::A), (b, Source::B)].map(|(m, side)| arrange(m, &seam, side).mesh)
    };
    let kept_room = || {
        KEPT.with(|k| {
            let s = k.take();
            let room = s.as_ref().map(|s| s.local.as_ref().map_or(0, |l| l.room()));
            k.set(s);
            room
        })
    };
    std::thread::scope(|s| {
        s.spawn(|| {
            crate::par::serially(|| {
                let fresh = arranged(&small);
                assert!(kept_room().is_some_and(|r| r > 0));
                let _ = arranged(&large);
                let grown = kept_room().unwrap();
                assert_eq!(arranged(&small), fresh);
                assert!(kept_room().unwrap() >= grown);
                let seam = intersect(&fine.0, &fine.1);
                let triangle = arrange(&fine.0, &seam, Source::A).mesh;
                assert!(triangle.triangles.len() > 2 * KEEP_UP_TO);
                assert_eq!(kept_room(), None);
            })
        });
    });
}
