//! Chaining seam segments into polylines: closed loops and open chains.

use super::Seam;

/// A polyline with its coordinates, open or closed (the first point is not repeated).
#[derive(Clone, Debug, PartialEq)]
pub struct PolylineXyz {
    /// The points in order.
    pub points: Vec<[f64; 3]>,
    /// True when the last point connects back to the first.
    pub closed: bool,
}

impl PolylineXyz {
    /// Length: the sum of its steps (and the closing step of a closed line).
    pub fn length(&self) -> f64 {
        let n = self.points.len();
        let steps = if self.closed { n } else { n.saturating_sub(1) };
        (0..steps)
            .map(|k| {
                let (p, q) = (self.points[k], self.points[(k + 1) % n]);
                ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
            })
            .sum()
    }

    /// The polyline thinned for drawing or export (the reference's `simplifyPolyline`):
    /// walking along it, a point is kept when it is at least `spacing` from the last kept
    /// point; the first point is always kept, and the last of an open line. A closed line
    /// keeps at least three points (it stays a loop). Geometry only: the curve's topology
    /// (loops, chains, where they end) does not change.
    pub fn simplified(&self, spacing: f64) -> PolylineXyz {
        let n = self.points.len();
        if n <= 2 {
            return self.clone();
        }
        let dist2 = |p: &[f64; 3], q: &[f64; 3]| {
            (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)
        };
        let limit = spacing * spacing;
        let mut kept = vec![self.points[0]];
        let last = if self.closed { n } else { n - 1 };
        for p in &self.points[1..last] {
            if dist2(p, kept.last().unwrap_or(p)) >= limit {
                kept.push(*p);
            }
        }
        if !self.closed {
            kept.push(self.points[n - 1]);
        } else if kept.len() < 3 {
            // Too coarse for the loop: keep three points spread along it.
            kept = vec![self.points[0], self.points[n / 3], self.points[2 * n / 3]];
        }
        PolylineXyz {
            points: kept,
            closed: self.closed,
        }
    }
}

/// A chain of seam points.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Polyline {
    /// Seam point ids in order; for a closed loop the first point is not repeated.
    pub points: Vec<u32>,
    /// True for a closed loop.
    pub closed: bool,
    /// For each step `points[k] → points[k+1]` (and the closing step of a loop): the seam
    /// segment and one triangle pair `(tri_a, tri_b)` it was found in.
    pub steps: Vec<(u32, u32, u32)>,
}

impl Polyline {
    /// The polyline with the seam points' approximate coordinates, for writing out.
    pub fn to_xyz(&self, seam: &Seam) -> PolylineXyz {
        PolylineXyz {
            points: self
                .points
                .iter()
                .map(|&p| seam.positions[p as usize])
                .collect(),
            closed: self.closed,
        }
    }
}

/// Chains the seam's segments (coplanar ones too when `with_coplanar`) into polylines.
/// Chains end at points where other than two segments meet (open surface boundaries,
/// branchings); everything else closes into loops. Deterministic.
pub fn chain(seam: &Seam, with_coplanar: bool) -> Vec<Polyline> {
    let n = seam.points.len();
    let segs: Vec<usize> = (0..seam.segments.len())
        .filter(|&s| with_coplanar || !seam.segments[s].coplanar)
        .collect();
    // Adjacency in compressed rows.
    let mut degree = vec![0u32; n + 1];
    for &s in &segs {
        for &p in &seam.segments[s].ends {
            degree[p as usize + 1] += 1;
        }
    }
    for i in 0..n {
        degree[i + 1] += degree[i];
    }
    let start = degree;
    let mut fill = start.clone();
    let mut adj = vec![0u32; start[n] as usize];
    for &s in &segs {
        for &p in &seam.segments[s].ends {
            adj[fill[p as usize] as usize] = s as u32;
            fill[p as usize] += 1;
        }
    }
    let deg = |p: usize| start[p + 1] - start[p];
    let mut source = vec![(0u32, 0u32); seam.segments.len()];
    for src in seam.sources.iter().rev() {
        source[src.segment as usize] = (src.tri_a, src.tri_b);
    }
    let mut used = vec![false; seam.segments.len()];
    let other = |s: u32, p: u32| {
        let e = seam.segments[s as usize].ends;
        if e[0] == p {
            e[1]
        } else {
            e[0]
        }
    };
    let walk = |first: u32, seg: u32, used: &mut Vec<bool>| -> Polyline {
        let (mut points, mut steps) = (vec![first], Vec::new());
        let (mut at, mut s) = (first, seg);
        loop {
            used[s as usize] = true;
            steps.push((s, source[s as usize].0, source[s as usize].1));
            at = other(s, at);
            if at == first {
                return Polyline {
                    points,
                    closed: true,
                    steps,
                };
            }
            points.push(at);
            if deg(at as usize) != 2 {
                return Polyline {
                    points,
                    closed: false,
                    steps,
                };
            }
            let row = &adj[start[at as usize] as usize..start[at as usize + 1] as usize];
            match row.iter().find(|&&t| !used[t as usize]) {
                Some(&t) => s = t,
                None => {
                    return Polyline {
                        points,
                        closed: false,
                        steps,
                    }
                }
            }
        }
    };
    let mut out = Vec::new();
    // Open chains first: from every point that is not a plain pass-through.
    for p in 0..n {
        if deg(p) != 2 {
            for k in start[p]..start[p + 1] {
                let s = adj[k as usize];
                if !used[s as usize] {
                    out.push(walk(p as u32, s, &mut used));
                }
            }
        }
    }
    // What is left forms loops.
    for &s in &segs {
        if !used[s] {
            let first = seam.segments[s].ends[0];
            out.push(walk(first, s as u32, &mut used));
        }
    }
    out
}
