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

With --xml, it renders a scene file as it is (a reference suite's export, whose
size it keeps) and writes OUT.pfm and OUT.variance.pfm: the candidate and its
variance `lumiere check --physically-based --candidate-renders N` reads
(docs/testing-your-renderer.md):

    python3 tools/mitsuba_moments.py --xml suite/ID/export/scene.xml --renders 8 \\
        --spp 64 --out mitsuba/ID

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
    parser.add_argument("entry", nargs="?", help="a catalogue id, exported at --size")
    parser.add_argument("--xml", help="a Mitsuba scene file rendered as it is (instead of an entry)")
    parser.add_argument("--size", type=int, default=128)
    parser.add_argument("--renders", type=int, default=32)
    parser.add_argument("--spp", type=int, default=1024)
    parser.add_argument("--variant", default="llvm_ad_rgb")
    parser.add_argument("--out", required=True, help="path prefix of the two PFM files")
    args = parser.parse_args()
    if args.renders < 2:
        sys.exit("--renders: at least 2 (a variance needs two renders)")
    if (args.entry is None) == (args.xml is None):
        sys.exit("name a catalogue entry or --xml SCENE, one of the two")
    if args.variant.startswith("llvm") and "DRJIT_LIBLLVM_PATH" not in os.environ:
        os.environ["DRJIT_LIBLLVM_PATH"] = peers.libllvm()
    import mitsuba as mi
    import numpy as np

    mi.set_variant(args.variant)
    lumiere = os.path.join(ROOT, "target", "release", "lumiere")
    with tempfile.TemporaryDirectory() as work:
        if args.xml:
            xml = args.xml
        else:
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
    # A candidate for `lumiere check` is ID.pfm beside ID.variance.pfm.
    mean_file, variance_file = (
        (args.out + ".pfm", args.out + ".variance.pfm") if args.xml
        else (args.out + "-mean.pfm", args.out + "-variance.pfm")
    )
    write_pfm(mean_file, mean)
    write_pfm(variance_file, variance)
    height, width, _ = mean.shape
    print(f"{args.xml or args.entry}: {args.renders} renders x {args.spp} spp at {width} x {height} "
          f"({args.variant}): {mean_file}, {variance_file}")


if __name__ == "__main__":
    main()
