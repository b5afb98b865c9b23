//! The boolean at the front door ([`meshbool::ops::boolean`]) on two small meshes built
//! from the fuzz bytes, every operation.
//!
//! - Never a panic, whatever the meshes (triangle soups on a small grid included).
//! - Two valid solids (closed, outward-facing, not crossing themselves: boxes,
//!   tetrahedra, cylinders, cones, spheres and tori on a small integer grid, moved by exact axis
//!   permutations and reflections or by an inexact rotation, the pair scaled by a power of
//!   two up to 2^±1000): every operation succeeds, cuts every triangle (no failed
//!   triangles), gives a closed result (no boundary edges; non-manifold edges are not
//!   asked about: where two wedges of a result meet along an edge and join around both
//!   its ends, no vertex copy can split it, see docs/fuzzing.md), and the volumes satisfy vol(A∪B) + vol(A∩B) = vol(A) + vol(B), vol(A−B) = vol(A) − vol(A∩B)
//!   and vol(B−A) = vol(B) − vol(A∩B) up to the rounding of seam points to `f64` (a
//!   relative 1e-9).
//! - Where the bytes ask for it, every operation of two valid solids also snapped at a
//!   tolerance D ([`snapped`]): it succeeds, stays closed, gains no non-manifold edge,
//!   moves no vertex more than D, and changes the volume by what it reports, at most
//!   D × area.
//!
//! Run (docs/fuzzing.md): `cd crates/meshbool/fuzz && cargo +nightly fuzz run boolean
//! corpus/boolean`
#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use meshbool::measure::signed_volume;
use meshbool::ops::{boolean, BooleanOptions, BooleanOutput, Checks, Measures, Shape as Primitive};
use meshbool::{shapes, Mesh, Op};

/// A grid coordinate in −4 … 4.
fn grid(c: i8) -> f64 {
    f64::from(c.rem_euclid(9) - 4)
}

/// A length in 1 … `max`.
fn length(l: u8, max: u8) -> f64 {
    f64::from(l % max + 1)
}

fn point(p: [i8; 3]) -> [f64; 3] {
    p.map(grid)
}

#[derive(Arbitrary, Debug)]
enum Shape {
    Cuboid {
        min: [i8; 3],
        size: [u8; 3],
    },
    Tetrahedron([[i8; 3]; 4]),
    Cone {
        base: [i8; 3],
        radius: u8,
        top: u8,
        height: u8,
        segments: u8,
    },
    Cylinder {
        base: [i8; 3],
        radius: u8,
        height: u8,
        segments: u8,
    },
    Sphere {
        center: [i8; 3],
        radius: u8,
        segments: u8,
        rings: u8,
    },
    Torus {
        center: [i8; 3],
        minor: u8,
        gap: u8,
        segments: u8,
        sides: u8,
    },
    /// Anything: triangles with corners on the grid (welded exactly).
    Soup(Vec<[[i8; 3]; 3]>),
}

#[derive(Arbitrary, Debug)]
enum Motion {
    Stay,
    /// Axes permuted (one of six), then reflected (a bit per axis), then shifted: exact.
    Permute {
        perm: u8,
        reflect: u8,
        shift: [i8; 3],
    },
    /// A rotation by `angle`/256 of a turn about `axis`, then a shift by eighths: rounded.
    Rotate {
        axis: [i8; 3],
        angle: u8,
        shift: [i8; 3],
    },
}

#[derive(Arbitrary, Debug)]
struct Solid {
    shape: Shape,
    motion: Motion,
}

#[derive(Arbitrary, Debug)]
struct Case {
    /// Every operation of two valid solids also snapped at D = 2^−(snap mod 16) grid
    /// units (scaled with the meshes) when present (first: the short inputs libFuzzer
    /// starts from end before the last fields, which then take their defaults).
    snap: Option<u8>,
    a: Solid,
    b: Solid,
    /// Both meshes scaled by 2^(scale mod 2001 − 1000) when present.
    scale: Option<i16>,
}

impl Solid {
    /// The mesh, and whether it is a valid solid by construction (closed, outward-facing,
    /// not crossing itself, positive volume).
    fn build(&self) -> Option<(Mesh, bool)> {
        let (mesh, solid) = match &self.shape {
            Shape::Cuboid { .. }
            | Shape::Cylinder { .. }
            | Shape::Cone { .. }
            | Shape::Sphere { .. } => (self.primitive()?.mesh().ok()?, true),
            Shape::Tetrahedron(p) => {
                let soup = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]
                    .map(|t: [usize; 3]| t.map(|k| point(p[k])));
                let mesh = Mesh::from_soup(&soup);
                let v = signed_volume(&mesh);
                let mesh = if v < 0.0 { mesh.flipped() } else { mesh };
                let solid = v != 0.0 && mesh_is_tetrahedron(&mesh);
                (mesh, solid)
            }
            Shape::Torus {
                center,
                minor,
                gap,
                segments,
                sides,
            } => {
                let minor = length(*minor, 2);
                let m = shapes::torus(
                    point(*center),
                    minor + length(*gap, 3),
                    minor,
                    u32::from(segments % 6 + 3),
                    u32::from(sides % 5 + 3),
                );
                (m, true)
            }
            Shape::Soup(tris) => {
                let soup: Vec<[[f64; 3]; 3]> = tris.iter().take(16).map(|t| t.map(point)).collect();
                (Mesh::from_soup(&soup), false)
            }
        };
        Some((self.moved(mesh), solid))
    }

    /// The shapes `meshbool make` builds, as its [`Primitive`] ([`meshbool::ops::make()`]).
    fn primitive(&self) -> Option<Primitive> {
        Some(match self.shape {
            Shape::Cuboid { min, size } => {
                let min = point(min);
                Primitive::Cube {
                    min,
                    max: [0, 1, 2].map(|k| min[k] + length(size[k], 4)),
                }
            }
            Shape::Cylinder {
                base,
                radius,
                height,
                segments,
            } => Primitive::Cylinder {
                base: point(base),
                radius: length(radius, 4),
                height: length(height, 4),
                segments: u32::from(segments % 8 + 3),
            },
            Shape::Cone {
                base,
                radius,
                top,
                height,
                segments,
            } => {
                let radius = length(radius, 4);
                Primitive::Cone {
                    base: point(base),
                    radius,
                    // An apex, or a frustum's top no wider than its bottom.
                    top_radius: f64::from(top) % (radius + 1.0),
                    height: length(height, 4),
                    segments: u32::from(segments % 8 + 3),
                }
            }
            Shape::Sphere {
                center,
                radius,
                segments,
                rings,
            } => Primitive::Sphere {
                center: point(center),
                radius: length(radius, 4),
                segments: u32::from(segments % 8 + 3),
                rings: u32::from(rings % 6 + 2),
            },
            _ => return None,
        })
    }

    fn moved(&self, mesh: Mesh) -> Mesh {
        match self.motion {
            Motion::Stay => mesh,
            Motion::Permute {
                perm,
                reflect,
                shift,
            } => {
                const PERMS: [[usize; 3]; 6] = [
                    [0, 1, 2],
                    [1, 2, 0],
                    [2, 0, 1],
                    [1, 0, 2],
                    [0, 2, 1],
                    [2, 1, 0],
                ];
                let p = PERMS[usize::from(perm % 6)];
                let sign = |k: usize| if reflect >> k & 1 == 1 { -1.0 } else { 1.0 };
                let shift = point(shift);
                let (positions, triangles) = mesh.into_parts();
                let positions = positions
                    .iter()
                    .map(|q| [0, 1, 2].map(|k| sign(k) * q[p[k]] + shift[k]))
                    .collect();
                let m = Mesh::new(positions, triangles).expect("indices unchanged");
                // An odd permutation or an odd number of reflections turns the solid inside out.
                let odd = (perm % 6 >= 3) ^ ((reflect & 7).count_ones() % 2 == 1);
                if odd {
                    m.flipped()
                } else {
                    m
                }
            }
            Motion::Rotate { axis, angle, shift } => {
                let axis = point(axis);
                if axis == [0.0; 3] {
                    return mesh;
                }
                let angle = f64::from(angle) / 256.0 * std::f64::consts::TAU;
                shapes::rigid_motion(&mesh, axis, angle, point(shift).map(|c| c / 8.0))
            }
        }
    }
}

/// A tetrahedron from the soup welds to 4 vertices only when its corners are distinct.
fn mesh_is_tetrahedron(m: &Mesh) -> bool {
    m.vertex_count() == 4 && m.triangle_count() == 4
}

/// `x` times 2^e, in two steps (2^e alone is not a normal `f64` for every `e` used here).
fn times_pow2(x: f64, e: i32) -> f64 {
    x * 2f64.powi(e / 2) * 2f64.powi(e - e / 2)
}

/// The sum of the magnitudes of the terms of `m`'s signed volume: per triangle, the six
/// products of the determinant p0 · (p1 × p2) taken apart, in absolute value, over 6. What
/// the rounding of the volume's `f64` sum is relative to: a determinant computed in
/// floating point errs by a few ulps of these products, not of its value (a zero-area
/// triangle far from the origin has a determinant near 0 computed from products of its
/// coordinates' size).
fn volume_terms(m: &Mesh) -> f64 {
    let p = m.positions();
    m.triangles()
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| p[v as usize]);
            let products = a[0].abs() * ((b[1] * c[2]).abs() + (b[2] * c[1]).abs())
                + a[1].abs() * ((b[2] * c[0]).abs() + (b[0] * c[2]).abs())
                + a[2].abs() * ((b[0] * c[1]).abs() + (b[1] * c[0]).abs());
            products / 6.0
        })
        .sum()
}

/// `m` with every coordinate multiplied by 2^e ([`times_pow2`]).
fn scaled(m: &Mesh, e: i32) -> Mesh {
    let mut m = m.clone();
    for p in m.positions_mut() {
        for x in p.iter_mut() {
            *x = times_pow2(*x, e);
        }
    }
    m
}

/// The boolean `op` of two valid solids snapped at `d` (in grid units; the meshes are
/// scaled by 2^`e`), against the exact result's measures `exact` and volume `v` (at grid
/// scale): it succeeds and stays closed, gains no non-manifold edge, moves no vertex more
/// than `d`, and its volume is the exact one plus the reported change, which is within
/// `d` × the exact result's area (at scales whose volumes `f64` holds).
fn snapped(a: &Mesh, b: &Mesh, op: Op, d: f64, e: i32, exact: &Measures, v: f64) {
    let options = BooleanOptions {
        snap: times_pow2(d, e),
        ..BooleanOptions::default()
    };
    if !(options.snap.is_normal()) {
        return; // the tolerance itself under- or overflows at this scale
    }
    let out = boolean(a, b, op, &options)
        .unwrap_or_else(|err| panic!("{op:?} of two valid solids snapped at {d} failed: {err}"));
    let report = out.snap.expect("a snap report");
    let m = Measures::of(&out.mesh);
    assert_eq!(m.boundary_edges, 0, "{op:?} snapped at {d}: not closed");
    assert!(
        m.non_manifold_edges <= exact.non_manifold_edges,
        "{op:?} snapped at {d}: {} non-manifold edges, {} before",
        m.non_manifold_edges,
        exact.non_manifold_edges
    );
    assert!(
        report.max_move <= options.snap,
        "{op:?} snapped at {d}: a vertex moved {} > D = {}",
        report.max_move,
        options.snap
    );
    // At grid scale: the change is the one reported, within D × area (to the rounding of
    // the volumes and areas summed, a relative 1e-9 of the volume and of the bound);
    // only where volumes and areas at the meshes' scale neither overflow nor underflow
    // (the cube of 2^±300 is well inside `f64`'s range).
    if e.abs() > 300 {
        return;
    }
    let snapped = scaled(&out.mesh, -e);
    let change = signed_volume(&snapped) - v;
    let reported = times_pow2(report.volume_change, -3 * e);
    let area = times_pow2(exact.area, -2 * e);
    // Plus the rounding of the volume sums themselves: a relative 1e-9 of the sum of the
    // terms' magnitudes, twice the snapped result's (the exact result's terms are of the
    // same size: the same surface but for moves under `d`). A result of almost no volume
    // still sums terms of its coordinates' size.
    let slack = 1e-9 * (v.abs() + d * area + 2.0 * volume_terms(&snapped));
    assert!(
        (change - reported).abs() <= slack,
        "{op:?} snapped at {d}: volume changed by {change}, {reported} reported (slack {slack}: v {v}, area {area}, terms {})", volume_terms(&snapped)
    );
    assert!(
        change.abs() <= d * area + slack,
        "{op:?} snapped at {d}: volume changed by {change} > D × area = {}",
        d * area
    );
}

fuzz_target!(
    init: {
        // One worker thread: the machines that run this have two cores for everything.
        let _ = rayon::ThreadPoolBuilder::new().num_threads(1).build_global();
    },
    |case: Case| {
        let (Some((a, a_solid)), Some((b, b_solid))) = (case.a.build(), case.b.build()) else {
            return;
        };
        let e = case.scale.map_or(0, |s| i32::from(s).rem_euclid(2001) - 1000);
        let (sa, sb) = (scaled(&a, e), scaled(&b, e));
        if !(a_solid && b_solid) {
            let forced = BooleanOptions {
                checks: Checks { force: true, ..Checks::default() },
                ..BooleanOptions::default()
            };
            for op in Op::ALL {
                let _ = boolean(&sa, &sb, op, &BooleanOptions::default());
                if let Ok(out) = boolean(&sa, &sb, op, &forced) {
                    let _ = out.report();
                }
            }
            return;
        }
        let run = |op: Op| -> f64 {
            let out: BooleanOutput = boolean(&sa, &sb, op, &BooleanOptions::default())
                .unwrap_or_else(|err| panic!("{op:?} of two valid solids failed: {err}"));
            assert!(out.failed.is_empty(), "{op:?}: failed triangles {:?}", out.failed);
            let m = Measures::of(&out.mesh);
            assert_eq!(
                m.boundary_edges, 0,
                "{op:?}: the result of two solids must be closed"
            );
            let v = signed_volume(&scaled(&out.mesh, -e));
            if let Some(k) = case.snap {
                snapped(&sa, &sb, op, 2f64.powi(-i32::from(k % 16)), e, &m, v);
            }
            v
        };
        let (va, vb) = (signed_volume(&a), signed_volume(&b));
        let [u, i, d, r] = Op::ALL.map(run);
        let tol = 1e-9 * (va.abs() + vb.abs());
        let close = |x: f64, y: f64| (x - y).abs() <= tol;
        assert!(close(u + i, va + vb), "vol(A∪B) + vol(A∩B) = {u} + {i} ≠ vol(A) + vol(B) = {va} + {vb}");
        assert!(close(d, va - i), "vol(A−B) = {d} ≠ vol(A) − vol(A∩B) = {va} − {i}");
        assert!(close(r, vb - i), "vol(B−A) = {r} ≠ vol(B) − vol(A∩B) = {vb} − {i}");
    }
);
