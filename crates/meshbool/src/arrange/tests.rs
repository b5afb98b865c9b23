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
