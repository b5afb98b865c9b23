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
//! Two mining examples are checked and exactly welded the same way: [`terrain`], a
//! seeded height field with hills, hollows and a regional slope, and [`pit`], a benched
//! open-pit shell. Both are open surfaces facing up; with the command line's defaults
//! the pit crosses the terrain along one closed curve, as a pit design crosses a
//! survey.
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

/// An error unless `v` is 0 or positive and finite.
fn non_negative(what: &str, v: f64) -> Result<()> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(Error::InvalidParameter(format!(
            "{what} must be 0 or positive and finite, got {v}"
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
    non_negative("the cone's top radius", top_radius)?;
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

/// splitmix64 (Steele, Lea and Flood 2014), written out here rather than taken from a
/// crate: it is a few lines, and a generated terrain must stay the same surface for the
/// same seed whatever version of a random-number crate the lock file holds.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[lo, hi)`.
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next() >> 11) as f64 / (1u64 << 53) as f64)
    }

    /// A direction in the plane, uniform (by rejection: no trigonometry).
    fn direction(&mut self) -> [f64; 2] {
        loop {
            let (x, y) = (self.uniform(-1.0, 1.0), self.uniform(-1.0, 1.0));
            let r2 = x * x + y * y;
            if (0.01..=1.0).contains(&r2) {
                let r = r2.sqrt();
                return [x / r, y / r];
            }
        }
    }
}

/// One hill (`amplitude > 0`) or hollow of a terrain: a smooth bump over an ellipse in
/// plan, `amplitude · (1 − s)³` where `s < 1` is the squared elliptical distance from
/// the centre, zero outside (flat to second order at its edge).
struct Bump {
    center: [f64; 2],
    /// Unit vector of the major axis.
    axis: [f64; 2],
    /// 1 / semi-axis², major and minor.
    inv2: [f64; 2],
    amplitude: f64,
}

/// A seeded relief over normalized plan coordinates (the terrain's longer side is 1,
/// centred on 0): a regional slope, a few hills and hollows, and three octaves of value
/// noise (rolling ground and roughness). Only `+ − × ÷` and `√`, which IEEE 754 rounds exactly, so the
/// same seed gives bit-identical heights on every platform.
struct Relief {
    slope: [f64; 2],
    bumps: Vec<Bump>,
    /// Lattices of values in `[−1, 1]` over `[−½, ½]²`: cells per side, amplitude, values.
    noise: Vec<(usize, f64, Vec<f64>)>,
}

impl Relief {
    fn new(seed: u64, half: [f64; 2]) -> Relief {
        let mut rng = SplitMix64(seed);
        let d = rng.direction();
        let g = rng.uniform(0.25, 0.6);
        let slope = [g * d[0], g * d[1]];
        let bumps = (0..10)
            .map(|_| {
                let center = [
                    rng.uniform(-1.2 * half[0], 1.2 * half[0]),
                    rng.uniform(-1.2 * half[1], 1.2 * half[1]),
                ];
                let major = rng.uniform(0.15, 0.45);
                let minor = major * rng.uniform(0.35, 1.0);
                let axis = rng.direction();
                let sign = if rng.uniform(0.0, 1.0) < 0.6 {
                    1.0
                } else {
                    -1.0
                };
                Bump {
                    center,
                    axis,
                    inv2: [1.0 / (major * major), 1.0 / (minor * minor)],
                    amplitude: sign * rng.uniform(0.3, 1.0),
                }
            })
            .collect();
        let noise = [(5, 0.3), (16, 0.08), (48, 0.025)]
            .into_iter()
            .map(|(n, a)| {
                let values = (0..(n + 1) * (n + 1))
                    .map(|_| rng.uniform(-1.0, 1.0))
                    .collect();
                (n, a, values)
            })
            .collect();
        Relief {
            slope,
            bumps,
            noise,
        }
    }

    fn height(&self, u: f64, v: f64) -> f64 {
        let mut h = self.slope[0] * u + self.slope[1] * v;
        for b in &self.bumps {
            let (du, dv) = (u - b.center[0], v - b.center[1]);
            let p = du * b.axis[0] + dv * b.axis[1];
            let q = dv * b.axis[0] - du * b.axis[1];
            let s = p * p * b.inv2[0] + q * q * b.inv2[1];
            if s < 1.0 {
                let t = 1.0 - s;
                h += b.amplitude * t * t * t;
            }
        }
        for (n, a, values) in &self.noise {
            // Bilinear in smoothstep weights: smooth across the lattice's cells.
            let cell = |w: f64| {
                let g = ((w + 0.5) * *n as f64).clamp(0.0, *n as f64);
                let i = (g.floor() as usize).min(n - 1);
                let t = g - i as f64;
                (i, t * t * (3.0 - 2.0 * t))
            };
            let ((i, s), (j, t)) = (cell(u), cell(v));
            let at = |i: usize, j: usize| values[j * (n + 1) + i];
            let bottom = at(i, j) + s * (at(i + 1, j) - at(i, j));
            let top = at(i, j + 1) + s * (at(i + 1, j + 1) - at(i, j + 1));
            h += a * (bottom + t * (top - bottom));
        }
        h
    }
}

/// A seeded, realistic terrain: an open height field over the rectangle `center.xy ±
/// size / 2`, `cells[0]` × `cells[1]` (each ≥ 1) cells of two triangles, facing +z. The
/// relief is a gentle regional slope, ten hills and hollows (some elongated into
/// ridges and valleys) and a little roughness, scaled so that the lowest vertex is at
/// `center.z − relief / 2` and the highest at `center.z + relief / 2` (`relief` ≥ 0; 0
/// gives a flat grid). `2 · cells[0] · cells[1]` triangles, `(cells[0] + 1)(cells[1] +
/// 1)` vertices, one boundary loop of `2 (cells[0] + cells[1])` edges.
///
/// The same `seed` gives bit-identical positions on every run and platform (the relief
/// uses only correctly rounded arithmetic). Other `cells` sample the same relief more or
/// less finely (scaled to the range by the extremes they sample). The command line's and
/// Python's defaults are centre 0,0,0, size 1000 × 1000, cells 100 × 100, relief 40,
/// seed 1: crossed by the default [`pit`].
///
/// ```
/// use meshbool::shapes::terrain;
///
/// let t = terrain([478600.0, 6772300.0, 400.0], [1000.0; 2], [100; 2], 40.0, 1)?;
/// let b = t.bounds().unwrap();
/// assert_eq!((t.triangle_count(), b.min[2], b.max[2]), (20000, 380.0, 420.0));
/// # Ok::<(), meshbool::Error>(())
/// ```
pub fn terrain(
    center: [f64; 3],
    size: [f64; 2],
    cells: [u32; 2],
    relief: f64,
    seed: u64,
) -> Result<Mesh> {
    finite_point("the terrain's centre", center)?;
    positive("the terrain's width", size[0])?;
    positive("the terrain's depth", size[1])?;
    at_least("the terrain's cells along x", cells[0], 1)?;
    at_least("the terrain's cells along y", cells[1], 1)?;
    non_negative("the terrain's relief", relief)?;
    not_too_many("terrain", 2 * u64::from(cells[0]) * u64::from(cells[1]))?;
    let (hw, hd) = (size[0] / 2.0, size[1] / 2.0);
    let scale = size[0].max(size[1]);
    let shape = Relief::new(seed, [hw / scale, hd / scale]);
    let mut m = heightfield(
        [center[0] - hw, center[1] - hd],
        [center[0] + hw, center[1] + hd],
        cells[0],
        cells[1],
        |x, y| shape.height((x - center[0]) / scale, (y - center[1]) / scale),
    );
    let (lo, hi) = m
        .positions
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p[2]), hi.max(p[2]))
        });
    for p in &mut m.positions {
        let t = if hi > lo {
            (p[2] - lo) / (hi - lo)
        } else {
            0.5
        };
        p[2] = center[2] + relief * (t - 0.5);
    }
    checked("terrain", m)
}

/// An open-pit design shell: a benched bowl, elliptical in plan, its rim the ellipse of
/// semi-axes `radius` (along x and y) about `center` at height `center.z`, its floor
/// `depth` below. From the rim down: `benches` (≥ 1) faces, each `depth / benches` high
/// at a batter of 2 vertical to 1 horizontal (63.4°), separated by flat berms `berm`
/// (≥ 0) wide, then a flat floor. Each face and berm is a band between two elliptical
/// rings of `segments` (≥ 3) vertices (a ring's semi-axes are the rim's less the
/// horizontal distance from the rim, vertex `i` at angle `360° i / segments` from +x);
/// the floor is a fan about a vertex at `center.xy`. The rings must fit: `depth / 2 +
/// (benches − 1) · berm` less than both radii.
///
/// An open surface, single-valued in plan, facing up (into the pit's air): with berms,
/// `2 · benches` rings, `segments · (4 · benches − 1)` triangles and `2 · benches ·
/// segments + 1` vertices (without: `benches + 1` rings, `segments · (2 · benches + 1)`
/// triangles, `(benches + 1) · segments + 1` vertices); one boundary loop, the rim, of
/// `segments` edges. The command line's and Python's defaults are centre 0,0,60, radius
/// 220 × 160, depth 140, 5 benches, berm 8, 64 segments: with the default [`terrain`] the
/// rim stands above the ground all round and the floor below it.
///
/// ```
/// let p = meshbool::shapes::pit([0.0, 0.0, 60.0], [220.0, 160.0], 140.0, 5, 8.0, 64)?;
/// let b = p.bounds().unwrap();
/// assert_eq!((p.triangle_count(), b.min[2], b.max), (1216, -80.0, [220.0, 160.0, 60.0]));
/// # Ok::<(), meshbool::Error>(())
/// ```
pub fn pit(
    center: [f64; 3],
    radius: [f64; 2],
    depth: f64,
    benches: u32,
    berm: f64,
    segments: u32,
) -> Result<Mesh> {
    finite_point("the pit's centre", center)?;
    positive("the pit's radius along x", radius[0])?;
    positive("the pit's radius along y", radius[1])?;
    positive("the pit's depth", depth)?;
    at_least("the pit's benches", benches, 1)?;
    non_negative("the pit's berm", berm)?;
    at_least("the pit's segments", segments, 3)?;
    let inset = depth / 2.0 + f64::from(benches - 1) * berm;
    if inset >= radius[0].min(radius[1]) {
        return Err(Error::InvalidParameter(format!(
            "the pit's faces and berms reach {inset} in from the rim (depth / 2 + \
             (benches − 1) · berm), not less than its smaller radius {}: fewer benches, \
             narrower berms or a shallower pit",
            radius[0].min(radius[1])
        )));
    }
    let rings_n = if berm > 0.0 { 2 * benches } else { benches + 1 };
    let n = u64::from(segments);
    not_too_many("pit", n * (2 * u64::from(rings_n) - 1))?;
    // (distance in from the rim, height) of each ring, rim first.
    let face = depth / f64::from(benches);
    let mut rings = vec![(0.0, center[2])];
    for k in 1..=benches {
        let (top_in, _) = *rings.last().expect("the rim");
        let z = if k == benches {
            center[2] - depth
        } else {
            center[2] - face * f64::from(k)
        };
        rings.push((top_in + face / 2.0, z));
        if berm > 0.0 && k < benches {
            rings.push((top_in + face / 2.0 + berm, z));
        }
    }
    let angles: Vec<(f64, f64)> = (0..segments)
        .map(|i| sin_cos_deg(360.0 * f64::from(i) / f64::from(segments)))
        .collect();
    let mut positions = Vec::with_capacity(rings.len() * segments as usize + 1);
    for &(inset, z) in &rings {
        let (a, b) = (radius[0] - inset, radius[1] - inset);
        positions.extend(
            angles
                .iter()
                .map(|&(s, c)| [center[0] + a * c, center[1] + b * s, z]),
        );
    }
    let floor = positions.len() as u32;
    positions.push([center[0], center[1], center[2] - depth]);
    let at = |ring: usize, i: u32| ring as u32 * segments + i % segments;
    let mut triangles = Vec::with_capacity((n * (2 * u64::from(rings_n) - 1)) as usize);
    for r in 0..rings.len() - 1 {
        for i in 0..segments {
            // Outer ring r, inner ring r + 1, angles counter-clockwise: faces up.
            triangles.push([at(r, i), at(r, i + 1), at(r + 1, i)]);
            triangles.push([at(r + 1, i), at(r, i + 1), at(r + 1, i + 1)]);
        }
    }
    let last = rings.len() - 1;
    for i in 0..segments {
        triangles.push([floor, at(last, i), at(last, i + 1)]);
    }
    checked("pit", Mesh::new_unchecked(positions, triangles))
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

    /// The z component of each triangle's (unnormalized) normal, and its length.
    fn normals(m: &Mesh) -> Vec<(f64, f64)> {
        (0..m.triangle_count())
            .map(|t| {
                let [a, b, c] = m.corners(t);
                let n = crate::vec3::cross(&crate::vec3::sub(&b, &a), &crate::vec3::sub(&c, &a));
                (n[2], crate::vec3::norm(&n))
            })
            .collect()
    }

    /// An open surface of one boundary loop: manifold, consistently oriented, welded,
    /// no degenerate triangles; the loop's vertices.
    fn assert_clean_sheet(m: &Mesh) -> (crate::measure::MeshStats, Vec<u32>) {
        let s = mesh_stats(m);
        assert!(!s.closed);
        assert_eq!(
            (
                s.non_manifold_edges,
                s.inconsistent_edges,
                s.degenerate_triangles,
                s.duplicate_triangles,
                s.unreferenced_vertices,
                s.components
            ),
            (0, 0, 0, 0, 0, 1)
        );
        assert_eq!(weld_exact(m).mesh.positions.len(), m.positions.len());
        let (mut loops, open) = crate::repair::boundary_loops(m);
        assert_eq!((loops.len(), open), (1, 0));
        let rim = loops.pop().unwrap();
        assert_eq!(rim.len(), s.boundary_edges);
        // A disc: Euler characteristic 1.
        assert_eq!(s.vertices + s.triangles - s.edges, 1);
        (s, rim)
    }

    const TERRAIN: ([f64; 3], [f64; 2], [u32; 2], f64, u64) =
        ([0.0; 3], [1000.0; 2], [100; 2], 40.0, 1);
    const PIT: ([f64; 3], [f64; 2], f64, u32, f64, u32) =
        ([0.0, 0.0, 60.0], [220.0, 160.0], 140.0, 5, 8.0, 64);

    fn default_terrain() -> Mesh {
        let (c, s, n, r, seed) = TERRAIN;
        terrain(c, s, n, r, seed).unwrap()
    }

    fn default_pit() -> Mesh {
        let (c, r, d, b, w, n) = PIT;
        pit(c, r, d, b, w, n).unwrap()
    }

    #[test]
    fn terrain_is_an_open_grid_facing_up_with_the_asked_relief() {
        for center in [[0.0; 3], [478600.0, 6772300.0, 400.0]] {
            let (_, size, cells, relief, seed) = TERRAIN;
            let m = terrain(center, size, cells, relief, seed).unwrap();
            let (s, rim) = assert_clean_sheet(&m);
            assert_eq!(
                (s.triangles, s.vertices, s.boundary_edges),
                (20000, 10201, 400)
            );
            assert_eq!(rim.len(), 400);
            let b = m.bounds().unwrap();
            let [x, y, z] = center;
            assert_eq!(b.min, [x - 500.0, y - 500.0, z - 20.0]);
            assert_eq!(b.max, [x + 500.0, y + 500.0, z + 20.0]);
            assert_eq!(s.projected_area.xy, 1e6);
            // Facing up, and smooth: no triangle steeper than 30°, the roughness included.
            for (nz, len) in normals(&m) {
                assert!(
                    nz > 0.0 && nz > len * 30f64.to_radians().cos(),
                    "{nz} {len}"
                );
            }
        }
        let m = terrain([1.0, 2.0, 3.0], [30.0, 10.0], [3, 2], 0.0, 7).unwrap();
        let s = assert_clean_sheet(&m).0;
        assert_eq!((s.triangles, s.vertices, s.boundary_edges), (12, 12, 10));
        assert!(m.positions.iter().all(|p| p[2] == 3.0));
    }

    #[test]
    fn terrain_is_a_function_of_its_seed() {
        let bits = |m: &Mesh| -> Vec<[u64; 3]> {
            m.positions.iter().map(|p| p.map(f64::to_bits)).collect()
        };
        let (c, s, n, r, _) = TERRAIN;
        let one = terrain(c, s, n, r, 1).unwrap();
        assert_eq!(bits(&one), bits(&terrain(c, s, n, r, 1).unwrap()));
        assert_eq!(one.triangles, terrain(c, s, n, r, 1).unwrap().triangles);
        for seed in [0, 2, u64::MAX] {
            let other = terrain(c, s, n, r, seed).unwrap();
            let moved = one
                .positions
                .iter()
                .zip(&other.positions)
                .filter(|(p, q)| p[2] != q[2])
                .count();
            assert!(moved > 10000, "seed {seed}: {moved} heights differ");
            assert!(one
                .positions
                .iter()
                .zip(&other.positions)
                .all(|(p, q)| p[..2] == q[..2]));
        }
        // The relief is not just its slope: hills and hollows, i.e. interior vertices
        // higher (and lower) than their eight neighbours.
        let z = |i: usize, j: usize| one.positions[j * 101 + i][2];
        let (mut peaks, mut pits) = (0, 0);
        for j in 1..100 {
            for i in 1..100 {
                let around = [
                    (0, 0),
                    (1, 0),
                    (2, 0),
                    (0, 1),
                    (2, 1),
                    (0, 2),
                    (1, 2),
                    (2, 2),
                ]
                .map(|(di, dj)| z(i + di - 1, j + dj - 1));
                peaks += usize::from(around.iter().all(|&w| w < z(i, j)));
                pits += usize::from(around.iter().all(|&w| w > z(i, j)));
            }
        }
        assert!(peaks > 0 && pits > 0, "{peaks} peaks, {pits} pits");
    }

    #[test]
    fn terrain_refuses_bad_parameters() {
        let (c, s, n, r, seed) = TERRAIN;
        assert!(terrain([f64::NAN, 0.0, 0.0], s, n, r, seed).is_err());
        assert!(terrain(c, [0.0, 1.0], n, r, seed).is_err());
        assert!(terrain(c, [1.0, -1.0], n, r, seed).is_err());
        assert!(terrain(c, [f64::INFINITY, 1.0], n, r, seed).is_err());
        assert!(terrain(c, s, [0, 1], r, seed).is_err());
        assert!(terrain(c, s, [1, 0], r, seed).is_err());
        assert!(terrain(c, s, n, -1.0, seed).is_err());
        assert!(terrain(c, s, n, f64::NAN, seed).is_err());
        let e = terrain(c, s, [1 << 14, 1 << 14], r, seed).unwrap_err();
        assert!(e.to_string().contains("more than"), "{e}");
        let e = terrain([1e9, 0.0, 0.0], [1e-9, 1e-9], [4, 4], r, seed).unwrap_err();
        assert!(e.to_string().contains("too small"), "{e}");
    }

    #[test]
    fn pit_is_a_benched_bowl_facing_up() {
        let m = default_pit();
        let (s, rim) = assert_clean_sheet(&m);
        // 10 rings of 64 and the floor's centre; 9 bands of 128 triangles and a fan of 64.
        assert_eq!((s.triangles, s.vertices, s.boundary_edges), (1216, 641, 64));
        assert!(rim.iter().all(|&v| m.positions[v as usize][2] == 60.0));
        let b = m.bounds().unwrap();
        assert_eq!(
            (b.min, b.max),
            ([-220.0, -160.0, -80.0], [220.0, 160.0, 60.0])
        );
        // The plan is the rim's polygon (single-valued: no overlap in plan).
        let rim_area = 32.0 * (2.0 * PI / 64.0).sin() * 220.0 * 160.0;
        assert!((s.projected_area.xy - rim_area).abs() < 1e-9 * rim_area);
        // Flat: four berms and the floor; steep: five faces, at the 2:1 batter on the
        // axes and steeper between them (the rings are ellipses of equal insets).
        let (mut flat, mut steep) = (0, 0);
        let batter = 1.0 / 5f64.sqrt();
        for (t, (nz, len)) in normals(&m).into_iter().enumerate() {
            assert!(nz > 0.0);
            let z = m.corners(t).map(|p| p[2]);
            if z[0] == z[1] && z[1] == z[2] {
                flat += 1;
                assert!([-80.0, 32.0, 4.0, -24.0, -52.0].contains(&z[0]), "{z:?}");
            } else {
                steep += 1;
                assert!(nz / len <= batter * (1.0 + 1e-12) && nz / len > 0.75 * batter);
            }
        }
        assert_eq!((flat, steep), (4 * 128 + 64, 5 * 128));
        // The floor: the 64 triangles at the bottom, 220 − 102 by 160 − 102.
        let floor: Vec<_> = m.positions.iter().filter(|p| p[2] == -80.0).collect();
        assert_eq!(floor.len(), 65);
        assert!(floor.iter().any(|p| p[..2] == [118.0, 0.0]));
        assert!(floor.iter().any(|p| p[..2] == [0.0, -58.0]));
    }

    #[test]
    fn pit_without_berms_and_its_refusals() {
        let m = pit([10.0, 20.0, 5.0], [50.0, 50.0], 30.0, 3, 0.0, 12).unwrap();
        let s = assert_clean_sheet(&m).0;
        // 4 rings of 12 and the centre: 3 bands of 24 and a fan of 12.
        assert_eq!((s.triangles, s.vertices, s.boundary_edges), (84, 49, 12));
        assert_eq!(m.bounds().unwrap().min[2], -25.0);
        let (c, r, d, b, w, n) = PIT;
        assert!(pit([0.0, f64::INFINITY, 0.0], r, d, b, w, n).is_err());
        assert!(pit(c, [0.0, 1.0], d, b, w, n).is_err());
        assert!(pit(c, r, -1.0, b, w, n).is_err());
        assert!(pit(c, r, d, 0, w, n).is_err());
        assert!(pit(c, r, d, b, -1.0, n).is_err());
        assert!(pit(c, r, d, b, f64::NAN, n).is_err());
        assert!(pit(c, r, d, b, w, 2).is_err());
        // Faces and berms 70 + 4 · 8 in from a rim of radius 100 fit; of 102 do not.
        assert!(pit(c, [300.0, 103.0], d, b, w, n).is_ok());
        let e = pit(c, [300.0, 102.0], d, b, w, n).unwrap_err();
        assert!(e.to_string().contains("reach 102"), "{e}");
        assert!(pit(c, r, d, b, w, u32::MAX).is_err());
    }

    #[test]
    fn default_pit_crosses_default_terrain_along_one_closed_curve() {
        use crate::ops;
        let (t, p) = (default_terrain(), default_pit());
        let c = ops::curves(&t, &p, &ops::CurvesOptions::default()).unwrap();
        let r = c.report();
        assert_eq!((r.loops, r.open_chains, r.touching_points), (1, 0, 0));
        // The rim stands above the ground all round and the floor below it: the seam
        // runs round the pit between them, longer than the floor's ellipse.
        let b = c.polylines[0]
            .points
            .iter()
            .fold([f64::INFINITY, 0.0], |[lo, hi], q| {
                [lo.min(q[2]), hi.max(q[2])]
            });
        assert!(b[0] > -20.0 && b[1] < 20.0, "{b:?}");
        assert!(r.total_length > 2.0 * PI * 58.0, "{}", r.total_length);
        // Split: the same seam; each surface in two groups whose areas add up to its own.
        let split = ops::split(&t, &p, &ops::SplitOptions::default()).unwrap();
        let sr = split.report(crate::Format::Obj);
        assert_eq!(sr.seam_points, r.points);
        let area = |names: [crate::Group; 2]| -> f64 {
            names
                .iter()
                .map(|n| sr.groups.iter().find(|g| g.name == *n).unwrap().piece.area)
                .sum()
        };
        use crate::Group::{AInB, AOutB, BInA, BOutA};
        assert_eq!(sr.groups.len(), 4);
        let (ta, pa) = (mesh_stats(&t).area, mesh_stats(&p).area);
        assert!((area([AInB, AOutB]) - ta).abs() < 1e-9 * ta);
        assert!((area([BInA, BOutA]) - pa).abs() < 1e-9 * pa);
        // Cut and fill of the terrain against the pit: material to dig inside the seam,
        // the pit's upper walls standing in the air outside it, over the pit's plan.
        let cf = ops::cutfill(&p, &t, &ops::CutFillOptions::default()).unwrap();
        assert!(cf.cut > 1e6 && cf.fill > 1e5, "{} {}", cf.cut, cf.fill);
        assert!((cf.common_area - cf.design_area).abs() < 1e-9 * cf.design_area);
        assert_eq!((cf.lines.len(), cf.topo_area), (1, 1e6));
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
