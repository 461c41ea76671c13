//! Textures and mappings from the scene file: `[textures.NAME]` loaded or generated,
//! `mapping` tables turned into two-part mappings, and per-vertex texture coordinates
//! computed from a material's mapping (the "projection function unknown" case, where
//! the scan-line pass interpolates them).

use super::file::{MappingFile, ProceduralKind, TextureFile};
use super::resources::Resources;
use super::validate::{colour, vec3};
use super::{ObjectFrame, Vertex};
use crate::error::ensure_valid;
use crate::error::{Error, Result};
use crate::texture::mapping::{Frame, Mapping, fix_seam};
use crate::texture::procedural::Procedural;
use crate::texture::{Texels, Texture};
use glam::{DVec2, DVec3, Vec3};
use std::path::Path;

/// Default texels per side of a procedural texture sampled into an image.
const DEFAULT_RESOLUTION: u32 = 256;

/// What the scene's textures may take of `render.max_memory_mb`, and have taken.
#[derive(Default)]
pub struct TextureBudget {
    /// Bytes the textures loaded take.
    pub used: u64,
    /// Bytes the geometry takes.
    pub geometry: u64,
    /// Bytes allowed.
    pub limit: u64,
}

impl TextureBudget {
    /// Takes what a `width` x `height` texture needs under `filter` (with `decoding`
    /// bytes a texel while an image is decoded), or refuses it naming `key = value`.
    fn take(
        &mut self,
        (key, value): (String, String),
        (width, height): (u32, u32),
        filter: crate::settings::Filter,
        decoding: u64,
    ) -> Result<()> {
        let kept = Texture::bytes_kept(width, height, filter);
        let transient = u64::from(width) * u64::from(height) * decoding;
        let needed = (self.used + self.geometry)
            .saturating_add(kept)
            .saturating_add(transient);
        if needed > self.limit {
            return Err(Error::OverBudget(Box::new(crate::error::OverBudget {
                key,
                value,
                what: format!(
                    "its {width}x{height} texels under the {} filter, with the scene's other textures",
                    filter.name()
                ),
                needed,
                budget: self.limit,
                budget_key: "render.max_memory_mb".into(),
                suggestion: "use a smaller image or resolution, or a filter without a pyramid or table (nearest, bilinear), or raise render.max_memory_mb".into(),
            })));
        }
        self.used += kept;
        Ok(())
    }
}

/// While an image is decoded it is held in its own format (up to 16-bit RGBA, 8 bytes
/// a texel) and as 8-bit RGB (3) beside the texels.
const DECODING_BYTES_PER_TEXEL: u64 = 11;

/// A texture checked and its memory taken from the budget, not yet decoded or
/// generated: a scene's textures are all counted before any is made.
pub struct Prepared {
    name: String,
    source: Source,
    wrap: crate::texture::Wrap,
    filter: crate::settings::Filter,
}

enum Source {
    Image { path: String, bytes: Vec<u8> },
    Procedural(Procedural, u32),
}

impl Prepared {
    /// The texture: its image decoded, or its pattern sampled.
    pub fn load(self) -> Result<Texture> {
        let (texels, procedural) = match self.source {
            Source::Image { path, bytes } => {
                let texels = Texels::decode(&bytes).map_err(|e| {
                    e.at_path(Path::new(&path))
                        .within(format!("textures.{}", self.name))
                })?;
                (texels, None)
            }
            Source::Procedural(p, n) => (Texels::generate(n, n, |uv| p.color(uv)), Some(p)),
        };
        Ok(Texture::new(
            &self.name,
            texels,
            procedural,
            self.wrap,
            self.filter,
        ))
    }
}

/// Checks `[textures.NAME]`, reads its image's header and takes its memory from
/// `budget`.
pub fn prepare(
    name: &str,
    t: &TextureFile,
    resources: &dyn Resources,
    budget: &mut TextureBudget,
) -> Result<Prepared> {
    let what = |key: &str| format!("textures.{name}.{key}");
    let procedural_keys = [
        ("cells", t.cells.is_some()),
        ("colors", t.colors.is_some()),
        ("line", t.line.is_some()),
        ("seed", t.seed.is_some()),
        ("resolution", t.resolution.is_some()),
    ];
    let source = match (&t.image, t.procedural) {
        (Some(_), Some(_)) => {
            return Err(Error::invalid(
                format!("textures.{name}"),
                format!("textures.{name}: give `image` or `procedural`, not both"),
            ));
        }
        (None, None) => {
            return Err(Error::invalid(
                format!("textures.{name}"),
                format!("textures.{name}: needs an `image` file or a `procedural` pattern"),
            ));
        }
        (Some(path), None) => {
            if let Some((key, _)) = procedural_keys.iter().find(|(_, given)| *given) {
                return Err(Error::invalid(
                    what(key),
                    format!("{}: applies to procedural textures only", what(key)),
                ));
            }
            let bytes = resources
                .read(Path::new(path))
                .map_err(|e| e.within(what("image")))?;
            let size = crate::texture::texels::image_size(&bytes).map_err(|e| {
                e.at_path(Path::new(path))
                    .within(format!("textures.{name}"))
            })?;
            budget.take(
                (what("image"), path.clone()),
                size,
                t.filter,
                DECODING_BYTES_PER_TEXEL,
            )?;
            Source::Image {
                path: path.clone(),
                bytes,
            }
        }
        (None, Some(kind)) => {
            let p = procedural(name, kind, t)?;
            let n = t.resolution.unwrap_or(DEFAULT_RESOLUTION);
            ensure_valid!(
                (1..=8192).contains(&n),
                what("resolution"),
                "{} must be between 1 and 8192, got {n}",
                what("resolution")
            );
            budget.take((what("resolution"), n.to_string()), (n, n), t.filter, 0)?;
            Source::Procedural(p, n)
        }
    };
    Ok(Prepared {
        name: name.to_string(),
        source,
        wrap: t.wrap,
        filter: t.filter,
    })
}

fn procedural(name: &str, kind: ProceduralKind, t: &TextureFile) -> Result<Procedural> {
    let what = |key: &str| format!("textures.{name}.{key}");
    let cells = t.cells.unwrap_or(8);
    ensure_valid!(
        (1..=65_536).contains(&cells),
        what("cells"),
        "{} must be between 1 and 65536, got {cells}",
        what("cells")
    );
    let colors = match t.colors {
        Some([a, b]) => [colour(&what("colors"), a)?, colour(&what("colors"), b)?],
        None => [Vec3::ONE, Vec3::ZERO],
    };
    for (key, given, applies) in [
        ("line", t.line.is_some(), kind == ProceduralKind::Grid),
        ("seed", t.seed.is_some(), kind == ProceduralKind::Noise),
    ] {
        ensure_valid!(
            !given || applies,
            what(key),
            "{} does not apply to {kind:?}",
            what(key)
        );
    }
    Ok(match kind {
        ProceduralKind::Checkerboard => Procedural::Checkerboard { cells, colors },
        ProceduralKind::Grid => {
            let line = t.line.unwrap_or(0.1);
            ensure_valid!(
                line > 0.0 && line < 1.0,
                what("line"),
                "{} must be between 0 and 1 (cell units)",
                what("line")
            );
            Procedural::Grid {
                cells,
                line,
                colors,
            }
        }
        ProceduralKind::Noise => Procedural::Noise {
            cells,
            seed: t.seed.unwrap_or(0),
            colors,
        },
    })
}

pub fn mapping(what: &str, m: &MappingFile) -> Result<Mapping> {
    let frame = Frame::new(
        vec3(&format!("{what}.centre"), m.centre)?,
        vec3(&format!("{what}.axis"), m.axis)?,
        vec3(&format!("{what}.reference"), m.reference)?,
    )
    .map_err(|e| e.within(what))?;
    let mapping = Mapping {
        surface: m.surface,
        projector: m.projector,
        frame,
        size: DVec2::from(m.size),
        height: m.height,
        radius: m.radius,
        repeat: DVec2::from(m.repeat),
    };
    mapping.check().map_err(|e| e.within(what))?;
    Ok(mapping)
}

/// Sets the texture coordinates of a face (in modelling coordinates) from `mapping`:
/// the mapping at each vertex, the seam and poles fixed so interpolation across the
/// face stays continuous. `eye` is the eye in modelling coordinates (for the
/// reflected-ray projector).
pub fn map_vertices(mapping: &Mapping, face: &mut [Vertex], frame: &ObjectFrame, eye: DVec3) {
    let mut uvs: Vec<DVec2> = face
        .iter()
        .map(|v| {
            let to_eye = (eye - v.position).normalize_or_zero();
            mapping.uv(v.position, v.normal, frame.centroid, to_eye)
        })
        .collect();
    if mapping.wraps_in_u() {
        let on_axis: Vec<bool> = face.iter().map(|v| mapping.on_axis(v.position)).collect();
        fix_seam(&mut uvs, &on_axis, mapping.repeat.x);
    }
    for (v, uv) in face.iter_mut().zip(uvs) {
        v.uv = uv;
    }
}
