//! The command line: one file per subcommand.

mod bench;
mod bench_radiosity;
mod compare;
mod form_factors;
mod list;
mod radiosity;
mod render;
mod shadow_polygons;
mod timing;

use anyhow::Result;
use clap::{Parser, Subcommand};

/// lumiere renders the classic scan-line algorithms as their papers did them.
///
/// Every demonstration of the catalogue renders by its id from any directory:
/// `lumiere list` shows them, `lumiere render cornell-box -o cornell.png` renders one.
/// Scene files (TOML, see docs/scene-format.md) render the same way.
#[derive(Parser, Debug)]
#[command(name = "lumiere", version, about, long_about)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    List(list::Args),
    Render(render::Args),
    Compare(compare::Args),
    Bench(bench::Args),
    ShadowPolygons(shadow_polygons::Args),
    FormFactors(form_factors::Args),
}

pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::List(a) => list::run(a),
        Command::Render(a) => render::run(a),
        Command::Compare(a) => compare::run(a),
        Command::Bench(a) => bench::run(a),
        Command::ShadowPolygons(a) => shadow_polygons::run(a),
        Command::FormFactors(a) => form_factors::run(a),
    }
}
