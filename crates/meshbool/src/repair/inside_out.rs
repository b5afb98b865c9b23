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
    let n = mesh.positions.len();
    let mut root: Vec<u32> = (0..n as u32).collect();
    fn find(root: &mut [u32], mut x: u32) -> u32 {
        while root[x as usize] != x {
            let up = root[root[x as usize] as usize];
            root[x as usize] = up;
            x = up;
        }
        x
    }
    for &[a, b, c] in &mesh.triangles {
        for (x, y) in [(a, b), (a, c)] {
            let (rx, ry) = (find(&mut root, x), find(&mut root, y));
            if rx != ry {
                root[rx.max(ry) as usize] = rx.min(ry);
            }
        }
    }
    let comp: Vec<u32> = mesh
        .triangles
        .iter()
        .map(|t| find(&mut root, t[0]))
        .collect();
    // Six times the signed volume per component, relative to one of its vertices (a
    // component far from the origin keeps its precision).
    let mut volume = vec![0.0f64; n];
    for (t, &c) in mesh.triangles.iter().zip(&comp) {
        let o = mesh.positions[c as usize];
        let [a, b, p] = t.map(|v| sub(&mesh.positions[v as usize], &o));
        volume[c as usize] += dot(&a, &cross(&b, &p));
    }
    let inward: Vec<u32> = (0..n as u32)
        .filter(|&c| volume[c as usize] < 0.0)
        .collect();
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
}
