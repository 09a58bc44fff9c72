//! Bridges between free edges that found no partner (Sheen et al. 5.4, in-plane joints): two levels of a wall
//! at a thickness step, laid down into a ramp when steep, and in-plane gaps bridged flat.

use std::f64::consts::{FRAC_PI_2, TAU};

use glam::DVec3;

/// A free edge, as the step search sees it.
#[derive(Debug, Clone)]
pub struct LooseEdge {
    pub patch: usize,
    /// The wall the patch was made from (`PatchInfo::wall`).
    pub wall: (usize, usize),
    pub thickness: f64,
    /// How far away the partner its rays found is (infinite when it found none).
    pub nearest: f64,
    /// How far its patch's joints reach (`PatchInfo::reach`).
    pub reach: f64,
    /// Its patch is the offset of a freeform face (`PatchInfo::freeform`).
    pub freeform: bool,
    /// Its outside lies in the material (else it is on the rim).
    pub open: bool,
    /// Samples along the edge, ends included.
    pub points: Vec<DVec3>,
    /// The patch normal at the edge's middle sample.
    pub normal: DVec3,
    /// The outward direction (in the patch, away from it) at each sample.
    pub outwards: Vec<DVec3>,
    /// A point of the face the edge bounds and the face's unit normal there: with the edge's own samples, they
    /// tell whether the face is flat up to the edge (`plane`) and how it runs on inside the edge (`run_inside`).
    pub face: [DVec3; 2],
}

impl LooseEdge {
    /// The plane of the face the edge bounds (a point on it, its unit normal), when the edge's samples lie in the
    /// face's tangent plane there within `coplanar`: the face is flat up to the edge (a curved face's tangent
    /// plane leaves its edges), and a flat bridge lying in it continues that face (`step_bridges`).
    pub fn plane(&self, coplanar: f64) -> Option<[DVec3; 2]> {
        let [point, normal] = self.face;
        let flat = normal != DVec3::ZERO && in_plane(&self.points, self.face, coplanar);
        flat.then_some([point, normal])
    }

    /// The outward direction at the edge's middle sample.
    pub fn outward(&self) -> DVec3 {
        self.outwards[self.outwards.len() / 2]
    }
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
    /// The side the quad faces: a ramp its patch's, a quad lying in the plane of its owner's face that face's
    /// normal, any other its owner's outward direction.
    pub normal: DVec3,
    /// For two coaxial arcs, the axis (a point on it, its direction): the quad's sides are arcs about it, each
    /// turning counter-clockwise about the direction from quad[0] to quad[3] and from quad[1] to quad[2].
    pub axis: Option<[DVec3; 2]>,
}

/// What an edge runs along, for the step search: a straight line or an arc of a circle.
#[derive(Debug, Clone, Copy)]
enum Course {
    /// From `start` along the unit `direction`, `length` long.
    Line { start: DVec3, direction: DVec3, length: f64 },
    /// About `axis` (unit) through `center`, of `radius`, from the unit radial direction `from`, turning
    /// counter-clockwise about the axis by `sweep` (0..2 pi).
    Arc { center: DVec3, axis: DVec3, radius: f64, from: DVec3, sweep: f64 },
}

impl Course {
    /// Where `p` lies along the course, as a length from its start (an arc's by its angle times its radius).
    fn position(&self, p: DVec3) -> f64 {
        match *self {
            Course::Line { start, direction, .. } => (p - start).dot(direction),
            Course::Arc { center, axis, radius, from, .. } => angle_about(p - center, axis, from) * radius,
        }
    }
}

/// The stretch (from, to) of `course` between the ends `p` and `q` of a bridge along it. Ends that meet on a whole
/// circle are a whole turn (`arc_bridge` makes no sliver), the circle's whole length.
fn stretch_along(course: Course, p: DVec3, q: DVec3) -> (f64, f64) {
    if let Course::Arc { radius, sweep, .. } = course {
        if sweep >= TAU && p.distance(q) <= 0.5 * ARC_SHARE * radius {
            return (0.0, sweep * radius);
        }
    }
    let (s, t) = (course.position(p), course.position(q));
    (s.min(t), s.max(t))
}

/// The angle of `v` about unit `axis` from unit `from` (square to it), counter-clockwise, in -pi/2..3 pi/2: a
/// point a little before an arc's start reads as a small negative angle, not as nearly a whole turn.
fn angle_about(v: DVec3, axis: DVec3, from: DVec3) -> f64 {
    let angle = v.dot(axis.cross(from)).atan2(v.dot(from));
    if angle < -FRAC_PI_2 {
        angle + TAU
    } else {
        angle
    }
}

/// The course of edge samples `points`: a line when they lie within STRAIGHT_SHARE of their chord (with a floor
/// for a zero chord) from it, else an arc when they lie within ARC_SHARE of its radius of the circle through the
/// first, middle and last, in its plane; None otherwise.
fn course(points: &[DVec3]) -> Option<Course> {
    let (a, b) = (*points.first()?, *points.last()?);
    let length = a.distance(b);
    let u = (b - a).normalize_or_zero();
    let straight = points
        .iter()
        .all(|p| (*p - a).reject_from_normalized(u).length() <= STRAIGHT_SHARE * length.max(STRAIGHT_FLOOR));
    if straight {
        return (length > 0.0).then_some(Course::Line { start: a, direction: u, length });
    }
    // A closed edge (a whole circle: a tube's end, a stepped bore) starts where it ends: its circle goes
    // through the start and the points a third and two thirds along, and it sweeps a whole turn.
    let spread = points.iter().map(|p| p.distance(a)).fold(0.0, f64::max);
    let closed = length <= ARC_SHARE * spread;
    let (m, b) =
        if closed { (points[points.len() / 3], points[2 * points.len() / 3]) } else { (points[points.len() / 2], b) };
    let (v, w) = (m - a, b - a);
    let normal = v.cross(w);
    if normal.length_squared() == 0.0 {
        return None;
    }
    // The circumcentre of a, m, b.
    let center = a + (v.length_squared() * w - w.length_squared() * v).cross(normal) / (2.0 * normal.length_squared());
    let axis = normal.normalize();
    let radius = a.distance(center);
    let on_circle = |p: &DVec3| {
        let r = *p - center;
        (r.reject_from_normalized(axis).length() - radius).abs() <= ARC_SHARE * radius
            && r.dot(axis).abs() <= ARC_SHARE * radius
    };
    if !points.iter().all(on_circle) {
        return None;
    }
    let from = (a - center) / radius;
    let sweep = if closed { TAU } else { angle_about(b - center, axis, from).rem_euclid(TAU) };
    Some(Course::Arc { center, axis, radius, from, sweep })
}

/// Edge samples lie on a circle when within this share of its radius from it (an edge of a cylinder or cone
/// patch is an exact arc; a spline one is not bridged).
const ARC_SHARE: f64 = 1e-3;

/// Two arcs are coaxial when the centre of one lies within this share of the larger radius from the other's axis.
const COAXIAL_SHARE: f64 = 1e-3;

/// Bridges across thickness steps and in-plane gaps (the in-plane joint): two straight free edges, or two arcs
/// about one axis, of different, parallel patches that may bridge (`bridgeable`), running side by side and
/// facing each other (outward directions opposite), whose levels differ by at most the larger thickness and whose
/// in-plane gap is no wider than it. The quad between the edges over the stretch they share fills an in-plane
/// gap. A step steeper than 45 degrees and higher than `STEP_LEVEL_SHARE` of the thinner wall is laid down into
/// a ramp from the thinner patch's edge to a line `RAMP_RUN` x its thickness inside the thicker patch (whose
/// strip past that line trimming drops), when that edge spans the thicker one: a face standing across the wall
/// would give a crash mesh elements as short as the step, and has no wall thickness of its own (the judge
/// measures it along the wall). Between arcs (a thinner rim band above a moulded housing's wall, round its
/// rounded corners) the ramp is a band of a cone. Each stretch of an edge is bridged once, nearest pairs first,
/// sorted by (owner, other).
///
/// A flat bridge lying in the plane of one edge's face (within `coplanar`) and not of the other's joins the
/// planar one: a flat wall running tangentially into a bend whose patch stops a hair from the flat's (the bend's
/// skins drawn on axes apart) is bridged in the flat's own plane, and the flat's patch merges the quad into its
/// face; given to the bend's patch it would stay a sliver face of its own, as narrow as the gap.
pub fn step_bridges(edges: &[LooseEdge], coplanar: f64) -> Vec<StepBridge> {
    let (courses, candidates) = nearest_first(edges, |i, j, courses, parallel| {
        let (ei, ej) = (&edges[i], &edges[j]);
        if ei.patch == ej.patch
            || !may_bridge(ei, ej)
            || ei.normal.dot(ej.normal).abs() < parallel
            || ei.outward().dot(ej.outward()) > -parallel
        {
            return None;
        }
        // Measured from the thinner edge (the first on a tie), which carries a ramp.
        let (thin, thick) = if ej.thickness < ei.thickness { (j, i) } else { (i, j) };
        match (courses[thin], courses[thick]) {
            (Some(a @ Course::Line { .. }), Some(b @ Course::Line { .. })) => {
                line_bridge(edges, (thin, a), (thick, b), i, parallel)
            }
            (Some(a @ Course::Arc { .. }), Some(b @ Course::Arc { .. })) => {
                arc_bridge(edges, (thin, a), (thick, b), i, parallel)
            }
            _ => None,
        }
    });
    // Per edge, the stretches (along its own course) already bridged: a long edge facing several shorter ones
    // (the levels of a step split by a third) is bridged once per stretch.
    let mut used: Vec<Vec<(f64, f64)>> = vec![Vec::new(); edges.len()];
    let mut out = Vec::new();
    for (_, bridge) in candidates {
        let stretch =
            |k: usize, p: DVec3, q: DVec3| stretch_along(courses[k].expect("bridged edges are lines or arcs"), p, q);
        let owner = stretch(bridge.owner, bridge.quad[0], bridge.quad[3]);
        let other = stretch(bridge.other, bridge.quad[1], bridge.quad[2]);
        let free = |k: usize, (s, t): (f64, f64)| {
            let slack = STRETCH_SLACK * (t - s);
            used[k].iter().all(|&(u0, u1)| t <= u0 + slack || s >= u1 - slack)
        };
        if free(bridge.owner, owner) && free(bridge.other, other) {
            used[bridge.owner].push(owner);
            used[bridge.other].push(other);
            out.push(continuing_plane(bridge, edges, coplanar));
        }
    }
    out.sort_by_key(|b| (b.owner, b.other));
    out
}

/// The bridge given to the edge in whose face's plane the quad lies, its owner's first, facing the way that face
/// does (`StepBridge::normal`, so that the merge into the face sees one surface, not its reverse); as it is when
/// it lies in neither.
fn continuing_plane(bridge: StepBridge, edges: &[LooseEdge], coplanar: f64) -> StepBridge {
    let continues = |k: usize| edges[k].plane(coplanar).is_some_and(|plane| in_plane(&bridge.quad, plane, coplanar));
    if continues(bridge.owner) {
        return StepBridge { normal: edges[bridge.owner].normal, ..bridge };
    }
    if !continues(bridge.other) {
        return bridge;
    }
    let q = bridge.quad;
    StepBridge {
        owner: bridge.other,
        other: bridge.owner,
        quad: [q[1], q[0], q[3], q[2]],
        normal: edges[bridge.other].normal,
        axis: bridge.axis,
    }
}

/// Whether every point lies within `tolerance` of the plane (a point on it, its unit normal).
pub fn in_plane(points: &[DVec3], [origin, normal]: [DVec3; 2], tolerance: f64) -> bool {
    points.iter().all(|&q| (q - origin).dot(normal).abs() <= tolerance)
}

/// A step bridge between two edges that are one curve at two levels: the `owner` edge swept by `along` onto
/// the `other`, straight (`run` 0: an upright band) or, for a ramp, out to `run` inside the other's patch.
#[derive(Debug, Clone, PartialEq)]
pub struct SweptStep {
    pub owner: usize,
    pub other: usize,
    pub along: DVec3,
    pub run: f64,
}

/// Bridges across thickness steps whose edges are neither lines nor arcs about one axis (a spline outline of a
/// pocket or a cut-out under a flat skin): two free edges of different, parallel patches that may bridge
/// (`bridgeable`), where every sample of one edge moved by one offset along its patch's normal lies on the other
/// edge (within `STEP_LEVEL_SHARE` of the thinner wall) and faces it, the offset no longer than the larger
/// thickness. As between lines, the thinner edge is laid down into a ramp to `RAMP_RUN` x its thickness inside
/// the thicker patch when the two edges are the same stretch of the outline (each lands on the other), at least
/// the larger thickness long, and the step is higher than `STEP_LEVEL_SHARE` of the thinner wall. Otherwise the
/// edge that lands on the other (the shorter) is swept straight onto it: an upright band, since a ramp would cut
/// the longer edge's patch along part of its edge only. Edges `done` are left out (bridged already); each edge is
/// bridged once, nearest pairs first.
pub fn swept_steps(edges: &[LooseEdge], done: &[bool]) -> Vec<SweptStep> {
    let parallel = STEP_PARALLEL_DEG.to_radians().cos();
    let mut candidates: Vec<(f64, SweptStep)> = Vec::new();
    for i in 0..edges.len() {
        for j in i + 1..edges.len() {
            let (ei, ej) = (&edges[i], &edges[j]);
            // Facing each other is told sample by sample (`one_curve`): along a curved outline the middles of a
            // short edge and of a long one lie apart.
            if done[i]
                || done[j]
                || ei.patch == ej.patch
                || !may_bridge(ei, ej)
                || ei.normal.dot(ej.normal).abs() < parallel
            {
                continue;
            }
            let (thin, thick) = if ej.thickness < ei.thickness { (j, i) } else { (i, j) };
            let (et, ek) = (&edges[thin], &edges[thick]);
            let tolerance = STEP_LEVEL_SHARE * et.thickness;
            let reach = ek.thickness;
            let step = match (one_curve(et, ek, tolerance, reach), one_curve(ek, et, tolerance, reach)) {
                (Some(along), Some(_)) => {
                    let ramp = along.length() > STEP_LEVEL_SHARE * et.thickness && polyline_length(&et.points) >= reach;
                    SweptStep {
                        owner: thin,
                        other: thick,
                        along,
                        run: if ramp { RAMP_RUN * et.thickness } else { 0.0 },
                    }
                }
                (Some(along), None) => SweptStep { owner: thin, other: thick, along, run: 0.0 },
                (None, Some(along)) => SweptStep { owner: thick, other: thin, along, run: 0.0 },
                (None, None) => continue,
            };
            if bridgeable(ei, ej, step.along.length()) {
                candidates.push((step.along.length(), step));
            }
        }
    }
    candidates.sort_by(|x, y| {
        let key = |b: &SweptStep| (b.owner.min(b.other), b.owner.max(b.other));
        x.0.total_cmp(&y.0).then(key(&x.1).cmp(&key(&y.1)))
    });
    each_edge_once(candidates, done.to_vec(), |b| (b.owner, b.other))
}

/// The bridges of `candidates` (in their order), each taken only while neither of its two edges (`ends`) is
/// `used`; sorted by their edges.
fn each_edge_once<T>(candidates: Vec<(f64, T)>, mut used: Vec<bool>, ends: impl Fn(&T) -> (usize, usize)) -> Vec<T> {
    let mut out = Vec::new();
    for (_, bridge) in candidates {
        let (a, b) = ends(&bridge);
        if !used[a] && !used[b] {
            (used[a], used[b]) = (true, true);
            out.push(bridge);
        }
    }
    out.sort_by_key(|b| ends(b));
    out
}

fn polyline_length(points: &[DVec3]) -> f64 {
    points.windows(2).map(|w| w[0].distance(w[1])).sum()
}

/// The offset along `a`'s normal that moves every sample of edge `a` onto edge `b` (within `tolerance`), facing
/// it (outward directions apart by more than `FACING_DEG` there), when it is a step: longer than the
/// tolerance, at most `reach`.
fn one_curve(a: &LooseEdge, b: &LooseEdge, tolerance: f64, reach: f64) -> Option<DVec3> {
    let middle = a.points[a.points.len() / 2];
    let along = (nearest_on(&b.points, middle).0 - middle).project_onto_normalized(a.normal);
    if along.length() <= tolerance || along.length() > reach {
        return None;
    }
    let facing = -FACING_DEG.to_radians().cos();
    let lands = |(p, out): (&DVec3, &DVec3)| {
        let (q, k) = nearest_on(&b.points, *p + along);
        q.distance(*p + along) <= tolerance && out.dot(b.outwards[k]) <= facing
    };
    a.points.iter().zip(&a.outwards).all(lands).then_some(along)
}

/// Two edges face each other where their outward directions lie more than this far from square (degrees): the
/// samples of a curved edge meet the other edge between its samples, whose directions differ a little.
const FACING_DEG: f64 = 60.0;

/// The point of the polyline `points` nearest to `p`, and the sample nearest to that point.
fn nearest_on(points: &[DVec3], p: DVec3) -> (DVec3, usize) {
    let on_segment = |k: usize| {
        let (a, d) = (points[k], points[k + 1] - points[k]);
        let t = if d.length_squared() > 0.0 { ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0) } else { 0.0 };
        (a + d * t, if t <= 0.5 { k } else { k + 1 })
    };
    let segments = (0..points.len().saturating_sub(1)).map(on_segment);
    segments.chain([(points[0], 0)]).min_by(|x, y| x.0.distance(p).total_cmp(&y.0.distance(p))).expect("a sample")
}

/// Where two bridges between the same two patches meet at a corner, the sides on one patch end at one point v
/// while those on the other stop short of each other and leave a notch: a and b (their ends there) and c, where
/// their lines meet. The quad v, a, c, b fills it, given to the patch whose sides end at v and oriented along its
/// edge's normal (edge, quad, normal). Either patch may be the one: round a pocket's corner (the thinner level
/// inside) the ramps' feet in the thicker patch stop short; round a pad's sloped sides (the thicker level
/// inside, narrower than the hole its footprint leaves in the thinner one) the bridges meet at the pad's
/// corner and the thinner patch's edges run on past them to its own corner. Only where the lines through a and
/// b run apart from the corner (a convex corner: at a reflex one the bridges overlap instead), meeting within
/// the reach of the patch whose sides end at v; not between arcs (a round corner has no notch). `same_point`:
/// two points closer than this are one.
pub fn bridge_corners(bridges: &[StepBridge], edges: &[LooseEdge], same_point: f64) -> Vec<(usize, [DVec3; 4], DVec3)> {
    // A bridge seen from one of its two edges: that edge, the other, the quad with its first side on that edge.
    let views =
        |b: &StepBridge| [(b.owner, b.other, b.quad), (b.other, b.owner, [b.quad[1], b.quad[0], b.quad[3], b.quad[2]])];
    // (corner on the near side, end of the far side, direction along the far side out past that end) at both ends.
    let ends = |quad: &[DVec3; 4]| {
        let along = (quad[2] - quad[1]).normalize_or_zero();
        [(quad[0], quad[1], -along), (quad[3], quad[2], along)]
    };
    let mut out = Vec::new();
    for (i, x) in bridges.iter().enumerate() {
        for y in &bridges[i + 1..] {
            if x.axis.is_some() || y.axis.is_some() {
                continue;
            }
            for (near, far, quad_x) in views(x) {
                // y seen from its edge on the same patch as x's near edge, its far edge on the same patch as x's.
                let same = |(e, f, _): &(usize, usize, [DVec3; 4])| {
                    edges[*e].patch == edges[near].patch && edges[*f].patch == edges[far].patch
                };
                let Some((_, _, quad_y)) = views(y).into_iter().find(same) else {
                    continue;
                };
                let reach = edges[near].reach;
                for (v, a, ua) in ends(&quad_x) {
                    for (w, b, ub) in ends(&quad_y) {
                        if v.distance(w) > same_point || a.distance(b) <= same_point {
                            continue;
                        }
                        let Some(c) = meeting((a, ua), (b, ub), same_point) else { continue };
                        let apart = (c - a).dot(ua) > same_point && (c - b).dot(ub) > same_point;
                        if apart && c.distance(a) <= reach && c.distance(b) <= reach {
                            out.push((near, [v, a, c, b], edges[near].normal));
                        }
                    }
                }
            }
        }
    }
    out
}

/// Where the lines a + s u and b + t v (unit directions) meet, within `tolerance`; None when they are parallel
/// or pass each other farther apart.
fn meeting((a, u): (DVec3, DVec3), (b, v): (DVec3, DVec3), tolerance: f64) -> Option<DVec3> {
    let w = a - b;
    let (p, q, r) = (u.dot(v), u.dot(w), v.dot(w));
    let den = 1.0 - p * p;
    if den <= PARALLEL_LINES {
        return None;
    }
    let s = (p * r - q) / den;
    let (on_a, on_b) = (a + u * s, b + v * (r + p * s));
    (on_a.distance(on_b) <= tolerance).then(|| (on_a + on_b) * 0.5)
}

/// 1 - cos^2 of the angle between two lines under which they are parallel (about 0.06 degrees).
const PARALLEL_LINES: f64 = 1e-6;

/// The bridge between straight edges `thin` and `thick` (indices and courses), with the gap between their lines;
/// `first` is the pair's first edge, which owns a flat or upright bridge.
fn line_bridge(
    edges: &[LooseEdge],
    (thin, a_course): (usize, Course),
    (thick, b_course): (usize, Course),
    first: usize,
    parallel: f64,
) -> Option<(f64, StepBridge)> {
    let Course::Line { start: a, direction: u, length: la } = a_course else { return None };
    let Course::Line { start: b, direction: v, length: lb } = b_course else { return None };
    let (et, ek) = (&edges[thin], &edges[thick]);
    let reach = et.thickness.max(ek.thickness);
    if u.dot(v).abs() < parallel {
        return None;
    }
    // The thick edge's line relative to the thin one's: its offset (level and in-plane gap) and where it starts
    // and ends on u.
    let offset = (b - a).reject_from_normalized(u);
    let gap = offset.length();
    if !bridgeable(et, ek, gap) {
        return None;
    }
    let (level, across) = (offset.dot(et.normal).abs(), offset.dot(et.outward()));
    if level > reach || across.abs() > reach {
        return None;
    }
    let (s0, s1) = shared_stretch((a, u, la), (b, v, lb))?;
    // A ramp ends on a line a run inside the thick edge, on the thick patch: where the patch's course inside
    // the edge is not known (neither flat nor a cylinder about the edge's line), the bridge stays upright.
    let inside = || run_inside(ek, v, RAMP_RUN * et.thickness);
    let ramp = laid_down(et, s1 - s0 >= STEP_SPAN_SHARE * lb && s1 - s0 >= reach, level, across).then(inside).flatten();
    let far = offset + ramp.unwrap_or(DVec3::ZERO);
    let ramp = ramp.is_some();
    let on_a = |s: f64| a + u * s;
    let quad = [on_a(s0), on_a(s0) + far, on_a(s1) + far, on_a(s1)];
    Some((gap, owned(edges, thin, thick, first, ramp, quad, None)))
}

/// The bridge between arcs `thin` and `thick` (indices and courses) about one axis, with the gap between them
/// in the middle of the stretch they share; `first` is the pair's first edge, which owns a flat or upright
/// bridge. The same rules as `line_bridge`, measured in the plane through the axis at that middle, where the two
/// arcs are two points: their offset splits into the level (along the thin patch's normal) and the in-plane gap.
fn arc_bridge(
    edges: &[LooseEdge],
    (thin, a_course): (usize, Course),
    (thick, b_course): (usize, Course),
    first: usize,
    parallel: f64,
) -> Option<(f64, StepBridge)> {
    let Course::Arc { center: ca, axis, radius: ra, from, sweep: sa } = a_course else { return None };
    let Course::Arc { center: cb, axis: axis_b, radius: rb, sweep: sb, .. } = b_course else { return None };
    let (et, ek) = (&edges[thin], &edges[thick]);
    let reach = et.thickness.max(ek.thickness);
    if axis.dot(axis_b).abs() < parallel || (cb - ca).reject_from_normalized(axis).length() > COAXIAL_SHARE * ra.max(rb)
    {
        return None;
    }
    // The thick arc's ends as angles about the thin one's axis, from its start; a whole circle spans it all.
    let (lo, hi) = if sb >= TAU {
        (0.0, sa)
    } else {
        let (first_b, last_b) = (*ek.points.first()?, *ek.points.last()?);
        let (b0, b1) = (angle_about(first_b - ca, axis, from), angle_about(last_b - ca, axis, from));
        (b0.min(b1), b0.max(b1))
    };
    // An arc read across the thin one's start the long way round is no neighbour of it.
    if hi - lo > sb + ARC_SHARE {
        return None;
    }
    let (s0, s1) = (lo.max(0.0), hi.min(sa));
    // No sliver of an arc: a bridge whose ends meet is a whole turn (`stretch_along`).
    if (s1 - s0) <= SHARED_STRETCH_SHARE * sa || s1 - s0 <= ARC_SHARE {
        return None;
    }
    // Directions at angle s: radial, and the thin and thick edges' normals and outward ones turned there from
    // their middle samples (each arc's normal and outward turn with it about the axis).
    let radial = |s: f64| from * s.cos() + axis.cross(from) * s.sin();
    let turned = |vector: DVec3, at: DVec3, s: f64| {
        let angle = angle_about(at - ca, axis, from);
        glam::DQuat::from_axis_angle(axis, s - angle) * vector
    };
    let height_b = (cb - ca).dot(axis);
    let on_a = |s: f64| ca + radial(s) * ra;
    let on_b = |s: f64| ca + axis * height_b + radial(s) * rb;
    let middle = 0.5 * (s0 + s1);
    let (mid_a, mid_b) = (et.points[et.points.len() / 2], ek.points[ek.points.len() / 2]);
    let offset = on_b(middle) - on_a(middle);
    let gap = offset.length();
    if !bridgeable(et, ek, gap) {
        return None;
    }
    let (normal, outward) = (turned(et.normal, mid_a, middle), turned(et.outward(), mid_a, middle));
    let (level, across) = (offset.dot(normal).abs(), offset.dot(outward));
    if level > reach || across.abs() > reach {
        return None;
    }
    let ramp = laid_down(et, s1 - s0 >= STEP_SPAN_SHARE * sb && (s1 - s0) * ra.min(rb) >= reach, level, across);
    let run = if ramp { RAMP_RUN * et.thickness } else { 0.0 };
    let far = |s: f64| on_b(s) - turned(ek.outward(), mid_b, s) * run;
    let quad = [on_a(s0), far(s0), far(s1), on_a(s1)];
    Some((gap, owned(edges, thin, thick, first, ramp, quad, Some([ca, axis]))))
}

/// Gaps in a cylindrical patch's own surface: two straight free edges of one patch (not a freeform one, whose
/// straight edges need not lie on one cylinder with the band between them), both open (their outside in
/// the material), rulings of one cylinder (parallel, their normals square to them and meeting on one axis) whose
/// outward directions face each other across an arc no longer than the patch's joint reach. Another wall
/// crossing a tube off its axis (a rib running into a boss beside its bore) splits the tube's skin into arcs;
/// their offsets stop inside the crossing wall, which may meet the tube's mid-surface on one side only. The
/// tube's mid-surface runs on through the crossing wall, as a plate's runs on under a rib, and the crossing wall
/// joins it there: the band of the cylinder between the two edges over the stretch they share fills the gap, on
/// the patch's own surface, whatever partner the edges' rays found (growing each to it, the two strips would
/// cross each other past it). Each edge is bridged once, nearest pairs first. The quad is
/// [a(s0), a(s1), b(s1), b(s0)] with `axis` turning counter-clockwise from a to b: `_coaxial_band`'s arcs
/// a(s0) -> b(s0) and a(s1) -> b(s1).
pub fn ruling_gaps(edges: &[LooseEdge]) -> Vec<StepBridge> {
    let (_, candidates) = nearest_first(edges, |i, j, courses, parallel| {
        let (ei, ej) = (&edges[i], &edges[j]);
        if ei.patch != ej.patch || ei.freeform || !ei.open || !ej.open {
            return None;
        }
        let (
            Some(Course::Line { start: a, direction: u, length: la }),
            Some(Course::Line { start: b, direction: v, length: lb }),
        ) = (courses[i], courses[j])
        else {
            return None;
        };
        if u.dot(v).abs() < parallel {
            return None;
        }
        // In the plane square to the rulings: b's line relative to a's, and the normals there.
        let d = (b - a).reject_from_normalized(u);
        let (na, nb) = (ei.normal.reject_from_normalized(u), ej.normal.reject_from_normalized(u));
        if na.length() < parallel || nb.length() < parallel {
            return None;
        }
        let (na, nb) = (na.normalize(), nb.normalize());
        // One cylinder: a - r na = b - r nb for one signed radius r.
        let turn = nb - na;
        if turn.length_squared() <= COAXIAL_SHARE * COAXIAL_SHARE {
            return None;
        }
        let r = d.dot(turn) / turn.length_squared();
        if (d - turn * r).length() > COAXIAL_SHARE * r.abs() {
            return None;
        }
        if ei.outward().dot(d) <= 0.0 || ej.outward().dot(d) >= 0.0 {
            return None;
        }
        let center = a - na * r;
        let (from, to) = (a - center, a + d - center);
        let gap = r.abs() * from.angle_between(to);
        if gap > ei.reach.min(ej.reach) {
            return None;
        }
        let (s0, s1) = shared_stretch((a, u, la), (b, v, lb))?;
        let direction = if from.cross(to).dot(u) > 0.0 { u } else { -u };
        let on_a = |s: f64| a + u * s;
        let quad = [on_a(s0), on_a(s1), on_a(s1) + d, on_a(s0) + d];
        Some((gap, StepBridge { owner: i, other: j, quad, normal: ei.normal, axis: Some([center, direction]) }))
    });
    each_edge_once(candidates, vec![false; edges.len()], |b| (b.owner, b.other))
}

/// The edges' courses, and the bridges `find` makes for each pair of edges i < j (given the courses and the
/// cosine of `STEP_PARALLEL_DEG`) with their gaps, nearest first, then by the pair (lower edge first).
fn nearest_first(
    edges: &[LooseEdge],
    find: impl Fn(usize, usize, &[Option<Course>], f64) -> Option<(f64, StepBridge)>,
) -> (Vec<Option<Course>>, Vec<(f64, StepBridge)>) {
    let parallel = STEP_PARALLEL_DEG.to_radians().cos();
    let courses: Vec<Option<Course>> = edges.iter().map(|e| course(&e.points)).collect();
    let mut candidates: Vec<(f64, StepBridge)> = Vec::new();
    for i in 0..edges.len() {
        for j in i + 1..edges.len() {
            candidates.extend(find(i, j, &courses, parallel));
        }
    }
    let key = |b: &StepBridge| (b.owner.min(b.other), b.owner.max(b.other));
    candidates.sort_by(|x, y| x.0.total_cmp(&y.0).then(key(&x.1).cmp(&key(&y.1))));
    (courses, candidates)
}

/// The stretch (from, to, along the first line from its start) two parallel lines (start, unit direction,
/// length) share, None when it is no longer than `SHARED_STRETCH_SHARE` of the first: touching end to end.
fn shared_stretch((a, u, la): (DVec3, DVec3, f64), (b, v, lb): (DVec3, DVec3, f64)) -> Option<(f64, f64)> {
    let (b0, b1) = ((b - a).dot(u), (b - a).dot(u) + lb * u.dot(v).signum());
    let (s0, s1) = (b0.min(b1).max(0.0), b0.max(b1).min(la));
    (s1 - s0 > SHARED_STRETCH_SHARE * la).then_some((s0, s1))
}

/// The middle of a band `ruling_gaps` makes: on its cylinder (about `origin`, unit `direction`), half-way round
/// from a to b and half-way along the stretch.
pub fn band_middle(quad: &[DVec3; 4], origin: DVec3, direction: DVec3) -> DVec3 {
    let height = |p: DVec3| (p - origin).dot(direction);
    let (from, to) =
        ((quad[0] - origin).reject_from_normalized(direction), (quad[3] - origin).reject_from_normalized(direction));
    let turn = angle_about(to, direction, from.normalize()).rem_euclid(TAU);
    let middle = glam::DQuat::from_axis_angle(direction, 0.5 * turn) * from;
    origin + direction * (0.5 * (height(quad[0]) + height(quad[1]))) + middle
}

/// The move from the straight edge `ek` (direction `u`) onto the line `run` inside it along its face: straight
/// into a flat face; about the axis of a cylindrical face whose axis runs along the edge (a boss's wall seen from
/// a rib running into it off its axis, whose mid-plane passes the mid-cylinder: a straight run in the tangent
/// plane would end off the cylinder, and the ramp there joins neither patch); None for any other face. The face
/// is told from its point and normal (`LooseEdge::face`) against the edge's middle sample and normal.
fn run_inside(ek: &LooseEdge, u: DVec3, run: f64) -> Option<DVec3> {
    let [point, normal] = ek.face;
    let (p, n) = (ek.points[ek.points.len() / 2], ek.normal);
    let into = -ek.outward();
    let span = (p - point).length().max(STRAIGHT_FLOOR);
    // The face's normal may be given for either side of it.
    let parallel = n.distance(normal).min(n.distance(-normal)) <= COURSE_SHARE;
    if parallel && (p - point).dot(n).abs() <= COURSE_SHARE * span {
        return Some(into * run);
    }
    if n.dot(u).abs() > COURSE_SHARE || normal.dot(u).abs() > COURSE_SHARE {
        return None;
    }
    // A cylinder about an axis along u: p = c + r n and point = c + r normal, so across u their offset is r
    // times the normals' difference (r < 0 where the normal points to the axis).
    let across = |v: DVec3| v.reject_from_normalized(u);
    let offset = across(p - point);
    let radius = [normal, -normal].into_iter().find_map(|normal| {
        let turn = across(n - normal);
        let r = offset.dot(turn) / turn.length_squared().max(f64::MIN_POSITIVE);
        (turn.length() > COURSE_SHARE && (offset - turn * r).length() <= COURSE_SHARE * span).then_some(r)
    })?;
    let (radial, angle) = (n * radius.signum(), run / radius.abs());
    Some(radius.abs() * (radial * (angle.cos() - 1.0) + into * angle.sin()))
}

/// A face runs on flat, or round a cylinder, inside its edge when its point and normal fit that within this
/// share (of the distance between the point and the edge, for lengths).
const COURSE_SHARE: f64 = 1e-3;

/// Whether the bridge from the thin edge `et` is laid down into a ramp, given its offset to the thick edge along
/// the thin patch's normal (`level`) and outward direction (`across`). A ramp only where the thin edge `spans`
/// the whole thick edge, over at least the larger thickness: the thick patch is cut along a line through it, and
/// a shorter ramp would cut away the rest of that patch's edge, a short one (the corner of a notch) pieces
/// beside the notch, and what joins there. Only a bridge steeper than 45 degrees needs laying down; a flatter
/// one already spans the gap.
fn laid_down(et: &LooseEdge, spans: bool, level: f64, across: f64) -> bool {
    spans && level > STEP_LEVEL_SHARE * et.thickness && level > across
}

/// The bridge `quad` between `thin` and `thick` given to its owner: the thinner edge for a ramp, else the pair's
/// `first` edge (the same quad seen from the other side when that is the thick one).
fn owned(
    edges: &[LooseEdge],
    thin: usize,
    thick: usize,
    first: usize,
    ramp: bool,
    quad: [DVec3; 4],
    axis: Option<[DVec3; 2]>,
) -> StepBridge {
    let (et, ek) = (&edges[thin], &edges[thick]);
    if ramp || thin == first {
        StepBridge { owner: thin, other: thick, quad, normal: if ramp { et.normal } else { et.outward() }, axis }
    } else {
        // A flat or upright bridge joins the first edge's patch: the same quad seen from the other side.
        StepBridge { owner: thick, other: thin, quad: [quad[1], quad[0], quad[3], quad[2]], normal: ek.outward(), axis }
    }
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
