//! Progress of a batch on stderr: a bar redrawn in place on a terminal, one line per part otherwise (logs,
//! CI, job arrays). Hand-written: a dozen lines do what a progress crate would, without its dependencies.

use std::io::{IsTerminal, Write};
use std::time::Instant;

use super::summary::Row;

pub struct Progress {
    total: usize,
    done: usize,
    failed: usize,
    tty: bool,
    started: Instant,
}

impl Progress {
    pub fn new(total: usize) -> Progress {
        let progress =
            Progress { total, done: 0, failed: 0, tty: std::io::stderr().is_terminal(), started: Instant::now() };
        progress.draw("");
        progress
    }

    /// A message that must stay visible (above the bar on a terminal).
    pub fn note(&self, text: &str) {
        if self.tty {
            eprint!("\r\x1b[K");
        }
        eprintln!("batch: {text}");
        self.draw("");
    }

    pub fn done(&mut self, row: &Row) {
        self.done += 1;
        if row.exit >= 2 {
            self.failed += 1;
        }
        let what = format!("{} exit {} {:.1} s ({})", row.part, row.exit, row.time_s, row.status);
        if !self.tty {
            eprintln!("batch: [{}/{}] {what}", self.done, self.total);
        } else if row.exit >= 2 {
            self.note(&format!("{what}: {}", row.error.as_deref().unwrap_or("")));
        } else {
            self.draw(&what);
        }
    }

    fn draw(&self, last: &str) {
        if !self.tty {
            return;
        }
        const WIDTH: usize = 30;
        let filled = (WIDTH * self.done).checked_div(self.total).unwrap_or(WIDTH);
        let elapsed = self.started.elapsed().as_secs_f64();
        let eta = if self.done > 0 && self.done < self.total {
            format!(" eta {:.0} s", elapsed / self.done as f64 * (self.total - self.done) as f64)
        } else {
            String::new()
        };
        eprint!(
            "\r\x1b[K[{}{}] {}/{} {} failed {:.0} s{eta}  {last}",
            "#".repeat(filled),
            " ".repeat(WIDTH - filled),
            self.done,
            self.total,
            self.failed,
            elapsed
        );
        let _ = std::io::stderr().flush();
    }

    pub fn finish(&self) {
        if self.tty {
            eprintln!();
        }
    }
}
