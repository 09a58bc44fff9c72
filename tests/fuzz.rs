//! Fuzz: mutants of small fixtures (byte flips, deleted and duplicated lines, references redirected or
//! swapped) through `midsurf run`. Whatever the file, midsurf must not panic (exit 101), show a Python
//! traceback, hang, or leave anything written when it fails (exit 2); when it succeeds the set is whole.
//! The mutants come from a fixed seed, so a failure reproduces; MIDSURF_FUZZ_MUTANTS changes how many.

mod common;

use std::path::Path;
use std::sync::Mutex;
use std::time::Duration;

use common::{midsurf, outcome, scratch};

const FIXTURES: [&str; 4] = ["flat_plate", "l_bracket", "t_rib", "u_channel"];
const DEFAULT_MUTANTS: usize = 208;
/// Runs at a time: each is mostly the sidecar's start-up, on one core.
const WORKERS: usize = 2;

/// xorshift64*: a fixed, dependency-free stream of numbers.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// The `#N` references in a line, as byte ranges.
fn references(line: &str) -> Vec<(usize, usize)> {
    let bytes = line.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'#' {
            let end = (i + 1..bytes.len()).find(|&j| !bytes[j].is_ascii_digit()).unwrap_or(bytes.len());
            if end > i + 1 {
                out.push((i, end));
            }
            i = end;
        } else {
            i += 1;
        }
    }
    out
}

/// One mutant of `text` and what was done to it.
fn mutate(text: &str, rng: &mut Rng) -> (Vec<u8>, String) {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let data = lines.iter().position(|l| l.starts_with("DATA;")).map_or(0, |k| k + 1);
    let entity = |rng: &mut Rng, lines: &[String]| data + rng.below(lines.len().saturating_sub(data + 2));
    match rng.below(5) {
        0 => {
            let mut bytes = text.as_bytes().to_vec();
            let flips = 1 + rng.below(3);
            let mut at = Vec::new();
            for _ in 0..flips {
                let k = rng.below(bytes.len());
                bytes[k] ^= 1 << rng.below(8);
                at.push(k);
            }
            (bytes, format!("byte flips at {at:?}"))
        }
        1 => {
            let k = entity(rng, &lines);
            let removed = lines.remove(k);
            (lines.join("\n").into_bytes(), format!("line {k} deleted: {removed}"))
        }
        2 => {
            let k = entity(rng, &lines);
            lines.insert(k, lines[k].clone());
            (lines.join("\n").into_bytes(), format!("line {k} duplicated: {}", lines[k]))
        }
        3 => {
            // A reference pointed at another entity's number (a duplicated reference).
            let k = entity(rng, &lines);
            let refs = references(&lines[k]);
            let all: Vec<String> = lines[data..]
                .iter()
                .flat_map(|l| references(l).into_iter().map(|(a, b)| l[a..b].to_string()))
                .collect();
            if refs.len() < 2 || all.is_empty() {
                lines.swap(k, k + 1);
                return (lines.join("\n").into_bytes(), format!("lines {k} and {} swapped", k + 1));
            }
            let (a, b) = refs[1 + rng.below(refs.len() - 1)];
            let to = all[rng.below(all.len())].clone();
            let old = lines[k].clone();
            lines[k].replace_range(a..b, &to);
            (lines.join("\n").into_bytes(), format!("line {k}: {old} -> {}", lines[k]))
        }
        _ => {
            // Two references of one entity swapped.
            let k = entity(rng, &lines);
            let refs = references(&lines[k]);
            if refs.len() < 3 {
                lines.remove(k);
                return (lines.join("\n").into_bytes(), format!("line {k} deleted"));
            }
            let (i, j) = (1 + rng.below(refs.len() - 1), 1 + rng.below(refs.len() - 1));
            let (i, j) = (i.min(j), i.max(j));
            if i == j {
                lines.remove(k);
                return (lines.join("\n").into_bytes(), format!("line {k} deleted"));
            }
            let old = lines[k].clone();
            let (ri, rj) = (old[refs[i].0..refs[i].1].to_string(), old[refs[j].0..refs[j].1].to_string());
            let swapped = format!("{}{rj}{}{ri}{}", &old[..refs[i].0], &old[refs[i].1..refs[j].0], &old[refs[j].1..]);
            lines[k] = swapped;
            (lines.join("\n").into_bytes(), format!("line {k}: {old} -> {}", lines[k]))
        }
    }
}

/// What is wrong with one mutant's run, if anything.
fn check(input: &Path, out: &Path) -> Option<String> {
    let (step, report) = (out.join("mid.step"), out.join("r.json"));
    let o = outcome(
        midsurf()
            .env("MIDSURF_TIMEOUT_SECS", "60")
            .args(["run", input.to_str().unwrap(), "-o", step.to_str().unwrap(), "--report", report.to_str().unwrap()])
            .timeout(Duration::from_secs(150)),
    );
    let mut files: Vec<String> =
        std::fs::read_dir(out).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    files.sort();
    let problem = if o.stderr.contains("panicked") || o.code == 101 {
        "panic".to_string()
    } else if o.stderr.contains("Traceback") {
        "Python traceback on stderr".to_string()
    } else if o.code == -1 {
        "hang (killed after 150 s) or killed by a signal".to_string()
    } else if o.code == 2 && !files.is_empty() {
        format!("exit 2 left files {files:?}")
    } else if o.code == 2 && (o.stderr.lines().count() != 1 || !o.stderr.starts_with("midsurf: error: ")) {
        "exit 2 without the one-line error".to_string()
    } else if (o.code == 0 || o.code == 1) && files != ["mid.step", "r.json"] {
        format!("exit {} with files {files:?}", o.code)
    } else if !(0..=2).contains(&o.code) {
        format!("exit {}", o.code)
    } else {
        return None;
    };
    Some(format!("{problem}: exit {}, stderr {:?}", o.code, o.stderr.chars().take(300).collect::<String>()))
}

#[test]
fn mutants_never_panic_hang_or_leave_files() {
    let count = std::env::var("MIDSURF_FUZZ_MUTANTS").ok().and_then(|s| s.parse().ok()).unwrap_or(DEFAULT_MUTANTS);
    let dir = scratch("fuzz");
    let texts: Vec<String> = FIXTURES
        .iter()
        .map(|f| std::fs::read_to_string(common::root().join(format!("fixtures/{f}.step"))).unwrap())
        .collect();
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut jobs = Vec::new();
    for k in 0..count {
        let f = k % FIXTURES.len();
        let (bytes, what) = mutate(&texts[f], &mut rng);
        let input = dir.join(format!("m{k:03}_{}.step", FIXTURES[f]));
        std::fs::write(&input, bytes).unwrap();
        let out = dir.join(format!("out{k:03}"));
        std::fs::create_dir_all(&out).unwrap();
        jobs.push((input, out, what));
    }
    let next = Mutex::new(0usize);
    let failures = Mutex::new(Vec::new());
    let exits = Mutex::new([0usize; 3]);
    std::thread::scope(|s| {
        for _ in 0..WORKERS {
            s.spawn(|| loop {
                let k = {
                    let mut n = next.lock().unwrap();
                    *n += 1;
                    *n - 1
                };
                let Some((input, out, what)) = jobs.get(k) else { break };
                match check(input, out) {
                    Some(problem) => failures.lock().unwrap().push(format!("{}: {what}: {problem}", input.display())),
                    None => {
                        let written = std::fs::read_dir(out).unwrap().count() > 0;
                        let code = if written { 0 } else { 2 };
                        exits.lock().unwrap()[code] += 1;
                        let _ = std::fs::remove_dir_all(out);
                        let _ = std::fs::remove_file(input);
                    }
                }
            });
        }
    });
    let failures = failures.into_inner().unwrap();
    let exits = exits.into_inner().unwrap();
    eprintln!("fuzz: {count} mutants, {} written, {} refused, {} failed", exits[0], exits[2], failures.len());
    assert!(failures.is_empty(), "{} of {count} mutants failed:\n{}", failures.len(), failures.join("\n"));
    // Mutants that change nothing that matters are fine, but a fuzz whose mutants all pass through is no test.
    assert!(exits[2] > 0 && exits[0] > 0, "written {}, refused {}", exits[0], exits[2]);
}
