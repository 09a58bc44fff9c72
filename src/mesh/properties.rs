//! The decks' properties: one per solid and section (a thickness band, or a patch), numbered in (solid,
//! section) order so that ids do not depend on gmsh's surface order.

use std::collections::BTreeMap;

use super::deck::Property;
use super::shell::Element;
use super::Sections;

/// The properties of `elements` from `start_id` on, and the index (into them) of each element's property.
pub fn properties(
    elements: &[Element],
    part_of: &BTreeMap<usize, usize>,
    thickness_of: &BTreeMap<usize, f64>,
    sections: Sections,
    start_id: u64,
) -> (Vec<Property>, Vec<usize>) {
    let section_key = |patch: usize| -> (usize, i64, usize) {
        let t = thickness_of[&patch];
        match sections {
            Sections::Band => (part_of[&patch], (t * 1000.0).round() as i64, 0),
            Sections::Patch => (part_of[&patch], 0, patch),
        }
    };
    let mut keys: Vec<(usize, i64, usize)> = elements.iter().map(|e| section_key(e.patch)).collect();
    keys.sort();
    keys.dedup();
    let mut properties: Vec<Property> = keys
        .iter()
        .enumerate()
        .map(|(i, k)| Property {
            id: start_id + i as u64,
            part: k.0,
            thickness: 0.0,
            patches: vec![],
            label: String::new(),
        })
        .collect();
    let property_of: Vec<usize> =
        elements.iter().map(|e| keys.binary_search(&section_key(e.patch)).expect("every key listed")).collect();
    for (e, &k) in elements.iter().zip(&property_of) {
        let p = &mut properties[k];
        if !p.patches.contains(&e.patch) {
            p.patches.push(e.patch);
        }
        p.thickness = thickness_of[&e.patch];
    }
    for p in &mut properties {
        p.patches.sort_unstable();
        p.label = match sections {
            Sections::Band => format!("solid {} t={:.3}", p.part, p.thickness),
            Sections::Patch => format!("solid {} patch {} t={:.3}", p.part, p.patches[0], p.thickness),
        };
    }
    (properties, property_of)
}
