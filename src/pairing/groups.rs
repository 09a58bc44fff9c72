//! Pair groups (one face may pair with many: a plate's bottom with the pieces of its top between ribs) and
//! the role of every face (Sheen et al. Table 1).

use serde::Serialize;

use super::{NearMiss, Pair, PairKind, Thickness};
use crate::model::face_graph::{FaceGraph, FaceId};

/// The two skins of a wall; `A` holds the group's lowest face id.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize)]
pub enum Side {
    A,
    B,
}

impl Side {
    fn other(self) -> Side {
        match self {
            Side::A => Side::B,
            Side::B => Side::A,
        }
    }
}

/// Faces connected through pairs: the two skins of one wall.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PairGroup {
    pub id: usize,
    /// Faces of side A and side B, each sorted.
    pub sides: [Vec<FaceId>; 2],
    /// The side with the larger total area: its faces are offset to make the mid-patch.
    pub reference: Side,
    /// The kind covering the largest overlap area.
    pub kind: PairKind,
    /// Overlap-weighted mean, and range, over the group's pairs.
    pub thickness: Thickness,
    pub overlap_area: f64,
    /// Indices into `Pairing::pairs`.
    pub pairs: Vec<usize>,
    /// Faces that would have to be on both sides (an odd cycle of pairs): the grouping is doubtful there.
    pub side_conflicts: Vec<FaceId>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "role", rename_all = "snake_case")]
pub enum FaceRole {
    /// A skin of a wall, part of pair group `group`.
    Pair { group: usize, side: Side },
    /// A side face joining the two skins of group `group` (it becomes an edge of the mid-surface).
    Thickness { group: usize },
    /// Joins walls of different groups (a fillet, an unpaired bend): bridged when stitching.
    /// `near_miss`: its closest candidate partner and why it failed (a connecting face as large as a wall
    /// with a near miss is a wall the tests missed).
    Connecting {
        groups: Vec<usize>,
        #[serde(skip_serializing_if = "Option::is_none")]
        near_miss: Option<NearMiss>,
    },
    /// Left out of pairing on purpose (a suppressed small feature).
    Suppressed,
    /// Nothing to pair with; `near_miss` is the candidate that came closest and why it failed.
    Unpaired { near_miss: Option<NearMiss> },
}

impl FaceRole {
    /// Why an unpaired face found no partner (None for the other roles).
    pub fn unpaired_reason(&self) -> Option<String> {
        match self {
            FaceRole::Unpaired { near_miss: Some(m) } => {
                Some(format!("best candidate face {}: {}", m.candidate, m.rejection.describe()))
            }
            FaceRole::Unpaired { near_miss: None } => Some("no face within t_max".to_string()),
            _ => None,
        }
    }
}

pub fn group_and_classify(
    graph: &FaceGraph,
    pairs: &[Pair],
    near: &[Option<NearMiss>],
    pairable: &[bool],
) -> (Vec<PairGroup>, Vec<FaceRole>) {
    let n = graph.faces.len();
    let mut partners: Vec<Vec<(FaceId, usize)>> = vec![Vec::new(); n];
    for (i, p) in pairs.iter().enumerate() {
        let [a, b] = p.faces;
        partners[a].push((b, i));
        partners[b].push((a, i));
    }

    // Components in order of their lowest face id: group ids are stable for a given input.
    let mut group_of: Vec<Option<usize>> = vec![None; n];
    let mut side_of: Vec<Side> = vec![Side::A; n];
    let mut groups: Vec<PairGroup> = Vec::new();
    for start in 0..n {
        if partners[start].is_empty() || group_of[start].is_some() {
            continue;
        }
        let id = groups.len();
        let mut group = PairGroup {
            id,
            sides: [Vec::new(), Vec::new()],
            reference: Side::A,
            kind: PairKind::Parallel,
            thickness: Thickness::uniform(0.0),
            overlap_area: 0.0,
            pairs: Vec::new(),
            side_conflicts: Vec::new(),
        };
        group_of[start] = Some(id);
        side_of[start] = Side::A;
        let mut queue = std::collections::VecDeque::from([start]);
        while let Some(f) = queue.pop_front() {
            group.sides[side_of[f] as usize].push(f);
            for &(g, pair) in &partners[f] {
                if f < g {
                    group.pairs.push(pair);
                }
                match group_of[g] {
                    None => {
                        group_of[g] = Some(id);
                        side_of[g] = side_of[f].other();
                        queue.push_back(g);
                    }
                    Some(_) if side_of[g] == side_of[f] => group.side_conflicts.push(g.max(f)),
                    Some(_) => {}
                }
            }
        }
        finish_group(&mut group, graph, pairs);
        groups.push(group);
    }

    let roles = (0..n)
        .map(|f| {
            if !pairable[f] {
                return FaceRole::Suppressed;
            }
            if let Some(group) = group_of[f] {
                return FaceRole::Pair { group, side: side_of[f] };
            }
            // A suppressed round between this face and a skin (a rib top with rounded edges) does not hide
            // the skin: the face still joins the wall's two sides.
            let neighbours = super::criteria::reach(graph, f, pairable);
            let joined = neighbours.iter().find_map(|&a| {
                let ga = group_of[a]?;
                neighbours.iter().any(|&b| group_of[b] == Some(ga) && side_of[b] != side_of[a]).then_some(ga)
            });
            if let Some(group) = joined {
                return FaceRole::Thickness { group };
            }
            let mut touching: Vec<usize> = neighbours.iter().filter_map(|&a| group_of[a]).collect();
            touching.sort_unstable();
            touching.dedup();
            if !touching.is_empty() {
                return FaceRole::Connecting { groups: touching, near_miss: near[f].clone() };
            }
            FaceRole::Unpaired { near_miss: near[f].clone() }
        })
        .collect();
    (groups, roles)
}

fn finish_group(group: &mut PairGroup, graph: &FaceGraph, pairs: &[Pair]) {
    for side in &mut group.sides {
        side.sort_unstable();
    }
    group.pairs.sort_unstable();
    group.side_conflicts.sort_unstable();
    group.side_conflicts.dedup();
    let area = |side: &Vec<FaceId>| side.iter().map(|&f| graph.faces[f].area).sum::<f64>();
    group.reference = if area(&group.sides[1]) > area(&group.sides[0]) { Side::B } else { Side::A };

    let mut by_kind: Vec<(PairKind, f64)> = Vec::new();
    let (mut weighted, mut total) = (0.0, 0.0);
    let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
    for &i in &group.pairs {
        let p = &pairs[i];
        weighted += p.thickness.mean * p.overlap_area;
        total += p.overlap_area;
        min = min.min(p.thickness.min);
        max = max.max(p.thickness.max);
        match by_kind.iter_mut().find(|(k, _)| *k == p.kind) {
            Some((_, a)) => *a += p.overlap_area,
            None => by_kind.push((p.kind, p.overlap_area)),
        }
    }
    by_kind.sort_by(|x, y| y.1.total_cmp(&x.1).then(x.0.cmp(&y.0)));
    group.kind = by_kind.first().map(|k| k.0).unwrap_or(PairKind::Parallel);
    group.overlap_area = total;
    let mean = if total > 0.0 { weighted / total } else { 0.5 * (min + max) };
    group.thickness = Thickness { mean, min, max };
}
