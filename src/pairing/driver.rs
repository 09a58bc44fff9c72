//! The pairing stage: every solid of a part paired with its parameters (t_max estimate, tolerances, a first
//! pairing, the small features it reveals, a second pairing without them, the junction loops to fill).

use serde::Serialize;

use crate::model::face_graph::{EdgeId, FaceGraph, FaceId, Surface};
use crate::model::tolerance::Tolerances;
use crate::model::warning::Warning;
use crate::pairing::estimate::{estimate_t_max, TMaxEstimate};
use crate::pairing::features::{self, Feature, LimitArgs, Limits};
use crate::pairing::wall_class::{classify, WallClass};
use crate::pairing::{self, FaceRole, NearMiss, Pairing, Rejection};

/// What the user asked for; None means "estimate from the part".
#[derive(Debug, Clone, Copy)]
pub struct PairingParams {
    pub t_max: Option<f64>,
    pub draft_max_deg: f64,
    pub limits: LimitArgs,
}

#[derive(Debug, Clone, Serialize)]
pub struct SolidPairing {
    /// Thin-walled or not (chunky): a solid that is not thin-walled is not paired and gets no patch.
    pub class: WallClass,
    /// Where t_max came from: "user" or the estimate's method.
    pub t_max_source: String,
    pub estimate: TMaxEstimate,
    pub tolerances: Tolerances,
    /// Size limits of the small features (user values or defaults from t_max).
    pub limits: Limits,
    /// The small features suppressed: their faces did not pair.
    pub features: Vec<Feature>,
    /// The edges of the junction loops (`junction_loops`), sorted.
    #[serde(skip)]
    pub junction: Vec<EdgeId>,
    pub pairing: Pairing,
    /// Share of the solid's area on paired faces.
    pub paired_share: f64,
    /// Share of the skins' area on paired faces. Skins are the faces a mid-surface replaces: all faces but
    /// thickness faces and the rounds (radius <= t_max) that only connect walls.
    pub paired_skin_share: f64,
}

impl SolidPairing {
    /// Widest uncovered band between covered pieces a clipped mid-patch keeps (see `Tolerances::clip_narrow`):
    /// under a crossing wall the band also spans the suppressed blends at the wall's root, up to twice the
    /// largest fillet radius or chamfer width (a chamfer's footprint is no wider than the chamfer).
    pub fn clip_narrow(&self) -> f64 {
        self.tolerances.clip_narrow + 2.0 * self.blend_size()
    }

    /// Widest uncovered piece at a dead end that the mid-patch of `faces` (its reference faces and their
    /// partners) keeps when clipped: a corner's overshoot spans the blends there, so only blends touching
    /// those faces count (`beside`: see [`Self::blends_beside`]). Blends elsewhere say nothing about this
    /// patch: a 5 mm round on a block's corner must not keep a slot end's patch lying over the block.
    pub fn clip_narrow_end(&self, beside: &[f64], faces: &[FaceId]) -> f64 {
        self.tolerances.clip_narrow + 2.0 * faces.iter().map(|&f| beside[f]).fold(0.0, f64::max)
    }

    /// Per face, the largest fillet radius or chamfer width among the suppressed blends next to it (0 for none):
    /// worked out once per solid for every patch's [`Self::clip_narrow_end`].
    pub fn blends_beside(&self, graph: &FaceGraph) -> Vec<f64> {
        let mut beside = vec![0.0_f64; graph.faces.len()];
        for blend in self.blends() {
            for &b in &blend.faces {
                graph.neighbours(b).into_iter().for_each(|n| beside[n] = beside[n].max(blend.size));
            }
        }
        beside
    }

    /// The largest fillet radius or chamfer width among the suppressed blends, 0 for none.
    fn blend_size(&self) -> f64 {
        self.blends().map(|f| f.size).fold(0.0, f64::max)
    }

    fn blends(&self) -> impl Iterator<Item = &Feature> {
        self.features
            .iter()
            .filter(|f| matches!(f.kind, features::FeatureKind::Fillet | features::FeatureKind::Chamfer))
    }

    /// The edges whose loops the mid-patches fill (every suppressed hole's and boss's, and every junction
    /// loop's: see [`junction_loops`]), sorted.
    pub fn fill_edges(&self) -> Vec<EdgeId> {
        let mut fill: Vec<EdgeId> = self.features.iter().flat_map(|f| f.fill.iter().copied()).collect();
        fill.extend(&self.junction);
        fill.sort_unstable();
        fill.dedup();
        fill
    }

    /// What the pairing of solid `solid` (1-based) could not do: faces with no partner, groups whose faces pair
    /// with faces of their own side.
    pub fn warnings(&self, solid: usize, graph: &FaceGraph) -> Vec<Warning> {
        // A face the kernel could not describe is said once, with the kernel's reason, not as unpaired.
        let mut out = undescribed_face_warnings(solid, graph);
        for (f, role) in self.pairing.roles.iter().enumerate() {
            // A minor level is no missing wall: its wall's patch runs on past it (`criteria::minor_level`).
            let minor = matches!(
                role,
                FaceRole::Unpaired { near_miss: Some(NearMiss { rejection: Rejection::MinorLevel { .. }, .. }) }
            );
            if let Some(why) = role.unpaired_reason().filter(|_| graph.faces[f].problem.is_none() && !minor) {
                out.push(Warning {
                    code: "unpaired_face",
                    message: format!(
                        "face {f} ({}, {:.3} mm2) has no partner: {why}",
                        graph.faces[f].surface.kind_name(),
                        graph.faces[f].area
                    ),
                    solid: Some(solid),
                    faces: vec![f],
                });
            }
        }
        for g in &self.pairing.groups {
            if !g.side_conflicts.is_empty() {
                out.push(Warning {
                    code: "side_conflict",
                    message: format!("group {}: faces pair with faces of their own side", g.id),
                    solid: Some(solid),
                    faces: g.side_conflicts.clone(),
                });
            }
        }
        out
    }
}

/// The edges of the inner loops of wall skins where another wall runs in: a branch pipe entering a main one
/// leaves a hole in each skin of the main, bounded by the branch's skins. Offset, that hole is wider than
/// the branch's mid-surface (the outer skin's hole by the branch's outer radius): no strip grown from its
/// edge along a tangent follows the main's curved surface to the branch. Filled, the main's patch runs
/// through and the branch meets it as a T; the piece across the branch's bore lies outside the material and
/// is trimmed (`trim::outside_material`). A loop qualifies when every face across it is a skin of another
/// wall or a suppressed blend at the junction, at least one the former; a hole's loop borders its bore. Only
/// on curved skins: a strip grown along a plane stays on it.
///
/// Returns the loops' edges, sorted. Not yet: a hole across a tube's seam, which is no inner loop (the hole's
/// edges join the outline between the two pieces of the seam); its edges are joined as before, by strips from
/// both sides.
pub fn junction_loops(graph: &FaceGraph, roles: &[FaceRole]) -> Vec<EdgeId> {
    let mut out = Vec::new();
    for face in &graph.faces {
        let FaceRole::Pair { group, .. } = roles[face.id] else { continue };
        if face.surface.is_plane() {
            continue; // a strip along a plane stays on it: the hole's edges are joined from both sides
        }
        let wall = |h: usize| matches!(roles[h], FaceRole::Pair { group: k, .. } if k != group);
        let blend = |h: usize| matches!(roles[h], FaceRole::Suppressed);
        let joins = |e: &EdgeId| {
            let mut others = graph.across(*e, face.id).peekable();
            others.peek().is_some() && others.all(|h| wall(h) || blend(h))
        };
        for lp in face.loops.iter().skip(1) {
            if lp.iter().all(joins) && lp.iter().any(|&e| graph.across(e, face.id).any(wall)) {
                out.extend(lp.iter().copied());
            }
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}

/// Pairs one solid: a first pairing with every face gives the roles the feature recognition needs (a fillet
/// is a round that did not pair), then the features' faces are left out and the solid is paired again, from
/// the same tested candidates.
pub fn pair_solid(graph: &FaceGraph, params: PairingParams) -> SolidPairing {
    let draft_max = params.draft_max_deg.to_radians();
    let class = classify(graph);
    if !class.is_thin_walled() {
        return not_paired(graph, params, class);
    }
    let estimate = estimate_t_max(graph, draft_max);
    let (t_max, t_max_source) = match params.t_max {
        Some(t) => (t, "user (--t-max)".to_string()),
        None => (estimate.t_max, format!("estimated: {}", estimate.method)),
    };
    let mut tolerances = Tolerances::new(graph.bbox.diagonal(), t_max, draft_max);
    if params.t_max.is_none() {
        // The estimate is the part's gauges; a wall thicker than those is still a wall when it is thin for its
        // width. A t_max the user gives is a hard limit.
        tolerances.t_bound = estimate.search_bound.max(t_max);
    }
    let limits = params.limits.resolve(t_max);
    let tested = pairing::test_candidates(graph, &tolerances);
    let first = pairing::assemble(graph, &tested, &vec![true; graph.faces.len()], &tolerances);
    let thickness: Vec<f64> = first.groups.iter().map(|g| g.thickness.mean).collect();
    let features = features::recognise(graph, &first.roles, &thickness, &limits, tolerances.coaxial);
    let pairing = if features.is_empty() {
        first
    } else {
        pairing::assemble(graph, &tested, &features::pairable(graph.faces.len(), &features), &tolerances)
    };
    let area_with = |keep: &dyn Fn(&FaceRole) -> bool| -> f64 {
        graph.faces.iter().filter(|f| keep(&pairing.roles[f.id])).map(|f| f.area).sum()
    };
    let paired = area_with(&|r| matches!(r, FaceRole::Pair { .. }));
    let skins: f64 = graph
        .faces
        .iter()
        .filter(|f| match pairing.roles[f.id] {
            FaceRole::Thickness { .. } => false,
            FaceRole::Connecting { .. } => !is_small_round(&f.surface, t_max),
            _ => true,
        })
        .map(|f| f.area)
        .sum();
    let junction = junction_loops(graph, &pairing.roles);
    SolidPairing {
        class,
        t_max_source,
        estimate,
        tolerances,
        limits,
        features,
        junction,
        paired_share: if graph.area > 0.0 { paired / graph.area } else { 0.0 },
        paired_skin_share: if skins > 0.0 { paired / skins } else { 0.0 },
        pairing,
    }
}

/// A solid that is not thin-walled: no candidate is tested, every face is left out of pairing (role
/// suppressed), and no patch is made of it.
fn not_paired(graph: &FaceGraph, params: PairingParams, class: WallClass) -> SolidPairing {
    let t_max = params.t_max.unwrap_or(class.thickness);
    let tolerances = Tolerances::new(graph.bbox.diagonal(), t_max, params.draft_max_deg.to_radians());
    let estimate = TMaxEstimate {
        t_max,
        dominant: None,
        clusters: Vec::new(),
        method: format!("not paired, {}", class.describe()),
        search_bound: t_max,
    };
    let pairable = vec![false; graph.faces.len()];
    SolidPairing {
        class,
        t_max_source: estimate.method.clone(),
        estimate,
        tolerances,
        limits: params.limits.resolve(t_max),
        features: Vec::new(),
        junction: Vec::new(),
        pairing: pairing::assemble(graph, &[], &pairable, &tolerances),
        paired_share: 0.0,
        paired_skin_share: 0.0,
    }
}

/// Pairs every solid of a part.
pub fn pair_part(part: &crate::load::Part, params: PairingParams) -> Vec<SolidPairing> {
    part.solids.iter().map(|s| pair_solid(&s.graph, params)).collect()
}

/// A fillet or round: a cylinder, torus or sphere whose (minor) radius is within the wall thickness.
fn is_small_round(surface: &Surface, t_max: f64) -> bool {
    match *surface {
        Surface::Cylinder { radius, .. } | Surface::Sphere { radius, .. } => radius <= t_max,
        Surface::Torus { minor_radius, .. } => minor_radius <= t_max,
        _ => false,
    }
}

/// The faces of one solid the kernel could not describe whole: never paired, bridged by the joints if they
/// lie between walls.
pub fn undescribed_face_warnings(solid: usize, graph: &FaceGraph) -> Vec<Warning> {
    graph
        .faces
        .iter()
        .filter_map(|f| {
            f.problem.as_ref().map(|why| Warning {
                code: "face_not_described",
                message: format!(
                    "face {} ({}, {:.3} mm2) is left out of pairing: {why}",
                    f.id,
                    f.surface.kind_name(),
                    f.area
                ),
                solid: Some(solid),
                faces: vec![f.id],
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::face_graph::Convexity;
    use crate::pairing::Side;
    use crate::synthetic::{cuboid, cylinder, graph, rect};
    use glam::DVec3;

    #[test]
    fn a_loop_where_another_wall_runs_in_is_filled_a_hole_is_not() {
        let square = || rect(DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z);
        // Face 0: a main pipe's skin (group 0); 1: a branch's skin (group 1); 2: a hole's bore (thickness of
        // group 0); 3: a suppressed blend.
        let c = Convexity::Concave;
        let pipe = cylinder(DVec3::ZERO, 20.0, (0.0, std::f64::consts::TAU), 100.0, true);
        let adjacent = [(0, 1, c), (0, 1, c), (0, 2, c), (0, 3, c), (0, 1, c), (0, 3, c)];
        let mut g = graph(vec![pipe, square(), square(), square()], &adjacent);
        // Loops of face 0: its outline (no edges here), the branch's (0, 1), a hole's (2), a blend's alone (3),
        // the branch's through a blend at the junction (4, 5).
        g.faces[0].loops = vec![vec![], vec![0, 1], vec![2], vec![3], vec![4, 5]];
        let roles = vec![
            FaceRole::Pair { group: 0, side: Side::A },
            FaceRole::Pair { group: 1, side: Side::A },
            FaceRole::Thickness { group: 0 },
            FaceRole::Suppressed,
        ];
        assert_eq!(junction_loops(&g, &roles), vec![0, 1, 4, 5]);
        // The same loops on a face of the branch's own group: no other wall runs in.
        let own =
            vec![FaceRole::Pair { group: 1, side: Side::B }, roles[1].clone(), roles[2].clone(), roles[3].clone()];
        assert_eq!(junction_loops(&g, &own), Vec::<EdgeId>::new());
        // On a flat skin a strip grown from the loop stays on the plane: nothing to fill.
        let loops = g.faces[0].loops.clone();
        g.faces[0] = square();
        g.faces[0].loops = loops;
        assert_eq!(junction_loops(&g, &roles), Vec::<EdgeId>::new());
    }

    #[test]
    fn a_dead_end_keeps_only_as_much_as_the_blends_touching_its_patch_span() {
        // A 100 x 100 x 2 plate (faces 4 and 5 pair). Blends set by hand on two faces of it: face 1 (+x) touches
        // every face but face 0 (-x), face 2 (-y) every face but face 3.
        let g = cuboid(DVec3::ZERO, DVec3::new(100.0, 100.0, 2.0));
        let params = PairingParams { t_max: Some(3.0), draft_max_deg: 3.0, limits: LimitArgs::default() };
        let mut sp = pair_solid(&g, params);
        let blend = |face: FaceId, size: f64| Feature {
            kind: features::FeatureKind::Fillet,
            faces: vec![face],
            size,
            fill: vec![],
        };
        sp.features = vec![blend(1, 5.0), blend(2, 0.5)];
        // A band between covered pieces may span any blend of the part, a dead end only the blends beside it.
        assert_eq!(sp.clip_narrow(), 3.0 + 2.0 * 5.0);
        let beside = sp.blends_beside(&g);
        assert_eq!(sp.clip_narrow_end(&beside, &[0]), 3.0 + 2.0 * 0.5);
        assert_eq!(sp.clip_narrow_end(&beside, &[0, 3]), 3.0 + 2.0 * 5.0);
        assert_eq!(sp.clip_narrow_end(&beside, &[]), 3.0, "no face, no blend beside it");
    }
}
