//! Materials from the scene file and from MTL files.

use super::Material;
use super::file::MaterialFile;
use super::validate::colour;
use anyhow::{Result, ensure};
use glam::Vec3;

pub fn from_file(name: &str, m: &MaterialFile) -> Result<Material> {
    let what = |key: &str| format!("materials.{name}.{key}");
    let material = Material {
        name: name.to_string(),
        diffuse: colour(&what("diffuse"), m.diffuse)?,
        specular: colour(&what("specular"), m.specular)?,
        exponent: m.exponent as f32,
        emission: colour(&what("emission"), m.emission)?,
    };
    ensure!(
        m.exponent.is_finite() && m.exponent >= 0.0,
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
    };
    ensure!(
        [material.diffuse, material.specular, material.emission]
            .iter()
            .all(|c| c.is_finite() && c.min_element() >= 0.0),
        "MTL material {} has a negative or non-finite colour",
        m.name
    );
    check_energy(&material)?;
    Ok(material)
}

/// A surface may not reflect more than it receives.
fn check_energy(m: &Material) -> Result<()> {
    let total = m.diffuse + m.specular;
    ensure!(
        total.max_element() <= 1.0,
        "material {}: diffuse + specular reflectance exceeds 1 ({total})",
        m.name
    );
    Ok(())
}
