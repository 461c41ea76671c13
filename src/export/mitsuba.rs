//! Mitsuba 3 XML. Mitsuba shares lumiere's conventions (right-handed, y up,
//! radiance in the pixels, a diffuse BSDF of ρ/π, point lights in W/sr with
//! inverse-square fall-off), so values go over as they are. What must be asked
//! for: a float32 film (the default is float16) with a box filter (the default is
//! Gaussian), and two-sided diffuse surfaces (Mitsuba's are black from behind,
//! lumiere shades both sides). Area emitters are one-sided in both.

use super::{Mesh, MitsubaIntegrator as Integrator, sibling};
use crate::error::{Error, FileOp, Result};
use crate::geometry::polygon::triangulate;
use crate::image_io::{StagedDirectory, refuse_read_only};
use crate::scene::{Light, Scene};
use glam::{DVec3, Vec3};
use std::fmt::Write as _;
use std::path::Path;

fn point(name: &str, p: DVec3) -> String {
    format!(
        r#"<point name="{name}" x="{}" y="{}" z="{}"/>"#,
        p.x, p.y, p.z
    )
}

fn rgb(name: &str, c: Vec3) -> String {
    format!(r#"<rgb name="{name}" value="{}, {}, {}"/>"#, c.x, c.y, c.z)
}

/// Writes the XML at `output` and its meshes in `output`'s `-meshes` folder.
pub(super) fn write(
    scene: &Scene,
    meshes: &[Mesh],
    output: &Path,
    spp: u32,
    integrator: Integrator,
) -> Result<()> {
    // Everything is written before anything is replaced: the meshes into a staging
    // folder that takes the old folder's place whole (no stale mesh of an earlier
    // export stays), the XML inside it until then, moved out last.
    let folder = sibling(output, "-meshes");
    let staged = StagedDirectory::for_replacing(&folder)?;
    let folder_name = folder
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut xml = String::from("<scene version=\"3.0.0\">\n");
    match integrator {
        // Emitter sampling alone: one shadow ray per camera sample.
        Integrator::Direct => xml.push_str(
            "  <integrator type=\"direct\">\n    <integer name=\"emitter_samples\" value=\"1\"/>\n    <integer name=\"bsdf_samples\" value=\"0\"/>\n  </integrator>\n",
        ),
        // Unbounded paths, Russian roulette only after 1000 bounces.
        Integrator::Path => xml.push_str(
            "  <integrator type=\"path\">\n    <integer name=\"max_depth\" value=\"-1\"/>\n    <integer name=\"rr_depth\" value=\"1000\"/>\n  </integrator>\n",
        ),
    }
    let c = &scene.camera;
    let _ = write!(
        xml,
        r#"  <sensor type="perspective">
    <float name="fov" value="{fov}"/>
    <string name="fov_axis" value="y"/>
    <float name="near_clip" value="{near}"/>
    <transform name="to_world">
      <lookat origin="{}, {}, {}" target="{}, {}, {}" up="{}, {}, {}"/>
    </transform>
    <film type="hdrfilm">
      <integer name="width" value="{w}"/>
      <integer name="height" value="{h}"/>
      <rfilter type="box"/>
      <string name="pixel_format" value="rgb"/>
      <string name="component_format" value="float32"/>
    </film>
    <sampler type="stratified">
      <integer name="sample_count" value="{spp}"/>
    </sampler>
  </sensor>
"#,
        c.eye.x,
        c.eye.y,
        c.eye.z,
        c.look_at.x,
        c.look_at.y,
        c.look_at.z,
        c.up.x,
        c.up.y,
        c.up.z,
        fov = c.fov_y,
        near = c.near,
        w = c.width,
        h = c.height,
    );
    for (k, mesh) in meshes.iter().enumerate() {
        let material = &scene.materials[mesh.material];
        let file = format!("{k:03}.obj");
        std::fs::write(staged.path(&file), obj(mesh))
            .map_err(|e| Error::io(FileOp::Write, &folder.join(&file), e))?;
        let _ = writeln!(
            xml,
            "  <shape type=\"obj\" id=\"{k:03}\">\n    <string name=\"filename\" value=\"{folder_name}/{file}\"/>\n    <boolean name=\"face_normals\" value=\"{}\"/>",
            mesh.faceted
        );
        let _ = writeln!(xml, "    <!-- material {} -->", escape(&material.name));
        if let Some(ior) = material.ior {
            // Glass: Fresnel's reflection tinted by the mirror colour (white when
            // unset) and the transmitted rest by the transmittance, as lumiere's.
            let tint = if material.mirror == Vec3::ZERO {
                Vec3::ONE
            } else {
                material.mirror
            };
            let _ = writeln!(
                xml,
                "    <bsdf type=\"dielectric\">\n      <float name=\"int_ior\" value=\"{ior}\"/>\n      <float name=\"ext_ior\" value=\"1\"/>\n      {}\n      {}\n    </bsdf>",
                rgb("specular_reflectance", tint),
                rgb("specular_transmittance", material.transmittance)
            );
        } else if material.mirror != Vec3::ZERO {
            let _ = writeln!(
                xml,
                "    <bsdf type=\"conductor\">\n      <string name=\"material\" value=\"none\"/>\n      {}\n    </bsdf>",
                rgb("specular_reflectance", material.mirror)
            );
        } else {
            let _ = writeln!(
                xml,
                "    <bsdf type=\"twosided\">\n      <bsdf type=\"diffuse\">\n        {}\n      </bsdf>\n    </bsdf>",
                rgb("reflectance", material.diffuse)
            );
        }
        if material.is_emitter() {
            let _ = writeln!(
                xml,
                "    <emitter type=\"area\">\n      {}\n    </emitter>",
                rgb("radiance", material.emission)
            );
        }
        xml.push_str("  </shape>\n");
    }
    for light in &scene.lights {
        match light {
            Light::Point(l) => {
                let _ = writeln!(
                    xml,
                    "  <emitter type=\"point\">\n    {}\n    {}\n  </emitter>",
                    point("position", l.position),
                    rgb("intensity", l.intensity)
                );
            }
            Light::Distant(l) => {
                let d = l.direction;
                let _ = writeln!(
                    xml,
                    "  <emitter type=\"directional\">\n    <vector name=\"direction\" x=\"{}\" y=\"{}\" z=\"{}\"/>\n    {}\n  </emitter>",
                    d.x,
                    d.y,
                    d.z,
                    rgb("irradiance", l.irradiance)
                );
            }
            Light::Spot(l) => {
                let target = l.position + l.axis;
                let up = l.axis.any_orthonormal_vector();
                let angle = l.cone_angle.to_degrees();
                let _ = writeln!(
                    xml,
                    "  <emitter type=\"spot\">\n    <transform name=\"to_world\">\n      <lookat origin=\"{}, {}, {}\" target=\"{}, {}, {}\" up=\"{}, {}, {}\"/>\n    </transform>\n    {}\n    <float name=\"cutoff_angle\" value=\"{angle}\"/>\n    <float name=\"beam_width\" value=\"{}\"/>\n  </emitter>",
                    l.position.x,
                    l.position.y,
                    l.position.z,
                    target.x,
                    target.y,
                    target.z,
                    up.x,
                    up.y,
                    up.z,
                    rgb("intensity", l.intensity),
                    angle * 0.999
                );
            }
            Light::Sphere(l) => {
                let _ = writeln!(
                    xml,
                    "  <shape type=\"sphere\">\n    {}\n    <float name=\"radius\" value=\"{}\"/>\n    <bsdf type=\"diffuse\">\n      {}\n    </bsdf>\n    <emitter type=\"area\">\n      {}\n    </emitter>\n  </shape>",
                    point("center", l.centre),
                    l.radius,
                    rgb("reflectance", Vec3::ZERO),
                    rgb("radiance", l.radiance)
                );
            }
            // An emitting polygon: its material's area emitter, above.
            Light::Polygon(_) => {}
        }
    }
    xml.push_str("</scene>\n");
    const XML: &str = ".scene.xml";
    std::fs::write(staged.path(XML), xml).map_err(|e| Error::io(FileOp::Write, output, e))?;
    refuse_read_only(output)?;
    staged.replace()?;
    let xml = folder.join(XML);
    std::fs::rename(&xml, output).map_err(|e| {
        let _ = std::fs::remove_file(&xml);
        Error::io(FileOp::Write, output, e)
    })
}

/// A mesh as OBJ: positions, normals, and each polygon cut into triangles by ear
/// clipping (a concave polygon stays what it was).
fn obj(mesh: &Mesh) -> String {
    let mut text = String::new();
    let mut next = 1;
    for polygon in &mesh.polygons {
        for (p, n) in polygon {
            let _ = writeln!(
                text,
                "v {} {} {}\nvn {} {} {}",
                p.x, p.y, p.z, n.x, n.y, n.z
            );
        }
        let positions: Vec<DVec3> = polygon.iter().map(|v| v.0).collect();
        for [a, b, c] in triangulate(&positions) {
            let (a, b, c) = (next + a, next + b, next + c);
            let _ = writeln!(text, "f {a}//{a} {b}//{b} {c}//{c}");
        }
        next += polygon.len();
    }
    text
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace("--", "- -")
}
