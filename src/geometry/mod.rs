//! Polygons and clipping, shared by every pass that works at object precision;
//! the bounding volume hierarchy; Lambert's contour formula.

pub mod bvh;
pub mod central_projection;
pub(crate) mod contour_sweep;
pub mod convex;
pub mod disc;
pub mod kd_tree;
pub mod lambert_contour;
pub mod plane;
pub mod polygon;
pub(crate) mod region;
pub mod sampling;
pub mod sutherland_hodgman;
pub mod weiler_atherton;
