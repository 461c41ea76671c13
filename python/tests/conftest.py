"""What the package's tests share: the command line they compare with, and a
reader of its PFM output."""

import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def lumiere_binary():
    """The lumiere command line: $LUMIERE_BIN (the test harness sets it), else the
    checkout's release build, else the one on PATH."""
    for candidate in (
        os.environ.get("LUMIERE_BIN"),
        str(ROOT / "target" / "release" / "lumiere"),
        shutil.which("lumiere"),
    ):
        if candidate and os.path.isfile(candidate):
            return candidate
    pytest.skip("no lumiere binary: build it with cargo build --release")


@pytest.fixture(scope="session")
def cli():
    binary = lumiere_binary()

    def run(*args, cwd=None, check=True):
        done = subprocess.run(
            [binary, *map(str, args)], cwd=cwd, capture_output=True, text=True
        )
        if check and done.returncode != 0:
            raise AssertionError(f"lumiere {' '.join(map(str, args))}: {done.stderr}")
        return done

    return run


def read_pfm(path):
    """A PFM file as float32 H x W x C, row 0 at the top (PFM stores rows bottom up)."""
    with open(path, "rb") as f:
        kind = f.readline().strip()
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        channels = 3 if kind == b"PF" else 1
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    image = data.reshape(height, width, channels)[::-1]
    return np.ascontiguousarray(image).astype(np.float32)
