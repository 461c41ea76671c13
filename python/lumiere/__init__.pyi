"""Type stubs for lumiere (the native module lumiere._lumiere)."""

from os import PathLike
from typing import Any, Dict, List, Literal, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

Override = Union[bool, int, float, str, Sequence[Any], Mapping[str, Any]]

class Error(Exception):
    """Every error lumiere reports; its message is the command line's one line."""

class IoError(Error):
    """A file could not be read or written."""

class ParseError(Error):
    """A scene's TOML does not parse."""

class OverrideError(Error):
    """An override (``key=value``) cannot be applied."""

class SceneError(Error):
    """A scene value or catalogue id that cannot be used."""

class ImageError(Error):
    """An image that cannot be read, or images of different sizes."""

class UnsupportedError(Error):
    """A combination of settings a method does not handle."""

class OverBudgetError(Error):
    """Settings that would need more memory than their budget."""

class Scene:
    """A scene: geometry, materials, lights, camera and method settings."""

    @staticmethod
    def load(
        spec: Union[str, PathLike[str]],
        overrides: Optional[Mapping[str, Override]] = None,
        **kwargs: Override,
    ) -> "Scene":
        """A catalogue entry or scene file (.toml, .gltf, .glb), with overrides:
        the keys of ``--set`` (``**{"camera.width": 256}``) or nested
        (``camera={"width": 256}``)."""
    @staticmethod
    def from_toml(
        text: str, overrides: Optional[Mapping[str, Override]] = None, **kwargs: Override
    ) -> "Scene":
        """A scene from the text of a scene file, with overrides as for ``load``."""
    def with_overrides(
        self, overrides: Optional[Mapping[str, Override]] = None, **kwargs: Override
    ) -> "Scene":
        """This scene with more overrides applied after its own."""
    @property
    def sets(self) -> List[str]:
        """The overrides applied, as ``key=value``, in order."""
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def camera(self) -> Dict[str, Any]:
        """eye, look_at, up, fov_y, width, height."""
    @property
    def lights(self) -> List[Tuple[str, str]]:
        """Each light as (kind, label)."""
    @property
    def shadow_method(self) -> str: ...
    @property
    def warnings(self) -> List[str]: ...

def load(
    spec: Union[str, PathLike[str]],
    overrides: Optional[Mapping[str, Override]] = None,
    **kwargs: Override,
) -> Scene:
    """A catalogue entry or scene file with overrides (``Scene.load``)."""

class Frame:
    """A rendered frame: the linear radiance image and the buffers asked for."""

    @property
    def image(self) -> npt.NDArray[np.float32]:
        """Linear radiance, float32, height x width x 3."""
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def exposure(self) -> float:
        """The scene's exposure (what ``srgb()`` uses by default)."""
    def buffers(self) -> List[str]:
        """The names of the buffers this frame holds."""
    def srgb(self, exposure: Optional[float] = None) -> npt.NDArray[np.uint8]:
        """8-bit sRGB after the exposure, height x width x 3, as a PNG shows it."""
    def __getitem__(self, name: str) -> npt.NDArray[Any]:
        """A buffer: ids as int64 (-1 where none), counts as int32, values as
        float32 (H x W or H x W x 3)."""
    def __contains__(self, name: str) -> bool: ...

class Renderer:
    """A scene and the view-independent work of its frames, kept between them."""

    def __init__(self, scene: Scene) -> None: ...
    @property
    def scene(self) -> Scene: ...
    @property
    def prepasses(self) -> Dict[str, int]:
        """Pre-passes built: occluders, light_shadows, radiosity, captures."""
    @property
    def warnings(self) -> List[str]: ...
    @property
    def texture_filter(self) -> Optional[str]: ...
    def available_buffers(self) -> List[Tuple[str, str]]:
        """The buffers this scene's frame can make, as (name, description)."""
    def set_camera(self, **fields: Override) -> None:
        """Moves the camera (eye, look_at, up, fov_y, width, height); pre-passes kept."""
    def set_light(self, index: int, **fields: Override) -> None:
        """Changes light ``index``; only its pre-pass is built again."""
    def set_shadows(self, **fields: Override) -> None:
        """Changes the shadow settings (method, map_resolution, light_points, ...)."""
    def set_texture_filter(self, filter: Optional[str]) -> None:
        """Forces a texture filter on every texture (None: each texture's own)."""
    def render(self, aovs: Sequence[str] = ...) -> Frame:
        """Renders a frame with the buffers named (``["all"]`` for every one). The
        GIL is released; Ctrl-C stops the render (KeyboardInterrupt)."""

ImageLike = Union[npt.ArrayLike, str, PathLike[str]]

def catalogue() -> List[Dict[str, Any]]:
    """The catalogue's entries: id, year, topic, title, authors, summary, citation."""

def compare(
    a: ImageLike,
    b: ImageLike,
    exposure: float = 1.0,
    flip: Optional[Literal["ldr", "hdr"]] = None,
    ppd: Optional[float] = None,
    border: int = 0,
) -> Dict[str, Any]:
    """How far two images (arrays or files) are apart: rmse, psnr, max_difference,
    differing_share, fuzzy, and with ``flip`` FLIP's mean, percentiles and map."""

def export(scene: Scene, format: Literal["pov", "mitsuba", "gltf", "obj"], path: Union[str, PathLike[str]]) -> List[str]:
    """Writes the scene for another renderer; returns what the format could not hold."""

def form_factors(
    scene: Scene,
    method: Literal["hemicube", "nusselt", "analytic"] = "hemicube",
    resolution: int = 128,
    elements: int = 1,
) -> Tuple[List[str], npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Patch names, areas and the form-factor matrix (row i: where i's energy goes)."""

def shadow_polygons(scene: Scene, light: int = 0) -> List[Dict[str, Any]]:
    """Each polygon's area, lit area and shadowed area under a point or spot light."""

def read_image(path: Union[str, PathLike[str]]) -> npt.NDArray[np.float32]:
    """An image file (PNG, PFM, EXR) as linear float32 H x W x 3."""

def write_image(image: npt.ArrayLike, path: Union[str, PathLike[str]], exposure: float = 1.0) -> None:
    """Writes linear H x W x 3 as PNG (sRGB after exposure), PFM or EXR; whole or not at all."""
