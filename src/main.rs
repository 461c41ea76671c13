use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = lumiere_cli::Cli::parse();
    match lumiere_cli::run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // One line: the error and its causes, joined.
            eprintln!("error: {}", format!("{e:#}").replace('\n', " "));
            ExitCode::FAILURE
        }
    }
}

#[path = "cli/mod.rs"]
mod lumiere_cli;
