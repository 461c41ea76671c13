"""The Python package against the command line it wraps: the same pixels bit for
bit, the same overrides, the same errors; the renderer's pre-passes kept between
frames; the GIL released and Ctrl-C heard during a render; bad values refused."""

import json
import os
import signal
import threading
import time

import numpy as np
import pytest

import lumiere
from conftest import read_pfm

SMALL = {"camera.width": 48, "camera.height": 40}


@pytest.mark.parametrize(
    "entry, sets",
    [
        ("cornell-box-point", ["shadows.method=\"shadow-volumes\""]),
        ("cornell-box", []),
        ("jittered-soft-shadows", ["shadows.seed=3"]),
        ("perspective-texture", []),
        ("radiosity-shooting", []),
    ],
)
def test_the_image_equals_the_command_lines_pfm_bit_for_bit(cli, tmp_path, entry, sets):
    args = ["render", entry, "-o", tmp_path / "out.pfm", "--width", 48, "--height", 40]
    for s in sets:
        args += ["--set", s]
    cli(*args)
    expected = read_pfm(tmp_path / "out.pfm")
    overrides = dict(SMALL)
    for s in sets:
        key, value = s.split("=", 1)
        overrides[key] = json.loads(value) if value.startswith('"') else int(value)
    frame = lumiere.Renderer(lumiere.load(entry, overrides)).render()
    assert frame.image.dtype == np.float32
    assert frame.image.shape == (40, 48, 3)
    assert np.array_equal(frame.image, expected)


@pytest.mark.parametrize(
    "entry, method, buffer",
    [
        ("cornell-box-point", "shadow-volumes", "shadow-volume-counts-0"),
        ("cornell-box-point", "shadow-map", "shadow-map-0-ny"),
        ("cornell-box-point", "scanline", "visibility-0"),
        ("cornell-box-point", "ray-cast", "polygon"),
        ("cornell-box-point", "ray-cast", "depth"),
    ],
)
def test_buffers_equal_the_command_lines_pfm(cli, tmp_path, entry, method, buffer):
    out = tmp_path / "buffer.pfm"
    cli("render", entry, "--width", 48, "--height", 40, "--shadows", method, "--aov", buffer, "-o", out)
    expected = read_pfm(out)
    renderer = lumiere.Renderer(lumiere.load(entry, SMALL, **{"shadows.method": method}))
    frame = renderer.render(aovs=[buffer])
    assert frame.buffers() == [buffer]
    array = frame[buffer]
    # The PFM holds numbers as floats (ids: -1 where none); the array their own type.
    numbers = array.astype(np.float32).reshape(expected.shape[:2] + (-1,))
    assert np.array_equal(numbers, expected[:, :, : numbers.shape[2]]), buffer
    if buffer == "polygon":
        assert array.dtype == np.int64 and array.min() >= -1
    if buffer.startswith("shadow-volume-counts"):
        assert array.dtype == np.int32


def test_keyword_dict_nested_and_dotted_overrides_equal_set(cli):
    a = lumiere.load("cornell-box-point", camera={"width": 32, "height": 24}, shadows={"method": "shadow-map"})
    b = lumiere.load("cornell-box-point", {"camera.width": 32, "camera.height": 24, "shadows.method": "shadow-map"})
    c = lumiere.load("cornell-box-point", **{"camera.width": 32}, camera={"height": 24}, **{"shadows.method": "shadow-map"})
    assert a.sets == ["camera.width=32", "camera.height=24", 'shadows.method="shadow-map"']
    images = [lumiere.Renderer(s).render().image for s in (a, b, c)]
    assert all(np.array_equal(images[0], i) for i in images[1:])
    # Lists, floats, booleans and strings become the literals --set takes.
    d = lumiere.load("cornell-box-point", **{"lights.0.position": (0.28, 0.5, 0.28), "render.exposure": 1.5})
    assert d.sets == ["lights.0.position=[0.28, 0.5, 0.28]", "render.exposure=1.5"]
    scene = lumiere.Scene.from_toml('extends = "cornell-box-point"\n', camera={"width": 16, "height": 16})
    assert (scene.width, scene.height) == (16, 16)


def test_errors_are_the_right_exception_with_the_command_lines_message(cli, tmp_path):
    cases = [
        (lambda: lumiere.load("no-such-entry"), lumiere.SceneError, ["render", "no-such-entry", "-o", tmp_path / "x.png"]),
        (
            lambda: lumiere.load("cornell-box", **{"camera.width": "wide"}),
            lumiere.SceneError,
            ["render", "cornell-box", "--set", 'camera.width="wide"', "-o", tmp_path / "x.png"],
        ),
        (
            lambda: lumiere.load("cornell-box", **{"camera.width.x": 3}),
            lumiere.OverrideError,
            ["render", "cornell-box", "--set", "camera.width.x=3", "-o", tmp_path / "x.png"],
        ),
        (
            lambda: lumiere.load("cornell-box", **{"shadows.method": "nonsense"}),
            lumiere.Error,
            ["render", "cornell-box", "--set", 'shadows.method="nonsense"', "-o", tmp_path / "x.png"],
        ),
        (lambda: lumiere.load(tmp_path / "missing.toml"), lumiere.IoError, ["render", tmp_path / "missing.toml", "-o", tmp_path / "x.png"]),
        (lambda: lumiere.Scene.from_toml("camera = ["), lumiere.ParseError, None),
        (lambda: lumiere.read_image(tmp_path / "none.png"), lumiere.IoError, None),
    ]
    for call, kind, args in cases:
        with pytest.raises(kind) as raised:
            call()
        message = str(raised.value)
        assert "\n" not in message and message
        if args is not None:
            stderr = cli(*args, check=False).stderr.strip().splitlines()
            assert stderr[-1].startswith("error: ")
            assert message in stderr[-1], (message, stderr[-1])
    with pytest.raises(KeyError, match="no buffer `depth`"):
        lumiere.Renderer(lumiere.load("cornell-box-point", SMALL)).render()["depth"]


def test_bad_values_are_refused_clearly():
    with pytest.raises(ValueError, match="camera.fov_y: NaN is not a number"):
        lumiere.load("cornell-box", **{"camera.fov_y": float("nan")})
    with pytest.raises(ValueError, match="camera.fov_y: inf"):
        lumiere.load("cornell-box", camera={"fov_y": float("inf")})
    with pytest.raises(TypeError, match="camera.width: None"):
        lumiere.load("cornell-box", camera={"width": None})
    with pytest.raises(TypeError, match="camera.width: a object"):
        lumiere.load("cornell-box", camera={"width": object()})
    with pytest.raises(TypeError, match="overrides: a dict"):
        lumiere.load("cornell-box", ["camera.width=3"])
    with pytest.raises(TypeError):
        lumiere.Renderer("cornell-box")
    with pytest.raises(ValueError, match="H x W x 3"):
        lumiere.compare(np.zeros((4, 4)), np.zeros((4, 4)))
    with pytest.raises(lumiere.ImageError):
        lumiere.compare(np.zeros((4, 4, 3)), np.zeros((4, 5, 3)))
    with pytest.raises(ValueError, match="exposure"):
        lumiere.Renderer(lumiere.load("cornell-box-point", SMALL)).render().srgb(exposure=float("nan"))


def test_a_moved_camera_renders_without_building_the_prepasses_again():
    renderer = lumiere.Renderer(lumiere.load("cornell-box-point", SMALL, shadows={"method": "shadow-map"}))
    first = renderer.render().image
    assert renderer.prepasses["light_shadows"] == 1
    renderer.set_camera(eye=[0.35, 0.27, -0.7])
    moved = renderer.render().image
    assert renderer.prepasses["light_shadows"] == 1, "the shadow map was built again"
    assert not np.array_equal(first, moved)
    # The same as a renderer made for the moved camera from scratch.
    fresh = lumiere.Renderer(renderer.scene).render().image
    assert np.array_equal(moved, fresh)
    renderer.set_light(0, position=[0.3, 0.5, 0.25])
    renderer.render()
    assert renderer.prepasses["light_shadows"] == 2
    renderer.set_shadows(method="shadow-volumes")
    assert renderer.scene.shadow_method == "shadow-volumes"


def test_the_gil_is_released_while_rendering():
    # 512 x 512 at 2 x 2 samples: long enough (about 0.1 s on two cores) that the
    # counter has time to run; 256 x 256 at one sample took 10 ms.
    renderer = lumiere.Renderer(lumiere.load(
        "cornell-box", **{"camera.width": 512, "camera.height": 512, "render.supersample": 2}))
    ticks = 0
    done = threading.Event()

    def count():
        nonlocal ticks
        while not done.is_set():
            ticks += 1
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    start = time.perf_counter()
    renderer.render()
    elapsed = time.perf_counter() - start
    done.set()
    counter.join()
    assert elapsed > 0.02, "the render is long enough to see the counter run"
    assert ticks >= 5, f"the Python thread ran {ticks} times in {elapsed:.3f} s of rendering"


def test_ctrl_c_stops_a_render_and_the_renderer_renders_again():
    renderer = lumiere.Renderer(lumiere.load("cornell-box", **{"camera.width": 512, "camera.height": 512, "render.supersample": 4}))
    start = time.perf_counter()
    whole = renderer.render().image
    full = time.perf_counter() - start
    threading.Timer(0.05, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
    start = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        renderer.render()
    stopped_after = time.perf_counter() - start
    # Stopped at a band, not after the frame: well before a whole frame's time.
    assert stopped_after < 0.5 * full, (stopped_after, full)
    # The same renderer renders again, the same picture.
    assert np.array_equal(renderer.render().image, whole)


def test_srgb_and_catalogue_and_tools(tmp_path, cli):
    frame = lumiere.Renderer(lumiere.load("cornell-box-point", SMALL)).render()
    srgb = frame.srgb()
    assert srgb.dtype == np.uint8 and srgb.shape == (40, 48, 3)
    lumiere.write_image(frame.image, tmp_path / "a.png")
    assert np.array_equal(np.asarray(lumiere.read_image(tmp_path / "a.png")).shape, (40, 48, 3))
    entries = lumiere.catalogue()
    assert {"id", "year", "topic", "title", "summary", "citation"} <= set(entries[0])
    assert any(e["id"] == "shadow-volumes" and e["topic"] == "hard-shadows" for e in entries)
    # compare on arrays and on files gives the command line's figures.
    lumiere.write_image(frame.image * 0.9, tmp_path / "b.pfm")
    lumiere.write_image(frame.image, tmp_path / "a.pfm")
    ours = lumiere.compare(frame.image, tmp_path / "b.pfm", flip="ldr")
    theirs = json.loads(cli("compare", tmp_path / "a.pfm", tmp_path / "b.pfm", "--json", "--flip").stdout)
    assert ours["rmse"] == pytest.approx(theirs["rmse"], abs=0)
    assert ours["flip"]["mean"] == pytest.approx(theirs["flip"]["mean"], rel=1e-12)
    assert ours["flip"]["map"].shape == (40, 48)
    warnings = lumiere.export(lumiere.load("cornell-box"), "mitsuba", tmp_path / "box.xml")
    assert (tmp_path / "box.xml").is_file() and isinstance(warnings, list)
    names, areas, factors = lumiere.form_factors(lumiere.load("cornell-box"), method="analytic")
    assert factors.shape == (len(names), len(names)) == (len(areas), len(areas))
    assert np.all(factors.sum(axis=1) <= 1.0 + 1e-9)
    polygons = lumiere.shadow_polygons(lumiere.load("cornell-box-point"))
    # Lit and shadowed pieces tile each polygon (to the rounding of summing clipped
    # pieces' areas: 1.7e-9 of the area at most here).
    assert all(abs(p["lit_area"] + p["shadowed_area"] - p["area"]) < 1e-8 * max(1, p["area"]) for p in polygons)
    assert any(p["shadowed_area"] > 0 for p in polygons)


def test_import_takes_under_a_third_of_a_second():
    import subprocess
    import sys

    code = "import time; t = time.perf_counter(); import lumiere; print(time.perf_counter() - t)"
    runs = [float(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout) for _ in range(3)]
    assert min(runs) < 0.3, runs
