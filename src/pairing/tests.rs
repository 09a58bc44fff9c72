//! Pairing on hand-made face graphs: every test and curved kind, with near misses on each side of a limit.

use glam::DVec3;

use super::*;
use crate::model::face_graph::{Convexity, Face};
use crate::synthetic::{self, cone, cylinder, rect, sphere, torus};

const T_MAX: f64 = 3.0;

fn tol() -> Tolerances {
    Tolerances::new(200.0, T_MAX, 3.0_f64.to_radians())
}

fn run(faces: Vec<Face>) -> Pairing {
    let g = synthetic::graph(faces, &[]);
    detect(&g, &tol(), &vec![true; g.faces.len()])
}

fn pair_of(faces: Vec<Face>) -> Result<Pair, Rejection> {
    let g = synthetic::graph(faces, &[]);
    criteria::test_pair(&g, 0, 1, &tol())
}

/// The 60 x 40 top (+z) at height `z` over the bottom (-z) at 0.
fn slab_faces(z: f64) -> Vec<Face> {
    vec![
        rect(DVec3::ZERO, DVec3::Y * 40.0, DVec3::X * 60.0, -DVec3::Z),
        rect(DVec3::Z * z, DVec3::X * 60.0, DVec3::Y * 40.0, DVec3::Z),
    ]
}

/// An 8 mm wide top strip tilted about the x axis by `degrees` (its normal turns toward -y), over the bottom.
fn tilted_top(degrees: f64) -> Vec<Face> {
    let a = degrees.to_radians();
    let dv = DVec3::new(0.0, a.cos(), a.sin()) * 8.0;
    let normal = DVec3::X.cross(dv).normalize();
    vec![
        rect(DVec3::ZERO, DVec3::Y * 40.0, DVec3::X * 60.0, -DVec3::Z),
        rect(DVec3::Z * 2.0, DVec3::X * 60.0, dv, normal),
    ]
}

#[test]
fn parallel_pair_with_its_thickness() {
    let p = pair_of(slab_faces(2.0)).unwrap();
    assert_eq!(p.kind, PairKind::Parallel);
    assert!((p.thickness.mean - 2.0).abs() < 1e-9);
    assert!((p.overlap_area - 2400.0).abs() < 1e-6);
}

#[test]
fn parallel_tolerance_edge() {
    assert_eq!(pair_of(tilted_top(0.45)).unwrap().kind, PairKind::Parallel);
    assert_eq!(pair_of(tilted_top(0.55)).unwrap().kind, PairKind::Draft);
}

#[test]
fn draft_pair_within_twice_the_draft_limit_only() {
    // draft_max 3 degrees: normals may differ by up to 6 degrees from opposite.
    let inside = pair_of(tilted_top(5.9)).unwrap();
    assert_eq!(inside.kind, PairKind::Draft);
    let outside = pair_of(tilted_top(6.1)).unwrap_err();
    assert!(matches!(outside, Rejection::Angle { degrees, .. } if (degrees - 6.1).abs() < 1e-6), "{outside:?}");
}

#[test]
fn draft_thickness_is_the_mean_over_the_face_with_its_range() {
    let p = pair_of(tilted_top(2.0)).unwrap();
    // The strip rises from z=2 at y=0 to 2 + 8 sin(2 deg) = 2.279 at its far edge: the wall's mean is about
    // 2.14 and its range 2..2.28 (measured across the bisector, so a hair less).
    let far = 2.0 + 8.0 * 2.0_f64.to_radians().sin();
    assert!((p.thickness.mean - 0.5 * (2.0 + far)).abs() < 0.01, "{:?}", p.thickness);
    assert!((p.thickness.min - 2.0).abs() < 0.01 && (p.thickness.max - far).abs() < 0.01, "{:?}", p.thickness);
}

#[test]
fn distance_limit() {
    assert!(pair_of(slab_faces(2.99)).is_ok());
    let err = pair_of(slab_faces(3.01)).unwrap_err();
    assert!(matches!(err, Rejection::Distance { distance, .. } if (distance - 3.01).abs() < 1e-9), "{err:?}");
}

#[test]
fn a_wall_as_thick_as_t_max_pairs_whatever_the_rounding() {
    // t_max 3 on a part of diagonal 200: its length tolerance is 2e-4. A wall measured a rounding over 3 is 3.
    assert!(pair_of(slab_faces(3.0 + 1e-8)).is_ok());
    assert!(pair_of(slab_faces(3.0 + 1e-4)).is_ok());
    assert!(pair_of(slab_faces(3.0 + 1e-3)).is_err());
}

/// A `length` x `width` top (+z) at height `z` over its bottom (-z) at 0, their edges `length` and `width` round.
fn band(length: f64, width: f64, z: f64) -> crate::model::face_graph::FaceGraph {
    let faces = vec![
        rect(DVec3::ZERO, DVec3::Y * width, DVec3::X * length, -DVec3::Z),
        rect(DVec3::Z * z, DVec3::X * length, DVec3::Y * width, DVec3::Z),
    ];
    graph_with_lengths(faces, &[(0, 1, Convexity::Convex, 2.0 * (length + width))])
}

#[test]
fn a_wall_thicker_than_t_max_pairs_when_thin_for_its_extent() {
    // Over t_max 3, when the solid's safety bound allows it, a wall is thin for its extent: at most a third of
    // its length (a square slab that thick is as thin as a thin-walled solid may be) and no more than its
    // width. A long low band (a tray's thick rim, 60 x 5): up to 5 thick.
    let bounded = Tolerances { t_bound: 10.0, ..tol() };
    let p = criteria::test_pair(&band(60.0, 5.0, 4.5), 0, 1, &bounded).unwrap();
    assert!((p.thickness.mean - 4.5).abs() < 1e-9);
    let err = criteria::test_pair(&band(60.0, 5.0, 5.1), 0, 1, &bounded).unwrap_err();
    assert!(matches!(err, Rejection::Distance { limit, .. } if (limit - 5.0).abs() < 1e-9), "{err:?}");
    // A square 20 x 20 (a lug's sides): a third of its side.
    assert!(criteria::test_pair(&band(20.0, 20.0, 6.6), 0, 1, &bounded).is_ok());
    let err = criteria::test_pair(&band(20.0, 20.0, 6.7), 0, 1, &bounded).unwrap_err();
    assert!(matches!(err, Rejection::Distance { limit, .. } if (limit - 20.0 / 3.0).abs() < 1e-9), "{err:?}");
    // A short thick band (a rounded corner of a thicker lug, 9 x 6): 3 thick, where a fifth would stop at 1.8.
    let small = Tolerances { t_max: 1.2, t_bound: 10.0, ..tol() };
    let p = criteria::test_pair(&band(9.0, 6.0, 2.9), 0, 1, &small);
    assert!(p.is_ok(), "{p:?}");
    assert!(criteria::test_pair(&band(9.0, 6.0, 3.1), 0, 1, &small).is_err());
    // At t_max when t_max is the user's hard limit, and the bound holds whatever the extent.
    assert!(criteria::test_pair(&band(60.0, 40.0, 3.9), 0, 1, &tol()).is_err());
    assert!(criteria::test_pair(&band(60.0, 40.0, 9.9), 0, 1, &bounded).is_ok());
    assert!(criteria::test_pair(&band(60.0, 40.0, 10.1), 0, 1, &bounded).is_err());
}

#[test]
fn two_sheets_lying_one_on_the_other_are_not_one_wall() {
    // Two 2 mm sheets 0.1 apart (a hem): each pairs on its own; their outer skins, 4.1 apart and over t_max,
    // have the gap's faces between them.
    let faces = vec![
        rect(DVec3::ZERO, DVec3::Y * 40.0, DVec3::X * 60.0, -DVec3::Z),
        rect(DVec3::Z * 4.1, DVec3::X * 60.0, DVec3::Y * 40.0, DVec3::Z),
        rect(DVec3::Z * 2.0, DVec3::X * 60.0, DVec3::Y * 40.0, DVec3::Z),
        rect(DVec3::Z * 2.1, DVec3::Y * 40.0, DVec3::X * 60.0, -DVec3::Z),
    ];
    let g = graph_with_lengths(faces, &[(0, 1, Convexity::Convex, 200.0)]);
    let bounded = Tolerances { t_bound: 10.0, ..tol() };
    let err = criteria::test_pair(&g, 0, 1, &bounded).unwrap_err();
    assert!(matches!(err, Rejection::Stacked { between, .. } if (between - 2.0).abs() < 1e-6), "{err:?}");
    assert!(criteria::test_pair(&g, 0, 2, &bounded).is_ok());
    // Without the second sheet the skins 4.1 apart are one wall.
    let g = graph_with_lengths(g.faces[..2].to_vec(), &[(0, 1, Convexity::Convex, 200.0)]);
    assert!(criteria::test_pair(&g, 0, 1, &bounded).is_ok());
}

#[test]
fn faces_with_air_between_them_do_not_pair() {
    // Two walls of a slot: each outward normal points at the other face.
    let faces = vec![
        rect(DVec3::ZERO, DVec3::X * 60.0, DVec3::Y * 40.0, DVec3::Z),
        rect(DVec3::Z * 2.0, DVec3::Y * 40.0, DVec3::X * 60.0, -DVec3::Z),
    ];
    assert_eq!(pair_of(faces).unwrap_err(), Rejection::NotFacing);
}

#[test]
fn side_by_side_faces_fail_the_overlap_test() {
    // Paper Fig. 9(c): a step; the lower top and the upper bottom are parallel, facing and close, but beside
    // each other.
    let faces = vec![
        rect(DVec3::ZERO, DVec3::Y * 40.0, DVec3::X * 30.0, -DVec3::Z),
        rect(DVec3::new(31.0, 0.0, 1.0), DVec3::X * 30.0, DVec3::Y * 40.0, DVec3::Z),
    ];
    assert!(matches!(pair_of(faces).unwrap_err(), Rejection::Overlap { share, .. } if share == 0.0));
    // A sliver of overlap (2 of 30 mm) is still too little.
    let faces = vec![
        rect(DVec3::ZERO, DVec3::Y * 40.0, DVec3::X * 30.0, -DVec3::Z),
        rect(DVec3::new(28.0, 0.0, 1.0), DVec3::X * 30.0, DVec3::Y * 40.0, DVec3::Z),
    ];
    assert!(matches!(pair_of(faces).unwrap_err(), Rejection::Overlap { share, .. } if share > 0.0 && share < 0.1));
}

#[test]
fn one_face_pairs_with_twelve() {
    // A 130 x 10 bottom under twelve 8 x 10 top pieces separated by rib roots.
    let mut faces = vec![rect(DVec3::ZERO, DVec3::Y * 10.0, DVec3::X * 130.0, -DVec3::Z)];
    for k in 0..12 {
        let x = 2.0 + 10.0 * k as f64;
        faces.push(rect(DVec3::new(x, 0.0, 2.0), DVec3::X * 8.0, DVec3::Y * 10.0, DVec3::Z));
    }
    let pairing = run(faces);
    assert_eq!(pairing.pairs.len(), 12);
    assert_eq!(pairing.groups.len(), 1);
    let g = &pairing.groups[0];
    assert_eq!(g.sides[0], vec![0]);
    assert_eq!(g.sides[1], (1..=12).collect::<Vec<_>>());
    assert_eq!(g.reference, Side::A, "the bottom (1300) is larger than the pieces (960)");
    assert!((g.thickness.mean - 2.0).abs() < 1e-9);
}

#[test]
fn coaxial_cylinders_of_a_bend() {
    let c = DVec3::new(0.0, 0.0, 0.0);
    let span = (0.0, std::f64::consts::FRAC_PI_2);
    let p = pair_of(vec![cylinder(c, 3.0, span, 40.0, false), cylinder(c, 3.8, span, 40.0, true)]).unwrap();
    assert_eq!(p.kind, PairKind::Cylindrical);
    assert!((p.thickness.mean - 0.8).abs() < 1e-12);
    // Overlap measured at the mean radius 3.4: a quarter turn x 40.
    let expected = 3.4 * std::f64::consts::FRAC_PI_2 * 40.0;
    assert!((p.overlap_area - expected).abs() < 0.01 * expected, "{} vs {expected}", p.overlap_area);
}

#[test]
fn full_tube_overlaps_across_the_seam() {
    let span = (-std::f64::consts::PI, std::f64::consts::PI);
    let p = pair_of(vec![cylinder(DVec3::ZERO, 10.0, span, 5.0, false), cylinder(DVec3::ZERO, 11.0, span, 5.0, true)])
        .unwrap();
    let expected = std::f64::consts::TAU * 10.5 * 5.0;
    assert!((p.overlap_area - expected).abs() < 0.01 * expected);
}

#[test]
fn cylinder_near_misses() {
    let span = (0.0, std::f64::consts::FRAC_PI_2);
    // Axes 2 apart: the gap runs from nothing to 2.8 across the quarter turn, no wall by measurement either.
    let off_axis = pair_of(vec![
        cylinder(DVec3::ZERO, 3.0, span, 40.0, false),
        cylinder(DVec3::new(-2.0, 0.0, 0.0), 3.8, span, 40.0, true),
    ]);
    assert!(matches!(off_axis, Err(Rejection::NotCoaxial { .. } | Rejection::Spread { .. })), "{off_axis:?}");
    let same_sense =
        pair_of(vec![cylinder(DVec3::ZERO, 3.0, span, 40.0, true), cylinder(DVec3::ZERO, 3.8, span, 40.0, true)]);
    assert_eq!(same_sense, Err(Rejection::SameSense));
    // A shaft inside a hole: the convex face is inside the concave one, air between them.
    let shaft_in_hole =
        pair_of(vec![cylinder(DVec3::ZERO, 3.0, span, 40.0, true), cylinder(DVec3::ZERO, 3.8, span, 40.0, false)]);
    assert_eq!(shaft_in_hole, Err(Rejection::NotFacing));
    let apart = pair_of(vec![
        cylinder(DVec3::ZERO, 3.0, span, 40.0, false),
        cylinder(DVec3::ZERO, 3.8, (2.0, 3.0), 40.0, true),
    ]);
    assert!(matches!(apart, Err(Rejection::Overlap { .. })), "{apart:?}");
}

#[test]
fn concentric_spheres() {
    let theta = (0.0, 1.0);
    let p = pair_of(vec![sphere(DVec3::ZERO, 20.0, theta, false), sphere(DVec3::ZERO, 21.5, theta, true)]).unwrap();
    assert_eq!(p.kind, PairKind::Spherical);
    assert!((p.thickness.mean - 1.5).abs() < 1e-12);
    // Centres 10 apart: the skins cross, no wall.
    let off = pair_of(vec![sphere(DVec3::ZERO, 20.0, theta, false), sphere(DVec3::X * 10.0, 21.5, theta, true)]);
    assert!(off.is_err(), "{off:?}");
}

#[test]
fn curved_skins_a_little_off_axis_pair_by_measurement() {
    // Inner and outer arcs of a bend drawn on axes 0.05 apart (the coaxial limit is 1% of t_max, 0.03): the
    // distance measured along the normals runs from 0.85 (along the offset) to 0.8 (across it), a wall.
    let span = (0.0, std::f64::consts::FRAC_PI_2);
    let p = pair_of(vec![
        cylinder(DVec3::ZERO, 3.0, span, 40.0, false),
        cylinder(DVec3::new(0.05, 0.0, 0.0), 3.8, span, 40.0, true),
    ])
    .unwrap();
    assert_eq!(p.kind, PairKind::Freeform);
    assert!(p.thickness.mean > 0.81 && p.thickness.mean < 0.84, "{:?}", p.thickness);
    assert!(p.thickness.min > 0.79 && p.thickness.max < 0.86, "{:?}", p.thickness);
    // The same skins turned apart, the inner one meeting the outer over 60% of it: two faces of a block that
    // face each other in part, not the skins of one wall.
    let turned = pair_of(vec![
        cylinder(DVec3::ZERO, 3.0, span, 40.0, false),
        cylinder(DVec3::new(0.05, 0.0, 0.0), 3.8, (0.2 * std::f64::consts::PI, 0.7 * std::f64::consts::PI), 40.0, true),
    ]);
    assert!(matches!(turned, Err(Rejection::Overlap { limit, .. }) if limit == 0.8), "{turned:?}");
    // A dome's skins on centres 0.2 apart: 1.5 +/- 0.2 over the cap.
    let theta = (0.0, 1.0);
    let dome =
        pair_of(vec![sphere(DVec3::ZERO, 20.0, theta, false), sphere(DVec3::Z * 0.2, 21.5, theta, true)]).unwrap();
    assert_eq!(dome.kind, PairKind::Freeform);
    assert!(dome.thickness.min >= 1.25 && dome.thickness.max <= 1.75, "{:?}", dome.thickness);
}

#[test]
fn a_round_along_a_rim_does_not_pair_with_the_far_skin_by_measurement() {
    // A wall 2 thick (z 0..2) whose top meets its end through a convex round R 2 on the axis y = 0, z = 0 (x
    // along the wall): only the round's stretch next to the top faces the bottom skin across the wall.
    let round = crate::synthetic::face(
        crate::model::face_graph::Surface::Cylinder { origin: DVec3::ZERO, axis: DVec3::X, radius: 2.0, convex: true },
        24,
        |u, v| {
            let a = std::f64::consts::FRAC_PI_2 * v;
            let radial = DVec3::new(0.0, a.cos(), a.sin());
            (DVec3::X * 40.0 * u + radial * 2.0, radial)
        },
    );
    let faces = vec![rect(DVec3::new(0.0, -30.0, 0.0), DVec3::Y * 32.0, DVec3::X * 40.0, -DVec3::Z), round];
    let r = pair_of(faces);
    assert!(matches!(r, Err(Rejection::Overlap { .. } | Rejection::Incompatible { .. })), "{r:?}");
}

#[test]
fn tori_with_shared_axis_and_major_radius() {
    let p = pair_of(vec![torus(DVec3::ZERO, 30.0, 3.0, false), torus(DVec3::ZERO, 30.0, 5.0, true)]).unwrap();
    assert_eq!(p.kind, PairKind::Toroidal);
    assert!((p.thickness.mean - 2.0).abs() < 1e-12);
    let other_major = pair_of(vec![torus(DVec3::ZERO, 30.0, 3.0, false), torus(DVec3::ZERO, 31.0, 5.0, true)]);
    // Measured, the gap runs from 2 to 3 over the outer half of the tube: no wall of one thickness.
    assert!(matches!(other_major, Err(Rejection::Spread { .. })), "{other_major:?}");
}

#[test]
fn coaxial_cones_with_the_same_half_angle() {
    let half = 30.0_f64.to_radians();
    // The outer cone's apex sits 2 / sin(30) = 4 below the inner one's: the walls are 2 apart.
    let inner = cone(DVec3::ZERO, half, (10.0, 30.0), false);
    let outer = cone(DVec3::new(0.0, 0.0, -4.0), half, (12.0, 34.0), true);
    let p = pair_of(vec![inner, outer]).unwrap();
    assert_eq!(p.kind, PairKind::Conical);
    // Exact (from the apexes), not measured on the faceted mesh.
    assert!((p.thickness.mean - 2.0).abs() < 1e-9 && p.thickness.min == p.thickness.max, "{:?}", p.thickness);
}

/// A convex cone of half-angle `degrees` about the z axis, radius 6 at z = 0, up to z = 15.
fn cone_round_the_axis(degrees: f64) -> Face {
    let h = degrees.to_radians();
    let apex = DVec3::new(0.0, 0.0, -6.0 / h.tan());
    let d0 = -apex.z / h.cos();
    cone(apex, h, (d0, d0 + 15.0 / h.cos()), true)
}

#[test]
fn a_drafted_cone_round_a_cylindrical_hole_is_a_tapered_wall() {
    let hole = || cylinder(DVec3::ZERO, 4.0, (-std::f64::consts::PI, std::f64::consts::PI), 15.0, false);
    // Drafted by 1 degree: the wall runs from 2 at z = 0 to 2 + 15 tan(1 deg) = 2.26 at the top, and says so.
    let p = pair_of(vec![hole(), cone_round_the_axis(1.0)]).unwrap();
    assert_eq!(p.kind, PairKind::Conical);
    let t = p.thickness;
    assert!(t.min > 1.9 && t.max < 2.35 && t.max - t.min > 0.15 && t.min < t.mean && t.mean < t.max, "{t:?}");
    // Leaning apart by more than twice the 3 degree draft limit: not one wall.
    let steep = pair_of(vec![hole(), cone_round_the_axis(7.0)]);
    assert!(matches!(steep, Err(Rejection::Angle { .. })), "{steep:?}");
}

/// A wavy sheet z = base + 2 sin(x/10) over [0,60]x[0,40]; `outward` up or down.
fn wavy(base: f64, up: bool) -> Face {
    crate::synthetic::face(crate::model::face_graph::Surface::Bspline, 30, |u, v| {
        let (x, y) = (60.0 * u, 40.0 * v);
        let z = base + 2.0 * (x / 10.0).sin();
        let n = DVec3::new(-0.2 * (x / 10.0).cos(), 0.0, 1.0).normalize();
        (DVec3::new(x, y, z), if up { n } else { -n })
    })
}

#[test]
fn freeform_offset_sheets_pair_at_nearly_constant_distance() {
    let p = pair_of(vec![wavy(0.0, false), wavy(1.5, true)]).unwrap();
    assert_eq!(p.kind, PairKind::Freeform);
    // Vertical offset 1.5 of a sheet sloping up to atan(0.2) = 11.3 deg: normal distance 1.47..1.5.
    assert!(p.thickness.min > 1.4 && p.thickness.max < 1.55, "{:?}", p.thickness);
}

#[test]
fn a_tapered_freeform_wall_pairs_with_its_thickness_as_a_range() {
    // The wavy sheet's top skin rises from 1 to 2 above it along x (0.95 deg of taper): one wall, every point of
    // the bottom facing the top, however much the distance varies.
    let top = crate::synthetic::face(crate::model::face_graph::Surface::Bspline, 30, |u, v| {
        let (x, y) = (60.0 * u, 40.0 * v);
        let z = 1.0 + x / 60.0 + 2.0 * (x / 10.0).sin();
        (DVec3::new(x, y, z), DVec3::new(-0.2 * (x / 10.0).cos() - 1.0 / 60.0, 0.0, 1.0).normalize())
    });
    let p = pair_of(vec![wavy(0.0, false), top]).unwrap();
    assert_eq!(p.kind, PairKind::Freeform);
    assert!(p.thickness.min < 1.1 && p.thickness.max > 1.85, "{:?}", p.thickness);
}

#[test]
fn freeform_with_a_varying_gap_is_not_one_wall() {
    let flat_top = crate::synthetic::face(crate::model::face_graph::Surface::Bspline, 30, |u, v| {
        (DVec3::new(60.0 * u, 40.0 * v, 2.2), DVec3::Z)
    });
    let err = pair_of(vec![wavy(0.0, false), flat_top]).unwrap_err();
    assert!(matches!(err, Rejection::Spread { .. } | Rejection::Overlap { .. }), "{err:?}");
}

#[test]
fn plane_and_cylinder_cannot_pair() {
    let faces = vec![
        rect(DVec3::ZERO, DVec3::Y * 4.0, DVec3::X * 4.0, -DVec3::Z),
        cylinder(DVec3::ZERO, 1.0, (0.0, 1.0), 1.0, true),
    ];
    assert!(matches!(pair_of(faces), Err(Rejection::Incompatible { .. })));
}

#[test]
fn plate_roles_skins_and_thickness_faces() {
    let g = synthetic::cuboid(DVec3::ZERO, DVec3::new(100.0, 60.0, 2.0));
    let pairing = detect(&g, &tol(), &[true; 6]);
    assert_eq!(pairing.pairs.len(), 1);
    assert_eq!(pairing.pairs[0].faces, [4, 5]);
    for f in 0..4 {
        assert_eq!(pairing.roles[f], FaceRole::Thickness { group: 0 }, "face {f}");
    }
    assert!(matches!(pairing.roles[4], FaceRole::Pair { group: 0, .. }));
    assert!((pairing.paired_area_share(&g) - 12000.0 / 12640.0).abs() < 1e-9);
}

#[test]
fn suppressed_faces_do_not_pair_and_unpaired_faces_say_why() {
    let g = synthetic::cuboid(DVec3::ZERO, DVec3::new(100.0, 60.0, 2.0));
    let mut pairable = [true; 6];
    pairable[5] = false;
    let pairing = detect(&g, &tol(), &pairable);
    assert!(pairing.pairs.is_empty());
    assert_eq!(pairing.roles[5], FaceRole::Suppressed);
    match &pairing.roles[0] {
        FaceRole::Unpaired { near_miss: Some(NearMiss { rejection: Rejection::Angle { .. }, .. }) } => {}
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_rim_face_beyond_a_suppressed_round_is_still_a_thickness_face() {
    // A plate (faces 0, 1) whose end face 2 meets the bottom directly and the top through a round (3).
    let faces = vec![
        rect(DVec3::ZERO, DVec3::Y * 40.0, DVec3::X * 60.0, -DVec3::Z),
        rect(DVec3::new(0.0, 0.0, 2.0), DVec3::X * 59.5, DVec3::Y * 40.0, DVec3::Z),
        rect(DVec3::new(60.0, 0.0, 0.0), DVec3::Y * 40.0, DVec3::Z * 1.5, DVec3::X),
        cylinder(DVec3::new(59.5, 0.0, 1.5), 0.5, (0.0, std::f64::consts::FRAC_PI_2), 40.0, true),
    ];
    let g = synthetic::graph(faces, &[(0, 2, Convexity::Convex), (2, 3, Convexity::Smooth), (1, 3, Convexity::Smooth)]);
    let pairing = detect(&g, &tol(), &[true, true, true, false]);
    assert_eq!(pairing.roles[2], FaceRole::Thickness { group: 0 });
    assert_eq!(pairing.roles[3], FaceRole::Suppressed);
}

/// A flat 60 x 40 face at height `z` from x = `x0`, facing up or down, but a B-spline: paired by rays.
fn freeform_flat(x0: f64, z: f64, up: bool) -> Face {
    crate::synthetic::face(crate::model::face_graph::Surface::Bspline, 12, |u, v| {
        (DVec3::new(x0 + 60.0 * u, 40.0 * v, z), if up { DVec3::Z } else { -DVec3::Z })
    })
}

#[test]
fn measured_pairs_whose_skins_run_on_smoothly_on_both_sides_share_one_thickness() {
    // Two measured walls side by side, 2 and `right` thick; where their bottoms meet and their tops meet across
    // smooth edges, the skins run on (a vault into its dome). At one thickness (within 1%) both pairs take the
    // overlap-weighted mean, so their patches meet edge to edge; joined on one side only (a T), or at another
    // thickness (a step), each keeps its own. Each stays its own group.
    let means = |right: f64, joints: &[(usize, usize, Convexity)]| {
        let faces = vec![
            freeform_flat(0.0, 0.0, false),
            freeform_flat(0.0, 2.0, true),
            freeform_flat(60.0, 0.0, false),
            freeform_flat(60.0, right, true),
        ];
        let g = synthetic::graph(faces, joints);
        let pairing = detect(&g, &tol(), &[true; 4]);
        assert_eq!(pairing.groups.len(), 2);
        pairing.pairs.iter().map(|p| p.thickness.mean).collect::<Vec<_>>()
    };
    let both = [(0, 2, Convexity::Smooth), (1, 3, Convexity::Smooth)];
    let shared = means(2.01, &both);
    assert!((shared[0] - 2.005).abs() < 1e-9 && shared[1] == shared[0], "{shared:?}");
    let t_joint = means(2.01, &[(1, 3, Convexity::Smooth), (0, 2, Convexity::Concave)]);
    assert!((t_joint[0] - 2.0).abs() < 1e-9 && (t_joint[1] - 2.01).abs() < 1e-9, "{t_joint:?}");
    let step = means(2.1, &both);
    assert!((step[1] - 2.1).abs() < 1e-9, "{step:?}");
    // Three in a row, 2.0, 2.015 and 2.03 thick: each within 1% of the next, but the chain drifts 1.5%, a taper:
    // each keeps its own.
    let faces = vec![
        freeform_flat(0.0, 0.0, false),
        freeform_flat(0.0, 2.0, true),
        freeform_flat(60.0, 0.0, false),
        freeform_flat(60.0, 2.015, true),
        freeform_flat(120.0, 0.0, false),
        freeform_flat(120.0, 2.03, true),
    ];
    let joints =
        [(0, 2, Convexity::Smooth), (1, 3, Convexity::Smooth), (2, 4, Convexity::Smooth), (3, 5, Convexity::Smooth)];
    let g = synthetic::graph(faces, &joints);
    let taper: Vec<f64> = detect(&g, &tol(), &[true; 6]).pairs.iter().map(|p| p.thickness.mean).collect();
    assert!((taper[0] - 2.0).abs() < 1e-9 && (taper[2] - 2.03).abs() < 1e-9, "{taper:?}");
}

#[test]
fn connecting_face_between_two_walls() {
    // Two slabs side by side joined by a face touching one skin of each.
    let mut faces = slab_faces(2.0);
    faces.extend([
        rect(DVec3::new(100.0, 0.0, 0.0), DVec3::Y * 40.0, DVec3::X * 60.0, -DVec3::Z),
        rect(DVec3::new(100.0, 0.0, 2.0), DVec3::X * 60.0, DVec3::Y * 40.0, DVec3::Z),
        rect(DVec3::new(60.0, 0.0, 2.0), DVec3::X * 40.0, DVec3::Y * 40.0, DVec3::Z * 1.0 + DVec3::X * 0.0),
    ]);
    let g = synthetic::graph(faces, &[(1, 4, Convexity::Smooth), (3, 4, Convexity::Smooth)]);
    let pairing = detect(&g, &tol(), &[true; 5]);
    assert_eq!(pairing.groups.len(), 2);
    assert!(matches!(&pairing.roles[4], FaceRole::Connecting { groups, .. } if groups == &[0, 1]));
    // Why it is no skin (`pairs --json` says so): the slabs' bottoms below it lie beside it, not under it.
    match &pairing.roles[4] {
        FaceRole::Connecting { near_miss: Some(NearMiss { rejection: Rejection::Overlap { .. }, .. }), .. } => {}
        other => panic!("expected a near miss on the overlap test, got {other:?}"),
    }
}

#[test]
fn far_faces_are_not_even_candidates() {
    let mut faces = slab_faces(2.0);
    faces.push(rect(DVec3::new(500.0, 0.0, 0.0), DVec3::X * 10.0, DVec3::Y * 10.0, DVec3::Z));
    let g = synthetic::graph(faces, &[]);
    assert_eq!(candidates::candidate_pairs(&g, T_MAX), vec![(0, 1)]);
}

#[test]
fn t_max_estimate_from_the_dominant_wall() {
    let mut g = synthetic::cuboid(DVec3::ZERO, DVec3::new(100.0, 60.0, 2.0));
    g.area = g.faces.iter().map(|f| f.area).sum();
    let e = estimate::estimate_t_max(&g, 3.0_f64.to_radians());
    assert_eq!(e.dominant, Some(2.0));
    assert!((e.t_max - 3.0).abs() < 1e-9, "{e:?}");
}

/// Faces 0 and 1: a land's sides (y = 10 facing -y, y = 11 facing +y), 20 long and 0.9 tall over z 2.0..2.9.
fn land_sides() -> Vec<Face> {
    vec![
        rect(DVec3::new(0.0, 10.0, 2.0), DVec3::Z * 0.9, DVec3::X * 20.0, -DVec3::Y),
        rect(DVec3::new(0.0, 11.0, 2.0), DVec3::X * 20.0, DVec3::Z * 0.9, DVec3::Y),
    ]
}

/// The graph of `faces` with each edge as long as given (the perimeters the widths are measured on).
fn graph_with_lengths(
    faces: Vec<Face>,
    adjacent: &[(usize, usize, Convexity, f64)],
) -> crate::model::face_graph::FaceGraph {
    let edges: Vec<(usize, usize, Convexity)> = adjacent.iter().map(|&(a, b, c, _)| (a, b, c)).collect();
    let mut g = synthetic::graph(faces, &edges);
    for (edge, &(_, _, _, length)) in g.edges.iter_mut().zip(adjacent) {
        edge.length = length;
    }
    g
}

#[test]
fn the_sides_of_a_land_between_pockets_are_no_wall() {
    // A 2.9 plate (back 2, top 3) with a pocket each side of the land (floors 4 and 5 at z = 2.0, 2.0 thick):
    // the land's sides stand 1.0 apart but are 0.9 tall, and the plate's top joins them. Whether the land's top
    // is a face of its own (then the narrow top of a stub) or part of the plate's top skin, the sides do not
    // pair; the plate's back pairs with the floors (and with the top when that is a skin).
    for top_is_skin in [false, true] {
        let mut faces = land_sides();
        let top = if top_is_skin { (60.0, 40.0) } else { (20.0, 1.0) };
        faces.extend([
            rect(DVec3::ZERO, DVec3::Y * 40.0, DVec3::X * 60.0, -DVec3::Z),
            rect(DVec3::new(0.0, 10.0, 2.9), DVec3::X * top.0, DVec3::Y * top.1, DVec3::Z),
            rect(DVec3::new(0.0, 0.0, 2.0), DVec3::X * 20.0, DVec3::Y * 10.0, DVec3::Z),
            rect(DVec3::new(0.0, 11.0, 2.0), DVec3::X * 20.0, DVec3::Y * 10.0, DVec3::Z),
        ]);
        let mut edges = vec![
            (0, 3, Convexity::Convex, 20.0),
            (1, 3, Convexity::Convex, 20.0),
            (0, 4, Convexity::Concave, 20.0),
            (1, 5, Convexity::Concave, 20.0),
        ];
        if top_is_skin {
            // The rest of the plate top's outline.
            edges.push((3, 2, Convexity::Convex, 200.0));
        }
        let pairing = detect(&graph_with_lengths(faces, &edges), &tol(), &[true; 6]);
        let paired: Vec<[usize; 2]> = pairing.pairs.iter().map(|p| p.faces).collect();
        let expected = if top_is_skin { vec![[2, 3], [2, 4], [2, 5]] } else { vec![[2, 4], [2, 5]] };
        assert_eq!(paired, expected, "top is a skin: {top_is_skin}");
        assert!(pairing.roles[..2].iter().all(|r| !matches!(r, FaceRole::Pair { .. })), "{:?}", pairing.roles);
    }
}

#[test]
fn the_round_sides_of_a_curved_land_are_no_wall_either() {
    // The land of the test above bent round the z axis (a logo's stroke): its sides are coaxial cylinders
    // r = 10 and 11 over 2 radians, 0.9 tall, 1.0 apart, joined by the land's narrow top.
    let span = (0.0, 2.0);
    let mut faces = vec![
        cylinder(DVec3::Z * 2.0, 10.0, span, 0.9, false),
        cylinder(DVec3::Z * 2.0, 11.0, span, 0.9, true),
        rect(DVec3::new(-30.0, -30.0, 0.0), DVec3::Y * 60.0, DVec3::X * 60.0, -DVec3::Z),
        rect(DVec3::new(0.0, 10.0, 2.9), DVec3::X * 20.0, DVec3::Y * 1.0, DVec3::Z),
        rect(DVec3::new(-30.0, -30.0, 2.0), DVec3::X * 60.0, DVec3::Y * 60.0, DVec3::Z),
    ];
    faces.push(faces[4].clone());
    let edges = [
        (0, 3, Convexity::Convex, 20.0),
        (1, 3, Convexity::Convex, 22.0),
        (0, 4, Convexity::Concave, 20.0),
        (1, 5, Convexity::Concave, 22.0),
    ];
    let g = graph_with_lengths(faces, &edges);
    assert!(criteria::test_pair(&g, 0, 1, &tol()).is_ok(), "the sides alone pass the coaxial tests");
    let pairing = detect(&g, &tol(), &[true; 6]);
    assert!(pairing.pairs.iter().all(|p| p.faces != [0, 1]), "{:?}", pairing.pairs);
    assert!(pairing.roles[..2].iter().all(|r| !matches!(r, FaceRole::Pair { .. })), "{:?}", pairing.roles);
}

#[test]
fn a_short_tab_joined_only_by_its_edge_faces_stays_a_wall() {
    // The same two sides, joined by a top that pairs with nothing: a tab 1.0 thick and 0.9 wide.
    let mut faces = land_sides();
    faces.push(rect(DVec3::new(0.0, 10.0, 2.9), DVec3::X * 20.0, DVec3::Y * 1.0, DVec3::Z));
    let long = |a, b, c| (a, b, c, 20.0);
    let g = graph_with_lengths(faces, &[long(0, 2, Convexity::Convex), long(1, 2, Convexity::Convex)]);
    let pairing = detect(&g, &tol(), &[true; 3]);
    assert_eq!(pairing.pairs.iter().map(|p| p.faces).collect::<Vec<_>>(), vec![[0, 1]]);
}

#[test]
fn planar_slivers_far_apart_are_no_wall_whatever_joins_them() {
    // Two strips 20 long facing each other 1.0 apart, each with one concave long side (so no stub top), joined
    // only by an edge face (no skin): 0.9 wide they are a short tab's sides (a wall), 0.2 wide slivers (a
    // counterbore's annular steps seen edge on).
    for (width, wall) in [(0.9, true), (0.2, false)] {
        let faces = vec![
            rect(DVec3::new(0.0, 10.0, 2.0), DVec3::Z * width, DVec3::X * 20.0, -DVec3::Y),
            rect(DVec3::new(0.0, 11.0, 2.0), DVec3::X * 20.0, DVec3::Z * width, DVec3::Y),
            rect(DVec3::new(0.0, 10.0, 2.0 + width), DVec3::X * 20.0, DVec3::Y * 1.0, DVec3::Z),
            rect(DVec3::new(0.0, 0.0, -50.0), DVec3::X * 20.0, DVec3::Y * 5.0, DVec3::Z),
            rect(DVec3::new(0.0, 20.0, -50.0), DVec3::X * 20.0, DVec3::Y * 5.0, DVec3::Z),
        ];
        let long = |a, b, c| (a, b, c, 20.0);
        let edges = [
            long(0, 2, Convexity::Convex),
            long(1, 2, Convexity::Convex),
            long(0, 3, Convexity::Concave),
            long(1, 4, Convexity::Concave),
        ];
        let pairing = detect(&graph_with_lengths(faces, &edges), &tol(), &[true; 5]);
        let paired: Vec<[usize; 2]> = pairing.pairs.iter().map(|p| p.faces).collect();
        assert_eq!(paired, if wall { vec![[0, 1]] } else { vec![] }, "width {width}");
    }
}

#[test]
fn a_low_side_over_a_taller_partner_is_a_stub_side_where_both_stand_on_one_plane_skin() {
    // A rib 1.0 thick on a plate (back 2 at z = 0, top in two pieces 3 and 4 either side of the rib): its side 0
    // is 0.9 tall, its side 1 runs on up to 6 (a hook rising from the rib, whose other side 7 stands on the rib's
    // top 5), so only side 0 is narrower than the rib is thick, and it lies wholly over side 1. Standing on the
    // plate's top (split by the rib) the two are the sides of a low stub, whose material is the plate's. When
    // side 1 stands on a skin off that plane (a level 0.5 higher), side 0 is but a narrow piece of a wall's skin,
    // and the two stay a wall.
    for (level, stub) in [(2.0, true), (2.5, false)] {
        let faces = vec![
            rect(DVec3::new(0.0, 10.0, 2.0), DVec3::Z * 0.9, DVec3::X * 20.0, -DVec3::Y),
            rect(DVec3::new(0.0, 11.0, 2.0), DVec3::X * 20.0, DVec3::Z * 6.0, DVec3::Y),
            rect(DVec3::new(-20.0, -20.0, 0.0), DVec3::Y * 60.0, DVec3::X * 60.0, -DVec3::Z),
            rect(DVec3::new(-20.0, -20.0, 2.0), DVec3::X * 60.0, DVec3::Y * 30.0, DVec3::Z),
            rect(DVec3::new(-20.0, 11.0, level), DVec3::X * 60.0, DVec3::Y * 29.0, DVec3::Z),
            rect(DVec3::new(0.0, 10.0, 2.9), DVec3::X * 20.0, DVec3::Y * 1.0, DVec3::Z),
            rect(DVec3::new(0.0, 11.0, 8.0), DVec3::X * 20.0, DVec3::Y * 1.0, DVec3::Z),
            rect(DVec3::new(0.0, 10.0, 3.0), DVec3::Z * 5.0, DVec3::X * 20.0, -DVec3::Y),
        ];
        let edges = [
            (0, 3, Convexity::Concave, 20.0),
            (0, 5, Convexity::Convex, 20.0),
            (1, 4, Convexity::Concave, 20.0),
            (1, 6, Convexity::Convex, 20.0),
            (7, 6, Convexity::Convex, 20.0),
            (7, 5, Convexity::Concave, 20.0),
        ];
        let g = graph_with_lengths(faces, &edges);
        assert!(criteria::test_pair(&g, 0, 1, &tol()).is_ok(), "the sides alone pass the pair tests");
        let pairing = detect(&g, &tol(), &[true; 8]);
        let paired = pairing.pairs.iter().any(|p| p.faces == [0, 1]);
        assert_eq!(paired, !stub, "level {level}: {:?}", pairing.pairs);
        if stub {
            let near_miss = match &pairing.roles[0] {
                FaceRole::Unpaired { near_miss } | FaceRole::Connecting { near_miss, .. } => near_miss.clone(),
                _ => None,
            };
            assert!(matches!(
                near_miss,
                Some(NearMiss { candidate: 1, rejection: Rejection::Stub { top: false, .. } })
            ));
        }
    }
}

fn is_stub_top(role: &FaceRole) -> bool {
    matches!(
        role,
        FaceRole::Unpaired { near_miss: Some(NearMiss { rejection: Rejection::Stub { top: true, .. }, .. }) }
    )
}

#[test]
fn a_narrow_face_standing_proud_is_the_top_of_a_stub_not_a_skin() {
    // A strip 0.8 wide at 2.9 over a plate's back: with every edge convex it tops a bead and does not pair;
    // with a concave edge (a strip between two ribs) it is a skin of the plate.
    let strip = || {
        vec![
            rect(DVec3::ZERO, DVec3::Y * 40.0, DVec3::X * 60.0, -DVec3::Z),
            rect(DVec3::new(0.0, 10.0, 2.9), DVec3::X * 20.0, DVec3::Y * 0.8, DVec3::Z),
            rect(DVec3::new(0.0, 10.0, 2.0), DVec3::Z * 0.9, DVec3::X * 20.0, -DVec3::Y),
        ]
    };
    for (convexity, pairs) in [(Convexity::Convex, 0), (Convexity::Concave, 1)] {
        let g = graph_with_lengths(strip(), &[(1, 2, convexity, 20.0), (1, 0, Convexity::Convex, 20.0)]);
        let pairing = detect(&g, &tol(), &[true; 3]);
        assert_eq!(pairing.pairs.len(), pairs, "{convexity:?}");
        if pairs == 0 {
            assert!(is_stub_top(&pairing.roles[1]));
        }
    }
}

#[test]
fn a_groove_narrower_than_the_wall_is_a_minor_level_of_it() {
    // A 2.0 plate (back 0) whose top is split by a groove along x: top skins 1 and 3 beside it, the groove's
    // floor 2 at `floor`. A floor 1.0 wide and 1.2 from the back is a minor level and does not pair; at the
    // plate's own level (a strip between two ribs) it stays a skin; and a floor wider than its distance to the
    // back is a level of its own.
    let plate = |floor: f64, width: f64| {
        vec![
            rect(DVec3::ZERO, DVec3::Y * 40.0, DVec3::X * 60.0, -DVec3::Z),
            rect(DVec3::new(0.0, 0.0, 2.0), DVec3::X * 60.0, DVec3::Y * 19.0, DVec3::Z),
            rect(DVec3::new(0.0, 19.0, floor), DVec3::X * 60.0, DVec3::Y * width, DVec3::Z),
            rect(DVec3::new(0.0, 19.0 + width, 2.0), DVec3::X * 60.0, DVec3::Y * (21.0 - width), DVec3::Z),
        ]
    };
    for (floor, width, floor_pairs) in [(1.2, 1.0, false), (2.0, 1.0, true), (1.2, 1.3, true)] {
        // The floor's outline: its two long sides (to the groove's walls, here straight to the skins) and ends.
        let edges = [
            (1, 2, Convexity::Concave, 60.0),
            (2, 3, Convexity::Concave, 60.0),
            (0, 2, Convexity::Convex, 2.0 * width),
        ];
        let pairing = detect(&graph_with_lengths(plate(floor, width), &edges), &tol(), &[true; 4]);
        let paired: Vec<[usize; 2]> = pairing.pairs.iter().map(|p| p.faces).collect();
        let expected = if floor_pairs { vec![[0, 1], [0, 2], [0, 3]] } else { vec![[0, 1], [0, 3]] };
        assert_eq!(paired, expected, "floor at {floor}, {width} wide");
        // Between the plate's two skins the floor is one of its wall's side faces.
        if !floor_pairs {
            assert_eq!(pairing.roles[2], FaceRole::Thickness { group: 0 });
        }
    }
}

#[test]
fn a_band_round_a_rounded_corner_narrower_than_thick_is_a_minor_level_as_on_the_flats() {
    // A box's rounded corner (a quarter turn about z): outside R 6 up to 30 (0), inside R 4 up to 28.8 (1, a
    // wall 2.0 thick), and above it a rebate's band R 4.6, 1.2 tall (2): 1.4 from the outside and narrower
    // than that. Like a planar band on the flats beside it, it is a minor level of the corner's wall; 2.0 tall,
    // it is a level of its own.
    let quarter = (0.0, std::f64::consts::FRAC_PI_2);
    for (tall, band_pairs) in [(1.2, false), (2.0, true)] {
        let faces = vec![
            cylinder(DVec3::ZERO, 6.0, quarter, 30.0, true),
            cylinder(DVec3::ZERO, 4.0, quarter, 30.0 - tall, false),
            cylinder(DVec3::Z * (30.0 - tall), 4.6, quarter, tall, false),
        ];
        let arc = 4.6 * std::f64::consts::FRAC_PI_2;
        // The band's outline: two arcs and two short ends.
        let edges = [
            (1, 2, Convexity::Concave, arc),
            (1, 2, Convexity::Convex, arc),
            (1, 2, Convexity::Convex, tall),
            (1, 2, Convexity::Convex, tall),
        ];
        let pairing = detect(&graph_with_lengths(faces, &edges), &tol(), &[true; 3]);
        let paired: Vec<[usize; 2]> = pairing.pairs.iter().map(|p| p.faces).collect();
        let expected = if band_pairs { vec![[0, 1], [0, 2]] } else { vec![[0, 1]] };
        assert_eq!(paired, expected, "band {tall} tall");
        if !band_pairs {
            let minor = |r: &FaceRole| match r {
                FaceRole::Unpaired { near_miss: Some(m) } | FaceRole::Connecting { near_miss: Some(m), .. } => {
                    matches!(m.rejection, Rejection::MinorLevel { .. })
                }
                _ => false,
            };
            assert!(minor(&pairing.roles[2]), "{:?}", pairing.roles[2]);
        }
    }
}

#[test]
fn a_lip_along_a_plate_edge_is_a_stub_whichever_face_is_proud() {
    // A plate's end face (0: z=0, facing -z, 1.7 wide) runs on under a lip whose top (1: z=1.9, facing +z,
    // 0.95 wide) meets the plate's skin along a concave edge. The end face is the proud one: convex long sides,
    // concave only at its short ends (corner blends). The pair is the top of a stub, not a wall 1.9 thick.
    let faces = vec![
        rect(DVec3::new(-2.8, 0.0, 0.0), DVec3::Y * 90.0, DVec3::X * 1.7, -DVec3::Z),
        rect(DVec3::new(-3.0, 0.0, 1.9), DVec3::X * 0.95, DVec3::Y * 90.0, DVec3::Z),
        rect(DVec3::new(-2.05, 0.0, 1.9), DVec3::Y * 90.0, DVec3::Z * 50.0, -DVec3::X),
    ];
    for ends in [Convexity::Concave, Convexity::Convex] {
        let edges = [
            (0, 2, Convexity::Convex, 90.0),
            (0, 2, Convexity::Convex, 90.0),
            (0, 2, ends, 1.7),
            (0, 2, ends, 1.7),
            (1, 2, Convexity::Concave, 90.0),
            (1, 2, Convexity::Convex, 90.0),
        ];
        let pairing = detect(&graph_with_lengths(faces.clone(), &edges), &tol(), &[true; 3]);
        assert!(pairing.pairs.is_empty(), "ends {ends:?}");
        assert!(is_stub_top(&pairing.roles[0]));
    }
    // With a concave long side the end face is a skin again (a strip beside a rib): the pair stands.
    let edges = [(0, 2, Convexity::Concave, 90.0), (0, 2, Convexity::Convex, 90.0), (1, 2, Convexity::Concave, 90.0)];
    assert_eq!(detect(&graph_with_lengths(faces, &edges), &tol(), &[true; 3]).pairs.len(), 1);
}

#[test]
fn a_lip_under_a_plate_end_is_no_wall_a_chamfered_corner_is() {
    // A plate 2.0 thick between skins 2 and 3, whose end face 0 (2.6 wide, facing +z) caps a 1.0 lip: the lip's
    // underside 1 (1.0 wide, 1.7 below the end) runs into skin 2 along a concave edge. Faces 0 and 1 pair with
    // nothing else: the pair measures the lip along the plate (`Lip`). With the plate turned 45 degrees (a
    // chamfered corner's bevels meet their walls at 45 degrees) the pair stays.
    for (tilt, lip) in [(0.0_f64, true), (45.0, false)] {
        let (s, c) = tilt.to_radians().sin_cos();
        let normal = DVec3::new(-c, 0.0, -s);
        let down = DVec3::new(-s, 0.0, c) * -50.0;
        let faces = vec![
            rect(DVec3::new(-2.8, 0.0, 1.7), DVec3::Y * 90.0, DVec3::X * 2.6, DVec3::Z),
            rect(DVec3::new(-3.0, 0.0, 0.0), DVec3::X, DVec3::Y * 90.0, -DVec3::Z),
            rect(DVec3::new(-2.0, 0.0, 0.0), DVec3::Y * 90.0, down, normal),
            rect(DVec3::new(-2.0, 0.0, 0.0) - normal * 2.0, down, DVec3::Y * 90.0, -normal),
        ];
        let edges = [
            (1, 2, Convexity::Concave, 90.0),
            (0, 1, Convexity::Convex, 90.0),
            (0, 3, Convexity::Convex, 90.0),
            (2, 3, Convexity::Convex, 2.0),
        ];
        let pairing = detect(&graph_with_lengths(faces, &edges), &tol(), &[true; 4]);
        let paired: Vec<[usize; 2]> = pairing.pairs.iter().map(|p| p.faces).collect();
        let expected = if lip { vec![[2, 3]] } else { vec![[0, 1], [2, 3]] };
        assert_eq!(paired, expected, "plate at {tilt} degrees");
    }
}

#[test]
fn a_bevel_cutting_a_trays_corner_stands_on_the_floor_by_its_end_and_stays_a_wall() {
    // A tray's vertical corner bevelled on both skins: the outer bevel 0 (4.0 wide, 30 tall), the inner bevel 1
    // (1.8 wide, narrower than the 2.0 between them) standing on the floor 2 (paired with the bottom 3) along a
    // concave edge 1.8 long, its end, and meeting the inner skins 4 and 6 of two walls (paired with 5 and 7) at
    // 45 degrees along its 28 long sides (its top meets the rim 8). No lip: the pair stays. With one side
    // meeting a face that is no wall skin, the narrow face standing on the floor is a lip's underside.
    let out = DVec3::new(-1.0, -1.0, 0.0).normalize();
    let along = DVec3::new(1.0, -1.0, 0.0).normalize();
    for (second_side, lip) in [(6, false), (8, true)] {
        let faces = vec![
            rect(-along * 2.0, along * 4.0, DVec3::Z * 30.0, out),
            rect(-out * 2.0 - along * 0.9 + DVec3::Z * 2.0, DVec3::Z * 28.0, along * 1.8, -out),
            rect(DVec3::new(0.0, 0.0, 2.0), DVec3::X * 50.0, DVec3::Y * 50.0, DVec3::Z),
            rect(DVec3::ZERO, DVec3::Y * 50.0, DVec3::X * 50.0, -DVec3::Z),
            rect(DVec3::new(10.0, 2.0, 2.0), DVec3::X * 30.0, DVec3::Z * 28.0, DVec3::Y),
            rect(DVec3::new(10.0, 0.0, 0.0), DVec3::Z * 30.0, DVec3::X * 30.0, -DVec3::Y),
            rect(DVec3::new(2.0, 10.0, 2.0), DVec3::Z * 28.0, DVec3::Y * 30.0, DVec3::X),
            rect(DVec3::new(0.0, 10.0, 0.0), DVec3::Y * 30.0, DVec3::Z * 30.0, -DVec3::X),
            rect(DVec3::new(0.0, 0.0, 30.0), DVec3::X, DVec3::Y, DVec3::Z),
        ];
        let edges = [
            (1, 2, Convexity::Concave, 1.8),
            (1, 4, Convexity::Concave, 28.0),
            (1, second_side, Convexity::Concave, 28.0),
            (1, 8, Convexity::Convex, 1.8),
            (0, 3, Convexity::Convex, 4.0),
        ];
        let mut graph = graph_with_lengths(faces, &edges);
        for (edge, turn) in graph.edges.iter_mut().zip([90.0_f64, 45.0, 45.0, 90.0, 90.0]) {
            edge.angle = turn.to_radians();
        }
        let pairing = detect(&graph, &tol(), &[true; 9]);
        let bevels = pairing.pairs.iter().any(|p| p.faces == [0, 1]);
        assert_eq!(bevels, !lip, "the inner bevel's second side on face {second_side}");
    }
}

#[test]
fn a_near_miss_across_the_wall_says_more_than_a_face_beside_it() {
    // The near miss kept per face is the candidate that passed most tests. A face beside this one (its box within
    // reach, but lying over none of it: overlap 0) says less than a partner across the wall that failed on its
    // distance, and no more than faces that do not enclose material.
    let beside = Rejection::Overlap { share: 0.0, limit: 0.1 };
    let across = Rejection::Distance { distance: 4.0, limit: 3.0 };
    let partly = Rejection::Overlap { share: 0.05, limit: 0.1 };
    assert!(beside.stage() < across.stage() && across.stage() < partly.stage());
    assert_eq!(beside.stage(), Rejection::NotFacing.stage());
}

#[test]
fn a_web_between_two_holes_of_a_plate_is_the_plate_a_rib_on_it_is_a_wall() {
    // The 3.0 slab (bottom 0, top 1) with two faces 1.0 apart facing away from each other, 20 long: through
    // the plate (z 0..3, both skins meet both faces: a web between two slots) they are the plate's own; standing
    // on its top (z 3..6, meeting the top only: a rib) they are a wall.
    let web = |z: f64| {
        vec![
            rect(DVec3::new(20.0, 10.0, z), DVec3::Z * 3.0, DVec3::Y * 20.0, -DVec3::X),
            rect(DVec3::new(21.0, 10.0, z), DVec3::Y * 20.0, DVec3::Z * 3.0, DVec3::X),
        ]
    };
    let through = [
        (0, 2, Convexity::Convex, 20.0),
        (0, 3, Convexity::Convex, 20.0),
        (1, 2, Convexity::Convex, 20.0),
        (1, 3, Convexity::Convex, 20.0),
    ];
    let mut faces = slab_faces(3.0);
    faces.extend(web(0.0));
    let pairing = detect(&graph_with_lengths(faces, &through), &tol(), &[true; 4]);
    assert_eq!(pairing.pairs.iter().map(|p| p.faces).collect::<Vec<_>>(), vec![[0, 1]]);
    assert_eq!(pairing.roles[2], FaceRole::Thickness { group: 0 });
    assert_eq!(pairing.roles[3], FaceRole::Thickness { group: 0 });
    let rib = [(1, 2, Convexity::Concave, 20.0), (1, 3, Convexity::Concave, 20.0)];
    let mut faces = slab_faces(3.0);
    faces.extend(web(3.0));
    let pairing = detect(&graph_with_lengths(faces, &rib), &tol(), &[true; 4]);
    assert_eq!(pairing.pairs.iter().map(|p| p.faces).collect::<Vec<_>>(), vec![[0, 1], [2, 3]]);
}

#[test]
fn a_face_spanning_a_plate_facing_a_pocket_inside_it_is_the_plate_not_a_wall() {
    // The 3.0 slab (bottom 0, top 1); face 2 spans it (meets both skins: its rim, or a rib's top), face 3 faces
    // it 1.5 away, lying inside the slab (a bore's ceiling, a pocket's side): the plate's own material. When
    // face 3 reaches out of the slab (z 0.5..4.5), the material between is no longer the plate's: a wall.
    let pocket = |height: f64| {
        vec![
            rect(DVec3::new(20.0, 10.0, 0.0), DVec3::Z * 3.0, DVec3::Y * 20.0, -DVec3::X),
            rect(DVec3::new(21.5, 10.0, 0.5), DVec3::Y * 20.0, DVec3::Z * height, DVec3::X),
        ]
    };
    let spans = [(0, 2, Convexity::Convex, 20.0), (1, 2, Convexity::Convex, 20.0)];
    let mut faces = slab_faces(3.0);
    faces.extend(pocket(2.0));
    let pairing = detect(&graph_with_lengths(faces, &spans), &tol(), &[true; 4]);
    assert_eq!(pairing.pairs.iter().map(|p| p.faces).collect::<Vec<_>>(), vec![[0, 1]]);
    let mut faces = slab_faces(3.0);
    faces.extend(pocket(4.0));
    let pairing = detect(&graph_with_lengths(faces, &spans), &tol(), &[true; 4]);
    assert_eq!(pairing.pairs.iter().map(|p| p.faces).collect::<Vec<_>>(), vec![[0, 1], [2, 3]]);
}

#[test]
fn a_flat_skin_split_along_a_line_is_one_skin_for_the_stub_test() {
    // A 60 x 40 plate 2.5 thick whose top is two faces in one plane, split 2 from its edge (a sketch's line):
    // the 2 wide strip alone is narrower than the wall is thick and stands proud, but it is a piece of the
    // plate's top, not the top of a stub, and pairs with the bottom.
    let faces = vec![
        rect(DVec3::ZERO, DVec3::Y * 40.0, DVec3::X * 60.0, -DVec3::Z),
        rect(DVec3::Z * 2.5, DVec3::X * 60.0, DVec3::Y * 2.0, DVec3::Z),
        rect(DVec3::new(0.0, 2.0, 2.5), DVec3::X * 60.0, DVec3::Y * 38.0, DVec3::Z),
    ];
    let edges = [(1, 2, Convexity::Smooth, 60.0), (0, 1, Convexity::Convex, 64.0), (0, 2, Convexity::Convex, 136.0)];
    let g = graph_with_lengths(faces, &edges);
    let p = criteria::test_pair(&g, 0, 1, &tol()).unwrap();
    assert!((p.thickness.mean - 2.5).abs() < 1e-9);
    // The same strip with a step between it and the rest (not in one plane) stays the top of a stub.
    let mut faces = g.faces.clone();
    faces[2] = rect(DVec3::new(0.0, 2.0, 2.0), DVec3::X * 60.0, DVec3::Y * 38.0, DVec3::Z);
    let g = graph_with_lengths(faces, &edges);
    let err = criteria::test_pair(&g, 0, 1, &tol()).unwrap_err();
    assert!(matches!(err, Rejection::Stub { top: true, .. }), "{err:?}");
}
