//! Data shared between the stages: the face graph of a solid, the tolerances derived from it, the run's
//! parameters, the shapes the kernel returns, the warnings.

pub mod face_graph;
pub(crate) mod params;
pub(crate) mod shapes;
pub mod tolerance;
pub(crate) mod union_find;
pub(crate) mod warning;
