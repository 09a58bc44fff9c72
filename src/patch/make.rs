//! Making the planned mid-patches in the kernel: one `make_patch` request per plan, clipped to the plan's
//! partners, with the loops of suppressed features filled.

use super::plan::{plan_patches, PatchPlan, PlanNote};
use crate::kernel::protocol::{Clip, MadePatch, Request};
use crate::kernel::{Kernel, SidecarError};
use crate::load::Part;
use crate::model::face_graph::FaceId;
use crate::model::params::Position;
use crate::model::shapes::Handle;
use crate::model::warning::Warning;
use crate::pairing::driver::SolidPairing;
use crate::pairing::Thickness;

/// A patch made in the kernel, with what it came from.
pub struct Made {
    /// 1-based solid.
    pub solid: usize,
    pub plan: PatchPlan,
    pub handle: Handle,
}

/// The patches made, and per solid in order the warnings of its pairing, its plans and the patches that failed.
pub struct Patches {
    pub made: Vec<Made>,
    pub warnings: Vec<Warning>,
}

/// Plans and makes the patches of every solid. A patch the kernel fails to make is a warning; a kernel that
/// stops answering is an error.
pub fn make_patches<K: Kernel>(
    kernel: &mut K,
    part: &Part,
    pairings: &[SolidPairing],
    position: Position,
) -> Result<Patches, SidecarError> {
    let mut out = Patches { made: Vec::new(), warnings: Vec::new() };
    for (i, (solid, sp)) in part.solids.iter().zip(pairings).enumerate() {
        out.warnings.extend(sp.warnings(i + 1, &solid.graph));
        let (fill, narrow, beside) = (sp.fill_edges(), sp.clip_narrow(), sp.blends_beside(&solid.graph));
        let (plans, notes) = plan_patches(&solid.graph, &sp.pairing, position, &fill);
        out.warnings.extend(notes.into_iter().map(|note| plan_warning(i + 1, note)));
        for plan in plans {
            let near: Vec<FaceId> = plan.faces.iter().chain(plan.partners.iter().flatten()).copied().collect();
            let (narrow, narrow_end) =
                if plan.strict { (0.0, 0.0) } else { (narrow, sp.clip_narrow_end(&beside, &near)) };
            let request = Request::MakePatch {
                handle: solid.handle,
                faces: plan.faces.clone(),
                placement: (&plan.placement).into(),
                clip: Some(Clip {
                    partners: plan.partners.clone(),
                    fuzzy: sp.tolerances.fuse,
                    narrow,
                    narrow_end,
                    exclude: plan.exclude.clone(),
                    thickness: plan.thickness.mean,
                    // The patch normal is the faces' outward one turned over when the plan reverses it.
                    to_mid: if plan.reverse { -plan.to_mid } else { plan.to_mid },
                    wall_max: sp.tolerances.t_max,
                }),
                reverse: plan.reverse,
                mid_wall: plan.mid_wall,
                fill: plan.fill.clone(),
            };
            match kernel.call::<MadePatch>(&request) {
                Ok(patch) => {
                    if patch.filled != plan.fill_loops {
                        // The kernel can skip a loop silently: say which feature may still show.
                        out.warnings.push(Warning {
                            code: "feature_not_suppressed",
                            message: format!(
                                "group {} faces {:?}: {} of {} loops of suppressed features filled",
                                plan.group, plan.faces, patch.filled, plan.fill_loops
                            ),
                            solid: Some(i + 1),
                            faces: plan.faces.clone(),
                        });
                    }
                    out.made.push(Made { solid: i + 1, plan, handle: patch.handle })
                }
                Err(e) if e.code().is_some() => out.warnings.push(Warning {
                    code: "patch_failed",
                    message: format!("group {} faces {:?}: {e}", plan.group, plan.faces),
                    solid: Some(i + 1),
                    faces: plan.faces.clone(),
                }),
                Err(e) => return Err(e),
            }
        }
    }
    Ok(out)
}

/// "(min..max); the patch is offset at the mean m".
fn at_mean(t: Thickness) -> String {
    format!("({:.3}..{:.3}); the patch is offset at the mean {:.3}", t.min, t.max, t.mean)
}

fn plan_warning(solid: usize, note: PlanNote) -> Warning {
    match note {
        PlanNote::ThicknessStep { group, faces, thickness: t } => Warning {
            code: "thickness_step",
            message: format!("group {group}: both sides span a thickness step {}", at_mean(t)),
            solid: Some(solid),
            faces,
        },
        PlanNote::ThicknessVaries { group, faces, thickness: t, mid_wall } => Warning {
            code: "thickness_varies",
            message: if mid_wall {
                format!(
                    "group {group}: the wall tapers ({:.3}..{:.3}, mean {:.3}); the patch follows its mid-points",
                    t.min, t.max, t.mean
                )
            } else {
                format!("group {group}: the wall's thickness varies within its pairs {}", at_mean(t))
            },
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
