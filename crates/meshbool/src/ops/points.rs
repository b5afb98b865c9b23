//! Point queries at the front door: where points lie against a mesh — inside, outside, or
//! exactly on its surface — with the winding number at each (`meshbool classify`).

use rayon::prelude::*;
use serde::Serialize;
use web_time::Instant;

use super::{with_threads, Checks, Input, RunOptions, SCHEMA};
use crate::classify::FastWinding;
use crate::edges::EdgeCounts;
use crate::query::TriangleIndex;
use crate::{Error, Mesh, Result};

/// Options of [`classify_points`].
#[derive(Clone, Debug, Default)]
pub struct ClassifyOptions {
    /// Checks of the mesh (default: every check, as for a boolean operand, so that a
    /// point is classified against the solid a boolean would see).
    pub checks: Checks,
    /// Threads.
    pub run: RunOptions,
}

/// Where a point lies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum PointClass {
    /// Inside a closed mesh (winding number at least 1/2), or behind an open surface
    /// (winding number above 0: on the side its normals point away from).
    Inside,
    /// Outside, or in front of an open surface.
    Outside,
    /// Exactly on a triangle (decided exactly).
    On,
}

impl PointClass {
    /// The class's name: `inside`, `outside`, `on`.
    pub fn name(self) -> &'static str {
        match self {
            PointClass::Inside => "inside",
            PointClass::Outside => "outside",
            PointClass::On => "on",
        }
    }

    /// The class as a small code, for arrays (the Python and JavaScript packages): 0
    /// outside, 1 inside, 2 on.
    pub fn code(self) -> u8 {
        match self {
            PointClass::Outside => 0,
            PointClass::Inside => 1,
            PointClass::On => 2,
        }
    }
}

/// The result of [`classify_points`].
#[derive(Clone, Debug)]
pub struct ClassifyOutput {
    /// Per point, in input order.
    pub classes: Vec<PointClass>,
    /// Per point: the generalized winding number (the hierarchical approximation,
    /// typically within a few hundredths of the exact sum, and on the exact sum's side of
    /// the threshold: where the approximation's error bound straddles it, the value is
    /// completed through the mesh's boundary or summed exactly; an integer there for a
    /// closed mesh; about 1/2 on a closed surface).
    pub winding: Vec<f64>,
    /// True when the mesh is closed (inside means winding number ≥ 1/2; else behind the
    /// surface means winding number > 0).
    pub closed: bool,
    /// Time of the classification (after the checks), in seconds.
    pub seconds: f64,
}

/// One point of [`ClassifyReport::results`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PointResult {
    /// Where it lies.
    pub class: PointClass,
    /// Its winding number.
    pub winding: f64,
}

/// What [`ClassifyOutput::report`] tells: the JSON of `meshbool classify --json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ClassifyReport {
    /// [`SCHEMA`].
    pub schema: u32,
    /// Points classified.
    pub points: usize,
    /// Points inside (or behind an open surface).
    pub inside: usize,
    /// Points outside.
    pub outside: usize,
    /// Points exactly on the surface.
    pub on: usize,
    /// Whether the mesh is closed.
    pub closed: bool,
    /// Per point (only when asked: `meshbool classify --json` without `-o`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub results: Option<Vec<PointResult>>,
    /// [`ClassifyOutput::seconds`].
    pub seconds: f64,
}

impl ClassifyOutput {
    /// The report; with `results`, the class and winding number of every point too.
    pub fn report(&self, results: bool) -> ClassifyReport {
        let count = |c: PointClass| self.classes.iter().filter(|&&x| x == c).count();
        ClassifyReport {
            schema: SCHEMA,
            points: self.classes.len(),
            inside: count(PointClass::Inside),
            outside: count(PointClass::Outside),
            on: count(PointClass::On),
            closed: self.closed,
            results: results.then(|| {
                self.classes
                    .iter()
                    .zip(&self.winding)
                    .map(|(&class, &winding)| PointResult { class, winding })
                    .collect()
            }),
            seconds: self.seconds,
        }
    }
}

/// Classifies `points` against `mesh`: exactly on its surface (exact predicates on the
/// input coordinates: in a triangle's plane and inside its closure), else inside or
/// outside by the winding number — at least 1/2 for a closed mesh, above 0 (behind the
/// surface) for an open one. The winding number is a measure: it decides only for points
/// off the surface, wrongly only within rounding of it. Non-finite points are an error.
pub fn classify_points<'a>(
    mesh: impl Into<Input<'a>>,
    points: &[[f64; 3]],
    opts: &ClassifyOptions,
) -> Result<ClassifyOutput> {
    if let Some(i) = points.iter().position(|p| p.iter().any(|x| !x.is_finite())) {
        // An input's fault, not a parameter's: the points are data.
        return Err(Error::Malformed {
            what: "points",
            message: format!("point {i} has a non-finite coordinate: {:?}", points[i]),
        });
    }
    let input: Input<'a> = mesh.into();
    // The classes and winding numbers do not change with a power-of-two scale.
    if let Some(e) = super::extreme_scale(&[input.mesh()]) {
        let mut pts = points.to_vec();
        super::scale_points(&mut pts, e);
        return classify_points(input.scaled(e).input(), &pts, opts);
    }
    with_threads(opts.run.threads, || {
        let operand = input.operand("mesh", &opts.checks)?;
        let start = Instant::now();
        let m = operand.mesh();
        let counts = EdgeCounts::of(m);
        let closed = !m.triangles.is_empty() && counts.boundary == 0 && counts.non_manifold == 0;
        let on = on_surface(m, points);
        let threshold = if closed { 0.5 } else { 0.0 };
        let fast = FastWinding::new(m);
        // Points off the surface on the exact sum's side; those on it keep the
        // hierarchy's own value (about ½ on a closed surface).
        let (on_pts, off_pts): (Vec<usize>, Vec<usize>) = (0..points.len()).partition(|&i| on[i]);
        let pick = |ids: &[usize]| -> Vec<[f64; 3]> { ids.iter().map(|&i| points[i]).collect() };
        let mut winding = vec![0.0; points.len()];
        for (&i, (w, _)) in off_pts
            .iter()
            .zip(fast.sided_many(&pick(&off_pts), threshold))
        {
            winding[i] = w;
        }
        for (&i, w) in on_pts.iter().zip(fast.at_many(&pick(&on_pts))) {
            winding[i] = w;
        }
        let classes = winding
            .iter()
            .zip(&on)
            .map(|(&w, &on)| match (on, closed) {
                (true, _) => PointClass::On,
                (false, true) if w >= 0.5 => PointClass::Inside,
                (false, false) if w > 0.0 => PointClass::Inside,
                _ => PointClass::Outside,
            })
            .collect();
        Ok(ClassifyOutput {
            classes,
            winding,
            closed,
            seconds: start.elapsed().as_secs_f64(),
        })
    })?
}

/// Per point: whether it lies exactly on a triangle of `m` (closed triangles: edges and
/// corners count), through the triangle index.
fn on_surface(m: &Mesh, points: &[[f64; 3]]) -> Vec<bool> {
    if points.is_empty() || m.triangles.is_empty() {
        return vec![false; points.len()];
    }
    let index = TriangleIndex::new(m);
    points
        .par_iter()
        .map(|p| !index.containing(p).is_empty())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_against_a_cube_and_a_terrain_patch() {
        let cube = Mesh::unit_cube();
        let pts = [
            [0.5, 0.5, 0.5],                      // inside
            [2.0, 0.5, 0.5],                      // outside
            [1.0, 0.25, 0.75],                    // on a face
            [1.0, 1.0, 1.0],                      // a corner
            [0.5, 0.0, 0.5],                      // on a face diagonal's plane, in the face
            [1.0 + f64::EPSILON, 0.5, 0.5],       // just outside the face: outside, not on
            [0.5, 0.5, 1.0 - f64::EPSILON / 2.0], // just inside
        ];
        let out = classify_points(&cube, &pts, &ClassifyOptions::default()).unwrap();
        use PointClass::*;
        assert_eq!(
            out.classes,
            [Inside, Outside, On, On, On, Outside, Inside],
            "{:?}",
            out.winding
        );
        assert!(out.closed);
        assert!((out.winding[0] - 1.0).abs() < 1e-9 && out.winding[1].abs() < 1e-9);
        let r = out.report(true);
        assert_eq!((r.points, r.inside, r.outside, r.on), (7, 2, 2, 3));
        assert_eq!(r.results.unwrap()[2].class, On);
        // An open surface (z = 0, facing up): below is behind it.
        let patch = crate::shapes::heightfield([0.0, 0.0], [4.0, 4.0], 4, 4, |_, _| 0.0);
        let (cx, cy) = (1.5, 2.25);
        let out = classify_points(
            &patch,
            &[[cx, cy, -0.1], [cx, cy, 0.1], [cx, cy, 0.0]],
            &ClassifyOptions::default(),
        )
        .unwrap();
        assert!(!out.closed);
        assert_eq!(out.classes, [Inside, Outside, On]);
        // Bad points are an error; no points is nothing to do.
        let nan = classify_points(&cube, &[[f64::NAN, 0.0, 0.0]], &ClassifyOptions::default());
        assert!(matches!(nan, Err(Error::Malformed { what: "points", .. })));
        let none = classify_points(&cube, &[], &ClassifyOptions::default()).unwrap();
        assert_eq!(none.report(false).points, 0);
    }
}
