#!/usr/bin/env python3
"""lumlab's CPU reference against Mitsuba 3 (scalar_rgb): same scene, same
camera, same light, same resolution and samples per pixel, timed in one run.

The scene is a Lambert plane and a box under a point light. It is written
twice from the same numbers: as glTF for lumlab (its scene format) and as
Wavefront OBJ for Mitsuba. Conventions matched on both sides:
  - +Y up, right-handed, metres; the camera looks from eye at target with the
    vertical field of view (Mitsuba: `perspective`, fov_axis = 'y');
  - a point light of power P has intensity I = P / 4π W/sr (Mitsuba's
    `point` emitter takes I);
  - f_r = c / π (lumlab --k 1; Mitsuba `diffuse` with reflectance c);
  - one emitter sample and no BSDF sample per pixel sample (Mitsuba `direct`
    with bsdf_samples = 0: a BSDF sample cannot find a point light anyway);
  - the same number of pixel samples (lumlab stratifies them; Mitsuba's
    `independent` sampler is its fastest, `stratified` can be asked for),
    box filter, linear radiance in W/m²/sr (lumlab EXR, Mitsuba hdrfilm).

Prints both times, their ratio and the relative difference on lit pixels;
exits 1 when the mean relative difference reaches 1 %.

    pip install mitsuba
    cargo build --release
    python3 bench/mitsuba_compare.py [--size 960x540] [--spp 16] [--threads 2]
"""

import argparse
import base64
import json
import math
import os
import re
import struct
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

EYE = (3.5, 3.0, 5.0)
TARGET = (0.0, 0.4, 0.0)
FOVY_DEG = 40.0
LIGHT = (2.0, 4.0, 1.5)
POWER_W = 800.0
PLANE_COLOR = (0.7, 0.7, 0.7)
BOX_COLOR = (0.8, 0.2, 0.1)

# Rec. 709 luminance, as lumlab's noise estimate uses.
LUMINANCE = np.array([0.2126, 0.7152, 0.0722])


def quad(corners, normal):
    """Two triangles, counter-clockwise seen from the side the normal points to."""
    return corners, [normal] * 4, [0, 1, 2, 0, 2, 3]


def plane(half):
    return quad(
        [(-half, 0.0, half), (half, 0.0, half), (half, 0.0, -half), (-half, 0.0, -half)],
        (0.0, 1.0, 0.0),
    )


def box(lo, hi, yaw_deg):
    """An axis-aligned box turned by yaw_deg about +Y, flat normals."""
    c = [(hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1], hi[2] if i & 4 else lo[2]) for i in range(8)]
    faces = [
        ([1, 3, 7, 5], (1, 0, 0)),
        ([4, 6, 2, 0], (-1, 0, 0)),
        ([2, 6, 7, 3], (0, 1, 0)),
        ([0, 1, 5, 4], (0, -1, 0)),
        ([4, 5, 7, 6], (0, 0, 1)),
        ([1, 0, 2, 3], (0, 0, -1)),
    ]
    a = math.radians(yaw_deg)
    ca, sa = math.cos(a), math.sin(a)

    def turn(v):
        # Rotation about +Y (right-handed): x' = x cos a + z sin a, z' = −x sin a + z cos a.
        return (v[0] * ca + v[2] * sa, v[1], -v[0] * sa + v[2] * ca)

    positions, normals, indices = [], [], []
    for ids, n in faces:
        base = len(positions)
        positions += [turn(c[i]) for i in ids]
        normals += [turn(n)] * 4
        indices += [base + k for k in (0, 1, 2, 0, 2, 3)]
    return positions, normals, indices


def meshes():
    return [
        ("plane", plane(5.0), PLANE_COLOR),
        ("box", box((-0.6, 0.0, -0.6), (0.6, 1.2, 0.6), 25.0), BOX_COLOR),
    ]


def write_gltf(path):
    """A glTF 2.0 file with the buffer embedded: one node per mesh, positions
    already in world space, normals, u32 indices, a base colour per material."""
    blob = bytearray()
    doc = {
        "asset": {"version": "2.0", "generator": "lumlab bench/mitsuba_compare.py"},
        "scene": 0,
        "scenes": [{"nodes": []}],
        "nodes": [],
        "meshes": [],
        "materials": [],
        "accessors": [],
        "bufferViews": [],
        "buffers": [],
    }

    def view(data, target):
        while len(blob) % 4:
            blob.append(0)
        doc["bufferViews"].append(
            {"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target}
        )
        blob.extend(data)
        return len(doc["bufferViews"]) - 1

    def vec3_accessor(values):
        data = b"".join(struct.pack("<3f", *v) for v in values)
        acc = {
            "bufferView": view(data, 34962),
            "componentType": 5126,
            "count": len(values),
            "type": "VEC3",
            "min": [min(v[i] for v in values) for i in range(3)],
            "max": [max(v[i] for v in values) for i in range(3)],
        }
        doc["accessors"].append(acc)
        return len(doc["accessors"]) - 1

    for name, (positions, normals, indices), color in meshes():
        position = vec3_accessor(positions)
        normal = vec3_accessor(normals)
        index_data = struct.pack(f"<{len(indices)}I", *indices)
        doc["accessors"].append(
            {"bufferView": view(index_data, 34963), "componentType": 5125, "count": len(indices), "type": "SCALAR"}
        )
        doc["materials"].append(
            {"name": name, "pbrMetallicRoughness": {"baseColorFactor": [*color, 1.0], "metallicFactor": 0.0}}
        )
        doc["meshes"].append(
            {
                "name": name,
                "primitives": [
                    {
                        "attributes": {"POSITION": position, "NORMAL": normal},
                        "indices": len(doc["accessors"]) - 1,
                        "material": len(doc["materials"]) - 1,
                    }
                ],
            }
        )
        doc["nodes"].append({"name": name, "mesh": len(doc["meshes"]) - 1})
        doc["scenes"][0]["nodes"].append(len(doc["nodes"]) - 1)
    uri = "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()
    doc["buffers"].append({"byteLength": len(blob), "uri": uri})
    path.write_text(json.dumps(doc, indent=1))


def write_objs(folder):
    """One OBJ per mesh, the same vertices, normals and (1-based) faces."""
    files = []
    for name, (positions, normals, indices), color in meshes():
        lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in positions]
        lines += [f"vn {x!r} {y!r} {z!r}" for x, y, z in normals]
        for t in range(0, len(indices), 3):
            a, b, c = (i + 1 for i in indices[t : t + 3])
            lines.append(f"f {a}//{a} {b}//{b} {c}//{c}")
        path = folder / f"{name}.obj"
        path.write_text("\n".join(lines) + "\n")
        files.append((path, color))
    return files


def start_mitsuba(threads):
    """Mitsuba's variant and thread pool, set once per process (setting the
    pool again between renders can leave it waiting forever)."""
    import drjit as dr
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    dr.set_thread_count(threads)


def render_mitsuba(folder, width, height, spp, sampler="independent"):
    import mitsuba as mi

    intensity = POWER_W / (4.0 * math.pi)
    scene = {
        "type": "scene",
        "integrator": {"type": "direct", "emitter_samples": 1, "bsdf_samples": 0},
        "sensor": {
            "type": "perspective",
            "fov": FOVY_DEG,
            "fov_axis": "y",
            "near_clip": 0.01,
            "far_clip": 1000.0,
            "to_world": mi.ScalarTransform4f().look_at(origin=EYE, target=TARGET, up=(0.0, 1.0, 0.0)),
            "film": {
                "type": "hdrfilm",
                "width": width,
                "height": height,
                "rfilter": {"type": "box"},
                "pixel_format": "rgb",
            },
            "sampler": {"type": sampler, "sample_count": spp},
        },
        "light": {
            "type": "point",
            "position": LIGHT,
            "intensity": {"type": "rgb", "value": [intensity] * 3},
        },
    }
    for path, color in write_objs(folder):
        scene[path.stem] = {
            "type": "obj",
            "filename": str(path),
            "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": list(color)}},
        }
    start = time.perf_counter()
    loaded = mi.load_dict(scene)
    load_s = time.perf_counter() - start
    start = time.perf_counter()
    image = mi.render(loaded, spp=spp)
    render_s = time.perf_counter() - start
    return np.array(image)[:, :, :3], load_s, render_s


def render_lumlab(lumlab, folder, width, height, spp, threads):
    gltf = folder / "scene.gltf"
    write_gltf(gltf)
    exr = folder / "lumlab.exr"
    vec = lambda v: ",".join(repr(float(x)) for x in v)
    command = [
        str(lumlab), "reference",
        "--scene", str(gltf),
        "--camera", f"{vec(EYE)}:{vec(TARGET)}:{FOVY_DEG}",
        "--size", f"{width}x{height}",
        "--light", vec(LIGHT),
        "--power", repr(POWER_W),
        "--color", "1,1,1",
        "--k", "1",
        "--spp", str(spp),
        "--out", str(exr),
    ]  # fmt: skip
    env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
    start = time.perf_counter()
    run = subprocess.run(command, env=env, capture_output=True, text=True)
    wall_s = time.perf_counter() - start
    if run.returncode != 0:
        sys.exit(f"lumlab failed ({run.returncode}): {run.stderr.strip()}")
    summary = run.stderr.strip().splitlines()[-1]
    # "... 1 spp: 0.842 s (BVH ...": the render alone, as lumlab timed it.
    found = re.search(r"spp: ([0-9.]+) s", summary)
    render_s = float(found.group(1)) if found else float("nan")
    import mitsuba as mi

    image = np.array(mi.Bitmap(str(exr)))[:, :, :3]
    return image, wall_s, render_s, summary


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--lumlab", default="target/release/lumlab", help="the lumlab binary")
    parser.add_argument("--size", default="960x540", help="WxH")
    parser.add_argument("--spp", type=int, default=16, help="samples per pixel (a square)")
    parser.add_argument("--threads", type=int, default=2, help="threads for both renderers")
    parser.add_argument(
        "--mitsuba-sampler",
        default="independent",
        choices=["independent", "stratified"],
        help="Mitsuba's pixel sampler: independent is its fastest (lumlab stratifies)",
    )
    parser.add_argument(
        "--repeat",
        type=int,
        default=3,
        help="runs of each renderer, alternating; the fastest of each counts (the machine may be shared)",
    )
    parser.add_argument("--keep", type=Path, help="keep the scene files and images in this folder")
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.lower().split("x"))
    if not Path(args.lumlab).exists():
        sys.exit(f"no lumlab binary at {args.lumlab} (cargo build --release)")

    with tempfile.TemporaryDirectory() as tmp:
        folder = args.keep or Path(tmp)
        folder.mkdir(parents=True, exist_ok=True)
        start_mitsuba(args.threads)
        times = {"mts_load": [], "mts_render": [], "lum_wall": [], "lum_render": []}
        for _ in range(max(1, args.repeat)):
            mts, mts_load_s, mts_render_s = render_mitsuba(folder, width, height, args.spp, args.mitsuba_sampler)
            lum, lum_wall_s, lum_render_s, summary = render_lumlab(
                args.lumlab, folder, width, height, args.spp, args.threads
            )
            for key, value in zip(times, (mts_load_s, mts_render_s, lum_wall_s, lum_render_s)):
                times[key].append(value)
        mts_load_s, mts_render_s, lum_wall_s, lum_render_s = (min(v) for v in times.values())
        if args.keep:
            import mitsuba as mi

            mi.Bitmap(mts.astype(np.float32)).write(str(folder / "mitsuba.exr"))

    y_lum, y_mts = lum @ LUMINANCE, mts @ LUMINANCE
    lit = (y_lum > 0.0) & (y_mts > 0.0)
    rel = np.abs(y_lum[lit] - y_mts[lit]) / y_mts[lit]
    mean_rel = float(rel.mean())
    fmt = lambda values: ", ".join(f"{v:.3f}" for v in values)
    print(
        f"scene: plane + box, point light {POWER_W} W, {width}×{height}, {args.spp} spp, "
        f"{args.threads} threads, fastest of {max(1, args.repeat)} alternating runs"
    )
    print(f"lumlab:  {summary}")
    print(f"lumlab   process {lum_wall_s:.3f} s, render {lum_render_s:.3f} s (renders: {fmt(times['lum_render'])})")
    print(
        f"mitsuba  load {mts_load_s:.3f} s + render {mts_render_s:.3f} s = {mts_load_s + mts_render_s:.3f} s "
        f"(renders: {fmt(times['mts_render'])})"
    )
    print(
        f"speed-up: render {mts_render_s / lum_render_s:.2f}×, "
        f"whole run {(mts_load_s + mts_render_s) / lum_wall_s:.2f}× (lumlab process vs Mitsuba load + render)"
    )
    print(
        f"lit pixels: {int(lit.sum())} of {width * height}; relative difference of luminance: "
        f"mean {100 * mean_rel:.3f} %, median {100 * float(np.median(rel)):.3f} %, "
        f"95th percentile {100 * float(np.percentile(rel, 95)):.3f} %; "
        f"total flux ratio lumlab / Mitsuba {float(y_lum.sum() / y_mts.sum()):.5f}"
    )
    if mean_rel >= 0.01:
        sys.exit("the two images differ by 1 % or more on lit pixels")


if __name__ == "__main__":
    main()
