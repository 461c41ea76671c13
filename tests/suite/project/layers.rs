//! The crate's layers, bottom to top: geometry and settings → the errors → image_io
//! (image input and output) → texture → scene → raster → shadow, shading,
//! radiosity, media (siblings) → global (ray tracing and the two-pass method's
//! second pass, over shading's light model and radiosity's solution) → render →
//! catalogue, export and environment maps → the loader → the viewer's engine → the command line, the
//! crate root. A module names only modules
//! below its own layer (and its own): read from the sources, every `crate::` path
//! checked. Inside a folder, the files import one another without a circle.

use std::path::Path;

fn layer(module: &str) -> Option<u32> {
    Some(match module {
        "geometry" | "settings" => 0,
        "error" => 1,
        "image_io" => 2,
        "texture" => 3,
        "scene" => 4,
        "raster" => 5,
        "shadow" | "shading" | "radiosity" | "media" => 6,
        "global" => 7,
        "render" => 8,
        "catalogue"
        | "export"
        | "environment_maps"
        | "radiosity_solution"
        | "visible_surface_pass" => 9,
        "load" => 10,
        "viewer" => 11,
        "cli" | "main" | "lib" => 12,
        _ => return None,
    })
}

/// The module a crate path's first name is. Below the root, code names the module
/// an item lives in (`crate::error::Result`), never a re-export of the root, so the
/// root stands at the top of the tree only.
fn module_of(name: &str) -> &str {
    match name {
        "load_scene" | "scene_from_toml" => "lib",
        module => module,
    }
}

fn sources(dir: &Path, found: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            sources(&path, found);
        } else if path.extension().is_some_and(|e| e == "rs") {
            found.push(path);
        }
    }
}

#[test]
fn no_module_names_a_module_above_it() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    sources(&src, &mut files);
    let mut violations = Vec::new();
    let mut checked = 0;
    for file in &files {
        let relative = file.strip_prefix(&src).unwrap();
        let first = relative
            .components()
            .next()
            .unwrap()
            .as_os_str()
            .to_str()
            .unwrap();
        let own = first.trim_end_matches(".rs");
        let own_layer = layer(own).unwrap_or_else(|| panic!("{own}: a module of no layer"));
        let text = std::fs::read_to_string(file).unwrap();
        // Unit tests may use the whole crate.
        let text = text.split("#[cfg(test)]").next().unwrap();
        // Paths into the crate, in `use` lines and in code: `crate::name`, and the
        // names inside `use crate::{a, b}`.
        let mut named: Vec<String> = Vec::new();
        for (i, _) in text.match_indices("crate::") {
            let rest = &text[i + 7..];
            if let Some(group) = rest.strip_prefix('{') {
                let end = group.find('}').unwrap_or(group.len());
                named.extend(
                    group[..end]
                        .split(',')
                        .map(|s| s.trim().split("::").next().unwrap_or("").to_string()),
                );
            } else {
                named.push(
                    rest.chars()
                        .take_while(|c| c.is_alphanumeric() || *c == '_')
                        .collect(),
                );
            }
        }
        for name in named.into_iter().filter(|n| !n.is_empty()) {
            checked += 1;
            let name = module_of(&name);
            let Some(their) = layer(name) else {
                panic!("{}: crate::{name} belongs to no layer", relative.display());
            };
            if name != own && their >= own_layer {
                violations.push(format!("{} names crate::{name}", relative.display()));
            }
        }
    }
    assert!(checked > 100, "only {checked} crate paths found");
    assert!(violations.is_empty(), "{}", violations.join("\n"));
}

/// The sibling files `text` names: `super::name` and `crate::folder::name`, in `use`
/// lines and in code (inside groups too), where `name` is a file of the folder.
fn siblings_named(text: &str, folder: &str, files: &[String]) -> Vec<String> {
    let mut named = Vec::new();
    for prefix in ["super::".to_string(), format!("crate::{folder}::")] {
        for (i, _) in text.match_indices(&prefix) {
            let rest = &text[i + prefix.len()..];
            let names: Vec<String> = match rest.strip_prefix('{') {
                Some(group) => group[..group.find('}').unwrap_or(group.len())]
                    .split(',')
                    .map(|s| s.trim().split("::").next().unwrap_or("").to_string())
                    .collect(),
                None => vec![
                    rest.chars()
                        .take_while(|c| c.is_alphanumeric() || *c == '_')
                        .collect(),
                ],
            };
            named.extend(names.into_iter().filter(|n| files.contains(n)));
        }
    }
    named
}

/// Inside each folder of src/, the files' imports of one another (`super::` and
/// `crate::folder::` paths; the folder's mod.rs declares them and is left out) form
/// no circle.
#[test]
fn no_folder_has_a_circle_of_files() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut circles = Vec::new();
    let mut edges_seen = 0;
    let mut folders = vec![src.clone()];
    while let Some(dir) = folders.pop() {
        let mut files: Vec<String> = Vec::new();
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                folders.push(path.clone());
                files.push(path.file_name().unwrap().to_str().unwrap().to_string());
            } else if path.extension().is_some_and(|e| e == "rs") {
                let stem = path.file_stem().unwrap().to_str().unwrap();
                if stem != "mod" && dir != src {
                    files.push(stem.to_string());
                }
            }
        }
        if dir == src {
            continue;
        }
        let folder = dir
            .strip_prefix(&src)
            .unwrap()
            .to_str()
            .unwrap()
            .replace('/', "::");
        let mut edges: Vec<(String, String)> = Vec::new();
        for file in &files {
            let path = match dir.join(format!("{file}.rs")) {
                p if p.exists() => p,
                _ => dir.join(file).join("mod.rs"),
            };
            let Ok(text) = std::fs::read_to_string(&path) else {
                continue;
            };
            let text = text.split("#[cfg(test)]").next().unwrap();
            for other in siblings_named(text, &folder, &files) {
                if &other != file && !edges.contains(&(file.clone(), other.clone())) {
                    edges.push((file.clone(), other));
                }
            }
        }
        edges_seen += edges.len();
        // A depth-first search for a path back to where it started.
        for start in &files {
            let mut stack = vec![(start.clone(), vec![start.clone()])];
            let mut seen = vec![start.clone()];
            while let Some((at, path)) = stack.pop() {
                for (_, next) in edges.iter().filter(|(from, _)| *from == at) {
                    if next == start {
                        let mut circle = path.clone();
                        circle.push(start.clone());
                        circles.push(format!("src/{folder}: {}", circle.join(" -> ")));
                    } else if !seen.contains(next) {
                        seen.push(next.clone());
                        let mut longer = path.clone();
                        longer.push(next.clone());
                        stack.push((next.clone(), longer));
                    }
                }
            }
        }
    }
    assert!(
        edges_seen > 50,
        "only {edges_seen} imports between files found"
    );
    circles.sort();
    circles.dedup();
    assert!(circles.is_empty(), "{}", circles.join("\n"));
}

/// The modules behind the API, public for the checks in tests/ alone.
const HIDDEN: [&str; 11] = [
    "geometry",
    "global",
    "image_io",
    "media",
    "radiosity",
    "raster",
    "render",
    "scene",
    "shading",
    "shadow",
    "texture",
];

/// The hidden modules `text` names through the crate: `lumiere::name` paths and the
/// names inside `use lumiere::{a, b::c}` groups.
fn hidden_named(text: &str) -> Vec<&'static str> {
    let mut found = Vec::new();
    for (i, _) in text.match_indices("lumiere::") {
        let rest = &text[i + "lumiere::".len()..];
        let names: Vec<&str> = match rest.strip_prefix('{') {
            Some(group) => {
                let group = &group[..group.find('}').unwrap_or(group.len())];
                group.split(',').map(|n| n.trim()).collect()
            }
            None => vec![rest],
        };
        for name in names {
            let head: String = name
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            // `lumiere::render` alone is also the root's function.
            let into = name[head.len()..].starts_with("::");
            if into || head != "render" {
                found.extend(HIDDEN.iter().filter(|h| **h == head));
            }
        }
    }
    found
}

#[test]
fn only_the_checks_open_the_hidden_modules() {
    // The parser sees what it must: a path, a group, a nested group.
    assert_eq!(hidden_named("use lumiere::raster::View;"), ["raster"]);
    assert_eq!(
        hidden_named("use lumiere::{Image, shadow::x, catalogue};"),
        ["shadow"]
    );
    assert_eq!(
        hidden_named("use lumiere::{render::band_rows, raster};"),
        ["render", "raster"]
    );
    assert!(hidden_named("use lumiere::{Renderer, render, form_factors};").is_empty());
    assert!(hidden_named("lumiere::render(&scene); lumiere::scene_from_toml").is_empty());
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for dir in [
        "src/cli",
        "src/main.rs",
        "python/src",
        "web/src",
        "examples",
    ] {
        let path = root.join(dir);
        if path.is_dir() {
            sources(&path, &mut files);
        } else {
            files.push(path);
        }
    }
    assert!(files.len() > 40, "{} files", files.len());
    let mut violations = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        for name in hidden_named(&text) {
            violations.push(format!("{} names lumiere::{name}", file.display()));
        }
    }
    assert!(violations.is_empty(), "{violations:#?}");
}
