# The app's text in English. Keys are shared with fr.ftl (the tests check
# that both files have the same keys and placeholders). Numbers arrive
# formatted, with their unit, and keep a decimal point in both languages.
# Formulas (E = I cos θ / r², f_r = ...) stay as they are in both.

## The language menu

menu-language = Language
menu-language-tip = The language of the app's text (the command line stays in English)

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
section-colour = Colour
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
view-delta-e-tip = ΔE2000 per pixel between the spectral result and the RGB product, both as displayed (L · 2^EV), in CIE Lab with the illuminant's white at Y = 1 (CIEDE2000, Sharma, Wu & Dalal 2005): about 1 is just visible, 2.3 is the JND. Needs a spectral illuminant (Colour panel)
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

## Help: shortcuts and gestures (shortcuts.rs)

shortcut-help = this help
shortcut-redo = redo
shortcut-undo = undo a settings change
shortcut-save-settings = save the settings file
shortcut-open-scene = open a glTF/GLB file (file dialog)
shortcut-reset-view = reset the view
shortcut-frame-all = frame all: the model fills the view
shortcut-auto-exposure = auto exposure from the image
shortcut-split = split view A | B on/off
shortcut-previous-view = previous debug view
shortcut-next-view = next debug view
shortcut-reference = compute the CPU reference
shortcut-cancel = cancel the reference / close this help
shortcut-screenshot = save a screenshot
shortcut-panels = hide/show the side panels
gesture-left-drag = Left drag
gesture-left-drag-does = orbit the camera around its target
gesture-pan = Shift + drag / middle drag
gesture-pan-does = pan
gesture-wheel = Wheel
gesture-wheel-does = zoom
gesture-click = Click
gesture-click-does = probe the pixel (every term of L = f_r · E · V)
gesture-double-click = Double-click
gesture-double-click-does = orbit around the point under the cursor
gesture-drag-light = Drag the yellow light
gesture-drag-light-does = move the light parallel to the image
gesture-ctrl-drag-light = Ctrl + drag the light
gesture-ctrl-drag-light-does = move the light up and down
shortcut-or = {" "}or{" "}
help-title = Keyboard and mouse
help-footer = Every number has its unit; hover a control or a value to see its formula.

## Scene panel (scene_panel.rs)

scene-size = { $triangles } triangles · { $size } across
scene-size-tip = The model's bounding-box diagonal: the lab's lengths follow it
scene-empty = nothing to draw: the file has no triangles
scene-frame-all = Frame all (F)
scene-frame-all-tip = Move the camera along its direction until the model fills the view
scene-auto-exposure = Auto exposure (E)
scene-auto-exposure-tip = EV such that the 95th percentile of the lit pixels' luminance shows at 0.8 (linear)
scene-cameras = File cameras:
scene-camera-tip = The file's camera { $index } (--camera gltf:{ $index })
scene-file-light = File light '{ $name }': I = { $intensity }
scene-file-light-tip =
    KHR_lights_punctual gives candela; I (W/sr) = I (cd) / { $efficacy } lm/W, the efficacy of
    555 nm light (a white source emits more watts for the same candela). The lab's
    light starts there with Φ = 4π I.
scene-ground = Ground
scene-ground-tip = A shadow-receiving ground at the model's lowest point (--ground)
scene-ground-auto-tip = Under a model that has none
scene-ground-on-tip = Always
scene-ground-off-tip = Never: the file's geometry only
scene-ground-k = ground k
scene-ground-k-tip = The ground's diffuse/specular mix: f_r = c (k/π + (1 − k) N(m) cos^m θ_h)
scene-ground-m = ground m
scene-ground-m-tip = The ground's Blinn-Phong exponent m

## Energy panel (energy.rs)

energy-curve-tip = a(θ_i) = ∫ f_r(l, o) cos θ_o dω_o over the hemisphere, with c = 1
energy-lecture-angles = lecture angles
energy-red-band = red band: a(θ_i) > 1, the BRDF creates energy
energy-albedo-tip = Directional albedo; red above 1: the BRDF reflects more than it receives
energy-default-incidence = default 45°
energy-lobe = Lobe in the plane of incidence, θ_i = { $theta }° ({ $source })
energy-lobe-tip = Radius: f_r / c (1/sr) towards each outgoing direction θ_o; n points up
energy-light-l = light l
energy-normal-n = normal n
energy-surface = surface
energy-peak = peak f_r / c = { $peak } 1/sr

## Reference panel (reference.rs)

reference-cannot-start = cannot start the reference thread: { $message }
reference-cancelled = reference cancelled
reference-stopped = the reference thread stopped without a result
reference-compute = Compute reference (F5)
reference-compute-tip =
    Ray trace the current view on the CPU in f64 (a background thread): the exact
    L and V that the shadow map approximates
reference-cancel = Cancel (Esc)
reference-cancel-tip = Stop the computation
reference-progress-tip = { $done } of { $total } pixels
reference-none = No reference yet: the error and ref-visibility views need one.
reference-done = { $width }×{ $height } in { $seconds } s
reference-stale = STALE: the view, light, material or size changed since; recompute
reference-rmse-tip = √(mean over covered pixels of (L − L_ref)²), luminance
reference-relative = relative
reference-max-error = max |error|
reference-pixels = pixels
reference-pixels-tip = Pixels covered by the scene
reference-rmse-in-error-view = RMSE: shown in the error view
reference-error-view = Error view
reference-error-view-tip = Signed L − L_ref in false colour
reference-visibility = Reference V
reference-visibility-tip = The reference's visibility V_ref

## Pixel probe (probe.rs)

probe-p-tip = Where the pixel's ray meets the surface (m)
probe-n-tip = Unit shading normal (interpolated vertex normals)
probe-l-tip = l = (q − p) / r, unit direction to the light
probe-r-tip = r = |q − p|, distance to the light's centre (m)
probe-cos-tip = cos θ = n·l; negative: the light is below the horizon
probe-e-tip = E = I · max(0, cos θ) / r² (W/m²); a sphere light straddling the horizon uses its closed form
probe-c-tip = The BRDF colour c (linear RGB): base colour × texture at the hit's uv, or the override
probe-v-map-tip = Visibility from the shadow map with the current filter and bias, V ∈ [0, 1]
probe-texels-tip = Shadow-map texels per screen pixel: below 1 the map is magnified (aliasing)
probe-l-value-tip = L = f_r · E · V · light colour (W/m²/sr), in f64 with the GPU's V
probe-l-gpu-tip = The renderer's radiance at this pixel (f32)
probe-reading-tip = Reading the renderer's aux target
probe-unshadowed-tip = L / V = f_r · E · light colour
probe-v-traced-tip = Visibility of the light from p, ray traced on the CPU in f64: the exact V the shadow map approximates
probe-l-traced-tip = The CPU reference's radiance at this pixel's centre
probe-l-image-tip = The computed reference image at this pixel (F5), which the error view compares with
probe-v-map = V (shadow map)
probe-texels = texels/pixel
probe-l-gpu = L (GPU)
probe-v-traced = V (ray traced)
probe-l-traced = L (ray traced)
probe-l-image = L (reference image)
probe-o-tip = Unit direction to the eye
probe-stale = {"  "}(stale)
probe-hint = Click a pixel of the image to see every term of L = f_r · E · V there.
probe-pixel = pixel ({ $x }, { $y }) of { $width }×{ $height }, half { $half }
probe-background = background: the pixel's ray meets no surface
probe-object = { $object } — material { $material }

## Files: menu, panel, dialogs (files.rs)

dialog-open-scene = Open a glTF/GLB scene
dialog-load-settings = Load a TOML settings file
dialog-save-settings = Save the settings as TOML
dialog-screenshot = Save a screenshot (PNG)
dialog-export-exr = Export linear radiance (EXR)
files-open-scene-dialog = Open scene…
files-open-scene-dialog-tip = A .gltf or .glb file (Ctrl+O; or drop it on the window)
files-built-in = Built-in scene
files-built-in-tip = Back to the lab's own scene
files-load-settings-dialog = Load settings…
files-load-settings-dialog-tip = A TOML settings file, as `lumlab render --settings FILE` reads
files-save-settings = Save settings
files-save-settings-tip = Write every setting to the settings file used last (Ctrl+S)
files-save-settings-as = Save settings as…
files-save-settings-as-tip = Write every setting to a new TOML file
files-screenshot-dialog = Save screenshot…
files-screenshot-dialog-tip = The whole window as PNG
files-export-exr-dialog = Export EXR…
files-export-exr-dialog-tip = Half A's linear values, no exposure, no sRGB
files-browse = Browse…
files-browse-tip = Pick a .gltf/.glb file and open it (Ctrl+O)
files-open-scene = Open scene
files-open-scene-tip = Open the file shown again
files-kind-settings = Settings
files-save = Save (Ctrl+S)
files-save-tip = Write every setting to the file shown
files-load = Load
files-load-tip = Read the settings from the file shown (undo with Ctrl+Z)
files-save-as = Save as…
files-save-as-tip = Write the settings to another TOML file
files-load-dialog = Load…
files-load-dialog-tip = Pick a TOML settings file and load it
files-screenshot = Save screenshot (F12)
files-screenshot-tip = The whole window, as displayed, to the file shown
files-screenshot-as-tip = The whole window, to a PNG file you pick
files-export-exr = Export EXR
files-export-exr-tip = Half A's unscaled linear values (radiance L in W/m²/sr for `shaded`) to the file shown
files-export-as = Export as…
files-export-as-tip = The same, to an EXR file you pick
replace-title = Replace the file?
replace-exists = '{ $path }' already exists.
replace-replace = Replace
replace-cancel = Cancel
files-scene = Scene: { $name }
files-reset-everything = Reset everything
files-reset-everything-tip =
    Every setting, the split view, the panels and the scene back to their defaults
    (Ctrl+Z undoes the settings)
files-none = (none)

## Toasts (toast.rs)

toast-dismiss = Dismiss

## Recent files (recent.rs)

recent-scenes = Recent scenes
recent-settings = Recent settings
recent-none = (none yet)
recent-missing = { $name } (missing)
