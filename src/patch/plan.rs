//! The patch plan (Sheen et al. 5.2): which faces make each mid-patch and where they go.
//!
//! A patch is made from the reference side of a pair group (the side with the larger area, so fewer patches
//! need extending): offset by half the thickness into the material, or for a draft pair projected onto the
//! exact bisector plane of the two faces. Reference faces whose own pairs have different thicknesses (a
//! thickness step) get separate patches, each at its own mid-plane.

use glam::DVec3;
use serde::Serialize;

use crate::face_graph::{EdgeId, FaceGraph, FaceId, Surface};
use crate::pairing::{Pair, PairKind, Pairing, Side, Thickness};
use crate::patch::sides::top_sides;
use crate::sidecar::protocol::Placement;

/// Where a patch lies through its wall, as shell pre-processors offer it; the thickness is the same for all.
/// Every patch's normal points out of its wall's top side (see `sides`), so on `Top` the material lies on the
/// side opposite the normal and on `Bottom` on the normal's side: a solver reading the shell puts its
/// reference surface at the top or bottom fibre (Abaqus SPOS/SNEG, Nastran ZOFFS of -t/2 or +t/2).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Position {
    #[default]
    Mid,
    Top,
    Bottom,
}

impl Position {
    /// On a skin: whether it is the reference face's own skin (true) or its partner's, for a wall whose top
    /// side is the reference side (`reference_on_top`) or the other. None mid-way.
    fn on_reference_skin(self, reference_on_top: bool) -> Option<bool> {
        match self {
            Position::Mid => None,
            Position::Top => Some(reference_on_top),
            Position::Bottom => Some(!reference_on_top),
        }
    }

    /// Offset of the patch from its reference face along the face's outward normal, for a wall `t` thick.
    fn offset(self, t: f64, reference_on_top: bool) -> f64 {
        match self.on_reference_skin(reference_on_top) {
            None => -0.5 * t,
            Some(true) => 0.0,
            Some(false) => -t,
        }
    }

    /// From the patch to the middle of its wall, along the patch normal: the joint tests look there, since a
    /// point on a skin is on the solid's boundary and says nothing about the material.
    pub fn to_mid(self, t: f64) -> f64 {
        match self {
            Position::Mid => 0.0,
            Position::Top => -0.5 * t,
            Position::Bottom => 0.5 * t,
        }
    }
}

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

/// Reference faces of one group whose thicknesses differ by less than this share are offset together.
const SAME_THICKNESS: f64 = 0.01;

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

/// Why a group's patch may not lie mid-way everywhere.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub enum PlanNote {
    /// Both sides span a thickness step: offset at the mean.
    ThicknessStep { group: usize, faces: Vec<FaceId>, thickness: Thickness },
    /// Neither side is mostly covered by its partners: the patch overshoots the wall.
    PartialOverlap { group: usize, faces: Vec<FaceId>, coverage: f64 },
}

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
) -> (Side, Vec<(FaceId, Vec<&'a Pair>)>, Option<PlanNote>) {
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
        Some(PlanNote::ThicknessStep { group: group.id, faces: group.sides[side].clone(), thickness: group.thickness })
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
        let (side, per_face, warning) = choose_reference(graph, group, pairing);
        if let Some(w) = warning {
            notes.push(w);
        }
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
            let same = |p: &&mut PatchPlan| {
                (p.thickness.mean - t.mean).abs() <= SAME_THICKNESS * p.thickness.mean
                    && p.strict == share.minor
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
                    kind: offset_kind(group.kind, &share.pairs),
                    faces: vec![share.face],
                    placement: Placement::Offset(position.offset(t.mean, on_top)),
                    thickness: t,
                    partners: vec![partners],
                    exclude: vec![share.exclude],
                    strict: share.minor,
                    to_mid: position.to_mid(t.mean),
                    reverse: !on_top,
                    fill: Vec::new(),
                    fill_loops: 0,
                }),
            }
        }
        plans.extend(clustered.into_iter().map(|plan| plan.with_fill(graph, fill)));
    }
    (plans, notes)
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
mod tests {
    use super::*;
    use crate::pairing::detect;
    use crate::synthetic;
    use crate::tolerance::Tolerances;

    #[test]
    fn bisector_of_a_drafted_wall() {
        // x = 0 facing -x, and a face tilted by 2 degrees facing +x, 3 apart at the origin.
        let a = 2.0_f64.to_radians();
        let nb = DVec3::new(a.cos(), 0.0, a.sin());
        let (o, n) = bisector(DVec3::ZERO, -DVec3::X, DVec3::X * 3.0, nb);
        // Equidistant from both planes, and near the midpoint of the origins.
        let (da, db) = (-(-DVec3::X).dot(o), -nb.dot(o - DVec3::X * 3.0));
        assert!((da - db).abs() < 1e-12 && da > 0.0, "{da} {db}");
        assert!(o.distance(DVec3::X * 1.5) < 1e-3, "{o}");
        let expected = (-DVec3::X - nb).normalize();
        assert!(n.distance(expected) < 1e-12);
    }

    #[test]
    fn plate_offsets_its_larger_face_by_half_the_thickness() {
        let g = synthetic::cuboid(DVec3::ZERO, DVec3::new(100.0, 60.0, 2.0));
        let pairing = detect(&g, &Tolerances::new(120.0, 3.0, 0.05), &[true; 6]);
        let (plans, steps) = plan_patches(&g, &pairing, Position::Mid, &[]);
        assert!(steps.is_empty());
        assert_eq!(plans.len(), 1);
        assert_eq!(plans[0].faces, vec![4]);
        assert_eq!(plans[0].placement, Placement::Offset(-1.0));
    }

    #[test]
    fn a_skin_position_keeps_the_thickness_and_says_where_the_middle_is() {
        let g = synthetic::cuboid(DVec3::ZERO, DVec3::new(100.0, 60.0, 2.0));
        let pairing = detect(&g, &Tolerances::new(120.0, 3.0, 0.05), &[true; 6]);
        let placed = |position| {
            let (plans, _) = plan_patches(&g, &pairing, position, &[]);
            (plans[0].placement.clone(), plans[0].to_mid, plans[0].thickness.mean)
        };
        assert_eq!(placed(Position::Mid), (Placement::Offset(-1.0), 0.0, 2.0));
        assert_eq!(placed(Position::Top), (Placement::Offset(0.0), -1.0, 2.0));
        assert_eq!(placed(Position::Bottom), (Placement::Offset(-2.0), 1.0, 2.0));
    }

    #[test]
    fn a_draft_patch_on_a_skin_lies_on_that_face_plane() {
        // A wall 3 thick at its foot, one side drafted by 1 degree.
        let a = 1.0_f64.to_radians();
        let tilted = DVec3::new(a.cos(), 0.0, a.sin());
        let faces = vec![
            synthetic::rect(DVec3::ZERO, DVec3::Z * 20.0, DVec3::Y * 40.0, -DVec3::X),
            synthetic::rect(DVec3::X * 3.0, DVec3::Y * 40.0, DVec3::new(-a.sin(), 0.0, a.cos()) * 20.0, tilted),
        ];
        let g = synthetic::graph(faces, &[]);
        let pairing = detect(&g, &Tolerances::new(60.0, 4.0, 2.0_f64.to_radians()), &[true; 2]);
        let plane = |position| {
            let (plans, _) = plan_patches(&g, &pairing, position, &[]);
            let reference = plans[0].faces[0];
            match plans[0].placement {
                Placement::Plane { origin, normal } => (reference, DVec3::from(origin), DVec3::from(normal)),
                Placement::Offset(_) => panic!("a draft pair is projected"),
            }
        };
        let (reference, origin, normal) = plane(Position::Top);
        let Surface::Plane { origin: ro, normal: rn } = g.faces[reference].surface else { panic!() };
        assert!(normal.distance(rn) < 1e-12 && (origin - ro).dot(rn).abs() < 1e-12);
        let (_, origin, normal) = plane(Position::Bottom);
        let Surface::Plane { origin: po, normal: pn } = g.faces[1 - reference].surface else { panic!() };
        assert!(normal.distance(-pn) < 1e-12 && (origin - po).dot(pn).abs() < 1e-12);
    }

    #[test]
    fn a_freeform_face_in_a_draft_group_is_offset_not_projected() {
        // A floor: a plane (x 0..100) and a flat B-spline strip beside it (x 100..110), both facing down; over
        // them one roof plane tilted by 1.5 degree (x 0..109). The roof pairs with the plane as a draft pair
        // (the group's kind: most overlap) and with the strip as a freeform pair: the strip has no plane to
        // project onto the bisector of, so it is offset like any curved pair.
        let a = 1.5_f64.to_radians();
        let up = DVec3::new(-a.sin(), 0.0, a.cos());
        let faces = vec![
            synthetic::rect(DVec3::ZERO, DVec3::Y * 40.0, DVec3::X * 100.0, -DVec3::Z),
            synthetic::face(Surface::Bspline, 20, |u, v| (DVec3::new(100.0 + 10.0 * u, 40.0 * v, 0.0), -DVec3::Z)),
            synthetic::rect(DVec3::Z * 2.0, DVec3::new(a.cos(), 0.0, a.sin()) * 109.0, DVec3::Y * 40.0, up),
        ];
        let g = synthetic::graph(faces, &[]);
        let pairing = detect(&g, &Tolerances::new(120.0, 6.0, 2.0_f64.to_radians()), &[true; 3]);
        assert_eq!(pairing.groups.len(), 1, "{:?}", pairing.pairs);
        assert_eq!(pairing.groups[0].kind, PairKind::Draft);
        let (plans, _) = plan_patches(&g, &pairing, Position::Mid, &[]);
        let of = |f: FaceId| plans.iter().find(|p| p.faces.contains(&f)).expect("a patch per floor face");
        assert!(matches!(of(0).placement, Placement::Plane { .. }), "{:?}", of(0).placement);
        assert!(matches!(of(1).placement, Placement::Offset(_)), "{:?}", of(1).placement);
        assert_eq!(of(1).kind, PairKind::Freeform);
    }

    #[test]
    fn a_thickness_step_gives_one_patch_per_level() {
        // One bottom under two tops at heights 2 and 3: two patches from the bottom would be wrong, so the
        // tops (the reference side here, being larger) are offset each by its own half thickness.
        let faces = vec![
            synthetic::rect(DVec3::ZERO, DVec3::Y * 10.0, DVec3::X * 40.0, -DVec3::Z),
            synthetic::rect(DVec3::new(-5.0, 0.0, 2.0), DVec3::X * 25.0, DVec3::Y * 10.0, DVec3::Z),
            synthetic::rect(DVec3::new(20.0, 0.0, 3.0), DVec3::X * 25.0, DVec3::Y * 10.0, DVec3::Z),
        ];
        let g = synthetic::graph(faces, &[]);
        let pairing = detect(&g, &Tolerances::new(60.0, 4.0, 0.05), &[true; 3]);
        let (plans, _) = plan_patches(&g, &pairing, Position::Mid, &[]);
        let offsets: Vec<(Vec<FaceId>, Placement)> =
            plans.iter().map(|p| (p.faces.clone(), p.placement.clone())).collect();
        assert_eq!(offsets, vec![(vec![1], Placement::Offset(-1.0)), (vec![2], Placement::Offset(-1.5))]);
    }

    #[test]
    fn a_face_over_two_levels_gives_a_patch_per_level_each_kept_off_the_other() {
        // A bottom at z=0 (x 0..40) under a floor at z=2 (x -30..25) and a recess-like top at z=3 (x 25..40); the
        // floor also lies over a lower bottom at z=-1 (x -35..0), so neither side sits at one thickness and
        // the bottoms, being larger, are the reference. One offset of the first bottom would be mid-way over
        // one level only: it gives a patch per level, clipped to that level's partner and off the other's.
        let faces = vec![
            synthetic::rect(DVec3::ZERO, DVec3::Y * 10.0, DVec3::X * 40.0, -DVec3::Z),
            synthetic::rect(DVec3::new(-35.0, 0.0, -1.0), DVec3::Y * 10.0, DVec3::X * 35.0, -DVec3::Z),
            synthetic::rect(DVec3::new(-30.0, 0.0, 2.0), DVec3::X * 55.0, DVec3::Y * 10.0, DVec3::Z),
            synthetic::rect(DVec3::new(25.0, 0.0, 3.0), DVec3::X * 15.0, DVec3::Y * 10.0, DVec3::Z),
        ];
        let g = synthetic::graph(faces, &[]);
        let pairing = detect(&g, &Tolerances::new(60.0, 4.0, 0.05), &[true; 4]);
        let (plans, _) = plan_patches(&g, &pairing, Position::Mid, &[]);
        let got: Vec<(Vec<FaceId>, Placement, Vec<Vec<FaceId>>, Vec<Vec<FaceId>>, bool)> = plans
            .iter()
            .map(|p| (p.faces.clone(), p.placement.clone(), p.partners.clone(), p.exclude.clone(), p.strict))
            .collect();
        assert_eq!(
            got,
            vec![
                // The level of most overlap keeps the clip's narrow pieces; the other keeps only its footprint.
                (vec![0], Placement::Offset(-1.0), vec![vec![2]], vec![vec![3]], false),
                (vec![0], Placement::Offset(-1.5), vec![vec![3]], vec![vec![2]], true),
                (vec![1], Placement::Offset(-1.5), vec![vec![2]], vec![vec![]], false),
            ]
        );
    }

    #[test]
    fn a_step_under_the_larger_face_is_offset_from_the_other_side() {
        // A long bottom (larger) under two shorter tops at 2 and 3: the bottom spans the step, the tops do
        // not, so each top is offset by its own half thickness.
        let faces = vec![
            synthetic::rect(DVec3::ZERO, DVec3::Y * 10.0, DVec3::X * 60.0, -DVec3::Z),
            synthetic::rect(DVec3::new(0.0, 0.0, 2.0), DVec3::X * 25.0, DVec3::Y * 10.0, DVec3::Z),
            synthetic::rect(DVec3::new(30.0, 0.0, 3.0), DVec3::X * 25.0, DVec3::Y * 10.0, DVec3::Z),
        ];
        let g = synthetic::graph(faces, &[]);
        let pairing = detect(&g, &Tolerances::new(70.0, 4.0, 0.05), &[true; 3]);
        assert_eq!(pairing.groups[0].reference, crate::pairing::Side::A, "the bottom is larger");
        let (plans, steps) = plan_patches(&g, &pairing, Position::Mid, &[]);
        assert!(steps.is_empty());
        let offsets: Vec<f64> = plans
            .iter()
            .map(|p| match p.placement {
                Placement::Offset(d) => d,
                Placement::Plane { .. } => panic!("parallel pairs are offset"),
            })
            .collect();
        assert_eq!(plans.iter().map(|p| p.faces.clone()).collect::<Vec<_>>(), vec![vec![1], vec![2]]);
        assert!((offsets[0] + 1.0).abs() < 1e-12 && (offsets[1] + 1.5).abs() < 1e-12, "{offsets:?}");
    }

    #[test]
    fn a_larger_face_mostly_beyond_its_partner_is_not_offset() {
        // A 100 x 10 bottom under a 20 x 10 top: offsetting the bottom would put 80% of the patch where no
        // wall is, so the top (fully covered) is offset instead; 40% coverage keeps the larger face.
        let faces = |w: f64| {
            vec![
                synthetic::rect(DVec3::ZERO, DVec3::Y * 10.0, DVec3::X * 100.0, -DVec3::Z),
                synthetic::rect(DVec3::new(10.0, 0.0, 2.0), DVec3::X * w, DVec3::Y * 10.0, DVec3::Z),
            ]
        };
        let tol = Tolerances::new(110.0, 3.0, 0.05);
        let g = synthetic::graph(faces(20.0), &[]);
        let (plans, notes) = plan_patches(&g, &detect(&g, &tol, &[true; 2]), Position::Mid, &[]);
        assert_eq!(plans[0].faces, vec![1]);
        assert!(notes.is_empty());
        let g = synthetic::graph(faces(60.0), &[]);
        let (plans, _) = plan_patches(&g, &detect(&g, &tol, &[true; 2]), Position::Mid, &[]);
        assert_eq!(plans[0].faces, vec![0]);
    }
}
