//! The library's errors: one enum a caller can match, whose messages (each with its
//! `source` chain, joined by ": ") make the one line the command line prints.
//!
//! Where a problem sits inside a larger thing (a scene file, one of its objects or
//! lights), the error is wrapped (`InScene`, `In`) and the wrapper's message names
//! the place: "scene s.toml: lights[1] (`bulb`): radius must be a positive number,
//! got 0". `Error::root` looks through the wrappers.

use crate::settings::ShadowMethod;
use std::fmt;
use std::path::{Path, PathBuf};

/// A shadow method asked for a light it cannot handle.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Unsupported {
    /// The method asked.
    pub method: ShadowMethod,
    /// The method's name, and what it handles ("a hard-shadow method for point and
    /// spot lights"), as the method declares them.
    pub name: &'static str,
    /// What the method handles, as it declares it.
    pub handles: &'static str,
    /// The light refused, as the scene labels it (`lights[1] (`bulb`)`).
    pub light: String,
}

impl std::fmt::Display for Unsupported {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "shadow method `{}` cannot shadow {}: it is {}; use `ray-cast` (it samples extended lights) or `none`",
            self.name, self.light, self.handles
        )
    }
}

impl std::error::Error for Unsupported {}

/// A setting (`key`, set to `value`) that would need `needed` bytes for `what`,
/// more than the `budget` that `budget_key` allows.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "{key} = {value} would need about {} for {what}, more than the {} that {budget_key} allows; {suggestion}",
    bytes(*needed),
    bytes(*budget)
)]
pub struct OverBudget {
    /// The scene key that asks for too much (`shadows.map_resolution`).
    pub key: String,
    /// Its value.
    pub value: String,
    /// What the memory would hold.
    pub what: String,
    /// The bytes needed.
    pub needed: u64,
    /// The bytes allowed.
    pub budget: u64,
    /// The key that sets the budget (`shadows.max_memory_mb`).
    pub budget_key: String,
    /// What to do instead.
    pub suggestion: String,
}

/// What the library reports.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be read or written.
    #[error("cannot {op} {}", path.display())]
    Io {
        /// What was being done.
        op: FileOp,
        /// The file.
        path: PathBuf,
        #[source]
        /// What the system said.
        source: std::io::Error,
    },

    /// TOML that does not parse: `file` is the scene file or catalogue entry,
    /// `position` its (line, column), from 1.
    #[error("{file}{}: {message}", line_column(position))]
    Parse {
        /// The scene file or catalogue entry.
        file: String,
        /// Line and column, from 1.
        position: Option<(usize, usize)>,
        /// What the parser said.
        message: String,
    },

    /// A `--set key=value` override that cannot be applied.
    #[error("--set {assignment}: {message}")]
    Override {
        /// The assignment as given (`camera.width=abc`).
        assignment: String,
        /// Why it cannot be applied.
        message: String,
    },

    /// A scene value that cannot be used (unknown, missing, out of range, not
    /// applicable). `key` is its path in the scene file (`radiosity.tolerance`),
    /// relative to the object, light or mapping it is in when the error is wrapped in
    /// `In` (`radius` in `lights[1]`); `message` is the whole line, naming the key
    /// and, where there is one, the value.
    #[error("{message}")]
    Invalid {
        /// The key's path.
        key: String,
        /// The whole line.
        message: String,
    },

    /// A scene that cannot be used in a way no single key of the scene file names
    /// (an OBJ model's materials, the size of the sample grid).
    #[error("{0}")]
    Scene(String),

    /// A problem with the scene `spec` (a scene file or catalogue id).
    #[error("scene {spec}")]
    InScene {
        /// The scene file or catalogue id.
        spec: String,
        #[source]
        /// The problem.
        source: Box<Error>,
    },

    /// A problem inside `place` (`objects[0]`, `lights[1] (`bulb`)`,
    /// `textures.wood`, `materials.grey.mapping`, `model.obj: its MTL file`).
    #[error("{place}")]
    In {
        /// Where it is.
        place: String,
        #[source]
        /// The problem.
        source: Box<Error>,
    },

    /// An OBJ, MTL or glTF model that cannot be read as one.
    #[error("{}: {message}", path.display())]
    Model {
        /// The OBJ, MTL or glTF file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },

    /// Image bytes that cannot be decoded, or an image that cannot be encoded; `path`
    /// is the file when one is known.
    #[error("{}{message}", path_prefix(path))]
    Image {
        /// The file, when one is known.
        path: Option<PathBuf>,
        /// What is wrong.
        message: String,
    },

    /// An output path whose extension names no image format lumiere writes.
    #[error(
        "{}: unknown image format (use .png for sRGB, .pfm or .exr for linear radiance)",
        path.display()
    )]
    Format {
        /// The path.
        path: PathBuf,
    },

    /// Two images compared are not the same size.
    #[error(
        "the images differ in size: {}x{} and {}x{}",
        first.0,
        first.1,
        second.0,
        second.1
    )]
    SizeMismatch {
        /// The first image's width and height.
        first: (u32, u32),
        /// The second image's width and height.
        second: (u32, u32),
    },

    /// No catalogue entry has this id; `suggestion` is the nearest one, if any is
    /// near.
    #[error(
        "no catalogue entry `{id}`{} (`lumiere list` shows them all)",
        did_you_mean(suggestion)
    )]
    UnknownEntry {
        /// The id asked for.
        id: String,
        /// The nearest id, if one is near.
        suggestion: Option<String>,
    },

    /// The embedded catalogue is broken (an entry without its `[algorithm]` table,
    /// entries extending each other in a cycle) or lacks a file a scene names.
    #[error("{0}")]
    Catalogue(String),

    /// A shadow method asked for a light it cannot handle.
    #[error(transparent)]
    Unsupported(#[from] Unsupported),

    /// The radiosity solver refuses the scene (a reflectance of 1 or more, nothing
    /// emitting, settings that do not go together).
    #[error("{0}")]
    Radiosity(String),

    /// Gathering would store more form factors (`needed` bytes, for `elements` ×
    /// `patches` of them) than the `budget` allows.
    #[error(
        "gathering would store {} form factors ({:.1} GiB) for {} elements and {} patches, more than the {:.1} GiB that radiosity.max_memory_mb allows; use the shooting solver (O(n) memory) or coarser patches and elements (radiosity.patch_size, radiosity.element_size), or raise radiosity.max_memory_mb",
        count((*elements as u64).saturating_mul(*patches as u64)),
        gib(*needed),
        count(*elements as u64),
        count(*patches as u64),
        gib(*budget)
    )]
    Memory {
        /// Elements (rows).
        elements: usize,
        /// Patches (columns).
        patches: usize,
        /// Bytes needed.
        needed: u64,
        /// Bytes allowed.
        budget: u64,
    },

    /// A setting that would need more memory than its budget allows.
    #[error(transparent)]
    OverBudget(Box<OverBudget>),

    /// A frame stopped by its renderer's stop switch (`Renderer::set_stop`) before
    /// it was done.
    #[error("the render was stopped before it was done")]
    Stopped,

    /// A frame was asked for a buffer it does not make; `known` are those it does.
    #[error("this scene's frame has no buffer `{name}`; it has: {}", known.join(", "))]
    UnknownBuffer {
        /// The buffer asked for.
        name: String,
        /// The buffers the frame makes.
        known: Vec<String>,
    },

    /// A renderer was asked to change light `index`, which it cannot.
    #[error("{message}")]
    Light {
        /// The light's index in the scene.
        index: usize,
        /// Why.
        message: String,
    },
}

/// Returns `Error::Invalid` for `key`, with the formatted message, unless `cond`
/// holds.
macro_rules! ensure_valid {
    ($cond:expr, $key:expr, $($message:tt)+) => {
        let holds: bool = $cond;
        if !holds {
            return Err($crate::error::Error::invalid($key, format!($($message)+)));
        }
    };
}
pub(crate) use ensure_valid;

/// `Result` with the library's `Error`.
pub type Result<T> = std::result::Result<T, Error>;

/// What was being done with a file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileOp {
    /// Reading a scene file.
    ReadScene,
    /// Reading any other file (a model, a texture, an image).
    Read,
    /// Writing a file.
    Write,
    /// Creating a file in a directory (`path` is the directory).
    WriteIn,
}

impl fmt::Display for FileOp {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            FileOp::ReadScene => "read scene",
            FileOp::Read => "read",
            FileOp::Write => "write",
            FileOp::WriteIn => "write in",
        })
    }
}

impl Error {
    /// The error inside the `InScene` and `In` wrappers.
    // Errors pass through unchanged: `Error` is no method or kind a new variant of
    // which would need placing.
    #[allow(clippy::wildcard_enum_match_arm)]
    pub fn root(&self) -> &Error {
        match self {
            Error::InScene { source, .. } | Error::In { source, .. } => source.root(),
            other => other,
        }
    }

    pub(crate) fn io(op: FileOp, path: &Path, source: std::io::Error) -> Error {
        Error::Io {
            op,
            path: path.to_path_buf(),
            source,
        }
    }

    pub(crate) fn invalid(key: impl Into<String>, message: impl Into<String>) -> Error {
        Error::Invalid {
            key: key.into(),
            message: message.into(),
        }
    }

    pub(crate) fn image(message: impl Into<String>) -> Error {
        Error::Image {
            path: None,
            message: message.into(),
        }
    }

    /// This error inside `place`.
    pub(crate) fn within(self, place: impl Into<String>) -> Error {
        Error::In {
            place: place.into(),
            source: Box::new(self),
        }
    }

    /// An image error without a path given `path`; any other error is unchanged.
    #[allow(clippy::wildcard_enum_match_arm)]
    pub(crate) fn at_path(self, path: &Path) -> Error {
        match self {
            Error::Image {
                path: None,
                message,
            } => Error::Image {
                path: Some(path.to_path_buf()),
                message,
            },
            other => other,
        }
    }
}

/// The `image` crate's errors carry their cause both in their message and as their
/// source: the message alone says it once.
impl From<image::ImageError> for Error {
    fn from(e: image::ImageError) -> Error {
        Error::image(e.to_string())
    }
}

fn line_column(position: &Option<(usize, usize)>) -> String {
    match position {
        Some((line, column)) => format!(":{line}:{column}"),
        None => String::new(),
    }
}

fn path_prefix(path: &Option<PathBuf>) -> String {
    match path {
        Some(p) => format!("{}: ", p.display()),
        None => String::new(),
    }
}

fn did_you_mean(suggestion: &Option<String>) -> String {
    match suggestion {
        Some(s) => format!("; did you mean `{s}`?"),
        None => String::new(),
    }
}

/// A byte count for people: MiB below a GiB, GiB above.
fn bytes(n: u64) -> String {
    if n >= 1 << 30 {
        format!("{:.1} GiB", gib(n))
    } else {
        format!("{:.1} MiB", n as f64 / (1u64 << 20) as f64)
    }
}

/// A count for a message: one that saturated is no count any machine holds, and is
/// said so rather than printed as 2^64 - 1.
pub(crate) fn count(n: u64) -> String {
    match n {
        u64::MAX => "more than 1.8e19".to_string(),
        n => n.to_string(),
    }
}

fn gib(bytes: u64) -> f64 {
    bytes as f64 / (1u64 << 30) as f64
}

/// `text` on one line, any word of it longer than a line (a megabyte name, a
/// mistyped key of thousands of characters) cut to its ends and its length.
pub fn one_line(text: &str) -> String {
    const LONGEST: usize = 120;
    text.split('\n')
        .flat_map(|line| line.split(' '))
        .map(|word| {
            let chars = word.chars().count();
            if chars <= LONGEST {
                return word.to_string();
            }
            let head: String = word.chars().take(60).collect();
            let tail: String = word.chars().skip(chars - 20).collect();
            format!("{head}…[{} characters]…{tail}", chars - 80)
        })
        .collect::<Vec<_>>()
        .join(" ")
}

impl Error {
    /// The error and its causes, joined by ": " on one line: what the command
    /// line prints after `error: `.
    pub fn line(&self) -> String {
        let mut text = self.to_string();
        let mut cause = std::error::Error::source(self);
        while let Some(c) = cause {
            text.push_str(": ");
            text.push_str(&c.to_string());
            cause = c.source();
        }
        one_line(&text)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{image_io, load_scene, render};

    /// The message and its causes joined by ": ", as the command line prints them.
    fn line(e: &Error) -> String {
        let mut text = e.to_string();
        let mut cause = std::error::Error::source(e);
        while let Some(c) = cause {
            text += &format!(": {c}");
            cause = c.source();
        }
        text
    }

    fn sets(extra: &[&str]) -> Vec<String> {
        ["camera.width=8", "camera.height=8"]
            .iter()
            .chain(extra)
            .map(|s| s.to_string())
            .collect()
    }

    #[test]
    fn a_missing_scene_file_is_an_io_error_naming_it() {
        let e = load_scene("no-such-scene.toml", &[]).err().unwrap();
        match &e {
            Error::Io {
                op: FileOp::ReadScene,
                path,
                source,
            } => {
                assert_eq!(path, Path::new("no-such-scene.toml"));
                assert_eq!(source.kind(), std::io::ErrorKind::NotFound);
            }
            other => panic!("not Io: {other:?}"),
        }
        assert!(
            line(&e).starts_with("cannot read scene no-such-scene.toml: "),
            "{}",
            line(&e)
        );
        let e = image_io::load(Path::new("no-such-image.png"))
            .err()
            .unwrap();
        assert!(
            matches!(&e, Error::Io { op: FileOp::Read, path, .. } if path == Path::new("no-such-image.png"))
        );
    }

    #[test]
    fn a_hard_shadow_method_refuses_a_polygon_light() {
        let scene = load_scene("cornell-box", &sets(&["shadows.method=shadow-map"])).unwrap();
        match render(&scene).err().unwrap() {
            Error::Unsupported(u) => {
                assert_eq!(u.method, ShadowMethod::ShadowMap);
                assert!(u.light.contains("polygon"), "{}", u.light);
            }
            other => panic!("not Unsupported: {other:?}"),
        }
    }

    /// A bad value inside a scene: the wrappers name the scene and the light, the
    /// root names the key, and the line reads as the context chain did.
    #[test]
    fn a_bad_value_names_the_scene_the_place_and_the_key() {
        let e = load_scene("cornell-box", &sets(&["radiosity.tolerance=2.0"]))
            .err()
            .unwrap();
        assert!(matches!(&e, Error::InScene { spec, .. } if spec == "cornell-box"));
        assert!(
            matches!(e.root(), Error::Invalid { key, .. } if key == "radiosity.tolerance"),
            "{e:?}"
        );
        assert_eq!(
            line(&e),
            "scene cornell-box: radiosity.tolerance must be between 0 and 1, got 2"
        );

        let bulb = "lights=[{type = 'sphere', name = 'bulb', centre = [0.0, 0.0, 0.0], \
                    radius = 0.0, radiance = [1.0, 1.0, 1.0]}]";
        let e = load_scene("cornell-box-point", &sets(&[bulb]))
            .err()
            .unwrap();
        assert_eq!(
            line(&e),
            "scene cornell-box-point: lights[0] (`bulb`): radius must be a positive number, got 0"
        );
        let Error::InScene { source, .. } = &e else {
            panic!("not InScene: {e:?}")
        };
        assert!(matches!(&**source, Error::In { place, .. } if place == "lights[0] (`bulb`)"));
        assert!(matches!(e.root(), Error::Invalid { key, .. } if key == "radius"));
    }

    #[test]
    fn an_unknown_entry_suggests_the_nearest() {
        match load_scene("cornel-box", &[]).err().unwrap() {
            Error::UnknownEntry { id, suggestion } => {
                assert_eq!(id, "cornel-box");
                assert_eq!(suggestion.as_deref(), Some("cornell-box"));
            }
            other => panic!("not UnknownEntry: {other:?}"),
        }
    }

    /// The image crate's errors carry their cause twice (message and source): it is
    /// said once.
    #[test]
    fn an_undecodable_image_says_its_cause_once() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("broken.exr");
        std::fs::write(&path, "not an image").unwrap();
        let e = image_io::load(&path).err().unwrap();
        assert!(matches!(&e, Error::Image { path: Some(p), .. } if *p == path));
        let text = line(&e);
        let cause = text.rsplit(": ").next().unwrap();
        assert_eq!(text.matches(cause).count(), 1, "{text}");
    }
}
