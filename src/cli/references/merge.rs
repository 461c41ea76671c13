//! `lumiere references --merge`: the parts of a sharded suite joined into the suite
//! one machine would have made, byte for byte; refused in one line when the parts
//! were made with other settings or versions, or one is missing or given twice.

use super::manifest::Manifest;
use super::{read_manifest, write_manifest};
use anyhow::{Context, Result, bail};
use lumiere::StagedDirectory;
use std::path::{Path, PathBuf};

pub fn run(parts: &[PathBuf], output: &Path) -> Result<()> {
    let mut manifests = Vec::new();
    for dir in parts {
        let path = dir.join("manifest.json");
        let manifest = read_manifest(&path)?;
        let Some(shard) = manifest.shard else {
            bail!(
                "{}: a whole suite, not a part made with --shard",
                path.display()
            );
        };
        manifests.push((path, shard, manifest));
    }
    let (first_path, first_shard, first) = &manifests[0];
    let mut seen = vec![None::<&PathBuf>; first_shard.count as usize];
    for (path, shard, m) in &manifests {
        let same = m.settings == first.settings
            && m.ids == first.ids
            && m.lumiere == first.lumiere
            && shard.count == first_shard.count;
        if !same {
            bail!(
                "{}: made with other settings, entries, version or part count than {}",
                path.display(),
                first_path.display()
            );
        }
        if let Some(earlier) = seen[shard.index as usize - 1].replace(path) {
            bail!(
                "{} and {}: both are part {}/{}",
                earlier.display(),
                path.display(),
                shard.index,
                shard.count
            );
        }
    }
    if let Some(missing) = seen.iter().position(Option::is_none) {
        bail!(
            "part {}/{} is missing: give every part to --merge",
            missing + 1,
            first_shard.count
        );
    }
    let staged = StagedDirectory::for_replacing(output)?;
    let mut entries = Vec::new();
    for id in &first.ids {
        let (dir, record) = parts
            .iter()
            .zip(&manifests)
            .find_map(|(dir, (_, _, m))| m.entries.iter().find(|e| &e.id == id).map(|e| (dir, e)))
            .with_context(|| format!("no part holds entry {id}"))?;
        copy_tree(&dir.join(id), &staged.root().join(id))?;
        entries.push(record.clone());
    }
    let manifest = Manifest {
        shard: None,
        entries,
        ..first.clone()
    };
    write_manifest(staged.root(), &manifest)?;
    Ok(staged.replace()?)
}

/// Copies `from` into `to`, file by file, in a fixed order.
fn copy_tree(from: &Path, to: &Path) -> Result<()> {
    std::fs::create_dir_all(to).with_context(|| to.display().to_string())?;
    let mut children: Vec<_> = std::fs::read_dir(from)
        .with_context(|| from.display().to_string())?
        .collect::<std::io::Result<_>>()
        .with_context(|| from.display().to_string())?;
    children.sort_by_key(|c| c.file_name());
    for child in children {
        let (source, target) = (child.path(), to.join(child.file_name()));
        if child.file_type()?.is_dir() {
            copy_tree(&source, &target)?;
        } else {
            std::fs::copy(&source, &target).with_context(|| source.display().to_string())?;
        }
    }
    Ok(())
}
