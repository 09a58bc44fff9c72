//! The OCCT sidecar: a Python process that executes kernel operations for us (see sidecar/PROTOCOL.md).

pub mod client;
pub mod convert;
#[cfg(test)]
pub mod fake;
pub mod process;
pub mod protocol;
pub mod python;
pub mod timeout;

use std::fmt;
use std::time::Duration;

use serde::de::DeserializeOwned;

pub use client::{Client, Sidecar};
use protocol::{EdgeRef, Probed, Request};

use crate::model::shapes::{EdgeProbe, Fused, Handle, Shells};

/// What a fuse is given, which decides how much it must intersect.
#[derive(Debug, Clone, PartialEq)]
pub enum FuseKind {
    /// Patches as made: every face of every patch is intersected with every other.
    Patches,
    /// A stitching pass: every patch comes out of a fuse (its faces already share their edges), so only
    /// different patches are intersected; the `settled` ones (indices into the patches), taken unchanged from
    /// one earlier fuse, not even with each other. Faces are also split along joints that end inside them.
    Again { settled: Vec<usize> },
}

/// What the stages ask of the geometric kernel. The real one is the sidecar process ([`Sidecar`]); unit tests
/// drive the stages with a fake that answers from a script. The ops whose replies the stages keep return the
/// domain shapes of `model::shapes`, converted here from the wire types.
pub trait Kernel {
    /// Sends one request and decodes its `ok` payload into `R`.
    fn call<R: DeserializeOwned>(&mut self, request: &Request) -> Result<R, SidecarError>;

    /// The patches behind `patches` fused into one shape, split where they cross; `bodies` (the body of each
    /// patch) keeps the bodies apart: patches of different bodies are fused separately and never share an edge.
    fn fuse(
        &mut self,
        patches: Vec<Handle>,
        bodies: &[usize],
        fuzzy: f64,
        kind: FuseKind,
    ) -> Result<Fused, SidecarError> {
        let apart = bodies.iter().any(|&b| Some(&b) != bodies.first());
        let bodies = if apart { bodies.to_vec() } else { Vec::new() };
        let (again, settled) = match kind {
            FuseKind::Patches => (false, Vec::new()),
            FuseKind::Again { settled } => (true, settled),
        };
        let request = Request::Fuse { patches, fuzzy, split_internal: again, patches_fused: again, bodies, settled };
        self.call::<protocol::Fused>(&request).map(Fused::from)
    }

    /// One shell per set of faces of the fused shape `handle`, the faces of each set of `merge` made one face
    /// where they lie on one surface.
    fn make_shells(
        &mut self,
        handle: Handle,
        shells: Vec<Vec<usize>>,
        merge: Vec<Vec<usize>>,
        fuzzy: f64,
    ) -> Result<Shells, SidecarError> {
        self.call::<protocol::Shells>(&Request::MakeShells { handle, shells, merge, fuzzy }).map(Shells::from)
    }

    /// The free `edges` of the fused shape `handle` sampled `samples` times each, with the rays' meetings with
    /// the faces `targets` within `reach`.
    fn probe_edges(
        &mut self,
        handle: Handle,
        edges: Vec<EdgeRef>,
        targets: Vec<usize>,
        samples: usize,
        reach: f64,
    ) -> Result<Vec<EdgeProbe>, SidecarError> {
        let probed: Probed = self.call(&Request::ProbeEdges { handle, edges, targets, samples, reach })?;
        Ok(probed.edges.into_iter().map(EdgeProbe::from).collect())
    }
}

impl Kernel for Sidecar {
    fn call<R: DeserializeOwned>(&mut self, request: &Request) -> Result<R, SidecarError> {
        Sidecar::call(self, request)
    }
}

impl<T: Transport> Kernel for Client<T> {
    fn call<R: DeserializeOwned>(&mut self, request: &Request) -> Result<R, SidecarError> {
        Client::call(self, request)
    }
}

/// What can go wrong talking to the sidecar. Every variant says which op it concerns.
#[derive(Debug, Clone, PartialEq)]
pub enum SidecarError {
    /// The Python interpreter or the sidecar package could not be found or started.
    Spawn { why: String },
    /// The op ran and failed: the sidecar's own error code and message.
    Op { op: String, code: String, message: String },
    /// The process ended (crash, segfault, killed) while we waited for `op`.
    Died { op: String, stderr: String },
    /// No reply to `op` within its timeout; the process was killed.
    Timeout { op: String, after: Duration, stderr: String },
    /// A reply that does not follow the protocol.
    BadReply { op: String, why: String, line: String },
}

impl SidecarError {
    /// The sidecar's error code, when the op itself failed.
    pub fn code(&self) -> Option<&str> {
        match self {
            SidecarError::Op { code, .. } => Some(code),
            _ => None,
        }
    }
}

/// The last line of the child's stderr that says something, for one-line error messages, without the
/// terminal colour codes OCCT puts in its messages.
pub fn last_words(stderr: &str) -> String {
    let plain = strip_ansi(stderr);
    plain
        .lines()
        .rev()
        .find(|l| !l.trim().is_empty())
        .map(|l| format!(" (sidecar stderr: {})", l.trim()))
        .unwrap_or_default()
}

/// Text without ANSI escape sequences (ESC [ ... final byte) or other control characters but newlines.
pub fn strip_ansi(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        if c == '\u{1b}' {
            if chars.peek() == Some(&'[') {
                chars.next();
                // Parameters and intermediates, up to the final byte (@ to ~).
                for d in chars.by_ref() {
                    if ('@'..='~').contains(&d) {
                        break;
                    }
                }
            }
        } else if c == '\n' || c == '\t' || !c.is_control() {
            out.push(c);
        }
    }
    out
}

impl fmt::Display for SidecarError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SidecarError::Spawn { why } => write!(f, "cannot start the OCCT sidecar: {why}"),
            SidecarError::Op { message, .. } => write!(f, "{message}"),
            SidecarError::Died { op, stderr } => {
                write!(f, "the OCCT sidecar died during '{op}'{}", last_words(stderr))
            }
            SidecarError::Timeout { op, after, stderr } => write!(
                f,
                "the OCCT sidecar did not answer '{op}' within {} s and was stopped{}",
                after.as_secs(),
                last_words(stderr)
            ),
            SidecarError::BadReply { op, why, line } => {
                write!(f, "the OCCT sidecar broke the protocol during '{op}': {why}: {line}")
            }
        }
    }
}

impl std::error::Error for SidecarError {}

/// A line-based, bidirectional channel to a sidecar; the real one is a child process, tests use a fake.
pub trait Transport {
    fn send(&mut self, line: &str) -> Result<(), TransportError>;
    fn recv(&mut self, timeout: Duration) -> Result<String, TransportError>;
    /// What the other side said on its diagnostic channel (the child's stderr), most recent last.
    fn diagnostics(&self) -> String;
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TransportError {
    Closed,
    Timeout,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kernel_colour_codes_are_stripped_from_the_last_words() {
        let stderr = "\u{1b}[31;1m**** ERR StepFile : Incorrect syntax ****\n\u{1b}[0m\n";
        assert_eq!(last_words(stderr), " (sidecar stderr: **** ERR StepFile : Incorrect syntax ****)");
        assert_eq!(strip_ansi("a\u{1b}[0mb\u{7}c"), "abc");
    }
}
