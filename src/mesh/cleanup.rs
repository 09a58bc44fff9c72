//! The clean-up of a shell mesh: every edge too short for an explicit solver's time step is collapsed, its
//! more constrained end staying, without turning an element over.

use glam::DVec3;
use serde::Serialize;

use super::shell::{element_normal, ShellMesh};

/// What the clean-up did.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Cleanup {
    /// Edges shorter than this were collapsed (mm); no node moved farther.
    pub tolerance: f64,
    pub collapsed_edges: usize,
    /// Elements that lost a node (quads become triangles) or vanished (triangles, slivers).
    pub quads_to_trias: usize,
    pub removed_elements: usize,
    /// Edges still shorter than the tolerance at the end: every way of collapsing them would turn an element
    /// over or tear a quad across.
    pub kept_short_edges: usize,
}

/// Collapses every mesh edge shorter than `tolerance`: its more constrained end (CAD vertex, then curve, then
/// surface; the lower index on a tie) stays, the other moves onto it, so the shape changes by less than
/// `tolerance`. Tiny CAD edges and sliver faces no longer dictate the element size: a sliver narrower than
/// the tolerance closes up and its neighbours meet. A collapse is skipped when an element would turn over or a
/// quad hold both ends across a diagonal. Shortest edges first; deterministic.
pub fn clean(mesh: &mut ShellMesh, tolerance: f64) -> Cleanup {
    let mut report = Cleanup { tolerance, ..Default::default() };
    if tolerance <= 0.0 {
        return report;
    }
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
            // The more constrained end stays; when that would turn an element over, the other end stays
            // (either way no node moves farther than the edge is long).
            let preferred = if (mesh.dims[b], b) < (mesh.dims[a], a) { (b, a) } else { (a, b) };
            let at = |n: usize| mesh.nodes[n];
            let mut choice = [preferred, (preferred.1, preferred.0)]
                .into_iter()
                .map(|(keep, gone)| (keep, gone, at(keep)))
                .find(|&(keep, gone, to)| collapsible(mesh, &adjacency[gone], keep, gone, to));
            if choice.is_none() {
                // Last, both ends meet half-way (each moves half the edge).
                let (keep, gone) = preferred;
                let half = (at(a) + at(b)) * 0.5;
                let mut elements = adjacency[gone].clone();
                elements.extend(&adjacency[keep]);
                if collapsible(mesh, &elements, keep, gone, half) {
                    choice = Some((keep, gone, half));
                }
            }
            let Some((keep, gone, to)) = choice else {
                refused.insert((a, b));
                continue;
            };
            mesh.nodes[keep] = to;
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
            for &i in &adjacency[keep] {
                for &n in &mesh.elements[i].nodes {
                    touched[n] = true;
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

/// Whether moving `gone` onto `keep` and `keep` to `to` leaves every element of `elements` the right way up
/// (and no quad holding both across a diagonal).
fn collapsible(mesh: &ShellMesh, elements: &[usize], keep: usize, gone: usize, to: DVec3) -> bool {
    let normal = |ids: &[usize], moved: bool| {
        let p: Vec<DVec3> = ids.iter().map(|&n| if moved && n == keep { to } else { mesh.nodes[n] }).collect();
        let local: Vec<usize> = (0..p.len()).collect();
        element_normal(&p, &local)
    };
    for &i in elements {
        let e = &mesh.elements[i].nodes;
        let before = normal(e, false);
        let k = e.len();
        if let Some(pk) = e.iter().position(|&n| n == keep) {
            if let Some(pg) = e.iter().position(|&n| n == gone) {
                let adjacent = (pk + 1) % k == pg || (pg + 1) % k == pk;
                if !adjacent {
                    return false;
                }
                if k == 3 {
                    continue; // vanishes
                }
            }
        }
        let mut after: Vec<usize> = e.iter().map(|&n| if n == gone { keep } else { n }).collect();
        after.dedup();
        if after.first() == after.last() && after.len() > 1 {
            after.pop();
        }
        if after.len() < 3 {
            continue;
        }
        let n = normal(&after, true);
        // The element must keep its side and a real area: a tenth of its normal's length in its old direction.
        if n.dot(before) <= 0.1 * before.length() * n.length() || n.length() <= 1e-12 * before.length().max(1e-300) {
            return false;
        }
    }
    true
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
    use crate::mesh::shell::Element;

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
}
