//! Mid-patches: planning them from pair groups (which faces, where through the wall, which loops to fill).

pub mod plan;
pub mod sides;
