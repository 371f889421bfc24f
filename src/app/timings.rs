//! The timings panel: frame time, GPU time per pass, whether the shadow map
//! was redrawn, what was drawn into it, and the adapter.

use super::gpu_view::GpuViews;
use super::render_scale::{MIN_SCALE, RenderScale, SHADOW_STEPS, TARGET_FPS};
use super::widgets::{number, value_row};
use crate::presets::Half;
use crate::scene::simplify::THRESHOLD_TRIANGLES;
use crate::tr;
use egui::RichText;
use std::time::Instant;

/// Wall-clock frame times of the UI.
#[derive(Default)]
pub struct FrameClock {
    last: Option<Instant>,
    /// Time between the last two UI frames (ms); frames come only on change.
    pub frame_ms: f64,
    /// CPU time of the last UI pass, rendering included (ms).
    pub ui_ms: f64,
}

impl FrameClock {
    /// At the start of a UI pass.
    pub fn begin(&mut self) -> Instant {
        let now = Instant::now();
        if let Some(last) = self.last {
            self.frame_ms = (now - last).as_secs_f64() * 1e3;
        }
        self.last = Some(now);
        now
    }

    /// At the end of a UI pass started at `start`.
    pub fn end(&mut self, start: Instant) {
        self.ui_ms = start.elapsed().as_secs_f64() * 1e3;
    }
}

/// The render scale, the frame rate and the meshes while dragging.
fn interaction_rows(ui: &mut egui::Ui, gpu: &GpuViews) {
    let scale = &gpu.render_scale;
    egui::Grid::new("interaction")
        .num_columns(2)
        .striped(true)
        .show(ui, |ui| {
            value_row(
                ui,
                &tr!("timings-render-scale"),
                &format!(
                    "{} % {}{}",
                    number(100.0 * scale.shown.image),
                    if scale.shown.image < 1.0 {
                        tr!("timings-dragging")
                    } else {
                        tr!("timings-full")
                    },
                    if scale.shown.shadow < scale.shown.image {
                        tr!("timings-map-scale", percent = number(100.0 * scale.shown.shadow))
                    } else {
                        String::new()
                    }
                ),
                &tr!(
                    "timings-render-scale-tip",
                    budget = number(RenderScale::budget_ms()),
                    fps = number(TARGET_FPS),
                    min = number(100.0 * MIN_SCALE),
                    map_min = number(100.0 * SHADOW_STEPS[0])
                ),
            );
            value_row(
                ui,
                &tr!("timings-drag-fps"),
                &scale.drag_fps.map_or_else(|| "—".into(), number),
                &tr!("timings-drag-fps-tip"),
            );
            value_row(
                ui,
                &tr!("timings-drag-device"),
                &if gpu.has_drag_device() {
                    tr!("timings-drag-device-own")
                } else {
                    tr!("timings-drag-device-window")
                },
                &tr!("timings-drag-device-tip"),
            );
            let thousands = |n: usize| number((n as f64 / 1e3).round());
            value_row(
                ui,
                &tr!("timings-drag-meshes"),
                &match gpu.simplified {
                    Some(counts) => tr!(
                        "timings-drag-meshes-simplified",
                        drawn = thousands(counts.camera),
                        casters = thousands(counts.casters),
                        full = thousands(counts.full)
                    ),
                    None if gpu.simplifying() => tr!("timings-drag-meshes-building"),
                    None => tr!("timings-drag-meshes-full"),
                },
                &tr!(
                    "timings-drag-meshes-tip",
                    threshold = thousands(THRESHOLD_TRIANGLES)
                ),
            );
        });
}

fn ms(value: Option<f64>) -> String {
    value.map_or_else(|| "—".into(), |v| format!("{} ms", number(v)))
}

pub fn ui(ui: &mut egui::Ui, clock: &FrameClock, gpu: Option<&GpuViews>) {
    egui::Grid::new("frame times")
        .num_columns(2)
        .striped(true)
        .show(ui, |ui| {
            value_row(
                ui,
                &tr!("timings-ui-pass"),
                &format!("{} ms", number(clock.ui_ms)),
                &tr!("timings-ui-pass-tip"),
            );
            value_row(
                ui,
                &tr!("timings-since-previous"),
                &format!("{} ms", number(clock.frame_ms)),
                &tr!("timings-since-previous-tip"),
            );
        });
    let Some(gpu) = gpu else {
        return;
    };
    let caps = gpu.capabilities();
    interaction_rows(ui, gpu);
    for half in [Half::A, Half::B] {
        let Some(h) = gpu.half(half) else { continue };
        if gpu.half(Half::B).is_some() {
            let name = if half == Half::A {
                tr!("timings-half-a")
            } else {
                tr!("timings-half-b")
            };
            ui.label(RichText::new(name).strong());
        }
        let r = &h.report;
        let t = h.times.unwrap_or_default();
        egui::Grid::new(("pass times", half as u8))
            .num_columns(2)
            .striped(true)
            .show(ui, |ui| {
                value_row(
                    ui,
                    "render()",
                    &format!("{} ms", number(h.render_cpu_ms)),
                    &tr!("timings-render-tip"),
                );
                value_row(
                    ui,
                    &tr!("timings-shadow"),
                    &match (t.shadow_ms, h.last_shadow_ms) {
                        (None, Some(last)) => tr!("timings-shadow-reused", time = ms(Some(last))),
                        (now, _) => ms(now),
                    },
                    &tr!("timings-shadow-tip"),
                );
                value_row(ui, &tr!("timings-blur"), &ms(t.blur_ms), &tr!("timings-blur-tip"));
                value_row(
                    ui,
                    &tr!("timings-shading"),
                    &ms(t.shade_ms),
                    &tr!("timings-shading-tip"),
                );
                value_row(
                    ui,
                    &tr!("timings-display"),
                    &ms(t.display_ms),
                    &tr!("timings-display-tip"),
                );
                value_row(
                    ui,
                    &tr!("timings-gpu-total"),
                    &ms(h.times.map(|t| t.total_ms())),
                    &tr!("timings-gpu-total-tip"),
                );
                value_row(
                    ui,
                    &tr!("timings-shadow-map"),
                    &if r.shadow_redrawn {
                        tr!("timings-redrawn")
                    } else if r.shadow_map_unused {
                        tr!("timings-unused")
                    } else if let Some(block) = r.depth_ranges {
                        tr!("timings-reused-ranges", block = block)
                    } else {
                        tr!("timings-reused")
                    },
                    &tr!("timings-shadow-map-tip"),
                );
                value_row(
                    ui,
                    &tr!("timings-layout"),
                    &r.layout_summary(),
                    &tr!("timings-layout-tip"),
                );
                value_row(
                    ui,
                    &tr!("timings-casters"),
                    &tr!(
                        "timings-casters-value",
                        drawn = r.casters_per_layer.iter().sum::<usize>(),
                        total = r.casters_total,
                        layers = r
                            .casters_per_layer
                            .iter()
                            .map(usize::to_string)
                            .collect::<Vec<_>>()
                            .join(" + ")
                    ),
                    &tr!("timings-casters-tip"),
                );
                value_row(
                    ui,
                    &tr!("timings-resolution"),
                    &format!("{}²", r.resolution),
                    &tr!("timings-resolution-tip"),
                );
                value_row(
                    ui,
                    &tr!("timings-near-far"),
                    &format!(
                        "{} / {} m",
                        number(r.camera_near_far.0),
                        number(r.camera_near_far.1)
                    ),
                    &tr!("timings-near-far-tip"),
                );
                value_row(
                    ui,
                    &tr!("timings-visible-objects"),
                    &r.visible_objects.to_string(),
                    &tr!("timings-visible-objects-tip"),
                );
            });
    }
    ui.add_space(4.0);
    // The adapter's description is long: a wrapping line, not a grid cell.
    ui.add(
        egui::Label::new(RichText::new(tr!("timings-adapter", adapter = caps.adapter.as_str())).monospace())
            .wrap(),
    )
    .on_hover_text(tr!("timings-adapter-tip"));
    egui::Grid::new("adapter").num_columns(2).show(ui, |ui| {
        value_row(
            ui,
            &tr!("timings-backend"),
            &gpu.backend(),
            &tr!("timings-backend-tip"),
        );
        value_row(
            ui,
            &tr!("timings-max-texture"),
            &format!("{}²", caps.max_texture_side),
            &tr!("timings-max-texture-tip"),
        );
        value_row(
            ui,
            &tr!("timings-timestamps"),
            &if caps.timestamps {
                tr!("timings-timestamps-yes")
            } else {
                tr!("timings-timestamps-no")
            },
            &tr!("timings-timestamps-tip"),
        );
    });
}
