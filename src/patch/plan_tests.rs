use super::*;
use crate::model::tolerance::Tolerances;
use crate::pairing::detect;
use crate::synthetic;
use std::f64::consts::FRAC_PI_2;

#[test]
fn bisector_of_a_drafted_wall() {
    // x = 0 facing -x, and a face tilted by 2 degrees facing +x, 3 apart at the origin.
    let a = 2.0_f64.to_radians();
    let nb = DVec3::new(a.cos(), 0.0, a.sin());
    let (o, n) = bisector(DVec3::ZERO, -DVec3::X, DVec3::X * 3.0, nb);
    // Equidistant from both planes, and near the midpoint of the origins.
    let (da, db) = (-(-DVec3::X).dot(o), -nb.dot(o - DVec3::X * 3.0));
    assert!((da - db).abs() < 1e-12 && da > 0.0, "{da} {db}");
    assert!(o.distance(DVec3::X * 1.5) < 1e-3, "{o}");
    let expected = (-DVec3::X - nb).normalize();
    assert!(n.distance(expected) < 1e-12);
}

#[test]
fn plate_offsets_its_larger_face_by_half_the_thickness() {
    let g = synthetic::cuboid(DVec3::ZERO, DVec3::new(100.0, 60.0, 2.0));
    let pairing = detect(&g, &Tolerances::new(120.0, 3.0, 0.05), &[true; 6]);
    let (plans, steps) = plan_patches(&g, &pairing, Position::Mid, &[]);
    assert!(steps.is_empty());
    assert_eq!(plans.len(), 1);
    assert_eq!(plans[0].faces, vec![4]);
    assert_eq!(plans[0].placement, Placement::Offset(-1.0));
}

#[test]
fn a_skin_position_keeps_the_thickness_and_says_where_the_middle_is() {
    let g = synthetic::cuboid(DVec3::ZERO, DVec3::new(100.0, 60.0, 2.0));
    let pairing = detect(&g, &Tolerances::new(120.0, 3.0, 0.05), &[true; 6]);
    let placed = |position| {
        let (plans, _) = plan_patches(&g, &pairing, position, &[]);
        (plans[0].placement.clone(), plans[0].to_mid, plans[0].thickness.mean)
    };
    assert_eq!(placed(Position::Mid), (Placement::Offset(-1.0), 0.0, 2.0));
    assert_eq!(placed(Position::Top), (Placement::Offset(0.0), -1.0, 2.0));
    assert_eq!(placed(Position::Bottom), (Placement::Offset(-2.0), 1.0, 2.0));
}

#[test]
fn a_draft_patch_on_a_skin_lies_on_that_face_plane() {
    // A wall 3 thick at its foot, one side drafted by 1 degree.
    let a = 1.0_f64.to_radians();
    let tilted = DVec3::new(a.cos(), 0.0, a.sin());
    let faces = vec![
        synthetic::rect(DVec3::ZERO, DVec3::Z * 20.0, DVec3::Y * 40.0, -DVec3::X),
        synthetic::rect(DVec3::X * 3.0, DVec3::Y * 40.0, DVec3::new(-a.sin(), 0.0, a.cos()) * 20.0, tilted),
    ];
    let g = synthetic::graph(faces, &[]);
    let pairing = detect(&g, &Tolerances::new(60.0, 4.0, 2.0_f64.to_radians()), &[true; 2]);
    let plane = |position| {
        let (plans, _) = plan_patches(&g, &pairing, position, &[]);
        let reference = plans[0].faces[0];
        match plans[0].placement {
            Placement::Plane { origin, normal } => (reference, DVec3::from(origin), DVec3::from(normal)),
            Placement::Offset(_) => panic!("a draft pair is projected"),
        }
    };
    let (reference, origin, normal) = plane(Position::Top);
    let Surface::Plane { origin: ro, normal: rn } = g.faces[reference].surface else { panic!() };
    assert!(normal.distance(rn) < 1e-12 && (origin - ro).dot(rn).abs() < 1e-12);
    let (_, origin, normal) = plane(Position::Bottom);
    let Surface::Plane { origin: po, normal: pn } = g.faces[1 - reference].surface else { panic!() };
    assert!(normal.distance(-pn) < 1e-12 && (origin - po).dot(pn).abs() < 1e-12);
}

/// A bottom at z=0 (x 0..40) under a floor at z=2 (x -30..25) and a recess-like top at z=3 (x 25..40); the
/// floor also lies over a lower bottom at z=-1 (x -35..0): neither side sits at one thickness.
fn two_levels_on_each_side() -> (FaceGraph, Pairing) {
    let faces = vec![
        synthetic::rect(DVec3::ZERO, DVec3::Y * 10.0, DVec3::X * 40.0, -DVec3::Z),
        synthetic::rect(DVec3::new(-35.0, 0.0, -1.0), DVec3::Y * 10.0, DVec3::X * 35.0, -DVec3::Z),
        synthetic::rect(DVec3::new(-30.0, 0.0, 2.0), DVec3::X * 55.0, DVec3::Y * 10.0, DVec3::Z),
        synthetic::rect(DVec3::new(25.0, 0.0, 3.0), DVec3::X * 15.0, DVec3::Y * 10.0, DVec3::Z),
    ];
    let g = synthetic::graph(faces, &[]);
    let pairing = detect(&g, &Tolerances::new(60.0, 4.0, 0.05), &[true; 4]);
    (g, pairing)
}

#[test]
fn a_tapered_freeform_wall_follows_its_mid_points() {
    // One freeform pair measured at several spreads: past TAPER_SPREAD of the mean its patch follows the
    // mid-points at mid-wall; on a skin, or tapering less, it is offset.
    let g = synthetic::cuboid(DVec3::ZERO, DVec3::new(100.0, 60.0, 2.0));
    let mut pairing = detect(&g, &Tolerances::new(120.0, 3.0, 0.05), &[true; 6]);
    pairing.groups[0].kind = PairKind::Freeform;
    pairing.pairs[0].kind = PairKind::Freeform;
    let mut mid_wall = |(min, max): (f64, f64), position: Position| {
        pairing.pairs[0].thickness = Thickness { mean: 2.0, min, max };
        let (plans, notes) = plan_patches(&g, &pairing, position, &[]);
        let noted = notes.iter().any(|n| matches!(n, PlanNote::ThicknessVaries { mid_wall: true, .. }));
        assert_eq!(noted, plans[0].mid_wall, "{notes:?}");
        plans[0].mid_wall
    };
    assert!(mid_wall((1.5, 2.5), Position::Mid));
    assert!(!mid_wall((1.5, 2.5), Position::Top));
    assert!(!mid_wall((1.75, 2.25), Position::Mid));
}

#[test]
fn a_tapered_wall_is_noted_as_varying_not_as_a_step() {
    // A plate whose one pair was measured 1.8 to 2.2 thick (a taper) is noted as varying; bottoms at two
    // heights under tops at two heights (neither side at one thickness) are a step between pairs.
    let g = synthetic::cuboid(DVec3::ZERO, DVec3::new(100.0, 60.0, 2.0));
    let mut pairing = detect(&g, &Tolerances::new(120.0, 3.0, 0.05), &[true; 6]);
    assert_eq!(pairing.pairs.len(), 1);
    pairing.pairs[0].thickness = Thickness { mean: 2.0, min: 1.8, max: 2.2 };
    let (_, notes) = plan_patches(&g, &pairing, Position::Mid, &[]);
    assert!(matches!(notes[..], [PlanNote::ThicknessVaries { .. }]), "{notes:?}");
    let (g, pairing) = two_levels_on_each_side();
    let (_, notes) = plan_patches(&g, &pairing, Position::Mid, &[]);
    assert!(!notes.is_empty() && notes.iter().all(|n| matches!(n, PlanNote::ThicknessStep { .. })), "{notes:?}");
}

#[test]
fn a_thickness_step_gives_one_patch_per_level() {
    // One bottom under two tops at heights 2 and 3: two patches from the bottom would be wrong, so the
    // tops (the reference side here, being larger) are offset each by its own half thickness.
    let faces = vec![
        synthetic::rect(DVec3::ZERO, DVec3::Y * 10.0, DVec3::X * 40.0, -DVec3::Z),
        synthetic::rect(DVec3::new(-5.0, 0.0, 2.0), DVec3::X * 25.0, DVec3::Y * 10.0, DVec3::Z),
        synthetic::rect(DVec3::new(20.0, 0.0, 3.0), DVec3::X * 25.0, DVec3::Y * 10.0, DVec3::Z),
    ];
    let g = synthetic::graph(faces, &[]);
    let pairing = detect(&g, &Tolerances::new(60.0, 4.0, 0.05), &[true; 3]);
    let (plans, _) = plan_patches(&g, &pairing, Position::Mid, &[]);
    let offsets: Vec<(Vec<FaceId>, Placement)> = plans.iter().map(|p| (p.faces.clone(), p.placement.clone())).collect();
    assert_eq!(offsets, vec![(vec![1], Placement::Offset(-1.0)), (vec![2], Placement::Offset(-1.5))]);
}

#[test]
fn a_face_over_two_levels_gives_a_patch_per_level_each_kept_off_the_other() {
    // A bottom at z=0 (x 0..40) under a floor at z=2 (x -30..25) and a recess-like top at z=3 (x 25..40); the
    // floor also lies over a lower bottom at z=-1 (x -35..0), so neither side sits at one thickness and
    // the bottoms, being larger, are the reference. One offset of the first bottom would be mid-way over
    // one level only: it gives a patch per level, clipped to that level's partner and off the other's.
    let (g, pairing) = two_levels_on_each_side();
    let (plans, _) = plan_patches(&g, &pairing, Position::Mid, &[]);
    type Seen = (Vec<FaceId>, Placement, Vec<Vec<FaceId>>, Vec<Vec<FaceId>>, bool);
    let got: Vec<Seen> = plans
        .iter()
        .map(|p| (p.faces.clone(), p.placement.clone(), p.partners.clone(), p.exclude.clone(), p.strict))
        .collect();
    assert_eq!(
        got,
        vec![
            // The level of most overlap keeps the clip's narrow pieces; the other keeps only its footprint.
            (vec![0], Placement::Offset(-1.0), vec![vec![2]], vec![vec![3]], false),
            (vec![0], Placement::Offset(-1.5), vec![vec![3]], vec![vec![2]], true),
            (vec![1], Placement::Offset(-1.5), vec![vec![2]], vec![vec![]], false),
        ]
    );
}

#[test]
fn a_step_under_the_larger_face_is_offset_from_the_other_side() {
    // A long bottom (larger) under two shorter tops at 2 and 3: the bottom spans the step, the tops do
    // not, so each top is offset by its own half thickness.
    let faces = vec![
        synthetic::rect(DVec3::ZERO, DVec3::Y * 10.0, DVec3::X * 60.0, -DVec3::Z),
        synthetic::rect(DVec3::new(0.0, 0.0, 2.0), DVec3::X * 25.0, DVec3::Y * 10.0, DVec3::Z),
        synthetic::rect(DVec3::new(30.0, 0.0, 3.0), DVec3::X * 25.0, DVec3::Y * 10.0, DVec3::Z),
    ];
    let g = synthetic::graph(faces, &[]);
    let pairing = detect(&g, &Tolerances::new(70.0, 4.0, 0.05), &[true; 3]);
    assert_eq!(pairing.groups[0].reference, crate::pairing::Side::A, "the bottom is larger");
    let (plans, steps) = plan_patches(&g, &pairing, Position::Mid, &[]);
    assert!(steps.is_empty());
    let offsets: Vec<f64> = plans
        .iter()
        .map(|p| match p.placement {
            Placement::Offset(d) => d,
            Placement::Plane { .. } => panic!("parallel pairs are offset"),
        })
        .collect();
    assert_eq!(plans.iter().map(|p| p.faces.clone()).collect::<Vec<_>>(), vec![vec![1], vec![2]]);
    assert!((offsets[0] + 1.0).abs() < 1e-12 && (offsets[1] + 1.5).abs() < 1e-12, "{offsets:?}");
}

#[test]
fn a_larger_face_mostly_beyond_its_partner_is_not_offset() {
    // A 100 x 10 bottom under a 20 x 10 top: offsetting the bottom would put 80% of the patch where no
    // wall is, so the top (fully covered) is offset instead; 40% coverage keeps the larger face.
    let faces = |w: f64| {
        vec![
            synthetic::rect(DVec3::ZERO, DVec3::Y * 10.0, DVec3::X * 100.0, -DVec3::Z),
            synthetic::rect(DVec3::new(10.0, 0.0, 2.0), DVec3::X * w, DVec3::Y * 10.0, DVec3::Z),
        ]
    };
    let tol = Tolerances::new(110.0, 3.0, 0.05);
    let g = synthetic::graph(faces(20.0), &[]);
    let (plans, notes) = plan_patches(&g, &detect(&g, &tol, &[true; 2]), Position::Mid, &[]);
    assert_eq!(plans[0].faces, vec![1]);
    assert!(notes.is_empty());
    let g = synthetic::graph(faces(60.0), &[]);
    let (plans, _) = plan_patches(&g, &detect(&g, &tol, &[true; 2]), Position::Mid, &[]);
    assert_eq!(plans[0].faces, vec![0]);
}

#[test]
fn a_freeform_face_in_a_draft_group_is_offset_not_projected() {
    // A floor: a plane (x 0..100) and a flat B-spline strip beside it (x 100..110), both facing down; over
    // them one roof plane tilted by 1.5 degree (x 0..109). The roof pairs with the plane as a draft pair
    // (the group's kind: most overlap) and with the strip as a freeform pair: the strip has no plane to
    // project onto the bisector of, so it is offset like any curved pair.
    let a = 1.5_f64.to_radians();
    let up = DVec3::new(-a.sin(), 0.0, a.cos());
    let faces = vec![
        synthetic::rect(DVec3::ZERO, DVec3::Y * 40.0, DVec3::X * 100.0, -DVec3::Z),
        synthetic::face(Surface::Bspline, 20, |u, v| (DVec3::new(100.0 + 10.0 * u, 40.0 * v, 0.0), -DVec3::Z)),
        synthetic::rect(DVec3::Z * 2.0, DVec3::new(a.cos(), 0.0, a.sin()) * 109.0, DVec3::Y * 40.0, up),
    ];
    let g = synthetic::graph(faces, &[]);
    let pairing = detect(&g, &Tolerances::new(120.0, 6.0, 2.0_f64.to_radians()), &[true; 3]);
    assert_eq!(pairing.groups.len(), 1, "{:?}", pairing.pairs);
    assert_eq!(pairing.groups[0].kind, PairKind::Draft);
    let (plans, _) = plan_patches(&g, &pairing, Position::Mid, &[]);
    let of = |f: FaceId| plans.iter().find(|p| p.faces.contains(&f)).expect("a patch per floor face");
    assert!(matches!(of(0).placement, Placement::Plane { .. }), "{:?}", of(0).placement);
    assert!(matches!(of(1).placement, Placement::Offset(_)), "{:?}", of(1).placement);
    assert_eq!(of(1).kind, PairKind::Freeform);
}

#[test]
fn a_bend_drawn_on_centres_apart_follows_its_mid_wall_and_a_coaxial_one_does_not() {
    // Quarter cylinders on vertical axes: the outer arc R 5 about the origin (face 0), an inner arc R 3.6 about
    // (0.1, 0.1) (face 1), a coaxial inner arc R 3.5 (face 2) and a flat (face 3).
    let faces = vec![
        synthetic::cylinder(DVec3::ZERO, 5.0, (0.0, FRAC_PI_2), 5.0, true),
        synthetic::cylinder(DVec3::new(0.1, 0.1, 0.0), 3.6, (0.0, FRAC_PI_2), 5.0, false),
        synthetic::cylinder(DVec3::ZERO, 3.5, (0.0, FRAC_PI_2), 5.0, false),
        synthetic::rect(DVec3::new(3.5, 0.0, 0.0), DVec3::Y, DVec3::Z, -DVec3::X),
    ];
    let g = synthetic::graph(faces, &[]);
    let pair = |other: usize| Pair {
        faces: [0, other],
        kind: PairKind::Freeform,
        thickness: Thickness { mean: 1.5, min: 1.4, max: 1.6 },
        overlap_area: 10.0,
    };
    let (apart, coaxial, flat) = (pair(1), pair(2), pair(3));
    fn share<'a>(pairs: &[&'a Pair]) -> Share<'a> {
        Share { face: 0, pairs: pairs.to_vec(), exclude: Vec::new(), minor: false }
    }
    assert!(skins_apart(&g, &share(&[&apart])));
    assert!(!skins_apart(&g, &share(&[&coaxial])), "an offset already lies mid-way");
    assert!(!skins_apart(&g, &share(&[&flat])));
    assert!(!skins_apart(&g, &share(&[&apart, &coaxial])), "two partner axes: no one mean cylinder");
}
