//! What the fuzz targets share: files held in memory as a scene's directory, and the
//! OBJ/MTL pair and scene they start from.

use lumiere::scene::resources::InMemory;
use std::collections::HashMap;

/// A scene's directory in memory: `m.obj` and `m.mtl`.
pub fn files(obj: &[u8], mtl: &[u8]) -> InMemory {
    InMemory(HashMap::from([
        ("m.obj".to_string(), obj.to_vec()),
        ("m.mtl".to_string(), mtl.to_vec()),
    ]))
}

pub const OBJ: &str = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\nusemtl red\nf 1/1/1 2/2/1 3/3/1 4/1/1\n";
pub const MTL: &str = "newmtl red\nKd 0.6 0.1 0.1\nKe 0 0 0\n";

/// A scene whose one object is `m.obj`.
pub const OBJ_SCENE: &str = r#"
[camera]
eye = [0.0, 1.0, 4.0]
look_at = [0.0, 0.0, 0.0]
fov_y = 40.0
width = 16
height = 12

[materials.grey]
diffuse = [0.5, 0.5, 0.5]

[[lights]]
type = "point"
position = [0.0, 2.0, 0.0]
intensity = [5.0, 5.0, 5.0]

[[objects]]
shape = "obj"
name = "model"
file = "m.obj"
material = "grey"
"#;
