//! `[global]` from the file, checked.

use super::file::{FinalGatherFile, GlobalFile, MechanismFile};
use super::validate::colour;
use crate::error::Result;
use crate::error::ensure_valid;
use crate::settings::{
    FinalGatherSettings, GlobalMethod, GlobalSettings as Settings, Mechanisms, PhotonSettings,
};

/// The longest ray tree `depth` allows: rays grow as 2^depth under glass.
pub const MAX_DEPTH: u32 = 16;
/// Whitted's subdivision of a pixel: 4^levels squares at most.
pub const MAX_SUBDIVISIONS: u32 = 6;
/// Mirror-of-mirror paths: each level renders a virtual environment per window.
pub const MAX_WINDOW_DEPTH: u32 = 4;
/// Rays of one final gather: 2²⁰ is a thousand times a usual gather.
pub const MAX_GATHER_RAYS: u32 = 1 << 20;
/// Reflected and refracted rays from the eye when the scene gives none.
const DEFAULT_DEPTH: u32 = 5;
/// A path's bounces when the scene gives none: a safeguard (Russian roulette ends
/// paths long before under albedos below 1), not a choice of the method.
pub const DEFAULT_PATH_DEPTH: u32 = 1000;
/// A path's longest allowed chain: one ray a bounce, so depth costs linearly.
pub const MAX_PATH_DEPTH: u32 = 1_000_000;
/// The path tracer's n x n paths a pixel when the scene gives none.
const DEFAULT_PATH_SAMPLES: u32 = 4;
/// 1024 x 1024 paths a pixel: a million, far beyond any converged image.
pub const MAX_PATH_SAMPLES: u32 = 1024;
/// Photons a map may hold: 50 million, about 3 GB.
pub const MAX_PHOTONS: u32 = 50_000_000;
/// Photons an estimate may read.
pub const MAX_NEAREST: u32 = 10_000;
/// A ray's least weight when the scene gives none.
const DEFAULT_THRESHOLD: f64 = 1e-3;
/// Whitted's subdivision levels when the scene gives none.
const DEFAULT_SUBDIVISIONS: u32 = 2;
/// Whitted's corner contrast when the scene gives none.
const DEFAULT_CONTRAST: f64 = 0.05;
/// Mirror-of-mirror levels when the scene gives none.
const DEFAULT_WINDOW_DEPTH: u32 = 2;
/// The reflection frustum's cells a side when the scene gives none.
const DEFAULT_FRUSTUM_RESOLUTION: u32 = 10;
/// A frustum of 256² cells is 65,536 rays a glossy sample.
pub const MAX_FRUSTUM_RESOLUTION: u32 = 256;

pub fn from_file(g: &GlobalFile) -> Result<Settings> {
    let paths = g.method == GlobalMethod::PathTracing;
    let depth = g.depth.unwrap_or(if paths {
        DEFAULT_PATH_DEPTH
    } else {
        DEFAULT_DEPTH
    });
    let threshold = g.threshold.unwrap_or(DEFAULT_THRESHOLD);
    let subdivisions = g.subdivisions.unwrap_or(DEFAULT_SUBDIVISIONS);
    let contrast = g.contrast.unwrap_or(DEFAULT_CONTRAST);
    if paths {
        ensure_valid!(
            (1..=MAX_PATH_DEPTH).contains(&depth),
            "global.depth",
            "global.depth must be from 1 to {MAX_PATH_DEPTH} bounces of a path, got {}",
            depth
        );
    } else {
        ensure_valid!(
            depth <= MAX_DEPTH,
            "global.depth",
            "global.depth must be at most {MAX_DEPTH} (a ray tree under glass doubles with each level), got {}",
            depth
        );
    }
    let samples = g.samples.unwrap_or(DEFAULT_PATH_SAMPLES);
    ensure_valid!(
        (1..=MAX_PATH_SAMPLES).contains(&samples),
        "global.samples",
        "global.samples must be from 1 to {MAX_PATH_SAMPLES} (n x n paths a pixel), got {}",
        samples
    );
    ensure_valid!(
        threshold.is_finite() && (0.0..1.0).contains(&threshold),
        "global.threshold",
        "global.threshold must be a fraction from 0 to 1, got {}",
        threshold
    );
    ensure_valid!(
        subdivisions <= MAX_SUBDIVISIONS,
        "global.subdivisions",
        "global.subdivisions must be at most {MAX_SUBDIVISIONS} (4^levels squares per pixel), got {}",
        subdivisions
    );
    ensure_valid!(
        contrast.is_finite() && contrast > 0.0,
        "global.contrast",
        "global.contrast must be a positive number, got {}",
        contrast
    );
    let photons = PhotonSettings {
        global: g.photons.unwrap_or(200_000),
        caustic: g.caustic_photons.unwrap_or(100_000),
        nearest: g.nearest.unwrap_or(100),
        caustic_nearest: g.caustic_nearest.unwrap_or(80),
        precomputed_irradiance: g.precomputed_irradiance.unwrap_or(false),
    };
    for (key, value) in [
        ("global.photons", photons.global),
        ("global.caustic_photons", photons.caustic),
    ] {
        ensure_valid!(
            value <= MAX_PHOTONS,
            key,
            "{key} must be at most {MAX_PHOTONS} photons, got {}",
            value
        );
    }
    for (key, value) in [
        ("global.nearest", photons.nearest),
        ("global.caustic_nearest", photons.caustic_nearest),
    ] {
        ensure_valid!(
            (1..=MAX_NEAREST).contains(&value),
            key,
            "{key} must be from 1 to {MAX_NEAREST} photons, got {}",
            value
        );
    }
    let window_depth = g.window_depth.unwrap_or(DEFAULT_WINDOW_DEPTH);
    ensure_valid!(
        window_depth <= MAX_WINDOW_DEPTH,
        "global.window_depth",
        "global.window_depth must be at most {MAX_WINDOW_DEPTH} (each level renders a virtual environment per mirror), got {}",
        window_depth
    );
    let frustum_resolution = g.frustum_resolution.unwrap_or(DEFAULT_FRUSTUM_RESOLUTION);
    ensure_valid!(
        (1..=MAX_FRUSTUM_RESOLUTION).contains(&frustum_resolution),
        "global.frustum_resolution",
        "global.frustum_resolution must be from 1 to {MAX_FRUSTUM_RESOLUTION} (cells along each side of the reflection frustum), got {}",
        frustum_resolution
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
    let final_gather = match &g.final_gather {
        None => None,
        Some(f) => {
            ensure_valid!(
                g.method == GlobalMethod::PhotonMap
                    || (g.method.reads_radiosity() && g.exact_direct == Some(true)),
                "global.final_gather",
                "global.final_gather gathers the indirect light from a radiosity solution beside the exact direct light, or from a photon map: it needs a two-pass method and global.exact_direct = true, or method = \"photon-map\""
            );
            Some(final_gather(f)?)
        }
    };
    Ok(Settings {
        method: g.method,
        depth,
        samples,
        photons,
        threshold,
        subdivisions,
        contrast,
        weights: g.weights.unwrap_or_default(),
        window_depth,
        frustum_resolution,
        mechanisms,
        exact_direct: g.exact_direct.unwrap_or(false),
        analytic_spheres: g.analytic_spheres.unwrap_or(true),
        ambient: colour("global.ambient", g.ambient.unwrap_or_default())?,
        final_gather,
        keys_set: g.keys_set(),
    })
}

/// The final gather's settings when `[global.final_gather]` gives none (the
/// photon map always gathers).
pub fn default_final_gather() -> FinalGatherSettings {
    let defaults: FinalGatherFile = toml::from_str("").expect("every key has a default");
    final_gather(&defaults).expect("the defaults are valid")
}

fn final_gather(f: &FinalGatherFile) -> Result<FinalGatherSettings> {
    ensure_valid!(
        (1..=MAX_GATHER_RAYS).contains(&f.rays),
        "global.final_gather.rays",
        "global.final_gather.rays must be from 1 to {MAX_GATHER_RAYS}, got {}",
        f.rays
    );
    ensure_valid!(
        f.error.is_finite() && (0.0..=1.0).contains(&f.error),
        "global.final_gather.error",
        "global.final_gather.error (Ward's accuracy a) must be from 0 to 1, got {}",
        f.error
    );
    ensure_valid!(
        f.min_spacing.is_finite() && f.min_spacing > 0.0 && f.min_spacing <= 1.0,
        "global.final_gather.min_spacing",
        "global.final_gather.min_spacing must be a fraction of the scene's size above 0 and at most 1, got {}",
        f.min_spacing
    );
    ensure_valid!(
        f.max_spacing.is_finite() && f.max_spacing >= f.min_spacing && f.max_spacing <= 1.0,
        "global.final_gather.max_spacing",
        "global.final_gather.max_spacing must be a fraction of the scene's size from min_spacing ({}) to 1, got {}",
        f.min_spacing,
        f.max_spacing
    );
    Ok(FinalGatherSettings {
        rays: f.rays,
        error: f.error,
        min_spacing: f.min_spacing,
        max_spacing: f.max_spacing,
        gradients: f.gradients,
        direct_at_hits: f.direct_at_hits,
    })
}
