//! Writing the results: the report and its topology summary, and files written atomically.

pub mod inspect;
pub mod pending;
pub mod report;
pub mod topology;
