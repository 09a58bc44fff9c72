//! The sidecar as a child process: stdin/stdout carry protocol lines, stderr is kept for error messages.

use std::collections::VecDeque;
use std::io::{BufRead, BufReader, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::sync::{Arc, Mutex};
use std::thread;
use std::time::Duration;

use super::python::Launch;
use super::{SidecarError, Transport, TransportError};

/// Enough stderr to show a Python traceback's tail without holding a chatty kernel's whole log.
const STDERR_TAIL_LINES: usize = 40;

/// How `diagnostics` says the child was ended by a signal.
pub const KILLED_BY: &str = "ended by signal ";

fn signal_name(sig: i32) -> &'static str {
    match sig {
        6 => " (SIGABRT)",
        9 => " (SIGKILL)",
        11 => " (SIGSEGV)",
        15 => " (SIGTERM)",
        _ => "",
    }
}

pub struct ProcessTransport {
    child: Child,
    stdin: Option<ChildStdin>,
    lines: Receiver<String>,
    stderr: Arc<Mutex<VecDeque<String>>>,
    /// The signal that ended the child, once seen: a kill from outside, not a crash of its own making.
    killed_by: Option<i32>,
}

impl ProcessTransport {
    pub fn spawn(launch: &Launch) -> Result<ProcessTransport, SidecarError> {
        let mut command = Command::new(&launch.python);
        command
            .args(["-u", "-m", "midsurf_sidecar"])
            .env("PYTHONPATH", &launch.sidecar_dir)
            .env("PYTHONDONTWRITEBYTECODE", "1")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped());
        // Its own process group, so that a stop signal can take it and anything it starts; the sidecar sets
        // its parent-death signal at start-up and checks it is still this process's child (a SIGKILL here).
        #[cfg(unix)]
        std::os::unix::process::CommandExt::process_group(&mut command, 0);
        command.env("MIDSURF_PARENT_PID", std::process::id().to_string());
        if launch.serial_booleans {
            command.env("MIDSURF_SERIAL_BOOLEANS", "1");
        }
        let mut child = command.spawn().map_err(|e| SidecarError::Spawn {
            why: format!("{}: {e}; set MIDSURF_PYTHON or run scripts/setup", launch.python.display()),
        })?;
        crate::cleanup::add_child(child.id());
        let stdin = child.stdin.take().expect("stdin was configured as piped");
        let stdout = child.stdout.take().expect("stdout was configured as piped");
        let stderr_pipe = child.stderr.take().expect("stderr was configured as piped");

        let (tx, lines) = mpsc::channel();
        thread::spawn(move || {
            for line in BufReader::new(stdout).lines() {
                let Ok(line) = line else { break };
                if tx.send(line).is_err() {
                    break;
                }
            }
        });
        let stderr = Arc::new(Mutex::new(VecDeque::new()));
        let tail = Arc::clone(&stderr);
        thread::spawn(move || {
            for line in BufReader::new(stderr_pipe).lines() {
                let Ok(line) = line else { break };
                let mut tail = tail.lock().expect("stderr tail lock is never poisoned: no panics while held");
                if tail.len() == STDERR_TAIL_LINES {
                    tail.pop_front();
                }
                tail.push_back(line);
            }
        });
        Ok(ProcessTransport { child, stdin: Some(stdin), lines, stderr, killed_by: None })
    }

    /// Waits briefly for the stderr reader so that a dying child's last words make it into the error.
    fn settle_stderr(&mut self) {
        for _ in 0..20 {
            if let Ok(Some(status)) = self.child.try_wait() {
                #[cfg(unix)]
                {
                    self.killed_by = std::os::unix::process::ExitStatusExt::signal(&status);
                }
                let _ = status;
                break;
            }
            thread::sleep(Duration::from_millis(10));
        }
        thread::sleep(Duration::from_millis(30));
    }
}

impl Transport for ProcessTransport {
    fn send(&mut self, line: &str) -> Result<(), TransportError> {
        let stdin = self.stdin.as_mut().ok_or(TransportError::Closed)?;
        let sent = stdin.write_all(line.as_bytes()).and_then(|_| stdin.write_all(b"\n")).and_then(|_| stdin.flush());
        sent.map_err(|_| TransportError::Closed)
    }

    fn recv(&mut self, timeout: Duration) -> Result<String, TransportError> {
        match self.lines.recv_timeout(timeout) {
            Ok(line) => Ok(line),
            Err(RecvTimeoutError::Timeout) => {
                let _ = self.child.kill();
                Err(TransportError::Timeout)
            }
            Err(RecvTimeoutError::Disconnected) => {
                self.settle_stderr();
                Err(TransportError::Closed)
            }
        }
    }

    fn diagnostics(&self) -> String {
        let tail = self.stderr.lock().expect("stderr tail lock is never poisoned: no panics while held");
        let mut lines: Vec<String> = tail.iter().cloned().collect();
        // Last, so that the one-line message shows it: SIGSEGV is the kernel's crash, SIGKILL someone's kill.
        if let Some(sig) = self.killed_by {
            lines.push(format!("{KILLED_BY}{sig}{}", signal_name(sig)));
        }
        lines.join("\n")
    }
}

impl Drop for ProcessTransport {
    fn drop(&mut self) {
        // Closing stdin lets a healthy sidecar exit by itself; kill covers a stuck one; wait reaps either.
        self.stdin.take();
        for _ in 0..50 {
            if matches!(self.child.try_wait(), Ok(Some(_))) {
                crate::cleanup::forget_child(self.child.id());
                return;
            }
            thread::sleep(Duration::from_millis(10));
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
        crate::cleanup::forget_child(self.child.id());
    }
}
