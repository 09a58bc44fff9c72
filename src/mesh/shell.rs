//! The shell mesh: gmsh's elements with the patch of each gmsh surface (matched to midsurf's named faces by
//! geometry), oriented as the patch.

use std::collections::BTreeMap;

use glam::DVec3;
use serde::Serialize;

use super::mesher::{GmshMesh, NamedFace};

/// A shell element: 3 or 4 node indices (counter-clockwise about its normal), its patch and named face.
#[derive(Debug, Clone, PartialEq)]
pub struct Element {
    pub nodes: Vec<usize>,
    /// 1-based patch id (the report's).
    pub patch: usize,
    /// Index of the named face of the mid-surface STEP it meshes.
    pub face: usize,
}

#[derive(Debug, Clone)]
pub struct ShellMesh {
    pub nodes: Vec<DVec3>,
    /// Dimension of the CAD entity each node lies on (0 vertex, 1 curve, 2 surface).
    pub dims: Vec<u8>,
    pub elements: Vec<Element>,
}

/// How the gmsh surfaces found their named faces.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Matching {
    pub surfaces: usize,
    pub matched: usize,
    /// gmsh surfaces whose centroid and area matched no named face within the tolerance: they took the patch
    /// of the face with the nearest centroid.
    pub nearest_only: Vec<i64>,
    /// Named faces no gmsh surface matched.
    pub faces_unmatched: Vec<usize>,
    /// Surfaces whose elements were turned over to follow the face's normal.
    pub flipped: usize,
    /// gmsh surfaces whose face has no "patch <id> t=<thickness>" name: their elements are left out.
    pub without_patch: Vec<i64>,
    /// The named face each gmsh surface (by tag) took.
    #[serde(skip)]
    pub face_of_surface: BTreeMap<i64, usize>,
}

/// Same face read by two kernels: centroids within this share of the part's diagonal...
pub const MATCH_CENTROID_SHARE: f64 = 1e-4;
/// ...and areas within this share of the larger: both integrate the same B-rep, so they agree far closer.
pub const MATCH_AREA_SHARE: f64 = 1e-3;

/// The patch id in a face name `patch <id> t=<thickness>`.
pub fn patch_of_name(name: &str) -> Option<usize> {
    name.strip_prefix("patch ")?.split_whitespace().next()?.parse().ok()
}

pub fn element_normal(nodes: &[DVec3], element: &[usize]) -> DVec3 {
    // Newell's normal: the area vector, exact for a triangle, the mean plane's for a warped quad.
    let mut n = DVec3::ZERO;
    for i in 0..element.len() {
        let a = nodes[element[i]];
        let b = nodes[element[(i + 1) % element.len()]];
        n += a.cross(b);
    }
    n * 0.5
}

pub fn centroid(nodes: &[DVec3], element: &[usize]) -> DVec3 {
    element.iter().map(|&i| nodes[i]).sum::<DVec3>() / element.len() as f64
}

/// Builds the shell mesh from gmsh's reply: each surface takes the patch of its named face and that face's
/// orientation; a surface whose face has no patch name is left out (`Matching::without_patch`).
pub fn assemble(gmsh: &GmshMesh, faces: &[NamedFace]) -> Result<(ShellMesh, Matching), String> {
    let nodes: Vec<DVec3> = gmsh.nodes.iter().map(|p| DVec3::from_array(*p)).collect();
    let (lo, hi) =
        nodes.iter().fold((DVec3::splat(f64::MAX), DVec3::splat(f64::MIN)), |(l, h), p| (l.min(*p), h.max(*p)));
    let diagonal = if nodes.is_empty() { 1.0 } else { (hi - lo).length().max(1e-9) };
    let mut matching = Matching { surfaces: gmsh.surfaces.len(), ..Default::default() };
    let mut used = vec![false; faces.len()];
    let mut face_of = Vec::with_capacity(gmsh.surfaces.len());
    for s in &gmsh.surfaces {
        let c = DVec3::from_array(s.centroid);
        let distance = |f: &NamedFace| (DVec3::from_array(f.centroid) - c).length();
        let area_gap = |f: &NamedFace| (f.area - s.area).abs() / f.area.max(s.area).max(1e-300);
        let best = (0..faces.len())
            .filter(|&i| {
                distance(&faces[i]) <= MATCH_CENTROID_SHARE * diagonal && area_gap(&faces[i]) <= MATCH_AREA_SHARE
            })
            .min_by(|&a, &b| distance(&faces[a]).total_cmp(&distance(&faces[b])).then(a.cmp(&b)));
        let face = match best {
            Some(f) => {
                matching.matched += 1;
                f
            }
            None => {
                matching.nearest_only.push(s.tag);
                (0..faces.len())
                    .min_by(|&a, &b| distance(&faces[a]).total_cmp(&distance(&faces[b])).then(a.cmp(&b)))
                    .ok_or("the mid-surface has no faces")?
            }
        };
        used[face] = true;
        face_of.push(face);
        matching.face_of_surface.insert(s.tag, face);
    }
    matching.faces_unmatched = (0..faces.len()).filter(|&i| !used[i]).collect();

    let mut elements = Vec::new();
    for block in &gmsh.elements {
        let Some(k) = gmsh.surfaces.iter().position(|s| s.tag == block.surface) else {
            return Err(format!("gmsh elements on unknown surface {}", block.surface));
        };
        let face = face_of[k];
        let named = &faces[face];
        let Some(patch) = patch_of_name(&named.name) else {
            // No patch, so no thickness: left out of the decks and named with the unmeshed faces.
            matching.without_patch.push(block.surface);
            continue;
        };
        let mut mine: Vec<Vec<usize>> =
            block.quads.iter().map(|q| q.to_vec()).chain(block.trias.iter().map(|t| t.to_vec())).collect();
        // gmsh orients a surface's elements consistently, but by its own parametrisation: compare the element
        // nearest the face's reference point with the face's normal there, and turn them all over if needed.
        let point = DVec3::from_array(named.point);
        let nearest = mine.iter().min_by(|a, b| {
            (centroid(&nodes, a) - point).length_squared().total_cmp(&(centroid(&nodes, b) - point).length_squared())
        });
        if let Some(e) = nearest {
            if element_normal(&nodes, e).dot(DVec3::from_array(named.normal)) < 0.0 {
                matching.flipped += 1;
                for e in &mut mine {
                    e[1..].reverse();
                }
            }
        }
        elements.extend(mine.into_iter().map(|nodes| Element { nodes, patch, face }));
    }
    Ok((ShellMesh { nodes, dims: gmsh.node_dims.clone(), elements }, matching))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn patch_ids_come_from_the_face_names() {
        assert_eq!(patch_of_name("patch 12 t=2.000"), Some(12));
        assert_eq!(patch_of_name("face 3"), None);
    }
}
