//! Fault injection: the sidecar killed in the middle of an operation, and midsurf itself stopped (SIGTERM)
//! or killed (SIGKILL) mid-run. Each must end with a clear error, no sidecar left running and no file left.
//! The sidecar is held at a known point by its test hook MIDSURF_TEST_STALL="OP:MARKER" (it runs OP, writes
//! its pid to MARKER, and hangs).

#![cfg(unix)]

mod common;

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use common::{root, scratch};

/// `midsurf run fixtures/flat_plate.step` into `dir`, the sidecar stalling after `op`.
fn start(dir: &Path, op: &str) -> (Child, PathBuf) {
    let marker = dir.join("stalled.pid");
    let mut cmd = Command::new(assert_cmd::cargo::cargo_bin("midsurf"));
    cmd.current_dir(root()).env_clear();
    for var in ["PATH", "HOME"] {
        if let Some(v) = std::env::var_os(var) {
            cmd.env(var, v);
        }
    }
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    cmd.env("MIDSURF_TEST_STALL", format!("{op}:{}", marker.display()))
        .args(["run", "fixtures/flat_plate.step", "-o"])
        .arg(out.join("mid.step"))
        .arg("--report")
        .arg(out.join("r.json"))
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    (cmd.spawn().unwrap(), marker)
}

/// The sidecar's pid once it stalls (it wrote the marker).
fn stalled_sidecar(marker: &Path) -> i32 {
    let started = Instant::now();
    loop {
        if let Some(pid) = std::fs::read_to_string(marker).ok().and_then(|s| s.trim().parse().ok()) {
            return pid;
        }
        assert!(started.elapsed() < Duration::from_secs(120), "the sidecar never reached its stall point");
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// A process that is gone (or a zombie waiting for its new parent to reap it), within a few seconds.
fn gone(pid: i32) -> bool {
    let started = Instant::now();
    while started.elapsed() < Duration::from_secs(10) {
        match std::fs::read_to_string(format!("/proc/{pid}/stat")) {
            Err(_) => return true,
            // The state follows the command name in parentheses.
            Ok(stat) if stat.rsplit(')').next().is_some_and(|rest| rest.trim_start().starts_with('Z')) => return true,
            Ok(_) => std::thread::sleep(Duration::from_millis(50)),
        }
    }
    false
}

fn kill(pid: i32, signal: i32) {
    // SAFETY: kill(2) on a pid this test started (directly or as midsurf's child).
    assert_eq!(unsafe { libc::kill(pid, signal) }, 0);
}

/// Exit code and stderr of a finished midsurf, failing the test if it does not finish.
fn finish(mut child: Child) -> (Option<i32>, String) {
    let started = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if started.elapsed() > Duration::from_secs(60) {
            let _ = child.kill();
            panic!("midsurf hung after the fault");
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let mut stderr = String::new();
    std::io::Read::read_to_string(child.stderr.as_mut().unwrap(), &mut stderr).unwrap();
    (status.code(), stderr)
}

fn files_in(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect()
}

#[test]
fn the_sidecar_killed_mid_operation_is_a_clear_error_and_nothing_is_written() {
    let dir = scratch("fault-sidecar");
    let (child, marker) = start(&dir, "describe");
    let sidecar = stalled_sidecar(&marker);
    kill(sidecar, libc::SIGKILL);
    let (code, stderr) = finish(child);
    assert_eq!(code, Some(2), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("the OCCT sidecar died during 'describe'") && stderr.contains("SIGKILL"), "{stderr}");
    assert!(gone(sidecar));
    assert!(files_in(&dir.join("out")).is_empty(), "{:?}", files_in(&dir.join("out")));
}

#[test]
fn midsurf_stopped_by_sigterm_kills_its_sidecar_and_removes_its_temporaries() {
    let dir = scratch("fault-term");
    // Stalled after writing the STEP: its temporary is on disk when the signal comes.
    let (child, marker) = start(&dir, "write_step");
    let sidecar = stalled_sidecar(&marker);
    assert!(files_in(&dir.join("out")).iter().any(|f| f.ends_with(".tmp")), "the STEP temporary is written");
    kill(child.id() as i32, libc::SIGTERM);
    let (code, stderr) = finish(child);
    assert_eq!(code, Some(2), "{stderr}");
    assert_eq!(
        stderr.trim(),
        "midsurf: error: stopped by SIGTERM: the sidecar was killed and no output was left half-written"
    );
    assert!(gone(sidecar), "the sidecar outlived midsurf");
    assert!(files_in(&dir.join("out")).is_empty(), "{:?}", files_in(&dir.join("out")));
}

#[test]
fn midsurf_killed_outright_takes_its_sidecar_with_it() {
    let dir = scratch("fault-kill");
    let (child, marker) = start(&dir, "describe");
    let sidecar = stalled_sidecar(&marker);
    kill(child.id() as i32, libc::SIGKILL);
    let (code, _) = finish(child);
    assert_eq!(code, None, "killed by a signal");
    // SIGKILL cannot be caught: the sidecar goes by its parent-death signal.
    assert!(gone(sidecar), "the sidecar outlived midsurf (orphaned)");
    assert!(files_in(&dir.join("out")).is_empty(), "{:?}", files_in(&dir.join("out")));
}

/// `midsurf run fixtures/t_rib.step` into `dir` with the sidecar crashing after `op` (test hook
/// MIDSURF_TEST_CRASH: once when `once`, else every time): exit code, stderr, files written.
fn run_crashing(dir: &Path, op: &str, once: bool) -> (Option<i32>, String, Vec<String>) {
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    let marker = if once { dir.join("crashed.pid").display().to_string() } else { String::new() };
    let output = Command::new(assert_cmd::cargo::cargo_bin("midsurf"))
        .current_dir(root())
        .env_clear()
        .env("PATH", std::env::var_os("PATH").unwrap_or_default())
        .env("MIDSURF_TEST_CRASH", format!("{op}:{marker}"))
        .args(["run", "fixtures/t_rib.step", "-o"])
        .arg(out.join("mid.step"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    (output.status.code(), stderr, files_in(&out))
}

#[test]
fn a_kernel_crash_after_loading_is_tried_once_more_and_a_second_one_is_the_error() {
    let dir = scratch("fault-crash-once");
    let (code, stderr, files) = run_crashing(&dir, "fuse", true);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stderr.contains("crashed during 'fuse'; running") && stderr.contains("once more"), "{stderr}");
    assert!(stderr.contains("its booleans on one thread"), "{stderr}");
    assert_eq!(files, vec!["mid.step".to_string()]);

    let dir = scratch("fault-crash-always");
    let (code, stderr, files) = run_crashing(&dir, "fuse", false);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.lines().last().unwrap().starts_with("midsurf: error:"), "{stderr}");
    assert!(stderr.contains("died during 'fuse'") && stderr.contains("SIGABRT"), "{stderr}");
    assert!(files.is_empty(), "{files:?}");
}

#[test]
fn a_kernel_hung_while_stitching_gives_the_patches_unstitched_with_a_warning() {
    // The sidecar hangs in its first probe of the free edges (a stitching op): past the op timeout the part
    // is run once more without stitching, which never probes, and written with a `stitch_failed` warning.
    let dir = scratch("fault-stitch-hang");
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    let output = Command::new(assert_cmd::cargo::cargo_bin("midsurf"))
        .current_dir(root())
        .env_clear()
        .env("PATH", std::env::var_os("PATH").unwrap_or_default())
        .env("MIDSURF_TEST_STALL", format!("probe_edges:{}", dir.join("stalled.pid").display()))
        .env("MIDSURF_TIMEOUT_SECS", "20")
        .args(["run", "fixtures/t_rib.step", "-o"])
        .arg(out.join("mid.step"))
        .arg("--report")
        .arg(out.join("mid.json"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("hung in 'probe_edges' while stitching") && stderr.contains("without stitching"),
        "{stderr}"
    );
    let report: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("mid.json")).unwrap()).unwrap();
    let codes: Vec<&str> = report["warnings"].as_array().unwrap().iter().map(|w| w["code"].as_str().unwrap()).collect();
    assert!(codes.contains(&"stitch_failed"), "{codes:?}");
    let mut files = files_in(&out);
    files.sort();
    assert_eq!(files, vec!["mid.json".to_string(), "mid.step".to_string()]);
}
