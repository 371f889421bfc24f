#!/usr/bin/env python3
"""Exports the spectral tables of `lumlab colour` to assets/colour/*.csv.

Run once, by hand, when the tables must be regenerated:

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install colour-science
    /tmp/venv/bin/python scripts/export_colour_tables.py

colour-science (BSD-3-Clause) is only the carrier of the published data; the
product never depends on Python: the CSV files are checked in and embedded in
the binary with include_str!. Every file names its primary source in its
header. All tables are sampled on 380-780 nm every 5 nm (81 rows), the range
and interval of CIE 015:2018's 5 nm tables and of N. Ohta's reflectances.
"""

from pathlib import Path

import colour

OUT = Path(__file__).resolve().parent.parent / "assets" / "colour"
WAVELENGTHS = range(380, 781, 5)
ILLUMINANTS = ["D65", "A", "FL2", "FL11", "LED-B3"]
# Ohta's names, shortened for the neutrals (the density stays in the docs).
PATCHES = {
    "dark skin": "dark skin",
    "light skin": "light skin",
    "blue sky": "blue sky",
    "foliage": "foliage",
    "blue flower": "blue flower",
    "bluish green": "bluish green",
    "orange": "orange",
    "purplish blue": "purplish blue",
    "moderate red": "moderate red",
    "purple": "purple",
    "yellow green": "yellow green",
    "orange yellow": "orange yellow",
    "blue": "blue",
    "green": "green",
    "red": "red",
    "yellow": "yellow",
    "magenta": "magenta",
    "cyan": "cyan",
    "white 9.5 (.05 D)": "white 9.5",
    "neutral 8 (.23 D)": "neutral 8",
    "neutral 6.5 (.44 D)": "neutral 6.5",
    "neutral 5 (.70 D)": "neutral 5",
    "neutral 3.5 (1.05 D)": "neutral 3.5",
    "black 2 (1.5 D)": "black 2",
}


def number(v):
    """The published digits, without float noise (colour-science holds
    z_bar(650 nm) as -1.9e-21 where CIE publishes 0)."""
    text = f"{round(float(v), 12):.10g}"
    return "0" if text == "-0" else text


def write(name, header, columns, sds):
    lines = [f"# {h}" for h in header]
    lines.append(
        f"# Exported by scripts/export_colour_tables.py from colour-science {colour.__version__}."
    )
    lines.append(",".join(["nm", *columns]))
    for nm in WAVELENGTHS:
        lines.append(",".join([str(nm), *(number(sd[nm]) for sd in sds)]))
    (OUT / name).write_text("\n".join(lines) + "\n", encoding="utf-8")


def main():
    OUT.mkdir(parents=True, exist_ok=True)
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    write(
        "cie1931_2deg.csv",
        [
            "CIE 1931 2 degree standard observer colour-matching functions x_bar, y_bar, z_bar.",
            "Source: CIE 015:2018 Colorimetry, 4th ed., doi:10.25039/TR.015.2018 (the CIE 1931",
            "standard observer's 1 nm table, as distributed by CVRL, cvrl.ioo.ucl.ac.uk, 'Older CIE",
            "standards'), sampled every 5 nm.",
        ],
        ["x_bar", "y_bar", "z_bar"],
        [cmfs.signals[c] for c in ("x_bar", "y_bar", "z_bar")],
    )
    write(
        "illuminants.csv",
        [
            "Relative spectral power of CIE illuminants D65, A, FL2, FL11 and LED-B3 (S(560 nm) = 100 for D65 and A).",
            "Source: CIE 015:2018 Colorimetry, 4th ed., doi:10.25039/TR.015.2018, its 5 nm tables",
            "(D65, A, FL2 and FL11 as in the CIE 15:2004 tables; LED-B3 is new in CIE 015:2018).",
        ],
        ILLUMINANTS,
        [colour.SDS_ILLUMINANTS[n] for n in ILLUMINANTS],
    )
    checker = colour.SDS_COLOURCHECKERS["ColorChecker N Ohta"]
    write(
        "colorchecker_ohta.csv",
        [
            "Spectral reflectance (0..1) of the 24 patches of the ColorChecker Classic, in chart order.",
            "Source: N. Ohta, The Basis of Color Reproduction Engineering (Corona, 1997), identical",
            "to ISO 17321-1:2012 Annex; also Munsell Color Science Laboratory, MacbethColorChecker.xls.",
        ],
        list(PATCHES.values()),
        [checker[n] for n in PATCHES],
    )


if __name__ == "__main__":
    main()
