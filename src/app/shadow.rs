//! The shadow panel: the shadow map's resolution, filter and bias.

use super::View;
use super::widgets::{number, warning};
use crate::scene::SceneScale;
use crate::settings::{BiasMode, BiasSettings, Filter, ShadowSettings, Visibility};

pub struct ShadowPanel<'a> {
    pub shadow: &'a mut ShadowSettings,
    /// The light's radius R (m): PCSS sizes its penumbra from it.
    pub light_radius_m: &'a mut f32,
    /// The scene's scale: the radius and bias sliders' ranges follow it.
    pub scale: SceneScale,
    /// The adapter's largest texture side (texels).
    pub max_texture_side: u32,
    /// Why the last frame used a smaller map than asked, if it did.
    pub resolution_note: Option<(u32, String)>,
}

/// Tooltip of each filter.
pub fn filter_help(filter: Filter) -> &'static str {
    match filter {
        Filter::None => "One depth test at the nearest texel: V ∈ {0, 1}, hard aliased edges",
        Filter::Hw2x2 => "The hardware comparison sampler: 2×2 depth tests, bilinearly weighted",
        Filter::Pcf => "Percentage-closer filtering: V = mean of n×n depth tests (blurs, not physical)",
        Filter::Poisson => "Poisson-disc depth tests rotated per pixel: noise instead of banding",
        Filter::Pcss => {
            "Percentage-closer soft shadows: a blocker search estimates the penumbra width \
             w = R · (d_receiver − d_blocker) / d_blocker, then filters over w"
        }
        Filter::Vsm => "Variance shadow map: blurred moments (μ, σ²), V ≤ σ² / (σ² + (d − μ)²) (Chebyshev)",
        Filter::Evsm => "Exponential VSM: moments of e^(c·d), less light bleeding than VSM",
        Filter::Msm => {
            "Moment shadow map: moments d, d², d³, d⁴, Hamburger reconstruction (Peters & Klein 2015)"
        }
    }
}

/// Tooltip of each bias mode.
pub fn bias_help(mode: BiasMode) -> &'static str {
    match mode {
        BiasMode::Auto => "The receiver's tangent plane predicts its depth at each texel, plus a small slack",
        BiasMode::Constant => "d_compared = d − D: too little gives acne, too much peter-panning",
        BiasMode::Slope => "d_compared = d − (D + S · texel · tan θ): more bias at grazing light",
        BiasMode::Normal => "The lookup point moves N texel footprints along the surface normal",
    }
}

impl View for ShadowPanel<'_> {
    fn ui(&mut self, ui: &mut egui::Ui) {
        let ShadowSettings {
            enabled,
            visibility,
            resolution,
            filter,
            pcf_size,
            poisson_samples,
            poisson_radius_texels,
            pcss_blocker_samples,
            vsm_blur_texels,
            vsm_bleed_reduction,
            msm_bias,
            bias,
            rt_light_samples,
            rt_max_frames,
        } = self.shadow;

        ui.checkbox(enabled, "Shadows")
            .on_hover_text("L = f_r · E · V; off: V = 1 everywhere");
        ui.add_enabled_ui(*enabled, |ui| {
            super::visibility::visibility_ui(ui, visibility, rt_light_samples, rt_max_frames);
        });
        ui.add_enabled_ui(*enabled && *visibility == Visibility::ShadowMap, |ui| {
            resolution_ui(
                ui,
                resolution,
                self.max_texture_side,
                self.resolution_note.as_ref(),
            );
            ui.horizontal(|ui| {
                ui.label("Filter")
                    .on_hover_text("How depth tests become a visibility V ∈ [0, 1]");
                egui::ComboBox::from_id_salt("shadow filter")
                    .selected_text(filter.name())
                    .show_ui(ui, |ui| {
                        for &choice in Filter::ALL {
                            ui.selectable_value(filter, choice, choice.name())
                                .on_hover_text(filter_help(choice));
                        }
                    })
                    .response
                    .on_hover_text(filter_help(*filter));
            });
            match filter {
                Filter::None | Filter::Hw2x2 => {}
                Filter::Pcf => {
                    ui.horizontal(|ui| {
                        ui.label("Kernel")
                            .on_hover_text("n×n depth tests one texel apart");
                        for n in ShadowSettings::PCF_SIZES {
                            ui.selectable_value(pcf_size, n, format!("{n}×{n}"))
                                .on_hover_text(format!("V = mean of {} depth tests", n * n));
                        }
                    });
                }
                Filter::Poisson => {
                    samples(ui, poisson_samples, "Samples", "Depth tests on a Poisson disc");
                    ui.add(
                        egui::Slider::new(poisson_radius_texels, 0.0..=16.0)
                            .text("radius")
                            .suffix(" texels"),
                    )
                    .on_hover_text("Radius of the disc (shadow-map texels): wider is softer");
                }
                Filter::Pcss => {
                    ui.add(
                        egui::Slider::new(self.light_radius_m, 0.0..=self.scale.max_light_radius_m())
                            .text("light R")
                            .suffix(" m")
                            .custom_formatter(|x, _| number(x)),
                    )
                    .on_hover_text(
                        "The light's radius R (same as in the Light panel): the penumbra width is \
                         w = R · (d_receiver − d_blocker) / d_blocker. R = 0 gives hard shadows.",
                    );
                    samples(
                        ui,
                        pcss_blocker_samples,
                        "Blocker samples",
                        "Depth tests of the blocker search",
                    );
                    samples(
                        ui,
                        poisson_samples,
                        "Filter samples",
                        "Depth tests over the estimated penumbra",
                    );
                }
                Filter::Vsm | Filter::Evsm => {
                    ui.add(
                        egui::Slider::new(vsm_blur_texels, 0..=16)
                            .text("blur")
                            .suffix(" texels"),
                    )
                    .on_hover_text("Radius of the separable blur of the moments (texels)");
                    ui.add(egui::Slider::new(vsm_bleed_reduction, 0.0..=0.99).text("bleed reduction"))
                        .on_hover_text(
                            "V' = clamp((V − b) / (1 − b), 0, 1): cuts Chebyshev's light bleeding",
                        );
                }
                Filter::Msm => {
                    ui.add(
                        egui::Slider::new(vsm_blur_texels, 0..=16)
                            .text("blur")
                            .suffix(" texels"),
                    )
                    .on_hover_text("Radius of the separable blur of the moments (texels)");
                    ui.add(
                        egui::Slider::new(msm_bias, 0.0..=0.01)
                            .logarithmic(true)
                            .text("moment bias α"),
                    )
                    .on_hover_text(
                        "b' = (1 − α) b + α (½, ½, ½, ½): larger α, more light leaking, less noise",
                    );
                }
            }
            bias_ui(ui, bias, self.scale);
        });
    }
}

fn samples(ui: &mut egui::Ui, value: &mut u32, label: &str, help: &str) {
    ui.add(egui::Slider::new(value, 4..=64).text(label))
        .on_hover_text(format!("{help} (4 … 64): more is smoother and slower"));
}

/// The resolutions offered: powers of two from the minimum to the adapter's limit.
pub fn resolution_choices(max_texture_side: u32) -> Vec<u32> {
    let max = max_texture_side.min(ShadowSettings::MAX_RESOLUTION);
    std::iter::successors(Some(ShadowSettings::MIN_RESOLUTION), |r| r.checked_mul(2))
        .take_while(|&r| r <= max)
        .collect()
}

fn resolution_ui(
    ui: &mut egui::Ui,
    resolution: &mut u32,
    max_texture_side: u32,
    note: Option<&(u32, String)>,
) {
    ui.horizontal(|ui| {
        ui.label("Resolution").on_hover_text(
            "Texels per side of the shadow map: one texel covers (frustum width / resolution) \
             metres; too few texels per pixel → aliasing",
        );
        egui::ComboBox::from_id_salt("shadow resolution")
            .selected_text(format!("{resolution}²"))
            .show_ui(ui, |ui| {
                for r in resolution_choices(max_texture_side) {
                    let mib = (r as f64).powi(2) * 4.0 / (1024.0 * 1024.0);
                    ui.selectable_value(resolution, r, format!("{r}²"))
                        .on_hover_text(format!("{r} × {r} texels, {} MiB of depth", number(mib)));
                }
            })
            .response
            .on_hover_text(format!("Adapter limit: {max_texture_side} texels per side"));
    });
    if let Some((used, why)) = note {
        warning(ui, &format!("using {used}²: {why}"));
    }
}

fn bias_ui(ui: &mut egui::Ui, bias: &mut BiasSettings, scale: SceneScale) {
    let BiasSettings {
        mode,
        depth_m,
        slope,
        normal_texels,
    } = bias;
    ui.horizontal(|ui| {
        ui.label("Bias")
            .on_hover_text("Offsets the compared depth: acne (too little) against peter-panning (too much)");
        egui::ComboBox::from_id_salt("shadow bias")
            .selected_text(mode.name())
            .show_ui(ui, |ui| {
                for &choice in BiasMode::ALL {
                    ui.selectable_value(mode, choice, choice.name())
                        .on_hover_text(bias_help(choice));
                }
            })
            .response
            .on_hover_text(bias_help(*mode));
    });
    let depth = |ui: &mut egui::Ui, depth_m: &mut f32| {
        ui.add(
            egui::Slider::new(depth_m, 0.0..=scale.length(2.0))
                .logarithmic(true)
                .smallest_positive(scale.length(1e-5) as f64)
                .text("D")
                .suffix(" m")
                .custom_formatter(|x, _| number(x)),
        )
        .on_hover_text("Constant depth offset D towards the light (m)");
    };
    match mode {
        BiasMode::Auto => {
            ui.label("from the receiver's plane and the texel footprint");
        }
        BiasMode::Constant => depth(ui, depth_m),
        BiasMode::Slope => {
            depth(ui, depth_m);
            ui.add(egui::Slider::new(slope, 0.0..=10.0).text("S"))
                .on_hover_text("Slope factor S: bias D + S · texel footprint · tan θ");
        }
        BiasMode::Normal => {
            ui.add(
                egui::Slider::new(normal_texels, 0.0..=8.0)
                    .text("N")
                    .suffix(" texels"),
            )
            .on_hover_text("Normal offset N: the lookup moves N texel footprints along n");
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resolutions_stop_at_the_adapter_limit() {
        assert_eq!(resolution_choices(2048), vec![256, 512, 1024, 2048]);
        assert_eq!(*resolution_choices(16384).last().unwrap(), 16384);
        assert!(resolution_choices(100).is_empty());
    }
}
