//! `midsurf inspect`: what a part is made of, per solid, as a readable table.

use std::collections::BTreeMap;
use std::fmt::Write;

use serde::Serialize;

use crate::model::face_graph::{Convexity, FaceGraph};

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SolidSummary {
    pub faces: usize,
    pub edges: usize,
    pub vertices: usize,
    pub volume: f64,
    pub area: f64,
    /// 2V/A (see `FaceGraph::thickness_estimate`).
    pub thickness_estimate: f64,
    pub bbox_min: [f64; 3],
    pub bbox_max: [f64; 3],
    pub faces_by_surface: BTreeMap<&'static str, usize>,
    pub edges_by_convexity: BTreeMap<&'static str, usize>,
}

pub fn summarize(graph: &FaceGraph) -> SolidSummary {
    let mut faces_by_surface = BTreeMap::new();
    for face in &graph.faces {
        *faces_by_surface.entry(face.surface.kind_name()).or_insert(0) += 1;
    }
    let mut edges_by_convexity = BTreeMap::new();
    for edge in &graph.edges {
        *edges_by_convexity.entry(edge.convexity.name()).or_insert(0) += 1;
    }
    SolidSummary {
        faces: graph.faces.len(),
        edges: graph.edges.len(),
        vertices: graph.vertices.len(),
        volume: graph.volume,
        area: graph.area,
        thickness_estimate: graph.thickness_estimate(),
        bbox_min: graph.bbox.min.to_array(),
        bbox_max: graph.bbox.max.to_array(),
        faces_by_surface,
        edges_by_convexity,
    }
}

/// The table `midsurf inspect` prints for a part's solids.
pub fn render(file: &str, solids: &[SolidSummary]) -> String {
    let mut out = String::new();
    let faces: usize = solids.iter().map(|s| s.faces).sum();
    writeln!(out, "{file}: {} solid(s), {faces} faces", solids.len()).unwrap();
    for (i, s) in solids.iter().enumerate() {
        let size: Vec<String> = (0..3).map(|k| format!("{:.2}", s.bbox_max[k] - s.bbox_min[k])).collect();
        let by_kind: Vec<String> = s.faces_by_surface.iter().map(|(k, n)| format!("{k} {n}")).collect();
        let by_convexity: Vec<String> = Convexity::ALL
            .iter()
            .filter_map(|c| s.edges_by_convexity.get(c.name()).map(|n| format!("{} {n}", c.name())))
            .collect();
        writeln!(out, "solid {}: {} faces, {} edges, {} vertices", i + 1, s.faces, s.edges, s.vertices).unwrap();
        writeln!(out, "  volume      {:.3} mm3", s.volume).unwrap();
        writeln!(out, "  area        {:.3} mm2", s.area).unwrap();
        writeln!(out, "  wall        {:.3} mm (2V/A estimate)", s.thickness_estimate).unwrap();
        writeln!(
            out,
            "  bbox        [{:.2}, {:.2}, {:.2}] .. [{:.2}, {:.2}, {:.2}] ({} mm)",
            s.bbox_min[0],
            s.bbox_min[1],
            s.bbox_min[2],
            s.bbox_max[0],
            s.bbox_max[1],
            s.bbox_max[2],
            size.join(" x ")
        )
        .unwrap();
        writeln!(out, "  surfaces    {}", by_kind.join(", ")).unwrap();
        writeln!(out, "  edges       {}", by_convexity.join(", ")).unwrap();
    }
    out
}
