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
