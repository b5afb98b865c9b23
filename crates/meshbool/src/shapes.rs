//! Generated test shapes: spheres, tori, height-field grids (boxes are [`Mesh::cuboid`]).
//! Closed shapes are outward-facing and manifold; surfaces face +z.

use std::f64::consts::PI;

use crate::Mesh;

/// A UV sphere: `segments` ≥ 3 around the axis (z), `rings` ≥ 2 from pole to pole.
/// `2 · segments · (rings − 1)` triangles, `segments · (rings − 1) + 2` vertices, closed.
pub fn uv_sphere(center: [f64; 3], radius: f64, segments: u32, rings: u32) -> Mesh {
    let (segments, rings) = (segments.max(3), rings.max(2));
    let mut positions = vec![[center[0], center[1], center[2] - radius]];
    for j in 1..rings {
        let phi = PI * f64::from(j) / f64::from(rings) - PI / 2.0;
        for i in 0..segments {
            let theta = 2.0 * PI * f64::from(i) / f64::from(segments);
            positions.push([
                center[0] + radius * phi.cos() * theta.cos(),
                center[1] + radius * phi.cos() * theta.sin(),
                center[2] + radius * phi.sin(),
            ]);
        }
    }
    positions.push([center[0], center[1], center[2] + radius]);
    let top = positions.len() as u32 - 1;
    let ring = |j: u32, i: u32| 1 + (j - 1) * segments + i % segments;
    let mut triangles = Vec::with_capacity(2 * (segments * (rings - 1)) as usize);
    for i in 0..segments {
        triangles.push([0, ring(1, i + 1), ring(1, i)]);
        triangles.push([top, ring(rings - 1, i), ring(rings - 1, i + 1)]);
    }
    for j in 1..rings - 1 {
        for i in 0..segments {
            let (a, b, c, d) = (
                ring(j, i),
                ring(j, i + 1),
                ring(j + 1, i),
                ring(j + 1, i + 1),
            );
            triangles.push([a, b, d]);
            triangles.push([a, d, c]);
        }
    }
    Mesh::new_unchecked(positions, triangles)
}

/// A torus around the z axis: `major` radius of the tube's centre line, `minor` tube radius,
/// `segments` ≥ 3 around z, `sides` ≥ 3 around the tube. `2 · segments · sides` triangles, closed.
pub fn torus(center: [f64; 3], major: f64, minor: f64, segments: u32, sides: u32) -> Mesh {
    let (segments, sides) = (segments.max(3), sides.max(3));
    let mut positions = Vec::with_capacity((segments * sides) as usize);
    for i in 0..segments {
        let theta = 2.0 * PI * f64::from(i) / f64::from(segments);
        for j in 0..sides {
            let phi = 2.0 * PI * f64::from(j) / f64::from(sides);
            let r = major + minor * phi.cos();
            positions.push([
                center[0] + r * theta.cos(),
                center[1] + r * theta.sin(),
                center[2] + minor * phi.sin(),
            ]);
        }
    }
    let v = |i: u32, j: u32| (i % segments) * sides + j % sides;
    let mut triangles = Vec::with_capacity(2 * (segments * sides) as usize);
    for i in 0..segments {
        for j in 0..sides {
            let (a, b, c, d) = (v(i, j), v(i + 1, j), v(i, j + 1), v(i + 1, j + 1));
            triangles.push([a, b, d]);
            triangles.push([a, d, c]);
        }
    }
    Mesh::new_unchecked(positions, triangles)
}

/// A height field over the rectangle `min..max` (x, y) sampled on an `nx` × `ny` grid of
/// cells, z = `height(x, y)`, two triangles per cell, facing +z; an open surface with
/// `2 (nx + ny)` boundary edges.
pub fn heightfield(
    min: [f64; 2],
    max: [f64; 2],
    nx: u32,
    ny: u32,
    height: impl Fn(f64, f64) -> f64,
) -> Mesh {
    let (nx, ny) = (nx.max(1), ny.max(1));
    let mut positions = Vec::with_capacity(((nx + 1) * (ny + 1)) as usize);
    for j in 0..=ny {
        let y = min[1] + (max[1] - min[1]) * f64::from(j) / f64::from(ny);
        for i in 0..=nx {
            let x = min[0] + (max[0] - min[0]) * f64::from(i) / f64::from(nx);
            positions.push([x, y, height(x, y)]);
        }
    }
    let v = |i: u32, j: u32| j * (nx + 1) + i;
    let mut triangles = Vec::with_capacity((2 * nx * ny) as usize);
    for j in 0..ny {
        for i in 0..nx {
            triangles.push([v(i, j), v(i + 1, j), v(i + 1, j + 1)]);
            triangles.push([v(i, j), v(i + 1, j + 1), v(i, j + 1)]);
        }
    }
    Mesh::new_unchecked(positions, triangles)
}

/// `mesh` rotated by `angle` radians about `axis` (through the origin; any non-zero
/// length), then translated by `shift`. Triangles are unchanged.
pub fn rigid_motion(mesh: &Mesh, axis: [f64; 3], angle: f64, shift: [f64; 3]) -> Mesh {
    let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    let [x, y, z] = axis.map(|c| c / n);
    let (s, c) = angle.sin_cos();
    let r = [
        [
            c + x * x * (1.0 - c),
            x * y * (1.0 - c) - z * s,
            x * z * (1.0 - c) + y * s,
        ],
        [
            y * x * (1.0 - c) + z * s,
            c + y * y * (1.0 - c),
            y * z * (1.0 - c) - x * s,
        ],
        [
            z * x * (1.0 - c) - y * s,
            z * y * (1.0 - c) + x * s,
            c + z * z * (1.0 - c),
        ],
    ];
    let positions = mesh
        .positions
        .iter()
        .map(|p| {
            std::array::from_fn(|i| r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2] + shift[i])
        })
        .collect();
    Mesh::new_unchecked(positions, mesh.triangles.clone())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measure::mesh_stats;

    #[test]
    fn sphere_is_closed_and_close_to_analytic_volume() {
        let s = mesh_stats(&uv_sphere([1.0, 2.0, 3.0], 2.0, 128, 64));
        assert_eq!(s.triangles, 2 * 128 * 63);
        assert_eq!(s.vertices, 128 * 63 + 2);
        assert!(s.closed);
        assert_eq!(
            (
                s.boundary_edges,
                s.inconsistent_edges,
                s.degenerate_triangles
            ),
            (0, 0, 0)
        );
        let exact = 4.0 / 3.0 * PI * 8.0;
        assert!(s.volume > 0.99 * exact && s.volume < exact, "{}", s.volume);
    }

    #[test]
    fn torus_is_closed_with_analytic_volume() {
        let s = mesh_stats(&torus([0.0; 3], 3.0, 1.0, 96, 48));
        assert!(s.closed);
        assert_eq!(
            (s.boundary_edges, s.inconsistent_edges, s.components),
            (0, 0, 1)
        );
        let exact = 2.0 * PI * PI * 3.0;
        assert!(s.volume > 0.99 * exact && s.volume < exact, "{}", s.volume);
    }

    #[test]
    fn rigid_motion_keeps_shape_and_moves_it() {
        let cube = Mesh::unit_cube();
        // A quarter turn about z maps the unit cube onto [-1,0]x[0,1]x[0,1], then shifted.
        let m = rigid_motion(
            &cube,
            [0.0, 0.0, 2.0],
            std::f64::consts::FRAC_PI_2,
            [1.0, 0.0, 5.0],
        );
        let b = m.bounds().unwrap();
        for k in 0..3 {
            assert!(
                (b.min[k] - [0.0, 0.0, 5.0][k]).abs() < 1e-15
                    && (b.max[k] - [1.0, 1.0, 6.0][k]).abs() < 1e-15
            );
        }
        assert!((mesh_stats(&m).volume - 1.0).abs() < 1e-14);
        assert_eq!(m.triangles, cube.triangles);
        assert_eq!(
            rigid_motion(&cube, [1.0, 2.0, 3.0], 0.0, [0.0; 3]).positions,
            cube.positions
        );
    }

    #[test]
    fn heightfield_is_an_open_grid() {
        let m = heightfield([0.0, 0.0], [10.0, 5.0], 10, 5, |x, y| 0.1 * x + 0.2 * y);
        let s = mesh_stats(&m);
        assert_eq!(
            (s.triangles, s.boundary_edges, s.inconsistent_edges),
            (100, 30, 0)
        );
        assert!((s.projected_area.xy - 50.0).abs() < 1e-12);
    }
}
