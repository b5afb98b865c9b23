//! The first pass over every triangle: the bad ones, the area that bounds the volume
//! budget, and the candidates of the first gathering.

use rayon::prelude::*;

use super::grid::Grid;
use super::shape::{badness, max, min, tri_box};
use crate::bvh::Box3;
use crate::par::Grain;
use crate::vec3::{cross, dot, sub};
use crate::Mesh;

/// The first pass, over every triangle: the bad ones (key, id) in triangle order (only
/// those with a corner in `seam` when given), the area (with `seam`: of the triangles
/// touching the halo, a lower bound), and the triangles touching the
/// halo's marked cells with their [`Grid::key`]s (the candidates of the first gathering).
/// Input triangles with their [`Grid::key`]s: (id, key).
pub(super) type Keyed = Vec<(u32, u32)>;

/// What [`Scan::of`] finds in a piece of the triangles: bad ones, area, candidates.
pub(super) type ScanPiece = (Vec<(f64, u32)>, f64, Keyed);

pub(super) struct Scan {
    pub(super) bad: Vec<(f64, u32)>,
    pub(super) area: f64,
    pub(super) candidates: Vec<(u32, u32)>,
}

impl Scan {
    /// `halos`: the halo, and the cells in it or next to it; `halo_box`: a box around the
    /// halo's cells (`None`: no halo).
    pub(super) fn of(
        mesh: &Mesh,
        d: f64,
        grid: &Grid,
        seam: Option<&[bool]>,
        halos: [&Grid; 2],
        halo_box: Option<Box3>,
    ) -> Scan {
        const PIECE: usize = 1 << 13;
        let [halo, next_to_halo] = halos;
        let d2 = d * d;
        // A corner's cell, with bit [`Grid::NEAR_BIT`] set where the cell is in or next to
        // the halo: a triangle spanning at most two cells along each axis with no corner
        // there does not touch the halo.
        let cell = |p: &[f64; 3]| {
            let c = [0, 1, 2].map(|k| grid.cell(p[k], k));
            grid.pack(c) | u32::from(next_to_halo.get(grid.index(c))) << Grid::NEAR_BIT
        };
        // Each vertex's sides of the halo's box it is beyond (a bit per side): a triangle
        // whose corners are all beyond one side misses the box (an exact box test, on
        // a byte per corner). Nothing is near without a halo.
        let beyond: Vec<u8> = match halo_box {
            Some(hb) => mesh
                .positions
                .par_iter()
                .grained()
                .with_min_len(PIECE)
                .map(|p| {
                    (0..3).fold(0u8, |code, k| {
                        code | u8::from(p[k] < hb[0][k]) << (2 * k)
                            | u8::from(p[k] > hb[1][k]) << (2 * k + 1)
                    })
                })
                .collect(),
            None => Vec::new(),
        };
        let pieces: Vec<ScanPiece> = mesh
            .triangles
            .par_chunks(PIECE)
            .grained()
            .enumerate()
            .map(|(k, tris)| {
                let (mut bad, mut area, mut near) = (Vec::new(), 0.0, Vec::new());
                let pos = &mesh.positions;
                for (i, tri) in tris.iter().enumerate() {
                    let t = (k * PIECE + i) as u32;
                    // Outside the halo's box (most triangles, far from the seam) no cell is
                    // needed, nor (with a seam) anything else. Else, with no corner near
                    // the halo, only a triangle spanning more than two cells along an axis
                    // may touch it.
                    let in_box = !beyond.is_empty()
                        && beyond[tri[0] as usize]
                            & beyond[tri[1] as usize]
                            & beyond[tri[2] as usize]
                            == 0;
                    if !in_box && seam.is_some() {
                        continue;
                    }
                    let p = [
                        pos[tri[0] as usize],
                        pos[tri[1] as usize],
                        pos[tri[2] as usize],
                    ];
                    let key = Some(()).filter(|_| in_box).and_then(|_| {
                        let c = p.map(|q| cell(&q));
                        if (c[0] | c[1] | c[2]) >> Grid::NEAR_BIT != 0 {
                            Some(grid.key(c)).filter(|&key| halo.touches_key(key, || p))
                        } else {
                            Some(Grid::WIDE).filter(|_| grid.wide(c) && halo.touches(&tri_box(&p)))
                        }
                    });
                    if let Some(key) = key {
                        near.push((t, key));
                    } else if seam.is_some() {
                        // Far from the seam: neither bad nor counted in the area (the
                        // area of the triangles near it bounds the whole from below).
                        continue;
                    }
                    let (u, v, w) = (sub(&p[1], &p[0]), sub(&p[2], &p[0]), sub(&p[2], &p[1]));
                    let c = cross(&u, &v);
                    let twice2 = dot(&c, &c);
                    area += twice2.sqrt();
                    if seam.is_some_and(|s| !tri.iter().any(|&v| s[v as usize])) {
                        continue;
                    }
                    let (eu, ev, ew) = (dot(&u, &u), dot(&v, &v), dot(&w, &w));
                    let (short, long) = (min(min(eu, ev), ew), max(max(eu, ev), ew));
                    // A filter, squared: edge² ≤ d², or (2 · area)² ≤ d² · longest² (≤ so
                    // that zero edges and areas pass where d² underflows); `badness`
                    // decides, as everywhere else.
                    if short <= d2 || twice2 <= d2 * long {
                        if let Some(key) = badness(&p, d) {
                            bad.push((key, t));
                        }
                    }
                }
                (bad, area / 2.0, near)
            })
            .collect();
        let mut scan = Scan {
            bad: Vec::new(),
            area: 0.0,
            candidates: Vec::new(),
        };
        for (bad, area, near) in pieces {
            scan.bad.extend(bad);
            scan.area += area;
            scan.candidates.extend(near);
        }
        scan
    }
}
