//! The files of one run, each written to a temporary beside its target and renamed into place only when every
//! one is complete: a failure leaves none half-written.

use std::path::{Path, PathBuf};

use super::pending::{commit_all, distinct, Pending};
use super::report::{patches_csv, Report};
use crate::error::Error;

pub struct Files {
    pub step: Pending,
    pub report: Option<Pending>,
    pub summary: Option<Pending>,
    pub csv: Option<Pending>,
    pub preview: Option<Pending>,
}

impl Files {
    /// Checks every target before any work is done (no two the same, their directories exist, none is the
    /// input).
    pub fn open(
        input: &Path,
        step: &Path,
        [report, summary, csv, preview]: [&Option<PathBuf>; 4],
    ) -> Result<Files, Error> {
        let named = [("-o", Some(step)), ("--report", report.as_deref()), ("--summary", summary.as_deref())];
        let named = named.into_iter().chain([("--csv", csv.as_deref()), ("--preview", preview.as_deref())]);
        let named: Vec<(&str, &Path)> = named.filter_map(|(n, p)| p.map(|p| (n, p))).collect();
        distinct(&named)?;
        let step = Pending::new(step, input)?;
        let optional = |path: &Option<PathBuf>| path.as_deref().map(|p| Pending::new(p, input)).transpose();
        let (report, summary) = (optional(report)?, optional(summary)?);
        let (csv, preview) = (optional(csv)?, optional(preview)?);
        Ok(Files { step, report, summary, csv, preview })
    }

    /// Writes the report's files (the STEP and preview are written by the kernel), then renames all into place.
    pub fn finish(self, report: &Report) -> Result<(), Error> {
        if let Some(pending) = &self.report {
            pending
                .write((serde_json::to_string_pretty(report).expect("reports always serialise") + "\n").as_bytes())?;
        }
        if let Some(pending) = &self.summary {
            pending.write(report.topology.text().as_bytes())?;
        }
        if let Some(pending) = &self.csv {
            pending.write(patches_csv(&report.patches, &report.solids).as_bytes())?;
        }
        let set = [Some(self.step), self.report, self.summary, self.csv, self.preview];
        commit_all(set.into_iter().flatten().collect())
    }
}
