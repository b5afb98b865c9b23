//! Generated shapes.
//!
//! Primitives for scripting — [`cube`], [`cuboid`], [`sphere`], [`cylinder`], [`cone`]
//! (a frustum with a top radius) and [`plane`] — check their parameters and return an
//! [`Error::InvalidParameter`] for a non-positive or non-finite size, too few segments or
//! more than [`MAX_TRIANGLES`] triangles. Closed ones face outward, are consistently
//! oriented and manifold; every primitive is exactly welded (each position one vertex,
//! shared by its triangles) and has no degenerate triangle (checked exactly: a shape too
//! small or too finely divided for `f64` to tell its vertices apart is an error). Angles
//! are taken in degrees, so that quarter turns are exact: a cylinder of 4 segments is a
//! square prism with corners exactly on the axes. Orient or place them with
//! [`crate::Transform`].
//!
//! ```
//! use meshbool::shapes::{cube, cylinder};
//! use meshbool::ops::{boolean, BooleanOptions};
//! use meshbool::Op;
//!
//! let block = cube([0.0; 3], 2.0)?;
//! let drill = cylinder([0.0, 0.0, -2.0], 0.5, 4.0, 64)?;
//! let out = boolean(&block, &drill, Op::Difference, &BooleanOptions::default())?;
//! let r = out.report().result;
//! assert!(r.closed && r.volume < 8.0 && r.volume > 8.0 - std::f64::consts::PI);
//! # Ok::<(), meshbool::Error>(())
//! ```
//!
//! The unchecked generators [`uv_sphere`], [`torus`], [`heightfield`] and
//! [`rigid_motion`] serve tests and benchmarks (radians, clamped counts).

use std::f64::consts::PI;

use crate::measure::degenerate_triangles;
use crate::transform::sin_cos_deg;
use crate::{weld_exact, Error, Mesh, Result};

/// The most triangles a primitive may have (2²⁶, about 67 million).
pub const MAX_TRIANGLES: u64 = 1 << 26;

/// An error unless `v` is finite and positive.
fn positive(what: &str, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(Error::InvalidParameter(format!(
            "{what} must be positive and finite, got {v}"
        )))
    }
}

/// An error unless every coordinate of `p` is finite.
fn finite_point(what: &str, p: [f64; 3]) -> Result<()> {
    if p.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(Error::InvalidParameter(format!(
            "{what} must be finite, got {p:?}"
        )))
    }
}

/// An error unless `n ≥ least`.
fn at_least(what: &str, n: u32, least: u32) -> Result<()> {
    if n >= least {
        Ok(())
    } else {
        Err(Error::InvalidParameter(format!(
            "{what} must be at least {least}, got {n}"
        )))
    }
}

/// An error when a primitive would have more than [`MAX_TRIANGLES`] triangles.
fn not_too_many(shape: &str, triangles: u64) -> Result<()> {
    if triangles <= MAX_TRIANGLES {
        Ok(())
    } else {
        Err(Error::InvalidParameter(format!(
            "the {shape} would have {triangles} triangles, more than {MAX_TRIANGLES}"
        )))
    }
}

/// `mesh` when its coordinates are finite, its vertices pairwise distinct and none of its
/// triangles degenerate (exactly); else the error saying so.
fn checked(shape: &str, mesh: Mesh) -> Result<Mesh> {
    if mesh.validate().is_err() {
        return Err(Error::InvalidParameter(format!(
            "the {shape}'s coordinates overflow f64"
        )));
    }
    let distinct = weld_exact(&mesh).mesh.positions.len() == mesh.positions.len();
    if !distinct || degenerate_triangles(&mesh) > 0 {
        return Err(Error::InvalidParameter(format!(
            "the {shape} is too small or too finely divided for f64: its vertices coincide or line up"
        )));
    }
    Ok(mesh)
}

/// An axis-aligned cube of edge `size` centred on `center`: 8 vertices, 12 triangles,
/// outward-facing ([`Mesh::cuboid`] from `center − size/2` to `center + size/2`).
pub fn cube(center: [f64; 3], size: f64) -> Result<Mesh> {
    finite_point("the cube's centre", center)?;
    positive("the cube's size", size)?;
    let h = size / 2.0;
    cuboid(center.map(|c| c - h), center.map(|c| c + h))
}

/// An axis-aligned box from `min` to `max` (each coordinate of `min` below that of
/// `max`): 8 vertices, 12 triangles, outward-facing ([`Mesh::cuboid`], checked).
pub fn cuboid(min: [f64; 3], max: [f64; 3]) -> Result<Mesh> {
    finite_point("the box's min", min)?;
    finite_point("the box's max", max)?;
    if (0..3).any(|k| min[k] >= max[k]) {
        return Err(Error::InvalidParameter(format!(
            "the box's min must be below its max on every axis, got {min:?} .. {max:?}"
        )));
    }
    checked("box", Mesh::cuboid(min, max))
}

/// A UV sphere of `radius` about `center`, its axis along z: `segments` ≥ 3 meridians,
/// `rings` ≥ 2 bands from pole to pole (a vertex at each pole; ring `j` at latitude
/// `−90° + 180° j / rings`, vertex `i` at longitude `360° i / segments`). All vertices lie on
/// the sphere (up to rounding): the volume is that of the inscribed polyhedron, a little
/// under `4/3 π r³`. `2 · segments · (rings − 1)` triangles, `segments · (rings − 1) + 2`
/// vertices, closed, outward-facing.
pub fn sphere(center: [f64; 3], radius: f64, segments: u32, rings: u32) -> Result<Mesh> {
    finite_point("the sphere's centre", center)?;
    positive("the sphere's radius", radius)?;
    at_least("the sphere's segments", segments, 3)?;
    at_least("the sphere's rings", rings, 2)?;
    not_too_many("sphere", 2 * u64::from(segments) * (u64::from(rings) - 1))?;
    let mut positions = Vec::with_capacity((segments * (rings - 1) + 2) as usize);
    positions.push([center[0], center[1], center[2] - radius]);
    for j in 1..rings {
        let (sp, cp) = sin_cos_deg(180.0 * f64::from(j) / f64::from(rings) - 90.0);
        for i in 0..segments {
            let (st, ct) = sin_cos_deg(360.0 * f64::from(i) / f64::from(segments));
            positions.push([
                center[0] + radius * (cp * ct),
                center[1] + radius * (cp * st),
                center[2] + radius * sp,
            ]);
        }
    }
    positions.push([center[0], center[1], center[2] + radius]);
    checked(
        "sphere",
        Mesh::new_unchecked(positions, uv_triangles(segments, rings)),
    )
}

/// A cylinder standing on the disc of `radius` about `base` (its bottom centre), its axis
/// along +z, `height` tall, the circles as regular polygons of `segments` ≥ 3 sides with
/// a vertex at angle `360° i / segments` (the first on +x). Caps are fans about their
/// centres: `4 · segments` triangles, `2 · segments + 2` vertices, closed,
/// outward-facing; volume `segments/2 · sin(360°/segments) · radius² · height` (the
/// inscribed prism).
pub fn cylinder(base: [f64; 3], radius: f64, height: f64, segments: u32) -> Result<Mesh> {
    finite_point("the cylinder's base", base)?;
    positive("the cylinder's radius", radius)?;
    positive("the cylinder's height", height)?;
    at_least("the cylinder's segments", segments, 3)?;
    frustum("cylinder", base, radius, radius, height, segments)
}

/// A cone standing on the disc of `radius` about `base` (its bottom centre), its axis
/// along +z, `height` tall, up to an apex (`top_radius` 0) or cut off at a disc of
/// `top_radius` (a frustum), polygons of `segments` ≥ 3 sides as in [`cylinder`]. Apex:
/// `2 · segments` triangles, `segments + 2` vertices; frustum: as a cylinder. Closed,
/// outward-facing; volume `height/3 · A(radius, top_radius)` with the polygons' areas
/// `a = segments/2 · sin(360°/segments) · r²`: `h/3 (a₀ + √(a₀a₁) + a₁)`.
pub fn cone(
    base: [f64; 3],
    radius: f64,
    top_radius: f64,
    height: f64,
    segments: u32,
) -> Result<Mesh> {
    finite_point("the cone's base", base)?;
    positive("the cone's radius", radius)?;
    if !(top_radius.is_finite() && top_radius >= 0.0) {
        return Err(Error::InvalidParameter(format!(
            "the cone's top radius must be 0 or positive and finite, got {top_radius}"
        )));
    }
    positive("the cone's height", height)?;
    at_least("the cone's segments", segments, 3)?;
    frustum("cone", base, radius, top_radius, height, segments)
}

/// A frustum (checked parameters): bottom centre 0, bottom ring `1..=n`, then the top
/// ring `n+1..=2n` and the top centre `2n+1`, or the apex `n+1` when `top` is 0.
fn frustum(
    shape: &str,
    base: [f64; 3],
    bottom: f64,
    top: f64,
    height: f64,
    n: u32,
) -> Result<Mesh> {
    let tris = if top > 0.0 { 4 } else { 2 } * u64::from(n);
    not_too_many(shape, tris)?;
    let z1 = base[2] + height;
    let ring = |r: f64, z: f64| {
        (0..n).map(move |i| {
            let (s, c) = sin_cos_deg(360.0 * f64::from(i) / f64::from(n));
            [base[0] + r * c, base[1] + r * s, z]
        })
    };
    let mut positions = vec![base];
    positions.extend(ring(bottom, base[2]));
    let b = |i: u32| 1 + i % n;
    let mut triangles = Vec::with_capacity(tris as usize);
    for i in 0..n {
        triangles.push([0, b(i + 1), b(i)]);
    }
    if top > 0.0 {
        positions.extend(ring(top, z1));
        positions.push([base[0], base[1], z1]);
        let t = |i: u32| 1 + n + i % n;
        let centre = 2 * n + 1;
        for i in 0..n {
            triangles.push([b(i), b(i + 1), t(i + 1)]);
            triangles.push([b(i), t(i + 1), t(i)]);
            triangles.push([centre, t(i), t(i + 1)]);
        }
    } else {
        positions.push([base[0], base[1], z1]);
        let apex = n + 1;
        for i in 0..n {
            triangles.push([b(i), b(i + 1), apex]);
        }
    }
    checked(shape, Mesh::new_unchecked(positions, triangles))
}

/// A flat rectangle `width` (along x) by `depth` (along y) centred on `center`, divided
/// into `nx` × `ny` cells (each ≥ 1) of two triangles, facing +z: an open surface of
/// `2 · nx · ny` triangles, `(nx + 1)(ny + 1)` vertices and `2 (nx + ny)` boundary edges.
pub fn plane(center: [f64; 3], width: f64, depth: f64, nx: u32, ny: u32) -> Result<Mesh> {
    finite_point("the plane's centre", center)?;
    positive("the plane's width", width)?;
    positive("the plane's depth", depth)?;
    at_least("the plane's nx", nx, 1)?;
    at_least("the plane's ny", ny, 1)?;
    not_too_many("plane", 2 * u64::from(nx) * u64::from(ny))?;
    let (hw, hd) = (width / 2.0, depth / 2.0);
    let m = heightfield(
        [center[0] - hw, center[1] - hd],
        [center[0] + hw, center[1] + hd],
        nx,
        ny,
        |_, _| center[2],
    );
    checked("plane", m)
}

/// The triangles of a UV sphere: south pole 0, rings of `segments` from 1, north pole
/// last.
fn uv_triangles(segments: u32, rings: u32) -> Vec<[u32; 3]> {
    let top = segments * (rings - 1) + 1;
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
    triangles
}

/// A UV sphere for tests: `segments` around the axis (z, at least 3), `rings` from pole
/// to pole (at least 2), angles in radians, nothing checked ([`sphere`] checks).
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
    Mesh::new_unchecked(positions, uv_triangles(segments, rings))
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

    /// Closed, manifold, consistently oriented, one component, welded, no degenerates.
    fn assert_clean_solid(m: &Mesh) -> crate::measure::MeshStats {
        let s = mesh_stats(m);
        assert!(s.closed);
        assert_eq!(
            (
                s.boundary_edges,
                s.non_manifold_edges,
                s.inconsistent_edges,
                s.degenerate_triangles,
                s.duplicate_triangles,
                s.unreferenced_vertices,
                s.components
            ),
            (0, 0, 0, 0, 0, 0, 1)
        );
        assert_eq!(weld_exact(m).mesh.positions.len(), m.positions.len());
        // Outward: the volume is positive (and, being closed, Euler characteristic 2).
        assert!(s.volume > 0.0);
        assert_eq!(s.vertices + s.triangles - s.edges, 2);
        s
    }

    /// The volume of a frustum of regular `n`-gons of circumradii `r0`, `r1`, `h` apart.
    fn polygon_frustum(n: u32, r0: f64, r1: f64, h: f64) -> f64 {
        let k = f64::from(n) / 2.0 * (2.0 * PI / f64::from(n)).sin();
        h / 3.0 * k * (r0 * r0 + r0 * r1 + r1 * r1)
    }

    #[test]
    fn cube_and_cuboid_volumes_are_exact() {
        let c = cube([1.0, 2.0, 3.0], 2.0).unwrap();
        let s = assert_clean_solid(&c);
        assert_eq!((s.triangles, s.vertices, s.volume), (12, 8, 8.0));
        assert_eq!(c.bounds().unwrap().min, [0.0, 1.0, 2.0]);
        let b = cuboid([-1.0, 0.0, 0.5], [2.0, 0.25, 4.5]).unwrap();
        assert_eq!(assert_clean_solid(&b).volume, 3.0);
        assert!(cube([0.0; 3], 0.0).is_err());
        assert!(cube([0.0; 3], -1.0).is_err());
        assert!(cube([f64::NAN, 0.0, 0.0], 1.0).is_err());
        assert!(cuboid([0.0; 3], [1.0, 1.0, 0.0]).is_err());
    }

    #[test]
    fn cylinder_volume_is_the_inscribed_prism() {
        for n in [3, 4, 7, 64, 1000] {
            let m = cylinder([1.0, -2.0, 0.5], 1.5, 2.0, n).unwrap();
            let s = assert_clean_solid(&m);
            assert_eq!(
                (s.triangles, s.vertices),
                (4 * n as usize, 2 * n as usize + 2)
            );
            let want = polygon_frustum(n, 1.5, 1.5, 2.0);
            assert!((s.volume - want).abs() <= 1e-13 * want, "{n}: {}", s.volume);
        }
        // Four segments: a square prism with corners exactly on the axes, volume exact.
        let m = cylinder([0.0; 3], 1.0, 3.0, 4).unwrap();
        assert_eq!(mesh_stats(&m).volume, 6.0);
        assert!(m.positions().contains(&[0.0, 1.0, 3.0]));
        let b = m.bounds().unwrap();
        assert_eq!((b.min, b.max), ([-1.0, -1.0, 0.0], [1.0, 1.0, 3.0]));
        assert!(cylinder([0.0; 3], -1.0, 1.0, 8).is_err());
        assert!(cylinder([0.0; 3], 1.0, 0.0, 8).is_err());
        assert!(cylinder([0.0; 3], 1.0, 1.0, 2).is_err());
        assert!(cylinder([0.0; 3], 1.0, f64::INFINITY, 8).is_err());
    }

    #[test]
    fn cone_and_frustum_volumes_are_the_inscribed_pyramids() {
        for n in [3, 4, 12, 360] {
            let m = cone([0.0, 0.0, -1.0], 2.0, 0.0, 3.0, n).unwrap();
            let s = assert_clean_solid(&m);
            assert_eq!((s.triangles, s.vertices), (2 * n as usize, n as usize + 2));
            let want = polygon_frustum(n, 2.0, 0.0, 3.0);
            assert!((s.volume - want).abs() <= 1e-13 * want, "{n}: {}", s.volume);
            let m = cone([5.0, 5.0, 5.0], 2.0, 0.5, 3.0, n).unwrap();
            let s = assert_clean_solid(&m);
            assert_eq!(s.triangles, 4 * n as usize);
            let want = polygon_frustum(n, 2.0, 0.5, 3.0);
            assert!((s.volume - want).abs() <= 1e-13 * want, "{n}: {}", s.volume);
        }
        // Square pyramid: base 2 (diagonal 2√2... corners on the axes at distance 1).
        assert_eq!(
            mesh_stats(&cone([0.0; 3], 1.0, 0.0, 3.0, 4).unwrap()).volume,
            2.0
        );
        assert!(cone([0.0; 3], 1.0, -0.5, 1.0, 8).is_err());
        assert!(cone([0.0; 3], 0.0, 1.0, 1.0, 8).is_err());
        assert!(cone([0.0; 3], 1.0, 0.0, 1.0, 0).is_err());
    }

    #[test]
    fn sphere_volume_is_the_inscribed_polyhedron() {
        for (n, rings) in [(3, 2), (4, 2), (8, 3), (24, 12), (128, 64)] {
            let m = sphere([1.0, 2.0, 3.0], 2.0, n, rings).unwrap();
            let s = assert_clean_solid(&m);
            assert_eq!(s.triangles, 2 * (n * (rings - 1)) as usize);
            assert_eq!(s.vertices, (n * (rings - 1) + 2) as usize);
            // Bands between latitudes: frustums of regular n-gons (the poles: pyramids).
            let ring = |j: u32| {
                let phi = (180.0 * f64::from(j) / f64::from(rings) - 90.0).to_radians();
                (2.0 * phi.cos(), 2.0 * phi.sin())
            };
            let want: f64 = (0..rings)
                .map(|j| {
                    let ((r0, z0), (r1, z1)) = (ring(j), ring(j + 1));
                    polygon_frustum(n, r0, r1, z1 - z0)
                })
                .sum();
            assert!(
                (s.volume - want).abs() <= 1e-13 * want,
                "{n}x{rings}: {} vs {want}",
                s.volume
            );
            assert!(s.volume < 4.0 / 3.0 * PI * 8.0);
        }
        // Four segments, two rings: an octahedron with vertices exactly on the axes.
        let m = sphere([0.0; 3], 1.0, 4, 2).unwrap();
        assert_eq!(mesh_stats(&m).volume, 4.0 / 3.0);
        assert!(m.positions().contains(&[0.0, -1.0, 0.0]));
        assert!(sphere([0.0; 3], 1.0, 2, 4).is_err());
        assert!(sphere([0.0; 3], 1.0, 8, 1).is_err());
        assert!(sphere([0.0; 3], -1.0, 8, 4).is_err());
        assert!(sphere([0.0; 3], f64::NAN, 8, 4).is_err());
    }

    #[test]
    fn plane_is_an_open_grid_facing_up() {
        let m = plane([1.0, 1.0, 2.0], 4.0, 2.0, 4, 2).unwrap();
        let s = mesh_stats(&m);
        assert_eq!(
            (
                s.triangles,
                s.vertices,
                s.boundary_edges,
                s.non_manifold_edges,
                s.inconsistent_edges,
                s.degenerate_triangles
            ),
            (16, 15, 12, 0, 0, 0)
        );
        assert!(!s.closed);
        assert_eq!(s.projected_area.xy, 8.0);
        let b = m.bounds().unwrap();
        assert_eq!((b.min, b.max), ([-1.0, 0.0, 2.0], [3.0, 2.0, 2.0]));
        // Facing +z: every triangle's normal points up.
        for t in 0..m.triangle_count() {
            let [a, b, c] = m.corners(t);
            let z = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
            assert!(z > 0.0);
        }
        assert!(plane([0.0; 3], 1.0, 1.0, 0, 1).is_err());
        assert!(plane([0.0; 3], 1.0, -1.0, 1, 1).is_err());
    }

    #[test]
    fn too_fine_or_too_large_is_an_error_not_a_bad_mesh() {
        // Vertices that f64 cannot tell apart.
        let e = sphere([1e6, 0.0, 0.0], 1e-12, 64, 32).unwrap_err();
        assert!(e.to_string().contains("too small"), "{e}");
        let e = cylinder([0.0; 3], 1.0, 1.0, u32::MAX).unwrap_err();
        assert!(e.to_string().contains("more than"), "{e}");
        assert!(plane([0.0; 3], 1.0, 1.0, 1 << 14, 1 << 14).is_err());
        assert!(cube([f64::MAX, 0.0, 0.0], 1.0).is_err());
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
