//! Shading: the light model (Lambert diffuse, normalised Phong specular), the exact
//! irradiance of polygonal emitters (Lambert's contour formula) and of spheres
//! (`sphere_form_factor`), the three shading modes (flat, Gouraud, Phong) and the pass that turns a visible-surface buffer
//! into linear radiance, with textures and bump maps (`textured`).

pub use crate::geometry::lambert_contour;
pub mod environment_mapping;
pub mod light_model;
pub mod optics;
mod pass;
mod point_lanes;
pub mod sphere_form_factor;
mod textured;

pub use pass::{FrameShading, POST_PASS_SHADE, radiance_at, vertex_colors};
