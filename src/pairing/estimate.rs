//! The default t_max, estimated from the part when the user gives none.
//!
//! Pairs are searched with a generous bound (four times the 2V/A wall estimate, at most the part's smallest
//! extent); their uniform thicknesses (parallel and cylindrical pairs) are clustered and weighted by overlap
//! area. The heaviest cluster is the dominant wall. t_max is 1.5 x the dominant wall, raised to 1.2 x the
//! thickest cluster that still carries 10% of the paired area (parts with several wall gauges).

use serde::Serialize;

use super::{candidates, criteria, PairKind};
use crate::model::face_graph::FaceGraph;
use crate::model::tolerance::Tolerances;

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ThicknessCluster {
    pub thickness: f64,
    pub overlap_area: f64,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TMaxEstimate {
    pub t_max: f64,
    /// The dominant wall thickness (None when no wall was found).
    pub dominant: Option<f64>,
    pub clusters: Vec<ThicknessCluster>,
    pub method: String,
    /// How thick a pair the search accepted (four times the 2V/A wall, at most the smallest extent): the safety
    /// bound on walls thicker than t_max that are thin for their width.
    pub search_bound: f64,
}

/// Relative width of a thickness cluster: gauges of one sheet differ by less than 2%.
const CLUSTER_WIDTH: f64 = 0.02;
/// t_max over the dominant wall: room for local thickening and bosses, not for a second wall across a gap.
const DOMINANT_FACTOR: f64 = 1.5;
/// t_max over the thickest significant gauge.
const GAUGE_FACTOR: f64 = 1.2;
const SIGNIFICANT_SHARE: f64 = 0.10;

/// The smallest extent of the part bounds the search with this relative slack, so that a wall as thick as the
/// part (a plain plate) still pairs despite float noise in its box.
const EXTENT_SLACK: f64 = 1e-6;

pub fn estimate_t_max(graph: &FaceGraph, draft_max: f64) -> TMaxEstimate {
    let wall = graph.thickness_estimate();
    let smallest_extent = graph.bbox.size().min_element();
    let bound = (4.0 * wall).min(smallest_extent * (1.0 + EXTENT_SLACK));
    let tol = Tolerances::new(graph.bbox.diagonal(), bound, draft_max);
    let mut samples: Vec<(f64, f64)> = candidates::candidate_pairs(graph, bound)
        .into_iter()
        .filter_map(|(a, b)| criteria::test_pair(graph, a, b, &tol).ok())
        .filter(|p| matches!(p.kind, PairKind::Parallel | PairKind::Cylindrical))
        .map(|p| (p.thickness.mean, p.overlap_area))
        .collect();
    samples.sort_by(|x, y| x.0.total_cmp(&y.0));
    let clusters = cluster(&samples);
    let total: f64 = clusters.iter().map(|c| c.overlap_area).sum();
    let Some(dominant) = clusters.iter().max_by(|x, y| x.overlap_area.total_cmp(&y.overlap_area)) else {
        return TMaxEstimate {
            t_max: DOMINANT_FACTOR * wall,
            dominant: None,
            clusters,
            method: format!("no parallel walls found: {DOMINANT_FACTOR} x 2V/A ({wall:.4})"),
            search_bound: bound,
        };
    };
    let thickest = clusters
        .iter()
        .filter(|c| c.overlap_area >= SIGNIFICANT_SHARE * total)
        .map(|c| c.thickness)
        .fold(0.0, f64::max);
    let t_max = (DOMINANT_FACTOR * dominant.thickness).max(GAUGE_FACTOR * thickest);
    TMaxEstimate {
        t_max,
        dominant: Some(dominant.thickness),
        method: format!(
            "max({DOMINANT_FACTOR} x dominant wall {:.4}, {GAUGE_FACTOR} x thickest wall with >= {}% of paired area {:.4})",
            dominant.thickness,
            SIGNIFICANT_SHARE * 100.0,
            thickest
        ),
        clusters,
        search_bound: bound,
    }
}

/// Groups sorted (thickness, weight) samples whose neighbours differ by under `CLUSTER_WIDTH`.
fn cluster(sorted: &[(f64, f64)]) -> Vec<ThicknessCluster> {
    let mut out: Vec<(f64, f64, f64)> = Vec::new(); // (weighted sum, weight, last thickness)
    for &(t, w) in sorted {
        match out.last_mut() {
            Some(c) if t - c.2 <= CLUSTER_WIDTH * t => {
                c.0 += t * w;
                c.1 += w;
                c.2 = t;
            }
            _ => out.push((t * w, w, t)),
        }
    }
    out.into_iter()
        .filter(|c| c.1 > 0.0)
        .map(|(sum, w, _)| ThicknessCluster { thickness: sum / w, overlap_area: w })
        .collect()
}
