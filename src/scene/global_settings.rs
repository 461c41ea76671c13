//! `[global]` from the file, checked.

use super::file::{GlobalFile, MechanismFile};
use super::validate::colour;
use crate::error::Result;
use crate::error::ensure_valid;
use crate::settings::{GlobalMethod, GlobalSettings as Settings, Mechanisms};

/// The longest ray tree `depth` allows: rays grow as 2^depth under glass.
pub const MAX_DEPTH: u32 = 16;
/// Whitted's subdivision of a pixel: 4^levels squares at most.
pub const MAX_SUBDIVISIONS: u32 = 6;
/// Mirror-of-mirror paths: each level renders a virtual environment per window.
pub const MAX_WINDOW_DEPTH: u32 = 4;
/// Mirror-of-mirror levels when the scene gives none.
const DEFAULT_WINDOW_DEPTH: u32 = 2;

pub fn from_file(g: &GlobalFile) -> Result<Settings> {
    ensure_valid!(
        g.depth <= MAX_DEPTH,
        "global.depth",
        "global.depth must be at most {MAX_DEPTH} (a ray tree under glass doubles with each level), got {}",
        g.depth
    );
    ensure_valid!(
        g.threshold.is_finite() && (0.0..1.0).contains(&g.threshold),
        "global.threshold",
        "global.threshold must be a fraction from 0 to 1, got {}",
        g.threshold
    );
    ensure_valid!(
        g.subdivisions <= MAX_SUBDIVISIONS,
        "global.subdivisions",
        "global.subdivisions must be at most {MAX_SUBDIVISIONS} (4^levels squares per pixel), got {}",
        g.subdivisions
    );
    ensure_valid!(
        g.contrast.is_finite() && g.contrast > 0.0,
        "global.contrast",
        "global.contrast must be a positive number, got {}",
        g.contrast
    );
    let ray_traced = g.method == GlobalMethod::RayTracing;
    ensure_valid!(
        !(ray_traced && g.window_depth.is_some()),
        "global.window_depth",
        "global.window_depth = {} is the two-pass methods' (mirrors seen through mirrors in pass 1); ray tracing follows mirrors by its reflected rays (global.depth) and would ignore it",
        g.window_depth.unwrap_or_default()
    );
    ensure_valid!(
        !(ray_traced && g.mechanisms.is_some()),
        "global.mechanisms",
        "global.mechanisms selects the two-pass methods' transfers; ray tracing would ignore it (leave it out, or choose method = \"two-pass\")"
    );
    let window_depth = g.window_depth.unwrap_or(DEFAULT_WINDOW_DEPTH);
    ensure_valid!(
        window_depth <= MAX_WINDOW_DEPTH,
        "global.window_depth",
        "global.window_depth must be at most {MAX_WINDOW_DEPTH} (each level renders a virtual environment per mirror), got {}",
        window_depth
    );
    let mechanisms = match &g.mechanisms {
        None => Mechanisms::ALL,
        Some(list) => Mechanisms {
            diffuse_diffuse: list.contains(&MechanismFile::DiffuseDiffuse),
            specular_diffuse: list.contains(&MechanismFile::SpecularDiffuse),
            diffuse_specular: list.contains(&MechanismFile::DiffuseSpecular),
            specular_specular: list.contains(&MechanismFile::SpecularSpecular),
        },
    };
    Ok(Settings {
        method: g.method,
        depth: g.depth,
        threshold: g.threshold,
        subdivisions: g.subdivisions,
        contrast: g.contrast,
        weights: g.weights,
        window_depth,
        mechanisms,
        exact_direct: g.exact_direct,
        analytic_spheres: g.analytic_spheres,
        ambient: colour("global.ambient", g.ambient)?,
    })
}
