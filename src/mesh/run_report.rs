//! What meshing takes from `midsurf run`'s JSON report: each patch's solid and deck thickness, each solid's
//! volume, the position of the mid-surface in the wall, its area and free length, and the thickness legend
//! (the STEP's colours).

use std::collections::BTreeMap;
use std::path::Path;

use serde::Deserialize;

use super::deck::Placement;
use crate::error::Error;
use crate::output::report::{legend, LegendEntry};

/// The run's facts, keyed by patch id and solid id (both 1-based, the report's).
#[derive(Debug, Clone)]
pub struct RunFacts {
    pub placement: Placement,
    pub part_of: BTreeMap<usize, usize>,
    /// Thickness as written to the decks (to 0.001 mm).
    pub thickness_of: BTreeMap<usize, f64>,
    pub solid_volume: BTreeMap<usize, f64>,
    /// Area of the mid-surface (mm²).
    pub area: f64,
    /// Rim + open edges of the mid-surface, when the run could stitch it.
    pub free_length: Option<f64>,
    pub legend: Vec<LegendEntry>,
}

#[derive(Debug, Deserialize)]
struct RunReport {
    parameters: RunParameters,
    solids: Vec<RunSolid>,
    patches: Vec<RunPatch>,
    result: RunResult,
    #[serde(default)]
    thickness_legend: Vec<RunLegendEntry>,
}

#[derive(Debug, Deserialize)]
struct RunLegendEntry {
    thickness: f64,
    color: [f64; 3],
}

#[derive(Debug, Deserialize)]
struct RunParameters {
    position: String,
}

#[derive(Debug, Deserialize)]
struct RunSolid {
    solid: usize,
    volume: f64,
}

#[derive(Debug, Deserialize)]
struct RunPatch {
    id: usize,
    solid: usize,
    thickness: RunThickness,
    /// The thickness written for the patch (its band); reports from before bands had none: the mean then.
    #[serde(default)]
    band: Option<f64>,
}

impl RunPatch {
    fn written(&self) -> f64 {
        self.band.unwrap_or(self.thickness.mean)
    }
}

#[derive(Debug, Deserialize)]
struct RunThickness {
    mean: f64,
}

#[derive(Debug, Deserialize)]
struct RunResult {
    area: f64,
    free_edges: Option<RunFreeEdges>,
}

#[derive(Debug, Deserialize)]
struct RunFreeEdges {
    rim_length: f64,
    open_length: f64,
}

/// Thickness as written to the decks and names: to 0.001 mm.
fn deck_thickness(t: f64) -> f64 {
    crate::output::round(t, 3)
}

/// Reads the run's report at `path`.
pub fn read(path: &Path) -> Result<RunFacts, Error> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::input(path, e.to_string()))?;
    let run: RunReport =
        serde_json::from_str(&text).map_err(|e| Error::input(path, format!("not a midsurf run report: {e}")))?;
    let placement = match run.parameters.position.as_str() {
        "mid" => Placement::Mid,
        "top" => Placement::Top,
        "bottom" => Placement::Bottom,
        other => return Err(Error::input(path, format!("unknown position {other:?}"))),
    };
    let part_of = run.patches.iter().map(|p| (p.id, p.solid)).collect();
    let thickness_of: BTreeMap<usize, f64> = run.patches.iter().map(|p| (p.id, deck_thickness(p.written()))).collect();
    // The STEP's colours: the report's legend, or (a report without one) the same legend made again.
    let legend = if run.thickness_legend.is_empty() {
        legend(&run.patches.iter().map(RunPatch::written).collect::<Vec<f64>>())
    } else {
        run.thickness_legend.iter().map(|e| LegendEntry { thickness: e.thickness, color: e.color }).collect()
    };
    Ok(RunFacts {
        placement,
        part_of,
        thickness_of,
        solid_volume: run.solids.iter().map(|s| (s.solid, s.volume)).collect(),
        area: run.result.area,
        free_length: run.result.free_edges.as_ref().map(|f| f.rim_length + f.open_length),
        legend,
    })
}
