#!/usr/bin/env python3
"""lumlab's CPU reference against Mitsuba 3, both `scalar_rgb` and `llvm_ad_rgb`
(JIT-compiled SIMD wavefront over Embree): the same triangles, camera, light,
resolution and samples, on the same threads, several alternating runs.

Races (each prints its times and the speed-up Mitsuba / lumlab, median and
[min–max] over --runs):
  small    plane + box, 14 triangles, 256×192, 64 spp, point light, Lambert;
  model    a real model of ≥ 100 k triangles (--model, a GLB file), 512×384,
           32 spp, point light, Lambert; see MODEL below;
  million  1 M generated triangles (a ground and 25 bumpy spheres), 512×384,
           16 spp, point light, Lambert;
  sphere   plane + box under a sphere light (R = 0.5 m), 256×192: the time each
           needs to bring the RMSE against its own converged image below 1 % of
           that image's mean luminance (lumlab: the pixel centre, N light
           samples; Mitsuba: N samples per pixel, one emitter sample each),
           N the least on the finest ladder each sampler takes (every count
           for lumlab's strata, squares for Mitsuba's stratified sampler).

Times: "render" is the render call alone (lumlab: the `N spp: S s` of its
summary line, which excludes loading, the BVH build and file output; Mitsuba:
`mi.render` on a loaded scene, llvm's kernels compiled by a warm-up render).
"process" is the whole `lumlab reference` command (start, scene file, BVH,
render, EXR file), timed from outside.

Conventions matched on both sides:
  - +Y up, right-handed, metres; the camera looks from eye at target with the
    vertical field of view (Mitsuba: `perspective`, fov_axis = 'y');
  - a point light of power P has intensity I = P / 4π W/sr (Mitsuba `point`);
    a sphere light of power P and radius R has radiance P / (4π² R²)
    (Mitsuba: a `sphere` with an `area` emitter);
  - f_r = c / π (lumlab --k 1; Mitsuba `diffuse` with reflectance c);
  - face normals on both sides (no vertex normals are written);
  - one emitter sample, no BSDF sample per pixel sample (Mitsuba `direct`);
  - box filter, linear radiance in W/m²/sr (lumlab EXR, Mitsuba hdrfilm).
Both renderers read identical f32 triangles: the script writes them as GLB
for lumlab and as binary PLY for Mitsuba.

Mitsuba 3.5.2: later versions (3.6 to 3.9) emit `llvm.maximum`, which the
LLVM 15 of Debian's Mesa cannot compile for x86 ("Cannot select: fmaximum")
under the sphere emitter; llvm_ad_rgb needs libLLVM (DRJIT_LIBLLVM_PATH=
/usr/lib/x86_64-linux-gnu/libLLVM-15.so.1 if it is not found).

MODEL: a public Khronos sample, not committed. 2CylinderEngine (121 k
triangles) is in KhronosGroup/glTF-Sample-Models,
2.0/2CylinderEngine/glTF-Binary/2CylinderEngine.glb (also in assimp's
test/models/glTF2/2CylinderEngine-glTF-Binary/). Without --model the script
fetches it from there once into $XDG_CACHE_HOME/lumlab (~/.cache/lumlab) and
says so when its SHA-256 is not that of the copy the README's numbers were
measured on. Its node transforms are applied, then it is centred and scaled
to 4 m across.

    pip install mitsuba==3.5.2 drjit==0.4.6
    cargo build --release
    python3 bench/mitsuba_compare.py [--model 2CylinderEngine.glb] [--runs 5]
"""

import argparse
import math
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from race_scenes import MODEL_NAME, fetched_model, million_scene, model_scene, small_scene, write_glb, write_ply

FOVY_DEG = 40.0
POWER_W = 800.0
SPHERE_RADIUS_M = 0.5
VARIANTS = ("scalar_rgb", "llvm_ad_rgb")
# Seconds of rest before each timed run (see `settle`).
SETTLE_S = 0.05
# Rec. 709 luminance, as lumlab's noise estimate uses.
LUMINANCE = np.array([0.2126, 0.7152, 0.0722])


# ---------------------------------------------------------------- renderers


def start_mitsuba(variant, threads):
    """Mitsuba's variant; the thread pool is set once per process (setting it
    again between renders can leave it waiting forever)."""
    import drjit as dr
    import mitsuba as mi

    mi.set_variant(variant)
    if not getattr(start_mitsuba, "threads_set", False):
        # Dr.Jit's pool counts its workers beside the calling thread, which
        # works too: a count of 1 kept two cores busy (CPU time twice the
        # wall time, both variants), 0 one. `threads` threads in all, as
        # RAYON_NUM_THREADS gives lumlab.
        dr.set_thread_count(max(threads - 1, 0))
        start_mitsuba.threads_set = True
    return mi


def load_mitsuba(mi, folder, scene, radius, sampler):
    width, height = scene.size
    d = {
        "type": "scene",
        "integrator": {"type": "direct", "emitter_samples": 1, "bsdf_samples": 0},
        "sensor": {
            "type": "perspective",
            "fov": FOVY_DEG,
            "fov_axis": "y",
            "near_clip": 0.01,
            "far_clip": 1000.0,
            "to_world": mi.ScalarTransform4f().look_at(origin=scene.eye, target=scene.target, up=(0.0, 1.0, 0.0)),
            "film": {"type": "hdrfilm", "width": width, "height": height, "rfilter": {"type": "box"},
                     "pixel_format": "rgb"},  # fmt: skip
            "sampler": {"type": sampler, "sample_count": scene.spp},
        },
    }
    if radius > 0.0:
        radiance = POWER_W / (4.0 * math.pi**2 * radius**2)
        d["light"] = {
            "type": "sphere",
            "center": scene.light,
            "radius": radius,
            "emitter": {"type": "area", "radiance": {"type": "rgb", "value": [radiance] * 3}},
        }
    else:
        intensity = POWER_W / (4.0 * math.pi)
        d["light"] = {"type": "point", "position": scene.light, "intensity": {"type": "rgb", "value": [intensity] * 3}}
    for name, positions, tris, color in scene.meshes:
        path = folder / f"{name}.ply"
        if not path.exists():
            write_ply(path, positions, tris)
        d[name] = {
            "type": "ply",
            "filename": str(path),
            "face_normals": True,
            "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": list(color)}},
        }
    return mi.load_dict(d)


def settle():
    """A pause before each timed run, lumlab's or Mitsuba's: Dr.Jit's worker
    threads spin on for some milliseconds after a render, and a lumlab process
    started at once shared the two cores with them (the sphere race's 7 ms
    render read 10-12 ms; 20 ms of pause was enough)."""
    time.sleep(SETTLE_S)


def render_mitsuba(mi, loaded, spp, seed=0):
    settle()
    start = time.perf_counter()
    image = mi.render(loaded, spp=spp, seed=seed)
    image = np.array(image)[:, :, :3]  # waits for llvm's kernels to finish
    return image, time.perf_counter() - start


def lumlab_command(lumlab, glb, exr, scene, spp, radius=0.0, light_samples=1, extra=()):
    """The race's `lumlab reference` command line: the scene in `glb`, the image to `exr`."""
    vec = lambda v: ",".join(repr(float(x)) for x in v)
    width, height = scene.size
    return [
        str(lumlab), "reference", "--yes", "--ground", "off",
        "--scene", str(glb),
        "--camera", f"{vec(scene.eye)}:{vec(scene.target)}:{FOVY_DEG}",
        "--size", f"{width}x{height}",
        "--light", vec(scene.light),
        "--power", repr(POWER_W),
        "--light-radius", repr(radius),
        "--light-samples", str(light_samples),
        "--color", "1,1,1",
        "--k", "1",
        "--spp", str(spp),
        "--out", str(exr),
        *extra,
    ]  # fmt: skip


def run_timed(command, threads, extra_env=None):
    """One lumlab run: (whole process s, render s, its summary line); the
    render is the summary's `N spp: S s` (no loading, BVH or file output).
    `extra_env`: variables set for this run only."""
    env = {**os.environ, "RAYON_NUM_THREADS": str(threads), **(extra_env or {})}
    settle()
    start = time.perf_counter()
    run = subprocess.run(command, env=env, capture_output=True, text=True)
    wall_s = time.perf_counter() - start
    if run.returncode != 0:
        sys.exit(f"{command[0]} failed ({run.returncode}): {run.stderr.strip()}")
    summary = run.stderr.strip().splitlines()[-1]
    found = re.search(r"spp: ([0-9.]+) s", summary)
    render_s = float(found.group(1)) if found else float("nan")
    return wall_s, render_s, summary


def run_lumlab(lumlab, folder, scene, threads, spp, radius=0.0, light_samples=1, extra=()):
    glb = folder / "scene.glb"
    if not glb.exists():
        write_glb(glb, scene)
    exr = folder / "lumlab.exr"
    command = lumlab_command(lumlab, glb, exr, scene, spp, radius, light_samples, extra)
    wall_s, render_s, summary = run_timed(command, threads)
    import mitsuba as mi

    if mi.variant() is None:
        # Reading a bitmap needs a variant (the sphere race alone has none yet).
        mi.set_variant("scalar_rgb")
    image = np.array(mi.Bitmap(str(exr)))[:, :, :3]
    return image, wall_s, render_s, summary


# ---------------------------------------------------------------- races


def spread(values):
    v = sorted(values)
    return f"{float(np.median(v)):.2f}× [{v[0]:.2f}–{v[-1]:.2f}]"


def difference(lum, mts):
    y_lum, y_mts = lum @ LUMINANCE, mts @ LUMINANCE
    lit = (y_lum > 0.0) & (y_mts > 0.0)
    rel = np.abs(y_lum[lit] - y_mts[lit]) / y_mts[lit]
    # The median: edge pixels differ by their own sampling of the pixel square.
    return float(np.median(rel)), float(y_lum.sum() / y_mts.sum())


def point_race(name, scene, args, folder):
    """Alternating runs of lumlab and both Mitsuba variants on one scene."""
    print(f"\n== {name}: {scene.triangles()} triangles, {scene.size[0]}×{scene.size[1]}, {scene.spp} spp, point light")
    times = {k: [] for k in ("process", "render", *VARIANTS)}
    summary, loaded, images = "", {}, {}
    for variant in VARIANTS:
        mi = start_mitsuba(variant, args.threads)
        loaded[variant] = load_mitsuba(mi, folder, scene, 0.0, args.mitsuba_sampler)
        images[variant], _ = render_mitsuba(mi, loaded[variant], scene.spp)  # warm-up, kernels compiled
    for _ in range(args.runs):
        lum, wall_s, render_s, summary = run_lumlab(args.lumlab, folder, scene, args.threads, scene.spp)
        times["process"].append(wall_s)
        times["render"].append(render_s)
        for variant in VARIANTS:
            mi = start_mitsuba(variant, args.threads)
            _, seconds = render_mitsuba(mi, loaded[variant], scene.spp)
            times[variant].append(seconds)
    med = {k: float(np.median(v)) for k, v in times.items()}
    print(f"lumlab:  {summary}")
    print(f"lumlab   render {med['render']:.3f} s, process {med['process']:.3f} s (medians of {args.runs})")
    for variant in VARIANTS:
        ratio_render = [m / l for m, l in zip(times[variant], times["render"])]
        ratio_process = [m / l for m, l in zip(times[variant], times["process"])]
        print(
            f"{variant:12s} render {med[variant]:.3f} s; lumlab faster by: render {spread(ratio_render)}, "
            f"whole lumlab process {spread(ratio_process)}"
        )
    median_rel, flux = difference(lum, images["llvm_ad_rgb"])
    print(f"images: median relative difference on lit pixels {100 * median_rel:.3f} %, flux ratio {flux:.4f}")
    return {
        "scene": name,
        "lumlab": med["render"],
        "process": med["process"],
        **{v: med[v] for v in VARIANTS},
        **{f"{v}/render": [m / l for m, l in zip(times[v], times["render"])] for v in VARIANTS},
        **{f"{v}/process": [m / l for m, l in zip(times[v], times["process"])] for v in VARIANTS},
    }


def rmse_ratio(image, converged):
    y, yc = image @ LUMINANCE, converged @ LUMINANCE
    return float(np.sqrt(np.mean((y - yc) ** 2)) / yc.mean())


def first_below(render, counts, converged, target):
    """The first count whose image's RMSE falls below target: (count, rmse)."""
    for n in counts:
        error = rmse_ratio(render(n)[0], converged)
        if error < target:
            return n, error
    sys.exit(f"RMSE still {100 * error:.2f} % at {counts[-1]} samples")


def sphere_race(args, folder):
    """Time to RMSE < 1 % of the mean, each against its own converged image:
    the sample count that reaches it is found once, then timed --runs times."""
    scene = small_scene()
    scene.spp = 1
    target = 0.01
    print(f"\n== sphere light R = {SPHERE_RADIUS_M} m, plane + box, {scene.size[0]}×{scene.size[1]}: "
          f"time to RMSE < {100 * target:.0f} % of the mean")  # fmt: skip

    def lumlab(n, extra=()):
        image, _, seconds, _ = run_lumlab(args.lumlab, folder, scene, args.threads, 1, SPHERE_RADIUS_M, n, extra)
        return image, seconds

    # lumlab's default integrates the diffuse part in closed form wherever no
    # shadow ray can be blocked; `--sample-everywhere` samples it there too
    # (plain stratified Monte Carlo, what Mitsuba does), timed beside it.
    plain = ("--sample-everywhere",)

    lum_conv, _ = lumlab(4096)
    mi = start_mitsuba("llvm_ad_rgb", args.threads)
    loaded = {"llvm_ad_rgb": load_mitsuba(mi, folder, scene, SPHERE_RADIUS_M, args.race_sampler)}
    mts_conv = np.mean([render_mitsuba(mi, loaded["llvm_ad_rgb"], 4096, seed)[0] for seed in range(2)], axis=0)
    median_rel, flux = difference(lum_conv, mts_conv)
    print(f"converged images: median relative difference on lit pixels {100 * median_rel:.3f} %, flux ratio {flux:.4f}")
    # Each count on the finest ladder its sampler takes: lumlab stratifies
    # any count of light samples (n = a × b strata); Mitsuba's stratified
    # sampler rounds a count to a square, so it is offered the squares.
    ladder = [*range(4, 65), 81, 100, 144, 196, 256]
    lum_n, _ = first_below(lumlab, ladder, lum_conv, target)
    plain_n, _ = first_below(lambda n: lumlab(n, plain), ladder, lum_conv, target)
    mts_n, _ = first_below(
        lambda n: render_mitsuba(mi, loaded["llvm_ad_rgb"], n, 100),
        [k * k for k in range(2, 46)],
        mts_conv,
        target,
    )
    mi = start_mitsuba("scalar_rgb", args.threads)
    loaded["scalar_rgb"] = load_mitsuba(mi, folder, scene, SPHERE_RADIUS_M, args.race_sampler)
    keys = ("lumlab", "plain", *VARIANTS)
    times, errors = {k: [] for k in keys}, {k: [] for k in keys}
    for run in range(args.runs):
        for key, n, extra in (("lumlab", lum_n, ()), ("plain", plain_n, plain)):
            image, seconds = lumlab(n, extra)
            times[key].append(seconds)
            errors[key].append(rmse_ratio(image, lum_conv))
        for variant in VARIANTS:
            mi = start_mitsuba(variant, args.threads)
            image, seconds = render_mitsuba(mi, loaded[variant], mts_n, run)
            times[variant].append(seconds)
            errors[variant].append(rmse_ratio(image, mts_conv))
    worst = lambda k: f"RMSE {100 * max(errors[k]):.2f} % at worst"
    print(f"lumlab       {lum_n} light samples, {worst('lumlab')}: {np.median(times['lumlab']):.3f} s")
    llvm_over_plain = [m / l for m, l in zip(times["llvm_ad_rgb"], times["plain"])]
    print(f"lumlab --sample-everywhere {plain_n} light samples, {worst('plain')}: "
          f"{np.median(times['plain']):.3f} s; faster than llvm_ad_rgb by {spread(llvm_over_plain)}")  # fmt: skip
    for variant in VARIANTS:
        ratios = [m / l for m, l in zip(times[variant], times["lumlab"])]
        print(f"{variant:12s} {mts_n} spp ({args.race_sampler}), {worst(variant)}: "
              f"{np.median(times[variant]):.3f} s; lumlab faster by {spread(ratios)}")  # fmt: skip
    return {
        "scene": "sphere light, equal error",
        "lumlab": float(np.median(times["lumlab"])),
        **{v: float(np.median(times[v])) for v in VARIANTS},
        **{f"{v}/render": [m / l for m, l in zip(times[v], times["lumlab"])] for v in VARIANTS},
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--lumlab", default="target/release/lumlab", help="the lumlab binary")
    parser.add_argument("--model", type=Path, help="a GLB of ≥ 100 k triangles (default: MODEL above, fetched)")
    parser.add_argument("--only", nargs="*", choices=["small", "model", "million", "sphere"], help="races to run")
    parser.add_argument("--runs", type=int, default=5, help="alternating runs of each renderer")
    parser.add_argument("--threads", type=int, default=2, help="threads for every renderer")
    parser.add_argument("--mitsuba-sampler", default="independent", help="Mitsuba's sampler for the point-light races")
    parser.add_argument("--race-sampler", default="stratified", help="Mitsuba's sampler for the sphere-light race")
    parser.add_argument("--keep", type=Path, help="keep the scene files and images in this folder")
    args = parser.parse_args()
    if not Path(args.lumlab).exists():
        sys.exit(f"no lumlab binary at {args.lumlab} (cargo build --release)")
    races = args.only or ["small", "model", "million", "sphere"]
    if "model" in races:
        if args.model is None:
            args.model = fetched_model()
        elif not args.model.exists():
            sys.exit(f"no model at {args.model} (leave --model out to fetch {MODEL_NAME})")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for race in races:
            folder = (args.keep or Path(tmp)) / race
            folder.mkdir(parents=True, exist_ok=True)
            if race == "sphere":
                rows.append(sphere_race(args, folder))
                continue
            scene = {"small": small_scene, "million": million_scene, "model": lambda: model_scene(args.model)}[race]()
            rows.append(point_race(race, scene, args, folder))
    print("\n| scene | lumlab s | scalar_rgb s | llvm_ad_rgb s | vs scalar | vs llvm | process vs scalar |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        process = spread(r["scalar_rgb/process"]) if "scalar_rgb/process" in r else "–"
        print(
            f"| {r['scene']} | {r['lumlab']:.3f} | {r['scalar_rgb']:.3f} | {r['llvm_ad_rgb']:.3f} | "
            f"{spread(r['scalar_rgb/render'])} | {spread(r['llvm_ad_rgb/render'])} | {process} |"
        )


if __name__ == "__main__":
    main()
