//! H. E. Rushmeier & K. E. Torrance, "Extending the radiosity method to include
//! specularly reflecting and translucent materials", ACM TOG 9(1), 1990: the
//! two-pass method with pass 1 extended to specular transmission through thin panes
//! and diffuse transmission through translucent panels (`crate::radiosity`'s
//! windows follow both). Chosen by `[global] method = "rushmeier-torrance"`; it
//! keeps what the two-pass method keeps.

use super::solution::lights_beside_the_solution;
use super::two_pass::{BUFFERS, KEYS, KeptTwoPass, needs_a_solution};
use super::{Declaration, Integrator, Role};
use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::settings::GlobalMethod;

pub static DECLARATION: Declaration = Declaration {
    integrator: Integrator::RushmeierTorrance,
    name: "rushmeier-torrance",
    global_method: Some(GlobalMethod::RushmeierTorrance),
    entry: "rushmeier-torrance",
    keys: KEYS,
    buffers: BUFFERS,
    role: Role::ScanLine,
    direct_lights: lights_beside_the_solution,
    check,
    kept: || Box::new(KeptTwoPass::new()),
};

/// Refuses a scene without `[radiosity]`, and panes with an index of refraction:
/// Rushmeier & Torrance's panes are thin (light goes straight through).
fn check(scene: &Scene) -> Result<()> {
    needs_a_solution(scene, DECLARATION.name)?;
    match scene
        .materials
        .iter()
        .find(|m| m.transmittance.max_element() > 0.0 && m.ior.is_some())
    {
        Some(m) => Err(Error::invalid(
            format!("materials.{}.ior", m.name),
            format!(
                "materials.{}.ior: Rushmeier & Torrance's panes are thin (light goes straight through): leave ior out",
                m.name
            ),
        )),
        None => Ok(()),
    }
}
