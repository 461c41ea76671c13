//! `lumiere show`: one catalogue entry's paper, summary and scene.

use anyhow::Result;
use lumiere::catalogue;

/// Print an entry's citation and summary, then its scene as TOML with the scene it
/// extends merged in: every key shown can be changed with `--set KEY=VALUE`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// A catalogue id (see `lumiere list`).
    id: String,
    /// Print the entry's file as written instead (its `extends` unresolved).
    #[arg(long)]
    source: bool,
}

pub fn run(args: Args) -> Result<()> {
    if args.source {
        out!("{}", catalogue::source(&args.id)?)?;
        return Ok(());
    }
    let entry = catalogue::entry(&args.id)?;
    let a = &entry.algorithm;
    outln!("# {}: {}", a.id, a.title)?;
    outln!("# {} ({}), topic {}", a.authors, a.year, a.topic.name())?;
    outln!("#")?;
    for line in super::list::wrap(&a.citation, 84) {
        outln!("# {line}")?;
    }
    outln!("#")?;
    for line in super::list::wrap(&a.summary, 84) {
        outln!("# {line}")?;
    }
    outln!("#")?;
    if let Some(base) = &a.extends {
        outln!("# The scene of `{base}` with this entry's tables merged over it.")?;
    }
    outln!(
        "# Change any key with --set, e.g. lumiere render {} --set camera.width=256 -o out.png",
        a.id
    )?;
    outln!()?;
    out!("{}", toml::to_string(&entry.scene)?)?;
    Ok(())
}
