//! Ray against triangle (Moller-Trumbore), for sampled distances between curved or freeform faces.

use glam::DVec3;

/// A ray is parallel to a triangle's plane when the determinant is under this share of the triangle's size
/// squared.
const GRAZING: f64 = 1e-12;
/// Barycentric slack: a ray through a shared edge of two triangles hits at least one of them despite round-off.
const EDGE_SLACK: f64 = 1e-9;

/// Distance along `dir` (unit) from `origin` to the triangle, if the ray hits it in front of the origin.
pub fn hit_triangle(origin: DVec3, dir: DVec3, tri: [DVec3; 3]) -> Option<f64> {
    let e1 = tri[1] - tri[0];
    let e2 = tri[2] - tri[0];
    let p = dir.cross(e2);
    let det = e1.dot(p);
    // Relative to the triangle's size: a ray grazing the triangle's plane has no stable hit.
    if det.abs() <= GRAZING * e1.length_squared().max(e2.length_squared()) {
        return None;
    }
    let inv = 1.0 / det;
    let s = origin - tri[0];
    let u = s.dot(p) * inv;
    if !(-EDGE_SLACK..=1.0 + EDGE_SLACK).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv;
    if v < -EDGE_SLACK || u + v > 1.0 + EDGE_SLACK {
        return None;
    }
    let t = e2.dot(q) * inv;
    (t >= 0.0).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_in_front_only() {
        let tri = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let o = DVec3::new(0.2, 0.2, 1.0);
        assert!((hit_triangle(o, -DVec3::Z, tri).unwrap() - 1.0).abs() < 1e-12);
        assert_eq!(hit_triangle(o, DVec3::Z, tri), None);
        assert_eq!(hit_triangle(DVec3::new(2.0, 2.0, 1.0), -DVec3::Z, tri), None);
    }
}
