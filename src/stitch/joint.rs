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
/// A sample of an edge that meets no partner through the material, and whose way out leaves the material within
/// this share of its patch's thickness (the first probe step), is on the rim: its strip is a stub of
/// [`RIM_STUB`] of the thickness there (a strip needs a length at every sample), not filled in from its
/// neighbours' lengths.
pub const RIM_TEST: f64 = 0.5;
pub const RIM_STUB: f64 = 0.02;
/// Samples per free edge (ends included): enough to follow a curved edge or a tilted partner.
pub const SAMPLES: usize = 5;
/// Samples of an edge probed again because its partner ends part way along it ([`Extension::rim_ends`]): eight
/// times as dense, so its strip drops to the rim stub within an eighth of the first spacing of where the partner
/// ends, not along a slope from one sample to the next that leaves a wedge of the material unstitched.
pub const DENSE_SAMPLES: usize = (SAMPLES - 1) * 8 + 1;
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
    /// Whether a run of samples at an end of the edge is on the rim (the partner ends part way along the edge,
    /// past it the edge is the part's boundary: a rib standing above the boss it runs into): the strip's length
    /// drops there from the partner's distance to a stub.
    pub rim_ends: bool,
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
/// `inside(q, n)` tells whether point q, tested past a sample whose patch normal is n, is in the material.
pub fn is_open(probe: &EdgeProbe, step: f64, to_mid: f64, inside: impl Fn(DVec3, DVec3) -> bool) -> bool {
    let beyond = |k: usize| probe.points[k] + probe.outward[k] * step + probe.normals[k] * to_mid;
    let count = (0..probe.points.len()).filter(|&k| inside(beyond(k), probe.normals[k])).count();
    2 * count > probe.points.len()
}

/// Within this share of the step past an edge, a face parallel to the patch through the point tested makes it
/// in the material for the step search (`edges::open_on_level`): past the edge of a wall whose middle runs
/// exactly along a face (the floor of a recess half the wall deep: a thinner level of the wall), the point lies
/// on that face, where an inside test is a toss-up, and the wall goes on. A face across the patch there (the
/// rim's) does not count.
pub const LEVEL_FACE_SHARE: f64 = 0.01;

/// A face is parallel to a patch (`LEVEL_FACE_SHARE`) when their normals are within about 2.6 degrees (cosine
/// 0.999).
pub const LEVEL_FACE_COS: f64 = 0.999;

/// Decides one free edge of patch `patch` (`open`: see [`is_open`]). `patch_of[f]` is the patch of fused face f,
/// `thickness[p]` of patch p. `through(k, d)` says whether the way out from sample k stays in the material for
/// the first `d` (see [`through_material`]): a meeting counts only when the way to its partner's wall does, for
/// walls join through material, never across a void (a ring's bore) to its far side. With `stubs`, the samples
/// at the edge's ends that are on the rim grow stubs (see [`stubs_at_ends`]).
#[allow(clippy::too_many_arguments)]
pub fn decide(
    patch: usize,
    open: bool,
    probe: &EdgeProbe,
    patch_of: &[usize],
    thickness: &[f64],
    reach: f64,
    stubs: bool,
    through: impl Fn(usize, f64) -> bool,
) -> Verdict {
    if !open {
        return Verdict::Rim;
    }
    // Per sample, the meetings that count. On the partner's face (a T) the way must stay in the material up to
    // the partner's wall, which begins half its thickness before its patch. Past the partner's boundary (an L)
    // it must stay in the material up to the meeting itself: two walls meeting at a corner share the corner's
    // block, where their mid-surfaces cross; where they do not cross in the material (a corner rounded outside,
    // its own curved wall between them), the meeting is no joint. The way through the material is tested once
    // per meeting (each test casts rays), after the cheap tests.
    let usable: Vec<Vec<&Hit>> = probe
        .hits
        .iter()
        .enumerate()
        .map(|(k, hits)| {
            hits.iter()
                .filter(|h| {
                    let partner_t = thickness[patch_of[h.face]];
                    let way = if h.gap > OVERSHOOT * partner_t { h.distance } else { h.distance - 0.5 * partner_t };
                    patch_of[h.face] != patch && h.gap <= reach && h.distance <= reach && through(k, way)
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
    let own = thickness[patch];
    let (reached, rim_ends) = if stubs {
        // The way out is tested (rays) only along the runs at the ends.
        let on_rim = |k: usize| reached[k].is_none() && !through(k, RIM_TEST * own);
        let stubbed = stubs_at_ends(reached.clone(), on_rim, RIM_STUB * own);
        let rim_ends = stubbed != reached;
        (stubbed, rim_ends)
    } else {
        (reached, false)
    };
    Verdict::Extend(Extension { kind, partner, lengths: fill_gaps(&reached), distance, rim_ends })
}

/// `reached` with the samples of a run at either end of the edge that met no partner and whose way out leaves
/// the material at once (`on_rim`) set to `stub`. Such a run is the stretch of the edge past its partner's wall,
/// on the part's boundary (a rib's end standing above the boss it runs into): filled in from its neighbours'
/// lengths, the strip would run on out of the material. A sample inside the edge that met nothing is filled in
/// as before (a ray that slipped between faces).
fn stubs_at_ends(mut reached: Vec<Option<f64>>, on_rim: impl Fn(usize) -> bool, stub: f64) -> Vec<Option<f64>> {
    let n = reached.len();
    let leading = (0..n).take_while(|&k| on_rim(k)).count();
    let trailing = if leading == n { 0 } else { (0..n).rev().take_while(|&k| on_rim(k)).count() };
    for k in (0..leading).chain(n - trailing..n) {
        reached[k] = Some(stub);
    }
    reached
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
    // A way shorter than a step is tested halfway: past a partner's end (a rib's end beside a boss, just above
    // the boss's top) the short way to the partner's wall runs through air.
    if length <= step {
        return length <= 0.0 || contains(at(0.5 * length));
    }
    (1..).map(|j| j as f64 * step).take_while(|&s| s < length).all(|s| contains(at(s)))
}

/// How far past its samples a free edge with no partner must grow to reach the part's boundary, or None when
/// it is on the rim already (median shortfall <= `on_rim`) or most samples are not inside the material with
/// the boundary within reach. Each sample is first moved `to_mid` along the patch normal to the middle of the
/// wall; `exit(q, d, n)` is the distance from q, inside the material, along d to the boundary, if within reach
/// (n: the patch normal there).
pub fn rim_shortfall(
    probe: &EdgeProbe,
    to_mid: f64,
    on_rim: f64,
    contains: impl Fn(DVec3) -> bool,
    exit: impl Fn(DVec3, DVec3, DVec3) -> Option<f64>,
) -> Option<Vec<f64>> {
    let shortfall: Vec<Option<f64>> = (0..probe.points.len())
        .map(|k| {
            let q = probe.points[k] + probe.normals[k] * to_mid;
            // A sample on the boundary (an end of the edge at a rim) tells nothing: it takes its neighbours'.
            contains(q).then(|| exit(q, probe.outward[k], probe.normals[k])).flatten()
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
#[path = "joint_tests.rs"]
mod tests;
