//! Consistent orientation: every triangle is flipped, where needed, to agree with its
//! neighbours across manifold edges, component by component; then each component is turned
//! to face the way asked for.

use std::collections::VecDeque;

use serde::{Deserialize, Serialize};

use crate::edges::EdgeTopology;
use crate::Mesh;

/// Which way each component should face once it is consistent.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Facing {
    /// Keep the orientation most of the component's triangles already had (fewest flips).
    Majority,
    /// Normals up: the component's signed area projected on the XY plane is positive
    /// (terrain, open surfaces). Components with zero projected area keep the majority.
    ZUp,
    /// Outward: closed components get a positive volume; open ones keep the majority.
    Outward,
}

impl Facing {
    /// Every facing.
    pub const ALL: [Facing; 3] = [Facing::Majority, Facing::ZUp, Facing::Outward];

    /// The facing's name: `majority`, `z-up`, `outward`.
    pub fn name(self) -> &'static str {
        match self {
            Facing::Majority => "majority",
            Facing::ZUp => "z-up",
            Facing::Outward => "outward",
        }
    }
}

by_name!(Facing, "facing");

/// What [`orient`] did.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct OrientReport {
    /// Triangles whose orientation was reversed.
    pub flipped: usize,
    /// Orientation-connected components (split at non-manifold edges).
    pub components: usize,
    /// Manifold edges that could not be made consistent (the surface is not orientable
    /// there, e.g. a Möbius strip); each is counted once.
    pub conflicting_edges: usize,
    /// Edges with more than two triangles, across which orientation is not propagated.
    pub non_manifold_edges: usize,
}

/// Makes the orientation of `mesh` consistent across every manifold edge
/// where the surface allows it, facing each component as `facing` asks. Vertices and the
/// order of triangles are unchanged; only corner order changes.
pub fn orient(mesh: &Mesh, facing: Facing) -> (Mesh, OrientReport) {
    let n = mesh.triangles.len();
    let topo = EdgeTopology::new(mesh);
    let mut flip = vec![false; n];
    let mut comp = vec![u32::MAX; n];
    let mut report = OrientReport::default();
    let mut conflict_edge = vec![false; topo.edge_count()];
    for e in 0..topo.edge_count() {
        if topo.uses_of(e).len() > 2 {
            report.non_manifold_edges += 1;
        }
    }
    let mut queue = VecDeque::new();
    let mut members: Vec<Vec<u32>> = Vec::new();
    for start in 0..n {
        if comp[start] != u32::MAX {
            continue;
        }
        let c = members.len() as u32;
        members.push(vec![start as u32]);
        comp[start] = c;
        queue.push_back(start as u32);
        while let Some(t) = queue.pop_front() {
            for (k, &e) in topo.triangle_edges[t as usize].iter().enumerate() {
                if e == EdgeTopology::NO_EDGE {
                    continue;
                }
                let uses = topo.uses_of(e as usize);
                if uses.len() != 2 {
                    continue;
                }
                let (me, other) = if uses[0].triangle == t && uses[0].corner as usize == k {
                    (uses[0], uses[1])
                } else {
                    (uses[1], uses[0])
                };
                let u = other.triangle as usize;
                // Consistent: the two run along the edge in opposite directions, after flips.
                let want_flip = flip[t as usize] ^ (me.forward == other.forward);
                if comp[u] == u32::MAX {
                    comp[u] = c;
                    flip[u] = want_flip;
                    members[c as usize].push(u as u32);
                    queue.push_back(u as u32);
                } else if flip[u] != want_flip && !conflict_edge[e as usize] {
                    conflict_edge[e as usize] = true;
                    report.conflicting_edges += 1;
                }
            }
        }
    }
    report.components = members.len();
    let oriented = |t: usize, f: bool| {
        let [a, b, c] = mesh.triangles[t];
        if f {
            [a, c, b]
        } else {
            [a, b, c]
        }
    };
    for tris in &members {
        let majority_keep = 2 * tris.iter().filter(|&&t| !flip[t as usize]).count() >= tris.len();
        // Decide whether to reverse the whole component relative to the current choice.
        let reverse = match facing {
            Facing::Majority => !majority_keep,
            Facing::ZUp | Facing::Outward => {
                let sub: Vec<[u32; 3]> = tris
                    .iter()
                    .map(|&t| oriented(t as usize, flip[t as usize]))
                    .collect();
                let sub = Mesh::new_unchecked(mesh.positions.clone(), sub);
                let measure = if facing == Facing::ZUp {
                    signed_projected_xy(&sub)
                } else if EdgeTopology::new(&sub).is_closed() {
                    crate::measure::signed_volume(&sub)
                } else {
                    0.0
                };
                if measure == 0.0 {
                    !majority_keep
                } else {
                    measure < 0.0
                }
            }
        };
        if reverse {
            for &t in tris {
                flip[t as usize] = !flip[t as usize];
            }
        }
    }
    report.flipped = flip.iter().filter(|&&f| f).count();
    let triangles = (0..n).map(|t| oriented(t, flip[t])).collect();
    (
        Mesh::new_unchecked(mesh.positions.clone(), triangles),
        report,
    )
}

/// Signed area of the projection on the XY plane (positive where triangles face +z).
fn signed_projected_xy(m: &Mesh) -> f64 {
    (0..m.triangles.len())
        .map(|t| {
            let [a, b, c] = m.corners(t);
            0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::mesh_stats;
    use crate::shapes::{heightfield, uv_sphere};

    #[test]
    fn kirra_terrain_becomes_consistent_and_faces_up() {
        // Exactly vertical triangles: the UTM copy is separately rounded and has one more.
        for (name, vertical) in [("kirra_terrain.obj", 8), ("kap_terrain.obj", 9)] {
            let Some(t) = crate::test_util::shared_data(name) else {
                return;
            };
            assert_eq!(mesh_stats(&t).inconsistent_edges, 46);
            let (o, r) = orient(&t, Facing::ZUp);
            let s = mesh_stats(&o);
            assert_eq!(
                (s.inconsistent_edges, s.boundary_edges, s.triangles),
                (0, 560, 11200),
                "{name}"
            );
            assert_eq!(
                (r.components, r.conflicting_edges, r.non_manifold_edges),
                (1, 0, 0)
            );
            // The file has no down-facing triangle, but 43 of its 46 inconsistent edges are
            // folds: two up-facing neighbours overlapping in plan view. Consistency then
            // forces one side of each fold down: exactly 22 triangles, while the surface as
            // a whole faces up. (Removing the overlaps is a separate repair step.)
            use crate::kernel::{orient2d, Point, Sign};
            let up: Vec<Sign> = (0..o.triangles.len())
                .map(|t| {
                    let [a, b, c] = o.corners(t).map(Point::Explicit);
                    orient2d(&a, &b, &c, 2)
                })
                .collect();
            assert_eq!(
                up.iter().filter(|&&z| z == Sign::Negative).count(),
                22,
                "{name}"
            );
            // The only triangles reversed are those: nothing else was touched.
            assert_eq!(r.flipped, 22, "{name}");
            for (i, z) in up.iter().enumerate() {
                assert_eq!(
                    *z == Sign::Negative,
                    o.triangles[i] != t.triangles[i],
                    "{name} triangle {i}"
                );
            }
            assert_eq!(
                up.iter().filter(|&&z| z == Sign::Zero).count(),
                vertical,
                "{name}"
            );
            assert!(
                signed_projected_xy(&o)
                    > 0.99 * crate::measure::projected_area(&o, crate::measure::Plane::XY)
            );
        }
    }

    #[test]
    fn scrambled_sphere_turns_outward() {
        let s = uv_sphere([0.0; 3], 1.0, 24, 12);
        let mut bad = s.flipped();
        for t in (0..bad.triangles.len()).step_by(3) {
            let [a, b, c] = bad.triangles[t];
            bad.triangles[t] = [a, c, b];
        }
        assert!(mesh_stats(&bad).inconsistent_edges > 0);
        let (o, r) = orient(&bad, Facing::Outward);
        let st = mesh_stats(&o);
        assert_eq!((st.inconsistent_edges, r.conflicting_edges), (0, 0));
        assert_eq!(o.triangles, s.triangles);
        // Majority keeps the (inward) orientation most triangles had.
        let (m, _) = orient(&bad, Facing::Majority);
        assert_eq!(m.triangles, s.flipped().triangles);
    }

    #[test]
    fn downward_grid_flips_up_and_mobius_strip_reports_its_seam() {
        let g = heightfield([0.0, 0.0], [4.0, 4.0], 4, 4, |x, _| 0.1 * x).flipped();
        let (o, r) = orient(&g, Facing::ZUp);
        assert_eq!(r.flipped, 32);
        assert_eq!(o.triangles, g.flipped().triangles);
        // A Möbius strip: a band of quads whose ends are joined with a half twist.
        let n = 12u32;
        let mut positions = Vec::new();
        for i in 0..n {
            let th = 2.0 * std::f64::consts::PI * f64::from(i) / f64::from(n);
            for s in [-0.3, 0.3] {
                let w = s * (th / 2.0).cos();
                positions.push([
                    (1.0 + w) * th.cos(),
                    (1.0 + w) * th.sin(),
                    s * (th / 2.0).sin(),
                ]);
            }
        }
        let mut triangles = Vec::new();
        for i in 0..n {
            let (a, b) = (2 * i, 2 * i + 1);
            let (c, d) = if i + 1 < n {
                (2 * i + 2, 2 * i + 3)
            } else {
                (1, 0)
            }; // the twist
            triangles.push([a, c, b]);
            triangles.push([b, c, d]);
        }
        let m = Mesh::new_unchecked(positions, triangles);
        let (_, r) = orient(&m, Facing::Majority);
        assert_eq!((r.components, r.conflicting_edges), (1, 1));
        assert_eq!(
            mesh_stats(&orient(&m, Facing::Majority).0).inconsistent_edges,
            1
        );
    }
}
