//! Peeling dangling pieces: after the joints are grown and everything is split against everything, a piece of a
//! patch that does not lie in its own wall and hangs free is an overshoot, whatever made it.
//!
//! The rule is one for every joint: a piece is *out of its wall* when, at its inner point (moved to mid-wall),
//! the material across it along its normal is not its patch's thickness (it runs along another wall, or there is
//! none: the point is outside the solid). Such pieces also occur where a joint is right (the stretch of a rib
//! between the plate's skin and the plate's mid-surface lies in the plate), but those are held on both sides;
//! an overshoot past the wall it crossed is held along that crossing only, and the rest of its boundary is free.
//! So a piece out of its wall goes when a large share of its boundary is free, and only when taking it away
//! leaves no neighbour with a new free edge (a piece that other pieces hang on stays). An island of such pieces,
//! joined to no piece lying in its wall, goes whole; so does any island smaller than (2 t)^2, a fragment.

use crate::geom::inside::SolidMesh;
use crate::model::shapes::Fused;
use crate::trim::{largest_pieces, written_sets, Branch, TrimReason};

use super::PatchInfo;

/// Material across a piece up to this many times its patch's thickness is its own wall (a tapered wall measures
/// up to its thickest end; a wall crossed lengthwise measures its whole extent).
const OWN_WALL_FACTOR: f64 = 2.0;
/// An island of pieces (joined to no other) smaller than a square this many times its thickness wide is a
/// fragment (a sliver left where patches cross, a scrap cut off by the joints), not a wall: a shell element is no
/// smaller than the wall is thick, so it would hold at most four, joined to nothing; a floating fragment in a
/// crash model only flies off. A thin-walled solid is at least 5 t across (its thickness is at most a fifth of
/// its extent), so no whole solid's mid-surface is this small.
const FRAGMENT_SIDE: f64 = 2.0;
/// Share of a piece's boundary that must be free for it to dangle: an overshoot strip has one long side free
/// (about half its boundary); a piece held on two sides has at most its short ends free.
const FREE_SHARE: f64 = 0.25;

/// The pieces of `fused` (among `keep`) to peel off, as branches (`TrimReason::Dangling`).
pub(super) fn dangling(fused: &Fused, keep: &[bool], patches: &[PatchInfo], solids: &[SolidMesh]) -> Vec<Branch> {
    let out: Vec<bool> = (0..fused.faces.len()).map(|f| keep[f] && out_of_wall(fused, f, patches, solids)).collect();
    let mut kept = keep.to_vec();
    let mut peeled = Vec::new();
    // Round by round: a piece peeled may leave the next one (further out of its wall) hanging free.
    loop {
        let largest = largest_pieces(fused, &kept);
        let mut peel: Vec<bool> = (0..fused.faces.len())
            .map(|f| {
                kept[f]
                    && out[f]
                    && largest[fused.faces[f].patch] != Some(f)
                    && narrow(fused, f, patches)
                    && free_share(fused, &kept, f) >= FREE_SHARE
            })
            .collect();
        // A piece that would leave a piece of its wall with a new free edge stays (a piece out of its wall may
        // be left hanging: the next round judges it).
        loop {
            let held: Vec<usize> =
                (0..peel.len()).filter(|&f| peel[f] && holds_a_wall(fused, &kept, &peel, &out, f)).collect();
            if held.is_empty() {
                break;
            }
            for f in held {
                peel[f] = false;
            }
        }
        let round: Vec<usize> = (0..peel.len()).filter(|&f| peel[f]).collect();
        if round.is_empty() {
            break;
        }
        for &f in &round {
            kept[f] = false;
        }
        peeled.extend(round);
    }
    // An island of narrow pieces none of which lies in its own wall (cut off by the rounds, or made so) is no
    // wall's mid-surface, even the largest piece of its patch; nor is an island smaller than a square twice as
    // wide as its wall is thick, wherever it lies (`FRAGMENT_SIDE`). Islands are taken as the file will hold
    // them (`written_sets`): a piece joined to the rest only through an edge inside another piece is alone.
    for set in written_sets(fused, &kept) {
        let area: f64 = set.iter().map(|&f| fused.faces[f].area).sum();
        let thickness = set.iter().map(|&f| patches[fused.faces[f].patch].thickness).fold(0.0, f64::max);
        let side = FRAGMENT_SIDE * thickness;
        if area < side * side || set.iter().all(|&f| out[f] && narrow(fused, f, patches)) {
            for f in set {
                kept[f] = false;
                peeled.push(f);
            }
        }
    }
    peeled.sort_unstable();
    peeled
        .into_iter()
        .map(|f| {
            let face = &fused.faces[f];
            let mut crossing: Vec<usize> = face
                .edges
                .iter()
                .flat_map(|&e| fused.edges[e].faces.iter().copied())
                .filter(|&g| keep[g] && fused.faces[g].patch != face.patch)
                .map(|g| fused.faces[g].patch)
                .collect();
            crossing.sort_unstable();
            crossing.dedup();
            Branch { piece: f, patch: face.patch, area: face.area, width: 0.0, crossing, reason: TrimReason::Dangling }
        })
        .collect()
}

/// Whether piece `f` is no wider (2 x area / perimeter, the width of a band) than its patch's joints reach: an
/// overshoot is never wider than the growth or the offset that made it, while a wide piece that measures out of
/// its wall is a wall the measurement misread (a curved one seen from its centroid), not an overshoot.
fn narrow(fused: &Fused, f: usize, patches: &[PatchInfo]) -> bool {
    let face = &fused.faces[f];
    let perimeter: f64 = face.edges.iter().map(|&e| fused.edges[e].length).sum();
    perimeter > 0.0 && 2.0 * face.area / perimeter <= patches[face.patch].reach
}

/// Free length over boundary length of piece `f`.
fn free_share(fused: &Fused, keep: &[bool], f: usize) -> f64 {
    let (mut free, mut all) = (0.0, 0.0);
    for &e in &fused.faces[f].edges {
        let edge = &fused.edges[e];
        all += edge.length;
        if edge.faces.iter().filter(|&&g| keep[g]).count() == 1 {
            free += edge.length;
        }
    }
    if all > 0.0 {
        free / all
    } else {
        0.0
    }
}

/// Whether the material across piece `f`, at its inner point moved to mid-wall, is not its patch's wall.
fn out_of_wall(fused: &Fused, f: usize, patches: &[PatchInfo], solids: &[SolidMesh]) -> bool {
    let face = &fused.faces[f];
    let info = &patches[face.patch];
    let solid = &solids[info.solid];
    let p = face.point + face.normal * info.to_mid;
    if !solid.contains(p) {
        return true;
    }
    let reach = OWN_WALL_FACTOR * info.thickness;
    match (solid.exit(p, face.normal, reach), solid.exit(p, -face.normal, reach)) {
        (Some(up), Some(down)) => up + down > reach,
        _ => true,
    }
}

/// Whether taking piece `f` away (with the others marked `peel`) leaves a kept piece that lies in its wall with
/// a new free edge.
fn holds_a_wall(fused: &Fused, kept: &[bool], peel: &[bool], out: &[bool], f: usize) -> bool {
    fused.faces[f].edges.iter().any(|&e| {
        let faces = &fused.edges[e].faces;
        let on_edge = faces.iter().filter(|&&g| kept[g]).count();
        let staying: Vec<usize> = faces.iter().copied().filter(|&g| kept[g] && !peel[g]).collect();
        on_edge >= 2 && staying.len() == 1 && !out[staying[0]]
    })
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::model::shapes::{FusedEdge, FusedFace};
    use crate::synthetic;

    fn face(patch: usize, area: f64, point: DVec3, normal: DVec3, edges: Vec<usize>) -> FusedFace {
        FusedFace { patch, area, centroid: point, point, normal, edges }
    }

    fn edge(length: f64, faces: Vec<usize>) -> FusedEdge {
        FusedEdge { length, faces, points: Vec::new(), inside: Vec::new(), stem_end: false }
    }

    fn info() -> PatchInfo {
        PatchInfo {
            thickness: 2.0,
            to_mid: 0.0,
            solid: 0,
            body: 0,
            reach: 3.0,
            on_rim: 0.2,
            junction: false,
            wall: (0, 0),
            freeform: false,
        }
    }

    /// A plate 100 x 60 x 2 (the solid) whose mid-patch (patch 0, two halves) a wall's patch (patch 1) crosses
    /// at x = 50: above the plate the wall (its largest piece), below the plate's mid-surface its overshoot, a
    /// strip 1 high held along the crossing only. Beside them, a strip of the wall's patch inside the plate at
    /// x = 70 held by the right half of the plate alone (an edge of two pieces).
    fn plate_and_wall() -> (Fused, Vec<SolidMesh>) {
        let (x, z) = (DVec3::X, DVec3::Z);
        let faces = vec![
            face(0, 3000.0, DVec3::new(25.0, 30.0, 1.0), z, vec![0]),
            face(1, 1140.0, DVec3::new(50.0, 30.0, 10.0), x, vec![0, 1]),
            face(1, 60.0, DVec3::new(50.0, 30.0, 0.5), x, vec![0, 2, 3, 4]),
            face(0, 3000.0, DVec3::new(75.0, 30.0, 1.0), z, vec![0, 5]),
            face(1, 60.0, DVec3::new(70.0, 30.0, 0.5), x, vec![5, 6, 7, 8]),
        ];
        let edges = vec![
            edge(60.0, vec![0, 1, 2, 3]),
            edge(60.0, vec![1]),
            edge(60.0, vec![2]),
            edge(1.0, vec![2]),
            edge(1.0, vec![2]),
            edge(60.0, vec![3, 4]),
            edge(60.0, vec![4]),
            edge(1.0, vec![4]),
            edge(1.0, vec![4]),
        ];
        let mesh = SolidMesh::new(&synthetic::cuboid(DVec3::ZERO, DVec3::new(100.0, 60.0, 2.0))).unwrap();
        (Fused { handle: 0, faces, edges, invalid: vec![] }, vec![mesh])
    }

    #[test]
    fn the_overshoot_past_a_crossing_is_peeled_and_a_piece_holding_a_wall_stays() {
        let (fused, solids) = plate_and_wall();
        let peeled = dangling(&fused, &[true; 5], &[info(), info()], &solids);
        assert_eq!(peeled.iter().map(|b| (b.piece, b.reason)).collect::<Vec<_>>(), vec![(2, TrimReason::Dangling)]);
        assert_eq!(peeled[0].crossing, vec![0]);
    }

    #[test]
    fn an_island_of_pieces_out_of_their_wall_is_peeled_whole() {
        let (mut fused, solids) = plate_and_wall();
        // Patch 2's one piece, a strip inside the plate standing across it, joined to nothing: the largest piece of
        // its patch, yet no wall's mid-surface.
        fused.faces.push(face(2, 30.0, DVec3::new(20.0, 10.0, 0.5), DVec3::Y, vec![9]));
        fused.edges.push(edge(62.0, vec![5]));
        let peeled = dangling(&fused, &[true; 6], &[info(), info(), info()], &solids);
        assert_eq!(peeled.iter().map(|b| b.piece).collect::<Vec<_>>(), vec![2, 5]);
    }

    #[test]
    fn an_island_smaller_than_twice_its_thickness_squared_is_peeled_even_in_its_wall() {
        let (mut fused, solids) = plate_and_wall();
        // Patch 2's one piece lies in the plate's mid-plane, joined to nothing: 15.9 mm2 under 4 x 4 goes, 16.1
        // stays.
        fused.faces.push(face(2, 15.9, DVec3::new(20.0, 10.0, 1.0), DVec3::Z, vec![9]));
        fused.edges.push(edge(8.0, vec![5]));
        let peeled = dangling(&fused, &[true; 6], &[info(), info(), info()], &solids);
        assert_eq!(peeled.iter().map(|b| b.piece).collect::<Vec<_>>(), vec![2, 5]);
        fused.faces[5].area = 16.1;
        let peeled = dangling(&fused, &[true; 6], &[info(), info(), info()], &solids);
        assert_eq!(peeled.iter().map(|b| b.piece).collect::<Vec<_>>(), vec![2]);
    }

    #[test]
    fn a_piece_in_its_own_wall_is_never_peeled() {
        let (mut fused, solids) = plate_and_wall();
        // The overshoot turned to lie in the plate's plane: the plate's material is its own wall.
        fused.faces[2].normal = DVec3::Z;
        let peeled = dangling(&fused, &[true; 5], &[info(), info()], &solids);
        assert!(peeled.is_empty(), "{peeled:?}");
    }

    #[test]
    fn a_wide_piece_is_never_peeled() {
        let (mut fused, solids) = plate_and_wall();
        fused.faces[2].area = 400.0; // 2 x 400 / 122 = 6.6 wide, over the reach of 3
        let peeled = dangling(&fused, &[true; 5], &[info(), info()], &solids);
        assert!(peeled.is_empty(), "{peeled:?}");
    }
}
