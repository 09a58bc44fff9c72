//! Process exit codes, as scripts rely on them: 0 all good, 1 finished with warnings, 2 failed.

use std::process::ExitCode;

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Exit {
    /// Everything asked for was done.
    Clean,
    /// Output written, but the report carries warnings the user should look at.
    Warnings,
    /// Bad input, sidecar failure: nothing (or nothing trustworthy) was written.
    Failed,
}

impl Exit {
    pub fn code(self) -> u8 {
        match self {
            Exit::Clean => 0,
            Exit::Warnings => 1,
            Exit::Failed => 2,
        }
    }
}

impl From<Exit> for ExitCode {
    fn from(exit: Exit) -> ExitCode {
        ExitCode::from(exit.code())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_are_the_documented_ones_and_worst_wins() {
        assert_eq!([Exit::Clean, Exit::Warnings, Exit::Failed].map(Exit::code), [0, 1, 2]);
        assert_eq!(Exit::Clean.max(Exit::Warnings).max(Exit::Clean), Exit::Warnings);
    }
}
