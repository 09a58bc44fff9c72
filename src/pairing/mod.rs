//! Face-pair detection (Sheen et al. 5.1, after Rezayat): which faces are the two skins of a wall.
//!
//! Candidates come from an R-tree over face boxes inflated by t_max (`candidates`); each candidate is tested
//! by the criteria of its surface kinds (`criteria`); accepted pairs are grouped one-to-many and every face
//! gets a role (`groups`); pairs that continue each other across smooth edges share one thickness
//! (`continuation`). The default t_max is estimated from the part (`estimate`).

pub(crate) mod candidates;
pub(crate) mod continuation;
pub(crate) mod criteria;
pub(crate) mod driver;
pub(crate) mod estimate;
pub(crate) mod features;
pub(crate) mod groups;
pub(crate) mod isolation;
pub(crate) mod levels;
pub(crate) mod overlap;
pub(crate) mod wall_class;

use serde::Serialize;

use crate::model::face_graph::{FaceGraph, FaceId};
use crate::model::tolerance::Tolerances;

pub use groups::{FaceRole, PairGroup, Side};

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PairKind {
    Parallel,
    Draft,
    Cylindrical,
    Conical,
    Spherical,
    Toroidal,
    Freeform,
}

impl PairKind {
    pub fn name(self) -> &'static str {
        match self {
            PairKind::Parallel => "parallel",
            PairKind::Draft => "draft",
            PairKind::Cylindrical => "cylindrical",
            PairKind::Conical => "conical",
            PairKind::Spherical => "spherical",
            PairKind::Toroidal => "toroidal",
            PairKind::Freeform => "freeform",
        }
    }
}

/// Thickness across a pair: mean over the overlap, and its range where it varies (draft, freeform).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Thickness {
    pub mean: f64,
    pub min: f64,
    pub max: f64,
}

impl Thickness {
    pub fn uniform(t: f64) -> Thickness {
        Thickness { mean: t, min: t, max: t }
    }
}

/// Two faces found to be the opposite skins of one wall.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Pair {
    /// Sorted face ids.
    pub faces: [FaceId; 2],
    pub kind: PairKind,
    pub thickness: Thickness,
    /// Area of one face projected onto the other that lies on it.
    pub overlap_area: f64,
}

impl Pair {
    /// The face paired with `face` (one of the two).
    pub fn other(&self, face: FaceId) -> FaceId {
        if self.faces[0] == face {
            self.faces[1]
        } else {
            self.faces[0]
        }
    }
}

/// Why a candidate did not pair. Variants are ordered by how far the candidate got through the tests, so the
/// greatest rejection of a face is its most telling one.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "test", rename_all = "snake_case")]
pub enum Rejection {
    /// Surface kinds that cannot be the two skins of one wall (a plane and a cylinder...).
    Incompatible {
        kinds: [&'static str; 2],
    },
    /// Normals neither opposite nor within the draft limit.
    Angle {
        degrees: f64,
        limit_degrees: f64,
    },
    /// Curved faces that do not share their axis or centre.
    NotCoaxial {
        offset: f64,
    },
    /// Both faces have the material on the same side (two shafts, two holes...).
    SameSense,
    /// The other face is not behind this one, so no material lies between them.
    NotFacing,
    Distance {
        distance: f64,
        limit: f64,
    },
    Overlap {
        share: f64,
        limit: f64,
    },
    /// A freeform pair whose distance varies too much to be one wall.
    Spread {
        min: f64,
        max: f64,
    },
    /// Both faces are narrower than the distance between them (the sides of a stub, not a wall), or
    /// (`top`) the narrower one is a planar face standing proud, the top of a stub.
    Stub {
        width: f64,
        thickness: f64,
        top: bool,
    },
    /// A planar face narrower than its distance to its partner, which pairs at another thickness with a face
    /// wide enough to be a wall: a minor level of that wall (a groove's floor, a rebate or a bead along it).
    MinorLevel {
        width: f64,
        thickness: f64,
        wall: f64,
    },
    /// A planar face narrower than its distance to a wider partner, neither of them pairing with anything else:
    /// the material between is a lip or bead along a wall's edge (measured along the wall), not a wall.
    Lip {
        width: f64,
        thickness: f64,
    },
    /// Both faces run from one skin of a wider wall to its other skin: the material between them is a web of
    /// that wall (between two holes of a perforated sheet), which the wall's own patch already spans.
    Web {
        thickness: f64,
        sheet: f64,
    },
    /// Faces farther apart than t_max with another face between them across most of the smaller one: the
    /// outer skins of two walls lying one on the other (a hemmed or doubled sheet, layers a gap apart), each
    /// wall already paired on its own.
    Stacked {
        thickness: f64,
        between: f64,
    },
}

impl Rejection {
    fn stage(&self) -> u8 {
        match self {
            Rejection::Incompatible { .. } => 0,
            Rejection::Angle { .. } => 1,
            Rejection::NotCoaxial { .. } => 2,
            Rejection::SameSense => 3,
            Rejection::NotFacing => 4,
            Rejection::Distance { .. } => 5,
            // Faces that overlap nowhere (a face beside this one, not across it) say less than a partner across
            // the wall that failed on its distance: as little as faces that do not enclose material.
            Rejection::Overlap { share, .. } if *share <= 0.0 => 4,
            Rejection::Overlap { .. } => 6,
            Rejection::Spread { .. } => 7,
            Rejection::Stub { .. }
            | Rejection::MinorLevel { .. }
            | Rejection::Lip { .. }
            | Rejection::Web { .. }
            | Rejection::Stacked { .. } => 8,
        }
    }

    pub fn describe(&self) -> String {
        match self {
            Rejection::Incompatible { kinds } => {
                format!("{} and {} cannot form a wall", kinds[0], kinds[1])
            }
            Rejection::Angle { degrees, limit_degrees } => {
                format!("normals {degrees:.2} deg from opposite (limit {limit_degrees:.2})")
            }
            Rejection::NotCoaxial { offset } => {
                format!("not coaxial/concentric (offset {offset:.4})")
            }
            Rejection::SameSense => "material on the same side of both faces".to_string(),
            Rejection::NotFacing => "faces do not enclose material between them".to_string(),
            Rejection::Distance { distance, limit } => {
                format!("distance {distance:.4} > t_max {limit:.4}")
            }
            Rejection::Overlap { share, limit } => {
                format!("overlap {:.1}% < {:.1}%", share * 100.0, limit * 100.0)
            }
            Rejection::Spread { min, max } => format!("distance varies {min:.4}..{max:.4}"),
            Rejection::Stub { width, thickness, top: false } => {
                format!("faces at most {width:.4} wide, {thickness:.4} apart: the sides of a stub, not a wall")
            }
            Rejection::Stub { width, thickness, top: true } => {
                format!("a face {width:.4} wide standing proud, {thickness:.4} from its partner: the top of a stub")
            }
            Rejection::MinorLevel { width, thickness, wall } => {
                format!(
                    "a face {width:.4} wide, {thickness:.4} from its partner, on a wall {wall:.4} thick: a minor level"
                )
            }
            Rejection::Lip { width, thickness } => {
                format!("a face {width:.4} wide, {thickness:.4} from a partner pairing with nothing else: a lip, not a wall")
            }
            Rejection::Web { thickness, sheet } => {
                format!("faces {thickness:.4} apart spanning a wall {sheet:.4} thick: a web of that wall, not a wall")
            }
            Rejection::Stacked { thickness, between } => {
                format!("faces {thickness:.4} apart with another face {between:.4} from one: stacked walls, not one")
            }
        }
    }
}

/// The closest a face came to pairing: its best candidate and why that candidate failed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NearMiss {
    pub candidate: FaceId,
    pub rejection: Rejection,
}

/// Everything pairing found on one solid.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Pairing {
    pub pairs: Vec<Pair>,
    pub groups: Vec<PairGroup>,
    /// One role per face, indexed by face id.
    pub roles: Vec<FaceRole>,
}

impl Pairing {
    /// Share of the solid's area that lies on paired faces.
    pub fn paired_area_share(&self, graph: &FaceGraph) -> f64 {
        let paired: f64 =
            graph.faces.iter().filter(|f| matches!(self.roles[f.id], FaceRole::Pair { .. })).map(|f| f.area).sum();
        if graph.area > 0.0 {
            paired / graph.area
        } else {
            0.0
        }
    }
}

/// Finds the face pairs of a solid. `pairable[f]` false leaves face f out (a suppressed feature).
pub fn detect(graph: &FaceGraph, tol: &Tolerances, pairable: &[bool]) -> Pairing {
    assemble(graph, &test_candidates(graph, tol), pairable, tol)
}

/// A candidate pair of faces and the verdict of the pair tests on it.
pub type Tested = (FaceId, FaceId, Result<Pair, Rejection>);

/// Every candidate pair of the solid tested, in candidate order. A verdict does not depend on which faces are
/// pairable, so one list serves every pairing of the solid (before and after its features are left out).
pub fn test_candidates(graph: &FaceGraph, tol: &Tolerances) -> Vec<Tested> {
    candidates::candidate_pairs(graph, tol.t_bound)
        .into_iter()
        .map(|(a, b)| (a, b, criteria::test_pair(graph, a, b, tol)))
        .collect()
}

/// The pairing of a solid from its `tested` candidates, leaving out the faces not `pairable`.
pub fn assemble(graph: &FaceGraph, tested: &[Tested], pairable: &[bool], tol: &Tolerances) -> Pairing {
    let mut pairs = Vec::new();
    let mut near: Vec<Option<NearMiss>> = vec![None; graph.faces.len()];
    for &(a, b, ref verdict) in tested {
        if !pairable[a] || !pairable[b] {
            continue;
        }
        match verdict {
            Ok(pair) => pairs.push(pair.clone()),
            Err(rejection) => {
                for (me, other) in [(a, b), (b, a)] {
                    let better = match &near[me] {
                        None => true,
                        Some(old) => rejection.stage() > old.rejection.stage(),
                    };
                    if better {
                        near[me] = Some(NearMiss { candidate: other, rejection: rejection.clone() });
                    }
                }
            }
        }
    }
    // Walls over t_max (thin for their extent, `criteria::wall_limit`) are settled after the others, against
    // them: they take nothing from the walls within t_max (whose narrow faces the context rules judge by the
    // walls around them), and go through the same rules themselves.
    let (mut pairs, mut thick): (Vec<Pair>, Vec<Pair>) =
        pairs.into_iter().partition(|p| !criteria::over(p.thickness.mean, tol.t_max, tol));
    reject_in_context(graph, &mut pairs, &[], &mut near, pairable, tol, tol.t_max);
    reject_in_context(graph, &mut thick, &pairs, &mut near, pairable, tol, f64::INFINITY);
    if !thick.is_empty() {
        // Back in candidate order, as one pass would have left them.
        let rank: std::collections::HashMap<[FaceId; 2], usize> =
            tested.iter().enumerate().map(|(k, &(a, b, _))| ([a.min(b), a.max(b)], k)).collect();
        pairs.extend(thick);
        pairs.sort_by_key(|p| rank.get(&p.faces).copied());
    }
    continuation::share_continued_thickness(graph, &mut pairs);
    let (groups, roles) = groups::group_and_classify(graph, &pairs, &near, pairable);
    Pairing { pairs, groups, roles }
}

/// Drops the `pairs` that the rules of the walls around them reject (the sides of a stub, a minor level or a
/// lip, a web of a wider wall), judged among themselves and the `settled` pairs, which stay. The tops of stubs
/// up to `tops_up_to` thick count as skins that join the sides of a stub.
fn reject_in_context(
    graph: &FaceGraph,
    pairs: &mut Vec<Pair>,
    settled: &[Pair],
    near: &mut [Option<NearMiss>],
    pairable: &[bool],
    tol: &Tolerances,
    tops_up_to: f64,
) {
    // The faces that can join the sides of a stub: the skins of walls, and the stubs' own tops (a top's near
    // miss also lands on its partner, which is a skin of the wall beneath anyway).
    let mut skins = vec![false; graph.faces.len()];
    for pair in settled.iter().chain(pairs.iter()) {
        pair.faces.iter().for_each(|&f| skins[f] = true);
    }
    for (face, miss) in near.iter().enumerate() {
        if let Some(NearMiss { rejection: Rejection::Stub { top: true, thickness, .. }, .. }) = miss {
            skins[face] |= *thickness <= tops_up_to;
        }
    }
    let stubs = pairs
        .iter()
        .map(|p| {
            let stub = criteria::stub_sides(graph, p, &skins).or_else(|| criteria::low_side(graph, p, &skins, tol));
            stub.map(|r| (p.faces.to_vec(), r))
        })
        .collect();
    drop_rejected(pairs, near, stubs);
    let pairs_of = pairs_by_face(graph.faces.len(), settled.iter().chain(pairs.iter()));
    let minor = pairs
        .iter()
        .map(|p| criteria::minor_level(graph, p, &pairs_of, tol.point).map(|(f, r)| (vec![f], r)))
        .collect();
    drop_rejected(pairs, near, minor);
    let pairs_of = pairs_by_face(graph.faces.len(), settled.iter().chain(pairs.iter()));
    let webs = pairs
        .iter()
        .map(|p| criteria::web_of_sheet(graph, p, &pairs_of, pairable).map(|r| (p.faces.to_vec(), r)))
        .collect();
    drop_rejected(pairs, near, webs);
}

/// The pairs of each face, indexed by face id.
fn pairs_by_face<'a>(faces: usize, pairs: impl IntoIterator<Item = &'a Pair>) -> Vec<Vec<&'a Pair>> {
    let mut out: Vec<Vec<&Pair>> = vec![Vec::new(); faces];
    for pair in pairs {
        pair.faces.iter().for_each(|&f| out[f].push(pair));
    }
    out
}

/// Drops the pairs with a verdict (one per pair, in order): the faces it names get it as their near miss.
fn drop_rejected(
    pairs: &mut Vec<Pair>,
    near: &mut [Option<NearMiss>],
    verdicts: Vec<Option<(Vec<FaceId>, Rejection)>>,
) {
    let mut verdicts = verdicts.into_iter();
    pairs.retain(|pair| match verdicts.next().flatten() {
        None => true,
        Some((faces, rejection)) => {
            for me in faces {
                near[me] = Some(NearMiss { candidate: pair.other(me), rejection: rejection.clone() });
            }
            false
        }
    });
}

#[cfg(test)]
mod tests;
