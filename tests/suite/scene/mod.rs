//! Scenes (src/scene): glTF and OBJ, ray queries.

mod gltf;
mod lights;
mod ray_queries;
