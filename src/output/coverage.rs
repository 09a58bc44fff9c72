//! The report's coverage of every thin-walled solid by the mid-surface written (geom::coverage), measured on a
//! mesh of the shells as written: the patches of the solid's body count (a partition's solids share them).

use crate::geom::coverage::{self, Coverage, Triangles};
use crate::geom::inside::SolidMesh;
use crate::kernel::protocol::{FaceMeshes, Request};
use crate::kernel::{Kernel, SidecarError};
use crate::load::Part;
use crate::model::face_graph::Mesh;
use crate::model::shapes::{Fused, Shells};
use crate::model::warning::Warning;
use crate::pairing::driver::SolidPairing;
use crate::patch::make::Made;

/// A solid with more than this share of its volume out of reach of every patch gets a warning.
const UNCOVERED_WARN: f64 = 0.05;
/// Faces the warning names, the most missed first.
const NAMED_IN_WARNING: usize = 5;

/// What the coverage is measured on: the part and its pairing, the patches made, and the shells written of
/// their fused pieces (`body_of_solid`: the body of each solid, whose patches count for all its solids).
#[derive(Clone, Copy)]
pub struct Written<'a> {
    pub part: &'a Part,
    pub pairings: &'a [SolidPairing],
    pub made: &'a [Made],
    pub fused: &'a Fused,
    pub shells: &'a Shells,
    pub body_of_solid: &'a [usize],
}

/// Per solid (as `part.solids`): its coverage, None for a solid that is not thin-walled; and the warnings: a
/// solid with much of its material out of reach, or no figure at all when the kernel failed to mesh the shells
/// (whether the op failed or the sidecar stopped answering): the mid-surface is written by then, and a check
/// is never a reason to lose it.
pub fn measure<K: Kernel>(kernel: &mut K, written: &Written) -> (Vec<Option<Coverage>>, Vec<Warning>) {
    match per_solid(kernel, written) {
        Ok(coverage) => {
            let warnings = warnings(&coverage);
            (coverage, warnings)
        }
        Err(e) => {
            let warning = Warning {
                code: "coverage_not_measured",
                message: format!(
                    "the coverage of the solids by the mid-surface was not measured: the kernel could not mesh the \
                     mid-surface ({})",
                    crate::error::one_line(&e.to_string())
                ),
                solid: None,
                faces: Vec::new(),
            };
            (vec![None; written.part.solids.len()], vec![warning])
        }
    }
}

fn per_solid<K: Kernel>(kernel: &mut K, written: &Written) -> Result<Vec<Option<Coverage>>, SidecarError> {
    let Written { part, pairings, made, fused, shells, body_of_solid } = *written;
    let thin = |i: usize| pairings[i].class.is_thin_walled();
    let mesh_tolerance = (0..part.solids.len())
        .filter(|&i| thin(i))
        .map(|i| part.solids[i].mesh_tolerance)
        .fold(f64::INFINITY, f64::min);
    let meshed: Option<FaceMeshes> = if shells.faces.is_empty() || !mesh_tolerance.is_finite() {
        None
    } else {
        Some(kernel.call(&Request::Mesh { handle: shells.handle, mesh_tolerance })?)
    };
    // Per face of the shells (the meshes keep their order): its patch.
    let patch_of = |j: usize| fused.faces[shells.faces[j]].patch;
    // A patch placed on a skin (--position) lies `to_mid` from its wall's middle: its reach grows by as much.
    let reach: Vec<f64> = made.iter().map(|m| coverage::reach(m.plan.thickness.mean) + m.plan.to_mid.abs()).collect();
    let measured = part.solids.iter().enumerate().map(|(i, solid)| {
        if !thin(i) {
            return None;
        }
        let body = body_of_solid[i];
        let own = |j: usize| body_of_solid[made[patch_of(j)].solid - 1] == body;
        let patches = Triangles::new(
            meshed
                .iter()
                .flat_map(|m| m.faces.iter().enumerate())
                .filter(|(j, _)| own(*j))
                .flat_map(|(j, m)| triangles(Some(m), patch_of(j))),
        );
        let faces = Triangles::new(solid.graph.faces.iter().flat_map(|f| triangles(f.mesh.as_ref(), f.id)));
        let samples = coverage::material_samples(&SolidMesh::of_faces(solid.graph.faces.iter())?);
        coverage::coverage(&samples, &patches, &reach, &faces)
    });
    Ok(measured.collect())
}

/// The warnings of solids (1-based as reported) with much of their material out of reach of every patch.
fn warnings(coverage: &[Option<Coverage>]) -> Vec<Warning> {
    let low = coverage.iter().enumerate().filter_map(|(i, c)| c.as_ref().map(|c| (i + 1, c)));
    low.filter(|(_, c)| 1.0 - c.share > UNCOVERED_WARN)
        .map(|(solid, c)| {
            let named: Vec<String> = c
                .missed
                .iter()
                .take(NAMED_IN_WARNING)
                .map(|m| format!("face {} ({:.1}%)", m.face, 100.0 * m.share))
                .collect();
            Warning {
                code: "material_uncovered",
                message: format!(
                    "solid {solid}: {:.1}% of its material lies out of reach of every patch (more than {:.2} x the \
                     patch's thickness away); most of it near {}",
                    100.0 * (1.0 - c.share),
                    coverage::REACH_SHARE,
                    named.join(", ")
                ),
                solid: Some(solid),
                faces: c.missed.iter().take(NAMED_IN_WARNING).map(|m| m.face).collect(),
            }
        })
        .collect()
}

fn triangles(mesh: Option<&Mesh>, tag: usize) -> impl Iterator<Item = ([glam::DVec3; 3], usize)> + '_ {
    mesh.into_iter().flat_map(move |m| m.triangles.iter().map(move |t| (t.map(|i| m.vertices[i as usize]), tag)))
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::kernel::fake::FakeKernel;
    use crate::load::Solid;
    use crate::model::shapes::FusedFace;
    use crate::pairing::driver::{pair_solid, PairingParams};
    use crate::pairing::features::LimitArgs;

    #[test]
    fn a_kernel_that_cannot_mesh_the_mid_surface_costs_the_figure_not_the_run() {
        let graph = crate::synthetic::cuboid(DVec3::ZERO, DVec3::new(100.0, 60.0, 2.0));
        let pairing =
            pair_solid(&graph, PairingParams { t_max: None, draft_max_deg: 3.0, limits: LimitArgs::default() });
        let part = Part {
            solids: vec![Solid { handle: 1, graph, mesh_tolerance: 0.1 }],
            skipped: vec![],
            entity_problems: vec![],
        };
        let face = FusedFace {
            patch: 0,
            area: 6000.0,
            centroid: DVec3::ZERO,
            point: DVec3::ZERO,
            normal: DVec3::Z,
            edges: vec![],
        };
        let fused = Fused { handle: 2, faces: vec![face], edges: vec![], invalid: vec![] };
        let shells = Shells {
            handle: 3,
            count: 1,
            components: 1,
            faces: vec![0],
            valid: true,
            invalid: vec![],
            edges: 4,
            vertices: 4,
            free_edges: 4,
            nonmanifold_edges: 0,
        };
        let mut kernel = FakeKernel::new(vec![
            serde_json::json!({"error": {"code": "kernel_failed", "message": "BRepMesh failed"}}),
        ]);
        let written = Written {
            part: &part,
            pairings: &[pairing],
            made: &[],
            fused: &fused,
            shells: &shells,
            body_of_solid: &[0],
        };
        let (coverage, warnings) = measure(&mut kernel, &written);
        assert_eq!(kernel.ops(), ["mesh"]);
        assert_eq!(coverage, vec![None]);
        assert_eq!(warnings.len(), 1);
        assert_eq!(warnings[0].code, "coverage_not_measured");
        assert!(warnings[0].message.contains("BRepMesh failed"), "{}", warnings[0].message);
    }
}
