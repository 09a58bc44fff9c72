//! Writing outputs atomically: everything goes to a temporary file beside the target, renamed into place only
//! when complete, so a failure never leaves a half-written file (and the input is never opened for writing).
//! A run's outputs (STEP, report, summary, CSV, preview) are one set: every temporary is written first, then
//! all are renamed together (`commit_all`), under a lock on their directories so that two runs writing the
//! same paths cannot interleave their sets; a stop signal waits for the renames (see `cleanup`).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use crate::error::Error;

/// Distinguishes the temporaries of one process, so two outputs never share one.
static SEQUENCE: AtomicUsize = AtomicUsize::new(0);

/// A file being written: the temporary path, removed on drop unless committed.
pub struct Pending {
    pub temp: PathBuf,
    pub target: PathBuf,
    committed: bool,
}

impl Pending {
    /// Checks that the target's directory exists and that the target is not the input.
    pub fn new(target: &Path, input: &Path) -> Result<Pending, Error> {
        let dir = parent_dir(target);
        if !dir.is_dir() {
            return Err(Error::output(target, format!("directory {} does not exist", dir.display())));
        }
        if target.is_dir() {
            return Err(Error::output(target, "is a directory"));
        }
        if same_file(target, input) {
            return Err(Error::output(target, "is the input file; midsurf never overwrites its input"));
        }
        let name = target.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let k = SEQUENCE.fetch_add(1, Ordering::Relaxed);
        let temp = dir.join(format!(".{name}.midsurf-{}-{k}.tmp", std::process::id()));
        crate::cleanup::add_temp(temp.clone());
        Ok(Pending { temp, target: target.to_path_buf(), committed: false })
    }

    pub fn write(&self, bytes: &[u8]) -> Result<(), Error> {
        std::fs::write(&self.temp, bytes).map_err(|e| Error::output(&self.target, e.to_string()))
    }

    pub fn commit(mut self) -> Result<(), Error> {
        std::fs::rename(&self.temp, &self.target).map_err(|e| Error::output(&self.target, e.to_string()))?;
        self.committed = true;
        crate::cleanup::forget_temp(&self.temp);
        Ok(())
    }
}

impl Drop for Pending {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_file(&self.temp);
            crate::cleanup::forget_temp(&self.temp);
        }
    }
}

fn parent_dir(target: &Path) -> PathBuf {
    match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

fn same_file(a: &Path, b: &Path) -> bool {
    matches!((a.canonicalize(), b.canonicalize()), (Ok(a), Ok(b)) if a == b)
}

/// A path as it will be opened: absolute, its directory resolved through links (the file may not exist yet).
fn resolved(path: &Path) -> PathBuf {
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let dir = parent_dir(&absolute).canonicalize().unwrap_or_else(|_| parent_dir(&absolute));
    match absolute.file_name() {
        Some(name) => dir.join(name),
        None => absolute,
    }
}

/// Refuses an output set naming one file twice (`-o x --report x`): one would overwrite the other.
pub fn distinct(outputs: &[(&str, &Path)]) -> Result<(), Error> {
    for (i, (name_a, a)) in outputs.iter().enumerate() {
        for (name_b, b) in &outputs[..i] {
            if resolved(a) == resolved(b) {
                return Err(Error::output(
                    a,
                    format!("given to both {name_b} and {name_a}; each output needs its own path"),
                ));
            }
        }
    }
    Ok(())
}

/// Renames every temporary of the set into place, as one unit: under the commit guard (a stop signal waits)
/// and a lock on each target directory (another run's renames wait). If a rename fails, the targets already
/// renamed by this call are removed again, so the set is written whole or not at all.
pub fn commit_all(set: Vec<Pending>) -> Result<(), Error> {
    let _guard = crate::cleanup::commit_guard();
    let mut dirs: Vec<PathBuf> = set.iter().map(|p| resolved(&p.target)).map(|t| parent_dir(&t)).collect();
    dirs.sort();
    dirs.dedup();
    let _locks: Vec<DirLock> = dirs.iter().filter_map(|d| DirLock::new(d)).collect();
    let mut done: Vec<PathBuf> = Vec::new();
    for pending in set {
        let target = pending.target.clone();
        if let Err(e) = pending.commit() {
            for path in &done {
                let _ = std::fs::remove_file(path);
            }
            return Err(e);
        }
        done.push(target);
    }
    Ok(())
}

/// An advisory lock (flock) on a directory, released on drop. Best effort: where it cannot be taken the
/// renames go on unlocked, as before.
struct DirLock {
    #[cfg(unix)]
    file: std::fs::File,
}

impl DirLock {
    #[cfg(unix)]
    fn new(dir: &Path) -> Option<DirLock> {
        use std::os::fd::AsRawFd;
        let file = std::fs::File::open(dir).ok()?;
        // SAFETY: flock(2) on a descriptor this struct owns.
        (unsafe { libc::flock(file.as_raw_fd(), libc::LOCK_EX) } == 0).then_some(DirLock { file })
    }

    #[cfg(not(unix))]
    fn new(_dir: &Path) -> Option<DirLock> {
        None
    }
}

#[cfg(unix)]
impl Drop for DirLock {
    fn drop(&mut self) {
        use std::os::fd::AsRawFd;
        // SAFETY: unlocks the descriptor locked in `new`.
        unsafe { libc::flock(self.file.as_raw_fd(), libc::LOCK_UN) };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_outputs_never_share_a_temporary_and_one_path_twice_is_refused() {
        let dir = std::env::temp_dir().join(format!("midsurf-output-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let input = dir.join("in.step");
        std::fs::write(&input, "x").unwrap();
        let (a, b) =
            (Pending::new(&dir.join("x.out"), &input).unwrap(), Pending::new(&dir.join("x.out"), &input).unwrap());
        assert_ne!(a.temp, b.temp);
        let same = dir.join("sub/../x.out");
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        let err = distinct(&[("-o", &dir.join("x.out")), ("--report", &same)]).unwrap_err();
        assert!(err.to_string().contains("given to both -o and --report"), "{err}");
        assert!(distinct(&[("-o", &dir.join("x.out")), ("--report", &dir.join("y.out"))]).is_ok());
        drop((a, b));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_set_is_committed_whole() {
        let dir = std::env::temp_dir().join(format!("midsurf-output-set-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let input = dir.join("in.step");
        std::fs::write(&input, "x").unwrap();
        let ok = Pending::new(&dir.join("a.out"), &input).unwrap();
        ok.write(b"a").unwrap();
        // The second's temporary was never written: its rename fails, and the first is taken back.
        let missing = Pending::new(&dir.join("b.out"), &input).unwrap();
        assert!(commit_all(vec![ok, missing]).is_err());
        assert!(!dir.join("a.out").exists() && !dir.join("b.out").exists());
        let names: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name()).collect();
        assert_eq!(names, ["in.step"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
