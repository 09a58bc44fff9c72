//! The per-op timeout set in the environment (MIDSURF_TIMEOUT_SECS): parsed in one place, checked at start-up
//! by `checks::environment`.

use std::time::Duration;

/// The variable that replaces every sidecar op's timeout (tests use it to provoke timeouts quickly).
pub const TIMEOUT_VAR: &str = "MIDSURF_TIMEOUT_SECS";

/// The largest timeout accepted: a week. Beyond it a value is a typo (1e30), and `Duration` overflows anyway.
const TIMEOUT_MAX_SECS: f64 = 7.0 * 24.0 * 3600.0;

/// Parses a timeout in seconds: a finite number above 0, at most a week.
pub fn parse_timeout(text: &str) -> Result<Duration, String> {
    match text.trim().parse::<f64>() {
        Ok(secs) if secs.is_finite() && secs > 0.0 && secs <= TIMEOUT_MAX_SECS => Ok(Duration::from_secs_f64(secs)),
        _ => Err(format!(
            "{TIMEOUT_VAR}={text:?} is not a timeout: give seconds, a number above 0 and at most {TIMEOUT_MAX_SECS}"
        )),
    }
}

/// The timeout set in the environment, if any (a bad value was refused at start-up by `environment`).
pub fn timeout_override() -> Option<Duration> {
    std::env::var(TIMEOUT_VAR).ok().and_then(|s| parse_timeout(&s).ok())
}
