//! The patch plan (Sheen et al. 5.2): which faces make each mid-patch and where they go.
//!
//! A patch is made from the reference side of a pair group (the side with the larger area, so fewer patches
//! need extending): offset by half the thickness into the material, or for a draft pair projected onto the
//! exact bisector plane of the two faces. Reference faces whose own pairs have different thicknesses (a
//! thickness step) get separate patches, each at its own mid-plane.

use glam::DVec3;
use serde::Serialize;

use crate::face_graph::{FaceGraph, FaceId, Surface};
use crate::pairing::{Pair, PairKind, Pairing, Thickness};
use crate::sidecar::protocol::Placement;

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PatchPlan {
    /// Index of the pair group the patch comes from.
    pub group: usize,
    pub kind: PairKind,
    /// Reference faces, sorted.
    pub faces: Vec<FaceId>,
    #[serde(skip)]
    pub placement: Placement,
    pub thickness: Thickness,
}

/// Reference faces of one group whose thicknesses differ by less than this share are offset together.
const SAME_THICKNESS: f64 = 0.01;

pub fn plan_patches(graph: &FaceGraph, pairing: &Pairing) -> Vec<PatchPlan> {
    let mut plans = Vec::new();
    for group in &pairing.groups {
        let reference = &group.sides[group.reference as usize];
        // Each reference face with the pairs it belongs to.
        let mut per_face: Vec<(FaceId, Vec<&Pair>)> = reference
            .iter()
            .map(|&f| (f, group.pairs.iter().map(|&i| &pairing.pairs[i]).filter(|p| p.faces.contains(&f)).collect()))
            .collect();
        per_face.sort_by_key(|(f, _)| *f);
        if group.kind == PairKind::Draft {
            for (face, pairs) in &per_face {
                plans.push(draft_plan(graph, group.id, *face, pairs));
            }
            continue;
        }
        // Cluster reference faces by their own mean thickness.
        let mut clusters: Vec<(Thickness, Vec<FaceId>)> = Vec::new();
        for (face, pairs) in &per_face {
            let t = combined(pairs);
            match clusters.iter_mut().find(|(ct, _)| (ct.mean - t.mean).abs() <= SAME_THICKNESS * ct.mean) {
                Some((ct, faces)) => {
                    *ct = Thickness { mean: ct.mean, min: ct.min.min(t.min), max: ct.max.max(t.max) };
                    faces.push(*face);
                }
                None => clusters.push((t, vec![*face])),
            }
        }
        for (thickness, faces) in clusters {
            plans.push(PatchPlan {
                group: group.id,
                kind: group.kind,
                faces,
                placement: Placement::Offset(-0.5 * thickness.mean),
                thickness,
            });
        }
    }
    plans
}

/// Overlap-weighted mean thickness of a face's pairs, with their range.
fn combined(pairs: &[&Pair]) -> Thickness {
    let total: f64 = pairs.iter().map(|p| p.overlap_area).sum();
    let mean = pairs.iter().map(|p| p.thickness.mean * p.overlap_area).sum::<f64>() / total;
    let min = pairs.iter().map(|p| p.thickness.min).fold(f64::INFINITY, f64::min);
    let max = pairs.iter().map(|p| p.thickness.max).fold(f64::NEG_INFINITY, f64::max);
    Thickness { mean, min, max }
}

/// A draft face goes onto the exact bisector plane with its partner of largest overlap.
fn draft_plan(graph: &FaceGraph, group: usize, face: FaceId, pairs: &[&Pair]) -> PatchPlan {
    let main = pairs
        .iter()
        .max_by(|a, b| a.overlap_area.total_cmp(&b.overlap_area))
        .expect("a reference face belongs to at least one pair");
    let other = if main.faces[0] == face { main.faces[1] } else { main.faces[0] };
    let plane = |f: FaceId| match graph.faces[f].surface {
        Surface::Plane { origin, normal } => (origin, normal),
        _ => unreachable!("draft pairs are made of planes"),
    };
    let (pa, na) = plane(face);
    let (pb, nb) = plane(other);
    let (origin, normal) = bisector(pa, na, pb, nb);
    PatchPlan {
        group,
        kind: PairKind::Draft,
        faces: vec![face],
        placement: Placement::Plane { origin: origin.to_array(), normal: normal.to_array() },
        thickness: combined(pairs),
    }
}

/// The plane halfway between two planes facing each other (outward normals roughly opposite):
/// n = (na - nb) / |na - nb|, through the point of it nearest to the midpoint of the two origins.
pub fn bisector(pa: DVec3, na: DVec3, pb: DVec3, nb: DVec3) -> (DVec3, DVec3) {
    let scale = (na - nb).length();
    let normal = (na - nb) / scale;
    let offset = (na.dot(pa) - nb.dot(pb)) / scale;
    let mid = 0.5 * (pa + pb);
    (mid - normal * (normal.dot(mid) - offset), normal)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pairing::detect;
    use crate::synthetic;
    use crate::tolerance::Tolerances;

    #[test]
    fn bisector_of_a_drafted_wall() {
        // x = 0 facing -x, and a face tilted by 2 degrees facing +x, 3 apart at the origin.
        let a = 2.0_f64.to_radians();
        let nb = DVec3::new(a.cos(), 0.0, a.sin());
        let (o, n) = bisector(DVec3::ZERO, -DVec3::X, DVec3::X * 3.0, nb);
        // Equidistant from both planes, and near the midpoint of the origins.
        let (da, db) = (-(-DVec3::X).dot(o), -nb.dot(o - DVec3::X * 3.0));
        assert!((da - db).abs() < 1e-12 && da > 0.0, "{da} {db}");
        assert!(o.distance(DVec3::X * 1.5) < 1e-3, "{o}");
        let expected = (-DVec3::X - nb).normalize();
        assert!(n.distance(expected) < 1e-12);
    }

    #[test]
    fn plate_offsets_its_larger_face_by_half_the_thickness() {
        let g = synthetic::cuboid(DVec3::ZERO, DVec3::new(100.0, 60.0, 2.0));
        let pairing = detect(&g, &Tolerances::new(120.0, 3.0, 0.05), &[true; 6]);
        let plans = plan_patches(&g, &pairing);
        assert_eq!(plans.len(), 1);
        assert_eq!(plans[0].faces, vec![4]);
        assert_eq!(plans[0].placement, Placement::Offset(-1.0));
    }

    #[test]
    fn a_thickness_step_gives_one_patch_per_level() {
        // One bottom under two tops at heights 2 and 3: two patches from the bottom would be wrong, so the
        // tops (the reference side here, being larger) are offset each by its own half thickness.
        let faces = vec![
            synthetic::rect(DVec3::ZERO, DVec3::Y * 10.0, DVec3::X * 40.0, -DVec3::Z),
            synthetic::rect(DVec3::new(-5.0, 0.0, 2.0), DVec3::X * 25.0, DVec3::Y * 10.0, DVec3::Z),
            synthetic::rect(DVec3::new(20.0, 0.0, 3.0), DVec3::X * 25.0, DVec3::Y * 10.0, DVec3::Z),
        ];
        let g = synthetic::graph(faces, &[]);
        let pairing = detect(&g, &Tolerances::new(60.0, 4.0, 0.05), &[true; 3]);
        let plans = plan_patches(&g, &pairing);
        let offsets: Vec<(Vec<FaceId>, Placement)> = plans.iter().map(|p| (p.faces.clone(), p.placement.clone())).collect();
        assert_eq!(offsets, vec![(vec![1], Placement::Offset(-1.0)), (vec![2], Placement::Offset(-1.5))]);
    }
}
