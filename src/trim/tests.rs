use super::*;
use crate::model::shapes::{FusedEdge, FusedFace};

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
    FusedEdge {
        length: a.distance(b),
        faces,
        points: (0..5).map(|k| a.lerp(b, k as f64 / 4.0)).collect(),
        inside: Vec::new(),
        stem_end: false,
    }
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
        invalid: vec![],
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
        invalid: vec![],
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

/// Adds piece 4 of patch 0 to `l_corner`: a 1 x 1 corner touching no other patch, joined to branch 1 by edge 5
/// (its one other edge, 6, free). The perimeter of its two listed edges is 2, its mean width 2 x 1 / 2 = 1 <=
/// 0.75 x 2: overshoot-sized.
fn add_corner_off_branch(fused: &mut Fused) {
    fused.faces.push(face(0, 1.0, vec![5, 6]));
    fused.edges.push(edge(vec![1, 4], DVec3::new(0.0, 40.0, 1.0), DVec3::new(1.0, 40.0, 1.0)));
    fused.edges.push(edge(vec![4], DVec3::new(0.0, 41.0, 1.0), DVec3::new(1.0, 41.0, 1.0)));
    fused.faces[1].edges.push(5);
}

#[test]
fn a_loose_corner_joined_only_to_a_branch_goes_with_it() {
    // Piece 4 of patch 0 touches no other patch: an overshoot corner hanging off branch 1 only.
    let mut fused = l_corner();
    add_corner_off_branch(&mut fused);
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

#[test]
fn an_edge_inside_a_piece_joins_it_to_nothing_once_written() {
    // The crossing held inside piece 0 (a joint that ended inside it): connected, yet apart once written.
    let mut fused = l_corner();
    fused.edges[0].inside = vec![0];
    let keep = [true, false, true, false];
    assert_eq!(connected_sets(&fused, &keep), vec![vec![0, 2]]);
    assert_eq!(written_sets(&fused, &keep), vec![vec![0], vec![2]]);
    assert_eq!(written_sets(&fused, &[true, true, true, false]), vec![vec![0], vec![1, 2]]);
}

#[test]
fn merge_sets_join_pieces_of_one_patch_across_edges_only_they_share() {
    let v = |x: f64| DVec3::new(x, 0.0, 0.0);
    // Patch 0: pieces 0, 1, 2 in a row; 1 and 2 also meet piece 3 of patch 1 along their common edge (a T).
    // Patch 1: pieces 3 and 4 side by side, and 4 is dropped.
    let fused = Fused {
        handle: 1,
        invalid: vec![],
        faces: vec![
            face(0, 1.0, vec![0]),
            face(0, 1.0, vec![0, 1]),
            face(0, 1.0, vec![1]),
            face(1, 1.0, vec![1, 2]),
            face(1, 1.0, vec![2]),
        ],
        edges: vec![
            edge(vec![0, 1], v(0.0), v(1.0)),
            edge(vec![1, 2, 3], v(1.0), v(2.0)),
            edge(vec![3, 4], v(2.0), v(3.0)),
        ],
    };
    assert_eq!(merge_sets(&fused, &[true, true, true, true, false]), vec![vec![0, 1]]);
    assert_eq!(merge_sets(&fused, &[true; 5]), vec![vec![0, 1], vec![3, 4]]);
}

#[test]
fn merge_sets_keep_apart_pieces_that_also_share_a_t_joints_edge() {
    let v = |x: f64| DVec3::new(x, 0.0, 0.0);
    // Pieces 0 and 1 of patch 0 share edge 0 (theirs alone) and edge 1, where piece 2 of patch 1 stands (a T
    // ending on their common boundary): merged, the T's edge would lie inside the face.
    let fused = Fused {
        handle: 1,
        invalid: vec![],
        faces: vec![face(0, 1.0, vec![0, 1]), face(0, 1.0, vec![0, 1]), face(1, 1.0, vec![1])],
        edges: vec![edge(vec![0, 1], v(0.0), v(1.0)), edge(vec![0, 1, 2], v(1.0), v(2.0))],
    };
    assert!(merge_sets(&fused, &[true; 3]).is_empty());
    // Without the T, the two pieces merge.
    assert_eq!(merge_sets(&fused, &[true, true, false]), vec![vec![0, 1]]);
}

/// A ribbed floor's patch (0) at its edge, in plan: the band its offset overshoots past a wall (piece 0, between
/// the wall's mid-surface at x = 1 and the floor's outer edge at x = 0, 40 long), and two cells (pieces 1 and 2,
/// x 1..11) between that wall (patch 1), a rib (patch 2, x = 11) and a cross wall (patch 3, at y = 0 and y = 40),
/// split at y = 20 where a rib's line, stopping short, was carried through. The band is larger than either cell.
fn ribbed_floor_edge() -> Fused {
    let v = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let edges = vec![
        edge(vec![0, 1, 3], v(1.0, 0.0, 0.0), v(1.0, 20.0, 0.0)),
        edge(vec![0, 2, 3], v(1.0, 20.0, 0.0), v(1.0, 40.0, 0.0)),
        edge(vec![0], v(0.0, 0.0, 0.0), v(0.0, 40.0, 0.0)),
        edge(vec![1, 4], v(11.0, 0.0, 0.0), v(11.0, 20.0, 0.0)),
        edge(vec![2, 4], v(11.0, 20.0, 0.0), v(11.0, 40.0, 0.0)),
        edge(vec![1, 2], v(1.0, 20.0, 0.0), v(11.0, 20.0, 0.0)),
        edge(vec![1, 5], v(1.0, 0.0, 0.0), v(11.0, 0.0, 0.0)),
        edge(vec![2, 5], v(1.0, 40.0, 0.0), v(11.0, 40.0, 0.0)),
        edge(vec![3], v(1.0, 0.0, 30.0), v(1.0, 40.0, 30.0)),
        edge(vec![4], v(11.0, 0.0, 8.0), v(11.0, 40.0, 8.0)),
        edge(vec![5], v(0.0, 0.0, 30.0), v(40.0, 0.0, 30.0)),
    ];
    Fused {
        handle: 1,
        invalid: vec![],
        faces: vec![
            face(0, 300.0, vec![0, 1, 2]),
            face(0, 200.0, vec![0, 3, 5, 6]),
            face(0, 200.0, vec![1, 4, 5, 7]),
            face(1, 1200.0, vec![0, 1, 8]),
            face(2, 320.0, vec![3, 4, 9]),
            face(3, 1200.0, vec![6, 7, 10]),
        ],
        edges,
    }
}

#[test]
fn the_band_past_the_walls_goes_though_it_is_the_largest_piece() {
    // The band hangs past the wall by 1 (within 0.75 x 2); the two cells, joined along y = 20, outweigh it and
    // are the floor's body, though every vertex of theirs lies on a crossing line.
    let branches = find_branches(&ribbed_floor_edge(), &mid_limits(&[2.0; 4]));
    assert_eq!(branches.iter().map(|b| b.piece).collect::<Vec<_>>(), vec![0]);
    assert!((branches[0].width - 1.0).abs() < 1e-12);
}

/// Adds piece 4 of patch 0 to `l_corner`: the wall running on past a tube's end, joined to branch 1 by a 1.0
/// edge (5, plain: make it the cut with `stem_end`) and to the main piece 0 by a long edge of their own (7).
fn add_wall_past_a_tube_end(fused: &mut Fused) {
    fused.faces.push(face(0, 400.0, vec![5, 6, 7]));
    fused.edges.push(edge(vec![1, 4], DVec3::new(0.0, 40.0, 1.0), DVec3::new(1.0, 40.0, 1.0)));
    fused.edges.push(edge(vec![4], DVec3::new(0.0, 60.0, 1.0), DVec3::new(20.0, 60.0, 1.0)));
    fused.edges.push(edge(vec![0, 4], DVec3::new(1.0, 40.0, 1.0), DVec3::new(20.0, 40.0, 1.0)));
    fused.faces[1].edges.push(5);
    fused.faces[0].edges.push(7);
}

#[test]
fn a_strip_inside_a_tube_wall_is_a_branch_though_the_wall_runs_on_past_the_tube() {
    // Piece 4 of patch 0 (the wall running on past a tube's end) is joined to branch 1 (the wall inside the
    // tube's wall) by the cut across the tube's end, and to the main piece 0 by a long edge of their own.
    let mut fused = l_corner();
    add_wall_past_a_tube_end(&mut fused);
    // Any other edge that short joins piece 4 to the strip, which stays.
    assert_eq!(branch_pieces(&fused), vec![3]);
    // The cut joins nothing: the strip goes.
    fused.edges[5].stem_end = true;
    assert_eq!(branch_pieces(&fused), vec![1, 3]);
    // Unless piece 4 reaches no crossing but through the strip: it keeps it.
    fused.faces[0].edges.pop();
    fused.faces[4].edges.pop();
    fused.edges.pop();
    assert_eq!(branch_pieces(&fused), vec![3]);
}

#[test]
fn a_strip_closed_in_by_crossings_and_a_tube_end_cut_is_still_a_branch() {
    // Branch 1 loses its free edge to a crossing (closed in), but one of its edges is the cut across a tube's
    // end to piece 4 (held by the main piece 0): the cut bounds it as a free edge would.
    let mut fused = l_corner();
    fused.edges[2].faces = vec![1, 2];
    fused.faces[2].edges.push(2);
    add_wall_past_a_tube_end(&mut fused);
    assert_eq!(branch_pieces(&fused), vec![3]);
    fused.edges[5].stem_end = true;
    assert_eq!(branch_pieces(&fused), vec![1, 3]);
}

#[test]
fn a_loose_piece_beyond_a_tube_end_cut_stays_with_the_strip_that_stays() {
    // Piece 4 (overshoot-sized, touching no other patch) is joined only by the cut across a tube's end to strip
    // 1, which is held by the main piece 0 through a long edge of their own: both stay.
    let mut fused = l_corner();
    add_corner_off_branch(&mut fused);
    fused.edges.push(edge(vec![0, 1], DVec3::new(0.5, 0.0, 1.0), DVec3::new(0.5, 40.0, 1.0)));
    fused.faces[1].edges.push(7);
    fused.faces[0].edges.push(7);
    fused.edges[5].stem_end = true;
    assert_eq!(branch_pieces(&fused), vec![3]);
}
