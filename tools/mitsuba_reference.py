#!/usr/bin/env python3
"""Independent checks of lumiere against Mitsuba 3 on the Cornell box.

Default: the point-lit box of `cornell-box-point`, Mitsuba's direct illumination
against `render cornell-box-point --shadows ray-cast --supersample 4`.
With --global: the box lit by its quad light with every diffuse bounce, Mitsuba's
path tracer against the converged radiosity solution, `render radiosity-gathering
--element-size 10 --patch-size 35 --supersample 4`.
With --point-global: the point-lit box with every diffuse bounce, Mitsuba's path
tracer against `render radiosity-point-light --supersample 4` (the point light shot
into the radiosity solution, its direct light exact per sample).
With --quad: the box lit by its quad light, direct light only (Mitsuba's `direct`
integrator, one bounce, emitter sampling), against `render cornell-box --shadows
umbra-penumbra --supersample 4` (another method with --shadows and --set). This is the
reference held in tests/references/ for tests/suite/global/mitsuba.rs:

    python3 tools/mitsuba_reference.py --quad --spp 4096 --self-check \
        --write tests/references/cornell-box-direct-mitsuba.pfm

With --mirrors: the two-pass entry's scene, the box lit by its quad light plus the
three perfect mirrors of algorithms/two-pass.toml (its polygon objects, read from the
toml: a one-sided smooth `conductor` with material "none" and specular_reflectance the
entry's `mirror`, 0.9), Mitsuba's path tracer (unbounded depth, Russian roulette only
after 1000 bounces) against `render two-pass --supersample 4` with the entry's own
mesh (35 mm elements, 140 mm patches; --element-size and --patch-size change it, as
they change --global's 10 and 35). The reference held for it in tests/references/:

    python3 tools/mitsuba_reference.py --mirrors --size 128 --spp 4096 --self-check \
        --write tests/references/two-pass-mitsuba.pfm

(7.5 minutes a render on 2 busy cores, twice with --self-check. Its own noise, FLIP
between two seeds, is 0.018, highest on the ceiling's caustic, which a path tracer
finds only by BSDF samples that hit the lamp in the top mirror; 256 spp gives 0.049,
so 0.01 would take about 5x the samples.) To tell the mirrors' share of the error
from plain radiosity's, compare the box without mirrors at the same mesh, size and
spp:

    python3 tools/mitsuba_reference.py --global --size 128 --spp 4096 \
        --element-size 35 --patch-size 140

(At 128 x 128: two-pass 0.080 against the box without mirrors' 0.070 at the entry's
mesh, 0.035 against 0.032 at --element-size 10 --patch-size 35: at the entry's mesh
the mirrors' share is mostly the 35 mm elements' blur of the caustics' sharp edges.)

All in Mitsuba's scalar_rgb variant (or --variant) with a box filter and a float32 film, at the same
size, compared with NVIDIA's FLIP on the sRGB images. Not part of the test suite (it
needs two large PyPI packages): run it by hand. --self-check renders the reference a
second time with another seed and prints FLIP between the two: the reference's own
noise. --no-compare renders (and writes) the reference without running lumiere.

    python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba flip-evaluator numpy
    cargo build --release
    /tmp/mi/bin/python tools/mitsuba_reference.py [--global | --quad | --mirrors] [--size 256] [--spp 1024]
"""
import argparse, os, subprocess, tempfile, time, tomllib
import numpy as np
import mitsuba as mi
import flip_evaluator as flip

MATERIALS = {"white": [0.725, 0.71, 0.68], "red": [0.63, 0.065, 0.05],
             "green": [0.14, 0.45, 0.091], "light": [0.0, 0.0, 0.0]}


def split_obj(path, folder):
    """One OBJ file per object of the Cornell box (Mitsuba gives a mesh one BSDF)."""
    vertices, objects, current = [], {}, None
    for line in open(path):
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            vertices.append(parts[1:4])
        elif parts[0] == "o":
            current = parts[1]
        elif parts[0] == "usemtl":
            objects.setdefault(current, [parts[1], []])
        elif parts[0] == "f":
            objects[current][1].append([int(i.split("/")[0]) for i in parts[1:]])
    files = {}
    for name, (material, faces) in objects.items():
        used = sorted({i for f in faces for i in f})
        index = {old: new + 1 for new, old in enumerate(used)}
        file = os.path.join(folder, name + ".obj")
        with open(file, "w") as out:
            out.writelines(f"v {' '.join(vertices[i - 1])}\n" for i in used)
            out.writelines("f " + " ".join(str(index[i]) for i in f) + "\n" for f in faces)
        files[name] = (file, material)
    return files


def mirror_polygons(entry, folder):
    """The entry's polygon objects (the two-pass mirrors), one OBJ each (a triangle fan
    in the toml's vertex order, so the face normal, the mirror's front, is the same)
    with its material's specular reflectance."""
    with open(entry, "rb") as f:
        toml = tomllib.load(f)
    mirrors = []
    for k, o in enumerate(toml["objects"]):
        if o["shape"] != "polygon":
            continue
        material = toml["materials"][o["material"]]
        assert set(material) == {"mirror"}, f"{o['name']}: a perfect mirror only ({material})"
        file = os.path.join(folder, f"mirror{k}.obj")
        with open(file, "w") as out:
            out.writelines(f"v {x!r} {y!r} {z!r}\n" for x, y, z in o["vertices"])
            out.writelines(f"f 1 {i} {i + 1}\n" for i in range(2, len(o["vertices"])))
        mirrors.append((o["name"], file, material["mirror"]))
    return mirrors


def read_pfm(path):
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(height, width, 3)[::-1]


def write_pfm(path, image):
    """Linear RGB as PFM: little-endian (negative scale), rows from the bottom up."""
    height, width, _ = image.shape
    with open(path, "wb") as f:
        f.write(f"PF\n{width} {height}\n-1.0\n".encode())
        f.write(np.ascontiguousarray(image[::-1], dtype="<f4").tobytes())


def srgb(linear):
    c = np.clip(linear, 0.0, 1.0)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)


def flip_mean(reference, test):
    _, mean, _ = flip.evaluate(srgb(reference).astype(np.float32), srgb(test).astype(np.float32), "LDR")
    return mean


def main():
    args = argparse.ArgumentParser()
    args.add_argument("--size", type=int, default=256)
    args.add_argument("--spp", type=int, default=1024)
    mode = args.add_mutually_exclusive_group()
    mode.add_argument("--global", dest="global_", action="store_true")
    mode.add_argument("--quad", action="store_true")
    mode.add_argument("--mirrors", action="store_true")
    mode.add_argument("--point-global", action="store_true")
    # With one emitter sample per camera sample, every camera sample places its own
    # stratified point on the quad: the shadow rays are spread as well as they can be.
    args.add_argument("--variant", default="scalar_rgb", help="Mitsuba's variant (llvm_ad_rgb needs DRJIT_LIBLLVM_PATH)")
    args.add_argument("--emitter-samples", type=int, default=1)
    args.add_argument("--seed", type=int, default=0)
    args.add_argument("--self-check", action="store_true")
    args.add_argument("--write", metavar="PATH")
    args.add_argument("--no-compare", action="store_true")
    args.add_argument("--shadows", help="lumiere's method (default ray-cast, umbra-penumbra with --quad)")
    args.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="passed to lumiere")
    args.add_argument("--element-size", help="lumiere's radiosity mesh (default: 10 with --global, the entry's with --mirrors)")
    args.add_argument("--patch-size", help="lumiere's radiosity patches (default: 35 with --global, the entry's with --mirrors)")
    a = args.parse_args()
    mi.set_variant(a.variant)
    folder = tempfile.mkdtemp()
    lit_by_quad = a.global_ or a.quad or a.mirrors
    if a.global_ or a.mirrors or a.point_global:
        # Unbounded paths, Russian roulette only after 1000 bounces (no path gets that
        # far: the box is open to the front). Through a perfect mirror only BSDF samples
        # find the lamp, and the path tracer weighs them fully (MIS gives emitter
        # samples no share of a delta lobe): the mirrors' reflected light is unbiased.
        integrator = {"type": "path", "max_depth": -1, "rr_depth": 1000}
    else:
        # Light sampling alone: every surface is diffuse, so BSDF samples would only
        # add variance (MIS helps glossy surfaces), and emitter sampling is unbiased.
        integrator = {"type": "direct", "emitter_samples": a.emitter_samples, "bsdf_samples": 0}

    def scene(seed):
        s = {
            "type": "scene",
            "integrator": integrator,
            "sensor": {
                "type": "perspective", "fov": 39.307648, "fov_axis": "y",
                "to_world": mi.ScalarTransform4f().look_at(origin=[278, 273, -800], target=[278, 273, 0], up=[0, 1, 0]),
                "film": {"type": "hdrfilm", "width": a.size, "height": a.size, "rfilter": {"type": "box"},
                         "pixel_format": "rgb", "component_format": "float32"},
                "sampler": {"type": "stratified", "sample_count": a.spp, "seed": seed},
            },
        }
        if not lit_by_quad:
            s["lamp"] = {"type": "point", "position": [278.0, 548.6, 279.5],
                         "intensity": {"type": "rgb", "value": [228437.5, 161250.0, 53750.0]}}
        for name, (file, material) in split_obj("algorithms/models/cornell_box.obj", folder).items():
            s[name] = {"type": "obj", "filename": file, "face_normals": True,
                       "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": MATERIALS[material]}}}
            if lit_by_quad and name == "light":
                s[name]["emitter"] = {"type": "area", "radiance": {"type": "rgb", "value": [17.0, 12.0, 4.0]}}
        if a.mirrors:
            # A smooth conductor with material "none" (eta 0, k 1: Fresnel reflectance 1
            # at every angle) scaled by specular_reflectance is a perfect mirror; it is
            # one-sided, black from behind, like lumiere's mirrors.
            for k, (_, file, reflectance) in enumerate(mirror_polygons("algorithms/two-pass.toml", folder)):
                s[f"mirror{k}"] = {"type": "obj", "filename": file, "face_normals": True,
                                   "bsdf": {"type": "conductor", "material": "none",
                                            "specular_reflectance": {"type": "rgb", "value": reflectance}}}
        return mi.load_dict(s)

    start = time.perf_counter()
    reference = np.array(mi.render(scene(a.seed)), dtype=np.float32)
    light = "" if a.global_ or a.mirrors or a.point_global else f", {a.emitter_samples} emitter sample(s) per sample"
    print(f"Mitsuba: {a.size} x {a.size}, {a.spp} spp{light}, seed {a.seed}, {time.perf_counter() - start:.1f} s")
    print(f"mean radiance, Mitsuba: {reference.mean(axis=(0, 1))}")
    if a.write:
        os.makedirs(os.path.dirname(os.path.abspath(a.write)), exist_ok=True)
        write_pfm(a.write, reference)
        print(f"reference written to {a.write}")
    if a.self_check:
        start = time.perf_counter()
        again = np.array(mi.render(scene(a.seed + 1)), dtype=np.float32)
        print(f"second render, seed {a.seed + 1}: {time.perf_counter() - start:.1f} s")
        print(f"FLIP (mean) between the two Mitsuba renders: {flip_mean(reference, again):.5f}")
        print(f"mean radiance, second render: {again.mean(axis=(0, 1))}")
        np.save(os.path.join(folder, "mitsuba-second.npy"), again)
    np.save(os.path.join(folder, "mitsuba.npy"), reference)
    print(f"images in {folder}")
    if a.no_compare:
        return
    ours = os.path.join(folder, "lumiere.pfm")
    if a.point_global:
        command = ["radiosity-point-light"]
    elif a.global_ or a.mirrors:
        command = ["two-pass" if a.mirrors else "radiosity-gathering"]
        element, patch = (a.element_size, a.patch_size) if a.mirrors else (a.element_size or "10", a.patch_size or "35")
        command += ["--element-size", element] if element else []
        command += ["--patch-size", patch] if patch else []
    else:
        command = ["cornell-box" if a.quad else "cornell-box-point",
                   "--shadows", a.shadows or ("umbra-penumbra" if a.quad else "ray-cast")]
    command += [arg for kv in a.set for arg in ("--set", kv)]
    subprocess.run(["target/release/lumiere", "render", *command,
                    "--supersample", "4", "--width", str(a.size), "--height", str(a.size), "-o", ours], check=True)
    test = read_pfm(ours)
    print(f"FLIP (mean) lumiere vs Mitsuba 3: {flip_mean(reference, test):.5f}")
    print(f"mean radiance: Mitsuba {reference.mean(axis=(0, 1))}, lumiere {test.mean(axis=(0, 1))}")


if __name__ == "__main__":
    main()
