//! Curtain: turn an open surface (terrain, an open boolean result) into a solid by
//! dropping vertical walls from its boundary to a horizontal floor and capping the floor.

use rustc_hash::FxHashMap;
use serde::Serialize;

use super::cap::{boundary_loops, cap_holes};
use crate::Mesh;

/// What [`curtain`] did.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct CurtainReport {
    /// Triangles reversed first so that every component faces up (a down-facing or
    /// inconsistently oriented surface would otherwise give a solid turned inside out);
    /// 0 when the surface already faced up.
    pub faced_up: usize,
    /// The floor height: lowest z of the surface minus the offset.
    pub floor: f64,
    /// Boundary loops given walls.
    pub loops: usize,
    /// Wall triangles added.
    pub wall_triangles: usize,
    /// Floor triangles added.
    pub floor_triangles: usize,
    /// Floor loops whose projection folded (fan used instead; check the result).
    pub fan_fallbacks: usize,
    /// Boundary edges that do not close into a loop, left without walls.
    pub open_boundary_edges: usize,
}

/// Drops a vertical wall from every boundary loop of `mesh` to the floor
/// `z = min z − floor_offset` and caps the floor, so that the surface becomes a closed
/// solid with outward normals (volume > 0). The surface is first oriented consistently
/// with every component facing up ([`super::orient`] with [`super::Facing::ZUp`]; the
/// report's `faced_up` counts the triangles that reversed); loops are then walled in the
/// direction the surface runs along them.
pub fn curtain(mesh: &Mesh, floor_offset: f64) -> (Mesh, CurtainReport) {
    let floor = mesh.bounds().map_or(0.0, |b| b.min[2]) - floor_offset;
    curtain_to(mesh, floor)
}

/// [`curtain`] down to the plane `z = floor` given as such (at or below the lowest point),
/// so that several surfaces can stand on the same floor exactly.
pub(crate) fn curtain_to(mesh: &Mesh, floor: f64) -> (Mesh, CurtainReport) {
    let (up, oriented) = super::orient(mesh, super::Facing::ZUp);
    let mesh = &up;
    let (loops, open) = boundary_loops(mesh);
    let mut out = mesh.clone();
    let mut below: FxHashMap<u32, u32> = FxHashMap::default();
    let mut drop = |v: u32, out: &mut Mesh| -> u32 {
        *below.entry(v).or_insert_with(|| {
            let p = mesh.positions[v as usize];
            out.positions.push([p[0], p[1], floor]);
            (out.positions.len() - 1) as u32
        })
    };
    let mut walls = 0;
    for lp in &loops {
        for i in 0..lp.len() {
            let (a, b) = (lp[i], lp[(i + 1) % lp.len()]);
            let (fa, fb) = (drop(a, &mut out), drop(b, &mut out));
            // The surface runs a -> b; the wall runs b -> a, then down.
            out.triangles.push([b, a, fa]);
            out.triangles.push([b, fa, fb]);
            walls += 2;
        }
    }
    let (capped, cap) = cap_holes(&out);
    let report = CurtainReport {
        faced_up: oriented.flipped,
        floor,
        loops: loops.len(),
        wall_triangles: walls,
        floor_triangles: cap.triangles_added,
        fan_fallbacks: cap.fan_fallbacks,
        open_boundary_edges: open,
    };
    (capped, report)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::{mesh_stats, signed_volume};
    use crate::repair::{orient, Facing};
    use crate::shapes::heightfield;

    #[test]
    fn a_down_facing_surface_is_faced_up_first() {
        // Before: the solid came out inside out (closed, negative volume).
        let m = heightfield([0.0, 0.0], [4.0, 3.0], 4, 3, |x, _| 0.5 * x + 10.0);
        let (up, r_up) = curtain(&m, 2.0);
        assert_eq!(r_up.faced_up, 0);
        let (down, r) = curtain(&m.flipped(), 2.0);
        assert_eq!(r.faced_up, m.triangles.len());
        let v = signed_volume(&down);
        assert!(mesh_stats(&down).closed);
        assert_eq!(v, signed_volume(&up));
        // Prism over 4 x 3 down to z = 8: mean height above the floor 2 + 1 = 3.
        assert!((v - 36.0).abs() < 1e-12, "{v}");
        // Half the triangles wound the other way: oriented, same solid.
        let (positions, mut triangles) = m.clone().into_parts();
        for t in triangles.iter_mut().step_by(2) {
            t.swap(1, 2);
        }
        let mixed = Mesh::new(positions, triangles).unwrap();
        let (solid, r) = curtain(&mixed, 2.0);
        assert_eq!(r.faced_up, m.triangles.len() / 2);
        assert_eq!(signed_volume(&solid), v);
    }

    #[test]
    fn tilted_plane_curtained_is_the_analytic_prism() {
        // z = 0.3 x − 0.2 y + 5 over [2, 12] x [−1, 7]; floor = min z − 10.
        let (a, b, c) = (0.3, -0.2, 5.0);
        let m = heightfield([2.0, -1.0], [12.0, 7.0], 10, 8, |x, y| a * x + b * y + c);
        let (solid, r) = curtain(&m, 10.0);
        let s = mesh_stats(&solid);
        assert_eq!(
            (s.boundary_edges, s.non_manifold_edges, s.inconsistent_edges),
            (0, 0, 0)
        );
        assert!(s.closed);
        let zmin = a * 2.0 + b * 7.0 + c;
        assert_eq!(r.floor, zmin - 10.0);
        // Prism volume = area × (z at the centroid − floor).
        let area = 10.0 * 8.0;
        let z_mid = a * 7.0 + b * 3.0 + c;
        let want = area * (z_mid - r.floor);
        assert!(
            (s.volume - want).abs() < 1e-9 * want,
            "{} vs {want}",
            s.volume
        );
        assert_eq!((r.loops, r.wall_triangles, r.fan_fallbacks), (1, 2 * 36, 0));
    }

    #[test]
    fn terrain_curtained_volume_matches_direct_integral() {
        for center in [[0.0; 3], crate::test_util::UTM] {
            let name = format!("{center:?}");
            let (t, _) = crate::test_util::terrain_and_drill(center);
            let (t, _) = orient(&crate::test_util::wound_badly(&t), Facing::ZUp);
            let (solid, r) = curtain(&t, 10.0);
            let s = mesh_stats(&solid);
            assert_eq!(
                (s.boundary_edges, s.non_manifold_edges, s.inconsistent_edges),
                (0, 0, 0),
                "{name}"
            );
            // Direct: sum over triangles of signed projected area × (mean z − floor),
            // taken relative to the first vertex for precision at UTM coordinates.
            let o = t.positions[0];
            let direct: f64 = (0..t.triangles.len())
                .map(|i| {
                    let [p, q, w] = t.corners(i).map(|v| [v[0] - o[0], v[1] - o[1], v[2]]);
                    let area =
                        0.5 * ((q[0] - p[0]) * (w[1] - p[1]) - (q[1] - p[1]) * (w[0] - p[0]));
                    area * ((p[2] + q[2] + w[2]) / 3.0 - r.floor)
                })
                .sum();
            assert!(
                (s.volume - direct).abs() < 1e-9 * direct,
                "{name}: {} vs {direct}",
                s.volume
            );
            assert!((signed_volume(&solid) - s.volume).abs() == 0.0);
            assert_eq!(
                (r.loops, r.wall_triangles, r.fan_fallbacks),
                (1, 2 * 240, 0),
                "{name}"
            );
        }
    }
}
