//! A box index over the triangles of one mesh, built on first use, so that a ray or box query touches only the
//! triangles near it: a perforated skin has tens of thousands of triangles, and every hole's wall queries it.

use std::sync::OnceLock;

use glam::DVec3;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{RTree, AABB};

type Entry = GeomWithData<Rectangle<[f64; 3]>, u32>;

/// Derived from the mesh it belongs to: it compares equal to any other and is never serialized.
#[derive(Clone, Default)]
pub struct TriangleIndex(OnceLock<RTree<Entry>>);

impl TriangleIndex {
    /// The indices of the `triangles` whose boxes meet the box `lo`..`hi`, in no particular order.
    pub fn meeting<'a>(
        &'a self,
        vertices: &[DVec3],
        triangles: &[[u32; 3]],
        lo: DVec3,
        hi: DVec3,
    ) -> impl Iterator<Item = usize> + 'a {
        let tree = self.0.get_or_init(|| {
            let entries = triangles
                .iter()
                .enumerate()
                .map(|(k, t)| {
                    let p = t.map(|i| vertices[i as usize]);
                    let (a, b) = (p[0].min(p[1]).min(p[2]), p[0].max(p[1]).max(p[2]));
                    GeomWithData::new(Rectangle::from_corners(a.to_array(), b.to_array()), k as u32)
                })
                .collect();
            RTree::bulk_load(entries)
        });
        tree.locate_in_envelope_intersecting(&AABB::from_corners(lo.to_array(), hi.to_array())).map(|e| e.data as usize)
    }
}

impl PartialEq for TriangleIndex {
    fn eq(&self, _: &TriangleIndex) -> bool {
        true
    }
}

impl std::fmt::Debug for TriangleIndex {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(if self.0.get().is_some() { "TriangleIndex(built)" } else { "TriangleIndex" })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_box_query_finds_the_triangles_it_meets_and_no_other() {
        let vertices: Vec<DVec3> = (0..10)
            .flat_map(|k| {
                let x = 10.0 * k as f64;
                [DVec3::new(x, 0.0, 0.0), DVec3::new(x + 1.0, 0.0, 0.0), DVec3::new(x, 1.0, 0.0)]
            })
            .collect();
        let triangles: Vec<[u32; 3]> = (0..10u32).map(|k| [3 * k, 3 * k + 1, 3 * k + 2]).collect();
        let index = TriangleIndex::default();
        let mut found: Vec<usize> =
            index.meeting(&vertices, &triangles, DVec3::new(29.5, 0.5, -1.0), DVec3::new(40.5, 0.6, 1.0)).collect();
        found.sort();
        assert_eq!(found, vec![3, 4]);
        // Touching a box's face counts; a box beside every triangle finds none.
        assert_eq!(
            index.meeting(&vertices, &triangles, DVec3::new(91.0, 0.0, 0.0), DVec3::new(95.0, 1.0, 0.0)).count(),
            1
        );
        assert_eq!(
            index.meeting(&vertices, &triangles, DVec3::new(2.0, 0.0, 0.0), DVec3::new(9.0, 1.0, 0.0)).count(),
            0
        );
    }
}
