use glam::DVec3;

use super::*;

fn loose(patch: usize, thickness: f64, x: f64, z: f64, y: (f64, f64), outward: DVec3) -> LooseEdge {
    let points = (0..5).map(|k| DVec3::new(x, y.0 + (y.1 - y.0) * k as f64 / 4.0, z)).collect();
    LooseEdge {
        patch,
        wall: (1, patch),
        thickness,
        nearest: f64::INFINITY,
        open: true,
        points,
        normal: DVec3::Z,
        outward,
    }
}

#[test]
fn two_levels_of_a_thickness_step_meet_through_a_ramp_into_the_thicker_wall() {
    // A t=3 patch at z=1.5 starting at x=50 (outward -x), a t=2 patch at z=1 ending there (outward +x).
    let edges = [loose(0, 3.0, 50.0, 1.5, (60.0, 10.0), -DVec3::X), loose(1, 2.0, 50.0, 1.0, (0.0, 60.0), DVec3::X)];
    let bridges = step_bridges(&edges);
    assert_eq!(bridges.len(), 1);
    let StepBridge { owner, other, quad, .. } = &bridges[0];
    assert_eq!((*owner, *other), (1, 0), "the thinner patch owns the ramp");
    // From the thin edge up to a line RAMP_RUN x 2 = 1 inside the thick patch.
    let expected = [(50.0, 10.0, 1.0), (51.0, 10.0, 1.5), (51.0, 60.0, 1.5), (50.0, 60.0, 1.0)];
    for (q, (x, y, z)) in quad.iter().zip(expected) {
        assert!(q.distance(DVec3::new(x, y, z)) < 1e-9, "{quad:?}");
    }
}

#[test]
fn a_long_edge_facing_two_shorter_levels_is_bridged_to_each_along_its_own_stretch() {
    // A t=3 patch at z=1.5 starting at x=50 along y 0..60; two thinner levels of its wall end there, y 0..30
    // at z=1 and y 30..60 at z=1.2 (a plate over a floor and over a recess). Before, the long edge went to the
    // nearer level only and the other's edge stayed open.
    let edges = [
        loose(0, 3.0, 50.0, 1.5, (60.0, 0.0), -DVec3::X),
        loose(1, 2.0, 50.0, 1.0, (0.0, 30.0), DVec3::X),
        loose(2, 2.6, 50.0, 1.2, (30.0, 60.0), DVec3::X),
    ];
    let bridges = step_bridges(&edges);
    let pairs: Vec<(usize, usize)> = bridges.iter().map(|b| (b.owner.min(b.other), b.owner.max(b.other))).collect();
    assert_eq!(pairs, vec![(0, 1), (0, 2)]);
    for (b, (y0, y1)) in bridges.iter().zip([(0.0, 30.0), (30.0, 60.0)]) {
        let ys: Vec<f64> = b.quad.iter().map(|q| q.y).collect();
        assert!(ys.iter().all(|&y| y >= y0 - 1e-9 && y <= y1 + 1e-9), "{ys:?} within {y0}..{y1}");
    }
    // Overlapping stretches are still bridged once: a third level along y 20..40 finds the long edge taken.
    let mut crowded = edges.to_vec();
    crowded.push(loose(3, 2.2, 50.0, 1.1, (20.0, 40.0), DVec3::X));
    assert_eq!(step_bridges(&crowded).iter().filter(|b| b.owner == 3 || b.other == 3).count(), 0);
}

#[test]
fn a_step_edge_that_saw_a_farther_wall_still_bridges_to_the_other_level_of_its_wall() {
    // The thin level's edge found an L partner 4 away (a wall past the step, seen along the patch); the
    // thick level's edge reads as rim. Levels of one wall 0.5 apart: the step wins.
    let thin = LooseEdge { nearest: 4.0, wall: (1, 7), ..loose(1, 2.0, 50.0, 1.0, (0.0, 60.0), DVec3::X) };
    let thick = LooseEdge { open: false, wall: (1, 7), ..loose(0, 3.0, 50.0, 1.5, (60.0, 10.0), -DVec3::X) };
    assert_eq!(step_bridges(&[thick.clone(), thin.clone()]).len(), 1);
    // Not across two walls, not past a nearer partner, and not between two rim edges.
    let other_wall = LooseEdge { wall: (1, 8), ..thick.clone() };
    assert!(step_bridges(&[other_wall, thin.clone()]).is_empty());
    let near = LooseEdge { nearest: 0.4, ..thin.clone() };
    assert!(step_bridges(&[thick.clone(), near]).is_empty());
    let rim = LooseEdge { open: false, ..thin };
    assert!(step_bridges(&[thick, rim]).is_empty());
}

#[test]
fn an_in_plane_gap_is_bridged_flat() {
    let edges = [loose(0, 2.0, 50.0, 1.0, (0.0, 60.0), DVec3::X), loose(1, 2.0, 51.5, 1.0, (0.0, 60.0), -DVec3::X)];
    let bridges = step_bridges(&edges);
    assert_eq!(bridges.len(), 1);
    let expected = [(50.0, 0.0), (51.5, 0.0), (51.5, 60.0), (50.0, 60.0)];
    for (q, (x, y)) in bridges[0].quad.iter().zip(expected) {
        assert!(q.distance(DVec3::new(x, y, 1.0)) < 1e-9, "{:?}", bridges[0].quad);
    }
}

#[test]
fn no_bridge_between_edges_facing_the_same_way_too_far_or_of_one_patch() {
    let same_way = [loose(0, 2.0, 50.0, 1.0, (0.0, 60.0), DVec3::X), loose(1, 2.0, 50.0, 1.5, (0.0, 60.0), DVec3::X)];
    assert!(step_bridges(&same_way).is_empty());
    let far = [loose(0, 2.0, 50.0, 1.0, (0.0, 60.0), DVec3::X), loose(1, 2.0, 50.0, 4.0, (0.0, 60.0), -DVec3::X)];
    assert!(step_bridges(&far).is_empty(), "3 apart, thicker than either wall");
    let one = [loose(0, 2.0, 50.0, 1.0, (0.0, 60.0), DVec3::X), loose(0, 2.0, 50.0, 1.5, (0.0, 60.0), -DVec3::X)];
    assert!(step_bridges(&one).is_empty());
}
