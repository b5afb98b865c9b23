//! Link and fan topology around a vertex: the edge kinds at a vertex, the number of fans
//! its triangles form, and the link condition of a collapse within one sheet.

use super::refusal::{refuse, Gate, Refusal::*};
use crate::mesh_edit::{common, neighbours};

/// Edge counts by kind around one vertex.
#[derive(Clone, Copy, Default, Debug)]
pub(super) struct Defects {
    pub(super) boundary: usize,
    pub(super) non_manifold: usize,
    pub(super) inconsistent: usize,
}

impl Defects {
    pub(super) fn plus(self, o: Defects) -> Defects {
        Defects {
            boundary: self.boundary + o.boundary,
            non_manifold: self.non_manifold + o.non_manifold,
            inconsistent: self.inconsistent + o.inconsistent,
        }
    }
}

/// The topology gate of collapsing `gone` onto `keep` within one sheet: `of_keep` are
/// `keep`'s triangles in the sheet, `of_gone` the indices in `sg_tris` (`gone`'s
/// triangles) of those in the sheet. Returns the indices of the sheet's triangles on the
/// edge and their far corners; none where the sheet has `gone` but not `keep` (its
/// triangles there only take `keep`'s name). Refuses what would break the sheet's
/// manifoldness (see [`Editor::collapse`]).
pub(super) fn collapse_topology(
    keep: u32,
    gone: u32,
    of_keep: &[[u32; 3]],
    of_gone: &[usize],
    sg_tris: &[[u32; 3]],
) -> Gate<(Vec<usize>, Vec<u32>)> {
    let on_edge = |tri: &[u32; 3]| tri.contains(&keep);
    let shared: Vec<usize> = of_gone
        .iter()
        .copied()
        .filter(|&i| on_edge(&sg_tris[i]))
        .collect();
    if shared.is_empty() {
        // Both ends in the sheet but no edge between them there: it would be pinched.
        return if of_keep.is_empty() {
            Ok((Vec::new(), Vec::new()))
        } else {
            refuse(Manifold)
        };
    }
    if shared.len() > 2 {
        return refuse(Manifold);
    }
    let runs_keep_gone =
        |tri: &[u32; 3]| (0..3).any(|k| tri[k] == keep && tri[(k + 1) % 3] == gone);
    if shared.len() == 2
        && runs_keep_gone(&sg_tris[shared[0]]) == runs_keep_gone(&sg_tris[shared[1]])
    {
        return refuse(Manifold);
    }
    let mut far: Vec<u32> = shared
        .iter()
        .map(|&i| {
            sg_tris[i]
                .into_iter()
                .find(|&w| w != keep && w != gone)
                .unwrap_or(keep)
        })
        .collect();
    far.sort_unstable();
    if far.windows(2).any(|w| w[0] == w[1]) {
        return refuse(Manifold);
    }
    let sg_sheet: Vec<[u32; 3]> = of_gone.iter().map(|&i| sg_tris[i]).collect();
    let (nk, ng) = (
        neighbours(of_keep.iter().copied(), keep),
        neighbours(sg_sheet.iter().copied(), gone),
    );
    if common(&nk, &ng)[..] != far[..] {
        return refuse(Manifold);
    }
    let uses = |tris: &[[u32; 3]], x: u32| tris.iter().filter(|t| t.contains(&x)).count();
    for &x in &ng {
        let c = uses(&sg_sheet, x);
        // A vertex on a boundary (or a non-manifold edge) moves only along it.
        if c > 2 || (c == 1 && shared.len() == 2) {
            return refuse(Manifold);
        }
    }
    if shared.len() == 1 && uses(&sg_sheet, far[0]) == 1 && uses(of_keep, far[0]) == 1 {
        return refuse(Manifold); // a lone triangle: it would vanish
    }
    let after: Vec<[u32; 3]> = of_keep
        .iter()
        .copied()
        .filter(|t| !t.contains(&gone))
        .chain(
            of_gone
                .iter()
                .filter(|i| !shared.contains(i))
                .map(|&i| sg_tris[i].map(|v| if v == gone { keep } else { v })),
        )
        .collect();
    let before = defects(keep, of_keep, None).plus(defects(gone, &sg_sheet, Some(keep)));
    let now = defects(keep, &after, None);
    if now.boundary > before.boundary
        || now.non_manifold > before.non_manifold
        || now.inconsistent > before.inconsistent
    {
        return refuse(Manifold);
    }
    let mut sets: Vec<[u32; 3]> = after
        .iter()
        .map(|t| {
            let mut s = *t;
            s.sort_unstable();
            s
        })
        .collect();
    sets.sort_unstable();
    if sets.windows(2).any(|w| w[0] == w[1]) || fans(keep, &after) != 1 {
        return refuse(Manifold);
    }
    Ok((shared, far))
}

/// The kinds of the edges at `v` in the triangles `star` (all containing `v`), leaving
/// out the edge to `skip`.
pub(super) fn defects(v: u32, star: &[[u32; 3]], skip: Option<u32>) -> Defects {
    // (other end, uses v -> other, uses other -> v).
    let mut uses: Vec<(u32, usize, usize)> = Vec::new();
    let mut add = |x: u32, forward: bool| {
        if Some(x) == skip || x == v {
            return;
        }
        let i = match uses.iter().position(|u| u.0 == x) {
            Some(i) => i,
            None => {
                uses.push((x, 0, 0));
                uses.len() - 1
            }
        };
        if forward {
            uses[i].1 += 1;
        } else {
            uses[i].2 += 1;
        }
    };
    for t in star {
        for k in 0..3 {
            if t[k] == v {
                add(t[(k + 1) % 3], true);
                add(t[(k + 2) % 3], false);
            }
        }
    }
    let mut d = Defects::default();
    for (_, f, b) in uses {
        match (f, b) {
            (1, 0) | (0, 1) => d.boundary += 1,
            (1, 1) => {}
            (f, b) if f + b == 2 => d.inconsistent += 1,
            _ => d.non_manifold += 1,
        }
    }
    d
}

/// The number of fans the triangles `star` (all containing `v`) form around `v`:
/// triangles sharing an edge at `v` are in one fan.
pub(super) fn fans(v: u32, star: &[[u32; 3]]) -> usize {
    let n = star.len();
    let mut parent: Vec<usize> = (0..n).collect();
    pub(super) fn root(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    let others: Vec<[u32; 3]> = star
        .iter()
        .map(|t| t.map(|w| if w == v { u32::MAX } else { w }))
        .collect();
    for i in 0..n {
        for j in i + 1..n {
            if others[i]
                .iter()
                .any(|&x| x != u32::MAX && others[j].contains(&x))
            {
                let (a, b) = (root(&mut parent, i), root(&mut parent, j));
                parent[a] = b;
            }
        }
    }
    (0..n).filter(|&i| root(&mut parent, i) == i).count()
}
