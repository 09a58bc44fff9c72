//! What each made patch brings to stitching ([`PatchInfo`]): how far its joints reach, how near the rim its
//! free edges count as on it, whether a junction loop of its solid was filled.

use super::PatchInfo;
use crate::load::Part;
use crate::model::params::Position;
use crate::model::tolerance;
use crate::pairing::driver::SolidPairing;
use crate::pairing::levels;
use crate::pairing::PairKind;
use crate::patch::make::Made;
use crate::trim::branch_limit;

/// Per made patch (in order), what stitching needs to know of it.
/// `bodies`: the body of each solid.
pub fn patch_infos(
    part: &Part,
    pairings: &[SolidPairing],
    made: &[Made],
    position: Position,
    bodies: &[usize],
) -> Vec<PatchInfo> {
    // Per solid: some patch of it was made with a junction loop filled.
    let mut junctions = vec![false; part.solids.len()];
    for m in made {
        let junction = &pairings[m.solid - 1].junction;
        junctions[m.solid - 1] |= m.plan.fill.iter().any(|e| junction.binary_search(e).is_ok());
    }
    // Per solid, the wall of each pair group: the levels of a thickness step are one wall.
    let walls: Vec<Vec<usize>> = part
        .solids
        .iter()
        .zip(pairings)
        .map(|(solid, p)| levels::walls(&solid.graph, &p.pairing.roles, p.pairing.groups.len(), &p.tolerances))
        .collect();
    made.iter()
        .map(|m| {
            let tolerances = &pairings[m.solid - 1].tolerances;
            // On a skin the patch a joint grows to may lie up to half a thickness farther than its middle.
            let skin = position.to_mid(tolerances.t_max).abs();
            PatchInfo {
                thickness: m.plan.thickness.mean,
                to_mid: m.plan.to_mid,
                solid: m.solid - 1,
                body: bodies[m.solid - 1],
                reach: tolerances.joint_reach + skin,
                on_rim: tolerance::on_rim(m.plan.thickness.mean, part.solids[m.solid - 1].mesh_tolerance),
                junction: junctions[m.solid - 1],
                wall: (m.solid, walls[m.solid - 1][m.plan.group]),
                freeform: m.plan.kind == PairKind::Freeform,
            }
        })
        .collect()
}

/// The body of each patch.
pub fn patch_bodies(patches: &[PatchInfo]) -> Vec<usize> {
    patches.iter().map(|p| p.body).collect()
}

/// How far a branch may hang past each patch.
pub fn branch_limits(patches: &[PatchInfo]) -> Vec<f64> {
    patches.iter().map(|p| branch_limit(p.thickness, p.to_mid)).collect()
}
