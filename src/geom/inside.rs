//! Point in solid, from the solid's face meshes: ray parity along three fixed, slightly skewed directions,
//! majority vote (a ray grazing a mesh edge can miscount; two rays rarely both do). Triangles are found with
//! an R-tree, so a query costs a few dozen triangle tests, not the whole mesh (the kernel's solid classifier
//! takes ~4 ms per point on a 500-face part).

use glam::DVec3;
use rstar::{RTree, RTreeObject, AABB};

use super::ray::hit_triangle;
use crate::model::face_graph::FaceGraph;

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

pub struct SolidMesh {
    tree: RTree<Triangle>,
    lo: DVec3,
    hi: DVec3,
}

/// Mostly along an axis (a thin query box) but off every axis and diagonal a CAD mesh is likely to line up with.
const DIRECTIONS: [DVec3; 3] = [
    DVec3::new(1.0, 0.012_345_7, 0.021_734_9),
    DVec3::new(0.017_320_5, 1.0, -0.013_142_1),
    DVec3::new(-0.011_180_3, 0.019_364_9, 1.0),
];

impl SolidMesh {
    /// None when the graph was described without meshes.
    pub fn new(graph: &FaceGraph) -> Option<SolidMesh> {
        let mut triangles = Vec::new();
        for face in &graph.faces {
            let mesh = face.mesh.as_ref()?;
            for t in &mesh.triangles {
                let corners = t.map(|i| mesh.vertices[i as usize]);
                let lo = corners[0].min(corners[1]).min(corners[2]);
                let hi = corners[0].max(corners[1]).max(corners[2]);
                triangles.push(Triangle { corners, envelope: AABB::from_corners(lo.to_array(), hi.to_array()) });
            }
        }
        let lo = triangles.iter().map(|t| DVec3::from(t.envelope.lower())).fold(DVec3::INFINITY, DVec3::min);
        let hi = triangles.iter().map(|t| DVec3::from(t.envelope.upper())).fold(DVec3::NEG_INFINITY, DVec3::max);
        Some(SolidMesh { tree: RTree::bulk_load(triangles), lo, hi })
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

    fn crossings(&self, p: DVec3, dir: DVec3, reach: f64) -> usize {
        self.hits(p, dir, reach).count()
    }

    /// Distances along `dir` from `p` to the triangles the ray meets among those whose boxes touch the segment
    /// of length `reach`.
    fn hits(&self, p: DVec3, dir: DVec3, reach: f64) -> impl Iterator<Item = f64> + '_ {
        let end = p + dir * reach;
        let query = AABB::from_corners(p.min(end).to_array(), p.max(end).to_array());
        self.tree.locate_in_envelope_intersecting(&query).filter_map(move |t| hit_triangle(p, dir, t.corners))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthetic::cuboid;

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
    fn exit_distance_to_the_nearest_side() {
        let graph = cuboid(DVec3::ZERO, DVec3::new(10.0, 4.0, 2.0));
        let solid = SolidMesh::new(&graph).unwrap();
        let d = solid.exit(DVec3::new(5.0, 2.0, 1.5), DVec3::Z, 1.0).unwrap();
        assert!((d - 0.5).abs() < 1e-9, "{d}");
        assert!((solid.exit(DVec3::new(5.0, 2.0, 1.0), -DVec3::X, 9.0).unwrap() - 5.0).abs() < 1e-9);
        assert_eq!(solid.exit(DVec3::new(5.0, 2.0, 1.0), -DVec3::X, 4.0), None, "beyond the reach");
    }
}
