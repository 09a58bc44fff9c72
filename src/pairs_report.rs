//! Pairing of every solid of a part with its parameters, and `midsurf pairs`'s table.

use std::fmt::Write;

use serde::Serialize;

use crate::face_graph::{EdgeId, FaceGraph, Surface};
use crate::features::{self, Feature, LimitArgs, Limits};
use crate::pairing::estimate::{estimate_t_max, TMaxEstimate};
use crate::pairing::{self, FaceRole, Pairing};
use crate::tolerance::Tolerances;

/// What the user asked for; None means "estimate from the part".
#[derive(Debug, Clone, Copy)]
pub struct PairingParams {
    pub t_max: Option<f64>,
    pub draft_max_deg: f64,
    pub limits: LimitArgs,
}

#[derive(Debug, Clone, Serialize)]
pub struct SolidPairing {
    /// Where t_max came from: "user" or the estimate's method.
    pub t_max_source: String,
    pub estimate: TMaxEstimate,
    pub tolerances: Tolerances,
    /// Size limits of the small features (user values or defaults from t_max).
    pub limits: Limits,
    /// The small features suppressed: their faces did not pair.
    pub features: Vec<Feature>,
    pub pairing: Pairing,
    /// Share of the solid's area on paired faces.
    pub paired_share: f64,
    /// Share of the skins' area on paired faces. Skins are the faces a mid-surface replaces: all faces but
    /// thickness faces and the rounds (radius <= t_max) that only connect walls.
    pub paired_skin_share: f64,
}

impl SolidPairing {
    /// Widest uncovered band a clipped mid-patch keeps (see `Tolerances::clip_narrow`): under a crossing wall
    /// the band also spans the suppressed blends at the wall's root, up to twice the largest fillet radius or
    /// chamfer width (a chamfer's footprint is no wider than the chamfer).
    pub fn clip_narrow(&self) -> f64 {
        let fillet = self
            .features
            .iter()
            .filter(|f| matches!(f.kind, features::FeatureKind::Fillet | features::FeatureKind::Chamfer))
            .map(|f| f.size)
            .fold(0.0, f64::max);
        self.tolerances.clip_narrow + 2.0 * fillet
    }

    /// The edges whose loops the mid-patches fill (every suppressed hole's and boss's), sorted.
    pub fn fill_edges(&self) -> Vec<EdgeId> {
        let mut fill: Vec<EdgeId> = self.features.iter().flat_map(|f| f.fill.iter().copied()).collect();
        fill.sort_unstable();
        fill.dedup();
        fill
    }
}

/// Pairs one solid: a first pairing with every face gives the roles the feature recognition needs (a fillet
/// is a round that did not pair), then the features' faces are left out and the solid is paired again, from
/// the same tested candidates.
pub fn pair_solid(graph: &FaceGraph, params: PairingParams) -> SolidPairing {
    let draft_max = params.draft_max_deg.to_radians();
    let estimate = estimate_t_max(graph, draft_max);
    let (t_max, t_max_source) = match params.t_max {
        Some(t) => (t, "user (--t-max)".to_string()),
        None => (estimate.t_max, format!("estimated: {}", estimate.method)),
    };
    let tolerances = Tolerances::new(graph.bbox.diagonal(), t_max, draft_max);
    let limits = params.limits.resolve(t_max);
    let tested = pairing::test_candidates(graph, &tolerances);
    let first = pairing::assemble(graph, &tested, &vec![true; graph.faces.len()]);
    let features = features::recognise(graph, &first.roles, &limits, tolerances.coaxial);
    let pairing = if features.is_empty() {
        first
    } else {
        pairing::assemble(graph, &tested, &features::pairable(graph.faces.len(), &features))
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
    SolidPairing {
        t_max_source,
        estimate,
        tolerances,
        limits,
        features,
        paired_share: if graph.area > 0.0 { paired / graph.area } else { 0.0 },
        paired_skin_share: if skins > 0.0 { paired / skins } else { 0.0 },
        pairing,
    }
}

/// Pairs every solid of a part.
pub fn pair_part(part: &crate::part::Part, params: PairingParams) -> Vec<SolidPairing> {
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

fn faces_list(ids: &[usize]) -> String {
    const SHOWN: usize = 8;
    let mut s: Vec<String> = ids.iter().take(SHOWN).map(|i| i.to_string()).collect();
    if ids.len() > SHOWN {
        s.push(format!("... ({} faces)", ids.len()));
    }
    s.join(",")
}

/// The table `midsurf pairs` prints for one solid.
pub fn render(out: &mut String, index: usize, graph: &FaceGraph, sp: &SolidPairing) {
    let p = &sp.pairing;
    writeln!(
        out,
        "solid {}: {} faces; t_max {:.4} mm ({}); draft_max {:.2} deg",
        index + 1,
        graph.faces.len(),
        sp.tolerances.t_max,
        sp.t_max_source,
        sp.tolerances.draft_max.to_degrees()
    )
    .unwrap();
    writeln!(
        out,
        "  {:>5}  {:<11}  {:>9}  {:>19}  {:>12}  side A / side B (* = reference)",
        "group", "kind", "t mean", "t range", "overlap mm2"
    )
    .unwrap();
    for g in &p.groups {
        let star = |side: pairing::Side| if g.reference == side { "*" } else { "" };
        writeln!(
            out,
            "  {:>5}  {:<11}  {:>9.4}  {:>9.4}..{:<9.4}  {:>12.2}  {}{} / {}{}{}",
            g.id,
            g.kind.name(),
            g.thickness.mean,
            g.thickness.min,
            g.thickness.max,
            g.overlap_area,
            star(pairing::Side::A),
            faces_list(&g.sides[0]),
            star(pairing::Side::B),
            faces_list(&g.sides[1]),
            if g.side_conflicts.is_empty() {
                String::new()
            } else {
                format!("  side conflicts {:?}", g.side_conflicts)
            }
        )
        .unwrap();
    }
    let counts = crate::report::RoleCounts::of(&p.roles);
    writeln!(
        out,
        "  roles: pair {}, thickness {}, connecting {}, suppressed {}, unpaired {}",
        counts.pair, counts.thickness, counts.connecting, counts.suppressed, counts.unpaired
    )
    .unwrap();
    for f in &sp.features {
        let (kind, what) = (f.kind.name(), f.kind.size_name());
        writeln!(out, "  suppressed {kind} faces {} ({what} {:.2} mm)", faces_list(&f.faces), f.size).unwrap();
    }
    for (f, role) in p.roles.iter().enumerate() {
        let Some(why) = role.unpaired_reason() else {
            continue;
        };
        let face = &graph.faces[f];
        writeln!(out, "  unpaired face {f} ({}, {:.2} mm2): {why}", face.surface.kind_name(), face.area).unwrap();
    }
    writeln!(
        out,
        "  paired: {:.1}% of the area, {:.1}% of the skins (all faces but thickness faces and connecting rounds)",
        sp.paired_share * 100.0,
        sp.paired_skin_share * 100.0
    )
    .unwrap();
}
