//! Parameters of a run that several stages read.

use serde::Serialize;

/// Where a patch lies through its wall, as shell pre-processors offer it; the thickness is the same for all.
/// Every patch's normal points out of its wall's top side (see `sides`), so on `Top` the material lies on the
/// side opposite the normal and on `Bottom` on the normal's side: a solver reading the shell puts its
/// reference surface at the top or bottom fibre (Abaqus SPOS/SNEG, Nastran ZOFFS of -t/2 or +t/2).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Position {
    #[default]
    Mid,
    Top,
    Bottom,
}

impl Position {
    /// On a skin: whether it is the reference face's own skin (true) or its partner's, for a wall whose top
    /// side is the reference side (`reference_on_top`) or the other. None mid-way.
    pub fn on_reference_skin(self, reference_on_top: bool) -> Option<bool> {
        match self {
            Position::Mid => None,
            Position::Top => Some(reference_on_top),
            Position::Bottom => Some(!reference_on_top),
        }
    }

    /// Offset of the patch from its reference face along the face's outward normal, for a wall `t` thick.
    pub fn offset(self, t: f64, reference_on_top: bool) -> f64 {
        match self.on_reference_skin(reference_on_top) {
            None => -0.5 * t,
            Some(true) => 0.0,
            Some(false) => -t,
        }
    }

    /// From the patch to the middle of its wall, along the patch normal: the joint tests look there, since a
    /// point on a skin is on the solid's boundary and says nothing about the material.
    pub fn to_mid(self, t: f64) -> f64 {
        match self {
            Position::Mid => 0.0,
            Position::Top => -0.5 * t,
            Position::Bottom => 0.5 * t,
        }
    }
}
