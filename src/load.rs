//! Scenes from a catalogue id, a scene file or a TOML string, with the command
//! line's `--set` overrides applied in order, and the refusals that need the whole
//! scene (an override that adds a texture or material nothing uses).

use crate::catalogue;
use crate::error::{Error, FileOp, Result};
use crate::image_io::read_file;
use crate::scene::resources::{Directory, InMemory, Layered, Resources, normalise};
use crate::scene::{self, Scene};
use crate::shadow;
use std::collections::HashMap;
use std::path::Path;

/// Loads a scene named by a catalogue id, a path to a `.toml` scene file or a glTF
/// 2.0 file (`.gltf`, `.glb`), with `key=value` overrides applied in order (the
/// command line's `--set`).
///
/// A scene file's models and textures are found beside it, then in the catalogue.
/// A glTF scene gets lumiere's default render settings (phong shading, no
/// shadows, a 512-pixel image at its camera's aspect ratio), which the overrides
/// change like any scene file's; what it holds that lumiere cannot render is in
/// the scene's warnings, each starting `gltf: `.
pub fn load_scene(spec: &str, overrides: &[String]) -> Result<Scene> {
    let path = Path::new(spec);
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    if matches!(extension.as_deref(), Some("gltf" | "glb")) {
        scene_from_gltf(scene::gltf::read(path)?, spec, overrides)
    } else if spec.ends_with(".toml") || path.exists() {
        let bytes = read_file(path, FileOp::ReadScene)?;
        let text = String::from_utf8(bytes).map_err(|_| {
            let not_text = std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                "stream did not contain valid UTF-8",
            );
            Error::io(FileOp::ReadScene, path, not_text)
        })?;
        let base_dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        scene_from_text(&text, spec, Some(Box::new(Directory(base_dir))), overrides)
    } else {
        let table = catalogue::entry(spec)?.scene;
        scene_from_parsed(table, spec, None, overrides)
    }
}

/// A scene from files held in memory, by their paths relative to the folder of
/// `main` (a page's chosen files; a program's): `main` is a scene file (`.toml`),
/// a glTF 2.0 file (`.gltf`, `.glb`) or a Wavefront OBJ file (`.obj`, with its MTL
/// and textures among the files; framed from +z under one point light), with
/// `key=value` overrides applied in order. Files the scene names and `files` lacks
/// are looked for in the catalogue.
pub fn scene_from_files(
    main: &str,
    files: HashMap<String, Vec<u8>>,
    overrides: &[String],
) -> Result<Scene> {
    let base = Path::new(main).parent().unwrap_or(Path::new(""));
    let relative = |name: &str| {
        let name = normalise(Path::new(name));
        name.strip_prefix(base)
            .ok()
            .map(|p| p.to_string_lossy().into_owned())
    };
    let own: HashMap<String, Vec<u8>> = files
        .into_iter()
        .filter_map(|(name, bytes)| Some((relative(&name)?, bytes)))
        .collect();
    let name = relative(main).unwrap_or_else(|| main.to_string());
    let Some(bytes) = own.get(&name) else {
        return Err(Error::Scene(format!("{main}: not among the files given")));
    };
    let extension = Path::new(main)
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match extension.as_deref() {
        Some("gltf" | "glb") => {
            let own = InMemory(own);
            let imported = scene::gltf::from_bytes(
                own.read(Path::new(&name))?.as_slice(),
                Path::new(main),
                &own,
            )?;
            scene_from_gltf(imported, main, overrides)
        }
        Some("obj") => {
            let own = InMemory(own);
            let (table, warnings) =
                scene::obj_scene::table(&name, &own).map_err(|e| Error::InScene {
                    spec: main.to_string(),
                    source: Box::new(e),
                })?;
            let mut scene = scene_from_parsed(table, main, Some(Box::new(own)), overrides)?;
            scene.warnings.splice(0..0, warnings);
            Ok(scene)
        }
        Some("toml") => {
            let text = String::from_utf8(bytes.clone())
                .map_err(|_| Error::Scene(format!("{main}: not a text file (UTF-8)")))?;
            scene_from_text(&text, main, Some(Box::new(InMemory(own))), overrides)
        }
        _ => Err(Error::Scene(format!(
            "{main}: a scene is a .toml, .gltf, .glb or .obj file"
        ))),
    }
}

/// The scene of an imported glTF file, its warnings first.
fn scene_from_gltf(
    imported: scene::gltf::Imported,
    spec: &str,
    overrides: &[String],
) -> Result<Scene> {
    let files = Box::new(InMemory(imported.files));
    let mut scene = scene_from_parsed(imported.table, spec, Some(files), overrides)?;
    let mut warnings = imported.warnings;
    warnings.append(&mut scene.warnings);
    scene.warnings = warnings;
    Ok(scene)
}

/// A scene from the text of a scene file, with `key=value` overrides applied in
/// order. It may `extends` a catalogue entry; the models and textures it names are
/// the catalogue's (`models/teapot.obj`, `textures/brick.png`).
pub fn scene_from_toml(text: &str, overrides: &[String]) -> Result<Scene> {
    scene_from_text(text, "<toml>", None, overrides)
}

/// `text` parsed, and its `extends` merged in: a scene file may start from a
/// catalogue entry (`extends = "cornell-box"`).
fn scene_from_text(
    text: &str,
    spec: &str,
    own: Option<Box<dyn Resources>>,
    overrides: &[String],
) -> Result<Scene> {
    let mut table = scene::tables::parse(text, spec)?;
    if let Some(base) = table.remove("extends") {
        let base = base
            .as_str()
            .ok_or_else(|| Error::invalid("extends", "`extends` must be a catalogue id"))?;
        let mut merged = catalogue::entry(base)?.scene;
        scene::tables::merge(&mut merged, table);
        table = merged;
    }
    scene_from_parsed(table, spec, own, overrides)
}

/// The scene of a parsed table, its overrides applied; files are looked for in
/// `own` (a scene file's folder, a glTF file's meshes and images) first, then in
/// the catalogue.
fn scene_from_parsed(
    mut table: toml::Table,
    spec: &str,
    own: Option<Box<dyn Resources>>,
    overrides: &[String],
) -> Result<Scene> {
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
    let resources: &dyn Resources = match own {
        Some(own) => {
            layered = Layered(vec![own, Box::new(catalogue)]);
            &layered
        }
        None => &catalogue,
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
