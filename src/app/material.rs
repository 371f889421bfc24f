//! The material panel: the BRDF's mix k, exponent m and normalization N(m).

use super::View;
use super::widgets::{derived, log_slider_with_zero, number};
use crate::physics::Normalization;
use crate::settings::MaterialSettings;
use crate::tr;
use egui::RichText;

/// The BRDF, shown in every tooltip of this panel.
pub const BRDF: &str = "f_r = c · (k/π + (1 − k) · N(m) · cos^m θ_h), h = normalize(l + o)";

pub struct MaterialPanel<'a> {
    pub material: &'a mut MaterialSettings,
}

/// What each normalization is for, beside its formula.
pub fn norm_note(norm: Normalization) -> String {
    match norm {
        Normalization::None => tr!("norm-none-note"),
        Normalization::Ndf => tr!("norm-ndf-note"),
        Normalization::Approx => tr!("norm-approx-note"),
        Normalization::Exact => tr!("norm-exact-note"),
    }
}

impl View for MaterialPanel<'_> {
    fn ui(&mut self, ui: &mut egui::Ui) {
        let MaterialSettings {
            k,
            m,
            norm,
            use_scene_materials,
            color_override,
        } = self.material;

        ui.checkbox(use_scene_materials, tr!("material-use-scene"))
            .on_hover_text(tr!("material-use-scene-tip"));

        let label = ui.label(tr!("material-k")).on_hover_text(BRDF);
        ui.add(egui::Slider::new(k, 0.0..=1.0).custom_formatter(|x, _| number(x)))
            .labelled_by(label.id)
            .on_hover_text(tr!("material-k-tip", brdf = BRDF));

        let label = ui.label(tr!("material-m")).on_hover_text(BRDF);
        log_slider_with_zero(ui, label.id, m, 0.1, 1e6, "", &tr!("material-m-tip", brdf = BRDF));

        ui.label(tr!("material-norm")).on_hover_text(BRDF);
        egui::Grid::new("normalizations").num_columns(2).show(ui, |ui| {
            for &choice in Normalization::ALL {
                ui.radio_value(norm, choice, choice.name())
                    .on_hover_text(norm_note(choice));
                ui.label(RichText::new(choice.formula().trim_start_matches("N(m) = ")).size(14.0))
                    .on_hover_text(norm_note(choice));
                ui.end_row();
            }
        });
        derived(
            ui,
            &format!("N({}) = {}", number(*m as f64), number(norm.factor(*m as f64))),
            norm.formula(),
        );

        ui.horizontal(|ui| {
            let mut on = color_override.is_some();
            if ui
                .checkbox(&mut on, tr!("material-override"))
                .on_hover_text(tr!("material-override-tip"))
                .changed()
            {
                *color_override = on.then_some(glam::Vec3::splat(0.8));
            }
            if let Some(c) = color_override {
                let mut rgb = c.to_array();
                if ui
                    .color_edit_button_rgb(&mut rgb)
                    .on_hover_text(tr!("material-colour-tip"))
                    .changed()
                {
                    *c = glam::Vec3::from(rgb).clamp(glam::Vec3::ZERO, glam::Vec3::ONE);
                }
            }
        });
    }
}
