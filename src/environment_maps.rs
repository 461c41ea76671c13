//! Environment maps as images: the six cube faces of a scene rendered from a point
//! by lumiere itself (Greene 1986's acquisition, with renders for photographs), and
//! a map converted from one layout to another. What `lumiere envmap` writes.

use crate::error::{Error, Result};
use crate::image_io::Image;
use crate::render::capture_cube;
use crate::scene::Scene;
use crate::settings::Filter;
use crate::texture::Texels;
use crate::texture::environment::EnvironmentMap;
use glam::DVec3;

pub use crate::texture::environment::Layout;

/// The cube map of `scene` seen from `at`, `size` texels a side, without the
/// objects `hidden` (indices into the scene's objects: the reflector), written in
/// `layout` at `size`.
pub fn capture(
    scene: &Scene,
    at: DVec3,
    size: u32,
    hidden: &[usize],
    layout: Layout,
) -> Result<Image> {
    let cube = capture_cube(scene, at, size, hidden, Filter::Trilinear)?;
    Ok(image_of(&in_layout(cube, layout, size)))
}

/// `image`, a map laid out as `from`, laid out as `to` at `size` texels (its own
/// size when `None`): the size of a cube face's side, a sphere map's side or a
/// latitude-longitude map's height. `Err` says what is wrong with the image's shape.
pub fn convert(image: Image, from: Layout, to: Layout, size: Option<u32>) -> Result<Image> {
    let texels = Texels {
        width: image.width,
        height: image.height,
        texels: image.pixels,
    };
    let map = EnvironmentMap::from_image(from, texels, Filter::Trilinear).map_err(Error::Scene)?;
    let size = size.unwrap_or(map.size());
    Ok(image_of(&in_layout(map, to, size)))
}

fn in_layout(map: EnvironmentMap, layout: Layout, size: u32) -> EnvironmentMap {
    if map.layout() == layout && map.size() == size {
        map
    } else {
        map.convert(layout, size)
    }
}

fn image_of(map: &EnvironmentMap) -> Image {
    let texels = map.to_texels();
    Image {
        width: texels.width,
        height: texels.height,
        pixels: texels.texels,
    }
}
