//! Candidate pairs: faces whose bounding boxes come within t_max of each other, found with an R-tree
//! (O(n log n + k), never all pairs).

use rstar::{RTree, RTreeObject, AABB};

use crate::model::face_graph::{FaceGraph, FaceId};

struct FaceBox {
    face: FaceId,
    envelope: AABB<[f64; 3]>,
}

impl RTreeObject for FaceBox {
    type Envelope = AABB<[f64; 3]>;
    fn envelope(&self) -> Self::Envelope {
        self.envelope
    }
}

/// Sorted pairs (a < b) of faces whose boxes, each inflated by t_max / 2, intersect: every two faces closer
/// than t_max are among them.
pub fn candidate_pairs(graph: &FaceGraph, t_max: f64) -> Vec<(FaceId, FaceId)> {
    // A face the kernel could not describe whole has no trustworthy point, normal or mesh: it never pairs.
    let boxes: Vec<FaceBox> = graph
        .faces
        .iter()
        .filter(|f| f.problem.is_none())
        .map(|f| {
            let b = f.bbox.inflated(t_max * 0.5);
            FaceBox { face: f.id, envelope: AABB::from_corners(b.min.to_array(), b.max.to_array()) }
        })
        .collect();
    let envelopes: Vec<(FaceId, AABB<[f64; 3]>)> = boxes.iter().map(|b| (b.face, b.envelope)).collect();
    let tree = RTree::bulk_load(boxes);
    let mut out = Vec::new();
    for &(a, ref envelope) in &envelopes {
        for hit in tree.locate_in_envelope_intersecting(envelope) {
            if hit.face > a {
                out.push((a, hit.face));
            }
        }
    }
    out.sort_unstable();
    out
}
