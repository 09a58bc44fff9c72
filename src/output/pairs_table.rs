//! The table `midsurf pairs` prints for each solid: its pair groups, roles, suppressed features, unpaired faces.

use std::fmt::Write;

use crate::model::face_graph::FaceGraph;
use crate::output::report::RoleCounts;
use crate::pairing::driver::SolidPairing;
use crate::pairing::{self, FaceRole};

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
    if !sp.class.is_thin_walled() {
        writeln!(out, "solid {}: {} faces; {}; no patch", index + 1, graph.faces.len(), sp.class.describe()).unwrap();
        return;
    }
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
    let counts = RoleCounts::of(&p.roles);
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
        // A face the kernel could not describe never reached the pair tests: its reason is the kernel's.
        let why = face.problem.as_ref().map_or(why, |p| format!("not described by the kernel: {p}"));
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

/// Every candidate partner of `face` with the pair tests' verdict, then the face's role in the end.
pub fn explain(graph: &FaceGraph, sp: &SolidPairing, face: usize) -> String {
    let describe = |f: usize| {
        let g = &graph.faces[f];
        let [length, width] = graph.face_size(f);
        format!("face {f} ({}, {:.2} mm2, about {length:.2} x {width:.2} mm)", g.surface.kind_name(), g.area)
    };
    let mut out = format!("{}\n", describe(face));
    if !sp.class.is_thin_walled() {
        writeln!(out, "  not paired: {}", sp.class.describe()).unwrap();
        return out;
    }
    let tol = &sp.tolerances;
    write!(out, "  t_max {:.4} mm", tol.t_max).unwrap();
    if tol.t_bound > tol.t_max {
        write!(out, "; thicker walls up to {:.4} mm when thin for their extent", tol.t_bound).unwrap();
    }
    out.push('\n');
    let tested = pairing::test_candidates(graph, tol);
    let mine: Vec<_> = tested.iter().filter(|(a, b, _)| *a == face || *b == face).collect();
    if mine.is_empty() {
        writeln!(out, "  no candidate: no face within {:.4} mm faces it", tol.t_bound).unwrap();
    }
    // Faces of another kind or turned away say little: counted, not listed.
    let (mine, turned): (Vec<_>, Vec<_>) = mine.into_iter().partition(|(_, _, verdict)| {
        !matches!(verdict, Err(pairing::Rejection::Incompatible { .. } | pairing::Rejection::Angle { .. }))
    });
    if !turned.is_empty() {
        writeln!(out, "  {} candidate(s) of another surface kind or turned too far from opposite", turned.len())
            .unwrap();
    }
    for (a, b, verdict) in mine {
        let other = if *a == face { *b } else { *a };
        let verdict = match verdict {
            Ok(p) => format!(
                "pair ({}, t {:.4}, {:.4}..{:.4}, overlap {:.2} mm2)",
                p.kind.name(),
                p.thickness.mean,
                p.thickness.min,
                p.thickness.max,
                p.overlap_area
            ),
            Err(r) => format!("rejected: {}", r.describe()),
        };
        writeln!(out, "  with {}: {verdict}", describe(other)).unwrap();
    }
    let role = &sp.pairing.roles[face];
    let kept: Vec<String> =
        sp.pairing.pairs.iter().filter(|p| p.faces.contains(&face)).map(|p| p.other(face).to_string()).collect();
    let role = match role {
        FaceRole::Pair { group, .. } => format!("pair, group {group}, with faces {}", kept.join(", ")),
        FaceRole::Thickness { group } => format!("thickness face of group {group}"),
        FaceRole::Connecting { groups, near_miss } => format!(
            "connecting groups {groups:?}{}",
            near_miss.as_ref().map_or(String::new(), |m| format!(
                "; nearest miss face {}: {}",
                m.candidate,
                m.rejection.describe()
            ))
        ),
        FaceRole::Suppressed => "suppressed (a small feature, left out of pairing)".to_string(),
        FaceRole::Unpaired { .. } => format!("unpaired: {}", role.unpaired_reason().unwrap_or_default()),
    };
    writeln!(out, "  in the end: {role}").unwrap();
    out
}
