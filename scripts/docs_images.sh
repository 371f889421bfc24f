#!/usr/bin/env bash
# Regenerates the README's figures with the release binary:
#   docs/views/VIEW.png      every debug view of the default scene
#   docs/filters/FILTER.png  the occluder's shadow under a sphere light, every filter and the reference
#   docs/energy.png          the albedo curves
#   docs/pareto.png, docs/report.csv   from a full `lumlab report` (kept in target/docs-report)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --locked
lumlab=target/release/lumlab
mkdir -p docs/views docs/filters
size=480x270
for view in shaded depth visibility ndotl irradiance brdf diffuse specular texel-density frustum ref-visibility error; do
  "$lumlab" render --size "$size" --view "$view" --out "docs/views/$view.png"
done
# ΔE2000 needs a spectral light: the RGB product against the spectral result under A.
"$lumlab" render --size "$size" --view delta-e --illuminant A --out docs/views/delta-e.png
# A close look at the thin occluder's shadow: R = 0.25 m gives a wide penumbra.
close=(--size "$size" --camera=-3.7,2.4,2.4:-3.7,0,-0.1:40 --light-radius 0.25 --shadow-res 1024)
for filter in none hw2x2 pcf poisson pcss vsm evsm msm; do
  "$lumlab" render "${close[@]}" --filter "$filter" --pcf-size 5 --out "docs/filters/$filter.png"
done
"$lumlab" reference "${close[@]}" --light-samples 256 --out docs/filters/reference.png
"$lumlab" energy --plot docs/energy.png > /dev/null
"$lumlab" report --out target/docs-report
cp target/docs-report/pareto.png target/docs-report/report.csv docs/
