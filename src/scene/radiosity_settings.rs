//! `[radiosity]` from the file, checked.

use super::file::{MAX_MEMORY_BUDGET_MB, RadiosityFile};
use crate::error::Result;
use crate::error::ensure_valid;
use crate::settings::{Division, RadiositySettings as Settings, Subdivision};

pub fn from_file(r: &RadiosityFile) -> Result<Settings> {
    ensure_valid!(
        (2..=4096).contains(&r.resolution),
        "radiosity.resolution",
        "radiosity.resolution must be between 2 and 4096, got {}",
        r.resolution
    );
    let size = |key: &str, value: Option<f64>| -> Result<Division> {
        match value {
            None => Ok(Division::Whole),
            Some(v) => {
                ensure_valid!(
                    v.is_finite() && v > 0.0,
                    format!("radiosity.{key}"),
                    "radiosity.{key} must be a positive length, got {v}"
                );
                Ok(Division::Size(v))
            }
        }
    };
    ensure_valid!(
        r.tolerance.is_finite() && r.tolerance > 0.0 && r.tolerance < 1.0,
        "radiosity.tolerance",
        "radiosity.tolerance must be between 0 and 1, got {}",
        r.tolerance
    );
    ensure_valid!(
        r.unshot.is_finite() && (0.0..1.0).contains(&r.unshot),
        "radiosity.unshot",
        "radiosity.unshot must be a fraction from 0 to 1, got {}",
        r.unshot
    );
    ensure_valid!(
        (1..=MAX_MEMORY_BUDGET_MB).contains(&r.max_memory_mb),
        "radiosity.max_memory_mb",
        "radiosity.max_memory_mb must be from 1 to {MAX_MEMORY_BUDGET_MB} (1 TiB), got {}",
        r.max_memory_mb
    );
    if let Some(t) = r.subdivide {
        ensure_valid!(
            t.is_finite() && t > 0.0,
            "radiosity.subdivide",
            "radiosity.subdivide must be a positive fraction, got {t}"
        );
    }
    ensure_valid!(
        r.subdivision_levels <= 8,
        "radiosity.subdivision_levels",
        "radiosity.subdivision_levels must be at most 8 (each level can quadruple the elements), got {}",
        r.subdivision_levels
    );
    Ok(Settings {
        solver: r.solver,
        form_factors: r.form_factors,
        resolution: r.resolution,
        patches: size("patch_size", r.patch_size)?,
        elements: size("element_size", r.element_size)?,
        tolerance: r.tolerance,
        unshot: r.unshot,
        max_steps: r.max_steps,
        ambient: r.ambient,
        display: r.display,
        memory_budget: r.max_memory_mb.saturating_mul(1 << 20),
        subdivision: r.subdivide.map(|threshold| Subdivision {
            threshold,
            levels: r.subdivision_levels,
        }),
    })
}
