#!/usr/bin/env python3
"""The peer benchmark behind bench/peers.sh: see that script, and BENCHMARKS.md for
what it writes. Every scene is exported by `lumiere export`, so the three renderers
see the same camera, geometry, materials and lights. Mitsuba runs in two variants:
scalar_rgb (one ray at a time) and llvm_ad_rgb (JIT-compiled, vectorised over the
CPU's SIMD lanes), the latter at several sample counts. bench/global_convergence.py
imports this file for its exports, timings and measures."""

import argparse
import json
import math
import os
import platform
import re
import signal
import statistics
import subprocess
import sys
import tempfile
import time

import flip_evaluator as flip
import mitsuba as mi
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LUMIERE = os.path.join(ROOT, "target", "release", "lumiere")
mi.set_variant("scalar_rgb")

# Mitsuba's JIT-vectorised CPU variant, and the sample counts it is timed at: where
# its cost per sample goes and how its error falls, beside scalar_rgb's 16.
LLVM = "llvm_ad_rgb"
LLVM_SPP = [16, 64, 256]

# Where the last run's measurements are kept.
RESULTS = os.path.join(ROOT, "target", "peers-results.json")

# The exact hard-shadow methods, and the label of their rows on the rotated grid.
EXACT = ["scanline", "shadow-volumes", "shadow-polygons", "ray-cast"]
ROTATED = "rotated grid 4 x 4"

# The first row of the point-lit box at 512 x 512 under its ceiling (the back
# wall's top edge crosses row 110).
FIRST_ROW_UNDER_CEILING = 110

# A growth run longer than this is stopped and shown as "> LIMIT s".
LIMIT = 120


def run(command, cwd, limit=None):
    """Wall time (s) and peak memory (MB) of a whole process; None past `limit`."""
    start = time.perf_counter()
    timed = ["/usr/bin/time", "-f", "%M"] + command
    # Its own process group, so that a run stopped at `limit` is stopped whole:
    # killing /usr/bin/time alone left the renderer running beside later runs.
    process = subprocess.Popen(timed, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True, start_new_session=True)
    try:
        _, stderr = process.communicate(timeout=limit)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        process.communicate()
        return None
    result = subprocess.CompletedProcess(timed, process.returncode, "", stderr)
    wall = time.perf_counter() - start
    if result.returncode != 0:
        sys.exit(f"{' '.join(command)} failed:\n{result.stderr}")
    peak_kb = int(result.stderr.strip().splitlines()[-1])
    return wall, peak_kb / 1024


def timed(command, cwd, runs):
    walls, peaks = [], []
    for _ in range(runs):
        wall, peak = run(command, cwd)
        walls.append(wall)
        peaks.append(peak)
    return statistics.median(walls), min(walls), max(walls), max(peaks)


def timed_together(commands, cwd, runs):
    """`timed` for several commands, run in turns (each once per round): a
    disturbance of the machine falls on all of them alike, so their ratios hold."""
    walls, peaks = [[] for _ in commands], [[] for _ in commands]
    for _ in range(runs):
        for i, command in enumerate(commands):
            wall, peak = run(command, cwd)
            walls[i].append(wall)
            peaks[i].append(peak)
    return [(statistics.median(w), min(w), max(w), max(p)) for w, p in zip(walls, peaks)]


def load(path):
    return np.array(mi.Bitmap(path), dtype=np.float32)[:, :, :3]


def srgb(linear):
    c = np.clip(linear, 0.0, 1.0)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)


def quality(reference, test, first_row=0):
    """FLIP (NVIDIA's perceptual difference, on sRGB) and RMSE of sRGB values, over
    the rows from `first_row` down."""
    a, b = srgb(load(reference)).astype(np.float32), srgb(load(test)).astype(np.float32)
    a, b = np.ascontiguousarray(a[first_row:]), np.ascontiguousarray(b[first_row:])
    _, mean, _ = flip.evaluate(a, b, "LDR")
    return float(mean), float(np.sqrt(np.mean((a - b) ** 2)))


# The variant and the sampler's seed are arguments: one script for both variants,
# and a reference can be rendered with a seed that no timed render uses.
MITSUBA_RENDER = (
    "import mitsuba as mi, sys\nmi.set_variant(sys.argv[3])\n"
    "mi.util.write_bitmap(sys.argv[2], mi.render(mi.load_file(sys.argv[1]), seed=int(sys.argv[4])))\n"
)


def libllvm():
    """The LLVM library that Mitsuba's llvm variants load: DRJIT_LIBLLVM_PATH when set,
    else Debian's libLLVM-19.so (libllvm19, installed by tools/install-peers.sh; its
    folder is the machine's multiarch one, so dpkg is asked where)."""
    if os.environ.get("DRJIT_LIBLLVM_PATH"):
        return os.environ["DRJIT_LIBLLVM_PATH"]
    listed = subprocess.run(["dpkg", "-L", "libllvm19"], capture_output=True, text=True).stdout.split()
    path = next((p for p in listed if p.endswith("/libLLVM-19.so")), None)
    if path is None:
        sys.exit("Debian's libllvm19 is missing (Mitsuba's llvm variants need it): run tools/install-peers.sh")
    return path


def mitsuba(xml, exr, variant="scalar_rgb", seed=0):
    """The command rendering `xml` to `exr`. An llvm variant is given the library
    through `env` in the command itself, so that the timed process (env execs Python:
    no process of its own) is the one a user runs."""
    command = [sys.executable, "-c", MITSUBA_RENDER, xml, exr, variant, str(seed)]
    if variant.startswith("llvm"):
        command = ["env", f"DRJIT_LIBLLVM_PATH={libllvm()}"] + command
    return command


class Bench:
    def __init__(self, args, work):
        self.size = args.size
        self.runs = args.runs
        self.reference_spp = args.reference_spp
        self.work = work
        self.rows = []
        self.images = {}
        # FLIP of the point-lit box's images under its ceiling: (first row, rows).
        self.below = None

    def lumiere(self, *words):
        return [LUMIERE, *words]

    def export(self, scene, fmt, out, sets, spp=16, integrator=None):
        words = ["export", scene, "--format", fmt, "-o", out, "--width", str(self.size),
                 "--height", str(self.size), "--spp", str(spp)]
        if integrator:
            words += ["--integrator", integrator]
        for s in sets:
            words += ["--set", s]
        subprocess.run(self.lumiere(*words), cwd=self.work, check=True, capture_output=True)

    def povray(self, pov, exr):
        # 4 x 4 samples in every pixel (non-adaptive), linear half-float EXR.
        return ["povray", f"+I{pov}", f"+O{exr}", f"+W{self.size}", f"+H{self.size}", "+FE",
                "File_Gamma=1.0", "+A0.0", "+AM1", "+R4", "-D", "-GA"]

    def scene(self, title, scene, sets, methods, pov=True, integrator=None):
        """Times lumiere's methods, POV-Ray and Mitsuba on `scene` and measures each
        image against Mitsuba's converged render."""
        tag = re.sub(r"[^a-z0-9]+", "-", title.lower()).strip("-")
        reference = f"{tag}-reference.exr"
        self.export(scene, "mitsuba", f"{tag}-reference.xml", sets, self.reference_spp, integrator)
        run(mitsuba(f"{tag}-reference.xml", reference), self.work)
        rows, images, commands = [], [], []
        for label, words, *ext in methods:
            out = f"{tag}-{len(commands)}.{ext[0] if ext else 'exr'}"
            command = self.lumiere("render", scene, "--width", str(self.size), "--height",
                                   str(self.size), *words, "-o", out)
            for s in sets:
                command += ["--set", s]
            commands.append(command)
            images.append(("lumiere " + label, out))
        # lumiere's rows in turns: the ratios between them (EXR against PFM, one
        # method against another) are measured under the same conditions.
        for (label, out), times in zip(images, timed_together(commands, self.work, self.runs)):
            rows.append((label, *times,
                         *quality(os.path.join(self.work, reference), os.path.join(self.work, out))))
        if pov:
            self.export(scene, "pov", f"{tag}.pov", sets)
            out = f"{tag}-pov.exr"
            images.append(("POV-Ray 3.7, 16 samples per pixel", out))
            rows.append(("POV-Ray 3.7, 16 samples per pixel",
                         *timed(self.povray(f"{tag}.pov", out), self.work, self.runs),
                         *quality(os.path.join(self.work, reference), os.path.join(self.work, out))))
        self.export(scene, "mitsuba", f"{tag}-16.xml", sets, 16, integrator)
        out = f"{tag}-mitsuba.exr"
        rows.append(("Mitsuba 3 (scalar_rgb), 16 samples per pixel",
                     *timed(mitsuba(f"{tag}-16.xml", out), self.work, self.runs),
                     *quality(os.path.join(self.work, reference), os.path.join(self.work, out))))
        # The JIT variant, timed like every row: its first run on a scene may compile
        # kernels (kept in ~/.drjit), what a user pays once; the median is a warm run.
        for spp in LLVM_SPP:
            self.export(scene, "mitsuba", f"{tag}-{spp}.xml", sets, spp, integrator)
            out = f"{tag}-{LLVM}-{spp}.exr"
            images.append((f"Mitsuba 3 ({LLVM}), {spp} samples per pixel", out))
            rows.append((f"Mitsuba 3 ({LLVM}), {spp} samples per pixel",
                         *timed(mitsuba(f"{tag}-{spp}.xml", out, LLVM), self.work, self.runs),
                         *quality(os.path.join(self.work, reference), os.path.join(self.work, out))))
        self.rows.append((title, scene, sets, rows))
        self.images[title] = (reference, images)
        return rows

    def flip_below(self, title, first_row):
        """FLIP of each image of scene `title` over the rows from `first_row` down."""
        reference, images = self.images[title]
        return [(label, quality(os.path.join(self.work, reference), os.path.join(self.work, out),
                                first_row)[0]) for label, out in images]

    def growth(self, label, command_for, values):
        """Time against a parameter (None past LIMIT: larger values are not tried),
        and the exponent of the fit over all but the smallest value."""
        times = []
        for v in values:
            measured = run(command_for(v), self.work, LIMIT) if not times or times[-1] else None
            times.append(measured[0] if measured else None)
        points = [(v, t) for v, t in zip(values[1:], times[1:]) if t]
        if len(points) >= 2:
            xs, ys = np.log([p[0] for p in points]), np.log([p[1] for p in points])
            exponent = float(np.polyfit(xs, ys, 1)[0])
        else:
            exponent = float("nan")
        return label, times, exponent


SPHERE = """[camera]
eye = [0.0, 3.0, 6.0]
look_at = [0.0, 0.8, 0.0]
fov_y = 40.0
width = 512
height = 512

[materials.grey]
diffuse = [0.6, 0.6, 0.6]

[[objects]]
shape = "quad"
material = "grey"
transform = [{{ scale = 10.0 }}]

{spheres}
{lights}"""

# The scene format tessellates a sphere at most 1,024 ways: past half a million
# polygons the count is split between spheres side by side.
MOST_PER_SPHERE = 500_000


def spheres(polygons):
    """Tessellated spheres making about `polygons` polygons over the ground."""
    count = math.ceil(polygons / MOST_PER_SPHERE)
    resolution = round(math.sqrt(2 * polygons / count))
    text = ""
    for k in range(count):
        x = 2.2 * (k - (count - 1) / 2)
        text += (f"\n[[objects]]\nshape = \"sphere\"\nmaterial = \"grey\"\nresolution = {resolution}\n"
                 f"transform = [{{ translate = [{x:.2f}, 1.0, 0.0] }}]\n")
    return text


def lights(n):
    text = ""
    for k in range(n):
        angle = 2 * math.pi * k / n
        text += (f"\n[[lights]]\ntype = \"point\"\nposition = [{3 * math.cos(angle):.4f}, 5.0, "
                 f"{3 * math.sin(angle):.4f}]\nintensity = [{40.0 / n}, {40.0 / n}, {40.0 / n}]\n")
    return text


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--output", default=os.path.join(ROOT, "BENCHMARKS.md"))
    parser.add_argument("--rewrite", action="store_true",
                        help="write the tables again from the last run's measurements")
    args = parser.parse_args()
    if args.rewrite:
        return rewrite(args)
    args.size = 256 if args.quick else 512
    args.runs = 3 if args.quick else 5
    args.reference_spp = 256 if args.quick else 1024
    work = tempfile.mkdtemp(prefix="lumiere-peers-")
    bench = Bench(args, work)
    hard = ["none", "scanline", "shadow-volumes", "shadow-polygons", "shadow-map", "ray-cast"]
    ss4 = ["--supersample", "4"]
    rotated = ["--sample-pattern", "rotated-grid"]
    point = bench.scene("The point-lit Cornell box", "cornell-box-point", [],
                        [(f"{m}, 4 x 4", ["--shadows", m, *ss4]) for m in hard]
                        + [("none, 4 x 4, PFM out", ["--shadows", "none", *ss4], "pfm"),
                           ("scanline, 8 x 8", ["--shadows", "scanline", "--supersample", "8"])]
                        + [(f"{m}, {ROTATED}", ["--shadows", m, *ss4, *rotated]) for m in EXACT])
    # The lamp's fixture hangs 0.1 mm under the ceiling and the point 0.1 mm under
    # it: the ceiling around the fixture is in its shadow out to twice its size, and
    # Mitsuba's shadow rays, which leave the ceiling offset by its epsilon (about
    # 0.1 mm at this scene's scale), pass the fixture and light that ring. The rows
    # under the ceiling compare the rest alone.
    bench.below = (FIRST_ROW_UNDER_CEILING * args.size // 512,
                   bench.flip_below("The point-lit Cornell box", FIRST_ROW_UNDER_CEILING * args.size // 512))
    quad = bench.scene("The Cornell box under its quad light, direct light", "cornell-box", [],
                [("umbra-penumbra (exact), 4 x 4", ["--shadows", "umbra-penumbra", *ss4]),
                 (f"umbra-penumbra (exact), {ROTATED}", ["--shadows", "umbra-penumbra", *ss4, *rotated]),
                 ("ray-cast, 4 x 4 light samples, 4 x 4", ["--shadows", "ray-cast", *ss4])])
    bench.scene("The diffuse Cornell box, every bounce", "cornell-box-global", [],
                [("cornell-box-global (radiosity, exact direct), 2 x 2", ["--supersample", "2"]),
                 # irradiance-caching's settings over the same scene, as the export has it.
                 ("final gather through Ward's irradiance cache (irradiance-caching), 2 x 2",
                  ["--supersample", "2", "--set", "radiosity.ambient=true",
                   "--set", "global.final_gather.rays=1024", "--set", "global.final_gather.error=0.15",
                   "--set", "global.final_gather.direct_at_hits=true"])],
                pov=False, integrator="path")
    # The peers have no background colour (an environment would light the scene) and
    # no Phong lobe: the curved scene is compared without either.
    curved = bench.scene("The curved scene (3,353 polygons)", "ray-cast-shadows-curved",
                         ["render.background=[0.0, 0.0, 0.0]", "materials.glossy.specular=[0.0, 0.0, 0.0]"],
                         [(f"{m}, 1 x 1", ["--shadows", m]) for m in
                          ["scanline", "shadow-volumes", "stencil-shadow-volumes", "shadow-polygons",
                           "ray-cast"]] + [("shadow-polygons, 4 x 4", ["--shadows", "shadow-polygons", *ss4])])

    # Cost growth.
    growth = []
    methods = ["none", "scanline", "shadow-volumes", "shadow-polygons", "shadow-map", "ray-cast"]
    sizes = [256, 512, 1024, 2048] if args.quick else [256, 512, 1024, 2048, 4096]
    for m in methods:
        growth.append(("image side", m, *bench.growth(
            m, lambda s, m=m: bench.lumiere("render", "cornell-box-point", "--shadows", m, "--width", str(s),
                                            "--height", str(s), "-o", "g.pfm"), sizes)[1:], sizes))
    counts = [1_000, 10_000, 100_000] if args.quick else [1_000, 10_000, 100_000, 1_000_000]
    for m in methods:
        def command(n, m=m):
            path = os.path.join(work, f"sphere-{n}.toml")
            with open(path, "w") as f:
                f.write(SPHERE.format(spheres=spheres(n), lights=lights(1)))
            return bench.lumiere("render", path, "--shadows", m, "-o", "g.pfm")
        growth.append(("polygons", m, *bench.growth(m, command, counts)[1:], counts))
    numbers = [1, 2, 4, 8]
    for m in methods:
        def command(n, m=m):
            path = os.path.join(work, f"lights-{n}.toml")
            with open(path, "w") as f:
                f.write(SPHERE.format(spheres=spheres(5_000), lights=lights(n)))
            return bench.lumiere("render", path, "--shadows", m, "-o", "g.pfm")
        growth.append(("lights", m, *bench.growth(m, command, numbers)[1:], numbers))

    # Peak memory at a large image: the frame's buffers and the edge table only.
    large = 8192
    memory = []
    for m in ["none", "scanline"]:
        wall, peak = run(bench.lumiere("render", "cornell-box-point", "--shadows", m, "--width", str(large),
                                       "--height", str(large), "-o", "large.exr"), work)
        memory.append((m, large, wall, peak))

    # The measurements, kept so that the tables can be written again (--rewrite)
    # after a change to how they are shown, without measuring again.
    with open(RESULTS, "w") as f:
        json.dump({"rows": bench.rows, "point": point, "quad": quad, "curved": curved, "growth": growth,
                   "memory": memory, "below": bench.below, "size": args.size, "runs": args.runs,
                   "reference_spp": args.reference_spp}, f)
    write(args, bench, point, quad, curved, growth, memory)


def rewrite(args):
    with open(RESULTS) as f:
        kept = json.load(f)
    args.size, args.runs, args.reference_spp = kept["size"], kept["runs"], kept["reference_spp"]
    bench = Bench(args, tempfile.mkdtemp(prefix="lumiere-peers-"))
    bench.rows = kept["rows"]
    bench.below = kept.get("below")
    write(args, bench, kept["point"], kept["quad"], kept["curved"], kept["growth"], kept["memory"])


def llvm_match(rows, flip_value):
    """Mitsuba llvm's fastest run at the same or better FLIP than `flip_value`, and
    whether one reached it (if none did, its best run: a ratio against it is a lower
    bound)."""
    llvm = [r for r in rows if LLVM in r[0]]
    reaching = [r for r in llvm if r[5] <= flip_value]
    if reaching:
        return min(reaching, key=lambda r: r[1]), True
    return min(llvm, key=lambda r: r[5]), False


def targets(args, point, quad, curved, growth, memory, below=None):
    """The speed targets, each with what was measured and whether it holds."""
    yes = lambda held: "yes" if held else "no"
    out = ["## Targets", "", "| target | measured | holds |", "|---|---|---|"]
    row = lambda rows, label: next(r for r in rows if r[0] == "lumiere " + label)
    none, pfm = row(point, "none, 4 x 4"), row(point, "none, 4 x 4, PFM out")
    samples = args.size * args.size * 16
    out.append(f"| point-lit box, no shadows, 4 x 4, PFM out: 100 M samples per second whole process "
               f"(at most {samples / 1e8 * 1000:.0f} ms) | {samples / pfm[1] / 1e6:.0f} M samples/s "
               f"({pfm[1] * 1000:.0f} ms) | {yes(samples / pfm[1] >= 1e8)} |")
    slower = none[1] / pfm[1] - 1
    out.append(f"| point-lit box, no shadows: EXR out at most 20% slower than PFM | {100 * slower:+.0f}% "
               f"({none[1] * 1000:.0f} ms against {pfm[1] * 1000:.0f} ms) | {yes(slower <= 0.2)} |")
    pov_time = next(r[1] for r in point if r[0].startswith("POV-Ray"))
    for m in EXACT:
        for grid in ["4 x 4", ROTATED]:
            r = next((r for r in point if r[0] == f"lumiere {m}, {grid}"), None)
            if r is None:
                continue
            ratio = pov_time / r[1]
            out.append(f"| point-lit box, {m}, {grid}: 30 x faster than POV-Ray at 16 spp | {ratio:.1f} x "
                       f"({r[1]:.3f} s against {pov_time:.3f} s) | {yes(ratio >= 30)} |")
            peer, reached = llvm_match(point, r[5])
            ratio = peer[1] / r[1]
            how = "at FLIP " + (f"{peer[5]:.4f} <= {r[5]:.4f}" if reached else
                                f"{peer[5]:.4f}, its best, against our {r[5]:.4f}: a lower bound")
            out.append(f"| point-lit box, {m}, {grid}: 8 x faster than Mitsuba {LLVM}'s fastest run at the "
                       f"same or better FLIP | {ratio:.1f} x ({r[1]:.3f} s against {peer[1]:.3f} s, "
                       f"{peer[0].split(', ')[1]}, {how}) | {yes(ratio >= 8 and reached)} |")
    if below:
        # The same comparison under the ceiling, where Mitsuba's reference is right.
        first, flips = below
        under = dict((label, f) for label, f in flips)
        times = dict((r[0], r[1]) for r in point)
        for label in ["scanline, 4 x 4", "scanline, 8 x 8"] + [f"{m}, {ROTATED}" for m in EXACT]:
            ours = under.get("lumiere " + label)
            if ours is None:
                continue
            llvm = [(times[l], f, l) for l, f in flips if LLVM in l]
            reaching = [p for p in llvm if p[1] <= ours]
            peer = min(reaching) if reaching else min(llvm, key=lambda p: p[1])
            ratio = peer[0] / times["lumiere " + label]
            out.append(f"| point-lit box under the ceiling (rows {first} down), {label}: 8 x faster than "
                       f"Mitsuba {LLVM}'s fastest run at the same or better FLIP | {ratio:.1f} x "
                       f"({times['lumiere ' + label]:.3f} s against {peer[0]:.3f} s, {peer[2].split(', ')[1]}, "
                       f"FLIP {peer[1]:.4f} against {ours:.4f}) | {yes(ratio >= 8 and bool(reaching))} |")
    for grid in ["4 x 4", ROTATED]:
        umbra = next((r for r in quad if r[0] == f"lumiere umbra-penumbra (exact), {grid}"), None)
        if umbra is None:
            continue
        out.append(f"| quad-lit box, umbra-penumbra, {grid}: at most 0.3 s | {umbra[1]:.3f} s | "
                   f"{yes(umbra[1] <= 0.3)} |")
        peer, reached = llvm_match(quad, umbra[5])
        ratio = peer[1] / umbra[1]
        how = (f"FLIP {peer[5]:.4f} against {umbra[5]:.4f}" if reached else
               f"FLIP {peer[5]:.4f}, its best, against our {umbra[5]:.4f}: a lower bound")
        out.append(f"| quad-lit box, umbra-penumbra, {grid}: 10 x faster than Mitsuba {LLVM} at the same "
                   f"FLIP | {ratio:.1f} x ({umbra[1]:.3f} s against {peer[1]:.3f} s, "
                   f"{peer[0].split(', ')[1]}, {how}) | {yes(ratio >= 10 and reached)} |")
    for label, median, *_ in curved:
        if "1 x 1" in label:
            out.append(f"| curved scene, {label}: under 100 ms | {median * 1000:.0f} ms | "
                       f"{yes(median < 0.1)} |")
    for kind, method, times, exponent, values in growth:
        if kind != "polygons":
            continue
        last = times[-1]
        shown = f"{last:.1f} s" if last else f"> {LIMIT} s"
        out.append(f"| {values[-1]:,} polygons, {method}: under 10 s, growth from {values[1]:,} at most "
                   f"n^1.3 | {shown}, n^{exponent:.2f} | {yes(bool(last) and last < 10 and exponent <= 1.3)} |")
    out.append(f"| point-lit box, no shadows, 4 x 4: under 100 MB | {pfm[4]:.0f} MB | {yes(pfm[4] < 100)} |")
    for method, side, wall, peak in memory:
        out.append(f"| point-lit box, {method}, {side:,} x {side:,}: under 1 GB | {peak:.0f} MB ({wall:.1f} s) "
                   f"| {yes(peak < 1024)} |")
    return out


def versions():
    pov = subprocess.run(["povray", "--version"], capture_output=True, text=True)
    pov = next((l for l in (pov.stdout + pov.stderr).splitlines() if l.startswith("POV-Ray")), "POV-Ray ?")
    lum = subprocess.run([LUMIERE, "--version"], capture_output=True, text=True).stdout.strip()
    cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
    return lum, pov, f"Mitsuba {mi.__version__}", cpu


# The line after which BENCHMARKS.md is written by hand.
KEEP = "<!-- Written by hand from here on: bench/peers.py keeps it when it rewrites the tables above. -->"


def write(args, bench, point, quad, curved, growth, memory):
    lum, pov, mts, cpu = versions()
    out = ["# Benchmarks", "",
           "Written by `bench/peers.sh" + (" --quick" if args.quick else "") + "`: every scene is exported by "
           "`lumiere export`, rendered by lumiere, POV-Ray and Mitsuba at the same size with a box pixel "
           "filter, each whole process timed (median of the runs, then the fastest and slowest) with its "
           "peak memory; each image measured against Mitsuba's converged render (FLIP, NVIDIA's perceptual "
           "difference, and the RMSE of sRGB values).", "",
           f"- machine: {cpu}, {os.cpu_count()} cores, {platform.system()} {platform.release()}",
           f"- renderers: {lum}; {pov}; {mts}",
           f"- images: {args.size} x {args.size}; {args.runs} runs each; references {args.reference_spp} "
           "samples per pixel",
           f"- Mitsuba {LLVM}: LLVM from {libllvm()}; the kernels it compiles on first use are kept in "
           "~/.drjit, so the cache is warm after the first run of each row (the median is a warm run; the "
           "slowest may include compiling, once per machine)"
           + (f"; the references have no more samples than its {max(LLVM_SPP)} samples per pixel: there its "
              "FLIP is mostly the reference's own noise" if args.reference_spp <= max(LLVM_SPP) else ""), ""]
    for title, scene, sets, rows in bench.rows:
        out += [f"## {title}", "", f"`{scene}`" + (f" with {' '.join(sets)}" if sets else ""), "",
                "| renderer | time (median; fastest-slowest) | peak memory | FLIP | RMSE |", "|---|---|---|---|---|"]
        for label, median, low, high, peak, f, e in rows:
            out.append(f"| {label} | {median:.3f} s ({low:.3f}-{high:.3f}) | {peak:.0f} MB | {f:.4f} | {e:.4f} |")
        out.append("")
        if scene == "cornell-box-point" and bench.below:
            first, below = bench.below
            out += [f"Under the ceiling (rows {first} down): the lamp's fixture hangs 0.1 mm under the "
                    "ceiling and the point light 0.1 mm under the fixture, so the ceiling around the "
                    "fixture is in its shadow out to twice its size; Mitsuba's shadow rays, which leave "
                    "the ceiling offset by its epsilon (about 0.1 mm at this scene's scale), pass the "
                    "fixture and light that ring, in its reference as in its renders. FLIP over the "
                    "rest of the image:", "",
                    "| renderer | FLIP under the ceiling |", "|---|---|"]
            out += [f"| {label} | {f:.4f} |" for label, f in below] + [""]
    out += targets(args, point, quad, curved, growth, memory, bench.below)
    out += ["", "## Cost growth", "",
            "Whole-process time of `lumiere render` against one parameter, the others fixed; the exponent "
            "is the slope of log time against log parameter over all but the smallest value (1: linear). "
            "Image side: the point-lit Cornell box, one sample per pixel (the work grows as the side "
            "squared: 2 is linear in pixels). Polygons: a tessellated sphere over a ground quad, 512 x 512, "
            "one point light. Lights: the sphere at 5,000 polygons under 1 to 8 point lights.", ""]
    for kind in ["image side", "polygons", "lights"]:
        rows = [g for g in growth if g[0] == kind]
        values = rows[0][4]
        out += [f"| {kind} | " + " | ".join(f"{v:,}" for v in values) + " | exponent |",
                "|---|" + "---|" * (len(values) + 1)]
        for _, method, times, exponent, _ in rows:
            shown = [f"{t:.3f} s" if t else f"> {LIMIT} s" for t in times]
            out.append(f"| {method} | " + " | ".join(shown) + f" | {exponent:.2f} |")
        out.append("")
    # What follows KEEP in the file (the analysis written by hand) is kept as it is.
    kept = ""
    if os.path.exists(args.output):
        with open(args.output) as f:
            old = f.read()
        if KEEP in old:
            kept = old[old.index(KEEP):]
    with open(args.output, "w") as f:
        f.write("\n".join(out))
        if kept:
            f.write("\n" + kept)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
