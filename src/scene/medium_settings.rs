//! `[medium]` checked and turned into `MediumSettings`.

use super::file::MediumFile;
use crate::error::Result;
use crate::error::ensure_valid;
use crate::settings::{MediumSettings, PhaseFunction};

/// The most Gauss–Legendre nodes per piece of a lit interval.
pub const MAX_NODES: u32 = 64;

pub fn from_file(m: &MediumFile) -> Result<MediumSettings> {
    ensure_valid!(
        m.extinction.is_finite() && m.extinction >= 0.0,
        "medium.extinction",
        "medium.extinction must be a non-negative number (per scene unit), got {}",
        m.extinction
    );
    ensure_valid!(
        m.albedo.is_finite() && (0.0..=1.0).contains(&m.albedo),
        "medium.albedo",
        "medium.albedo must be between 0 and 1 (the scattered share of what is removed), got {}",
        m.albedo
    );
    ensure_valid!(
        m.g.is_finite() && m.g.abs() < 1.0,
        "medium.g",
        "medium.g must be strictly between -1 and 1, got {}",
        m.g
    );
    ensure_valid!(
        m.g == 0.0 || m.phase == PhaseFunction::HenyeyGreenstein,
        "medium.g",
        "medium.g is Henyey-Greenstein's asymmetry: set phase = \"henyey-greenstein\" to use it"
    );
    ensure_valid!(
        (1..=MAX_NODES).contains(&m.nodes),
        "medium.nodes",
        "medium.nodes must be between 1 and {MAX_NODES}, got {}",
        m.nodes
    );
    let extent = match &m.extent {
        None => None,
        Some(e) => {
            ensure_valid!(
                e.min.iter().chain(&e.max).all(|v| v.is_finite())
                    && (0..3).all(|i| e.min[i] < e.max[i]),
                "medium.extent",
                "medium.extent needs finite corners with min below max on every axis, got {:?} and {:?}",
                e.min,
                e.max
            );
            Some((e.min, e.max))
        }
    };
    let march_step = m.march_step.unwrap_or(0.0);
    ensure_valid!(
        march_step.is_finite() && march_step >= 0.0,
        "medium.march_step",
        "medium.march_step must be a positive length (0: a 500th of the scene's size), got {march_step}"
    );
    ensure_valid!(
        march_step == 0.0 || m.method == crate::settings::MediumMethod::RayMarching,
        "medium.march_step",
        "medium.march_step is ray marching's step; light volumes integrate each lit interval without one (set method = \"ray-marching\" to march)"
    );
    ensure_valid!(
        m.max_march_steps.is_finite() && m.max_march_steps >= 1.0,
        "medium.max_march_steps",
        "medium.max_march_steps must be a count of at least 1, got {}",
        m.max_march_steps
    );
    Ok(MediumSettings {
        extinction: m.extinction,
        albedo: m.albedo,
        phase: m.phase,
        g: m.g,
        extent,
        method: m.method,
        nodes: m.nodes,
        march_step,
        max_march_steps: m.max_march_steps,
    })
}
