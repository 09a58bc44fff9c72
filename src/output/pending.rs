//! Writing outputs atomically: everything goes to a temporary file beside the target, renamed into place only
//! when complete, so a failure never leaves a half-written file (and the input is never opened for writing).

use std::path::{Path, PathBuf};

use crate::error::Error;

/// A file being written: the temporary path, removed on drop unless committed.
pub struct Pending {
    pub temp: PathBuf,
    pub target: PathBuf,
    committed: bool,
}

impl Pending {
    /// Checks that the target's directory exists and that the target is not the input.
    pub fn new(target: &Path, input: &Path) -> Result<Pending, Error> {
        let dir = match target.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        if !dir.is_dir() {
            return Err(Error::output(target, format!("directory {} does not exist", dir.display())));
        }
        let same = |a: &Path, b: &Path| match (a.canonicalize(), b.canonicalize()) {
            (Ok(a), Ok(b)) => a == b,
            _ => false,
        };
        if target.is_dir() {
            return Err(Error::output(target, "is a directory"));
        }
        if same(target, input) {
            return Err(Error::output(target, "is the input file; midsurf never overwrites its input"));
        }
        let name = target.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let temp = dir.join(format!(".{name}.midsurf-{}.tmp", std::process::id()));
        Ok(Pending { temp, target: target.to_path_buf(), committed: false })
    }

    pub fn write(&self, bytes: &[u8]) -> Result<(), Error> {
        std::fs::write(&self.temp, bytes).map_err(|e| Error::output(&self.target, e.to_string()))
    }

    pub fn commit(mut self) -> Result<(), Error> {
        std::fs::rename(&self.temp, &self.target).map_err(|e| Error::output(&self.target, e.to_string()))?;
        self.committed = true;
        Ok(())
    }
}

impl Drop for Pending {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_file(&self.temp);
        }
    }
}
