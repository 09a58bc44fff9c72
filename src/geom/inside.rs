//! Point in solid, from the solid's face meshes: ray parity along three fixed, slightly skewed directions,
//! majority vote (a ray grazing a mesh edge can miscount; two rays rarely both do). Triangles are found with
//! an R-tree walked along the ray itself (nodes whose boxes the ray segment misses are skipped), so a query
//! costs the triangles near the ray, not the whole mesh (the kernel's solid classifier takes ~4 ms per point
//! on a 500-face part). The box around a long skewed ray holds a band of the part: on a plate with 900 holes
//! the rays of one point met some thousand triangles that way, and the point tests took 2 of its 13 s.

use std::sync::Arc;

use glam::DVec3;
use rstar::{Envelope, RTree, RTreeObject, SelectionFunction, AABB};

use super::ray::hit_triangle;
use crate::model::face_graph::{Face, Mesh};

struct Triangle {
    corners: [DVec3; 3],
    envelope: AABB<[f64; 3]>,
}

impl RTreeObject for Triangle {
    type Envelope = AABB<[f64; 3]>;
    fn envelope(&self) -> Self::Envelope {
        self.envelope
    }
}

/// Cheap to clone: the solids of one body share its mesh (`geom::bodies`).
#[derive(Clone)]
pub struct SolidMesh {
    tree: Arc<RTree<Triangle>>,
    lo: DVec3,
    hi: DVec3,
    /// Boxes are widened by this when a ray is tested against them, so that a hit the triangle test accepts
    /// within its barycentric slack (ray::EDGE_SLACK, relative to the triangle) is never in a box the ray misses.
    margin: f64,
}

/// Relative to the mesh's diagonal: far above the triangle test's slack, far below any feature.
const BOX_MARGIN: f64 = 1e-7;

/// Mostly along an axis (a thin query box) but off every axis and diagonal a CAD mesh is likely to line up with.
const DIRECTIONS: [DVec3; 3] = [
    DVec3::new(1.0, 0.012_345_7, 0.021_734_9),
    DVec3::new(0.017_320_5, 1.0, -0.013_142_1),
    DVec3::new(-0.011_180_3, 0.019_364_9, 1.0),
];

impl SolidMesh {
    /// One solid's material (tests; a run builds every solid's through `geom::bodies`). None when the graph
    /// was described without meshes.
    #[cfg(test)]
    pub fn new(graph: &crate::model::face_graph::FaceGraph) -> Option<SolidMesh> {
        SolidMesh::of_faces(graph.faces.iter())
    }

    /// The material bounded by `faces` (of one solid, or of the solids of a body without the faces they
    /// share); None when a face was described without a mesh.
    pub fn of_faces<'a>(faces: impl Iterator<Item = &'a Face>) -> Option<SolidMesh> {
        let meshes: Option<Vec<&Mesh>> = faces.map(|face| face.mesh.as_ref()).collect();
        Some(SolidMesh::of_meshes(meshes?))
    }

    /// The triangles of `meshes` (also one face's alone: `Mesh::nearest_hit`).
    pub fn of_meshes<'a>(meshes: impl IntoIterator<Item = &'a Mesh>) -> SolidMesh {
        let mut triangles = Vec::new();
        for mesh in meshes {
            for t in &mesh.triangles {
                let corners = t.map(|i| mesh.vertices[i as usize]);
                let lo = corners[0].min(corners[1]).min(corners[2]);
                let hi = corners[0].max(corners[1]).max(corners[2]);
                triangles.push(Triangle { corners, envelope: AABB::from_corners(lo.to_array(), hi.to_array()) });
            }
        }
        let lo = triangles.iter().map(|t| DVec3::from(t.envelope.lower())).fold(DVec3::INFINITY, DVec3::min);
        let hi = triangles.iter().map(|t| DVec3::from(t.envelope.upper())).fold(DVec3::NEG_INFINITY, DVec3::max);
        let margin = BOX_MARGIN * (hi - lo).length();
        SolidMesh { tree: Arc::new(RTree::bulk_load(triangles)), lo, hi, margin }
    }

    pub fn contains(&self, p: DVec3) -> bool {
        if p.cmplt(self.lo).any() || p.cmpgt(self.hi).any() {
            return false;
        }
        let reach = (self.hi - self.lo).length() * 2.0;
        let odd = DIRECTIONS.iter().filter(|d| self.crossings(p, d.normalize(), reach) % 2 == 1).count();
        odd >= 2
    }

    /// Distance from `p` along the unit direction `dir` to the nearest mesh triangle, if within `reach`.
    pub fn exit(&self, p: DVec3, dir: DVec3, reach: f64) -> Option<f64> {
        self.hits(p, dir, reach).filter(|&d| d <= reach).min_by(f64::total_cmp)
    }

    /// Distance along `dir` (unit) from `p` to the nearest triangle that `accept` takes (by its corners) and
    /// the ray meets within `reach`. Every triangle whose widened box the segment meets is tried: no parity
    /// rule here, so a hit within the triangle test's slack is never left out.
    pub fn nearest_where(&self, p: DVec3, dir: DVec3, reach: f64, accept: impl Fn(&[DVec3; 3]) -> bool) -> Option<f64> {
        let segment = Segment { origin: p, inverse: dir.recip(), reach, margin: self.margin };
        self.tree
            .locate_with_selection_function(segment)
            .filter(|t| accept(&t.corners))
            .filter_map(|t| hit_triangle(p, dir, t.corners))
            .filter(|&d| d <= reach)
            .min_by(f64::total_cmp)
    }

    /// Whether a triangle square to the unit `normal` (its own normal within `cos` of it, either way) lies within
    /// `within` of `p` along it: `p` lies on a face parallel to a patch of that normal.
    pub fn on_face_across(&self, p: DVec3, normal: DVec3, within: f64, cos: f64) -> bool {
        let square = |t: &[DVec3; 3]| {
            let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize_or_zero();
            n.dot(normal).abs() >= cos
        };
        self.nearest_where(p - normal * within, normal, 2.0 * within, square).is_some()
    }

    /// Distances along `dir` (unit) from `p` to every triangle the ray meets within `reach`, sorted, hits
    /// closer than `merge` to the previous one dropped (a ray through an edge two triangles share meets both).
    pub fn crossings_along(&self, p: DVec3, dir: DVec3, reach: f64, merge: f64) -> Vec<f64> {
        let mut all: Vec<f64> = self.hits(p, dir, reach).filter(|&d| d <= reach).collect();
        all.sort_by(f64::total_cmp);
        all.dedup_by(|later, earlier| *later - *earlier <= merge);
        all
    }

    /// The box around the mesh.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        (self.lo, self.hi)
    }

    fn crossings(&self, p: DVec3, dir: DVec3, reach: f64) -> usize {
        self.hits(p, dir, reach).count()
    }

    /// Distances along `dir` from `p` to the triangles the ray meets among those whose boxes touch the segment
    /// of length `reach`.
    fn hits(&self, p: DVec3, dir: DVec3, reach: f64) -> impl Iterator<Item = f64> + '_ {
        // A triangle counts when its box meets the box of the segment, whether or not the segment itself
        // meets the box: at a point on the mesh, which of the triangles around it count decides the parity of
        // a ray, and this rule is the one the answers were made with. The walk finds those triangles among
        // the ones whose widened boxes the segment meets, which holds every triangle the ray hits.
        let end = p + dir * reach;
        let query = AABB::from_corners(p.min(end).to_array(), p.max(end).to_array());
        let segment = Segment { origin: p, inverse: dir.recip(), reach, margin: self.margin };
        self.tree
            .locate_with_selection_function(segment)
            .filter(move |t| t.envelope.intersects(&query))
            .filter_map(move |t| hit_triangle(p, dir, t.corners))
    }
}

/// The part of a ray within `reach` of its origin, as an R-tree walk: a node is opened when the segment meets
/// its box (slab test), widened by `margin`.
struct Segment {
    origin: DVec3,
    /// 1 / direction per axis (infinite along an axis the ray is parallel to).
    inverse: DVec3,
    reach: f64,
    margin: f64,
}

impl Segment {
    fn meets(&self, envelope: &AABB<[f64; 3]>) -> bool {
        let lo = DVec3::from(envelope.lower()) - DVec3::splat(self.margin);
        let hi = DVec3::from(envelope.upper()) + DVec3::splat(self.margin);
        let (mut enter, mut leave) = (0.0_f64, self.reach);
        for axis in 0..3 {
            let (o, inv) = (self.origin[axis], self.inverse[axis]);
            if inv.is_infinite() {
                // Parallel to this pair of slabs: in them or never.
                if o < lo[axis] || o > hi[axis] {
                    return false;
                }
                continue;
            }
            let (a, b) = ((lo[axis] - o) * inv, (hi[axis] - o) * inv);
            enter = enter.max(a.min(b));
            leave = leave.min(a.max(b));
            if enter > leave {
                return false;
            }
        }
        true
    }
}

impl SelectionFunction<Triangle> for Segment {
    fn should_unpack_parent(&self, envelope: &AABB<[f64; 3]>) -> bool {
        self.meets(envelope)
    }

    fn should_unpack_leaf(&self, leaf: &Triangle) -> bool {
        self.meets(&leaf.envelope)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::face_graph::Surface;
    use crate::synthetic::{self, cuboid};

    #[test]
    fn inside_outside_of_a_box() {
        let graph = cuboid(DVec3::ZERO, DVec3::new(10.0, 4.0, 2.0));
        let solid = SolidMesh::new(&graph).expect("cuboid faces carry meshes");
        assert!(solid.contains(DVec3::new(5.0, 2.0, 1.0)));
        assert!(solid.contains(DVec3::new(0.1, 0.1, 0.1)));
        assert!(!solid.contains(DVec3::new(5.0, 2.0, 2.5)));
        assert!(!solid.contains(DVec3::new(-0.1, 2.0, 1.0)));
        assert!(!solid.contains(DVec3::new(50.0, 2.0, 1.0)));
    }

    #[test]
    fn a_point_on_a_face_square_to_the_normal_is_told_from_one_on_a_face_along_it() {
        let solid = SolidMesh::new(&cuboid(DVec3::ZERO, DVec3::new(10.0, 4.0, 2.0))).unwrap();
        let on_top = DVec3::new(5.0, 2.0, 2.0);
        assert!(solid.on_face_across(on_top, DVec3::Z, 1e-3, 0.999));
        assert!(solid.on_face_across(on_top + DVec3::Z * 5e-4, -DVec3::Z, 1e-3, 0.999));
        assert!(!solid.on_face_across(on_top + DVec3::Z * 5e-3, DVec3::Z, 1e-3, 0.999), "farther than `within`");
        assert!(!solid.on_face_across(on_top, DVec3::X, 1e-3, 0.999), "the top is along x, not across it");
        assert!(!solid.on_face_across(DVec3::new(5.0, 2.0, 1.0), DVec3::Z, 1e-3, 0.999));
    }

    #[test]
    fn the_nearest_hit_a_filter_takes_is_the_nearest_of_those_a_scan_finds() {
        // A finely meshed face (two triangles per quad, 40 x 40) and rays across it at a slant; the filter keeps
        // the triangles of one diagonal orientation only, so about half the rays' nearest hits change.
        let plane = Surface::Plane { origin: DVec3::ZERO, normal: DVec3::Z };
        let face = synthetic::face(plane, 40, |u, v| (DVec3::new(40.0 * u, 40.0 * v, 0.0), DVec3::Z));
        let mesh = face.mesh.unwrap();
        // Each quad's first triangle starts along +x, its second along the diagonal.
        let keep = |t: &[DVec3; 3]| (t[1] - t[0]).y == 0.0;
        for k in 0..200 {
            let p = DVec3::new(0.37 + 0.19 * k as f64, 0.53 + 0.17 * k as f64, 1.0 + 0.01 * k as f64);
            let dir = DVec3::new(0.1, -0.05, -1.0).normalize();
            let scan = mesh
                .triangles
                .iter()
                .map(|t| t.map(|i| mesh.vertices[i as usize]))
                .filter(|t| keep(t))
                .filter_map(|t| crate::geom::ray::hit_triangle(p, dir, t))
                .filter(|&d| d <= 3.0)
                .min_by(f64::total_cmp);
            assert_eq!(mesh.nearest_hit(p, dir, 3.0, keep), scan, "ray {k}");
        }
        assert_eq!(mesh.nearest_hit(DVec3::new(5.0, 5.0, 4.0), -DVec3::Z, 3.0, |_| true), None, "beyond the reach");
    }

    #[test]
    fn exit_distance_to_the_nearest_side() {
        let graph = cuboid(DVec3::ZERO, DVec3::new(10.0, 4.0, 2.0));
        let solid = SolidMesh::new(&graph).unwrap();
        let d = solid.exit(DVec3::new(5.0, 2.0, 1.5), DVec3::Z, 1.0).unwrap();
        assert!((d - 0.5).abs() < 1e-9, "{d}");
        assert!((solid.exit(DVec3::new(5.0, 2.0, 1.0), -DVec3::X, 9.0).unwrap() - 5.0).abs() < 1e-9);
        assert_eq!(solid.exit(DVec3::new(5.0, 2.0, 1.0), -DVec3::X, 4.0), None, "beyond the reach");
    }

    #[test]
    fn the_walk_along_the_ray_finds_every_hit_a_scan_of_all_triangles_finds() {
        // Curved faces give triangles at every slant; rays from inside and outside, along and off the axes.
        let graph = synthetic::graph(
            vec![
                synthetic::cylinder(DVec3::new(3.0, 1.0, 0.0), 2.5, (0.0, 6.0), 4.0, true),
                synthetic::sphere(DVec3::new(-2.0, 4.0, 1.0), 3.0, (0.1, 3.0), true),
                synthetic::rect(DVec3::ZERO, DVec3::new(9.0, 0.0, 0.0), DVec3::new(0.0, 7.0, 0.0), DVec3::Z),
            ],
            &[],
        );
        let solid = SolidMesh::new(&graph).unwrap();
        let triangles: Vec<[DVec3; 3]> = graph
            .faces
            .iter()
            .flat_map(|f| {
                let m = f.mesh.as_ref().unwrap();
                m.triangles.iter().map(move |t| t.map(|i| m.vertices[i as usize]))
            })
            .collect();
        let mut seed = 12345_u64;
        let mut next = move || {
            seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut compared = 0;
        for k in 0..400 {
            let p = DVec3::new(next() * 14.0 - 6.0, next() * 12.0 - 3.0, next() * 6.0 - 2.0);
            let dir = match k % 4 {
                0 => DVec3::Z,
                1 => -DVec3::X,
                _ => DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5).normalize(),
            };
            let reach = 1.0 + next() * 12.0;
            let scan = triangles.iter().filter_map(|&t| hit_triangle(p, dir, t)).filter(|&d| d <= reach);
            let scanned = scan.clone().min_by(f64::total_cmp);
            assert_eq!(solid.exit(p, dir, reach), scanned, "from {p} along {dir}");
            let all = triangles.iter().filter_map(|&t| hit_triangle(p, dir, t)).count();
            assert_eq!(solid.crossings(p, dir, 100.0), all, "from {p} along {dir}");
            compared += usize::from(scanned.is_some());
        }
        assert!(compared > 100, "{compared} rays hit something");
    }
}
