//! What the fuzz targets share: files held in memory as a scene's directory, and the
//! OBJ/MTL pair and scene they start from.

use std::collections::HashMap;
use std::path::Path;

/// A scene's directory in memory: `m.obj` and `m.mtl`.
pub struct Files(HashMap<&'static str, Vec<u8>>);

impl Files {
    pub fn new(obj: &[u8], mtl: &[u8]) -> Files {
        Files(HashMap::from([
            ("m.obj", obj.to_vec()),
            ("m.mtl", mtl.to_vec()),
        ]))
    }
}

impl lumiere::scene::resources::Resources for Files {
    fn read(&self, path: &Path) -> lumiere::Result<Vec<u8>> {
        self.0
            .get(path.to_str().unwrap_or(""))
            .cloned()
            .ok_or_else(|| lumiere::Error::Scene(format!("no file {}", path.display())))
    }
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
