//! Trimming (Sheen et al. 5.3): after the patches are split where they cross, drop the small branches.
//!
//! Offsetting the larger face of each wall makes neighbouring patches run past each other: at an L corner
//! each patch overshoots the other by half the other's thickness. A piece of a split patch is such a branch
//! when it touches another patch (a crossing line), is not the largest piece of its patch, and every point
//! of its boundary lies within 0.75 x the crossing patch's thickness of the crossing lines (the overshoot is
//! half a thickness; the margin absorbs tilted walls). A piece joined to another piece of its own patch by an
//! edge that no other patch shares (longer than the overshoot) is not hanging: a joint strip grown from the
//! patch's edge stays. A hanging piece touching no other patch stays only when so joined to a piece that is
//! not a branch: overshoot corners joined only to branches go with them.

use glam::DVec3;
use serde::Serialize;

use crate::kernel::protocol::{Fused, FusedFace};
use union_find::find;

mod union_find;

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

/// The branches to drop; `limit[k]` is how far a branch may hang past patch k (see [`branch_limit`]).
pub fn find_branches(fused: &Fused, limit: &[f64]) -> Vec<Branch> {
    let largest = largest_pieces(fused, &vec![true; fused.faces.len()]);
    let mut candidates: Vec<Option<Branch>> = vec![None; fused.faces.len()];
    // Pieces of the same patch sharing an edge no other patch crosses.
    let mut own_links: Vec<Vec<usize>> = vec![Vec::new(); fused.faces.len()];
    // Hanging pieces that touch no other patch (an overshoot corner, the end of a strip): they anchor nothing
    // and stay only when joined to a piece that does.
    let mut loose = vec![false; fused.faces.len()];
    for (i, face) in fused.faces.iter().enumerate() {
        let mut crossing: Vec<usize> = Vec::new();
        let mut lines: Vec<&[DVec3]> = Vec::new();
        let mut own: Vec<usize> = Vec::new();
        let mut hanging = false;
        for &e in &face.edges {
            let edge = &fused.edges[e];
            let others: Vec<usize> =
                edge.faces.iter().map(|&g| fused.faces[g].patch).filter(|&p| p != face.patch).collect();
            if !others.is_empty() {
                crossing.extend(others);
                lines.push(&edge.points);
            } else if edge.faces.iter().any(|&g| g != i) {
                own.push(e);
            } else {
                // A free edge, or a seam (listed twice for this face): the piece's boundary goes on past it.
                hanging = true;
            }
        }
        crossing.sort_unstable();
        crossing.dedup();
        let across = crossing.iter().map(|&p| limit[p]).fold(0.0, f64::max);
        for e in own {
            let edge = &fused.edges[e];
            if edge.length < across {
                // Shorter than an overshoot: where the crossing line stops a little before the strip does, the
                // stub between the two is part of the cut, not what joins the piece to its patch.
                lines.push(&edge.points);
            } else {
                own_links[i].extend(edge.faces.iter().copied().filter(|&g| g != i));
            }
        }
        if largest[face.patch] == Some(i) || (!hanging && own_links[i].is_empty()) {
            // The main piece, or one closed in by crossing lines all round (a floor between walls): however
            // narrow, a branch hangs past the crossing, by a free edge or with other overshoot pieces.
            continue;
        }
        if crossing.is_empty() {
            // Only an overshoot-sized piece (mean width 2 x area / perimeter within the branch limit of its own
            // thickness) is loose: a large piece split off by its patch's own edges is part of the wall.
            let perimeter: f64 = face.edges.iter().map(|&e| fused.edges[e].length).sum();
            loose[i] = hanging && 2.0 * face.area <= limit[face.patch] * perimeter;
            continue;
        }
        let width = face
            .edges
            .iter()
            .flat_map(|&e| fused.edges[e].points.iter())
            .map(|&p| lines.iter().map(|l| distance_to_polyline(p, l)).fold(f64::INFINITY, f64::min))
            .fold(0.0, f64::max);
        if width <= across {
            candidates[i] = Some(Branch::of(i, face, width, crossing, TrimReason::Overshoot));
        }
    }
    // A narrow piece joined (through other narrow pieces) to a piece of its patch that is not narrow continues
    // the patch (a joint strip grown from its edge): only the rest hang past crossings.
    let mut anchored: Vec<bool> = candidates.iter().zip(&loose).map(|(c, &l)| c.is_none() && !l).collect();
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
        if loose[i] && !anchored[i] {
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

/// Per patch (indexed by patch), its largest piece among those kept (`keep`), the first on a tie.
fn largest_pieces(fused: &Fused, keep: &[bool]) -> Vec<Option<usize>> {
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

/// Groups the kept pieces into connected sets (through edges shared by two kept pieces), each sorted, in
/// order of their lowest piece: one shell each.
pub fn connected_sets(fused: &Fused, keep: &[bool]) -> Vec<Vec<usize>> {
    let n = fused.faces.len();
    let mut parent: Vec<usize> = (0..n).collect();
    for edge in &fused.edges {
        let kept: Vec<usize> = edge.faces.iter().copied().filter(|&f| keep[f]).collect();
        for w in kept.windows(2) {
            let (a, b) = (find(&mut parent, w[0]), find(&mut parent, w[1]));
            parent[a.max(b)] = a.min(b);
        }
    }
    let mut sets: Vec<Vec<usize>> = Vec::new();
    let mut set_of_root: Vec<Option<usize>> = vec![None; n];
    for f in (0..n).filter(|&f| keep[f]) {
        let root = find(&mut parent, f);
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
mod tests {
    use super::*;
    use crate::kernel::protocol::{FusedEdge, FusedFace};

    fn mid_limits(thickness: &[f64]) -> Vec<f64> {
        thickness.iter().map(|&t| branch_limit(t, 0.0)).collect()
    }

    /// The pieces found to be branches of two 2 mm mid patches.
    fn branch_pieces(fused: &Fused) -> Vec<usize> {
        find_branches(fused, &mid_limits(&[2.0, 2.0])).iter().map(|b| b.piece).collect()
    }

    fn face(patch: usize, area: f64, edges: Vec<usize>) -> FusedFace {
        FusedFace { patch, area, centroid: DVec3::ZERO, point: DVec3::ZERO, normal: DVec3::Z, edges }
    }

    fn edge(faces: Vec<usize>, a: DVec3, b: DVec3) -> FusedEdge {
        FusedEdge { length: a.distance(b), faces, points: (0..5).map(|k| a.lerp(b, k as f64 / 4.0)).collect() }
    }

    /// An L corner in the x-z section, 40 deep in y: the bottom patch (z = 1, x 0..60) crossed by the wall
    /// patch (x = 1, z 0..40). Each is split at the crossing line (x = 1, z = 1) into a main piece and a
    /// branch of width 1.
    fn l_corner() -> Fused {
        let v = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
        let crossing = edge(vec![0, 1, 2, 3], v(1.0, 0.0, 1.0), v(1.0, 40.0, 1.0));
        let mut edges = vec![crossing];
        // Free edges of each piece (outline only; enough for the widths).
        let outline = [
            (0, v(60.0, 0.0, 1.0), v(60.0, 40.0, 1.0)),
            (1, v(0.0, 0.0, 1.0), v(0.0, 40.0, 1.0)),
            (2, v(1.0, 0.0, 40.0), v(1.0, 40.0, 40.0)),
            (3, v(1.0, 0.0, 0.0), v(1.0, 40.0, 0.0)),
        ];
        for (f, a, b) in outline {
            edges.push(edge(vec![f], a, b));
        }
        Fused {
            handle: 1,
            faces: vec![
                face(0, 2360.0, vec![0, 1]),
                face(0, 40.0, vec![0, 2]),
                face(1, 1560.0, vec![0, 3]),
                face(1, 40.0, vec![0, 4]),
            ],
            edges,
        }
    }

    /// A main pipe's patch (0) split by a branch's patch (1) into its body (piece 0) and the cap across the
    /// branch's bore (piece 1, point at x = 100); the branch (piece 2) and a loose piece of the main touching
    /// no other patch (piece 3, point at x = 200).
    fn tee() -> Fused {
        let v = |x: f64| DVec3::new(x, 0.0, 0.0);
        let at = |mut f: FusedFace, x: f64| {
            f.point = v(x);
            f
        };
        Fused {
            handle: 1,
            faces: vec![
                at(face(0, 5000.0, vec![0, 2]), 0.0),
                at(face(0, 600.0, vec![0]), 100.0),
                at(face(1, 3000.0, vec![0]), 50.0),
                at(face(0, 300.0, vec![2]), 200.0),
            ],
            edges: vec![
                edge(vec![0, 1, 2], v(0.0), v(1.0)),
                edge(vec![3], v(0.0), v(1.0)),
                edge(vec![0, 3], v(0.0), v(1.0)),
            ],
        }
    }

    #[test]
    fn the_cap_across_a_bore_is_outside_the_material() {
        // Material everywhere but beyond x = 90: the cap and the loose piece are out, only the cap touches
        // another patch.
        let fused = tee();
        let out = outside_material(&fused, &[true; 4], |f| f.point.x < 90.0);
        assert_eq!(out.iter().map(|b| (b.piece, b.reason)).collect::<Vec<_>>(), vec![(1, TrimReason::Outside)]);
        assert_eq!(out[0].crossing, vec![1]);
        // A piece already dropped neither counts as the patch's largest nor as a neighbour.
        let keep = [false, true, true, true];
        let out = outside_material(&fused, &keep, |_| false);
        assert_eq!(out.iter().map(|b| b.piece).collect::<Vec<_>>(), Vec::<usize>::new(), "piece 1 is now the largest");
    }

    #[test]
    fn the_body_of_a_patch_is_never_outside() {
        assert!(outside_material(&tee(), &[true; 4], |_| false).iter().all(|b| b.piece != 0 && b.piece != 2));
    }

    #[test]
    fn l_corner_loses_both_overshoots() {
        let branches = find_branches(&l_corner(), &mid_limits(&[2.0, 2.0]));
        let pieces: Vec<usize> = branches.iter().map(|b| b.piece).collect();
        assert_eq!(pieces, vec![1, 3]);
        assert!((branches[0].width - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_wide_piece_is_not_a_branch() {
        // With thin crossing walls (t = 1.2) the 1 mm overshoot exceeds 0.75 x 1.2 = 0.9: kept.
        assert!(find_branches(&l_corner(), &mid_limits(&[1.2, 1.2])).is_empty());
    }

    #[test]
    fn past_a_patch_on_a_skin_a_branch_may_hang_a_whole_thickness() {
        // The same 1 mm overshoot past walls 1.2 thick whose patches lie on a skin (0.6 off the middle).
        let limits: Vec<f64> = [1.2, 1.2].iter().map(|&t| branch_limit(t, 0.6)).collect();
        let pieces: Vec<usize> = find_branches(&l_corner(), &limits).iter().map(|b| b.piece).collect();
        assert_eq!(pieces, vec![1, 3]);
    }

    #[test]
    fn a_piece_closed_in_by_crossings_is_not_a_branch() {
        // Piece 1 of patch 0 loses its free edge: only the crossing line and another crossing bound it.
        let mut fused = l_corner();
        fused.edges[2].faces = vec![1, 2];
        let pieces = branch_pieces(&fused);
        assert_eq!(pieces, vec![3]);
    }

    #[test]
    fn a_strip_attached_to_its_patch_is_not_a_branch() {
        // Piece 1 of patch 0 also shares a free-standing edge with piece 0 (the edge it grew from).
        let mut fused = l_corner();
        fused.edges.push(edge(vec![0, 1], DVec3::new(0.5, 0.0, 1.0), DVec3::new(0.5, 40.0, 1.0)));
        fused.faces[0].edges.push(5);
        fused.faces[1].edges.push(5);
        let pieces = branch_pieces(&fused);
        assert_eq!(pieces, vec![3]);
    }

    #[test]
    fn a_loose_corner_joined_only_to_a_branch_goes_with_it() {
        // Piece 4 of patch 0 touches no other patch: an overshoot corner hanging off branch 1 only.
        let mut fused = l_corner();
        fused.faces.push(face(0, 1.0, vec![5, 6]));
        // (perimeter of its two listed edges 2, mean width 2 x 1 / 2 = 1 <= 0.75 x 2: overshoot-sized)
        fused.edges.push(edge(vec![1, 4], DVec3::new(0.0, 40.0, 1.0), DVec3::new(1.0, 40.0, 1.0)));
        fused.edges.push(edge(vec![4], DVec3::new(0.0, 41.0, 1.0), DVec3::new(1.0, 41.0, 1.0)));
        fused.faces[1].edges.push(5);
        let pieces = branch_pieces(&fused);
        assert_eq!(pieces, vec![1, 3, 4]);
        // Joined to the main piece instead (by an edge longer than the overshoot), it stays.
        fused.edges[5] = edge(vec![0, 4], DVec3::new(1.0, 40.0, 1.0), DVec3::new(3.0, 40.0, 1.0));
        fused.faces[1].edges.pop();
        fused.faces[0].edges.push(5);
        let pieces = branch_pieces(&fused);
        assert_eq!(pieces, vec![1, 3]);
    }

    #[test]
    fn a_large_piece_touching_no_other_patch_is_not_loose() {
        let mut fused = l_corner();
        fused.faces.push(face(0, 400.0, vec![5, 6]));
        fused.edges.push(edge(vec![1, 4], DVec3::new(0.0, 40.0, 1.0), DVec3::new(1.0, 40.0, 1.0)));
        fused.edges.push(edge(vec![4], DVec3::new(0.0, 60.0, 1.0), DVec3::new(20.0, 60.0, 1.0)));
        fused.faces[1].edges.push(5);
        // It is part of the wall: it stays, and anchors the strip joined to it.
        let pieces = branch_pieces(&fused);
        assert_eq!(pieces, vec![3]);
    }

    #[test]
    fn a_stub_shorter_than_the_overshoot_does_not_anchor() {
        // Piece 1 reaches past the end of the crossing line by a 0.3 stub shared with piece 0: still a branch.
        let mut fused = l_corner();
        fused.edges.push(edge(vec![0, 1], DVec3::new(1.0, 40.0, 1.0), DVec3::new(1.0, 40.3, 1.0)));
        fused.faces[0].edges.push(5);
        fused.faces[1].edges.push(5);
        let pieces = branch_pieces(&fused);
        assert_eq!(pieces, vec![1, 3]);
    }

    #[test]
    fn kept_pieces_group_into_shells() {
        let fused = l_corner();
        assert_eq!(connected_sets(&fused, &[true, false, true, false]), vec![vec![0, 2]]);
        assert_eq!(connected_sets(&fused, &[true, false, false, true]), vec![vec![0, 3]]);
    }
}
