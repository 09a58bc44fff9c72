//! The two Python processes behind `midsurf mesh` (package `sidecar/midsurf_mesher`): one reads the named
//! faces of the mid-surface with OCP, the other meshes it with the gmsh wheel. They are separate processes
//! because gmsh brings its own OCCT, which must not share a process with OCP's.

use std::io::Write;
use std::path::Path;
use std::process::{Command, Stdio};

use serde::{Deserialize, Serialize};

use crate::error::Error;
use crate::kernel::python;

/// A face of the mid-surface STEP as midsurf named it (`patch <id> t=<thickness>`), with its geometry.
#[derive(Debug, Clone, Deserialize)]
pub struct NamedFace {
    pub name: String,
    pub area: f64,
    pub centroid: [f64; 3],
    /// Unit normal at `point`, oriented as the face (out of its wall's top side).
    pub point: [f64; 3],
    pub normal: [f64; 3],
}

#[derive(Debug, Deserialize)]
struct FacesReply {
    faces: Vec<NamedFace>,
}

/// A gmsh surface: its geometry (to be matched to a named face) and its elements.
#[derive(Debug, Clone, Deserialize)]
pub struct GmshSurface {
    pub tag: i64,
    pub area: f64,
    pub centroid: [f64; 3],
}

#[derive(Debug, Clone, Deserialize)]
pub struct GmshElements {
    pub surface: i64,
    pub quads: Vec<[usize; 4]>,
    pub trias: Vec<[usize; 3]>,
}

#[derive(Debug, Clone, Deserialize)]
pub struct GmshMesh {
    pub gmsh: String,
    pub surfaces: Vec<GmshSurface>,
    pub nodes: Vec<[f64; 3]>,
    /// Dimension of the CAD entity each node lies on: 0 a vertex, 1 a curve, 2 a surface's inside.
    pub node_dims: Vec<u8>,
    pub elements: Vec<GmshElements>,
    /// "meshed", or why the whole model did not mesh at once (then the surfaces were meshed one by one).
    pub whole_model: String,
    pub retried: Vec<RetriedSurface>,
    pub unmeshed: Vec<UnmeshedSurface>,
    /// The first errors gmsh logged.
    pub gmsh_errors: Vec<String>,
    /// "fixed" when gmsh ran without address space randomisation (the same request then gives the same mesh:
    /// gmsh orders some entities by address), else "random".
    pub address_layout: String,
}

/// A surface meshed on its own after the whole model failed: `how` names the attempt that worked.
#[derive(Debug, Clone, Deserialize)]
pub struct RetriedSurface {
    pub surface: i64,
    pub how: String,
}

/// A surface no attempt could mesh, and the last attempt's failure.
#[derive(Debug, Clone, Deserialize)]
pub struct UnmeshedSurface {
    pub surface: i64,
    pub why: String,
}

#[derive(Debug, Serialize)]
pub struct MeshRequest<'a> {
    pub path: &'a Path,
    pub size: f64,
    pub all_quads: bool,
    /// An attempt (the whole model, or one surface) counts as hung after `time_floor_s` plus
    /// `time_per_element_s` per expected element.
    pub time_floor_s: f64,
    pub time_per_element_s: f64,
    pub expected_elements: f64,
}

/// A gmsh attempt gets this long at least: a small surface meshes in milliseconds, a hung one never ends.
pub const TIME_FLOOR_S: f64 = 10.0;
/// And this long per expected element: gmsh meshed the corpus at about 0.3 ms per element (133712 elements
/// in 42 s), so a surface or model gets 6 times that before it is given up.
pub const TIME_PER_ELEMENT_S: f64 = 2e-3;

/// The named faces of `step`, in the file's face order.
pub fn named_faces(step: &Path) -> Result<Vec<NamedFace>, Error> {
    let path = step.to_string_lossy().into_owned();
    let reply: FacesReply = run(step, &["faces", &path], None)?;
    Ok(reply.faces)
}

/// The gmsh mesh of `request.path`.
pub fn gmsh_mesh(request: &MeshRequest) -> Result<GmshMesh, Error> {
    let input = serde_json::to_string(request).expect("requests always serialise");
    run(request.path, &["mesh"], Some(&input))
}

fn run<R: serde::de::DeserializeOwned>(step: &Path, args: &[&str], stdin: Option<&str>) -> Result<R, Error> {
    let launch = python::locate().map_err(|e| Error::input(step, format!("cannot start the mesher: {e}")))?;
    let mut child = Command::new(&launch.python)
        .arg("-m")
        .arg("midsurf_mesher")
        .args(args)
        .env("PYTHONPATH", &launch.sidecar_dir)
        .env("MIDSURF_PARENT_PID", std::process::id().to_string())
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| Error::input(step, format!("cannot start {}: {e}", launch.python.display())))?;
    if let Some(text) = stdin {
        let mut pipe = child.stdin.take().expect("stdin is piped");
        pipe.write_all(text.as_bytes()).map_err(|e| Error::input(step, format!("mesher: {e}")))?;
    }
    drop(child.stdin.take());
    let out = child.wait_with_output().map_err(|e| Error::input(step, format!("mesher: {e}")))?;
    if !out.status.success() {
        let stderr = String::from_utf8_lossy(&out.stderr);
        let tail: Vec<&str> = stderr.lines().rev().filter(|l| !l.trim().is_empty()).take(1).collect();
        return Err(Error::input(
            step,
            format!("mesher `{}` failed ({}): {}", args[0], out.status, tail.first().unwrap_or(&"no message")),
        ));
    }
    serde_json::from_slice(&out.stdout)
        .map_err(|e| Error::input(step, format!("mesher `{}` gave an unreadable reply: {e}", args[0])))
}
