//! Bridges between free edges that found no partner (Sheen et al. 5.4, in-plane joints): two levels of a wall
//! at a thickness step, laid down into a ramp when steep, and in-plane gaps bridged flat.

use glam::DVec3;

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

/// An edge is straight when its samples lie within this share of its chord (with a floor for a zero chord)
/// from it: a bridge is a flat quad between two straight lines.
const STRAIGHT_SHARE: f64 = 1e-3;
const STRAIGHT_FLOOR: f64 = 1e-9;

/// Two edges side by side share a stretch only when it is longer than this share of the thin edge: touching
/// end to end is no overlap.
const SHARED_STRETCH_SHARE: f64 = 1e-6;

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
        let straight = e
            .points
            .iter()
            .all(|p| (*p - a).reject_from_normalized(u).length() <= STRAIGHT_SHARE * length.max(STRAIGHT_FLOOR));
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
            if s1 - s0 <= SHARED_STRETCH_SHARE * la {
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

#[cfg(test)]
#[path = "bridge_tests.rs"]
mod tests;
