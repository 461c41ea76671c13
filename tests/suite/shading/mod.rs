//! Shading (src/shading): lights and optics against closed forms.

mod lights;
mod optics;
