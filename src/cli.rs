//! Command-line interface: argument definitions and dispatch to the commands.

use std::io::Write;
use std::path::PathBuf;

use clap::{Parser, Subcommand};
use serde::Serialize;

use crate::error::Error;
use crate::exit::Exit;
use crate::face_graph::FaceGraph;
use crate::inspect::{self, SolidSummary};
use crate::part::{self, MeshRequest};
use crate::sidecar::Sidecar;

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
}

pub fn run(cli: Cli) -> Result<Exit, Error> {
    match cli.command {
        Command::Inspect { part, json, mesh } => inspect_command(part, json, mesh),
    }
}

/// Starts the sidecar for work on `path`, so that a broken install is reported against the file at hand.
pub fn start_sidecar(path: &std::path::Path) -> Result<Sidecar, Error> {
    part::check_input(path)?;
    Sidecar::start().map_err(|error| Error::Sidecar { path: path.to_path_buf(), error })
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
    let mut sidecar = start_sidecar(&path)?;
    // The mesh tolerance only matters for --mesh; 1/1000 of the part is fine enough to see its shape.
    let part = part::load(&mut sidecar, &path, MeshRequest { mesh, tolerance: 0.1 })?;
    sidecar.shutdown();
    let file = path.display().to_string();
    let text = if json {
        let solids = part
            .solids
            .iter()
            .map(|s| SolidJson { summary: inspect::summarize(&s.graph), graph: &s.graph })
            .collect();
        serde_json::to_string_pretty(&InspectJson { file, solids }).expect("face graphs always serialise") + "\n"
    } else {
        let summaries: Vec<SolidSummary> = part.solids.iter().map(|s| inspect::summarize(&s.graph)).collect();
        inspect::render(&file, &summaries)
    };
    std::io::stdout().write_all(text.as_bytes()).map_err(|e| Error::output(std::path::Path::new("<stdout>"), e.to_string()))?;
    Ok(Exit::Clean)
}
