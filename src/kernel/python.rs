//! Finding the Python interpreter and the sidecar package.
//!
//! Interpreter, first match wins:
//! 1. `MIDSURF_PYTHON` (an interpreter path; it must exist),
//! 2. `<project>/.venv/bin/python`, the venv made by `scripts/setup`,
//! 3. `python3` on `PATH`.
//!
//! Project directory (holds `sidecar/midsurf_sidecar`), first match wins: `MIDSURF_ROOT`, the ancestors of the
//! running executable (`target/*/midsurf` lives inside the project), the directory this binary was built from.

use std::path::{Path, PathBuf};

use super::SidecarError;

/// How to start the sidecar.
#[derive(Debug, Clone, PartialEq)]
pub struct Launch {
    pub python: PathBuf,
    /// Put on `PYTHONPATH` so that `python -m midsurf_sidecar` finds the package.
    pub sidecar_dir: PathBuf,
    /// Run OCCT's booleans on one thread (the sidecar's `MIDSURF_SERIAL_BOOLEANS`): their threads crash the
    /// kernel now and then, so a part that crashed it runs again this way.
    pub serial_booleans: bool,
}

const PACKAGE_MARKER: &str = "sidecar/midsurf_sidecar/__main__.py";

fn holds_sidecar(dir: &Path) -> bool {
    dir.join(PACKAGE_MARKER).is_file()
}

/// The project directory, from the environment variable, the executable's location or the build directory.
pub fn project_root(env_root: Option<PathBuf>, exe: Option<PathBuf>) -> Option<PathBuf> {
    if let Some(root) = env_root {
        return holds_sidecar(&root).then_some(root);
    }
    let from_exe = exe.and_then(|exe| exe.ancestors().skip(1).find(|d| holds_sidecar(d)).map(Path::to_path_buf));
    from_exe.or_else(|| {
        let built = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
        holds_sidecar(&built).then_some(built)
    })
}

/// Where to find Python and the sidecar, from this process's environment.
pub fn locate() -> Result<Launch, SidecarError> {
    let env_root = std::env::var_os("MIDSURF_ROOT").map(PathBuf::from);
    let root = project_root(env_root.clone(), std::env::current_exe().ok()).ok_or_else(|| SidecarError::Spawn {
        why: match env_root {
            Some(r) => format!("MIDSURF_ROOT={} has no {PACKAGE_MARKER}", r.display()),
            None => format!("no {PACKAGE_MARKER} near the executable; set MIDSURF_ROOT to the midsurf checkout"),
        },
    })?;
    let python = choose_python(std::env::var_os("MIDSURF_PYTHON").map(PathBuf::from), &root)?;
    Ok(Launch { python, sidecar_dir: root.join("sidecar"), serial_booleans: false })
}

fn choose_python(env_python: Option<PathBuf>, root: &Path) -> Result<PathBuf, SidecarError> {
    if let Some(python) = env_python {
        if python.is_file() {
            return Ok(python);
        }
        return Err(SidecarError::Spawn {
            why: format!("MIDSURF_PYTHON={} is not a file; unset it or point it at a Python 3.11", python.display()),
        });
    }
    let venv = root.join(".venv/bin/python");
    if venv.is_file() {
        return Ok(venv);
    }
    Ok(PathBuf::from("python3"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp_project(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("midsurf-python-test-{name}-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("sidecar/midsurf_sidecar")).unwrap();
        std::fs::write(dir.join(PACKAGE_MARKER), "").unwrap();
        dir
    }

    #[test]
    fn root_from_env_must_hold_the_package() {
        let dir = temp_project("env");
        assert_eq!(project_root(Some(dir.clone()), None), Some(dir.clone()));
        assert_eq!(project_root(Some(dir.join("nope")), None), None);
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn root_from_executable_ancestors() {
        let dir = temp_project("exe");
        let exe = dir.join("target/release/midsurf");
        assert_eq!(project_root(None, Some(exe)), Some(dir.clone()));
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn python_order_env_then_venv_then_path() {
        let dir = temp_project("py");
        assert_eq!(choose_python(None, &dir).unwrap(), PathBuf::from("python3"));
        std::fs::create_dir_all(dir.join(".venv/bin")).unwrap();
        std::fs::write(dir.join(".venv/bin/python"), "").unwrap();
        assert_eq!(choose_python(None, &dir).unwrap(), dir.join(".venv/bin/python"));
        let env = dir.join(PACKAGE_MARKER);
        assert_eq!(choose_python(Some(env.clone()), &dir).unwrap(), env);
        assert!(choose_python(Some(dir.join("missing")), &dir).is_err());
        std::fs::remove_dir_all(dir).unwrap();
    }
}
