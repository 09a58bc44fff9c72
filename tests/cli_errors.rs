//! Bad input and a broken sidecar: exit code 2, one line `midsurf: error: <file>: <what went wrong>`, no hang.

mod common;

use common::{midsurf, outcome, root, scratch};

/// Runs `midsurf inspect <path>` and checks the failure contract; returns the error line.
fn fails_with_one_line(cmd: &mut assert_cmd::Command, path: &str) -> String {
    let out = outcome(cmd.timeout(std::time::Duration::from_secs(120)));
    assert_eq!(out.code, 2, "stderr: {}", out.stderr);
    assert!(out.stdout.is_empty(), "nothing on stdout: {}", out.stdout);
    let lines: Vec<&str> = out.stderr.lines().collect();
    assert_eq!(lines.len(), 1, "one line: {:?}", out.stderr);
    let prefix = format!("midsurf: error: {path}: ");
    assert!(lines[0].starts_with(&prefix), "{:?} should start with {prefix:?}", lines[0]);
    lines[0][prefix.len()..].to_string()
}

fn inspect(path: &str) -> String {
    fails_with_one_line(midsurf().args(["inspect", path]), path)
}

#[test]
fn missing_file() {
    assert_eq!(inspect("fixtures/nope.step"), "no such file");
}

#[test]
fn directory() {
    assert_eq!(inspect("fixtures"), "is a directory, not a STEP file");
}

#[test]
fn empty_file() {
    assert_eq!(inspect("tests/data/empty.step"), "is empty, not a STEP file");
}

#[test]
fn text_that_is_not_step() {
    let why = inspect("tests/data/not_step.step");
    assert!(why.contains("not a readable STEP file") || why.contains("STEP"), "{why}");
}

#[test]
fn truncated_step() {
    let why = inspect("tests/data/truncated.step");
    assert!(why.contains("STEP") || why.contains("solid"), "{why}");
}

#[test]
fn surfaces_without_a_solid() {
    let why = inspect("tests/data/faces_only.step");
    assert!(why.contains("no solid"), "{why}");
    assert!(why.contains("1 face"), "says what the file has instead: {why}");
}

#[test]
fn bad_file_at_a_path_with_spaces_and_non_ascii() {
    let dir = scratch("bad path");
    let path = dir.join("pièce vide ü.step");
    std::fs::write(&path, "").unwrap();
    inspect(path.to_str().unwrap());
}

#[test]
fn good_file_at_a_path_with_spaces_and_non_ascii() {
    let dir = scratch("good path");
    let path = dir.join("plaque épaisse ü.step");
    std::fs::copy(root().join("fixtures/flat_plate.step"), &path).unwrap();
    let out = outcome(midsurf().args(["inspect", path.to_str().unwrap()]));
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert!(out.stdout.contains("6 faces"), "{}", out.stdout);
}

#[test]
fn sidecar_that_dies_mid_request() {
    let why = fails_with_one_line(
        midsurf()
            .env("MIDSURF_PYTHON", root().join("tests/fake/dying_python"))
            .args(["inspect", "fixtures/flat_plate.step"]),
        "fixtures/flat_plate.step",
    );
    // Dying while reading is the reader crashing on the file (issue 25), said as such.
    assert_eq!(
        why,
        "the STEP reader crashed on this file; it is probably corrupt (sidecar stderr: Fatal Python error: \
         Segmentation fault)"
    );
}

#[test]
fn sidecar_that_hangs_is_stopped() {
    let why = fails_with_one_line(
        midsurf()
            .env("MIDSURF_PYTHON", root().join("tests/fake/hanging_python"))
            .env("MIDSURF_TIMEOUT_SECS", "2")
            .args(["inspect", "fixtures/flat_plate.step"]),
        "fixtures/flat_plate.step",
    );
    assert_eq!(why, "the OCCT sidecar did not answer 'load_step' within 2 s and was stopped");
}

#[test]
fn python_without_ocp_names_the_setup_command() {
    let real = root().join(".venv/bin/python");
    let why = fails_with_one_line(
        midsurf()
            .env("MIDSURF_PYTHON", root().join("tests/fake/python_without_ocp"))
            .env("MIDSURF_TEST_REAL_PYTHON", real)
            .args(["inspect", "fixtures/flat_plate.step"]),
        "fixtures/flat_plate.step",
    );
    assert!(why.contains("OCP") && why.contains("scripts/setup"), "{why}");
}

#[test]
fn sidecar_of_another_protocol_version() {
    let why = fails_with_one_line(
        midsurf()
            .env("MIDSURF_PYTHON", root().join("tests/fake/old_protocol_python"))
            .args(["inspect", "fixtures/flat_plate.step"]),
        "fixtures/flat_plate.step",
    );
    assert!(why.contains("protocol") && why.contains("scripts/setup"), "{why}");
}

#[test]
fn missing_python_says_how_to_fix() {
    let why = fails_with_one_line(
        midsurf().env("MIDSURF_PYTHON", "/nonexistent/python").args(["inspect", "fixtures/flat_plate.step"]),
        "fixtures/flat_plate.step",
    );
    assert!(why.contains("MIDSURF_PYTHON"), "{why}");
}

#[test]
fn bad_option_values_are_usage_errors() {
    let out = outcome(midsurf().args(["pairs", "fixtures/flat_plate.step", "--t-max", "0"]));
    assert_eq!(out.code, 2);
    assert!(out.stderr.contains("not a positive length"), "{}", out.stderr);
}
