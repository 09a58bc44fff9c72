//! Solver decks of a shell mesh: LS-DYNA keyword (`.k`, which OpenRadioss also reads), Nastran bulk data
//! (`.bdf`) and Abaqus input (`.inp`). Units: mm, tonne, s (so MPa and t/mm³). Every id is the start id plus
//! a 0-based index: nodes and elements in mesh order, properties (LS-DYNA part + section, Nastran PSHELL,
//! Abaqus element set + shell section) in (solid, section) order; the material takes the start id.

use std::fmt::Write;

use super::quality::Material;
use super::shell::ShellMesh;

/// Where the mesh lies through the wall (the run's `--position`): element normals point out of the wall's top
/// side, so on `Top` the material lies behind the normal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Placement {
    Mid,
    Top,
    Bottom,
}

impl Placement {
    /// LS-DYNA NLOC: 1 top fibre, -1 bottom fibre, 0 mid.
    fn nloc(self) -> f64 {
        match self {
            Placement::Mid => 0.0,
            Placement::Top => 1.0,
            Placement::Bottom => -1.0,
        }
    }
    /// Nastran ZOFFS: from the grids to the shell's mid-plane along the normal.
    fn zoffs(self, t: f64) -> f64 {
        match self {
            Placement::Mid => 0.0,
            Placement::Top => -t / 2.0,
            Placement::Bottom => t / 2.0,
        }
    }
    /// Abaqus OFFSET: SPOS puts the reference surface on the positive (normal) face.
    fn abaqus_offset(self) -> &'static str {
        match self {
            Placement::Mid => "",
            Placement::Top => ", OFFSET=SPOS",
            Placement::Bottom => ", OFFSET=SNEG",
        }
    }
}

/// One property: a solid's elements of one section (a thickness band, or one patch).
#[derive(Debug, Clone, serde::Serialize)]
pub struct Property {
    pub id: u64,
    pub part: usize,
    pub thickness: f64,
    pub patches: Vec<usize>,
    pub label: String,
}

pub struct Deck<'a> {
    pub title: String,
    pub mesh: &'a ShellMesh,
    /// Index into `properties` per element.
    pub property_of: Vec<usize>,
    pub properties: Vec<Property>,
    pub material: Material,
    pub placement: Placement,
    pub start_id: u64,
}

impl Deck<'_> {
    fn node_id(&self, i: usize) -> u64 {
        self.start_id + i as u64
    }
    fn element_id(&self, i: usize) -> u64 {
        self.start_id + i as u64
    }
    fn material_id(&self) -> u64 {
        self.start_id
    }
    /// Largest id written; decks of several parts can be included together when their ranges do not overlap.
    pub fn last_id(&self) -> u64 {
        let n = self.mesh.nodes.len().max(self.mesh.elements.len()).max(self.properties.len()).max(1);
        self.start_id + n as u64 - 1
    }
}

/// A real in at most `width` characters, always with a decimal point or exponent (Nastran reads a number
/// without one as an integer): the shortest exact form when it fits, else scientific with fewer digits.
pub fn real(x: f64, width: usize) -> String {
    let mut s = format!("{x}");
    if !s.contains(['.', 'e', 'E']) {
        s.push('.');
    }
    if s.len() <= width {
        return s;
    }
    // The most precise of the fixed and scientific forms that fit.
    let fixed = (1..16).rev().map(|d| format!("{x:.d$}")).find(|t| t.len() <= width);
    let scientific = (0..16)
        .rev()
        .map(|d| {
            let t = format!("{x:.d$E}");
            if t.contains('.') {
                t
            } else {
                t.replacen('E', ".E", 1)
            }
        })
        .find(|t| t.len() <= width);
    let error = |t: &String| (t.parse::<f64>().unwrap_or(f64::INFINITY) - x).abs();
    match (fixed, scientific) {
        (Some(f), Some(e)) => {
            if error(&f) <= error(&e) {
                f
            } else {
                e
            }
        }
        (Some(f), None) => f,
        (None, Some(e)) => e,
        (None, None) => format!("{x:.0E}"),
    }
}

/// A real right-aligned in a fixed field of `width`, at most `width - 1` characters long: a blank always
/// separates it from the field before, for readers that split on blanks.
fn field(x: f64, width: usize) -> String {
    format!("{:>width$}", real(x, width - 1))
}

pub fn lsdyna(deck: &Deck) -> String {
    let mut out = String::new();
    let m = &deck.material;
    let r10 = |x: f64| field(x, 10);
    let _ = writeln!(out, "*KEYWORD\n*TITLE\n{}", deck.title);
    let _ = writeln!(out, "*MAT_ELASTIC\n$#     mid        ro         e        pr");
    let _ = writeln!(out, "{:>10}{}{}{}", deck.material_id(), r10(m.density_t_mm3), r10(m.young_mpa), r10(m.poisson));
    for p in &deck.properties {
        let t = r10(p.thickness);
        let _ = writeln!(out, "*SECTION_SHELL\n$#   secid    elform      shrf       nip     propt");
        let _ = writeln!(out, "{:>10}{:>10}{}{:>10}{}", p.id, 2, r10(1.0), 5, r10(1.0));
        let _ = writeln!(out, "$#      t1        t2        t3        t4      nloc");
        let _ = writeln!(out, "{t}{t}{t}{t}{}", r10(deck.placement.nloc()));
        let _ = writeln!(out, "*PART\n{}\n$#     pid     secid       mid", p.label);
        let _ = writeln!(out, "{:>10}{:>10}{:>10}", p.id, p.id, deck.material_id());
    }
    let _ = writeln!(out, "*NODE\n$#   nid               x               y               z      tc      rc");
    for (i, p) in deck.mesh.nodes.iter().enumerate() {
        let r16 = |x: f64| field(x, 16);
        let _ = writeln!(out, "{:>8}{}{}{}{:>8}{:>8}", deck.node_id(i), r16(p.x), r16(p.y), r16(p.z), 0, 0);
    }
    let _ = writeln!(out, "*ELEMENT_SHELL\n$#   eid     pid      n1      n2      n3      n4");
    for (i, e) in deck.mesh.elements.iter().enumerate() {
        let n: Vec<u64> = e.nodes.iter().map(|&k| deck.node_id(k)).collect();
        // A triangle repeats its third node, as LS-DYNA expects.
        let n4 = if n.len() == 4 { n[3] } else { n[2] };
        let pid = deck.properties[deck.property_of[i]].id;
        let _ = writeln!(out, "{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}", deck.element_id(i), pid, n[0], n[1], n[2], n4);
    }
    out.push_str("*END\n");
    out
}

pub fn nastran(deck: &Deck) -> String {
    let mut out = String::new();
    let m = &deck.material;
    let r8 = |x: f64| field(x, 8);
    // Bulk data only (no BEGIN BULK, no ENDDATA): a file to INCLUDE in a main deck with its solution and case
    // control, next to the decks of other parts.
    let _ = writeln!(out, "$ {}", deck.title);
    let _ = writeln!(
        out,
        "MAT1    {:>8}{}{:8}{}{}",
        deck.material_id(),
        r8(m.young_mpa),
        "",
        r8(m.poisson),
        r8(m.density_t_mm3)
    );
    for p in &deck.properties {
        let _ = writeln!(out, "$ {}", p.label);
        // MID2 (bending) and MID3 (transverse shear) as MID1: a homogeneous shell.
        let mid = deck.material_id();
        let _ = writeln!(out, "PSHELL  {:>8}{:>8}{}{:>8}{:8}{:>8}", p.id, mid, r8(p.thickness), mid, "", mid);
    }
    for (i, p) in deck.mesh.nodes.iter().enumerate() {
        // Large field: 16 characters keep the coordinates exact to ~1e-9 relative.
        let r16 = |x: f64| field(x, 16);
        let _ = writeln!(out, "GRID*   {:>16}{:16}{}{}\n*       {}", deck.node_id(i), "", r16(p.x), r16(p.y), r16(p.z));
    }
    for (i, e) in deck.mesh.elements.iter().enumerate() {
        let prop = &deck.properties[deck.property_of[i]];
        let z = deck.placement.zoffs(prop.thickness);
        let zoffs = if z == 0.0 { String::new() } else { r8(z) };
        let n: Vec<String> = e.nodes.iter().map(|&k| format!("{:>8}", deck.node_id(k))).collect();
        let card = if n.len() == 4 { "CQUAD4  " } else { "CTRIA3  " };
        let _ = writeln!(out, "{card}{:>8}{:>8}{}{:8}{}", deck.element_id(i), prop.id, n.concat(), "", zoffs);
    }
    out
}

pub fn abaqus(deck: &Deck) -> String {
    let mut out = String::new();
    let m = &deck.material;
    let _ = writeln!(out, "*HEADING\n{}\n*NODE, NSET=ALL_NODES", deck.title);
    for (i, p) in deck.mesh.nodes.iter().enumerate() {
        let _ = writeln!(out, "{}, {}, {}, {}", deck.node_id(i), real(p.x, 24), real(p.y, 24), real(p.z, 24));
    }
    // One element set per property and element type, each with its shell section: a set named on two
    // *ELEMENT blocks is legal Abaqus, but readers such as meshio keep only the last block's elements.
    let mut sections = Vec::new();
    for (k, p) in deck.properties.iter().enumerate() {
        for (kind, nodes) in [("S4R", 4), ("S3", 3)] {
            let mine: Vec<usize> = (0..deck.mesh.elements.len())
                .filter(|&i| deck.property_of[i] == k && deck.mesh.elements[i].nodes.len() == nodes)
                .collect();
            if mine.is_empty() {
                continue;
            }
            let set = format!("P{}_{kind}", p.id);
            let _ = writeln!(out, "*ELEMENT, TYPE={kind}, ELSET={set}");
            for i in mine {
                let n: Vec<String> = deck.mesh.elements[i].nodes.iter().map(|&k| deck.node_id(k).to_string()).collect();
                let _ = writeln!(out, "{}, {}", deck.element_id(i), n.join(", "));
            }
            sections.push((set, p));
        }
    }
    for (set, p) in sections {
        let _ = writeln!(out, "** {}", p.label);
        let _ = writeln!(
            out,
            "*SHELL SECTION, ELSET={set}, MATERIAL=MAT{}{}",
            deck.material_id(),
            deck.placement.abaqus_offset()
        );
        let _ = writeln!(out, "{}, 5", real(p.thickness, 24));
    }
    let _ = writeln!(
        out,
        "*MATERIAL, NAME=MAT{}\n*ELASTIC\n{}, {}",
        deck.material_id(),
        real(m.young_mpa, 24),
        real(m.poisson, 24)
    );
    let _ = writeln!(out, "*DENSITY\n{}", real(m.density_t_mm3, 24));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reals_fit_their_field_and_keep_a_decimal_point() {
        assert_eq!(real(2.0, 8), "2.");
        assert_eq!(real(7.85e-9, 8), "7.850E-9");
        assert_eq!(real(210000.0, 10), "210000.");
        assert_eq!(real(0.1 + 0.2, 16), "0.30000000000000");
        assert_eq!(real(-123.456_789_012_345_68, 8), "-123.457");
        assert_eq!(real(1e-20, 8), "1.00E-20");
        assert_eq!(real(1e-20, 6), "1.E-20");
        for x in [1e-20, -9.87654321e15, 1.0 / 3.0] {
            assert!(real(x, 8).len() <= 8);
            assert!((real(x, 16).parse::<f64>().unwrap() / x - 1.0).abs() < 1e-9);
        }
    }
}
