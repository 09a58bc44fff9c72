//! Mid-patches: planning them from pair groups, and trimming the branches where they cross.

pub mod plan;
pub mod sides;
pub mod trim;
