//! One edge collapse of the clean-up, decided: which end stays (or where the two meet), and how the elements
//! around it are mended (a face-inside neighbour moved, a quad split) so that every element around the moved
//! nodes stays a proper element, seen along the face's own normal. Decides only; `cleanup` applies.

use std::collections::BTreeSet;

use glam::DVec3;

use super::shell::{element_normal, ShellMesh};

/// The smallest corner sine (about 0.6°) a collapse may leave in an element it changes, unless the element
/// already had a smaller one or is a sliver on its way to closing (it has an edge the clean-up will collapse
/// next): a flatter corner makes a degenerate element. 0.05 was tried: it refused the collapses that close a
/// sliver face 0.05 mm wide into a needle triangle and left 3 more corpus parts with short edges.
const MIN_CORNER_SINE: f64 = 0.01;

/// An element's normal may tilt by less than this cosine (84°) in a collapse: more is a fold.
const MIN_TILT_COSINE: f64 = 0.1;

/// A collapse: `gone` merges into `keep`; `moves` are the new positions of the nodes that move (`keep` when
/// both ends meet half-way, face-inside neighbours relaxed to keep their corners convex); `splits` are the
/// quads (element index, and the node its new diagonal starts from) cut into two triangles because a corner
/// of theirs would turn reflex or flat, which the diagonal from that corner halves.
#[derive(Debug, Clone, PartialEq)]
pub struct Collapse {
    pub keep: usize,
    pub gone: usize,
    pub moves: Vec<(usize, DVec3)>,
    pub splits: Vec<(usize, usize)>,
}

/// Why a collapse was refused.
enum Refusal {
    /// A quad would hold both ends across its diagonal, or an element would fold over: nothing mends it.
    Fold,
    /// These (element, node) corners would be reflex or flat.
    Corners(Vec<(usize, usize)>),
}

/// Rounds of mending (moving a node, splitting a quad) tried on a collapse: a mend can leave one more corner
/// to mend next to it, rarely more.
const MEND_ROUNDS: usize = 2;

/// The collapse of the short edge `a`-`b`, or None when every way would leave an element inverted, degenerate
/// or folded. In order: the more constrained end stays (CAD vertex, then curve, then face inside; the lower
/// index on a tie), the other end stays, both meet half-way; then the same three mended: a face-inside node at
/// a bad corner moves to the middle of its neighbours (no farther than `tolerance` from `origin`, where gmsh
/// put it), any other bad corner of a quad splits the quad there. `adjacency[n]` lists the live elements
/// holding node `n`.
pub fn plan(
    mesh: &ShellMesh,
    adjacency: &[Vec<usize>],
    origin: &[DVec3],
    (a, b): (usize, usize),
    tolerance: f64,
) -> Option<Collapse> {
    let (keep, gone) = if (mesh.dims[b], b) < (mesh.dims[a], a) { (b, a) } else { (a, b) };
    let half = (mesh.nodes[a] + mesh.nodes[b]) * 0.5;
    let candidates = [
        Collapse { keep, gone, moves: vec![], splits: vec![] },
        Collapse { keep: gone, gone: keep, moves: vec![], splits: vec![] },
        Collapse { keep, gone, moves: vec![(keep, half)], splits: vec![] },
    ];
    let mut to_mend = Vec::new();
    for c in &candidates {
        match check(mesh, adjacency, c, tolerance) {
            Ok(()) => return Some(c.clone()),
            Err(Refusal::Corners(corners)) => to_mend.push((c.clone(), corners)),
            Err(Refusal::Fold) => {}
        }
    }
    for (mut c, mut corners) in to_mend {
        for _ in 0..MEND_ROUNDS {
            if !mend(mesh, adjacency, origin, &mut c, &corners, tolerance) {
                break;
            }
            match check(mesh, adjacency, &c, tolerance) {
                Ok(()) => return Some(c),
                Err(Refusal::Corners(more)) => corners = more,
                Err(Refusal::Fold) => break,
            }
        }
    }
    None
}

/// Adds to `c` a mend of every bad corner: a face-inside node (not an end of the edge) moves to the middle of
/// its neighbours, a quad's other corner (or one whose node moved in an earlier round) splits it. False when a
/// corner has no mend left (a triangle's corner on a CAD edge, a quad split in an earlier round).
fn mend(
    mesh: &ShellMesh,
    adjacency: &[Vec<usize>],
    origin: &[DVec3],
    c: &mut Collapse,
    corners: &[(usize, usize)],
    tolerance: f64,
) -> bool {
    let moved_before: Vec<usize> = c.moves.iter().map(|m| m.0).collect();
    let split_before: Vec<usize> = c.splits.iter().map(|s| s.0).collect();
    for &(element, n) in corners {
        if mesh.dims[n] == 2 && n != c.keep && n != c.gone && !moved_before.contains(&n) {
            if !c.moves.iter().any(|m| m.0 == n) {
                let to = relaxed_position(mesh, adjacency, c, n);
                let step = to - origin[n];
                let to = if step.length() > tolerance { origin[n] + step * (tolerance / step.length()) } else { to };
                c.moves.push((n, to));
            }
        } else if renamed(&mesh.elements[element].nodes, c).len() == 4 && !split_before.contains(&element) {
            if !c.splits.iter().any(|s| s.0 == element) {
                c.splits.push((element, n));
            }
        } else {
            return false;
        }
    }
    true
}

/// Where `c` puts node `n`: its move, or where it is.
fn position(mesh: &ShellMesh, c: &Collapse, n: usize) -> DVec3 {
    c.moves.iter().find(|m| m.0 == n).map_or(mesh.nodes[n], |m| m.1)
}

/// `element` after `c`: `gone` renamed `keep`, repeated nodes dropped.
fn renamed(element: &[usize], c: &Collapse) -> Vec<usize> {
    let mut after: Vec<usize> = element.iter().map(|&n| if n == c.gone { c.keep } else { n }).collect();
    after.dedup();
    if after.len() > 1 && after.first() == after.last() {
        after.pop();
    }
    after
}

/// The middle of `n`'s edge neighbours after `c`.
fn relaxed_position(mesh: &ShellMesh, adjacency: &[Vec<usize>], c: &Collapse, n: usize) -> DVec3 {
    let mut neighbours = BTreeSet::new();
    for &i in &adjacency[n] {
        let after = renamed(&mesh.elements[i].nodes, c);
        if let Some(j) = after.iter().position(|&m| m == n).filter(|_| after.len() >= 3) {
            neighbours.insert(after[(j + 1) % after.len()]);
            neighbours.insert(after[(j + after.len() - 1) % after.len()]);
        }
    }
    if neighbours.is_empty() {
        return mesh.nodes[n];
    }
    neighbours.iter().map(|&m| position(mesh, c, m)).sum::<DVec3>() / neighbours.len() as f64
}

/// Whether every element holding `gone` or a moved node stays a proper element after `c`: every corner convex
/// (sine above 0, and above `MIN_CORNER_SINE`) seen along the element's normal before (the face's own normal
/// there, as assembled), the normal tilted by less than 84°, and no quad holding both ends across a diagonal.
fn check(mesh: &ShellMesh, adjacency: &[Vec<usize>], c: &Collapse, tolerance: f64) -> Result<(), Refusal> {
    let mut elements: Vec<usize> = adjacency[c.gone].clone();
    for &(n, _) in &c.moves {
        elements.extend(&adjacency[n]);
    }
    elements.sort_unstable();
    elements.dedup();
    let mut bad = Vec::new();
    for i in elements {
        let e = &mesh.elements[i].nodes;
        let k = e.len();
        if let (Some(pk), Some(pg)) = (e.iter().position(|&n| n == c.keep), e.iter().position(|&n| n == c.gone)) {
            if (pk + 1) % k != pg && (pg + 1) % k != pk {
                return Err(Refusal::Fold);
            }
        }
        let after = renamed(e, c);
        if after.len() < 3 {
            continue; // a triangle on the edge vanishes
        }
        let before: Vec<DVec3> = e.iter().map(|&n| mesh.nodes[n]).collect();
        let frame = polygon_normal(&before).normalize_or_zero();
        let old_smallest = corner_sines(&before, frame).into_iter().fold(f64::MAX, f64::min);
        for polygon in split(&after, c.splits.iter().find(|s| s.0 == i).map(|s| s.1)) {
            let moved: Vec<DVec3> = polygon.iter().map(|&n| position(mesh, c, n)).collect();
            if polygon_normal(&moved).normalize_or_zero().dot(frame) <= MIN_TILT_COSINE {
                return Err(Refusal::Fold);
            }
            let closing = (0..moved.len()).any(|j| (moved[(j + 1) % moved.len()] - moved[j]).length() < tolerance);
            let floor = if closing { 0.0 } else { MIN_CORNER_SINE.min(old_smallest) };
            for (j, sine) in corner_sines(&moved, frame).into_iter().enumerate() {
                if sine <= 0.0 || sine < floor {
                    bad.push((i, polygon[j]));
                }
            }
        }
    }
    if bad.is_empty() {
        Ok(())
    } else {
        Err(Refusal::Corners(bad))
    }
}

/// `element` as it stays, or as the two triangles of its split from `at` (the diagonal from `at` to the
/// opposite node).
pub fn split(element: &[usize], at: Option<usize>) -> Vec<Vec<usize>> {
    match at.and_then(|n| element.iter().position(|&m| m == n)).filter(|_| element.len() == 4) {
        Some(j) => {
            let node = |k: usize| element[(j + k) % 4];
            vec![vec![node(0), node(1), node(2)], vec![node(0), node(2), node(3)]]
        }
        None => vec![element.to_vec()],
    }
}

fn polygon_normal(points: &[DVec3]) -> DVec3 {
    let local: Vec<usize> = (0..points.len()).collect();
    element_normal(points, &local)
}

/// The sine of each corner of the polygon `points` about the unit `normal`: the cross product of the corner's
/// two edges on `normal`, over their lengths. Negative at a corner turned inside out (a reflex corner of a
/// quad, or a whole element turned over), 0 at a flat corner or a zero-length edge.
pub fn corner_sines(points: &[DVec3], normal: DVec3) -> Vec<f64> {
    let k = points.len();
    (0..k)
        .map(|i| {
            let next = points[(i + 1) % k] - points[i];
            let prev = points[(i + k - 1) % k] - points[i];
            let lengths = next.length() * prev.length();
            if lengths > 0.0 {
                next.cross(prev).dot(normal) / lengths
            } else {
                0.0
            }
        })
        .collect()
}
