//! Reliability from the outside: one bad face never sinks a part, options and environment are checked up
//! front, the output set is written as one unit, and nothing is left behind (no file, no sidecar) on failure.

mod common;

use std::path::{Path, PathBuf};

use common::{midsurf, outcome, read_json, scratch, Outcome};

fn names_in(dir: &std::path::Path) -> Vec<String> {
    let mut names: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    names.sort();
    names
}

/// `midsurf run INPUT -o DIR/mid.step --report DIR/r.json EXTRA...`: its outcome and the report's path.
fn run_into(dir: &Path, input: &Path, extra: &[&str]) -> (Outcome, PathBuf) {
    let rep = dir.join("r.json");
    let mut cmd = midsurf();
    cmd.arg("run").arg(input).arg("-o").arg(dir.join("mid.step")).arg("--report").arg(&rep).args(extra);
    (outcome(&mut cmd), rep)
}

#[test]
fn a_face_with_no_point_inside_is_left_out_with_a_warning() {
    // The groove's floor is a ring 2e-6 wide: the kernel finds no point inside it (it made the run fail).
    let dir = scratch("rel-hairline");
    let (o, rep) = run_into(&dir, Path::new("fixtures/plate_hairline_groove.step"), &[]);
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

/// The failure contract for argument and environment problems: exit 2, one line, nothing on stdout.
fn one_line_error(o: &common::Outcome) -> String {
    assert_eq!(o.code, 2, "stderr: {}", o.stderr);
    assert!(o.stdout.is_empty(), "{}", o.stdout);
    let lines: Vec<&str> = o.stderr.lines().collect();
    assert_eq!(lines.len(), 1, "one line: {:?}", o.stderr);
    assert!(lines[0].starts_with("midsurf: error: "), "{}", lines[0]);
    lines[0].to_string()
}

#[test]
fn a_bad_timeout_in_the_environment_is_one_line_not_a_panic() {
    let dir = scratch("rel-timeout");
    let out = dir.join("mid.step");
    for bad in ["-1", "NaN", "inf", "1e30", "abc", "0"] {
        let o = outcome(midsurf().env("MIDSURF_TIMEOUT_SECS", bad).args([
            "run",
            "fixtures/flat_plate.step",
            "-o",
            out.to_str().unwrap(),
        ]));
        let line = one_line_error(&o);
        assert!(line.contains("MIDSURF_TIMEOUT_SECS"), "{bad}: {line}");
    }
    assert!(names_in(&dir).is_empty(), "nothing written");
}

#[test]
fn argument_errors_are_one_line_and_help_still_works() {
    for args in [&["run", "--bogus"][..], &["run", "fixtures/flat_plate.step"], &[], &["frobnicate"]] {
        one_line_error(&outcome(midsurf().args(args)));
    }
    let line = one_line_error(&outcome(midsurf().args(["run", "x.step", "-o", "y.step", "--t-max", "-1"])));
    assert!(line.contains("--t-max"), "{line}");
    for args in [&["--help"][..], &["--version"], &["run", "--help"]] {
        let o = outcome(midsurf().args(args));
        assert_eq!(o.code, 0, "{args:?}: {}", o.stderr);
        assert!(o.stdout.lines().count() >= 1, "{args:?}");
    }
}

#[test]
fn a_t_max_larger_than_the_part_is_refused_before_anything_is_written() {
    let dir = scratch("rel-tmax");
    let (o, _) = run_into(&dir, Path::new("fixtures/flat_plate.step"), &["--t-max", "1e9"]);
    assert!(one_line_error(&o).contains("larger than the part"), "{}", o.stderr);
    assert!(names_in(&dir).is_empty(), "nothing written");
}

/// flat_plate.step with `edit` applied to its lines, written to `dir/name`.
fn mutant(dir: &std::path::Path, name: &str, edit: impl Fn(&mut Vec<String>)) -> std::path::PathBuf {
    let text = std::fs::read_to_string(common::root().join("fixtures/flat_plate.step")).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    edit(&mut lines);
    let path = dir.join(name);
    std::fs::write(&path, lines.join("\n") + "\n").unwrap();
    path
}

#[test]
fn a_bad_entity_the_shape_does_not_use_is_a_warning_with_its_number() {
    let dir = scratch("rel-syntax");
    let input = mutant(&dir, "in.step", |lines| {
        let end = lines.iter().rposition(|l| l.starts_with("ENDSEC")).unwrap();
        lines.insert(end, "#9003 = CARTESIAN_POINT('',(1.,2.,3.),5.);".into());
    });
    let (o, rep) = run_into(&dir, &input, &[]);
    assert_eq!(o.code, 1, "{}", o.stderr);
    let report = read_json(&rep);
    let w: Vec<&serde_json::Value> =
        report["warnings"].as_array().unwrap().iter().filter(|w| w["code"] == "step_syntax").collect();
    assert_eq!(w.len(), 1, "{:?}", report["warnings"]);
    assert!(w[0]["message"].as_str().unwrap().contains("#9003"), "{}", w[0]);
}

#[test]
fn a_bad_entity_that_costs_the_solid_is_an_error_naming_it() {
    let dir = scratch("rel-syntax-used");
    // The fifth point of the plate gets a third parameter: the reader drops it, and the solid falls apart.
    let input = mutant(&dir, "in.step", |lines| {
        let k = lines.iter().enumerate().filter(|(_, l)| l.contains("CARTESIAN_POINT")).nth(4).unwrap().0;
        let end = lines[k].rfind("));").unwrap();
        lines[k].replace_range(end.., "),5.);");
    });
    let out = dir.join("mid.step");
    let o = outcome(midsurf().args(["run", input.to_str().unwrap(), "-o", out.to_str().unwrap()]));
    let line = one_line_error(&o);
    assert!(line.contains("no solid; the reader failed on entity #") && line.contains("cartesian_point"), "{line}");
    assert_eq!(names_in(&dir), ["in.step"]);
}
