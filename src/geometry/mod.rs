//! Polygons and clipping, shared by every pass that works at object precision.

pub mod bvh;
pub mod polygon;
pub mod sampling;
pub mod sutherland_hodgman;
pub mod weiler_atherton;
