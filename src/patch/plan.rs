//! The patch plan (Sheen et al. 5.2): which faces make each mid-patch and where they go.
//!
//! A patch is made from the reference side of a pair group (the side with the larger area, so fewer patches
//! need extending): offset by half the thickness into the material, or for a draft pair projected onto the
//! exact bisector plane of the two faces. Reference faces whose own pairs have different thicknesses (a
//! thickness step) get separate patches, each at its own mid-plane.

use glam::DVec3;
use serde::Serialize;

use crate::model::face_graph::{EdgeId, FaceGraph, FaceId, Surface};
use crate::model::params::Position;
use crate::model::shapes::Placement;
use crate::model::tolerance::{PARALLEL_AXES, SAME_AXIS, SAME_THICKNESS, TAPER_SPREAD};
use crate::pairing::{Pair, PairKind, Pairing, Side, Thickness};
use crate::patch::sides::top_sides;

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PatchPlan {
    /// Index of the pair group the patch comes from.
    pub group: usize,
    pub kind: PairKind,
    /// Reference faces, sorted.
    pub faces: Vec<FaceId>,
    #[serde(skip)]
    pub placement: Placement,
    pub thickness: Thickness,
    /// Per reference face (same order), the faces it pairs with: the patch is clipped to their footprint.
    #[serde(skip)]
    pub partners: Vec<Vec<FaceId>>,
    /// Per reference face (same order), the partners of its other thickness levels: their footprint goes to
    /// the patches of those levels.
    #[serde(skip)]
    pub exclude: Vec<Vec<FaceId>>,
    /// The clip keeps only what lies over the partners (a face's minor thickness level; see `shares`).
    #[serde(skip)]
    pub strict: bool,
    /// The wall tapers: each point of the reference faces goes halfway to its partners, not all by the offset
    /// (which stays the mean, where no partner lies across). See `follows_mid_wall`.
    #[serde(skip)]
    pub mid_wall: bool,
    /// From the patch to the middle of its wall along the patch normal (0 unless placed on a skin).
    #[serde(skip)]
    pub to_mid: f64,
    /// The reference faces lie on the wall's bottom side: the patch is turned over so its normal points out
    /// of the top side like its neighbours'.
    #[serde(skip)]
    pub reverse: bool,
    /// Edges of suppressed features on the reference faces: the inner loops holding them are filled.
    #[serde(skip)]
    pub fill: Vec<EdgeId>,
    /// How many inner loops of the reference faces that fills.
    #[serde(skip)]
    pub fill_loops: usize,
}

impl PatchPlan {
    /// Keeps the edges of `fill` (sorted) that lie on inner loops of the reference faces.
    fn with_fill(mut self, graph: &FaceGraph, fill: &[EdgeId]) -> PatchPlan {
        for &f in &self.faces {
            for lp in graph.faces[f].loops.iter().skip(1) {
                let on: Vec<EdgeId> = lp.iter().copied().filter(|e| fill.binary_search(e).is_ok()).collect();
                if !on.is_empty() {
                    self.fill.extend(on);
                    self.fill_loops += 1;
                }
            }
        }
        self.fill.sort_unstable();
        self.fill.dedup();
        self
    }
}

/// The other face of each pair of `face`, sorted.
fn partners_of(face: FaceId, pairs: &[&Pair]) -> Vec<FaceId> {
    let mut out: Vec<FaceId> = pairs.iter().map(|p| p.other(face)).collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// Each face of `side` with the pairs of the group it belongs to, by face id.
fn pairs_per_face<'a>(side: &[FaceId], pairs: &[usize], pairing: &'a Pairing) -> Vec<(FaceId, Vec<&'a Pair>)> {
    let mut out: Vec<(FaceId, Vec<&Pair>)> = side
        .iter()
        .map(|&f| (f, pairs.iter().map(|&i| &pairing.pairs[i]).filter(|p| p.faces.contains(&f)).collect()))
        .collect();
    out.sort_by_key(|(f, _)| *f);
    out
}

/// Every face of the side sits at one thickness from its partners (a thickness step lies between faces).
fn uniform(per_face: &[(FaceId, Vec<&Pair>)]) -> bool {
    per_face.iter().all(|(_, pairs)| {
        let t = combined(pairs);
        t.max - t.min <= SAME_THICKNESS * t.mean
    })
}

/// The faces of a side sit at distinct thicknesses from their partners (a step between pairs), not only at
/// a thickness that varies within a pair (a tapered or freeform wall).
fn levels_differ(per_face: &[(FaceId, Vec<&Pair>)]) -> bool {
    let means = per_face.iter().flat_map(|(_, pairs)| pairs.iter().map(|p| p.thickness.mean));
    let (low, high) = means.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), m| (l.min(m), h.max(m)));
    high - low > SAME_THICKNESS * high
}

/// Why a group's patch may not lie mid-way everywhere.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum PlanNote {
    /// Both sides span a thickness step: offset at the mean.
    ThicknessStep { group: usize, faces: Vec<FaceId>, thickness: Thickness },
    /// The wall's thickness varies within its pairs (a taper): offset at the mean, or (`mid_wall`) following
    /// the local mid-points.
    ThicknessVaries { group: usize, faces: Vec<FaceId>, thickness: Thickness, mid_wall: bool },
    /// Neither side is mostly covered by its partners: the patch overshoots the wall.
    PartialOverlap { group: usize, faces: Vec<FaceId>, coverage: f64 },
}

/// Each reference face with the pairs it belongs to.
type FacePartners<'a> = Vec<(FaceId, Vec<&'a Pair>)>;

/// The larger side is kept as the reference while at least this share of it faces its partners.
const MIN_COVERAGE: f64 = 0.5;

/// The side to offset. The paper offsets the larger face (fewer extensions later), which assumes it is mostly
/// covered by its partners: its excess is then the overshoot trimmed at joints. When the overlap covers less
/// than half of it, the better covered side is used instead; and a side whose faces each sit at one thickness
/// is preferred to one spanning a thickness step.
fn choose_reference<'a>(
    graph: &FaceGraph,
    group: &crate::pairing::PairGroup,
    pairing: &'a Pairing,
) -> (Side, FacePartners<'a>, Option<PlanNote>) {
    let area = |side: usize| group.sides[side].iter().map(|&f| graph.faces[f].area).sum::<f64>();
    let coverage = |side: usize| (group.overlap_area / area(side)).min(1.0);
    let larger = group.reference as usize;
    let order = if coverage(larger) >= MIN_COVERAGE || coverage(larger) >= coverage(1 - larger) {
        [larger, 1 - larger]
    } else {
        [1 - larger, larger]
    };
    let candidates = order.map(|side| pairs_per_face(&group.sides[side], &group.pairs, pairing));
    let chosen = if uniform(&candidates[0]) || !uniform(&candidates[1]) { 0 } else { 1 };
    let side = order[chosen];
    let note = if !uniform(&candidates[chosen]) {
        let (id, faces, thickness) = (group.id, group.sides[side].clone(), group.thickness);
        Some(if levels_differ(&candidates[chosen]) {
            PlanNote::ThicknessStep { group: id, faces, thickness }
        } else {
            // Whether the patch follows the mid-points is known once it is planned (plan_patches).
            PlanNote::ThicknessVaries { group: id, faces, thickness, mid_wall: false }
        })
    } else if coverage(side) < MIN_COVERAGE {
        Some(PlanNote::PartialOverlap { group: group.id, faces: group.sides[side].clone(), coverage: coverage(side) })
    } else {
        None
    };
    let [first, second] = candidates;
    let side = if side == 0 { Side::A } else { Side::B };
    (side, if chosen == 0 { first } else { second }, note)
}

/// The patches of one solid; `fill` (sorted) holds the edges of suppressed features, whose loops in the
/// reference faces are filled.
pub fn plan_patches(
    graph: &FaceGraph,
    pairing: &Pairing,
    position: Position,
    fill: &[EdgeId],
) -> (Vec<PatchPlan>, Vec<PlanNote>) {
    let mut plans = Vec::new();
    let mut notes = Vec::new();
    let top = top_sides(graph, pairing);
    for group in &pairing.groups {
        let (side, per_face, mut warning) = choose_reference(graph, group, pairing);
        let on_top = top[group.id] == side;
        // A group is named by the kind of most overlap: a draft group may hold faces whose main pair is not two
        // planes (a corrugated freeform band beside its flat ends). Only the planar ones go onto a bisector;
        // the others are offset like any curved pair.
        let (draft, offset): (Vec<_>, Vec<_>) = per_face
            .iter()
            .partition(|(face, pairs)| group.kind == PairKind::Draft && draft_planar(graph, *face, pairs));
        for (face, pairs) in draft {
            plans.push(draft_plan(graph, group.id, *face, pairs, position, on_top).with_fill(graph, fill));
        }
        // Cluster the reference faces' shares by their own mean thickness (a face once per patch).
        let mut clustered: Vec<PatchPlan> = Vec::new();
        for share in offset.into_iter().flat_map(|(face, pairs)| shares(graph, *face, pairs)) {
            let t = combined(&share.pairs);
            let partners = partners_of(share.face, &share.pairs);
            let kind = offset_kind(group.kind, &share.pairs);
            let mid_wall = follows_mid_wall(kind, t, position)
                || (kind == PairKind::Freeform && position == Position::Mid && skins_apart(graph, &share));
            let same = |p: &&mut PatchPlan| {
                (p.thickness.mean - t.mean).abs() <= SAME_THICKNESS * p.thickness.mean
                    && p.strict == share.minor
                    && p.mid_wall == mid_wall
                    && !p.faces.contains(&share.face)
            };
            match clustered.iter_mut().find(same) {
                Some(plan) => {
                    let ct = plan.thickness;
                    plan.thickness = Thickness { mean: ct.mean, min: ct.min.min(t.min), max: ct.max.max(t.max) };
                    plan.faces.push(share.face);
                    plan.partners.push(partners);
                    plan.exclude.push(share.exclude);
                }
                None => clustered.push(PatchPlan {
                    group: group.id,
                    kind,
                    faces: vec![share.face],
                    placement: Placement::Offset(position.offset(t.mean, on_top)),
                    thickness: t,
                    partners: vec![partners],
                    exclude: vec![share.exclude],
                    strict: share.minor,
                    mid_wall,
                    to_mid: position.to_mid(t.mean),
                    reverse: !on_top,
                    fill: Vec::new(),
                    fill_loops: 0,
                }),
            }
        }
        if let Some(PlanNote::ThicknessVaries { mid_wall, .. }) = &mut warning {
            *mid_wall = clustered.iter().any(|plan| plan.mid_wall);
        }
        notes.extend(warning);
        plans.extend(clustered.into_iter().map(|plan| plan.with_fill(graph, fill)));
    }
    (plans, notes)
}

/// Whether a share's face is a cylinder whose partners are all cylinders on one axis parallel to its own, apart
/// from it (a bend or a rounded corner whose inner and outer arcs a CAD drew on centres a little apart, paired
/// by rays), or a sphere whose partners are all spheres on one centre apart from its own (the dome capping such
/// a vault). Its wall's mid-surface is then the cylinder (sphere) on the mean axis (centre) with the mean radius:
/// at each tangent line with a flat beside a bend, it runs into that flat's mid-plane, whatever the flat's
/// thickness (each skin's tangent point lies on the same normal), where an offset of one skin at the mean
/// thickness stands a hair off both flats, and the stitching's rays along the common tangent pass the other
/// patch by; a vault and its dome meet along their common circle as their skins do.
fn skins_apart(graph: &FaceGraph, share: &Share) -> bool {
    let centre = |face: FaceId| match graph.faces[face].surface {
        Surface::Cylinder { origin, axis, .. } => Some((origin, Some(axis))),
        Surface::Sphere { center, .. } => Some((center, None)),
        _ => None,
    };
    let Some((origin, axis)) = centre(share.face) else { return false };
    // The offset of a partner's axis or centre from the face's own, across the axis.
    let apart = |face: FaceId| {
        let (o, a) = centre(face)?;
        let across = |v: DVec3| axis.map_or(v, |axis| v.reject_from_normalized(axis));
        match (axis, a) {
            (Some(axis), Some(a)) if a.cross(axis).length() <= PARALLEL_AXES => Some(across(o - origin)),
            (None, None) => Some(o - origin),
            _ => None,
        }
    };
    let Some(offsets) = share.pairs.iter().map(|p| apart(p.other(share.face))).collect::<Option<Vec<DVec3>>>() else {
        return false;
    };
    let Some(&first) = offsets.first() else { return false };
    first.length() > 0.0 && offsets.iter().all(|o| o.distance(first) <= SAME_AXIS * (1.0 + first.length()))
}

/// Whether a patch follows the local mid-points of its wall rather than an offset at the mean thickness: at
/// mid-wall, for a freeform wall that tapers past `TAPER_SPREAD` (a blade, a cast web). Planar tapers go onto a
/// bisector plane (`draft_plan`); on a skin the patch is the skin itself.
fn follows_mid_wall(kind: PairKind, t: Thickness, position: Position) -> bool {
    kind == PairKind::Freeform && position == Position::Mid && t.max - t.min > TAPER_SPREAD * t.mean
}

/// `pairs` in levels of thickness: sorted by mean thickness, each within `SAME_THICKNESS` of the one before.
fn levels<'a>(pairs: &[&'a Pair]) -> Vec<Vec<&'a Pair>> {
    let mut sorted = pairs.to_vec();
    sorted.sort_by(|a, b| a.thickness.mean.total_cmp(&b.thickness.mean));
    let mut out: Vec<Vec<&Pair>> = Vec::new();
    let mut last = f64::NEG_INFINITY;
    for p in sorted {
        let t = p.thickness.mean;
        match out.last_mut() {
            Some(level) if t - last <= SAME_THICKNESS * t => level.push(p),
            _ => out.push(vec![p]),
        }
        last = t;
    }
    out
}

fn overlap(pairs: &[&Pair]) -> f64 {
    pairs.iter().map(|p| p.overlap_area).sum()
}

/// The thickness a face's patch is offset at: the overlap-weighted mean of its pairs when they agree within
/// `SAME_THICKNESS`; across a thickness step, the mean of the level with the most overlap (a mean of two
/// levels would be mid-way on neither). The range covers all its pairs.
fn combined(pairs: &[&Pair]) -> Thickness {
    let min = pairs.iter().map(|p| p.thickness.min).fold(f64::INFINITY, f64::min);
    let max = pairs.iter().map(|p| p.thickness.max).fold(f64::NEG_INFINITY, f64::max);
    let level = levels(pairs)
        .into_iter()
        .max_by(|a, b| overlap(a).total_cmp(&overlap(b)))
        .expect("a reference face belongs to at least one pair");
    let mean = level.iter().map(|p| p.thickness.mean * p.overlap_area).sum::<f64>() / overlap(&level);
    Thickness { mean, min, max }
}

/// A thickness level of a face gets a patch of its own when its pairs hold at least this share of the face's
/// overlap; smaller levels (a pad, a boss) stay in the patch of the main level.
const LEVEL_SHARE: f64 = 0.1;

/// What one reference face brings to a patch: the pairs it is offset for, and the faces whose footprint goes
/// to the patches of its other levels.
struct Share<'a> {
    face: FaceId,
    pairs: Vec<&'a Pair>,
    exclude: Vec<FaceId>,
    /// Not the face's level of most overlap: its patch keeps only what lies over its partners.
    minor: bool,
}

/// A planar face over planar partners at different thicknesses (a plate over a floor and over a recess in that
/// floor) gives one share per level of its parallel pairs, each clipped to its own partners and kept off the
/// others': one offset is mid-way over one level only. Its other pairs (drafts) go with the level of most
/// overlap, and so do the narrow uncovered pieces the clip keeps (bands under crossing walls): the other levels
/// keep only what lies over their partners. Any other face gives one share with all its pairs.
fn shares<'a>(graph: &FaceGraph, face: FaceId, pairs: &[&'a Pair]) -> Vec<Share<'a>> {
    let whole = || vec![Share { face, pairs: pairs.to_vec(), exclude: Vec::new(), minor: false }];
    if !graph.faces[face].surface.is_plane() {
        return whole();
    }
    let parallel: Vec<&Pair> = pairs
        .iter()
        .copied()
        .filter(|p| p.kind == PairKind::Parallel && graph.faces[p.other(face)].surface.is_plane())
        .collect();
    let total = overlap(pairs);
    let levels: Vec<Vec<&Pair>> = levels(&parallel).into_iter().filter(|l| overlap(l) >= LEVEL_SHARE * total).collect();
    if levels.len() < 2 {
        return whole();
    }
    let main = (0..levels.len())
        .max_by(|&a, &b| overlap(&levels[a]).total_cmp(&overlap(&levels[b])))
        .expect("two levels at least");
    (0..levels.len())
        .map(|k| {
            let others: Vec<&Pair> =
                levels.iter().enumerate().filter(|&(j, _)| j != k).flat_map(|(_, l)| l.iter().copied()).collect();
            // The main level takes every pair of the face but the other levels'.
            let mine: Vec<&Pair> = if k == main {
                pairs.iter().copied().filter(|p| !others.iter().any(|q| std::ptr::eq(*p, *q))).collect()
            } else {
                levels[k].clone()
            };
            Share { face, pairs: mine, exclude: partners_of(face, &others), minor: k != main }
        })
        .collect()
}

/// Whether a draft group's face can go onto a bisector: it and the partner of its largest overlap are planes.
fn draft_planar(graph: &FaceGraph, face: FaceId, pairs: &[&Pair]) -> bool {
    let main = pairs.iter().max_by(|a, b| a.overlap_area.total_cmp(&b.overlap_area));
    main.is_some_and(|p| graph.faces[face].surface.is_plane() && graph.faces[p.other(face)].surface.is_plane())
}

/// The kind an offset patch is reported as: its group's, unless the group is a draft group (whose offset
/// faces are those that are not planar draft pairs): then the kind of the share's pair of largest overlap.
fn offset_kind(group: PairKind, pairs: &[&Pair]) -> PairKind {
    if group != PairKind::Draft {
        return group;
    }
    let main = pairs.iter().max_by(|a, b| a.overlap_area.total_cmp(&b.overlap_area));
    match main.map(|p| p.kind) {
        Some(PairKind::Draft) | None => PairKind::Freeform,
        Some(kind) => kind,
    }
}

/// A draft face goes onto the exact bisector plane with its partner of largest overlap (or, on a skin, onto
/// its own plane or its partner's).
fn draft_plan(
    graph: &FaceGraph,
    group: usize,
    face: FaceId,
    pairs: &[&Pair],
    position: Position,
    reference_on_top: bool,
) -> PatchPlan {
    let main = pairs
        .iter()
        .max_by(|a, b| a.overlap_area.total_cmp(&b.overlap_area))
        .expect("a reference face belongs to at least one pair");
    let other = main.other(face);
    let plane = |f: FaceId| match graph.faces[f].surface {
        Surface::Plane { origin, normal } => (origin, normal),
        _ => unreachable!("draft pairs are made of planes"),
    };
    let (pa, na) = plane(face);
    let (pb, nb) = plane(other);
    let (origin, normal) = match position.on_reference_skin(reference_on_top) {
        None => bisector(pa, na, pb, nb),
        Some(true) => (pa, na),
        Some(false) => (pb, -nb),
    };
    let thickness = combined(pairs);
    PatchPlan {
        group,
        kind: PairKind::Draft,
        faces: vec![face],
        placement: Placement::Plane { origin: origin.to_array(), normal: normal.to_array() },
        thickness,
        partners: vec![partners_of(face, pairs)],
        exclude: vec![Vec::new()],
        strict: false,
        mid_wall: false,
        to_mid: position.to_mid(thickness.mean),
        reverse: !reference_on_top,
        fill: Vec::new(),
        fill_loops: 0,
    }
}

/// The plane halfway between two planes facing each other (outward normals roughly opposite):
/// n = (na - nb) / |na - nb|, through the point of it nearest to the midpoint of the two origins.
pub fn bisector(pa: DVec3, na: DVec3, pb: DVec3, nb: DVec3) -> (DVec3, DVec3) {
    let scale = (na - nb).length();
    let normal = (na - nb) / scale;
    let offset = (na.dot(pa) - nb.dot(pb)) / scale;
    let mid = 0.5 * (pa + pb);
    (mid - normal * (normal.dot(mid) - offset), normal)
}

#[cfg(test)]
#[path = "plan_tests.rs"]
mod tests;
