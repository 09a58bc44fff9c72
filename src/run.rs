//! `midsurf run`: STEP solid in, mid-surface STEP (a shell per connected set of patches) and report out.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::error::Error;
use crate::exit::Exit;
use crate::face_graph::{FaceGraph, FaceId};
use crate::geom::inside::SolidMesh;
use crate::output::Pending;
use crate::pairs_report::{PairingParams, SolidPairing};
use crate::part::{self, MeshRequest};
use crate::patch::plan::{plan_patches, PatchPlan, PlanNote, Position};
use crate::patch::trim::{connected_sets, find_branches, keep_mask};
use crate::report::{self, *};
use crate::sidecar::protocol::{Clip, FaceAttributes, Fused, MadePatch, Request, Shells, Written};
use crate::stitch::{branch_limits, stitch, FreeEdges, JointReport, PatchInfo};

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
}

/// A patch made in the sidecar, with what it came from.
struct Made {
    solid: usize,
    plan: PatchPlan,
    handle: u64,
}

pub fn run(args: &RunArgs) -> Result<Exit, Error> {
    let started = Instant::now();
    let mut timings = Timings::default();
    let named = [("-o", Some(&args.output)), ("--report", args.report.as_ref()), ("--summary", args.summary.as_ref())];
    let named = named.into_iter().chain([("--csv", args.csv.as_ref()), ("--preview", args.preview.as_ref())]);
    let named: Vec<(&str, &Path)> = named.filter_map(|(n, p)| p.map(|p| (n, p.as_path()))).collect();
    crate::output::distinct(&named)?;
    let step_out = Pending::new(&args.output, &args.input)?;
    let optional = |path: &Option<PathBuf>| path.as_deref().map(|p| Pending::new(p, &args.input)).transpose();
    let (report_out, summary_out) = (optional(&args.report)?, optional(&args.summary)?);
    let (csv_out, preview_out) = (optional(&args.csv)?, optional(&args.preview)?);
    let mut sidecar = part::start_sidecar(&args.input)?;
    let kernel = |e| Error::Sidecar { path: args.input.clone(), error: e };

    let t = Instant::now();
    let mut part = part::load(&mut sidecar, &args.input, MeshRequest { mesh: true, tolerance: None })?;
    timings.load = t.elapsed().as_secs_f64();
    let option_warnings = crate::checks::against_part(&args.params, &part).map_err(|p| Error::input(&args.input, p))?;

    let t = Instant::now();
    let pairings: Vec<SolidPairing> = crate::isolation::pair_solids(&mut part, args.params);
    if part.solids.is_empty() {
        let why: Vec<String> = part.skipped.iter().map(|(n, why)| format!("solid {n}: {why}")).collect();
        return Err(Error::input(&args.input, format!("no solid could be paired: {}", why.join("; "))));
    }
    timings.pairing = t.elapsed().as_secs_f64();

    let mut warnings = option_warnings;
    warnings.extend(crate::isolation::entity_warning(&part));
    warnings.extend(crate::isolation::skipped_solid_warnings(&part));
    let t = Instant::now();
    let mut made: Vec<Made> = Vec::new();
    for (i, (solid, sp)) in part.solids.iter().zip(&pairings).enumerate() {
        warnings.extend(crate::isolation::undescribed_face_warnings(i + 1, &solid.graph));
        warnings.extend(pairing_warnings(i + 1, &solid.graph, sp));
        let (fill, narrow, beside) = (sp.fill_edges(), sp.clip_narrow(), sp.blends_beside(&solid.graph));
        let (plans, notes) = plan_patches(&solid.graph, &sp.pairing, args.position, &fill);
        warnings.extend(notes.into_iter().map(|note| plan_warning(i + 1, note)));
        for plan in plans {
            let near: Vec<FaceId> = plan.faces.iter().chain(plan.partners.iter().flatten()).copied().collect();
            let (narrow, narrow_end) =
                if plan.strict { (0.0, 0.0) } else { (narrow, sp.clip_narrow_end(&beside, &near)) };
            let request = Request::MakePatch {
                handle: solid.handle,
                faces: plan.faces.clone(),
                placement: plan.placement.clone(),
                clip: Some(Clip {
                    partners: plan.partners.clone(),
                    fuzzy: sp.tolerances.fuse,
                    narrow,
                    narrow_end,
                    exclude: plan.exclude.clone(),
                }),
                reverse: plan.reverse,
                fill: plan.fill.clone(),
            };
            match sidecar.call::<MadePatch>(&request) {
                Ok(patch) => {
                    if patch.filled != plan.fill_loops {
                        // The kernel can skip a loop silently: say which feature may still show.
                        warnings.push(Warning {
                            code: "feature_not_suppressed",
                            message: format!(
                                "group {} faces {:?}: {} of {} loops of suppressed features filled",
                                plan.group, plan.faces, patch.filled, plan.fill_loops
                            ),
                            solid: Some(i + 1),
                            faces: plan.faces.clone(),
                        });
                    }
                    made.push(Made { solid: i + 1, plan, handle: patch.handle })
                }
                Err(e) if e.code().is_some() => warnings.push(Warning {
                    code: "patch_failed",
                    message: format!("group {} faces {:?}: {e}", plan.group, plan.faces),
                    solid: Some(i + 1),
                    faces: plan.faces.clone(),
                }),
                Err(e) => return Err(kernel(e)),
            }
        }
    }
    timings.patches = t.elapsed().as_secs_f64();

    let t = Instant::now();
    let fuzzy = pairings.iter().map(|p| p.tolerances.fuse).fold(f64::INFINITY, f64::min);
    let fuzzy = if fuzzy.is_finite() { fuzzy } else { 0.0 };
    let fused: Fused = sidecar
        .call(&Request::Fuse { patches: made.iter().map(|m| m.handle).collect(), fuzzy, split_internal: false })
        .map_err(kernel)?;
    let thickness: Vec<f64> = made.iter().map(|m| m.plan.thickness.mean).collect();
    // Per solid: some patch of it was made with a junction loop filled.
    let mut junctions = vec![false; part.solids.len()];
    for m in &made {
        let junction = &pairings[m.solid - 1].junction;
        junctions[m.solid - 1] |= m.plan.fill.iter().any(|e| junction.binary_search(e).is_ok());
    }
    let infos: Vec<PatchInfo> = made
        .iter()
        .map(|m| {
            let tolerances = &pairings[m.solid - 1].tolerances;
            // On a skin the patch a joint grows to may lie up to half a thickness farther than its middle.
            let skin = args.position.to_mid(tolerances.t_max).abs();
            PatchInfo {
                thickness: m.plan.thickness.mean,
                to_mid: m.plan.to_mid,
                solid: m.solid - 1,
                reach: tolerances.joint_reach + skin,
                on_rim: crate::tolerance::on_rim(m.plan.thickness.mean, part.solids[m.solid - 1].mesh_tolerance),
                junction: junctions[m.solid - 1],
                wall: (m.solid, m.plan.group),
            }
        })
        .collect();
    let meshes: Vec<SolidMesh> =
        part.solids.iter().map(|s| SolidMesh::new(&s.graph).expect("run describes every solid with meshes")).collect();
    let mut branches = find_branches(&fused, &branch_limits(&infos));
    let keep = keep_mask(fused.faces.len(), &branches);
    timings.trim = t.elapsed().as_secs_f64();

    let t = Instant::now();
    let (fused, keep, joints, free) = match stitch(&mut sidecar, &fused, &keep, &infos, &meshes, fuzzy) {
        Ok(s) => {
            branches.extend(s.branches);
            warnings.extend(open_edges_warning(&s.free, &s.open_patches));
            (s.fused, s.keep, s.joints, Some(s.free))
        }
        Err(e) if e.code().is_some() => {
            warnings.push(Warning {
                code: "stitch_failed",
                message: format!("the patches are written unstitched: {e}"),
                solid: None,
                faces: Vec::new(),
            });
            (fused, keep, Vec::new(), None)
        }
        Err(e) => return Err(kernel(e)),
    };
    warnings.extend(joint_warnings(&joints));
    let sets = connected_sets(&fused, &keep);
    let shells: Shells =
        sidecar.call(&Request::MakeShells { handle: fused.handle, shells: sets.clone(), fuzzy }).map_err(kernel)?;
    warnings.extend(invalid_output_warning(&shells, &fused));
    timings.stitch = t.elapsed().as_secs_f64();

    let legend = report::legend(&thickness);
    let patches = patch_reports(&made, &fused, &keep);
    if made.is_empty() {
        warnings.push(Warning {
            code: "no_pairs",
            message: "no face pairs found: the output is empty; check --t-max and --draft-max".to_string(),
            solid: None,
            faces: Vec::new(),
        });
    }

    let t = Instant::now();
    let faces: Vec<FaceAttributes> = shells
        .faces
        .iter()
        .enumerate()
        .map(|(j, &piece)| {
            let k = fused.faces[piece].patch;
            let t = made[k].plan.thickness.mean;
            FaceAttributes {
                face: j,
                name: format!("patch {} t={t:.3}", k + 1),
                color: report::band_color(&legend, t),
                thickness: t,
            }
        })
        .collect();
    let utf8 = |p: &Pending| {
        p.temp.to_str().map(str::to_string).ok_or_else(|| Error::output(&p.target, "path is not valid UTF-8"))
    };
    let preview = preview_out.as_ref().map(utf8).transpose()?;
    sidecar
        .call::<Written>(&Request::WriteStep { path: utf8(&step_out)?, handle: shells.handle, faces, preview })
        .map_err(kernel)?;
    sidecar.shutdown();
    timings.write = t.elapsed().as_secs_f64();
    timings.total = started.elapsed().as_secs_f64();

    let topology = crate::topology::summarise(&fused, &keep, &shells, sets.len(), &patches, &joints, free);
    let report = Report {
        report_version: REPORT_VERSION,
        midsurf_version: env!("CARGO_PKG_VERSION"),
        input: args.input.display().to_string(),
        output: args.output.display().to_string(),
        parameters: Parameters {
            t_max: args.params.t_max,
            draft_max_deg: args.params.draft_max_deg,
            position: args.position,
        },
        solids: part
            .solids
            .iter()
            .zip(&pairings)
            .enumerate()
            .map(|(i, (s, sp))| solid_report(i + 1, &s.graph, sp))
            .collect(),
        patches,
        trimmed: branches.iter().map(TrimmedReport::from_branch).collect(),
        joints,
        thickness_legend: legend,
        result: ResultSummary {
            faces: shells.faces.len(),
            shells: sets.len(),
            valid: shells.valid,
            area: written_area(&shells, &fused),
            free_edges: free,
        },
        topology,
        warnings,
        timings_s: args.timings.then_some(timings),
    };
    if let Some(pending) = &report_out {
        pending.write((serde_json::to_string_pretty(&report).expect("reports always serialise") + "\n").as_bytes())?;
    }
    if let Some(pending) = &summary_out {
        pending.write(report.topology.text().as_bytes())?;
    }
    if let Some(pending) = &csv_out {
        pending.write(report::patches_csv(&report.patches).as_bytes())?;
    }
    let set = [Some(step_out), report_out, summary_out, csv_out, preview_out];
    crate::output::commit_all(set.into_iter().flatten().collect())?;
    eprintln!("{}", summary_line(&args.output, &report));
    Ok(if report.warnings.is_empty() { Exit::Clean } else { Exit::Warnings })
}

fn joint_warnings(joints: &[JointReport]) -> Vec<Warning> {
    joints
        .iter()
        .filter(|j| j.status != "extended")
        .map(|j| Warning {
            code: "joint_failed",
            message: match j.status {
                "no_partner" => format!(
                    "patch {}: {} open edge(s), {:.3} mm, meet no patch within reach; left unstitched",
                    j.patches[0], j.edges, j.length
                ),
                _ => format!(
                    "{} joint of patches {:?}: the kernel could not grow {} edge(s), {:.3} mm",
                    j.kind, j.patches, j.edges, j.length
                ),
            },
            solid: None,
            faces: Vec::new(),
        })
        .collect()
}

/// Open edges left after stitching are gaps in the mid-surface a mesher would keep: said once, with the patches.
fn open_edges_warning(free: &FreeEdges, open_patches: &BTreeSet<usize>) -> Option<Warning> {
    (free.open_edges > 0).then(|| Warning {
        code: "open_edges",
        message: format!(
            "{} free edge(s), {:.3} mm, still lie inside the material after stitching (patches {}): the \
             mid-surface has gaps there",
            free.open_edges,
            free.open_length,
            patch_list(open_patches)
        ),
        solid: None,
        faces: Vec::new(),
    })
}

/// Faces failing the kernel's check are written as they are (readers usually repair them), but a script must
/// know: said once, with their patches.
fn invalid_output_warning(shells: &Shells, fused: &Fused) -> Option<Warning> {
    let patches: BTreeSet<usize> = shells.invalid.iter().map(|&j| fused.faces[shells.faces[j]].patch).collect();
    (!shells.valid).then(|| Warning {
        code: "invalid_output",
        message: format!(
            "the mid-surface fails the kernel's validity check (BRepCheck){}: check them before meshing",
            if patches.is_empty() {
                String::new()
            } else {
                format!(" on {} face(s) of patches {}", shells.invalid.len(), patch_list(&patches))
            }
        ),
        solid: None,
        faces: Vec::new(),
    })
}

/// The area of the faces written. A face closed on itself is written as two pieces that both name it: count
/// each fused face once (its pieces make it up exactly).
fn written_area(shells: &Shells, fused: &Fused) -> f64 {
    let written: BTreeSet<usize> = shells.faces.iter().copied().collect();
    written.iter().map(|&p| fused.faces[p].area).sum()
}

/// Patch indices as the ids the output names them by ("patch 3"), comma separated.
fn patch_list(patches: &BTreeSet<usize>) -> String {
    patches.iter().map(|k| (k + 1).to_string()).collect::<Vec<_>>().join(", ")
}

fn plan_warning(solid: usize, note: PlanNote) -> Warning {
    match note {
        PlanNote::ThicknessStep { group, faces, thickness: t } => Warning {
            code: "thickness_step",
            message: format!(
                "group {group}: both sides span a thickness step ({:.3}..{:.3}); the patch is offset at the mean {:.3}",
                t.min, t.max, t.mean
            ),
            solid: Some(solid),
            faces,
        },
        PlanNote::PartialOverlap { group, faces, coverage } => Warning {
            code: "partial_overlap",
            message: format!(
                "group {group}: the partners cover only {:.0}% of the offset faces; the patch runs past the wall",
                coverage * 100.0
            ),
            solid: Some(solid),
            faces,
        },
    }
}

fn summary_line(output: &Path, r: &Report) -> String {
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

fn patch_reports(made: &[Made], fused: &Fused, keep: &[bool]) -> Vec<PatchReport> {
    made.iter()
        .enumerate()
        .map(|(k, m)| {
            let pieces: Vec<&crate::sidecar::protocol::FusedFace> =
                fused.faces.iter().enumerate().filter(|(i, f)| keep[*i] && f.patch == k).map(|(_, f)| f).collect();
            PatchReport {
                id: k + 1,
                solid: m.solid,
                group: m.plan.group,
                kind: m.plan.kind,
                source_faces: m.plan.faces.clone(),
                thickness: m.plan.thickness,
                area: pieces.iter().map(|f| f.area).sum(),
                faces: pieces.len(),
            }
        })
        .collect()
}

fn pairing_warnings(solid: usize, graph: &FaceGraph, sp: &SolidPairing) -> Vec<Warning> {
    let mut out = Vec::new();
    for (f, role) in sp.pairing.roles.iter().enumerate() {
        if let Some(why) = role.unpaired_reason().filter(|_| graph.faces[f].problem.is_none()) {
            out.push(Warning {
                code: "unpaired_face",
                message: format!(
                    "face {f} ({}, {:.3} mm2) has no partner: {why}",
                    graph.faces[f].surface.kind_name(),
                    graph.faces[f].area
                ),
                solid: Some(solid),
                faces: vec![f],
            });
        }
    }
    for g in &sp.pairing.groups {
        if !g.side_conflicts.is_empty() {
            out.push(Warning {
                code: "side_conflict",
                message: format!("group {}: faces pair with faces of their own side", g.id),
                solid: Some(solid),
                faces: g.side_conflicts.clone(),
            });
        }
    }
    out
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
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sidecar::protocol::FusedFace;
    use glam::DVec3;

    /// Fused pieces of the given (patch, area).
    fn fused(faces: &[(usize, f64)]) -> Fused {
        let face = |&(patch, area): &(usize, f64)| FusedFace {
            patch,
            area,
            centroid: DVec3::ZERO,
            point: DVec3::ZERO,
            normal: DVec3::Z,
            edges: vec![],
        };
        Fused { handle: 1, faces: faces.iter().map(face).collect(), edges: vec![] }
    }

    fn shells(faces: Vec<usize>, valid: bool, invalid: Vec<usize>) -> Shells {
        Shells { handle: 2, faces, valid, invalid, edges: 0, vertices: 0 }
    }

    #[test]
    fn invalid_faces_are_named_by_the_patches_they_belong_to() {
        // Shell face j is fused piece faces[j]; pieces 0..3 belong to patches 4, 4, 0, 2 (ids 5, 5, 1, 3).
        let fused = fused(&[(4, 1.0), (4, 1.0), (0, 1.0), (2, 1.0)]);
        let w = invalid_output_warning(&shells(vec![3, 0, 1, 2], false, vec![1, 2, 0]), &fused).unwrap();
        assert_eq!(w.code, "invalid_output");
        assert!(w.message.contains("on 3 face(s) of patches 3, 5:"), "{}", w.message);
        assert!(invalid_output_warning(&shells(vec![0, 1, 2, 3], true, vec![]), &fused).is_none());
        // Invalid as a whole (say, a shell in two pieces) with every face sound: no patch to name.
        let whole = invalid_output_warning(&shells(vec![0, 1, 2, 3], false, vec![]), &fused).unwrap();
        assert!(!whole.message.contains("patches"), "{}", whole.message);
    }

    #[test]
    fn a_face_split_at_its_seam_counts_once_in_the_written_area() {
        let fused = fused(&[(0, 2.0), (1, 3.0), (2, 5.0)]);
        // Fused face 1 (a tube) is written as two pieces, both naming it.
        assert_eq!(written_area(&shells(vec![0, 1, 1, 2], true, vec![]), &fused), 10.0);
    }

    #[test]
    fn open_edges_are_said_once_with_their_patches() {
        let free = FreeEdges { rim_edges: 4, rim_length: 40.0, open_edges: 3, open_length: 2.5 };
        let w = open_edges_warning(&free, &BTreeSet::from([6, 0])).unwrap();
        assert_eq!(w.code, "open_edges");
        assert!(
            w.message.starts_with("3 free edge(s), 2.500 mm") && w.message.contains("(patches 1, 7)"),
            "{}",
            w.message
        );
        assert!(open_edges_warning(&FreeEdges { open_edges: 0, ..free }, &BTreeSet::new()).is_none());
    }
}
