//! The shadow methods (src/shadow): each against an exact or independent method,
//! their geometric cores as properties, and the registry.

mod hard;
mod independent;
mod percentage_closer;
mod registry;
mod sampled_soft;
mod shadow_polygons;
mod soft_geometry;
mod soft_ray_casting;
mod umbra_penumbra;
