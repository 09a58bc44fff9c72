//! Data shared between the stages: the face graph of a solid and the tolerances derived from it.

pub mod face_graph;
pub mod shapes;
pub mod tolerance;
pub mod warning;
