//! Intersection curves at the front door: where two meshes meet, exactly, chained into
//! polylines (closed loops and open chains).

use std::path::Path;

use serde::Serialize;

use web_time::Instant;

use super::{with_threads, Checks, Input, Operand, RunOptions, SCHEMA};
use crate::boolean::Stage;
use crate::intersect::{chain, intersect, self_intersections, self_seam, PolylineXyz, Seam};
use crate::io::write_polylines;
use crate::{Error, Format, Result};

/// Options of [`curves`].
#[derive(Clone, Debug)]
pub struct CurvesOptions {
    /// Also the segments that only bound coplanar overlaps (shared faces).
    pub with_coplanar: bool,
    /// Checks of inputs given as meshes (default: none; curves do not depend on
    /// orientation).
    pub checks: Checks,
    /// Threads and progress.
    pub run: RunOptions,
}

impl Default for CurvesOptions {
    fn default() -> Self {
        CurvesOptions {
            with_coplanar: true,
            checks: Checks::NONE,
            run: RunOptions::default(),
        }
    }
}

/// The result of [`curves`].
#[derive(Clone, Debug)]
pub struct CurvesOutput {
    /// The curves with the seam points' coordinates (rounded to `f64`).
    pub polylines: Vec<PolylineXyz>,
    /// The exact intersection the curves are chained from.
    pub seam: Seam,
    /// The names of A and B.
    pub names: [String; 2],
    /// Time of the intersection and chaining, in seconds.
    pub seconds: f64,
}

/// What [`CurvesOutput::report`] tells: the JSON of `meshbool curves --json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CurvesReport {
    /// [`SCHEMA`].
    pub schema: u32,
    /// Closed loops.
    pub loops: usize,
    /// Open chains (ending on an open surface's boundary or at a branching).
    pub open_chains: usize,
    /// Length of all curves, on the rounded coordinates.
    pub total_length: f64,
    /// Seam points.
    pub points: usize,
    /// Seam segments (coplanar ones included).
    pub segments: usize,
    /// Segments that only bound coplanar overlaps.
    pub coplanar_segments: usize,
    /// Points where the meshes only touch.
    pub touching_points: usize,
    /// Triangle pairs whose boxes overlap (broad-phase candidates).
    pub candidate_pairs: usize,
    /// Zero-area triangles of A and of B where the meshes meet, left out.
    pub degenerate_triangles: [usize; 2],
    /// [`CurvesOutput::seconds`].
    pub seconds: f64,
}

impl CurvesOutput {
    /// The report.
    pub fn report(&self) -> CurvesReport {
        let seam = &self.seam;
        CurvesReport {
            schema: SCHEMA,
            loops: self.polylines.iter().filter(|c| c.closed).count(),
            open_chains: self.polylines.iter().filter(|c| !c.closed).count(),
            // `+ 0.0`: an empty sum is -0.0.
            total_length: self.polylines.iter().map(PolylineXyz::length).sum::<f64>() + 0.0,
            points: seam.points.len(),
            segments: seam.segments.len(),
            coplanar_segments: seam.segments.iter().filter(|s| s.coplanar).count(),
            touching_points: seam.touching.len(),
            candidate_pairs: seam.candidate_pairs,
            degenerate_triangles: seam.degenerate,
            seconds: self.seconds,
        }
    }

    /// Writes the polylines to a file in the format its name says: `.obj` (`l` elements),
    /// `.dxf` (3D polylines) or `.json`.
    pub fn write(&self, path: impl AsRef<Path>) -> Result<()> {
        let path = path.as_ref();
        let format = Format::for_path(path).ok_or_else(|| {
            Error::InvalidParameter(format!(
                "cannot tell the polyline format of {}: use .obj, .dxf or .json",
                path.display()
            ))
        })?;
        crate::io::write_file(path, |out| write_polylines(out, &self.polylines, format))
            .map_err(|e| e.in_file("writing", path))
    }

    /// What the curves leave out, one line each (degenerate triangles).
    pub fn warnings(&self) -> Vec<String> {
        let [da, db] = self.seam.degenerate;
        if da + db == 0 {
            return Vec::new();
        }
        vec![format!(
            "left out degenerate (zero-area) triangles: {da} in {}, {db} in {}",
            self.names[0], self.names[1]
        )]
    }
}

/// The intersection curves of `a` and `b` (meshes or operands, as for [`super::boolean`]).
pub fn curves<'a>(
    a: impl Into<Input<'a>>,
    b: impl Into<Input<'a>>,
    opts: &CurvesOptions,
) -> Result<CurvesOutput> {
    let run = |a: &Operand, b: &Operand| {
        opts.run.stage(Stage::Intersect);
        let seam = intersect(a.mesh(), b.mesh());
        let polylines = chain(&seam, opts.with_coplanar)
            .iter()
            .map(|c| c.to_xyz(&seam))
            .collect();
        (
            seam,
            polylines,
            [a.name().to_string(), b.name().to_string()],
        )
    };
    let ((seam, polylines, names), seconds) =
        Input::with_both(a.into(), b.into(), &opts.checks, &opts.run, run)?;
    Ok(CurvesOutput {
        polylines,
        seam,
        names,
        seconds,
    })
}

/// Where one input crosses itself, exactly, chained into polylines: the seam of the mesh
/// with itself ([`crate::intersect::self_seam`]), without what neighbouring triangles
/// share. The input is validated and welded (`opts.checks` are not used: a self-crossing
/// mesh is what this looks at). The report's `candidate_pairs` counts the
/// self-intersecting triangle pairs.
pub fn self_curves<'a>(mesh: impl Into<Input<'a>>, opts: &CurvesOptions) -> Result<CurvesOutput> {
    let input: Input<'a> = mesh.into();
    with_threads(opts.run.threads, || {
        let operand = input.operand("mesh", &Checks::NONE)?;
        let start = Instant::now();
        opts.run.stage(Stage::Intersect);
        let m = operand.mesh();
        let seam = self_seam(m, &self_intersections(m));
        let polylines = chain(&seam, opts.with_coplanar)
            .iter()
            .map(|c| c.to_xyz(&seam))
            .collect();
        let name = operand.name().to_string();
        Ok(CurvesOutput {
            polylines,
            seam,
            names: [name.clone(), name],
            seconds: start.elapsed().as_secs_f64(),
        })
    })?
}
