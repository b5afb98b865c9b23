use super::engine::Editor;
use super::shape::tri_box;
use super::*;
use crate::bvh::overlaps as overlap;

/// A unit square (z = 0) of four triangles around vertex 4 at `p`.
fn square_around(p: [f64; 3]) -> Mesh {
    Mesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            p,
        ],
        vec![[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]],
    )
    .unwrap()
}

#[test]
fn a_vertex_next_to_a_corner_goes_into_it_and_parents_follow() {
    let square = square_around([0.999, 0.999, 0.0]);
    let s = snap_with(
        &square,
        &SnapOptions {
            tolerance: 0.01,
            ..SnapOptions::default()
        },
    )
    .unwrap();
    let r = &s.report;
    assert_eq!((r.found, r.collapsed, r.flipped, r.left), (2, 1, 0, 0));
    // The interior vertex moved (never the boundary corner), the two triangles on the
    // edge went, the other two keep their places.
    assert_eq!(s.mesh.triangles, vec![[0, 1, 2], [3, 0, 2]]);
    assert_eq!(s.mesh.positions.len(), 4);
    assert_eq!(s.parent, vec![0, 3]);
    assert_eq!((r.volume_change, r.area_change), (0.0, 0.0));
    assert!((r.max_move - 0.001 * 2f64.sqrt()).abs() < 1e-15);
}

#[test]
fn a_needle_on_the_boundary_stays_and_is_counted() {
    // Vertex 4 a millimetre inside the boundary edge 0-1: a needle on it, with no short
    // edge to collapse and no neighbour across the boundary edge to flip with.
    let square = square_around([0.5, 0.001, 0.0]);
    let (m, r) = snap(&square, 0.01).unwrap();
    assert_eq!(m, square);
    assert_eq!((r.found, r.collapsed, r.flipped, r.left), (1, 0, 0, 1));
    assert_eq!(r.refused_manifold, 1);
}

#[test]
fn a_boundary_vertex_moves_only_along_the_boundary() {
    // Vertex 4 on the boundary edge 0-1, a millimetre from corner 1: moving it onto the
    // interior vertex would open the boundary; it goes into the corner along the edge.
    let m = Mesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.999, 0.0, 0.0],
            [0.5, 0.5, 0.0],
        ],
        vec![[0, 4, 5], [4, 1, 5], [1, 2, 5], [2, 3, 5], [3, 0, 5]],
    )
    .unwrap();
    let (s, r) = snap(&m, 0.01).unwrap();
    assert_eq!((r.collapsed, r.left), (1, 0));
    assert_eq!(s.positions.len(), 5);
    assert!(!s.positions.contains(&[0.999, 0.0, 0.0]));
    assert!(s.positions.contains(&[0.5, 0.5, 0.0]));
    let counts = crate::edges::EdgeCounts::of(&s);
    assert_eq!((counts.boundary, counts.non_manifold), (4, 0));
}

#[test]
fn a_thin_tetrahedron_is_left_alone() {
    // Collapsing its short edge would fold it into two coincident triangles (the link
    // condition fails); flipping turns a face over.
    let t = Mesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 0.001],
        ],
        vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]],
    )
    .unwrap();
    let (m, r) = snap(&t, 0.01).unwrap();
    assert_eq!(m, t);
    assert_eq!((r.collapsed, r.flipped), (0, 0));
    assert_eq!(r.left, r.found);
    assert!(r.left > 0);
}

/// A square split by the diagonal 0-2 with vertex 4 a millimetre off that diagonal: the
/// cap 0-4-2 is 7e-4 high over its long edge 0-2 and has no short edge.
fn cap_square() -> Mesh {
    let positions = square_around([0.5005, 0.4995, 0.0]).positions;
    Mesh::new(positions, vec![[0, 1, 4], [1, 2, 4], [0, 4, 2], [0, 2, 3]]).unwrap()
}

#[test]
fn a_cap_is_flipped_away() {
    // The cap 0-4-2 goes by flipping 0-2 into 4-3.
    let m = cap_square();
    let (s, r) = snap(&m, 0.01).unwrap();
    assert_eq!((r.found, r.flipped, r.left), (1, 1, 0));
    assert_eq!(s.triangles.len(), 4);
    assert_eq!(r.volume_change, 0.0);
    assert!((r.area_change).abs() < 1e-15);
}

#[test]
fn zero_changes_nothing_and_bad_tolerances_are_errors() {
    let square = square_around([0.999, 0.999, 0.0]);
    let (m, r) = snap(&square, 0.0).unwrap();
    assert_eq!(m, square);
    assert_eq!(r.found, 0);
    for bad in [-1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            snap(&square, bad),
            Err(Error::InvalidParameter(_))
        ));
    }
    let labels = [0u32; 3];
    let opts = SnapOptions {
        tolerance: 0.01,
        labels: Some(&labels),
        ..SnapOptions::default()
    };
    assert!(snap_with(&square, &opts).is_err());
}

#[test]
fn labels_keep_flips_off_the_seam() {
    // The cap of `a_cap_is_flipped_away` with its neighbour across the long edge from the
    // other input: no flip across the seam.
    let m = cap_square();
    let labels = [0, 0, 0, 1];
    let s = snap_with(
        &m,
        &SnapOptions {
            tolerance: 0.01,
            labels: Some(&labels),
            ..SnapOptions::default()
        },
    )
    .unwrap();
    assert_eq!((s.report.flipped, s.report.left), (0, 1));
    assert_eq!(s.report.refused_seam, 1);
    assert_eq!(s.mesh, m);
}

/// A unit square of four triangles around vertex 4 raised 5e-3 just inside corner 2
/// (two needles along the edges at corner 2, edge 4-2 8.7e-3 long), and with `poker` a
/// separate vertical triangle in the plane y = 0.9 reaching from z = −1 up to `top`.
fn raised_square(poker_top: Option<f64>) -> Mesh {
    let mut positions = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.995, 0.995, 0.005],
    ];
    let mut triangles = vec![[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]];
    if let Some(top) = poker_top {
        positions.extend([[0.85, 0.9, -1.0], [0.95, 0.9, -1.0], [0.9, 0.9, top]]);
        triangles.push([5, 6, 7]);
    }
    Mesh::new(positions, triangles).unwrap()
}

#[test]
fn a_collapse_that_would_cross_another_sheet_is_refused() {
    // Alone, vertex 4 goes into corner 2 and the square lies flat.
    let (flat, r) = snap(&raised_square(None), 0.01).unwrap();
    assert_eq!((r.found, r.collapsed, r.left), (2, 1, 0));
    assert!(flat.positions.iter().all(|p| p[2] == 0.0));
    // A sheet poking up to z = 0.001 under the raised square (which is 4.5e-3 high
    // there) would cross the flat square: the collapse is refused, nothing crosses.
    let poked = raised_square(Some(0.001));
    assert!(crate::intersect::self_intersections(&poked).is_empty());
    // (Each needle is counted by the first refusal of its fixes: moving the boundary
    // corner 2 off its boundary comes before moving vertex 4.)
    let (m, r) = snap(&poked, 0.01).unwrap();
    assert_eq!((r.collapsed, r.flipped, r.left), (0, 0, 2), "{r:?}");
    assert_eq!(m, poked);
    assert!(crate::intersect::self_intersections(&m).is_empty());
}

/// A sphere of 4,032 triangles and three long triangles across it (each spanning many
/// cells: [`Grid::WIDE`]), as one mesh.
fn sphere_and_long_triangles() -> Mesh {
    let s = crate::shapes::uv_sphere([0.0; 3], 1.0, 64, 32);
    let (mut p, mut t) = (s.positions.clone(), s.triangles.clone());
    for (a, b, c) in [
        ([-1.2, -0.1, 0.0], [1.2, 0.1, 0.05], [0.0, 0.0, 0.3]),
        ([0.0, -1.3, -0.5], [0.1, 1.3, 0.5], [0.3, 0.0, 0.0]),
        ([-0.9, 0.9, -0.9], [0.9, -0.9, 0.9], [0.0, 0.2, 0.0]),
    ] {
        let n = p.len() as u32;
        p.extend([a, b, c]);
        t.push([n, n + 1, n + 2]);
    }
    Mesh::new(p, t).unwrap()
}

/// The row-by-row search of the gathered triangles by grid key finds every triangle
/// whose box meets the query box, once, on both of its paths (rows of small boxes, all
/// entries for large ones), and on rows only those whose cells meet the box's: boxes from
/// a point to the whole sphere, at random places.
#[test]
fn keyed_rows_find_every_triangle_whose_box_meets_a_box() {
    let m = sphere_and_long_triangles();
    let grid = Grid::new(&m, 1e-3);
    let cell = |t: &[u32; 3]| t.map(|v| grid.packed(&m.positions[v as usize]));
    let mut keyed: Vec<(u32, u32)> = m
        .triangles
        .iter()
        .enumerate()
        .map(|(t, tri)| (grid.key(cell(tri)), t as u32))
        .filter(|&(k, _)| k != Grid::WIDE)
        .collect();
    let n = m.triangles.len();
    assert!(keyed.len() > n * 9 / 10 && keyed.iter().all(|&(_, t)| (t as usize) < n - 3));
    keyed.sort_unstable();
    let rows_of = grid.rows_of_keys(&keyed);
    let mut rng = crate::test_util::Rng(0x5eed);
    let mut unit = || rng.unit();
    let (mut by_rows, mut whole) = (0, 0);
    for round in 0..2000 {
        let c: [f64; 3] = std::array::from_fn(|_| 2.4 * unit() - 1.2);
        let h = [0.0, 0.01, 0.05, 0.2, 1.5, 3.0][round % 6] * unit();
        let b: Box3 = [c.map(|x| x - h), c.map(|x| x + h)];
        let mut found = Vec::new();
        grid.keyed_near(&keyed, &rows_of, &b, |i| found.push(keyed[i].1));
        let r = grid.range(&b);
        let rows =
            (r[1][1] - r[0][1].saturating_sub(1) + 1) * (r[1][2] - r[0][2].saturating_sub(1) + 1);
        if rows * Grid::ROW_COST > keyed.len() {
            whole += 1;
        } else {
            by_rows += 1;
            // Row by row, only those whose cells meet the box's.
            for &t in &found {
                let c = grid.range(&tri_box(&m.corners(t as usize)));
                let meets = (0..3).all(|k| c[0][k] <= r[1][k] && r[0][k] <= c[1][k]);
                assert!(meets, "round {round}: {t} {c:?} {r:?}");
            }
        }
        let n = found.len();
        found.sort_unstable();
        found.dedup();
        assert_eq!(found.len(), n, "each once");
        for &(_, t) in &keyed {
            if overlap(&tri_box(&m.corners(t as usize)), &b) {
                assert!(found.binary_search(&t).is_ok(), "round {round}: {t} missed");
            }
        }
    }
    assert!(by_rows > 1000 && whole > 100, "{by_rows} {whole}");
}

/// The scan keeps as candidates exactly the triangles touching the halo (a box test of
/// each against the marked cells): those with a corner near the seam, the long ones
/// crossing it with no corner near it, and among 20,000 small ones scattered at random
/// those reaching into it from the cells next to it; at unit size and UTM-shifted (the
/// scan first drops the triangles outside a box around the halo).
#[test]
fn the_scan_keeps_every_triangle_touching_the_halo() {
    for shift in [0.0, 5.3e6] {
        let base = sphere_and_long_triangles();
        let (mut p, mut t) = (base.positions.clone(), base.triangles.clone());
        let mut rng = crate::test_util::Rng(0xca11);
        let mut unit = || rng.unit();
        for _ in 0..20_000 {
            let c: [f64; 3] = std::array::from_fn(|_| 2.2 * unit() - 1.1);
            let n = p.len() as u32;
            for _ in 0..3 {
                p.push(std::array::from_fn(|k| c[k] + 0.1 * unit() - 0.05));
            }
            t.push([n, n + 1, n + 2]);
        }
        for q in &mut p {
            q[0] += shift;
            q[1] -= shift;
        }
        let m = Mesh::new_unchecked(p, t);
        // The seam: the equator's points.
        let seam: Vec<u32> = (0..m.positions.len() as u32)
            .filter(|&v| {
                m.positions[v as usize][2].abs() < 1e-9 && v < base.positions.len() as u32 - 9
            })
            .collect();
        assert_eq!(seam.len(), 64);
        let opts = SnapOptions {
            tolerance: 1e-3,
            seam: &seam,
            seam_only: true,
            ..SnapOptions::default()
        };
        let grid = Grid::new(&m, opts.tolerance);
        let (at, [halo, next_to_halo], halo_box) = seam_and_halo(&m, &opts, &grid);
        let scan = Scan::of(
            &m,
            opts.tolerance,
            &grid,
            at.as_deref(),
            [&halo, &next_to_halo],
            halo_box,
        );
        let mut kept: Vec<u32> = scan.candidates.iter().map(|&(t, _)| t).collect();
        kept.sort_unstable();
        let touching: Vec<u32> = (0..m.triangles.len() as u32)
            .filter(|&t| halo.touches(&tri_box(&m.corners(t as usize))))
            .collect();
        let missed = touching
            .iter()
            .filter(|t| kept.binary_search(t).is_err())
            .count();
        assert!(
            kept == touching,
            "shift {shift}: {} kept, {} touching the halo, {missed} of those missed",
            kept.len(),
            touching.len()
        );
        let n = base.triangles.len() as u32;
        assert!(kept.len() > 2000 && kept.len() < 15_000, "{}", kept.len());
        assert!(
            (n - 3..n).all(|t| kept.contains(&t)),
            "the long triangles cross the halo"
        );
        // The box around the halo: most triangles are outside it.
        let inside = (0..m.triangles.len())
            .filter(|&t| overlap(&tri_box(&m.corners(t)), &halo_box.expect("a halo")))
            .count();
        assert!(inside < m.triangles.len() / 2, "{inside}");
    }
}

/// The least coordinate of each cell ([`Grid::first_at_least`]) splits the coordinates
/// exactly: below it the cell is less, from it on not; so a box meets [`Grid::enclosing`]
/// of a range exactly when its cells meet the range. At unit size, UTM-shifted, and
/// where the cells are finer than the coordinates' spacing.
#[test]
fn the_least_coordinate_of_a_cell_splits_exactly() {
    let mut rng = crate::test_util::Rng(0xb0c5);
    for (lo, extent, d) in [
        (-1.0, 2.0, 1e-3),
        (5.3e6, 1.5e3, 1e-2),
        (1e15, 3.0, 1e-4),
        (-7.0e-3, 1e-6, 1e-9),
    ] {
        let m = Mesh::new_unchecked(
            vec![
                [lo, lo, lo],
                [lo + extent, lo, lo],
                [lo, lo + extent, lo + extent],
            ],
            vec![[0, 1, 2]],
        );
        let grid = Grid::new(&m, d);
        for _ in 0..300 {
            let k = (rng.next() % 3) as usize;
            let c = (rng.next() % (grid.n[k] as u64 + 1)) as usize;
            let x = grid.first_at_least(k, c);
            if c == 0 {
                assert_eq!(x, f64::NEG_INFINITY);
                continue;
            }
            if c >= grid.n[k] {
                assert_eq!(x, f64::INFINITY);
                continue;
            }
            assert!(grid.cell(x, k) >= c, "{lo} {c}");
            assert!(grid.cell(x.next_down(), k) < c, "{lo} {c}");
        }
        // Random boxes against random ranges.
        for _ in 0..300 {
            let r: [[usize; 3]; 2] = {
                let a: [usize; 3] = std::array::from_fn(|k| (rng.next() as usize) % grid.n[k]);
                let b: [usize; 3] = std::array::from_fn(|k| (rng.next() as usize) % grid.n[k]);
                [
                    std::array::from_fn(|k| a[k].min(b[k])),
                    std::array::from_fn(|k| a[k].max(b[k])),
                ]
            };
            let e = grid.enclosing(&r);
            let mut unit = || rng.unit();
            let p: [[f64; 3]; 2] = std::array::from_fn(|_| {
                std::array::from_fn(|_| lo + extent * (1.2 * unit() - 0.1))
            });
            let b: Box3 = [
                std::array::from_fn(|k| p[0][k].min(p[1][k])),
                std::array::from_fn(|k| p[0][k].max(p[1][k])),
            ];
            let cells = grid.range(&b);
            let meets = (0..3).all(|k| cells[0][k] <= r[1][k] && r[0][k] <= cells[1][k]);
            assert!(!meets || overlap(&b, &e), "{lo}: {b:?} {r:?}");
        }
    }
}

/// A gathering that adds to an index built before ([`Editor::extend`]) leaves it answering
/// as a brute-force search does: the live triangles around every vertex in a marked cell
/// ([`Editor::star`]) and those whose boxes meet a box the marked cells cover
/// ([`Editor::near_triangles`]), before and after changes made between the gatherings and
/// after them, each triangle once. The union of two spheres at a tolerance that makes
/// many seam triangles bad: three seeds gathered and fixed first, then one half of the
/// seam, then the other.
#[test]
fn an_extended_index_answers_as_a_search_of_every_triangle() {
    use crate::boolean::{boolean, Op};
    use crate::shapes::{rigid_motion, uv_sphere};
    let a = uv_sphere([0.0; 3], 1.0, 48, 25);
    let b = rigid_motion(&a, [0.0, 0.0, 1.0], 0.1, [0.5, 0.0, 0.0]);
    let r = boolean(&a, &b, Op::Union, &Default::default());
    let m = &r.mesh;
    let opts = SnapOptions {
        tolerance: 0.02,
        seam: &r.seam_vertices,
        seam_only: true,
        ..SnapOptions::default()
    };
    let grid = Grid::new(m, opts.tolerance);
    let (at, [halo, next_to_halo], halo_box) = seam_and_halo(m, &opts, &grid);
    let scan = Scan::of(
        m,
        opts.tolerance,
        &grid,
        at.as_deref(),
        [&halo, &next_to_halo],
        halo_box,
    );
    let bad: Vec<u32> = scan.bad.iter().map(|&(_, t)| t).collect();
    let mut w = Editor::new(m, &opts, Labels::Given(opts.labels), scan, grid, halo);
    // By the side of the seam's plane (x = 0.25): two gatherings far apart.
    let side = |w: &Editor, t: u32| w.corners(&w.tri(t))[0][1] < 0.0;
    let (first, second): (Vec<u32>, Vec<u32>) = bad.iter().partition(|&&t| side(&w, t));
    assert!(
        first.len() > 20 && second.len() > 20,
        "{} {}",
        first.len(),
        second.len()
    );
    let check = |w: &Editor, what: &str| {
        let count = w.base + w.made.len() as u32;
        let live: Vec<u32> = (0..count).filter(|&t| w.alive(t)).collect();
        let mut checked = 0;
        for v in 0..m.positions.len() as u32 {
            if w.dead.contains(&v) {
                continue;
            }
            let Ok(mut star) = w.star(v) else { continue };
            star.sort_unstable();
            let all: Vec<u32> = live
                .iter()
                .copied()
                .filter(|&t| w.tri(t).contains(&v))
                .collect();
            assert_eq!(star, all, "{what}: the star of {v}");
            checked += 1;
        }
        let mut rng = crate::test_util::Rng(0x9a7e);
        let mut searched = 0;
        for _ in 0..3000 {
            let c = w.pos(rng.next() as u32 % m.positions.len() as u32);
            let h = 0.05 * rng.unit();
            let b: Box3 = [c.map(|x| x - h), c.map(|x| x + h)];
            if !w.grid.covers(&b) {
                continue;
            }
            let mut near = w.near_triangles(&b);
            near.sort_unstable();
            let all: Vec<u32> = live
                .iter()
                .copied()
                .filter(|&t| overlap(&tri_box(&w.corners(&w.tri(t))), &b))
                .collect();
            assert_eq!(near, all, "{what}: near {b:?}");
            searched += 1;
        }
        assert!(
            checked > 100 && searched > 100,
            "{what}: {checked} {searched}"
        );
    };
    let fix_all = |w: &mut Editor, ts: &[u32]| {
        let mut fixed = 0;
        for &t in ts {
            if w.alive(t) && w.bad_key(t).is_some() && w.fix(t).is_ok() {
                fixed += 1;
            }
        }
        fixed
    };
    // A few seeds first: the changes at the border of their cells make triangles with
    // corners in cells the next gathering marks.
    assert!(w.gather(&first[..3]));
    assert!(w.near.built);
    check(&w, "first gathering");
    assert!(fix_all(&mut w, &first) > 0);
    check(&w, "first changes");
    let extended = |w: &Editor| w.near.later.iter().any(|&t| t < w.base);
    for (round, seeds) in [&first, &second].into_iter().enumerate() {
        assert!(w.gather(seeds));
        assert!(extended(&w), "round {round}: extended, not built anew");
        check(&w, "a later gathering");
        assert!(fix_all(&mut w, seeds) > 10);
        check(&w, "later changes");
    }
    check(&w, "second changes");
}
