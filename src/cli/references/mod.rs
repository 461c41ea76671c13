//! `lumiere references`: a reference suite other renderers test against (see
//! `manifest` for its layout), made whole on one machine, or in parts (`--shard
//! K/N`) that `--merge` joins into the same bytes.

mod entry;
mod ground_truth;
pub mod manifest;
mod merge;

use anyhow::{Result, bail};
use lumiere::{catalogue, write_atomically};
use manifest::{Manifest, SCHEMA, Settings, Shard};
use std::path::{Path, PathBuf};

/// Write a reference suite: per catalogue entry its linear reference (EXR), the
/// buffers its methods make, its scene for lumiere, POV-Ray, Mitsuba 3 and the
/// other exporters, and for a sampled entry the per-pixel mean and variance over
/// --samples seeds; and manifest.json naming the paper, the settings, the files
/// and the checks a candidate must pass (its schema: docs/testing-your-renderer.md).
///
/// Each entry is written whole or not at all and kept when the same command runs
/// again (an interrupted suite resumes); manifest.json comes last, so a suite
/// without it is unfinished. The output is the same bytes on any machine.
///
/// --shard K/N makes part K of N (entries K, K + N, K + 2N… of those asked for),
/// one job of a Slurm array or of GNU parallel; `lumiere references --merge DIR...
/// -o OUT` joins the parts into the suite one machine would have made.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Catalogue ids (default: the whole catalogue).
    ids: Vec<String>,
    /// The suite's directory.
    #[arg(short, long)]
    output: PathBuf,
    /// Width of every reference (height at each entry's aspect ratio; default:
    /// each entry's test size).
    #[arg(long, value_parser = clap::value_parser!(u32).range(8..=8192))]
    width: Option<u32>,
    /// Renders (seeds) a sampled entry's mean and variance are taken over.
    #[arg(long, default_value_t = 16, value_parser = clap::value_parser!(u32).range(2..=1 << 20))]
    samples: u32,
    /// Samples per pixel side: antialiased by default, as the peers' renders are.
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u32).range(1..=16))]
    supersample: u32,
    /// Paths per pixel side of each of a ground truth's renders (--samples of
    /// them): biased entries (radiosity, the two-pass methods, sampled soft
    /// shadows) get the path tracer's answer beside their reference.
    #[arg(long, default_value_t = 16, value_parser = clap::value_parser!(u32).range(1..=64))]
    ground_truth_paths: u32,
    /// Make part K of N (1 ≤ K ≤ N).
    #[arg(long, value_name = "K/N", value_parser = shard, conflicts_with = "merge")]
    shard: Option<Shard>,
    /// Join the parts made with --shard in these directories into --output.
    #[arg(long, value_name = "DIR", num_args = 1.., conflicts_with_all = ["ids", "width", "supersample", "ground_truth_paths"])]
    merge: Vec<PathBuf>,
}

fn shard(text: &str) -> std::result::Result<Shard, String> {
    let (k, n) = text
        .split_once('/')
        .ok_or("must be K/N, part K of N (e.g. 2/8)")?;
    let parse = |s: &str| s.trim().parse::<u32>().map_err(|e| e.to_string());
    let (index, count) = (parse(k)?, parse(n)?);
    if count == 0 || index == 0 || index > count {
        return Err(format!("{text}: part K of N needs 1 <= K <= N"));
    }
    Ok(Shard { index, count })
}

pub fn run(args: Args) -> Result<()> {
    if !args.merge.is_empty() {
        return merge::run(&args.merge, &args.output);
    }
    let all = catalogue::ids();
    for id in &args.ids {
        if !all.contains(id) {
            // The catalogue's own error names the id and suggests one.
            catalogue::entry(id)?;
        }
    }
    // Catalogue order, each once, whatever order they were named in.
    let ids: Vec<String> = all
        .into_iter()
        .filter(|id| args.ids.is_empty() || args.ids.contains(id))
        .collect();
    let settings = Settings {
        width: args.width,
        samples: args.samples,
        supersample: args.supersample,
        ground_truth_paths: args.ground_truth_paths,
    };
    let mine: Vec<&String> = ids
        .iter()
        .enumerate()
        .filter(|(i, _)| {
            args.shard
                .is_none_or(|s| *i as u32 % s.count == s.index - 1)
        })
        .map(|(_, id)| id)
        .collect();
    std::fs::create_dir_all(&args.output)
        .map_err(|e| anyhow::anyhow!("{}: {e}", args.output.display()))?;
    let mut entries = Vec::new();
    for (n, id) in mine.iter().enumerate() {
        let record = match entry::already_made(&args.output, id, &settings) {
            Some(record) => {
                eprintln!("[{}/{}] {id}: kept", n + 1, mine.len());
                record
            }
            None => {
                eprintln!("[{}/{}] {id}", n + 1, mine.len());
                entry::make(&args.output, id, &settings)?
            }
        };
        entries.push(record);
    }
    let manifest = Manifest {
        schema: SCHEMA.into(),
        lumiere: env!("CARGO_PKG_VERSION").into(),
        settings,
        ids,
        shard: args.shard,
        entries,
    };
    write_manifest(&args.output, &manifest)
}

fn write_manifest(dir: &Path, manifest: &Manifest) -> Result<()> {
    Ok(write_atomically(
        &dir.join("manifest.json"),
        &manifest.to_bytes(),
    )?)
}

/// Reads and checks a suite's manifest, refusing it in one line.
pub fn read_manifest(path: &Path) -> Result<Manifest> {
    let bytes = std::fs::read(path).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    let manifest: Manifest = serde_json::from_slice(&bytes).map_err(|e| {
        anyhow::anyhow!("{}: not a reference suite's manifest: {e}", path.display())
    })?;
    if manifest.schema != SCHEMA {
        bail!(
            "{}: schema {:?}: this lumiere reads {SCHEMA:?}",
            path.display(),
            manifest.schema
        );
    }
    Ok(manifest)
}
