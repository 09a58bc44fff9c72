//! Levels of one wall: pair groups whose skins on one side are one surface, split into faces where the other
//! side steps (a pocket under a flat top whose CAD split the top along the pocket's outline, letters cut into a
//! cover). The stitching bridges a thickness step between levels of one wall (`stitch::bridge`); how the CAD
//! split a skin into faces must not decide whether a step is one.

use crate::model::face_graph::{Face, FaceGraph, Surface};
use crate::model::tolerance::Tolerances;
use crate::model::union_find::{find, union};

use super::FaceRole;

/// Per pair group (`groups` of them; `roles` per face), its wall: the lowest group id among the groups whose
/// skins run on into each other, two faces of different groups sharing an edge and lying on one surface
/// (`one_surface`).
pub fn walls(graph: &FaceGraph, roles: &[FaceRole], groups: usize, tolerances: &Tolerances) -> Vec<usize> {
    let mut wall: Vec<usize> = (0..groups).collect();
    let group = |f: usize| match roles.get(f) {
        Some(&FaceRole::Pair { group, .. }) => Some(group),
        _ => None,
    };
    for edge in &graph.edges {
        let [a, b] = edge.faces[..] else { continue };
        let (Some(ga), Some(gb)) = (group(a), group(b)) else { continue };
        if ga != gb && one_surface(&graph.faces[a], &graph.faces[b], tolerances.point, tolerances.parallel_angle) {
            union(&mut wall, ga, gb);
        }
    }
    (0..wall.len()).map(|g| find(&mut wall, g)).collect()
}

/// Whether two faces lie on one surface with the material on the same side: the same plane (outward normals
/// within `angle` radians, `length` apart), or the same cylinder, cone, sphere or torus (centres, axes and radii
/// within `length` and `angle`). Freeform surfaces are never compared.
pub fn one_surface(a: &Face, b: &Face, length: f64, angle: f64) -> bool {
    let parallel = |u: glam::DVec3, v: glam::DVec3| u.dot(v).abs() >= angle.cos();
    let near = |x: f64, y: f64| (x - y).abs() <= length;
    // The distance of point q from the line through p along the unit u.
    let off_line = |p: glam::DVec3, u: glam::DVec3, q: glam::DVec3| (q - p).reject_from_normalized(u).length();
    match (&a.surface, &b.surface) {
        (Surface::Plane { .. }, Surface::Plane { .. }) => {
            a.normal.dot(b.normal) >= angle.cos() && (b.point - a.point).dot(a.normal).abs() <= length
        }
        (
            Surface::Cylinder { origin: o1, axis: u1, radius: r1, convex: c1 },
            Surface::Cylinder { origin: o2, axis: u2, radius: r2, convex: c2 },
        ) => c1 == c2 && near(*r1, *r2) && parallel(*u1, *u2) && off_line(*o1, *u1, *o2) <= length,
        (
            Surface::Cone { axis: u1, half_angle: h1, apex: p1, convex: c1, .. },
            Surface::Cone { axis: u2, half_angle: h2, apex: p2, convex: c2, .. },
        ) => {
            // The same cone is described with its axis either way round, its half-angle then changing sign.
            let same_way = u1.dot(*u2) >= angle.cos() && (h1 - h2).abs() <= angle;
            let other_way = u1.dot(*u2) <= -angle.cos() && (h1 + h2).abs() <= angle;
            c1 == c2 && p1.distance(*p2) <= length && (same_way || other_way)
        }
        (
            Surface::Sphere { center: p1, radius: r1, convex: c1 },
            Surface::Sphere { center: p2, radius: r2, convex: c2 },
        ) => c1 == c2 && near(*r1, *r2) && p1.distance(*p2) <= length,
        (
            Surface::Torus { center: p1, axis: u1, major_radius: m1, minor_radius: n1, convex: c1 },
            Surface::Torus { center: p2, axis: u2, major_radius: m2, minor_radius: n2, convex: c2 },
        ) => c1 == c2 && near(*m1, *m2) && near(*n1, *n2) && parallel(*u1, *u2) && p1.distance(*p2) <= length,
        _ => false,
    }
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
    fn one_surface_tells_planes_and_cylinders() {
        let a = rect(DVec3::new(0.0, 0.0, 2.0), DVec3::X, DVec3::Y, DVec3::Z);
        let b = rect(DVec3::new(20.0, 0.0, 2.0), DVec3::X, DVec3::Y, DVec3::Z);
        assert!(one_surface(&a, &b, LENGTH, angle()));
        let higher = rect(DVec3::new(20.0, 0.0, 2.1), DVec3::X, DVec3::Y, DVec3::Z);
        assert!(!one_surface(&a, &higher, LENGTH, angle()));
        let facing = rect(DVec3::new(20.0, 0.0, 2.0), DVec3::Y, DVec3::X, -DVec3::Z);
        assert!(!one_surface(&a, &facing, LENGTH, angle()), "material on the other side: another skin");
        let cylinder = |origin: DVec3, radius: f64| Face {
            surface: Surface::Cylinder { origin, axis: DVec3::Z, radius, convex: true },
            ..a.clone()
        };
        let same = (cylinder(DVec3::ZERO, 5.0), cylinder(DVec3::new(0.0, 0.0, 7.0), 5.0));
        assert!(one_surface(&same.0, &same.1, LENGTH, angle()));
        assert!(!one_surface(&cylinder(DVec3::ZERO, 5.0), &cylinder(DVec3::ZERO, 5.5), LENGTH, angle()));
        assert!(!one_surface(&cylinder(DVec3::ZERO, 5.0), &cylinder(DVec3::X, 5.0), LENGTH, angle()));
    }
}
