//! What the door makes of real data before a boolean: triangles that collapse when their
//! corners are welded (distinct vertices at one position, as UV-seamed models and
//! exports with duplicate vertices have them).

// Only its check of parents' faces is used here.
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
