//! Mid-patches: planning them from pair groups (which faces, where through the wall, which loops to fill), and
//! making them in the kernel.

pub mod make;
pub mod plan;
pub mod sides;
