//! Environment maps from the scene file: `[environments.NAME]` loaded from one image
//! or six faces, baked from a procedural environment, or left for the renderer to
//! capture from a point of the scene.

use super::file::EnvironmentFile;
use super::resources::Resources;
use super::validate::vec3;
use super::{Capture, Environment, EnvironmentSource};
use crate::error::ensure_valid;
use crate::error::{Error, Result};
use crate::image_io::{self, Format};
use crate::settings::Filter;
use crate::texture::Texels;
use crate::texture::environment::{EnvironmentMap, FILTERS, Layout};
use crate::texture::texels::MAX_TEXTURE_SIDE;
use std::path::Path;
use std::sync::Arc;

/// Default side (in texels) of a generated or captured map.
const DEFAULT_RESOLUTION: u32 = 256;
/// The largest generated or captured map side: six 4096² faces are 1.2 GB of texels.
const MAX_RESOLUTION: u32 = 4096;

/// The environment `name`, and the object names its capture hides (resolved by the
/// caller once the objects exist).
pub fn load(
    name: &str,
    e: &EnvironmentFile,
    resources: &dyn Resources,
) -> Result<(Environment, Vec<String>)> {
    let what = |key: &str| format!("environments.{name}.{key}");
    ensure_valid!(
        matches!(
            e.filter,
            Filter::Nearest | Filter::Bilinear | Filter::MipNearest | Filter::Trilinear
        ),
        what("filter"),
        "{} must be {FILTERS} (an environment has no summed-area table)",
        what("filter")
    );
    let given: Vec<&str> = [
        ("image", e.image.is_some()),
        ("faces", e.faces.is_some()),
        ("procedural", e.procedural.is_some()),
        ("capture", e.capture.is_some()),
    ]
    .iter()
    .filter(|(_, g)| *g)
    .map(|(k, _)| *k)
    .collect();
    ensure_valid!(
        given.len() == 1,
        format!("environments.{name}"),
        "environments.{name}: give one of `image`, `faces`, `procedural` or `capture`{}",
        if given.is_empty() {
            String::new()
        } else {
            format!(", not {}", given.join(" and "))
        }
    );
    ensure_valid!(
        e.hide.is_empty() || e.capture.is_some(),
        what("hide"),
        "{} applies to a capture only",
        what("hide")
    );
    let generated = e.procedural.is_some() || e.capture.is_some();
    ensure_valid!(
        e.resolution.is_none() || generated,
        what("resolution"),
        "{} applies to procedural and captured environments only (an image has its own)",
        what("resolution")
    );
    let resolution = e.resolution.unwrap_or(DEFAULT_RESOLUTION);
    ensure_valid!(
        (1..=MAX_RESOLUTION).contains(&resolution),
        what("resolution"),
        "{} must be between 1 and {MAX_RESOLUTION}, got {resolution}",
        what("resolution")
    );
    let source = if let Some(at) = e.capture {
        ensure_valid!(
            e.layout.is_none_or(|l| l == Layout::Cube),
            what("layout"),
            "{}: a capture renders a cube map (convert it with `lumiere envmap`)",
            what("layout")
        );
        EnvironmentSource::Capture(Capture {
            at: vec3(&what("capture"), at)?,
            resolution,
            hide: Vec::new(),
            filter: e.filter,
        })
    } else if let Some(procedural) = e.procedural {
        let layout = e.layout.unwrap_or(Layout::Cube);
        EnvironmentSource::Map(Arc::new(EnvironmentMap::generate(
            layout,
            resolution,
            e.filter,
            |d| procedural.radiance(d),
        )))
    } else if let Some(faces) = &e.faces {
        ensure_valid!(
            e.layout.is_none_or(|l| l == Layout::Cube),
            what("layout"),
            "{}: six faces make a cube map",
            what("layout")
        );
        let paths = [
            &faces.px, &faces.nx, &faces.py, &faces.ny, &faces.pz, &faces.nz,
        ];
        let keys = ["px", "nx", "py", "ny", "pz", "nz"];
        let mut texels = Vec::with_capacity(6);
        for (key, path) in keys.iter().zip(paths) {
            let key = format!("faces.{key}");
            let t = read_image(path, &what(&key), resources)?;
            ensure_valid!(
                t.width == t.height,
                what(&key),
                "{}: a cube face must be square, {path} is {}x{}",
                what(&key),
                t.width,
                t.height
            );
            if let Some(first) = texels.first() {
                let first: &Texels = first;
                ensure_valid!(
                    t.width == first.width,
                    what(&key),
                    "{}: the faces must have one size, {path} is {}x{} and faces.px is {}x{}",
                    what(&key),
                    t.width,
                    t.height,
                    first.width,
                    first.height
                );
            }
            texels.push(t);
        }
        EnvironmentSource::Map(Arc::new(EnvironmentMap::cube(texels, e.filter)))
    } else {
        let path = e.image.as_ref().expect("one source is given");
        let Some(layout) = e.layout else {
            return Err(Error::invalid(
                what("layout"),
                format!(
                    "{}: say how the image is laid out: \"lat-long\", \"sphere\" or \"cube\" (a horizontal cross)",
                    what("layout")
                ),
            ));
        };
        let t = read_image(path, &what("image"), resources)?;
        let map = EnvironmentMap::from_image(layout, t, e.filter).map_err(|m| {
            Error::invalid(what("image"), format!("{}: {path}: {m}", what("image")))
        })?;
        EnvironmentSource::Map(Arc::new(map))
    };
    Ok((
        Environment {
            name: name.to_string(),
            source,
            procedural: e.procedural.is_some(),
        },
        e.hide.clone(),
    ))
}

/// An image file as linear texels: PNG decoded from sRGB, PFM and EXR as they are.
fn read_image(path: &str, what: &str, resources: &dyn Resources) -> Result<Texels> {
    let path_ref = Path::new(path);
    let format = Format::of(path_ref).map_err(|_| {
        Error::invalid(
            what,
            format!("{what}: {path} is not a .png, .pfm or .exr file"),
        )
    })?;
    let bytes = resources.read(path_ref).map_err(|e| e.within(what))?;
    let image = image_io::decode(&bytes, format)
        .and_then(|image| image_io::refuse_non_radiance(&image).map(|()| image))
        .map_err(|e| e.at_path(path_ref).within(what))?;
    ensure_valid!(
        image.width > 0
            && image.height > 0
            && image.width <= MAX_TEXTURE_SIDE
            && image.height <= MAX_TEXTURE_SIDE,
        what,
        "{what}: {path} is {}x{}; an environment image must be 1 to {MAX_TEXTURE_SIDE} texels on a side",
        image.width,
        image.height
    );
    Ok(Texels {
        width: image.width,
        height: image.height,
        texels: image.pixels,
    })
}
