use std::process::ExitCode;

use clap::Parser;
use midsurf::cli::{self, Cli};
use midsurf::exit::Exit;

fn main() -> ExitCode {
    match cli::run(Cli::parse()) {
        Ok(exit) => exit.into(),
        Err(error) => {
            eprintln!("midsurf: error: {error}");
            Exit::Failed.into()
        }
    }
}
