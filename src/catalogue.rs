//! The catalogue: one `algorithms/<id>.toml` per demonstration, embedded in the
//! binary. An entry is a scene file with an `[algorithm]` table naming the paper,
//! saying what the entry shows and the size its golden image is rendered at. An
//! entry may `extends` another: its tables are merged over the other's, key by key.

use crate::error::{Error, Result};
use crate::scene::resources::Embedded;
use crate::scene::tables;
use include_dir::{Dir, include_dir};
use serde::{Deserialize, Serialize};

static ALGORITHMS: Dir = include_dir!("$CARGO_MANIFEST_DIR/algorithms");

/// Files the catalogue's scenes refer to (models, textures).
pub fn resources() -> Embedded {
    Embedded(&ALGORITHMS)
}

/// The `[algorithm]` table of an entry.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Algorithm {
    /// The entry's id, its file name without `.toml`.
    pub id: String,
    /// What the entry shows, in a line.
    pub title: String,
    /// Authors and year as cited, e.g. "Watkins 1970".
    pub authors: String,
    /// The year of the paper.
    pub year: u32,
    /// The part of the course it belongs to (a page of the gallery).
    pub topic: Topic,
    /// The full reference.
    pub citation: String,
    /// What the entry shows, in a paragraph.
    pub summary: String,
    /// The size the golden image is rendered at.
    pub test_width: u32,
    /// The golden image's height.
    pub test_height: u32,
    /// Another entry whose scene this one starts from.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub extends: Option<String>,
}

/// The parts of the course, in its order: each is a page of the gallery.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Topic {
    /// Watkins's scan-line pass, clipping, flat, Gouraud and Phong shading.
    VisibleSurfaces,
    /// Shadows of point, spot and distant lights.
    HardShadows,
    /// Shadows of extended lights: umbra and penumbra.
    SoftShadows,
    /// Light scattered by a participating medium.
    LightVolumes,
    /// Texture, mip and bump mapping.
    Texture,
    /// Reflection and refraction maps.
    EnvironmentMapping,
    /// Gathering, shooting and substructuring.
    Radiosity,
    /// Whitted's ray tracing and the two-pass methods.
    GlobalIllumination,
}

impl Topic {
    /// Every topic, in the course's order.
    pub const ALL: [Topic; 8] = [
        Topic::VisibleSurfaces,
        Topic::HardShadows,
        Topic::SoftShadows,
        Topic::LightVolumes,
        Topic::Texture,
        Topic::EnvironmentMapping,
        Topic::Radiosity,
        Topic::GlobalIllumination,
    ];

    /// The name scene files and page names use.
    pub fn name(self) -> &'static str {
        match self {
            Topic::VisibleSurfaces => "visible-surfaces",
            Topic::HardShadows => "hard-shadows",
            Topic::SoftShadows => "soft-shadows",
            Topic::LightVolumes => "light-volumes",
            Topic::Texture => "texture",
            Topic::EnvironmentMapping => "environment-mapping",
            Topic::Radiosity => "radiosity",
            Topic::GlobalIllumination => "global-illumination",
        }
    }

    /// The title of the topic's page.
    pub fn title(self) -> &'static str {
        match self {
            Topic::VisibleSurfaces => "Visible surfaces and shading",
            Topic::HardShadows => "Hard shadows",
            Topic::SoftShadows => "Soft shadows",
            Topic::LightVolumes => "Light volumes",
            Topic::Texture => "Texture, mip and bump mapping",
            Topic::EnvironmentMapping => "Environment mapping",
            Topic::Radiosity => "Radiosity",
            Topic::GlobalIllumination => "Global illumination",
        }
    }
}

#[derive(Clone, Debug)]
/// A catalogue entry: what it demonstrates, and its scene.
pub struct Entry {
    /// Its `[algorithm]` table.
    pub algorithm: Algorithm,
    /// The scene, `extends` resolved.
    pub scene: toml::Table,
}

/// Ids of all entries, sorted.
pub fn ids() -> Vec<String> {
    let mut ids: Vec<String> = ALGORITHMS
        .files()
        .filter_map(|f| {
            let path = f.path();
            (path.extension()? == "toml").then(|| path.file_stem()?.to_str().map(String::from))?
        })
        .collect();
    ids.sort();
    ids
}

/// All entries, in id order.
pub fn entries() -> Result<Vec<Entry>> {
    ids().iter().map(|id| entry(id)).collect()
}

/// The text of the entry's file, `algorithms/<id>.toml`, as written (its
/// `extends` unresolved).
pub fn source(id: &str) -> Result<&'static str> {
    ALGORITHMS
        .get_file(format!("{id}.toml"))
        .ok_or_else(|| unknown(id))?
        .contents_utf8()
        .ok_or_else(|| Error::Catalogue(format!("{id}.toml is not UTF-8")))
}

/// The entry `id`, its `extends` resolved (an unknown id is refused, with the
/// nearest id suggested).
pub fn entry(id: &str) -> Result<Entry> {
    entry_from(id, &mut Vec::new())
}

fn entry_from(id: &str, chain: &mut Vec<String>) -> Result<Entry> {
    if chain.iter().any(|c| c == id) {
        return Err(Error::Catalogue(format!(
            "catalogue entries extend each other in a cycle: {} -> {id}",
            chain.join(" -> ")
        )));
    }
    chain.push(id.to_string());
    let name = format!("{id}.toml");
    let file = ALGORITHMS.get_file(&name).ok_or_else(|| unknown(id))?;
    let text = file
        .contents_utf8()
        .ok_or_else(|| Error::Catalogue(format!("{name} is not UTF-8")))?;
    let mut table = tables::parse(text, &format!("algorithms/{name}"))?;
    let algorithm: Algorithm = table
        .remove("algorithm")
        .ok_or_else(|| Error::Catalogue(format!("algorithms/{name}: no [algorithm] table")))?
        .try_into()
        .map_err(|e| Error::Catalogue(format!("algorithms/{name}: [algorithm]: {e}")))?;
    if algorithm.id != id {
        return Err(Error::Catalogue(format!(
            "algorithms/{name}: [algorithm] id is `{}`",
            algorithm.id
        )));
    }
    let scene = match &algorithm.extends {
        Some(base) => {
            let mut scene = entry_from(base, chain)?.scene;
            tables::merge(&mut scene, table);
            scene
        }
        None => table,
    };
    Ok(Entry { algorithm, scene })
}

fn unknown(id: &str) -> Error {
    let known = ids();
    let nearest = tables::nearest(known.iter().map(String::as_str), id);
    Error::UnknownEntry {
        id: id.to_string(),
        suggestion: nearest.map(str::to_string),
    }
}
