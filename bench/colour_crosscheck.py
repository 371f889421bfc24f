#!/usr/bin/env python3
"""Cross-checks `lumlab colour --format csv` against colour-science.

A one-off check, never a dependency of the product:

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install colour-science
    cargo build && /tmp/venv/bin/python bench/colour_crosscheck.py target/debug/lumlab [--iec] [-- lumlab options]

colour-science computes every column of the contract on its own: spectral
XYZ with its ASTM E308 method (on the same 5 nm, 380-780 nm tables: Lagrange
interpolation to 1 nm, then summation) and with plain 5 nm integration; the
RGB product through its own sRGB colourspace; Lab and CIEDE2000 with its own
code. The script prints the largest disagreement per column and illuminant.
"""

import csv
import io
import subprocess
import sys
import warnings

import numpy as np

warnings.filterwarnings("ignore")
import colour  # noqa: E402

SHAPE = colour.SpectralShape(380, 780, 5)
CMFS = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"].copy().align(SHAPE)
CHECKER = colour.SDS_COLOURCHECKERS["ColorChecker N Ohta"]
SRGB = colour.RGB_COLOURSPACES["sRGB"]
# lumlab derives the sRGB matrix from the primaries and the D65 white
# (SMPTE RP 177); colour-science's sRGB defaults to IEC 61966-2-1's matrix
# rounded to 4 decimals. `--iec` compares against the rounded one instead.
IEC = "--iec" in sys.argv
RGB_TO_XYZ = SRGB.matrix_RGB_to_XYZ if IEC else colour.normalised_primary_matrix(SRGB.primaries, SRGB.whitepoint)
XYZ_TO_RGB = SRGB.matrix_XYZ_to_RGB if IEC else np.linalg.inv(RGB_TO_XYZ)


def illuminant_sd(name):
    if name.startswith("blackbody:"):
        return colour.sd_blackbody(float(name.split(":")[1]), SHAPE)
    return colour.SDS_ILLUMINANTS[name].copy().align(SHAPE)


def xyz(sd, illuminant, method):
    return colour.sd_to_XYZ(sd.copy().align(SHAPE), CMFS, illuminant, method=method)


def to_rgb(XYZ):
    return np.dot(XYZ_TO_RGB, XYZ)


def to_xyz(RGB):
    return np.dot(RGB_TO_XYZ, RGB)


def main():
    args = [a for a in sys.argv[1:] if a != "--iec"]
    binary = args[0] if args else "target/debug/lumlab"
    extra = args[1:]
    out = subprocess.run([binary, "colour", "--format", "csv", *extra], capture_output=True, text=True, check=True)
    rows = list(csv.DictReader(io.StringIO(out.stdout)))
    d65 = illuminant_sd("D65")
    names = list(CHECKER.keys())
    by_illuminant = {}
    for i, row in enumerate(rows):
        by_illuminant.setdefault(row["illuminant"], []).append(row)
    matrix = "IEC 61966-2-1 rounded" if IEC else "derived"
    print(f"colour-science {colour.__version__} ({matrix} sRGB matrix); largest |difference| against lumlab:")
    print(f"{'illuminant':<16}{'XYZ (ASTM E308)':>17}{'XYZ (5 nm sum)':>16}{'approx XYZ':>12}{'dE2000':>10}  mean dE2000 (lumlab / colour-science)")
    for name, patch_rows in by_illuminant.items():
        ill = illuminant_sd(name)
        white = xyz(colour.sd_ones(SHAPE), ill, "Integration")
        light_rgb = to_rgb(white / 100)
        worst = np.zeros(4)
        ours_de, their_de = [], []
        for p, row in enumerate(patch_rows):
            sd = CHECKER[names[p]]
            ours = np.array([float(row[c]) for c in ("X", "Y", "Z")])
            ours_approx = np.array([float(row[c]) for c in ("approx_X", "approx_Y", "approx_Z")])
            astm = xyz(sd, ill, "ASTM E308")
            summed = xyz(sd, ill, "Integration")
            patch_rgb = to_rgb(xyz(sd, d65, "Integration") / 100)
            approx = 100 * to_xyz(patch_rgb * light_rgb)
            white_xy = colour.XYZ_to_xy(white / 100)
            de = colour.delta_E(
                colour.XYZ_to_Lab(summed / 100, white_xy),
                colour.XYZ_to_Lab(approx / 100, white_xy),
                method="CIE 2000",
            )
            worst = np.maximum(
                worst,
                [
                    np.abs(ours - astm).max(),
                    np.abs(ours - summed).max(),
                    np.abs(ours_approx - approx).max(),
                    abs(float(row["delta_e2000"]) - de),
                ],
            )
            ours_de.append(float(row["delta_e2000"]))
            their_de.append(de)
        print(
            f"{name:<16}{worst[0]:>17.2e}{worst[1]:>16.2e}{worst[2]:>12.2e}{worst[3]:>10.2e}"
            f"  {np.mean(ours_de):.4f} / {np.mean(their_de):.4f}"
        )


if __name__ == "__main__":
    main()
