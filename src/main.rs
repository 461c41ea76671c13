use clap::Parser;
use std::process::ExitCode;

// The renderer allocates many small, short-lived lists (clipped polygons, contours,
// spans): glibc's allocator took 12-20% of the time of the exact shadow methods.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> ExitCode {
    // Interrupted (Ctrl-C, SIGTERM): no temporary file or staging directory is left
    // behind, and the status says so (128 + SIGINT).
    let _ = ctrlc::set_handler(|| {
        lumiere::remove_unfinished();
        std::process::exit(130);
    });
    let cli = match lumiere_cli::Cli::try_parse() {
        Ok(cli) => cli,
        // Help and version, asked for or shown for a bare `lumiere`: clap's own pages.
        Err(e)
            if !e.use_stderr()
                || e.kind() == clap::error::ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand =>
        {
            e.exit()
        }
        Err(e) => {
            eprintln!("{}", lumiere_cli::usage_error_line(&e));
            return ExitCode::from(2);
        }
    };
    let failure_status = cli.failure_status();
    match lumiere_cli::run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        // The reader of standard output stopped reading (`| head -1`): nothing more to say.
        Err(e) if lumiere_cli::is_broken_pipe(&e) => ExitCode::SUCCESS,
        Err(e) => {
            // One line: the error and its causes, joined.
            eprintln!("error: {}", lumiere_cli::one_line(&format!("{e:#}")));
            ExitCode::from(failure_status(&e))
        }
    }
}

#[path = "cli/mod.rs"]
mod lumiere_cli;
