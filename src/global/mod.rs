//! Global illumination: the methods that follow light past its first bounce off
//! specular surfaces.
//!
//! - `whitted`: recursive ray tracing (Whitted 1980), on `traced_scene` (polygons
//!   and analytic spheres) with the local terms of `local`;
//! - `two_pass`: the view-dependent second pass of Wallace, Cohen & Greenberg 1987
//!   and of Rushmeier & Torrance 1990, rays from the eye off specular surfaces that
//!   read the first pass's radiosity (`radiosity::windows` is the first pass's
//!   extension through mirrors and panes);
//! - `final_gather`: the view pass that gathers the indirect light from the
//!   solution at visible points (Reichert 1992; Lischinski, Tampieri & Greenberg
//!   1993), through `irradiance_cache` (Ward, Rubinstein & Clear 1988; Ward &
//!   Heckbert 1992); `solution_radiance` reads the solution where rays land;
//! - `path_tracing`: the rendering equation by path tracing (Kajiya 1986), the
//!   ground truth the others are measured against;
//! - `photon_map` and `photon_rendering`: Jensen's photon maps (1996), photons
//!   shot from the lights into a balanced kd-tree, read by the final gather and,
//!   for caustics, directly;
//! - `reflection_frustum`: how the second pass gathers a glossy reflection
//!   (Wallace, Cohen & Greenberg 1987).

pub mod final_gather;
pub mod irradiance_cache;
pub mod local;
pub mod path_tracing;
pub mod photon_map;
pub mod photon_rendering;
pub mod precomputed_irradiance;
pub mod reflection_frustum;
pub mod solution_radiance;
pub mod traced_scene;
pub mod two_pass;
pub mod whitted;

pub use traced_scene::TracedScene;
