//! The free edges of the stitched result: open (in the material: a joint not made) or on the rim, and how far
//! an edge stops short of the part's boundary.

use std::collections::BTreeSet;

use super::{joint, FreeEdges, PatchInfo};
use crate::geom::inside::SolidMesh;
use crate::model::shapes::{EdgeProbe, Fused, FusedEdge};
use glam::DVec3;

/// Whether the free edge of `face` lies in the material of its patch's solid (`joint::is_open`).
pub(super) fn open(fused: &Fused, face: usize, probe: &EdgeProbe, patches: &[PatchInfo], solids: &[SolidMesh]) -> bool {
    outside_in_material(fused, face, probe, patches, solids, false)
}

/// Whether the free edge of `face` is open once a point tested on a face parallel to the patch counts as in the
/// material (`joint::LEVEL_FACE_SHARE`): the edge of a wall's level whose middle runs along a thinner level's
/// floor. Only the step search takes such an edge as open; where it bridges nothing the edge is the rim, as the
/// boundary runs through it (a counterbore half the wall deep round a hole), and is reported so.
pub(super) fn open_on_level(
    fused: &Fused,
    face: usize,
    probe: &EdgeProbe,
    patches: &[PatchInfo],
    solids: &[SolidMesh],
) -> bool {
    outside_in_material(fused, face, probe, patches, solids, true)
}

/// `joint::is_open` on the patch's solid; with `levels`, a point on a face parallel to the patch counts as in it.
fn outside_in_material(
    fused: &Fused,
    face: usize,
    probe: &EdgeProbe,
    patches: &[PatchInfo],
    solids: &[SolidMesh],
    levels: bool,
) -> bool {
    let patch = &patches[fused.faces[face].patch];
    let (solid, step) = (&solids[patch.solid], joint::PROBE_STEP * patch.thickness);
    let within = joint::LEVEL_FACE_SHARE * step;
    let on_level = |q: DVec3, n: DVec3| levels && solid.on_face_across(q, n, within, joint::LEVEL_FACE_COS);
    joint::is_open(probe, step, patch.to_mid, |q, n| solid.contains(q) || on_level(q, n))
}

/// How far the free edge `edge` of `face` must grow to reach the part's boundary, if it stops short of it (see
/// `joint::rim_shortfall`): straight and curved edges alike (a tube cut obliquely falls short on one side) when
/// `curved`, but for a curved edge of a freeform patch. Its strip (ruled, or a face of the patch's own offset
/// surface: both tried) leaves faces of the patch that fail the kernel's check once fused, and a broken file is
/// worse than a gap the report names.
pub(super) fn to_rim(
    fused: &Fused,
    edge: usize,
    face: usize,
    probe: &EdgeProbe,
    patches: &[PatchInfo],
    solids: &[SolidMesh],
    curved: bool,
) -> Option<Vec<f64>> {
    let patch = &patches[fused.faces[face].patch];
    if (patch.freeform || !curved) && !straight(&fused.edges[edge]) {
        return None;
    }
    shortfall(fused, face, probe, patches, solids)
}

/// Whether an edge of the fused result is straight: its chord is STRAIGHT of its length.
pub(super) fn straight(edge: &FusedEdge) -> bool {
    let chord = match (edge.points.first(), edge.points.last()) {
        (Some(a), Some(b)) => a.distance(*b),
        _ => 0.0,
    };
    chord >= STRAIGHT * edge.length
}

/// How far the free edge of `face` stops short of the part's boundary, if it does (`joint::rim_shortfall`).
fn shortfall(
    fused: &Fused,
    face: usize,
    probe: &EdgeProbe,
    patches: &[PatchInfo],
    solids: &[SolidMesh],
) -> Option<Vec<f64>> {
    let patch = &patches[fused.faces[face].patch];
    let solid = &solids[patch.solid];
    let reach = joint::RIM_REACH * patch.thickness + patch.on_rim;
    joint::rim_shortfall(
        probe,
        patch.to_mid,
        patch.on_rim,
        |q| solid.contains(q),
        |q, d| solid.exit(q, d.normalize_or_zero(), reach),
    )
}

/// An edge whose chord is this share of its length is straight.
const STRAIGHT: f64 = 0.999;

/// Sorts the free edges of the result into rim and open (the inside test of `decide`, or the edge stopping short
/// of the boundary by more than the rim tolerance); also the patches with an open edge.
pub(super) fn classify_free(
    fused: &Fused,
    free: &[(usize, usize)],
    probes: &[EdgeProbe],
    patches: &[PatchInfo],
    solids: &[SolidMesh],
) -> (FreeEdges, BTreeSet<usize>) {
    let mut out = FreeEdges::default();
    let mut open_patches = BTreeSet::new();
    for (&(edge, face), p) in free.iter().zip(probes) {
        let length = fused.edges[edge].length;
        // Short of the rim is open too: the material goes on past the edge, if only for a round's width.
        if open(fused, face, p, patches, solids) || shortfall(fused, face, p, patches, solids).is_some() {
            out.open_edges += 1;
            out.open_length += length;
            open_patches.insert(fused.faces[face].patch);
        } else {
            out.rim_edges += 1;
            out.rim_length += length;
        }
    }
    (out, open_patches)
}
