//! Closed components that face inward without enclosing anything: inside out.
//!
//! A closed component with negative volume is either a cavity (inside another component,
//! legitimately facing inward) or inside out (a mesh written with the other winding
//! convention). The winding number of the rest of the mesh at a point of the component
//! tells them apart: 0 outside everything (inside out), 1 or more inside another part (a
//! cavity).

use rayon::prelude::*;

use crate::classify::winding_number;
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

impl Inward {
    /// [`inside_out`] of `mesh`, the mesh these components are of.
    pub(crate) fn inside_out(self, mesh: &Mesh) -> (Vec<u32>, usize) {
        let Inward { comp, inward } = self;
        if inward.is_empty() {
            return (Vec::new(), 0);
        }
        let reversed: Vec<u32> = inward
            .par_iter()
            .copied()
            .filter(|&c| {
                let (mine, rest): (Vec<u32>, Vec<u32>) =
                    (0..mesh.triangles.len() as u32).partition(|&t| comp[t as usize] == c);
                if rest.is_empty() {
                    return true;
                }
                // The centroid of the component's largest triangle: on it, off the rest.
                let at = mesh
                    .probe(mine.iter().map(|&t| t as usize))
                    .expect("a component has triangles");
                winding_number(&mesh.subset(&rest), at).round() < 1.0
            })
            .collect();
        let mut triangles: Vec<u32> = (0..mesh.triangles.len() as u32)
            .filter(|&t| reversed.binary_search(&comp[t as usize]).is_ok())
            .collect();
        triangles.sort_unstable();
        (triangles, reversed.len())
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
}
