//! The free edges of the stitched result: open (in the material: a joint not made) or on the rim, and how far
//! an edge stops short of the part's boundary.

use super::{joint, FreeEdges, PatchInfo};
use crate::geom::inside::SolidMesh;
use crate::model::shapes::{EdgeProbe, Fused, FusedEdge};
use crate::model::tolerance::SAME_THICKNESS;
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

/// Which free edges grow to the rim, and how far (`to_rim`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct RimGrowth {
    /// Curved edges too (a tube cut obliquely falls short on one side), but for a curved edge of a freeform
    /// patch. Its strip (ruled, or a face of the patch's own offset surface: both tried) leaves faces of the
    /// patch that fail the kernel's check once fused, and a broken file is worse than a gap the report names.
    pub curved: bool,
    /// Past the wall's end through its own thinner material too (`lip_exit`): for the edges the patches were
    /// made with (the joints pass), which end where their skins do. A later pass's free edges are those of
    /// strips and cuts, whose outside need not be the wall's own end.
    pub lips: bool,
}

/// How far the free edge `edge` of `face` must grow to reach the part's boundary, if it stops short of it (see
/// `joint::rim_shortfall`): straight edges, and curved ones as `growth` says.
pub(super) fn to_rim(
    fused: &Fused,
    edge: usize,
    face: usize,
    probe: &EdgeProbe,
    patches: &[PatchInfo],
    solids: &[SolidMesh],
    growth: RimGrowth,
) -> Option<Vec<f64>> {
    let patch = &patches[fused.faces[face].patch];
    let curved = !straight(&fused.edges[edge]);
    if (curved && !growth.curved) || freeform_curve(patch, &fused.edges[edge]) {
        return None;
    }
    shortfall(fused, face, probe, patches, solids, growth.lips)
}

/// Whether `edge` is a curved edge of a freeform patch: a strip of uneven lengths on it (ruled through points
/// nearly on the edge where it is short) comes out off the edge or leaves faces that fail the kernel's check, so
/// it grows neither to the rim nor stubs where it runs out of the material.
pub(super) fn freeform_curve(patch: &PatchInfo, edge: &FusedEdge) -> bool {
    patch.freeform && !straight(edge)
}

/// Whether an edge of the fused result is straight: its chord is STRAIGHT of its length.
pub(super) fn straight(edge: &FusedEdge) -> bool {
    let chord = match (edge.points.first(), edge.points.last()) {
        (Some(a), Some(b)) => a.distance(*b),
        _ => 0.0,
    };
    chord >= STRAIGHT * edge.length
}

/// How far the free edge of `face` stops short of the part's boundary, if it does (`joint::rim_shortfall`):
/// within half a thickness, or with `lips` through the wall's own thinner material (`lip_exit`).
fn shortfall(
    fused: &Fused,
    face: usize,
    probe: &EdgeProbe,
    patches: &[PatchInfo],
    solids: &[SolidMesh],
    lips: bool,
) -> Option<Vec<f64>> {
    let patch = &patches[fused.faces[face].patch];
    let solid = &solids[patch.solid];
    let reach = joint::RIM_REACH * patch.thickness + patch.on_rim;
    joint::rim_shortfall(
        probe,
        patch.to_mid,
        patch.on_rim,
        |q| solid.contains(q),
        |q, d, n| {
            let d = d.normalize_or_zero();
            let lip = || lips.then(|| lip_exit(solid, q, d, n.normalize_or_zero(), patch)).flatten();
            solid.exit(q, d, reach).or_else(lip)
        },
    )
}

/// The distance from `q` (at mid-wall) along `d` to the boundary, within the patch's joint reach, when the
/// material on the way is no thicker than the wall across its patch normal `n`: the wall runs on, thinner, past
/// its skins' edges to the boundary (a lip standing on a wall's end, a tongue, a chamfered or stepped edge).
/// Such material is the wall's own, too narrow to pair (`pairing::criteria`); a block or another wall on the
/// way (thicker across `n`) is not, and stops the growth; nor does it grow to a boundary met at a grazing angle
/// (`LIP_END_COS`).
fn lip_exit(solid: &SolidMesh, q: DVec3, d: DVec3, n: DVec3, patch: &PatchInfo) -> Option<f64> {
    let t = patch.thickness;
    let limit = t * (1.0 + SAME_THICKNESS) + patch.on_rim;
    let exit = solid.exit(q, d, patch.reach)?;
    let across = |p: DVec3| match (solid.exit(p, n, limit), solid.exit(p, -n, limit)) {
        (Some(a), Some(b)) => a + b <= limit,
        _ => false,
    };
    // The end it grows to faces the way it grows: met at a grazing angle, the boundary is the skin of another
    // wall the strip runs into, past the joint with it.
    let facing = |c: &[DVec3; 3]| (c[1] - c[0]).cross(c[2] - c[0]).normalize_or_zero().dot(d).abs() >= LIP_END_COS;
    if solid.nearest_where(q, d, patch.reach, facing).is_none_or(|end| end > exit + patch.on_rim) {
        return None;
    }
    let step = joint::PROBE_STEP * t;
    (1..).map(|j| j as f64 * step).take_while(|&s| s < exit).all(|s| across(q + d * s)).then_some(exit)
}

/// The boundary a wall's end grows to through its own material faces the way it grows within 60 degrees (cosine
/// 0.5): an end face, a chamfer or a rounding across the wall, not a skin along it.
const LIP_END_COS: f64 = 0.5;

/// An edge whose chord is this share of its length is straight.
const STRAIGHT: f64 = 0.999;

/// Sorts the free edges of the result into rim and open (the inside test of `decide`, or the edge stopping short
/// of the boundary by more than the rim tolerance); also the open length of each patch (indexed by patch).
pub(super) fn classify_free(
    fused: &Fused,
    free: &[(usize, usize)],
    probes: &[EdgeProbe],
    patches: &[PatchInfo],
    solids: &[SolidMesh],
) -> (FreeEdges, Vec<f64>) {
    let mut out = FreeEdges::default();
    let mut open_by_patch = vec![0.0; patches.len()];
    for (&(edge, face), p) in free.iter().zip(probes) {
        let length = fused.edges[edge].length;
        // Short of the rim is open too: the material goes on past the edge, if only for a round's width.
        if open(fused, face, p, patches, solids) || shortfall(fused, face, p, patches, solids, false).is_some() {
            out.open_edges += 1;
            out.open_length += length;
            open_by_patch[fused.faces[face].patch] += length;
        } else {
            out.rim_edges += 1;
            out.rim_length += length;
        }
    }
    (out, open_by_patch)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthetic::cuboid;

    fn patch(thickness: f64) -> PatchInfo {
        PatchInfo {
            thickness,
            to_mid: 0.0,
            solid: 0,
            body: 0,
            reach: 3.0,
            on_rim: 0.01,
            junction: false,
            wall: (0, 0),
            freeform: false,
        }
    }

    #[test]
    fn a_wall_runs_on_to_the_boundary_through_material_no_thicker_than_itself() {
        // Past the edge at x = 0 (mid-wall z = 0.7): material 1.4 thick across z, ending 1.5 away at x = 1.5.
        let solid = SolidMesh::new(&cuboid(DVec3::new(-10.0, 0.0, 0.0), DVec3::new(11.5, 60.0, 1.4))).unwrap();
        let q = DVec3::new(0.0, 30.0, 0.7);
        let exit = lip_exit(&solid, q, DVec3::X, DVec3::Z, &patch(2.0)).expect("a lip of a 2 mm wall");
        assert!((exit - 1.5).abs() < 1e-9, "{exit}");
        // The same material past the edge of a 1 mm wall is a block: thicker across than the wall.
        assert_eq!(lip_exit(&solid, q, DVec3::X, DVec3::Z, &patch(1.0)), None);
        // Farther than the joint reach: not the wall's end.
        assert_eq!(lip_exit(&solid, q - DVec3::X * 2.0, DVec3::X, DVec3::Z, &patch(2.0)), None);
        // A strip leaving at 63 degrees to the top skin would end on it at a grazing angle: a skin, not an end.
        let (d, n) = (DVec3::new(1.0, 0.0, 0.5).normalize(), DVec3::new(-0.5, 0.0, 1.0).normalize());
        assert_eq!(lip_exit(&solid, q, d, n, &patch(2.0)), None);
        let steep = DVec3::new(1.0, 0.0, 2.0).normalize();
        assert!(lip_exit(&solid, q, steep, steep.cross(DVec3::Y), &patch(2.0)).is_some(), "ends on the top, facing it");
    }
}
