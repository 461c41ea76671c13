//! Images: linear radiance in memory; PNG (sRGB after exposure), PFM and OpenEXR
//! (linear, 32-bit float) on disk, chosen by extension; files are written whole or
//! not at all.

mod animation;
mod buffer;
mod compare;
mod exr;
mod pfm;
mod png;
mod staged_directory;

pub use animation::Animation;
pub use buffer::{Buffer, BufferData, NO_ID};
pub use compare::{
    Candidate, Comparison, Flip, FlipRange, FuzzyMatch, Moments, MomentsSum, StatisticalTest,
    ToleranceCheck, apply_mask, compare, default_pixels_per_degree, difference_image, edge_mask,
    flip, fuzzy_match, pixels_per_degree, statistical_test, strip, tolerance_check,
};
pub use staged_directory::StagedDirectory;

use crate::error::{Error, FileOp, Result};
use glam::Vec3;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Linear RGB radiance, row-major, row 0 at the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Linear radiance per pixel, `width × height` of them.
    pub pixels: Vec<Vec3>,
}

impl Image {
    /// The pixels as a PNG shows them: 8-bit sRGB after `exposure`, clamped, three
    /// bytes a pixel, row-major.
    pub fn to_srgb8(&self, exposure: f32) -> Vec<u8> {
        self.pixels
            .iter()
            .flat_map(|p| to_srgb8(*p, exposure))
            .collect()
    }

    /// The mean of each `factor × factor` block: the box filter over each pixel's
    /// square, from a grid sampled `factor` times finer.
    pub fn downsample(self, factor: u32) -> Image {
        if factor == 1 {
            return self;
        }
        let (w, h) = (self.width / factor, self.height / factor);
        let weight = 1.0 / (factor * factor) as f32;
        let pixels = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| {
                let mut sum = Vec3::ZERO;
                for sy in 0..factor {
                    let row = ((y * factor + sy) * self.width) as usize;
                    for sx in 0..factor {
                        sum += self.pixels[row + (x * factor + sx) as usize];
                    }
                }
                sum * weight
            })
            .collect();
        Image {
            width: w,
            height: h,
            pixels,
        }
    }
}

/// The file formats, by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// PNG, 8-bit sRGB after an exposure.
    Png,
    /// Portable float map, linear 32-bit float.
    Pfm,
    /// OpenEXR, linear 32-bit float.
    Exr,
}

impl Format {
    /// The file extension it is written with.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Png => "png",
            Format::Pfm => "pfm",
            Format::Exr => "exr",
        }
    }

    /// The format a path's extension names (`.png`, `.pfm`, `.exr`).
    pub fn of(path: &Path) -> Result<Format> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("png") => Ok(Format::Png),
            Some("pfm") => Ok(Format::Pfm),
            Some("exr") => Ok(Format::Exr),
            _ => Err(Error::Format {
                path: path.to_path_buf(),
            }),
        }
    }
}

/// The bytes of `image` in `format` (exposure applies to PNG only).
pub fn encode(image: &Image, format: Format, exposure: f32) -> Result<Vec<u8>> {
    match format {
        Format::Png => png::encode(image, exposure),
        Format::Pfm => Ok(pfm::encode(image)),
        Format::Exr => exr::encode(image),
    }
}

/// Writes `image` to `path`: to a temporary file beside it, then renamed, so a
/// failure never leaves a half-written file.
pub fn save(image: &Image, path: &Path, exposure: f32) -> Result<()> {
    let format = Format::of(path)?;
    write_atomically_with(path, |out| match format {
        Format::Png => png::write(image, exposure, out),
        Format::Pfm => pfm::write(image, out).map_err(|e| Error::io(FileOp::Write, path, e)),
        Format::Exr => exr::write(image, out),
    })
}

/// Writes `bytes` to `path` atomically (see `save`).
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<()> {
    write_atomically_with(path, |out| {
        out.write_all(bytes)
            .map_err(|e| Error::io(FileOp::Write, path, e))
    })
}

/// Refuses to replace `path` if it is a read-only file: renaming over it, or
/// removing it, would not ask.
pub(crate) fn refuse_read_only(path: &Path) -> Result<()> {
    if std::fs::metadata(path).is_ok_and(|m| m.permissions().readonly()) {
        return Err(Error::io(
            FileOp::Write,
            path,
            std::io::Error::new(
                std::io::ErrorKind::PermissionDenied,
                "the file is read-only: it is left as it is",
            ),
        ));
    }
    Ok(())
}

/// Temporary files and staging directories being written: what an interrupted
/// process must remove so that nothing half-written is left (`remove_unfinished`).
static UNFINISHED: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

/// Keeps `path` on the list of unfinished files while it lives.
pub(crate) struct Unfinished(PathBuf);

impl Unfinished {
    pub(crate) fn track(path: &Path) -> Unfinished {
        let mut list = UNFINISHED.lock().unwrap_or_else(|e| e.into_inner());
        list.push(path.to_path_buf());
        Unfinished(path.to_path_buf())
    }
}

impl Drop for Unfinished {
    fn drop(&mut self) {
        let mut list = UNFINISHED.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(k) = list.iter().position(|p| *p == self.0) {
            list.swap_remove(k);
        }
    }
}

/// Removes every temporary file and staging directory still being written: for a
/// process about to end on an interruption (Ctrl-C, SIGTERM). Outputs appear whole
/// under their names or not at all; this leaves no hidden remains either.
pub fn remove_unfinished() {
    let list = UNFINISHED.lock().unwrap_or_else(|e| e.into_inner());
    for path in list.iter() {
        if path.is_dir() {
            let _ = std::fs::remove_dir_all(path);
        } else {
            let _ = std::fs::remove_file(path);
        }
    }
}

/// Streams `write`'s output into a temporary file beside `path`, renamed to `path`
/// once complete.
fn write_atomically_with(
    path: &Path,
    write: impl FnOnce(&mut std::io::BufWriter<&mut std::fs::File>) -> Result<()>,
) -> Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    // Renaming over a read-only file would replace it silently.
    refuse_read_only(path)?;
    let mut file = tempfile::NamedTempFile::new_in(dir)
        .map_err(|e| Error::io(FileOp::WriteIn, dir, without_temporary_name(e, dir)))?;
    let _unfinished = Unfinished::track(file.path());
    let cannot_write = |e| Error::io(FileOp::Write, path, e);
    {
        let mut out = std::io::BufWriter::new(file.as_file_mut());
        write(&mut out).map_err(|e| e.at_path(path))?;
        out.flush().map_err(cannot_write)?;
    }
    // A temporary file is private; the image is an ordinary file.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        file.as_file()
            .set_permissions(std::fs::Permissions::from_mode(0o644))
            .map_err(cannot_write)?;
    }
    file.persist(path).map_err(|e| cannot_write(e.error))?;
    Ok(())
}

/// Why a file cannot be made in `dir`, without the name of the temporary file that
/// tempfile adds to its error (a name the user never chose and cannot act on).
fn without_temporary_name(e: std::io::Error, dir: &Path) -> std::io::Error {
    match std::fs::metadata(dir) {
        Err(missing) => missing,
        Ok(m) if !m.is_dir() => std::io::ErrorKind::NotADirectory.into(),
        Ok(_) => e.kind().into(),
    }
}

/// The bytes of the file at `path`, refused unless it is a regular file: a device
/// (`/dev/zero`) would be read without end and a FIFO would wait for a writer that
/// may never come.
pub fn read_file(path: &Path, op: FileOp) -> Result<Vec<u8>> {
    let metadata = std::fs::metadata(path).map_err(|e| Error::io(op, path, e))?;
    if !metadata.is_file() {
        let what = if metadata.is_dir() {
            "it is a directory"
        } else {
            "not a regular file (a device, a FIFO or a socket)"
        };
        return Err(Error::io(op, path, std::io::Error::other(what)));
    }
    std::fs::read(path).map_err(|e| Error::io(op, path, e))
}

/// Reads a PNG (decoded from sRGB to linear), a PFM or an OpenEXR file.
pub fn load(path: &Path) -> Result<Image> {
    let bytes = read_file(path, FileOp::Read)?;
    decode(&bytes, Format::of(path)?).map_err(|e| e.at_path(path))
}

/// Decodes an image file's bytes in `format`.
pub fn decode(bytes: &[u8], format: Format) -> Result<Image> {
    match format {
        Format::Png => png::decode(bytes),
        Format::Pfm => pfm::decode(bytes),
        Format::Exr => exr::decode(bytes),
    }
}

/// The width and height an image file's header declares, read without decoding
/// (nothing is allocated for its pixels).
pub fn dimensions(bytes: &[u8], format: Format) -> Result<(u32, u32)> {
    match format {
        Format::Png => {
            // The signature, then IHDR: width and height big-endian at 16 and 20.
            if bytes.len() < 24 || &bytes[..8] != b"\x89PNG\r\n\x1a\n" || &bytes[12..16] != b"IHDR"
            {
                return Err(Error::image("not a PNG file"));
            }
            let word =
                |at: usize| u32::from_be_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
            Ok((word(16), word(20)))
        }
        Format::Pfm => pfm::header(bytes).map(|h| (h.width, h.height)),
        Format::Exr => exr::dimensions(bytes),
    }
}

/// Refuses an image that is to be read as radiance (an environment map) if a
/// texel is NaN, infinite or negative: it would turn every sum it enters, a
/// filtered texel, a reflection, into the same. Names the count and the first.
pub fn refuse_non_radiance(image: &Image) -> Result<()> {
    let bad = |p: &Vec3| !p.is_finite() || p.min_element() < 0.0;
    let Some(first) = image.pixels.iter().position(bad) else {
        return Ok(());
    };
    let count = image.pixels.iter().filter(|p| bad(p)).count();
    let width = image.width as usize;
    let p = image.pixels[first];
    Err(Error::image(format!(
        "{count} of its texels are not radiance (finite, at least 0): the first, at x = {}, y = {}, is ({}, {}, {})",
        first % width,
        first / width,
        p.x,
        p.y,
        p.z
    )))
}

/// Decodes PNG bytes (sRGB to linear).
pub fn load_png_bytes(bytes: &[u8]) -> Result<Image> {
    png::decode(bytes)
}

/// sRGB transfer function of a linear value in [0, 1].
pub fn srgb_encode(linear: f32) -> f32 {
    if linear <= 0.003_130_8 {
        12.92 * linear
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    }
}

/// The linear value of an sRGB-encoded value in [0, 1].
pub fn srgb_decode(encoded: f32) -> f32 {
    if encoded <= 0.040_45 {
        encoded / 12.92
    } else {
        ((encoded + 0.055) / 1.055).powf(2.4)
    }
}

/// 8-bit sRGB of a linear radiance after exposure (clamped to [0, 1]).
pub fn to_srgb8(radiance: Vec3, exposure: f32) -> [u8; 3] {
    let q = |c: f32| (srgb_encode((c * exposure).clamp(0.0, 1.0)) * 255.0).round() as u8;
    [q(radiance.x), q(radiance.y), q(radiance.z)]
}
