#!/usr/bin/env python3
"""How Mitsuba 3's JIT-vectorised CPU variant (llvm_ad_rgb) converges on the diffuse
Cornell box with every bounce (`cornell-box-global`, exported by `lumiere export` with
the `path` integrator: unbounded paths), beside any lumiere commands given: FLIP
against a converged render and whole-process time (median of the runs), at each
sample count. Prints a markdown table.

    python3 bench/global_convergence.py [--size 512] [--runs 3] [--spp 16 64 256 1024]
        [--reference PATH] [--reference-spp 4096]
        [--lumiere "render cornell-box-global --supersample 2"] ...

Each --lumiere string is a lumiere command line (repeatable); --width/--height are the
script's --size unless it sets them, and the output is the script's (no -o). Without
--reference, a converged render is made by Mitsuba (llvm_ad_rgb, --reference-spp,
another seed than the timed renders', so that their noise is not shared) and kept as
target/bench/cornell-box-global-SIZE-SPPspp-seed1.exr: later runs at the same size
reuse it (delete it after a change to the scene or the exporter). Scaled from 64 x 64
on two busy cores, at 512 x 512 the reference takes about 15 minutes and the whole
default run under an hour (the 1024 spp row about 7 minutes a run). tests/references/cornell-box-global-mitsuba.pfm
(tools/mitsuba_reference.py --global: 256 x 256, 4096 spp, scalar_rgb) serves at
--size 256.

Needs target/release/lumiere (for the export; it builds nothing: `cargo build
--release` first) and the peers (tools/install-peers.sh: Mitsuba, flip-evaluator,
numpy, and Debian's libllvm19, found as in bench/peers.py)."""

import argparse
import os
import shlex
import sys
import tempfile

# The repository ignores no __pycache__: importing peers leaves none behind.
sys.dont_write_bytecode = True
try:
    import peers
except ImportError as error:
    sys.exit(f"{error}: tools/install-peers.sh installs Mitsuba 3, flip-evaluator and numpy")

SCENE = "cornell-box-global"
# The timed renders use the sampler's seed 0; the reference made here another.
REFERENCE_SEED = 1


def reference_for(args, bench):
    """The converged render's path: --reference, or the one kept under target/bench/
    (made when missing, written under another name first so that a stopped run leaves
    none half-written)."""
    if args.reference:
        return os.path.abspath(args.reference)
    folder = os.path.join(peers.ROOT, "target", "bench")
    path = os.path.join(folder, f"{SCENE}-{args.size}-{args.reference_spp}spp-seed{REFERENCE_SEED}.exr")
    if os.path.exists(path):
        print(f"reference: {path} (kept from an earlier run)", file=sys.stderr)
        return path
    os.makedirs(folder, exist_ok=True)
    print(f"reference: rendering {path} ({args.reference_spp} spp, {peers.LLVM})...", file=sys.stderr)
    bench.export(SCENE, "mitsuba", "reference.xml", [], args.reference_spp, "path")
    partial = os.path.join(folder, f"partial-{os.getpid()}.exr")
    seconds, _ = peers.run(peers.mitsuba("reference.xml", partial, peers.LLVM, REFERENCE_SEED), bench.work)
    os.replace(partial, path)
    print(f"reference: {seconds:.0f} s", file=sys.stderr)
    return path


def lumiere_command(bench, line, out):
    """A --lumiere string as a command: the script's size unless it says one, its
    output the script's."""
    words = shlex.split(line)
    if "-o" in words or "--output" in words:
        sys.exit(f"--lumiere {line!r}: leave out -o, the script names the output")
    for option in ["--width", "--height"]:
        if option not in words:
            words += [option, str(bench.size)]
    return bench.lumiere(*words, "-o", out)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--size", type=int, default=512, help="image side in pixels (default 512)")
    parser.add_argument("--runs", type=int, default=3, help="timed runs of each row (default 3)")
    parser.add_argument("--spp", type=int, nargs="+", default=[16, 64, 256, 1024],
                        help="Mitsuba's samples per pixel (default 16 64 256 1024)")
    parser.add_argument("--reference", metavar="PATH", help="a converged render (PFM or EXR) at --size")
    parser.add_argument("--reference-spp", type=int, default=4096,
                        help="samples per pixel of the reference made without --reference (default 4096)")
    parser.add_argument("--lumiere", action="append", default=[], metavar="COMMAND",
                        help='a lumiere command line to time too, e.g. "render cornell-box-global --supersample 2"')
    args = parser.parse_args()
    if not os.path.exists(peers.LUMIERE):
        sys.exit(f"{peers.LUMIERE} is missing: build it first (cargo build --release); this script builds nothing")
    if args.reference and not os.path.exists(args.reference):
        sys.exit(f"--reference {args.reference}: no such file")
    bench = peers.Bench(argparse.Namespace(size=args.size, runs=args.runs, reference_spp=args.reference_spp),
                        tempfile.mkdtemp(prefix="lumiere-convergence-"))
    # The lumiere commands checked before anything is rendered.
    commands = [(line, lumiere_command(bench, line, os.path.join(bench.work, f"lumiere-{k}.exr")))
                for k, line in enumerate(args.lumiere)]
    reference = reference_for(args, bench)
    shape = peers.load(reference).shape
    if shape[:2] != (args.size, args.size):
        sys.exit(f"{reference} is {shape[1]} x {shape[0]}, not {args.size} x {args.size}: give --size {shape[1]}")

    rows = []
    for spp in args.spp:
        bench.export(SCENE, "mitsuba", f"box-{spp}.xml", [], spp, "path")
        out = os.path.join(bench.work, f"mitsuba-{spp}.exr")
        median, low, high, _ = peers.timed(peers.mitsuba(f"box-{spp}.xml", out, peers.LLVM), bench.work, args.runs)
        rows.append((f"Mitsuba 3 ({peers.LLVM}), {spp} samples per pixel", median, low, high,
                     peers.quality(reference, out)[0]))
        print(f"{rows[-1][0]}: {median:.3f} s, FLIP {rows[-1][4]:.4f}", file=sys.stderr)
    for line, command in commands:
        # From the caller's folder, where the paths the command names were meant.
        median, low, high, _ = peers.timed(command, os.getcwd(), args.runs)
        rows.append((f"lumiere {line}", median, low, high, peers.quality(reference, command[-1])[0]))
        print(f"{rows[-1][0]}: {median:.3f} s, FLIP {rows[-1][4]:.4f}", file=sys.stderr)

    print(f"images in {bench.work}", file=sys.stderr)
    print(f"`{SCENE}` at {args.size} x {args.size}, every bounce; FLIP against {os.path.relpath(reference)}; "
          f"whole processes, median of {args.runs} runs (fastest-slowest). Mitsuba's LLVM: {peers.libllvm()}; "
          "its kernels, compiled on first use, are kept in ~/.drjit: the cache is warm after the first run.")
    print()
    print(f"| renderer / settings | time (median of {args.runs} runs; fastest-slowest) | FLIP |")
    print("|---|---|---|")
    for label, median, low, high, f in rows:
        print(f"| {label} | {median:.3f} s ({low:.3f}-{high:.3f}) | {f:.4f} |")


if __name__ == "__main__":
    main()
