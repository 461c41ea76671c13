//! `[shadows]` from the file, checked. What each method handles, and its budget,
//! are the method's own (`shadow::method`); here only the values' ranges.

use super::file::{MAX_MEMORY_BUDGET_MB, ShadowsFile};
use crate::error::Result;
use crate::error::ensure_valid;
use crate::settings::{MapFilter, PercentageCloser, ShadowSettings as Settings};

/// The most rings of hexagonal cells a jittered soft shadow takes (12,481 cells).
const MAX_RINGS: u32 = 64;

pub fn from_file(s: &ShadowsFile) -> Result<Settings> {
    ensure_valid!(
        (1..=8192).contains(&s.map_resolution),
        "shadows.map_resolution",
        "shadows.map_resolution must be between 1 and 8192, got {}",
        s.map_resolution
    );
    ensure_valid!(
        (1..=MAX_MEMORY_BUDGET_MB).contains(&s.max_memory_mb),
        "shadows.max_memory_mb",
        "shadows.max_memory_mb must be from 1 to {MAX_MEMORY_BUDGET_MB} (1 TiB), got {}",
        s.max_memory_mb
    );
    ensure_valid!(
        s.map_bias.is_finite() && s.map_bias >= 0.0,
        "shadows.map_bias",
        "shadows.map_bias must be a non-negative number"
    );
    ensure_valid!(
        s.pcf % 2 == 1 && s.pcf <= 15,
        "shadows.pcf",
        "shadows.pcf must be an odd kernel size from 1 to 15, got {}",
        s.pcf
    );
    if let Some(filter @ (MapFilter::None | MapFilter::PercentageCloser)) = s.map_filter {
        let name = match filter {
            MapFilter::None => "none",
            MapFilter::Box | MapFilter::PercentageCloser => "percentage-closer",
        };
        ensure_valid!(
            s.pcf == 1,
            "shadows.pcf",
            "shadows.pcf = {} is the box filter's kernel, which map_filter = \"{name}\" does not use: set map_filter = \"box\", or leave pcf out",
            s.pcf
        );
    }
    let n = s.pcf_samples.isqrt();
    ensure_valid!(
        (1..=1024).contains(&s.pcf_samples) && n * n == s.pcf_samples,
        "shadows.pcf_samples",
        "shadows.pcf_samples must be a square number from 1 to 1024 (n x n jittered points), got {}",
        s.pcf_samples
    );
    let [low, high] = s.pcf_bias;
    ensure_valid!(
        low.is_finite() && high.is_finite() && 0.0 <= low && low <= high,
        "shadows.pcf_bias",
        "shadows.pcf_bias must be [min, max] with 0 <= min <= max (slope-scaled texels), got [{low}, {high}]"
    );
    ensure_valid!(
        s.pcf_scale.is_finite() && s.pcf_scale > 0.0 && s.pcf_scale <= 64.0,
        "shadows.pcf_scale",
        "shadows.pcf_scale must be a positive number up to 64, got {}",
        s.pcf_scale
    );
    ensure_valid!(
        s.pcf_min_size.is_finite() && (0.0..=64.0).contains(&s.pcf_min_size),
        "shadows.pcf_min_size",
        "shadows.pcf_min_size must be between 0 and 64 texels, got {}",
        s.pcf_min_size
    );
    ensure_valid!(
        (1..=64).contains(&s.light_samples),
        "shadows.light_samples",
        "shadows.light_samples must be between 1 and 64 (N x N samples per extended light), got {}",
        s.light_samples
    );
    ensure_valid!(
        (1..=1024).contains(&s.light_points),
        "shadows.light_points",
        "shadows.light_points must be between 1 and 1024 (points replacing each light), got {}",
        s.light_points
    );
    ensure_valid!(
        s.rings <= MAX_RINGS,
        "shadows.rings",
        "shadows.rings must be at most {MAX_RINGS} (1 + 3K(K + 1) cells, one shadow ray each per sample), got {}",
        s.rings
    );
    Ok(Settings {
        light_points: s.light_points,
        rings: s.rings,
        sampling: s.sampling,
        seed: s.seed,
        light_samples: s.light_samples,
        method: s.method,
        map_resolution: s.map_resolution,
        map_bias: s.map_bias,
        map_filter: s.map_filter.unwrap_or(match s.pcf {
            1 => MapFilter::None,
            _ => MapFilter::Box,
        }),
        pcf: s.pcf,
        percentage_closer: PercentageCloser {
            samples: s.pcf_samples,
            bias: s.pcf_bias,
            scale: s.pcf_scale,
            min_size: s.pcf_min_size,
        },
        post_pass: s.post_pass,
        self_shadow: s.self_shadow,
        max_memory_mb: s.max_memory_mb,
    })
}
