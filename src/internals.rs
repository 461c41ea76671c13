//! The modules behind the public API, one per layer or family of papers. They are
//! public for the tests and the command line's instruments (form-factor tables,
//! shadow-polygon plans, the gallery's plots), which look inside a method; they are
//! not a stable API, and an embedding program should not need them.

#[path = "geometry/mod.rs"]
pub mod geometry;
#[path = "global/mod.rs"]
pub mod global;
#[path = "image_io/mod.rs"]
pub mod image_io;
#[path = "media/mod.rs"]
pub mod media;
#[path = "radiosity/mod.rs"]
pub mod radiosity;
#[path = "raster/mod.rs"]
pub mod raster;
#[path = "render/mod.rs"]
pub mod render;
#[path = "scene/mod.rs"]
pub mod scene;
#[path = "shading/mod.rs"]
pub mod shading;
#[path = "shadow/mod.rs"]
pub mod shadow;
#[path = "texture/mod.rs"]
pub mod texture;
