//! `lumiere list`: the catalogue.

use anyhow::Result;
use lumiere::catalogue;

/// List the catalogue: id, year, title.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Print every entry's [algorithm] table as JSON instead.
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> Result<()> {
    let entries = catalogue::entries()?;
    if args.json {
        let tables: Vec<_> = entries.iter().map(|e| &e.algorithm).collect();
        outln!("{}", serde_json::to_string_pretty(&tables)?)?;
        return Ok(());
    }
    let width = entries
        .iter()
        .map(|e| e.algorithm.id.len())
        .max()
        .unwrap_or(0);
    for e in &entries {
        let a = &e.algorithm;
        outln!("{:width$}  {}  {}", a.id, a.year, a.title)?;
    }
    Ok(())
}
