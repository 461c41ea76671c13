//! The ground truth of a biased entry: the same scene rendered by Kajiya's path
//! tracer (`[global] method = "path-tracing"`), the mean and variance of its
//! renders over seeds, so that a physically based renderer is held to what the
//! scene's light is, not to what radiosity's mesh or sixteen points on a light
//! make of it.
//!
//! Which entries have one, and with which transport:
//! - radiosity, the two-pass methods and the photon map: every path (the light
//!   their solutions approximate; Mitsuba's export of them asks for unbounded
//!   paths too);
//! - soft shadows from a sampled light (ray casting under an extended light,
//!   Brotman & Badler's points, Cook's jittered cells) and shadow maps (their
//!   depth bias and texels): direct light only, paths of one surface (the
//!   transport the entry and its Mitsuba export model);
//! - environment mapping, where the map's surroundings are the scene's (the
//!   backdrop, or a map captured from inside the scene): Whitted's tracer, whose
//!   rays meet what the map only approximates (the object itself, parallax,
//!   both faces of a refracting object), deterministic, held by FLIP;
//! - the path-tracing entries: their reference is the ground truth already;
//! - a participating medium (light volumes), translucent panels, glossy mirrors,
//!   bump maps, or an environment map of surroundings the scene does not hold:
//!   none, for the tracers carry no medium, no diffuse transmission, no glossy
//!   lobe about the mirror and no perturbed normals, and would trace into
//!   emptiness where the map shows a world (the manifest says which); nor lights
//!   that cast no shadows (`shadows.method = "none"`);
//! - every other entry is exact for what it models: its reference is the answer.

use super::manifest::Transport;
use anyhow::{Context, Result};
use lumiere::glam::Vec3;
use lumiere::settings::{GlobalMethod, ShadowMethod};
use lumiere::{EnvironmentSource, Light, Scene};
use lumiere::{Moments, MomentsSum, Renderer, scene_from_toml};

/// What a physically based renderer is held to for one entry.
#[derive(Clone, Debug, PartialEq)]
pub enum Plan {
    /// A path-traced ground truth with this transport, for an entry whose method
    /// is biased by `biased_by`.
    Trace {
        transport: Transport,
        biased_by: String,
    },
    /// The reference is a path tracer's: the ground truth itself.
    Itself,
    /// A biased entry the path tracer cannot give the answer for, and why.
    Unavailable(String),
    /// An exact method: the reference is the answer.
    Exact,
}

/// The plan for `scene` (an entry's scene as its reference renders it).
pub fn plan(scene: &Scene) -> Plan {
    // The integrator the scene chooses: `[global] method`, else radiosity when it
    // has `[radiosity]`, else direct light.
    let method = scene.global.as_ref().map(|g| g.method);
    if method == Some(GlobalMethod::PathTracing) {
        return Plan::Itself;
    }
    let used = |index: usize| scene.polygons.iter().any(|p| p.material == index);
    let materials = || {
        scene
            .materials
            .iter()
            .enumerate()
            .filter(move |(i, _)| used(*i))
            .map(|(_, m)| m)
    };
    if materials().any(|m| m.translucence != Vec3::ZERO) {
        return Plan::Unavailable(
            "translucent panels (diffuse transmission): the path tracer carries none".into(),
        );
    }
    if materials().any(|m| m.gloss.is_some()) {
        return Plan::Unavailable(
            "a glossy mirror (`gloss`): the path tracer's mirrors are ideal".into(),
        );
    }
    if materials().any(|m| m.bump.is_some()) {
        return Plan::Unavailable("bump maps: the tracers do not perturb normals".into());
    }
    let solves_interreflection = match method {
        Some(m) => matches!(
            m,
            GlobalMethod::TwoPass | GlobalMethod::RushmeierTorrance | GlobalMethod::PhotonMap
        ),
        None => scene.radiosity.is_some(),
    };
    if solves_interreflection {
        return Plan::Trace {
            transport: Transport::Full,
            biased_by: method.map_or("radiosity", |m| m.name()).to_string(),
        };
    }
    if scene.medium.is_some() {
        return Plan::Unavailable(
            "a participating medium (light volumes): the path tracer carries none".into(),
        );
    }
    // An environment map has a traced answer where its surroundings are the
    // scene's: the backdrop rays that leave the scene meet, or a map captured
    // from the scene itself.
    let traced_answer = |e: usize| {
        scene.render.backdrop == Some(e)
            || matches!(scene.environments[e].source, EnvironmentSource::Capture(_))
    };
    let mapped: Vec<usize> = materials().filter_map(|m| m.environment).collect();
    if !mapped.is_empty() {
        if !mapped.iter().all(|&e| traced_answer(e)) {
            return Plan::Unavailable(
                "an environment map of surroundings the scene does not hold: no traced answer"
                    .into(),
            );
        }
        return Plan::Trace {
            transport: Transport::Whitted,
            biased_by: "environment mapping".into(),
        };
    }
    if method == Some(GlobalMethod::RayTracing) {
        return Plan::Exact;
    }
    let extended = scene
        .lights
        .iter()
        .any(|l| matches!(l, Light::Polygon(_) | Light::Sphere(_)));
    let method = scene.shadows.method;
    if method == ShadowMethod::None && !scene.lights.is_empty() {
        return Plan::Unavailable(
            "shadows.method = \"none\": its lights cast no shadows, which a physically based renderer's do".into(),
        );
    }
    let biased = match method {
        ShadowMethod::SoftShadowVolumes
        | ShadowMethod::JitteredSoftShadows
        | ShadowMethod::ShadowMap => true,
        ShadowMethod::RayCast => extended,
        _ => false,
    };
    if biased {
        Plan::Trace {
            transport: Transport::Direct,
            biased_by: format!("shadows.method = \"{}\"", method.name()),
        }
    } else {
        Plan::Exact
    }
}

/// The entry's scene `table` (extends resolved, its size set) made a tracer's:
/// its radiosity and global settings and its shadow method replaced; for the
/// path tracer `paths` × `paths` paths a pixel, one surface a path for direct
/// transport; Whitted's tracer with its defaults.
pub fn scene_table(table: &toml::Table, transport: Transport, paths: u32) -> toml::Table {
    let mut table = table.clone();
    table.remove("radiosity");
    table.remove("shadows");
    let mut global = toml::Table::new();
    if transport == Transport::Whitted {
        global.insert("method".into(), "ray-tracing".into());
    } else {
        global.insert("method".into(), "path-tracing".into());
        global.insert("samples".into(), (paths as i64).into());
    }
    if transport == Transport::Direct {
        global.insert("depth".into(), 1.into());
    }
    table.insert("global".into(), toml::Value::Table(global));
    if let Some(render) = table.get_mut("render").and_then(|r| r.as_table_mut()) {
        // The tracer antialiases by its paths over the pixel.
        render.remove("supersample");
    }
    table
}

/// One render of `text` (a `scene_table` as TOML) with `overrides`.
fn render_text(text: &str, overrides: &[String]) -> Result<lumiere::Image> {
    let scene = scene_from_toml(text, overrides).context("the ground truth's scene")?;
    Ok(Renderer::new(scene).render()?)
}

fn to_text(table: &toml::Table) -> Result<String> {
    toml::to_string(table).context("writing the ground truth's scene as TOML")
}

/// Whitted's render of `table` (from `scene_table`): deterministic, one render.
pub fn render_once(table: &toml::Table) -> Result<lumiere::Image> {
    render_text(&to_text(table)?, &[])
}

/// The mean and variance over `renders` seeds of the path tracer's renders of
/// `table` (from `scene_table`).
pub fn render(table: &toml::Table, renders: u32) -> Result<Moments> {
    let text = to_text(table)?;
    let mut sum: Option<MomentsSum> = None;
    for seed in 0..renders {
        let image = render_text(&text, &[format!("shadows.seed={seed}")])?;
        sum.get_or_insert_with(|| MomentsSum::new(image.width, image.height))
            .add(&image)?;
    }
    Ok(sum.context("no renders")?.finish()?)
}
