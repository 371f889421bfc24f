//! The material panel: the BRDF's mix k, exponent m and normalization N(m).

use super::View;
use super::widgets::{derived, log_slider_with_zero, number};
use crate::physics::Normalization;
use crate::settings::MaterialSettings;
use egui::RichText;

/// The BRDF, shown in every tooltip of this panel.
pub const BRDF: &str = "f_r = c · (k/π + (1 − k) · N(m) · cos^m θ_h), h = normalize(l + o)";

pub struct MaterialPanel<'a> {
    pub material: &'a mut MaterialSettings,
}

/// What each normalization is for, beside its formula.
pub fn norm_note(norm: Normalization) -> &'static str {
    match norm {
        Normalization::None => "the raw lobe: energy falls as m grows, and exceeds 1 at small m",
        Normalization::Ndf => "normalizes the lobe over half-vectors, not the reflected energy",
        Normalization::Approx => "the usual approximation; a(0°) > 1 at small m (1.075 at m = 8)",
        Normalization::Exact => "exact at normal incidence: a(0°) = 1 for every m",
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

        ui.checkbox(use_scene_materials, "Use the scene's own k and m")
            .on_hover_text(
                "On: objects whose glTF material gives k and m keep them; the others use the \
                 values below. Off: every object uses the values below.",
            );

        let label = ui.label("Diffuse mix k").on_hover_text(BRDF);
        ui.add(egui::Slider::new(k, 0.0..=1.0).custom_formatter(|x, _| number(x)))
            .labelled_by(label.id)
            .on_hover_text(format!(
                "k ∈ [0, 1]: 1 is pure Lambert (f_r = c/π), 0 is the lobe alone.\n{BRDF}"
            ));

        let label = ui.label("Exponent m").on_hover_text(BRDF);
        log_slider_with_zero(
            ui,
            label.id,
            m,
            0.1,
            1e6,
            "",
            &format!(
                "Blinn-Phong exponent m ∈ [0, 10⁶]: larger is a sharper highlight; m = 0 is a flat lobe (0⁰ = 1).\n{BRDF}"
            ),
        );

        ui.label("Normalization N(m)").on_hover_text(BRDF);
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
                .checkbox(&mut on, "Override base colour c")
                .on_hover_text("Replace every object's colour c (linear RGB) in the BRDF")
                .changed()
            {
                *color_override = on.then_some(glam::Vec3::splat(0.8));
            }
            if let Some(c) = color_override {
                let mut rgb = c.to_array();
                if ui
                    .color_edit_button_rgb(&mut rgb)
                    .on_hover_text("c (linear RGB, each in [0, 1])")
                    .changed()
                {
                    *c = glam::Vec3::from(rgb).clamp(glam::Vec3::ZERO, glam::Vec3::ONE);
                }
            }
        });
    }
}
