//! The clean-up of a shell mesh: every edge too short for an explicit solver's time step is collapsed, its
//! more constrained end staying, without turning an element over.

use serde::Serialize;

use super::collapse;
use glam::DVec3;

use super::shell::{element_normal, Element, ShellMesh};

/// What the clean-up did.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Cleanup {
    /// Edges shorter than this were collapsed (mm); no node moved farther.
    pub tolerance: f64,
    pub collapsed_edges: usize,
    /// Elements that lost a node (quads become triangles) or vanished (triangles, slivers).
    pub quads_to_trias: usize,
    pub removed_elements: usize,
    /// Face-inside nodes moved to the middle of their neighbours (by at most the tolerance) so that a collapse
    /// next to them leaves their corners convex.
    pub relaxed_nodes: usize,
    /// Quads cut into two triangles along the diagonal from a corner that a collapse would turn reflex or flat.
    pub split_quads: usize,
    /// Triangles gmsh made with no area (a node on the opposite edge, and in no other element), dropped: the
    /// opposite edge takes over as the rim, on the same line.
    pub dropped_flat_triangles: usize,
    /// Quads gmsh made with a reflex corner (a Jacobian below 0: a solver stops on it), cut into two triangles
    /// along the diagonal from that corner.
    pub split_reflex_quads: usize,
    /// Edges still shorter than the tolerance at the end: every way of collapsing them would turn an element
    /// over or tear a quad across.
    pub kept_short_edges: usize,
}

/// Collapses every mesh edge shorter than `tolerance`: its more constrained end (CAD vertex, then curve, then
/// surface; the lower index on a tie) stays, the other moves onto it, so the shape changes by less than
/// `tolerance`. Tiny CAD edges and sliver faces no longer dictate the element size: a sliver narrower than
/// the tolerance closes up and its neighbours meet. A collapse never leaves an element inverted, degenerate
/// or folded (`collapse::plan` decides how, or refuses). Shortest edges first; deterministic.
pub fn clean(mesh: &mut ShellMesh, tolerance: f64) -> Cleanup {
    let mut report = Cleanup { tolerance, ..Default::default() };
    if tolerance <= 0.0 {
        return report;
    }
    let origin = mesh.nodes.clone();
    let mut alive = vec![true; mesh.elements.len()];
    let mut refused = std::collections::BTreeSet::new();
    for _pass in 0..50 {
        let mut adjacency: Vec<Vec<usize>> = vec![Vec::new(); mesh.nodes.len()];
        for (i, e) in mesh.elements.iter().enumerate().filter(|(i, _)| alive[*i]) {
            for &n in &e.nodes {
                adjacency[n].push(i);
            }
        }
        let mut short: Vec<(f64, usize, usize)> = Vec::new();
        for (i, e) in mesh.elements.iter().enumerate().filter(|(i, _)| alive[*i]) {
            let _ = i;
            for k in 0..e.nodes.len() {
                let (a, b) = (e.nodes[k], e.nodes[(k + 1) % e.nodes.len()]);
                let (a, b) = (a.min(b), a.max(b));
                let length = (mesh.nodes[a] - mesh.nodes[b]).length();
                if length < tolerance && !refused.contains(&(a, b)) {
                    short.push((length, a, b));
                }
            }
        }
        short.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)).then(x.2.cmp(&y.2)));
        short.dedup();
        if short.is_empty() {
            break;
        }
        let mut touched = vec![false; mesh.nodes.len()];
        let mut progress = false;
        for &(_, a, b) in &short {
            if touched[a] || touched[b] {
                continue;
            }
            let Some(collapse) = collapse::plan(mesh, &adjacency, &origin, (a, b), tolerance) else {
                refused.insert((a, b));
                continue;
            };
            let (keep, gone) = (collapse.keep, collapse.gone);
            for &(n, to) in &collapse.moves {
                mesh.nodes[n] = to;
            }
            report.relaxed_nodes += collapse.moves.iter().filter(|m| m.0 != keep).count();
            for &i in &adjacency[gone] {
                let e = &mut mesh.elements[i];
                let had_keep = e.nodes.contains(&keep);
                for n in &mut e.nodes {
                    if *n == gone {
                        *n = keep;
                    }
                }
                if had_keep {
                    e.nodes.dedup();
                    if e.nodes.first() == e.nodes.last() {
                        e.nodes.pop();
                    }
                    if e.nodes.len() < 3 {
                        alive[i] = false;
                        report.removed_elements += 1;
                    } else {
                        report.quads_to_trias += 1;
                    }
                }
            }
            let moved = std::mem::take(&mut adjacency[gone]);
            adjacency[keep].extend(moved);
            adjacency[keep].sort_unstable();
            adjacency[keep].dedup();
            // Every node whose elements changed: their neighbours wait for the next pass.
            let mut rings: Vec<usize> = collapse.moves.iter().map(|m| m.0).chain([keep]).collect();
            for &(i, at) in &collapse.splits {
                let [first, second] = <[Vec<usize>; 2]>::try_from(collapse::split(&mesh.elements[i].nodes, Some(at)))
                    .expect("a split quad makes two triangles");
                let new = mesh.elements.len();
                // The first triangle keeps the quad's index; the node it lost now holds the second only.
                let lost = second[2];
                adjacency[lost].retain(|&j| j != i);
                for &n in &second {
                    adjacency[n].push(new);
                }
                let e = &mesh.elements[i];
                let (patch, face) = (e.patch, e.face);
                rings.extend(&e.nodes);
                mesh.elements[i].nodes = first;
                mesh.elements.push(Element { nodes: second, patch, face });
                alive.push(true);
                report.split_quads += 1;
            }
            for n in rings {
                for &i in &adjacency[n] {
                    for &m in &mesh.elements[i].nodes {
                        touched[m] = true;
                    }
                }
            }
            touched[gone] = true;
            report.collapsed_edges += 1;
            progress = true;
        }
        if !progress {
            break;
        }
    }
    let mut i = 0;
    mesh.elements.retain(|_| {
        i += 1;
        alive[i - 1]
    });
    report.dropped_flat_triangles = drop_flat_triangles(mesh);
    report.split_reflex_quads = split_reflex_quads(mesh);
    drop_unused_nodes(mesh);
    let mut left = std::collections::BTreeSet::new();
    for e in &mesh.elements {
        for k in 0..e.nodes.len() {
            let (a, b) = (e.nodes[k], e.nodes[(k + 1) % e.nodes.len()]);
            if (mesh.nodes[a] - mesh.nodes[b]).length() < tolerance {
                left.insert((a.min(b), a.max(b)));
            }
        }
    }
    report.kept_short_edges = left.len();
    report
}

/// A triangle whose area is below this share of its longest edge squared has no area (its three nodes on a
/// line, up to rounding).
const FLAT_TRIANGLE_SHARE: f64 = 1e-9;

/// Drops every triangle with no area whose middle node (the one on its longest edge's line) no other element
/// holds: the longest edge then lies where its two short ones were. Returns how many.
fn drop_flat_triangles(mesh: &mut ShellMesh) -> usize {
    let mut uses = vec![0usize; mesh.nodes.len()];
    for e in &mesh.elements {
        for &n in &e.nodes {
            uses[n] += 1;
        }
    }
    let flat_middle = |e: &[usize]| -> Option<usize> {
        let p = |k: usize| mesh.nodes[e[k % 3]];
        let longest = (0..3).max_by(|&a, &b| (p(a + 1) - p(a)).length().total_cmp(&(p(b + 1) - p(b)).length()))?;
        let edge = (p(longest + 1) - p(longest)).length_squared();
        let area = element_normal(&mesh.nodes, e).length();
        (area <= FLAT_TRIANGLE_SHARE * edge).then_some(e[(longest + 2) % 3])
    };
    let before = mesh.elements.len();
    mesh.elements.retain(|e| e.nodes.len() != 3 || flat_middle(&e.nodes).is_none_or(|m| uses[m] > 1));
    before - mesh.elements.len()
}

/// Cuts every quad with a reflex or flat corner (seen along its own normal) into the two triangles of the
/// diagonal from that corner, when both come out convex; the second triangle goes to the end. Returns how many.
fn split_reflex_quads(mesh: &mut ShellMesh) -> usize {
    let mut split = 0;
    for i in 0..mesh.elements.len() {
        let e = &mesh.elements[i];
        if e.nodes.len() != 4 {
            continue;
        }
        let points: Vec<DVec3> = e.nodes.iter().map(|&n| mesh.nodes[n]).collect();
        let normal = element_normal(&mesh.nodes, &e.nodes).normalize_or_zero();
        let sines = collapse::corner_sines(&points, normal);
        let (worst, sine) = sines.iter().enumerate().fold((0, f64::MAX), |w, (j, &s)| if s < w.1 { (j, s) } else { w });
        if sine > 0.0 {
            continue;
        }
        let halves = collapse::split(&e.nodes, Some(e.nodes[worst]));
        let convex = halves.iter().all(|h| {
            let p: Vec<DVec3> = h.iter().map(|&n| mesh.nodes[n]).collect();
            collapse::corner_sines(&p, normal).into_iter().all(|s| s > 0.0)
        });
        if !convex {
            continue;
        }
        let (patch, face) = (e.patch, e.face);
        let [first, second] = <[Vec<usize>; 2]>::try_from(halves).expect("a split quad makes two triangles");
        mesh.elements[i].nodes = first;
        mesh.elements.push(Element { nodes: second, patch, face });
        split += 1;
    }
    split
}

fn drop_unused_nodes(mesh: &mut ShellMesh) {
    let mut new_index = vec![usize::MAX; mesh.nodes.len()];
    for e in &mesh.elements {
        for &n in &e.nodes {
            new_index[n] = 0;
        }
    }
    let mut nodes = Vec::new();
    let mut dims = Vec::new();
    for (i, slot) in new_index.iter_mut().enumerate() {
        if *slot == 0 {
            *slot = nodes.len();
            nodes.push(mesh.nodes[i]);
            dims.push(mesh.dims[i]);
        }
    }
    for e in &mut mesh.elements {
        for n in &mut e.nodes {
            *n = new_index[*n];
        }
    }
    mesh.nodes = nodes;
    mesh.dims = dims;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::collapse::corner_sines;

    fn strip(width: f64) -> ShellMesh {
        // Two unit quads side by side with a sliver quad of `width` between them, all in z = 0.
        let xs = [0.0, 1.0, 1.0 + width, 2.0 + width];
        let mut nodes = Vec::new();
        for &x in &xs {
            nodes.push(DVec3::new(x, 0.0, 0.0));
            nodes.push(DVec3::new(x, 1.0, 0.0));
        }
        let quad = |i: usize| Element { nodes: vec![2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1], patch: 1, face: 0 };
        let dims = vec![1; nodes.len()];
        ShellMesh { nodes, dims, elements: vec![quad(0), quad(1), quad(2)] }
    }

    #[test]
    fn a_sliver_narrower_than_the_tolerance_closes_and_its_neighbours_meet() {
        let mut mesh = strip(0.01);
        let report = clean(&mut mesh, 0.1);
        assert_eq!(mesh.elements.len(), 2);
        assert_eq!(report.collapsed_edges, 2);
        assert_eq!(mesh.nodes.len(), 6);
        // The two quads share an edge now.
        let shared = mesh.elements[0].nodes.iter().filter(|n| mesh.elements[1].nodes.contains(n)).count();
        assert_eq!(shared, 2);
    }

    #[test]
    fn a_sliver_wider_than_the_tolerance_stays() {
        let mut mesh = strip(0.2);
        let report = clean(&mut mesh, 0.1);
        assert_eq!((mesh.elements.len(), report.collapsed_edges), (3, 0));
    }

    /// The smallest corner sine of every element, on its own normal (quality's Jacobian before its triangle
    /// scaling).
    fn smallest_corner_sine(mesh: &ShellMesh) -> f64 {
        let points = |e: &Element| e.nodes.iter().map(|&n| mesh.nodes[n]).collect::<Vec<_>>();
        mesh.elements.iter().flat_map(|e| corner_sines(&points(e), DVec3::Z)).fold(f64::MAX, f64::min)
    }

    #[test]
    fn a_collapse_that_would_fold_a_neighbouring_quad_goes_the_other_way() {
        // A quad whose corner n1 is nearly flat, and a sliver triangle under its edge n1-g with a short edge
        // g-k (0.08). k is a CAD vertex, so it would stay and g would move onto it: the quad keeps its side (its
        // normal barely changes) but its corner n1 turns reflex (sine -0.03). The collapse must go the other way.
        let nodes = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(2.0, 0.05, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(2.0, -0.03, 0.0),
        ];
        let (n0, n1, g, n3, k) = (0, 1, 2, 3, 4);
        let element = |nodes: Vec<usize>| Element { nodes, patch: 1, face: 0 };
        let mut mesh = ShellMesh {
            nodes,
            dims: vec![2, 1, 2, 1, 0],
            elements: vec![element(vec![n0, n1, g, n3]), element(vec![n1, k, g])],
        };
        assert!(smallest_corner_sine(&mesh) > 0.0);
        let report = clean(&mut mesh, 0.1);
        assert_eq!((report.collapsed_edges, mesh.elements.len()), (1, 1));
        assert!(smallest_corner_sine(&mesh) > 0.0, "{:?}", mesh.nodes);
        assert_eq!(mesh.nodes[mesh.elements[0].nodes[2]], DVec3::new(2.0, 0.05, 0.0), "g stays, k moved onto it");
    }

    #[test]
    fn a_quad_whose_corner_would_turn_reflex_either_way_is_split_there() {
        // As above, but k cannot move onto g either: the triangle k-r-s beside it would turn over. So g moves
        // onto k and the quad, whose corner n1 turns reflex, is cut along the diagonal from n1.
        let nodes = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(2.0, 0.05, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(2.0, -0.03, 0.0),
            DVec3::new(3.0, -0.03, 0.0),
            DVec3::new(2.5, -0.01, 0.0),
        ];
        let (n0, n1, g, n3, k, r, s) = (0, 1, 2, 3, 4, 5, 6);
        let element = |nodes: Vec<usize>| Element { nodes, patch: 1, face: 0 };
        let mut mesh = ShellMesh {
            nodes,
            dims: vec![1, 1, 0, 1, 0, 1, 1],
            elements: vec![element(vec![n0, n1, g, n3]), element(vec![n1, k, g]), element(vec![k, r, s])],
        };
        assert!(smallest_corner_sine(&mesh) > 0.0);
        let report = clean(&mut mesh, 0.1);
        assert_eq!((report.collapsed_edges, report.split_quads, mesh.elements.len()), (1, 1, 3));
        assert!(smallest_corner_sine(&mesh) > 0.0, "{:?}", mesh.elements);
        assert!(mesh.elements.iter().all(|e| e.nodes.len() == 3));
    }

    #[test]
    fn a_triangle_with_no_area_on_the_rim_is_dropped_and_a_dart_quad_is_split_at_its_reflex_corner() {
        // gmsh's own: a triangle whose middle node lies on its long edge (shared with a real triangle), and a
        // dart-shaped quad (corner 2 reflex). The clean-up is given no short edge to collapse.
        let nodes = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(4.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.0, 3.0, 0.0),
            DVec3::new(10.0, 0.0, 0.0),
            DVec3::new(14.0, 0.0, 0.0),
            DVec3::new(12.0, 1.0, 0.0),
            DVec3::new(12.0, 4.0, 0.0),
        ];
        let element = |nodes: Vec<usize>| Element { nodes, patch: 1, face: 0 };
        let mut mesh = ShellMesh {
            nodes,
            dims: vec![1; 8],
            elements: vec![element(vec![0, 1, 3]), element(vec![1, 0, 2]), element(vec![4, 5, 7, 6])],
        };
        let own_frame_sine = |mesh: &ShellMesh| {
            let points = |e: &Element| e.nodes.iter().map(|&n| mesh.nodes[n]).collect::<Vec<_>>();
            let normal = |e: &Element| element_normal(&mesh.nodes, &e.nodes).normalize();
            mesh.elements.iter().flat_map(|e| corner_sines(&points(e), normal(e))).fold(f64::MAX, f64::min)
        };
        assert!(own_frame_sine(&mesh) < 0.0);
        let report = clean(&mut mesh, 0.1);
        assert_eq!((report.dropped_flat_triangles, report.split_reflex_quads), (1, 1));
        assert_eq!(mesh.elements.len(), 3);
        assert!(own_frame_sine(&mesh) > 0.0, "{:?}", mesh.elements);
        assert_eq!(mesh.nodes.len(), 7, "the flat triangle's middle node went with it");
    }
}
