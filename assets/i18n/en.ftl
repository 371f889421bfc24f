# The app's text in English. Keys are shared with fr.ftl (the tests check
# that both files have the same keys and placeholders). Numbers arrive
# formatted, with their unit, and keep a decimal point in both languages.
# Formulas (E = I cos θ / r², f_r = ...) stay as they are in both.

## The language menu, errors

menu-language = Language
menu-language-tip = The language of the app's text (the command line stays in English)
error-frame = Error: { $message }

## Top bar, status bar, panels (lab/panels.rs)

top-undo = Undo
top-undo-tip = Undo the last settings change (Ctrl+Z)
top-redo = Redo
top-redo-tip = Redo (Ctrl+Shift+Z or Ctrl+Y)
top-reset-view = Reset view
top-reset-view-tip = Camera back to the scene's own view (R)
top-split = Split A | B
top-split-tip = Compare two settings side by side (S)
top-settings = Settings
top-settings-tip = Show the settings panel (F9 hides both panels)
top-analysis = Analysis
top-analysis-tip = Show the probe, energy, reference and timings panel
top-help = Help (F1)
top-help-tip = Keyboard and mouse shortcuts
status-hint = Drag: orbit · Shift+drag: pan · wheel: zoom · click: probe · F1: help
status-impossible = Impossible set-up: { $first }
status-impossible-more = Impossible set-up: { $first } (+{ $more } more)
status-impossible-tip =
    { $lines }
    The GPU and the CPU reference disagree on such a set-up.
section-experiments = Experiments
section-scene = Scene
section-light = Light
section-material = Material
section-shadow = Shadow
section-view = View
section-files = Files
section-probe = Pixel probe
section-energy = Energy: albedo a(θ)
section-reference = Reference and error
section-timings = Timings
lobe-at-probe = at the probed point
lobe-at-centre = light to scene centre, n = +Y

## Desktop (lab/desktop.rs)

menu-file = File

## Status lines (lab/apply.rs)

status-settings-saved = settings saved to { $path }
status-exr-written = linear values written to { $path }
status-reset-everything = everything reset (Ctrl+Z brings the settings back)
status-preset = preset: { $preset } (Ctrl+Z to undo)
error-settings-scene-missing = its scene '{ $scene }' cannot be found
status-settings-loaded = settings loaded from { $path } (Ctrl+Z to undo)
scene-built-in = built-in
status-scene = scene: { $name }, { $triangles } triangles
status-scene-warnings = {" "}({ $count } { $count ->
        [one] warning
       *[other] warnings
    }: { $warnings })
status-loading = loading { $path }…
error-cannot-start-loading = cannot start loading: { $message }
error-no-image-to-export = no image to export yet
error-image-changed-size = the image changed size while reading it; try again

## Shadow panel (shadow.rs)

filter-none-tip = One depth test at the nearest texel: V ∈ {"{"}0, 1{"}"}, hard aliased edges
filter-hw2x2-tip = The hardware comparison sampler: 2×2 depth tests, bilinearly weighted
filter-pcf-tip = Percentage-closer filtering: V = mean of n×n depth tests (blurs, not physical)
filter-poisson-tip = Poisson-disc depth tests rotated per pixel: noise instead of banding
filter-pcss-tip =
    Percentage-closer soft shadows: a blocker search estimates the penumbra width
    w = R · (d_receiver − d_blocker) / d_blocker, then filters over w
filter-vsm-tip = Variance shadow map: blurred moments (μ, σ²), V ≤ σ² / (σ² + (d − μ)²) (Chebyshev)
filter-evsm-tip = Exponential VSM: moments of e^(c·d), less light bleeding than VSM
filter-msm-tip = Moment shadow map: moments d, d², d³, d⁴, Hamburger reconstruction (Peters & Klein 2015)
bias-auto-tip = The receiver's tangent plane predicts its depth at each texel, plus a small slack
bias-constant-tip = d_compared = d − D: too little gives acne, too much peter-panning
bias-slope-tip = d_compared = d − (D + S · texel · tan θ): more bias at grazing light
bias-normal-tip = The lookup point moves N texel footprints along the surface normal
shadow-enabled = Shadows
shadow-enabled-tip = L = f_r · E · V; off: V = 1 everywhere
shadow-filter = Filter
shadow-filter-tip = How depth tests become a visibility V ∈ [0, 1]
shadow-kernel = Kernel
shadow-kernel-tip = n×n depth tests one texel apart
shadow-kernel-size-tip = V = mean of { $tests } depth tests
shadow-samples = Samples
shadow-samples-tip = Depth tests on a Poisson disc
shadow-samples-range-tip = { $help } (4 … 64): more is smoother and slower
shadow-radius = radius
shadow-radius-tip = Radius of the disc (shadow-map texels): wider is softer
unit-texels = {" "}texels
shadow-light-radius = light R
shadow-light-radius-tip =
    The light's radius R (same as in the Light panel): the penumbra width is
    w = R · (d_receiver − d_blocker) / d_blocker. R = 0 gives hard shadows.
shadow-blocker-samples = Blocker samples
shadow-blocker-samples-tip = Depth tests of the blocker search
shadow-filter-samples = Filter samples
shadow-filter-samples-tip = Depth tests over the estimated penumbra
shadow-blur = blur
shadow-blur-tip = Radius of the separable blur of the moments (texels)
shadow-bleed-reduction = bleed reduction
shadow-bleed-reduction-tip = V' = clamp((V − b) / (1 − b), 0, 1): cuts Chebyshev's light bleeding
shadow-moment-bias = moment bias α
shadow-moment-bias-tip = b' = (1 − α) b + α (½, ½, ½, ½): larger α, more light leaking, less noise
shadow-resolution = Resolution
shadow-resolution-tip =
    Texels per side of the shadow map: one texel covers (frustum width / resolution)
    metres; too few texels per pixel → aliasing
shadow-resolution-size-tip = { $side } × { $side } texels, { $mib } MiB of depth
shadow-adapter-limit-tip = Adapter limit: { $side } texels per side
shadow-resolution-used = using { $used }²: { $why }
shadow-bias = Bias
shadow-bias-tip = Offsets the compared depth: acne (too little) against peter-panning (too much)
shadow-bias-depth-tip = Constant depth offset D towards the light (m)
shadow-bias-auto = from the receiver's plane and the texel footprint
shadow-bias-slope-tip = Slope factor S: bias D + S · texel footprint · tan θ
shadow-bias-normal-tip = Normal offset N: the lookup moves N texel footprints along n

## View panel (view.rs)

view-shaded-tip = Reflected radiance L = f_r · E · V (W/m²/sr), exposed and sRGB encoded
view-depth-tip = The light's depth map (normalized distance from the light)
view-visibility-tip = V ∈ [0, 1] from the shadow map: black = shadowed, white = lit
view-ndotl-tip = cos θ = max(0, n·l): black at the horizon, white facing the light
view-irradiance-tip = E · V = I cos θ / r² · V (W/m²), false colour
view-brdf-tip = f_r / c (1/sr), false colour, log scale over two decades
view-diffuse-tip = The diffuse part c · k/π · E · V (W/m²/sr)
view-specular-tip = The specular part c · (1 − k) N(m) cos^m θ_h · E · V (W/m²/sr)
view-texel-density-tip = Shadow-map texels per screen pixel (log₂), red: magnified and aliased
view-frustum-tip = The light's frustum (or cube faces) drawn over the shaded image
view-ref-visibility-tip = The CPU reference's visibility V_ref (compute it in the Reference panel)
view-error-tip = Signed error of luminance L − L_ref against the CPU reference (W/m²/sr)
view-show = Show
view-show-tip = What the image shows (V: next view)
view-exposure = exposure
view-exposure-tip = Displayed value = L · 2^EV, then the sRGB transfer (shaded, diffuse, specular)
split-enabled = Split view A | B  (S)
split-enabled-tip =
    Both halves show the current settings; B differs from A in one setting.
    Drag the divider to wipe between them.
split-compare = Compare
split-compare-tip = The setting that differs between A and B
split-layout = Layout
split-wipe = wipe
split-wipe-tip = One image: A left of the divider, B right of it
split-side-by-side = side by side
split-side-by-side-tip = Two whole images of the same view, cameras linked: A left, B right
split-divider = divider
split-divider-tip = Where A ends and B begins (fraction of the width); or drag the line in the image

## Light panel (light.rs)

light-position = Position q
light-position-tip =
    Centre of the light (m). Drag the yellow gizmo in the image:
    parallel to the image, or Ctrl+drag for the height.
light-position-axis-tip = Light position, { $axis } coordinate (m); +Y is up
light-power = Power Φ
light-power-tip = Radiant power emitted in all directions (W)
light-power-slider-tip = Φ (W), scaled by the colour. I = Φ / 4π; E = I cos θ / r²
light-intensity-tip = Intensity of an isotropic point light: power per steradian, I = Φ / 4π (W/sr)
light-radius = Sphere radius R
light-radius-tip =
    R = 0: a point light (hard shadows). R > 0: a sphere light of the same power
    (soft shadows with the PCSS filter).
light-radius-slider-tip = R (m); the sphere's radiance is L_e = Φ / (4π² R²)
light-sphere-radiance-tip = Uniform radiance of the sphere light's surface (W/m²/sr)
light-point = point light
light-colour = Colour
light-colour-tip = Linear RGB factors multiplying Φ
light-colour-button-tip = Light colour (linear RGB): Φ_rgb = Φ · colour
light-white = white
light-white-tip = Colour (1, 1, 1)

## Material panel (material.rs)

norm-none-note = the raw lobe: energy falls as m grows, and exceeds 1 at small m
norm-ndf-note = normalizes the lobe over half-vectors, not the reflected energy
norm-approx-note = the usual approximation; a(0°) > 1 at small m (1.075 at m = 8)
norm-exact-note = exact at normal incidence: a(0°) = 1 for every m
material-use-scene = Use the scene's own k and m
material-use-scene-tip =
    On: objects whose glTF material gives k and m keep them; the others use the
    values below. Off: every object uses the values below.
material-k = Diffuse mix k
material-k-tip =
    k ∈ [0, 1]: 1 is pure Lambert (f_r = c/π), 0 is the lobe alone.
    { $brdf }
material-m = Exponent m
material-m-tip =
    Blinn-Phong exponent m ∈ [0, 10⁶]: larger is a sharper highlight; m = 0 is a flat lobe (0⁰ = 1).
    { $brdf }
material-norm = Normalization N(m)
material-override = Override base colour c
material-override-tip = Replace every object's colour c (linear RGB) in the BRDF
material-colour-tip = c (linear RGB, each in [0, 1])

## Widgets (widgets.rs)

slider-zero-tip = Set exactly 0 (a log slider cannot reach it)
