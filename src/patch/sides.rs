//! Which skin of each wall is its top. The skins of neighbouring walls that run into each other (the outer
//! skins of an L, a bend's outer skin and the flats' beside it, also across a fillet) are the same side of the
//! sheet; choosing the top side of every wall that way makes the patch normals agree across joints and lets
//! patches placed on a skin (`--position top|bottom`) meet their neighbours.
//!
//! The sides form a graph: a link between (wall g, side X) and (wall k, side Y) says "X and Y are the same side
//! of the sheet", weighted by the length of the edges that say so. A T-joint says both sides of the rib are the
//! plate's same side, a contradiction: links are taken longest first (a maximum spanning forest) and the ones
//! that contradict the links taken already are dropped.

use std::collections::BTreeMap;

use crate::model::face_graph::{FaceGraph, FaceId};
use crate::pairing::{FaceRole, Pairing, Side};

/// The skin a face is: (group, side), or None for faces that are no skin.
fn skin(roles: &[FaceRole], face: FaceId) -> Option<(usize, Side)> {
    match roles[face] {
        FaceRole::Pair { group, side } => Some((group, side)),
        _ => None,
    }
}

/// Two skins (pair group, side) that run into each other, the lower group first.
type SkinLink = ((usize, Side), (usize, Side));

/// Skins that run into each other, with the length of the edges between them: directly, or through a
/// connecting or suppressed face (a fillet between two walls) touching both. Keyed by ((g, X), (k, Y)) with g < k.
fn links(graph: &FaceGraph, pairing: &Pairing) -> BTreeMap<SkinLink, f64> {
    let roles = &pairing.roles;
    let mut out: BTreeMap<SkinLink, f64> = BTreeMap::new();
    let mut add = |a: (usize, Side), b: (usize, Side), length: f64| {
        if a.0 != b.0 {
            *out.entry(if a.0 < b.0 { (a, b) } else { (b, a) }).or_insert(0.0) += length;
        }
    };
    // Skins beside each connecting face, with the length they share with it.
    let mut beside: BTreeMap<FaceId, BTreeMap<(usize, Side), f64>> = BTreeMap::new();
    for edge in &graph.edges {
        for (i, &f) in edge.faces.iter().enumerate() {
            for &h in &edge.faces[i + 1..] {
                match (skin(roles, f), skin(roles, h)) {
                    (Some(a), Some(b)) => add(a, b, edge.length),
                    (Some(a), None) | (None, Some(a)) => {
                        let other = if skin(roles, f).is_some() { h } else { f };
                        if matches!(roles[other], FaceRole::Connecting { .. } | FaceRole::Suppressed) {
                            *beside.entry(other).or_default().entry(a).or_insert(0.0) += edge.length;
                        }
                    }
                    (None, None) => {}
                }
            }
        }
    }
    for skins in beside.values() {
        let skins: Vec<(&(usize, Side), &f64)> = skins.iter().collect();
        for (i, &(&a, &la)) in skins.iter().enumerate() {
            for &(&b, &lb) in &skins[i + 1..] {
                add(a, b, la.min(lb));
            }
        }
    }
    out
}

/// A union-find forest whose nodes carry their parity relative to their parent (1: opposite top sides).
struct Parity {
    parent: Vec<usize>,
    parity: Vec<u8>,
}

impl Parity {
    /// The root of `x` and x's parity relative to it; the path is compressed on the way back, so chains of
    /// links (one wall after another along a sheet) do not make later look-ups walk them again.
    fn root(&mut self, x: usize) -> (usize, u8) {
        let mut path = Vec::new();
        let mut node = x;
        while self.parent[node] != node {
            path.push(node);
            node = self.parent[node];
        }
        let root = node;
        // From the node nearest the root outwards, each node's parity to the root.
        for &n in path.iter().rev() {
            let parent = self.parent[n];
            if parent != root {
                self.parity[n] ^= self.parity[parent];
            }
            self.parent[n] = root;
        }
        (root, if x == root { 0 } else { self.parity[x] })
    }
}

fn bit(side: Side) -> u8 {
    u8::from(side == Side::B)
}

/// The top side of every pair group: the reference side of the largest group of each set of linked walls, and
/// from it the linked sides of the others. A group with no link keeps its reference side.
pub fn top_sides(graph: &FaceGraph, pairing: &Pairing) -> Vec<Side> {
    let n = pairing.groups.len();
    let mut forest = Parity { parent: (0..n).collect(), parity: vec![0; n] };
    let mut ordered: Vec<(SkinLink, f64)> = links(graph, pairing).into_iter().collect();
    // Longest first; the key order (group ids) breaks ties, so the result does not depend on the map.
    ordered.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
    for (((g, x), (k, y)), _) in ordered {
        let (rg, pg) = forest.root(g);
        let (rk, pk) = forest.root(k);
        if rg != rk {
            // top(g) is X exactly when top(k) is Y: their flags differ by bit(X) ^ bit(Y).
            forest.parent[rk] = rg;
            forest.parity[rk] = pg ^ pk ^ bit(x) ^ bit(y);
        }
    }
    let area = |g: usize| pairing.groups[g].overlap_area;
    let mut leader: BTreeMap<usize, usize> = BTreeMap::new();
    for g in 0..n {
        let (root, _) = forest.root(g);
        let best = leader.entry(root).or_insert(g);
        if area(g) > area(*best) {
            *best = g;
        }
    }
    (0..n)
        .map(|g| {
            let (root, pg) = forest.root(g);
            let lead = leader[&root];
            let (_, pl) = forest.root(lead);
            let flag = bit(pairing.groups[lead].reference) ^ pl ^ pg;
            if flag == 1 {
                Side::B
            } else {
                Side::A
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::model::face_graph::Convexity;
    use crate::model::tolerance::Tolerances;
    use crate::pairing::detect;
    use crate::synthetic;

    /// The side of `group` holding `face`.
    fn side_of(pairing: &Pairing, face: FaceId) -> (usize, Side) {
        skin(&pairing.roles, face).expect("a skin")
    }

    #[test]
    fn the_outer_skins_of_an_l_are_one_side() {
        // Leg 1: bottom z = 0 (outer, 0) under top z = 2 (inner, 1); leg 2: x = 0 (outer, 2) beside x = 2
        // (inner, 3). The outer skins meet at the convex corner, the inner ones at the concave one.
        let faces = vec![
            synthetic::rect(DVec3::ZERO, DVec3::Y * 40.0, DVec3::X * 60.0, -DVec3::Z),
            synthetic::rect(DVec3::new(2.0, 0.0, 2.0), DVec3::X * 58.0, DVec3::Y * 40.0, DVec3::Z),
            synthetic::rect(DVec3::ZERO, DVec3::Z * 50.0, DVec3::Y * 40.0, -DVec3::X),
            synthetic::rect(DVec3::new(2.0, 0.0, 2.0), DVec3::Y * 40.0, DVec3::Z * 48.0, DVec3::X),
        ];
        let g = synthetic::graph(faces, &[(0, 2, Convexity::Convex), (1, 3, Convexity::Concave)]);
        let pairing = detect(&g, &Tolerances::new(80.0, 3.0, 0.05), &[true; 4]);
        assert_eq!(pairing.groups.len(), 2);
        let top = top_sides(&g, &pairing);
        let on_top = |face| {
            let (group, side) = side_of(&pairing, face);
            top[group] == side
        };
        assert_eq!(on_top(0), on_top(2), "outer skins on one side");
        assert_eq!(on_top(1), on_top(3), "inner skins on one side");
        assert_ne!(on_top(0), on_top(1));
    }

    #[test]
    fn a_lone_wall_keeps_its_reference_side_on_top() {
        let g = synthetic::cuboid(DVec3::ZERO, DVec3::new(100.0, 60.0, 2.0));
        let pairing = detect(&g, &Tolerances::new(120.0, 3.0, 0.05), &[true; 6]);
        assert_eq!(top_sides(&g, &pairing), vec![pairing.groups[0].reference]);
    }
}
