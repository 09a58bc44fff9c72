//! `midsurf batch` from the outside: same outputs as `midsurf run`, whatever the number of workers; resuming;
//! shards that cover a manifest exactly; manifest errors before any part runs.

mod common;

use std::path::{Path, PathBuf};

use common::{midsurf, outcome, read_json, root, scratch};

fn batch(source: &Path, out: &Path, extra: &[&str]) -> common::Outcome {
    let mut cmd = midsurf();
    cmd.arg("batch").arg(source).arg("-o").arg(out).args(extra);
    outcome(&mut cmd)
}

/// A folder holding copies of some fixtures.
fn folder_of(dir: &Path, fixtures: &[&str]) -> PathBuf {
    let inputs = dir.join("in");
    std::fs::create_dir_all(&inputs).unwrap();
    for f in fixtures {
        std::fs::copy(root().join("fixtures").join(format!("{f}.step")), inputs.join(format!("{f}.step"))).unwrap();
    }
    inputs
}

/// A report without what legitimately differs between two runs: the times and the output path.
fn comparable(path: &Path) -> serde_json::Value {
    let mut report = read_json(path);
    let map = report.as_object_mut().unwrap();
    map.remove("timings_s");
    map.remove("output");
    report
}

fn summary_rows(path: &Path) -> Vec<serde_json::Value> {
    read_json(path)["parts"].as_array().unwrap().clone()
}

#[test]
fn outputs_are_those_of_run_with_one_or_two_workers() {
    let dir = scratch("batch-j");
    let inputs = folder_of(&dir, &["flat_plate", "l_bracket"]);
    let (one, two) = (dir.join("j1"), dir.join("j2"));
    let o = batch(&inputs, &one, &["-j", "1"]);
    assert_eq!(o.code, 0, "{}", o.stderr);
    let o = batch(&inputs, &two, &["-j", "2"]);
    assert_eq!(o.code, 0, "{}", o.stderr);
    assert!(o.stderr.contains("2 parts (2 ran, 0 reused): 2 clean"), "{}", o.stderr);
    for name in ["flat_plate", "l_bracket"] {
        let (step, json) = (format!("{name}.step"), format!("{name}.json"));
        let by_hand = (dir.join(&step), dir.join(&json));
        let mut cmd = midsurf();
        cmd.arg("run").arg(inputs.join(&step)).arg("-o").arg(&by_hand.0).arg("--report").arg(&by_hand.1);
        assert_eq!(outcome(&mut cmd).code, 0);
        let bytes = std::fs::read(&by_hand.0).unwrap();
        assert!(bytes == std::fs::read(one.join(&step)).unwrap(), "{name}: -j 1 STEP differs from run's");
        assert!(bytes == std::fs::read(two.join(&step)).unwrap(), "{name}: -j 2 STEP differs from run's");
        assert_eq!(comparable(&by_hand.1), comparable(&one.join(&json)), "{name}: -j 1 report");
        assert_eq!(comparable(&by_hand.1), comparable(&two.join(&json)), "{name}: -j 2 report");
    }
    // The summaries agree but for the times, in name order.
    let strip = |rows: Vec<serde_json::Value>| -> Vec<serde_json::Value> {
        rows.into_iter()
            .map(|mut r| {
                r.as_object_mut().unwrap().remove("time_s");
                r
            })
            .collect()
    };
    let rows = strip(summary_rows(&one.join("batch-summary.json")));
    assert_eq!(rows, strip(summary_rows(&two.join("batch-summary.json"))));
    let names: Vec<&str> = rows.iter().map(|r| r["part"].as_str().unwrap()).collect();
    assert_eq!(names, ["flat_plate", "l_bracket"]);
    assert_eq!((rows[1]["patches"].as_u64(), rows[1]["exit"].as_u64()), (Some(2), Some(0)));
    let csv = std::fs::read_to_string(two.join("batch-summary.csv")).unwrap();
    assert_eq!(csv.lines().count(), 3, "header and a row per part");
}

#[test]
fn a_rerun_skips_what_is_unchanged_and_runs_what_changed() {
    let dir = scratch("batch-resume");
    let inputs = folder_of(&dir, &["flat_plate"]);
    // A manifest: the plate twice under two names (the second with its own option), a file that is not STEP
    // (fails the same way every time) and a missing file (may turn up: always tried again).
    let manifest = inputs.join("parts.csv");
    let not_step = root().join("tests/data/not_step.step");
    let write = |t_max: &str| {
        let text = format!(
            "input,name,t_max\nflat_plate.step,,\nflat_plate.step,plate_t5,{t_max}\nmissing.step,,\n{},,\n",
            not_step.display()
        );
        std::fs::write(&manifest, text).unwrap();
    };
    write("5");
    let out = dir.join("out");
    let o = batch(&manifest, &out, &[]);
    assert_eq!(o.code, 2, "worst of the parts: the missing file fails\n{}", o.stderr);
    assert!(o.stderr.contains("4 ran, 0 reused"), "{}", o.stderr);
    let rows = summary_rows(&out.join("batch-summary.json"));
    assert!(rows[1]["error"].as_str().unwrap().contains("no such file"), "{:?}", rows[1]);
    assert_eq!((rows[0]["exit"].as_u64(), rows[3]["exit"].as_u64()), (Some(0), Some(0)));
    let step = out.join("flat_plate.step");
    let first = std::fs::metadata(&step).unwrap().modified().unwrap();

    let o = batch(&manifest, &out, &[]);
    assert_eq!(o.code, 2);
    assert!(o.stderr.contains("1 ran, 3 reused"), "nothing changed: only the missing file is tried\n{}", o.stderr);
    assert_eq!(std::fs::metadata(&step).unwrap().modified().unwrap(), first, "outputs untouched");

    // A changed option reruns that part; a removed output its part; --retry-failed the failure.
    write("4.5");
    std::fs::remove_file(&step).unwrap();
    let o = batch(&manifest, &out, &["--retry-failed"]);
    assert!(o.stderr.contains("4 ran, 0 reused"), "{}", o.stderr);
    // A changed input (same name, other content) reruns the parts made from it.
    let mut bytes = std::fs::read(inputs.join("flat_plate.step")).unwrap();
    bytes.extend_from_slice(b"\n");
    std::fs::write(inputs.join("flat_plate.step"), bytes).unwrap();
    let o = batch(&manifest, &out, &[]);
    assert!(o.stderr.contains("3 ran, 1 reused"), "{}", o.stderr);
    let rows = summary_rows(&out.join("batch-summary.json"));
    let status: Vec<&str> = rows.iter().map(|r| r["status"].as_str().unwrap()).collect();
    assert_eq!(status, ["ran", "ran", "reused", "ran"], "name order: flat_plate, missing, not_step, plate_t5");
}

#[test]
fn shards_cover_a_manifest_exactly() {
    let dir = scratch("batch-shard");
    // Missing files fail at once (before any sidecar starts), so the shards cost nothing but the split.
    let names: Vec<String> = (0..11).map(|i| format!("part{i:02}")).collect();
    let manifest = dir.join("parts.json");
    let list: Vec<String> = names.iter().rev().map(|n| format!("{{\"input\": \"{n}.step\"}}")).collect();
    std::fs::write(&manifest, format!("[{}]", list.join(","))).unwrap();
    let out = dir.join("out");
    let mut covered: Vec<String> = Vec::new();
    for i in 1..=4 {
        let o = batch(&manifest, &out, &["--shard", &format!("{i}/4"), "-j", "2"]);
        assert_eq!(o.code, 2, "{}", o.stderr);
        let rows = summary_rows(&out.join(format!("batch-summary-{i}-of-4.json")));
        assert!(rows.len() == 2 || rows.len() == 3, "balanced shards: {}", rows.len());
        covered.extend(rows.iter().map(|r| r["part"].as_str().unwrap().to_string()));
    }
    covered.sort();
    assert_eq!(covered, names, "every part in exactly one shard");
    assert_ne!(batch(&manifest, &out, &["--shard", "5/4"]).code, 0);
}

#[test]
fn a_bad_manifest_fails_before_any_part_runs() {
    let dir = scratch("batch-bad");
    let manifest = dir.join("parts.csv");
    std::fs::write(&manifest, "input,t_max\nfixtures/flat_plate.step,2\nfixtures/l_bracket.step,-1\n").unwrap();
    let o = batch(&manifest, &dir.join("out"), &[]);
    assert_eq!(o.code, 2);
    assert_eq!(o.stderr.lines().count(), 1, "one line: {}", o.stderr);
    assert!(o.stderr.contains("parts.csv: line 3") && o.stderr.contains("not a positive length"), "{}", o.stderr);
    assert!(!dir.join("out").exists(), "nothing written");
    std::fs::write(&manifest, "input\na/x.step\nb/x.step\n").unwrap();
    let o = batch(&manifest, &dir.join("out"), &[]);
    assert!(o.code == 2 && o.stderr.contains("two parts are named 'x'"), "{}", o.stderr);
    // The output folder is never the input folder (a part's output would overwrite its input).
    let inputs = folder_of(&dir, &["flat_plate"]);
    let o = batch(&inputs, &inputs, &[]);
    assert!(o.code == 2 && o.stderr.contains("input folder"), "{}", o.stderr);
}
