//! Scenes (src/scene): glTF and OBJ, ray queries.

mod gltf;
mod ray_queries;
