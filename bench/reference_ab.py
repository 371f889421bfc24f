#!/usr/bin/env python3
"""Two builds of lumlab's CPU reference against each other, one change at a
time: the measurement the speed journal (docs/journal/reference*.md) reports
for every step it kept or dropped.

For one race scene of mitsuba_compare.py (from race_scenes.py: the same
triangles, camera, light, size and samples), both binaries render in
alternation, A then B, then B then A, so that a slow spell of the host falls
on both alike; the script prints each one's render time (the `N spp: S s` of
its summary line: no loading, no BVH build, no file output), its BVH build and
its whole process, as the median and [min–max] of --runs, and the ratio B / A
of the render medians. It then says whether the two wrote the same EXR bytes:
a change to the walks or the tests' order must keep every pixel, since each
ray's answer is exact.

With --branches, both also run once under valgrind's cachegrind with its
branch simulation, on one thread: instructions and mispredicted branches, the
counts that told which steps pay on this kind of host (wall times move by
some ±5 % from one spell to the next; these do not move at all).

    cargo build --release && cp target/release/lumlab /tmp/lumlab.a
    # ...the change, then:
    cargo build --release
    python3 bench/reference_ab.py /tmp/lumlab.a target/release/lumlab --scene small --runs 12
    python3 bench/reference_ab.py /tmp/lumlab.a target/release/lumlab --scene sphere --runs 20
    python3 bench/reference_ab.py /tmp/lumlab.a target/release/lumlab \\
        --scene model --model /work/models/2CylinderEngine.glb --branches

An experiment that one build switches by an environment variable it reads
once a process (a temporary one) runs against itself, which rules out any
difference of code layout between the two sides (--env-a sets A's):

    python3 bench/reference_ab.py target/release/lumlab target/release/lumlab \\
        --scene million --env-b LUMLAB_TRY=1

Only numpy is needed (Mitsuba is not: no image is read back).
"""

import argparse
import filecmp
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from mitsuba_compare import SPHERE_RADIUS_M, lumlab_command, run_timed
from race_scenes import million_scene, model_scene, small_scene, write_glb


def run(argv, threads, env):
    """One run: (render s, BVH s, process s), from its summary line and the clock."""
    process_s, render_s, summary = run_timed(argv, threads, env)
    if math.isnan(render_s):
        sys.exit(f"no render time in {argv[0]}'s summary line: {summary}")
    bvh = re.search(r"BVH ([0-9.]+) s", summary)
    return render_s, float(bvh.group(1)) if bvh else float("nan"), process_s


def spread(values):
    v = sorted(values)
    return f"{statistics.median(v):.4f} s [{v[0]:.4f}–{v[-1]:.4f}]"


def branches(argv, env):
    """(instructions, mispredicted branches) of one run under cachegrind, one thread."""
    with tempfile.NamedTemporaryFile(suffix=".cg") as out:
        done = subprocess.run(
            ["valgrind", "--tool=cachegrind", "--cache-sim=no", "--branch-sim=yes",
             f"--cachegrind-out-file={out.name}", *argv],
            env={**os.environ, "RAYON_NUM_THREADS": "1", **env}, capture_output=True, text=True,
        )  # fmt: skip
    if done.returncode != 0:
        sys.exit(f"valgrind failed ({done.returncode}): {done.stderr.strip()[-400:]}")
    count = lambda label: int(re.search(rf"{label}:\s+([0-9,]+)", done.stderr).group(1).replace(",", ""))
    return count("I\\s+refs"), count("Mispredicts")


def variable(text):
    """NAME=VALUE of --env-a and --env-b, as a pair."""
    name, sep, value = text.partition("=")
    if not sep or not name:
        raise argparse.ArgumentTypeError(f"{text!r} is not NAME=VALUE")
    return name, value


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("a", type=Path, help="the build before the change")
    parser.add_argument("b", type=Path, help="the build after it")
    parser.add_argument(
        "--scene",
        choices=["small", "model", "million", "sphere"],
        default="small",
        help="a race's scene; sphere: the small one under the sphere-light race's light, at 1 spp",
    )
    parser.add_argument("--model", type=Path, help="the GLB of the model scene (see mitsuba_compare.py)")
    parser.add_argument("--spp", type=int, help="samples per pixel (default: the race's)")
    parser.add_argument("--light-samples", type=int, default=10, help="the sphere scene's (the race found 10)")
    parser.add_argument("--runs", type=int, default=10, help="runs of each build, alternated")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--branches", action="store_true", help="also count with cachegrind (valgrind)")
    for k in ("a", "b"):
        parser.add_argument(f"--env-{k}", metavar="NAME=VALUE", action="append", default=[], type=variable,
                            help=f"an environment variable for {k.upper()}'s runs only (repeatable)")  # fmt: skip
    args = parser.parse_args()
    for binary in (args.a, args.b):
        if not binary.is_file():
            sys.exit(f"no lumlab binary at {binary}")
    if args.scene == "model" and not (args.model and args.model.is_file()):
        sys.exit("the model scene needs --model FILE.glb")
    if args.branches and not shutil.which("valgrind"):
        sys.exit("--branches needs valgrind (apt-get install -y valgrind)")
    sphere = args.scene == "sphere"
    scene = {
        "small": small_scene,
        "sphere": small_scene,
        "million": million_scene,
        "model": lambda: model_scene(args.model),
    }[args.scene]()
    spp = args.spp or (1 if sphere else scene.spp)
    light = (SPHERE_RADIUS_M, args.light_samples) if sphere else (0.0, 1)
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        glb = folder / "scene.glb"
        write_glb(glb, scene)
        argv = {
            k: lumlab_command(b, glb, folder / f"{k}.exr", scene, spp, *light) for k, b in (("A", args.a), ("B", args.b))
        }
        times = {"A": [], "B": []}
        env = {"A": dict(args.env_a), "B": dict(args.env_b)}
        for i in range(args.runs):
            for k in ("AB" if i % 2 == 0 else "BA"):
                times[k].append(run(argv[k], args.threads, env[k]))
        same = filecmp.cmp(folder / "A.exr", folder / "B.exr", shallow=False)
        lit = f", sphere light R = {light[0]} m, {light[1]} light samples" if sphere else ""
        print(f"{args.scene}: {scene.triangles()} triangles, {scene.size[0]}×{scene.size[1]}, {spp} spp{lit}, "
              f"{args.threads} threads, {args.runs} alternated runs each")  # fmt: skip
        for k, binary in (("A", args.a), ("B", args.b)):
            render, bvh, process = zip(*times[k])
            switches = "".join(f" {name}={value}" for name, value in env[k].items())
            print(f"  {k} {binary}{switches}: render {spread(render)}, BVH {spread(bvh)}, process {spread(process)}")
        ratio = statistics.median(t[0] for t in times["B"]) / statistics.median(t[0] for t in times["A"])
        print(f"  render B / A: {ratio:.3f} (medians); EXRs {'the same bytes' if same else 'DIFFERENT'}")
        if args.branches:
            for k in ("A", "B"):
                instructions, mispredicted = branches(argv[k], env[k])
                print(f"  {k} cachegrind, 1 thread: {instructions / 1e6:,.0f} M instructions, "
                      f"{mispredicted / 1e6:.2f} M mispredicted branches")  # fmt: skip
    if not same:
        sys.exit(1)


if __name__ == "__main__":
    main()
