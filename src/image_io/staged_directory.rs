//! A directory of outputs that is always consistent (the frames of a progressive
//! solve, every buffer of a frame): the files of one run are written into a hidden
//! staging directory beside it and moved in only when the run is complete,
//! replacing what an earlier run left; a run that fails or is interrupted leaves
//! the directory as it was.

use super::{Unfinished, refuse_read_only, without_temporary_name};
use crate::error::{Error, FileOp, Result};
use std::path::{Path, PathBuf};

pub struct StagedDirectory {
    target: PathBuf,
    staging: tempfile::TempDir,
    _unfinished: Unfinished,
    /// The directory `create` made, removed again if the run fails while it is
    /// still empty (a full disk must not leave an empty directory behind).
    made: MadeDirectory,
}

/// A directory made for a run, removed when dropped unless `kept`, and only if
/// empty: nothing of anyone's is lost.
struct MadeDirectory(Option<PathBuf>);

impl MadeDirectory {
    fn kept(&mut self) {
        self.0 = None;
    }
}

impl Drop for MadeDirectory {
    fn drop(&mut self) {
        if let Some(dir) = &self.0 {
            let _ = std::fs::remove_dir(dir);
        }
    }
}

impl StagedDirectory {
    /// Makes `target` (if missing) and a staging directory beside it.
    pub fn create(target: &Path) -> Result<StagedDirectory> {
        let made = MadeDirectory((!target.exists()).then(|| target.to_path_buf()));
        std::fs::create_dir_all(target).map_err(|e| Error::io(FileOp::Write, target, e))?;
        Ok(StagedDirectory {
            made,
            ..StagedDirectory::for_replacing(target)?
        })
    }

    /// A staging directory for a `target` directory that is replaced whole when
    /// the run completes (`replace`): its files refer to each other, so no file of
    /// an earlier run may stay beside them. `target` is not made until then.
    pub fn for_replacing(target: &Path) -> Result<StagedDirectory> {
        let parent = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        std::fs::create_dir_all(parent).map_err(|e| Error::io(FileOp::Write, parent, e))?;
        let staging = tempfile::Builder::new()
            .prefix(".lumiere-staging-")
            .tempdir_in(parent)
            .map_err(|e| Error::io(FileOp::WriteIn, parent, without_temporary_name(e, parent)))?;
        Ok(StagedDirectory {
            target: target.to_path_buf(),
            _unfinished: Unfinished::track(staging.path()),
            staging,
            made: MadeDirectory(None),
        })
    }

    /// The staging directory itself.
    pub fn root(&self) -> &Path {
        self.staging.path()
    }

    /// Puts the staging directory in `target`'s place: an earlier `target` is moved
    /// aside, the new one renamed in, and the earlier one removed (put back if the
    /// rename fails).
    pub fn replace(self) -> Result<()> {
        let target = &self.target;
        if !target.exists() {
            let staging = self.staging.keep();
            return std::fs::rename(&staging, target)
                .map_err(|e| Error::io(FileOp::Write, target, e));
        }
        refuse_read_only(target)?;
        let parent = self.staging.path().parent().unwrap_or(Path::new("."));
        let aside = tempfile::Builder::new()
            .prefix(".lumiere-replaced-")
            .tempdir_in(parent)
            .map_err(|e| Error::io(FileOp::WriteIn, parent, without_temporary_name(e, parent)))?;
        // Renaming a directory over an empty one replaces it.
        std::fs::rename(target, aside.path()).map_err(|e| Error::io(FileOp::Write, target, e))?;
        if let Err(e) = std::fs::rename(self.staging.path(), target) {
            let _ = std::fs::rename(aside.path(), target);
            return Err(Error::io(FileOp::Write, target, e));
        }
        // The staging directory is now `target`: nothing is left to remove there.
        let _ = self.staging.keep();
        drop(aside);
        Ok(())
    }

    /// Where the file `name` is written until the run completes.
    pub fn path(&self, name: &str) -> PathBuf {
        self.staging.path().join(name)
    }

    /// Moves the run's files into the directory, first removing what an earlier
    /// run wrote there (the files `earlier` recognises); other files are left.
    pub fn publish(mut self, earlier: impl Fn(&str) -> bool) -> Result<()> {
        let names = |dir: &Path| -> Result<Vec<String>> {
            let entries = std::fs::read_dir(dir).map_err(|e| Error::io(FileOp::Read, dir, e))?;
            entries
                .map(|entry| {
                    let entry = entry.map_err(|e| Error::io(FileOp::Read, dir, e))?;
                    Ok(entry.file_name().to_string_lossy().into_owned())
                })
                .collect()
        };
        let made = names(self.staging.path())?;
        let stale: Vec<String> = names(&self.target)?
            .into_iter()
            .filter(|n| earlier(n) || made.contains(n))
            .collect();
        // A read-only file is never replaced: refuse before anything moves.
        for name in &stale {
            refuse_read_only(&self.target.join(name))?;
        }
        for name in &stale {
            let path = self.target.join(name);
            std::fs::remove_file(&path).map_err(|e| Error::io(FileOp::Write, &path, e))?;
        }
        for name in &made {
            let to = self.target.join(name);
            std::fs::rename(self.staging.path().join(name), &to)
                .map_err(|e| Error::io(FileOp::Write, &to, e))?;
        }
        self.made.kept();
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A run that fails (the staged directory dropped unpublished) removes the
    /// directory `create` made, if empty; one that was there, or holds a file, stays.
    #[test]
    fn a_failed_run_leaves_no_empty_directory_it_made() {
        let dir = tempfile::tempdir().unwrap();
        let made = dir.path().join("frames");
        drop(StagedDirectory::create(&made).unwrap());
        assert!(!made.exists());
        std::fs::create_dir(&made).unwrap();
        drop(StagedDirectory::create(&made).unwrap());
        assert!(made.exists(), "a directory that was there is kept");
        let other = dir.path().join("other");
        let staged = StagedDirectory::create(&other).unwrap();
        std::fs::write(other.join("mine.txt"), "keep").unwrap();
        drop(staged);
        assert!(other.join("mine.txt").exists());
        let published = dir.path().join("done");
        let staged = StagedDirectory::create(&published).unwrap();
        std::fs::write(staged.path("a.png"), "png").unwrap();
        staged.publish(|_| false).unwrap();
        assert!(published.join("a.png").exists());
        let leftovers: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.starts_with(".lumiere"))
            .collect();
        assert!(leftovers.is_empty(), "{leftovers:?}");
    }
}
