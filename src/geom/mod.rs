//! Small geometric kernels computed in Rust: 2D clipping, rays, frames.

pub mod bodies;
pub mod clip;
pub mod coverage;
pub mod inside;
pub mod ray;

use glam::DVec3;

/// Two unit vectors completing `n` (unit) to a right-handed orthonormal frame, chosen deterministically.
pub fn plane_basis(n: DVec3) -> (DVec3, DVec3) {
    let helper = if n.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    let u = n.cross(helper).normalize();
    (u, n.cross(u))
}

/// Angle between two unit vectors, robust near 0 and pi.
pub fn angle_between(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}
