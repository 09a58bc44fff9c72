//! Reliability from the outside: one bad face never sinks a part, options and environment are checked up
//! front, the output set is written as one unit, and nothing is left behind (no file, no sidecar) on failure.

mod common;

use common::{midsurf, outcome, read_json, scratch};

fn names_in(dir: &std::path::Path) -> Vec<String> {
    let mut names: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    names.sort();
    names
}

#[test]
fn a_face_with_no_point_inside_is_left_out_with_a_warning() {
    // The groove's floor is a ring 2e-6 wide: the kernel finds no point inside it (it made the run fail).
    let dir = scratch("rel-hairline");
    let (out, rep) = (dir.join("mid.step"), dir.join("r.json"));
    let o = outcome(midsurf().args([
        "run",
        "fixtures/plate_hairline_groove.step",
        "-o",
        out.to_str().unwrap(),
        "--report",
        rep.to_str().unwrap(),
    ]));
    assert_eq!(o.code, 1, "{}", o.stderr);
    let report = read_json(&rep);
    let left_out: Vec<&serde_json::Value> =
        report["warnings"].as_array().unwrap().iter().filter(|w| w["code"] == "face_not_described").collect();
    assert_eq!(left_out.len(), 1, "{:?}", report["warnings"]);
    assert_eq!(left_out[0]["solid"], 1);
    assert!(left_out[0]["message"].as_str().unwrap().contains("no point inside the face"), "{}", left_out[0]);
    // The plate itself is still there: one patch, its whole area less the groove.
    assert!(!report["patches"].as_array().unwrap().is_empty());
    assert!(report["result"]["area"].as_f64().unwrap() > 0.99 * 300.0 * 300.0, "{}", report["result"]);
    assert_eq!(names_in(&dir), ["mid.step", "r.json"]);
}
