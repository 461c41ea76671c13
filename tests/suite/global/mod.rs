//! The global methods (src/global): Whitted, the two-pass methods, the final
//! gather, and the whole against Mitsuba 3.

mod final_gather;
mod mitsuba;
mod path_tracing;
mod photon_map;
mod ray_tracing;
mod reflection_frustum;
mod two_pass;
