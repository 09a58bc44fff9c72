use std::process::ExitCode;

use clap::error::ErrorKind;
use clap::Parser;
use midsurf::cli::{self, Cli};
use midsurf::exit::Exit;

fn main() -> ExitCode {
    // Before any thread: stop signals are then taken by one thread that cleans up (temporaries, sidecar).
    midsurf::cleanup::install();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // Help and version are answers, not errors: clap prints them and exits 0.
        Err(e) if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) => e.exit(),
        Err(e) => return fail(&midsurf::checks::clap_error_line(&e)),
    };
    if let Err(problem) = midsurf::checks::environment() {
        return fail(&problem);
    }
    match cli::run(cli) {
        Ok(exit) => exit.into(),
        Err(error) => {
            eprintln!("midsurf: error: {error}");
            Exit::Failed.into()
        }
    }
}

/// The documented failure: one line on stderr, exit 2.
fn fail(problem: &str) -> ExitCode {
    eprintln!("midsurf: error: {problem}");
    Exit::Failed.into()
}
