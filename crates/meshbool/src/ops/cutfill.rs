//! Cut and fill between two surfaces (`meshbool cutfill DESIGN TOPO`): how much material
//! lies above a design surface (cut) and how much is missing below it (fill), over the
//! plan footprint both surfaces cover.
//!
//! Computed with the exact booleans: each surface, faced up, becomes the solid below it
//! down to a common floor (a curtain), `T` for the topography and `D` for the design; `T⁺`
//! and `D⁺` are the same raised above everything (walls at the same plan positions, so
//! the same footprint). Then:
//!
//! - cut = vol(T ∩ D⁺) − vol(T ∩ D): the topography over the common footprint, less what
//!   lies under both;
//! - fill = vol(D ∩ T⁺) − vol(T ∩ D);
//! - common footprint = (vol(T⁺ ∩ D⁺) − vol(T ∩ D)) / raise.
//!
//! Every inside/outside decision is the booleans' (exact); the volumes are sums over the
//! results' rounded coordinates. The surfaces must be single-valued in plan (no
//! overhangs: a vertical wall or a fold has no meaning as a height).

use serde::Serialize;
use web_time::Instant;

use super::{
    boolean, curves, with_threads, BooleanOptions, Checks, CurvesOptions, Input, RunOptions, SCHEMA,
};
use crate::boolean::Op;
use crate::intersect::PolylineXyz;
use crate::measure::{projected_area, signed_volume, Plane};
use crate::repair::{curtain_to, orient, Facing};
use crate::{Error, Mesh, Result};

/// Options of [`cutfill`].
#[derive(Clone, Debug, Default)]
pub struct CutFillOptions {
    /// Threads.
    pub run: RunOptions,
}

/// The result of [`cutfill`].
#[derive(Clone, Debug)]
pub struct CutFillOutput {
    /// Volume where the topography is above the design.
    pub cut: f64,
    /// Volume where the topography is below the design.
    pub fill: f64,
    /// Plan (XY) area of the design surface.
    pub design_area: f64,
    /// Plan area of the topography.
    pub topo_area: f64,
    /// Plan area both cover (where cut and fill are measured).
    pub common_area: f64,
    /// Where the surfaces cross or touch (zero thickness), as polylines.
    pub lines: Vec<PolylineXyz>,
    /// Triangles reversed to face up, of the design and of the topography.
    pub faced_up: [usize; 2],
    /// Time, in seconds.
    pub seconds: f64,
}

/// What [`CutFillOutput::report`] tells: the JSON of `meshbool cutfill --json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CutFillReport {
    /// [`SCHEMA`].
    pub schema: u32,
    /// [`CutFillOutput::cut`].
    pub cut: f64,
    /// [`CutFillOutput::fill`].
    pub fill: f64,
    /// Cut less fill.
    pub net: f64,
    /// [`CutFillOutput::design_area`].
    pub design_plan_area: f64,
    /// [`CutFillOutput::topo_area`].
    pub topo_plan_area: f64,
    /// [`CutFillOutput::common_area`].
    pub common_plan_area: f64,
    /// Polylines where the surfaces meet.
    pub zero_lines: usize,
    /// Their total length.
    pub zero_line_length: f64,
    /// [`CutFillOutput::faced_up`].
    pub faced_up: [usize; 2],
    /// [`CutFillOutput::seconds`].
    pub seconds: f64,
}

impl CutFillOutput {
    /// The output of surfaces computed at unit size, for the surfaces scaled by `2^e`:
    /// lengths times `2^e`, areas `2^2e`, volumes `2^3e`.
    fn scale_back(&mut self, e: i32) {
        use super::scaled_measure;
        let cube = |v: f64| scaled_measure(v, e, 3);
        (self.cut, self.fill) = (cube(self.cut), cube(self.fill));
        for a in [
            &mut self.design_area,
            &mut self.topo_area,
            &mut self.common_area,
        ] {
            *a = scaled_measure(*a, e, 2);
        }
        for l in &mut self.lines {
            super::scale_points(&mut l.points, e);
        }
    }

    /// The report.
    pub fn report(&self) -> CutFillReport {
        CutFillReport {
            schema: SCHEMA,
            cut: self.cut,
            fill: self.fill,
            net: self.cut - self.fill,
            design_plan_area: self.design_area,
            topo_plan_area: self.topo_area,
            common_plan_area: self.common_area,
            zero_lines: self.lines.len(),
            zero_line_length: self.lines.iter().map(PolylineXyz::length).sum::<f64>() + 0.0,
            faced_up: self.faced_up,
            seconds: self.seconds,
        }
    }
}

/// Cut and fill of `topo` against `design` (both surfaces, faced up here), over the plan
/// footprint both cover. See the module's documentation for how; an error when either
/// has no triangles or a boolean refuses a solid built from it (a surface with overhangs).
pub fn cutfill<'a>(
    design: impl Into<Input<'a>>,
    topo: impl Into<Input<'a>>,
    opts: &CutFillOptions,
) -> Result<CutFillOutput> {
    let (design, topo): (Input<'a>, Input<'a>) = (design.into(), topo.into());
    let unit = |d: Input<'_>, t: Input<'_>| cutfill(d, t, opts);
    if let Some(out) = super::at_unit_scale(design, topo, unit, CutFillOutput::scale_back) {
        return out;
    }
    with_threads(opts.run.threads, || {
        let d = design.operand("design", &Checks::NONE)?;
        let t = topo.operand("topography", &Checks::NONE)?;
        let start = Instant::now();
        let (d_up, rd) = orient(d.mesh(), Facing::ZUp);
        let (t_up, rt) = orient(t.mesh(), Facing::ZUp);
        let (Some(bd), Some(bt)) = (d_up.bounds(), t_up.bounds()) else {
            let empty = if d_up.is_empty() { &d } else { &t };
            return Err(Error::Empty {
                name: empty.name().to_string(),
                needs: "cut and fill need two surfaces",
            });
        };
        // A floor below both, and a raise that lifts either surface above the other, by a
        // margin of the surfaces' own size (any fixed length would make the curtains'
        // walls needles on a small model and slivers on a large one).
        let (lo, hi) = (bd.min[2].min(bt.min[2]), bd.max[2].max(bt.max[2]));
        let size = (0..3)
            .map(|k| bd.max[k].max(bt.max[k]) - bd.min[k].min(bt.min[k]))
            .fold(0.0f64, f64::max);
        let margin = (hi - lo).max(size).max(f64::MIN_POSITIVE);
        let (floor, raise) = (lo - margin, (hi - lo) + margin);
        // The design's solids stand on a floor below the topography's: every intersection
        // below is bounded beneath by the topography's floor alone, so its volume is the
        // same as on one floor, and the two floors never lie on each other (coplanar caps
        // of long thin triangles, each against each, cost as much as all the rest).
        let design_floor = floor - margin;
        let solid = |m: &Mesh, floor: f64| curtain_to(m, floor).0;
        let raised = |m: &Mesh, floor: f64| {
            let mut up = m.clone();
            for p in &mut up.positions {
                p[2] += raise;
            }
            curtain_to(&up, floor).0
        };
        let ((ts, ds), (tr, dr)) = crate::par::join(
            || (solid(&t_up, floor), solid(&d_up, design_floor)),
            || (raised(&t_up, floor), raised(&d_up, design_floor)),
        );
        let bopts = BooleanOptions {
            checks: Checks {
                self_intersections: false,
                orient: false,
                ..Checks::default()
            },
            ..BooleanOptions::default()
        };
        let meet = |a: &Mesh, b: &Mesh| -> Result<Mesh> {
            Ok(boolean(a, b, Op::Intersection, &bopts)?.mesh)
        };
        let both = signed_volume(&meet(&ts, &ds)?);
        let cut = signed_volume(&meet(&ts, &dr)?) - both;
        let fill = signed_volume(&meet(&ds, &tr)?) - both;
        // Both raised, less both as they are: the common footprint times the raise.
        let common = (signed_volume(&meet(&tr, &dr)?) - both) / raise;
        let lines = curves(&t_up, &d_up, &CurvesOptions::default())?.polylines;
        Ok(CutFillOutput {
            // Clamped at zero: a difference of two rounded volumes of equal solids.
            cut: cut.max(0.0) + 0.0,
            fill: fill.max(0.0) + 0.0,
            design_area: projected_area(&d_up, Plane::XY),
            topo_area: projected_area(&t_up, Plane::XY),
            common_area: common,
            lines,
            faced_up: [rd.flipped, rt.flipped],
            seconds: start.elapsed().as_secs_f64(),
        })
    })?
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::heightfield;

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs().max(1.0)
    }

    #[test]
    fn two_planes_crossing_along_a_line() {
        // Design z = 0, topography z = x − 5, both over [0, 10]²: cut and fill are the two
        // wedges, 10 · 5 · 5 / 2 each; they meet along x = 5.
        let design = heightfield([0.0, 0.0], [10.0, 10.0], 4, 4, |_, _| 0.0);
        let topo = heightfield([0.0, 0.0], [10.0, 10.0], 4, 4, |x, _| x - 5.0);
        let out = cutfill(&design, &topo, &CutFillOptions::default()).unwrap();
        assert!(rel(out.cut, 125.0) < 1e-12, "{}", out.cut);
        assert!(rel(out.fill, 125.0) < 1e-12, "{}", out.fill);
        assert!(rel(out.common_area, 100.0) < 1e-12);
        let r = out.report();
        assert_eq!(r.zero_lines, 1);
        assert!(rel(r.zero_line_length, 10.0) < 1e-12);
        // Turned over, the answer is the same (the surfaces are faced up first).
        let out2 = cutfill(&design.flipped(), &topo, &CutFillOptions::default()).unwrap();
        assert_eq!(out2.faced_up[0], design.triangles.len());
        assert!(rel(out2.cut, 125.0) < 1e-12);
    }

    #[test]
    fn a_stockpile_on_flat_ground_and_a_surface_against_itself() {
        // A square pyramid of height 3 over [−1, 1]² on the plane z = 0: cut 4 · 3 / 3.
        let p = |x: f64, y: f64, z: f64| [x, y, z];
        let pile = Mesh::new(
            vec![
                p(-1.0, -1.0, 0.0),
                p(1.0, -1.0, 0.0),
                p(1.0, 1.0, 0.0),
                p(-1.0, 1.0, 0.0),
                p(0.0, 0.0, 3.0),
            ],
            vec![[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]],
        )
        .unwrap();
        let ground = heightfield([-2.0, -2.0], [2.0, 2.0], 2, 2, |_, _| 0.0);
        let out = cutfill(&ground, &pile, &CutFillOptions::default()).unwrap();
        assert!(rel(out.cut, 4.0) < 1e-12, "{}", out.cut);
        assert!(out.fill.abs() < 1e-12, "{}", out.fill);
        assert!(rel(out.common_area, 4.0) < 1e-12);
        assert!(rel(out.design_area, 16.0) < 1e-12 && rel(out.topo_area, 4.0) < 1e-12);
        let same = cutfill(&pile, &pile, &CutFillOptions::default()).unwrap();
        assert!(same.cut.abs() < 1e-12 && same.fill.abs() < 1e-12);
    }

    /// Cut and fill of `terrain` against a plane at its mean height covering it: the
    /// common footprint is the terrain's, and cut − fill is the volume between them, ∫ (z −
    /// mean) dA = 0 by the choice of mean. The output, and how much the terrain's plan area
    /// exceeds its signed plan area (its folds' extra layers).
    fn against_its_mean_plane(terrain: &Mesh) -> (CutFillOutput, f64) {
        let (up, _) = orient(&crate::weld_exact(terrain).mesh, Facing::ZUp);
        // ∫ z dA over the terrain's plan (prisms down to z = 0) and its plan area, both
        // with signed plan areas: where a terrain folds over itself (the triangles reversed
        // to make it consistent face down), a fold's three layers count once.
        let (mut prisms, mut area) = (0.0, 0.0);
        for t in &up.triangles {
            let [a, b, c] = t.map(|v| up.positions[v as usize]);
            let s = ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])) / 2.0;
            prisms += s * (a[2] + b[2] + c[2]) / 3.0;
            area += s;
        }
        let mean = prisms / area;
        let b = up.bounds().unwrap();
        let plane = heightfield(
            [b.min[0] - 10.0, b.min[1] - 10.0],
            [b.max[0] + 10.0, b.max[1] + 10.0],
            3,
            3,
            |_, _| mean,
        );
        let out = cutfill(&plane, terrain, &CutFillOptions::default()).unwrap();
        assert!(
            rel(out.common_area, area) < 1e-9,
            "{} vs {area}",
            out.common_area
        );
        assert!(out.cut > 0.0 && out.fill > 0.0);
        assert!(
            (out.cut - out.fill).abs() < 1e-9 * out.cut,
            "{} {}",
            out.cut,
            out.fill
        );
        (out, projected_area(&up, Plane::XY) - area)
    }

    #[test]
    fn terrain_against_a_plane_at_its_mean_height() {
        use crate::test_util::{shared_data, terrain_and_drill, wound_badly, UTM};
        for center in [[0.0; 3], UTM] {
            // Badly wound, not folded: faced up, its plan area is its signed plan area.
            let terrain = wound_badly(&terrain_and_drill(center).0);
            let (out, folds) = against_its_mean_plane(&terrain);
            assert_eq!(out.faced_up[1], 5);
            assert!(folds.abs() < 1e-9 * 360_000.0, "{folds}");
        }
        // The real terrain folds over itself in one place: the 22 triangles reversed to
        // make it consistent face down.
        if let Some(terrain) = shared_data("kirra_terrain.obj") {
            let (out, folds) = against_its_mean_plane(&terrain);
            assert_eq!(out.faced_up[1], 22);
            assert!(folds > 2.0, "{folds}");
        }
    }

    /// A topography whose boundary passes twice through one vertex (two squares touching
    /// at a corner, as a tile of a terrain or a survey with a gap can be): its curtain
    /// solid has a wall edge of four triangles, used as often each way, and cut and fill
    /// are answered, not refused.
    #[test]
    fn a_surface_pinched_at_a_vertex() {
        let p = |x: f64, y: f64| [x, y, 0.0];
        let topo = Mesh::new(
            vec![
                p(0.0, 0.0),
                p(1.0, 0.0),
                p(1.0, 1.0),
                p(0.0, 1.0),
                p(2.0, 1.0),
                p(2.0, 2.0),
                p(1.0, 2.0),
            ],
            vec![[0, 1, 2], [0, 2, 3], [2, 4, 5], [2, 5, 6]],
        )
        .unwrap();
        let design = heightfield([-1.0, -1.0], [3.0, 3.0], 4, 4, |_, _| 2.0);
        let out = cutfill(&design, &topo, &CutFillOptions::default()).unwrap();
        assert!(rel(out.fill, 4.0) < 1e-12, "{}", out.fill);
        assert!(out.cut.abs() < 1e-12, "{}", out.cut);
        assert!(rel(out.common_area, 2.0) < 1e-12, "{}", out.common_area);
    }
}
