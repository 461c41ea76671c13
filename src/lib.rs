//! lumiere: a software scan-line renderer that reproduces the classic rendering
//! algorithms literally, one module per paper.
//!
//! The flow of a frame: a `Scene` (from a TOML scene file or a catalogue entry) is
//! clipped and projected, swept by the scan-line visible-surface pass (`raster`)
//! into a visible-surface buffer, shaded (`shading`) with each light weighted by its
//! visibility term (`shadow`), and box-filtered into a linear radiance `Image`
//! (`output`), saved as sRGB PNG or linear PFM or EXR.

pub mod catalogue;
mod error;
pub mod geometry;
pub mod global;
pub mod image_io;
pub mod media;
pub mod radiosity;
pub mod raster;
pub mod render;
pub mod scene;
pub mod settings;
pub mod shading;
pub mod shadow;
pub mod texture;

use scene::resources::{Directory, Layered};
use std::path::Path;

pub use error::{Error, FileOp, OverBudget, Result};
pub use image_io::Image;
pub use render::render;
pub use scene::Scene;

/// Loads a scene named by a catalogue id or a path to a `.toml` scene file, with
/// `key=value` overrides applied in order.
pub fn load_scene(spec: &str, overrides: &[String]) -> Result<Scene> {
    let path = Path::new(spec);
    let is_file = spec.ends_with(".toml") || path.exists();
    let (mut table, base_dir) = if is_file {
        let text =
            std::fs::read_to_string(path).map_err(|e| Error::io(FileOp::ReadScene, path, e))?;
        let mut table = scene::tables::parse(&text, spec)?;
        // A scene file may start from a catalogue entry: `extends = "cornell-box"`.
        if let Some(base) = table.remove("extends") {
            let base = base
                .as_str()
                .ok_or_else(|| Error::invalid("extends", "`extends` must be a catalogue id"))?;
            let mut merged = catalogue::entry(base)?.scene;
            scene::tables::merge(&mut merged, table);
            table = merged;
        }
        (
            table,
            path.parent().map(Path::to_path_buf).unwrap_or_default(),
        )
    } else {
        (catalogue::entry(spec)?.scene, Default::default())
    };
    // Entries of the named collections the overrides add (collection, name, assignment).
    let mut added = Vec::new();
    for assignment in overrides {
        let before = scene::tables::named_entries(&table);
        scene::tables::set(&mut table, assignment)?;
        for (collection, name) in scene::tables::named_entries(&table).difference(&before) {
            added.push((*collection, name.clone(), assignment.as_str()));
        }
    }
    refuse_unused_textures(&table, &added)?;
    let catalogue = catalogue::resources();
    let layered;
    let resources: &dyn scene::resources::Resources = if is_file {
        layered = Layered(vec![Box::new(Directory(base_dir)), Box::new(catalogue)]);
        &layered
    } else {
        &catalogue
    };
    // The shadow method's own budget, refused before any work.
    let scene = scene::scene_from_table(table, resources)
        .and_then(|scene| {
            (shadow::method(scene.shadows.method).budget)(&scene).map_err(Error::OverBudget)?;
            Ok(scene)
        })
        .map_err(|e| Error::InScene {
            spec: spec.to_string(),
            source: Box::new(e),
        })?;
    refuse_unused_materials(&scene, &added)?;
    Ok(scene)
}

/// A texture an override adds that no material names (a misspelt name) is refused.
fn refuse_unused_textures(table: &toml::Table, added: &[(&str, String, &str)]) -> Result<()> {
    let materials = table.get("materials").and_then(toml::Value::as_table);
    let used = |name: &str| {
        materials.into_iter().flat_map(|m| m.values()).any(|m| {
            ["diffuse_texture", "specular_texture", "bump_texture"]
                .iter()
                .any(|key| m.get(*key).and_then(toml::Value::as_str) == Some(name))
        })
    };
    for (_, name, assignment) in added.iter().filter(|a| a.0 == "textures") {
        if !used(name) {
            let textures = table.get("textures").and_then(toml::Value::as_table);
            let defined = textures
                .into_iter()
                .flat_map(|t| t.keys())
                .filter(|k| !added.iter().any(|(c, n, _)| *c == "textures" && n == *k));
            return Err(Error::Override {
                assignment: assignment.to_string(),
                message: scene::tables::not_defined("textures", name, defined.map(String::as_str)),
            });
        }
    }
    Ok(())
}

/// A material an override adds that no polygon wears (a misspelt name) is refused;
/// one named like an OBJ file's MTL material replaces it, and is worn.
fn refuse_unused_materials(scene: &Scene, added: &[(&str, String, &str)]) -> Result<()> {
    let is_added = |name: &str| added.iter().any(|(c, n, _)| *c == "materials" && n == name);
    for (_, name, assignment) in added.iter().filter(|a| a.0 == "materials") {
        let worn = scene
            .polygons
            .iter()
            .any(|p| scene.materials[p.material].name == *name);
        if !worn {
            let defined = scene
                .materials
                .iter()
                .map(|m| m.name.as_str())
                .filter(|n| !is_added(n));
            return Err(Error::Override {
                assignment: assignment.to_string(),
                message: scene::tables::not_defined("materials", name, defined),
            });
        }
    }
    Ok(())
}
