# The app's text in English, second file: the viewport, the lecture, the
# timings, colour and tour texts. The same rules as en.ftl; read after it.

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
visibility-ray-traced-tip = Ray traced on the GPU through a BVH: a shadow ray from p to the light. Point light: exact V ∈ {"{"}0, 1{"}"}. Sphere light: V = Σ V_i cos θ_i / Σ cos θ_i over S directions of its cone per frame, the next points of a low-discrepancy sequence of the pixel's, averaged over the frames while nothing changes: N frames make one well-spread set of N·S directions
visibility-label = Visibility
visibility-label-tip = Where V(p, q) ∈ [0, 1] comes from: L = f_r · E · V
visibility-rays = rays / frame
visibility-rays-tip = S: shadow rays per pixel and frame towards a sphere light, the next S points of a low-discrepancy sequence (R2) over its solid angle, traced four to a walk of the BVH (eight from S = 8 on); a point light needs one. While you drag, each frame sends one (the still frame after the drag sends S again and starts its average anew)
visibility-frames = frames
visibility-frames-tip = N: frames averaged while nothing changes under a sphere light; the noise of V falls at least as 1/√(N·S), faster thanks to the low-discrepancy sequence (the view's label gives the noise measured on the image, comparing the mean of N frames with that of its first N/2), then the image holds. A point light is exact after one frame
visibility-noise-target = stop below noise
visibility-noise-target-tip = The lab stops adding frames before N once the noise measured on the image (the label's "noise ≈ … % of the mean") is at most this share of the mean; 0: never, the mean goes on to N frames. The default 0.1 % is under a tenth of an 8-bit display step at mid-grey: the image no longer changes on screen, and a software adapter's cores rest (on the default scene under R = 0.3 m, 32 frames of 8 rays, some 6 s on a software adapter, instead of 256 frames). It changes when the image holds, not what it holds: a new target goes on with the same mean. The command line's --accumulate N and the report always render their N frames
visibility-elapsed = after { $seconds } s
visibility-held = held: below { $target } %
visibility-exact = exact
visibility-noise-estimate = noise ≈ { $percent } % of the mean
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
