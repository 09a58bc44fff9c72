//! `midsurf run`: STEP solid in, mid-surface STEP (a shell per connected set of patches) and report out. Only
//! calls the stages, in order; each takes what the one before returned.

use std::path::PathBuf;
use std::time::Instant;

use crate::checks;
use crate::error::Error;
use crate::exit::Exit;
use crate::geom::bodies::Bodies;
use crate::kernel::client::killed_from_outside;
use crate::kernel::client::Sidecar;
use crate::kernel::SidecarError;
use crate::load::{self, MeshRequest};
use crate::model::params::Position;
use crate::model::shapes::Shells;
use crate::model::tolerance;
use crate::output::assemble::{self, Asked};
use crate::output::coverage;
use crate::output::files::Files;
use crate::output::report::Timings;
use crate::output::shells;
use crate::pairing::driver::PairingParams;
use crate::pairing::isolation;
use crate::patch::make::make_patches;
use crate::{stitch, trim};

pub struct RunArgs {
    pub input: PathBuf,
    pub output: PathBuf,
    pub report: Option<PathBuf>,
    pub summary: Option<PathBuf>,
    pub csv: Option<PathBuf>,
    pub preview: Option<PathBuf>,
    pub params: PairingParams,
    pub position: Position,
    pub timings: bool,
    /// Write the solids that are not thin-walled into the output STEP as solids.
    pub keep_solids: bool,
    /// Width of the thickness bands (--t-bands, mm).
    pub t_band: f64,
}

/// How one run goes: its booleans on one thread (`serial_booleans`), and whether it stitches.
#[derive(Debug, Clone, Copy)]
struct Attempt {
    serial_booleans: bool,
    stitch: bool,
}

/// `run_once`, and once more when the kernel crashed after the file was read (the sidecar ended by a signal
/// it raised itself, such as SIGSEGV, not one sent from outside): OCCT's booleans crash now and then on input
/// they handle on the next try, and a crash takes every kernel handle with it, so the part starts afresh. The
/// second run has the booleans on one thread: the crashes come from their threads (a part that crashed in
/// two runs of three on two threads ran clean on one), and a serial boolean gives the same result.
/// When the kernel hung while stitching (an op past its timeout), the part is run once more without
/// stitching: the same input would hang the same way, and patches with open joints (said in a warning) are of
/// more use than no file at all.
pub fn run(args: &RunArgs) -> Result<Exit, Error> {
    let mut stage = Stage::Before;
    match run_once(args, Attempt { serial_booleans: false, stitch: true }, &mut stage) {
        Err(Error::Sidecar { error: SidecarError::Died { op, stderr }, .. })
            if op != "load_step" && !killed_from_outside(&stderr) =>
        {
            eprintln!(
                "midsurf: the OCCT sidecar crashed during '{op}'; running {} once more, its booleans on one thread",
                args.input.display()
            );
            run_once(args, Attempt { serial_booleans: true, stitch: true }, &mut stage)
        }
        Err(Error::Sidecar { error: SidecarError::Timeout { op, after, .. }, .. }) if stage == Stage::Stitch => {
            eprintln!(
                "midsurf: the OCCT sidecar hung in '{op}' while stitching (no answer in {} s); running {} once more \
                 without stitching",
                after.as_secs(),
                args.input.display()
            );
            run_once(args, Attempt { serial_booleans: false, stitch: false }, &mut stage)
        }
        other => other,
    }
}

/// How far a run got: a kernel that hangs while stitching leaves a run without stitching to try.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Stage {
    Before,
    Stitch,
    After,
}

fn run_once(args: &RunArgs, attempt: Attempt, stage: &mut Stage) -> Result<Exit, Error> {
    let (started, mut timings) = (Instant::now(), Timings::default());
    let files = Files::open(&args.input, &args.output, [&args.report, &args.summary, &args.csv, &args.preview])?;
    let mut kernel = load::start_sidecar(&args.input, attempt.serial_booleans)?;
    let failed = |error| Error::Sidecar { path: args.input.clone(), error };
    let since = |t: Instant| t.elapsed().as_secs_f64();

    let t = Instant::now();
    let mut part = load::load(&mut kernel, &args.input, MeshRequest { mesh: true, tolerance: None })?;
    timings.load = since(t);
    let mut warnings = checks::against_part(&args.params, &part).map_err(|p| Error::input(&args.input, p))?;

    let t = Instant::now();
    let pairings = isolation::pair_solids(&mut part, args.params);
    if part.solids.is_empty() {
        let why: Vec<String> = part.skipped.iter().map(|(n, why)| format!("solid {n}: {why}")).collect();
        return Err(Error::input(&args.input, format!("no solid could be paired: {}", why.join("; "))));
    }
    warnings.extend(isolation::entity_warning(&part));
    warnings.extend(isolation::skipped_solid_warnings(&part));
    timings.pairing = since(t);

    let t = Instant::now();
    let patches = make_patches(&mut kernel, &part, &pairings, args.position).map_err(failed)?;
    warnings.extend(patches.warnings);
    timings.patches = since(t);

    let t = Instant::now();
    // Solids that are not thin-walled have no patch to fuse: their tolerances say nothing here.
    let fuzzy = tolerance::part_fuse(pairings.iter().filter(|p| p.class.is_thin_walled()).map(|p| &p.tolerances));
    let graphs: Vec<_> = part.solids.iter().map(|s| &s.graph).collect();
    let Bodies { shared, of_solid, materials: meshes } =
        Bodies::of(&graphs).expect("run describes every solid with meshes");
    let infos = stitch::patch_infos(&part, &pairings, &patches.made, args.position, &of_solid);
    let handles = patches.made.iter().map(|m| m.handle).collect();
    let limits = stitch::branch_limits(&infos);
    let trimmed =
        trim::fuse_and_trim(&mut kernel, handles, &stitch::patch_bodies(&infos), fuzzy, &limits).map_err(failed)?;
    timings.trim = since(t);

    let t = Instant::now();
    *stage = Stage::Stitch;
    let mut stitched = if attempt.stitch {
        stitch::stitch_part(&mut kernel, trimmed, &infos, &meshes, fuzzy).map_err(failed)?
    } else {
        stitch::unstitched(trimmed, "the kernel hung while stitching them in an earlier run")
    };
    warnings.extend(stitched.warnings.iter().cloned());
    let assembled = shells::make_shells(&mut kernel, &stitched, fuzzy).map_err(failed)?;
    *stage = Stage::After;
    timings.stitch = since(t);

    let t = Instant::now();
    let legend = assemble::thickness_legend(&patches.made, args.t_band);
    let made = &patches.made;
    let kept = if args.keep_solids { shells::kept_solids(&part, &pairings) } else { Vec::new() };
    let write = |kernel: &mut Sidecar, stitched: &stitch::Outcome, shells: &Shells| {
        let (fused, band) = (&stitched.fused, args.t_band);
        shells::write_step(kernel, &files, made, fused, shells, &legend, band, kept.clone(), &args.input)
    };
    let (mut assembled, written, left_out) =
        shells::write_checked(&mut kernel, &mut stitched, assembled, fuzzy, &args.input, write)?;
    warnings.extend(left_out);
    shells::checked(&mut assembled, &written, &stitched.fused);
    warnings.extend(assembled.warning.clone());
    let thinnest = made.iter().map(|m| m.plan.thickness.mean).fold(f64::INFINITY, f64::min);
    warnings.extend(shells::loose_edges_warning(assembled.max_edge_tolerance, thinnest));
    warnings.extend(shells::unshared_edges_warning(assembled.unshared_edges));
    timings.write = since(t);

    let t = Instant::now();
    let written = coverage::Written {
        part: &part,
        pairings: &pairings,
        made,
        fused: &stitched.fused,
        shells: &assembled.shells,
        body_of_solid: &of_solid,
    };
    let (coverage, uncovered) = coverage::measure(&mut kernel, &written);
    warnings.extend(uncovered);
    kernel.shutdown();
    timings.coverage = since(t);
    timings.total = since(started);

    let asked = Asked {
        input: &args.input,
        output: &args.output,
        params: args.params,
        position: args.position,
        keep_solids: args.keep_solids,
        t_band: args.t_band,
    };
    let timings = args.timings.then_some(timings);
    let report =
        assemble::report(&asked, &part, &pairings, made, &shared, stitched, assembled, coverage, warnings, timings);
    files.finish(&report)?;
    eprintln!("{}", assemble::summary_line(&args.output, &report));
    Ok(if report.warnings.is_empty() { Exit::Clean } else { Exit::Warnings })
}
