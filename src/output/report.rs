//! The JSON report of `midsurf run` (fields documented in README.md, "Report").

use serde::Serialize;

use super::round;
use super::topology::{Topology, TopologyPatch};
use crate::model::face_graph::FaceId;
use crate::model::tolerance::Tolerances;
pub use crate::model::warning::Warning;
use crate::pairing::estimate::TMaxEstimate;
use crate::pairing::{FaceRole, PairGroup, PairKind, Thickness};
use crate::stitch::{FreeEdges, JointReport};
use crate::trim::{Branch, TrimReason};

/// Bumped when a field changes meaning or disappears.
pub const REPORT_VERSION: u32 = 1;

#[derive(Debug, Clone, Serialize)]
pub struct Report {
    pub report_version: u32,
    pub midsurf_version: &'static str,
    pub input: String,
    pub output: String,
    pub parameters: Parameters,
    pub solids: Vec<SolidReport>,
    pub patches: Vec<PatchReport>,
    pub trimmed: Vec<TrimmedReport>,
    /// Joints grown between patches (and open edges that found no partner), per pair of patches and kind.
    pub joints: Vec<JointReport>,
    pub thickness_legend: Vec<LegendEntry>,
    pub result: ResultSummary,
    /// Stable summary of the stitched topology (rounded, sorted): what the snapshot tests compare.
    pub topology: Topology,
    pub warnings: Vec<Warning>,
    /// Seconds per stage; absent with --no-timings (for byte-identical reports).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub timings_s: Option<Timings>,
}

#[derive(Debug, Clone, Serialize)]
pub struct Parameters {
    /// The user's --t-max, or null when estimated per solid (see solids[].t_max).
    pub t_max: Option<f64>,
    pub draft_max_deg: f64,
    /// Where the patches lie through their walls: mid, top (the reference face's skin) or bottom.
    pub position: crate::model::params::Position,
    /// Width of the thickness bands (--t-bands): patches whose thickness falls in one band are written with
    /// one thickness.
    pub t_band: f64,
}

#[derive(Debug, Clone, Serialize)]
pub struct SolidReport {
    /// 1-based, in the order of the STEP file.
    pub solid: usize,
    /// Thin-walled or not (chunky, with the measure): a solid that is not thin-walled gets no patch.
    pub class: crate::pairing::wall_class::WallClass,
    /// Written into the output STEP as the solid it is (--keep-solids, solids that are not thin-walled).
    pub kept_as_solid: bool,
    pub faces: usize,
    pub volume: f64,
    pub area: f64,
    pub t_max: f64,
    pub t_max_source: String,
    pub t_max_estimate: TMaxEstimate,
    pub tolerances: Tolerances,
    /// Size limits of the small features (user values or defaults from t_max).
    pub feature_limits: crate::pairing::features::Limits,
    /// Small features suppressed: kind, faces, size (fillet radius, hole diameter, boss box diagonal).
    pub suppressed: Vec<crate::pairing::features::Feature>,
    pub groups: Vec<PairGroup>,
    pub roles: RoleCounts,
    pub unpaired: Vec<Unpaired>,
    pub paired_share: f64,
    pub paired_skin_share: f64,
    /// Share of the solid's volume within reach of the mid-surface written (thin-walled solids only), with
    /// the faces nearest to the material out of reach (geom::coverage).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coverage: Option<crate::geom::coverage::Coverage>,
    /// Faces this solid shares whole with other solids of the file (a partition): the stitching treats the
    /// solids as one body, and their patches meet across these faces.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub shared_faces: Vec<SharedFaceReport>,
}

/// A face of a solid lying on a face of another solid, facing the other way.
#[derive(Debug, Clone, Serialize)]
pub struct SharedFaceReport {
    pub face: usize,
    /// 1-based.
    pub other_solid: usize,
    pub other_face: usize,
}

#[derive(Debug, Clone, Default, Serialize)]
pub struct RoleCounts {
    pub pair: usize,
    pub thickness: usize,
    pub connecting: usize,
    pub suppressed: usize,
    pub unpaired: usize,
}

impl RoleCounts {
    pub fn of(roles: &[FaceRole]) -> RoleCounts {
        let mut counts = RoleCounts::default();
        for role in roles {
            *match role {
                FaceRole::Pair { .. } => &mut counts.pair,
                FaceRole::Thickness { .. } => &mut counts.thickness,
                FaceRole::Connecting { .. } => &mut counts.connecting,
                FaceRole::Suppressed => &mut counts.suppressed,
                FaceRole::Unpaired { .. } => &mut counts.unpaired,
            } += 1;
        }
        counts
    }
}

#[derive(Debug, Clone, Serialize)]
pub struct Unpaired {
    pub face: FaceId,
    pub surface: &'static str,
    pub area: f64,
    pub reason: String,
}

#[derive(Debug, Clone, Serialize)]
pub struct PatchReport {
    /// 1-based; the output STEP names its faces "patch <id> t=<thickness>".
    pub id: usize,
    pub solid: usize,
    pub group: usize,
    pub kind: PairKind,
    pub source_faces: Vec<FaceId>,
    pub thickness: Thickness,
    /// The thickness written for the patch (its face names, colour, CSV row, deck section): the mean in its
    /// band (`parameters.t_band`).
    pub band: f64,
    /// Area after trimming (sum of its faces in the output).
    pub area: f64,
    /// Faces of the patch in the output.
    pub faces: usize,
}

impl PatchReport {
    /// The patch as the topology summary lists it, rounded for stable snapshots.
    pub fn topology(&self) -> TopologyPatch {
        TopologyPatch {
            id: self.id,
            kind: self.kind,
            source_faces: self.source_faces.clone(),
            thickness: round(self.thickness.mean, 3),
            area: round(self.area, 1),
            faces: self.faces,
        }
    }
}

#[derive(Debug, Clone, Serialize)]
pub struct TrimmedReport {
    pub patch: usize,
    pub area: f64,
    pub width: f64,
    pub crossing_patches: Vec<usize>,
    pub reason: TrimReason,
}

impl TrimmedReport {
    /// From a branch found on the fused pieces; patch indices become 1-based patch ids.
    pub fn from_branch(b: &Branch) -> TrimmedReport {
        TrimmedReport {
            patch: b.patch + 1,
            area: b.area,
            width: b.width,
            crossing_patches: b.crossing.iter().map(|p| p + 1).collect(),
            reason: b.reason,
        }
    }
}

#[derive(Debug, Clone, Serialize)]
pub struct LegendEntry {
    pub thickness: f64,
    pub color: [f64; 3],
}

#[derive(Debug, Clone, Serialize)]
pub struct ResultSummary {
    pub faces: usize,
    pub shells: usize,
    pub valid: bool,
    pub area: f64,
    /// The largest edge tolerance of the file read back: how far an edge may lie off its faces.
    pub max_edge_tolerance: f64,
    /// Free edges of the result: on the part's rim, or open (inside the material: an unmade joint).
    /// Absent when stitching failed.
    pub free_edges: Option<FreeEdges>,
}

#[derive(Debug, Clone, Default, Serialize)]
pub struct Timings {
    pub load: f64,
    pub pairing: f64,
    pub patches: f64,
    pub trim: f64,
    pub stitch: f64,
    pub write: f64,
    /// The report's coverage figures (`solids[].coverage`).
    pub coverage: f64,
    pub total: f64,
}

/// Colours for thickness bands, thinnest first: blue, cyan, green, yellow, orange, red, magenta, then grey.
const PALETTE: [[f64; 3]; 7] = [
    [0.12, 0.35, 0.85],
    [0.10, 0.70, 0.80],
    [0.20, 0.70, 0.25],
    [0.90, 0.85, 0.15],
    [0.95, 0.55, 0.10],
    [0.85, 0.15, 0.15],
    [0.75, 0.20, 0.75],
];

/// The finest thickness band (mm): the precision thicknesses are written with.
pub const T_BAND_MIN: f64 = 0.001;

/// `t` as written (names, colours, CSV, decks): the nearest multiple of the band width `width`, to 0.001 mm.
pub fn band(t: f64, width: f64) -> f64 {
    round((t / width).round() * width, 3)
}

/// One band per distinct thickness (to 0.001 mm), thinnest first.
pub fn legend(thicknesses: &[f64]) -> Vec<LegendEntry> {
    let mut bands: Vec<f64> = thicknesses.iter().map(|t| round(*t, 3)).collect();
    bands.sort_by(f64::total_cmp);
    bands.dedup();
    bands
        .into_iter()
        .enumerate()
        .map(|(i, thickness)| LegendEntry { thickness, color: PALETTE.get(i).copied().unwrap_or([0.5, 0.5, 0.5]) })
        .collect()
}

pub fn band_color(legend: &[LegendEntry], t: f64) -> [f64; 3] {
    let t = round(t, 3);
    legend.iter().find(|e| e.thickness == t).map(|e| e.color).unwrap_or([0.5, 0.5, 0.5])
}

/// The patches as CSV, one row per patch in id order: `patch,solid,kind,thickness,area,faces,source_faces`
/// (thickness in mm to 0.001, area in mm² to 0.01, source faces 0-based and separated by spaces); then one row
/// per solid that is not thin-walled, with no patch id, kind `not_thin_walled`, its 2V/A as thickness, its
/// area and no faces: every solid of the part shows in the table.
pub fn patches_csv(patches: &[PatchReport], solids: &[SolidReport]) -> String {
    let mut out = String::from("patch,solid,kind,thickness,area,faces,source_faces\n");
    for p in patches {
        let sources: Vec<String> = p.source_faces.iter().map(|f| f.to_string()).collect();
        out += &format!(
            "{},{},{},{:.3},{:.2},{},{}\n",
            p.id,
            p.solid,
            p.kind.name(),
            p.band,
            p.area,
            p.faces,
            sources.join(" ")
        );
    }
    for s in solids.iter().filter(|s| !s.class.is_thin_walled()) {
        out += &format!(",{},not_thin_walled,{:.3},{:.2},0,\n", s.solid, s.class.thickness, s.area);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_has_a_header_and_a_row_per_patch() {
        let patch = |id, kind, t: f64, sources: Vec<usize>| PatchReport {
            id,
            solid: 1,
            group: 0,
            kind,
            source_faces: sources,
            thickness: Thickness { mean: t, min: t, max: t },
            band: band(t, 0.5),
            area: 12.345,
            faces: 2,
        };
        let csv = patches_csv(
            &[patch(1, PairKind::Parallel, 2.0, vec![3, 7]), patch(2, PairKind::Draft, 1.25, vec![0])],
            &[],
        );
        assert_eq!(
            csv,
            "patch,solid,kind,thickness,area,faces,source_faces\n1,1,parallel,2.000,12.35,2,3 7\n2,1,draft,1.500,12.35,2,0\n"
        );
    }

    #[test]
    fn a_thickness_is_written_as_the_nearest_multiple_of_the_band_width() {
        assert_eq!(band(1.2345, T_BAND_MIN), 1.235);
        assert_eq!(band(1.87, 0.25), 1.75);
        assert_eq!(band(1.88, 0.25), 2.0);
        assert_eq!(band(2.96, 0.1), 3.0, "to 0.001 mm, without the binary fraction's tail");
    }
}
