//! `midsurf batch`: the parts of a folder or a manifest, each through `midsurf run`, N at a time, into one
//! output folder with a summary; resumable.
//!
//! Each part runs as a child process, this same executable's `midsurf run`, rather than in a thread of this
//! one: every part then gets exactly the outputs `midsurf run` gives it (same code path, same arguments), a
//! part that crashes its sidecar or panics costs that part only, and every worker's sidecar lives and dies
//! with its part as it does for `run` (no sidecar shared between parts, no state carried from one part to the
//! next). Starting a process and its sidecar per part costs about what importing OCCT costs, which the I/O
//! floor of a part counts anyway.

pub mod inputs;
pub mod key;
mod progress;
pub mod summary;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use crate::error::Error;
use crate::exit::Exit;
use inputs::{Options, Part, Shard};
use summary::{Counts, Row, Summary};

pub struct BatchArgs {
    /// A folder of STEP files or a manifest (.csv, .json).
    pub source: PathBuf,
    /// The output folder (made if missing).
    pub output: PathBuf,
    pub jobs: usize,
    pub shard: Option<Shard>,
    /// The options of every part, unless its manifest row sets its own.
    pub defaults: Options,
    /// `midsurf run`'s own check of a part's arguments (from the CLI).
    pub check_run_args: inputs::RunArgsCheck,
    /// Run every part, even those whose outputs are up to date.
    pub force: bool,
    /// Print the parts (after --shard) as JSON, with the arguments each would run with; run nothing.
    pub plan: bool,
    /// Run again the parts that failed with the same key (by default a failure is as reproducible as a
    /// success, and is kept).
    pub retry_failed: bool,
}

/// Where one part's files go.
struct Paths {
    step: PathBuf,
    report: PathBuf,
    log: PathBuf,
    state: PathBuf,
}

impl Paths {
    fn of(out: &Path, name: &str) -> Paths {
        Paths {
            step: out.join(format!("{name}.step")),
            report: out.join(format!("{name}.json")),
            log: out.join(format!("{name}.log")),
            state: out.join(STATE_DIR).join(format!("{name}.json")),
        }
    }
}

/// The folder of the per-part state files (row and key of the part's last run), inside the output folder.
const STATE_DIR: &str = ".midsurf-batch";

pub fn run(args: &BatchArgs) -> Result<Exit, Error> {
    let started = Instant::now();
    let parts = inputs::parts(&args.source, &args.defaults, args.check_run_args)?;
    let parts = match args.shard {
        Some(shard) => shard.select(parts),
        None => parts,
    };
    if args.plan {
        let list: Vec<serde_json::Value> = parts
            .iter()
            .map(|p| serde_json::json!({"part": p.name, "input": p.input.display().to_string(), "args": p.run_args()}))
            .collect();
        let text = serde_json::to_string_pretty(&list).expect("plans serialise") + "\n";
        std::io::Write::write_all(&mut std::io::stdout(), text.as_bytes())
            .map_err(|e| Error::output(Path::new("<stdout>"), e.to_string()))?;
        return Ok(Exit::Clean);
    }
    prepare_output(&args.source, &args.output)?;
    let exe =
        std::env::current_exe().map_err(|e| Error::input(Path::new("midsurf"), format!("cannot find itself: {e}")))?;
    let root =
        crate::kernel::python::project_root(std::env::var_os("MIDSURF_ROOT").map(PathBuf::from), Some(exe.clone()));
    let package = root.map(|r| r.join("sidecar/midsurf_sidecar"));
    let code =
        key::code_sha256(&exe, package.as_deref()).map_err(|e| Error::input(&exe, format!("cannot hash: {e}")))?;

    // Largest input first: a long part started last would leave the other workers idle at the end.
    let size = |p: &Part| std::fs::metadata(&p.input).map(|m| m.len()).unwrap_or(0);
    let mut order: Vec<usize> = (0..parts.len()).collect();
    order.sort_by_key(|&i| std::cmp::Reverse(size(&parts[i])));

    let jobs = args.jobs.max(1).min(parts.len().max(1));
    let next = AtomicUsize::new(0);
    let mut rows: Vec<Option<Row>> = vec![None; parts.len()];
    let mut progress = progress::Progress::new(parts.len());
    let (tx, rx) = std::sync::mpsc::channel::<(usize, Row, bool)>();
    std::thread::scope(|scope| {
        for _ in 0..jobs {
            let tx = tx.clone();
            let (parts, order, next, exe, code) = (&parts, &order, &next, &exe, &code);
            scope.spawn(move || loop {
                let k = next.fetch_add(1, Ordering::SeqCst);
                let Some(&i) = order.get(k) else { break };
                let (row, keep) = one_part(&parts[i], &args.output, exe, code, args);
                if tx.send((i, row, keep)).is_err() {
                    break;
                }
            });
        }
        drop(tx);
        for (i, row, keep) in rx {
            if keep && row.status == "ran" {
                if let Err(e) = summary::write_state(&Paths::of(&args.output, &row.part).state, &row) {
                    progress.note(&format!("cannot record {} for resuming: {e}", row.part));
                }
            }
            progress.done(&row);
            rows[i] = Some(row);
        }
    });
    let rows: Vec<Row> = rows.into_iter().map(|r| r.expect("every part reports")).collect();
    let worst = rows.iter().map(|r| r.exit).max().unwrap_or(0);
    let counts = Counts::of(&rows);
    let wall_s = started.elapsed().as_secs_f64();
    let suffix = args.shard.map(|s| format!("-{}-of-{}", s.index, s.count)).unwrap_or_default();
    let csv_path = args.output.join(format!("{}{suffix}.csv", inputs::SUMMARY_PREFIX));
    let json_path = args.output.join(format!("{}{suffix}.json", inputs::SUMMARY_PREFIX));
    summary::write_atomic(&csv_path, &summary::csv(&rows))?;
    let summary = Summary {
        midsurf_version: env!("CARGO_PKG_VERSION"),
        source: args.source.display().to_string(),
        shard: args.shard.map(|s| format!("{}/{}", s.index, s.count)),
        jobs,
        exit: worst,
        counts: counts.clone(),
        wall_s,
        parts: &rows,
    };
    summary::write_atomic(&json_path, &(serde_json::to_string_pretty(&summary).expect("summaries serialise") + "\n"))?;
    progress.finish();
    eprintln!(
        "batch: {} parts ({} ran, {} reused): {} clean, {} with warnings, {} failed; {:.1} s with -j {jobs}; summary {}",
        counts.parts,
        counts.ran,
        counts.reused,
        counts.clean,
        counts.warnings,
        counts.failed,
        wall_s,
        csv_path.display()
    );
    Ok(match worst {
        0 => Exit::Clean,
        1 => Exit::Warnings,
        _ => Exit::Failed,
    })
}

fn prepare_output(source: &Path, output: &Path) -> Result<(), Error> {
    if output.is_file() {
        return Err(Error::output(output, "is a file; the batch output is a folder"));
    }
    let same = matches!((source.canonicalize(), output.canonicalize()), (Ok(a), Ok(b)) if a == b);
    if same {
        return Err(Error::output(output, "is the input folder; a part's output would overwrite its input"));
    }
    std::fs::create_dir_all(output.join(STATE_DIR)).map_err(|e| Error::output(output, e.to_string()))
}

fn remove(path: &Path) {
    let _ = std::fs::remove_file(path); // absent already is fine; a file that stays makes the run fail later
}

/// Runs one part (or finds it up to date). Returns its row and whether the outcome is worth recording for a
/// later batch: not when the run was killed by a signal, nor when the input could not be read (it may turn
/// up later, and trying again costs nothing).
fn one_part(part: &Part, out: &Path, exe: &Path, code: &str, args: &BatchArgs) -> (Row, bool) {
    let paths = Paths::of(out, &part.name);
    let run_args = part.run_args();
    let input_sha = key::file_sha256(&part.input).ok();
    let key = input_sha.as_deref().map(|sha| key::part_key(sha, &run_args, code)).unwrap_or_default();
    if !args.force && !key.is_empty() {
        if let Some(mut prev) = summary::read_state(&paths.state) {
            let outputs = paths.step.is_file() && paths.report.is_file();
            let keep_failure = prev.exit >= 2 && !args.retry_failed;
            if prev.key == key && (outputs || keep_failure) {
                prev.status = "reused".into();
                prev.part.clone_from(&part.name);
                prev.input = part.input.display().to_string();
                return (prev, false);
            }
        }
    }
    // Whatever ran before is stale now: a run that fails must not leave an earlier run's outputs behind.
    for path in [&paths.state, &paths.step, &paths.report] {
        remove(path);
    }
    let mut row = Row {
        part: part.name.clone(),
        input: part.input.display().to_string(),
        exit: 2,
        status: "ran".into(),
        key: key.clone(),
        ..Row::default()
    };
    let log = match std::fs::File::create(&paths.log) {
        Ok(f) => f,
        Err(e) => {
            row.error = Some(format!("{}: cannot write: {e}", paths.log.display()));
            return (row, false);
        }
    };
    let started = Instant::now();
    let status = Command::new(exe)
        .arg("run")
        .arg(&part.input)
        .arg("-o")
        .arg(&paths.step)
        .arg("--report")
        .arg(&paths.report)
        .args(&run_args)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(log)
        .status();
    row.time_s = started.elapsed().as_secs_f64();
    let code = match status {
        Ok(s) => s.code(),
        Err(e) => {
            row.error = Some(format!("cannot start {}: {e}", exe.display()));
            return (row, false);
        }
    };
    row.exit = match code {
        Some(0) => 0,
        Some(1) => 1,
        _ => 2,
    };
    if row.exit < 2 {
        match std::fs::read_to_string(&paths.report).ok().and_then(|t| serde_json::from_str(&t).ok()) {
            Some(report) => row.fill_from_report(&report),
            None => {
                row.error = Some(format!("{}: no readable report after exit {}", paths.report.display(), row.exit));
                row.exit = 2;
            }
        }
    } else {
        row.error = Some(last_error(&paths.log, code));
    }
    (row, code.is_some() && !key.is_empty())
}

/// The error line `midsurf run` ended its log with, or what became of the process.
fn last_error(log: &Path, code: Option<i32>) -> String {
    let text = std::fs::read_to_string(log).unwrap_or_default();
    let line = text.lines().rev().find(|l| !l.trim().is_empty()).unwrap_or("").trim();
    let line = line.strip_prefix("midsurf: error: ").unwrap_or(line);
    match code {
        Some(2) if !line.is_empty() => line.to_string(),
        Some(c) => format!("exit {c}: {line}"),
        None => format!("killed by a signal: {line}"),
    }
}
