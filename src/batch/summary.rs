//! The batch summary: one row per part (exit code, warnings, patches, the self-check figures of its report,
//! time), written as CSV and JSON; and the per-part state files that make a batch resumable.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::error::Error;
use crate::output::pending::Pending;

/// One part's outcome. The figures come from its report (`result`, `topology`, `solids`), absent when the
/// run failed.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Row {
    pub part: String,
    pub input: String,
    /// 0 clean, 1 warnings, 2 failed (anything else `midsurf run` returned, a crash included, counts as 2).
    pub exit: u8,
    /// "ran" in this batch, or "reused" from an earlier one (same key, outputs present).
    pub status: String,
    pub warnings: Option<usize>,
    pub patches: Option<usize>,
    pub faces: Option<usize>,
    pub shells: Option<usize>,
    pub components: Option<usize>,
    pub valid: Option<bool>,
    pub nonmanifold_edges: Option<usize>,
    pub open_edges: Option<usize>,
    pub open_length: Option<f64>,
    pub rim_edges: Option<usize>,
    /// Share of the part's area in pairs, over all its solids (area-weighted).
    pub paired_share: Option<f64>,
    /// Share of the thin-walled solids' volume within reach of the mid-surface (volume-weighted over them).
    pub coverage: Option<f64>,
    /// Wall time of the part's `midsurf run`, in seconds (of the earlier batch when reused).
    pub time_s: f64,
    /// The error line of a failed run.
    pub error: Option<String>,
    /// What the outputs were made from (see `key`); the next batch skips the part while it is unchanged.
    pub key: String,
}

impl Row {
    /// The figures of a report (JSON as `midsurf run` writes it); fields it lacks stay empty.
    pub fn fill_from_report(&mut self, report: &serde_json::Value) {
        let count = |v: &serde_json::Value| v.as_array().map(Vec::len);
        let uint = |v: &serde_json::Value| v.as_u64().map(|n| n as usize);
        self.warnings = count(&report["warnings"]);
        self.patches = count(&report["patches"]);
        let result = &report["result"];
        self.faces = uint(&result["faces"]);
        self.shells = uint(&result["shells"]);
        self.valid = result["valid"].as_bool();
        let free = &result["free_edges"];
        self.open_edges = uint(&free["open_edges"]);
        self.open_length = free["open_length"].as_f64();
        self.rim_edges = uint(&free["rim_edges"]);
        let topology = &report["topology"];
        self.components = uint(&topology["components"]);
        self.nonmanifold_edges = uint(&topology["nonmanifold_edges"]);
        if let Some(solids) = report["solids"].as_array() {
            self.paired_share = weighted_mean(solids, |s| s["paired_share"].as_f64(), |s| s["area"].as_f64());
            self.coverage =
                weighted_mean(solids, |s| s["coverage"]["share"].as_f64(), |s| s["volume"].as_f64().map(f64::abs));
        }
    }
}

/// The mean of `value` over `solids`, weighted by `weight`; a solid lacking either is left out.
fn weighted_mean(
    solids: &[serde_json::Value],
    value: impl Fn(&serde_json::Value) -> Option<f64>,
    weight: impl Fn(&serde_json::Value) -> Option<f64>,
) -> Option<f64> {
    let (sum, total) = solids
        .iter()
        .filter_map(|s| Some((value(s)?, weight(s)?)))
        .fold((0.0, 0.0), |(sum, total), (v, w)| (sum + v * w, total + w));
    (total > 0.0).then(|| sum / total)
}

const COLUMNS: &str = "part,input,exit,status,warnings,patches,faces,shells,components,valid,nonmanifold_edges,\
open_edges,open_length,rim_edges,paired_share,coverage,time_s,error,key";

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

fn opt<T: ToString>(v: &Option<T>) -> String {
    v.as_ref().map(T::to_string).unwrap_or_default()
}

pub fn csv(rows: &[Row]) -> String {
    let mut out = format!("{COLUMNS}\n");
    for r in rows {
        let fields = [
            csv_field(&r.part),
            csv_field(&r.input),
            r.exit.to_string(),
            r.status.clone(),
            opt(&r.warnings),
            opt(&r.patches),
            opt(&r.faces),
            opt(&r.shells),
            opt(&r.components),
            opt(&r.valid),
            opt(&r.nonmanifold_edges),
            opt(&r.open_edges),
            r.open_length.map(|v| format!("{v:.3}")).unwrap_or_default(),
            opt(&r.rim_edges),
            r.paired_share.map(|v| format!("{v:.4}")).unwrap_or_default(),
            r.coverage.map(|v| format!("{v:.4}")).unwrap_or_default(),
            format!("{:.2}", r.time_s),
            csv_field(r.error.as_deref().unwrap_or("")),
            r.key.clone(),
        ];
        out += &fields.join(",");
        out.push('\n');
    }
    out
}

/// Counts of the parts by exit code.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Counts {
    pub parts: usize,
    pub clean: usize,
    pub warnings: usize,
    pub failed: usize,
    pub ran: usize,
    pub reused: usize,
}

impl Counts {
    pub fn of(rows: &[Row]) -> Counts {
        let mut c = Counts { parts: rows.len(), ..Counts::default() };
        for r in rows {
            match r.exit {
                0 => c.clean += 1,
                1 => c.warnings += 1,
                _ => c.failed += 1,
            }
            if r.status == "ran" {
                c.ran += 1;
            } else {
                c.reused += 1;
            }
        }
        c
    }
}

#[derive(Serialize)]
pub struct Summary<'a> {
    pub midsurf_version: &'static str,
    pub source: String,
    /// "I/N" when this batch ran one shard.
    pub shard: Option<String>,
    pub jobs: usize,
    /// The worst exit code of the parts, the batch's own.
    pub exit: u8,
    pub counts: Counts,
    pub wall_s: f64,
    pub parts: &'a [Row],
}

/// Writes a file atomically (temporary file renamed into place).
pub fn write_atomic(path: &Path, text: &str) -> Result<(), Error> {
    let pending = Pending::new(path, Path::new(""))?;
    pending.write(text.as_bytes())?;
    pending.commit()
}

/// The state of a part from an earlier batch: its row, read from its state file, if any and readable.
pub fn read_state(path: &Path) -> Option<Row> {
    serde_json::from_str(&std::fs::read_to_string(path).ok()?).ok()
}

pub fn write_state(path: &Path, row: &Row) -> Result<(), Error> {
    write_atomic(path, &(serde_json::to_string_pretty(row).expect("rows always serialise") + "\n"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn figures_come_from_the_report() {
        let report = serde_json::json!({
            "warnings": [{}, {}], "patches": [{}, {}, {}],
            "result": {"faces": 7, "shells": 2, "valid": true,
                       "free_edges": {"open_edges": 4, "open_length": 1.5, "rim_edges": 9}},
            "topology": {"components": 2, "nonmanifold_edges": 0},
            "solids": [{"paired_share": 1.0, "area": 3.0, "volume": 6.0, "coverage": {"share": 0.9}},
                       {"paired_share": 0.5, "area": 1.0, "volume": 2.0}],
        });
        let mut row = Row {
            part: "a,b".into(),
            input: "x".into(),
            exit: 1,
            status: "ran".into(),
            time_s: 1.234,
            key: "k".into(),
            ..Row::default()
        };
        row.fill_from_report(&report);
        assert_eq!((row.warnings, row.patches, row.faces, row.components), (Some(2), Some(3), Some(7), Some(2)));
        assert_eq!((row.open_edges, row.rim_edges, row.valid), (Some(4), Some(9), Some(true)));
        assert_eq!(row.paired_share, Some(0.875));
        // A solid without a coverage figure (not thin-walled) is left out of the weighting.
        assert_eq!(row.coverage, Some(0.9));
        let text = csv(&[row]);
        assert_eq!(text.lines().nth(1).unwrap(), "\"a,b\",x,1,ran,2,3,7,2,2,true,0,4,1.500,9,0.8750,0.9000,1.23,,k");
    }
}
