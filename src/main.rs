use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = lumiere_cli::Cli::parse();
    let failure_status = cli.failure_status();
    match lumiere_cli::run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        // The reader of standard output stopped reading (`| head -1`): nothing more to say.
        Err(e) if lumiere_cli::is_broken_pipe(&e) => ExitCode::SUCCESS,
        Err(e) => {
            // One line: the error and its causes, joined.
            eprintln!("error: {}", format!("{e:#}").replace('\n', " "));
            ExitCode::from(failure_status(&e))
        }
    }
}

#[path = "cli/mod.rs"]
mod lumiere_cli;
