//! The shadow panel: the shadow map's resolution, filter and bias.

use super::View;
use super::widgets::{number, warning};
use crate::scene::SceneScale;
use crate::settings::{BiasMode, BiasSettings, Filter, ShadowSettings, Visibility};
use crate::tr;

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
pub fn filter_help(filter: Filter) -> String {
    match filter {
        Filter::None => tr!("filter-none-tip"),
        Filter::Hw2x2 => tr!("filter-hw2x2-tip"),
        Filter::Pcf => tr!("filter-pcf-tip"),
        Filter::Poisson => tr!("filter-poisson-tip"),
        Filter::Pcss => tr!("filter-pcss-tip"),
        Filter::Vsm => tr!("filter-vsm-tip"),
        Filter::Evsm => tr!("filter-evsm-tip"),
        Filter::Msm => tr!("filter-msm-tip"),
    }
}

/// Tooltip of each bias mode.
pub fn bias_help(mode: BiasMode) -> String {
    match mode {
        BiasMode::Auto => tr!("bias-auto-tip"),
        BiasMode::Constant => tr!("bias-constant-tip"),
        BiasMode::Slope => tr!("bias-slope-tip"),
        BiasMode::Normal => tr!("bias-normal-tip"),
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
            rt_noise_target_percent,
        } = self.shadow;

        ui.checkbox(enabled, tr!("shadow-enabled"))
            .on_hover_text(tr!("shadow-enabled-tip"));
        ui.add_enabled_ui(*enabled, |ui| {
            super::visibility::visibility_ui(
                ui,
                visibility,
                rt_light_samples,
                rt_max_frames,
                rt_noise_target_percent,
            );
        });
        ui.add_enabled_ui(*enabled && *visibility == Visibility::ShadowMap, |ui| {
            resolution_ui(
                ui,
                resolution,
                self.max_texture_side,
                self.resolution_note.as_ref(),
            );
            ui.horizontal(|ui| {
                ui.label(tr!("shadow-filter"))
                    .on_hover_text(tr!("shadow-filter-tip"));
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
                        ui.label(tr!("shadow-kernel"))
                            .on_hover_text(tr!("shadow-kernel-tip"));
                        for n in ShadowSettings::PCF_SIZES {
                            ui.selectable_value(pcf_size, n, format!("{n}×{n}"))
                                .on_hover_text(tr!("shadow-kernel-size-tip", tests = n * n));
                        }
                    });
                }
                Filter::Poisson => {
                    samples(
                        ui,
                        poisson_samples,
                        &tr!("shadow-samples"),
                        &tr!("shadow-samples-tip"),
                    );
                    ui.add(
                        egui::Slider::new(poisson_radius_texels, 0.0..=16.0)
                            .text(tr!("shadow-radius"))
                            .suffix(tr!("unit-texels")),
                    )
                    .on_hover_text(tr!("shadow-radius-tip"));
                }
                Filter::Pcss => {
                    ui.add(
                        egui::Slider::new(self.light_radius_m, 0.0..=self.scale.max_light_radius_m())
                            .text(tr!("shadow-light-radius"))
                            .suffix(" m")
                            .custom_formatter(|x, _| number(x)),
                    )
                    .on_hover_text(tr!("shadow-light-radius-tip"));
                    samples(
                        ui,
                        pcss_blocker_samples,
                        &tr!("shadow-blocker-samples"),
                        &tr!("shadow-blocker-samples-tip"),
                    );
                    samples(
                        ui,
                        poisson_samples,
                        &tr!("shadow-filter-samples"),
                        &tr!("shadow-filter-samples-tip"),
                    );
                }
                Filter::Vsm | Filter::Evsm => {
                    blur(ui, vsm_blur_texels);
                    ui.add(
                        egui::Slider::new(vsm_bleed_reduction, 0.0..=0.99)
                            .text(tr!("shadow-bleed-reduction")),
                    )
                    .on_hover_text(tr!("shadow-bleed-reduction-tip"));
                }
                Filter::Msm => {
                    blur(ui, vsm_blur_texels);
                    ui.add(
                        egui::Slider::new(msm_bias, 0.0..=0.01)
                            .logarithmic(true)
                            .text(tr!("shadow-moment-bias")),
                    )
                    .on_hover_text(tr!("shadow-moment-bias-tip"));
                }
            }
            bias_ui(ui, bias, self.scale);
        });
    }
}

fn samples(ui: &mut egui::Ui, value: &mut u32, label: &str, help: &str) {
    ui.add(egui::Slider::new(value, 4..=64).text(label))
        .on_hover_text(tr!("shadow-samples-range-tip", help = help));
}

/// The radius of the moments' blur (VSM, EVSM, MSM).
fn blur(ui: &mut egui::Ui, texels: &mut u32) {
    ui.add(
        egui::Slider::new(texels, 0..=16)
            .text(tr!("shadow-blur"))
            .suffix(tr!("unit-texels")),
    )
    .on_hover_text(tr!("shadow-blur-tip"));
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
        ui.label(tr!("shadow-resolution"))
            .on_hover_text(tr!("shadow-resolution-tip"));
        egui::ComboBox::from_id_salt("shadow resolution")
            .selected_text(format!("{resolution}²"))
            .show_ui(ui, |ui| {
                for r in resolution_choices(max_texture_side) {
                    let mib = (r as f64).powi(2) * 4.0 / (1024.0 * 1024.0);
                    ui.selectable_value(resolution, r, format!("{r}²"))
                        .on_hover_text(tr!("shadow-resolution-size-tip", side = r, mib = number(mib)));
                }
            })
            .response
            .on_hover_text(tr!("shadow-adapter-limit-tip", side = max_texture_side));
    });
    if let Some((used, why)) = note {
        warning(
            ui,
            &tr!("shadow-resolution-used", used = *used, why = why.as_str()),
        );
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
        ui.label(tr!("shadow-bias")).on_hover_text(tr!("shadow-bias-tip"));
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
        .on_hover_text(tr!("shadow-bias-depth-tip"));
    };
    match mode {
        BiasMode::Auto => {
            ui.label(tr!("shadow-bias-auto"));
        }
        BiasMode::Constant => depth(ui, depth_m),
        BiasMode::Slope => {
            depth(ui, depth_m);
            ui.add(egui::Slider::new(slope, 0.0..=10.0).text("S"))
                .on_hover_text(tr!("shadow-bias-slope-tip"));
        }
        BiasMode::Normal => {
            ui.add(
                egui::Slider::new(normal_texels, 0.0..=8.0)
                    .text("N")
                    .suffix(tr!("unit-texels")),
            )
            .on_hover_text(tr!("shadow-bias-normal-tip"));
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
