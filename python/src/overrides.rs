//! Python values as the command line's `key=value` overrides: keyword arguments
//! or a dict, keys with dots (`**{"camera.width": 256}`) or nested dicts
//! (`camera={"width": 256}`), values written as TOML literals, so an override
//! from Python means exactly what the same `--set` means.

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// The overrides of `overrides` (a dict) then `kwargs`, each key under `prefix`.
pub fn sets(
    prefix: &str,
    overrides: Option<&Bound<'_, PyAny>>,
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<Vec<String>> {
    let mut out = Vec::new();
    if let Some(o) = overrides {
        if o.is_none() {
        } else if let Ok(d) = o.cast::<PyDict>() {
            flatten(prefix, d, &mut out)?;
        } else {
            return Err(PyTypeError::new_err(format!(
                "overrides: a dict of key: value, not {}",
                o.get_type().name()?
            )));
        }
    }
    if let Some(k) = kwargs {
        flatten(prefix, k, &mut out)?;
    }
    Ok(out)
}

fn flatten(prefix: &str, dict: &Bound<'_, PyDict>, out: &mut Vec<String>) -> PyResult<()> {
    for (key, value) in dict.iter() {
        let key: String = key
            .extract()
            .map_err(|_| PyTypeError::new_err(format!("override keys are strings, not {key:?}")))?;
        let key = if prefix.is_empty() {
            key
        } else {
            format!("{prefix}.{key}")
        };
        if let Ok(nested) = value.cast::<PyDict>() {
            flatten(&key, nested, out)?;
        } else {
            out.push(format!("{key}={}", literal(&key, &value)?));
        }
    }
    Ok(())
}

/// A Python value as a TOML literal.
fn literal(key: &str, value: &Bound<'_, PyAny>) -> PyResult<String> {
    if value.is_none() {
        return Err(PyTypeError::new_err(format!(
            "{key}: None is not a value a scene holds"
        )));
    }
    if value.is_instance_of::<PyBool>() {
        return Ok(if value.extract::<bool>()? {
            "true"
        } else {
            "false"
        }
        .into());
    }
    if value.is_instance_of::<PyString>() {
        return Ok(quoted(&value.extract::<String>()?));
    }
    if value.is_instance_of::<PyInt>()
        || (value.hasattr("__index__")? && !value.hasattr("__len__")?)
    {
        let n: i64 = value
            .call_method0("__index__")?
            .extract()
            .map_err(|_| PyValueError::new_err(format!("{key}: {value} is out of range")))?;
        return Ok(n.to_string());
    }
    if value.is_instance_of::<PyFloat>()
        || (value.hasattr("__float__")? && !value.hasattr("__len__")?)
    {
        let x: f64 = value.call_method0("__float__")?.extract()?;
        if !x.is_finite() {
            return Err(PyValueError::new_err(format!(
                "{key}: {x} is not a number a scene can hold"
            )));
        }
        let text = format!("{x:?}");
        return Ok(text);
    }
    if value.hasattr("tolist")? && !value.is_instance_of::<PyList>() {
        return literal(key, &value.call_method0("tolist")?);
    }
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        let items: Vec<String> = value
            .try_iter()?
            .enumerate()
            .map(|(i, item)| literal(&format!("{key}[{i}]"), &item?))
            .collect::<PyResult<_>>()?;
        return Ok(format!("[{}]", items.join(", ")));
    }
    if let Ok(d) = value.cast::<PyDict>() {
        let mut fields = Vec::new();
        for (k, v) in d.iter() {
            let k: String = k.extract()?;
            fields.push(format!(
                "{} = {}",
                quoted(&k),
                literal(&format!("{key}.{k}"), &v)?
            ));
        }
        return Ok(format!("{{ {} }}", fields.join(", ")));
    }
    Err(PyTypeError::new_err(format!(
        "{key}: a {} is not a value a scene holds (numbers, strings, booleans, lists)",
        value.get_type().name()?
    )))
}

/// A TOML basic string.
fn quoted(text: &str) -> String {
    let mut out = String::from('"');
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            c if c.is_control() => out.push_str(&format!("\\u{:04X}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}
