//! Whether a solid is thin-walled (it gets a mid-surface) or not (chunky: pins, screws, stems, solid blocks,
//! which a crash or stiffness model meshes as solids or beams, never as shells).
//!
//! The measure is the solid's mean wall thickness 2V/A (exact for a plate: volume over half its area) against
//! its middle bounding-box extent (the plate's width, the pin's diameter): a thin wall is far thinner than
//! the part is wide in its second direction. Measured on shells: plates, trays, ducts, castings 0.003 to 0.17;
//! hollow pins 0.21 to 0.22, screws and stems 0.23 to 0.31, a solid cube 0.33, a solid cylinder 0.43.

use serde::Serialize;

use crate::model::face_graph::FaceGraph;

/// Above this share of its middle extent, a solid's 2V/A says it is chunky (the independent judge's limit too).
pub const CHUNKY_SHARE: f64 = 0.2;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum WallKind {
    ThinWalled,
    NotThinWalled,
}

/// How a solid was classified, with the figures the class comes from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WallClass {
    pub kind: WallKind,
    /// 2V/A, the solid's mean wall thickness.
    pub thickness: f64,
    /// The middle of the three extents of the solid's bounding box.
    pub middle_extent: f64,
    /// thickness / middle_extent, against `limit`.
    pub ratio: f64,
    pub limit: f64,
}

impl WallClass {
    pub fn is_thin_walled(&self) -> bool {
        self.kind == WallKind::ThinWalled
    }

    /// The measure in one line, for reports and tables.
    pub fn describe(&self) -> String {
        let verdict = if self.is_thin_walled() { "thin-walled" } else { "not thin-walled (chunky)" };
        format!(
            "{verdict}: 2V/A {:.4} is {:.3} of the middle box extent {:.4} (limit {})",
            self.thickness, self.ratio, self.middle_extent, self.limit
        )
    }
}

pub fn classify(graph: &FaceGraph) -> WallClass {
    let thickness = graph.thickness_estimate();
    let mut extents = graph.bbox.size().to_array();
    extents.sort_by(f64::total_cmp);
    let middle_extent = extents[1];
    let ratio = if middle_extent > 0.0 { thickness / middle_extent } else { 0.0 };
    let kind = if ratio > CHUNKY_SHARE { WallKind::NotThinWalled } else { WallKind::ThinWalled };
    WallClass { kind, thickness, middle_extent, ratio, limit: CHUNKY_SHARE }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthetic::cuboid;
    use glam::DVec3;

    #[test]
    fn a_plate_is_thin_walled_a_block_and_a_bar_are_not() {
        let plate = classify(&cuboid(DVec3::ZERO, DVec3::new(100.0, 60.0, 2.0)));
        assert_eq!(plate.kind, WallKind::ThinWalled, "{}", plate.describe());
        assert!((plate.middle_extent - 60.0).abs() < 1e-9);
        let block = classify(&cuboid(DVec3::ZERO, DVec3::new(20.0, 20.0, 20.0)));
        assert_eq!(block.kind, WallKind::NotThinWalled, "{}", block.describe());
        // A square bar 6 x 6 x 40 (a pin): 2V/A 2.77 over its 6 mm width.
        let bar = classify(&cuboid(DVec3::ZERO, DVec3::new(6.0, 6.0, 40.0)));
        assert_eq!(bar.kind, WallKind::NotThinWalled, "{}", bar.describe());
        // A long narrow strip 2 thick and 8 wide is still a wall: 2V/A 1.6 over 8 = 0.2, not over the limit.
        let strip = classify(&cuboid(DVec3::ZERO, DVec3::new(200.0, 8.0, 2.0)));
        assert!(strip.ratio < CHUNKY_SHARE + 1e-9 && strip.is_thin_walled(), "{}", strip.describe());
    }
}
