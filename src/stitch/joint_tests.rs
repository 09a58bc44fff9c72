use super::*;
use glam::DVec3;

fn probe(hits: Vec<Vec<Hit>>) -> EdgeProbe {
    let n = hits.len();
    EdgeProbe { points: vec![DVec3::ZERO; n], normals: vec![DVec3::X; n], outward: vec![-DVec3::Z; n], hits }
}

fn hit(face: usize, distance: f64, gap: f64) -> Hit {
    Hit { face, distance, gap }
}

// Faces 0, 1 belong to patch 0 (the base), face 2 to patch 1 (the rib), face 3 to patch 2 (a far wall).
const PATCH_OF: [usize; 4] = [0, 0, 1, 2];
const THICKNESS: [f64; 3] = [2.0, 1.0, 1.0];

#[test]
fn an_edge_whose_outside_is_outside_the_solid_is_rim() {
    let mut p = probe(vec![vec![hit(0, 1.0, 0.0)]; 3]);
    p.points = vec![DVec3::new(0.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0), DVec3::new(2.0, 0.0, 0.0)];
    // Material only below z = -0.5 at x >= 1.5: one sample of three.
    let contains = |q: DVec3| q.z < -0.4 && q.x >= 1.5;
    assert!(!is_open(&p, 0.5, 0.0, |q, _| contains(q)));
    assert_eq!(decide(1, false, &p, &PATCH_OF, &THICKNESS, 3.0, true, |_, _| true), Verdict::Rim);
    assert!(is_open(&p, 0.5, 0.0, |q: DVec3, _| q.z < -0.4 && q.x >= 0.5));
}

#[test]
fn an_edge_on_a_skin_is_tested_at_the_middle_of_its_wall() {
    // A patch on the top skin z = 0 of a plate 2 thick ending at x = 5; its edge at x = 4 is open.
    let mut p = probe(vec![Vec::new(); 3]);
    p.points = (0..3).map(|k| DVec3::new(4.0, k as f64, 0.0)).collect();
    p.normals = vec![DVec3::Z; 3];
    p.outward = vec![DVec3::X; 3];
    let plate = |q: DVec3, _| q.z < 0.0 && q.z > -2.0 && q.x < 5.0;
    assert!(!is_open(&p, 0.5, 0.0, plate), "on the skin the test point is on the boundary");
    assert!(is_open(&p, 0.5, -1.0, plate));
    let short = |q: DVec3, n| plate(q, n) && q.x < 4.2;
    assert!(!is_open(&p, 0.5, -1.0, short), "the rim stays the rim");
}

#[test]
fn a_rib_edge_meeting_the_base_face_is_a_t_joint_with_overshoot() {
    let p = probe(vec![vec![hit(0, 1.0, 0.0)], vec![hit(1, 1.0, 0.0)], vec![hit(1, 1.0, 0.0), hit(3, 2.0, 0.0)]]);
    let Verdict::Extend(e) = decide(1, true, &p, &PATCH_OF, &THICKNESS, 3.0, true, |_, _| true) else { panic!() };
    assert_eq!(e.kind, JointKind::T);
    assert_eq!(e.partner, 0);
    assert_eq!(e.lengths, vec![1.5; 3]);
}

#[test]
fn meeting_the_support_past_the_boundary_is_an_l_joint() {
    let p = probe(vec![vec![hit(2, 0.5, 0.5)], vec![hit(2, 0.7, 0.5)]]);
    let Verdict::Extend(e) = decide(0, true, &p, &PATCH_OF, &THICKNESS, 3.0, true, |_, _| true) else { panic!() };
    assert_eq!(e.kind, JointKind::L);
    assert_eq!(e.partner, 1);
    assert_eq!(e.lengths, vec![0.75, 0.95]);
}

/// The section of fixture channel_thick_flanges: a flange's patch (patch 0, mid-plane x = 1.25) ends at z = 2.55,
/// facing -z; the web's patch (patch 1, 1.5 thick, z = 0.75) ends at x = 5; the corner between them is rounded
/// outside (R 5 about (5, 5)), so along x = 1.25 the material ends at z = 1.7.
/// Thicknesses of the flange (patch 0) and the web (patch 1).
const FLANGE_WEB: [f64; 3] = [2.5, 1.5, 1.5];

fn flange_over_rounded_corner(hits: Vec<Hit>) -> (EdgeProbe, impl Fn(DVec3) -> bool + Copy) {
    let mut p = probe(vec![hits; 3]);
    p.points = (0..3).map(|k| DVec3::new(1.25, 10.0 * k as f64, 2.55)).collect();
    p.outward = vec![-DVec3::Z; 3];
    let section = |q: DVec3| {
        let outer_round = q.x >= 5.0 || q.z >= 5.0 || (q.x - 5.0).powi(2) + (q.z - 5.0).powi(2) <= 25.0;
        outer_round && q.x >= 0.0 && q.z >= 0.0
    };
    (p, section)
}

#[test]
fn an_l_meeting_outside_the_material_is_no_joint_and_one_inside_is() {
    // The web's support at z = 0.75 lies 1.8 ahead, 3.75 past the web patch's end: the way there leaves the part.
    let (p, section) = flange_over_rounded_corner(vec![hit(2, 1.8, 3.75)]);
    let through = |k, length| through_material(&p, k, length, 0.625, 0.0, section);
    assert_eq!(decide(0, true, &p, &PATCH_OF, &FLANGE_WEB, 3.75, true, through), Verdict::Unresolved);
    // With a sharp outer corner the same meeting lies in the corner's block: an L-joint.
    let sharp = |q: DVec3| q.x >= 0.0 && q.z >= 0.0;
    let through = |k, length| through_material(&p, k, length, 0.625, 0.0, sharp);
    let Verdict::Extend(e) = decide(0, true, &p, &PATCH_OF, &FLANGE_WEB, 3.75, true, through) else { panic!() };
    assert_eq!((e.kind, e.partner), (JointKind::L, 1));
    // A partner's face met within the material (a T) needs the way only up to that wall's skin.
    let (p, section) = flange_over_rounded_corner(vec![hit(2, 1.2, 0.0)]);
    let through = |k, length| through_material(&p, k, length, 0.625, 0.0, section);
    let Verdict::Extend(e) = decide(0, true, &p, &PATCH_OF, &FLANGE_WEB, 3.75, true, through) else { panic!() };
    assert_eq!((e.kind, e.partner), (JointKind::T, 1));
}

#[test]
fn own_patch_and_out_of_reach_meetings_do_not_count() {
    let p = probe(vec![vec![hit(1, 0.5, 0.0), hit(3, 3.5, 0.0)], vec![hit(3, 1.0, 4.0)]]);
    assert_eq!(decide(0, true, &p, &PATCH_OF, &THICKNESS, 3.0, true, |_, _| true), Verdict::Unresolved);
}

#[test]
fn a_wall_across_a_void_is_no_partner_and_a_nearer_one_through_material_wins() {
    // A wall's edge at x = 0 (samples along y) facing +x: a ring's bore (void) over 1 < x < 3, its far
    // side (patch 2, 1 thick) at x = 4; a nearer wall through material is patch 1 (1 thick) at x = 0.9.
    let mut p = probe(vec![vec![hit(3, 4.0, 0.0)]; 3]);
    p.points = (0..3).map(|k| DVec3::new(0.0, k as f64, 0.0)).collect();
    p.outward = vec![DVec3::X; 3];
    let solid = |q: DVec3| q.x < 1.0 || q.x > 3.0;
    let through = |k, length| through_material(&p, k, length, 0.25, 0.0, solid);
    assert!(!through(1, 4.0 - 0.5), "the way to the far side crosses the bore");
    assert!(through(1, 0.9), "up to the bore it stays in the material");
    assert_eq!(decide(0, true, &p, &PATCH_OF, &THICKNESS, 5.0, true, through), Verdict::Unresolved);
    p.hits = vec![vec![hit(2, 0.9, 0.0), hit(3, 4.0, 0.0)]; 3];
    let through = |k, length| through_material(&p, k, length, 0.25, 0.0, solid);
    let Verdict::Extend(e) = decide(0, true, &p, &PATCH_OF, &THICKNESS, 5.0, true, through) else { panic!() };
    assert_eq!(e.partner, 1);
}

#[test]
fn an_end_of_the_edge_on_another_skin_is_tested_a_step_along_the_edge() {
    // A rib's edge standing on a base's top skin z = 0 at its end sample (k = 2 at z = 0): along that skin
    // the test reads material (boundary points count as inside here), a step up it reads the void.
    let mut p = probe(vec![Vec::new(); 3]);
    p.points = (0..3).map(|k| DVec3::new(0.0, 0.0, 2.0 - k as f64)).collect();
    p.outward = vec![DVec3::X; 3];
    let solid = |q: DVec3| q.z <= 0.0 || q.x < 0.5;
    assert!(!through_material(&p, 2, 2.0, 0.25, 0.0, solid));
    assert!(!through_material(&p, 1, 2.0, 0.25, 0.0, solid));
    assert!(through_material(&p, 1, 0.5, 0.25, 0.0, solid), "points before the length only");
}

#[test]
fn the_nearest_meeting_wins_and_samples_without_one_are_interpolated() {
    let p = probe(vec![
        vec![hit(2, 1.0, 0.0)],
        vec![],
        vec![hit(3, 0.5, 2.0), hit(2, 2.0, 0.0)],
        vec![hit(2, 3.0, 0.0)],
        vec![],
    ]);
    let Verdict::Extend(e) = decide(0, true, &p, &PATCH_OF, &THICKNESS, 3.0, true, |_, _| true) else { panic!() };
    assert_eq!(e.partner, 1);
    // Sample 2's best meeting is patch 2's support (0.5 + gap 2 = 2.5 > 2.0): patch 1 there too.
    assert_eq!(e.lengths, vec![1.25, 1.75, 2.25, 3.25, 3.25]);
}

#[test]
fn an_edge_short_of_the_boundary_grows_to_it_and_one_on_it_stays() {
    // Edge along x at z = 11.5 in a rib whose top is at z = 12 (rounded edges); outward +z.
    let mut p = probe(vec![vec![]; 3]);
    p.points = (0..3).map(|k| DVec3::new(k as f64, 0.0, 11.5)).collect();
    p.outward = vec![DVec3::Z; 3];
    let contains = |q: DVec3| q.z < 12.0;
    let exit = |q: DVec3, d: DVec3, _: DVec3| Some((12.0 - q.z) / d.z).filter(|&t| t <= 1.5);
    assert_eq!(rim_shortfall(&p, 0.0, 0.2, contains, exit), Some(vec![0.5; 3]));
    // One end on a boundary (a corner of the rim): a sliver there, never zero.
    let corner = |q: DVec3, d: DVec3, n: DVec3| if q.x > 1.5 { Some(0.0) } else { exit(q, d, n) };
    assert_eq!(rim_shortfall(&p, 0.0, 0.2, contains, corner), Some(vec![0.5, 0.5, 0.1]));
    assert_eq!(rim_shortfall(&p, 0.0, 0.6, contains, exit), None, "0.5 short counts as on the rim");
    p.points.iter_mut().for_each(|q| q.z = 12.0);
    assert_eq!(rim_shortfall(&p, 0.0, 0.2, contains, exit), None, "on the boundary");
    // Material on past the reach (another wall): no rim to grow to.
    p.points.iter_mut().for_each(|q| q.z = 5.0);
    assert_eq!(rim_shortfall(&p, 0.0, 0.2, contains, exit), None);
}

#[test]
fn gaps_fill_by_interpolation_and_holding() {
    assert_eq!(fill_gaps(&[None, Some(1.0), None, Some(3.0), None]), vec![1.0, 1.0, 2.0, 3.0, 3.0]);
}

#[test]
fn a_rib_end_standing_above_the_boss_it_runs_into_grows_only_where_it_meets_the_boss() {
    // A rib's end edge at x = 0 (samples up z, facing -x) running into a tube (patch 1) 1.2 away up to z = 2:
    // the boss's top. Above it the way out leaves the material at once: a stub there, not the lower samples'
    // length (before, the strip ran on over the boss's top, out of the material).
    let mut p = probe((0..5).map(|k| if k < 3 { vec![hit(2, 1.2, 0.0)] } else { Vec::new() }).collect());
    p.points = (0..5).map(|k| DVec3::new(0.0, 0.0, k as f64)).collect();
    p.outward = vec![-DVec3::X; 5];
    let solid = |q: DVec3| q.z <= 2.2 || q.x > 0.0;
    let through = |k, length| through_material(&p, k, length, 0.25, 0.0, solid);
    let Verdict::Extend(e) = decide(0, true, &p, &PATCH_OF, &THICKNESS, 3.0, true, through) else { panic!() };
    let full = 1.2 + OVERSHOOT * THICKNESS[1];
    assert_eq!(e.lengths, vec![full, full, full, RIM_STUB * 2.0, RIM_STUB * 2.0]);
    // Without stubs (a curved edge of a freeform patch), the lengths are filled in from the neighbours.
    let Verdict::Extend(e) = decide(0, true, &p, &PATCH_OF, &THICKNESS, 3.0, false, through) else { panic!() };
    assert_eq!(e.lengths, vec![full; 5]);
}

#[test]
fn only_runs_at_the_ends_of_the_edge_grow_stubs() {
    // A sample inside the edge that met nothing is filled in (a ray that slipped between faces); the run at the
    // end is the stretch past the partner's wall.
    let reached = vec![Some(1.0), None, Some(1.0), None, None];
    let on_rim = [false, true, false, true, true];
    assert_eq!(stubs_at_ends(reached, |k| on_rim[k], 0.1), vec![Some(1.0), None, Some(1.0), Some(0.1), Some(0.1)]);
}

#[test]
fn a_way_shorter_than_a_step_is_tested_halfway() {
    // A rib's end at x = 0 (samples up z, facing -x) beside a boss whose wall begins 0.25 away and whose top is
    // at z = 1.5: a sample at z = 2 (over the boss) is 0.25 from the boss's wall through air, one at z = 1
    // through material; the step (0.45) is longer than the way.
    let mut p = probe(vec![Vec::new(); 3]);
    p.points = (0..3).map(|k| DVec3::new(0.0, 0.0, k as f64)).collect();
    p.outward = vec![-DVec3::X; 3];
    p.normals = vec![DVec3::Y; 3];
    let rib_and_boss = |q: DVec3| q.z < 1.5 || q.x >= 0.0;
    let through = |k, length| through_material(&p, k, length, 0.45, 0.0, rib_and_boss);
    assert!(through(1, 0.25), "below the boss's top the way runs through the boss");
    assert!(!through(2, 0.25), "above it the way runs through air");
    assert!(through(2, 0.0), "no way at all is no crossing");
}

#[test]
fn a_partner_ending_part_way_along_the_edge_leaves_rim_ends() {
    // Samples 0..2 meet the partner's face; 3 and 4 meet nothing and their way out leaves the material at once.
    let mut hits = vec![vec![hit(2, 1.0, 0.0)]; 3];
    hits.extend(vec![Vec::new(); 2]);
    let p = probe(hits);
    let through = |k: usize, _| k < 3;
    let Verdict::Extend(e) = decide(0, true, &p, &PATCH_OF, &THICKNESS, 3.0, true, through) else { panic!() };
    assert!(e.rim_ends);
    let p = probe(vec![vec![hit(2, 1.0, 0.0)]; 5]);
    let Verdict::Extend(e) = decide(0, true, &p, &PATCH_OF, &THICKNESS, 3.0, true, |_, _| true) else { panic!() };
    assert!(!e.rim_ends);
}
