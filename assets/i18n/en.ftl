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

## Viewport (viewport.rs)

viewport-gizmo-tip =
    Light at ({ $x }, { $y }, { $z }) m
    Drag: move parallel to the image
    Ctrl+drag: move up and down
viewport-divider-tip = Drag to move the divider between A and B
viewport-no-gpu = no GPU renderer
viewport-light-off-image = light (off the image)
viewport-light-behind = light behind the camera

## Legends (legend.rs)

legend-visibility = visibility V (0 = shadowed, 1 = lit)
legend-ref-visibility = reference visibility V_ref
legend-depth = light's depth map (linear distance)
legend-near = near
legend-far = far
legend-delta-e = ΔE2000, RGB product vs spectral (1: visible, 2.3: JND)
legend-delta-e-needs-illuminant = ΔE needs a spectral illuminant: choose one in the Colour panel (in RGB mode both models are the same)

## Background jobs (lab/jobs.rs)

status-reference-ready = CPU reference ready: the error view compares with it
error-scene-kept = { $message }; the current scene is kept
status-exposure-no-image = auto exposure: no image yet
status-exposure = auto exposure: { $ev } EV (Ctrl+Z to undo)
status-exposure-nothing-lit = auto exposure: nothing lit in the image
status-screenshot-saved = screenshot saved to { $path }

## Over the image (lab/image.rs)

image-rmse = RMSE = { $rmse } ({ $percent } % of mean L_ref)
image-nothing-to-draw = nothing to draw
image-reference-running = Computing the CPU reference…
image-reference-none = No CPU reference yet: press F5 (Reference panel)
image-reference-stale = Reference is STALE: settings or size changed since (F5 recomputes)

## Start-up (lab.rs)

error-showing-built-in = { $message }; showing the built-in scene

## Experiments (names.rs)

preset-shadow-acne = Shadow acne
preset-peter-panning = Peter-panning
preset-aliasing = Aliasing
preset-pcf-smoothing = PCF smoothing
preset-penumbra = Penumbra (sphere light)
preset-energy-gain = Energy gain (no normalization)
preset-grazing = Grazing incidence
preset-shadow-acne-tip =
    No depth bias (constant, D = 0 m), no filter, 1024² map. Every lit surface
    compares its depth with its own quantized copy and shadows itself in stripes.
preset-peter-panning-tip =
    Constant bias D = 0.5 m, PCF 3×3, light at (3.5, 3, 3), a camera near the box's
    base. Too much bias: the shadow detaches from the object that casts it.
preset-aliasing-tip =
    256² shadow map, no filter, automatic bias: one shadow-map texel covers many
    pixels, so shadow edges show stair steps.
preset-pcf-smoothing-tip =
    The same 256² map with 7×7 percentage-closer filtering: the average of 49 depth
    tests turns the steps into a soft edge.
preset-penumbra-tip =
    Sphere light R = 0.4 m at (2.5, 4, 2), PCSS with 32 blocker-search and 32 filter
    samples, 2048² map: the penumbra widens with the distance to the occluder.
preset-energy-gain-tip =
    N(m) = 1 at m = 1, k = 0 on every object: a(0°) ≈ 2.86 > 1, the BRDF creates
    energy. Compare with the approx or exact normalization.
preset-grazing-tip =
    Light low at (6, 0.8, 0), 2000 W, view n·l: E = I cos θ / r² falls to zero as
    the light reaches the horizon.

## Lecture panel (lecture.rs)
top-lecture = Lecture
top-lecture-tip = Show the guided tour of the lecture (lumlab --tour)
lecture-no-steps = The tour has no steps.
lecture-previous = ◀ Previous
lecture-next = Next ▶
lecture-steps = Steps
lecture-close = Close
lecture-observe = Observe:
lecture-question = Question:

## Visibility (visibility.rs)
visibility-shadow-map-tip = Shadow map: depth from the light, then a filtered depth test per pixel (fast, approximate)
visibility-ray-traced-tip = Ray traced on the GPU through a BVH: a shadow ray from p to the light. Point light: exact V ∈ {"{"}0, 1{"}"}. Sphere light: V = Σ V_i cos θ_i / Σ cos θ_i over S stratified directions of its cone per frame, averaged over the frames while nothing changes
visibility-label = Visibility
visibility-label-tip = Where V(p, q) ∈ [0, 1] comes from: L = f_r · E · V
visibility-rays = rays / frame
visibility-rays-tip = S: shadow rays per pixel and frame towards a sphere light, on nx × ny strata of its solid angle (squares stratify best); a point light needs one. While you drag, each frame sends one (the still frame after the drag sends S again and starts its average anew)
visibility-frames = frames
visibility-frames-tip = N: frames averaged while nothing changes under a sphere light; the noise of V falls as 1/√(N·S), then the image holds. A point light is exact after one frame
visibility-exact = exact
visibility-accumulation = { $frames } / { $max } frames × { $rays } { $rays ->
        [one] ray
       *[other] rays
    }, { $noise }
probe-v-gpu-traced = V (GPU ray traced)
probe-v-gpu-traced-tip = Visibility traced on the GPU in f32 through the BVH: exact for a point light, the mean of the accumulated frames' samples for a sphere light
probe-xyz-tip = CIE 1931 XYZ of L (linear sRGB → XYZ, IEC 61966-2-1); under a spectral light the reference integrated S(λ) R(λ) against x̄, ȳ, z̄
probe-delta-e-tip = ΔE2000 between the spectral result and the RGB product at this pixel (L · 2^EV in CIE Lab, the illuminant's white at Y = 1): below 1 invisible, above 3 another colour
probe-delta-e-gpu = ΔE2000 (GPU view)
probe-delta-e-gpu-tip = The delta-e view's value at this pixel: both colour models shaded by the GPU in f32, CIEDE2000 in WGSL (shaders/delta_e.wgsl); it should match the ΔE2000 above, traced in f64

## Timings panel (timings.rs)

timings-render-scale = render scale
timings-dragging = (dragging)
timings-full = (full)
timings-map-scale = , shadow map { $percent } %
timings-render-scale-tip = Image side rendered / viewport side. While dragging, s = s_measured · √(budget / t_passes), budget { $budget } ms for { $fps } frames/s, rounded down to a step of √2 (25, 35, 50, 71, 100 %; up a step only with 10 % of room to spare), at least { $min } %. The shadow map's side follows s; at { $min } %, a map costing more than the image leaves of the budget shrinks alone, down to { $map_min } % of its side (never aiming below half the image's own cost). Full resolution as soon as the drag ends
timings-drag-fps = frames/s (drag)
timings-drag-fps-tip = Frames rendered per second during the last drag: 1 / (time between frames), smoothed
timings-drag-device = drag frames
timings-drag-device-own = own device
timings-drag-device-window = window's device
timings-drag-device-tip = On a software adapter (lavapipe, llvmpipe) drag frames render on a second device, on a thread of their own, while the window paints the last image that came back; on a GPU they render on the window's device (--drag-device auto|same|own)
timings-drag-meshes = drag meshes
timings-drag-meshes-simplified = simplified, { $drawn } k / { $full } k triangles (shadow map { $casters } k)
timings-drag-meshes-building = full (simplifying…)
timings-drag-meshes-full = full
timings-drag-meshes-tip = On a scene of more than { $threshold } k triangles, drag frames draw a simplified copy of each mesh (built once per scene on a thread of its own; borders and seams kept), and their shadow map a coarser one, welded along the seams since depth needs no normals; under ray-traced visibility their shadow rays meet the simplified copy they draw, through a BVH of its own: an approximation shown only while dragging. Still frames, the probe, the error statistics, the reference and exported images always use the full meshes
timings-ui-pass = UI pass
timings-ui-pass-tip = CPU time of the last UI frame, rendering calls included
timings-since-previous = since previous
timings-since-previous-tip = Time between the last two frames; the lab redraws only when something changes
timings-half-a = Half A
timings-half-b = Half B
timings-render-tip = CPU time to encode and submit the frame
timings-shadow = shadow
timings-shadow-reused = reused (last draw { $time })
timings-shadow-tip = GPU: drawing the depth map from the light (all layers); a reused map costs nothing
timings-blur = map prefilter
timings-blur-tip = GPU: blurring the VSM/EVSM/MSM moments, or the depth ranges over blocks of the map that let PCF decide fully lit and fully shadowed pixels with one read
timings-shading = shading
timings-shading-tip = GPU: the camera pass (BRDF, irradiance, shadow lookups)
timings-display = display
timings-display-tip = GPU: exposure, false colour, sRGB
timings-gpu-total = GPU total
timings-gpu-total-tip = Sum of the timed passes
timings-shadow-map = shadow map
timings-redrawn = redrawn this frame
timings-reused = reused
timings-reused-ranges = reused; the filter reads its depth ranges (blocks of { $block } texels)
timings-unused = not drawn: ray-traced V reads no shadow map
timings-shadow-map-tip = Redrawn only when the light, the geometry or the shadow settings change. A reused map gets depth ranges (the nearest and farthest depth over blocks of texels): PCF and the Poisson disc then decide a fully lit or fully shadowed pixel with one read instead of testing each of their taps
timings-layout = layout
timings-layout-tip = One frustum fitted to the scene, or the cube faces that see geometry
timings-casters = casters
timings-casters-value = { $drawn } of { $total } ({ $layers })
timings-casters-tip = Objects drawn into each layer: only those that can shadow a visible receiver
timings-resolution = resolution
timings-resolution-tip = Shadow-map texels per side in use
timings-near-far = near / far
timings-near-far-tip = The camera's depth range, fitted to the scene
timings-visible-objects = visible objects
timings-visible-objects-tip = Objects inside the camera's frustum
timings-adapter = adapter: { $adapter }
timings-adapter-tip = The GPU adapter, its backend and driver
timings-backend = backend
timings-backend-tip = The graphics API wgpu runs on (WGPU_BACKEND chooses)
timings-max-texture = max texture
timings-max-texture-tip = Largest 2D texture side of this device
timings-timestamps = timestamps
timings-timestamps-yes = yes
timings-timestamps-no = no (GPU times unavailable)
timings-timestamps-tip = Timestamp queries give the per-pass GPU times

## Colour panel (colour.rs)

colour-model = Model
colour-spectral = spectral
colour-spectral-tip = XYZ = Σ S(λ) R(λ) (x̄, ȳ, z̄)(λ) Δλ, scaled so a perfect white has the light colour's luminance, then linear sRGB
colour-rgb-approx = RGB approximation
colour-rgb-approx-tip = The lecture's product: (light's linear sRGB at Y = 1) × luminance of the light colour × base colour, channel by channel
colour-material = Material
colour-material-tip = Its reflectance R(λ): measured for a ColorChecker patch, else uplifted from the base colour (Jakob & Hanika 2019)
colour-illuminant = Illuminant
colour-illuminant-tip = The light's spectrum S(λ) (CIE 015:2018 tables, or Planck). It keeps the luminance of the light colour: only the chromaticity changes
colour-no-spectrum = RGB (no spectrum)
colour-no-spectrum-tip = The light's RGB colour times each base colour: the lecture's model
colour-d65-tip = CIE D65, average daylight
colour-a-tip = CIE A, tungsten lamp (2856 K)
colour-fl2-tip = CIE FL2, cool-white fluorescent
colour-fl11-tip = CIE FL11, three-band fluorescent
colour-led-b3-tip = CIE LED-B3, phosphor white LED
colour-blackbody-at = Planckian radiator at { $temperature }
colour-blackbody = blackbody
colour-blackbody-tip = Planck's law: M(λ, T) ∝ λ⁻⁵ / (exp(c₂ / λT) − 1)
colour-temperature = temperature T
colour-temperature-tip = Colour temperature of the Planckian radiator (K)
colour-relative = relative
colour-rgb-product = RGB product
colour-xyz-tip = Spectral XYZ = k Σ S R (x̄, ȳ, z̄), k = 100 / Σ S ȳ; ΔE2000 (CIE 2001) between the spectral result and the RGB product in CIE Lab, the illuminant's white as reference
colour-delta-e-invisible = below 1: not visible
colour-delta-e-visible = 1 to 3: visible side by side
colour-delta-e-different = above 3: a different colour

## Tour and dropped files (lab/tour.rs, lab/jobs.rs)

scene-lecture-spheres = lecture spheres
tour-status = tour { $step }/{ $count }: { $title } (Ctrl+Z to undo)
status-drop-unknown = '{ $path }': drop a .gltf, .glb or .toml file

## Split view labels (names.rs)
compare-norm = norm { $value }
compare-filter = filter { $value }
compare-resolution = shadow map { $texels }²
compare-bias = bias { $value }
compare-shadow-map = shadow map
compare-ray-traced = ray traced
compare-rgb-approx = RGB approximation
compare-spectral = spectral

## Split choices (names.rs)
split-choice-norm = norm none | approx
split-choice-filter = filter none | PCF
split-choice-pcss = filter PCF | PCSS
split-choice-resolution = resolution 256² | 2048²
split-choice-visibility = shadow map | ray traced
split-choice-colour = RGB | spectral
