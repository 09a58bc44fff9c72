//! Trimming (Sheen et al. 5.3): after the patches are split where they cross, drop the small branches.
//!
//! Offsetting the larger face of each wall makes neighbouring patches run past each other: at an L corner
//! each patch overshoots the other by half the other's thickness. A piece of a split patch is such a branch
//! when it touches another patch (a crossing line), is not the body of its patch (`heaviest_stretch_pieces`),
//! and every point of its boundary lies within 0.75 x the crossing patch's thickness of the crossing lines (the
//! overshoot is half a thickness; the margin absorbs tilted walls). A piece joined to another piece of its own
//! patch by an edge that no other patch shares (longer than the overshoot) is not hanging: a joint strip grown
//! from the patch's edge stays. A hanging piece touching no other patch stays only when so joined to a piece that
//! is not a branch: overshoot corners joined only to branches go with them. The cut across a tube's end, where the
//! wall runs on past a tube crossing it (`FusedEdge::stem_end`), joins nothing: the wall inside the tube's wall
//! below its end is an overshoot past the tube like any other.

use std::collections::BTreeSet;

use glam::DVec3;
use serde::Serialize;

use crate::kernel::{FuseKind, Kernel, SidecarError};
use crate::model::shapes::{Fused, FusedFace, Handle};
use crate::model::union_find::{find, union};

/// The patches fused, with the pieces kept and the branches dropped.
pub struct Trimmed {
    pub fused: Fused,
    pub keep: Vec<bool>,
    pub branches: Vec<Branch>,
}

/// The trim stage: the patches behind `patches` fused into one shape (split where they cross, `fuzzy`), and
/// the branches hanging past the crossings dropped (`limits`: how far a branch may hang past each patch).
pub fn fuse_and_trim<K: Kernel>(
    kernel: &mut K,
    patches: Vec<Handle>,
    bodies: &[usize],
    fuzzy: f64,
    limits: &[f64],
) -> Result<Trimmed, SidecarError> {
    let fused = kernel.fuse(patches, bodies, fuzzy, FuseKind::Patches)?;
    let branches = find_branches(&fused, limits);
    let keep = keep_mask(fused.faces.len(), &branches);
    Ok(Trimmed { fused, keep, branches })
}

/// Overshoot allowance over the crossing patch's thickness (nominal overshoot 0.5).
const BRANCH_WIDTH: f64 = 0.75;

/// How far a branch may hang past a patch `thickness` thick lying `to_mid` off the middle of its wall: a patch
/// on a skin is crossed by others up to a whole thickness before they reach the far skin.
pub fn branch_limit(thickness: f64, to_mid: f64) -> f64 {
    BRANCH_WIDTH * thickness + to_mid.abs()
}

/// Why a piece is trimmed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum TrimReason {
    /// It hangs past a crossing by an overshoot.
    Overshoot,
    /// It lies outside the material (see [`outside_material`]).
    Outside,
    /// It lies out of its own wall and hangs free (see `stitch::peel`).
    Dangling,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Branch {
    /// Index of the piece in the fused shape.
    pub piece: usize,
    pub patch: usize,
    pub area: f64,
    /// Farthest distance of the piece's boundary from the crossing lines (0 for a piece outside the material).
    pub width: f64,
    /// Patches it crosses, sorted.
    pub crossing: Vec<usize>,
    pub reason: TrimReason,
}

impl Branch {
    /// Fused piece `piece` (`face`) dropped for `reason`.
    fn of(piece: usize, face: &FusedFace, width: f64, crossing: Vec<usize>, reason: TrimReason) -> Branch {
        Branch { piece, patch: face.patch, area: face.area, width, crossing, reason }
    }
}

fn distance_to_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 { ((p - a).dot(ab) / len2).clamp(0.0, 1.0) } else { 0.0 };
    p.distance(a + ab * t)
}

fn distance_to_polyline(p: DVec3, line: &[DVec3]) -> f64 {
    line.windows(2).map(|w| distance_to_segment(p, w[0], w[1])).fold(f64::INFINITY, f64::min)
}

/// What a piece of a fused shape touches, read off its edges.
struct Touch<'a> {
    /// Other patches met along its edges, sorted.
    crossing: Vec<usize>,
    /// The lines along which they meet it, and (added by `find_branches`) its own edges shorter than an overshoot.
    lines: Vec<&'a [DVec3]>,
    /// Its edges shared with pieces of its own patch only.
    own: Vec<usize>,
    /// Whether its boundary goes on past a free edge or a seam.
    hanging: bool,
    /// How far a branch of it may hang past those patches: the largest of their limits (0 when it meets none).
    across: f64,
}

/// What piece `i` of `fused` touches; `limit` as for [`find_branches`].
fn touch<'a>(fused: &'a Fused, i: usize, limit: &[f64]) -> Touch<'a> {
    let face = &fused.faces[i];
    let mut touch = Touch { crossing: Vec::new(), lines: Vec::new(), own: Vec::new(), hanging: false, across: 0.0 };
    for &e in &face.edges {
        let edge = &fused.edges[e];
        let others: Vec<usize> =
            edge.faces.iter().map(|&g| fused.faces[g].patch).filter(|&p| p != face.patch).collect();
        if !others.is_empty() {
            touch.crossing.extend(others);
            touch.lines.push(&edge.points);
        } else if edge.faces.iter().any(|&g| g != i) {
            touch.own.push(e);
        } else {
            // A free edge, or a seam (listed twice for this face): the piece's boundary goes on past it.
            touch.hanging = true;
        }
    }
    touch.crossing.sort_unstable();
    touch.crossing.dedup();
    touch.across = touch.crossing.iter().map(|&p| limit[p]).fold(0.0, f64::max);
    touch
}

/// The branches to drop; `limit[k]` is how far a branch may hang past patch k (see [`branch_limit`]).
pub fn find_branches(fused: &Fused, limit: &[f64]) -> Vec<Branch> {
    let n = fused.faces.len();
    let mut touches: Vec<Touch> = (0..n).map(|i| touch(fused, i, limit)).collect();
    // Pieces of the same patch sharing an edge no other patch crosses.
    let mut own_links: Vec<Vec<usize>> = vec![Vec::new(); n];
    // Cuts across a tube's end, each seen from a piece it bounds: (that piece, the piece across the cut).
    let mut stem_ends: Vec<(usize, usize)> = Vec::new();
    for (i, touch) in touches.iter_mut().enumerate() {
        for &e in &touch.own {
            let edge = &fused.edges[e];
            let others = edge.faces.iter().copied().filter(|&g| g != i);
            // The cut across a tube's end parts the wall beyond the end from the wall inside the tube's wall
            // (which the tube's patch stands for): it joins neither to the other (unless it must, below), and
            // bounds each as a free edge would.
            touch.hanging |= edge.stem_end;
            if edge.length < touch.across {
                // Shorter than an overshoot: where the crossing line stops a little before the strip does, the
                // stub between the two is part of the cut, not what joins the piece to its patch.
                touch.lines.push(&edge.points);
            } else if edge.stem_end {
                stem_ends.extend(others.map(|g| (i, g)));
            } else {
                own_links[i].extend(others);
            }
        }
    }
    // A cut across a tube's end still joins the pieces either side when one reaches no crossing but through the
    // other: dropping the other would leave it loose. Pieces so joined are one stretch (for the body, below).
    let mut stretch: Vec<usize> = (0..n).collect();
    for (i, links) in own_links.iter().enumerate() {
        for &j in links {
            union(&mut stretch, i, j);
        }
    }
    let mut crosses = vec![false; n];
    for (i, t) in touches.iter().enumerate() {
        if !t.crossing.is_empty() {
            let root = find(&mut stretch, i);
            crosses[root] = true;
        }
    }
    let joined: Vec<(usize, usize)> = stem_ends.into_iter().filter(|&(i, _)| !crosses[find(&mut stretch, i)]).collect();
    for (i, j) in joined {
        own_links[i].push(j);
        own_links[j].push(i);
        union(&mut stretch, i, j);
    }
    // Hanging pieces that touch no other patch (an overshoot corner, the end of a strip): they anchor nothing
    // and stay only when joined to a piece that does.
    let mut loose = vec![false; n];
    // Pieces hanging past a crossing by no more than an overshoot: (width, crossing patches).
    let mut overshoot: Vec<Option<(f64, Vec<usize>)>> = vec![None; n];
    for (i, (face, t)) in fused.faces.iter().zip(touches).enumerate() {
        if !t.hanging && own_links[i].is_empty() {
            // Closed in by crossing lines all round (a floor between walls): however narrow, a branch hangs past
            // the crossing, by a free edge or with other overshoot pieces.
            continue;
        }
        if t.crossing.is_empty() {
            // Only an overshoot-sized piece (mean width 2 x area / perimeter within the branch limit of its own
            // thickness) is loose: a large piece split off by its patch's own edges is part of the wall.
            let perimeter: f64 = face.edges.iter().map(|&e| fused.edges[e].length).sum();
            loose[i] = t.hanging && 2.0 * face.area <= limit[face.patch] * perimeter;
            continue;
        }
        let mut width = 0.0;
        for p in face.edges.iter().flat_map(|&e| fused.edges[e].points.iter()) {
            width = t.lines.iter().map(|l| distance_to_polyline(*p, l)).fold(f64::INFINITY, f64::min).max(width);
            if width > t.across {
                break;
            }
        }
        if width <= t.across {
            overshoot[i] = Some((width, t.crossing));
        }
    }
    // The body of each patch stays, however it hangs.
    let body = heaviest_stretch_pieces(fused, &mut stretch);
    let mut candidates: Vec<Option<Branch>> = overshoot
        .into_iter()
        .enumerate()
        .map(|(i, o)| {
            let (width, crossing) = o.filter(|_| body[fused.faces[i].patch] != Some(i))?;
            Some(Branch::of(i, &fused.faces[i], width, crossing, TrimReason::Overshoot))
        })
        .collect();
    // A narrow piece joined (through other narrow pieces) to a piece of its patch that is not narrow continues
    // the patch (a joint strip grown from its edge): only the rest hang past crossings.
    let mut anchored: Vec<bool> =
        (0..n).map(|i| (candidates[i].is_none() && !loose[i]) || body[fused.faces[i].patch] == Some(i)).collect();
    let mut queue: Vec<usize> = (0..anchored.len()).filter(|&i| anchored[i]).collect();
    while let Some(i) = queue.pop() {
        for &j in &own_links[i] {
            if !anchored[j] {
                anchored[j] = true;
                queue.push(j);
            }
        }
    }
    for (i, face) in fused.faces.iter().enumerate() {
        if loose[i] && !anchored[i] && body[face.patch] != Some(i) {
            candidates[i] = Some(Branch::of(i, face, 0.0, Vec::new(), TrimReason::Overshoot));
        }
    }
    candidates.into_iter().zip(anchored).filter_map(|(c, a)| if a { None } else { c }).collect()
}

/// The kept pieces (`keep`) that lie outside the material: `inside(face)` says whether a point of the face (moved
/// to the middle of its wall) lies in its solid. A patch whose skin had a hole where another wall runs in (a
/// branch pipe) is made with the hole filled (`pairing::driver::junction_loops`), and the crossing wall cuts the
/// filling out as a piece of its own: across the branch's bore, where there is no material to be the middle of.
/// Only pieces that touch another patch and are not their patch's largest: the body of a patch is never
/// dropped, whatever a point of it says.
pub fn outside_material(fused: &Fused, keep: &[bool], inside: impl Fn(&FusedFace) -> bool) -> Vec<Branch> {
    let largest = largest_pieces(fused, keep);
    let mut out = Vec::new();
    for (i, face) in fused.faces.iter().enumerate() {
        if !keep[i] || largest[face.patch] == Some(i) {
            continue;
        }
        let mut crossing: Vec<usize> = face
            .edges
            .iter()
            .flat_map(|&e| fused.edges[e].faces.iter())
            .filter(|&&g| keep[g])
            .map(|&g| fused.faces[g].patch)
            .filter(|&p| p != face.patch)
            .collect();
        crossing.sort_unstable();
        crossing.dedup();
        if !crossing.is_empty() && !inside(face) {
            out.push(Branch::of(i, face, 0.0, crossing, TrimReason::Outside));
        }
    }
    out
}

/// Per patch (indexed by patch), the piece that stands for its body: the largest piece of its heaviest
/// *stretch*, a set of its pieces joined to each other (the union-find forest `parent`), weighed by area (the
/// first on a tie). The largest piece alone is not enough: a floor cut into cells by a grid of ribs can have
/// cells smaller than the band its offset overshoots past the walls all round, and that band, held to the walls
/// by crossing lines only, is the overshoot, not the body. With no pieces joined, the body is the largest piece.
fn heaviest_stretch_pieces(fused: &Fused, parent: &mut [usize]) -> Vec<Option<usize>> {
    let patches = fused.faces.iter().map(|f| f.patch + 1).max().unwrap_or(0);
    let mut weight = vec![0.0; fused.faces.len()];
    for (i, f) in fused.faces.iter().enumerate() {
        weight[find(parent, i)] += f.area;
    }
    // Per patch: (weight of the stretch, area of the piece, piece), the heaviest stretch's largest piece.
    let mut body: Vec<Option<(f64, f64, usize)>> = vec![None; patches];
    for (i, f) in fused.faces.iter().enumerate() {
        let w = weight[find(parent, i)];
        if body[f.patch].is_none_or(|(bw, ba, _)| w > bw || (w == bw && f.area > ba)) {
            body[f.patch] = Some((w, f.area, i));
        }
    }
    body.into_iter().map(|b| b.map(|(_, _, i)| i)).collect()
}

/// Per patch (indexed by patch), its largest piece among those kept (`keep`), the first on a tie.
pub fn largest_pieces(fused: &Fused, keep: &[bool]) -> Vec<Option<usize>> {
    let patches = fused.faces.iter().map(|f| f.patch + 1).max().unwrap_or(0);
    let mut largest: Vec<Option<(f64, usize)>> = vec![None; patches];
    for (i, f) in fused.faces.iter().enumerate().filter(|&(i, _)| keep[i]) {
        if largest[f.patch].is_none_or(|(a, _)| f.area > a) {
            largest[f.patch] = Some((f.area, i));
        }
    }
    largest.into_iter().map(|l| l.map(|(_, i)| i)).collect()
}

/// Which pieces stay once `branches` are dropped.
pub fn keep_mask(pieces: usize, branches: &[Branch]) -> Vec<bool> {
    let mut keep = vec![true; pieces];
    for b in branches {
        keep[b.piece] = false;
    }
    keep
}

/// The kept pieces of one patch joined only to each other (through edges no other kept piece uses), in sets of
/// two or more, each sorted, in order of their lowest piece: a strip grown from an edge, a band left between a
/// crossing and a peeled piece. One face each in the written shells: the STEP then has a face per stretch of
/// wall, not slivers a mesher would have to respect, and each face's measured thickness is its wall's. Two
/// pieces that also share an edge another piece uses (a T-joint's edge) stay apart: merged, that edge would lie
/// inside the face, which a STEP face cannot hold.
pub fn merge_sets(fused: &Fused, keep: &[bool]) -> Vec<Vec<usize>> {
    let n = fused.faces.len();
    let kept_on = |e: usize| fused.edges[e].faces.iter().copied().filter(|&f| keep[f]).collect::<Vec<usize>>();
    let inner: Vec<Option<(usize, usize)>> = (0..fused.edges.len())
        .map(|e| match kept_on(e)[..] {
            [a, b] if a != b && fused.faces[a].patch == fused.faces[b].patch => Some((a, b)),
            _ => None,
        })
        .collect();
    // Per set (by its root): the edges of its pieces that must stay boundary edges.
    let mut outer: Vec<BTreeSet<usize>> = (0..n)
        .map(|f| {
            if keep[f] {
                fused.faces[f].edges.iter().copied().filter(|&e| inner[e].is_none()).collect()
            } else {
                BTreeSet::new()
            }
        })
        .collect();
    let mut parent: Vec<usize> = (0..n).collect();
    for &(a, b) in inner.iter().flatten() {
        let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
        if ra == rb || !outer[ra].is_disjoint(&outer[rb]) {
            continue;
        }
        let (root, other) = (ra.min(rb), ra.max(rb));
        parent[other] = root;
        let moved = std::mem::take(&mut outer[other]);
        outer[root].extend(moved);
    }
    let mut sets = sets_of(&mut parent, keep);
    sets.retain(|s| s.len() > 1);
    sets
}

/// Groups the kept pieces into connected sets (through edges shared by two kept pieces), each sorted, in
/// order of their lowest piece: one shell each.
pub fn connected_sets(fused: &Fused, keep: &[bool]) -> Vec<Vec<usize>> {
    sets_joined(fused, keep, false)
}

/// `connected_sets` as a STEP file keeps them: an edge joins only the pieces that hold it on their boundary, not
/// one that holds it inside (an INTERNAL edge, which the file drops).
pub fn written_sets(fused: &Fused, keep: &[bool]) -> Vec<Vec<usize>> {
    sets_joined(fused, keep, true)
}

fn sets_joined(fused: &Fused, keep: &[bool], boundary_only: bool) -> Vec<Vec<usize>> {
    let n = fused.faces.len();
    let mut parent: Vec<usize> = (0..n).collect();
    for edge in &fused.edges {
        let joins = |f: usize| keep[f] && !(boundary_only && edge.inside.contains(&f));
        let kept: Vec<usize> = edge.faces.iter().copied().filter(|&f| joins(f)).collect();
        for w in kept.windows(2) {
            union(&mut parent, w[0], w[1]);
        }
    }
    sets_of(&mut parent, keep)
}

/// The kept pieces grouped by their root in the union-find forest `parent`, each set sorted, in order of its
/// lowest piece.
fn sets_of(parent: &mut [usize], keep: &[bool]) -> Vec<Vec<usize>> {
    let mut sets: Vec<Vec<usize>> = Vec::new();
    let mut set_of_root: Vec<Option<usize>> = vec![None; parent.len()];
    for f in (0..parent.len()).filter(|&f| keep[f]) {
        let root = find(parent, f);
        match set_of_root[root] {
            Some(s) => sets[s].push(f),
            None => {
                set_of_root[root] = Some(sets.len());
                sets.push(vec![f]);
            }
        }
    }
    sets
}

#[cfg(test)]
mod tests;
