//! Materials from the scene file and from MTL files.

use super::file::MaterialFile;
use super::tables::named;
use super::validate::colour;
use super::{Bump, Material, textures};
use crate::error::ensure_valid;
use crate::error::{Error, Result};
use glam::Vec3;
use std::collections::HashMap;

pub fn from_file(
    name: &str,
    m: &MaterialFile,
    textures: &HashMap<String, usize>,
    environments: &HashMap<String, usize>,
    traced: bool,
) -> Result<Material> {
    let what = |key: &str| format!("materials.{name}.{key}");
    let texture = |key: &str, given: &Option<String>| -> Result<Option<usize>> {
        given
            .as_ref()
            .map(|t| named(textures, t, &what(key), "texture"))
            .transpose()
    };
    let bump = match (texture("bump_texture", &m.bump_texture)?, m.bump_height) {
        (Some(texture), height) => {
            let height = height.unwrap_or(0.01);
            ensure_valid!(
                height.is_finite(),
                what("bump_height"),
                "{} must be a finite number",
                what("bump_height")
            );
            Some(Bump { texture, height })
        }
        (None, Some(_)) => {
            return Err(Error::invalid(
                what("bump_height"),
                format!("{} needs a bump_texture", what("bump_height")),
            ));
        }
        (None, None) => None,
    };
    let mapping = m
        .mapping
        .as_ref()
        .map(|mapping| textures::mapping(&what("mapping"), mapping))
        .transpose()?;
    let material = Material {
        name: name.to_string(),
        diffuse: colour(&what("diffuse"), m.diffuse)?,
        specular: colour(&what("specular"), m.specular)?,
        exponent: m.exponent as f32,
        emission: colour(&what("emission"), m.emission)?,
        diffuse_texture: texture("diffuse_texture", &m.diffuse_texture)?,
        specular_texture: texture("specular_texture", &m.specular_texture)?,
        bump,
        mapping,
        interpolation: m.interpolation,
        mirror: colour(&what("mirror"), m.mirror)?,
        gloss: m.gloss,
        ior: m.ior,
        transmittance: colour(&what("transmittance"), m.transmittance)?,
        translucence: colour(&what("translucence"), m.translucence)?,
        environment: m
            .environment
            .as_ref()
            .map(|e| named(environments, e, &what("environment"), "environment"))
            .transpose()?,
    };
    if let Some(gloss) = m.gloss {
        ensure_valid!(
            gloss.is_finite() && gloss >= 1.0,
            what("gloss"),
            "{} must be a number of at least 1 (the exponent n of the glossy lobe cos^n about the mirror direction; leave it out for an ideal mirror), got {gloss}",
            what("gloss")
        );
        ensure_valid!(
            material.mirror.max_element() > 0.0,
            what("gloss"),
            "{}: gloss spreads the mirror's reflection; give the material a mirror reflectance",
            what("gloss")
        );
    }
    if let Some(ior) = m.ior {
        ensure_valid!(
            ior.is_finite() && ior > 0.0,
            what("ior"),
            "{} must be a positive number (1.0 for vacuum, 1.33 water, 1.5 glass), got {ior}",
            what("ior")
        );
    }
    let shows_environment = material.mirror.max_element() > 0.0
        || material.transmittance.max_element() > 0.0
        || material.ior.is_some();
    // Under `[global]` reflected and refracted rays see the scene itself; an
    // environment map is then only what rays leaving the scene see.
    ensure_valid!(
        traced || !shows_environment || material.environment.is_some(),
        what("environment"),
        "{}: mirror, ior and transmittance look up an environment map; name one (or trace rays with a [global] method)",
        what("environment")
    );
    ensure_valid!(
        shows_environment || material.environment.is_none(),
        what("environment"),
        "{}: the environment is seen through mirror, or ior with transmittance; give one",
        what("environment")
    );
    ensure_valid!(
        traced || material.transmittance.max_element() == 0.0 || material.ior.is_some(),
        what("transmittance"),
        "{}: refraction needs the material's index of refraction, `ior`",
        what("transmittance")
    );
    ensure_valid!(
        traced || material.translucence.max_element() == 0.0,
        what("translucence"),
        "{}: diffuse transmission is Rushmeier & Torrance's radiosity; set [global] method = \"rushmeier-torrance\"",
        what("translucence")
    );
    ensure_valid!(
        m.exponent.is_finite() && m.exponent >= 0.0,
        what("exponent"),
        "{} must be a non-negative number",
        what("exponent")
    );
    check_energy(&material)?;
    Ok(material)
}

/// An MTL material: Kd, Ks, Ns and Ke.
pub fn from_mtl(m: &tobj::Material) -> Result<Material> {
    let rgb = |c: Option<[f64; 3]>| c.map_or(Vec3::ZERO, |c| glam::DVec3::from(c).as_vec3());
    let material = Material {
        name: m.name.clone(),
        diffuse: rgb(m.diffuse),
        specular: rgb(m.specular),
        exponent: m.shininess.unwrap_or(1.0) as f32,
        emission: rgb(m.emissive),
        ..Default::default()
    };
    if ![material.diffuse, material.specular, material.emission]
        .iter()
        .all(|c| c.is_finite() && c.min_element() >= 0.0)
    {
        return Err(Error::Scene(format!(
            "MTL material {} has a negative or non-finite colour",
            m.name
        )));
    }
    check_energy(&material)?;
    Ok(material)
}

/// A surface may not reflect more than it receives.
fn check_energy(m: &Material) -> Result<()> {
    let total = m.diffuse + m.specular;
    if total.max_element() > 1.0 {
        return Err(Error::Scene(format!(
            "material {}: diffuse + specular reflectance exceeds 1 ({total})",
            m.name
        )));
    }
    for (key, part) in [("mirror", m.mirror), ("transmittance", m.transmittance)] {
        let total = m.diffuse + m.specular + m.translucence + part;
        if total.max_element() > 1.0 {
            return Err(Error::Scene(format!(
                "material {}: diffuse + specular + translucence + {key} exceeds 1 ({total})",
                m.name
            )));
        }
    }
    // Without an index of refraction nothing weighs reflection against
    // transmission (Fresnel): every part is a constant share of the light.
    let total = m.diffuse + m.specular + m.mirror + m.transmittance + m.translucence;
    if m.ior.is_none() && total.max_element() > 1.0 {
        return Err(Error::Scene(format!(
            "material {}: diffuse + specular + mirror + transmittance + translucence exceeds 1 ({total})",
            m.name
        )));
    }
    Ok(())
}
