//! Overlap of two faces: how much of one, projected onto the other, lies on it.
//!
//! Planes and coaxial cylinders are mapped to a common 2D domain (plane coordinates; unrolled angle x axial
//! position) and their mesh triangles clipped exactly. Cones, spheres, tori and freeform faces are sampled:
//! rays from points of one face along its inward normal must hit the other face; the hit distances are the
//! wall thickness there.

use glam::{DVec2, DVec3};

use crate::geom::clip::{signed_area, soup_overlap};
use crate::geom::plane_basis;
use crate::model::face_graph::{Face, Mesh};

/// The mapped region where two faces overlap.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Overlap {
    pub area: f64,
    /// Areas of the two faces in the same 2D domain, so that `area / min(mapped)` is a share.
    pub mapped: [f64; 2],
}

impl Overlap {
    pub fn share(&self) -> f64 {
        let smaller = self.mapped[0].min(self.mapped[1]);
        if smaller > 0.0 {
            self.area / smaller
        } else {
            0.0
        }
    }
}

fn triangles(mesh: &Mesh, map: impl Fn(DVec3) -> DVec2) -> Vec<[DVec2; 3]> {
    mesh.triangles.iter().map(|t| t.map(|i| map(mesh.vertices[i as usize]))).collect()
}

fn soup_area(soup: &[[DVec2; 3]]) -> f64 {
    soup.iter().map(|t| signed_area(t).abs()).sum()
}

/// Both meshes projected along `normal` onto a plane, then clipped.
pub fn planar(a: &Mesh, b: &Mesh, normal: DVec3) -> Overlap {
    let (u, v) = plane_basis(normal);
    let map = |p: DVec3| DVec2::new(p.dot(u), p.dot(v));
    let (ta, tb) = (triangles(a, map), triangles(b, map));
    Overlap { area: soup_overlap(&ta, &tb), mapped: [soup_area(&ta), soup_area(&tb)] }
}

/// Both meshes unrolled around a common axis at radius `radius`: (angle * radius, axial position).
pub fn cylindrical(a: &Mesh, b: &Mesh, origin: DVec3, axis: DVec3, radius: f64) -> Overlap {
    let (u, v) = plane_basis(axis);
    let polar = |p: DVec3| {
        let r = p - origin;
        (r.dot(v).atan2(r.dot(u)), r.dot(axis))
    };
    // Each triangle is unrolled around its own first vertex so that none straddles the seam at +-pi.
    let unroll = |mesh: &Mesh| -> Vec<[DVec2; 3]> {
        mesh.triangles
            .iter()
            .map(|t| {
                let pts = t.map(|i| polar(mesh.vertices[i as usize]));
                let base = pts[0].0;
                pts.map(|(angle, z)| {
                    let mut d = angle - base;
                    d -= (d / std::f64::consts::TAU).round() * std::f64::consts::TAU;
                    DVec2::new((base + d) * radius, z)
                })
            })
            .collect()
    };
    let ta = unroll(a);
    let tb = unroll(b);
    let turn = std::f64::consts::TAU * radius;
    let shifted: Vec<[DVec2; 3]> =
        [-turn, 0.0, turn].iter().flat_map(|&s| tb.iter().map(move |t| t.map(|p| p + DVec2::new(s, 0.0)))).collect();
    Overlap { area: soup_overlap(&ta, &shifted), mapped: [soup_area(&ta), soup_area(&tb)] }
}

/// Rays cast from sample points of `from` along its inward normal that hit `to` within `max_distance` on a
/// triangle facing the other way (angle of normals within `max_angle` of opposite).
#[derive(Debug, Clone, PartialEq)]
pub struct Sampled {
    /// Area of `from` whose rays hit `to`.
    pub hit_area: f64,
    pub from_area: f64,
    /// Hit distances with the area each stands for.
    pub distances: Vec<(f64, f64)>,
}

impl Sampled {
    pub fn share(&self) -> f64 {
        if self.from_area > 0.0 {
            self.hit_area / self.from_area
        } else {
            0.0
        }
    }

    /// Area-weighted mean, min and max of the hit distances.
    pub fn distance_stats(&self) -> Option<(f64, f64, f64)> {
        if self.distances.is_empty() || self.hit_area <= 0.0 {
            return None;
        }
        let mean = self.distances.iter().map(|(d, w)| d * w).sum::<f64>() / self.hit_area;
        let min = self.distances.iter().map(|d| d.0).fold(f64::INFINITY, f64::min);
        let max = self.distances.iter().map(|d| d.0).fold(f64::NEG_INFINITY, f64::max);
        Some((mean, min, max))
    }
}

/// Barycentric sample points of a triangle: the centroid and the midpoints between it and each corner, so
/// that a coarse mesh still gives four samples per triangle.
const SAMPLES: [[f64; 3]; 4] = [
    [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0],
    [2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0],
    [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0],
    [1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0],
];

pub fn sampled(from: &Face, to: &Face, max_distance: f64, max_angle: f64) -> Option<Sampled> {
    let (fm, tm) = (from.mesh.as_ref()?, to.mesh.as_ref()?);
    let min_cos = max_angle.cos();
    let mut out = Sampled { hit_area: 0.0, from_area: 0.0, distances: Vec::new() };
    for t in &fm.triangles {
        let p = t.map(|i| fm.vertices[i as usize]);
        let n = t.map(|i| fm.normals[i as usize]);
        let area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length();
        let weight = area / SAMPLES.len() as f64;
        out.from_area += area;
        for w in SAMPLES {
            let origin = p[0] * w[0] + p[1] * w[1] + p[2] * w[2];
            let dir = -(n[0] * w[0] + n[1] * w[1] + n[2] * w[2]).normalize_or_zero();
            let facing =
                |tri: &[DVec3; 3]| (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalize_or_zero().dot(dir) >= min_cos;
            let nearest = tm.nearest_hit(origin, dir, max_distance, facing).unwrap_or(f64::INFINITY);
            if nearest.is_finite() {
                out.hit_area += weight;
                out.distances.push((nearest, weight));
            }
        }
    }
    Some(out)
}
