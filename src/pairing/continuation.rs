//! Pairs that continue each other: the same wall run on across smooth edges, split into faces of different
//! surfaces (a vault and its dome), whose patches must meet edge to edge.

use std::collections::BTreeMap;

use super::{Pair, PairKind, Thickness};
use crate::model::face_graph::{FaceGraph, FaceId};
use crate::model::tolerance::SAME_THICKNESS;
use crate::model::union_find::{find, union};

/// Pairs that run on into each other as one wall get one thickness: pairs (a, b) and (c, d) where a meets c and
/// b meets d across smooth edges (each skin runs on tangentially: a vault into its dome), at one thickness
/// (`SAME_THICKNESS`), one of them at least measured by rays (`freeform`). A measured thickness is a mean over
/// samples, never exactly its neighbour's, and patches offset at their own means would stand a little apart
/// at the edge, one grazing the other; at one mean (the chain's, weighted by overlap) their offsets of the
/// skins meet edge to edge. Pairs known exactly meet so already; walls of other thicknesses are other walls, and
/// so is a chain whose means drift past one thickness link by link (a taper keeps each pair's own).
pub fn share_continued_thickness(graph: &FaceGraph, pairs: &mut [Pair]) {
    let n = graph.faces.len();
    let smooth: Vec<Vec<FaceId>> = (0..n).map(|f| graph.smooth_neighbours(f)).collect();
    let mut pairs_of: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (i, p) in pairs.iter().enumerate() {
        pairs_of[p.faces[0]].push(i);
        pairs_of[p.faces[1]].push(i);
    }
    let one_wall = |p: &Pair, q: &Pair| {
        let measured = p.kind == PairKind::Freeform || q.kind == PairKind::Freeform;
        let (s, t) = (p.thickness.mean, q.thickness.mean);
        measured && (s - t).abs() <= SAME_THICKNESS * s.max(t)
    };
    // Chains of pairs: a union-find forest over pair indices.
    let mut root: Vec<usize> = (0..pairs.len()).collect();
    for (i, p) in pairs.iter().enumerate() {
        for (a, b) in [(p.faces[0], p.faces[1]), (p.faces[1], p.faces[0])] {
            for &c in &smooth[a] {
                for &j in &pairs_of[c] {
                    let q = &pairs[j];
                    if j != i && smooth[b].binary_search(&q.other(c)).is_ok() && one_wall(p, q) {
                        union(&mut root, i, j);
                    }
                }
            }
        }
    }
    let mut chains: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for i in 0..pairs.len() {
        let r = find(&mut root, i);
        chains.entry(r).or_default().push(i);
    }
    for chain in chains.values().filter(|c| c.len() > 1) {
        let area: f64 = chain.iter().map(|&i| pairs[i].overlap_area).sum();
        let means = chain.iter().map(|&i| pairs[i].thickness.mean);
        let (low, high) = means.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), m| (l.min(m), h.max(m)));
        // A chain that drifts past one thickness, link by link, is a taper: one mean would move its ends off
        // mid-wall, and its patches stand apart by the taper whatever their offsets.
        if area <= 0.0 || high - low > SAME_THICKNESS * high {
            continue;
        }
        let mean = chain.iter().map(|&i| pairs[i].thickness.mean * pairs[i].overlap_area).sum::<f64>() / area;
        for &i in chain {
            let t = &mut pairs[i].thickness;
            *t = Thickness { mean, min: t.min.min(mean), max: t.max.max(mean) };
        }
    }
}
