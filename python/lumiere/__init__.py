"""lumiere: the classic rendering algorithms as their papers did them.

Scenes come from the catalogue (``lumiere.catalogue()``), a scene file or TOML
text, with the command line's overrides as keyword arguments or a dict::

    import lumiere
    scene = lumiere.load("cornell-box-point", camera={"width": 256, "height": 256},
                         **{"shadows.method": "shadow-volumes"})
    renderer = lumiere.Renderer(scene)          # keeps its pre-passes between frames
    frame = renderer.render(aovs=["shadow-volume-counts-0"])
    frame.image                                 # float32 H x W x 3, linear radiance
    frame["shadow-volume-counts-0"]             # int32 H x W
    frame.srgb()                                # uint8 H x W x 3, as a PNG shows it

Every error is a ``lumiere.Error`` (``SceneError``, ``OverrideError``,
``ParseError``, ``IoError``, ``ImageError``, ``UnsupportedError``,
``OverBudgetError``) carrying the command line's one-line message.
"""

from ._lumiere import (
    Error,
    Frame,
    ImageError,
    IoError,
    OverBudgetError,
    OverrideError,
    ParseError,
    Renderer,
    Scene,
    SceneError,
    UnsupportedError,
    __version__,
    catalogue,
    compare,
    export,
    form_factors,
    read_image,
    shadow_polygons,
    write_image,
)

load = Scene.load

__all__ = [
    "Error",
    "Frame",
    "ImageError",
    "IoError",
    "OverBudgetError",
    "OverrideError",
    "ParseError",
    "Renderer",
    "Scene",
    "SceneError",
    "UnsupportedError",
    "__version__",
    "catalogue",
    "compare",
    "export",
    "form_factors",
    "load",
    "read_image",
    "shadow_polygons",
    "write_image",
]
