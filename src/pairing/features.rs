//! Small features that would spoil the mid-surface (Sheen et al. 4), recognised on the face graph and
//! suppressed logically: their faces do not pair, and the loops they leave in a wall's skin are filled when
//! the mid-patch is made. Fillets need nothing more: extend-and-stitch bridges the walls they joined.
//!
//! - A fillet or round: a cylinder or torus of radius <= `fillet_max` that did not pair and meets a wall skin
//!   tangentially (a sheet's bend pairs with its other side, a plate's rounded outline corner joins only side
//!   faces: neither is a fillet).
//! - A chamfer: a plane face that did not pair, bevelled at a sharp angle against the two faces along its long
//!   edges (both edges convex, or both concave at a root), one of them a wall skin, no wider than
//!   `fillet_max`: a chamfer is a flat blend. A bevel between the two skins of one wall is that wall's rim
//!   (a thickness face), not a chamfer.
//! - A hole: an inner loop of a skin whose edges are all convex, opening onto coaxial concave cylinders of
//!   one radius, diameter <= `hole_max`.
//! - A boss, protrusion or tab: an inner loop of a skin whose edges are all concave (the CLoop of Lu, Gadh &
//!   Tautges), opening onto faces that stay within a box of diagonal <= `boss_max` (a hole through it
//!   included) and that hold no wall: a protrusion with both skins of a wall among its faces (a hollow
//!   screw boss, a tab) standing out of the skin at least as far as the skin's wall is thick is a wall
//!   standing on that wall and keeps its mid-patch.
//!
//! The region behind a loop is flooded over face adjacency, never back into the skin holding the loop and
//! never into a face larger than the limit: a through hole's region stops at the opposite skin, whose loop
//! becomes part of the same feature.

use std::collections::BTreeSet;

use glam::DVec3;
use serde::Serialize;

use crate::model::face_graph::{Convexity, EdgeId, Face, FaceGraph, FaceId, Surface};
use crate::pairing::{FaceRole, Side};

/// Size limits of the features to suppress, in mm.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Limits {
    /// Largest fillet or round radius, and largest chamfer width.
    pub fillet_max: f64,
    /// Largest hole diameter.
    pub hole_max: f64,
    /// Largest box diagonal of a boss, protrusion or tab.
    pub boss_max: f64,
    /// Keep every hole (CAE models that need bolt holes meshed).
    pub keep_holes: bool,
}

/// The user's limits; None means the default relative to the wall-thickness limit.
#[derive(Debug, Clone, Copy, Default)]
pub struct LimitArgs {
    pub fillet_max: Option<f64>,
    pub hole_max: Option<f64>,
    pub boss_max: Option<f64>,
    pub keep_holes: bool,
}

impl LimitArgs {
    /// Defaults from t_max: a fillet up to 2 t is a blend a shell model does without (bends pair and are
    /// kept whatever their radius); a hole no wider than the wall is thick barely changes the wall's
    /// stiffness and is smaller than any shell element around it (larger ones are usually bolt or
    /// weight-saving holes the model keeps); a boss up to 4 t across is a standoff or a locating pin, not a
    /// wall.
    pub fn resolve(self, t_max: f64) -> Limits {
        Limits {
            fillet_max: self.fillet_max.unwrap_or(2.0 * t_max),
            hole_max: self.hole_max.unwrap_or(t_max),
            boss_max: self.boss_max.unwrap_or(4.0 * t_max),
            keep_holes: self.keep_holes,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FeatureKind {
    Fillet,
    Chamfer,
    Hole,
    Boss,
}

impl FeatureKind {
    pub fn name(self) -> &'static str {
        match self {
            FeatureKind::Fillet => "fillet",
            FeatureKind::Chamfer => "chamfer",
            FeatureKind::Hole => "hole",
            FeatureKind::Boss => "boss",
        }
    }

    /// What its size measures.
    pub fn size_name(self) -> &'static str {
        match self {
            FeatureKind::Fillet => "radius",
            FeatureKind::Chamfer => "width",
            FeatureKind::Hole => "diameter",
            FeatureKind::Boss => "box diagonal",
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Feature {
    pub kind: FeatureKind,
    /// Its faces, sorted.
    pub faces: Vec<FaceId>,
    /// Fillet radius, chamfer width, hole diameter or boss box diagonal (mm).
    pub size: f64,
    /// Edges between the feature and the skins around it: the loops to fill in the mid-patches.
    #[serde(skip)]
    pub fill: Vec<EdgeId>,
}

fn is_skin(role: &FaceRole) -> bool {
    matches!(role, FaceRole::Pair { .. })
}

/// The faces behind an inner loop of `base`: flooded from the loop over adjacency, not into `base` and not
/// into a face whose box diagonal exceeds `limit`. None when the region is larger than `limit` or reaches
/// more than `MAX_FACES` faces (a loop opening onto the rest of the part).
fn region_behind(graph: &FaceGraph, base: FaceId, lp: &[EdgeId], limit: f64) -> Option<BTreeSet<FaceId>> {
    const MAX_FACES: usize = 64;
    let small = |f: FaceId| graph.faces[f].bbox.diagonal() <= limit;
    let mut region: BTreeSet<FaceId> = BTreeSet::new();
    let mut queue: Vec<FaceId> = lp.iter().flat_map(|&e| graph.across(e, base)).collect();
    while let Some(f) = queue.pop() {
        if f == base || region.contains(&f) || !small(f) {
            continue;
        }
        region.insert(f);
        if region.len() > MAX_FACES {
            return None;
        }
        for lp in &graph.faces[f].loops {
            queue.extend(lp.iter().flat_map(|&e| graph.across(e, f)));
        }
    }
    (!region.is_empty() && diagonal(graph, &region) <= limit).then_some(region)
}

/// Both skins of one wall lie in `region`: the protrusion may be a wall standing on the skin (a hollow screw
/// boss's tube, a tab), which a shell model keeps, not a solid standoff or pin whose material has no
/// mid-surface of its own (see `stands_clear`).
fn holds_wall(roles: &[FaceRole], region: &BTreeSet<FaceId>) -> bool {
    let side_of = |f: &FaceId| match roles[*f] {
        FaceRole::Pair { group, side } => Some((group, side)),
        _ => None,
    };
    let sides: Vec<(usize, Side)> = region.iter().filter_map(side_of).collect();
    sides.iter().any(|&(group, side)| sides.iter().any(|&(g, s)| g == group && s != side))
}

/// `region` stands at least as far out of the planar skin `base` (along its outward normal: a bore running on
/// through the wall does not count) as that skin's wall is thick. A protrusion lower than the wall it stands
/// on (a ring round a hole, a short collar) is a local thickening of that wall, not a wall: its mid-patch,
/// reaching down to the wall's middle, would lie a third or more inside the wall. A curved skin has no plane
/// to measure from: the protrusion counts as standing clear.
fn stands_clear(
    graph: &FaceGraph,
    base: FaceId,
    roles: &[FaceRole],
    thickness: &[f64],
    region: &BTreeSet<FaceId>,
) -> bool {
    let Some((skin, wall)) = planar_skin(graph, base, roles, thickness) else { return true };
    region_reach(graph, region, skin, skin.normal) >= wall
}

/// The bore `region` behind a loop of the planar skin `base` runs on past the skin's wall at least as far
/// again as the wall is thick (its extent along the skin's normal is twice the wall's thickness or more): the
/// bore of a boss or tube standing on the wall (a screw boss over a through hole), whose tube keeps its
/// mid-patch, not a hole in the wall. A shorter bore (a hole through the wall, countersunk or with a low collar
/// round it) is the wall's hole. A curved skin has no plane to measure from: its bores are its holes.
fn runs_on(graph: &FaceGraph, base: FaceId, roles: &[FaceRole], thickness: &[f64], region: &BTreeSet<FaceId>) -> bool {
    let Some((skin, wall)) = planar_skin(graph, base, roles, thickness) else { return false };
    region_reach(graph, region, skin, skin.normal) + region_reach(graph, region, skin, -skin.normal) >= 2.0 * wall
}

/// `base` and its wall's thickness when it is a planar skin of a wall.
fn planar_skin<'a>(
    graph: &'a FaceGraph,
    base: FaceId,
    roles: &[FaceRole],
    thickness: &[f64],
) -> Option<(&'a Face, f64)> {
    let skin = &graph.faces[base];
    match (&skin.surface, &roles[base]) {
        (Surface::Plane { .. }, FaceRole::Pair { group, .. }) => Some((skin, thickness[*group])),
        _ => None,
    }
}

/// How far the faces of `region` reach from the plane of `skin` along `normal` (0 at least).
fn region_reach(graph: &FaceGraph, region: &BTreeSet<FaceId>, skin: &Face, normal: DVec3) -> f64 {
    region.iter().map(|&f| graph.reach(f, skin.point, normal)).fold(0.0, f64::max)
}

fn diagonal(graph: &FaceGraph, faces: &BTreeSet<FaceId>) -> f64 {
    let min = faces.iter().fold(DVec3::INFINITY, |m, &f| m.min(graph.faces[f].bbox.min));
    let max = faces.iter().fold(DVec3::NEG_INFINITY, |m, &f| m.max(graph.faces[f].bbox.max));
    (max - min).length()
}

/// Edges between the region and the faces outside it, sorted.
fn boundary(graph: &FaceGraph, region: &BTreeSet<FaceId>) -> Vec<EdgeId> {
    let mut out: Vec<EdgeId> = region
        .iter()
        .flat_map(|&f| graph.faces[f].loops.iter().flatten().copied())
        .filter(|&e| graph.edges[e].faces.iter().any(|g| !region.contains(g)))
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// The diameter of a region made only of concave cylinders sharing one axis and radius (a hole's wall,
/// often split in halves), or None.
fn hole_diameter(graph: &FaceGraph, region: &BTreeSet<FaceId>, tolerance: f64) -> Option<f64> {
    let mut first: Option<(DVec3, DVec3, f64)> = None;
    for &f in region {
        let Surface::Cylinder { origin, axis, radius, convex: false } = graph.faces[f].surface else {
            return None;
        };
        match first {
            None => first = Some((origin, axis, radius)),
            Some((o, a, r)) => {
                let off_axis = (origin - o).reject_from_normalized(a).length();
                if (radius - r).abs() > tolerance || off_axis > tolerance || a.cross(axis).length() > SAME_AXIS_SINE {
                    return None;
                }
            }
        }
    }
    first.map(|(_, _, r)| 2.0 * r)
}

/// How far (degrees) the faces at a bevel's edge turn: under 10 degrees is a tangent blend or a facet, over 80 a
/// square rim or step.
pub const BEVEL_TURN_DEG: std::ops::RangeInclusive<f64> = 10.0..=80.0;

/// The width of plane `face` if it is a chamfer: a plane whose two longest edges are bevels of one kind (both
/// convex or both concave, each turning by BEVEL degrees) onto two different faces, at least one a wall skin
/// and not the two sides of one wall. The width is the area over the mean length of the two edges (exact for
/// the trapezoid of a mitred chamfer).
fn chamfer_width(graph: &FaceGraph, roles: &[FaceRole], face: FaceId) -> Option<f64> {
    let f = &graph.faces[face];
    let mut edges: Vec<EdgeId> = f.loops.iter().flatten().copied().collect();
    edges.sort_by(|&a, &b| graph.edges[b].length.total_cmp(&graph.edges[a].length).then(a.cmp(&b)));
    let [a, b, ..] = edges[..] else { return None };
    let neighbour = |e: EdgeId| {
        let edge = &graph.edges[e];
        let turn = edge.angle.abs().to_degrees();
        let other = graph.across(e, face).next()?;
        (BEVEL_TURN_DEG.contains(&turn) && edge.faces.len() == 2).then_some((other, edge.convexity))
    };
    let ((fa, ca), (fb, cb)) = (neighbour(a)?, neighbour(b)?);
    let one_wall = match (&roles[fa], &roles[fb]) {
        (FaceRole::Pair { group: ga, side: sa }, FaceRole::Pair { group: gb, side: sb }) => ga == gb && sa != sb,
        _ => false,
    };
    let bevel = matches!(ca, Convexity::Convex | Convexity::Concave) && ca == cb;
    if fa == fb || one_wall || !bevel || !(is_skin(&roles[fa]) || is_skin(&roles[fb])) {
        return None;
    }
    Some(2.0 * f.area / (graph.edges[a].length + graph.edges[b].length))
}

/// Every small feature of a solid, given the roles of a first pairing with all faces pairable. `tolerance`
/// says when two radii or axes are the same. Sorted by kind, then faces.
/// Two bores' axes are parallel when the sine between them is under this: the faces of one drilled hole share
/// their axis exactly, up to the float noise of the STEP file.
const SAME_AXIS_SINE: f64 = 1e-6;

/// `thickness[g]`: the mean thickness of pair group g.
pub fn recognise(
    graph: &FaceGraph,
    roles: &[FaceRole],
    thickness: &[f64],
    limits: &Limits,
    tolerance: f64,
) -> Vec<Feature> {
    let mut features: Vec<Feature> = Vec::new();
    let mut taken: BTreeSet<FaceId> = BTreeSet::new();
    let flood_limit = limits.boss_max.max(limits.hole_max);
    for face in &graph.faces {
        if !is_skin(&roles[face.id]) {
            continue;
        }
        for lp in face.loops.iter().skip(1) {
            let all = |c: Convexity| lp.iter().all(|&e| graph.edges[e].convexity == c);
            let (protrusion, depression) = (all(Convexity::Concave), all(Convexity::Convex));
            if !protrusion && !depression {
                continue;
            }
            let Some(region) = region_behind(graph, face.id, lp, flood_limit) else { continue };
            if region.iter().any(|f| taken.contains(f)) {
                continue; // found already from the other end of a through hole
            }
            let feature = if protrusion {
                let size = diagonal(graph, &region);
                let wall = holds_wall(roles, &region) && stands_clear(graph, face.id, roles, thickness, &region);
                (size <= limits.boss_max && !wall).then_some((FeatureKind::Boss, size))
            } else {
                hole_diameter(graph, &region, tolerance)
                    .filter(|&d| d <= limits.hole_max && !limits.keep_holes)
                    .filter(|_| !runs_on(graph, face.id, roles, thickness, &region))
                    .map(|d| (FeatureKind::Hole, d))
            };
            if let Some((kind, size)) = feature {
                taken.extend(region.iter().copied());
                let fill = boundary(graph, &region);
                features.push(Feature { kind, faces: region.into_iter().collect(), size, fill });
            }
        }
    }
    // Blends: a fillet is a cylinder or torus, a chamfer a plane, so one look at each face left.
    for face in &graph.faces {
        if taken.contains(&face.id) || is_skin(&roles[face.id]) {
            continue;
        }
        let (kind, size) = match face.surface {
            Surface::Cylinder { radius, .. } | Surface::Torus { minor_radius: radius, .. } => {
                let tangent_to_skin = face.loops.iter().flatten().any(|&e| {
                    graph.edges[e].convexity == Convexity::Smooth
                        && graph.across(e, face.id).any(|g| is_skin(&roles[g]))
                });
                if !tangent_to_skin {
                    continue;
                }
                (FeatureKind::Fillet, radius)
            }
            Surface::Plane { .. } => match chamfer_width(graph, roles, face.id) {
                Some(width) => (FeatureKind::Chamfer, width),
                None => continue,
            },
            _ => continue,
        };
        if size <= limits.fillet_max {
            features.push(Feature { kind, faces: vec![face.id], size, fill: Vec::new() });
        }
    }
    features.sort_by(|a, b| a.kind.cmp(&b.kind).then(a.faces.cmp(&b.faces)));
    features
}

/// Which faces may pair: all but the features'.
pub fn pairable(faces: usize, features: &[Feature]) -> Vec<bool> {
    let mut out = vec![true; faces];
    for f in features.iter().flat_map(|x| &x.faces) {
        out[*f] = false;
    }
    out
}

#[cfg(test)]
#[path = "features_tests.rs"]
mod tests;
