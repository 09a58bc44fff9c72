//! midsurf: mid-surfaces of thin-walled solids by face pairing (Sheen et al., after Rezayat 1996).
//!
//! Rust decides (pairing, classification, joints); the OCCT sidecar executes kernel operations.

pub mod cli;
pub mod error;
pub mod exit;
pub mod face_graph;
pub mod features;
pub mod geom;
pub mod inspect;
pub mod joint;
pub mod mesh;
pub mod output;
pub mod pairing;
pub mod pairs_report;
pub mod part;
pub mod patch;
pub mod report;
pub mod run;
pub mod sidecar;
pub mod stitch;
pub mod synthetic;
pub mod tolerance;
pub mod topology;
pub mod union_find;
