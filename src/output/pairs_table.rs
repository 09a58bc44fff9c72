//! The table `midsurf pairs` prints for each solid: its pair groups, roles, suppressed features, unpaired faces.

use std::fmt::Write;

use crate::model::face_graph::FaceGraph;
use crate::output::report::RoleCounts;
use crate::pairing::driver::SolidPairing;
use crate::pairing::{self};

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
