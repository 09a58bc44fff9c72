//! One pass of stitching: per free edge the strip it grows (a joint to its partner, or to the rim), the quads
//! bridging thickness steps and the notches at corners, all made in one kernel call; then each patch gathered
//! with its strips and everything fused again and trimmed.

use std::collections::{BTreeMap, BTreeSet};

use super::bridge;
use super::edges::{freeform_curve, open, open_on_level, straight, to_rim, RimGrowth};
use super::joint::{self, Verdict};
use super::{kept_faces, probe, trim, JointReport, PatchInfo};
use crate::geom::inside::SolidMesh;
use crate::kernel::protocol::{CornerRequest, Extended, GatherPart, Gathered, MadeStrip, Request, StripRequest};
use crate::kernel::{FuseKind, Kernel, SidecarError};
use crate::model::shapes::{EdgeProbe, Fused};
use crate::trim::Branch;
use glam::DVec3;

/// What a pass makes: the patches fused again, the pieces kept and the branches dropped.
pub(super) type Grown = (Fused, Vec<bool>, Vec<Branch>);

/// Which free edges a pass grows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Pass {
    /// Every free edge: joints to partner patches, and edges short of the rim.
    Joints,
    /// The free edges left by the joints (an L-joint's overshoot that stayed joined to its patch past a wall's
    /// end, for one), grown to the rim when it is within reach.
    Rims,
    /// The open edges still left: grown to a partner patch only. Pieces peeled off after a joints pass leave
    /// edges whose partner is now in reach (a wall's foot over a floor whose overshoot went).
    Partners,
}

impl Pass {
    /// Its name in reports.
    pub(super) fn name(self) -> &'static str {
        match self {
            Pass::Joints => "joints",
            Pass::Rims => "rims",
            Pass::Partners => "partners",
        }
    }
}

/// One pass of `stitch` over the free edges `free` of `fused` and their probes (with meetings for a joints
/// pass): the result fused again, its kept pieces and the branches dropped; None when a rims pass finds
/// nothing to grow. `curved_rims`: Some when curved edges grow to the rim too (see `edges::to_rim`), set when
/// one does.
#[allow(clippy::too_many_arguments)]
pub(super) fn grow<K: Kernel>(
    kernel: &mut K,
    fused: &Fused,
    keep: &[bool],
    free: &[(usize, usize)],
    probes: &[EdgeProbe],
    patches: &[PatchInfo],
    solids: &[SolidMesh],
    fuzzy: f64,
    pass: Pass,
    mut curved_rims: Option<&mut bool>,
    tally: &mut JointTally,
) -> Result<Option<Grown>, SidecarError> {
    let thickness: Vec<f64> = patches.iter().map(|p| p.thickness).collect();
    let patch_of: Vec<usize> = fused.faces.iter().map(|f| f.patch).collect();

    let decide = |edge: usize, face: usize, p: &EdgeProbe| match pass {
        Pass::Joints | Pass::Partners => {
            let open = open(fused, face, p, patches, solids);
            let info = &patches[patch_of[face]];
            let through = |k, length| {
                let step = joint::PROBE_STEP * info.thickness;
                joint::through_material(p, k, length, step, info.to_mid, |q| solids[info.solid].contains(q))
            };
            // A curved edge of a freeform patch keeps its neighbours' lengths at the rim (`freeform_curve`).
            let stubs = !freeform_curve(info, &fused.edges[edge]);
            joint::decide(patch_of[face], open, p, &patch_of, &thickness, info.reach, stubs, through)
        }
        // Only growth to the rim; an edge that found no partner before is not counted again.
        Pass::Rims => Verdict::Rim,
    };
    let mut verdicts: Vec<Verdict> = free.iter().zip(probes).map(|(&(edge, face), p)| decide(edge, face, p)).collect();
    let dense = dense_probes(kernel, fused, keep, free, &mut verdicts, patches, &decide)?;

    // Per free edge: the strip it grows with its joint key, if any; and the open edges the step search sees.
    let mut grows: Vec<Option<Planned>> = Vec::new();
    let mut open_edges: Vec<OpenEdge> = Vec::new();
    for (k, ((&(edge, face), p), verdict)) in free.iter().zip(probes).zip(verdicts).enumerate() {
        let p = dense[k].as_ref().unwrap_or(p);
        let patch = patch_of[face];
        let length = fused.edges[edge].length;
        // The edge as the step search sees it when open with no partner; each verdict below adjusts it.
        let loose = OpenEdge {
            free: k,
            edge,
            face,
            patch,
            probe: p,
            length,
            nearest: f64::INFINITY,
            open: true,
            level: false,
            to_rim: false,
        };
        let grow = match verdict {
            Verdict::Rim | Verdict::Unresolved if pass == Pass::Partners => None,
            verdict @ (Verdict::Rim | Verdict::Unresolved) => {
                let open = verdict == Verdict::Unresolved;
                let growth = RimGrowth { curved: curved_rims.is_some(), lips: pass == Pass::Joints };
                let lengths = to_rim(fused, edge, face, p, patches, solids, growth);
                // The edge may still be one level of a step, which a bridge between the two levels joins instead:
                // short of the rim, the thicker level whose boundary slopes down to the thinner one (a chamfered
                // pad) or the thinner one running on as a lip past the thicker level's edge; on the rim, the
                // thicker level, the thinner level's edge lying on the boundary past it (its outside reads as out
                // of the material).
                if pass == Pass::Joints {
                    let level = lengths.is_none() && !open && open_on_level(fused, face, p, patches, solids);
                    open_edges.push(OpenEdge { open, level, to_rim: lengths.is_some(), ..loose });
                }
                lengths.map(|lengths| {
                    if let Some(grew) = curved_rims.as_deref_mut() {
                        *grew |= !straight(&fused.edges[edge]);
                    }
                    (
                        patch,
                        StripRequest { edge, face, lengths, onto_face: false, along: None },
                        (vec![patch + 1], joint::JointKind::Rim.name(), "extended"),
                        p,
                    )
                })
            }
            Verdict::Extend(x) => {
                let nearest = x.distance;
                open_edges.push(OpenEdge { nearest, ..loose });
                let mut ids = vec![patch + 1, x.partner + 1];
                ids.sort_unstable();
                Some((
                    patch,
                    StripRequest {
                        edge,
                        face,
                        lengths: x.lengths,
                        onto_face: x.kind == joint::JointKind::T,
                        along: None,
                    },
                    (ids, x.kind.name(), "extended"),
                    p,
                ))
            }
        };
        grows.push(grow);
    }
    let Steps { quads: steps, corners: step_corners, swept, bridged } =
        step_quads(fused, &open_edges, patches, solids, fuzzy, tally);
    let planned: Vec<Planned> =
        grows.into_iter().enumerate().filter(|(k, _)| !bridged.contains(k)).filter_map(|(_, g)| g).collect();
    if pass != Pass::Joints && planned.is_empty() && steps.is_empty() && swept.is_empty() {
        return Ok(None);
    }
    // (patch, index among the faces of the extension's handle) of each made strip and corner.
    let mut strips: Vec<(usize, usize)> = Vec::new();
    let mut extended_handle = None;
    if !planned.is_empty() || !steps.is_empty() || !swept.is_empty() {
        let mut corners = corners(&planned, fuzzy);
        corners.extend(step_corners);
        let extended: Extended = kernel.call(&Request::ExtendEdges {
            handle: fused.handle,
            strips: planned.iter().map(|(_, s, _, _)| s).chain(swept.iter().map(|(_, s, _, _)| s)).cloned().collect(),
            corners: corners.iter().map(|(_, c)| c).chain(steps.iter().map(|(_, c, _, _)| c)).cloned().collect(),
        })?;
        let planned_count = planned.len();
        for ((patch, request, key, _), made) in planned.into_iter().zip(&extended.strips) {
            let length = fused.edges[request.edge].length;
            // A pass whose fuse fails takes its tally back (`run_pass`).
            if made.area.is_some() {
                strips.push((patch, strips.len()));
                tally.add(key, length);
            } else {
                tally.add((key.0, key.1, "kernel_failed"), length);
            }
        }
        let mut bridges = |made: &[MadeStrip], bridges: Vec<(usize, JointKey, [f64; 2])>| {
            let mut kept = Vec::new();
            for ((patch, key, lengths), made) in bridges.into_iter().zip(made) {
                let status = if made.area.is_some() { key.2 } else { "kernel_failed" };
                for length in lengths {
                    tally.add((key.0.clone(), key.1, status), length);
                }
                kept.extend(made.area.is_some().then_some(patch));
            }
            kept
        };
        let swept = swept.into_iter().map(|(patch, _, key, lengths)| (patch, key, lengths)).collect();
        for patch in bridges(&extended.strips[planned_count..], swept) {
            strips.push((patch, strips.len()));
        }
        for (&(patch, _), made) in corners.iter().zip(&extended.corners) {
            if made.area.is_some() {
                strips.push((patch, strips.len()));
            }
        }
        let steps = steps.into_iter().map(|(patch, _, key, lengths)| (patch, key, lengths)).collect();
        for patch in bridges(&extended.corners[corners.len()..], steps) {
            strips.push((patch, strips.len()));
        }
        extended_handle = Some(extended.handle);
    }

    // One argument per patch: its kept pieces and its strips (each list ascending, as found).
    let mut pieces_of: Vec<Vec<usize>> = vec![Vec::new(); patches.len()];
    for f in kept_faces(keep) {
        pieces_of[patch_of[f]].push(f);
    }
    let mut strips_of: Vec<Vec<usize>> = vec![Vec::new(); patches.len()];
    for &(p, j) in &strips {
        strips_of[p].push(j);
    }
    let mut order: Vec<usize> = Vec::new();
    let mut handles = Vec::new();
    // A patch without strips keeps its pieces as `fused` made them: settled (`FuseKind::Again`).
    let mut settled = Vec::new();
    for (k, (pieces, own)) in pieces_of.into_iter().zip(strips_of).enumerate() {
        let mut parts = Vec::new();
        // Only a patch with strips has faces to merge.
        let unify = (!own.is_empty()).then_some(fuzzy);
        if own.is_empty() && !pieces.is_empty() {
            settled.push(handles.len());
        }
        if !pieces.is_empty() {
            parts.push(GatherPart { handle: fused.handle, faces: pieces });
        }
        if let (Some(handle), false) = (extended_handle, own.is_empty()) {
            parts.push(GatherPart { handle, faces: own });
        }
        if parts.is_empty() {
            continue;
        }
        let gathered: Gathered = kernel.call(&Request::Gather { parts, unify })?;
        order.push(k);
        handles.push(gathered.handle);
    }
    let bodies: Vec<usize> = order.iter().map(|&k| patches[k].body).collect();
    let mut again = kernel.fuse(handles, &bodies, fuzzy, FuseKind::Again { settled })?;
    for face in &mut again.faces {
        face.patch = order[face.patch];
    }
    let (keep, branches) = trim(&again, patches, solids);
    Ok(Some((again, keep, branches)))
}

/// A free edge for the step search: its index among the free edges, patch, probe, length, how far away the
/// partner its rays found is (infinite for none), and whether it is open (else on the rim).
#[derive(Clone, Copy)]
struct OpenEdge<'a> {
    free: usize,
    /// The edge and the face it bounds, in `fused`.
    edge: usize,
    face: usize,
    patch: usize,
    probe: &'a EdgeProbe,
    length: f64,
    nearest: f64,
    open: bool,
    /// Not open, but open once a point on a face parallel to the patch counts as in the material
    /// (`edges::open_on_level`): the step search takes it as open.
    level: bool,
    /// It grows a strip to the rim unless a bridge takes it: not an edge without a partner.
    to_rim: bool,
}

/// What bridges the open edges of a pass across thickness steps and gaps (`step_quads`).
struct Steps {
    /// Quads and bands between lines and arcs, each owned by a patch.
    quads: Vec<StepQuad>,
    /// The quads filling the notches where two step bridges of one patch meet at a corner, by patch.
    corners: Vec<(usize, CornerRequest)>,
    /// Edges swept straight onto the other level of a step (`bridge::swept_steps`).
    swept: Vec<SweptStrip>,
    /// The free edges (indices) bridged.
    bridged: BTreeSet<usize>,
}

/// The quads bridging open edges across thickness steps (`bridge::step_bridges`) and across gaps in a tube's own
/// surface (`bridge::ruling_gaps`), each owned by its `owner` edge's patch,
/// with its joint key and the lengths of both edges; the quads filling the notches where two step bridges of
/// one patch meet at a corner (`bridge::bridge_corners`, those whose middle lies in the material), by patch;
/// the edges left swept onto the other level of a step whose two edges are one curve (`bridge::swept_steps`);
/// and the free edges (indices) bridged. The edges that found no partner and no bridge are tallied as having no
/// partner.
fn step_quads(
    fused: &Fused,
    open: &[OpenEdge],
    patches: &[PatchInfo],
    solids: &[SolidMesh],
    fuzzy: f64,
    tally: &mut JointTally,
) -> Steps {
    let same_point = same_point(fuzzy);
    let edges: Vec<bridge::LooseEdge> = open
        .iter()
        .map(|e| {
            let p = e.probe;
            let mid = p.points.len() / 2;
            bridge::LooseEdge {
                patch: e.patch,
                wall: patches[e.patch].wall,
                thickness: patches[e.patch].thickness,
                nearest: e.nearest,
                reach: patches[e.patch].reach,
                freeform: patches[e.patch].freeform,
                open: e.open || e.level,
                points: p.points.clone(),
                normal: p.normals[mid],
                outwards: p.outward.clone(),
                face: [fused.faces[e.face].point, fused.faces[e.face].normal.normalize_or_zero()],
            }
        })
        .collect();
    let mut bridged = vec![false; open.len()];
    let mut out = Vec::new();
    let steps = bridge::step_bridges(&edges, same_point);
    let step_corners: Vec<(usize, CornerRequest)> = bridge::bridge_corners(&steps, &edges, same_point)
        .into_iter()
        .filter(|&(owner, quad, _)| {
            let middle = quad.iter().copied().sum::<DVec3>() / 4.0;
            solids[patches[edges[owner].patch].solid].contains(middle)
        })
        .map(|(owner, points, normal)| (edges[owner].patch, CornerRequest { points, normal, axis: None }))
        .collect();
    for bridge::StepBridge { owner, other, quad, normal, axis } in steps {
        (bridged[owner], bridged[other]) = (true, true);
        let mut ids = vec![edges[owner].patch + 1, edges[other].patch + 1];
        ids.sort_unstable();
        let request = CornerRequest { points: quad, normal, axis };
        let lengths = [open[owner].length, open[other].length];
        out.push((edges[owner].patch, request, (ids, joint::JointKind::Step.name(), "extended"), lengths));
    }
    // In the partners pass too: a gap's band stops where the skins beside it do, and the foot grown from their
    // edges down into a floor leaves a notch under the band between the foot's ends, rulings of the same tube.
    for bridge::StepBridge { owner, other, quad, normal, axis } in bridge::ruling_gaps(&edges) {
        if bridged[owner] || bridged[other] {
            continue;
        }
        // The band lies in the material where the edges' outsides do, unless the gap holds a slot: its middle.
        let inside = axis.is_some_and(|[origin, direction]| {
            solids[patches[edges[owner].patch].solid].contains(bridge::band_middle(&quad, origin, direction))
        });
        if !inside {
            continue;
        }
        (bridged[owner], bridged[other]) = (true, true);
        let patch = edges[owner].patch;
        let request = CornerRequest { points: quad, normal, axis };
        let lengths = [open[owner].length, open[other].length];
        out.push((patch, request, (vec![patch + 1, patch + 1], joint::JointKind::Step.name(), "extended"), lengths));
    }
    let mut swept = Vec::new();
    for bridge::SweptStep { owner, other, along, run } in bridge::swept_steps(&edges, &bridged) {
        (bridged[owner], bridged[other]) = (true, true);
        let (e, patch) = (&open[owner], edges[owner].patch);
        let mut ids = vec![patch + 1, edges[other].patch + 1];
        ids.sort_unstable();
        let lengths = vec![run; e.probe.points.len()];
        let request = StripRequest { edge: e.edge, face: e.face, lengths, onto_face: false, along: Some(along) };
        let key = (ids, joint::JointKind::Step.name(), "extended");
        swept.push((patch, request, key, [e.length, open[other].length]));
    }
    for (e, _) in open.iter().zip(&bridged).filter(|(e, &b)| !b && e.open && !e.to_rim && e.nearest.is_infinite()) {
        tally.add((vec![e.patch + 1], "none", "no_partner"), e.length);
    }
    let bridged = open.iter().zip(&bridged).filter(|(_, &b)| b).map(|(e, _)| e.free).collect();
    Steps { quads: out, corners: step_corners, swept, bridged }
}

/// Strips of two edges meeting at a convex corner of a face leave a notch between them (a rib's bottom
/// and end both growing into the walls they meet): a quad v, a, c, b fills it, where a and b are the strips'
/// far corners over v and c = a + b - v. Edges continuing each other (outward directions within 10 degrees)
/// need none; at a reflex corner the strips overlap instead.
/// Two strip ends are at one corner within this many fuzzy tolerances (the fuse merges points that close), and
/// never less than this floor (a fuzzy value of 0).
const CORNER_SAME_POINT_FUZZY: f64 = 10.0;
const CORNER_SAME_POINT_MIN: f64 = 1e-9;
/// Edges whose outward directions are within this angle (degrees) continue each other: no notch between them.
const CORNER_CONTINUING_DEG: f64 = 10.0;

/// Per free edge, its probe made again with [`joint::DENSE_SAMPLES`] when it is straight and its partner ends
/// part way along it ([`joint::Extension::rim_ends`]), all such edges in one kernel call, its verdict in
/// `verdicts` replaced by the dense probe's; None for the others, and when the dense probe does not tell the same
/// joint (partner and kind) as the first. `decide(edge, face, probe)` is the pass's verdict on an edge.
fn dense_probes<K: Kernel>(
    kernel: &mut K,
    fused: &Fused,
    keep: &[bool],
    free: &[(usize, usize)],
    verdicts: &mut [Verdict],
    patches: &[PatchInfo],
    decide: &impl Fn(usize, usize, &EdgeProbe) -> Verdict,
) -> Result<Vec<Option<EdgeProbe>>, SidecarError> {
    let mut dense = vec![None; free.len()];
    let flagged: Vec<usize> = (0..free.len())
        .filter(|&k| matches!(&verdicts[k], Verdict::Extend(x) if x.rim_ends && straight(&fused.edges[free[k].0])))
        .collect();
    if flagged.is_empty() {
        return Ok(dense);
    }
    let edges: Vec<(usize, usize)> = flagged.iter().map(|&k| free[k]).collect();
    let again = probe(kernel, fused, &edges, kept_faces(keep), patches, joint::DENSE_SAMPLES)?;
    for (k, p) in flagged.into_iter().zip(again) {
        let (edge, face) = free[k];
        let (Verdict::Extend(first), Verdict::Extend(x)) = (&verdicts[k], decide(edge, face, &p)) else { continue };
        if x.partner == first.partner && x.kind == first.kind {
            verdicts[k] = Verdict::Extend(x);
            dense[k] = Some(p);
        }
    }
    Ok(dense)
}

/// How close two ends must be to be one corner, for a fuse of fuzzy value `fuzzy`.
fn same_point(fuzzy: f64) -> f64 {
    (fuzzy * CORNER_SAME_POINT_FUZZY).max(CORNER_SAME_POINT_MIN)
}

fn corners(planned: &[Planned], fuzzy: f64) -> Vec<(usize, CornerRequest)> {
    let same_point = same_point(fuzzy);
    let continuing = CORNER_CONTINUING_DEG.to_radians().cos();
    // (point, direction along the edge into that end, outward, length, normal) at both ends of a strip.
    let ends = |s: &StripRequest, p: &EdgeProbe| {
        let n = p.points.len();
        [
            (p.points[0], (p.points[0] - p.points[1]).normalize_or_zero(), p.outward[0], s.lengths[0], p.normals[0]),
            (
                p.points[n - 1],
                (p.points[n - 1] - p.points[n - 2]).normalize_or_zero(),
                p.outward[n - 1],
                s.lengths[n - 1],
                p.normals[n - 1],
            ),
        ]
    };
    let mut out = Vec::new();
    for (i, (patch, a, _, pa)) in planned.iter().enumerate() {
        for (b, pb) in planned[i + 1..].iter().filter(|(_, b, _, _)| b.face == a.face).map(|(_, b, _, p)| (b, p)) {
            for &(va, along_a, out_a, len_a, normal) in &ends(a, pa) {
                for &(vb, along_b, out_b, len_b, _) in &ends(b, pb) {
                    let convex = out_b.dot(along_a) > 0.0 && out_a.dot(along_b) > 0.0;
                    if va.distance(vb) > same_point || out_a.dot(out_b) > continuing || !convex {
                        continue;
                    }
                    let far_a = va + out_a * len_a;
                    let far_b = va + out_b * len_b;
                    let points = [va, far_a, far_a + far_b - va, far_b];
                    out.push((*patch, CornerRequest { points, normal, axis: None }));
                }
            }
        }
    }
    out
}

/// Patch ids (sorted), kind, status.
type JointKey = (Vec<usize>, &'static str, &'static str);

/// A strip to grow: its patch, the request, its joint key and the probe of its edge.
type Planned<'a> = (usize, StripRequest, JointKey, &'a EdgeProbe);

/// A step bridge: the patch owning it, the quad, its joint key and the lengths of its two edges.
type StepQuad = (usize, CornerRequest, JointKey, [f64; 2]);

/// An edge swept onto the other level of a step: its patch, the request, the joint key and both edges' lengths.
type SweptStrip = (usize, StripRequest, JointKey, [f64; 2]);

/// Edges and length per joint key, in key order (deterministic).
#[derive(Default, Clone)]
pub(super) struct JointTally(BTreeMap<JointKey, (usize, f64)>);

impl JointTally {
    pub(super) fn add(&mut self, key: JointKey, length: f64) {
        let entry = self.0.entry(key).or_default();
        entry.0 += 1;
        entry.1 += length;
    }

    pub(super) fn reports(&self) -> Vec<JointReport> {
        self.0
            .iter()
            .map(|((patches, kind, status), &(edges, length))| JointReport {
                patches: patches.clone(),
                kind,
                status,
                edges,
                length,
            })
            .collect()
    }
}
