//! Mid-patches: planning them from pair groups, and trimming the branches where they cross.

pub mod plan;
pub mod trim;
