//! Errors that stop a command. Each names the file it concerns and says what went wrong, in one line.

use std::fmt;
use std::path::{Path, PathBuf};

use crate::kernel::SidecarError;

#[derive(Debug)]
pub enum Error {
    /// The input file cannot be used (missing, not STEP, no solid...).
    Input { path: PathBuf, problem: String },
    /// The kernel sidecar failed while working on a file.
    Sidecar { path: PathBuf, error: SidecarError },
    /// An output file could not be written.
    Output { path: PathBuf, problem: String },
}

impl Error {
    pub fn input(path: &Path, problem: impl Into<String>) -> Error {
        Error::Input { path: path.to_path_buf(), problem: problem.into() }
    }

    pub fn output(path: &Path, problem: impl Into<String>) -> Error {
        Error::Output { path: path.to_path_buf(), problem: problem.into() }
    }
}

/// Text on one line: runs of whitespace (newlines of quoted tracebacks included) become one space.
pub fn one_line(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // Messages may quote multi-line text (tracebacks): keep the promise of one line.
        let one_line = |s: &str| s.split_whitespace().collect::<Vec<_>>().join(" ");
        match self {
            Error::Input { path, problem } => {
                write!(f, "{}: {}", path.display(), one_line(problem))
            }
            Error::Sidecar { path, error } => {
                write!(f, "{}: {}", path.display(), one_line(&error.to_string()))
            }
            Error::Output { path, problem } => {
                write!(f, "{}: cannot write output: {}", path.display(), one_line(problem))
            }
        }
    }
}

impl std::error::Error for Error {}
