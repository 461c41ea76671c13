//! lumiere's checks in one test crate, its modules mirroring src/: each method
//! against an exact or independent reference, its geometric core as properties,
//! the command line, the viewer and the project as a user meets them. `support`
//! holds what they share (the binary launcher, scene builders, the browser). The
//! golden images are checked by their own harness (tests/golden.rs).

mod support;

mod cli;
mod export;
mod geometry;
mod global;
mod image_io;
mod load;
mod media;
mod project;
mod radiosity;
mod raster;
mod render;
mod scene;
mod shading;
mod shadow;
mod texture;
mod viewer;
