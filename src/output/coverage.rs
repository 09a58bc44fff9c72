//! The report's coverage of every thin-walled solid by the mid-surface written (geom::coverage), measured on a
//! mesh of the shells as written: the patches of the solid's body count (a partition's solids share them).

use crate::geom::coverage::{self, Coverage, Triangles};
use crate::geom::inside::SolidMesh;
use crate::kernel::protocol::Request;
use crate::kernel::{Kernel, SidecarError};
use crate::load::Part;
use crate::model::face_graph::{Face, FaceGraph};
use crate::model::shapes::{Fused, Shells};
use crate::model::warning::Warning;
use crate::pairing::driver::SolidPairing;
use crate::patch::make::Made;

/// A solid with more than this share of its volume out of reach of every patch gets a warning.
const UNCOVERED_WARN: f64 = 0.05;
/// Faces the warning names, the most missed first.
const NAMED_IN_WARNING: usize = 5;

/// Per solid (as `part.solids`): its coverage, None for a solid that is not thin-walled. All None when the
/// kernel cannot mesh the shells (an op error); a kernel that stops answering is an error.
pub fn per_solid<K: Kernel>(
    kernel: &mut K,
    part: &Part,
    pairings: &[SolidPairing],
    made: &[Made],
    fused: &Fused,
    shells: &Shells,
    body_of_solid: &[usize],
) -> Result<Vec<Option<Coverage>>, SidecarError> {
    let thin = |i: usize| pairings[i].class.is_thin_walled();
    let mesh_tolerance = (0..part.solids.len())
        .filter(|&i| thin(i))
        .map(|i| part.solids[i].mesh_tolerance)
        .fold(f64::INFINITY, f64::min);
    let written: Option<FaceGraph> = if shells.faces.is_empty() || !mesh_tolerance.is_finite() {
        None
    } else {
        let request = Request::Describe { handle: shells.handle, mesh: true, mesh_tolerance };
        match kernel.call(&request) {
            Ok(graph) => Some(graph),
            Err(e) if e.code().is_some() => return Ok(vec![None; part.solids.len()]),
            Err(e) => return Err(e),
        }
    };
    // Per face of the shells (the describe keeps their order): its patch.
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
            written.iter().flat_map(|g| g.faces.iter()).filter(|f| own(f.id)).flat_map(|f| tagged(f, patch_of(f.id))),
        );
        let faces = Triangles::new(solid.graph.faces.iter().flat_map(|f| tagged(f, f.id)));
        let samples = coverage::material_samples(&SolidMesh::of_faces(solid.graph.faces.iter())?);
        coverage::coverage(&samples, &patches, &reach, &faces)
    });
    Ok(measured.collect())
}

/// The warnings of solids (1-based as reported) with much of their material out of reach of every patch.
pub fn warnings(coverage: &[Option<Coverage>]) -> Vec<Warning> {
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

fn tagged(face: &Face, tag: usize) -> impl Iterator<Item = ([glam::DVec3; 3], usize)> + '_ {
    face.mesh.iter().flat_map(move |m| m.triangles.iter().map(move |t| (t.map(|i| m.vertices[i as usize]), tag)))
}
