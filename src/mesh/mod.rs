//! `midsurf mesh`: the mid-surface meshed with shells (gmsh, in its own process) and written as solver decks
//! (LS-DYNA `.k`, Nastran `.bdf`, Abaqus `.inp`), every element carrying its patch's thickness, with a quality
//! report per part that gates the exit code.
//!
//! Rust decides: which patch (and so thickness, part and section) each gmsh surface meshes, by matching its
//! centroid and area to the named faces of the mid-surface STEP; the clean-up of too-short edges; the ids; the
//! decks. gmsh only meshes.

pub mod cleanup;
pub mod collapse;
pub mod criteria;
pub mod deck;
pub mod mesher;
pub mod meshing;
pub mod preview;
pub mod properties;
pub mod quality;
pub mod run_report;
pub mod shell;

use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::error::Error;
use crate::exit::Exit;
use cleanup::Cleanup;
use criteria::{Criteria, CriterionResult};
use deck::{Deck, Placement, Property};
use meshing::{Meshing, UnmeshedFace};
use preview::Coloring;
use quality::{Material, PartQuality};
use shell::Matching;

/// Arguments of `midsurf mesh`.
#[derive(Debug, clap::Args)]
pub struct MeshCli {
    /// The mid-surface STEP written by `midsurf run`.
    pub midsurface: PathBuf,
    /// The JSON report of that run: each patch's thickness and solid, each solid's volume, the position.
    #[arg(long)]
    pub report: PathBuf,
    /// Base of the output paths: writes BASE.k, BASE.bdf, BASE.inp (as --format asks) and BASE.quality.json.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Decks to write, comma-separated: k (LS-DYNA keyword, OpenRadioss reads it too), bdf (Nastran), inp
    /// (Abaqus).
    #[arg(long, value_delimiter = ',', default_value = "k,bdf,inp")]
    pub format: Vec<Format>,
    /// Target element size in mm.
    #[arg(long, default_value_t = 2.0, value_parser = positive)]
    pub size: f64,
    /// Quads only (recombination, then every element split into quads) instead of quad-dominant; the clean-up
    /// may still leave a few triangles where it closes a sliver.
    #[arg(long)]
    pub all_quads: bool,
    /// Mesh edges shorter than this (mm) are collapsed, so tiny CAD edges and slivers do not set the time step;
    /// no node moves farther than this [default: 0.2 x --size; 0 turns the clean-up off].
    #[arg(long, value_parser = non_negative)]
    pub clean_tol: Option<f64>,
    /// One section (and property) per thickness band of each solid, or one per patch.
    #[arg(long, value_enum, default_value_t = Sections::Band)]
    pub sections: Sections,
    /// First id of nodes, elements, properties and the material: give each part's deck its own range to
    /// include several in one model (the quality report prints the last id used).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
    pub start_id: u64,
    /// A JSON file of quality criteria gating the exit code (fields in docs/mesh.md) [default: smallest edge at
    /// least 0.2 x --size].
    #[arg(long)]
    pub criteria: Option<PathBuf>,
    /// Young's modulus in MPa of the decks' material and the time-step estimate [default: steel].
    #[arg(long, default_value_t = 210_000.0, value_parser = positive)]
    pub young: f64,
    /// Density in t/mm³ [default: steel].
    #[arg(long, default_value_t = 7.85e-9, value_parser = positive)]
    pub density: f64,
    /// Poisson's ratio [default: steel].
    #[arg(long, default_value_t = 0.3)]
    pub poisson: f64,
    /// Also write a binary glTF (.glb) of the mesh here, for any glTF viewer (docs/mesh.md).
    #[arg(long)]
    pub preview: Option<PathBuf>,
    /// What the preview's colours show: each element's thickness band (the colours of the run's STEP), or
    /// whether it fails a quality criterion (red) or not (grey).
    #[arg(long, value_enum, default_value_t = Coloring::Thickness, requires = "preview")]
    pub color: Coloring,
    /// Refuse to mesh when the mid-surface's area over size² exceeds this many elements (a part measured in
    /// metres meshed at 2 mm would run for hours and fill the disk).
    #[arg(long, default_value_t = 2_000_000)]
    pub max_elements: u64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Format {
    K,
    Bdf,
    Inp,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Sections {
    Band,
    Patch,
}

fn positive(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("'{s}' is not a positive number")),
    }
}

fn non_negative(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        _ => Err(format!("'{s}' is not a number (0 or more)")),
    }
}

/// The quality report (BASE.quality.json).
#[derive(Debug, Serialize)]
pub struct QualityReport {
    pub midsurface: String,
    pub report: String,
    pub gmsh: String,
    pub size: f64,
    pub all_quads: bool,
    pub sections: Sections,
    pub position: Placement,
    pub material: Material,
    /// Plate wave speed of the material (mm/s).
    pub wave_speed: f64,
    pub matching: Matching,
    /// Whether the whole model meshed at once, and the faces meshed one by one after it did not.
    pub meshing: Meshing,
    /// Faces no attempt could mesh: left out of the decks (the `unmeshed_faces` criterion fails).
    pub unmeshed_faces: Vec<UnmeshedFace>,
    pub cleanup: Cleanup,
    pub nodes: usize,
    /// First and last id used (nodes, elements, properties share the start id).
    pub ids: [u64; 2],
    pub properties: Vec<Property>,
    pub parts: Vec<PartQuality>,
    pub total: PartQuality,
    /// Free length of the mid-surface (rim + open edges, from the run's report), to compare with the mesh's.
    pub midsurface_free_length: Option<f64>,
    pub criteria: Vec<CriterionResult>,
    pub passed: bool,
    pub decks: Vec<String>,
    pub preview: Option<String>,
}

pub fn run(args: &MeshCli) -> Result<Exit, Error> {
    let run = run_report::read(&args.report)?;
    if !(0.0..0.5).contains(&args.poisson) {
        return Err(Error::input(&args.midsurface, format!("--poisson {} is not in [0, 0.5)", args.poisson)));
    }
    let criteria = match &args.criteria {
        None => Criteria::default_gate(),
        Some(path) => {
            let text = std::fs::read_to_string(path).map_err(|e| Error::input(path, e.to_string()))?;
            serde_json::from_str(&text).map_err(|e| Error::input(path, format!("not a criteria file: {e}")))?
        }
    };
    let estimate = run.area / (args.size * args.size);
    if estimate > args.max_elements as f64 {
        return Err(Error::input(
            &args.midsurface,
            format!(
                "{:.3e} mm2 at --size {} makes about {:.1e} elements, over --max-elements {}: give a larger --size (>= {:.3})",
                run.area,
                args.size,
                estimate,
                args.max_elements,
                (run.area / args.max_elements as f64).sqrt()
            ),
        ));
    }
    let material = Material { young_mpa: args.young, density_t_mm3: args.density, poisson: args.poisson };

    let faces = mesher::named_faces(&args.midsurface)?;
    let gmsh = mesher::gmsh_mesh(&mesher::MeshRequest {
        path: &args.midsurface,
        size: args.size,
        all_quads: args.all_quads,
        time_floor_s: mesher::TIME_FLOOR_S,
        time_per_element_s: mesher::TIME_PER_ELEMENT_S,
        expected_elements: estimate,
    })?;
    let (mut mesh, matching) = shell::assemble(&gmsh, &faces).map_err(|e| Error::input(&args.midsurface, e))?;
    let (meshing, unmeshed_faces) = meshing::account(&gmsh, &faces, &matching);
    let cleanup = cleanup::clean(&mut mesh, args.clean_tol.unwrap_or(0.2 * args.size));
    if mesh.elements.is_empty() {
        let why = gmsh.unmeshed.first().map(|u| format!(" (gmsh: {})", u.why)).unwrap_or_default();
        return Err(Error::input(&args.midsurface, format!("the mesh has no elements{why}")));
    }
    if let Some(e) = mesh.elements.iter().find(|e| !run.part_of.contains_key(&e.patch)) {
        return Err(Error::input(
            &args.report,
            format!("has no patch {} (face {} of the mid-surface)", e.patch, e.face),
        ));
    }
    let (properties, property_of) =
        properties::properties(&mesh.elements, &run.part_of, &run.thickness_of, args.sections, args.start_id);

    let measured = quality::measure(&mesh, &run.part_of, &run.thickness_of, &run.solid_volume, &material);
    let results = criteria::check(&criteria, &mesh, &measured, args.size, &material, run.free_length, &unmeshed_faces);
    let passed = results.iter().all(|r| r.passed);

    let name = args.midsurface.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let deck = Deck {
        title: format!("midsurf mesh of {name}, size {} mm", args.size),
        mesh: &mesh,
        property_of,
        properties: properties.clone(),
        material,
        placement: run.placement,
        start_id: args.start_id,
    };
    let mut formats = args.format.clone();
    formats.sort_by_key(|f| *f as u8);
    formats.dedup();
    let mut outputs: Vec<(PathBuf, Vec<u8>)> = formats
        .iter()
        .map(|f| match f {
            Format::K => (with_suffix(&args.output, "k"), deck::lsdyna(&deck).into_bytes()),
            Format::Bdf => (with_suffix(&args.output, "bdf"), deck::nastran(&deck).into_bytes()),
            Format::Inp => (with_suffix(&args.output, "inp"), deck::abaqus(&deck).into_bytes()),
        })
        .collect();
    let quality = QualityReport {
        midsurface: args.midsurface.display().to_string(),
        report: args.report.display().to_string(),
        gmsh: gmsh.gmsh.clone(),
        size: args.size,
        all_quads: args.all_quads,
        sections: args.sections,
        position: run.placement,
        material,
        wave_speed: material.wave_speed(),
        matching,
        meshing,
        unmeshed_faces,
        cleanup,
        nodes: mesh.nodes.len(),
        ids: [args.start_id, deck.last_id()],
        properties,
        parts: measured.parts,
        total: measured.total,
        midsurface_free_length: run.free_length,
        criteria: results,
        passed,
        decks: outputs.iter().map(|(p, _)| p.display().to_string()).collect(),
        preview: args.preview.as_ref().map(|p| p.display().to_string()),
    };
    if let Some(path) = &args.preview {
        let colors = preview_colors(args.color, &mesh, &run, &quality.criteria);
        outputs.push((path.clone(), preview::glb(&mesh, &colors)));
    }
    let json = serde_json::to_string_pretty(&quality).expect("quality reports always serialise") + "\n";
    outputs.push((with_suffix(&args.output, "quality.json"), json.into_bytes()));
    write_all(&outputs)?;
    Ok(if passed { Exit::Clean } else { Exit::Warnings })
}

/// Each element's preview colour: its thickness band's, or red when it fails a criterion (grey when not).
fn preview_colors(
    coloring: Coloring,
    mesh: &shell::ShellMesh,
    run: &run_report::RunFacts,
    results: &[CriterionResult],
) -> Vec<[f64; 3]> {
    match coloring {
        Coloring::Thickness => mesh
            .elements
            .iter()
            .map(|e| crate::output::report::band_color(&run.legend, run.thickness_of[&e.patch]))
            .collect(),
        Coloring::Quality => {
            let mut failing = vec![false; mesh.elements.len()];
            for i in results.iter().flat_map(|r| &r.failing) {
                failing[*i] = true;
            }
            failing.into_iter().map(|f| if f { preview::FAILING } else { preview::PASSING }).collect()
        }
    }
}

fn with_suffix(base: &Path, suffix: &str) -> PathBuf {
    let mut s = base.as_os_str().to_owned();
    s.push(".");
    s.push(suffix);
    PathBuf::from(s)
}

/// Writes every file beside its final path, then renames them all: a failure leaves no half-written deck.
fn write_all(outputs: &[(PathBuf, Vec<u8>)]) -> Result<(), Error> {
    let temp = |p: &Path| with_suffix(p, &format!("tmp{}", std::process::id()));
    for (path, text) in outputs {
        if let Err(e) = std::fs::write(temp(path), text) {
            for (p, _) in outputs {
                let _ = std::fs::remove_file(temp(p));
            }
            return Err(Error::output(path, e.to_string()));
        }
    }
    for (path, _) in outputs {
        std::fs::rename(temp(path), path).map_err(|e| Error::output(path, e.to_string()))?;
    }
    Ok(())
}
