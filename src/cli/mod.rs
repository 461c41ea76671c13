//! The command line: one file per subcommand.

/// `println!` that hands back the write's error instead of panicking: a reader that
/// closes the pipe early (`lumiere list | head -1`) ends the command quietly (see
/// `main`).
macro_rules! outln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        anyhow::Context::context(writeln!(std::io::stdout(), $($arg)*), "writing standard output")
    }};
}

/// `print!` that hands back the write's error, as `outln!`.
macro_rules! out {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        anyhow::Context::context(write!(std::io::stdout(), $($arg)*), "writing standard output")
    }};
}

mod bench;
mod bench_radiosity;
mod bitmap_text;
mod check;
mod compare;
mod compare_checks;
mod contact_sheet;
mod envmap;
mod export;
mod form_factors;
mod gallery;
mod list;
mod radiosity;
mod references;
mod render;
mod shadow_polygons;
mod show;
mod timing;
mod url;
mod view;

use anyhow::{Context, Result};
use clap::{CommandFactory, Parser, Subcommand};

/// A count that must be at least one (`--runs`, `--frame-every`): zero would be
/// accepted and ignored, or divide by it.
fn at_least_one(text: &str) -> std::result::Result<usize, String> {
    match text.parse::<usize>() {
        Ok(n) if n >= 1 => Ok(n),
        Ok(_) => Err("must be at least 1".into()),
        Err(e) => Err(e.to_string()),
    }
}

/// lumiere renders the classic scan-line algorithms as their papers did them.
///
/// Every demonstration of the catalogue renders by its id from any directory:
/// `lumiere list` shows them, `lumiere render cornell-box -o cornell.png` renders one.
/// Scene files (TOML, see docs/scene-format.md) render the same way.
#[derive(Parser, Debug)]
#[command(name = "lumiere", version, about, long_about)]
pub struct Cli {
    /// Worker threads for the parallel passes (default: one per core). The output
    /// is the same for any count.
    #[arg(long, global = true, value_name = "N", value_parser = at_least_one)]
    threads: Option<usize>,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    List(list::Args),
    Show(show::Args),
    Gallery(gallery::Args),
    View(view::Args),
    Export(export::Args),
    Render(render::Args),
    Compare(compare::Args),
    References(references::Args),
    Check(check::Args),
    Envmap(envmap::Args),
    Bench(bench::Args),
    ShadowPolygons(shadow_polygons::Args),
    FormFactors(form_factors::Args),
    ContactSheet(contact_sheet::Args),
}

impl Cli {
    /// How this command's failures map to an exit status: 1, except for `compare`
    /// and `check` (1 beyond their thresholds, 2 for bad input).
    pub fn failure_status(&self) -> fn(&anyhow::Error) -> u8 {
        match self.command {
            Command::Compare(_) => compare::failure_status,
            Command::Check(_) => check::failure_status,
            _ => |_| 1,
        }
    }
}

/// Whether `error` comes from writing to a reader that has gone away (a closed pipe):
/// the conventional ending is a quiet one, not an error.
pub fn is_broken_pipe(error: &anyhow::Error) -> bool {
    error.chain().any(|cause| {
        cause
            .downcast_ref::<std::io::Error>()
            .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe)
    })
}

pub use lumiere::one_line;

/// A command-line usage error as one line: clap's message with the lines that
/// continue it (the missing arguments, the possible values) and a tip naming a
/// similar argument, without the usage summary. Tips to put `--` before a value are
/// left out: negative numbers are taken as values already.
pub fn usage_error_line(error: &clap::Error) -> String {
    let text = error.render().to_string();
    let mut line = String::new();
    for part in text.lines().take_while(|l| !l.starts_with("Usage:")) {
        let part = part.trim();
        if part.is_empty() || part.contains("use '--") || part.starts_with("For more information") {
            continue;
        }
        if let Some(tip) = part.strip_prefix("tip: ") {
            line += &format!(" ({tip})");
        } else {
            if !line.is_empty() {
                line.push(' ');
            }
            line += part;
        }
    }
    let subcommand = std::env::args()
        .nth(1)
        .filter(|name| Cli::command().find_subcommand(name).is_some())
        .map(|name| format!("{name} "))
        .unwrap_or_default();
    one_line(&format!("{line}; see `lumiere {subcommand}--help`"))
}

/// `--width` and `--height`, shared by the commands that make an image.
#[derive(clap::Args, Debug)]
pub struct ImageSize {
    /// Image width in pixels (overrides camera.width).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=lumiere::MAX_IMAGE_SIDE as i64))]
    width: Option<u32>,
    /// Image height in pixels (overrides camera.height).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=lumiere::MAX_IMAGE_SIDE as i64))]
    height: Option<u32>,
}

impl ImageSize {
    /// The sizes given, as scene-key overrides.
    pub fn sets(&self) -> Vec<String> {
        let mut sets = Vec::new();
        if let Some(w) = self.width {
            sets.push(format!("camera.width={w}"));
        }
        if let Some(h) = self.height {
            sets.push(format!("camera.height={h}"));
        }
        sets
    }
}

pub fn run(cli: Cli) -> Result<()> {
    if let Some(n) = cli.threads {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
            .context("--threads")?;
    }
    match cli.command {
        Command::List(a) => list::run(a),
        Command::Show(a) => show::run(a),
        Command::Gallery(a) => gallery::run(a),
        Command::View(a) => view::run(a),
        Command::Export(a) => export::run(a),
        Command::Render(a) => render::run(a),
        Command::Compare(a) => compare::run(a),
        Command::References(a) => references::run(a),
        Command::Check(a) => check::run(a),
        Command::Envmap(a) => envmap::run(a),
        Command::Bench(a) => bench::run(a),
        Command::ShadowPolygons(a) => shadow_polygons::run(a),
        Command::FormFactors(a) => form_factors::run(a),
        Command::ContactSheet(a) => contact_sheet::run(a),
    }
}
