//! Levels of one wall: pair groups whose skins on one side are one plane, split into faces where the other
//! side steps (a pocket under a flat top whose CAD split the top along the pocket's outline, letters cut into a
//! cover). The stitching bridges a thickness step between levels of one wall (`stitch::bridge`); how the CAD
//! split a skin into faces must not decide whether a step is one.

use crate::model::face_graph::{Face, FaceGraph, Surface};
use crate::model::tolerance::Tolerances;
use crate::model::union_find::{find, union};

use super::FaceRole;

/// Per pair group (`groups` of them; `roles` per face), its wall: the lowest group id among the groups whose
/// flat skins run on into each other, two faces of different groups sharing an edge and lying on one plane
/// (`one_plane`).
pub fn walls(graph: &FaceGraph, roles: &[FaceRole], groups: usize, tolerances: &Tolerances) -> Vec<usize> {
    let mut wall: Vec<usize> = (0..groups).collect();
    let group = |f: usize| match roles.get(f) {
        Some(&FaceRole::Pair { group, .. }) => Some(group),
        _ => None,
    };
    for edge in &graph.edges {
        let [a, b] = edge.faces[..] else { continue };
        let (Some(ga), Some(gb)) = (group(a), group(b)) else { continue };
        if ga != gb && one_plane(&graph.faces[a], &graph.faces[b], tolerances.point, tolerances.parallel_angle) {
            union(&mut wall, ga, gb);
        }
    }
    (0..wall.len()).map(|g| find(&mut wall, g)).collect()
}

/// Whether two faces lie on one plane with the material on the same side: outward normals within `angle`
/// radians, `length` apart. Only flat skins: two faces of one curved skin split along a line (a bore's halves
/// round a boss merging into a wall on one side) bound walls whose patches meet along that line at their own
/// T- and L-joints, and a step bridge across it (a ramp between two radii along the seam) stole those joints
/// on the real parts tried (gaps grew, a tube's halves were lost).
pub fn one_plane(a: &Face, b: &Face, length: f64, angle: f64) -> bool {
    matches!((&a.surface, &b.surface), (Surface::Plane { .. }, Surface::Plane { .. }))
        && a.normal.dot(b.normal) >= angle.cos()
        && (b.point - a.point).dot(a.normal).abs() <= length
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::model::face_graph::Convexity;
    use crate::pairing::Side;
    use crate::synthetic::{graph, rect};

    const LENGTH: f64 = 1e-6;

    fn angle() -> f64 {
        0.5_f64.to_radians()
    }

    /// A plate 2 thick whose top over x in [40, 50] is a face of its own, over a pocket 1 deep from below: the
    /// two tops (0, 1) pair with the two bottoms (2, 3) as groups 0 and 1. `top_z`: the second top's height.
    fn split_top(top_z: f64) -> (FaceGraph, Vec<FaceRole>) {
        let (x, y) = (DVec3::X, DVec3::Y * 30.0);
        let faces = vec![
            rect(DVec3::new(0.0, 0.0, 2.0), x * 40.0, y, DVec3::Z),
            rect(DVec3::new(40.0, 0.0, top_z), x * 10.0, y, DVec3::Z),
            rect(DVec3::ZERO, y, x * 40.0, -DVec3::Z),
            rect(DVec3::new(40.0, 0.0, 1.0), y, x * 10.0, -DVec3::Z),
        ];
        let pair = |group, side| FaceRole::Pair { group, side };
        let roles = vec![pair(0, Side::A), pair(1, Side::A), pair(0, Side::B), pair(1, Side::B)];
        (graph(faces, &[(0, 1, Convexity::Smooth)]), roles)
    }

    fn tolerances() -> Tolerances {
        Tolerances::new(100.0, 3.0, 3.0_f64.to_radians())
    }

    #[test]
    fn a_flat_skin_split_over_a_pocket_makes_the_two_levels_one_wall() {
        let (g, roles) = split_top(2.0);
        assert_eq!(walls(&g, &roles, 2, &tolerances()), vec![0, 0]);
    }

    #[test]
    fn skins_meeting_off_one_surface_leave_the_walls_apart() {
        // The second top 0.5 higher (a pad's top, not the same skin), though the faces share an edge.
        let (g, roles) = split_top(2.5);
        assert_eq!(walls(&g, &roles, 2, &tolerances()), vec![0, 1]);
        // The same skins sharing no edge: one plane, but nothing says they are one skin.
        let (mut g, roles) = split_top(2.0);
        g.edges.clear();
        assert_eq!(walls(&g, &roles, 2, &tolerances()), vec![0, 1]);
    }

    #[test]
    fn one_plane_tells_planes_apart() {
        let a = rect(DVec3::new(0.0, 0.0, 2.0), DVec3::X, DVec3::Y, DVec3::Z);
        let b = rect(DVec3::new(20.0, 0.0, 2.0), DVec3::X, DVec3::Y, DVec3::Z);
        assert!(one_plane(&a, &b, LENGTH, angle()));
        let higher = rect(DVec3::new(20.0, 0.0, 2.1), DVec3::X, DVec3::Y, DVec3::Z);
        assert!(!one_plane(&a, &higher, LENGTH, angle()));
        let facing = rect(DVec3::new(20.0, 0.0, 2.0), DVec3::Y, DVec3::X, -DVec3::Z);
        assert!(!one_plane(&a, &facing, LENGTH, angle()), "material on the other side: another skin");
        let cylinder =
            Face { surface: Surface::Cylinder { origin: DVec3::ZERO, axis: DVec3::Z, radius: 5.0, convex: true }, ..b };
        assert!(!one_plane(&a, &cylinder, LENGTH, angle()), "a curved skin is never a flat one");
    }
}
