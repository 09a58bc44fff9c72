//! The topology summary of the mid-surface (DESIGN.md section 9): counts, Euler characteristic, free edges,
//! patches and joints, with floats rounded and everything sorted so it is stable enough for snapshots.

use serde::Serialize;

use super::round;
use crate::model::shapes::Shells;
use crate::pairing::PairKind;
use crate::stitch::{FreeEdges, JointReport};

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Topology {
    pub faces: usize,
    pub edges: usize,
    pub vertices: usize,
    /// V - E + F.
    pub euler: i64,
    /// Edge-connected sets of faces written: one per connected part wanted.
    pub components: usize,
    /// Edges shared by three or more faces (T- and X-joints), in the file written.
    pub nonmanifold_edges: usize,
    /// Edges used by one face, in the file written (`free_edges` below sorts those of the stitched result into
    /// rim and open; a free edge of a face closed on itself is written as two).
    pub free_edge_count: usize,
    pub free_edges: Option<FreeEdges>,
    pub patches: Vec<TopologyPatch>,
    pub joints: Vec<JointReport>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TopologyPatch {
    pub id: usize,
    pub kind: PairKind,
    pub source_faces: Vec<usize>,
    pub thickness: f64,
    pub area: f64,
    pub faces: usize,
}

pub fn summarise(
    shells: &Shells,
    patches: Vec<TopologyPatch>,
    joints: &[JointReport],
    free: Option<FreeEdges>,
) -> Topology {
    let faces = shells.faces.len();
    let mut joints: Vec<JointReport> =
        joints.iter().map(|j| JointReport { length: round(j.length, 2), ..j.clone() }).collect();
    joints.sort_by(|a, b| (&a.patches, a.kind, a.status).cmp(&(&b.patches, b.kind, b.status)));
    Topology {
        faces,
        edges: shells.edges,
        vertices: shells.vertices,
        euler: shells.vertices as i64 - shells.edges as i64 + faces as i64,
        components: shells.components,
        nonmanifold_edges: shells.nonmanifold_edges,
        free_edge_count: shells.free_edges,
        free_edges: free.map(|f| FreeEdges {
            rim_length: round(f.rim_length, 2),
            open_length: round(f.open_length, 2),
            ..f
        }),
        patches,
        joints,
    }
}

impl Topology {
    /// The stable text form (`midsurf run --summary`), one fact per line.
    pub fn text(&self) -> String {
        let mut out = format!(
            "faces {}  edges {}  vertices {}  euler {}  components {}  nonmanifold_edges {}\n",
            self.faces, self.edges, self.vertices, self.euler, self.components, self.nonmanifold_edges
        );
        match &self.free_edges {
            Some(f) => {
                out += &format!(
                    "free edges: rim {} ({:.2} mm), open {} ({:.2} mm)\n",
                    f.rim_edges, f.rim_length, f.open_edges, f.open_length
                )
            }
            None => out += "free edges: not classified (stitching failed)\n",
        }
        for p in &self.patches {
            out += &format!(
                "patch {} {} t={:.3} area={:.1} faces={} source={:?}\n",
                p.id,
                p.kind.name(),
                p.thickness,
                p.area,
                p.faces,
                p.source_faces
            );
        }
        for j in &self.joints {
            let ids: Vec<String> = j.patches.iter().map(usize::to_string).collect();
            out +=
                &format!("joint {} {} {} edges={} length={:.2}\n", ids.join("-"), j.kind, j.status, j.edges, j.length);
        }
        out
    }
}
