//! How much of a solid's material lies within reach of the mid-surface, measured by midsurf on the meshes it
//! already has, so that a report shows which walls got no patch. A point of the material is covered when a
//! patch passes within REACH_SHARE of that patch's thickness: every point of a wall lies within half its
//! thickness of the wall's mid-surface, and the rest is room for joints and rounded corners.
//!
//! Points are drawn uniformly in the material: rays along a fixed direction, one per cell of a regular grid
//! over the solid's box (placed at a fixed pseudo-random spot of its cell), cross the material in intervals
//! between their hits; each interval gives one point at a pseudo-random depth, weighted by the interval's
//! length, so that the weights of a grid add up to the volume (Cavalieri). A ray with an odd number of hits
//! (one that grazed an edge) is left out. Three directions, nearly along the three axes, share the points. The
//! same meshes give the same points: the figure is deterministic.

use std::collections::BTreeMap;

use glam::DVec3;
use rstar::{PointDistance, RTree, RTreeObject, AABB};
use serde::Serialize;

use super::inside::SolidMesh;
use super::plane_basis;
use crate::model::face_graph::FaceId;

/// A point is covered within this share of the nearest patch's thickness.
pub const REACH_SHARE: f64 = 0.75;
/// Rays per side of the grid at first; doubled while the material gave fewer than MIN_POINTS points.
const GRID_START: usize = 48;
const GRID_MAX: usize = 256;
const MIN_POINTS: usize = 2000;
/// Mostly along each axis but off every axis and diagonal a CAD part is likely to line up with, so that few
/// rays graze its edges.
const DIRECTIONS: [DVec3; 3] = [
    DVec3::new(1.0, 0.021_734_9, -0.013_142_1),
    DVec3::new(-0.017_320_5, 1.0, 0.011_180_3),
    DVec3::new(0.013_142_1, -0.021_734_9, 1.0),
];
/// Two hits along a ray closer than this share of the box's diagonal are one (an edge two triangles share).
const MERGE_HITS: f64 = 1e-9;
/// Faces listed as the most missed, at most.
const MISSED_LISTED: usize = 10;

/// A point of the material and the volume it stands for.
#[derive(Debug, Clone, Copy)]
pub struct Sample {
    pub point: DVec3,
    pub weight: f64,
}

/// The share of a solid's volume within reach of its patches, from `samples` points; `missed` lists the
/// solid's faces nearest to the points out of reach, with the share of the volume each stands for.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Coverage {
    pub share: f64,
    pub samples: usize,
    pub missed: Vec<Missed>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Missed {
    pub face: FaceId,
    pub share: f64,
}

/// Triangles, each carrying a tag (the patch or the face it belongs to), for nearest-triangle queries.
pub struct Triangles {
    tree: RTree<Tagged>,
}

struct Tagged {
    corners: [DVec3; 3],
    tag: usize,
}

impl RTreeObject for Tagged {
    type Envelope = AABB<[f64; 3]>;
    fn envelope(&self) -> Self::Envelope {
        let [a, b, c] = self.corners;
        AABB::from_corners(a.min(b).min(c).to_array(), a.max(b).max(c).to_array())
    }
}

impl PointDistance for Tagged {
    fn distance_2(&self, point: &[f64; 3]) -> f64 {
        let p = DVec3::from(*point);
        p.distance_squared(closest_on_triangle(p, self.corners))
    }
}

impl Triangles {
    pub fn new(triangles: impl IntoIterator<Item = ([DVec3; 3], usize)>) -> Triangles {
        Triangles {
            tree: RTree::bulk_load(triangles.into_iter().map(|(corners, tag)| Tagged { corners, tag }).collect()),
        }
    }

    /// The tag of the triangle nearest to `p` and the distance to it; None when there are no triangles.
    pub fn nearest(&self, p: DVec3) -> Option<(usize, f64)> {
        self.tree.nearest_neighbor(&p.to_array()).map(|t| (t.tag, t.distance_2(&p.to_array()).sqrt()))
    }
}

/// Points spread uniformly through the material of `mesh` (see the module doc), from rays along each of
/// DIRECTIONS in turn: a wall along one direction is crossed across by another, so no wall's share rests
/// on a few long chords.
pub fn material_samples(mesh: &SolidMesh) -> Vec<Sample> {
    let mut grid = GRID_START;
    loop {
        let mut samples = Vec::new();
        for (d, dir) in DIRECTIONS.iter().enumerate() {
            along(mesh, dir.normalize(), grid, d as u64, &mut samples);
        }
        if samples.len() >= MIN_POINTS || grid >= GRID_MAX {
            // Each direction's points add up to the volume: together, to three times it.
            let share = 1.0 / DIRECTIONS.len() as f64;
            return samples.into_iter().map(|s| Sample { weight: s.weight * share, ..s }).collect();
        }
        grid *= 2;
    }
}

/// The points of the rays along `dir` from a `grid` x `grid` grid over the box of `mesh`, appended to `out`.
fn along(mesh: &SolidMesh, dir: DVec3, grid: usize, stream: u64, out: &mut Vec<Sample>) {
    let (u, v) = plane_basis(dir);
    let (lo, hi) = mesh.bounds();
    let corners = (0..8).map(|k| DVec3::new(pick(k & 1, lo.x, hi.x), pick(k & 2, lo.y, hi.y), pick(k & 4, lo.z, hi.z)));
    let (mut min, mut max) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    for c in corners {
        let local = DVec3::new(c.dot(u), c.dot(v), c.dot(dir));
        (min, max) = (min.min(local), max.max(local));
    }
    let diagonal = (hi - lo).length();
    let (start, reach) = (min.z - 0.01 * diagonal, max.z - min.z + 0.02 * diagonal);
    let cell = DVec3::new((max.x - min.x) / grid as f64, (max.y - min.y) / grid as f64, 0.0);
    for i in 0..grid {
        for j in 0..grid {
            let ray = ((stream * grid as u64 + i as u64) * grid as u64) + j as u64;
            let a = min.x + (i as f64 + unit(ray, 0)) * cell.x;
            let b = min.y + (j as f64 + unit(ray, 1)) * cell.y;
            let origin = u * a + v * b + dir * start;
            let hits = mesh.crossings_along(origin, dir, reach, MERGE_HITS * diagonal);
            if hits.len() % 2 == 1 {
                continue;
            }
            for (k, pair) in hits.chunks_exact(2).enumerate() {
                let depth = pair[0] + unit(ray, 2 + k as u64) * (pair[1] - pair[0]);
                out.push(Sample { point: origin + dir * depth, weight: (pair[1] - pair[0]) * cell.x * cell.y });
            }
        }
    }
}

/// The coverage of `samples` by `patches` (tagged by patch, `reach` per tag: `reach(thickness)` for a patch
/// at mid-wall); the points out of reach are charged to the nearest of `faces` (tagged by face id). None
/// without samples.
pub fn coverage(samples: &[Sample], patches: &Triangles, reach: &[f64], faces: &Triangles) -> Option<Coverage> {
    let total: f64 = samples.iter().map(|s| s.weight).sum();
    if samples.is_empty() || total <= 0.0 {
        return None;
    }
    let mut covered = 0.0;
    let mut missed: BTreeMap<FaceId, f64> = BTreeMap::new();
    for s in samples {
        let reached = patches.nearest(s.point).is_some_and(|(k, d)| d <= reach[k]);
        if reached {
            covered += s.weight;
        } else if let Some((face, _)) = faces.nearest(s.point) {
            *missed.entry(face).or_default() += s.weight;
        }
    }
    let mut missed: Vec<Missed> = missed.into_iter().map(|(face, w)| Missed { face, share: w / total }).collect();
    // Most missed first; equal shares by face id (the map's order, kept by the stable sort).
    missed.sort_by(|a, b| b.share.total_cmp(&a.share));
    missed.truncate(MISSED_LISTED);
    Some(Coverage { share: covered / total, samples: samples.len(), missed })
}

/// How far from a patch at mid-wall of a wall `thickness` thick its material reaches.
pub fn reach(thickness: f64) -> f64 {
    REACH_SHARE * thickness
}

fn pick(bit: usize, lo: f64, hi: f64) -> f64 {
    if bit == 0 {
        lo
    } else {
        hi
    }
}

/// A fixed number in [0, 1) for (cell, slot): splitmix64 of both, so every run draws the same points.
fn unit(cell: u64, slot: u64) -> f64 {
    let mut z = cell.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ slot.wrapping_mul(0xD1B5_4A32_D192_ED03);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}

/// The point of triangle `t` nearest to `p` (Ericson, Real-Time Collision Detection, 5.1.5).
fn closest_on_triangle(p: DVec3, [a, b, c]: [DVec3; 3]) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthetic::cuboid;

    /// The rectangle [0, x] x [0, 4] at height z, as two triangles tagged `tag`.
    fn sheet_triangles(x: f64, z: f64, tag: usize) -> Vec<([DVec3; 3], usize)> {
        let (a, b, c, d) =
            (DVec3::new(0.0, 0.0, z), DVec3::new(x, 0.0, z), DVec3::new(x, 4.0, z), DVec3::new(0.0, 4.0, z));
        vec![([a, b, c], tag), ([a, c, d], tag)]
    }

    fn faces_of(graph: &crate::model::face_graph::FaceGraph) -> Triangles {
        Triangles::new(graph.faces.iter().flat_map(|f| {
            let m = f.mesh.as_ref().unwrap();
            m.triangles.iter().map(move |t| (t.map(|i| m.vertices[i as usize]), f.id))
        }))
    }

    #[test]
    fn the_weights_of_the_samples_add_up_to_the_volume() {
        let graph = cuboid(DVec3::ZERO, DVec3::new(10.0, 4.0, 2.0));
        let samples = material_samples(&SolidMesh::new(&graph).unwrap());
        let volume: f64 = samples.iter().map(|s| s.weight).sum();
        assert!(samples.len() >= MIN_POINTS, "{}", samples.len());
        assert!((volume - 80.0).abs() < 0.8, "{volume}");
        assert!(samples
            .iter()
            .all(|s| s.point.cmpge(DVec3::ZERO).all() && s.point.cmple(DVec3::new(10.0, 4.0, 2.0)).all()));
    }

    #[test]
    fn a_plate_is_covered_by_its_mid_plane_and_only_half_by_half_of_it() {
        let graph = cuboid(DVec3::ZERO, DVec3::new(10.0, 4.0, 2.0));
        let samples = material_samples(&SolidMesh::new(&graph).unwrap());
        let faces = faces_of(&graph);
        let whole = coverage(&samples, &Triangles::new(sheet_triangles(10.0, 1.0, 0)), &[reach(2.0)], &faces).unwrap();
        assert!(whole.share > 0.999 && whole.missed.is_empty(), "{whole:?}");
        // The left half only (x <= 5): the right half's material is missed, charged to the faces nearest it.
        let half = Triangles::new(sheet_triangles(5.0, 1.0, 0));
        let part = coverage(&samples, &half, &[reach(2.0)], &faces).unwrap();
        // Covered up to 1.5 beyond x = 5 (0.75 x 2): 6.5 of 10.
        assert!((part.share - 0.65).abs() < 0.02, "{part:?}");
        let missed: f64 = part.missed.iter().map(|m| m.share).sum();
        assert!((missed - 0.35).abs() < 0.02, "{part:?}");
    }

    #[test]
    fn a_patch_off_the_middle_by_more_than_the_reach_covers_less() {
        let graph = cuboid(DVec3::ZERO, DVec3::new(10.0, 4.0, 2.0));
        let samples = material_samples(&SolidMesh::new(&graph).unwrap());
        // A patch 3 above the plate's bottom, claiming 1.0 thick: it reaches down to z = 2.25 only.
        let off = coverage(&samples, &Triangles::new(sheet_triangles(10.0, 3.0, 0)), &[reach(1.0)], &faces_of(&graph))
            .unwrap();
        assert!(off.share < 0.001, "{off:?}");
        // No patch at all: nothing covered.
        let none = coverage(&samples, &Triangles::new(Vec::new()), &[], &faces_of(&graph)).unwrap();
        assert_eq!(none.share, 0.0);
    }

    #[test]
    fn the_nearest_point_of_a_triangle_from_each_region() {
        let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let near = |p: DVec3, want: DVec3| closest_on_triangle(p, t).distance(want) < 1e-12;
        assert!(near(DVec3::new(0.2, 0.2, 5.0), DVec3::new(0.2, 0.2, 0.0)), "inside");
        assert!(near(DVec3::new(-1.0, -1.0, 0.0), DVec3::ZERO), "corner a");
        assert!(near(DVec3::new(3.0, -0.5, 1.0), DVec3::X), "corner b");
        assert!(near(DVec3::new(-0.5, 3.0, 1.0), DVec3::Y), "corner c");
        assert!(near(DVec3::new(0.5, -2.0, 0.0), DVec3::new(0.5, 0.0, 0.0)), "edge ab");
        assert!(near(DVec3::new(-2.0, 0.5, 0.0), DVec3::new(0.0, 0.5, 0.0)), "edge ac");
        assert!(near(DVec3::new(1.0, 1.0, 0.0), DVec3::new(0.5, 0.5, 0.0)), "edge bc");
    }

    #[test]
    fn the_same_mesh_gives_the_same_samples() {
        let graph = cuboid(DVec3::ZERO, DVec3::new(10.0, 4.0, 2.0));
        let mesh = SolidMesh::new(&graph).unwrap();
        let (a, b) = (material_samples(&mesh), material_samples(&mesh));
        assert!(a.iter().zip(&b).all(|(x, y)| x.point == y.point && x.weight == y.weight) && a.len() == b.len());
    }
}
