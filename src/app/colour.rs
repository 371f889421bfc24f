//! The colour panel: the light's spectrum (or RGB), a material's
//! reflectance, the CIE 1931 colour-matching functions and their products,
//! and how far the lecture's RGB product lands from the spectral result.

use super::View;
use super::widgets::{derived, number};
use crate::colour::chart::illuminant_linear_srgb;
use crate::colour::data::cmfs;
use crate::colour::shading::{material_reflectance, pixel_delta_e, spectral_colour};
use crate::colour::tristimulus::{linear_srgb_to_xyz, srgb_encode};
use crate::colour::{ColourModel, Illuminant, Spectrum};
use crate::settings::ColourSettings;
use egui::{Color32, RichText};
use egui_plot::{Legend, Line, Plot, PlotPoints};
use glam::DVec3;

/// Temperatures the blackbody choice starts from and allows (K).
const DEFAULT_BLACKBODY_K: f64 = 3000.0;

pub struct ColourPanel<'a> {
    pub colour: &'a mut ColourSettings,
    /// The scene's materials: name and linear RGB base colour.
    pub materials: Vec<(String, DVec3)>,
}

impl View for ColourPanel<'_> {
    fn ui(&mut self, ui: &mut egui::Ui) {
        let ColourSettings { illuminant, model } = self.colour;
        illuminant_ui(ui, illuminant);
        if illuminant.is_some() {
            ui.horizontal(|ui| {
                ui.label("Model");
                ui.selectable_value(model, ColourModel::Spectral, "spectral")
                    .on_hover_text(
                        "XYZ = Σ S(λ) R(λ) (x̄, ȳ, z̄)(λ) Δλ, scaled so a perfect white has the light colour's \
                     luminance, then linear sRGB",
                    );
                ui.selectable_value(model, ColourModel::RgbApprox, "RGB approximation")
                    .on_hover_text(
                        "The lecture's product: (light's linear sRGB at Y = 1) × luminance of the light \
                         colour × base colour, channel by channel",
                    );
            });
        }
        if self.materials.is_empty() {
            return;
        }
        let id = egui::Id::unique("lumlab colour panel material");
        let mut chosen: usize = ui
            .data(|d| d.get_temp(id))
            .unwrap_or(0)
            .min(self.materials.len() - 1);
        egui::ComboBox::from_label("Material")
            .selected_text(self.materials[chosen].0.clone())
            .show_ui(ui, |ui| {
                for (i, (name, _)) in self.materials.iter().enumerate() {
                    ui.selectable_value(&mut chosen, i, name);
                }
            })
            .response
            .on_hover_text(
                "Its reflectance R(λ): measured for a ColorChecker patch, else uplifted from the base \
                 colour (Jakob & Hanika 2019)",
            );
        ui.data_mut(|d| d.insert_temp(id, chosen));
        let (name, base) = &self.materials[chosen];
        let reflectance = material_reflectance(name, *base);
        let light = illuminant.unwrap_or(Illuminant::D65);
        spectra_plot(ui, light, &reflectance);
        comparison_ui(ui, light, *base, &reflectance);
    }
}

fn illuminant_ui(ui: &mut egui::Ui, illuminant: &mut Option<Illuminant>) {
    let name = illuminant.map_or_else(|| "RGB (no spectrum)".into(), Illuminant::name);
    egui::ComboBox::from_label("Illuminant")
        .selected_text(name)
        .show_ui(ui, |ui| {
            ui.selectable_value(illuminant, None, "RGB (no spectrum)")
                .on_hover_text("The light's RGB colour times each base colour: the lecture's model");
            for i in Illuminant::NAMED {
                ui.selectable_value(illuminant, Some(i), i.name())
                    .on_hover_text(i.description());
            }
            let blackbody = Illuminant::Blackbody {
                kelvin: DEFAULT_BLACKBODY_K,
            };
            if ui
                .selectable_label(
                    matches!(illuminant, Some(Illuminant::Blackbody { .. })),
                    "blackbody",
                )
                .on_hover_text("Planck's law: M(λ, T) ∝ λ⁻⁵ / (exp(c₂ / λT) − 1)")
                .clicked()
            {
                *illuminant = Some(blackbody);
            }
        })
        .response
        .on_hover_text(
            "The light's spectrum S(λ) (CIE 015:2018 tables, or Planck). It keeps the luminance of the \
             light colour: only the chromaticity changes",
        );
    if let Some(Illuminant::Blackbody { kelvin }) = illuminant {
        ui.add(
            egui::Slider::new(kelvin, 1000.0..=25000.0)
                .logarithmic(true)
                .suffix(" K")
                .text("temperature T"),
        )
        .on_hover_text("Colour temperature of the Planckian radiator (K)");
    }
}

/// S(λ) and R(λ) with the CMFs, and S·R·x̄, S·R·ȳ, S·R·z̄ (what X, Y, Z sum).
fn spectra_plot(ui: &mut egui::Ui, illuminant: Illuminant, reflectance: &Spectrum) {
    let s = illuminant.spectrum().normalized_to_peak();
    let line = |name: &str, spectrum: &Spectrum| {
        Line::new(
            name.to_owned(),
            PlotPoints::from_iter(spectrum.samples().map(|(nm, v)| [nm, v])),
        )
    };
    let [x_bar, y_bar, z_bar] = cmfs();
    let (red, green, blue) = (
        Color32::from_rgb(220, 60, 60),
        Color32::from_rgb(60, 170, 60),
        Color32::from_rgb(70, 110, 230),
    );
    Plot::new("spectra plot")
        .height(220.0)
        .allow_drag(false)
        .allow_zoom(false)
        .allow_scroll(false)
        .include_y(0.0)
        .include_y(1.8)
        .x_axis_label("λ (nm)")
        .y_axis_label("relative")
        .legend(Legend::default())
        .show(ui, |plot| {
            plot.add(
                line("S(λ) / max", &s)
                    .color(Color32::from_rgb(230, 180, 40))
                    .width(2.5),
            );
            plot.add(line("R(λ)", reflectance).color(Color32::GRAY).width(2.5));
            for (name, cmf, colour) in [("x̄", x_bar, red), ("ȳ", y_bar, green), ("z̄", z_bar, blue)] {
                plot.add(
                    line(name, cmf)
                        .color(colour)
                        .style(egui_plot::LineStyle::dashed_loose()),
                );
                plot.add(
                    line(&format!("S·R·{name}"), &(s * *reflectance * *cmf))
                        .color(colour)
                        .fill(0.0)
                        .fill_alpha(0.15),
                );
            }
        });
}

/// The material's colour under the light both ways, and their ΔE2000.
fn comparison_ui(ui: &mut egui::Ui, illuminant: Illuminant, base: DVec3, reflectance: &Spectrum) {
    let s = illuminant.spectrum();
    let spectral = spectral_colour(&s, reflectance);
    let approx = base * illuminant_linear_srgb(&s);
    let delta_e = pixel_delta_e(illuminant, spectral, approx);
    ui.horizontal(|ui| {
        for (label, rgb) in [("spectral", spectral), ("RGB product", approx)] {
            swatch(ui, rgb);
            ui.label(label);
        }
    });
    let xyz = linear_srgb_to_xyz(spectral) * 100.0;
    derived(
        ui,
        &format!(
            "X, Y, Z = {}, {}, {}   ΔE2000 = {}",
            number(xyz.x),
            number(xyz.y),
            number(xyz.z),
            number(delta_e)
        ),
        "Spectral XYZ = k Σ S R (x̄, ȳ, z̄), k = 100 / Σ S ȳ; ΔE2000 (CIE 2001) between the spectral \
         result and the RGB product in CIE Lab, the illuminant's white as reference",
    );
    ui.label(
        RichText::new(match delta_e {
            d if d < 1.0 => "below 1: not visible",
            d if d < 3.0 => "1 to 3: visible side by side",
            _ => "above 3: a different colour",
        })
        .small(),
    );
}

fn swatch(ui: &mut egui::Ui, linear: DVec3) {
    let [r, g, b] = linear
        .to_array()
        .map(|c| (255.0 * srgb_encode(c.clamp(0.0, 1.0))).round() as u8);
    let (rect, _) = ui.allocate_exact_size(egui::vec2(28.0, 18.0), egui::Sense::hover());
    ui.painter().rect_filled(rect, 2.0, Color32::from_rgb(r, g, b));
}
