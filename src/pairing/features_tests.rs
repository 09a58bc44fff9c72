use super::*;
use crate::model::face_graph::Edge;
use crate::pairing::Side;
use crate::synthetic;

/// A plate skin (0) with one inner loop of two edges onto faces 1 and 2, and an opposite skin (3) with
/// one inner loop onto the same faces when `through`.
fn plate_with(inner: [Surface; 2], convexity: Convexity, through: bool) -> (FaceGraph, Vec<FaceRole>) {
    let skin = |z: f64, n: DVec3| synthetic::rect(DVec3::new(0.0, 0.0, z), DVec3::X * 100.0, DVec3::Y * 60.0, n);
    let small = |s: Surface| {
        let mut f = synthetic::rect(DVec3::new(20.0, 20.0, 0.0), DVec3::X * 6.0, DVec3::Z * 3.0, DVec3::Y);
        f.surface = s;
        f
    };
    let [s1, s2] = inner;
    let mut g = synthetic::graph(vec![skin(3.0, DVec3::Z), small(s1), small(s2), skin(0.0, -DVec3::Z)], &[]);
    let edge = |id: usize, faces: Vec<usize>, convexity| Edge {
        id,
        vertices: [0, 0],
        faces,
        convexity,
        angle: 0.0,
        length: 10.0,
        curve: "circle".into(),
        midpoint: DVec3::ZERO,
    };
    g.edges = vec![
        edge(0, vec![0, 1], convexity),
        edge(1, vec![0, 2], convexity),
        edge(2, vec![1, 3], convexity),
        edge(3, vec![2, 3], convexity),
        edge(4, vec![1, 2], Convexity::Smooth),
        edge(5, vec![1, 2], Convexity::Smooth),
    ];
    g.faces[0].loops = vec![vec![], vec![0, 1]];
    g.faces[1].loops = vec![if through { vec![0, 4, 2, 5] } else { vec![0, 2, 3] }];
    g.faces[2].loops = vec![if through { vec![1, 5, 3, 4] } else { vec![1, 3, 2] }];
    g.faces[3].loops = if through { vec![vec![], vec![2, 3]] } else { vec![vec![]] };
    if !through {
        g.edges.truncate(2);
        g.edges.extend([edge(2, vec![1, 2], Convexity::Smooth), edge(3, vec![1, 2], Convexity::Smooth)]);
    }
    let pair = |side| FaceRole::Pair { group: 0, side };
    let roles = vec![pair(Side::A), FaceRole::Thickness { group: 0 }, FaceRole::Thickness { group: 0 }, pair(Side::B)];
    (g, roles)
}

/// The thickness of each pair group: the plate's (group 0) is its skins' distance apart, 3.
const WALLS: &[f64] = &[3.0, 2.0, 2.0];

fn hole_half() -> Surface {
    Surface::Cylinder { origin: DVec3::new(23.0, 23.0, 0.0), axis: DVec3::Z, radius: 3.0, convex: false }
}

fn limits(keep_holes: bool) -> Limits {
    LimitArgs { keep_holes, ..LimitArgs::default() }.resolve(8.0)
}

#[test]
fn a_small_through_hole_is_one_feature_with_both_skin_loops_to_fill() {
    let (g, roles) = plate_with([hole_half(), hole_half()], Convexity::Convex, true);
    let found = recognise(&g, &roles, WALLS, &limits(false), 1e-3);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!((found[0].kind, found[0].faces.clone(), found[0].size), (FeatureKind::Hole, vec![1, 2], 6.0));
    assert_eq!(found[0].fill, vec![0, 1, 2, 3]);
    assert_eq!(pairable(4, &found), vec![true, false, false, true]);
}

#[test]
fn large_or_kept_holes_stay() {
    let (g, roles) = plate_with([hole_half(), hole_half()], Convexity::Convex, true);
    assert!(recognise(&g, &roles, WALLS, &limits(true), 1e-3).is_empty(), "--keep-holes");
    let tight = Limits { hole_max: 5.0, ..limits(false) };
    assert!(recognise(&g, &roles, WALLS, &tight, 1e-3).is_empty(), "6 mm over a 5 mm limit");
}

#[test]
fn a_bore_running_on_past_the_wall_is_a_boss_s_bore_not_a_hole() {
    // The through hole of the test above, its bore running on 3 past the plate's top (z 0..6, twice the plate's
    // thickness): the bore of a screw boss over a through hole, kept for the boss's tube. 2.9 past (z 0..5.9),
    // it is still the plate's hole (a low collar round it).
    for (past, hole) in [(3.0, false), (2.9, true)] {
        let (mut g, roles) = plate_with([hole_half(), hole_half()], Convexity::Convex, true);
        for face in &mut g.faces[1..3] {
            face.mesh.as_mut().unwrap().vertices.iter_mut().for_each(|v| v.z *= (3.0 + past) / 3.0);
            face.bbox.max.z = 3.0 + past;
        }
        let found = recognise(&g, &roles, WALLS, &limits(false), 1e-3);
        assert_eq!(found.len(), usize::from(hole), "{past} past: {found:?}");
    }
}

#[test]
fn a_protrusion_behind_a_concave_loop_is_a_boss() {
    let side = Surface::Cylinder { origin: DVec3::new(23.0, 23.0, 0.0), axis: DVec3::Z, radius: 3.0, convex: true };
    let (g, roles) =
        plate_with([side, Surface::Plane { origin: DVec3::ZERO, normal: DVec3::Z }], Convexity::Concave, false);
    let found = recognise(&g, &roles, WALLS, &limits(false), 1e-3);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!((found[0].kind, found[0].faces.clone()), (FeatureKind::Boss, vec![1, 2]));
    assert_eq!(found[0].fill, vec![0, 1]);
    let small = Limits { boss_max: 6.5, ..limits(false) };
    assert!(recognise(&g, &roles, WALLS, &small, 1e-3).is_empty(), "its box is 6 x 0 x 3: diagonal 6.7");
}

#[test]
fn a_protrusion_holding_a_wall_and_standing_clear_of_its_skin_is_no_boss() {
    // A hollow screw boss: its outside and its bore pair as a tube's wall.
    let outside = Surface::Cylinder { origin: DVec3::new(23.0, 23.0, 0.0), axis: DVec3::Z, radius: 3.0, convex: true };
    let bore = Surface::Cylinder { origin: DVec3::new(23.0, 23.0, 0.0), axis: DVec3::Z, radius: 1.0, convex: false };
    let (mut g, mut roles) = plate_with([outside, bore], Convexity::Concave, false);
    for face in &mut g.faces[1..3] {
        // Standing 3 out of the plate's top (z = 3).
        face.mesh.as_mut().unwrap().vertices.iter_mut().for_each(|v| v.z += 3.0);
        (face.bbox.min.z, face.bbox.max.z) = (face.bbox.min.z + 3.0, face.bbox.max.z + 3.0);
    }
    assert_eq!(recognise(&g, &roles, WALLS, &limits(false), 1e-3).len(), 1, "unpaired sides: a solid boss");
    roles[1] = FaceRole::Pair { group: 1, side: Side::A };
    roles[2] = FaceRole::Pair { group: 1, side: Side::B };
    assert!(recognise(&g, &roles, WALLS, &limits(false), 1e-3).is_empty(), "a tube's wall stands on the plate");
    let thicker_plate = [3.5, 2.0];
    assert_eq!(recognise(&g, &roles, &thicker_plate, &limits(false), 1e-3).len(), 1, "3 high on a 3.5 plate: a collar");
    roles[2] = FaceRole::Pair { group: 2, side: Side::B };
    assert_eq!(recognise(&g, &roles, WALLS, &limits(false), 1e-3).len(), 1, "skins of two walls are no wall");
}

/// A plate rim: top skin 0, bottom skin 1 (one wall), rim face 2, and a plane face 3 between the top
/// skin and the rim face along two 60 mm edges turning `turn` degrees (convex), 2 mm wide.
fn rim_with_bevel(turn: f64, onto_bottom: bool) -> (FaceGraph, Vec<FaceRole>) {
    let rect = |o: DVec3, u: DVec3, v: DVec3, n: DVec3| synthetic::rect(o, u, v, n);
    let faces = vec![
        rect(DVec3::ZERO, DVec3::X * 100.0, DVec3::Y * 60.0, DVec3::Z),
        rect(DVec3::ZERO, DVec3::X * 100.0, DVec3::Y * 60.0, -DVec3::Z),
        rect(DVec3::ZERO, DVec3::Z * 2.0, DVec3::Y * 60.0, -DVec3::X),
        rect(DVec3::ZERO, DVec3::X * 2.0, DVec3::Y * 60.0, DVec3::Z),
    ];
    let mut g = synthetic::graph(faces, &[]);
    let edge = |id: usize, faces: Vec<usize>, length: f64| Edge {
        id,
        vertices: [0, 0],
        faces,
        convexity: Convexity::Convex,
        angle: turn.to_radians(),
        length,
        curve: "line".into(),
        midpoint: DVec3::ZERO,
    };
    let far = if onto_bottom { 1 } else { 2 };
    g.edges = vec![edge(0, vec![3, 0], 60.0), edge(1, vec![3, far], 60.0), edge(2, vec![3, 2], 2.0)];
    g.faces[3].loops = vec![vec![0, 2, 1, 2]];
    g.faces[3].area = 120.0;
    let roles = vec![
        FaceRole::Pair { group: 0, side: Side::A },
        FaceRole::Pair { group: 0, side: Side::B },
        FaceRole::Thickness { group: 0 },
        FaceRole::Thickness { group: 0 },
    ];
    (g, roles)
}

#[test]
fn a_narrow_bevel_between_a_skin_and_a_rim_is_a_chamfer() {
    let (g, roles) = rim_with_bevel(45.0, false);
    let found = recognise(&g, &roles, WALLS, &limits(false), 1e-3);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!((found[0].kind, found[0].faces.clone(), found[0].size), (FeatureKind::Chamfer, vec![3], 2.0));
    let narrow = Limits { fillet_max: 1.9, ..limits(false) };
    assert!(recognise(&g, &roles, WALLS, &narrow, 1e-3).is_empty(), "2 mm wide over a 1.9 mm limit");
}

#[test]
fn square_rims_tangent_facets_and_bevelled_wall_ends_are_no_chamfers() {
    for turn in [90.0, 5.0] {
        let (g, roles) = rim_with_bevel(turn, false);
        assert!(recognise(&g, &roles, WALLS, &limits(false), 1e-3).is_empty(), "turning {turn} degrees");
    }
    // Between the two skins of one wall the bevel is the wall's rim.
    let (g, roles) = rim_with_bevel(45.0, true);
    assert!(recognise(&g, &roles, WALLS, &limits(false), 1e-3).is_empty());
}

#[test]
fn a_mixed_loop_is_no_feature() {
    let (mut g, roles) = plate_with([hole_half(), hole_half()], Convexity::Convex, true);
    // One edge of each skin loop concave: neither a hole nor a boss from either side.
    g.edges[1].convexity = Convexity::Concave;
    g.edges[3].convexity = Convexity::Concave;
    assert!(recognise(&g, &roles, WALLS, &limits(false), 1e-3).is_empty());
}
