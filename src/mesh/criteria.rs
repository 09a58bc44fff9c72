//! The criteria that gate `midsurf mesh`'s exit code, checked on the measured quality; each failing one names
//! the patches of its worst elements.

use std::collections::BTreeSet;

use serde::{Deserialize, Serialize};

use super::meshing::UnmeshedFace;
use super::quality::{ElementQuality, Material, Measured};
use super::shell::ShellMesh;

/// Thresholds that gate the exit code; every one is optional. JSON, e.g.
/// `{"min_edge_share_of_size": 0.2, "max_tria_share": 0.1, "min_time_step_s": 2e-7, "max_aspect": 5,
///   "max_warpage_deg": 15, "max_skew_deg": 60, "min_jacobian": 0.5, "mass_ratio": [0.98, 1.02],
///   "max_free_edge_excess": 0.05}`.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Criteria {
    pub min_edge: Option<f64>,
    /// Smallest edge as a share of the target size.
    pub min_edge_share_of_size: Option<f64>,
    pub max_tria_share: Option<f64>,
    pub min_time_step_s: Option<f64>,
    pub max_aspect: Option<f64>,
    pub max_warpage_deg: Option<f64>,
    pub max_skew_deg: Option<f64>,
    pub min_jacobian: Option<f64>,
    /// Shell volume (area x thickness) over the solid's volume must lie in [low, high].
    pub mass_ratio: Option<[f64; 2]>,
    /// Free-edge length of the mesh over the mid-surface's free length, minus 1, at most this (a free mesh
    /// edge where the mid-surface has none: a gap).
    pub max_free_edge_excess: Option<f64>,
}

impl Criteria {
    /// Without a criteria file: the smallest edge at least 0.2 x the target size (a solver's time step falls
    /// with it; 0.2 is the share users accept before they fix a mesh by hand), and no element turned inside
    /// out (a Jacobian below 0: a solver stops on it).
    pub fn default_gate() -> Criteria {
        Criteria { min_edge_share_of_size: Some(0.2), min_jacobian: Some(0.0), ..Default::default() }
    }
}

#[derive(Debug, Clone, Serialize)]
pub struct CriterionResult {
    pub criterion: &'static str,
    pub limit: serde_json::Value,
    pub value: f64,
    pub passed: bool,
    /// Elements failing it, and their patches (first 20 by id): where to look.
    pub failing_elements: usize,
    pub culprit_patches: Vec<usize>,
    /// The failing elements' indices (for the preview).
    #[serde(skip)]
    pub failing: Vec<usize>,
}

/// Checks every criterion given on the total over all parts; each failing one names its worst patches.
pub fn check(
    criteria: &Criteria,
    mesh: &ShellMesh,
    measured: &Measured,
    size: f64,
    material: &Material,
    midsurface_free_length: Option<f64>,
    unmeshed: &[UnmeshedFace],
) -> Vec<CriterionResult> {
    let q = &measured.per_element;
    // Always checked: a face left out of the decks is a hole in the model, whatever the criteria file says.
    let unmeshed_patches: BTreeSet<usize> = unmeshed.iter().filter_map(|u| u.patch).collect();
    let mut out = vec![CriterionResult {
        criterion: "unmeshed_faces",
        limit: serde_json::json!(0),
        value: unmeshed.len() as f64,
        passed: unmeshed.is_empty(),
        failing_elements: 0,
        culprit_patches: unmeshed_patches.into_iter().take(20).collect(),
        failing: vec![],
    }];
    let t = &measured.total;
    let mut element_check = |name: &'static str, limit: f64, value: f64, fails: &dyn Fn(&ElementQuality) -> bool| {
        let failing: Vec<usize> = (0..q.len()).filter(|&i| fails(&q[i])).collect();
        let patches: BTreeSet<usize> = failing.iter().map(|&i| mesh.elements[i].patch).collect();
        out.push(CriterionResult {
            criterion: name,
            limit: serde_json::json!(limit),
            value,
            passed: failing.is_empty(),
            failing_elements: failing.len(),
            culprit_patches: patches.into_iter().take(20).collect(),
            failing,
        });
    };
    if let Some(l) = criteria.min_edge {
        element_check("min_edge", l, t.min_edge.value, &|e| e.min_edge < l);
    }
    if let Some(s) = criteria.min_edge_share_of_size {
        let l = s * size;
        element_check("min_edge_share_of_size", s, t.min_edge.value / size, &|e| e.min_edge < l);
    }
    if let Some(l) = criteria.min_time_step_s {
        let c = material.wave_speed();
        element_check("min_time_step_s", l, t.time_step_s, &|e| e.min_edge / c < l);
    }
    if let Some(l) = criteria.max_aspect {
        element_check("max_aspect", l, t.max_aspect.value, &|e| e.aspect > l);
    }
    if let Some(l) = criteria.max_warpage_deg {
        element_check("max_warpage_deg", l, t.max_warpage_deg.value, &|e| e.warpage_deg > l);
    }
    if let Some(l) = criteria.max_skew_deg {
        element_check("max_skew_deg", l, t.max_skew_deg.value, &|e| e.skew_deg > l);
    }
    if let Some(l) = criteria.min_jacobian {
        element_check("min_jacobian", l, t.min_jacobian.value, &|e| e.jacobian < l);
    }
    let mut whole = |name: &'static str, limit: serde_json::Value, value: f64, passed: bool| {
        out.push(CriterionResult {
            criterion: name,
            limit,
            value,
            passed,
            failing_elements: 0,
            culprit_patches: vec![],
            failing: vec![],
        });
    };
    if let Some(l) = criteria.max_tria_share {
        whole("max_tria_share", serde_json::json!(l), t.tria_share, t.tria_share <= l);
    }
    if let Some([lo, hi]) = criteria.mass_ratio {
        let r = t.mass.ratio.unwrap_or(f64::NAN);
        whole("mass_ratio", serde_json::json!([lo, hi]), r, r >= lo && r <= hi);
    }
    if let Some(l) = criteria.max_free_edge_excess {
        let excess = match midsurface_free_length {
            Some(m) if m > 0.0 => t.free_edges.length / m - 1.0,
            _ if t.free_edges.length == 0.0 => 0.0,
            _ => f64::INFINITY,
        };
        whole("max_free_edge_excess", serde_json::json!(l), excess, excess <= l);
    }
    out
}
