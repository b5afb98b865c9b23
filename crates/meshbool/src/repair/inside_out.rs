//! Closed components that face inward without enclosing anything: inside out.
//!
//! A closed component with negative volume is either a cavity (inside another component,
//! legitimately facing inward) or inside out (a mesh written with the other winding
//! convention). The winding number of the rest of the mesh at a point of the component
//! tells them apart: 0 outside everything (inside out), 1 or more inside another part (a
//! cavity).

use rayon::prelude::*;

use crate::classify::{side_margin, winding_number_of, winding_term, FastWinding};
use crate::vec3::{cross, dot, sub};
use crate::Mesh;

/// The triangles of the inside-out components of `mesh` (valid, closed, consistently
/// oriented; for other meshes the answer has no meaning): components (connected through
/// shared vertices) with negative volume whose points the rest of the mesh does not wind
/// around. Sorted triangle ids, and the number of such components.
pub fn inside_out(mesh: &Mesh) -> (Vec<u32>, usize) {
    // A corner naming no vertex: no meaning, and nothing to look up.
    let n = mesh.positions.len();
    if mesh
        .triangles
        .par_iter()
        .with_min_len(1 << 12)
        .any(|t| t.iter().any(|&v| v as usize >= n))
    {
        return (Vec::new(), 0);
    }
    inward(mesh).inside_out(mesh)
}

/// The components of a mesh with negative volume: the first, linear part of
/// [`inside_out`], which the input checks run beside the edge counts (before they know
/// whether the mesh is closed; the winding numbers, whose cost grows with the number of
/// such components, only once it is known to be).
pub(crate) struct Inward {
    /// Each triangle's component (its lowest vertex).
    comp: Vec<u32>,
    /// The components with negative volume, in increasing order.
    inward: Vec<u32>,
}

/// [`Inward`] of `mesh`, a mesh whose corners all name vertices.
pub(crate) fn inward(mesh: &Mesh) -> Inward {
    let n = mesh.positions.len();
    let comp = crate::edges::vertex_components(&mesh.triangles, n);
    // Six times the signed volume per component, relative to one of its vertices (a
    // component far from the origin keeps its precision): summed in fixed chunks of
    // triangles side by side (per run of one component's triangles), the chunks' sums
    // then added in order, so that the sums do not depend on the number of threads.
    const CHUNK: usize = 1 << 14;
    let runs: Vec<Vec<(u32, f64)>> = mesh
        .triangles
        .par_chunks(CHUNK)
        .zip(comp.par_chunks(CHUNK))
        .map(|(tris, comps)| {
            let mut runs: Vec<(u32, f64)> = Vec::new();
            for (t, &c) in tris.iter().zip(comps) {
                let o = mesh.positions[c as usize];
                let [a, b, p] = t.map(|v| sub(&mesh.positions[v as usize], &o));
                let term = dot(&a, &cross(&b, &p));
                match runs.last_mut() {
                    Some((last, sum)) if *last == c => *sum += term,
                    _ => runs.push((c, term)),
                }
            }
            runs
        })
        .collect();
    let mut volume = vec![0.0f64; n];
    for (c, v) in runs.into_iter().flatten() {
        volume[c as usize] += v;
    }
    let inward: Vec<u32> = (0..n as u32)
        .filter(|&c| volume[c as usize] < 0.0)
        .collect();
    Inward { comp, inward }
}

/// Inward components up to this many get the exact winding number of the rest of the
/// mesh at their probe (a sum over every other triangle each, O(n) per component); more
/// share one [`FastWinding`] hierarchy: the whole mesh's winding number at every probe at
/// once, less the component's own exact terms (so the cost stays O(n log n) with
/// thousands of them). Either way the decision is the rest's winding below ½, where the
/// rest's is 0 (inside out) or 1 or more (a cavity); a hierarchy value whose error bound
/// ([`FastWinding::at_many_bounded`]) does not clear ½ is summed exactly.
const EXACT_UP_TO: usize = 8;

impl Inward {
    /// [`inside_out`] of `mesh`, the mesh these components are of.
    pub(crate) fn inside_out(self, mesh: &Mesh) -> (Vec<u32>, usize) {
        self.inside_out_with(mesh, EXACT_UP_TO)
    }

    /// [`Inward::inside_out`] with exact sums up to `exact_up_to` inward components.
    fn inside_out_with(self, mesh: &Mesh, exact_up_to: usize) -> (Vec<u32>, usize) {
        if self.inward.is_empty() {
            return (Vec::new(), 0);
        }
        let rest = self.rest_windings(mesh, exact_up_to);
        let Inward { comp, inward } = self;
        let reversed: Vec<u32> = (inward.iter().zip(&rest))
            .filter(|&(_, w)| w.round() < 1.0)
            .map(|(&c, _)| c)
            .collect();
        let mut triangles: Vec<u32> = (0..mesh.triangles.len() as u32)
            .filter(|&t| reversed.binary_search(&comp[t as usize]).is_ok())
            .collect();
        triangles.sort_unstable();
        (triangles, reversed.len())
    }

    /// The winding number of the rest of the mesh at a point of each inward component
    /// (the centroid of its largest triangle: on it, off the rest), in the order of
    /// `inward`: exact sums up to `exact_up_to` components, else from one hierarchy.
    fn rest_windings(&self, mesh: &Mesh, exact_up_to: usize) -> Vec<f64> {
        let Inward { comp, inward } = self;
        // Each inward component's triangles, in one pass.
        let mut mine: Vec<Vec<u32>> = vec![Vec::new(); inward.len()];
        for (t, c) in comp.iter().enumerate() {
            if let Ok(i) = inward.binary_search(c) {
                mine[i].push(t as u32);
            }
        }
        let probes: Vec<[f64; 3]> = mine
            .iter()
            .map(|ts| {
                mesh.probe(ts.iter().map(|&t| t as usize))
                    .expect("a component has triangles")
            })
            .collect();
        let exact = |c: u32, at: [f64; 3]| winding_number_of(mesh, at, |t| comp[t] != c);
        if inward.len() <= exact_up_to {
            return (inward.iter().zip(&probes))
                .map(|(&c, &at)| exact(c, at))
                .collect();
        }
        let total = FastWinding::new(mesh).at_many_bounded(&probes);
        (mine.par_iter().zip(inward).zip(&probes).zip(total))
            .map(|(((ts, &c), &at), (total, e))| {
                let own: f64 = ts
                    .iter()
                    .map(|&t| {
                        let [a, b, c] = mesh.corners(t as usize);
                        winding_term(&a, &b, &c, &at)
                    })
                    .sum();
                let rest = total - own;
                // The side of ½ is certain clear of it by more than the bound; else
                // the exact sum decides.
                match side_margin(rest, e, 0.5) > 0.0 {
                    true => rest,
                    false => exact(c, at),
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn joined(parts: &[Mesh]) -> Mesh {
        let mut m = Mesh::default();
        for p in parts {
            m.append(p).unwrap();
        }
        m
    }

    #[test]
    fn inside_out_parts_are_found_and_cavities_are_not() {
        // Corners naming no vertex: nothing found, no panic.
        let mut broken = Mesh::cuboid([0.0; 3], [3.0; 3]).flipped();
        broken.triangles[5][1] = 99;
        assert_eq!(inside_out(&broken), (vec![], 0));
        let outer = Mesh::cuboid([0.0; 3], [3.0; 3]);
        let inner = Mesh::cuboid([1.0; 3], [2.0; 3]);
        assert_eq!(inside_out(&outer), (vec![], 0));
        assert_eq!(inside_out(&outer.flipped()), ((0..12).collect(), 1));
        // A cavity faces inward legitimately.
        assert_eq!(
            inside_out(&joined(&[outer.clone(), inner.flipped()])),
            (vec![], 0)
        );
        // An inside-out part beside a good one, far from the origin.
        let far = crate::shapes::rigid_motion(&inner, [0.0, 0.0, 1.0], 0.0, [5.0e5, 7.0e6, 0.0]);
        let m = joined(&[outer.clone(), far.flipped()]);
        assert_eq!(inside_out(&m), ((12..24).collect(), 1));
        // Everything inside out: the cavity inside an inside-out box is then the part
        // that faces outward; only the box is reported.
        let m = joined(&[outer.flipped(), inner.clone()]);
        assert_eq!(inside_out(&m), ((0..12).collect(), 1));
    }

    /// A large mesh takes the path joined on all threads: the same parts are found.
    #[test]
    fn large_meshes_give_the_same_parts_on_many_threads() {
        let sphere = |c: f64, r: f64| crate::shapes::uv_sphere([c, 0.0, 0.0], r, 128, 96);
        // An inside-out sphere, a good one with a cavity, a far inside-out small one.
        let m = joined(&[
            sphere(0.0, 1.0).flipped(),
            sphere(5.0, 2.0),
            sphere(5.0, 1.0).flipped(),
            sphere(1.0e4, 0.5).flipped(),
        ]);
        assert!(m.triangles.len() >= 1 << 16);
        let per = m.triangles.len() / 4;
        let want: Vec<u32> = (0..per as u32)
            .chain(3 * per as u32..4 * per as u32)
            .collect();
        for threads in [1, 4] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            assert_eq!(
                pool.install(|| inside_out(&m)),
                (want.clone(), 2),
                "{threads}"
            );
        }
    }

    /// Many inward components (past [`EXACT_UP_TO`]: one hierarchy for all) are told
    /// apart as the exact sums tell them: 40 small inside-out cubes scattered around (some
    /// with good cubes beside them), 45 cavities in two boxes; at unit size and
    /// UTM-shifted. Both paths give the answer the construction says.
    #[test]
    fn many_inward_parts_share_one_hierarchy() {
        let cube = |c: [f64; 3], h: f64| Mesh::cuboid(c.map(|x| x - h), c.map(|x| x + h));
        for shift in [[0.0; 3], [5.0e5, 7.0e6, 120.0]] {
            let mut parts: Vec<Mesh> = Vec::new();
            let mut want_parts: Vec<usize> = Vec::new();
            // Two big boxes with 5 × 5 cavities each (one row of the second box's are
            // left out and put inside out in the open instead).
            for (b, x0) in [0.0, 20.0].into_iter().enumerate() {
                parts.push(cube([x0 + 5.0, 5.0, 5.0], 5.0));
                for i in 0..5 {
                    for j in 0..5 {
                        if b == 1 && i == 4 {
                            continue;
                        }
                        let c = [x0 + 1.0 + 2.0 * i as f64, 1.0 + 2.0 * j as f64, 5.0];
                        parts.push(cube(c, 0.4).flipped());
                    }
                }
            }
            for i in 0..40 {
                let c = [
                    -30.0 + 3.0 * (i % 10) as f64,
                    -10.0 - 3.0 * (i / 10) as f64,
                    0.0,
                ];
                want_parts.push(parts.len());
                parts.push(cube(c, 0.7).flipped());
                if i % 4 == 0 {
                    parts.push(cube([c[0], c[1], 10.0], 0.7));
                }
            }
            let parts: Vec<Mesh> = parts
                .iter()
                .map(|p| crate::shapes::rigid_motion(p, [0.0, 0.0, 1.0], 0.0, shift))
                .collect();
            let m = joined(&parts);
            let mut want: Vec<u32> = Vec::new();
            let mut at = 0u32;
            for (i, p) in parts.iter().enumerate() {
                let n = p.triangles.len() as u32;
                if want_parts.contains(&i) {
                    want.extend(at..at + n);
                }
                at += n;
            }
            let fast = inward(&m).inside_out(&m);
            assert_eq!(fast, (want.clone(), 40), "{shift:?}: the hierarchy");
            // The rest's winding numbers themselves: whole, and the same both ways.
            let (w_fast, w_exact) = (
                inward(&m).rest_windings(&m, EXACT_UP_TO),
                inward(&m).rest_windings(&m, usize::MAX),
            );
            assert_eq!(w_fast.len(), 85);
            for (f, e) in w_fast.iter().zip(&w_exact) {
                assert!(
                    (f - e).abs() < 0.05 && (e - e.round()).abs() < 1e-6,
                    "{f} {e}"
                );
            }
            let exact = inward(&m).inside_out_with(&m, usize::MAX);
            assert_eq!(exact, (want, 40), "{shift:?}: exact sums");
        }
    }

    /// Below an open sheet (no meaning for [`inside_out`], but winding numbers all the
    /// same), the rest's winding numbers at the probes of small inward boxes lie within a
    /// few thousandths to three tenths of ½. Where the hierarchy's bound does not clear
    /// ½, the exact sum decides (the exact route's value, to its rounding); elsewhere the
    /// hierarchy's value is on the exact sum's side. Both happen.
    #[test]
    fn rest_windings_near_one_half_take_the_exact_sum() {
        let mut m = crate::shapes::heightfield([-1.0, -1.0], [1.0, 1.0], 60, 60, |_, _| 0.0);
        let mut rng = crate::test_util::Rng(0x0e5a_17f0_0d5e_a1e5);
        for _ in 0..40 {
            let c = [
                1.6 * (rng.unit() - 0.5),
                1.6 * (rng.unit() - 0.5),
                -0.02 - 0.3 * rng.unit(),
            ];
            let box_ = Mesh::cuboid(c.map(|x| x - 0.01), c.map(|x| x + 0.01));
            m.append(&box_.flipped()).unwrap();
        }
        let fast = inward(&m).rest_windings(&m, 0);
        let exact = inward(&m).rest_windings(&m, usize::MAX);
        assert_eq!(fast.len(), 40);
        let mut summed = 0;
        for (f, e) in fast.iter().zip(&exact) {
            assert!((0.2..0.5).contains(e), "{e}");
            assert_eq!(f.round(), e.round(), "{f} {e}");
            // Exact sums agree to their rounding (their order of summation follows the
            // threads); the hierarchy's values differ far more.
            summed += usize::from((f - e).abs() < 1e-12);
        }
        assert!(summed > 0 && summed < 40, "{summed} of 40 summed exactly");
    }
}
