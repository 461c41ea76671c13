//! Scene tables before they become scenes: parsing with positions in errors, merging
//! a base table under another (catalogue `extends`), and `--set key=value` overrides.

use crate::error::{Error, Result};
use std::collections::BTreeSet;
use std::collections::HashMap;
use toml::{Table, Value};

/// Parses TOML text; an error names `origin:line:column`.
pub fn parse(text: &str, origin: &str) -> Result<Table> {
    text.parse::<Table>().map_err(|e| Error::Parse {
        file: origin.to_string(),
        position: e.span().map(|span| {
            let before = &text[..span.start.min(text.len())];
            let line = before.matches('\n').count() + 1;
            let column = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
            (line, column)
        }),
        message: e.message().trim().replace('\n', " "),
    })
}

/// Puts `over` on top of `base`: tables merge key by key, anything else (arrays
/// included) is replaced whole.
pub fn merge(base: &mut Table, over: Table) {
    for (key, value) in over {
        match (base.get_mut(&key), value) {
            (Some(Value::Table(b)), Value::Table(o)) => merge(b, o),
            (_, value) => {
                base.insert(key, value);
            }
        }
    }
}

/// Applies `key.path=value`. The value is read as TOML (`64`, `[1, 2, 3]`, `"x"`);
/// a bare word that is not TOML is taken as a string. Array elements are named by
/// their index (`objects.0.material=red`).
/// An index past the end of an array is refused; a new entry of a named collection
/// (`materials.NAME`) is made here and checked by `load_scene` (see [`NAMED`]).
pub fn set(table: &mut Table, assignment: &str) -> Result<()> {
    let refuse = |message: String| Error::Override {
        assignment: assignment.to_string(),
        message,
    };
    let (path, raw) = assignment
        .split_once('=')
        .ok_or_else(|| refuse("expected key=value".into()))?;
    let keys: Vec<&str> = path.trim().split('.').collect();
    if keys.iter().any(|k| k.is_empty()) {
        return Err(refuse(format!("the key `{path}` has an empty part")));
    }
    let value = parse_value(raw.trim()).map_err(refuse)?;
    let mut slot = Slot::Table(table);
    for (depth, key) in keys.iter().enumerate() {
        let last = depth + 1 == keys.len();
        slot = match slot {
            Slot::Table(t) if last => {
                t.insert(key.to_string(), value);
                return Ok(());
            }
            Slot::Table(t) => Slot::from(
                t.entry(key.to_string())
                    .or_insert_with(|| Value::Table(Table::new())),
            ),
            Slot::Array(a) => {
                let index: usize = key
                    .parse()
                    .map_err(|_| refuse(format!("`{key}` must be an array index")))?;
                let len = a.len();
                let element = a.get_mut(index).ok_or_else(|| {
                    refuse(format!("index {index} is past the end ({len} elements)"))
                })?;
                if last {
                    *element = value;
                    return Ok(());
                }
                Slot::from(element)
            }
            Slot::Leaf => {
                return Err(refuse(format!(
                    "`{key}` is inside a value that is not a table"
                )));
            }
        };
    }
    unreachable!("the loop returns at the last key")
}

/// The scene's named collections. An override that adds an entry nothing uses
/// (`materials.flor.diffuse=...` for `floor`) would change nothing, so `load_scene`
/// refuses it with the nearest name the scene defines; settings tables (`shadows`,
/// `render`, ...) may be created freely.
pub const NAMED: [&str; 2] = ["materials", "textures"];

/// The (collection, name) of every entry of the named collections.
pub fn named_entries(table: &Table) -> BTreeSet<(&'static str, String)> {
    NAMED
        .iter()
        .filter_map(|c| Some((*c, table.get(*c)?.as_table()?)))
        .flat_map(|(c, t)| t.keys().map(move |name| (c, name.clone())))
        .collect()
}

/// "the scene defines no material `flor` that anything uses", with the nearest of
/// `defined` or, when none is near, all of them.
pub fn not_defined<'a>(
    collection: &str,
    name: &str,
    defined: impl IntoIterator<Item = &'a str>,
) -> String {
    let defined: Vec<&str> = defined.into_iter().collect();
    let kind = collection.trim_end_matches('s');
    let mut message = format!("the scene defines no {kind} `{name}` that anything uses");
    if let Some(near) = nearest(defined.iter().copied(), name) {
        message += &format!(" (did you mean `{near}`?)");
    } else if defined.is_empty() {
        message += &format!(" (it has no {collection})");
    } else {
        let names: Vec<_> = defined.iter().map(|k| format!("`{k}`")).collect();
        message += &format!(" (it defines {})", names.join(", "));
    }
    message
}

/// The candidate closest to `word` by edit distance, if it is close enough to be a
/// plausible misspelling (at most half the longer word's letters differ).
pub(crate) fn nearest<'a>(
    candidates: impl IntoIterator<Item = &'a str>,
    word: &str,
) -> Option<&'a str> {
    candidates
        .into_iter()
        .map(|c| (strsim::levenshtein(c, word), c))
        .min()
        .filter(|(distance, c)| *distance <= c.len().max(word.len()) / 2)
        .map(|(_, c)| c)
}

enum Slot<'a> {
    Table(&'a mut Table),
    Array(&'a mut Vec<Value>),
    Leaf,
}

impl<'a> From<&'a mut Value> for Slot<'a> {
    fn from(v: &'a mut Value) -> Self {
        match v {
            Value::Table(t) => Slot::Table(t),
            Value::Array(a) => Slot::Array(a),
            Value::String(_)
            | Value::Integer(_)
            | Value::Float(_)
            | Value::Boolean(_)
            | Value::Datetime(_) => Slot::Leaf,
        }
    }
}

fn parse_value(raw: &str) -> std::result::Result<Value, String> {
    if let Some(value) = format!("v = {raw}")
        .parse::<Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
    {
        return Ok(value);
    }
    // A whole number TOML cannot hold would become a string, and be refused as one.
    let digits = raw.trim_start_matches(['-', '+']).replace('_', "");
    if !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) {
        return Err(format!(
            "{raw} is beyond the whole numbers a scene holds (-9223372036854775808 to 9223372036854775807)"
        ));
    }
    Ok(Value::String(raw.to_string()))
}

/// The index of `name` among `known` (things of `kind`), or an error at `key` that
/// suggests the nearest name, or lists them all when none is near (as
/// `not_defined` does).
pub fn named(known: &HashMap<String, usize>, name: &str, key: &str, kind: &str) -> Result<usize> {
    known.get(name).copied().ok_or_else(|| {
        let mut names: Vec<&str> = known.keys().map(String::as_str).collect();
        names.sort();
        let hint = match nearest(names.iter().copied(), name) {
            Some(near) => format!("did you mean `{near}`?"),
            None if names.is_empty() => "known: none".to_string(),
            None => format!("known: {}", names.join(", ")),
        };
        Error::invalid(key, format!("{key}: unknown {kind} `{name}` ({hint})"))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_errors_name_line_and_column() {
        let err = parse("a = 1\nb = = 2\n", "x.toml").unwrap_err().to_string();
        assert!(err.starts_with("x.toml:2:"), "{err}");
        assert!(!err.contains('\n'));
    }

    #[test]
    fn set_reaches_tables_and_arrays() {
        let mut t = parse("[camera]\nwidth = 5\n[[objects]]\nmaterial = 'a'\n", "t").unwrap();
        set(&mut t, "camera.width=64").unwrap();
        set(&mut t, "objects.0.material=red").unwrap();
        set(&mut t, "render.exposure=2.5").unwrap();
        assert_eq!(t["camera"]["width"].as_integer(), Some(64));
        assert_eq!(t["objects"][0]["material"].as_str(), Some("red"));
        assert_eq!(t["render"]["exposure"].as_float(), Some(2.5));
        assert!(set(&mut t, "objects.3.material=red").is_err());
        assert!(set(&mut t, "camera.width.x=1").is_err());
        assert!(set(&mut t, "nothing").is_err());
    }

    #[test]
    fn an_unknown_name_is_answered_with_the_nearest_or_with_every_known_one() {
        let known: HashMap<String, usize> =
            [("floor".to_string(), 0), ("wall".to_string(), 1)].into();
        assert_eq!(named(&known, "wall", "material", "material").unwrap(), 1);
        let near = named(&known, "flor", "material", "material").unwrap_err();
        assert_eq!(
            near.to_string(),
            "material: unknown material `flor` (did you mean `floor`?)"
        );
        let far = named(&known, "xyzzy", "material", "material").unwrap_err();
        assert_eq!(
            far.to_string(),
            "material: unknown material `xyzzy` (known: floor, wall)"
        );
    }

    #[test]
    fn named_entries_and_suggestions() {
        let mut t = parse("[materials.floor]\n[textures.affine]\n", "t").unwrap();
        set(&mut t, "materials.flor.diffuse=[1, 0, 0]").unwrap();
        let names: Vec<_> = named_entries(&t).into_iter().collect();
        assert_eq!(
            names,
            [
                ("materials", "floor".to_string()),
                ("materials", "flor".to_string()),
                ("textures", "affine".to_string())
            ]
        );
        let m = not_defined("materials", "flor", ["floor", "wall"]);
        assert!(
            m.contains("no material `flor`") && m.contains("did you mean `floor`"),
            "{m}"
        );
        let m = not_defined("textures", "zzz", ["floor", "wall"]);
        assert!(m.contains("`floor`, `wall`"), "{m}");
        assert!(not_defined("textures", "x", []).contains("it has no textures"));
    }

    #[test]
    fn merge_replaces_arrays_and_merges_tables() {
        let mut base = parse("[a]\nx = 1\ny = 2\nlist = [1, 2]\n", "b").unwrap();
        merge(&mut base, parse("[a]\ny = 3\nlist = [9]\n", "o").unwrap());
        assert_eq!(base["a"]["x"].as_integer(), Some(1));
        assert_eq!(base["a"]["y"].as_integer(), Some(3));
        assert_eq!(base["a"]["list"].as_array().unwrap().len(), 1);
    }
}
