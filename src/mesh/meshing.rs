//! How gmsh's meshing went, told per named face: whether the whole model meshed at once, which faces were
//! meshed on their own afterwards and how, and which could not be meshed at all (left out of the decks).

use serde::Serialize;

use super::mesher::{GmshMesh, NamedFace};
use super::shell::{patch_of_name, Matching};

#[derive(Debug, Clone, Serialize)]
pub struct Meshing {
    /// "meshed", or why the whole model did not mesh at once.
    pub whole_model: String,
    /// Faces meshed one by one after that.
    pub retried: Vec<RetriedFace>,
    /// The first errors gmsh logged.
    pub gmsh_errors: Vec<String>,
    /// "fixed": gmsh ran without address space randomisation, so a rerun gives the same mesh; "random": it
    /// could not (personality(2) refused), and a few models mesh one of two ways.
    pub address_layout: String,
}

#[derive(Debug, Clone, Serialize)]
pub struct RetriedFace {
    pub patch: Option<usize>,
    /// Index of the mid-surface STEP face (0-based, file order).
    pub face: usize,
    pub how: String,
}

/// A face of the mid-surface with no element in the decks.
#[derive(Debug, Clone, Serialize)]
pub struct UnmeshedFace {
    pub patch: Option<usize>,
    pub face: usize,
    /// The face's area (mm²), as the STEP gives it.
    pub area: f64,
    pub why: String,
}

/// The meshing account of `gmsh`'s reply, by named face (as `matching` matched them); a face without a patch
/// name counts as unmeshed, as its elements were left out.
pub fn account(gmsh: &GmshMesh, faces: &[NamedFace], matching: &Matching) -> (Meshing, Vec<UnmeshedFace>) {
    let face = |tag: i64| matching.face_of_surface.get(&tag).copied();
    let patch = |f: usize| patch_of_name(&faces[f].name);
    let retried = gmsh
        .retried
        .iter()
        .filter_map(|r| face(r.surface).map(|f| RetriedFace { patch: patch(f), face: f, how: r.how.clone() }))
        .collect();
    let mut unmeshed: Vec<UnmeshedFace> = gmsh
        .unmeshed
        .iter()
        .filter_map(|u| {
            face(u.surface).map(|f| UnmeshedFace { patch: patch(f), face: f, area: faces[f].area, why: u.why.clone() })
        })
        .collect();
    unmeshed.extend(matching.without_patch.iter().filter_map(|&tag| {
        face(tag).map(|f| UnmeshedFace {
            patch: None,
            face: f,
            area: faces[f].area,
            why: format!("named {:?}, not \"patch <id> t=<thickness>\": no thickness", faces[f].name),
        })
    }));
    unmeshed.sort_by_key(|u| u.face);
    let meshing = Meshing {
        whole_model: gmsh.whole_model.clone(),
        retried,
        gmsh_errors: gmsh.gmsh_errors.clone(),
        address_layout: gmsh.address_layout.clone(),
    };
    (meshing, unmeshed)
}
