use super::tritri::{edge, intersect as tt, Feature::*, Label, Tri, TriTri};
use super::*;
use crate::edges::{EdgeKind, EdgeTopology};
use crate::shapes::rigid_motion;
use crate::shapes::{heightfield, uv_sphere};
use crate::test_util::Rng;

fn t(id: u32, base: u32, p: [[f64; 3]; 3]) -> Tri {
    Tri::new(id, [base, base + 1, base + 2], p).unwrap()
}

fn l(a: Feature, b: Feature) -> Label {
    Label { a, b }
}

/// Triangle A: in z = 0, vertices 0, 1, 2.
fn a_tri() -> Tri {
    t(0, 0, [[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [0.0, 4.0, 0.0]])
}

fn seg(r: TriTri) -> [Label; 2] {
    match r {
        TriTri::Segment(mut s) => {
            s.sort();
            s
        }
        other => panic!("expected a segment, got {other:?}"),
    }
}

#[test]
fn proper_crossing() {
    // B stands vertically through A's interior: both crossing points are B's edges
    // through A's face.
    let b = t(0, 10, [[1.0, 1.0, -1.0], [1.0, 1.0, 1.0], [2.0, 1.0, 0.5]]);
    let mut want = [l(Face(0), edge(10, 11)), l(Face(0), edge(10, 12))];
    want.sort();
    assert_eq!(seg(tt(&a_tri(), &b)), want);
}

#[test]
fn crossing_through_an_edge_of_a() {
    // B crosses A's edge 0-1 (y = 0): one end on that edge, labelled edge × edge.
    let b = t(
        0,
        10,
        [[1.0, -1.0, -1.0], [1.0, 1.0, -1.0], [1.0, 1.0, 1.0]],
    );
    let s = seg(tt(&a_tri(), &b));
    assert!(s.contains(&l(edge(0, 1), edge(10, 12))), "{s:?}");
    assert!(s.contains(&l(Face(0), edge(11, 12))), "{s:?}");
}

#[test]
fn vertex_on_plane_touches() {
    let b = t(0, 10, [[1.0, 1.0, 0.0], [1.0, 2.0, 1.0], [2.0, 1.0, 1.0]]);
    assert_eq!(tt(&a_tri(), &b), TriTri::Point(l(Face(0), Vertex(10))));
    // The vertex touches A's edge instead.
    let b = t(0, 10, [[1.0, 0.0, 0.0], [1.0, 2.0, 1.0], [2.0, 1.0, 1.0]]);
    assert_eq!(tt(&a_tri(), &b), TriTri::Point(l(edge(0, 1), Vertex(10))));
}

#[test]
fn vertex_on_vertex() {
    let b = t(0, 10, [[4.0, 0.0, 0.0], [5.0, 1.0, 1.0], [5.0, -1.0, 1.0]]);
    assert_eq!(tt(&a_tri(), &b), TriTri::Point(l(Vertex(1), Vertex(10))));
}

#[test]
fn vertex_in_plane_and_crossing() {
    // B's vertex 10 lies inside A, the opposite edge crosses below: segment from the
    // vertex to B's crossing edge... which is below A's plane, so the segment ends where
    // B's edge 10-11/10-12 leaves... construct: 11 above, 12 below.
    let b = t(0, 10, [[1.0, 1.0, 0.0], [1.0, 2.0, 1.0], [2.0, 2.0, -1.0]]);
    let s = seg(tt(&a_tri(), &b));
    let mut want = [l(Face(0), Vertex(10)), l(Face(0), edge(11, 12))];
    want.sort();
    assert_eq!(s, want);
}

#[test]
fn edge_in_plane() {
    // B's edge 10-11 lies in A's plane and crosses A's edge 1-2 (x + y = 4).
    let b = t(0, 10, [[1.0, 1.0, 0.0], [5.0, 1.0, 0.0], [3.0, 1.0, 2.0]]);
    let s = seg(tt(&a_tri(), &b));
    let mut want = [l(Face(0), Vertex(10)), l(edge(1, 2), edge(10, 11))];
    want.sort();
    assert_eq!(s, want);
}

#[test]
fn edge_through_edge_skew() {
    // B's edge 10-11 pierces A's edge 0-2 (x = 0) at (0, 1, 0); B's other vertex is above.
    let b = t(0, 10, [[-1.0, 1.0, -1.0], [1.0, 1.0, 1.0], [1.0, 3.0, 1.0]]);
    let r = tt(&a_tri(), &b);
    let s = seg(r);
    assert!(s.contains(&l(edge(0, 2), edge(10, 11))), "{s:?}");
}

#[test]
fn coplanar_overlap_gives_the_clipped_edges() {
    // B: a triangle in z = 0 overlapping A's corner region at (4,0).
    let b = t(0, 10, [[3.0, -1.0, 0.0], [6.0, -1.0, 0.0], [3.0, 2.0, 0.0]]);
    match tt(&a_tri(), &b) {
        TriTri::Coplanar { segments, points } => {
            assert!(points.is_empty());
            // Overlap polygon: (3,0) (4,0) (3,1): three sides, each along an edge of A or B.
            assert_eq!(segments.len(), 3, "{segments:?}");
            let all: Vec<Label> = segments.iter().flatten().copied().collect();
            assert!(all.contains(&l(Vertex(1), Face(0))));
            assert!(all.contains(&l(edge(0, 1), edge(10, 12))));
            assert!(all.contains(&l(edge(1, 2), edge(10, 12))));
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn coplanar_touching_at_a_vertex_and_apart() {
    let b = t(0, 10, [[4.0, 0.0, 0.0], [6.0, 0.0, 0.0], [6.0, -2.0, 0.0]]);
    assert_eq!(
        tt(&a_tri(), &b),
        TriTri::Coplanar {
            segments: vec![],
            points: vec![l(Vertex(1), Vertex(10))]
        }
    );
    let far = t(0, 10, [[5.0, 5.0, 0.0], [6.0, 5.0, 0.0], [6.0, 6.0, 0.0]]);
    assert_eq!(tt(&a_tri(), &far), TriTri::None);
}

#[test]
fn identical_triangles_share_their_edges() {
    let b = t(0, 10, *a_tri().corners());
    match tt(&a_tri(), &b) {
        TriTri::Coplanar { segments, .. } => {
            let mut want = vec![
                [l(Vertex(0), Vertex(10)), l(Vertex(1), Vertex(11))],
                [l(Vertex(1), Vertex(11)), l(Vertex(2), Vertex(12))],
                [l(Vertex(0), Vertex(10)), l(Vertex(2), Vertex(12))],
            ];
            want.sort();
            assert_eq!(segments, want);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn degenerate_triangle_is_refused() {
    assert!(Tri::new(0, [0, 1, 2], [[0.0; 3], [1.0; 3], [2.0; 3]]).is_none());
}

#[test]
fn two_spheres_meet_in_one_loop_on_the_analytic_circle() {
    for (seg, rings) in [(32, 16), (96, 48)] {
        let a = uv_sphere([0.0; 3], 1.0, seg, rings);
        let b = uv_sphere([0.5, 0.0, 0.0], 1.0, seg, rings);
        let seam = intersect(&a, &b);
        let curves = chain(&seam, false);
        assert_eq!(curves.len(), 1, "{seg}");
        assert!(curves[0].closed);
        assert_eq!(curves[0].points.len(), seam.points.len());
        // The circle x = 0.25, radius sqrt(1 - 0.25²); tessellation error of the sphere
        // is at most r (1 - cos(π / rings)) (rings are the coarser direction here).
        let sag = 1.0 - (std::f64::consts::PI / f64::from(rings)).cos();
        let rho = (1.0f64 - 0.0625).sqrt();
        for p in &seam.positions {
            assert!((p[0] - 0.25).abs() <= 2.0 * sag, "{p:?}");
            let r = (p[1] * p[1] + p[2] * p[2]).sqrt();
            assert!((r - rho).abs() <= 2.0 * sag, "{p:?}");
        }
        assert!((curves[0].to_xyz(&seam).length() - 2.0 * std::f64::consts::PI * rho).abs() < 0.05);
    }
}

#[test]
fn sphere_and_its_rotated_copy_shifted_1e9_give_closed_loops() {
    let a = uv_sphere([0.0; 3], 1.0, 48, 24);
    for (axis, angle) in [
        ([0.3, 0.5, 0.8], 0.2),
        ([0.0, 0.0, 1.0], 1e-12),
        ([1.0, 0.0, 0.0], 0.05),
    ] {
        let b = rigid_motion(&a, axis, angle, [1e-9, 0.0, 0.0]);
        let seam = intersect(&a, &b);
        let curves = chain(&seam, false);
        assert!(!curves.is_empty(), "{axis:?} {angle}");
        assert!(
            curves.iter().all(|c| c.closed),
            "{axis:?} {angle}: {:?}",
            curves.iter().map(|c| c.closed).collect::<Vec<_>>()
        );
    }
}

use crate::test_util::{bowl, shared_data, terrain_and_drill, UTM};

#[test]
fn terrain_and_cylinder_meet_in_one_closed_loop() {
    for center in [[0.0; 3], UTM] {
        let (terrain, drill) = terrain_and_drill(center);
        for tool in [drill, bowl(center)] {
            let seam = intersect(&terrain, &tool);
            let curves = chain(&seam, true);
            assert_eq!(curves.len(), 1, "{center:?}");
            assert!(curves[0].closed, "{center:?}");
            assert!(seam.touching.is_empty());
        }
    }
}

#[test]
fn crossing_terrains_give_open_chains_ending_on_boundaries() {
    let a = heightfield([0.0, 0.0], [10.0, 10.0], 23, 19, |x, y| {
        0.5 * (x * 0.7).sin() + 0.3 * (y * 0.9).cos()
    });
    let b = heightfield([-1.0, -1.0], [11.0, 11.0], 17, 29, |x, y| {
        0.08 * (x - 5.0) + 0.05 * (y - 5.0) + 0.1
    });
    let seam = intersect(&a, &b);
    let curves = chain(&seam, false);
    assert!(!curves.is_empty());
    let boundary = |m: &Mesh| -> Vec<[u32; 2]> {
        let topo = EdgeTopology::new(m);
        (0..topo.edge_count())
            .filter(|&e| topo.kind(e) == EdgeKind::Boundary)
            .map(|e| topo.edges[e])
            .collect()
    };
    let (ba, bb) = (boundary(&a), boundary(&b));
    let on_boundary = |lab: &Label| {
        let hit = |f: Feature, bnd: &[[u32; 2]]| match f {
            Feature::Edge(u, v) => bnd.contains(&[u, v]),
            Feature::Vertex(v) => bnd.iter().any(|e| e.contains(&v)),
            Feature::Face(_) => false,
        };
        hit(lab.a, &ba) || hit(lab.b, &bb)
    };
    for c in &curves {
        assert!(!c.closed);
        for end in [c.points[0], *c.points.last().unwrap()] {
            assert!(
                on_boundary(&seam.points[end as usize]),
                "{:?}",
                seam.points[end as usize]
            );
        }
    }
}

#[test]
fn identical_cubes_are_all_coplanar() {
    let cube = Mesh::unit_cube();
    let seam = intersect(&cube, &cube);
    // The 12 cube edges are the shared segments (found by coplanar pairs and where
    // perpendicular faces meet); the 6 face diagonals are flat edges of both cubes inside
    // one face of each, which cut nothing.
    assert_eq!(seam.segments.len(), 12);
    assert_eq!(seam.segments.iter().filter(|s| s.coplanar).count(), 0);
    assert_eq!(seam.points.len(), 8);
    assert!(seam
        .points
        .iter()
        .all(|p| matches!((p.a, p.b), (Feature::Vertex(_), Feature::Vertex(_)))));
}

fn swap(l: Label) -> Label {
    Label { a: l.b, b: l.a }
}

/// Every result must be the same with the triangles' roles swapped, and every reported
/// point must lie in both closed triangles. Integer coordinates in 0..=3 make vertices on
/// edges, shared vertices, edges in planes and coplanar pairs common.
#[test]
fn tritri_is_symmetric_and_its_points_lie_in_both_triangles() {
    let mut rng = Rng(0x1234_5678_9abc_def1);
    let mut next = || (rng.next() % 4) as f64;
    let (mut segments, mut points, mut coplanar) = (0, 0, 0);
    for _ in 0..20_000 {
        let pa: [[f64; 3]; 3] = std::array::from_fn(|_| std::array::from_fn(|_| next()));
        let pb: [[f64; 3]; 3] = std::array::from_fn(|_| std::array::from_fn(|_| next()));
        let (Some(a), Some(b)) = (Tri::new(0, [0, 1, 2], pa), Tri::new(0, [10, 11, 12], pb)) else {
            continue;
        };
        let (ab, ba) = (tt(&a, &b), tt(&b, &a));
        let normalise = |r: &TriTri, flip: bool| -> (Vec<[Label; 2]>, Vec<Label>) {
            let f = |l: Label| if flip { swap(l) } else { l };
            let (mut s, mut p): (Vec<[Label; 2]>, Vec<Label>) = match r {
                TriTri::None => (vec![], vec![]),
                TriTri::Point(l) => (vec![], vec![f(*l)]),
                TriTri::Segment(s) => (vec![s.map(f)], vec![]),
                TriTri::Coplanar { segments, points } => (
                    segments.iter().map(|s| s.map(f)).collect(),
                    points.iter().map(|&l| f(l)).collect(),
                ),
            };
            s.iter_mut().for_each(|x| x.sort());
            s.sort();
            p.sort();
            (s, p)
        };
        let (sab, pab) = normalise(&ab, false);
        // With the roles swapped the labels name b's features first.
        assert_eq!(
            (sab.clone(), pab.clone()),
            normalise(&ba, true),
            "{pa:?} {pb:?}"
        );
        segments += sab.len();
        points += pab.len();
        coplanar += matches!(ab, TriTri::Coplanar { .. }) as usize;
        // Every point lies in both closed triangles, on exactly the features its label
        // names. Single-triangle meshes: A has vertices 0..3, B vertices 10..13 (face 0 each).
        let mesh_a = Mesh::new_unchecked(pa.to_vec(), vec![[0, 1, 2]]);
        let mut pos_b = vec![[0.0; 3]; 10];
        pos_b.extend(pb);
        let mesh_b = Mesh::new_unchecked(pos_b, vec![[10, 11, 12]]);
        for lab in sab.iter().flatten().chain(&pab) {
            let x = label_point(lab, &mesh_a, &mesh_b);
            assert_eq!(a.locate(&x), Some(lab.a), "{lab:?} {pa:?} {pb:?}");
            assert_eq!(b.locate(&x), Some(lab.b), "{lab:?} {pa:?} {pb:?}");
        }
    }
    // The generator must really exercise every kind of result.
    assert!(
        segments > 1000 && points > 1000 && coplanar > 30,
        "{segments} {points} {coplanar}"
    );
}

#[test]
fn self_intersections_found_exactly() {
    // Valid closed meshes and the terrains: none (the real one's folded-but-not-overlapping
    // neighbours are not intersections).
    assert!(self_intersections(&uv_sphere([0.0; 3], 1.0, 32, 16)).is_empty());
    assert!(self_intersections(&Mesh::unit_cube()).is_empty());
    assert!(self_intersections(&terrain_and_drill(UTM).0).is_empty());
    if let Some(folded) = shared_data("kirra_terrain.obj") {
        assert!(self_intersections(&folded).is_empty());
    }
    // Two spheres in one mesh, overlapping: every crossing pair is reported.
    let a = uv_sphere([0.0; 3], 1.0, 32, 16);
    let b = uv_sphere([0.5, 0.1, 0.0], 1.0, 24, 12);
    let mut both = a.clone();
    both.append(&b).unwrap();
    let pairs = self_intersections(&both);
    // Expected: every pair of a and b that meets at all (segments and single points).
    let na = a.triangles.len() as u32;
    let crossing: std::collections::BTreeSet<(u32, u32)> = crate::bvh::Bvh::new(&a)
        .overlapping_pairs(&a, &crate::bvh::Bvh::new(&b), &b)
        .into_iter()
        .filter(|&(i, j)| {
            let (x, y) = (tri(&a, i as usize).unwrap(), tri(&b, j as usize).unwrap());
            tt(&x, &y) != TriTri::None
        })
        .map(|(i, j)| (i, j + na))
        .collect();
    assert!(crossing.len() > 100);
    assert_eq!(
        pairs
            .iter()
            .copied()
            .collect::<std::collections::BTreeSet<_>>(),
        crossing
    );
    // A triangle folded flat onto its neighbour (sharing an edge, overlapping).
    let fold = Mesh::new_unchecked(
        vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [1.0, 2.0, 0.0],
            [1.0, 1.0, 0.0],
        ],
        vec![[0, 1, 2], [1, 0, 3]],
    );
    assert_eq!(self_intersections(&fold), vec![(0, 1)]);
    // The same, but the second triangle on the other side of the edge: fine.
    let flat = Mesh::new_unchecked(
        vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [1.0, 2.0, 0.0],
            [1.0, -1.0, 0.0],
        ],
        vec![[0, 1, 2], [1, 0, 3]],
    );
    assert!(self_intersections(&flat).is_empty());
}

/// A fan around an apex whose rim visits five points in `order` (by index around a
/// circle), closed underneath by a fan around a second apex so that both apexes are
/// interior vertices.
fn double_fan(order: [usize; 5]) -> Mesh {
    let rim: Vec<[f64; 3]> = (0..5)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 5.0;
            [a.cos(), a.sin(), 0.0]
        })
        .collect();
    let mut positions = rim;
    positions.push([0.1, 0.05, 1.0]);
    positions.push([-0.05, 0.1, -1.0]);
    let mut triangles = Vec::new();
    for k in 0..5 {
        let (p, q) = (order[k] as u32, order[(k + 1) % 5] as u32);
        triangles.push([5, p, q]);
        triangles.push([6, q, p]);
    }
    Mesh::new_unchecked(positions, triangles)
}

#[test]
fn fans_wound_twice_and_poked_through_are_found() {
    // Rim in circle order: a double pyramid, no intersections.
    let once = double_fan([0, 1, 2, 3, 4]);
    assert!(self_intersections(&once).is_empty());
    // Rim as a pentagram: each apex fan winds twice around its apex, so triangles of one
    // fan (sharing the apex, or the apex and a rim edge) overlap one another.
    let twice = double_fan([0, 2, 4, 1, 3]);
    let pairs = self_intersections(&twice);
    assert!(
        pairs.iter().any(|&(i, j)| {
            let (a, b) = (twice.triangles[i as usize], twice.triangles[j as usize]);
            a[0] == 5 && b[0] == 5
        }),
        "{pairs:?}"
    );
    // A sphere vertex pushed out through the opposite side: its star crosses the surface.
    let mut poked = uv_sphere([0.0; 3], 1.0, 16, 8);
    let v = 40;
    poked.positions[v] = poked.positions[v].map(|x| -1.5 * x);
    let found = self_intersections(&poked);
    assert!(found.iter().any(|&(i, j)| {
        let shares = |t: u32| poked.triangles[t as usize].contains(&(v as u32));
        shares(i) || shares(j)
    }));
}

/// The self-intersections of `m` found pair by pair over all pairs with overlapping
/// boxes, without the fan certificates or the tree.
fn self_intersections_brute(m: &Mesh) -> Vec<(u32, u32)> {
    use crate::bvh::{overlaps, tri_box};
    let n = m.triangles.len() as u32;
    let mut out = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            if !overlaps(&tri_box(m, i), &tri_box(m, j)) {
                continue;
            }
            let (vi, vj) = (m.triangles[i as usize], m.triangles[j as usize]);
            let shared = (0..3).filter(|&k| vj.contains(&vi[k])).count();
            if shared == 3 || meets_beyond_shared(m, i, j, shared) {
                out.push((i, j));
            }
        }
    }
    out
}

#[test]
fn certified_fans_skip_only_pairs_that_do_not_meet() {
    // Crumpled spheres and in-plane jittered grids (folds of every size, many of them
    // between triangles sharing a vertex or an edge), and fans wound twice: the check
    // with its fan certificates finds exactly what the pair-by-pair test finds.
    let mut rng = Rng(0x5eed_f00d_1234_5678);
    let mut cases: Vec<Mesh> = Vec::new();
    for amplitude in [0.02, 0.1, 0.3, 0.6] {
        for _ in 0..6 {
            let mut m = uv_sphere([0.0; 3], 1.0, 12, 6);
            for p in &mut m.positions {
                *p = p.map(|x| x + amplitude * (2.0 * rng.unit() - 1.0));
            }
            cases.push(m);
        }
    }
    for amplitude in [0.3, 0.6, 0.9] {
        for lift in [0.0, 0.01] {
            let mut m = heightfield([0.0, 0.0], [8.0, 8.0], 8, 8, |_, _| 0.0);
            for p in &mut m.positions {
                p[0] += amplitude * (2.0 * rng.unit() - 1.0);
                p[1] += amplitude * (2.0 * rng.unit() - 1.0);
                p[2] += lift * rng.unit();
            }
            cases.push(m);
        }
    }
    cases.push(double_fan([0, 2, 4, 1, 3]));
    cases.push(double_fan([0, 1, 2, 3, 4]));
    let (mut with_found, mut sharing_found, mut certified) = (0, 0, 0);
    for (k, m) in cases.iter().enumerate() {
        certified += fans::certified(m).iter().filter(|&&ok| ok).count();
        let got = self_intersections(m);
        assert_eq!(got, self_intersections_brute(m), "case {k}");
        with_found += usize::from(!got.is_empty());
        sharing_found += got
            .iter()
            .filter(|&&(i, j)| {
                let (a, b) = (m.triangles[i as usize], m.triangles[j as usize]);
                a.iter().any(|v| b.contains(v))
            })
            .count();
    }
    // The cases really fold: most of them intersect, many pairs around shared vertices.
    assert!(
        with_found > cases.len() / 2,
        "{with_found} of {}",
        cases.len()
    );
    assert!(sharing_found > 50, "{sharing_found}");
    // And many fans are certified, so the shortcut is taken.
    assert!(certified > 500, "{certified}");
}

/// Triangle `t` moved by motion `how`: 0 none, 1 shifted to UTM-like coordinates, 2 scaled
/// by 2^-30 (exactly), 3 rotated and shifted (contacts become near-contacts, rounded
/// differently in each triangle).
fn moved(t: [[f64; 3]; 3], how: usize) -> [[f64; 3]; 3] {
    match how {
        0 => t,
        1 => t.map(|p| p.map(|x| x + 4.5e6)),
        2 => t.map(|p| p.map(|x| x * 2f64.powi(-30))),
        _ => {
            let m = rigid_motion(
                &Mesh::new_unchecked(t.to_vec(), vec![]),
                [1.0, 2.0, 3.0],
                0.3,
                [1e3; 3],
            );
            [m.positions[0], m.positions[1], m.positions[2]]
        }
    }
}

/// The separating-axis filter never calls meeting triangles apart: integer corners in
/// 0..=3 (touching at vertices, along edges, coplanar overlaps: every exact contact),
/// at the origin, shifted to UTM-like coordinates and scaled far down; and it does find
/// most of the separated pairs it is shown.
#[test]
fn separating_axis_filter_only_answers_apart_when_apart() {
    let mut rng = Rng(0x0dd_ba11_5eed_cafe);
    let (mut apart, mut said_apart) = (0, 0);
    for round in 0..30_000 {
        let mut next = || (rng.next() % 4) as f64;
        let pa: [[f64; 3]; 3] = std::array::from_fn(|_| std::array::from_fn(|_| next()));
        let pb: [[f64; 3]; 3] = std::array::from_fn(|_| std::array::from_fn(|_| next()));
        // The same pair moved: shifted, scaled by a power of two (exactly), or rotated
        // (contacts become near-contacts, rounded differently in each triangle).
        let (pa, pb) = (moved(pa, round % 4), moved(pb, round % 4));
        let (Some(a), Some(b)) = (Tri::new(0, [0, 1, 2], pa), Tri::new(0, [10, 11, 12], pb)) else {
            continue;
        };
        let meets = tt(&a, &b) != TriTri::None;
        let says = crate::kernel::certainly_separated(&pa, &pb);
        assert!(!(meets && says), "{pa:?} {pb:?}");
        apart += usize::from(!meets);
        said_apart += usize::from(says);
    }
    assert!(
        apart > 5000 && said_apart > apart / 4,
        "{apart} {said_apart}"
    );
}

/// The separating-axis filter through a shared corner never calls a pair apart that
/// meets beyond that corner (corners on a 0..=3 grid: shared edges' points, touching,
/// overlapping, coplanar fans; as given, shifted to UTM-like coordinates, scaled, or
/// rotated, the shared corner moved alike in both), and it calls most pairs that meet only
/// there apart (touching ones excepted: a corner or edge in the other's plane), among them
/// many whose corners each lean over the other's plane.
#[test]
fn shared_corner_filter_only_answers_apart_when_apart() {
    use crate::kernel::{certainly_apart_beyond_corner, FloatPlane};
    let mut rng = Rng(0x5aa_c0a_4e4);
    let (mut apart, mut said_apart, mut leaning) = (0, 0, 0);
    for round in 0..40_000 {
        let mut next = || (rng.next() % 4) as f64;
        let mut pa: [[f64; 3]; 3] = std::array::from_fn(|_| std::array::from_fn(|_| next()));
        let mut pb: [[f64; 3]; 3] = std::array::from_fn(|_| std::array::from_fn(|_| next()));
        let (ka, kb) = (round % 3, (round / 3) % 3);
        pb[kb] = pa[ka];
        let how = round % 4;
        (pa, pb) = (moved(pa, how), moved(pb, how));
        let mut vb = [10, 11, 12];
        vb[kb] = ka as u32;
        let (Some(a), Some(b)) = (Tri::new(0, [0, 1, 2], pa), Tri::new(1, vb, pb)) else {
            continue;
        };
        if pa.iter().filter(|p| pb.contains(p)).count() != 1 {
            continue;
        }
        let beyond = meet_beyond_shared_points(&a, &b);
        let says = certainly_apart_beyond_corner(&pa, ka, &pb, kb);
        assert!(!(beyond && says), "{pa:?} {pb:?}");
        if !beyond {
            apart += 1;
            said_apart += usize::from(says);
            // Neither plane separates: some corner of each on the other's plane or
            // across it.
            let one_side = |p: &[[f64; 3]; 3], q: &[[f64; 3]; 3], l: usize| {
                let plane = FloatPlane::new(p);
                let s = [(l + 1) % 3, (l + 2) % 3].map(|j| plane.side(&q[j]));
                s[0].is_some() && s[0] == s[1]
            };
            if says && !one_side(&pa, &pb, kb) && !one_side(&pb, &pa, ka) {
                leaning += 1;
            }
        }
    }
    assert!(
        apart > 20_000 && said_apart > apart / 5 && leaning > 500,
        "{apart} {said_apart} {leaning}"
    );
}

/// Triangles square to a coordinate axis (faces of boxes) take shortcuts: a point's side
/// of the plane from one coordinate, and the direction of two such planes' line from
/// their axes. Both give the general predicates' answers ([`orient3d_sides`],
/// [`planes_line_axis`]), and pairs of them meet as the reference test (points built and
/// compared) says, on random grid triangles in random axis planes, either way round,
/// as given and moved to UTM-like coordinates.
#[test]
fn square_triangles_take_shortcuts_with_the_general_answers() {
    use crate::kernel::{orient3d_sides, planes_line_axis};
    use tritri::{intersect_by_points, line_axis};
    let mut rng = Rng(0x0500_a7ef_4ce5);
    let (mut lines, mut met, mut sides_nonzero) = (0, 0, 0);
    for round in 0..20_000 {
        let square = |rng: &mut Rng| -> [[f64; 3]; 3] {
            let k = (rng.next() % 3) as usize;
            let at = (rng.next() % 4) as f64;
            std::array::from_fn(|_| {
                std::array::from_fn(|c| if c == k { at } else { (rng.next() % 4) as f64 })
            })
        };
        let (pa, pb) = (square(&mut rng), square(&mut rng));
        let how = round % 3;
        let (pa, pb) = (moved(pa, how), moved(pb, how));
        let (Some(a), Some(b)) = (Tri::new(0, [0, 1, 2], pa), Tri::new(0, [10, 11, 12], pb)) else {
            continue;
        };
        for (x, y) in [(&a, &b), (&b, &a)] {
            let sides = x.sides_of(y);
            assert_eq!(
                sides,
                orient3d_sides(x.corners(), y.corners()),
                "{pa:?} {pb:?}"
            );
            sides_nonzero += usize::from(sides != [Sign::Zero; 3]);
            let line = line_axis(x, y);
            assert_eq!(
                line,
                planes_line_axis(x.corners(), y.corners()),
                "{pa:?} {pb:?}"
            );
            lines += usize::from(line.is_some());
        }
        let by_points = intersect_by_points(&a, &b);
        assert_eq!(tt(&a, &b), by_points, "{pa:?} {pb:?}");
        met += usize::from(by_points != TriTri::None);
    }
    assert!(
        lines > 10_000 && met > 3000 && sides_nonzero > 10_000,
        "{lines} {met} {sides_nonzero}"
    );
}

/// Triangles that are not coplanar get what they share from orientations of their
/// corners alone, pair by pair the same (points or segments, ends labelled and in
/// order) as from their points on each other's planes built and compared along the
/// planes' line. Corners on a 0..=3 grid (corners on planes, edges in planes, touching,
/// shared corners) and random in the unit cube (general position: mostly apart or
/// crossing), both as given, moved to UTM-like coordinates or rotated (near-contacts
/// rounded differently).
#[test]
fn orientations_decide_crossing_pairs_as_their_points_do() {
    use crate::kernel::orient3d_sides;
    use tritri::intersect_by_points;
    let mut rng = Rng(0x5eed_0f11_7e57);
    let (mut general, mut apart, mut touching, mut on_plane, mut met) = (0, 0, 0, 0, 0);
    for round in 0..40_000 {
        let grid = round % 2 == 0;
        let mut next = || {
            if grid {
                (rng.next() % 4) as f64
            } else {
                rng.unit()
            }
        };
        let pa: [[f64; 3]; 3] = std::array::from_fn(|_| std::array::from_fn(|_| next()));
        let pb: [[f64; 3]; 3] = std::array::from_fn(|_| std::array::from_fn(|_| next()));
        // As given, shifted, or rotated.
        let how = [0, 1, 3][(round / 2) % 3];
        let (pa, pb) = (moved(pa, how), moved(pb, how));
        let (Some(a), Some(b)) = (Tri::new(0, [0, 1, 2], pa), Tri::new(0, [10, 11, 12], pb)) else {
            continue;
        };
        let by_points = intersect_by_points(&a, &b);
        assert_eq!(tt(&a, &b), by_points, "{pa:?} {pb:?}");
        let (sa, sb) = (orient3d_sides(&pb, &pa), orient3d_sides(&pa, &pb));
        let crossing = |s: [Sign; 3]| !s.contains(&Sign::Zero) && s.iter().any(|&x| x != s[0]);
        if crossing(sa) && crossing(sb) {
            general += 1;
            apart += usize::from(by_points == TriTri::None);
            touching += usize::from(matches!(by_points, TriTri::Point(_)));
        } else if (sa.contains(&Sign::Zero) || sb.contains(&Sign::Zero))
            && sa != [Sign::Zero; 3]
            && sb != [Sign::Zero; 3]
        {
            on_plane += 1;
            met += usize::from(by_points != TriTri::None);
        }
    }
    assert!(
        general > 10_000 && apart > 4000 && touching > 300 && on_plane > 5000 && met > 2000,
        "{general} {apart} {touching} {on_plane} {met}"
    );
}

/// Coplanar triangles: the filter's axes in each triangle's plane call most coplanar
/// pairs that are apart apart (its edge-cross-edge axes all lie along the normal and
/// called none), and never a pair that touches (corners on a 0..=5 grid in one plane:
/// shared corners, corners on edges, overlaps), in the plane z = 0, shifted to UTM-like
/// coordinates, and turned into a tilted plane (rounded: near-contacts).
#[test]
fn separating_axis_filter_separates_coplanar_triangles_apart_in_their_plane() {
    let mut rng = Rng(0x005e_edc0_91a4);
    let (mut apart, mut said_apart) = (0, 0);
    for round in 0..20_000 {
        let mut next = || (rng.next() % 6) as f64;
        let mut tri = || -> [[f64; 3]; 3] { std::array::from_fn(|_| [next(), next(), 0.0]) };
        let (pa, pb) = (tri(), tri());
        let moved = |t: [[f64; 3]; 3]| match round % 3 {
            0 => t,
            1 => t.map(|p| [p[0] + 4.5e5, p[1] + 6.1e6, p[2] + 300.0]),
            _ => {
                let m = rigid_motion(
                    &Mesh::new_unchecked(t.to_vec(), vec![]),
                    [1.0, 2.0, 3.0],
                    0.7,
                    [10.0; 3],
                );
                [m.positions[0], m.positions[1], m.positions[2]]
            }
        };
        let (pa, pb) = (moved(pa), moved(pb));
        let (Some(a), Some(b)) = (Tri::new(0, [0, 1, 2], pa), Tri::new(0, [10, 11, 12], pb)) else {
            continue;
        };
        let meets = tt(&a, &b) != TriTri::None;
        let says = crate::kernel::certainly_separated(&pa, &pb);
        assert!(!(meets && says), "{pa:?} {pb:?}");
        if round % 3 != 2 {
            // Exactly coplanar: the pair is apart exactly when it does not meet.
            apart += usize::from(!meets);
            said_apart += usize::from(says);
        }
    }
    assert!(
        apart > 2000 && said_apart > apart * 9 / 10,
        "{apart} {said_apart}"
    );
}

/// A point with coordinates in 0..=4 (random), in general position (`plane` 0), in the
/// plane z = 0 (1), or in the plane x + 2y − z = 0 through grid points (2).
fn grid_point(rng: &mut Rng, plane: usize) -> [f64; 3] {
    let mut next = || (rng.next() % 5) as f64;
    let (x, y, z) = (next(), next(), next());
    match plane {
        0 => [x, y, z],
        1 => [x, y, 0.0],
        _ => [x, y, x + 2.0 * y],
    }
}

/// What [`grid_pair`] gives: corners of A and B, B's vertex ids, the two triangles.
type GridPair = ([[f64; 3]; 3], [[f64; 3]; 3], [u32; 3], Tri, Tri);

/// A pair of triangles for the pair tests, from corners `pa` and `pb`: `pb` takes `shared`
/// corners of `pa` (corner `ka + s` of `pa` as corner `kb + 2s` of `pb`, with its vertex
/// id), then both are moved by `how` ([`moved`]). The corners, `pb`'s vertex ids (`pa`'s
/// are 0, 1, 2) and both triangles; `None` where one is degenerate or, moved, they share
/// more corners or fewer.
fn grid_pair(
    pa: [[f64; 3]; 3],
    mut pb: [[f64; 3]; 3],
    (ka, kb): (usize, usize),
    shared: usize,
    how: usize,
) -> Option<GridPair> {
    let mut vb = [10, 11, 12];
    for s in 0..shared {
        let (i, j) = ((ka + s) % 3, (kb + 2 * s) % 3);
        pb[j] = pa[i];
        vb[j] = i as u32;
    }
    let (pa, pb) = (moved(pa, how), moved(pb, how));
    let (a, b) = (Tri::new(0, [0, 1, 2], pa)?, Tri::new(1, vb, pb)?);
    (pa.iter().filter(|p| pb.contains(p)).count() == shared).then_some((pa, pb, vb, a, b))
}

/// The shadow filter never calls a pair apart that meets (beyond its shared corner): corners
/// on a grid, in general position or all in one plane (the plane z = 0, or a tilted one
/// through grid points: shared corners, corners on edges, overlaps, touching), with no
/// shared corner or one, as given, shifted to UTM-like coordinates, scaled, or rotated
/// (near-contacts, rounded differently in each triangle). And it calls most coplanar pairs
/// that are apart apart, with or without a shared corner, which the planes cannot.
#[test]
fn shadow_filter_only_answers_apart_when_apart() {
    use crate::kernel::certainly_apart_projected;
    let mut rng = Rng(0x05ad_0f11_7e55);
    // [coplanar, with a shared corner]: (apart, said apart)
    let mut tally = [[(0usize, 0usize); 2]; 2];
    let mut said_not_coplanar = 0;
    for round in 0..60_000 {
        let coplanar = round % 2 == 0;
        let corner = (round / 2) % 2 == 1;
        let plane = match (coplanar, round % 3) {
            (false, _) => 0,
            (true, 0) => 1,
            (true, _) => 2,
        };
        let mut point = || grid_point(&mut rng, plane);
        let pa: [[f64; 3]; 3] = std::array::from_fn(|_| point());
        let pb: [[f64; 3]; 3] = std::array::from_fn(|_| point());
        let (ka, kb) = ((round / 4) % 3, (round / 12) % 3);
        let how = (round / 36) % 4;
        let Some((pa, pb, _, a, b)) = grid_pair(pa, pb, (ka, kb), usize::from(corner), how) else {
            continue;
        };
        let meets = meet_beyond_shared_points(&a, &b);
        let says = certainly_apart_projected(&pa, &pb, corner.then_some((ka, kb)));
        assert!(!(meets && says), "{pa:?} {pb:?} {corner}");
        if how != 3 && !meets {
            let t = &mut tally[usize::from(coplanar)][usize::from(corner)];
            t.0 += 1;
            t.1 += usize::from(says);
            said_not_coplanar += usize::from(says && !coplanar);
        }
    }
    for (corner, &(apart, said)) in tally[1].iter().enumerate() {
        assert!(
            apart > 1000 && said > apart * 9 / 10,
            "corner {corner}: {apart} {said}"
        );
    }
    // Shadows separate some pairs in general position too.
    assert!(said_not_coplanar > 1000, "{said_not_coplanar} {tally:?}");
    // Where plain floating point gets orientations wrong (near-collinear points whose
    // rounded differences lose their offsets, as in Kettner et al.'s examples): a corner
    // of one triangle on a 64 × 64 grid of ulps around a point of the other's edge, the
    // rest of it clear of the other on the far side. It meets the other exactly when it
    // is on that edge's line or over it, about half the grid, and the unguarded sign of
    // the determinant calls 120 of those apart.
    let pa = [[-5.0, -11.0, 0.0], [7.0, 12.0, 0.0], [20.0, -30.0, 0.0]];
    let mut meeting = 0;
    for i in 0..64 {
        for j in 0..64 {
            let c = [
                0.4 + i as f64 * 2f64.powi(-54),
                -0.65 + j as f64 * 2f64.powi(-53),
                0.0,
            ];
            let pb = [c, [-20.0, 10.0, 0.0], [-10.0, 20.0, 0.0]];
            let (a, b) = (
                Tri::new(0, [0, 1, 2], pa).unwrap(),
                Tri::new(1, [3, 4, 5], pb).unwrap(),
            );
            let meets = meet_beyond_shared_points(&a, &b);
            assert!(
                !(meets && certainly_apart_projected(&pa, &pb, None)),
                "{c:?}"
            );
            meeting += usize::from(meets);
        }
    }
    assert!(meeting > 1500, "{meeting}");
}

#[test]
fn self_seam_points_lie_on_both_triangles_and_match_the_two_mesh_seam() {
    use crate::kernel::{orient3d_plane, Sign};
    // Two overlapping spheres given as one mesh: the self-seam is the seam of the two.
    let a = uv_sphere([0.0; 3], 1.0, 32, 16);
    let b = rigid_motion(
        &uv_sphere([0.0; 3], 1.0, 24, 12),
        [1.0, 2.0, 3.0],
        0.3,
        [0.5, 0.1, 0.0],
    );
    let mut both = a.clone();
    both.append(&b).unwrap();
    let own = self_seam(&both, &self_intersections(&both));
    let two = intersect(&a, &b);
    assert_eq!(own.points.len(), two.points.len());
    assert_eq!(own.segments.len(), two.segments.len());
    for s in &own.sources {
        assert!(s.tri_a < s.tri_b);
        for &p in &own.segments[s.segment as usize].ends {
            for t in [s.tri_a, s.tri_b] {
                let [x, y, z] = both.corners(t as usize);
                assert_eq!(
                    orient3d_plane(&x, &y, &z, &own.exact[p as usize]),
                    Sign::Zero
                );
            }
        }
    }
    // Every seam point is on a segment, and each has two segments (closed loops).
    let mut degree = vec![0; own.points.len()];
    for s in &own.segments {
        degree[s.ends[0] as usize] += 1;
        degree[s.ends[1] as usize] += 1;
    }
    assert!(degree.iter().all(|&d| d == 2), "{degree:?}");
    // Neighbours sharing an edge or a vertex contribute nothing of what they share.
    let cube = Mesh::unit_cube();
    let seam = self_seam(&cube, &self_intersections(&cube));
    assert!(seam.points.is_empty() && seam.segments.is_empty());
}

/// Long slivers (CAD-like) against many small triangles, some touching a sliver exactly at
/// a point of its edge or crossing it: the candidate pairs, found through the slivers'
/// pieces, hold every pair that meets (exact test, brute force), in both broad phases;
/// and far fewer pairs than the slivers' boxes overlap.
#[test]
fn large_triangles_are_covered_by_their_pieces() {
    let mut rng = Rng(0x511e_e70f_ca0d);
    let mut a = Mesh::default();
    // Integer corners: the points a + i/64 (b − a) of each edge are exact.
    let slivers = [
        [
            [0.0, 0.0, 0.0],
            [1024.0, 512.0, 256.0],
            [1024.0, 520.0, 256.0],
        ],
        [
            [0.0, 1024.0, 0.0],
            [1024.0, 0.0, 512.0],
            [1016.0, 0.0, 512.0],
        ],
        [[512.0, 0.0, 1024.0], [0.0, 1024.0, 0.0], [8.0, 1024.0, 8.0]],
    ];
    for s in slivers {
        let v = a.positions.len() as u32;
        a.positions.extend(s);
        a.triangles.push([v, v + 1, v + 2]);
    }
    // Fill A with small triangles too, so that the slivers are large next to the typical.
    let small = |m: &mut Mesh, c: [f64; 3], r: f64, rng: &mut Rng| {
        let v = m.positions.len() as u32;
        for _ in 0..3 {
            let p = std::array::from_fn(|k| c[k] + r * (rng.unit() - 0.5));
            m.positions.push(p);
        }
        m.triangles.push([v, v + 1, v + 2]);
    };
    for _ in 0..300 {
        let c = std::array::from_fn(|_| 1024.0 * rng.unit());
        small(&mut a, c, 8.0, &mut rng);
    }
    let mut b = Mesh::default();
    for _ in 0..3000 {
        let c = std::array::from_fn(|_| 1024.0 * rng.unit());
        small(&mut b, c, 8.0, &mut rng);
    }
    // Triangles with a corner exactly on a sliver's edge, and ones crossing near it.
    for s in slivers {
        for i in 0..=64 {
            let f = i as f64 / 64.0;
            for (p, q) in [(0, 1), (1, 2), (2, 0)] {
                let on: [f64; 3] = std::array::from_fn(|k| s[p][k] + f * (s[q][k] - s[p][k]));
                let v = b.positions.len() as u32;
                b.positions.push(on);
                b.positions.push([on[0] + 3.0, on[1] - 2.0, on[2] + 5.0]);
                b.positions.push([on[0] - 1.0, on[1] + 4.0, on[2] + 2.0]);
                b.triangles.push([v, v + 1, v + 2]);
                small(&mut b, on, 4.0, &mut rng);
            }
        }
    }
    let typical = crate::broad::typical_size(&a, &b);
    assert!(crate::broad::cover_large(&a, typical, None).is_some());
    let meets: Vec<(u32, u32)> = (0..a.triangles.len())
        .flat_map(|i| (0..b.triangles.len()).map(move |j| (i, j)))
        .filter(|&(i, j)| {
            let (Some(x), Some(y)) = (tri(&a, i), tri(&b, j)) else {
                return false;
            };
            tt(&x, &y) != TriTri::None
        })
        .map(|(i, j)| (i as u32, j as u32))
        .collect();
    assert!(meets.len() > 500, "{}", meets.len());
    let boxes = crate::broad::overlapping_pairs(&a, &b).len();
    // A's whole tree, kept and built, is not taken: A is looked at through its pieces.
    let (kept_a, kept_b) = (Keeps::default(), Keeps::default());
    for _ in 0..2 {
        kept_a.tree.get(|| Bvh::new(&a));
        kept_b.tree.get(|| Bvh::new(&b));
    }
    assert!(kept_a.tree.is_built() && kept_b.tree.is_built());
    let without = candidate_pairs(&a, &b, false, [None, None]);
    assert_eq!(
        candidate_pairs(&a, &b, false, [Some(&kept_a), Some(&kept_b)]),
        without
    );
    for grid in [false, true] {
        let pairs = candidate_pairs(&a, &b, grid, [None, None]);
        for p in &meets {
            assert!(
                pairs.binary_search(p).is_ok(),
                "{p:?} missing (grid {grid})"
            );
        }
        assert!(pairs.windows(2).all(|w| w[0] < w[1]));
        assert!(4 * pairs.len() < boxes, "{} of {boxes}", pairs.len());
    }
}

/// The slivers at the poles of a UV sphere are a small part of what its boxes sweep: the
/// sphere is looked at whole (no stand-in, no copy of its positions); a mesh of long
/// slivers (two fans of 800) is covered, and its self-intersection check finds the
/// same (no) pairs.
#[test]
fn only_meshes_whose_large_triangles_matter_are_covered() {
    let sphere = uv_sphere([0.0; 3], 1.0, 1000, 500);
    let typical = crate::broad::typical_size(&sphere, &sphere);
    assert!(crate::broad::cover_large(&sphere, typical, None).is_none());
    // A flat fan of long slivers around the origin, and a copy of it lifted by 1e-3.
    let mut fan = Mesh::default();
    let n = 800;
    for z in [0.0, 1e-3] {
        let c = fan.positions.len() as u32;
        fan.positions.push([0.0, 0.0, z]);
        for k in 0..n {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            fan.positions.push([a.cos(), a.sin(), z]);
        }
        for k in 0..n {
            fan.triangles.push([c, c + 1 + k, c + 1 + (k + 1) % n]);
        }
    }
    let typical = crate::broad::typical_size(&fan, &fan);
    let (stand_in, parent) = crate::broad::cover_large(&fan, typical, None).expect("slivers");
    assert!(stand_in.triangles.len() > 4 * fan.triangles.len());
    assert_eq!(stand_in.triangles.len(), parent.len());
    assert!(self_intersections(&fan).is_empty());
    // Tilt one sliver of the upper fan through the lower one: exactly the pairs it crosses.
    let mut tilted = fan.clone();
    let v = tilted.triangles[n as usize + 7][1] as usize;
    tilted.positions[v][2] = -1e-3;
    let found = self_intersections(&tilted);
    assert!(!found.is_empty());
    let brute: Vec<(u32, u32)> = (0..tilted.triangles.len() as u32)
        .flat_map(|i| (i + 1..tilted.triangles.len() as u32).map(move |j| (i, j)))
        .filter(|&(i, j)| {
            let (vi, vj) = (tilted.triangles[i as usize], tilted.triangles[j as usize]);
            let shared = (0..3).filter(|&k| vj.contains(&vi[k])).count();
            meets_beyond_shared(&tilted, i, j, shared)
        })
        .collect();
    assert_eq!(found, brute);
}

/// The pair test with all its filters (planes, shadows, separating axes, the shared
/// corner's or edge's shortcuts) answers as the exact intersection of the two triangles:
/// pairs sharing no corner, one or two, on a grid in general position and in one plane
/// (z = 0 and a tilted plane; touching, overlapping, corners on edges), as given,
/// shifted to UTM-like coordinates, scaled and rotated.
#[test]
fn pair_test_answers_as_the_exact_intersection() {
    let mut rng = Rng(0x9a1e_7e57_5a4e);
    let mut counts = [[0usize; 2]; 3];
    for round in 0..90_000 {
        let shared = round % 3;
        let plane = (round / 3) % 3;
        let mut point = || grid_point(&mut rng, plane);
        let pa: [[f64; 3]; 3] = std::array::from_fn(|_| point());
        let pb: [[f64; 3]; 3] = std::array::from_fn(|_| point());
        let (ka, kb) = ((round / 9) % 3, (round / 27) % 3);
        let how = (round / 81) % 4;
        let Some((pa, pb, vb, a, b)) = grid_pair(pa, pb, (ka, kb), shared, how) else {
            continue;
        };
        let exact = meet_beyond_shared_points(&a, &b);
        let got = corners_meet_beyond_shared([(0, [0, 1, 2], pa), (1, vb, pb)], shared);
        assert_eq!(got, exact, "{pa:?} {pb:?} {vb:?}");
        counts[shared][usize::from(exact)] += 1;
    }
    // Each kind of sharing, met and apart, many times.
    assert!(counts.iter().flatten().all(|&c| c > 1000), "{counts:?}");
}

/// A mesh of slivers through their pieces: bundles of slivers side by side, running the
/// same way and the other way (pieces in opposite orders), crossing at angles and
/// through each other, a few large triangles cut into rows of pieces under small ones.
/// The pairs of triangles that pairs of first pieces stand for are all those that any
/// pair of pieces stands for, from a few times fewer pairs; the self-intersection check
/// finds what the pair-by-pair test finds.
#[test]
fn first_pairs_of_pieces_stand_for_every_pair_of_triangles() {
    let mut rng = Rng(0x5111_7e55_f1a5);
    let mut m = Mesh::default();
    let add = |m: &mut Mesh, t: [[f64; 3]; 3]| {
        let v = m.positions.len() as u32;
        m.positions.extend(t);
        m.triangles.push([v, v + 1, v + 2]);
    };
    for bundle in 0..6 {
        // A direction and a place for the bundle; slivers 10 long, 1e-3 to 1e-2 wide,
        // 0.02 apart (their pieces' boxes meet those of the next few), every other one
        // the other way.
        let dir = [1.0, 0.3 * bundle as f64 - 0.7, 0.2 * rng.unit() - 0.1];
        let o = [rng.unit(), rng.unit(), 0.5 * rng.unit()];
        for k in 0..30 {
            let y = 0.02 * k as f64 + 0.003 * rng.unit();
            let w = 1e-3 + 9e-3 * rng.unit();
            let at = |s: f64, dy: f64, dz: f64| -> [f64; 3] {
                [
                    o[0] + s * dir[0],
                    o[1] + y + dy + s * dir[1],
                    o[2] + dz + s * dir[2],
                ]
            };
            let t = if k % 2 == 0 {
                [at(0.0, 0.0, 0.0), at(10.0, w, 0.0), at(10.0, 0.0, w)]
            } else {
                [at(10.0, 0.0, 0.0), at(0.0, w, 0.0), at(0.0, 0.0, w)]
            };
            add(&mut m, t);
        }
    }
    // Large triangles with small ones scattered over them, some crossing them.
    for k in 0..3 {
        let z = 0.3 * k as f64;
        add(&mut m, [[0.0, 0.0, z], [8.0, 0.5, z], [1.0, 7.0, z + 0.2]]);
    }
    for _ in 0..400 {
        let c = [8.0 * rng.unit(), 7.0 * rng.unit(), 0.7 * rng.unit()];
        let mut r = || 0.1 * (rng.unit() - 0.5);
        let t = [
            c,
            [c[0] + r(), c[1] + r(), c[2] + r()],
            [c[0] + r(), c[1] + r(), c[2] + r()],
        ];
        add(&mut m, t);
    }
    let typical = crate::broad::typical_size(&m, &m);
    let (stand_in, parent) = crate::broad::cover_large(&m, typical, None).expect("slivers");
    let bvh = Bvh::new(&stand_in);
    let unique = |mut p: Vec<(u32, u32)>| {
        p.sort_unstable();
        p.dedup();
        p
    };
    let every = piece_pairs(&bvh, &stand_in, &parent, false, None, &|_, _| true);
    let first = piece_pairs(&bvh, &stand_in, &parent, true, None, &|_, _| true);
    let want = unique(every.clone());
    assert_eq!(unique(first.clone()), want);
    // Of the slivers' pairs with each other, about one pair of pieces each.
    let slivers = 6 * 30;
    let of_slivers = |p: &[(u32, u32)]| p.iter().filter(|&&(_, j)| j < slivers).count();
    let distinct = of_slivers(&want);
    assert!(distinct > 500, "{distinct}");
    assert!(
        of_slivers(&every) > 20 * distinct,
        "{} {distinct}",
        of_slivers(&every)
    );
    assert!(
        10 * of_slivers(&first) < 11 * distinct,
        "{} {distinct}",
        of_slivers(&first)
    );
    assert!(
        2 * first.len() < every.len(),
        "{} {}",
        first.len(),
        every.len()
    );
    assert!(!self_intersections(&m).is_empty());
    assert_eq!(self_intersections(&m), self_intersections_brute(&m));
}

/// Coplanar triangles on either side of an edge's line: the shortcut gives exactly what
/// the clipping of every edge gives, and it is taken for most such pairs. Corners on a
/// 0..=4 grid of one plane (shared corners, corners on edges and on edge lines, collinear
/// edges that overlap or only touch end to end) of the plane z = 0 and of two sloped
/// planes, shifted to UTM-like coordinates or scaled by 2^-30.
#[test]
fn coplanar_shortcut_gives_what_the_clipping_gives() {
    use super::tritri::coplanar_filtered;
    let mut rng = Rng(0x00c0_91a4_b35d);
    let (mut pairs, mut beside) = (0, 0);
    for round in 0..40_000 {
        let mut next = || (rng.next() % 5) as f64;
        let plane = |x: f64, y: f64| -> [f64; 3] {
            match round % 3 {
                0 => [x, y, 0.0],
                1 => [x, y, x + 2.0 * y],
                _ => [3.0 * x - y, y, 0.5 * x],
            }
        };
        let mut tri = || -> [[f64; 3]; 3] { std::array::from_fn(|_| plane(next(), next())) };
        let (pa, pb) = (tri(), tri());
        let how = [0, 1, 2][(round / 3) % 3];
        let (pa, pb) = (moved(pa, how), moved(pb, how));
        let (Some(a), Some(b)) = (Tri::new(0, [0, 1, 2], pa), Tri::new(0, [10, 11, 12], pb)) else {
            continue;
        };
        if crate::kernel::orient3d_sides(&pb, &pa) != [crate::kernel::Sign::Zero; 3] {
            continue; // rounding in the sloped planes' coordinates
        }
        pairs += 1;
        let ((fast, taken), (full, _)) = (
            coplanar_filtered(&a, &b, true),
            coplanar_filtered(&a, &b, false),
        );
        assert_eq!(fast, full, "{pa:?} {pb:?}");
        assert_eq!(tt(&a, &b), full, "{pa:?} {pb:?}");
        beside += usize::from(taken);
    }
    assert!(pairs > 20_000 && beside > pairs / 4, "{pairs} {beside}");
}

/// A flat grid and a bumpy one that touches it only at isolated vertices (every other
/// vertex of every other row): no segment, and each touching point listed exactly once.
#[test]
fn grids_touching_at_isolated_vertices_list_each_point_once() {
    let n = 20;
    let flat = heightfield([0.0, 0.0], [20.0, 20.0], n, n, |_, _| 0.0);
    let bumps = heightfield([0.0, 0.0], [20.0, 20.0], n, n, |x, y| {
        if x % 2.0 == 0.0 && y % 2.0 == 0.0 {
            0.0
        } else {
            1.0
        }
    });
    let seam = intersect(&flat, &bumps);
    assert!(seam.segments.is_empty());
    assert_eq!(seam.touching.len(), 11 * 11);
    let mut ids = seam.touching.clone();
    ids.sort_unstable();
    ids.dedup();
    assert_eq!(ids.len(), 11 * 11);
    for &p in &seam.touching {
        assert_eq!(seam.positions[p as usize][2], 0.0);
    }
}

/// Meshes of unlike sizes (a terrain and a small solid over it, in both orders; a box
/// resting exactly on the terrain's highest point): the larger is indexed within the
/// smaller's box and the smaller within what that kept, and the candidate pairs are
/// still every pair of overlapping boxes.
#[test]
fn meshes_of_unlike_sizes_give_every_overlapping_pair() {
    let terrain =
        crate::shapes::heightfield([-5.0, -5.0], [5.0, 5.0], 40, 40, |x, y| 0.2 * (x * y).sin());
    let ball = uv_sphere([0.3, -0.2, 0.0], 0.7, 12, 7);
    let top = terrain
        .positions
        .iter()
        .copied()
        .max_by(|p, q| p[2].total_cmp(&q[2]))
        .unwrap();
    let resting = Mesh::cuboid(
        [top[0] - 0.5, top[1] - 0.5, top[2]],
        [top[0] + 0.5, top[1] + 0.5, top[2] + 1.0],
    );
    for (a, b) in [
        (&terrain, &ball),
        (&ball, &terrain),
        (&terrain, &resting),
        (&resting, &terrain),
    ] {
        assert!(
            a.triangles.len() >= 4 * b.triangles.len()
                || b.triangles.len() >= 4 * a.triangles.len()
        );
        let want = Bvh::new(a).overlapping_pairs(a, &Bvh::new(b), b);
        assert!(!want.is_empty());
        assert_eq!(candidate_pairs(a, b, false, [None, None]), want);
        // With the whole tree kept of either mesh or both: built on the second request.
        let (kept_a, kept_b) = (Keeps::default(), Keeps::default());
        for kept in [[Some(&kept_a), None], [None, Some(&kept_b)]] {
            assert_eq!(candidate_pairs(a, b, false, kept), want);
        }
        assert!(!kept_a.tree.is_built() && !kept_b.tree.is_built());
        for kept in [
            [Some(&kept_a), None],
            [None, Some(&kept_b)],
            [Some(&kept_a), Some(&kept_b)],
        ] {
            assert_eq!(candidate_pairs(a, b, false, kept), want);
        }
        assert!(kept_a.tree.is_built() && kept_b.tree.is_built());
        assert!(kept_a.slivers.is_built() && kept_b.slivers.is_built());
    }
}

/// A zero-area triangle whose box meets several of the other mesh's triangles is left
/// out of the test and counted once, and the seam is the one without it.
#[test]
fn a_degenerate_candidate_is_counted_once() {
    let b = Mesh::cuboid([0.3; 3], [1.3; 3]);
    let clean = intersect(&Mesh::unit_cube(), &b);
    let mut a = Mesh::unit_cube();
    let n = a.positions.len() as u32;
    a.positions.extend([[0.2; 3], [0.8; 3], [0.5; 3]]);
    a.triangles.push([n, n + 1, n + 2]);
    let seam = intersect(&a, &b);
    assert!(seam.candidate_pairs > clean.candidate_pairs + 1);
    assert_eq!(seam.degenerate, [1, 0]);
    assert_eq!(seam.points, clean.points);
    assert_eq!(seam.segments, clean.segments);
}

/// [`assemble`] in one pass over all pieces, as it was written before it numbered blocks
/// side by side: the oracle for the numbering.
fn assemble_in_one_pass(pieces: &[(u32, u32, Piece)], name: impl Fn(Label) -> Label) -> Seam {
    let mut seam = Seam::default();
    let mut point_ids: FxHashMap<Label, u32> = FxHashMap::default();
    let mut seg_ids: FxHashMap<[u32; 2], u32> = FxHashMap::default();
    let mut touching = Vec::new();
    let mut id_of = |l: Label, seam: &mut Seam| -> u32 {
        *point_ids.entry(name(l)).or_insert_with(|| {
            seam.points.push(name(l));
            (seam.points.len() - 1) as u32
        })
    };
    for &(i, j, piece) in pieces {
        match piece {
            Piece::Point(l) => touching.push(l),
            Piece::Segment(s, coplanar) => {
                let (x, y) = (id_of(s[0], &mut seam), id_of(s[1], &mut seam));
                if x == y {
                    continue;
                }
                let ends = [x.min(y), x.max(y)];
                let id = *seg_ids.entry(ends).or_insert_with(|| {
                    seam.segments.push(SeamSegment { ends, coplanar });
                    (seam.segments.len() - 1) as u32
                });
                seam.segments[id as usize].coplanar &= coplanar;
                seam.sources.push(SegmentSource {
                    segment: id,
                    tri_a: i,
                    tri_b: j,
                });
            }
        }
    }
    let on_segment: FxHashSet<u32> = seam.segments.iter().flat_map(|s| s.ends).collect();
    let mut listed = FxHashSet::default();
    for l in touching {
        let id = id_of(l, &mut seam);
        if !on_segment.contains(&id) && listed.insert(id) {
            seam.touching.push(id);
        }
    }
    seam
}

/// Blocks of pieces numbered side by side, then merged in order, give the numbers of one
/// pass over all pieces: points, segments (with their coplanar flags), sources and
/// touching points, for blocks of 1, 7, 1000 and all pieces on 1 to 5 threads (one run of
/// blocks per call on one thread, four per thread on more), on shared faces (a grid with
/// itself and with a shifted copy; cubes sharing faces, whose shared faces' edges are
/// found by coplanar and by crossing pairs), crossing spheres, meshes touching at a point,
/// and a self seam's names.
#[test]
fn blocks_numbered_side_by_side_give_the_numbers_of_one_pass() {
    let pieces_of = |a: &Mesh, b: &Mesh| {
        let mut out = Vec::new();
        for (i, j) in candidate_pairs(a, b, false, [None, None]) {
            if let (Some(x), Some(y)) = (tri(a, i as usize), tri(b, j as usize)) {
                tritri::meet(&x, &y, |p| out.push((i, j, p)));
            }
        }
        out
    };
    let grid = crate::shapes::plane([0.0; 3], 1.0, 1.0, 6, 6).unwrap();
    let shifted = crate::shapes::plane([0.25, 0.1, 0.0], 1.0, 1.0, 6, 6).unwrap();
    let sphere = uv_sphere([0.0; 3], 1.0, 24, 12);
    let moved = rigid_motion(&sphere, [1.0, 2.0, 3.0], 0.7, [0.3, 0.1, 0.05]);
    // Corner to corner: the cubes touch at one point only.
    let apart = Mesh::cuboid([1.0; 3], [2.0; 3]);
    // A point numbered by a segment whose two ends name it (as a vertex's own name can)
    // and touched there: on no segment, so listed as touching.
    let mut lone_point = pieces_of(&Mesh::unit_cube(), &apart);
    let lone = Label {
        a: Feature::Vertex(100),
        b: Feature::Vertex(200),
    };
    lone_point.push((0, 0, Piece::Segment([lone, lone], false)));
    lone_point.push((0, 1, Piece::Point(lone)));
    let cases = [
        (pieces_of(&grid, &grid), false),
        (pieces_of(&grid, &shifted), false),
        (pieces_of(&sphere, &moved), false),
        (pieces_of(&Mesh::unit_cube(), &apart), false),
        (
            pieces_of(
                &Mesh::unit_cube(),
                &Mesh::cuboid([0.5, 0.0, 0.0], [1.5, 1.0, 1.0]),
            ),
            false,
        ),
        (pieces_of(&grid, &grid), true),
        (lone_point, false),
    ];
    for (k, (pieces, own)) in cases.iter().enumerate() {
        assert!(!pieces.is_empty(), "case {k}");
        let name = |l: Label| if *own { own_label(l) } else { l };
        let want = assemble_in_one_pass(pieces, name);
        assert!(k != 3 || want.touching.len() == 1, "case {k}");
        assert!(k != 6 || want.touching.len() == 2, "case {k}");
        for (size, threads) in [(1, 1), (1, 3), (7, 2), (7, 5), (1000, 2), (pieces.len(), 2)] {
            let blocks: Vec<&[(u32, u32, Piece)]> = pieces.chunks(size).collect();
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let got = pool.install(|| assemble(&blocks, name));
            assert_eq!(got.points, want.points, "case {k}, blocks of {size}");
            assert_eq!(got.segments, want.segments, "case {k}, blocks of {size}");
            assert_eq!(got.sources, want.sources, "case {k}, blocks of {size}");
            assert_eq!(got.touching, want.touching, "case {k}, blocks of {size}");
        }
    }
}

/// Non-finite corners (a public caller's unvalidated mesh) give some answer, never a
/// panic (debug assertions included): each coordinate of either triangle of a crossing
/// pair, and of a pair where one lies in the other's plane, made NaN or infinite in turn,
/// one or two at a time.
#[test]
fn non_finite_corners_give_an_answer_not_a_panic() {
    let a0 = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
    let crossing = [[0.5, 0.5, -1.0], [0.5, 0.5, 1.0], [1.5, 0.5, 0.0]];
    let touching = [[0.5, 0.5, 0.0], [3.0, 0.5, 0.0], [0.5, 0.5, 1.0]];
    let mut tried = 0;
    for b0 in [crossing, touching] {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            for i in 0..18 {
                for j in i..18 {
                    let (mut pa, mut pb) = (a0, b0);
                    for x in [i, j] {
                        let p = if x < 9 { &mut pa } else { &mut pb };
                        p[(x % 9) / 3][x % 3] = bad;
                    }
                    let (Some(a), Some(b)) =
                        (Tri::new(0, [0, 1, 2], pa), Tri::new(0, [10, 11, 12], pb))
                    else {
                        continue;
                    };
                    tried += 1;
                    let _ = tt(&a, &b);
                    tritri::meet(&a, &b, |_| {});
                }
            }
        }
    }
    assert!(tried > 100, "{tried}");
}

/// Triangles whose boxes only touch, on a plane square to an axis, are answered from
/// their corners on it ([`tritri::touching`]): the same pieces as the general test
/// (`tt`), on the candidate pairs of grids (a plane's grid with itself and with a copy
/// shifted by half a cell, boxes of 4 × 4 grids with themselves and side by side) and on
/// random triangles with corners on a small lattice (in general position, in a plane
/// square to an axis, in a tilted plane; sharing no corner, one, two or all three; as
/// given, at UTM coordinates, scaled down, rotated), where boxes touch often and corners
/// land on edges. Each answer the shortcut gives (apart, a common corner, a corner on an
/// edge) is met many times, and so is its refusal (an edge on the plane); so are
/// triangles with the same corners ([`tritri::twins`]).
#[test]
fn touching_boxes_give_the_pieces_of_the_general_test() {
    // [apart, corner at corner, corner on edge, left to the general test, twins]
    let mut seen = [0usize; 5];
    let mut check = |a: &Tri, b: &Tri| {
        let mut got = Vec::new();
        tritri::meet(a, b, |p| got.push(p));
        let mut want = Vec::new();
        tritri::pieces_of(&tt(a, b), |p| want.push(p));
        assert_eq!(got, want, "{:?} {:?}", a.corners(), b.corners());
        if let Some(t) = tritri::touching(a, b) {
            seen[match t {
                None => 0,
                Some(Label {
                    a: Vertex(_),
                    b: Vertex(_),
                }) => 1,
                Some(_) => 2,
            }] += 1;
        } else {
            seen[3] += 1;
        }
        seen[4] += usize::from(tritri::twins(a, b).is_some());
    };
    let plane = crate::shapes::plane([0.0; 3], 1.0, 1.0, 6, 6).unwrap();
    let half = crate::shapes::plane([1.0 / 12.0, 0.0, 0.0], 1.0, 1.0, 6, 6).unwrap();
    // A box with each face a 4 × 4 grid of squares cut along a diagonal.
    let cube = |lo: [f64; 3], hi: [f64; 3]| {
        let (mut positions, mut triangles) = (Vec::new(), Vec::new());
        for d in 0..3 {
            for side in [lo[d], hi[d]] {
                let (u, v) = ((d + 1) % 3, (d + 2) % 3);
                let base = positions.len() as u32;
                for i in 0..=4 {
                    for j in 0..=4 {
                        let mut p = [side; 3];
                        p[u] = lo[u] + (hi[u] - lo[u]) * f64::from(i) / 4.0;
                        p[v] = lo[v] + (hi[v] - lo[v]) * f64::from(j) / 4.0;
                        positions.push(p);
                    }
                }
                for i in 0..4 {
                    for j in 0..4 {
                        let at = |i: u32, j: u32| base + 5 * i + j;
                        triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                        triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
                    }
                }
            }
        }
        crate::weld_exact(&Mesh::new_unchecked(positions, triangles)).mesh
    };
    let (c, side) = (
        cube([0.0; 3], [1.0; 3]),
        cube([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]),
    );
    for (a, b) in [(&plane, &plane), (&plane, &half), (&c, &c), (&c, &side)] {
        for (i, j) in candidate_pairs(a, b, false, [None, None]) {
            if let (Some(x), Some(y)) = (tri(a, i as usize), tri(b, j as usize)) {
                check(&x, &y);
            }
        }
    }
    let mut rng = Rng(0x70c4_b0e5_5eed);
    for round in 0..200_000 {
        let plane = round % 3;
        let pa = [(); 3].map(|_| grid_point(&mut rng, plane));
        let pb = [(); 3].map(|_| grid_point(&mut rng, plane));
        let k = (rng.next() % 3) as usize;
        if let Some((_, _, _, a, b)) = grid_pair(pa, pb, (k, k), round % 4, (round / 12) % 4) {
            check(&a, &b);
        }
    }
    assert!(seen.iter().all(|&n| n > 300), "{seen:?}");
}

/// `n` points on an ellipse of half-axes 2 and 1, counter-clockwise, each moved in the
/// plane by up to `jitter` (fans from the first point then fold where the jitter turns a
/// point back past its neighbour, as seen from there).
fn ellipse_ring(n: usize, jitter: f64, rng: &mut Rng) -> Vec<[f64; 2]> {
    (0..n)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            let d = [2.0 * rng.unit() - 1.0, 2.0 * rng.unit() - 1.0];
            [2.0 * t.cos() + jitter * d[0], t.sin() + jitter * d[1]]
        })
        .collect()
}

#[test]
fn fanned_caps_are_certified_runs_and_folded_ones_are_not() {
    // A prism's caps fanned from one corner: the corner's fan is not certified whole (the
    // walls stand at right angles to the cap) but its cap triangles are one run. Jittered
    // outlines fold the fans (pairs around the corner overlap); the check finds exactly
    // what the pair-by-pair test finds.
    let mut rng = Rng(0x0fa2_ca95_7e11_0b5e);
    let mut folded = 0;
    for (n, jitter) in [(24, 0.0), (24, 0.2), (24, 0.5), (40, 0.3), (40, 0.8), (12, 1.0)] {
        for _ in 0..3 {
            let m = crate::test_util::fanned_prism(&ellipse_ring(n, jitter, &mut rng), 1.0);
            let got = self_intersections(&m);
            assert_eq!(got, self_intersections_brute(&m), "{n} sides, jitter {jitter}");
            folded += usize::from(!got.is_empty());
            if jitter == 0.0 {
                assert!(got.is_empty());
                let runs = fans::runs(&m);
                assert!(!fans::certified(&m)[0]);
                // Corner 0 of each bottom cap triangle [0, i + 1, i] (triangles 2n, 2n + 2, …).
                let cap: Vec<u32> = (0..n - 2).map(|k| runs[3 * (2 * n + 2 * k)]).collect();
                assert!(cap[0] != fans::NO_RUN && cap.iter().all(|&r| r == cap[0]));
                // The walls at the corner are runs of their own.
                let wall = runs[0];
                assert!(wall != fans::NO_RUN && wall != cap[0]);
            }
        }
    }
    assert!(folded >= 6, "{folded} folded prisms");
}

#[test]
fn the_self_traversal_skips_nodes_of_one_certified_run() {
    // A 400-sided fanned prism: every pair of a cap's triangles shares the corner and their
    // boxes overlap there (79,000 pairs a cap), but the nodes below which all triangles are
    // in the cap's run are settled: of those pairs only the ones in nodes that hold walls
    // too are looked at (a tree of whole triangles: a sliver's box spans the cap). (The
    // walls' pairs with the caps' long triangles remain: the check looks at those through
    // the triangles' pieces, `broad::cover_large`.)
    let n = 400;
    let m = crate::test_util::fanned_prism(&ellipse_ring(n, 0.0, &mut Rng(1)), 1.0);
    let runs = fans::runs(&m);
    let bvh = Bvh::new(&m);
    let settled = bvh.common_labels(|t| {
        let r = |k: usize| runs[3 * t as usize + k];
        [r(0), r(1), r(2), crate::bvh::NO_LABEL]
    });
    let in_caps = |settled: Option<&[crate::bvh::Labels]>| {
        let calls = std::sync::atomic::AtomicUsize::new(0);
        let keep = |i: u32, j: u32| {
            if i.min(j) >= 2 * n as u32 {
                calls.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            }
            false
        };
        bvh.self_candidates_where(&m, &keep, settled);
        calls.into_inner()
    };
    let (all, skipping) = (in_caps(None), in_caps(Some(&settled)));
    assert!(all > 2 * 70_000, "{all} pairs of cap triangles");
    assert!(8 * skipping < all, "{skipping} of {all} pairs of cap triangles");
}

/// The share of `m`'s triangles in certified patches.
fn in_patches(m: &Mesh) -> f64 {
    let (start, slots) = fans::corners_at_vertices(m);
    let p = patches::patches(m, &start, &slots);
    p.iter().filter(|&&x| x != patches::NO_PATCH).count() as f64 / p.len().max(1) as f64
}

#[test]
fn smooth_surfaces_are_certified_in_patches() {
    let bumps = heightfield([0.0, 0.0], [10.0, 10.0], 60, 60, |x, y| {
        (0.7 * x).sin() * (0.5 * y).cos()
    });
    assert_eq!(in_patches(&bumps), 1.0);
    let sphere = uv_sphere([0.3, -0.2, 0.1], 2.0, 64, 32);
    let share = in_patches(&sphere);
    assert!(share > 0.9, "{share} of a sphere's triangles in patches");
}

/// A strip of `segments` quads between radii 1 and 2 from angle 0 to `turns` full turns,
/// rising by `pitch` per turn (a flat spiral where `pitch` is 0: its turns overlap), the
/// vertex ids of each turn its own.
fn spiral_strip(turns: f64, segments: usize, pitch: f64) -> Mesh {
    let mut positions = Vec::new();
    for k in 0..=segments {
        let a = turns * std::f64::consts::TAU * k as f64 / segments as f64;
        let z = pitch * a / std::f64::consts::TAU;
        positions.push([a.cos(), a.sin(), z]);
        positions.push([2.0 * a.cos(), 2.0 * a.sin(), z]);
    }
    let mut triangles = Vec::new();
    for k in 0..segments as u32 {
        let (i, o, i2, o2) = (2 * k, 2 * k + 1, 2 * k + 2, 2 * k + 3);
        triangles.push([i, o, o2]);
        triangles.push([i, o2, i2]);
    }
    Mesh::new(positions, triangles).unwrap()
}

#[test]
fn patches_hold_no_pair_that_meets() {
    // Surfaces whose every triangle faces up but that meet themselves: flat spirals whose
    // turns overlap, strips that come round to touch their start along an edge or at a
    // point (distinct vertex ids at one position), and the folded spheres and grids of the
    // fan test. No pair of triangles in one certified patch may meet, and the check finds
    // what the pair-by-pair test finds.
    let mut rng = Rng(0x9a7c_4e5d_0b1f_2233);
    let mut cases: Vec<Mesh> = vec![
        spiral_strip(1.5, 48, 0.0),
        spiral_strip(2.0, 64, 0.0),
        spiral_strip(1.0, 40, 0.0), // back to its start: the last edge lies on the first
        spiral_strip(2.0, 64, 1e-3),
    ];
    // A strip that comes round to touch its start at one point: its last outer corner
    // moved onto the middle of its first radial edge.
    let mut touch = spiral_strip(1.0, 40, 0.0);
    let last = touch.positions.len() - 1;
    touch.positions[last] = [1.5, 0.0, 0.0];
    cases.push(touch);
    for amplitude in [0.05, 0.3] {
        for _ in 0..4 {
            let mut m = uv_sphere([0.0; 3], 1.0, 16, 8);
            for p in &mut m.positions {
                *p = p.map(|x| x + amplitude * (2.0 * rng.unit() - 1.0));
            }
            cases.push(m);
        }
    }
    for amplitude in [0.3, 0.6, 0.9] {
        let mut m = heightfield([0.0, 0.0], [8.0, 8.0], 10, 10, |_, _| 0.0);
        for p in &mut m.positions {
            p[0] += amplitude * (2.0 * rng.unit() - 1.0);
            p[1] += amplitude * (2.0 * rng.unit() - 1.0);
        }
        cases.push(m);
    }
    let mut meeting_cases = 0;
    for (k, m) in cases.iter().enumerate() {
        let (start, slots) = fans::corners_at_vertices(m);
        let patch = patches::patches(m, &start, &slots);
        let brute = self_intersections_brute(m);
        for &(i, j) in &brute {
            let (pi, pj) = (patch[i as usize], patch[j as usize]);
            assert!(
                pi == patches::NO_PATCH || pi != pj,
                "case {k}: triangles {i} and {j} meet in patch {pi}"
            );
        }
        assert_eq!(self_intersections(m), brute, "case {k}");
        meeting_cases += usize::from(!brute.is_empty());
    }
    // The spirals and the strips that come round meet themselves, as most folded cases.
    assert!(meeting_cases >= 10, "{meeting_cases} of {}", cases.len());
    // The risen spiral meets nothing and is certified in patches all the same.
    assert!(self_intersections(&cases[3]).is_empty());
    assert!(in_patches(&cases[3]) > 0.9);
}

/// Whether the self-intersection check looks at `m` through its whole triangles (grouped
/// by patch) rather than its large triangles' pieces; `None` where no triangle is large.
fn checks_whole_triangles(m: &Mesh) -> Option<bool> {
    crate::broad::large_triangles(m, crate::broad::typical_size(m, m), None)?;
    let (start, slots) = fans::corners_at_vertices(m);
    Some(whole_tree(m, &patches::patches(m, &start, &slots)).is_some())
}

/// A fine sphere (3,968 triangles, radius 1, centre at height `z`) above or through a
/// floor of two large triangles, 20 across, at height 0.
fn sphere_on_floor(z: f64) -> Mesh {
    let sphere = uv_sphere([0.1, -0.2, z], 1.0, 64, 32);
    let mut positions = sphere.positions.clone();
    let mut triangles = sphere.triangles.clone();
    let v = positions.len() as u32;
    for [x, y] in [[-10.0, -10.0], [10.0, -10.0], [10.0, 10.0], [-10.0, 10.0]] {
        positions.push([x, y, 0.0]);
    }
    triangles.extend([[v, v + 1, v + 2], [v, v + 2, v + 3]]);
    Mesh::new_unchecked(positions, triangles)
}

#[test]
fn large_triangles_are_checked_whole_unless_their_boxes_span_other_patches() {
    // Two large triangles under a fine sphere: their boxes are flat and meet only the
    // sphere's triangles that reach the floor, and the check takes the whole triangles.
    // A long cylinder of slivers along a slanted axis: each sliver's box holds much of
    // the cylinder, and the check takes the large triangles' pieces. Both ways it finds
    // exactly what the pair-by-pair test finds.
    for (z, crossing) in [(1.5, false), (0.5, true)] {
        let m = sphere_on_floor(z);
        assert_eq!(checks_whole_triangles(&m), Some(true));
        let found = self_intersections(&m);
        assert_eq!(found.is_empty(), !crossing);
        assert_eq!(found, self_intersections_brute(&m), "sphere at {z}");
    }
    let ring: Vec<[f64; 2]> = (0..120)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / 120.0;
            [a.cos(), a.sin()]
        })
        .collect();
    let upright = crate::test_util::fanned_prism(&ring, 40.0);
    let slanted = rigid_motion(&upright, [1.0, 2.0, 0.5], 0.9, [0.0; 3]);
    assert_eq!(checks_whole_triangles(&slanted), Some(false));
    let found = self_intersections(&slanted);
    assert!(found.is_empty(), "{} pairs", found.len());
    assert_eq!(found, self_intersections_brute(&slanted));
    // Dented: one wall vertex pushed through the opposite wall.
    let mut dented = slanted.clone();
    let (p, q) = (dented.positions[0], dented.positions[60]);
    dented.positions[0] = std::array::from_fn(|k| p[k] + 1.2 * (q[k] - p[k]));
    assert_eq!(checks_whole_triangles(&dented), Some(false));
    let found = self_intersections(&dented);
    assert!(!found.is_empty());
    assert_eq!(found, self_intersections_brute(&dented));
}
