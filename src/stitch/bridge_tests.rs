use std::f64::consts::FRAC_PI_2;

use glam::{DVec2, DVec3};

use super::*;

const COPLANAR: f64 = 1e-6;

fn loose(patch: usize, thickness: f64, x: f64, z: f64, y: (f64, f64), outward: DVec3) -> LooseEdge {
    let points = (0..5).map(|k| DVec3::new(x, y.0 + (y.1 - y.0) * k as f64 / 4.0, z)).collect();
    open_edge(patch, thickness, points, DVec3::Z, outward)
}

/// An open edge of patch `patch` (its own wall) that found no partner.
fn open_edge(patch: usize, thickness: f64, points: Vec<DVec3>, normal: DVec3, outward: DVec3) -> LooseEdge {
    LooseEdge {
        patch,
        wall: (1, patch),
        thickness,
        nearest: f64::INFINITY,
        reach: 3.0 * thickness,
        freeform: false,
        open: true,
        outwards: vec![outward; points.len()],
        face: [points[0] - outward, normal],
        points,
        normal,
    }
}

#[test]
fn two_levels_of_a_thickness_step_meet_through_a_ramp_into_the_thicker_wall() {
    // A t=3 patch at z=1.5 starting at x=50 (outward -x), a t=2 patch at z=1 ending there (outward +x).
    let edges = [loose(0, 3.0, 50.0, 1.5, (60.0, 10.0), -DVec3::X), loose(1, 2.0, 50.0, 1.0, (0.0, 60.0), DVec3::X)];
    let bridges = step_bridges(&edges, COPLANAR);
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
    let bridges = step_bridges(&edges, COPLANAR);
    let pairs: Vec<(usize, usize)> = bridges.iter().map(|b| (b.owner.min(b.other), b.owner.max(b.other))).collect();
    assert_eq!(pairs, vec![(0, 1), (0, 2)]);
    for (b, (y0, y1)) in bridges.iter().zip([(0.0, 30.0), (30.0, 60.0)]) {
        let ys: Vec<f64> = b.quad.iter().map(|q| q.y).collect();
        assert!(ys.iter().all(|&y| y >= y0 - 1e-9 && y <= y1 + 1e-9), "{ys:?} within {y0}..{y1}");
    }
    // Overlapping stretches are still bridged once: a third level along y 20..40 finds the long edge taken.
    let mut crowded = edges.to_vec();
    crowded.push(loose(3, 2.2, 50.0, 1.1, (20.0, 40.0), DVec3::X));
    assert_eq!(step_bridges(&crowded, COPLANAR).iter().filter(|b| b.owner == 3 || b.other == 3).count(), 0);
}

#[test]
fn a_step_edge_that_saw_a_farther_wall_still_bridges_to_the_other_level_of_its_wall() {
    // The thin level's edge found an L partner 4 away (a wall past the step, seen along the patch); the
    // thick level's edge reads as rim. Levels of one wall 0.5 apart: the step wins.
    let thin = LooseEdge { nearest: 4.0, wall: (1, 7), ..loose(1, 2.0, 50.0, 1.0, (0.0, 60.0), DVec3::X) };
    let thick = LooseEdge { open: false, wall: (1, 7), ..loose(0, 3.0, 50.0, 1.5, (60.0, 10.0), -DVec3::X) };
    assert_eq!(step_bridges(&[thick.clone(), thin.clone()], COPLANAR).len(), 1);
    // Not across two walls, not past a nearer partner, and not between two rim edges.
    let other_wall = LooseEdge { wall: (1, 8), ..thick.clone() };
    assert!(step_bridges(&[other_wall, thin.clone()], COPLANAR).is_empty());
    let near = LooseEdge { nearest: 0.4, ..thin.clone() };
    assert!(step_bridges(&[thick.clone(), near], COPLANAR).is_empty());
    let rim = LooseEdge { open: false, ..thin };
    assert!(step_bridges(&[thick, rim], COPLANAR).is_empty());
}

#[test]
fn an_in_plane_gap_is_bridged_flat() {
    let edges = [loose(0, 2.0, 50.0, 1.0, (0.0, 60.0), DVec3::X), loose(1, 2.0, 51.5, 1.0, (0.0, 60.0), -DVec3::X)];
    let bridges = step_bridges(&edges, COPLANAR);
    assert_eq!(bridges.len(), 1);
    let expected = [(50.0, 0.0), (51.5, 0.0), (51.5, 60.0), (50.0, 60.0)];
    for (q, (x, y)) in bridges[0].quad.iter().zip(expected) {
        assert!(q.distance(DVec3::new(x, y, 1.0)) < 1e-9, "{:?}", bridges[0].quad);
    }
}

#[test]
fn a_flat_bridge_in_the_plane_of_one_edge_s_face_joins_that_face_facing_its_way() {
    // A bend's patch (no plane at its edge: its face's middle lies off the tangent plane there) ends at x = 4.95,
    // a flat wall's patch (plane z = 0.75, normal -z) starts at x = 5: the bend's edge comes first, but the quad
    // lies in the flat's plane, so the flat owns it, facing -z as its face does.
    let bend = LooseEdge {
        face: [DVec3::new(3.95, 15.0, 0.25), DVec3::Z],
        ..loose(0, 1.5, 4.95, 0.75, (0.0, 30.0), DVec3::X)
    };
    let flat = LooseEdge {
        normal: -DVec3::Z,
        face: [DVec3::new(40.0, 15.0, 0.75), -DVec3::Z],
        ..loose(1, 1.5, 5.0, 0.75, (30.0, 0.0), -DVec3::X)
    };
    let bridges = step_bridges(&[bend.clone(), flat.clone()], COPLANAR);
    assert_eq!(bridges.len(), 1);
    let StepBridge { owner, other, quad, normal, .. } = &bridges[0];
    assert_eq!((*owner, *other, *normal), (1, 0, -DVec3::Z));
    assert!(quad[0].x == 5.0 && quad[1].x == 4.95 && quad[2].x == 4.95 && quad[3].x == 5.0, "{quad:?}");
    // Out of its plane (the bend's edge 0.01 above it), the first edge keeps it, facing its outward way.
    let above = LooseEdge { points: bend.points.iter().map(|p| *p + DVec3::Z * 0.01).collect(), ..bend };
    let bridges = step_bridges(&[above, flat], COPLANAR);
    assert_eq!((bridges[0].owner, bridges[0].normal), (0, DVec3::X));
}

#[test]
fn no_bridge_between_edges_facing_the_same_way_too_far_or_of_one_patch() {
    let same_way = [loose(0, 2.0, 50.0, 1.0, (0.0, 60.0), DVec3::X), loose(1, 2.0, 50.0, 1.5, (0.0, 60.0), DVec3::X)];
    assert!(step_bridges(&same_way, COPLANAR).is_empty());
    let far = [loose(0, 2.0, 50.0, 1.0, (0.0, 60.0), DVec3::X), loose(1, 2.0, 50.0, 4.0, (0.0, 60.0), -DVec3::X)];
    assert!(step_bridges(&far, COPLANAR).is_empty(), "3 apart, thicker than either wall");
    let one = [loose(0, 2.0, 50.0, 1.0, (0.0, 60.0), DVec3::X), loose(0, 2.0, 50.0, 1.5, (0.0, 60.0), -DVec3::X)];
    assert!(step_bridges(&one, COPLANAR).is_empty());
}

/// A quarter arc about the z axis from angle a0 to a1 (radians), of radius r at height z, sampled as the probes
/// sample an edge (5 points, ends included), with the patch normal radial (outward from the axis) and the
/// given outward direction.
fn arc(patch: usize, thickness: f64, r: f64, z: f64, (a0, a1): (f64, f64), outward: DVec3) -> LooseEdge {
    let at = |k: usize| a0 + (a1 - a0) * k as f64 / 4.0;
    let points = (0..5).map(|k| DVec3::new(r * at(k).cos(), r * at(k).sin(), z)).collect();
    let mid = at(2);
    open_edge(patch, thickness, points, DVec3::new(mid.cos(), mid.sin(), 0.0), outward)
}

#[test]
fn a_rim_band_over_a_rounded_corner_meets_the_wall_below_through_a_conical_ramp() {
    // A housing's rounded corner (axis z): the wall's mid-surface (t = 2) at radius 10.39 up to z = 35.64, the
    // thinner rim band's (t = 1.27) at radius 10.76 from there up: the band's patch lies 0.37 further out.
    let edges = [
        arc(0, 2.0, 10.39, 35.64, (0.0, FRAC_PI_2), DVec3::Z),
        arc(1, 1.27, 10.76, 35.64, (FRAC_PI_2, 0.0), -DVec3::Z),
    ];
    let bridges = step_bridges(&edges, COPLANAR);
    assert_eq!(bridges.len(), 1, "{bridges:?}");
    let StepBridge { owner, other, quad, axis, .. } = &bridges[0];
    assert_eq!((*owner, *other), (1, 0), "the thinner patch owns the ramp");
    let [origin, direction] = axis.expect("a band between arcs has their axis");
    assert!(origin.truncate().length() < 1e-9 && (direction.z.abs() - 1.0).abs() < 1e-12, "{axis:?}");
    // From the band's edge down to an arc RAMP_RUN x 1.27 = 0.635 inside the wall's patch, over the quarter.
    let radius = |p: DVec3| p.truncate().length();
    for (q, (r, z)) in quad.iter().zip([(10.76, 35.64), (10.39, 35.005), (10.39, 35.005), (10.76, 35.64)]) {
        assert!((radius(*q) - r).abs() < 1e-9 && (q.z - z).abs() < 1e-9, "{quad:?}");
    }
    // Counter-clockwise about the axis from quad[0] to quad[3]: a quarter turn.
    let turn = |p: DVec3, q: DVec3| direction.dot(p.cross(q)).atan2(p.truncate().dot(q.truncate()));
    assert!((turn(quad[0], quad[3]) - FRAC_PI_2).abs() < 1e-9, "{quad:?}");
    // Arcs about different axes are no step.
    let mut moved = edges.clone();
    moved[1].points.iter_mut().for_each(|p| p.x += 0.5);
    assert!(step_bridges(&moved, COPLANAR).is_empty());
}

#[test]
fn a_tube_stepping_between_thicknesses_all_round_meets_through_a_whole_turn_of_a_ramp() {
    // A stepped bore (axis z): the 2.5 mm wall's mid-cylinder (r 17.25) up to z = 6, the 4 mm wall's (r 16.5)
    // from there up; each patch's edge at the step is a whole circle, starting where it ends.
    let edges = [arc(0, 4.0, 16.5, 6.0, (TAU, 0.0), -DVec3::Z), arc(1, 2.5, 17.25, 6.0, (0.0, TAU), DVec3::Z)];
    let bridges = step_bridges(&edges, COPLANAR);
    assert_eq!(bridges.len(), 1, "{bridges:?}");
    let StepBridge { owner, other, quad, axis, .. } = &bridges[0];
    assert_eq!((*owner, *other), (1, 0), "the thinner patch owns the ramp");
    assert!(axis.is_some(), "a band between circles has their axis");
    // A whole turn: each side of the quad starts where it ends, from the thin circle to one RAMP_RUN x 2.5
    // inside the thick patch.
    let radius = |p: DVec3| p.truncate().length();
    assert!(quad[0].distance(quad[3]) < 1e-9 && quad[1].distance(quad[2]) < 1e-9, "{quad:?}");
    assert!((radius(quad[0]) - 17.25).abs() < 1e-9 && (quad[0].z - 6.0).abs() < 1e-9, "{quad:?}");
    assert!((radius(quad[1]) - 16.5).abs() < 1e-9 && (quad[1].z - 7.25).abs() < 1e-9, "{quad:?}");
    // The whole circle is taken: a third level round the same bore finds no stretch left.
    let crowded = [edges[0].clone(), edges[1].clone(), arc(2, 2.6, 17.3, 6.0, (0.0, TAU), DVec3::Z)];
    assert_eq!(step_bridges(&crowded, COPLANAR).len(), 1);
}

/// A ruling of a cylinder of radius `r` about the z axis at angle `a` (radians), from z0 to z1, of patch `patch`
/// (t = 3), its outward direction the tangent turning `sense` (+1 counter-clockwise) about the axis.
fn ruling(patch: usize, r: f64, a: f64, (z0, z1): (f64, f64), sense: f64) -> LooseEdge {
    let points = (0..5).map(|k| DVec3::new(r * a.cos(), r * a.sin(), z0 + (z1 - z0) * k as f64 / 4.0)).collect();
    let outward = DVec3::new(-a.sin(), a.cos(), 0.0) * sense;
    open_edge(patch, 3.0, points, DVec3::new(a.cos(), a.sin(), 0.0), outward)
}

#[test]
fn a_gap_in_a_tubes_own_surface_is_closed_by_a_band_of_its_cylinder() {
    // A boss's mid-cylinder (r 3.75) split where a rib crosses it off its axis: one arc ends at angle 0 turning
    // clockwise, the other at -33 degrees turning counter-clockwise; the gap is 3.75 x 0.576 = 2.16 long.
    let gap = -33f64.to_radians();
    let edges = [ruling(2, 3.75, 0.0, (3.0, 31.6), -1.0), ruling(2, 3.75, gap, (31.6, 3.0), 1.0)];
    let bridges = ruling_gaps(&edges);
    assert_eq!(bridges.len(), 1, "{bridges:?}");
    let StepBridge { quad, axis, .. } = &bridges[0];
    let [origin, direction] = axis.expect("a band of the cylinder has its axis");
    assert!(origin.truncate().length() < 1e-9 && (direction.z.abs() - 1.0).abs() < 1e-12, "{axis:?}");
    // [a(s0), a(s1), b(s1), b(s0)]: the arcs a -> b turn counter-clockwise about `direction` by the gap.
    let level = |p: DVec3| DVec3::new(p.x, p.y, 0.0);
    let turn = |p: DVec3, q: DVec3| direction.dot(level(p).cross(level(q))).atan2(level(p).dot(level(q)));
    assert!((turn(quad[0], quad[3]).abs() - gap.abs()).abs() < 1e-9, "{quad:?}");
    assert!((turn(quad[0], quad[3]) - turn(quad[1], quad[2])).abs() < 1e-9 && turn(quad[0], quad[3]) > 0.0);
    assert!((quad[0].z - quad[3].z).abs() < 1e-9 && ((quad[0].z - quad[1].z).abs() - 28.6).abs() < 1e-9);
    // Its middle: half-way round (-16.5 degrees) and half-way up (z 17.3), where the material is tested.
    let middle = band_middle(quad, origin, direction);
    let half = 0.5 * gap;
    assert!(middle.distance(DVec3::new(3.75 * half.cos(), 3.75 * half.sin(), 17.3)) < 1e-9, "{middle:?}");
    // Not across the material (an edge on the rim), wider than the patch's reach, of two patches, or of a plane:
    // no band.
    let rim = [edges[0].clone(), LooseEdge { open: false, ..edges[1].clone() }];
    assert!(ruling_gaps(&rim).is_empty());
    let far = [ruling(2, 3.75, 0.0, (3.0, 31.6), -1.0), ruling(2, 3.75, -2.5, (31.6, 3.0), 1.0)];
    assert!(ruling_gaps(&far).is_empty(), "3.75 x 2.5 = 9.4 past the reach of 9");
    let two = [edges[0].clone(), LooseEdge { patch: 3, ..edges[1].clone() }];
    assert!(ruling_gaps(&two).is_empty());
    let freeform = edges.clone().map(|e| LooseEdge { freeform: true, ..e });
    assert!(ruling_gaps(&freeform).is_empty());
    let flat = [loose(0, 2.0, 50.0, 1.0, (0.0, 60.0), DVec3::X), loose(0, 2.0, 52.0, 1.0, (60.0, 0.0), -DVec3::X)];
    assert!(ruling_gaps(&flat).is_empty());
}

#[test]
fn a_step_from_a_rib_to_a_boss_beside_it_ramps_onto_the_boss_cylinder() {
    // A boss's mid-cylinder (r 2.5 about the z axis, t 2) stops at 90 degrees where a rib (t 1.8, mid-plane
    // y = 3) cuts its outside; the rib ends over the axis. The two edges face each other 0.5 apart: a step.
    let mut boss = ruling(0, 2.5, FRAC_PI_2, (0.0, 20.0), -1.0);
    boss.thickness = 2.0;
    boss.face = [DVec3::new(-2.5, 0.0, 10.0), -DVec3::X];
    let rib_end = (0..5).map(|k| DVec3::new(0.0, 3.0, 20.0 * k as f64 / 4.0)).collect();
    let rib = open_edge(1, 1.8, rib_end, DVec3::Y, -DVec3::X);
    let bridges = step_bridges(&[boss.clone(), rib.clone()], COPLANAR);
    assert_eq!(bridges.len(), 1, "{bridges:?}");
    let StepBridge { owner, quad, .. } = &bridges[0];
    assert_eq!(*owner, 1, "the thinner rib owns the ramp");
    // The ramp runs 0.5 x 1.8 = 0.9 round the cylinder from its edge: onto it, not off along its tangent.
    let turned = FRAC_PI_2 + 0.9 / 2.5;
    for far in [quad[1], quad[2]] {
        assert!(far.truncate().distance(2.5 * DVec2::new(turned.cos(), turned.sin())) < 1e-9, "{quad:?}");
    }
    // The face's normal given for its other side: the same cylinder.
    let flipped = LooseEdge { face: [DVec3::new(-2.5, 0.0, 10.0), DVec3::X], ..boss.clone() };
    assert_eq!(step_bridges(&[flipped, rib.clone()], COPLANAR), bridges);
    // A face that is neither flat nor a cylinder about the edge (a cone's normal leans along it): upright.
    let cone = LooseEdge { face: [DVec3::new(-2.5, 0.0, 10.0), DVec3::new(-0.8, 0.0, 0.6)], ..boss };
    let upright = step_bridges(&[cone, rib], COPLANAR);
    assert_eq!(upright.len(), 1, "{upright:?}");
    let on = |p: DVec3, y: f64| p.truncate().distance(DVec2::new(0.0, y)) < 1e-9;
    let quad = upright[0].quad;
    assert!(quad.iter().all(|&p| on(p, 2.5) || on(p, 3.0)), "between the two edges: {quad:?}");
}

/// A straight open edge of patch `patch` from `from` to `to` (5 samples), facing +z.
fn line(patch: usize, thickness: f64, from: DVec3, to: DVec3, outward: DVec3) -> LooseEdge {
    let points = (0..5).map(|k| from + (to - from) * k as f64 / 4.0).collect();
    open_edge(patch, thickness, points, DVec3::Z, outward)
}

/// `quad` is `expected`, or `expected` run the other way round from its first corner.
fn assert_same_quad(quad: &[DVec3; 4], expected: [DVec3; 4]) {
    let same = |p: DVec3, q: DVec3| p.distance(q) < 1e-9;
    let flipped = [expected[0], expected[3], expected[2], expected[1]];
    assert!(
        quad.iter().zip(expected).all(|(&p, q)| same(p, q)) || quad.iter().zip(flipped).all(|(&p, q)| same(p, q)),
        "{quad:?}"
    );
}

#[test]
fn ramps_meeting_at_a_pockets_convex_corner_get_the_notch_between_their_feet_filled() {
    // A pocket in a plate's underside: its wall (t=1, patch 1) at z=1.5 over x, y >= 20, the plate's (t=2,
    // patch 0) at z=1 round it; the two sides through the corner (20, 20) are ramps into the plate.
    let (v, z_thin, z_thick) = (DVec3::new(20.0, 20.0, 0.0), 1.5, 1.0);
    let at = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let edges = [
        line(1, 1.0, at(20.0, 20.0, z_thin), at(20.0, 40.0, z_thin), -DVec3::X),
        line(1, 1.0, at(20.0, 20.0, z_thin), at(30.0, 20.0, z_thin), -DVec3::Y),
        line(0, 2.0, at(20.0, 20.0, z_thick), at(20.0, 40.0, z_thick), DVec3::X),
        line(0, 2.0, at(20.0, 20.0, z_thick), at(30.0, 20.0, z_thick), DVec3::Y),
    ];
    let bridges = step_bridges(&edges, COPLANAR);
    assert_eq!(bridges.len(), 2, "{bridges:?}");
    let corners = bridge_corners(&bridges, &edges, 1e-9);
    assert_eq!(corners.len(), 1, "{corners:?}");
    let (owner, quad, normal) = corners[0];
    assert_eq!(edges[owner].patch, 1, "the pocket's wall owns the corner, as its ramps");
    assert_eq!(normal, DVec3::Z);
    // v, the ramps' feet half the thin wall (0.5) out into the plate, and where their lines meet.
    let expected = [v + DVec3::Z * z_thin, at(19.5, 20.0, z_thick), at(19.5, 19.5, z_thick), at(20.0, 19.5, z_thick)];
    assert_same_quad(&quad, expected);
}

#[test]
fn bridges_meeting_at_a_sloped_pads_corner_get_the_notch_out_to_the_thinner_patchs_corner_filled() {
    // A pad with 45-degree sides on a plate: the pad's patch (t=4, patch 1) at z=2 over x, y >= 97.5, the plate's
    // (t=1.5, patch 0) at z=0.75 round its footprint x, y >= 95. The bridges across the two sides through the
    // corner meet at the pad's corner; the plate's edges run on 2.5 past them to the footprint's corner.
    let at = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let edges = [
        line(0, 1.5, at(95.0, 45.0, 0.75), at(95.0, 95.0, 0.75), DVec3::X),
        line(0, 1.5, at(95.0, 45.0, 0.75), at(145.0, 45.0, 0.75), DVec3::Y),
        line(1, 4.0, at(97.5, 47.5, 2.0), at(97.5, 92.5, 2.0), -DVec3::X),
        line(1, 4.0, at(97.5, 47.5, 2.0), at(142.5, 47.5, 2.0), -DVec3::Y),
    ];
    let bridges = step_bridges(&edges, COPLANAR);
    assert_eq!(bridges.len(), 2, "{bridges:?}");
    let corners = bridge_corners(&bridges, &edges, 1e-9);
    assert_eq!(corners.len(), 1, "{corners:?}");
    let (owner, quad, _) = corners[0];
    assert_eq!(edges[owner].patch, 1, "the pad, whose bridge sides end at its corner, owns the fill");
    let expected = [at(97.5, 47.5, 2.0), at(95.0, 47.5, 0.75), at(95.0, 45.0, 0.75), at(97.5, 45.0, 0.75)];
    assert_same_quad(&quad, expected);
}

#[test]
fn ramps_meeting_at_a_pockets_reflex_corner_overlap_and_get_no_fill() {
    // The inner corner (56, 26) of an L-shaped pocket: the pocket lies at x < 56 and y < 26 of it; the ramps'
    // feet lines cross at (56.5, 26.5), behind both their ends.
    let at = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let edges = [
        line(1, 1.0, at(56.0, 26.0, 1.5), at(56.0, 40.0, 1.5), DVec3::X),
        line(1, 1.0, at(56.0, 26.0, 1.5), at(70.0, 26.0, 1.5), DVec3::Y),
        line(0, 2.0, at(56.0, 26.0, 1.0), at(56.0, 40.0, 1.0), -DVec3::X),
        line(0, 2.0, at(56.0, 26.0, 1.0), at(70.0, 26.0, 1.0), -DVec3::Y),
    ];
    let bridges = step_bridges(&edges, COPLANAR);
    assert_eq!(bridges.len(), 2, "{bridges:?}");
    assert!(bridge_corners(&bridges, &edges, 1e-9).is_empty());
}

/// Samples of a wavy curve in z = `z`, x from 0 to 20 (y = sin x, not a line or an arc), in the given direction,
/// with outward directions square to it in the plane, on the side `side` (+1: left of the way it runs).
fn wavy(patch: usize, thickness: f64, z: f64, (x0, x1): (f64, f64), side: f64) -> LooseEdge {
    let at = |k: usize| x0 + (x1 - x0) * k as f64 / 40.0;
    let points: Vec<DVec3> = (0..=40).map(|k| DVec3::new(at(k), at(k).sin(), z)).collect();
    let outwards: Vec<DVec3> = (0..=40)
        .map(|k| {
            let tangent = DVec3::new(1.0, at(k).cos(), 0.0).normalize() * (x1 - x0).signum();
            DVec3::Z.cross(tangent) * side
        })
        .collect();
    LooseEdge { outwards: outwards.clone(), ..open_edge(patch, thickness, points, DVec3::Z, outwards[20]) }
}

#[test]
fn two_levels_of_one_wavy_outline_meet_through_a_ramp_that_follows_it() {
    // A t=1 pocket's patch at z=1.5 (its material on the wave's left, outward to its right) and the plate's t=2
    // patch at z=1 beyond the wave (outward to the pocket's side), the same curve, one wall.
    let thin = LooseEdge { wall: (1, 0), ..wavy(0, 1.0, 1.5, (0.0, 20.0), -1.0) };
    let thick = LooseEdge { wall: (1, 0), open: false, ..wavy(1, 2.0, 1.0, (20.0, 0.0), -1.0) };
    assert!(step_bridges(&[thin.clone(), thick.clone()], COPLANAR).is_empty(), "neither a line nor an arc");
    let steps = swept_steps(&[thin.clone(), thick.clone()], &[false, false]);
    assert_eq!(steps.len(), 1, "{steps:?}");
    let SweptStep { owner, other, along, run } = steps[0];
    assert_eq!((owner, other), (0, 1), "the thinner level owns the ramp");
    assert!(along.distance(DVec3::new(0.0, 0.0, -0.5)) < 1e-9, "{along:?}");
    assert!((run - RAMP_RUN * 1.0).abs() < 1e-12);
    // Only part of the thick edge: an upright band from the shorter edge.
    let part = LooseEdge { wall: (1, 0), ..wavy(0, 1.0, 1.5, (0.0, 10.0), -1.0) };
    let steps = swept_steps(&[part, thick.clone()], &[false, false]);
    assert_eq!(steps.len(), 1, "{steps:?}");
    assert_eq!((steps[0].owner, steps[0].run), (0, 0.0));
    // Not facing (both patches on one side of the outline), another curve, a bridged edge: no step.
    let same_side = LooseEdge { wall: (1, 0), ..wavy(0, 1.0, 1.5, (0.0, 20.0), 1.0) };
    assert!(swept_steps(&[same_side, thick.clone()], &[false, false]).is_empty());
    let mut shifted = thin.clone();
    shifted.points.iter_mut().for_each(|p| p.y += 0.5);
    assert!(swept_steps(&[shifted, thick.clone()], &[false, false]).is_empty());
    assert!(swept_steps(&[thin.clone(), thick.clone()], &[false, true]).is_empty());
    // Levels of other walls with one rim edge: not a step.
    let other_wall = LooseEdge { wall: (1, 5), ..thick };
    assert!(swept_steps(&[thin, other_wall], &[false, false]).is_empty());
}
