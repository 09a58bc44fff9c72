//! The files of one run, each written to a temporary beside its target and renamed into place only when every
//! one is complete: a failure leaves none half-written.

use std::path::{Path, PathBuf};

use super::pending::Pending;
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
    /// Checks every target before any work is done (their directories exist, none is the input).
    pub fn open(
        input: &Path,
        step: &Path,
        [report, summary, csv, preview]: [&Option<PathBuf>; 4],
    ) -> Result<Files, Error> {
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
        self.step.commit()?;
        for pending in [self.report, self.summary, self.csv, self.preview].into_iter().flatten() {
            pending.commit()?;
        }
        Ok(())
    }
}
