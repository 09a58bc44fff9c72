//! The shapes the kernel hands back, as the stages use them: the fused patches with their faces and edges, the
//! shells written, and the probes of free edges. The kernel converts its wire replies into these
//! (`kernel::convert`), so a change of the protocol stops at the kernel.

use glam::DVec3;

/// The kernel's name for a shape it holds.
pub type Handle = u64;

/// Where a mid-patch goes: its faces offset along their outward normals, or projected onto a plane.
#[derive(Debug, Clone, PartialEq)]
pub enum Placement {
    Offset(f64),
    Plane { origin: [f64; 3], normal: [f64; 3] },
}

/// The patches fused into one shape, split where they cross.
#[derive(Debug, Clone, PartialEq)]
pub struct Fused {
    pub handle: Handle,
    pub faces: Vec<FusedFace>,
    pub edges: Vec<FusedEdge>,
    /// The faces (indices into `faces`) that fail the kernel's check (BRepCheck), as found by a stitching
    /// pass's fuse (`FuseKind::Again`); empty otherwise.
    pub invalid: Vec<usize>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct FusedFace {
    /// The patch (index among the patches fused) the piece comes from.
    pub patch: usize,
    pub area: f64,
    pub centroid: DVec3,
    /// A point on the face (its UV centre when that lies inside); `normal` is the face's normal there.
    pub point: DVec3,
    pub normal: DVec3,
    pub edges: Vec<usize>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct FusedEdge {
    pub length: f64,
    pub faces: Vec<usize>,
    pub points: Vec<DVec3>,
    /// The faces (of `faces`) that hold the edge inside them (an INTERNAL edge: a joint ending inside a face
    /// along a curve that could not split it). A STEP file keeps no such edge: it joins nothing once written.
    pub inside: Vec<usize>,
    /// A cut across the end of a stem (a tube) crossing the face, where the face runs on past the stem: it
    /// parts the face's stretch inside the stem's wall from the stretch beyond (see `trim::find_branches`).
    pub stem_end: bool,
}

/// The shells made of the kept faces of a fused shape.
#[derive(Debug, Clone, PartialEq)]
pub struct Shells {
    pub handle: Handle,
    /// How many shells were written: manifold shells, several sharing a T-joint's edge, and more than the sets
    /// asked for where faces joined only through an edge inside one of them (which a STEP file does not keep)
    /// were split apart.
    pub count: usize,
    /// Edge-connected pieces of the shells: one per connected part wanted.
    pub components: usize,
    /// Per face of the shells, the fused face it is (a face closed on itself may be written as two pieces).
    pub faces: Vec<usize>,
    pub valid: bool,
    /// Faces (indices into `faces`) that fail the kernel's check on their own; empty when `valid`.
    pub invalid: Vec<usize>,
    pub edges: usize,
    pub vertices: usize,
    /// Edges used by one face of the shells, and by three or more: counted on the shells written, where a free
    /// or T edge of a face closed on itself may be written as two edges.
    pub free_edges: usize,
    pub nonmanifold_edges: usize,
}

/// Where a ray along a free edge's outward direction meets a target face's support surface.
#[derive(Debug, Clone, PartialEq)]
pub struct Hit {
    pub face: usize,
    /// Along the ray, from the edge.
    pub distance: f64,
    /// From the meeting point to the face itself: 0 on the face, more beyond its boundary.
    pub gap: f64,
}

/// A free edge sampled: per sample its point, the patch's normal, the outward direction in the patch's tangent
/// plane, and the faces the outward ray meets, nearest first.
#[derive(Debug, Clone, PartialEq)]
pub struct EdgeProbe {
    pub points: Vec<DVec3>,
    pub normals: Vec<DVec3>,
    pub outward: Vec<DVec3>,
    pub hits: Vec<Vec<Hit>>,
}
