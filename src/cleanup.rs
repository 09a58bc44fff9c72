//! What must not outlive a run: its temporary files and its sidecar. Both are registered here; a signal
//! (SIGTERM, SIGINT, SIGHUP) is taken by one thread that removes the temporaries, kills the sidecar's process
//! group and exits with the documented one-line error. SIGKILL cannot be caught: the sidecar then dies by its
//! parent-death signal (set in the sidecar at start-up), and the temporaries, hidden dot-files named after
//! the process, are what is left.

use std::path::PathBuf;
use std::sync::{Mutex, MutexGuard};

/// Temporary files being written, removed if the run is stopped.
static TEMPS: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());
/// Process groups of live sidecars (each sidecar leads its own group).
static CHILDREN: Mutex<Vec<i32>> = Mutex::new(Vec::new());
/// Held while outputs are renamed into place, so that a signal never stops a set half-committed.
static COMMIT: Mutex<()> = Mutex::new(());

fn lock<T>(m: &'static Mutex<T>) -> MutexGuard<'static, T> {
    // A panic while holding one of these leaves plain data behind: still usable.
    m.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

pub fn add_temp(path: PathBuf) {
    lock(&TEMPS).push(path);
}

pub fn forget_temp(path: &std::path::Path) {
    lock(&TEMPS).retain(|p| p != path);
}

pub fn add_child(pid: u32) {
    lock(&CHILDREN).push(pid as i32);
}

pub fn forget_child(pid: u32) {
    lock(&CHILDREN).retain(|&p| p != pid as i32);
}

/// Held for the renames that commit an output set.
pub fn commit_guard() -> MutexGuard<'static, ()> {
    lock(&COMMIT)
}

/// Blocks the stop signals in this thread (and so in every thread started after it) and starts the one
/// thread that waits for them. Call first thing in `main`, before any other thread exists.
#[cfg(unix)]
pub fn install() {
    // SAFETY: plain libc calls on a local, initialised signal set.
    unsafe {
        let mut set: libc::sigset_t = std::mem::zeroed();
        libc::sigemptyset(&mut set);
        for sig in [libc::SIGTERM, libc::SIGINT, libc::SIGHUP] {
            libc::sigaddset(&mut set, sig);
        }
        if libc::pthread_sigmask(libc::SIG_BLOCK, &set, std::ptr::null_mut()) != 0 {
            return; // no handling then: the default action (the sidecar still dies with us)
        }
        let set_copy = set;
        std::thread::spawn(move || {
            let mut sig: libc::c_int = 0;
            // SAFETY: waits on the signal set blocked above.
            if libc::sigwait(&set_copy, &mut sig) == 0 {
                stop(sig);
            }
        });
    }
}

#[cfg(not(unix))]
pub fn install() {}

#[cfg(unix)]
fn stop(sig: i32) -> ! {
    let _commit = commit_guard();
    for pid in lock(&CHILDREN).iter() {
        // SAFETY: kill(2) on the sidecar's process group (negative pid), then on the process itself.
        unsafe {
            libc::kill(-pid, libc::SIGKILL);
            libc::kill(*pid, libc::SIGKILL);
        }
    }
    for path in lock(&TEMPS).iter() {
        let _ = std::fs::remove_file(path);
    }
    let name = match sig {
        libc::SIGTERM => "SIGTERM",
        libc::SIGINT => "SIGINT",
        libc::SIGHUP => "SIGHUP",
        _ => "a signal",
    };
    eprintln!("midsurf: error: stopped by {name}: the sidecar was killed and no output was left half-written");
    std::process::exit(crate::exit::Exit::Failed.code() as i32)
}
