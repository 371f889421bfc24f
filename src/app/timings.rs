//! The timings panel: frame time, GPU time per pass, whether the shadow map
//! was redrawn, what was drawn into it, and the adapter.

use super::gpu_view::GpuViews;
use super::render_scale::{MIN_SCALE, RenderScale, TARGET_FPS};
use super::widgets::{number, value_row};
use crate::presets::Half;
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

/// The render scale and the frame rate while dragging.
fn interaction_rows(ui: &mut egui::Ui, scale: &RenderScale) {
    egui::Grid::new("interaction")
        .num_columns(2)
        .striped(true)
        .show(ui, |ui| {
            value_row(
                ui,
                "render scale",
                &format!(
                    "{} % {}",
                    number(100.0 * scale.shown),
                    if scale.shown < 1.0 { "(dragging)" } else { "(full)" }
                ),
                &format!(
                    "Image side rendered / viewport side. While dragging, s = s_measured · √((budget − t_shadow) / t_pixels), \
                     budget {} ms for {} frames/s, at least {} %; full resolution as soon as the drag ends",
                    number(RenderScale::budget_ms()),
                    number(TARGET_FPS),
                    number(100.0 * MIN_SCALE)
                ),
            );
            value_row(
                ui,
                "frames/s (drag)",
                &scale.drag_fps.map_or_else(|| "—".into(), number),
                "Frames rendered per second during the last drag: 1 / (time between frames), smoothed",
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
                "UI pass",
                &format!("{} ms", number(clock.ui_ms)),
                "CPU time of the last UI frame, rendering calls included",
            );
            value_row(
                ui,
                "since previous",
                &format!("{} ms", number(clock.frame_ms)),
                "Time between the last two frames; the lab redraws only when something changes",
            );
        });
    let Some(gpu) = gpu else {
        return;
    };
    let caps = gpu.capabilities();
    interaction_rows(ui, &gpu.render_scale);
    for half in [Half::A, Half::B] {
        let Some(h) = gpu.half(half) else { continue };
        if gpu.half(Half::B).is_some() {
            ui.label(RichText::new(if half == Half::A { "Half A" } else { "Half B" }).strong());
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
                    "CPU time to encode and submit the frame",
                );
                value_row(
                    ui,
                    "shadow",
                    &match (t.shadow_ms, h.last_shadow_ms) {
                        (None, Some(last)) => format!("reused (last draw {})", ms(Some(last))),
                        (now, _) => ms(now),
                    },
                    "GPU: drawing the depth map from the light (all layers); a reused map costs nothing",
                );
                value_row(ui, "blur", &ms(t.blur_ms), "GPU: blurring the VSM/EVSM moments");
                value_row(
                    ui,
                    "shading",
                    &ms(t.shade_ms),
                    "GPU: the camera pass (BRDF, irradiance, shadow lookups)",
                );
                value_row(
                    ui,
                    "display",
                    &ms(t.display_ms),
                    "GPU: exposure, false colour, sRGB",
                );
                value_row(
                    ui,
                    "GPU total",
                    &ms(h.times.map(|t| t.total_ms())),
                    "Sum of the timed passes",
                );
                value_row(
                    ui,
                    "shadow map",
                    if r.shadow_redrawn {
                        "redrawn this frame"
                    } else {
                        "reused"
                    },
                    "Redrawn only when the light, the geometry or the shadow settings change",
                );
                value_row(
                    ui,
                    "layout",
                    &r.layout_summary(),
                    "One frustum fitted to the scene, or the cube faces that see geometry",
                );
                value_row(
                    ui,
                    "casters",
                    &format!(
                        "{} of {} ({})",
                        r.casters_per_layer.iter().sum::<usize>(),
                        r.casters_total,
                        r.casters_per_layer
                            .iter()
                            .map(usize::to_string)
                            .collect::<Vec<_>>()
                            .join(" + ")
                    ),
                    "Objects drawn into each layer: only those that can shadow a visible receiver",
                );
                value_row(
                    ui,
                    "resolution",
                    &format!("{}²", r.resolution),
                    "Shadow-map texels per side in use",
                );
                value_row(
                    ui,
                    "near / far",
                    &format!(
                        "{} / {} m",
                        number(r.camera_near_far.0),
                        number(r.camera_near_far.1)
                    ),
                    "The camera's depth range, fitted to the scene",
                );
                value_row(
                    ui,
                    "visible objects",
                    &r.visible_objects.to_string(),
                    "Objects inside the camera's frustum",
                );
            });
    }
    ui.add_space(4.0);
    // The adapter's description is long: a wrapping line, not a grid cell.
    ui.add(egui::Label::new(RichText::new(format!("adapter: {}", caps.adapter)).monospace()).wrap())
        .on_hover_text("The GPU adapter, its backend and driver");
    egui::Grid::new("adapter").num_columns(2).show(ui, |ui| {
        value_row(
            ui,
            "backend",
            &gpu.backend(),
            "The graphics API wgpu runs on (WGPU_BACKEND chooses)",
        );
        value_row(
            ui,
            "max texture",
            &format!("{}²", caps.max_texture_side),
            "Largest 2D texture side of this device",
        );
        value_row(
            ui,
            "timestamps",
            if caps.timestamps {
                "yes"
            } else {
                "no (GPU times unavailable)"
            },
            "Timestamp queries give the per-pass GPU times",
        );
    });
}
