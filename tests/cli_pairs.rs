//! `midsurf pairs --explain`: why a face pairs or not, from the pair tests themselves.

mod common;

use common::{midsurf, outcome};

fn explain(part: &str, face: &str) -> common::Outcome {
    outcome(midsurf().args(["pairs", part, "--explain", face]))
}

#[test]
fn a_paired_face_is_explained_by_its_partners_and_the_thickness_measured() {
    let out = explain("fixtures/plate_thick_pad.step", "1:10");
    assert_eq!(out.code, 0, "stderr: {}", out.stderr);
    // The pad over the plate: 4 mm thick where t_max is 2.25, a wall since it is thin for its extent.
    assert!(out.stdout.starts_with("face 10 (plane, 2500.00 mm2"), "{}", out.stdout);
    assert!(out.stdout.contains("with face 4 (plane, 33600.00 mm2"), "{}", out.stdout);
    assert!(out.stdout.contains("pair (parallel, t 4.0000"), "{}", out.stdout);
    assert!(out.stdout.contains("in the end: pair, group 0, with faces 4"), "{}", out.stdout);
}

#[test]
fn an_unpaired_face_names_the_rule_that_dropped_its_pair() {
    // The lip's narrow face passes the pair tests with the wall's far skin; the rules among the walls around
    // it make it a minor level: both show.
    let out = explain("fixtures/plate_lip.step", "1:2");
    assert_eq!(out.code, 0, "stderr: {}", out.stderr);
    assert!(out.stdout.contains("in the end: unpaired: best candidate face 5"), "{}", out.stdout);
    assert!(out.stdout.contains("a minor level"), "{}", out.stdout);
}

#[test]
fn a_face_or_solid_out_of_range_is_a_one_line_error() {
    for (arg, problem) in
        [("1:99", "solid 1 has 11 faces (0 to 10), no face 99"), ("2:0", "has 1 solid(s), no solid 2")]
    {
        let out = explain("fixtures/plate_thick_pad.step", arg);
        assert_eq!(out.code, 2, "stderr: {}", out.stderr);
        assert_eq!(
            out.stderr.trim(),
            format!("midsurf: error: fixtures/plate_thick_pad.step: {problem} to --explain"),
            "{arg}"
        );
    }
    let out = explain("fixtures/plate_thick_pad.step", "10");
    assert_eq!(out.code, 2, "stderr: {}", out.stderr);
    assert!(out.stderr.contains("'10' is not SOLID:FACE"), "{}", out.stderr);
}

#[test]
fn a_t_max_equal_to_the_gauge_pairs_every_wall_of_that_gauge() {
    // A drafted, rounded box 2 thick: its walls measure 2 give or take the kernel's rounding. Given as
    // --t-max, the gauge pairs them all, as the estimate (3 here) does.
    let out = outcome(midsurf().args(["pairs", "fixtures/box_drafted_rounded.step", "--t-max", "2"]));
    assert_eq!(out.code, 0, "stderr: {}", out.stderr);
    assert!(
        out.stdout.contains("roles: pair 18, thickness 1, connecting 0, suppressed 0, unpaired 0"),
        "{}",
        out.stdout
    );
    assert!(out.stdout.contains("paired: 97.3% of the area"), "{}", out.stdout);
}
