//! Failure isolation: what the kernel could not describe is left out and said, so that one awkward face or
//! solid never sinks a whole part. The warnings name the solid and face and carry the kernel's reason.

use crate::kernel::protocol::EntityProblem;
use crate::load::Part;
use crate::model::warning::Warning;
use crate::pairing::driver::{pair_solid, PairingParams, SolidPairing};

/// Pairs every solid of the part; a solid whose pairing panics (a bug, but one solid's) is moved to the
/// part's skipped solids with the panic's message, and the others go on.
pub fn pair_solids(part: &mut Part, params: PairingParams) -> Vec<SolidPairing> {
    let solids = std::mem::take(&mut part.solids);
    let mut pairings = Vec::with_capacity(solids.len());
    for (i, solid) in solids.into_iter().enumerate() {
        let graph = &solid.graph;
        match std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| pair_solid(graph, params))) {
            Ok(pairing) => {
                pairings.push(pairing);
                part.solids.push(solid);
            }
            Err(panic) => {
                let why = panic
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| panic.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "unknown".to_string());
                part.skipped.push((i + 1, format!("internal error while pairing its faces: {why}")));
            }
        }
    }
    pairings
}

/// The solids of the file left out because the kernel could not describe them.
pub fn skipped_solid_warnings(part: &Part) -> Vec<Warning> {
    part.skipped
        .iter()
        .map(|(number, why)| Warning {
            code: "solid_failed",
            message: format!("solid {number} of the file is left out: {why}"),
            solid: None,
            faces: Vec::new(),
        })
        .collect()
}

/// One warning for the entities the reader failed on that the shape does not use.
pub fn entity_warning(part: &Part) -> Option<Warning> {
    let problems = &part.entity_problems;
    (!problems.is_empty()).then(|| Warning {
        code: "step_syntax",
        message: format!(
            "the STEP reader failed on {} entit{} ({}); the solids were read all the same",
            problems.len(),
            if problems.len() == 1 { "y" } else { "ies" },
            problems
                .iter()
                .map(|p| format!(
                    "{}{}: {}",
                    entity_name(p),
                    if p.used { ", referred to by others" } else { "" },
                    p.message
                ))
                .collect::<Vec<_>>()
                .join("; ")
        ),
        solid: None,
        faces: Vec::new(),
    })
}

fn entity_name(p: &EntityProblem) -> String {
    p.entity.map_or_else(|| "(file header)".to_string(), |n| format!("#{n}"))
}

#[cfg(test)]
mod tests {
    use crate::model::face_graph::FaceGraph;
    use crate::model::face_graph::Surface;
    use crate::pairing::driver::undescribed_face_warnings;
    use crate::synthetic;
    use glam::DVec3;

    #[test]
    fn a_face_the_kernel_could_not_describe_is_named_with_its_reason() {
        let mut face = synthetic::rect(DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z);
        face.problem = Some("BRepMesh produced no triangulation for this face".into());
        let graph = FaceGraph {
            faces: vec![face],
            edges: vec![],
            vertices: vec![],
            volume: 0.0,
            area: 1.0,
            bbox: crate::model::face_graph::Bbox { min: DVec3::ZERO, max: DVec3::ONE },
        };
        let w = undescribed_face_warnings(3, &graph);
        assert_eq!(w.len(), 1);
        assert_eq!((w[0].code, w[0].solid, w[0].faces.clone()), ("face_not_described", Some(3), vec![0]));
        assert!(w[0].message.contains("no triangulation"), "{}", w[0].message);
        assert!(matches!(graph.faces[0].surface, Surface::Plane { .. }));
        // Left out of pairing: it is no candidate, not even of itself with a twin.
        let mut twin = graph.faces[0].clone();
        twin.id = 1;
        twin.problem = None;
        let mut two = graph.clone();
        two.faces.push(twin);
        assert!(crate::pairing::candidates::candidate_pairs(&two, 1.0).is_empty());
    }
}
