//! Global illumination: the methods that follow light past its first bounce off
//! specular surfaces.
//!
//! - `whitted`: recursive ray tracing (Whitted 1980), on `traced_scene` (polygons
//!   and analytic spheres) with the local terms of `local`;
//! - `two_pass`: the view-dependent second pass of Wallace, Cohen & Greenberg 1987
//!   and of Rushmeier & Torrance 1990, rays from the eye off specular surfaces that
//!   read the first pass's radiosity (`radiosity::windows` is the first pass's
//!   extension through mirrors and panes).

pub mod local;
pub mod traced_scene;
pub mod two_pass;
pub mod whitted;

pub use traced_scene::TracedScene;
