//! Element quality of a shell mesh, per part: what the quality report measures (`criteria` judges it).

use std::collections::{BTreeMap, BTreeSet};

use glam::DVec3;
use serde::Serialize;

use super::shell::{centroid, element_normal, ShellMesh};

/// The material of the time-step estimate and the decks (units: mm, tonne, s, so MPa and t/mm³).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Material {
    pub young_mpa: f64,
    pub density_t_mm3: f64,
    pub poisson: f64,
}

impl Material {
    /// Plate wave speed (mm/s): sqrt(E / (rho (1 - nu²))), the speed an explicit solver's shell step uses.
    pub fn wave_speed(&self) -> f64 {
        (self.young_mpa / (self.density_t_mm3 * (1.0 - self.poisson * self.poisson))).sqrt()
    }
}

/// Metrics of one element. Definitions (those of common pre-processors):
/// - aspect: longest edge over shortest;
/// - warpage (quads): the largest angle between the normals of the two triangles of either diagonal split;
/// - skew: 90° minus the smallest angle between a quad's two mid-lines (joining opposite edge midpoints), or
///   for a triangle between a median and the mid-line of the two other edges;
/// - jacobian: the smallest corner's sine (edges' cross product on the unit normal over their lengths), a
///   triangle's divided by sin 60° and capped at 1, so a square and an equilateral triangle score 1;
/// - characteristic length (LS-DYNA's default): area over the longest edge for a quad, twice it for a triangle.
#[derive(Debug, Clone, Copy)]
pub struct ElementQuality {
    pub min_edge: f64,
    pub aspect: f64,
    pub warpage_deg: f64,
    pub skew_deg: f64,
    pub jacobian: f64,
    pub char_length: f64,
    pub area: f64,
}

fn angle_deg(a: DVec3, b: DVec3) -> f64 {
    let d = a.normalize_or_zero().dot(b.normalize_or_zero()).clamp(-1.0, 1.0);
    d.acos().to_degrees()
}

/// The acute angle between two lines (degrees, 0..90).
fn line_angle_deg(a: DVec3, b: DVec3) -> f64 {
    let t = angle_deg(a, b);
    t.min(180.0 - t)
}

pub fn element_quality(nodes: &[DVec3], e: &[usize]) -> ElementQuality {
    let p: Vec<DVec3> = e.iter().map(|&i| nodes[i]).collect();
    let k = p.len();
    let edges: Vec<f64> = (0..k).map(|i| (p[(i + 1) % k] - p[i]).length()).collect();
    let min_edge = edges.iter().cloned().fold(f64::MAX, f64::min);
    let max_edge = edges.iter().cloned().fold(0.0, f64::max);
    let normal = element_normal(nodes, e);
    let area = normal.length();
    let unit = normal.normalize_or_zero();
    let mut jacobian = f64::MAX;
    for i in 0..k {
        let next = p[(i + 1) % k] - p[i];
        let prev = p[(i + k - 1) % k] - p[i];
        let s = next.cross(prev).dot(unit) / (next.length() * prev.length()).max(1e-300);
        jacobian = jacobian.min(if k == 3 { (s / 60f64.to_radians().sin()).min(1.0) } else { s });
    }
    let mid = |i: usize| (p[i] + p[(i + 1) % k]) * 0.5;
    let (warpage_deg, skew_deg, char_length) = if k == 4 {
        let n = |a: usize, b: usize, c: usize| (p[b] - p[a]).cross(p[c] - p[a]);
        let warp = angle_deg(n(0, 1, 2), n(0, 2, 3)).max(angle_deg(n(1, 2, 3), n(1, 3, 0)));
        let skew = 90.0 - line_angle_deg(mid(2) - mid(0), mid(3) - mid(1));
        (warp, skew, area / max_edge.max(1e-300))
    } else {
        let mut smallest = 90.0f64;
        for (v, &corner) in p.iter().enumerate().take(3) {
            let opposite = mid((v + 1) % 3);
            let median = opposite - corner;
            let midline = mid(v) - mid((v + 2) % 3);
            smallest = smallest.min(line_angle_deg(median, midline));
        }
        (0.0, 90.0 - smallest, 2.0 * area / max_edge.max(1e-300))
    };
    ElementQuality {
        min_edge,
        aspect: max_edge / min_edge.max(1e-300),
        warpage_deg,
        skew_deg,
        jacobian,
        char_length,
        area,
    }
}

#[derive(Debug, Clone, Serialize)]
pub struct Mass {
    /// Sum of element area x thickness (mm³).
    pub shell_volume: f64,
    /// The solid's volume from the run's report, when known.
    pub solid_volume: Option<f64>,
    pub ratio: Option<f64>,
}

#[derive(Debug, Clone, Serialize)]
pub struct EdgeTally {
    pub count: usize,
    pub length: f64,
}

#[derive(Debug, Clone, Serialize)]
pub struct Worst {
    pub value: f64,
    pub patch: usize,
    /// Index of the mid-surface STEP face (0-based, file order) holding the element.
    pub face: usize,
    pub at: [f64; 3],
}

#[derive(Debug, Clone, Serialize)]
pub struct PartQuality {
    /// The solid (1-based, the run's report numbering); `0` in the total over all parts.
    pub part: usize,
    pub elements: usize,
    pub quads: usize,
    pub trias: usize,
    pub tria_share: f64,
    pub area: f64,
    pub min_edge: Worst,
    /// min_edge / wave speed: the brief's explicit time step estimate.
    pub time_step_s: f64,
    /// LS-DYNA's own estimate: smallest characteristic length / wave speed.
    pub time_step_lsdyna_s: f64,
    pub max_aspect: Worst,
    pub max_warpage_deg: Worst,
    pub max_skew_deg: Worst,
    pub min_jacobian: Worst,
    pub mass: Mass,
    /// Mesh edges used by one element (the mesh's rim and any gap).
    pub free_edges: EdgeTally,
    /// Mesh edges shared by three or more elements (T-joints).
    pub t_edges: EdgeTally,
}

pub struct Measured {
    pub per_element: Vec<ElementQuality>,
    pub parts: Vec<PartQuality>,
    pub total: PartQuality,
}

/// Measures every element and sums per part. `part_of[patch]` is the solid of a patch, `thickness_of[patch]`
/// its thickness, `solid_volume[part]` the solid's volume when known.
pub fn measure(
    mesh: &ShellMesh,
    part_of: &BTreeMap<usize, usize>,
    thickness_of: &BTreeMap<usize, f64>,
    solid_volume: &BTreeMap<usize, f64>,
    material: &Material,
) -> Measured {
    let per_element: Vec<ElementQuality> =
        mesh.elements.iter().map(|e| element_quality(&mesh.nodes, &e.nodes)).collect();
    let parts: BTreeSet<usize> = mesh.elements.iter().map(|e| part_of[&e.patch]).collect();
    let mut out = Vec::new();
    for &part in &parts {
        let chosen: Vec<usize> =
            (0..mesh.elements.len()).filter(|&i| part_of[&mesh.elements[i].patch] == part).collect();
        out.push(summarise(
            mesh,
            &per_element,
            &chosen,
            part,
            thickness_of,
            solid_volume.get(&part).copied(),
            material,
        ));
    }
    let all: Vec<usize> = (0..mesh.elements.len()).collect();
    let total_volume = if parts.iter().all(|p| solid_volume.contains_key(p)) {
        Some(parts.iter().map(|p| solid_volume[p]).sum())
    } else {
        None
    };
    let total = summarise(mesh, &per_element, &all, 0, thickness_of, total_volume, material);
    Measured { per_element, parts: out, total }
}

fn summarise(
    mesh: &ShellMesh,
    q: &[ElementQuality],
    chosen: &[usize],
    part: usize,
    thickness_of: &BTreeMap<usize, f64>,
    solid_volume: Option<f64>,
    material: &Material,
) -> PartQuality {
    let worst = |value: &dyn Fn(&ElementQuality) -> f64, largest: bool| -> Worst {
        let mut best: Option<(f64, usize)> = None;
        for &i in chosen {
            let v = value(&q[i]);
            let better = match best {
                None => true,
                Some((b, _)) => {
                    if largest {
                        v > b
                    } else {
                        v < b
                    }
                }
            };
            if better {
                best = Some((v, i));
            }
        }
        match best {
            Some((v, i)) => Worst {
                value: v,
                patch: mesh.elements[i].patch,
                face: mesh.elements[i].face,
                at: centroid(&mesh.nodes, &mesh.elements[i].nodes).to_array(),
            },
            None => Worst { value: f64::NAN, patch: 0, face: 0, at: [0.0; 3] },
        }
    };
    let trias = chosen.iter().filter(|&&i| mesh.elements[i].nodes.len() == 3).count();
    let area: f64 = chosen.iter().map(|&i| q[i].area).sum();
    let shell_volume: f64 = chosen.iter().map(|&i| q[i].area * thickness_of[&mesh.elements[i].patch]).sum();
    let mut edge_use: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    for &i in chosen {
        let e = &mesh.elements[i].nodes;
        for k in 0..e.len() {
            let (a, b) = (e[k], e[(k + 1) % e.len()]);
            *edge_use.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let tally = |pred: &dyn Fn(usize) -> bool| {
        let picked: Vec<_> = edge_use.iter().filter(|(_, &n)| pred(n)).collect();
        EdgeTally {
            count: picked.len(),
            length: picked.iter().map(|((a, b), _)| (mesh.nodes[*a] - mesh.nodes[*b]).length()).sum(),
        }
    };
    let c = material.wave_speed();
    let min_edge = worst(&|e| e.min_edge, false);
    let min_char = worst(&|e| e.char_length, false);
    PartQuality {
        part,
        elements: chosen.len(),
        quads: chosen.len() - trias,
        trias,
        tria_share: if chosen.is_empty() { 0.0 } else { trias as f64 / chosen.len() as f64 },
        area,
        time_step_s: min_edge.value / c,
        time_step_lsdyna_s: min_char.value / c,
        min_edge,
        max_aspect: worst(&|e| e.aspect, true),
        max_warpage_deg: worst(&|e| e.warpage_deg, true),
        max_skew_deg: worst(&|e| e.skew_deg, true),
        min_jacobian: worst(&|e| e.jacobian, false),
        mass: Mass { shell_volume, solid_volume, ratio: solid_volume.filter(|v| *v > 0.0).map(|v| shell_volume / v) },
        free_edges: tally(&|n| n == 1),
        t_edges: tally(&|n| n >= 3),
    }
}

#[cfg(test)]
#[path = "quality_tests.rs"]
mod tests;
