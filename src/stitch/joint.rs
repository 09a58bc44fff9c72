//! Joints (Sheen et al. 5.4): what to do with each free edge of the mid-patches, decided from the sidecar's
//! probes (see `probe_edges` in sidecar/PROTOCOL.md).
//!
//! A free edge whose outside lies outside the solid is the part's rim and stays free. One whose outside lies in
//! the material is an open joint: a wall meets another there. Its partner is the patch met by rays cast from
//! the edge along the patch's tangent plane:
//! - on the partner's face: a T-joint (the edge grows up to the partner, which is then split along it);
//! - on the partner's support surface past its boundary: an L-joint (the partner's own open edge grows toward
//!   this one; both overshoot a little and the crossing trims the overshoot, as for the offset patches).
//!
//! Every strip overshoots its partner by [`OVERSHOOT`] of the partner's thickness so the fuse always finds a
//! crossing; the overshoot is then a branch under the trimming limit (0.75 t) and is dropped.
//!
//! A free edge with no partner may still stop short of the part's boundary: a wall's end rounded on both
//! sides (suppressed rounds) leaves its skins, and so its patch, up to half a thickness inside the rim. Such
//! an edge grows to the boundary, measured at mid-wall ([`rim_shortfall`]), with no overshoot.

use std::collections::BTreeMap;

use glam::DVec3;

use crate::model::shapes::{EdgeProbe, Hit};

/// Overshoot past the partner, as a share of the partner's thickness.
pub const OVERSHOOT: f64 = 0.25;
/// How far past a free edge the inside-the-material test looks, as a share of the edge's patch thickness: far
/// enough to leave a thickness face behind, not so far as to cross a thin wall.
pub const PROBE_STEP: f64 = 0.25;
/// Samples per free edge (ends included): enough to follow a curved edge or a tilted partner.
pub const SAMPLES: usize = 5;
/// Farthest a free edge with no partner grows to the part's boundary, as a share of its patch thickness (plus
/// the rim tolerance, for the meshes' chords): a wall's end rounded on both sides lies at most half a thickness
/// past its skins' edges (a full round). Farther material is another wall or a block, not the rim.
pub const RIM_REACH: f64 = 0.5;

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum JointKind {
    /// The edge meets the partner's face.
    T,
    /// The edge meets the partner's support past its boundary: both grow and cross.
    L,
    /// No partner: the edge grows to the part's boundary.
    Rim,
    /// Two parallel patches at a thickness step (or an in-plane gap) bridged by a quad.
    Step,
}

impl JointKind {
    /// As in the report's `joints[].kind`.
    pub fn name(self) -> &'static str {
        match self {
            JointKind::T => "t",
            JointKind::L => "l",
            JointKind::Rim => "rim",
            JointKind::Step => "step",
        }
    }
}

/// A strip to grow from a free edge up to (and a little past) a partner patch.
#[derive(Debug, Clone, PartialEq)]
pub struct Extension {
    pub kind: JointKind,
    pub partner: usize,
    /// Per sample of the edge: distance to the partner plus the overshoot.
    pub lengths: Vec<f64>,
    /// Median distance to the partner over the samples that met it (no overshoot).
    pub distance: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Verdict {
    /// On the part's boundary: stays free.
    Rim,
    /// An open joint with its extension.
    Extend(Extension),
    /// An open joint with no patch within reach.
    Unresolved,
}

/// Whether most of the points `step` past the edge's samples lie in the material: an open joint, not the rim.
/// The points are first moved `to_mid` along the patch normal to the middle of the wall (a patch on a skin).
pub fn is_open(probe: &EdgeProbe, step: f64, to_mid: f64, contains: impl Fn(DVec3) -> bool) -> bool {
    let beyond = |k: usize| probe.points[k] + probe.outward[k] * step + probe.normals[k] * to_mid;
    let inside = (0..probe.points.len()).filter(|&k| contains(beyond(k))).count();
    2 * inside > probe.points.len()
}

/// Decides one free edge of patch `patch` (`open`: see [`is_open`]). `patch_of[f]` is the patch of fused face f,
/// `thickness[p]` of patch p. `through(k, d)` says whether the way out from sample k stays in the material for
/// the first `d` (see [`through_material`]): a meeting counts only when the way to its partner's wall does, for
/// walls join through material, never across a void (a ring's bore) to its far side.
pub fn decide(
    patch: usize,
    open: bool,
    probe: &EdgeProbe,
    patch_of: &[usize],
    thickness: &[f64],
    reach: f64,
    through: impl Fn(usize, f64) -> bool,
) -> Verdict {
    if !open {
        return Verdict::Rim;
    }
    // Per sample, the meetings that count; the partner's wall begins half its thickness before its patch. The
    // way through the material is tested once per meeting (each test casts rays), after the cheap tests.
    let usable: Vec<Vec<&Hit>> = probe
        .hits
        .iter()
        .enumerate()
        .map(|(k, hits)| {
            hits.iter()
                .filter(|h| {
                    patch_of[h.face] != patch
                        && h.gap <= reach
                        && h.distance <= reach
                        && through(k, h.distance - 0.5 * thickness[patch_of[h.face]])
                })
                .collect()
        })
        .collect();
    let score = |h: &&Hit| h.distance + h.gap;
    // Each sample votes for the patch of its best meeting; ties go to the lowest patch.
    let mut votes: BTreeMap<usize, usize> = BTreeMap::new();
    for hits in &usable {
        if let Some(best) = hits.iter().min_by(|a, b| score(a).total_cmp(&score(b))) {
            *votes.entry(patch_of[best.face]).or_default() += 1;
        }
    }
    let Some((&partner, _)) = votes.iter().max_by(|a, b| a.1.cmp(b.1).then(b.0.cmp(a.0))) else {
        return Verdict::Unresolved;
    };
    let overshoot = OVERSHOOT * thickness[partner];
    let mut on_face = 0;
    let mut met = 0;
    let mut distances = Vec::new();
    let reached: Vec<Option<f64>> = usable
        .iter()
        .map(|hits| {
            let best =
                hits.iter().filter(|h| patch_of[h.face] == partner).min_by(|a, b| score(a).total_cmp(&score(b)))?;
            met += 1;
            if best.gap <= overshoot {
                on_face += 1;
            }
            distances.push(best.distance);
            Some(best.distance + overshoot)
        })
        .collect();
    let kind = if 2 * on_face > met { JointKind::T } else { JointKind::L };
    distances.sort_by(f64::total_cmp);
    let distance = distances[distances.len() / 2];
    Verdict::Extend(Extension { kind, partner, lengths: fill_gaps(&reached), distance })
}

/// Whether points every `step` along the way out from sample `k` of the edge, before `length`, lie in the
/// material (`contains`), each first moved `to_mid` along the patch normal to the middle of the wall.
pub fn through_material(
    probe: &EdgeProbe,
    k: usize,
    length: f64,
    step: f64,
    to_mid: f64,
    contains: impl Fn(DVec3) -> bool,
) -> bool {
    // An end of the edge often lies on another wall's skin (a rib's end on its base), and a way out along that
    // skin is neither in nor out: it is tested a step along the edge (at most halfway to the next sample).
    let points = &probe.points;
    let n = points.len();
    let along = match k {
        0 if n > 1 => points[1] - points[0],
        _ if k + 1 == n && n > 1 => points[n - 2] - points[n - 1],
        _ => DVec3::ZERO,
    };
    let start = points[k] + along.normalize_or_zero() * step.min(0.5 * along.length());
    let at = |s: f64| start + probe.outward[k] * s + probe.normals[k] * to_mid;
    (1..).map(|j| j as f64 * step).take_while(|&s| s < length).all(|s| contains(at(s)))
}

/// How far past its samples a free edge with no partner must grow to reach the part's boundary, or None when
/// it is on the rim already (median shortfall <= `on_rim`) or most samples are not inside the material with
/// the boundary within reach. Each sample is first moved `to_mid` along the patch normal to the middle of the
/// wall; `exit(q, d)` is the distance from q, inside the material, along d to the boundary, if within `reach`.
pub fn rim_shortfall(
    probe: &EdgeProbe,
    to_mid: f64,
    on_rim: f64,
    contains: impl Fn(DVec3) -> bool,
    exit: impl Fn(DVec3, DVec3) -> Option<f64>,
) -> Option<Vec<f64>> {
    let shortfall: Vec<Option<f64>> = (0..probe.points.len())
        .map(|k| {
            let q = probe.points[k] + probe.normals[k] * to_mid;
            // A sample on the boundary (an end of the edge at a rim) tells nothing: it takes its neighbours'.
            contains(q).then(|| exit(q, probe.outward[k])).flatten()
        })
        .collect();
    let mut known: Vec<f64> = shortfall.iter().flatten().copied().collect();
    if 2 * known.len() <= shortfall.len() {
        return None;
    }
    known.sort_by(f64::total_cmp);
    // A strip needs a positive length at every sample: where the edge touches the boundary it overshoots by a
    // sliver far inside the rim tolerance.
    (known[known.len() / 2] > on_rim).then(|| fill_gaps(&shortfall).into_iter().map(|d| d.max(0.5 * on_rim)).collect())
}

/// A free edge, as the step search sees it.
#[derive(Debug, Clone)]
pub struct LooseEdge {
    pub patch: usize,
    /// The wall the patch was made from (solid, pair group).
    pub wall: (usize, usize),
    pub thickness: f64,
    /// How far away the partner its rays found is (infinite when it found none).
    pub nearest: f64,
    /// Its outside lies in the material (else it is on the rim).
    pub open: bool,
    /// Samples along the edge, ends included.
    pub points: Vec<DVec3>,
    /// The patch normal and the outward direction (in the patch, away from it) at the edge.
    pub normal: DVec3,
    pub outward: DVec3,
}

/// Within this angle two directions are parallel for the step search (degrees).
const STEP_PARALLEL_DEG: f64 = 5.0;

/// A step no higher than this share of the thinner wall (the rim tolerance's share, `tolerance::on_rim`) stays
/// an upright quad: a shell mesher merges it into the thickness change, while the ramp's cut through the
/// thicker patch drops every piece of it narrower than the run, with whatever joins there (a 0.15 mm step on
/// fw13_top_cover's 2.7 mm boss cut off one of its joints).
const STEP_LEVEL_SHARE: f64 = crate::model::tolerance::RIM_SHARE;

/// The thin edge spans the thick edge when it runs along this share of it.
const STEP_SPAN_SHARE: f64 = 0.99;

/// How far (share of the thinner wall's thickness) a ramp between two levels runs into the thicker wall. Half a
/// thickness keeps the piece of the thicker patch it replaces inside the trimming's branch width (0.75 t), so
/// that piece is dropped as an overshoot, and gives a 0.5 mm step a slope of 27 degrees on a 2 mm wall.
pub const RAMP_RUN: f64 = 0.5;

/// Two bridges on one edge may overlap by this share of the newer one's stretch (they meet end to end).
const STRETCH_SLACK: f64 = 1e-3;

/// A bridge between two loose edges: the quad and the two edges' indices. The first side of the quad lies on
/// `owner`, whose patch the quad joins: the thinner edge for a ramp (so the strip of the thicker patch past the
/// ramp is trimmed as hanging past another patch), else the first edge.
#[derive(Debug, Clone, PartialEq)]
pub struct StepBridge {
    pub owner: usize,
    pub other: usize,
    /// [owner(s0), other'(s0), other'(s1), owner(s1)], other' the other edge moved in by a ramp's run.
    pub quad: [DVec3; 4],
    /// The side the quad faces: a ramp its patch's, an upright or flat quad its owner's outward direction.
    pub normal: DVec3,
}

/// Bridges across thickness steps and in-plane gaps (the in-plane joint): two straight free edges of
/// different, parallel patches that may bridge (`bridgeable`), running side by side and facing each other
/// (outward directions opposite), whose levels differ by at most the larger thickness and whose in-plane gap
/// is no wider than it. The quad between the edges over the stretch they share fills an in-plane gap. A step
/// steeper than 45 degrees and higher than `STEP_LEVEL_SHARE` of the thinner wall is laid down into a ramp from
/// the thinner patch's edge to a line `RAMP_RUN` x its thickness inside the thicker patch (whose strip past that
/// line trimming drops), when that edge spans the thicker one: a face standing across the wall would give a
/// crash mesh elements as short as the step, and has no wall thickness of its own (the judge measures it along
/// the wall). Each stretch of an edge is bridged once, nearest pairs first, sorted by (owner, other).
pub fn step_bridges(edges: &[LooseEdge]) -> Vec<StepBridge> {
    let parallel = STEP_PARALLEL_DEG.to_radians().cos();
    let line = |e: &LooseEdge| -> Option<(DVec3, DVec3, f64)> {
        let (a, b) = (*e.points.first()?, *e.points.last()?);
        let length = a.distance(b);
        let u = (b - a).normalize_or_zero();
        let straight = e.points.iter().all(|p| (*p - a).reject_from_normalized(u).length() <= 1e-3 * length.max(1e-9));
        (length > 0.0 && straight).then_some((a, u, length))
    };
    let lines: Vec<Option<(DVec3, DVec3, f64)>> = edges.iter().map(line).collect();
    let mut candidates: Vec<(f64, StepBridge)> = Vec::new();
    for i in 0..edges.len() {
        for j in i + 1..edges.len() {
            let (ei, ej) = (&edges[i], &edges[j]);
            if ei.patch == ej.patch
                || !may_bridge(ei, ej)
                || ei.normal.dot(ej.normal).abs() < parallel
                || ei.outward.dot(ej.outward) > -parallel
            {
                continue;
            }
            // Measured from the thinner edge (the first on a tie), which carries a ramp.
            let (thin, thick) = if ej.thickness < ei.thickness { (j, i) } else { (i, j) };
            let (Some((a, u, la)), Some((b, v, lb))) = (lines[thin], lines[thick]) else { continue };
            let (et, ek) = (&edges[thin], &edges[thick]);
            let reach = et.thickness.max(ek.thickness);
            if u.dot(v).abs() < parallel {
                continue;
            }
            // The thick edge's line relative to the thin one's: its offset (level and in-plane gap) and where it
            // starts and ends on u.
            let offset = (b - a).reject_from_normalized(u);
            let gap = offset.length();
            if !bridgeable(et, ek, gap) {
                continue;
            }
            let level = offset.dot(et.normal).abs();
            if level > reach || offset.dot(et.outward).abs() > reach {
                continue;
            }
            let (b0, b1) = ((b - a).dot(u), (b - a).dot(u) + lb * u.dot(v).signum());
            let (s0, s1) = (b0.min(b1).max(0.0), b0.max(b1).min(la));
            if s1 - s0 <= 1e-6 * la {
                continue;
            }
            // A ramp only where the thin edge spans the whole thick edge, over at least the larger thickness: the
            // thick patch is cut along a line through it, and a shorter ramp would cut away the rest of that
            // patch's edge, a short one (the corner of a notch) pieces beside the notch, and what joins there.
            let spans = s1 - s0 >= STEP_SPAN_SHARE * lb && s1 - s0 >= reach;
            // Only a bridge steeper than 45 degrees needs laying down; a flatter one already spans the gap.
            let ramp = spans && level > STEP_LEVEL_SHARE * et.thickness && level > offset.dot(et.outward);
            let run = if ramp { RAMP_RUN * et.thickness } else { 0.0 };
            let far = offset - ek.outward * run;
            let on_a = |s: f64| a + u * s;
            let quad = [on_a(s0), on_a(s0) + far, on_a(s1) + far, on_a(s1)];
            let bridge = if ramp || thin == i {
                StepBridge { owner: thin, other: thick, quad, normal: if ramp { et.normal } else { et.outward } }
            } else {
                // A flat or upright bridge joins the first edge's patch: the same quad seen from the other side.
                StepBridge { owner: thick, other: thin, quad: [quad[1], quad[0], quad[3], quad[2]], normal: ek.outward }
            };
            candidates.push((gap, bridge));
        }
    }
    let key = |b: &StepBridge| (b.owner.min(b.other), b.owner.max(b.other));
    candidates.sort_by(|x, y| x.0.total_cmp(&y.0).then(key(&x.1).cmp(&key(&y.1))));
    // Per edge, the stretches (along its own line) already bridged: a long edge facing several shorter ones
    // (the levels of a step split by a third) is bridged once per stretch.
    let mut used: Vec<Vec<(f64, f64)>> = vec![Vec::new(); edges.len()];
    let mut out = Vec::new();
    for (_, bridge) in candidates {
        let stretch = |k: usize, p: DVec3, q: DVec3| {
            let (a, u, _) = lines[k].expect("bridged edges are straight");
            let (s, t) = ((p - a).dot(u), (q - a).dot(u));
            (s.min(t), s.max(t))
        };
        let owner = stretch(bridge.owner, bridge.quad[0], bridge.quad[3]);
        let other = stretch(bridge.other, bridge.quad[1], bridge.quad[2]);
        let free = |k: usize, (s, t): (f64, f64)| {
            let slack = STRETCH_SLACK * (t - s);
            used[k].iter().all(|&(u0, u1)| t <= u0 + slack || s >= u1 - slack)
        };
        if free(bridge.owner, owner) && free(bridge.other, other) {
            used[bridge.owner].push(owner);
            used[bridge.other].push(other);
            out.push(bridge);
        }
    }
    out.sort_by_key(|b| (b.owner, b.other));
    out
}

/// Two loose edges (open, no partner) bridge anything within reach. Otherwise the bridge is a thickness step:
/// two levels of one wall, at least one open, each nearer to the other than to the partner its rays found. The
/// other level of a step is invisible to rays along a patch, which find a farther wall past it; and the thicker
/// level's edge may read as rim, the thinner level's skin running on past it. For edges that pass `may_bridge`.
fn bridgeable(a: &LooseEdge, b: &LooseEdge, distance: f64) -> bool {
    (loose(a) && loose(b)) || distance < a.nearest.min(b.nearest)
}

/// What `bridgeable` asks that needs no distance: both edges loose, or levels of one wall with one open. Asked
/// first, since every free edge of a pass is a candidate and most pairs fail it.
fn may_bridge(a: &LooseEdge, b: &LooseEdge) -> bool {
    (loose(a) && loose(b)) || (a.wall == b.wall && (a.open || b.open))
}

fn loose(e: &LooseEdge) -> bool {
    e.open && e.nearest.is_infinite()
}

/// Missing values linearly interpolated between their known neighbours, held constant past the ends.
fn fill_gaps(values: &[Option<f64>]) -> Vec<f64> {
    let known: Vec<(usize, f64)> = values.iter().enumerate().filter_map(|(i, v)| v.map(|v| (i, v))).collect();
    (0..values.len())
        .map(|i| {
            let before = known.iter().rev().find(|(j, _)| *j <= i);
            let after = known.iter().find(|(j, _)| *j >= i);
            match (before, after) {
                (Some(&(a, va)), Some(&(b, vb))) if b > a => va + (vb - va) * (i - a) as f64 / (b - a) as f64,
                (Some(&(_, v)), _) | (None, Some(&(_, v))) => v,
                (None, None) => unreachable!("only edges with at least one known value are filled"),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn probe(hits: Vec<Vec<Hit>>) -> EdgeProbe {
        let n = hits.len();
        EdgeProbe { points: vec![DVec3::ZERO; n], normals: vec![DVec3::X; n], outward: vec![-DVec3::Z; n], hits }
    }

    fn hit(face: usize, distance: f64, gap: f64) -> Hit {
        Hit { face, distance, gap }
    }

    // Faces 0, 1 belong to patch 0 (the base), face 2 to patch 1 (the rib), face 3 to patch 2 (a far wall).
    const PATCH_OF: [usize; 4] = [0, 0, 1, 2];
    const THICKNESS: [f64; 3] = [2.0, 1.0, 1.0];

    #[test]
    fn an_edge_whose_outside_is_outside_the_solid_is_rim() {
        let mut p = probe(vec![vec![hit(0, 1.0, 0.0)]; 3]);
        p.points = vec![DVec3::new(0.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0), DVec3::new(2.0, 0.0, 0.0)];
        // Material only below z = -0.5 at x >= 1.5: one sample of three.
        let contains = |q: DVec3| q.z < -0.4 && q.x >= 1.5;
        assert!(!is_open(&p, 0.5, 0.0, contains));
        assert_eq!(decide(1, false, &p, &PATCH_OF, &THICKNESS, 3.0, |_, _| true), Verdict::Rim);
        assert!(is_open(&p, 0.5, 0.0, |q: DVec3| q.z < -0.4 && q.x >= 0.5));
    }

    #[test]
    fn an_edge_on_a_skin_is_tested_at_the_middle_of_its_wall() {
        // A patch on the top skin z = 0 of a plate 2 thick ending at x = 5; its edge at x = 4 is open.
        let mut p = probe(vec![Vec::new(); 3]);
        p.points = (0..3).map(|k| DVec3::new(4.0, k as f64, 0.0)).collect();
        p.normals = vec![DVec3::Z; 3];
        p.outward = vec![DVec3::X; 3];
        let plate = |q: DVec3| q.z < 0.0 && q.z > -2.0 && q.x < 5.0;
        assert!(!is_open(&p, 0.5, 0.0, plate), "on the skin the test point is on the boundary");
        assert!(is_open(&p, 0.5, -1.0, plate));
        let short = |q: DVec3| plate(q) && q.x < 4.2;
        assert!(!is_open(&p, 0.5, -1.0, short), "the rim stays the rim");
    }

    #[test]
    fn a_rib_edge_meeting_the_base_face_is_a_t_joint_with_overshoot() {
        let p = probe(vec![vec![hit(0, 1.0, 0.0)], vec![hit(1, 1.0, 0.0)], vec![hit(1, 1.0, 0.0), hit(3, 2.0, 0.0)]]);
        let Verdict::Extend(e) = decide(1, true, &p, &PATCH_OF, &THICKNESS, 3.0, |_, _| true) else { panic!() };
        assert_eq!(e.kind, JointKind::T);
        assert_eq!(e.partner, 0);
        assert_eq!(e.lengths, vec![1.5; 3]);
    }

    #[test]
    fn meeting_the_support_past_the_boundary_is_an_l_joint() {
        let p = probe(vec![vec![hit(2, 0.5, 0.5)], vec![hit(2, 0.7, 0.5)]]);
        let Verdict::Extend(e) = decide(0, true, &p, &PATCH_OF, &THICKNESS, 3.0, |_, _| true) else { panic!() };
        assert_eq!(e.kind, JointKind::L);
        assert_eq!(e.partner, 1);
        assert_eq!(e.lengths, vec![0.75, 0.95]);
    }

    #[test]
    fn own_patch_and_out_of_reach_meetings_do_not_count() {
        let p = probe(vec![vec![hit(1, 0.5, 0.0), hit(3, 3.5, 0.0)], vec![hit(3, 1.0, 4.0)]]);
        assert_eq!(decide(0, true, &p, &PATCH_OF, &THICKNESS, 3.0, |_, _| true), Verdict::Unresolved);
    }

    #[test]
    fn a_wall_across_a_void_is_no_partner_and_a_nearer_one_through_material_wins() {
        // A wall's edge at x = 0 (samples along y) facing +x: a ring's bore (void) over 1 < x < 3, its far
        // side (patch 2, 1 thick) at x = 4; a nearer wall through material is patch 1 (1 thick) at x = 0.9.
        let mut p = probe(vec![vec![hit(3, 4.0, 0.0)]; 3]);
        p.points = (0..3).map(|k| DVec3::new(0.0, k as f64, 0.0)).collect();
        p.outward = vec![DVec3::X; 3];
        let solid = |q: DVec3| q.x < 1.0 || q.x > 3.0;
        let through = |k, length| through_material(&p, k, length, 0.25, 0.0, solid);
        assert!(!through(1, 4.0 - 0.5), "the way to the far side crosses the bore");
        assert!(through(1, 0.9), "up to the bore it stays in the material");
        assert_eq!(decide(0, true, &p, &PATCH_OF, &THICKNESS, 5.0, through), Verdict::Unresolved);
        p.hits = vec![vec![hit(2, 0.9, 0.0), hit(3, 4.0, 0.0)]; 3];
        let through = |k, length| through_material(&p, k, length, 0.25, 0.0, solid);
        let Verdict::Extend(e) = decide(0, true, &p, &PATCH_OF, &THICKNESS, 5.0, through) else { panic!() };
        assert_eq!(e.partner, 1);
    }

    #[test]
    fn an_end_of_the_edge_on_another_skin_is_tested_a_step_along_the_edge() {
        // A rib's edge standing on a base's top skin z = 0 at its end sample (k = 2 at z = 0): along that skin
        // the test reads material (boundary points count as inside here), a step up it reads the void.
        let mut p = probe(vec![Vec::new(); 3]);
        p.points = (0..3).map(|k| DVec3::new(0.0, 0.0, 2.0 - k as f64)).collect();
        p.outward = vec![DVec3::X; 3];
        let solid = |q: DVec3| q.z <= 0.0 || q.x < 0.5;
        assert!(!through_material(&p, 2, 2.0, 0.25, 0.0, solid));
        assert!(!through_material(&p, 1, 2.0, 0.25, 0.0, solid));
        assert!(through_material(&p, 1, 0.5, 0.25, 0.0, solid), "points before the length only");
    }

    #[test]
    fn the_nearest_meeting_wins_and_samples_without_one_are_interpolated() {
        let p = probe(vec![
            vec![hit(2, 1.0, 0.0)],
            vec![],
            vec![hit(3, 0.5, 2.0), hit(2, 2.0, 0.0)],
            vec![hit(2, 3.0, 0.0)],
            vec![],
        ]);
        let Verdict::Extend(e) = decide(0, true, &p, &PATCH_OF, &THICKNESS, 3.0, |_, _| true) else { panic!() };
        assert_eq!(e.partner, 1);
        // Sample 2's best meeting is patch 2's support (0.5 + gap 2 = 2.5 > 2.0): patch 1 there too.
        assert_eq!(e.lengths, vec![1.25, 1.75, 2.25, 3.25, 3.25]);
    }

    #[test]
    fn an_edge_short_of_the_boundary_grows_to_it_and_one_on_it_stays() {
        // Edge along x at z = 11.5 in a rib whose top is at z = 12 (rounded edges); outward +z.
        let mut p = probe(vec![vec![]; 3]);
        p.points = (0..3).map(|k| DVec3::new(k as f64, 0.0, 11.5)).collect();
        p.outward = vec![DVec3::Z; 3];
        let contains = |q: DVec3| q.z < 12.0;
        let exit = |q: DVec3, d: DVec3| Some((12.0 - q.z) / d.z).filter(|&t| t <= 1.5);
        assert_eq!(rim_shortfall(&p, 0.0, 0.2, contains, exit), Some(vec![0.5; 3]));
        // One end on a boundary (a corner of the rim): a sliver there, never zero.
        let corner = |q: DVec3, d: DVec3| if q.x > 1.5 { Some(0.0) } else { exit(q, d) };
        assert_eq!(rim_shortfall(&p, 0.0, 0.2, contains, corner), Some(vec![0.5, 0.5, 0.1]));
        assert_eq!(rim_shortfall(&p, 0.0, 0.6, contains, exit), None, "0.5 short counts as on the rim");
        p.points.iter_mut().for_each(|q| q.z = 12.0);
        assert_eq!(rim_shortfall(&p, 0.0, 0.2, contains, exit), None, "on the boundary");
        // Material on past the reach (another wall): no rim to grow to.
        p.points.iter_mut().for_each(|q| q.z = 5.0);
        assert_eq!(rim_shortfall(&p, 0.0, 0.2, contains, exit), None);
    }

    fn loose(patch: usize, thickness: f64, x: f64, z: f64, y: (f64, f64), outward: DVec3) -> LooseEdge {
        let points = (0..5).map(|k| DVec3::new(x, y.0 + (y.1 - y.0) * k as f64 / 4.0, z)).collect();
        LooseEdge {
            patch,
            wall: (1, patch),
            thickness,
            nearest: f64::INFINITY,
            open: true,
            points,
            normal: DVec3::Z,
            outward,
        }
    }

    #[test]
    fn two_levels_of_a_thickness_step_meet_through_a_ramp_into_the_thicker_wall() {
        // A t=3 patch at z=1.5 starting at x=50 (outward -x), a t=2 patch at z=1 ending there (outward +x).
        let edges =
            [loose(0, 3.0, 50.0, 1.5, (60.0, 10.0), -DVec3::X), loose(1, 2.0, 50.0, 1.0, (0.0, 60.0), DVec3::X)];
        let bridges = step_bridges(&edges);
        assert_eq!(bridges.len(), 1);
        let StepBridge { owner, other, quad, .. } = &bridges[0];
        assert_eq!((*owner, *other), (1, 0), "the thinner patch owns the ramp");
        // From the thin edge up to a line RAMP_RUN x 2 = 1 inside the thick patch.
        let expected = [(50.0, 10.0, 1.0), (51.0, 10.0, 1.5), (51.0, 60.0, 1.5), (50.0, 60.0, 1.0)];
        for (q, (x, y, z)) in quad.iter().zip(expected) {
            assert!(q.distance(DVec3::new(x, y, z)) < 1e-9, "{quad:?}");
        }
    }

    #[test]
    fn a_long_edge_facing_two_shorter_levels_is_bridged_to_each_along_its_own_stretch() {
        // A t=3 patch at z=1.5 starting at x=50 along y 0..60; two thinner levels of its wall end there, y 0..30
        // at z=1 and y 30..60 at z=1.2 (a plate over a floor and over a recess). Before, the long edge went to the
        // nearer level only and the other's edge stayed open.
        let edges = [
            loose(0, 3.0, 50.0, 1.5, (60.0, 0.0), -DVec3::X),
            loose(1, 2.0, 50.0, 1.0, (0.0, 30.0), DVec3::X),
            loose(2, 2.6, 50.0, 1.2, (30.0, 60.0), DVec3::X),
        ];
        let bridges = step_bridges(&edges);
        let pairs: Vec<(usize, usize)> = bridges.iter().map(|b| (b.owner.min(b.other), b.owner.max(b.other))).collect();
        assert_eq!(pairs, vec![(0, 1), (0, 2)]);
        for (b, (y0, y1)) in bridges.iter().zip([(0.0, 30.0), (30.0, 60.0)]) {
            let ys: Vec<f64> = b.quad.iter().map(|q| q.y).collect();
            assert!(ys.iter().all(|&y| y >= y0 - 1e-9 && y <= y1 + 1e-9), "{ys:?} within {y0}..{y1}");
        }
        // Overlapping stretches are still bridged once: a third level along y 20..40 finds the long edge taken.
        let mut crowded = edges.to_vec();
        crowded.push(loose(3, 2.2, 50.0, 1.1, (20.0, 40.0), DVec3::X));
        assert_eq!(step_bridges(&crowded).iter().filter(|b| b.owner == 3 || b.other == 3).count(), 0);
    }

    #[test]
    fn a_step_edge_that_saw_a_farther_wall_still_bridges_to_the_other_level_of_its_wall() {
        // The thin level's edge found an L partner 4 away (a wall past the step, seen along the patch); the
        // thick level's edge reads as rim. Levels of one wall 0.5 apart: the step wins.
        let thin = LooseEdge { nearest: 4.0, wall: (1, 7), ..loose(1, 2.0, 50.0, 1.0, (0.0, 60.0), DVec3::X) };
        let thick = LooseEdge { open: false, wall: (1, 7), ..loose(0, 3.0, 50.0, 1.5, (60.0, 10.0), -DVec3::X) };
        assert_eq!(step_bridges(&[thick.clone(), thin.clone()]).len(), 1);
        // Not across two walls, not past a nearer partner, and not between two rim edges.
        let other_wall = LooseEdge { wall: (1, 8), ..thick.clone() };
        assert!(step_bridges(&[other_wall, thin.clone()]).is_empty());
        let near = LooseEdge { nearest: 0.4, ..thin.clone() };
        assert!(step_bridges(&[thick.clone(), near]).is_empty());
        let rim = LooseEdge { open: false, ..thin };
        assert!(step_bridges(&[thick, rim]).is_empty());
    }

    #[test]
    fn an_in_plane_gap_is_bridged_flat() {
        let edges = [loose(0, 2.0, 50.0, 1.0, (0.0, 60.0), DVec3::X), loose(1, 2.0, 51.5, 1.0, (0.0, 60.0), -DVec3::X)];
        let bridges = step_bridges(&edges);
        assert_eq!(bridges.len(), 1);
        let expected = [(50.0, 0.0), (51.5, 0.0), (51.5, 60.0), (50.0, 60.0)];
        for (q, (x, y)) in bridges[0].quad.iter().zip(expected) {
            assert!(q.distance(DVec3::new(x, y, 1.0)) < 1e-9, "{:?}", bridges[0].quad);
        }
    }

    #[test]
    fn no_bridge_between_edges_facing_the_same_way_too_far_or_of_one_patch() {
        let same_way =
            [loose(0, 2.0, 50.0, 1.0, (0.0, 60.0), DVec3::X), loose(1, 2.0, 50.0, 1.5, (0.0, 60.0), DVec3::X)];
        assert!(step_bridges(&same_way).is_empty());
        let far = [loose(0, 2.0, 50.0, 1.0, (0.0, 60.0), DVec3::X), loose(1, 2.0, 50.0, 4.0, (0.0, 60.0), -DVec3::X)];
        assert!(step_bridges(&far).is_empty(), "3 apart, thicker than either wall");
        let one = [loose(0, 2.0, 50.0, 1.0, (0.0, 60.0), DVec3::X), loose(0, 2.0, 50.0, 1.5, (0.0, 60.0), -DVec3::X)];
        assert!(step_bridges(&one).is_empty());
    }

    #[test]
    fn gaps_fill_by_interpolation_and_holding() {
        assert_eq!(fill_gaps(&[None, Some(1.0), None, Some(3.0), None]), vec![1.0, 1.0, 2.0, 3.0, 3.0]);
    }
}
