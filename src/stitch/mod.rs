//! Extend and stitch (Sheen et al. 5.4): grow the open free edges of the trimmed patches up to their partners,
//! fuse again so every joint becomes a shared edge, and trim the overshoot.

mod bridge;
mod edges;
mod grow;
pub mod joint;
mod peel;
mod reach;
#[cfg(test)]
mod tests;

use std::collections::BTreeSet;

use serde::Serialize;

use crate::geom::inside::SolidMesh;
use crate::kernel::protocol::EdgeRef;
use crate::kernel::{Kernel, SidecarError};
use crate::model::shapes::{EdgeProbe, Fused};
use crate::model::warning::Warning;
use crate::trim::{find_branches, keep_mask, outside_material, Branch, Trimmed};
use edges::classify_free;
use grow::{grow, Grown, JointTally, Pass};
pub use reach::{branch_limits, patch_bodies, patch_infos};

/// What one patch brings: its thickness, its solid (index into the solids' meshes) and how far its joints
/// may reach.
#[derive(Debug, Clone, Copy)]
pub struct PatchInfo {
    pub thickness: f64,
    /// From the patch to the middle of its wall along the patch normal (0 for a mid-patch).
    pub to_mid: f64,
    pub solid: usize,
    /// The body of its solid (`geom::bodies`): patches of different bodies are fused apart.
    pub body: usize,
    pub reach: f64,
    /// A free edge closer than this to the boundary is on the rim (`tolerance::on_rim`).
    pub on_rim: f64,
    /// A patch of its solid was made with a junction loop filled (`pairing::driver::junction_loops`): the pieces
    /// outside the material (the filling across the branch's bore, the branch's strip past the main) are trimmed.
    pub junction: bool,
    /// The wall the patch was made from (solid, lowest pair group of the wall): the levels of a thickness step
    /// share it, whether they pair as one group or as groups whose flat skins on one side run on into each other
    /// (`pairing::levels`).
    pub wall: (usize, usize),
    /// A freeform patch (offset of a B-spline): its curved free edges do not grow to the rim (`edges::to_rim`).
    pub freeform: bool,
}

/// The joints made between two patches (or tried from one), summed over their edges.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JointReport {
    /// 1-based patch ids, sorted; one id for an edge that found no partner.
    pub patches: Vec<usize>,
    pub kind: &'static str,
    pub status: &'static str,
    pub edges: usize,
    pub length: f64,
}

/// Free edges of the result that still lie in the material (open joints), and the part's rim.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct FreeEdges {
    pub rim_edges: usize,
    pub rim_length: f64,
    pub open_edges: usize,
    pub open_length: f64,
}

pub struct Stitched {
    pub fused: Fused,
    pub keep: Vec<bool>,
    /// Branches dropped in this pass (the overshoot of the strips, and crossings they made).
    pub branches: Vec<Branch>,
    pub joints: Vec<JointReport>,
    pub free: FreeEdges,
    /// The patches (indices) with an open edge left.
    pub open_patches: BTreeSet<usize>,
    /// The passes after the first that the kernel failed (their joints are not made), with the kernel's word.
    pub failed_passes: Vec<String>,
}

/// A free edge of the kept faces: (edge, its one kept face).
type FreeEdge = (usize, usize);

/// Free edges of the kept faces, in edge order.
fn free_edges(fused: &Fused, keep: &[bool]) -> Vec<FreeEdge> {
    fused
        .edges
        .iter()
        .enumerate()
        .filter_map(|(e, edge)| {
            let kept: Vec<usize> = edge.faces.iter().copied().filter(|&f| keep[f]).collect();
            (kept.len() == 1 && edge.length > 0.0).then(|| (e, kept[0]))
        })
        .collect()
}

/// The free edges `free` of `fused` probed at `samples` points each, rays meeting the faces `targets`.
fn probe<K: Kernel>(
    kernel: &mut K,
    fused: &Fused,
    free: &[FreeEdge],
    targets: Vec<usize>,
    patches: &[PatchInfo],
    samples: usize,
) -> Result<Vec<EdgeProbe>, SidecarError> {
    if free.is_empty() {
        return Ok(Vec::new());
    }
    let edges = free.iter().map(|&(edge, face)| EdgeRef { edge, face }).collect();
    let reach = patches.iter().map(|p| p.reach).fold(0.0, f64::max);
    kernel.probe_edges(fused.handle, edges, targets, samples, reach)
}

/// The pieces of `fused` to drop: the branches hanging past crossings, then of the rest those of patches with a
/// filled junction that lie outside the material; with the mask of the pieces kept.
pub(super) fn trim(fused: &Fused, patches: &[PatchInfo], solids: &[SolidMesh]) -> (Vec<bool>, Vec<Branch>) {
    let mut branches = find_branches(fused, &branch_limits(patches));
    let keep = keep_mask(fused.faces.len(), &branches);
    // Only where a junction was filled: elsewhere a piece of a patch out of the material is an overshoot the
    // joints still use (dropping them all made ender3_x_limit's and fw13_top_cover's stitching worse).
    if !patches.iter().any(|p| p.junction) {
        return (keep, branches);
    }
    branches.extend(outside_material(fused, &keep, |face| {
        let patch = &patches[face.patch];
        !patch.junction || solids[patch.solid].contains(face.point + face.normal * patch.to_mid)
    }));
    (keep_mask(fused.faces.len(), &branches), branches)
}

/// Extends the open edges of `fused` (pieces `keep`, already trimmed) and fuses again (also without any
/// extension: the final fuse splits faces along joints that end inside them), peeling the dangling pieces after
/// each pass. When edges are still open after that, a second pass grows the free edges that stop short of the
/// rim, and a third the open edges to a partner patch.
pub fn stitch<K: Kernel>(
    kernel: &mut K,
    fused: &Fused,
    keep: &[bool],
    patches: &[PatchInfo],
    solids: &[SolidMesh],
    fuzzy: f64,
) -> Result<Stitched, SidecarError> {
    let mut tally = JointTally::default();
    let mut failed_passes = Vec::new();
    let (free, probes) = free_and_probed(kernel, fused, keep, patches, true)?;
    let grown = run_pass(
        kernel,
        fused,
        keep,
        &free,
        &probes,
        patches,
        solids,
        fuzzy,
        Pass::Joints,
        &mut tally,
        &mut failed_passes,
    )?;
    let (fused, keep, mut branches) = grown.expect("the joints pass fuses");
    let mut keep = keep;
    peel_dangling(&fused, &mut keep, &mut branches, patches, solids);
    // The free edges of the result, probed once for both the rims pass and the final count.
    let (free, probes) = free_and_probed(kernel, &fused, &keep, patches, false)?;
    let (counted, open_by_patch) = classify_free(&fused, &free, &probes, patches, solids);
    let mut state = State { fused, keep, branches, free, probes, counted, open_by_patch };
    let context = (patches, solids, fuzzy);
    state = later_pass(kernel, state, Pass::Rims, context, &mut tally, &mut failed_passes)?;
    state = later_pass(kernel, state, Pass::Partners, context, &mut tally, &mut failed_passes)?;
    let State { fused, keep, branches, counted, open_by_patch, .. } = state;
    let open_patches = (0..open_by_patch.len()).filter(|&p| open_by_patch[p] > 0.0).collect();
    Ok(Stitched { fused, keep, branches, joints: tally.reports(), free: counted, open_patches, failed_passes })
}

/// The stitching between passes: the fused patches, the pieces kept, the branches dropped so far, the free edges
/// with their probes and their count, and the open length of each patch.
struct State {
    fused: Fused,
    keep: Vec<bool>,
    branches: Vec<Branch>,
    free: Vec<FreeEdge>,
    probes: Vec<EdgeProbe>,
    counted: FreeEdges,
    open_by_patch: Vec<f64>,
}

impl State {
    /// Open length plus the length of the edges of broken pieces (see `broken_length`).
    fn unstitched(&self) -> f64 {
        self.counted.open_length + broken_length(&self.fused, &self.keep)
    }

    /// `unstitched`, per patch.
    fn unstitched_by_patch(&self) -> Vec<f64> {
        let mut out = self.open_by_patch.clone();
        for (face, length) in broken_faces(&self.fused, &self.keep) {
            out[self.fused.faces[face].patch] += length;
        }
        out
    }
}

/// A pass after the first (`Pass::Rims` on the free edges as they are, `Pass::Partners` on them probed for
/// partners), when edges are still open; its result peeled and counted. The result stands only when it leaves
/// no more open length than it found: a later pass is there to close what the first left, and one that opens
/// more (a strip's overshoot peeled with the piece it hung on, a fuse that split a patch apart) is undone with
/// its joints, so each pass can only improve the stitching. Undone, it is tried again (up to `MORE_TRIES` times)
/// without the edges of the patches its tries set back and of those whose rays meet them within reach: the
/// joints it made elsewhere stand when that leaves no more open than before.
fn later_pass<K: Kernel>(
    kernel: &mut K,
    state: State,
    pass: Pass,
    context: (&[PatchInfo], &[SolidMesh], f64),
    tally: &mut JointTally,
    failed_passes: &mut Vec<String>,
) -> Result<State, SidecarError> {
    if state.counted.open_edges == 0 {
        return Ok(state);
    }
    let patches = context.0;
    let before = tally.clone();
    let probed;
    let (free, probes) = if pass == Pass::Partners {
        probed = free_and_probed(kernel, &state.fused, &state.keep, patches, true)?;
        (&probed.0, &probed.1)
    } else {
        (&state.free, &state.probes)
    };
    let Some(tried) = try_pass(kernel, &state, free, probes, pass, context, tally, failed_passes)? else {
        return Ok(state);
    };
    if tried.unstitched() <= state.unstitched() {
        return Ok(tried);
    }
    // Each try that sets patches back is made again without their edges too, while edges are left to grow. A
    // kernel failure of a try after the first is no failure of the pass: its first try stood as a whole.
    let patch_of = |face: usize| state.fused.faces[face].patch;
    let mut excluded = BTreeSet::new();
    let mut last = tried;
    let mut growing = free.len();
    for _ in 0..MORE_TRIES {
        *tally = before.clone();
        excluded.extend(set_back(&state, &last, patches));
        let (rest, rest_probes): (Vec<FreeEdge>, Vec<EdgeProbe>) = free
            .iter()
            .zip(probes)
            .filter(|(&(_, face), p)| {
                let reach = patches[patch_of(face)].reach;
                let meets_excluded =
                    p.hits.iter().flatten().any(|h| h.distance <= reach && excluded.contains(&patch_of(h.face)));
                !excluded.contains(&patch_of(face)) && !meets_excluded
            })
            .map(|(&edge, p)| (edge, p.clone()))
            .unzip();
        if rest.is_empty() || rest.len() == growing {
            break;
        }
        growing = rest.len();
        let Some(retried) = try_pass(kernel, &state, &rest, &rest_probes, pass, context, tally, &mut Vec::new())?
        else {
            break;
        };
        if retried.unstitched() <= state.unstitched() {
            return Ok(retried);
        }
        last = retried;
    }
    *tally = before;
    Ok(state)
}

/// How many times an undone later pass is made again without the patches it set back: each try costs a fuse of
/// the whole part, and a third try rescued joints on a real part where the second set another patch back.
const MORE_TRIES: usize = 2;

/// Pass `pass` over the free edges `free` (probed `probes`) of `state`, peeled and counted; None when it grew
/// nothing or the kernel failed it.
#[allow(clippy::too_many_arguments)]
fn try_pass<K: Kernel>(
    kernel: &mut K,
    state: &State,
    free: &[FreeEdge],
    probes: &[EdgeProbe],
    pass: Pass,
    (patches, solids, fuzzy): (&[PatchInfo], &[SolidMesh], f64),
    tally: &mut JointTally,
    failed_passes: &mut Vec<String>,
) -> Result<Option<State>, SidecarError> {
    let grown =
        run_pass(kernel, &state.fused, &state.keep, free, probes, patches, solids, fuzzy, pass, tally, failed_passes)?;
    let Some((fused, mut keep, more)) = grown else {
        return Ok(None);
    };
    let mut branches = state.branches.clone();
    branches.extend(more);
    peel_dangling(&fused, &mut keep, &mut branches, patches, solids);
    let (free, probes) = free_and_probed(kernel, &fused, &keep, patches, false)?;
    let (counted, open_by_patch) = classify_free(&fused, &free, &probes, patches, solids);
    Ok(Some(State { fused, keep, branches, free, probes, counted, open_by_patch }))
}

/// The patches a pass left with more unstitched length than it found them with, beyond their rim tolerance
/// (the same edges measured again on faces fused anew).
fn set_back(before: &State, after: &State, patches: &[PatchInfo]) -> BTreeSet<usize> {
    let (was, is) = (before.unstitched_by_patch(), after.unstitched_by_patch());
    (0..patches.len()).filter(|&p| is[p] > was[p] + patches[p].on_rim).collect()
}

/// The length of the edges of the kept faces that fail the kernel's check: such a face is left out when the file
/// is written (`output::shells::write_checked`), which opens its edges, so a pass that makes it opens them.
fn broken_length(fused: &Fused, keep: &[bool]) -> f64 {
    broken_faces(fused, keep).iter().map(|&(_, length)| length).sum()
}

/// The kept faces that fail the kernel's check, sorted, each with the length of its edges (an edge between two
/// of them counted once, for the first).
fn broken_faces(fused: &Fused, keep: &[bool]) -> Vec<(usize, f64)> {
    let broken: BTreeSet<usize> = fused.invalid.iter().copied().filter(|&f| keep[f]).collect();
    let mut out: Vec<(usize, f64)> = broken.into_iter().map(|f| (f, 0.0)).collect();
    for e in &fused.edges {
        if let Some(k) = out.iter().position(|(f, _)| e.faces.contains(f)) {
            out[k].1 += e.length;
        }
    }
    out
}

/// One pass of stitching, growing curved edges to the rim too; when the kernel fails it (a fuse that gives up),
/// the same pass growing straight edges only: a curved edge's strip is a ruled face (but along a cylinder's
/// axis or a cone's ruling), which the fuse gives up on more often, and a failed pass loses every joint in it.
/// A pass after the first only improves on what the first made: when the kernel fails that too, the stitching
/// and its joint tally stand as they were, and the failure is added to `failed_passes`. When it fails the first
/// pass both ways, that pass is made growing nothing (the trimmed patches fused again), the failure added to
/// `failed_passes`: the later passes, each standing only where it leaves no more open than it found, then make
/// what joints they can (the rims, and the partners with their T- and L-joints), where before one strip the
/// kernel gave up on left the whole part unstitched. A kernel that stops answering is an error.
#[allow(clippy::too_many_arguments)]
fn run_pass<K: Kernel>(
    kernel: &mut K,
    fused: &Fused,
    keep: &[bool],
    free: &[FreeEdge],
    probes: &[EdgeProbe],
    patches: &[PatchInfo],
    solids: &[SolidMesh],
    fuzzy: f64,
    pass: Pass,
    tally: &mut JointTally,
    failed_passes: &mut Vec<String>,
) -> Result<Option<Grown>, SidecarError> {
    let before = tally.clone();
    let mut curved = false;
    let mut outcome = grow(kernel, fused, keep, free, probes, patches, solids, fuzzy, pass, Some(&mut curved), tally);
    // Without a curved edge grown, the pass made again would be the same.
    if curved && matches!(&outcome, Err(e) if e.code().is_some()) {
        *tally = before.clone();
        outcome = grow(kernel, fused, keep, free, probes, patches, solids, fuzzy, pass, None, tally);
    }
    match outcome {
        Err(e) if e.code().is_some() && pass != Pass::Joints => {
            *tally = before;
            failed_passes.push(format!(
                "the {} pass: {e}; its joints are not made and the edges it grows stay as the earlier passes \
                 left them",
                pass.name()
            ));
            Ok(None)
        }
        Err(e) if e.code().is_some() && !free.is_empty() => {
            *tally = before;
            failed_passes.push(format!(
                "the joints pass: {e}; it is made growing nothing, and the later passes make what joints they can"
            ));
            grow(kernel, fused, keep, &[], &[], patches, solids, fuzzy, pass, None, tally)
        }
        other => other,
    }
}

fn peel_dangling(
    fused: &Fused,
    keep: &mut [bool],
    branches: &mut Vec<Branch>,
    patches: &[PatchInfo],
    solids: &[SolidMesh],
) {
    for b in peel::dangling(fused, keep, patches, solids) {
        keep[b.piece] = false;
        branches.push(b);
    }
}

/// The free edges of `fused` (pieces `keep`) and their probes, with their meetings with the kept pieces when
/// `meetings` (a joints pass looks for partners; the rims pass and the final count do not).
fn free_and_probed<K: Kernel>(
    kernel: &mut K,
    fused: &Fused,
    keep: &[bool],
    patches: &[PatchInfo],
    meetings: bool,
) -> Result<(Vec<FreeEdge>, Vec<EdgeProbe>), SidecarError> {
    let free = free_edges(fused, keep);
    let targets = if meetings { kept_faces(keep) } else { Vec::new() };
    let probes = probe(kernel, fused, &free, targets, patches, joint::SAMPLES)?;
    Ok((free, probes))
}

pub(super) fn kept_faces(keep: &[bool]) -> Vec<usize> {
    (0..keep.len()).filter(|&f| keep[f]).collect()
}

/// What the stitch stage hands on: the fused patches with the pieces kept, every branch dropped (by trimming
/// and by stitching), the joints, the free edges (None when stitching failed and the patches are written
/// unstitched) and the warnings, in that order: the passes the kernel failed and the open edges, or the failure;
/// then the joints not made.
pub struct Outcome {
    pub fused: Fused,
    pub keep: Vec<bool>,
    pub branches: Vec<Branch>,
    pub joints: Vec<JointReport>,
    pub free: Option<FreeEdges>,
    pub warnings: Vec<Warning>,
}

/// The stitch stage on the trimmed patches. A kernel op that fails outside the passes' fuses (which fall back,
/// `run_pass`) leaves the patches unstitched, with a warning; a kernel that stops answering is an error.
pub fn stitch_part<K: Kernel>(
    kernel: &mut K,
    trimmed: Trimmed,
    patches: &[PatchInfo],
    solids: &[SolidMesh],
    fuzzy: f64,
) -> Result<Outcome, SidecarError> {
    let Trimmed { fused, keep, mut branches } = trimmed;
    let mut warnings = Vec::new();
    let (fused, keep, joints, free) = match stitch(kernel, &fused, &keep, patches, solids, fuzzy) {
        Ok(s) => {
            branches.extend(s.branches);
            warnings.extend(s.failed_passes.iter().map(|failure| Warning {
                code: "stitch_pass_failed",
                message: format!("the kernel failed {failure}"),
                solid: None,
                faces: Vec::new(),
            }));
            warnings.extend(open_edges_warning(&s.free, &s.open_patches));
            warnings.extend(joint_warnings(&s.joints, &s.open_patches));
            (s.fused, s.keep, s.joints, Some(s.free))
        }
        Err(e) if e.code().is_some() => return Ok(unstitched(Trimmed { fused, keep, branches }, &e.to_string())),
        Err(e) => return Err(e),
    };
    Ok(Outcome { fused, keep, branches, joints, free, warnings })
}

/// The trimmed patches handed on as they are, with a `stitch_failed` warning saying `why`.
pub fn unstitched(trimmed: Trimmed, why: &str) -> Outcome {
    let Trimmed { fused, keep, branches } = trimmed;
    let warnings = vec![Warning {
        code: "stitch_failed",
        message: format!("the patches are written unstitched: {why}"),
        solid: None,
        faces: Vec::new(),
    }];
    Outcome { fused, keep, branches, joints: Vec::new(), free: None, warnings }
}

/// The joints not made, as warnings. Edges that met no patch are said only for patches still open after
/// stitching: another patch's strip (a T-joint onto it, a bridge it owns) may have closed them in the same pass,
/// and the report's joints keep what each pass found.
fn joint_warnings(joints: &[JointReport], open_patches: &BTreeSet<usize>) -> Vec<Warning> {
    joints
        .iter()
        .filter(|j| j.status != "extended")
        .filter(|j| j.status != "no_partner" || j.patches.iter().any(|id| open_patches.contains(&(id - 1))))
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
            crate::model::warning::patch_list(open_patches)
        ),
        solid: None,
        faces: Vec::new(),
    })
}
