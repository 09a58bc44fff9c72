//! Checks on what the user gives besides the part: environment variables and the sense of option values.
//! Each problem is one line the caller prints as `midsurf: error: ...` (or a warning in the report), so a
//! typo never panics and a nonsense value never passes silently.

use crate::kernel::timeout::{parse_timeout, TIMEOUT_VAR};
use crate::model::warning::Warning;

/// Every midsurf environment variable that can be checked before any work; the first problem found.
pub fn environment() -> Result<(), String> {
    match std::env::var(TIMEOUT_VAR) {
        Ok(text) => parse_timeout(&text).map(|_| ()),
        Err(std::env::VarError::NotPresent) => Ok(()),
        Err(std::env::VarError::NotUnicode(_)) => Err(format!("{TIMEOUT_VAR} is not valid UTF-8")),
    }
}

/// A command-line error from clap as one line: its own first line without the `error: ` prefix, and where
/// to look. Help and version requests are no errors and are left to clap.
pub fn clap_error_line(error: &clap::Error) -> String {
    use clap::error::ErrorKind;
    if error.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
        return "no command given; see 'midsurf --help'".to_string();
    }
    // The first paragraph (a missing argument's names follow on their own lines), joined.
    let text = error.to_string();
    let first: Vec<&str> =
        text.lines().map(str::trim).skip_while(|l| l.is_empty()).take_while(|l| !l.is_empty()).collect();
    let first = first.join(" ");
    let first = first.strip_prefix("error: ").unwrap_or(&first);
    format!("{}; see 'midsurf --help'", if first.is_empty() { "bad arguments" } else { first })
}

/// A user's --t-max above the part's size is nonsense: every face would be a candidate of every other and
/// faces across the part would pair. Refused, naming the part's size.
pub fn t_max_fits(t_max: Option<f64>, diagonal: f64) -> Result<(), String> {
    match t_max {
        Some(t) if t > diagonal => Err(format!(
            "--t-max {t} mm is larger than the part itself (bounding box diagonal {diagonal:.3} mm): give the \
             thickest wall, or leave it out to have it estimated"
        )),
        _ => Ok(()),
    }
}

/// Feature limits above the part's size suppress the whole part as one feature: said as a warning.
pub fn limit_warnings(limits: &[(&str, Option<f64>)], diagonal: f64) -> Vec<Warning> {
    limits
        .iter()
        .filter_map(|&(name, value)| {
            let v = value.filter(|&v| v > diagonal)?;
            Some(Warning {
                code: "option_out_of_range",
                message: format!(
                    "--{name} {v} mm is larger than the part itself (bounding box diagonal {diagonal:.3} mm)"
                ),
                solid: None,
                faces: Vec::new(),
            })
        })
        .collect()
}

/// The option checks that need the part: an error for a --t-max larger than the largest solid, warnings for
/// feature limits larger than it.
pub fn against_part(
    params: &crate::pairing::driver::PairingParams,
    part: &crate::load::Part,
) -> Result<Vec<Warning>, String> {
    let diagonal = part.solids.iter().map(|s| s.graph.bbox.diagonal()).fold(0.0, f64::max);
    t_max_fits(params.t_max, diagonal)?;
    let l = &params.limits;
    Ok(limit_warnings(&[("fillet-max", l.fillet_max), ("hole-max", l.hole_max), ("boss-max", l.boss_max)], diagonal))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn timeouts_must_be_finite_positive_and_sane() {
        assert_eq!(parse_timeout("2").unwrap(), Duration::from_secs(2));
        assert_eq!(parse_timeout("0.5").unwrap(), Duration::from_millis(500));
        for bad in ["-1", "0", "NaN", "nan", "inf", "-inf", "1e30", "abc", ""] {
            let err = parse_timeout(bad).unwrap_err();
            assert!(err.starts_with("MIDSURF_TIMEOUT_SECS=") && !err.contains('\n'), "{bad}: {err}");
        }
    }

    #[test]
    fn clap_errors_become_one_line() {
        use clap::Parser;
        let err = crate::cli::Cli::try_parse_from(["midsurf", "run", "--bogus"]).unwrap_err();
        let line = clap_error_line(&err);
        assert!(!line.contains('\n') && line.contains("--bogus") && line.ends_with("see 'midsurf --help'"), "{line}");
        let err = crate::cli::Cli::try_parse_from(["midsurf", "run", "a.step"]).unwrap_err();
        assert!(clap_error_line(&err).contains("--output"), "{}", clap_error_line(&err));
    }

    #[test]
    fn a_t_max_larger_than_the_part_is_refused() {
        assert!(t_max_fits(Some(1e9), 120.0).unwrap_err().contains("larger than the part"));
        assert!(t_max_fits(Some(3.0), 120.0).is_ok() && t_max_fits(None, 120.0).is_ok());
        let w = limit_warnings(&[("hole-max", Some(500.0)), ("boss-max", Some(5.0)), ("fillet-max", None)], 120.0);
        assert_eq!(w.len(), 1);
        assert!(w[0].message.starts_with("--hole-max 500 mm"), "{}", w[0].message);
    }
}
