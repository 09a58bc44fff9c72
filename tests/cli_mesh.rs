//! `midsurf mesh` from the outside: decks written, ids from --start-id, byte-identical reruns, the criteria
//! gate on the exit code, one-line errors with nothing written. (The decks' contents are read back by
//! independent readers in sidecar/tests/test_mesh_decks.py.)

mod common;

use std::path::{Path, PathBuf};

use common::{midsurf, outcome, read_json, scratch};

/// The t_rib fixture's mid-surface and report, made once per test in `dir`.
fn t_rib(dir: &Path) -> (PathBuf, PathBuf) {
    let (mid, rep) = (dir.join("mid.step"), dir.join("mid.json"));
    let o = outcome(midsurf().args([
        "run",
        "fixtures/t_rib.step",
        "-o",
        mid.to_str().unwrap(),
        "--report",
        rep.to_str().unwrap(),
        "--no-timings",
    ]));
    assert_eq!(o.code, 0, "{}", o.stderr);
    (mid, rep)
}

fn mesh(mid: &Path, rep: &Path, base: &Path, extra: &[&str]) -> common::Outcome {
    let mut cmd = midsurf();
    cmd.args(["mesh", mid.to_str().unwrap(), "--report", rep.to_str().unwrap(), "-o", base.to_str().unwrap()])
        .args(extra);
    outcome(&mut cmd)
}

fn files(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    names.sort();
    names
}

#[test]
fn decks_are_byte_identical_on_a_rerun_and_ids_start_where_asked() {
    let dir = scratch("mesh-rerun");
    let (mid, rep) = t_rib(&dir);
    let o = mesh(&mid, &rep, &dir.join("a"), &["--size", "5"]);
    assert_eq!(o.code, 0, "{}", o.stderr);
    let o = mesh(&mid, &rep, &dir.join("b"), &["--size", "5"]);
    assert_eq!(o.code, 0, "{}", o.stderr);
    for ext in ["k", "bdf", "inp"] {
        let a = std::fs::read(dir.join(format!("a.{ext}"))).unwrap();
        let b = std::fs::read(dir.join(format!("b.{ext}"))).unwrap();
        assert!(a == b, "{ext} differs between two runs");
    }
    let q = read_json(&dir.join("a.quality.json"));
    let elements = q["total"]["elements"].as_u64().unwrap();
    assert!(elements > 100, "{elements} elements on a 100 x 60 plate with a rib at 5 mm");
    assert_eq!(q["total"]["t_edges"]["length"].as_f64().unwrap().round(), 60.0, "the rib's joint conforms");
    assert_eq!(q["parts"].as_array().unwrap().len(), 1);
    assert_eq!(q["meshing"]["address_layout"], "fixed", "gmsh without address randomisation: reruns repeat");

    // A second part's deck starts at 1000001: its ids never meet the first one's.
    let o = mesh(&mid, &rep, &dir.join("c"), &["--size", "5", "--start-id", "1000001", "--format", "k"]);
    assert_eq!(o.code, 0, "{}", o.stderr);
    let k = std::fs::read_to_string(dir.join("c.k")).unwrap();
    let first_node = k.lines().skip_while(|l| *l != "*NODE").nth(2).unwrap();
    assert!(first_node.starts_with(" 1000001"), "{first_node}");
    let q = read_json(&dir.join("c.quality.json"));
    assert_eq!(q["ids"][0], 1000001);
    assert!(q["ids"][1].as_u64().unwrap() >= 1000000 + elements);
    assert!(files(&dir).iter().all(|f| !f.contains("tmp")), "no temporary left: {:?}", files(&dir));
    assert!(!dir.join("c.bdf").exists(), "--format k writes the keyword deck only");
}

#[test]
fn a_failed_criterion_exits_1_and_names_its_patches() {
    let dir = scratch("mesh-criteria");
    let (mid, rep) = t_rib(&dir);
    let strict = dir.join("strict.json");
    // No element edge reaches 10 mm at a 5 mm target: every patch fails.
    std::fs::write(&strict, r#"{"min_edge": 10.0, "mass_ratio": [0.98, 1.02]}"#).unwrap();
    let o = mesh(&mid, &rep, &dir.join("m"), &["--size", "5", "--criteria", strict.to_str().unwrap()]);
    assert_eq!(o.code, 1, "{}", o.stderr);
    let q = read_json(&dir.join("m.quality.json"));
    assert_eq!(q["passed"], false);
    let by_name = |n: &str| q["criteria"].as_array().unwrap().iter().find(|c| c["criterion"] == n).unwrap().clone();
    assert_eq!(by_name("min_edge")["passed"], false);
    assert_eq!(by_name("min_edge")["culprit_patches"], serde_json::json!([1, 2]));
    // t_rib's shell volume is 7260 mm2 x 2 mm over 14400 mm3: 1.0083, inside 2%.
    assert_eq!(by_name("mass_ratio")["passed"], true);
    assert!((by_name("mass_ratio")["value"].as_f64().unwrap() - 1.00833).abs() < 1e-3);
}

#[test]
fn a_report_that_is_not_midsurfs_stops_with_one_line_and_writes_nothing() {
    let dir = scratch("mesh-bad-report");
    let (mid, _) = t_rib(&dir);
    let bad = dir.join("bad.json");
    std::fs::write(&bad, "{\"patches\": 3}").unwrap();
    let o = mesh(&mid, &bad, &dir.join("m"), &[]);
    assert_eq!(o.code, 2);
    assert_eq!(o.stderr.lines().count(), 1, "{}", o.stderr);
    assert!(o.stderr.contains("bad.json") && o.stderr.contains("not a midsurf run report"), "{}", o.stderr);
    assert_eq!(files(&dir), ["bad.json", "mid.json", "mid.step"]);
    // An unknown criterion is refused the same way, not ignored.
    let criteria = dir.join("c.json");
    std::fs::write(&criteria, r#"{"min_edgee": 1}"#).unwrap();
    let o = mesh(&mid, &dir.join("mid.json"), &dir.join("m"), &["--criteria", criteria.to_str().unwrap()]);
    assert_eq!(o.code, 2);
    assert!(o.stderr.contains("c.json") && o.stderr.contains("min_edgee"), "{}", o.stderr);
}

/// A face gmsh cannot mesh (MIDSURF_TEST_MESHER makes gmsh surface 1 fail or hang in every attempt): the other
/// face is meshed on its own, the decks are written without the lost one, and the quality report names it
/// (patch, area) with a failed criterion: exit 1, not 2.
fn a_lost_face_is_named_and_the_decks_are_still_written(fault: &str, whole_model: &str) {
    let dir = scratch(&format!("mesh-lost-{}", fault.replace(':', "-")));
    let (mid, rep) = t_rib(&dir);
    let mut cmd = midsurf();
    cmd.env("MIDSURF_TEST_MESHER", fault).args([
        "mesh",
        mid.to_str().unwrap(),
        "--report",
        rep.to_str().unwrap(),
        "-o",
        dir.join("m").to_str().unwrap(),
        "--size",
        "5",
    ]);
    let o = outcome(&mut cmd);
    assert_eq!(o.code, 1, "{}", o.stderr);
    for ext in ["k", "bdf", "inp"] {
        assert!(dir.join(format!("m.{ext}")).is_file(), "m.{ext} written");
    }
    let q = read_json(&dir.join("m.quality.json"));
    assert!(q["meshing"]["whole_model"].as_str().unwrap().starts_with(whole_model), "{}", q["meshing"]);
    // gmsh's surface 3 is t_rib's rib (patch 2, 60 x 21 mm), written last: the plate's two faces (either side
    // of the rib) make one manifold shell, the rib another. The plate's faces are meshed one by one.
    assert_eq!(q["meshing"]["retried"].as_array().unwrap().len(), 2, "{}", q["meshing"]);
    let lost = q["unmeshed_faces"].as_array().unwrap();
    assert_eq!(lost.len(), 1, "{lost:?}");
    assert_eq!(lost[0]["patch"], 2);
    assert!((lost[0]["area"].as_f64().unwrap() - 1260.0).abs() < 1e-6, "{lost:?}");
    let unmeshed = q["criteria"].as_array().unwrap().iter().find(|c| c["criterion"] == "unmeshed_faces").unwrap();
    assert_eq!(unmeshed["passed"], false);
    assert_eq!(unmeshed["culprit_patches"], serde_json::json!([2]));
    assert_eq!(q["parts"][0]["t_edges"]["count"], 0, "the plate alone: no T-joint");
    // The plate's two faces still share their nodes along the rib's line: no free edge there, only the rim.
    assert!((q["parts"][0]["free_edges"]["length"].as_f64().unwrap() - 320.0).abs() < 1e-6, "{}", q["parts"][0]);
}

#[test]
fn a_face_gmsh_fails_on_is_left_out_and_named() {
    a_lost_face_is_named_and_the_decks_are_still_written("fail:3", "failed: injected failure on surface 3");
}

#[test]
fn a_face_gmsh_hangs_on_is_given_up_after_its_time_limit() {
    a_lost_face_is_named_and_the_decks_are_still_written("hang:3", "failed: timed out after 1 s");
}

#[test]
fn thickness_bands_give_walls_of_nearly_one_thickness_one_name_one_colour_and_one_section() {
    let dir = scratch("mesh-bands");
    let sections = |bands: &[&str], name: &str| {
        let (mid, rep, csv) = (dir.join(format!("{name}.step")), dir.join(format!("{name}.json")), dir.join("p.csv"));
        let mut run = midsurf();
        run.args(["run", "fixtures/channel_thick_flanges.step", "-o", mid.to_str().unwrap()])
            .args(["--report", rep.to_str().unwrap(), "--csv", csv.to_str().unwrap()])
            .args(bands);
        let o = outcome(&mut run);
        assert_eq!(o.code, 0, "{}", o.stderr);
        let o = mesh(&mid, &rep, &dir.join(name), &["--size", "5", "--format", "k"]);
        assert_eq!(o.code, 0, "{}", o.stderr);
        let k = std::fs::read_to_string(dir.join(format!("{name}.k"))).unwrap();
        let report = read_json(&rep);
        let written: Vec<f64> =
            report["patches"].as_array().unwrap().iter().map(|p| p["band"].as_f64().unwrap()).collect();
        let csv = std::fs::read_to_string(&csv).unwrap();
        (k.matches("*SECTION_SHELL").count(), report["thickness_legend"].as_array().unwrap().len(), written, csv)
    };
    // The web and rounds are 1.5 thick, the flanges 2.5: two thicknesses, two sections, two colours.
    let (n, colours, written, _) = sections(&[], "fine");
    assert_eq!((n, colours), (2, 2));
    assert_eq!(written, [2.5, 1.5, 1.5, 1.5, 2.5]);
    // Bands 2 mm wide: both are written as 2.0 (the nearest multiple), in one section and one colour.
    let (n, colours, written, csv) = sections(&["--t-bands", "2"], "coarse");
    assert_eq!((n, colours), (1, 1));
    assert!(written.iter().all(|&t| t == 2.0), "{written:?}");
    assert!(csv.lines().skip(1).all(|l| l.split(',').nth(3) == Some("2.000")), "{csv}");
    let step = std::fs::read_to_string(dir.join("coarse.step")).unwrap();
    assert!(step.contains("patch 1 t=2.000") && !step.contains("t=2.500"));
}
