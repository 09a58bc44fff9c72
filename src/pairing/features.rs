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
//!   included).
//!
//! The region behind a loop is flooded over face adjacency, never back into the skin holding the loop and
//! never into a face larger than the limit: a through hole's region stops at the opposite skin, whose loop
//! becomes part of the same feature.

use std::collections::BTreeSet;

use glam::DVec3;
use serde::Serialize;

use crate::model::face_graph::{Convexity, EdgeId, FaceGraph, FaceId, Surface};
use crate::pairing::FaceRole;

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
                if (radius - r).abs() > tolerance || off_axis > tolerance || a.cross(axis).length() > 1e-6 {
                    return None;
                }
            }
        }
    }
    first.map(|(_, _, r)| 2.0 * r)
}

/// The width of plane `face` if it is a chamfer: a plane whose two longest edges are bevels of one kind (both
/// convex or both concave, each turning by BEVEL degrees) onto two different faces, at least one a wall skin
/// and not the two sides of one wall. The width is the area over the mean length of the two edges (exact for
/// the trapezoid of a mitred chamfer).
fn chamfer_width(graph: &FaceGraph, roles: &[FaceRole], face: FaceId) -> Option<f64> {
    /// A turn under 10 degrees is a tangent blend or a facet, one over 80 a square rim or step.
    const BEVEL: std::ops::RangeInclusive<f64> = 10.0..=80.0;
    let f = &graph.faces[face];
    let mut edges: Vec<EdgeId> = f.loops.iter().flatten().copied().collect();
    edges.sort_by(|&a, &b| graph.edges[b].length.total_cmp(&graph.edges[a].length).then(a.cmp(&b)));
    let [a, b, ..] = edges[..] else { return None };
    let neighbour = |e: EdgeId| {
        let edge = &graph.edges[e];
        let turn = edge.angle.abs().to_degrees();
        let other = graph.across(e, face).next()?;
        (BEVEL.contains(&turn) && edge.faces.len() == 2).then_some((other, edge.convexity))
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
pub fn recognise(graph: &FaceGraph, roles: &[FaceRole], limits: &Limits, tolerance: f64) -> Vec<Feature> {
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
                (size <= limits.boss_max).then_some((FeatureKind::Boss, size))
            } else {
                hole_diameter(graph, &region, tolerance)
                    .filter(|&d| d <= limits.hole_max && !limits.keep_holes)
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
mod tests {
    use super::*;
    use crate::model::face_graph::Edge;
    use crate::pairing::Side;
    use crate::synthetic;

    /// A plate skin (0) with one inner loop of two edges onto faces 1 and 2, and an opposite skin (3) with
    /// one inner loop onto the same faces when `through`.
    fn plate_with(inner: [Surface; 2], convexity: Convexity, through: bool) -> (FaceGraph, Vec<FaceRole>) {
        let skin = |z: f64, n: DVec3| synthetic::rect(DVec3::new(0.0, 0.0, z), DVec3::X * 100.0, DVec3::Y * 60.0, n);
        let small = |s: Surface| {
            let mut f = synthetic::rect(DVec3::new(20.0, 20.0, 0.0), DVec3::X * 6.0, DVec3::Z * 3.0, DVec3::Y);
            f.surface = s;
            f
        };
        let [s1, s2] = inner;
        let mut g = synthetic::graph(vec![skin(3.0, DVec3::Z), small(s1), small(s2), skin(0.0, -DVec3::Z)], &[]);
        let edge = |id: usize, faces: Vec<usize>, convexity| Edge {
            id,
            vertices: [0, 0],
            faces,
            convexity,
            angle: 0.0,
            length: 10.0,
            curve: "circle".into(),
            midpoint: DVec3::ZERO,
        };
        g.edges = vec![
            edge(0, vec![0, 1], convexity),
            edge(1, vec![0, 2], convexity),
            edge(2, vec![1, 3], convexity),
            edge(3, vec![2, 3], convexity),
            edge(4, vec![1, 2], Convexity::Smooth),
            edge(5, vec![1, 2], Convexity::Smooth),
        ];
        g.faces[0].loops = vec![vec![], vec![0, 1]];
        g.faces[1].loops = vec![if through { vec![0, 4, 2, 5] } else { vec![0, 2, 3] }];
        g.faces[2].loops = vec![if through { vec![1, 5, 3, 4] } else { vec![1, 3, 2] }];
        g.faces[3].loops = if through { vec![vec![], vec![2, 3]] } else { vec![vec![]] };
        if !through {
            g.edges.truncate(2);
            g.edges.extend([edge(2, vec![1, 2], Convexity::Smooth), edge(3, vec![1, 2], Convexity::Smooth)]);
        }
        let pair = |side| FaceRole::Pair { group: 0, side };
        let roles =
            vec![pair(Side::A), FaceRole::Thickness { group: 0 }, FaceRole::Thickness { group: 0 }, pair(Side::B)];
        (g, roles)
    }

    fn hole_half() -> Surface {
        Surface::Cylinder { origin: DVec3::new(23.0, 23.0, 0.0), axis: DVec3::Z, radius: 3.0, convex: false }
    }

    fn limits(keep_holes: bool) -> Limits {
        LimitArgs { keep_holes, ..LimitArgs::default() }.resolve(8.0)
    }

    #[test]
    fn a_small_through_hole_is_one_feature_with_both_skin_loops_to_fill() {
        let (g, roles) = plate_with([hole_half(), hole_half()], Convexity::Convex, true);
        let found = recognise(&g, &roles, &limits(false), 1e-3);
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!((found[0].kind, found[0].faces.clone(), found[0].size), (FeatureKind::Hole, vec![1, 2], 6.0));
        assert_eq!(found[0].fill, vec![0, 1, 2, 3]);
        assert_eq!(pairable(4, &found), vec![true, false, false, true]);
    }

    #[test]
    fn large_or_kept_holes_stay() {
        let (g, roles) = plate_with([hole_half(), hole_half()], Convexity::Convex, true);
        assert!(recognise(&g, &roles, &limits(true), 1e-3).is_empty(), "--keep-holes");
        let tight = Limits { hole_max: 5.0, ..limits(false) };
        assert!(recognise(&g, &roles, &tight, 1e-3).is_empty(), "6 mm over a 5 mm limit");
    }

    #[test]
    fn a_protrusion_behind_a_concave_loop_is_a_boss() {
        let side = Surface::Cylinder { origin: DVec3::new(23.0, 23.0, 0.0), axis: DVec3::Z, radius: 3.0, convex: true };
        let (g, roles) =
            plate_with([side, Surface::Plane { origin: DVec3::ZERO, normal: DVec3::Z }], Convexity::Concave, false);
        let found = recognise(&g, &roles, &limits(false), 1e-3);
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!((found[0].kind, found[0].faces.clone()), (FeatureKind::Boss, vec![1, 2]));
        assert_eq!(found[0].fill, vec![0, 1]);
        let small = Limits { boss_max: 6.5, ..limits(false) };
        assert!(recognise(&g, &roles, &small, 1e-3).is_empty(), "its box is 6 x 0 x 3: diagonal 6.7");
    }

    /// A plate rim: top skin 0, bottom skin 1 (one wall), rim face 2, and a plane face 3 between the top
    /// skin and the rim face along two 60 mm edges turning `turn` degrees (convex), 2 mm wide.
    fn rim_with_bevel(turn: f64, onto_bottom: bool) -> (FaceGraph, Vec<FaceRole>) {
        let rect = |o: DVec3, u: DVec3, v: DVec3, n: DVec3| synthetic::rect(o, u, v, n);
        let faces = vec![
            rect(DVec3::ZERO, DVec3::X * 100.0, DVec3::Y * 60.0, DVec3::Z),
            rect(DVec3::ZERO, DVec3::X * 100.0, DVec3::Y * 60.0, -DVec3::Z),
            rect(DVec3::ZERO, DVec3::Z * 2.0, DVec3::Y * 60.0, -DVec3::X),
            rect(DVec3::ZERO, DVec3::X * 2.0, DVec3::Y * 60.0, DVec3::Z),
        ];
        let mut g = synthetic::graph(faces, &[]);
        let edge = |id: usize, faces: Vec<usize>, length: f64| Edge {
            id,
            vertices: [0, 0],
            faces,
            convexity: Convexity::Convex,
            angle: turn.to_radians(),
            length,
            curve: "line".into(),
            midpoint: DVec3::ZERO,
        };
        let far = if onto_bottom { 1 } else { 2 };
        g.edges = vec![edge(0, vec![3, 0], 60.0), edge(1, vec![3, far], 60.0), edge(2, vec![3, 2], 2.0)];
        g.faces[3].loops = vec![vec![0, 2, 1, 2]];
        g.faces[3].area = 120.0;
        let roles = vec![
            FaceRole::Pair { group: 0, side: Side::A },
            FaceRole::Pair { group: 0, side: Side::B },
            FaceRole::Thickness { group: 0 },
            FaceRole::Thickness { group: 0 },
        ];
        (g, roles)
    }

    #[test]
    fn a_narrow_bevel_between_a_skin_and_a_rim_is_a_chamfer() {
        let (g, roles) = rim_with_bevel(45.0, false);
        let found = recognise(&g, &roles, &limits(false), 1e-3);
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!((found[0].kind, found[0].faces.clone(), found[0].size), (FeatureKind::Chamfer, vec![3], 2.0));
        let narrow = Limits { fillet_max: 1.9, ..limits(false) };
        assert!(recognise(&g, &roles, &narrow, 1e-3).is_empty(), "2 mm wide over a 1.9 mm limit");
    }

    #[test]
    fn square_rims_tangent_facets_and_bevelled_wall_ends_are_no_chamfers() {
        for turn in [90.0, 5.0] {
            let (g, roles) = rim_with_bevel(turn, false);
            assert!(recognise(&g, &roles, &limits(false), 1e-3).is_empty(), "turning {turn} degrees");
        }
        // Between the two skins of one wall the bevel is the wall's rim.
        let (g, roles) = rim_with_bevel(45.0, true);
        assert!(recognise(&g, &roles, &limits(false), 1e-3).is_empty());
    }

    #[test]
    fn a_mixed_loop_is_no_feature() {
        let (mut g, roles) = plate_with([hole_half(), hole_half()], Convexity::Convex, true);
        // One edge of each skin loop concave: neither a hole nor a boss from either side.
        g.edges[1].convexity = Convexity::Concave;
        g.edges[3].convexity = Convexity::Concave;
        assert!(recognise(&g, &roles, &limits(false), 1e-3).is_empty());
    }
}
