//! A warning of the run: each stage says what it could not do, and the report lists them in stage order.

use std::collections::BTreeSet;

use serde::Serialize;

use crate::model::face_graph::FaceId;

#[derive(Debug, Clone, Serialize)]
pub struct Warning {
    /// Stable, machine-readable: no_pairs, unpaired_face, patch_failed, side_conflict,
    /// thickness_step, thickness_varies, partial_overlap, joint_failed, stitch_failed, stitch_pass_failed,
    /// open_edges, material_uncovered, coverage_not_measured, invalid_output, feature_not_suppressed, face_not_described, solid_failed, step_syntax,
    /// option_out_of_range.
    pub code: &'static str,
    pub message: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub solid: Option<usize>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub faces: Vec<FaceId>,
}

/// Patch indices as the ids the output names them by ("patch 3"), comma separated.
pub fn patch_list(patches: &BTreeSet<usize>) -> String {
    patches.iter().map(|k| (k + 1).to_string()).collect::<Vec<_>>().join(", ")
}
