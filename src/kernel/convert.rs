//! Wire replies into the domain shapes of `model::shapes`, and domain placements into their wire form: the one
//! place where the protocol meets the stages.

use super::protocol as wire;
use crate::model::shapes::{EdgeProbe, Fused, FusedEdge, FusedFace, Hit, Placement, Shells};

impl From<wire::Fused> for Fused {
    fn from(w: wire::Fused) -> Fused {
        Fused {
            handle: w.handle,
            faces: w.faces.into_iter().map(FusedFace::from).collect(),
            edges: w.edges.into_iter().map(FusedEdge::from).collect(),
            invalid: w.invalid,
        }
    }
}

impl From<wire::FusedFace> for FusedFace {
    fn from(w: wire::FusedFace) -> FusedFace {
        FusedFace {
            patch: w.patch,
            area: w.area,
            centroid: w.centroid,
            point: w.point,
            normal: w.normal,
            edges: w.edges,
        }
    }
}

impl From<wire::FusedEdge> for FusedEdge {
    fn from(w: wire::FusedEdge) -> FusedEdge {
        FusedEdge { length: w.length, faces: w.faces, points: w.points, inside: w.inside, stem_end: w.stem_end }
    }
}

impl From<wire::Shells> for Shells {
    fn from(w: wire::Shells) -> Shells {
        Shells {
            handle: w.handle,
            count: w.shells,
            components: w.components,
            faces: w.faces,
            valid: w.valid,
            invalid: w.invalid,
            edges: w.edges,
            vertices: w.vertices,
            free_edges: w.free_edges,
            nonmanifold_edges: w.nonmanifold_edges,
        }
    }
}

impl From<wire::Hit> for Hit {
    fn from(w: wire::Hit) -> Hit {
        Hit { face: w.face, distance: w.distance, gap: w.gap }
    }
}

impl From<wire::EdgeProbe> for EdgeProbe {
    fn from(w: wire::EdgeProbe) -> EdgeProbe {
        EdgeProbe {
            points: w.points,
            normals: w.normals,
            outward: w.outward,
            hits: w.hits.into_iter().map(|hits| hits.into_iter().map(Hit::from).collect()).collect(),
        }
    }
}

impl From<&Placement> for wire::Placement {
    fn from(p: &Placement) -> wire::Placement {
        match *p {
            Placement::Offset(d) => wire::Placement::Offset(d),
            Placement::Plane { origin, normal } => wire::Placement::Plane { origin, normal },
        }
    }
}
