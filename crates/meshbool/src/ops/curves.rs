//! Intersection curves at the front door: where two meshes meet, exactly, chained into
//! polylines (closed loops and open chains).

use std::path::Path;

use serde::Serialize;

use web_time::Instant;

use super::{with_threads, Checks, Input, Operand, RunOptions, SCHEMA};
use crate::boolean::Stage;
use crate::intersect::{
    chain, intersect_coplanar, self_intersections, self_seam, PolylineXyz, Seam,
};
use crate::io::write_polylines;
use crate::{Error, Format, Mesh, Result};

/// Options of [`curves`].
#[derive(Clone, Debug)]
pub struct CurvesOptions {
    /// Also the segments that only bound coplanar overlaps (shared faces).
    pub with_coplanar: bool,
    /// Checks of inputs given as meshes (default: none; curves do not depend on
    /// orientation).
    pub checks: Checks,
    /// Thin the polylines for export: points closer than this to the last kept point along
    /// a line are left out ([`PolylineXyz::simplified`]). A distance the user chooses; the
    /// exact seam is unchanged. `None`: every seam point.
    pub simplify: Option<f64>,
    /// Put every raw seam segment, with the triangle of each input it lies in, in the
    /// report (`tagged_segments`; the reference's `intersectMeshPairTagged`).
    pub tagged: bool,
    /// Also the segments where an edge of either input crosses a coplanar overlap (the
    /// common refinement of both triangulations there, as the reference JS library's
    /// tagged segments list them). Off (the default), coplanar overlaps give their
    /// boundaries only.
    pub coplanar_refinement: bool,
    /// Threads and progress.
    pub run: RunOptions,
}

impl Default for CurvesOptions {
    fn default() -> Self {
        CurvesOptions {
            with_coplanar: true,
            checks: Checks::NONE,
            simplify: None,
            tagged: false,
            coplanar_refinement: false,
            run: RunOptions::default(),
        }
    }
}

impl CurvesOptions {
    /// Checks the options: a simplification distance must be finite and positive.
    fn validate(&self) -> Result<()> {
        match self.simplify {
            Some(d) if !(d.is_finite() && d > 0.0) => Err(Error::InvalidParameter(format!(
                "the simplification distance must be a finite number > 0, got {d}"
            ))),
            _ => Ok(()),
        }
    }

    /// The polylines of `seam` as these options ask: chained, with or without coplanar
    /// segments, simplified; and how many points simplification left out.
    fn polylines(&self, seam: &Seam) -> (Vec<PolylineXyz>, usize) {
        let lines: Vec<PolylineXyz> = chain(seam, self.with_coplanar)
            .iter()
            .map(|c| c.to_xyz(seam))
            .collect();
        let Some(d) = self.simplify else {
            return (lines, 0);
        };
        let before: usize = lines.iter().map(|l| l.points.len()).sum();
        let thinned: Vec<PolylineXyz> = lines.iter().map(|l| l.simplified(d)).collect();
        let after: usize = thinned.iter().map(|l| l.points.len()).sum();
        (thinned, before - after)
    }
}

/// A raw seam segment with the triangles it lies in: `tri_a` of A and `tri_b` of B (for a
/// mesh's own curves, two of its triangles). A segment along an edge is listed once per
/// pair of triangles it lies in.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TaggedSegment {
    /// One end (the exact point rounded to `f64`).
    pub p0: [f64; 3],
    /// The other end.
    pub p1: [f64; 3],
    /// Triangle of A (input order).
    pub tri_a: u32,
    /// Triangle of B.
    pub tri_b: u32,
    /// True when the segment only bounds a coplanar overlap.
    pub coplanar: bool,
}

/// The result of [`curves`].
#[derive(Clone, Debug)]
pub struct CurvesOutput {
    /// The curves with the seam points' coordinates (rounded to `f64`).
    pub polylines: Vec<PolylineXyz>,
    /// The exact intersection the curves are chained from.
    pub(crate) seam: Seam,
    /// The names of A and B.
    pub names: [String; 2],
    /// Points left out by [`CurvesOptions::simplify`] (`None`: not simplified).
    pub simplified_away: Option<usize>,
    /// Whether the report lists the tagged segments ([`CurvesOptions::tagged`]).
    pub tagged: bool,
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
    /// Points left out of the polylines by `--simplify` (absent without it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub simplified_points_removed: Option<usize>,
    /// Every raw seam segment with its triangles (with `--tagged` only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tagged_segments: Option<Vec<TaggedSegment>>,
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
            simplified_points_removed: self.simplified_away,
            tagged_segments: self.tagged.then(|| self.tagged_segments()),
            seconds: self.seconds,
        }
    }

    /// Multiplies the output's coordinates by `2^e` (the polylines and the seam's rounded
    /// positions; the exact constructions stay those of the unit-size computation).
    fn scale_back(&mut self, e: i32) {
        for l in &mut self.polylines {
            super::scale_points(&mut l.points, e);
        }
        super::scale_points(&mut self.seam.positions, e);
    }

    /// Every raw seam segment with the triangle of each input it lies in, in the order of
    /// the seam's sources (see [`TaggedSegment`]).
    pub fn tagged_segments(&self) -> Vec<TaggedSegment> {
        let seam = &self.seam;
        seam.sources
            .iter()
            .map(|s| {
                let seg = &seam.segments[s.segment as usize];
                let [p, q] = seg.ends.map(|e| seam.positions[e as usize]);
                TaggedSegment {
                    p0: p,
                    p1: q,
                    tri_a: s.tri_a,
                    tri_b: s.tri_b,
                    coplanar: seg.coplanar,
                }
            })
            .collect()
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
    opts.validate()?;
    let (a, b): (Input<'a>, Input<'a>) = (a.into(), b.into());
    let unit = |a: Input<'_>, b: Input<'_>| curves(a, b, opts);
    if let Some(out) = super::at_unit_scale(a, b, unit, CurvesOutput::scale_back) {
        return out;
    }
    let run = |a: &Operand, b: &Operand| {
        opts.run.report(Stage::Intersect);
        let seam = intersect_coplanar(a.mesh(), b.mesh(), opts.coplanar_refinement);
        let lines = opts.polylines(&seam);
        (seam, lines, [a.name().to_string(), b.name().to_string()])
    };
    let ((seam, (polylines, away), names), seconds) =
        Input::with_both(a, b, &opts.checks, &opts.run, run)?;
    Ok(CurvesOutput {
        polylines,
        seam,
        names,
        simplified_away: opts.simplify.map(|_| away),
        tagged: opts.tagged,
        seconds,
    })
}

/// Where one input crosses itself, exactly, chained into polylines: the seam of the mesh
/// with itself, without what neighbouring triangles
/// share. The input is validated and welded (`opts.checks` are not used: a self-crossing
/// mesh is what this looks at). The report's `candidate_pairs` counts the
/// self-intersecting triangle pairs.
pub fn self_curves<'a>(mesh: impl Into<Input<'a>>, opts: &CurvesOptions) -> Result<CurvesOutput> {
    let input: Input<'a> = mesh.into();
    opts.validate()?;
    with_threads(opts.run.threads, || {
        let operand = input.operand("mesh", &Checks::NONE)?;
        let start = Instant::now();
        opts.run.stage(Stage::Intersect)?;
        let m = operand.mesh();
        let seam = self_seam(m, &self_intersections(m));
        let (polylines, away) = opts.polylines(&seam);
        let name = operand.name().to_string();
        Ok(CurvesOutput {
            polylines,
            seam,
            names: [name.clone(), name],
            simplified_away: opts.simplify.map(|_| away),
            tagged: opts.tagged,
            seconds: start.elapsed().as_secs_f64(),
        })
    })?
}

/// A mesh cut where it crosses itself ([`self_arrangement`]).
#[derive(Clone, Debug)]
pub struct SelfArrangement {
    /// The input with every triangle its own seam crosses re-triangulated along it, so
    /// that the mesh conforms there (each seam segment an edge; seam points rounded to
    /// `f64` once).
    pub mesh: Mesh,
    /// For every triangle of [`SelfArrangement::mesh`], the input triangle it is part of.
    pub parent: Vec<u32>,
}

/// Cuts a mesh along where it crosses itself, deciding nothing else: the pieces of
/// [`self_curves`]'s seam, for front ends whose users classify the pieces themselves (the
/// JavaScript package's `bmsSelfArrange`). The input is validated and welded exactly
/// (triangles in their order; no checks: a self-crossing mesh is what this cuts).
pub fn self_arrangement<'a>(mesh: impl Into<Input<'a>>) -> Result<SelfArrangement> {
    let input: Input<'a> = mesh.into();
    let operand = input.operand("mesh", &Checks::NONE)?;
    let m = operand.mesh();
    let seam = self_seam(m, &self_intersections(m));
    let arranged = crate::arrange::arrange_self(m, &seam);
    Ok(SelfArrangement {
        mesh: arranged.mesh,
        parent: arranged.parent,
    })
}
