//! Boundary loops and hole capping.

use rustc_hash::FxHashMap;
use serde::Serialize;

use crate::edges::EdgeTopology;
use crate::vec3::{cross, norm, sub};
use crate::Mesh;

/// The closed boundary loops of `mesh`: vertex ids in the direction the adjacent triangles
/// run along them. Boundary edges that do not close into a loop (possible only around
/// non-manifold vertices) are left out; the second value counts them.
pub fn boundary_loops(mesh: &Mesh) -> (Vec<Vec<u32>>, usize) {
    let topo = EdgeTopology::new(mesh);
    // Directed boundary half-edges a -> b, as their triangle runs.
    let mut from: FxHashMap<u32, Vec<(u32, usize)>> = FxHashMap::default();
    let mut half = Vec::new();
    for e in 0..topo.edge_count() {
        if let [u] = topo.uses_of(e) {
            let tri = mesh.triangles[u.triangle as usize];
            let k = u.corner as usize;
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            from.entry(a).or_default().push((b, half.len()));
            half.push((a, b));
        }
    }
    let mut used = vec![false; half.len()];
    let mut loops = Vec::new();
    let mut open = 0;
    for h in 0..half.len() {
        if used[h] {
            continue;
        }
        let start = half[h].0;
        let mut lp = vec![start];
        let mut at = h;
        let closed = loop {
            used[at] = true;
            let b = half[at].1;
            if b == start {
                break true;
            }
            lp.push(b);
            match from
                .get(&b)
                .and_then(|v| v.iter().find(|&&(_, i)| !used[i]))
            {
                Some(&(_, i)) => at = i,
                None => break false,
            }
        };
        if closed {
            loops.push(lp);
        } else {
            open += lp.len() - 1;
        }
    }
    (loops, open)
}

/// The centroid of a closed polygon and its Newell normal (length: twice the area of the
/// polygon projected on its best-fit plane; direction by the right-hand rule).
fn centroid_and_newell_normal(pts: &[[f64; 3]]) -> ([f64; 3], [f64; 3]) {
    let n = pts.len();
    let c = std::array::from_fn(|k| pts.iter().map(|p| p[k]).sum::<f64>() / n as f64);
    let mut nn = [0.0f64; 3];
    for i in 0..n {
        let (p, q) = (pts[i], pts[(i + 1) % n]);
        nn[0] += (p[1] - q[1]) * (p[2] + q[2]);
        nn[1] += (p[2] - q[2]) * (p[0] + q[0]);
        nn[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    (c, nn)
}

/// What [`cap_holes`] did.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct CapReport {
    /// Boundary loops found.
    pub loops: usize,
    /// Loops capped.
    pub capped: usize,
    /// Triangles added.
    pub triangles_added: usize,
    /// Loops whose projection onto their best-fit plane folded over itself, capped with a
    /// fan from one vertex instead (may self-overlap: check the result).
    pub fan_fallbacks: usize,
    /// Boundary edges that do not close into a loop, left as they are.
    pub open_boundary_edges: usize,
}

/// Caps every boundary loop of `mesh` with triangles (orientation matching the adjacent
/// triangles), so that a mesh with holes becomes closed. Each loop is projected onto the
/// plane of its Newell normal (non-planar loops too) and triangulated by ear clipping
/// (`earcut`); where that projection folds, a fan is used and counted.
pub fn cap_holes(mesh: &Mesh) -> (Mesh, CapReport) {
    cap_loops(mesh, |_| true)
}

/// [`cap_holes`] for the small holes only: loops whose bounding box has a diagonal of at
/// most `max_size` (force-closing the gaps left after other repairs, without capping a
/// terrain's outer rim). The others are left open; `loops − capped` counts them.
pub fn cap_small_holes(mesh: &Mesh, max_size: f64) -> (Mesh, CapReport) {
    cap_loops(mesh, |pts| {
        let (lo, hi) = pts.iter().fold(
            ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
            |(lo, hi), p| {
                (
                    std::array::from_fn(|k| lo[k].min(p[k])),
                    std::array::from_fn(|k| hi[k].max(p[k])),
                )
            },
        );
        norm(&sub(&hi, &lo)) <= max_size
    })
}

/// Caps the boundary loops whose corner positions `keep` accepts.
fn cap_loops(mesh: &Mesh, keep: impl Fn(&[[f64; 3]]) -> bool) -> (Mesh, CapReport) {
    let (loops, open) = boundary_loops(mesh);
    let mut out = mesh.clone();
    let mut report = CapReport {
        loops: loops.len(),
        open_boundary_edges: open,
        ..CapReport::default()
    };
    let mut earcut = earcut::Earcut::new();
    let mut idx: Vec<u32> = Vec::new();
    for lp in &loops {
        // The cap runs against the loop so that it agrees with the neighbouring triangles.
        let poly: Vec<u32> = lp.iter().rev().copied().collect();
        let pts: Vec<[f64; 3]> = poly.iter().map(|&v| mesh.positions[v as usize]).collect();
        let n = pts.len();
        if n < 3 || !keep(&pts) {
            continue;
        }
        let (c, nn) = centroid_and_newell_normal(&pts);
        // An orthonormal basis (u, v) of the Newell plane with u x v = normal. The normal
        // is divided by its largest component before its length is taken: its squares
        // overflow beyond about 2^256 coordinates and underflow below 2^-256.
        let big = nn.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let mut tris: Vec<[u32; 3]> = Vec::new();
        if big > 0.0 && big.is_finite() {
            let nn = nn.map(|x| x / big);
            let len = norm(&nn);
            let nz = nn.map(|x| x / len);
            let helper = if nz[0].abs() < 0.9 {
                [1.0, 0.0, 0.0]
            } else {
                [0.0, 1.0, 0.0]
            };
            let u = cross(&helper, &nz);
            let ul = norm(&u);
            let u = u.map(|x| x / ul);
            let v = cross(&nz, &u);
            let flat: Vec<[f64; 2]> = pts
                .iter()
                .map(|p| {
                    let d = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
                    [
                        d[0] * u[0] + d[1] * u[1] + d[2] * u[2],
                        d[0] * v[0] + d[1] * v[1] + d[2] * v[2],
                    ]
                })
                .collect();
            earcut.earcut(flat.iter().copied(), &[] as &[u32], &mut idx);
            if idx.len() == 3 * (n - 2) {
                for t in idx.chunks_exact(3) {
                    let (a, b, cc) = (
                        flat[t[0] as usize],
                        flat[t[1] as usize],
                        flat[t[2] as usize],
                    );
                    let area = (b[0] - a[0]) * (cc[1] - a[1]) - (b[1] - a[1]) * (cc[0] - a[0]);
                    let t = if area < 0.0 {
                        [t[0], t[2], t[1]]
                    } else {
                        [t[0], t[1], t[2]]
                    };
                    tris.push(t.map(|i| poly[i as usize]));
                }
            }
        }
        if tris.is_empty() {
            report.fan_fallbacks += 1;
            tris = (1..n - 1)
                .map(|i| [poly[0], poly[i], poly[i + 1]])
                .collect();
        }
        report.capped += 1;
        report.triangles_added += tris.len();
        out.triangles.extend(tris);
    }
    (out, report)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::mesh_stats;

    #[test]
    fn cube_missing_a_face_capped_has_volume_exactly_one() {
        for drop in [0, 2, 4, 6, 8, 10] {
            let mut m = Mesh::unit_cube();
            m.triangles.drain(drop..drop + 2);
            let (loops, open) = boundary_loops(&m);
            assert_eq!((loops.len(), loops[0].len(), open), (1, 4, 0));
            let (c, r) = cap_holes(&m);
            let s = mesh_stats(&c);
            assert_eq!(
                (s.boundary_edges, s.non_manifold_edges, s.inconsistent_edges),
                (0, 0, 0),
                "face {drop}"
            );
            assert_eq!(s.volume, 1.0, "face {drop}");
            assert_eq!((r.capped, r.triangles_added, r.fan_fallbacks), (1, 2, 0));
        }
    }

    #[test]
    fn caps_at_extreme_scales_are_the_unit_caps_scaled() {
        // Before: at 2^300 the Newell normal's squared length overflowed and the cap came
        // out reversed; at 2^-330 it underflowed and the cap fell back to a fan.
        let mut m = Mesh::unit_cube();
        m.triangles.drain(10..12);
        let (unit, _) = cap_holes(&m);
        for k in [-330, -300, 300, 330] {
            let f = 2f64.powi(k);
            let mut scaled = m.clone();
            scaled.positions.iter_mut().flatten().for_each(|x| *x *= f);
            let (c, r) = cap_holes(&scaled);
            assert_eq!((r.capped, r.fan_fallbacks), (1, 0), "2^{k}");
            assert_eq!(c.triangles, unit.triangles, "2^{k}");
        }
    }

    #[test]
    fn non_planar_hole_in_a_sphere_is_capped() {
        // Remove the triangles near a point on the equator: the rim lies on the sphere,
        // not in a plane.
        let full = crate::shapes::uv_sphere([0.0; 3], 1.0, 24, 12);
        let mut m = full.clone();
        m.triangles.retain(|t| {
            let c: [f64; 3] = std::array::from_fn(|k| {
                t.iter()
                    .map(|&v| full.positions[v as usize][k])
                    .sum::<f64>()
                    / 3.0
            });
            (c[0] - 1.0).powi(2) + c[1].powi(2) + (c[2] - 0.1).powi(2) > 0.45f64.powi(2)
        });
        let removed = full.triangles.len() - m.triangles.len();
        assert!(removed > 10, "{removed}");
        let (loops, open) = boundary_loops(&m);
        assert_eq!((loops.len(), open), (1, 0));
        let rim: Vec<[f64; 3]> = loops[0].iter().map(|&v| m.positions[v as usize]).collect();
        // Non-planar: the rim strays from its Newell plane by more than 1 % of the radius.
        let (c, nn) = centroid_and_newell_normal(&rim);
        let l = (nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]).sqrt();
        let off = rim
            .iter()
            .map(|p| ((0..3).map(|k| (p[k] - c[k]) * nn[k]).sum::<f64>() / l).abs())
            .fold(0.0, f64::max);
        assert!(off > 0.01, "rim is planar: {off}");
        let (c, r) = cap_holes(&m);
        let s = mesh_stats(&c);
        assert_eq!(
            (s.boundary_edges, s.non_manifold_edges, s.inconsistent_edges),
            (0, 0, 0)
        );
        assert_eq!(
            (r.loops, r.capped, r.fan_fallbacks, r.open_boundary_edges),
            (1, 1, 0, 0)
        );
        assert_eq!(r.triangles_added, loops[0].len() - 2);
        // A shallow cap: slightly less volume than the full sphere, outward-facing.
        let full_v = crate::measure::signed_volume(&full);
        assert!(
            s.volume < full_v && s.volume > 0.95 * full_v,
            "{} vs {full_v}",
            s.volume
        );
    }
}
