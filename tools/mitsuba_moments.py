#!/usr/bin/env python3
"""Mitsuba 3's per-pixel mean and variance of a catalogue entry, for the statistical
test (`lumiere compare --reference-variance`, tests/suite/global/path_tracing.rs).

The entry is exported by `lumiere export ENTRY --format mitsuba` (its geometry,
materials and lights; Mitsuba's `path` integrator, unbounded depth) at --size and
rendered --renders times, each with --spp samples a pixel and its own seed (0, 1,
...). Written beside --out: OUT-mean.pfm (the renders' mean) and OUT-variance.pfm
(the unbiased variance of one render about it), linear RGB, and the count in the
printed line. Held in tests/references/ for the path tracer's tests:

    python3 tools/mitsuba_moments.py path-tracing --size 128 --renders 32 --spp 1024 \\
        --out tests/references/path-tracing-mitsuba
    python3 tools/mitsuba_moments.py path-tracing-mirrors --size 128 --renders 32 \\
        --spp 1024 --out tests/references/path-tracing-mirrors-mitsuba

Needs target/release/lumiere (`cargo build --release`) and Mitsuba with numpy
(tools/install-peers.sh). The llvm variants load Debian's libLLVM-19 (found as in
bench/peers.py); --variant scalar_rgb needs none.
"""
import argparse
import os
import subprocess
import sys
import tempfile

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "bench"))
import peers  # noqa: E402

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))


def write_pfm(path, image):
    """Linear RGB as PFM: little-endian (negative scale), rows from the bottom up."""
    import numpy as np

    height, width, _ = image.shape
    with open(path, "wb") as f:
        f.write(f"PF\n{width} {height}\n-1.0\n".encode())
        f.write(np.ascontiguousarray(image[::-1], dtype="<f4").tobytes())


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("entry")
    parser.add_argument("--size", type=int, default=128)
    parser.add_argument("--renders", type=int, default=32)
    parser.add_argument("--spp", type=int, default=1024)
    parser.add_argument("--variant", default="llvm_ad_rgb")
    parser.add_argument("--out", required=True, help="path prefix of the two PFM files")
    args = parser.parse_args()
    if args.renders < 2:
        sys.exit("--renders: at least 2 (a variance needs two renders)")
    if args.variant.startswith("llvm") and "DRJIT_LIBLLVM_PATH" not in os.environ:
        os.environ["DRJIT_LIBLLVM_PATH"] = peers.libllvm()
    import mitsuba as mi
    import numpy as np

    mi.set_variant(args.variant)
    lumiere = os.path.join(ROOT, "target", "release", "lumiere")
    with tempfile.TemporaryDirectory() as work:
        xml = os.path.join(work, "scene.xml")
        size = str(args.size)
        subprocess.run(
            [lumiere, "export", args.entry, "--format", "mitsuba", "--width", size,
             "--height", size, "-o", xml],
            check=True,
        )
        scene = mi.load_file(xml)
        # Welford's update in double precision.
        mean = squares = None
        for k in range(args.renders):
            image = np.array(mi.render(scene, spp=args.spp, seed=k), dtype=np.float64)[:, :, :3]
            if mean is None:
                mean, squares = np.zeros_like(image), np.zeros_like(image)
            delta = image - mean
            mean += delta / (k + 1)
            squares += delta * (image - mean)
            print(f"render {k + 1}/{args.renders}", file=sys.stderr)
    variance = squares / (args.renders - 1)
    write_pfm(args.out + "-mean.pfm", mean)
    write_pfm(args.out + "-variance.pfm", variance)
    print(f"{args.entry}: {args.renders} renders x {args.spp} spp at {size} x {size} "
          f"({args.variant}): {args.out}-mean.pfm, {args.out}-variance.pfm")


if __name__ == "__main__":
    main()
