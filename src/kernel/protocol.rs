//! Messages of the sidecar protocol (sidecar/PROTOCOL.md): typed requests, reply decoding.

use serde::{Deserialize, Serialize};
use serde_json::Value;

use super::SidecarError;

/// Bump together with `PROTOCOL_VERSION` in sidecar/midsurf_sidecar.
pub const PROTOCOL_VERSION: u32 = 2;

/// A face's attributes in the output STEP.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FaceAttributes {
    pub face: usize,
    pub name: String,
    pub color: [f64; 3],
    pub thickness: f64,
}

/// A solid of the input written as it is beside the mid-surface (one that is not thin-walled), named.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct KeptSolid {
    pub handle: u64,
    pub name: String,
}

/// Where a mid-patch goes: its faces offset along their outward normals, or projected onto a plane.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Placement {
    Offset(f64),
    Plane { origin: [f64; 3], normal: [f64; 3] },
}

/// Partner faces per requested face (same order), the fuzzy tolerance of the cut, the widths up to which
/// uncovered pieces stay: `narrow` between two covered pieces, `narrow_end` elsewhere; and per requested face
/// the faces whose footprint (holes and all) goes to other patches whatever its width; the wall's thickness, the
/// step from the patch to mid-wall along the faces' outward normals and the thickest wall that pairs whatever its
/// width, with which a narrow piece at a dead end that reaches far from the covered pieces (a tongue) is tested
/// for lying on another wall, whose own patch covers it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Clip {
    pub partners: Vec<Vec<usize>>,
    pub fuzzy: f64,
    pub narrow: f64,
    pub narrow_end: f64,
    #[serde(skip_serializing_if = "none_excluded")]
    pub exclude: Vec<Vec<usize>>,
    pub thickness: f64,
    pub to_mid: f64,
    pub wall_max: f64,
}

fn none_excluded(exclude: &[Vec<usize>]) -> bool {
    exclude.iter().all(Vec::is_empty)
}

/// A free edge of a fused shape, seen from its face.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EdgeRef {
    pub edge: usize,
    pub face: usize,
}

/// A strip grown outward from `edge` of `face`, by `lengths[k]` at the k-th of evenly spaced samples.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StripRequest {
    pub edge: usize,
    pub face: usize,
    pub lengths: Vec<f64>,
    /// The edge grows onto the partner's face (a T-joint), not toward a strip grown from the partner.
    pub onto_face: bool,
    /// The edge swept straight by this vector instead (an upright band across a thickness step whose two edges
    /// are one curve at two levels); `lengths` only set how it is sampled.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub along: Option<glam::DVec3>,
}

/// A quad closing the notch between two strips at a corner of a patch, oriented along the patch's normal. With
/// `axis` (a point on it and its direction) the quad is a band between two coaxial arcs instead: from points[0]
/// to points[3] and from points[1] to points[2], each turning counter-clockwise about the direction.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CornerRequest {
    pub points: [glam::DVec3; 4],
    pub normal: glam::DVec3,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub axis: Option<[glam::DVec3; 2]>,
}

/// Faces (indices of MapShapes(FACE)) of the shape behind `handle`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GatherPart {
    pub handle: u64,
    pub faces: Vec<usize>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "op", content = "args", rename_all = "snake_case")]
pub enum Request {
    Hello {
        protocol: u32,
    },
    /// A liveness check midsurf itself does not send (the client's tests and the sidecar's do).
    #[allow(dead_code)]
    Ping {},
    LoadStep {
        path: String,
    },
    Describe {
        handle: u64,
        mesh: bool,
        mesh_tolerance: f64,
    },
    /// The triangles of every face of a shape, without the rest of its face graph.
    Mesh {
        handle: u64,
        mesh_tolerance: f64,
    },
    /// `clip`: each face cut to the footprint of its partners (planar faces only).
    MakePatch {
        handle: u64,
        faces: Vec<usize>,
        #[serde(flatten)]
        placement: Placement,
        #[serde(skip_serializing_if = "Option::is_none")]
        clip: Option<Clip>,
        /// Turn the new faces over (their normal then points into the source face's material).
        #[serde(skip_serializing_if = "std::ops::Not::not")]
        reverse: bool,
        /// Each face goes halfway to its clip partners point by point (a tapered wall); `offset` is the step
        /// where none lies across.
        #[serde(skip_serializing_if = "std::ops::Not::not")]
        mid_wall: bool,
        /// Solid edge ids of suppressed features: the inner loops of the faces holding them are filled first.
        #[serde(skip_serializing_if = "Vec::is_empty")]
        fill: Vec<usize>,
    },
    /// `split_internal`: split faces along joints that end inside them (for the final result only).
    /// `patches_fused`: each patch's faces already share their edges (it comes out of a fuse), so each patch is
    /// one argument of the fuse, not each face. `bodies`: the body of each patch, when they are not all one
    /// (patches of different bodies are fused apart). `settled`: the patches (indices into `patches`) taken
    /// unchanged from one earlier fuse: together one argument, not intersected with each other again.
    Fuse {
        patches: Vec<u64>,
        fuzzy: f64,
        #[serde(skip_serializing_if = "std::ops::Not::not")]
        split_internal: bool,
        #[serde(skip_serializing_if = "std::ops::Not::not")]
        patches_fused: bool,
        #[serde(skip_serializing_if = "Vec::is_empty")]
        bodies: Vec<usize>,
        #[serde(skip_serializing_if = "Vec::is_empty")]
        settled: Vec<usize>,
    },
    MakeShells {
        handle: u64,
        shells: Vec<Vec<usize>>,
        merge: Vec<Vec<usize>>,
        fuzzy: f64,
    },
    ProbeEdges {
        handle: u64,
        edges: Vec<EdgeRef>,
        targets: Vec<usize>,
        samples: usize,
        reach: f64,
    },
    ExtendEdges {
        handle: u64,
        strips: Vec<StripRequest>,
        corners: Vec<CornerRequest>,
    },
    /// With `unify` (a fuzzy tolerance), the faces are joined and same-surface faces merged.
    Gather {
        parts: Vec<GatherPart>,
        #[serde(skip_serializing_if = "Option::is_none")]
        unify: Option<f64>,
    },
    /// `preview`: also a binary glTF of the same faces and colours at that path.
    WriteStep {
        path: String,
        handle: u64,
        faces: Vec<FaceAttributes>,
        #[serde(skip_serializing_if = "Option::is_none")]
        preview: Option<String>,
        /// Solids of the input written too, each as its own named shape.
        #[serde(skip_serializing_if = "Vec::is_empty")]
        solids: Vec<KeptSolid>,
        /// Read the file back and name the faces that fail BRepCheck there.
        #[serde(skip_serializing_if = "std::ops::Not::not")]
        check: bool,
    },
    /// Frees kernel shapes; midsurf runs one part per process and sends none.
    #[allow(dead_code)]
    Free {
        handles: Vec<u64>,
    },
    Shutdown {},
}

impl Request {
    pub fn op(&self) -> &'static str {
        match self {
            Request::Hello { .. } => "hello",
            Request::Ping {} => "ping",
            Request::LoadStep { .. } => "load_step",
            Request::Describe { .. } => "describe",
            Request::Mesh { .. } => "mesh",
            Request::MakePatch { .. } => "make_patch",
            Request::Fuse { .. } => "fuse",
            Request::MakeShells { .. } => "make_shells",
            Request::ProbeEdges { .. } => "probe_edges",
            Request::ExtendEdges { .. } => "extend_edges",
            Request::Gather { .. } => "gather",
            Request::WriteStep { .. } => "write_step",
            Request::Free { .. } => "free",
            Request::Shutdown {} => "shutdown",
        }
    }
}

#[derive(Serialize)]
struct Envelope<'a> {
    id: u64,
    #[serde(flatten)]
    request: &'a Request,
}

/// The single line (without newline) that carries `request` with `id`.
pub fn encode(id: u64, request: &Request) -> String {
    serde_json::to_string(&Envelope { id, request }).expect("protocol requests always serialise")
}

/// Decodes a reply line for request `id`: the `ok` payload, or the sidecar's `err` as an error.
pub fn decode(id: u64, op: &str, line: &str) -> Result<Value, SidecarError> {
    let bad = |why: String| SidecarError::BadReply { op: op.to_string(), why, line: clip(line) };
    let mut value: Value = serde_json::from_str(line).map_err(|e| bad(format!("not JSON ({e})")))?;
    let got = value.get("id").and_then(Value::as_u64);
    if got != Some(id) {
        return Err(bad(format!("reply id {got:?} for request {id}")));
    }
    if let Some(ok) = value.get_mut("ok") {
        return Ok(ok.take());
    }
    match value.get("err") {
        Some(err) => Err(SidecarError::Op {
            op: op.to_string(),
            code: err.get("code").and_then(Value::as_str).unwrap_or("unknown").to_string(),
            message: err.get("message").and_then(Value::as_str).unwrap_or("").to_string(),
        }),
        None => Err(bad("neither ok nor err".to_string())),
    }
}

fn clip(line: &str) -> String {
    const MAX: usize = 200;
    match line.char_indices().nth(MAX) {
        Some((at, _)) => format!("{}...", &line[..at]),
        None => line.to_string(),
    }
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Hello {
    pub protocol: u32,
    pub python: String,
    pub occt: String,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct LoadedSolid {
    pub handle: u64,
    pub faces: usize,
    pub volume: f64,
    pub area: f64,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Loaded {
    pub solids: Vec<LoadedSolid>,
    /// The reader's syntax and reference failures, per entity (none for a clean file).
    #[serde(default)]
    pub entity_problems: Vec<EntityProblem>,
}

/// An entity of the STEP file the reader could not read as written.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct EntityProblem {
    /// Its number in the file (`#N`), when known.
    pub entity: Option<u64>,
    pub message: String,
    /// Another entity refers to it, so what it stands for is missing from the shape.
    pub used: bool,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Written {
    pub path: String,
    pub bytes: u64,
    /// With `check`: whether the file reads back valid, and the faces (index in the written shape) whose
    /// read-back face fails BRepCheck.
    #[serde(default)]
    pub valid: Option<bool>,
    #[serde(default)]
    pub invalid: Vec<usize>,
    /// With `check`: the largest edge tolerance of the file read back.
    #[serde(default)]
    pub max_edge_tolerance: Option<f64>,
    /// With `check`: the edges of the file read back used by one face only.
    #[serde(default)]
    pub free_edges: Option<usize>,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct PatchFace {
    pub source: usize,
    pub area: f64,
    pub centroid: glam::DVec3,
    pub normal: glam::DVec3,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct MadePatch {
    pub handle: u64,
    pub faces: Vec<PatchFace>,
    /// Inner loops filled (those holding an edge of `fill`).
    #[serde(default)]
    pub filled: usize,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct FusedFace {
    pub patch: usize,
    pub area: f64,
    pub centroid: glam::DVec3,
    /// A point on the face (its UV centre when that lies inside); `normal` is the face's normal there.
    pub point: glam::DVec3,
    pub normal: glam::DVec3,
    pub edges: Vec<usize>,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct FusedEdge {
    pub length: f64,
    pub faces: Vec<usize>,
    pub points: Vec<glam::DVec3>,
    /// The faces (of `faces`) that hold the edge inside them (INTERNAL), not on their boundary.
    #[serde(default)]
    pub inside: Vec<usize>,
    /// Made by the cut across the end of a stem crossing the face (sidecar `_stem_end_cuts`).
    #[serde(default)]
    pub stem_end: bool,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Fused {
    pub handle: u64,
    pub faces: Vec<FusedFace>,
    pub edges: Vec<FusedEdge>,
    #[serde(default)]
    pub invalid: Vec<usize>,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Shells {
    pub handle: u64,
    pub shells: usize,
    /// Edge-connected pieces of the shells (several manifold shells meet at a T-joint's edge).
    pub components: usize,
    pub faces: Vec<usize>,
    pub valid: bool,
    /// Faces (indices into `faces`) that fail the kernel's check on their own; empty when `valid`.
    pub invalid: Vec<usize>,
    pub edges: usize,
    pub vertices: usize,
    /// Edges used by one face of the shells written, and by three or more (see model::shapes::Shells).
    pub free_edges: usize,
    pub nonmanifold_edges: usize,
}

/// Where a ray along a free edge's outward direction meets a target face's support surface.
/// The `mesh` reply: one mesh per face of the shape, in its face order.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct FaceMeshes {
    pub faces: Vec<crate::model::face_graph::Mesh>,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Hit {
    pub face: usize,
    /// Along the ray, from the edge.
    pub distance: f64,
    /// From the meeting point to the face itself: 0 on the face, more beyond its boundary.
    pub gap: f64,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct EdgeProbe {
    pub points: Vec<glam::DVec3>,
    pub normals: Vec<glam::DVec3>,
    pub outward: Vec<glam::DVec3>,
    /// Per sample, nearest first.
    pub hits: Vec<Vec<Hit>>,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Probed {
    pub edges: Vec<EdgeProbe>,
}

/// One requested strip: made (its area; the made strips are the faces of `Extended::handle`, in request
/// order) or not (the kernel's reason).
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct MadeStrip {
    pub area: Option<f64>,
    pub error: Option<String>,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Extended {
    pub handle: u64,
    pub strips: Vec<MadeStrip>,
    /// Made corners follow the made strips among the faces of `handle`.
    pub corners: Vec<MadeStrip>,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Gathered {
    pub handle: u64,
    pub faces: usize,
}

#[cfg(test)]
#[path = "protocol_tests.rs"]
mod tests;
