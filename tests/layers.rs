//! The crate's layers, bottom to top: geometry and settings → the errors → output
//! (images, files) → texture → scene → raster → shadow, shading, radiosity, media
//! (siblings) → global (ray tracing and the two-pass method's second pass, over
//! shading's light model and radiosity's solution) → render → catalogue → the command
//! line. A module names only modules below its
//! own layer (and its own): read from the sources, every `crate::` path checked.

use std::path::Path;

fn layer(module: &str) -> Option<u32> {
    Some(match module {
        "geometry" | "settings" => 0,
        "error" => 1,
        "output" => 2,
        "texture" => 3,
        "scene" => 4,
        "raster" => 5,
        "shadow" | "shading" | "radiosity" | "media" => 6,
        "global" => 7,
        "render" => 8,
        "catalogue" => 9,
        "cli" | "main" | "lib" => 10,
        _ => return None,
    })
}

/// The module a crate path's first name is: a module, or a re-export of the root.
fn module_of(name: &str) -> &str {
    match name {
        "Error" | "Result" | "FileOp" => "error",
        "Image" => "output",
        "Scene" => "scene",
        "load_scene" => "lib",
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
