//! Degenerate and sliver triangle removal without opening cracks: a bad triangle goes
//! away by collapsing its shortest edge (needles) or by flipping its longest edge into the
//! neighbour across it (caps), never by simply deleting it from a surface.

use serde::{Deserialize, Serialize};

use crate::measure::{is_degenerate, signed_volume};
use crate::vec3::{cross, dot, norm, sub};
use crate::Mesh;

/// Which triangles [`remove_degenerates`] removes. The default removes exactly the
/// zero-area triangles (decided exactly) and nothing else.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DegenerateOptions {
    /// Triangles whose area is at most this are removed as well (0: only zero area).
    pub min_area: f64,
    /// Triangles whose aspect — longest edge divided by the smallest height, about 1.15 for
    /// an equilateral triangle — exceeds this are removed as well (`None`: off).
    pub max_aspect: Option<f64>,
}

impl Default for DegenerateOptions {
    fn default() -> Self {
        DegenerateOptions {
            min_area: 0.0,
            max_aspect: None,
        }
    }
}

impl DegenerateOptions {
    /// The smallest aspect a triangle can have (an equilateral triangle's, 2/√3): a
    /// `max_aspect` below it would remove every triangle.
    pub const MIN_ASPECT: f64 = 1.154_700_538_379_251_5;

    /// Checks the thresholds: `min_area` a finite area ≥ 0, `max_aspect` a finite number
    /// at least [`Self::MIN_ASPECT`]. Anything else is an error, not a mesh emptied.
    pub fn validate(&self) -> crate::Result<()> {
        if !(self.min_area.is_finite() && self.min_area >= 0.0) {
            return Err(crate::Error::InvalidParameter(format!(
                "the minimum area must be a finite number >= 0, got {}",
                self.min_area
            )));
        }
        if let Some(a) = self.max_aspect {
            if !(a.is_finite() && a >= Self::MIN_ASPECT) {
                return Err(crate::Error::InvalidParameter(format!(
                    "the maximum aspect must be a finite number >= {:.4} (an equilateral \
                     triangle's: anything smaller removes every triangle), got {a}",
                    Self::MIN_ASPECT
                )));
            }
        }
        Ok(())
    }
}

/// What [`remove_degenerates`] did.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct DegenerateReport {
    /// Bad triangles at the start (zero area, or beyond the thresholds).
    pub found: usize,
    /// Triangles naming one vertex twice, dropped (they cover nothing and hide no edge).
    pub repeated_vertex: usize,
    /// Edges collapsed (needles): both end vertices became one, removing the needle and
    /// its neighbour across that edge.
    pub collapsed_edges: usize,
    /// Collapses that moved a vertex (needles whose edge had non-zero length, only under
    /// the thresholds): the surface changed by at most that edge's length.
    pub vertices_moved: usize,
    /// Edges flipped (caps): the cap and its neighbour across its longest edge became two
    /// triangles split at the cap's far vertex. Exact for zero-area caps.
    pub flipped_edges: usize,
    /// Bad triangles on the boundary with no neighbour to flip into, dropped (the
    /// boundary then runs along their two other edges).
    pub boundary_dropped: usize,
    /// Triangles fewer than in the input (every removal above, net).
    pub triangles_removed: usize,
    /// Bad triangles left: no collapse or flip possible without making an edge
    /// non-manifold, folding a neighbour over, or creating another degenerate triangle.
    pub left: usize,
    /// Fixes that changed the shape of the surface (only under the thresholds): collapses
    /// that moved a vertex, and flips or boundary drops of triangles with non-zero area.
    /// 0 when every fix was exact.
    pub shape_changes: usize,
    /// Signed volume of the result minus that of the input (meaningful for closed
    /// meshes); 0 when every fix was exact.
    pub volume_change: f64,
}

/// Passes over the bad triangles; each pass touches every vertex at most once.
const MAX_PASSES: usize = 16;

/// Edge lengths of a triangle: edge `k` runs from corner `k` to corner `k + 1`.
fn edge_lengths(p: &[[f64; 3]; 3]) -> [f64; 3] {
    std::array::from_fn(|k| norm(&sub(&p[(k + 1) % 3], &p[k])))
}

fn normal(p: &[[f64; 3]; 3]) -> [f64; 3] {
    cross(&sub(&p[1], &p[0]), &sub(&p[2], &p[0]))
}

/// The mesh whose degenerate triangles are collapsed: its triangles (dead ones kept in
/// place until the end) and the triangles around each vertex.
struct Collapser<'a> {
    positions: &'a [[f64; 3]],
    tris: Vec<[u32; 3]>,
    alive: Vec<bool>,
    /// Vertex -> triangles using it (alive or not; filtered on use).
    around: Vec<Vec<u32>>,
    touched: Vec<bool>,
}

impl Collapser<'_> {
    fn corners(&self, t: &[u32; 3]) -> [[f64; 3]; 3] {
        t.map(|v| self.positions[v as usize])
    }

    fn live_around(&self, v: u32) -> impl Iterator<Item = u32> + '_ {
        self.around[v as usize]
            .iter()
            .copied()
            .filter(|&t| self.alive[t as usize])
    }

    /// Live triangles using both `a` and `b`.
    fn sharing(&self, a: u32, b: u32) -> Vec<u32> {
        self.live_around(a)
            .filter(|&t| self.tris[t as usize].contains(&b))
            .collect()
    }

    fn neighbours(&self, v: u32) -> Vec<u32> {
        let mut n: Vec<u32> = self
            .live_around(v)
            .flat_map(|t| self.tris[t as usize])
            .filter(|&w| w != v)
            .collect();
        n.sort_unstable();
        n.dedup();
        n
    }

    fn is_boundary_edge(&self, a: u32, b: u32) -> bool {
        self.sharing(a, b).len() == 1
    }

    fn is_boundary_vertex(&self, v: u32) -> bool {
        self.neighbours(v)
            .into_iter()
            .any(|w| self.is_boundary_edge(v, w))
    }

    fn add(&mut self, t: [u32; 3]) {
        let id = self.tris.len() as u32;
        self.tris.push(t);
        self.alive.push(true);
        for v in t {
            self.around[v as usize].push(id);
        }
    }

    fn touch(&mut self, t: u32) {
        for v in self.tris[t as usize] {
            self.touched[v as usize] = true;
        }
    }

    /// Collapses edge `keep`–`gone` onto `keep`; `None` (nothing changed) when the link
    /// condition fails or a surviving triangle would fold over or become degenerate.
    fn collapse(&mut self, keep: u32, gone: u32) -> Option<usize> {
        let shared = self.sharing(keep, gone);
        if shared.is_empty() || shared.len() > 2 {
            return None;
        }
        // Link condition: the common neighbours are exactly the far vertices of the
        // triangles on the edge; a boundary vertex pair must share a boundary edge.
        let mut far: Vec<u32> = shared
            .iter()
            .map(|&t| {
                let tri = self.tris[t as usize];
                tri.into_iter()
                    .find(|&v| v != keep && v != gone)
                    .unwrap_or(keep)
            })
            .collect();
        far.sort_unstable();
        let (nk, ng) = (self.neighbours(keep), self.neighbours(gone));
        let common: Vec<u32> = nk.iter().copied().filter(|v| ng.contains(v)).collect();
        if common != far {
            return None;
        }
        if shared.len() == 2 && self.is_boundary_vertex(keep) && self.is_boundary_vertex(gone) {
            return None;
        }
        let moves = self.positions[keep as usize] != self.positions[gone as usize];
        let others: Vec<u32> = self
            .live_around(gone)
            .filter(|t| !shared.contains(t))
            .collect();
        for &t in &others {
            let old = self.tris[t as usize];
            let new = old.map(|v| if v == gone { keep } else { v });
            let (po, pn) = (self.corners(&old), self.corners(&new));
            if is_degenerate(pn[0], pn[1], pn[2]) {
                return None;
            }
            if moves && dot(&normal(&po), &normal(&pn)) <= 0.0 {
                return None;
            }
        }
        for &t in shared.iter().chain(&others) {
            self.touch(t);
        }
        for &t in &shared {
            self.alive[t as usize] = false;
        }
        for t in others {
            let tri = &mut self.tris[t as usize];
            for v in tri.iter_mut() {
                if *v == gone {
                    *v = keep;
                }
            }
            self.around[keep as usize].push(t);
        }
        Some(usize::from(moves))
    }

    /// Flips the edge of triangle `t` from corner `k` to `k + 1` into the neighbour
    /// across it. `Some(true)`: flipped; `Some(false)`: a boundary edge, `t` dropped;
    /// `None`: nothing changed.
    fn flip(&mut self, t: u32, k: usize, exact_cap: bool) -> Option<bool> {
        let tri = self.tris[t as usize];
        let (a, b, c) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
        let across: Vec<u32> = self.sharing(a, b).into_iter().filter(|&u| u != t).collect();
        match across.as_slice() {
            [] => {
                self.touch(t);
                self.alive[t as usize] = false;
                Some(false)
            }
            &[n] => {
                let nt = self.tris[n as usize];
                // The neighbour must run b -> a (consistent orientation).
                let j = (0..3).find(|&j| nt[j] == b && nt[(j + 1) % 3] == a)?;
                let d = nt[(j + 2) % 3];
                if d == c || self.neighbours(c).contains(&d) {
                    return None; // the new edge c–d exists already
                }
                let (t1, t2) = ([a, d, c], [c, d, b]);
                let (p1, p2) = (self.corners(&t1), self.corners(&t2));
                if is_degenerate(p1[0], p1[1], p1[2]) || is_degenerate(p2[0], p2[1], p2[2]) {
                    return None;
                }
                if !exact_cap {
                    let old = normal(&self.corners(&nt));
                    if dot(&old, &normal(&p1)) <= 0.0 || dot(&old, &normal(&p2)) <= 0.0 {
                        return None;
                    }
                }
                self.touch(t);
                self.touch(n);
                self.alive[t as usize] = false;
                self.alive[n as usize] = false;
                self.add(t1);
                self.add(t2);
                Some(true)
            }
            _ => None,
        }
    }
}

/// Removes zero-area triangles (exact) and, where `opts` asks, small or needle-like ones,
/// keeping the surface closed where it was: needles (a short edge) by collapsing that edge,
/// caps (a vertex near the opposite edge) by flipping the long edge into the neighbour
/// across it, which splits that neighbour at the cap's vertex — exact when the cap has
/// zero area. A zero-area triangle whose shortest edge has positive length is always a
/// cap; repeated-vertex triangles are dropped. Repeats in passes, since one fix can make
/// another possible; what stays bad is counted in [`DegenerateReport::left`].
/// Vertices are kept (unused ones included): positions never change.
pub fn remove_degenerates(mesh: &Mesh, opts: &DegenerateOptions) -> (Mesh, DegenerateReport) {
    let positions = &mesh.positions;
    let bad = |t: &[u32; 3]| -> bool {
        let p = t.map(|v| positions[v as usize]);
        if t[0] == t[1] || t[1] == t[2] || t[2] == t[0] || is_degenerate(p[0], p[1], p[2]) {
            return true;
        }
        let area2 = norm(&normal(&p));
        let longest = edge_lengths(&p).into_iter().fold(0.0, f64::max);
        area2 / 2.0 <= opts.min_area
            || opts
                .max_aspect
                .is_some_and(|m| longest * longest / area2 > m)
    };
    let mut report = DegenerateReport {
        found: mesh.triangles.iter().filter(|t| bad(t)).count(),
        ..DegenerateReport::default()
    };
    // Without thresholds only exact fixes are made: no vertex moves.
    let may_move = opts.min_area > 0.0 || opts.max_aspect.is_some();
    let mut tris: Vec<[u32; 3]> = Vec::with_capacity(mesh.triangles.len());
    for t in &mesh.triangles {
        if t[0] == t[1] || t[1] == t[2] || t[2] == t[0] {
            report.repeated_vertex += 1;
        } else {
            tris.push(*t);
        }
    }
    // Flips and boundary drops of triangles with non-zero area (shape changes).
    let mut area_fixes = 0;
    for _ in 0..MAX_PASSES {
        let todo: Vec<u32> = (0..tris.len() as u32)
            .filter(|&t| bad(&tris[t as usize]))
            .collect();
        if todo.is_empty() {
            break;
        }
        let mut around = vec![Vec::new(); positions.len()];
        for (i, t) in tris.iter().enumerate() {
            for &v in t {
                around[v as usize].push(i as u32);
            }
        }
        let mut w = Collapser {
            positions,
            alive: vec![true; tris.len()],
            tris,
            around,
            touched: vec![false; positions.len()],
        };
        let mut changed = false;
        for t in todo {
            let tri = w.tris[t as usize];
            if !w.alive[t as usize] || tri.iter().any(|&v| w.touched[v as usize]) {
                continue;
            }
            let p = w.corners(&tri);
            let len = edge_lengths(&p);
            let by_len = |x: &usize, y: &usize| len[*x].total_cmp(&len[*y]);
            let (short, long) = (
                (0..3).min_by(by_len).unwrap_or(0),
                (0..3).max_by(by_len).unwrap_or(0),
            );
            let exact_zero = is_degenerate(p[0], p[1], p[2]);
            let needle = len[short] == 0.0 || (!exact_zero && len[short] < len[long] / 3.0);
            let mut collapse = |w: &mut Collapser| {
                let (u, v) = (tri[short], tri[(short + 1) % 3]);
                let moves = w.positions[u as usize] != w.positions[v as usize];
                if moves && !may_move {
                    return None;
                }
                let r = w
                    .collapse(u.min(v), u.max(v))
                    .or_else(|| w.collapse(u.max(v), u.min(v)));
                r.map(|moved| {
                    report.collapsed_edges += 1;
                    report.vertices_moved += moved;
                })
            };
            let mut flip = |w: &mut Collapser| {
                w.flip(t, long, exact_zero).map(|flipped| {
                    if flipped {
                        report.flipped_edges += 1;
                    } else {
                        report.boundary_dropped += 1;
                    }
                    area_fixes += usize::from(!exact_zero);
                })
            };
            // The natural fix first, the other where it is blocked.
            let done = if needle {
                collapse(&mut w).or_else(|| flip(&mut w))
            } else {
                flip(&mut w).or_else(|| collapse(&mut w))
            };
            changed |= done.is_some();
        }
        tris = w
            .tris
            .into_iter()
            .zip(w.alive)
            .filter_map(|(t, a)| a.then_some(t))
            .collect();
        if !changed {
            break;
        }
    }
    report.left = tris.iter().filter(|t| bad(t)).count();
    report.triangles_removed = mesh.triangles.len() - tris.len();
    let out = Mesh::new_unchecked(positions.clone(), tris);
    report.shape_changes = report.vertices_moved + area_fixes;
    if report.shape_changes > 0 {
        report.volume_change = signed_volume(&out) - signed_volume(mesh);
    }
    (out, report)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::{degenerate_triangles, mesh_stats};
    use crate::shapes::uv_sphere;

    fn closed_consistent(m: &Mesh) {
        let s = mesh_stats(m);
        assert_eq!(
            (s.boundary_edges, s.non_manifold_edges, s.inconsistent_edges),
            (0, 0, 0)
        );
    }

    /// The unit cube with its top face (a, c, b) + (c, a, d), diagonal a–c, changed: the
    /// first triangle split at the diagonal's midpoint raised by `lift` into two proper
    /// triangles and a cap (a, c, mid) still facing the second across the diagonal
    /// (zero area when `lift` is 0).
    fn cube_with_cap(lift: f64) -> Mesh {
        let mut m = Mesh::unit_cube();
        assert_eq!(mesh_stats(&m).volume, 1.0);
        // Find the two triangles of the top face (z = 1) and their shared diagonal.
        let top: Vec<usize> = (0..m.triangles.len())
            .filter(|&t| m.corners(t).iter().all(|p| p[2] == 1.0))
            .collect();
        assert_eq!(top.len(), 2);
        let (t0, t1) = (m.triangles[top[0]], m.triangles[top[1]]);
        let k = (0..3)
            .find(|&k| t1.contains(&t0[k]) && t1.contains(&t0[(k + 1) % 3]))
            .unwrap();
        let (a, c, b) = (t0[k], t0[(k + 1) % 3], t0[(k + 2) % 3]);
        let (pa, pc) = (m.positions[a as usize], m.positions[c as usize]);
        let mid = m.positions.len() as u32;
        m.positions.push(std::array::from_fn(|i| {
            (pa[i] + pc[i]) / 2.0 + if i == 2 { lift } else { 0.0 }
        }));
        // t0 = (a, c, b) becomes (a, mid, b), (mid, c, b) and the cap (a, c, mid) —
        // which uses a -> c as t0 did, so t1 still meets it across that edge.
        m.triangles[top[0]] = [a, mid, b];
        m.triangles.push([mid, c, b]);
        m.triangles.push([a, c, mid]);
        closed_consistent(&m);
        m
    }

    #[test]
    fn thin_cap_flipped_under_a_threshold_reports_the_shape_change() {
        // The split point raised 1e-3 above the top face: a thin cap of non-zero area.
        // Before: flipped silently (vertices_moved 0, volume changed).
        let m = cube_with_cap(1e-3);
        let before = mesh_stats(&m).volume;
        assert!(before > 1.0);
        let exact = remove_degenerates(&m, &DegenerateOptions::default()).1;
        assert_eq!(
            (exact.found, exact.shape_changes, exact.volume_change),
            (0, 0, 0.0)
        );
        let opts = DegenerateOptions {
            max_aspect: Some(100.0),
            ..DegenerateOptions::default()
        };
        let (r, rep) = remove_degenerates(&m, &opts);
        closed_consistent(&r);
        assert_eq!(
            (rep.found, rep.flipped_edges, rep.vertices_moved),
            (1, 1, 0)
        );
        assert_eq!(rep.shape_changes, 1);
        let after = mesh_stats(&r).volume;
        assert_ne!(after, before);
        assert_eq!(rep.volume_change, after - before);
    }

    #[test]
    fn zero_area_cap_is_flipped_away_exactly() {
        let m = cube_with_cap(0.0);
        assert_eq!(degenerate_triangles(&m), 1);
        let (r, rep) = remove_degenerates(&m, &DegenerateOptions::default());
        closed_consistent(&r);
        assert_eq!(degenerate_triangles(&r), 0);
        assert_eq!(mesh_stats(&r).volume, 1.0);
        assert_eq!(
            (rep.found, rep.flipped_edges, rep.collapsed_edges, rep.left),
            (1, 1, 0, 0)
        );
        assert_eq!(rep.triangles_removed, 0); // the cap went, its neighbour split in two
        assert_eq!(r.triangles.len(), m.triangles.len());
    }

    #[test]
    fn coincident_vertices_needle_is_collapsed() {
        // A sphere with one vertex duplicated at the same position and a needle joining
        // the two copies: collapse merges them without moving anything.
        let s = uv_sphere([0.0; 3], 1.0, 12, 6);
        let mut m = s.clone();
        // Split vertex v's fan: triangles on one side of edge (v, w) use the copy v2.
        let t = 20usize;
        let [v, w, x] = m.triangles[t];
        let v2 = m.positions.len() as u32;
        m.positions.push(m.positions[v as usize]);
        // Replace t = (v, w, x) by (v2, w, x) plus needles (v, w, v2) and (v, v2, x):
        m.triangles[t] = [v2, w, x];
        m.triangles.push([v, w, v2]);
        m.triangles.push([v, v2, x]);
        closed_consistent(&m);
        assert_eq!(degenerate_triangles(&m), 2);
        let (r, rep) = remove_degenerates(&m, &DegenerateOptions::default());
        closed_consistent(&r);
        assert_eq!(
            (rep.found, rep.collapsed_edges, rep.vertices_moved, rep.left),
            (2, 1, 0, 0)
        );
        assert_eq!(rep.triangles_removed, 2);
        assert_eq!(r.triangles.len(), s.triangles.len());
        assert_eq!(mesh_stats(&r).volume, mesh_stats(&s).volume);
    }

    #[test]
    fn slivers_under_thresholds_go_and_the_sphere_stays_closed() {
        // A UV sphere's pole fans are needles (aspect about 41 here, every other triangle
        // below 15): the fans are thinned out by collapses until none is over 20.
        let s = uv_sphere([0.0; 3], 1.0, 256, 8);
        let opts = DegenerateOptions {
            min_area: 0.0,
            max_aspect: Some(20.0),
        };
        let (r, rep) = remove_degenerates(&s, &opts);
        closed_consistent(&r);
        assert!(rep.found > 0);
        assert_eq!(rep.left, 0, "{rep:?}");
        assert_eq!(rep.triangles_removed, s.triangles.len() - r.triangles.len());
        assert!(crate::intersect::self_intersections(&r).is_empty());
        // Volume changes a little (vertices moved), never by much.
        let (v0, v1) = (mesh_stats(&s).volume, mesh_stats(&r).volume);
        assert!((v1 - v0).abs() < 0.05 * v0, "{v0} -> {v1}");
    }

    #[test]
    fn repeated_vertex_triangles_are_dropped_and_counted() {
        let mut m = Mesh::unit_cube();
        m.triangles.push([0, 0, 1]);
        m.triangles.push([2, 3, 3]);
        let (r, rep) = remove_degenerates(&m, &DegenerateOptions::default());
        assert_eq!(
            (
                rep.found,
                rep.repeated_vertex,
                rep.triangles_removed,
                rep.left
            ),
            (2, 2, 2, 0)
        );
        assert_eq!(r, Mesh::unit_cube());
    }

    #[test]
    fn boundary_cap_is_dropped_and_the_boundary_runs_along_it() {
        // A flat 2 x 1 rectangle whose bottom edge runs 0 -> 4 -> 1 (vertex 4 in its
        // middle), and a zero-area cap (4, 0, 1) closing that edge from below: nothing lies
        // across the cap's longest edge 0–1, so it is dropped; the boundary goes back from
        // 4 edges (0 -> 1 along the cap) to 5 (0 -> 4 -> 1).
        let m = Mesh::new_unchecked(
            vec![
                [0.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [2.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
                [1.0, 0.0, 0.0],
            ],
            vec![[0, 4, 3], [4, 1, 2], [4, 2, 3], [4, 0, 1]],
        );
        assert_eq!(mesh_stats(&m).boundary_edges, 4);
        let (r, rep) = remove_degenerates(&m, &DegenerateOptions::default());
        assert_eq!(
            (
                rep.found,
                rep.boundary_dropped,
                rep.triangles_removed,
                rep.left
            ),
            (1, 1, 1, 0)
        );
        assert_eq!(mesh_stats(&r).boundary_edges, 5);
        assert_eq!(r.triangles, vec![[0, 4, 3], [4, 1, 2], [4, 2, 3]]);
    }
}

#[cfg(test)]
mod boolean_output {
    use super::*;
    use crate::boolean::{boolean, Op};
    use crate::measure::mesh_stats;
    use crate::shapes::{rigid_motion, uv_sphere};

    #[test]
    fn slivers_of_a_boolean_result_go_and_it_stays_closed() {
        // The seam of two spheres cuts many thin triangles.
        let a = uv_sphere([0.0; 3], 1.0, 48, 24);
        let b = rigid_motion(&a, [0.0, 0.0, 1.0], 0.1, [0.5, 0.0, 0.0]);
        let u = boolean(&a, &b, Op::Union, &Default::default()).mesh;
        let opts = DegenerateOptions {
            min_area: 0.0,
            max_aspect: Some(30.0),
        };
        let (r, rep) = remove_degenerates(&u, &opts);
        let s = mesh_stats(&r);
        assert_eq!(
            (s.boundary_edges, s.non_manifold_edges, s.inconsistent_edges),
            (0, 0, 0)
        );
        // 86 found; 2 left (every fix blocked by a fold or the link condition).
        assert!(rep.found > 50 && rep.left * 20 < rep.found, "{rep:?}");
        assert_eq!(rep.triangles_removed, u.triangles.len() - r.triangles.len());
        assert!(crate::intersect::self_intersections(&r).is_empty());
        let v0 = mesh_stats(&u).volume;
        assert!((s.volume - v0).abs() < 1e-3 * v0, "{v0} -> {}", s.volume);
    }
}
