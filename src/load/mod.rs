//! Loading a part: checks on the input file, then `load_step` and `describe` of every solid in the sidecar.

use std::path::Path;

use crate::error::Error;
use crate::kernel::protocol::{Loaded, Request};
use crate::kernel::{Kernel, Sidecar, SidecarError};
use crate::model::face_graph::FaceGraph;

/// One solid of the part: its sidecar handle and its face graph.
pub struct Solid {
    pub handle: u64,
    pub graph: FaceGraph,
    /// Chordal tolerance of the graph's face meshes (mm).
    pub mesh_tolerance: f64,
}

pub struct Part {
    pub solids: Vec<Solid>,
    /// Solids of the file the kernel could not describe, left out: (their number in the file, from 1; why).
    /// The solids kept are numbered by their place in `solids`.
    pub skipped: Vec<(usize, String)>,
    /// Entities of the file the reader could not read. The solids came out whole all the same (the kernel
    /// checks them later); a file whose bad entities cost it its solids is an error naming them.
    pub entity_problems: Vec<crate::kernel::protocol::EntityProblem>,
}

/// Mesh settings for `describe`: whether to tessellate, and the chordal tolerance in mm (None: derived from
/// each solid's wall estimate, see `tolerance::mesh_tolerance`).
#[derive(Debug, Clone, Copy)]
pub struct MeshRequest {
    pub mesh: bool,
    pub tolerance: Option<f64>,
}

/// Starts the sidecar for work on `path`, so that a broken install is reported against the file at hand; its
/// booleans on one thread when `serial_booleans` (see `kernel::python::Launch`).
pub fn start_sidecar(path: &Path, serial_booleans: bool) -> Result<Sidecar, Error> {
    check_input(path)?;
    Sidecar::start(serial_booleans).map_err(|error| Error::Sidecar { path: path.to_path_buf(), error })
}

/// Problems we can see without the kernel, with a message a user can act on.
pub fn check_input(path: &Path) -> Result<(), Error> {
    let meta = std::fs::metadata(path).map_err(|e| match e.kind() {
        std::io::ErrorKind::NotFound => Error::input(path, "no such file"),
        _ => Error::input(path, format!("cannot read: {e}")),
    })?;
    if meta.is_dir() {
        return Err(Error::input(path, "is a directory, not a STEP file"));
    }
    if meta.len() == 0 {
        return Err(Error::input(path, "is empty, not a STEP file"));
    }
    std::fs::File::open(path).map_err(|e| Error::input(path, format!("cannot open: {e}")))?;
    Ok(())
}

/// Error codes of `load_step` that are the input's fault, not the kernel's.
const INPUT_CODES: [&str; 4] = ["not_found", "not_a_file", "read_failed", "no_solid"];

fn classify(path: &Path, error: SidecarError) -> Error {
    if let SidecarError::Died { op, stderr } = &error {
        if op == "load_step" {
            // The reader segfaulting (a corrupt entity it does not check) is the file's doing, not the install's.
            return Error::input(
                path,
                format!(
                    "the STEP reader crashed on this file; it is probably corrupt{}",
                    crate::kernel::last_words(stderr)
                ),
            );
        }
    }
    match error.code() {
        Some(code) if INPUT_CODES.contains(&code) => Error::input(path, error.to_string()),
        _ => Error::Sidecar { path: path.to_path_buf(), error },
    }
}

/// The load stage: the STEP file read in the kernel and every solid described as a checked face graph.
pub fn load<K: Kernel>(kernel: &mut K, path: &Path, mesh: MeshRequest) -> Result<Part, Error> {
    check_input(path)?;
    // The sidecar gets an absolute path so that its working directory never matters.
    let absolute = std::path::absolute(path).map_err(|e| Error::input(path, format!("bad path: {e}")))?;
    let text = absolute.to_str().ok_or_else(|| Error::input(path, "path is not valid UTF-8"))?;
    let loaded: Loaded = kernel.call(&Request::LoadStep { path: text.to_string() }).map_err(|e| classify(path, e))?;
    let mut solids = Vec::with_capacity(loaded.solids.len());
    let mut skipped = Vec::new();
    for (number, solid) in loaded.solids.into_iter().enumerate() {
        let mesh_tolerance =
            mesh.tolerance.unwrap_or_else(|| crate::model::tolerance::mesh_tolerance(solid.volume, solid.area));
        let request = Request::Describe { handle: solid.handle, mesh: mesh.mesh, mesh_tolerance };
        // One solid the kernel cannot describe (an op error: the sidecar lives on) is left out and the others go
        // on; a dead or stuck sidecar takes every handle with it, so that stays an error.
        let graph: FaceGraph = match kernel.call(&request) {
            Ok(graph) => graph,
            Err(e) if e.code().is_some() => {
                skipped.push((number + 1, crate::error::one_line(&e.to_string())));
                continue;
            }
            Err(e) => return Err(classify(path, e)),
        };
        let problems = graph.validate();
        if !problems.is_empty() {
            skipped.push((number + 1, format!("inconsistent face graph: {}", problems.join("; "))));
            continue;
        }
        solids.push(Solid { handle: solid.handle, graph, mesh_tolerance });
    }
    if solids.is_empty() {
        // Nothing usable: the reasons of the solids left out are the error.
        let why: Vec<String> = skipped.iter().map(|(n, why)| format!("solid {n}: {why}")).collect();
        return Err(Error::input(path, format!("no solid could be described: {}", why.join("; "))));
    }
    Ok(Part { solids, skipped, entity_problems: loaded.entity_problems })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_reader_crash_is_the_file_s_problem_said_without_colour_codes() {
        let died = SidecarError::Died {
            op: "load_step".into(),
            stderr: "\u{1b}[31;1m**** ERR StepReaderData ****\u{1b}[0m\nended by signal 11 (SIGSEGV)".into(),
        };
        let e = classify(Path::new("p.step"), died).to_string();
        assert_eq!(
            e,
            "p.step: the STEP reader crashed on this file; it is probably corrupt (sidecar stderr: ended by signal \
             11 (SIGSEGV))"
        );
        let describe = SidecarError::Died { op: "describe".into(), stderr: String::new() };
        assert!(!classify(Path::new("p.step"), describe).to_string().contains("reader crashed"));
    }
}
