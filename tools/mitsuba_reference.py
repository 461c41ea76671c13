#!/usr/bin/env python3
"""Independent checks of lumiere against Mitsuba 3 on the Cornell box.

Default: the point-lit box of `cornell-box-point`, Mitsuba's direct illumination
against `render cornell-box-point --shadows ray-cast --supersample 4`.
With --global: the box lit by its quad light with every diffuse bounce, Mitsuba's
path tracer against the converged radiosity solution, `render radiosity-gathering
--element-size 10 --patch-size 35 --supersample 4`.
Both in Mitsuba's scalar_rgb variant with a box filter, at the same size, compared
with NVIDIA's FLIP on the sRGB images. Not part of the test suite (it needs two
large PyPI packages): run it by hand.

    python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba flip-evaluator numpy
    cargo build --release
    /tmp/mi/bin/python tools/mitsuba_reference.py [--global] [--size 256] [--spp 1024]
"""
import argparse, os, struct, subprocess, tempfile
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


def read_pfm(path):
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(height, width, 3)[::-1]


def srgb(linear):
    c = np.clip(linear, 0.0, 1.0)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)


def main():
    args = argparse.ArgumentParser()
    args.add_argument("--size", type=int, default=256)
    args.add_argument("--spp", type=int, default=1024)
    args.add_argument("--global", dest="global_", action="store_true")
    a = args.parse_args()
    mi.set_variant("scalar_rgb")
    folder = tempfile.mkdtemp()
    scene = {
        "type": "scene",
        "integrator": ({"type": "path", "max_depth": -1, "rr_depth": 1000} if a.global_ else
                       {"type": "direct", "emitter_samples": 1, "bsdf_samples": 0}),
        "sensor": {
            "type": "perspective", "fov": 39.307648, "fov_axis": "y",
            "to_world": mi.ScalarTransform4f().look_at(origin=[278, 273, -800], target=[278, 273, 0], up=[0, 1, 0]),
            "film": {"type": "hdrfilm", "width": a.size, "height": a.size, "rfilter": {"type": "box"}, "pixel_format": "rgb"},
            "sampler": {"type": "stratified", "sample_count": a.spp},
        },
    }
    if not a.global_:
        scene["lamp"] = {"type": "point", "position": [278.0, 548.6, 279.5],
                         "intensity": {"type": "rgb", "value": [228437.5, 161250.0, 53750.0]}}
    for name, (file, material) in split_obj("algorithms/models/cornell_box.obj", folder).items():
        scene[name] = {"type": "obj", "filename": file, "face_normals": True,
                       "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": MATERIALS[material]}}}
        if a.global_ and name == "light":
            scene[name]["emitter"] = {"type": "area", "radiance": {"type": "rgb", "value": [17.0, 12.0, 4.0]}}
    reference = np.array(mi.render(mi.load_dict(scene)))
    ours = os.path.join(folder, "lumiere.pfm")
    command = (["radiosity-gathering", "--element-size", "10", "--patch-size", "35"] if a.global_ else
               ["cornell-box-point", "--shadows", "ray-cast"])
    subprocess.run(["target/release/lumiere", "render", *command,
                    "--supersample", "4", "--width", str(a.size), "--height", str(a.size), "-o", ours], check=True)
    test = read_pfm(ours)
    _, mean, _ = flip.evaluate(srgb(reference).astype(np.float32), srgb(test).astype(np.float32), "LDR")
    print(f"FLIP (mean) lumiere vs Mitsuba 3: {mean:.5f}")
    np.save(os.path.join(folder, "mitsuba.npy"), reference)
    print(f"images in {folder}")
    print(f"mean radiance: Mitsuba {reference.mean(axis=(0, 1))}, lumiere {test.mean(axis=(0, 1))}")


if __name__ == "__main__":
    main()
