//! Where a scene's files come from: a directory on disk (a user's scene file) or the
//! catalogue embedded in the binary. Paths in a scene are relative to the scene.

use crate::error::{Error, FileOp, Result};
use crate::image_io::read_file;
use include_dir::Dir;
use std::collections::HashMap;
use std::path::{Component, Path, PathBuf};

pub trait Resources: Sync {
    /// The bytes of the file at `path`, relative to the scene.
    fn read(&self, path: &Path) -> Result<Vec<u8>>;
}

/// Files on disk, relative to a base directory.
pub struct Directory(pub PathBuf);

impl Resources for Directory {
    fn read(&self, path: &Path) -> Result<Vec<u8>> {
        let full = self.0.join(path);
        read_file(&full, FileOp::Read)
    }
}

/// Files held in memory, by their path relative to the scene: a scene a program
/// builds, tests, fuzzing.
pub struct InMemory(pub HashMap<String, Vec<u8>>);

impl Resources for InMemory {
    fn read(&self, path: &Path) -> Result<Vec<u8>> {
        self.0
            .get(path.to_str().unwrap_or(""))
            .cloned()
            .ok_or_else(|| Error::Scene(format!("no file {}", path.display())))
    }
}

/// Files embedded in the binary at build time.
pub struct Embedded(pub &'static Dir<'static>);

impl Resources for Embedded {
    fn read(&self, path: &Path) -> Result<Vec<u8>> {
        let normal = normalise(path);
        self.0
            .get_file(&normal)
            .map(|f| f.contents().to_vec())
            .ok_or_else(|| {
                Error::Catalogue(format!("the catalogue has no file {}", normal.display()))
            })
    }
}

/// Resolves `.` and `..` without touching the file system (embedded paths have no
/// file system to ask).
pub fn normalise(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            Component::ParentDir => {
                out.pop();
            }
            Component::CurDir => {}
            other @ (Component::Prefix(_) | Component::RootDir | Component::Normal(_)) => {
                out.push(other)
            }
        }
    }
    out
}

/// The first of several sources that has the file (a user's scene that extends a
/// catalogue entry reads its own files and the catalogue's).
pub struct Layered(pub Vec<Box<dyn Resources>>);

impl Resources for Layered {
    fn read(&self, path: &Path) -> Result<Vec<u8>> {
        let mut first_error = None;
        for source in &self.0 {
            match source.read(path) {
                Ok(bytes) => return Ok(bytes),
                Err(e) => {
                    first_error.get_or_insert(e);
                }
            }
        }
        Err(first_error.unwrap_or_else(|| {
            Error::io(
                FileOp::Read,
                path,
                std::io::Error::new(std::io::ErrorKind::NotFound, "no source for it"),
            )
        }))
    }
}
