//! midsurf: mid-surfaces of thin-walled solids by face pairing (Sheen et al., after Rezayat 1996).
//!
//! The stages of `midsurf run`, in data-flow order (`run.rs` calls them one after the other):
//! 1. [`load`]: the STEP file read in the kernel, each solid described as a face graph ([`model`]);
//! 2. [`pairing`]: faces paired into walls, small features suppressed (`pairing::driver`);
//! 3. [`patch`]: one mid-patch planned and made per pair group;
//! 4. [`trim`]: the patches fused, the branches hanging past crossings dropped;
//! 5. [`stitch`]: joints grown between patches (T, L, steps, rims) and fused again;
//! 6. [`output`]: shells, STEP attributes, the report and its topology summary, written atomically.
//!
//! Then, as commands of their own: [`mesh`] (`midsurf mesh`: the mid-surface meshed with shells by gmsh and
//! written as solver decks) and [`batch`] (`midsurf batch`: many parts, each a `midsurf run`).
//!
//! Rust decides (pairing, classification, joints); the OCCT sidecar executes kernel operations ([`kernel`]).
//! [`geom`] holds the small geometric computations done in Rust.

// Public: what main.rs (cli, checks, exit, cleanup) and the pairing benchmark (model, pairing, synthetic) use.
pub(crate) mod batch;
pub mod checks;
pub mod cleanup;
pub mod cli;
pub(crate) mod error;
pub mod exit;
pub(crate) mod geom;
pub(crate) mod kernel;
pub(crate) mod load;
pub(crate) mod mesh;
pub mod model;
pub(crate) mod output;
pub mod pairing;
pub(crate) mod patch;
pub(crate) mod run;
pub(crate) mod stitch;
/// Hand-made face graphs for unit tests and the pairing benchmark (`--features synthetic`).
#[cfg(any(test, feature = "synthetic"))]
pub mod synthetic;
pub(crate) mod trim;
