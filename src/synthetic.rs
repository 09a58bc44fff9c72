//! Hand-made face graphs for unit tests and benchmarks: faces built from a parametric surface, meshed on a
//! grid, with area, centroid and box computed from the mesh, so that no sidecar is needed.

use glam::DVec3;

use crate::model::face_graph::{Bbox, Convexity, Edge, Face, FaceGraph, Mesh, Surface};

/// A face from `eval(u, v) -> (point, outward normal)` over [0,1]^2 meshed with `n x n` quads.
pub fn face(surface: Surface, n: usize, eval: impl Fn(f64, f64) -> (DVec3, DVec3)) -> Face {
    let mut mesh = Mesh::default();
    for j in 0..=n {
        for i in 0..=n {
            let (p, nrm) = eval(i as f64 / n as f64, j as f64 / n as f64);
            mesh.vertices.push(p);
            mesh.normals.push(nrm.normalize());
        }
    }
    let at = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    for j in 0..n {
        for i in 0..n {
            for t in [[at(i, j), at(i + 1, j), at(i + 1, j + 1)], [at(i, j), at(i + 1, j + 1), at(i, j + 1)]] {
                let p = t.map(|k| mesh.vertices[k as usize]);
                let geometric = (p[1] - p[0]).cross(p[2] - p[0]);
                let outward = t.iter().map(|&k| mesh.normals[k as usize]).sum::<DVec3>();
                mesh.triangles.push(if geometric.dot(outward) >= 0.0 { t } else { [t[0], t[2], t[1]] });
            }
        }
    }
    let (mut area, mut moment) = (0.0, DVec3::ZERO);
    for t in &mesh.triangles {
        let p = t.map(|k| mesh.vertices[k as usize]);
        let a = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length();
        area += a;
        moment += a * (p[0] + p[1] + p[2]) / 3.0;
    }
    let min = mesh.vertices.iter().fold(DVec3::INFINITY, |m, &p| m.min(p));
    let max = mesh.vertices.iter().fold(DVec3::NEG_INFINITY, |m, &p| m.max(p));
    let (point, normal) = eval(0.5, 0.5);
    Face {
        id: 0,
        surface,
        reversed: false,
        point,
        normal: normal.normalize(),
        area,
        centroid: moment / area,
        bbox: Bbox { min, max },
        loops: Vec::new(),
        mesh: Some(mesh),
        problem: None,
    }
}

/// A planar parallelogram `origin + u * du + v * dv` with outward normal `normal`.
pub fn rect(origin: DVec3, du: DVec3, dv: DVec3, normal: DVec3) -> Face {
    let normal = normal.normalize();
    face(Surface::Plane { origin, normal }, 1, |u, v| (origin + du * u + dv * v, normal))
}

/// A cylindrical face around the z axis through `center`: radius, angular span [a0, a1], height.
pub fn cylinder(center: DVec3, radius: f64, span: (f64, f64), height: f64, convex: bool) -> Face {
    let surface = Surface::Cylinder { origin: center, axis: DVec3::Z, radius, convex };
    face(surface, 24, |u, v| {
        let a = span.0 + (span.1 - span.0) * u;
        let radial = DVec3::new(a.cos(), a.sin(), 0.0);
        (center + radial * radius + DVec3::Z * height * v, if convex { radial } else { -radial })
    })
}

/// A sphere patch around `center` (polar angle from `theta` range, full azimuth).
pub fn sphere(center: DVec3, radius: f64, theta: (f64, f64), convex: bool) -> Face {
    let surface = Surface::Sphere { center, radius, convex };
    face(surface, 24, |u, v| {
        let (t, p) = (theta.0 + (theta.1 - theta.0) * v, std::f64::consts::TAU * u);
        let radial = DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
        (center + radial * radius, if convex { radial } else { -radial })
    })
}

/// A torus patch around the z axis: the outer half of the tube (minor angle -90..90 degrees), full turn.
pub fn torus(center: DVec3, major: f64, minor: f64, convex: bool) -> Face {
    let surface = Surface::Torus { center, axis: DVec3::Z, major_radius: major, minor_radius: minor, convex };
    face(surface, 32, |u, v| {
        let (p, t) = (std::f64::consts::TAU * u, std::f64::consts::PI * (v - 0.5));
        let ring = DVec3::new(p.cos(), p.sin(), 0.0);
        let radial = ring * t.cos() + DVec3::Z * t.sin();
        (center + ring * major + radial * minor, if convex { radial } else { -radial })
    })
}

/// A cone around the z axis with apex at `apex`, half angle `half`, between distances s0..s1 from the apex
/// along the generator, full turn.
pub fn cone(apex: DVec3, half: f64, s: (f64, f64), convex: bool) -> Face {
    let surface = Surface::Cone { origin: apex, axis: DVec3::Z, radius: 0.0, half_angle: half, apex, convex };
    face(surface, 32, |u, v| {
        let (p, d) = (std::f64::consts::TAU * u, s.0 + (s.1 - s.0) * v);
        let ring = DVec3::new(p.cos(), p.sin(), 0.0);
        let generator = ring * half.sin() + DVec3::Z * half.cos();
        let out = ring * half.cos() - DVec3::Z * half.sin();
        (apex + generator * d, if convex { out } else { -out })
    })
}

/// Gives faces their ids and builds the graph; edges join faces listed in `adjacent` (one edge per pair).
pub fn graph(mut faces: Vec<Face>, adjacent: &[(usize, usize, Convexity)]) -> FaceGraph {
    for (i, f) in faces.iter_mut().enumerate() {
        f.id = i;
        f.loops.clear();
    }
    let mut edges = Vec::new();
    for (k, &(a, b, convexity)) in adjacent.iter().enumerate() {
        faces[a].loops.resize(1, Vec::new());
        faces[b].loops.resize(1, Vec::new());
        faces[a].loops[0].push(k);
        faces[b].loops[0].push(k);
        edges.push(Edge {
            id: k,
            vertices: [0, 0],
            faces: vec![a.min(b), a.max(b)],
            convexity,
            angle: 0.0,
            length: 1.0,
            curve: "line".into(),
            midpoint: DVec3::ZERO,
        });
    }
    let min = faces.iter().fold(DVec3::INFINITY, |m, f| m.min(f.bbox.min));
    let max = faces.iter().fold(DVec3::NEG_INFINITY, |m, f| m.max(f.bbox.max));
    let area = faces.iter().map(|f| f.area).sum();
    FaceGraph { volume: 0.0, area, bbox: Bbox { min, max }, vertices: vec![DVec3::ZERO], faces, edges }
}

/// A closed box [0,x]x[0,y]x[0,z] as six faces (-x, +x, -y, +y, -z, +z) with its twelve convex edges.
pub fn cuboid(origin: DVec3, size: DVec3) -> FaceGraph {
    let (x, y, z) = (DVec3::X * size.x, DVec3::Y * size.y, DVec3::Z * size.z);
    let o = origin;
    let faces = vec![
        rect(o, z, y, -DVec3::X),
        rect(o + x, y, z, DVec3::X),
        rect(o, x, z, -DVec3::Y),
        rect(o + y, z, x, DVec3::Y),
        rect(o, y, x, -DVec3::Z),
        rect(o + z, x, y, DVec3::Z),
    ];
    let mut adjacent = Vec::new();
    for a in 0..6 {
        for b in (a + 1)..6 {
            if a / 2 != b / 2 {
                adjacent.push((a, b, Convexity::Convex));
            }
        }
    }
    let mut g = graph(faces, &adjacent);
    g.volume = size.x * size.y * size.z;
    g
}
