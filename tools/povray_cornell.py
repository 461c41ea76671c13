#!/usr/bin/env python3
"""POV-Ray 3.7 as a timing peer for lumiere's soft shadows on the Cornell box.

Writes POV-Ray SDL for the `cornell-box` catalogue entry as lumiere renders it with
`--shadows ray-cast`: the box of algorithms/models/cornell_box.obj with the Kd of its
.mtl, the camera of algorithms/cornell-box.toml, direct light only from the ceiling
quad (the material with a Ke), soft shadows from an 8 x 8 jittered area_light. Then
renders it, times it, and compares it region by region with lumiere. Not part of the
test suite (it needs the Debian package povray): run it by hand.

    apt-get install povray            # POV-Ray 3.7
    cargo build --release
    python3 tools/povray_cornell.py --sdl scene.pov          # only write the SDL
    python3 tools/povray_cornell.py --render [--size 256]    # render once, compare with lumiere
    python3 tools/povray_cornell.py --time [--sizes 256 512] [--runs 3]
    python3 tools/povray_cornell.py --radiosity --time       # every bounce: time, then quality
    python3 tools/povray_cornell.py --radiosity --render     # every bounce: quality only

How lumiere's units are carried over (POV-Ray's own conventions in brackets):

* Handedness [left-handed]: every z (geometry, camera, light) is negated. A mirror
  image of the scene seen by a left-handed camera is the right-handed image of the
  scene, so the red wall (x = 556) stays on the image's left, as in lumiere.
* Radiometry [a light of colour C gives Kd * diffuse * C * cos(theta) * attenuation,
  no 1/pi, no fall-off]: the quad of radiance L and area A becomes n x n lightlets;
  with `area_illumination on` each gets C / n^2 and its own attenuation, and the
  irradiance of a Lambertian quad is E = L * A * mean(cos cos' / r^2), the radiance
  seen Kd E / pi. So: `diffuse 1`; `fade_power 2` with `fade_distance d` gives
  2 / (1 + (r/d)^2) = 2 d^2 / r^2 (to 1 + d^2/r^2: 3e-5 at 200 mm with d = 1 mm);
  the emitter's cos' comes from making the light a spotlight pointing along the quad's
  normal with `tightness 1` and radius = falloff = 90 degrees (attenuation
  cos(angle)^tightness, zero behind the quad: one-sided, as lumiere's); and
  C = L * A / (2 pi d^2).
* Without `area_illumination` (POV-Ray's default) the shading is computed once, from
  the quad's centre, and only the shadow test uses the lightlets: a point light of
  intensity L A cos'/pi at the centre, scaled by the visible fraction. That is wrong
  where the quad is large seen from the point or straddles the point's tangent plane
  (the tall block's faces): `--no-area-illumination` shows how much.
* Sample positions [the lightlets sit on the n x n corners of the area_light's axes,
  u / (n - 1) - 1/2 of each axis, and `jitter` moves each by up to half the grid
  spacing, axis / (n - 1)]: by default (`--span cells`) the axes are (n - 1)/n of the
  quad's edges, so the spacing is edge / n, the lightlets sit on the centres of an
  n x n grid of cells tiling the quad, and jitter moves each uniformly over its own
  cell: stratified sampling over exactly the quad, as lumiere's N x N jittered samples.
  `--span corners` puts the corner lightlets on the quad's corners instead (the axes
  are the edges); jitter then spreads samples over (n / (n - 1)) = 8/7 of each edge
  (a quad 14% wider and deeper, light outside the lamp), and without jitter the
  samples are trapezoidal-rule points: more weight on the quad's border.
* Shadows: POV-Ray tests the lightlets' visibility (64 shadow rays, all of them:
  no `adaptive`, which is POV-Ray's full sampling; `--adaptive 0` starts from the 4
  corners and refines where they differ) and multiplies the shading by the visible
  fraction (unweighted). lumiere's ray-cast weights each sample's visibility by its
  share of the unoccluded irradiance and multiplies the exact (Lambert contour)
  irradiance by it. Both agree where nothing is in the way; in penumbrae they are two
  estimators of the same integral.
* Colour: `assumed_gamma 1.0` and File_Gamma=1.0: the 16-bit PNG holds linear
  radiance, clipped to [0, 1] (only the lamp, radiance (17, 12, 4), is above 1).
  `ambient 0` everywhere, `ambient_light 0`, no radiosity, max_trace_level 2.
  The lamp quad is drawn with `emission` (its radiance, clipped in the PNG) and is
  `no_shadow`, so the lightlets on it are not blocked by it.
* Pixels [+AM1 +R4 supersamples each pixel on a regular 4 x 4 grid at offsets
  +-1/8, +-3/8, the same grid as lumiere's --supersample 4, and averages it with the
  pixel's first ray at its centre: 17 rays, (centre + 16) / 17]: POV-Ray 3.7 has no
  way to take exactly 16 rays per pixel in one pass (+AM2 shares corner samples
  between pixels with tent weights; +AM3 is 3.8's). +A0.0 makes every pixel
  supersampled (the test is difference >= threshold), -J keeps the grid regular.
  `--exact-16` renders at 4 times the size without antialiasing and box-filters
  4 x 4 blocks instead: exactly lumiere's 16 samples and filter (timing includes
  POV-Ray only).

What the comparison found (256 x 256 and 512 x 512, default settings, region means
of linear radiance, POV-Ray / lumiere): where the whole lamp is seen (floor, walls,
block tops) the two agree to 1e-4 (fully lit pixels) and within 0.2% per region; in
penumbrae POV-Ray is 1-2% darker (its visible fraction counts every lightlet alike,
lumiere's weights each by its share of the irradiance), which puts the floor at
0.995. The tall block's front face, (265, 296)-(423, 247), is 0.62: the lamp straddles
that face's plane and 61.9% of the lamp's area is in front of it. POV-Ray's shadow
test casts rays to all 64 lightlets; those behind the plane go into the block and are
blocked by its own faces, so the visible fraction is ~0.62 even where nothing else is
in the way; `area_illumination` then drops the same lightlets again (cos < 0): the
horizon is counted twice. lumiere gives those samples weight 0, so its fraction is 1
and its Lambert-contour irradiance (the lamp clipped to the face's half-space) is
exact. Without area_illumination the face is at 0.40 (the centre-point lighting at a
grazing angle, times the same fraction). The whole image is 0.98, mostly that face.
`--span corners` moves the lit regions by -1.2% (floor) to +0.3% (walls); `adaptive 0`
leaves the means as they are and casts 6.6 times fewer shadow rays.

--radiosity: every diffuse bounce, against `cornell-box-global`. The direct light is
the area light above, unchanged; the indirect light is POV-Ray's radiosity:
`global_settings { radiosity { pretrace_start 0.08 pretrace_end 0.005 count 600
nearest_count 10 error_bound 0.5 recursion_limit 10 low_error_factor 0.5
gray_threshold 0 minimum_reuse 0.015 brightness 1 adc_bailout 0.005 normal off
media off always_sample off } }` (RADIOSITY; --count, --recursion-limit and
--error-bound override three of them).

* Units of the indirect light [a radiosity sample is the mean of the radiance its
  `count` rays bring back, the rays cosine-distributed over the hemisphere, so it
  is E / pi; the surface then returns pigment * diffuse * brightness * that, no
  1/pi]: Kd E / pi is the Lambertian radiance, so with `diffuse 1` and `brightness
  1` the indirect light is in lumiere's units with nothing rescaled (a factor pi
  either way would show as 3.14 or 0.32). Checked at 128 x 128 against the Mitsuba
  reference minus lumiere's exact direct image: POV-Ray's indirect part (its
  radiosity image minus its direct-only image) is (0.95, 0.98, 1.00) of it (R, G, B),
  recursion_limit 10; 3 gives (0.86, 0.90, 0.95), 6 gives the same as 10 to 0.3%.
* The lamp: its `emission` would be gathered by radiosity rays on top of the
  light_source's direct light (counted twice), so the emitting mesh is
  `no_radiosity`, and a black copy (lumiere's Kd 0), `no_image no_shadow`, stands in
  for it for those rays (otherwise they would go through to the ceiling behind).
* Pixels: `--time` times 512 x 512 with +AM1 +R2 (a 2 x 2 grid plus the centre ray:
  5 rays, box-like) against `render cornell-box-global --supersample 2`, 3 runs
  each, interleaved (POV-Ray, lumiere, POV-Ray, ...), whole-process wall clock,
  medians. Then both at 256 x 256, POV-Ray +R4 (17 rays) and lumiere --supersample
  4, against Mitsuba's path-traced /tmp/cornell-global-4096.pfm (or -1024.pfm):
  FLIP (mitsuba_reference.flip_mean, sRGB LDR) and mean radiance without the lamp.

What it found (one run, 2 cores, load average ~8 from other jobs throughout):
512 x 512, median of 3 interleaved runs: POV-Ray 131.0 s wall (87.5 s CPU; 48 s of
it the radiosity pretrace, 82 s the final trace, which casts 86 million shadow rays
to the 64 lightlets, radiosity samples included), lumiere 5.25 s wall (3.4 s CPU):
POV-Ray / lumiere = 25 (26 in CPU time). At 256 x 256 against
/tmp/cornell-global-1024.pfm (the 4096-spp one was not yet written): FLIP POV-Ray
0.045 (108 s), lumiere 0.050 (3.4 s); mean radiance without the lamp / the
reference's, (R, G, B): POV-Ray (0.965, 0.980, 0.983), lumiere (0.977, 0.989,
0.998). POV-Ray is the darker by about 1%, mostly its direct light (0.98 of
lumiere's exact direct light, the tall block's front face: see above), which also
feeds its indirect light; its radiosity is smooth (no splotches at count 600) and
bleeds the colour as lumiere does. The 1024-spp reference's own noise is a part of
both FLIP figures.
"""
import argparse, math, os, re, statistics, struct, subprocess, sys, tomllib, zlib
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
LUMIERE = ROOT / "target" / "release" / "lumiere"
WORK = Path("/tmp/povray_cornell")  # POV-Ray's I/O restrictions allow /tmp and "."


# ---------------------------------------------------------------- the scene


def read_mtl(path):
    materials, current = {}, None
    for line in open(path):
        parts = line.split()
        if not parts or parts[0].startswith("#"):
            continue
        if parts[0] == "newmtl":
            current = parts[1]
            materials[current] = {"Kd": [0.0, 0.0, 0.0], "Ke": None}
        elif parts[0] in ("Kd", "Ke") and current:
            materials[current][parts[0]] = [float(v) for v in parts[1:4]]
    return materials


def read_obj(path):
    """Objects in file order: (name, material, [[(x, y, z), ...] per face])."""
    vertices, objects, mtllib = [], [], None
    name, material = None, None
    for line in open(path):
        parts = line.split()
        if not parts or parts[0].startswith("#"):
            continue
        if parts[0] == "mtllib":
            mtllib = parts[1]
        elif parts[0] == "v":
            vertices.append(tuple(float(v) for v in parts[1:4]))
        elif parts[0] == "o":
            name = parts[1]
        elif parts[0] == "usemtl":
            material = parts[1]
            objects.append((name, material, []))
        elif parts[0] == "f":
            objects[-1][2].append([vertices[int(i.split("/")[0]) - 1] for i in parts[1:]])
    return objects, mtllib


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    return math.sqrt(sum(x * x for x in a))


def the_light(objects, materials):
    """The emitting quad: its corners, centre, edges, area, unit normal (emitting side,
    from the OBJ's counter-clockwise winding) and radiance."""
    lights = [(o, m) for o in objects for m in [materials[o[1]]] if m["Ke"]]
    if len(lights) != 1 or len(lights[0][0][2]) != 1 or len(lights[0][0][2][0]) != 4:
        sys.exit("expected exactly one emitting quad in the OBJ")
    (_, _, [quad]), material = lights[0]
    e1, e2 = sub(quad[1], quad[0]), sub(quad[3], quad[0])
    if abs(sum(a * b for a, b in zip(e1, e2))) > 1e-9 * norm(e1) * norm(e2):
        sys.exit("the light quad is not a rectangle")
    n = cross(e1, e2)
    area = norm(n)
    centre = tuple(sum(v[i] for v in quad) / 4 for i in range(3))
    return {"quad": quad, "centre": centre, "edges": (e1, e2), "area": area,
            "normal": tuple(x / area for x in n), "radiance": material["Ke"]}


def camera_of(entry):
    c = tomllib.load(open(entry, "rb"))["camera"]
    return c


def vec(p, flip=True):
    """A point in POV-Ray's frame: z negated (see the module's docstring)."""
    x, y, z = p
    return f"<{x:.6g}, {y:.6g}, {-z if flip else z:.6g}>"


def sdl(width, height, samples=8, span="cells", jitter=True, adaptive=None,
        area_illumination=True, fade_distance=1.0, radiosity=None):
    """radiosity: None (direct light only) or a dict of radiosity {} settings (see
    RADIOSITY): every diffuse bounce, and the lamp made black to radiosity rays."""
    objects, mtllib = read_obj(ROOT / "algorithms/models/cornell_box.obj")
    materials = read_mtl(ROOT / "algorithms/models" / mtllib)
    cam = camera_of(ROOT / "algorithms/cornell-box.toml")
    light = the_light(objects, materials)
    # Camera: up of length 1, right of length width/height, direction length d so
    # that the vertical field of view is fov_y: tan(fov_y / 2) = (1/2) / d.
    d = 0.5 / math.tan(math.radians(cam["fov_y"]) / 2)
    out = [
        "// Written by tools/povray_cornell.py from algorithms/models/cornell_box.obj,",
        "// its .mtl and algorithms/cornell-box.toml. lumiere's units; z negated",
        "// (POV-Ray is left-handed). " + ("Direct light from the area light, every diffuse"
                                           " bounce by radiosity." if radiosity else "Direct light only."),
        "#version 3.7;",
        "global_settings { assumed_gamma 1.0 ambient_light rgb 0 max_trace_level 2"
        + ("" if not radiosity else "\n  radiosity {\n" + "".join(
            f"    {k} {v}\n" for k, v in radiosity.items()) + "  }\n") + " }",
        "background { rgb 0 }",
        "camera {",
        "  perspective",
        f"  location {vec(cam['eye'])}",
        f"  direction <0, 0, {d:.9g}>",
        f"  right <{width / height:.9g}, 0, 0>",
        "  up <0, 1, 0>",
        f"  sky {vec(cam['up'], flip=True)}",
        f"  look_at {vec(cam['look_at'])}",
        "}",
    ]
    # The light. C = L A / (2 pi d^2): see the docstring.
    e1, e2 = light["edges"]
    scale = (samples - 1) / samples if span == "cells" else 1.0
    colour = [l * light["area"] / (2 * math.pi * fade_distance ** 2) for l in light["radiance"]]
    centre, n = light["centre"], light["normal"]
    target = tuple(c + k for c, k in zip(centre, n))
    out += [
        f"// The {norm(e1):g} x {norm(e2):g} light quad (area {light['area']:g}) of radiance "
        f"{light['radiance']}: {samples} x {samples} lightlets, span = {span}.",
        "light_source {",
        f"  {vec(centre)}, rgb <{colour[0]:.9g}, {colour[1]:.9g}, {colour[2]:.9g}>",
        f"  spotlight point_at {vec(target)} radius 90 falloff 90 tightness 1  // cos' of a Lambertian emitter, one-sided",
        f"  fade_distance {fade_distance:g} fade_power 2  // 2 d^2 / (d^2 + r^2)",
        f"  area_light {vec(tuple(x * scale for x in e1))}, {vec(tuple(x * scale for x in e2))}, {samples}, {samples}",
    ]
    if jitter:
        out.append("  jitter")
    if adaptive is not None:
        out.append(f"  adaptive {adaptive}")
    out.append(f"  area_illumination {'on' if area_illumination else 'off'}")
    out.append("}")
    # The surfaces: one mesh per OBJ object, quads cut (v0 v1 v2) + (v0 v2 v3) as
    # lumiere does (the left wall is slightly non-planar).
    for name, material, faces in objects:
        m = materials[material]
        tris = []
        for f in faces:
            for k in range(1, len(f) - 1):
                tris.append(f"  triangle {{ {vec(f[0])}, {vec(f[k])}, {vec(f[k + 1])} }}")
        if m["Ke"]:
            kd = m["Ke"]
            texture = (f"  texture {{ pigment {{ rgb <{kd[0]:g}, {kd[1]:g}, {kd[2]:g}> }} "
                       "finish { ambient 0 diffuse 0 emission 1 } }\n  no_shadow")
            if radiosity:
                # The emission would be gathered by radiosity rays as well as shot by
                # the light_source: the lamp is no_radiosity, and a black copy (lumiere's
                # Kd 0), no_image, stands in for it so that those rays do not go through
                # to the ceiling above.
                texture += "\n  no_radiosity"
                out += [f"// {name}: {material}, black, for radiosity rays only", "mesh {", *tris,
                        "  texture { pigment { rgb 0 } finish { ambient 0 diffuse 0 emission 0 } }",
                        "  no_image no_shadow no_reflection", "}"]
        else:
            kd = m["Kd"]
            texture = (f"  texture {{ pigment {{ rgb <{kd[0]:g}, {kd[1]:g}, {kd[2]:g}> }} "
                       "finish { ambient 0 emission 0 diffuse 1 brilliance 1 specular 0 phong 0 } }")
        out += [f"// {name}: {material}", "mesh {", *tris, texture, "}"]
    return "\n".join(out) + "\n"


# ---------------------------------------------------------------- images


def read_png16(path):
    """An RGB PNG, 8 or 16 bits, non-interlaced, as floats in [0, 1]."""
    data = Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, header = 8, b"", None
    while pos < len(data):
        (length,), kind = struct.unpack(">I", data[pos:pos + 4]), data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    width, height, depth, colour, _, _, interlace = header
    channels = {2: 3, 6: 4}[colour]
    assert interlace == 0 and depth in (8, 16)
    bpp = channels * depth // 8
    raw = zlib.decompress(idat)
    stride = width * bpp
    out = np.zeros((height, stride), dtype=np.int32)
    prev = np.zeros(stride, dtype=np.int32)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = np.frombuffer(raw, dtype=np.uint8, count=stride, offset=y * (stride + 1) + 1).astype(np.int32)
        if kind == 0:
            cur = line
        elif kind == 2:
            cur = (line + prev) & 255
        else:  # 1 sub, 3 average, 4 Paeth: sequential along the row
            cur = line.copy()
            for x in range(stride):
                a = cur[x - bpp] if x >= bpp else 0
                b = prev[x]
                c = prev[x - bpp] if x >= bpp else 0
                if kind == 1:
                    p = a
                elif kind == 3:
                    p = (a + b) >> 1
                else:
                    pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                    p = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                cur[x] = (cur[x] + p) & 255
        out[y] = cur
        prev = cur
    if depth == 16:
        img = (out[:, 0::2] * 256 + out[:, 1::2]).astype(np.float64) / 65535.0
    else:
        img = out.astype(np.float64) / 255.0
    return img.reshape(height, width, channels)[:, :, :3]


def write_png8(path, rgb):
    """8-bit RGB PNG of values already in [0, 1]."""
    h, w, _ = rgb.shape
    pixels = np.round(np.clip(rgb, 0, 1) * 255).astype(np.uint8)
    raw = b"".join(b"\x00" + pixels[y].tobytes() for y in range(h))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    Path(path).write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                           + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def srgb(linear):
    c = np.clip(linear, 0.0, 1.0)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)


def read_pfm(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    channels = 3 if kind == b"PF" else 1
    return data.reshape(height, width, channels)[::-1].astype(np.float64)


# ---------------------------------------------------------------- running


def povray_command(pov, png, size, threads=2, aa=True, exact16=False, aa_depth=4):
    width = size * 4 if exact16 else size
    cmd = ["povray", f"+I{pov}", f"+O{png}", f"+W{width}", f"+H{width}",
           "+FN16", "File_Gamma=1.0", "-D", "-P", "-UA", f"+WT{threads}"]
    if exact16 or not aa:
        cmd.append("-A")
    else:
        cmd += ["+A0.0", "+AM1", f"+R{aa_depth}", "-J"]
    return cmd


def timed(cmd, log):
    """Run under /usr/bin/time -v; (wall s, peak RSS MiB, user + system CPU s, stderr)."""
    result = subprocess.run(["/usr/bin/time", "-v", *cmd], capture_output=True, text=True,
                            cwd=WORK)
    Path(log).write_text(result.stdout + result.stderr)
    if result.returncode != 0:
        sys.exit(f"failed ({result.returncode}): {' '.join(cmd)}\n{result.stderr[-3000:]}")
    wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (\S+)", result.stderr).group(1)
    seconds = 0.0
    for part in wall.split(":"):
        seconds = seconds * 60 + float(part)
    rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", result.stderr).group(1))
    cpu = sum(float(re.search(rf"{k} time \(seconds\): (\S+)", result.stderr).group(1)) for k in ("User", "System"))
    return seconds, rss / 1024.0, cpu, result.stderr


def povray_stats(text):
    """POV-Ray's own counters: rays per pixel, shadow rays, trace time and its CPU time."""
    stats = {}
    for key, pattern in [("samples", r"Samples:\s+(\d+)"),
                         ("shadow_tests", r"Shadow Ray Tests:\s+(\d+)"),
                         ("trace_s", r"Trace Time:.*?\(([\d.]+) seconds\)"),
                         ("trace_cpu_s", r"Trace Time:.*?\n.*?with ([\d.]+) CPU-seconds")]:
        m = re.search(pattern, text)
        if m:
            stats[key] = float(m.group(1))
    return stats


def write_scene(args, size):
    WORK.mkdir(parents=True, exist_ok=True)
    pov = WORK / f"cornell_{args.tag}.pov"
    pov.write_text(sdl(size, size, samples=args.samples, span=args.span, jitter=not args.no_jitter,
                       adaptive=args.adaptive, area_illumination=not args.no_area_illumination))
    return pov


def povray_image(png, exact16):
    img = read_png16(png)
    if exact16:
        h, w, _ = img.shape
        img = img.reshape(h // 4, 4, w // 4, 4, 3).mean(axis=(1, 3))
    return img


# lumiere's shadow method, set from the command line.
LUMIERE_SHADOWS = ["ray-cast"]


def lumiere_command(size, out, aov=None, supersample=4):
    cmd = [str(LUMIERE), "render", "cornell-box", "--shadows", LUMIERE_SHADOWS[0],
           "--set", "shadows.light_samples=8", "--supersample", str(supersample),
           "--width", str(size), "--height", str(size), "-o", str(out)]
    if aov:
        cmd += ["--aov", aov]
    return cmd


# ---------------------------------------------------------------- regions


def regions(size):
    """Masks of whole pixels inside one surface (centre sample's world position and
    normal from lumiere's AOVs), eroded by 2 pixels so no pixel mixes surfaces."""
    pos_file, nrm_file = WORK / f"position_{size}.pfm", WORK / f"normal_{size}.pfm"
    subprocess.run(lumiere_command(size, pos_file, "position", 1), check=True, capture_output=True)
    subprocess.run(lumiere_command(size, nrm_file, "normal", 1), check=True, capture_output=True)
    p, n = read_pfm(pos_file), read_pfm(nrm_file)
    x, y, z = p[..., 0], p[..., 1], p[..., 2]

    def facing(v, tol=0.999):
        v = np.array(v) / np.linalg.norm(v)
        return np.abs(n @ v) > tol

    tall = np.array([-49.0, 0.0, -158.0])  # the face from (265, 296) to (423, 247), facing the camera
    tall_side = np.array([159.0, 0.0, -49.0])  # the face from (423, 247) to (472, 406)
    short = np.array([49.0, 0.0, -160.0])  # short block face from (130, 65) to (290, 114)
    masks = {
        "floor": facing([0, 1, 0]) & (np.abs(y) < 1e-3),
        "back wall": facing([0, 0, 1]) & (np.abs(z - 559.2) < 1e-3),
        "tall block front (265,296)-(423,247)": facing(tall) & (x > 265) & (x < 423) & (y > 0) & (y < 330),
        "tall block side (423,247)-(472,406)": facing(tall_side) & (z > 247) & (z < 406) & (y > 0) & (y < 330),
        "short block front (130,65)-(290,114)": facing(short) & (x > 130) & (x < 290) & (y > 0) & (y < 165),
        "short block top": facing([0, 1, 0]) & (np.abs(y - 165) < 1e-3),
        "tall block top": facing([0, 1, 0]) & (np.abs(y - 330) < 1e-3),
        "red wall (left)": facing([1, 0, 0], 0.99) & (x > 540),
        "green wall (right)": facing([1, 0, 0]) & (np.abs(x) < 1e-3),
        "ceiling (without lamp)": facing([0, 1, 0]) & (np.abs(y - 548.8) < 1e-3),
    }
    out = {}
    for k, m in masks.items():
        e = m.copy()
        for _ in range(2):
            e[1:-1, 1:-1] &= e[:-2, 1:-1] & e[2:, 1:-1] & e[1:-1, :-2] & e[1:-1, 2:]
            e[0, :] = e[-1, :] = e[:, 0] = e[:, -1] = False
        out[k] = e
    return out


def compare(pov_img, lum_img, size):
    print(f"\nregion means, linear radiance (R, G, B), {size} x {size}, pixels eroded by 2:")
    print(f"  {'region':40s} {'pixels':>6s}  {'POV-Ray':>26s}  {'lumiere':>26s}  POV/lumiere (mean of RGB)")
    for name, m in regions(size).items():
        if not m.any():
            continue
        a, b = pov_img[m].mean(axis=0), lum_img[m].mean(axis=0)
        fmt = lambda v: "(" + ", ".join(f"{c:.4f}" for c in v) + ")"
        ratio = f"{a.sum() / b.sum():.4f}" if b.sum() > 0 else "-"
        print(f"  {name:40s} {int(m.sum()):6d}  {fmt(a):>26s}  {fmt(b):>26s}  {ratio}")
    lamp = lum_img.max(axis=2) > 1.0
    both = ~lamp
    a, b = pov_img[both].mean(axis=0), lum_img[both].mean(axis=0)
    print(f"  {'whole image without the lamp':40s} {int(both.sum()):6d}  "
          f"({a[0]:.4f}, {a[1]:.4f}, {a[2]:.4f})  ({b[0]:.4f}, {b[1]:.4f}, {b[2]:.4f})  {a.sum() / b.sum():.4f}")
    # Mirror check: the red wall must be on the left in both.
    left = pov_img[:, : size // 8].mean(axis=(0, 1))
    print(f"  image's left eighth, POV-Ray: R {left[0]:.4f} G {left[1]:.4f} "
          f"({'red: not mirrored' if left[0] > left[1] else 'GREEN: MIRRORED'})")


def render_once(args, size):
    pov = write_scene(args, size)
    png = WORK / f"povray_{args.tag}_{size}.png"
    cmd = povray_command(pov, png, size, args.threads, exact16=args.exact_16)
    print("$", " ".join(cmd))
    seconds, rss, cpu, err = timed(cmd, WORK / f"povray_{args.tag}_{size}.log")
    print(f"POV-Ray {size} x {size}: {seconds:.2f} s wall, {cpu:.2f} s CPU, {rss:.1f} MiB peak RSS, "
          f"{povray_stats(err)}")
    img = povray_image(png, args.exact_16)
    preview = WORK / f"povray_{args.tag}_{size}_srgb.png"
    write_png8(preview, srgb(img))
    lum = WORK / f"lumiere_{size}.pfm"
    subprocess.run(lumiere_command(size, lum), check=True, capture_output=True)
    subprocess.run(lumiere_command(size, WORK / f"lumiere_{size}.png"), check=True, capture_output=True)
    lum_img = read_pfm(lum)
    side = WORK / f"side_by_side_{args.tag}_{size}.png"
    diff = np.abs(img - np.clip(lum_img, 0, 1)).mean(axis=2, keepdims=True) * 20  # x20, linear, as clipped in the PNG
    write_png8(side, np.concatenate([srgb(img), srgb(lum_img), np.repeat(np.clip(diff, 0, 1), 3, 2)], axis=1))
    print(f"images: {preview} (POV-Ray, sRGB), {png} (POV-Ray, 16-bit linear), "
          f"{WORK / f'lumiere_{size}.png'} (lumiere, sRGB), {lum} (lumiere, linear), "
          f"{side} (POV-Ray | lumiere | 20 x |difference|)")
    compare(img, lum_img, size)


def summary(who, size, rows):
    t, c = [r[0] for r in rows], [r[2] for r in rows]
    print(f"{who} {size} x {size}: median {statistics.median(t):.2f} s wall "
          f"(min {min(t):.2f}, max {max(t):.2f}, spread {max(t) - min(t):.2f} s), "
          f"median {statistics.median(c):.2f} s CPU, peak RSS {max(r[1] for r in rows):.1f} MiB, "
          f"load average during {statistics.mean(r[3] for r in rows):.2f}", flush=True)


def time_all(args):
    print(f"load average before: {os.getloadavg()}, {os.cpu_count()} CPUs "
          "(other processes on the machine skew the figures)")
    for size in args.sizes:
        pov = write_scene(args, size)
        rows = []
        for run in range(args.runs):
            png = WORK / f"povray_{args.tag}_{size}_run{run}.png"
            cmd = povray_command(pov, png, size, args.threads, exact16=args.exact_16)
            if run == 0:
                print("$", " ".join(cmd))
            seconds, rss, cpu, err = timed(cmd, WORK / f"povray_{args.tag}_{size}_run{run}.log")
            rows.append((seconds, rss, cpu, os.getloadavg()[0], povray_stats(err)))
            print(f"  run {run + 1}: {seconds:.2f} s wall, {cpu:.2f} s CPU, {rss:.1f} MiB peak RSS, "
                  f"load {rows[-1][3]:.2f}, {rows[-1][4]}", flush=True)
        summary("POV-Ray", size, rows)
        write_png8(WORK / f"povray_{args.tag}_{size}_srgb.png", srgb(povray_image(png, args.exact_16)))
        if args.lumiere:
            rows = []
            cmd = lumiere_command(size, WORK / f"lumiere_{size}.pfm")
            print("$", " ".join(cmd))
            for run in range(args.runs):
                seconds, rss, cpu, _ = timed(cmd, WORK / f"lumiere_{size}_run{run}.log")
                rows.append((seconds, rss, cpu, os.getloadavg()[0]))
                print(f"  run {run + 1}: {seconds:.2f} s wall, {cpu:.2f} s CPU, {rss:.1f} MiB peak RSS, "
                      f"load {rows[-1][3]:.2f}", flush=True)
            summary("lumiere", size, rows)
    print(f"load average after: {os.getloadavg()}")


# ---------------------------------------------------------------- radiosity (--radiosity)

# POV-Ray 3.7's radiosity {} for every diffuse bounce (see the docstring). Depth-0
# samples shoot `count` cosine-distributed rays; a sample is reused within the
# error_bound (tightened by low_error_factor in the pretrace) of its nearest_count
# neighbours; recursion_limit bounces of radiosity rays; gray_threshold 0 keeps the
# colour bleeding; brightness 1: the gathered value is used as it is (lumiere's units).
RADIOSITY = {"pretrace_start": 0.08, "pretrace_end": 0.005, "count": 600, "nearest_count": 10,
             "error_bound": 0.5, "recursion_limit": 10, "low_error_factor": 0.5,
             "gray_threshold": 0, "minimum_reuse": 0.015, "brightness": 1, "adc_bailout": 0.005,
             "normal": "off", "media": "off", "always_sample": "off"}
REFERENCES = [Path("/tmp/cornell-global-4096.pfm"), Path("/tmp/cornell-global-1024.pfm")]


def lumiere_global_command(size, supersample, out):
    return [str(LUMIERE), "render", "cornell-box-global", "--width", str(size), "--height", str(size),
            "--supersample", str(supersample), "-o", str(out)]


def radiosity_scene(args, size):
    WORK.mkdir(parents=True, exist_ok=True)
    pov = WORK / f"cornell_radiosity_{args.tag}_{size}.pov"
    settings = dict(RADIOSITY, count=args.count, recursion_limit=args.recursion_limit,
                    error_bound=args.error_bound)
    pov.write_text(sdl(size, size, samples=args.samples, span=args.span, jitter=not args.no_jitter,
                       adaptive=args.adaptive, area_illumination=not args.no_area_illumination,
                       radiosity=settings))
    return pov


def quality(args, size=256):
    """POV-Ray radiosity (4 x 4 AA) and lumiere's cornell-box-global (--supersample 4)
    against the Mitsuba path-traced reference: FLIP and mean radiance ratios."""
    sys.path.insert(0, str(ROOT / "tools"))
    from mitsuba_reference import flip_mean
    ref_path = next((p for p in REFERENCES if p.exists()), None)
    if ref_path is None:
        print("no Mitsuba reference in", [str(p) for p in REFERENCES])
        return
    ref = read_pfm(ref_path)
    if ref.shape[0] != size:
        sys.exit(f"{ref_path} is {ref.shape[0]} x {ref.shape[1]}, not {size} x {size}")
    pov = radiosity_scene(args, size)
    png = WORK / f"povray_radiosity_{args.tag}_{size}_aa4.png"
    cmd = povray_command(pov, png, size, args.threads, aa_depth=4)
    print(f"\nquality at {size} x {size} against {ref_path}\n$", " ".join(cmd), flush=True)
    seconds, _, cpu, err = timed(cmd, WORK / f"povray_radiosity_{args.tag}_{size}_aa4.log")
    print(f"  POV-Ray: {seconds:.2f} s wall, {cpu:.2f} s CPU, {povray_stats(err)}")
    p = povray_image(png, False)
    lum = WORK / f"lumiere_global_{size}_ss4.pfm"
    cmd = lumiere_global_command(size, 4, lum)
    print("$", " ".join(cmd), flush=True)
    seconds, _, cpu, _ = timed(cmd, WORK / f"lumiere_global_{size}_ss4.log")
    print(f"  lumiere: {seconds:.2f} s wall, {cpu:.2f} s CPU")
    l = read_pfm(lum)
    # Means without the lamp (clipped to 1 in POV-Ray's PNG): pixels where the
    # reference or lumiere exceed 1, grown by one pixel.
    lamp = (ref.max(axis=2) > 1.0) | (l.max(axis=2) > 1.0)
    lamp[1:] |= lamp[:-1].copy(); lamp[:-1] |= lamp[1:].copy()
    lamp[:, 1:] |= lamp[:, :-1].copy(); lamp[:, :-1] |= lamp[:, 1:].copy()
    keep = ~lamp
    r = ref[keep].mean(axis=0)
    write_png8(WORK / f"radiosity_side_by_side_{size}.png",
               np.concatenate([srgb(p), srgb(l), srgb(ref)], axis=1))
    print(f"  reference mean radiance without the lamp: ({r[0]:.4f}, {r[1]:.4f}, {r[2]:.4f})")
    for who, img in (("POV-Ray radiosity, 4 x 4 AA", p), ("lumiere cornell-box-global, ss 4", l)):
        m = img[keep].mean(axis=0)
        print(f"  {who:34s} FLIP {flip_mean(ref, img):.4f}  mean ({m[0]:.4f}, {m[1]:.4f}, {m[2]:.4f})"
              f"  / reference R {m[0] / r[0]:.4f} G {m[1] / r[1]:.4f} B {m[2] / r[2]:.4f}"
              f" sum {m.sum() / r.sum():.4f}", flush=True)
    print(f"  images: {WORK / f'radiosity_side_by_side_{size}.png'} (POV-Ray | lumiere | Mitsuba, sRGB)")


def time_radiosity(args, size=512):
    """POV-Ray radiosity with 2 x 2 AA and lumiere's cornell-box-global with
    --supersample 2, interleaved run by run, whole-process wall clock."""
    print(f"load average before: {os.getloadavg()}, {os.cpu_count()} CPUs", flush=True)
    pov = radiosity_scene(args, size)
    lum_cmd = lumiere_global_command(size, 2, WORK / f"lumiere_global_{size}_ss2.pfm")
    rows = {"POV-Ray": [], "lumiere": []}
    for run in range(args.runs):
        pov_cmd = povray_command(pov, WORK / f"povray_radiosity_{args.tag}_{size}_aa2.png", size,
                                 args.threads, aa_depth=2)
        for who, cmd in (("POV-Ray", pov_cmd), ("lumiere", lum_cmd)):
            if run == 0:
                print("$", " ".join(cmd), flush=True)
            seconds, rss, cpu, err = timed(cmd, WORK / f"{who}_radiosity_{size}_run{run}.log")
            rows[who].append((seconds, rss, cpu, os.getloadavg()[0]))
            extra = povray_stats(err) if who == "POV-Ray" else ""
            print(f"  {who} run {run + 1}: {seconds:.2f} s wall, {cpu:.2f} s CPU, {rss:.1f} MiB, "
                  f"load {rows[who][-1][3]:.2f} {extra}", flush=True)
    for who in rows:
        summary(who, size, rows[who])
    a, b = (statistics.median(r[0] for r in rows[k]) for k in ("POV-Ray", "lumiere"))
    print(f"median wall clock POV-Ray / lumiere at {size} x {size}: {a / b:.1f}")
    print(f"load average after: {os.getloadavg()}", flush=True)


def main():
    a = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    a.add_argument("--sdl", metavar="FILE", help="write the SDL to FILE ('-': stdout) and stop")
    a.add_argument("--render", action="store_true", help="render once at --size and compare with lumiere")
    a.add_argument("--time", action="store_true", help="time --runs renders at each of --sizes")
    a.add_argument("--size", type=int, default=256)
    a.add_argument("--sizes", type=int, nargs="+", default=[256, 512])
    a.add_argument("--runs", type=int, default=3)
    a.add_argument("--threads", type=int, default=2)
    a.add_argument("--samples", type=int, default=8, help="n: n x n lightlets")
    a.add_argument("--span", choices=["cells", "corners"], default="cells")
    a.add_argument("--no-jitter", action="store_true")
    a.add_argument("--adaptive", type=int, default=None, help="area_light adaptive level (default: none, all lightlets)")
    a.add_argument("--no-area-illumination", action="store_true")
    a.add_argument("--exact-16", action="store_true", help="4x size, no AA, 4 x 4 box filter afterwards")
    a.add_argument("--lumiere", action="store_true", help="with --time: time lumiere the same way")
    a.add_argument("--lumiere-shadows", default="ray-cast",
                   help="lumiere's shadow method (ray-cast: 8 x 8 light samples, as POV-Ray's; umbra-penumbra: exact)")
    a.add_argument("--tag", default="default", help="name of this variant's files in /tmp/povray_cornell")
    a.add_argument("--radiosity", action="store_true",
                   help="every diffuse bounce by POV-Ray's radiosity: with --time, time it at 512 x 512 "
                        "(2 x 2 AA) against lumiere's cornell-box-global, interleaved, then measure both "
                        "at 256 x 256 (4 x 4) against the Mitsuba reference; with --render only the latter")
    a.add_argument("--count", type=int, default=RADIOSITY["count"], help="radiosity count")
    a.add_argument("--recursion-limit", type=int, default=RADIOSITY["recursion_limit"])
    a.add_argument("--error-bound", type=float, default=RADIOSITY["error_bound"])
    args = a.parse_args()
    LUMIERE_SHADOWS[0] = args.lumiere_shadows
    if args.radiosity:
        if args.sdl:
            text = radiosity_scene(args, args.size).read_text()
            sys.stdout.write(text) if args.sdl == "-" else Path(args.sdl).write_text(text)
            return
        if args.time:
            time_radiosity(args, 512)
        quality(args, 256)
    elif args.sdl:
        text = sdl(args.size, args.size, samples=args.samples, span=args.span, jitter=not args.no_jitter,
                   adaptive=args.adaptive, area_illumination=not args.no_area_illumination)
        sys.stdout.write(text) if args.sdl == "-" else Path(args.sdl).write_text(text)
    elif args.time:
        time_all(args)
    else:
        render_once(args, args.size)


if __name__ == "__main__":
    main()
