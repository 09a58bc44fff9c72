//! The report of `midsurf run` assembled from what every stage handed on, in the stages' order.

use std::path::Path;

use super::report::{
    band, legend, LegendEntry, Parameters, PatchReport, Report, ResultSummary, RoleCounts, SharedFaceReport,
    SolidReport, Timings, TrimmedReport, Unpaired, Warning, REPORT_VERSION,
};
use super::shells::{written_area, Assembled};
use super::topology;
use crate::geom::bodies::SharedFace;
use crate::geom::coverage::Coverage;
use crate::load::Part;
use crate::model::face_graph::FaceGraph;
use crate::model::params::Position;
use crate::model::shapes::Fused;
use crate::pairing::driver::{PairingParams, SolidPairing};
use crate::patch::make::Made;
use crate::stitch::Outcome;

/// What the run was asked.
pub struct Asked<'a> {
    pub input: &'a Path,
    pub output: &'a Path,
    pub params: PairingParams,
    pub position: Position,
    /// The solids that are not thin-walled are written as solids (--keep-solids).
    pub keep_solids: bool,
    /// Width of the thickness bands (--t-bands).
    pub t_band: f64,
}

/// The thickness legend of the made patches: one colour per band of width `t_band` holding a patch.
pub fn thickness_legend(made: &[Made], t_band: f64) -> Vec<LegendEntry> {
    legend(&made.iter().map(|m| band(m.plan.thickness.mean, t_band)).collect::<Vec<f64>>())
}

/// The report; `warnings` are those of the stages, in order (one more is added when nothing paired).
#[allow(clippy::too_many_arguments)]
pub fn report(
    asked: &Asked,
    part: &Part,
    pairings: &[SolidPairing],
    made: &[Made],
    shared: &[SharedFace],
    stitched: Outcome,
    assembled: Assembled,
    coverage: Vec<Option<Coverage>>,
    mut warnings: Vec<Warning>,
    timings: Option<Timings>,
) -> Report {
    let Outcome { fused, keep, branches, joints, free, .. } = stitched;
    let Assembled { shells, max_edge_tolerance, .. } = assembled;
    let patches = patch_reports(made, &fused, &keep, asked.t_band);
    if made.is_empty() {
        warnings.push(Warning {
            code: "no_pairs",
            message: "no face pairs found: the output is empty; check --t-max and --draft-max".to_string(),
            solid: None,
            faces: Vec::new(),
        });
    }
    let topology_patches = patches.iter().map(PatchReport::topology).collect();
    let topology = topology::summarise(&shells, topology_patches, &joints, free);
    Report {
        report_version: REPORT_VERSION,
        midsurf_version: env!("CARGO_PKG_VERSION"),
        input: asked.input.display().to_string(),
        output: asked.output.display().to_string(),
        parameters: Parameters {
            t_max: asked.params.t_max,
            draft_max_deg: asked.params.draft_max_deg,
            position: asked.position,
            t_band: asked.t_band,
        },
        solids: part
            .solids
            .iter()
            .zip(pairings)
            .zip(coverage)
            .enumerate()
            .map(|(i, ((s, sp), coverage))| SolidReport {
                kept_as_solid: asked.keep_solids && !sp.class.is_thin_walled(),
                coverage,
                shared_faces: shared_face_reports(i, shared),
                ..solid_report(i + 1, &s.graph, sp)
            })
            .collect(),
        patches,
        trimmed: branches.iter().map(TrimmedReport::from_branch).collect(),
        joints,
        thickness_legend: thickness_legend(made, asked.t_band),
        result: ResultSummary {
            faces: shells.faces.len(),
            shells: shells.count,
            valid: shells.valid,
            area: written_area(&fused, &keep),
            max_edge_tolerance,
            free_edges: free,
        },
        topology,
        warnings,
        timings_s: timings,
    }
}

/// The line `midsurf run` ends with on stderr.
pub fn summary_line(output: &Path, r: &Report) -> String {
    format!(
        "midsurf: wrote {} ({} patches, {} faces in {} shell(s), valid: {}); {} warning(s)",
        output.display(),
        r.patches.len(),
        r.result.faces,
        r.result.shells,
        r.result.valid,
        r.warnings.len()
    )
}

fn patch_reports(made: &[Made], fused: &Fused, keep: &[bool], t_band: f64) -> Vec<PatchReport> {
    made.iter()
        .enumerate()
        .map(|(k, m)| {
            let pieces: Vec<_> =
                fused.faces.iter().enumerate().filter(|(i, f)| keep[*i] && f.patch == k).map(|(_, f)| f).collect();
            PatchReport {
                id: k + 1,
                solid: m.solid,
                group: m.plan.group,
                kind: m.plan.kind,
                source_faces: m.plan.faces.clone(),
                thickness: m.plan.thickness,
                band: band(m.plan.thickness.mean, t_band),
                area: pieces.iter().map(|f| f.area).sum(),
                faces: pieces.len(),
            }
        })
        .collect()
}

fn solid_report(solid: usize, graph: &FaceGraph, sp: &SolidPairing) -> SolidReport {
    let unpaired = sp
        .pairing
        .roles
        .iter()
        .enumerate()
        .filter_map(|(f, role)| {
            let face = &graph.faces[f];
            role.unpaired_reason().map(|reason| Unpaired {
                face: f,
                surface: face.surface.kind_name(),
                area: face.area,
                reason,
            })
        })
        .collect();
    let roles = RoleCounts::of(&sp.pairing.roles);
    SolidReport {
        solid,
        class: sp.class,
        kept_as_solid: false,
        faces: graph.faces.len(),
        volume: graph.volume,
        area: graph.area,
        t_max: sp.tolerances.t_max,
        t_max_source: sp.t_max_source.clone(),
        t_max_estimate: sp.estimate.clone(),
        tolerances: sp.tolerances,
        feature_limits: sp.limits,
        suppressed: sp.features.clone(),
        groups: sp.pairing.groups.clone(),
        roles,
        unpaired,
        paired_share: sp.paired_share,
        paired_skin_share: sp.paired_skin_share,
        coverage: None,
        shared_faces: Vec::new(),
    }
}

/// The faces solid `solid` (0-based) shares with others, seen from it.
fn shared_face_reports(solid: usize, shared: &[SharedFace]) -> Vec<SharedFaceReport> {
    let seen = |(own, other): ((usize, usize), (usize, usize))| {
        (own.0 == solid).then_some(SharedFaceReport { face: own.1, other_solid: other.0 + 1, other_face: other.1 })
    };
    shared.iter().flat_map(|&[a, b]| [seen((a, b)), seen((b, a))]).flatten().collect()
}
