//! lumiere: a software scan-line renderer that reproduces the classic rendering
//! algorithms literally, one module per paper.
//!
//! A [`Scene`] comes from a catalogue entry, a scene file or a TOML string, with the
//! command line's `key=value` overrides; a [`Renderer`] keeps the view-independent
//! work of its frames (shadow maps, shadow polygons and volumes, a radiosity
//! solution) while its camera, lights and shadow settings change; a [`Frame`] holds
//! the linear radiance [`Image`] and the named buffers a method makes (visibility,
//! depth, shadow-volume counts, item buffers).
//!
//! ```
//! use lumiere::{Renderer, load_scene};
//!
//! // The point-lit Cornell box at 64 x 64, shadowed by Crow's shadow volumes.
//! let sets = ["camera.width=64", "camera.height=64", "shadows.method=shadow-volumes"];
//! let renderer = Renderer::new(load_scene("cornell-box-point", &sets.map(String::from))?);
//! let frame = renderer.render_with_buffers(&["shadow-volume-counts-0".to_string()])?;
//! let counts = frame.buffer("shadow-volume-counts-0").expect("Crow's counts");
//! assert_eq!((frame.image.width, counts.width), (64, 64));
//! # Ok::<(), lumiere::Error>(())
//! ```
//!
//! The flow of a frame: the scene is clipped and projected, swept by Watkins's
//! scan-line pass in bands of rows into visible samples, each shadowed light's method
//! answers how much of the light reaches each sample, and shading weighs each light
//! by that answer; the box filter gives the pixels. Radiosity, Whitted's ray tracing
//! and the two-pass method are the other integrators over the same passes.
//!
//! Beside the root's items, public modules hold the instruments that look inside
//! a method ([`form_factors`], [`shadow_polygons`], [`environment_maps`],
//! [`radiosity_solution`], [`visible_surface_pass`]) and the viewer's engine
//! ([`viewer`]). The modules behind them are hidden: the checks' door, not an API.

#![warn(missing_docs)]
// A new variant of a method or kind enum must be placed by hand wherever its
// enum is matched: no arm stands for "every other variant" (the unit tests may
// expect one variant and fail on the rest).
#![cfg_attr(not(test), deny(clippy::wildcard_enum_match_arm))]

pub mod catalogue;
pub mod environment_maps;
mod error;
pub mod export;
// The modules behind the API, one per layer or family of papers. Public for the
// checks in tests/, which look inside a method (a hemi-cube's item buffer, Crow's
// counts, a convex subtraction), and hidden from the documentation: not a stable
// API. Nothing but the checks names them (tests/suite/project/layers.rs holds the
// command line, the Python package, the web crate and the examples to the items
// above and below).
#[doc(hidden)]
pub mod geometry;
#[doc(hidden)]
pub mod global;
#[doc(hidden)]
pub mod image_io;
mod load;
#[doc(hidden)]
pub mod media;
#[doc(hidden)]
pub mod radiosity;
pub mod radiosity_solution;
#[doc(hidden)]
pub mod raster;
#[doc(hidden)]
pub mod render;
#[doc(hidden)]
pub mod scene;
pub mod settings;
#[doc(hidden)]
pub mod shading;
#[doc(hidden)]
pub mod shadow;
#[doc(hidden)]
pub mod texture;
pub mod viewer;
pub mod visible_surface_pass;

/// The form factors between a scene's polygons, as `lumiere form-factors` prints
/// them: each polygon one patch, by the hemi-cube, Nusselt's analog or the
/// analytic point-to-polygon formula.
pub mod form_factors {
    pub use crate::radiosity::form_factors::{MatrixPatch, PatchMatrix, polygon_form_factors};
    pub use crate::settings::FormFactorMethod;
}

/// Every polygon's lit and shadowed parts under a point light, as Atherton, Weiler
/// & Greenberg's method attaches them (`lumiere shadow-polygons`).
pub mod shadow_polygons {
    pub use crate::shadow::shadow_polygon_areas::{ReceiverShadows, receiver_shadows};
}

/// The vector types of the scene's fields (`DVec3` positions, `Vec3` colours).
pub use glam;

pub use error::{Error, FileOp, OverBudget, Result, Unsupported, one_line};
pub use image_io::{
    Animation as GifAnimation, Buffer, BufferData, Candidate, Comparison, Flip, FlipRange,
    Format as ImageFormat, FuzzyMatch, Image, Moments, MomentsSum, NO_ID, StagedDirectory,
    StatisticalTest, ToleranceCheck, apply_mask, compare as compare_images, decode as decode_image,
    default_pixels_per_degree, difference_image, dimensions as image_dimensions, edge_mask,
    encode as encode_image, flip, fuzzy_match, load as read_image, read_file, refuse_non_radiance,
    remove_unfinished, save as write_image, statistical_test, strip as comparison_strip,
    tolerance_check, write_atomically,
};
pub use load::{load_scene, scene_from_files, scene_from_toml};
pub use render::{BufferInfo, Frame, Prepasses, Renderer, render};
/// The largest image side a scene may ask for, in pixels.
pub use scene::MAX_SIDE as MAX_IMAGE_SIDE;
pub use scene::{
    Camera, DistantLight, Environment, EnvironmentSource, Light, LightKind, Material, Object,
    PointLight, Polygon, PolygonLight, Reach, Scene, SphereLight, SpotDistribution, SpotLight,
    Vertex,
};
