//! Command-line interface: argument definitions and dispatch to the commands.

use std::io::Write;
use std::path::PathBuf;

use clap::{Parser, Subcommand};
use serde::Serialize;

use crate::error::Error;
use crate::exit::Exit;
use crate::load::{self, MeshRequest};
use crate::model::face_graph::FaceGraph;
use crate::model::params::Position;
use crate::output::inspect::{self, SolidSummary};
use crate::pairing::driver::{self, PairingParams, SolidPairing};
use crate::pairing::features::LimitArgs;

/// Mid-surface generator for thin-walled CAD parts: a STEP solid in, a mid-surface STEP with a thickness per
/// patch out.
///
/// Exit codes: 0 all good, 1 finished with warnings (see the report), 2 failed (bad input, kernel failure).
#[derive(Debug, Parser)]
#[command(name = "midsurf", version, about, long_about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Show what a STEP part is made of: faces by surface kind, edges by convexity, volume, wall thickness.
    ///
    /// Reads every solid of the file through the OCCT sidecar and prints one block per solid. The wall
    /// thickness shown is the estimate 2V/A (volume over half the area), good for thin-walled parts.
    Inspect {
        /// The STEP file to read.
        part: PathBuf,
        /// Print the whole face graph as JSON instead of the table.
        #[arg(long)]
        json: bool,
        /// With --json, include a triangulation of every face.
        #[arg(long, requires = "json")]
        mesh: bool,
    },
    /// Make the mid-surface of a part: pair faces, make a mid-patch per pair group (offset of the larger side
    /// by half the thickness, or projection onto the bisector of a draft pair), trim the branches where patches
    /// cross, grow and stitch the joints, and write the patches as shells whose faces are named
    /// "patch <id> t=<thickness>".
    ///
    /// Exit code 1 when the report has warnings (unpaired faces, failed patches or joints, no pairs at all).
    Run(RunCli),
    /// Find the face pairs of a part: groups of opposite faces (the two skins of each wall) and the role of
    /// every face, ending with the paired share of the area.
    ///
    /// Parallel pairs have opposite normals; draft pairs normals within twice --draft-max of opposite; curved
    /// pairs share their axis or centre (cylinders, cones, spheres, tori) or keep a nearly constant distance
    /// measured by rays (freeform, and curved faces a little off each other's axis). Every pair is closer than
    /// --t-max and its faces overlap when projected onto each other.
    Pairs {
        /// The STEP file to read.
        part: PathBuf,
        /// Print pairs, groups and roles as JSON instead of the table.
        #[arg(long)]
        json: bool,
        /// Why a face pairs or not: every candidate partner of face FACE of solid SOLID (both numbered as in
        /// the table, solids from 1), the pair tests' verdict on each, and the face's role in the end (rules
        /// that judge a pair among the walls around it can still drop a pair the tests accepted).
        #[arg(long, value_name = "SOLID:FACE", value_parser = solid_face)]
        explain: Option<(usize, usize)>,
        #[command(flatten)]
        pairing: PairingArgs,
    },
    /// Mesh a mid-surface with shells (gmsh) and write solver decks: LS-DYNA .k (OpenRadioss reads it too),
    /// Nastran .bdf, Abaqus .inp; every element carries its patch's thickness. Writes a quality report per
    /// part (BASE.quality.json); exit code 1 when a quality criterion fails.
    Mesh(crate::mesh::MeshCli),
    /// Make the mid-surfaces of many parts: every STEP file of a folder, or the parts of a manifest (CSV
    /// with a header, or JSON: column or key `input`, optional `name` and any of the `run` options per part,
    /// e.g. `input,t_max,keep_holes`). Per part, in the output folder: NAME.step and NAME.json as `midsurf run`
    /// writes them, NAME.log (its messages); and one summary, batch-summary.csv and .json (exit code,
    /// warnings, patches, self-check figures of the report, time per part).
    ///
    /// Resumable: a part whose input content, options and midsurf (executable and sidecar) are unchanged and
    /// whose outputs exist is not run again. Exit code: the worst of the parts'.
    Batch(BatchCli),
}

/// Arguments of `midsurf batch`.
#[derive(Debug, clap::Args)]
pub struct BatchCli {
    /// A folder of STEP files (*.step, *.stp), or a manifest (.csv or .json).
    pub inputs: PathBuf,
    /// The output folder (made if missing; never the input folder).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Parts run at once (each a `midsurf run` with its own sidecar): up to one per core.
    #[arg(short, long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    pub jobs: u32,
    /// Run only shard I of N (1 <= I <= N): parts sorted by name, every N-th from the I-th, so that the N
    /// tasks of a job array (Slurm --array=1-N, PBS -J 1-N) cover every part once. The summary is then
    /// batch-summary-I-of-N.*.
    #[arg(long, value_parser = crate::batch::inputs::Shard::parse)]
    pub shard: Option<crate::batch::inputs::Shard>,
    /// Run every part, even those whose outputs are up to date.
    #[arg(long)]
    pub force: bool,
    /// Run again the parts that failed last time although nothing changed.
    #[arg(long)]
    pub retry_failed: bool,
    /// Print the parts (after --shard) as JSON with the `run` options of each, and run nothing.
    #[arg(long)]
    pub plan: bool,
    /// Where the patches lie through their walls (see `run`), for parts whose manifest row does not say.
    #[arg(long, value_enum)]
    pub position: Option<PositionArg>,
    /// Width of the thickness bands (see `run`), for parts whose manifest row does not say.
    #[arg(long, value_parser = band_width)]
    pub t_bands: Option<f64>,
    /// Pairing options for every part whose manifest row does not set its own (see `run`).
    #[command(flatten)]
    pub pairing: PairingArgs,
}

impl BatchCli {
    /// The batch-wide options as `midsurf run` flag values.
    fn defaults(&self) -> crate::batch::inputs::Options {
        let p = &self.pairing;
        let mut o = crate::batch::inputs::Options::new();
        let mut put = |flag: &str, v: Option<f64>| {
            if let Some(v) = v {
                o.insert(flag.to_string(), v.to_string());
            }
        };
        put("t-max", p.t_max);
        put("draft-max", Some(p.draft_max).filter(|d| *d != crate::model::tolerance::DEFAULT_DRAFT_MAX_DEG));
        put("fillet-max", p.fillet_max);
        put("hole-max", p.hole_max);
        put("boss-max", p.boss_max);
        put("t-bands", self.t_bands);
        if p.keep_holes {
            o.insert("keep-holes".into(), "true".into());
        }
        if let Some(pos) = self.position {
            use clap::ValueEnum;
            let name = pos.to_possible_value().expect("positions all have names").get_name().to_string();
            o.insert("position".into(), name);
        }
        o
    }
}

/// Arguments of `midsurf run`.
#[derive(Debug, clap::Args)]
pub struct RunCli {
    /// The STEP file to read (never modified).
    pub part: PathBuf,
    /// Where to write the mid-surface STEP (written atomically: a temporary file renamed into place).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Where to write the JSON report (fields in README.md, "Report").
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Where to write the topology summary as stable text (counts, free edges, patches, joints).
    #[arg(long)]
    pub summary: Option<PathBuf>,
    /// Where to write a CSV of the patches (patch, solid, kind, thickness, area, faces, source faces): the
    /// thickness per patch for tools that do not read JSON.
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// Where to write a binary glTF (.glb) preview of the mid-surface, faces coloured by thickness band as in
    /// the STEP (legend in the report), for any glTF viewer.
    #[arg(long)]
    pub preview: Option<PathBuf>,
    /// Where the patches lie through their walls: mid-way, or on the top or bottom skin with the thickness
    /// kept (top: the skin of each pair's reference face, the face normal pointing away from the material).
    #[arg(long, value_enum, default_value_t = PositionArg::Mid)]
    pub position: PositionArg,
    /// Leave the time per stage out of the report, so that two runs give byte-identical reports.
    #[arg(long)]
    pub no_timings: bool,
    /// Write the solids that are not thin-walled (pins, screws, solid blocks: no mid-surface, see the report's
    /// solids[].class) into the output STEP as the solids they are, named "solid <n> not_thin_walled", so that
    /// the model stays complete for meshing them as solids or beams.
    #[arg(long)]
    pub keep_solids: bool,
    /// Width of the thickness bands in mm: each patch's thickness is written (face names, colours, CSV, the
    /// report's `band`, solver decks) as the nearest multiple of this, so that walls of nearly one thickness
    /// share a name, a colour and a deck section. The report keeps the measured thickness too.
    #[arg(long, default_value_t = crate::output::report::T_BAND_MIN, value_parser = band_width)]
    pub t_bands: f64,
    #[command(flatten)]
    pub pairing: PairingArgs,
}

/// Pairing parameters shared by the commands that pair faces.
#[derive(Debug, Clone, clap::Args)]
pub struct PairingArgs {
    /// Largest wall thickness in mm [default: estimated per solid from its parallel walls, see the output].
    #[arg(long, value_parser = positive_mm, allow_negative_numbers = true)]
    pub t_max: Option<f64>,
    /// Largest draft angle of a wall side in degrees; draft pairs differ by up to twice this.
    #[arg(
        long,
        default_value_t = crate::model::tolerance::DEFAULT_DRAFT_MAX_DEG,
        value_parser = draft_degrees,
        allow_negative_numbers = true
    )]
    pub draft_max: f64,
    /// Fillets and rounds up to this radius, and chamfers up to this width (mm), are suppressed: they do not
    /// pair, the joints bridge them [default: 2 x t_max].
    #[arg(long, value_parser = non_negative_mm, allow_negative_numbers = true)]
    pub fillet_max: Option<f64>,
    /// Holes up to this diameter (mm) are filled in the mid-surface [default: t_max].
    #[arg(long, value_parser = non_negative_mm, allow_negative_numbers = true)]
    pub hole_max: Option<f64>,
    /// Solid bosses, pins and standoffs standing on a wall within a box of this diagonal (mm) are removed and
    /// their footprint filled; a hollow boss or a tab (its sides pair as a wall) standing out at least as far
    /// as the wall below is thick keeps its mid-patch [default: 4 x t_max].
    #[arg(long, value_parser = non_negative_mm, allow_negative_numbers = true)]
    pub boss_max: Option<f64>,
    /// Keep every hole, whatever its diameter.
    #[arg(long)]
    pub keep_holes: bool,
}

impl PairingArgs {
    pub fn params(&self) -> PairingParams {
        PairingParams {
            t_max: self.t_max,
            draft_max_deg: self.draft_max,
            limits: LimitArgs {
                fillet_max: self.fillet_max,
                hole_max: self.hole_max,
                boss_max: self.boss_max,
                keep_holes: self.keep_holes,
            },
        }
    }
}

fn band_width(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v >= crate::output::report::T_BAND_MIN => Ok(v),
        _ => Err(format!("'{s}' is not a band width in mm of at least {}", crate::output::report::T_BAND_MIN)),
    }
}

fn positive_mm(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("'{s}' is not a positive length in mm")),
    }
}

fn non_negative_mm(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        _ => Err(format!("'{s}' is not a length in mm (0 or more)")),
    }
}

fn draft_degrees(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if (0.0..45.0).contains(&v) => Ok(v),
        _ => Err(format!("'{s}' is not an angle in degrees from 0 to 45")),
    }
}

pub fn run(cli: Cli) -> Result<Exit, Error> {
    match cli.command {
        Command::Inspect { part, json, mesh } => inspect_command(part, json, mesh),
        Command::Pairs { part, json, explain, pairing } => pairs_command(part, json, explain, pairing.params()),
        Command::Mesh(m) => crate::mesh::run(&m),
        Command::Run(r) => crate::run::run(&crate::run::RunArgs {
            input: r.part,
            output: r.output,
            report: r.report,
            summary: r.summary,
            csv: r.csv,
            preview: r.preview,
            params: r.pairing.params(),
            position: r.position.into(),
            timings: !r.no_timings,
            keep_solids: r.keep_solids,
            t_band: r.t_bands,
        }),
        Command::Batch(b) => crate::batch::run(&crate::batch::BatchArgs {
            defaults: b.defaults(),
            check_run_args,
            source: b.inputs,
            output: b.output,
            jobs: b.jobs as usize,
            shard: b.shard,
            force: b.force,
            retry_failed: b.retry_failed,
            plan: b.plan,
        }),
    }
}

/// A part's `midsurf run` arguments (after `run PART -o OUT`) checked by the parser `run` itself uses: the
/// first line of its complaint.
fn check_run_args(args: Vec<String>) -> Result<(), String> {
    let mut argv = vec!["midsurf".to_string(), "run".into(), "part.step".into(), "-o".into(), "out.step".into()];
    argv.extend(args);
    Cli::try_parse_from(argv).map(|_| ()).map_err(|e| {
        let text = e.to_string();
        text.lines().next().unwrap_or("").trim_start_matches("error: ").to_string()
    })
}

#[derive(Serialize)]
struct InspectJson<'a> {
    file: String,
    solids: Vec<SolidJson<'a>>,
}

#[derive(Serialize)]
struct SolidJson<'a> {
    summary: SolidSummary,
    graph: &'a FaceGraph,
}

fn inspect_command(path: PathBuf, json: bool, mesh: bool) -> Result<Exit, Error> {
    let mut sidecar = load::start_sidecar(&path, false)?;
    let part = load::load(&mut sidecar, &path, MeshRequest { mesh, tolerance: None })?;
    sidecar.shutdown();
    let file = path.display().to_string();
    let text = if json {
        let solids =
            part.solids.iter().map(|s| SolidJson { summary: inspect::summarize(&s.graph), graph: &s.graph }).collect();
        serde_json::to_string_pretty(&InspectJson { file, solids }).expect("face graphs always serialise") + "\n"
    } else {
        let summaries: Vec<SolidSummary> = part.solids.iter().map(|s| inspect::summarize(&s.graph)).collect();
        inspect::render(&file, &summaries)
    };
    print(&text)?;
    Ok(Exit::Clean)
}

fn print(text: &str) -> Result<(), Error> {
    std::io::stdout()
        .write_all(text.as_bytes())
        .map_err(|e| Error::output(std::path::Path::new("<stdout>"), e.to_string()))
}

#[derive(Serialize)]
struct PairsJson<'a> {
    file: String,
    solids: &'a [SolidPairing],
}

/// `--explain SOLID:FACE`.
fn solid_face(text: &str) -> Result<(usize, usize), String> {
    let bad = || format!("'{text}' is not SOLID:FACE (e.g. 1:35: solid 1, face 35)");
    let (solid, face) = text.split_once(':').ok_or_else(bad)?;
    let solid: usize = solid.trim().parse().map_err(|_| bad())?;
    let face: usize = face.trim().parse().map_err(|_| bad())?;
    if solid == 0 {
        return Err(format!("solids are numbered from 1: '{text}'"));
    }
    Ok((solid, face))
}

fn pairs_command(
    path: PathBuf,
    json: bool,
    explain: Option<(usize, usize)>,
    params: PairingParams,
) -> Result<Exit, Error> {
    let mut sidecar = load::start_sidecar(&path, false)?;
    let part = load::load(&mut sidecar, &path, MeshRequest { mesh: true, tolerance: None })?;
    sidecar.shutdown();
    crate::checks::against_part(&params, &part).map_err(|p| Error::input(&path, p))?;
    let solids: Vec<SolidPairing> = driver::pair_part(&part, params);
    let file = path.display().to_string();
    if let Some((solid, face)) = explain {
        let found = part.solids.get(solid - 1).zip(solids.get(solid - 1));
        let (graph, sp) = found.ok_or_else(|| {
            Error::input(&path, format!("has {} solid(s), no solid {solid} to --explain", part.solids.len()))
        })?;
        let graph = &graph.graph;
        if face >= graph.faces.len() {
            let problem = format!(
                "solid {solid} has {} faces (0 to {}), no face {face} to --explain",
                graph.faces.len(),
                graph.faces.len() - 1
            );
            return Err(Error::input(&path, problem));
        }
        print(&crate::output::pairs_table::explain(graph, sp, face))?;
        return Ok(Exit::Clean);
    }
    let text = if json {
        serde_json::to_string_pretty(&PairsJson { file, solids: &solids }).expect("pairings always serialise") + "\n"
    } else {
        let mut out = format!("{file}: {} solid(s)\n", solids.len());
        for (i, (solid, sp)) in part.solids.iter().zip(&solids).enumerate() {
            crate::output::pairs_table::render(&mut out, i, &solid.graph, sp);
        }
        out
    };
    print(&text)?;
    Ok(Exit::Clean)
}

/// `--position` as clap parses it; the stages take [`Position`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum PositionArg {
    Mid,
    Top,
    Bottom,
}

impl From<PositionArg> for Position {
    fn from(p: PositionArg) -> Position {
        match p {
            PositionArg::Mid => Position::Mid,
            PositionArg::Top => Position::Top,
            PositionArg::Bottom => Position::Bottom,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_batch_part_s_run_arguments_are_checked_by_run_s_own_parser() {
        assert_eq!(check_run_args(vec!["--t-max=2.5".into(), "--keep-holes".into()]), Ok(()));
        assert!(check_run_args(vec!["--t-max=-1".into()]).unwrap_err().contains("not a positive length"));
        assert!(check_run_args(vec!["--position=sideways".into()]).unwrap_err().contains("sideways"));
    }
}
