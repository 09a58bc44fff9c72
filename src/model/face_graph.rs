//! The face graph of one solid, as the sidecar's `describe` returns it (sidecar/PROTOCOL.md).
//!
//! Topology (ids, adjacency, loops) and geometry (surfaces, points, normals) are kept in separate fields so that
//! algorithms can work on ids and look geometry up by id. Ids are indices into the vectors: stable for a given
//! input because the sidecar numbers shapes in `TopExp::MapShapes` order.

use std::sync::OnceLock;

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::geom::inside::SolidMesh;

pub type FaceId = usize;
pub type EdgeId = usize;
pub type VertexId = usize;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Bbox {
    pub min: DVec3,
    pub max: DVec3,
}

impl Bbox {
    pub fn size(&self) -> DVec3 {
        self.max - self.min
    }

    pub fn diagonal(&self) -> f64 {
        self.size().length()
    }

    pub fn inflated(&self, by: f64) -> Bbox {
        Bbox { min: self.min - DVec3::splat(by), max: self.max + DVec3::splat(by) }
    }

    pub fn overlaps(&self, other: &Bbox) -> bool {
        self.min.cmple(other.max).all() && other.min.cmple(self.max).all()
    }
}

/// The analytic type of a face's surface. `convex` tells on which side the material is: true when the outward
/// normal points away from the axis / centre (a shaft, the outside of a bend), false toward it (a hole).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Surface {
    Plane { origin: DVec3, normal: DVec3 },
    Cylinder { origin: DVec3, axis: DVec3, radius: f64, convex: bool },
    Cone { origin: DVec3, axis: DVec3, radius: f64, half_angle: f64, apex: DVec3, convex: bool },
    Sphere { center: DVec3, radius: f64, convex: bool },
    Torus { center: DVec3, axis: DVec3, major_radius: f64, minor_radius: f64, convex: bool },
    Bspline,
    Bezier,
    Revolution,
    Extrusion,
    Offset,
    Other,
}

impl Surface {
    /// A short name for tables and reports.
    pub fn kind_name(&self) -> &'static str {
        match self {
            Surface::Plane { .. } => "plane",
            Surface::Cylinder { .. } => "cylinder",
            Surface::Cone { .. } => "cone",
            Surface::Sphere { .. } => "sphere",
            Surface::Torus { .. } => "torus",
            Surface::Bspline => "bspline",
            Surface::Bezier => "bezier",
            Surface::Revolution => "revolution",
            Surface::Extrusion => "extrusion",
            Surface::Offset => "offset",
            Surface::Other => "other",
        }
    }

    pub fn is_plane(&self) -> bool {
        matches!(self, Surface::Plane { .. })
    }

    /// A plane or a cylinder: a face that can be a band of a wall, flat or running round a corner.
    pub fn is_flat_or_round(&self) -> bool {
        matches!(self, Surface::Plane { .. } | Surface::Cylinder { .. })
    }

    /// Freeform surfaces carry no analytic parameters: pairing them needs the mesh.
    pub fn is_freeform(&self) -> bool {
        !matches!(
            self,
            Surface::Plane { .. }
                | Surface::Cylinder { .. }
                | Surface::Cone { .. }
                | Surface::Sphere { .. }
                | Surface::Torus { .. }
        )
    }
}

/// A triangulation of one face; triangles are counter-clockwise seen from outside the solid.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Mesh {
    pub vertices: Vec<DVec3>,
    pub normals: Vec<DVec3>,
    pub triangles: Vec<[u32; 3]>,
    #[serde(skip)]
    pub index: TriangleIndex,
}

impl Mesh {
    /// Distance along `dir` (unit) from `p` to the nearest triangle of this mesh that `accept` takes and the ray
    /// meets within `reach` (`SolidMesh::nearest_where`, on an R-tree of the triangles built on first use).
    pub fn nearest_hit(&self, p: DVec3, dir: DVec3, reach: f64, accept: impl Fn(&[DVec3; 3]) -> bool) -> Option<f64> {
        self.index.0.get_or_init(|| SolidMesh::of_meshes([self])).nearest_where(p, dir, reach, accept)
    }
}

/// A mesh's triangles in an R-tree, made on first use: a perforated skin has tens of thousands of triangles and
/// every hole's wall casts rays at it. Derived from the mesh: it compares equal to any other and is never
/// serialized.
#[derive(Clone, Default)]
pub struct TriangleIndex(OnceLock<SolidMesh>);

impl PartialEq for TriangleIndex {
    fn eq(&self, _: &TriangleIndex) -> bool {
        true
    }
}

impl std::fmt::Debug for TriangleIndex {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(if self.0.get().is_some() { "TriangleIndex(built)" } else { "TriangleIndex" })
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Face {
    pub id: FaceId,
    pub surface: Surface,
    pub reversed: bool,
    /// A point inside the face and the outward unit normal there.
    pub point: DVec3,
    pub normal: DVec3,
    pub area: f64,
    pub centroid: DVec3,
    pub bbox: Bbox,
    /// Outer loop first; edge ids in wire order.
    pub loops: Vec<Vec<EdgeId>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mesh: Option<Mesh>,
    /// Why the kernel could not describe this face whole (no mesh, no point inside it, an edge without a
    /// convexity): the face stays in the graph, so ids and edges hold, but is never paired.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub problem: Option<String>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Convexity {
    Convex,
    Concave,
    Smooth,
    Seam,
    Free,
    Degenerate,
}

impl Convexity {
    pub const ALL: [Convexity; 6] = [
        Convexity::Convex,
        Convexity::Concave,
        Convexity::Smooth,
        Convexity::Seam,
        Convexity::Free,
        Convexity::Degenerate,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Convexity::Convex => "convex",
            Convexity::Concave => "concave",
            Convexity::Smooth => "smooth",
            Convexity::Seam => "seam",
            Convexity::Free => "free",
            Convexity::Degenerate => "degenerate",
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Edge {
    pub id: EdgeId,
    pub vertices: [VertexId; 2],
    /// Adjacent faces, sorted; a single entry for a seam or a free edge.
    pub faces: Vec<FaceId>,
    pub convexity: Convexity,
    /// Signed angle between the outward normals of the two faces (radians, > 0 convex).
    pub angle: f64,
    pub length: f64,
    pub curve: String,
    pub midpoint: DVec3,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FaceGraph {
    pub volume: f64,
    pub area: f64,
    pub bbox: Bbox,
    pub vertices: Vec<DVec3>,
    pub faces: Vec<Face>,
    pub edges: Vec<Edge>,
}

impl FaceGraph {
    /// Wall-thickness estimate of a thin-walled solid: a wall of thickness t has volume A_skin * t and two skins,
    /// so t ~ 2V/A. Side faces make A slightly larger, so this slightly underestimates.
    pub fn thickness_estimate(&self) -> f64 {
        if self.area > 0.0 {
            2.0 * self.volume / self.area
        } else {
            0.0
        }
    }

    /// Mean width of a face, 2 x area / perimeter: the width of a long band, the radius of a disc. Unbounded
    /// for a face without edges (a hand-made graph's): nothing says it is narrow.
    pub fn face_width(&self, face: FaceId) -> f64 {
        let perimeter = self.perimeter(face);
        if perimeter > 0.0 {
            2.0 * self.faces[face].area / perimeter
        } else {
            f64::INFINITY
        }
    }

    /// The `[length, width]` of the rectangle with the face's area and perimeter (a square of the face's area for a
    /// face rounder than a square, such as a disc): a long band's length and width.
    pub fn face_size(&self, face: FaceId) -> [f64; 2] {
        let (area, perimeter) = (self.faces[face].area, self.perimeter(face));
        if perimeter <= 0.0 {
            return [f64::INFINITY, f64::INFINITY];
        }
        let half = 0.25 * perimeter;
        if half * half <= area {
            return [area.sqrt(), area.sqrt()];
        }
        let length = half + (half * half - area).sqrt();
        [length, area / length]
    }

    /// Length of all of the face's loops.
    pub fn perimeter(&self, face: FaceId) -> f64 {
        self.faces[face].loops.iter().flatten().map(|&e| self.edges[e].length).sum()
    }

    /// The faces across `edge` from `face`.
    pub fn across(&self, edge: EdgeId, face: FaceId) -> impl Iterator<Item = FaceId> + '_ {
        self.edges[edge].faces.iter().copied().filter(move |&g| g != face)
    }

    /// Faces adjacent to `face` through an edge (excluding itself), sorted and deduplicated.
    pub fn neighbours(&self, face: FaceId) -> Vec<FaceId> {
        self.neighbours_through(face, |_| true)
    }

    /// Faces adjacent to `face` through a smooth (tangent) edge, sorted and deduplicated: where its surface runs
    /// on into another face's.
    pub fn smooth_neighbours(&self, face: FaceId) -> Vec<FaceId> {
        self.neighbours_through(face, |e| e.convexity == Convexity::Smooth)
    }

    /// How far `face` reaches from the plane through `point` along `normal` (unit): the farthest of its mesh's
    /// vertices, or of its box's two corners without a mesh.
    pub fn reach(&self, face: FaceId, point: DVec3, normal: DVec3) -> f64 {
        let f = &self.faces[face];
        let corners = [f.bbox.min, f.bbox.max];
        let vertices = match f.mesh.as_ref() {
            Some(mesh) if !mesh.vertices.is_empty() => &mesh.vertices[..],
            _ => &corners[..],
        };
        vertices.iter().map(|&v| normal.dot(v - point)).fold(f64::NEG_INFINITY, f64::max)
    }

    /// Faces adjacent to `face` through a concave edge, sorted and deduplicated: the walls it stands on or that
    /// stand on it.
    pub fn concave_neighbours(&self, face: FaceId) -> Vec<FaceId> {
        self.neighbours_through(face, |e| e.convexity == Convexity::Concave)
    }

    fn neighbours_through(&self, face: FaceId, through: impl Fn(&Edge) -> bool) -> Vec<FaceId> {
        let mut out: Vec<FaceId> = self.faces[face]
            .loops
            .iter()
            .flatten()
            .filter(|&&e| through(&self.edges[e]))
            .flat_map(|&e| self.edges[e].faces.iter().copied())
            .filter(|&f| f != face)
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Checks the invariants the algorithms rely on; returns every violation found.
    pub fn validate(&self) -> Vec<String> {
        let mut problems = Vec::new();
        for (i, f) in self.faces.iter().enumerate() {
            if f.id != i {
                problems.push(format!("FaceIdNotIndex: face at {i} has id {}", f.id));
            }
            for &e in f.loops.iter().flatten() {
                if e >= self.edges.len() {
                    problems.push(format!("LoopEdgeOutOfRange: face {i} names edge {e}"));
                }
            }
        }
        for (i, e) in self.edges.iter().enumerate() {
            if e.id != i {
                problems.push(format!("EdgeIdNotIndex: edge at {i} has id {}", e.id));
            }
            if e.faces.iter().any(|&f| f >= self.faces.len()) {
                problems.push(format!("EdgeFaceOutOfRange: edge {i} names {:?}", e.faces));
            }
            if e.vertices.iter().any(|&v| v >= self.vertices.len()) {
                problems.push(format!("EdgeVertexOutOfRange: edge {i} names {:?}", e.vertices));
            }
        }
        problems
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn surface_parses_from_protocol_json() {
        let s: Surface =
            serde_json::from_str(r#"{"kind":"cylinder","origin":[0,0,0],"axis":[0,0,1],"radius":3.0,"convex":false}"#)
                .unwrap();
        assert_eq!(s, Surface::Cylinder { origin: DVec3::ZERO, axis: DVec3::Z, radius: 3.0, convex: false });
        let f: Surface = serde_json::from_str(r#"{"kind":"bspline"}"#).unwrap();
        assert!(f.is_freeform());
        assert!(!s.is_freeform());
    }

    #[test]
    fn bbox_overlap_and_inflate() {
        let a = Bbox { min: DVec3::ZERO, max: DVec3::ONE };
        let b = Bbox { min: DVec3::splat(1.5), max: DVec3::splat(2.0) };
        assert!(!a.overlaps(&b));
        assert!(a.inflated(0.5).overlaps(&b));
    }
}
