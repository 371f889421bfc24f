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
use crate::tr;
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
                ui.label(tr!("colour-model"));
                ui.selectable_value(model, ColourModel::Spectral, tr!("colour-spectral"))
                    .on_hover_text(tr!("colour-spectral-tip"));
                ui.selectable_value(model, ColourModel::RgbApprox, tr!("colour-rgb-approx"))
                    .on_hover_text(tr!("colour-rgb-approx-tip"));
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
        egui::ComboBox::from_label(tr!("colour-material"))
            .selected_text(self.materials[chosen].0.clone())
            .show_ui(ui, |ui| {
                for (i, (name, _)) in self.materials.iter().enumerate() {
                    ui.selectable_value(&mut chosen, i, name);
                }
            })
            .response
            .on_hover_text(tr!("colour-material-tip"));
        ui.data_mut(|d| d.insert_temp(id, chosen));
        let (name, base) = &self.materials[chosen];
        let reflectance = material_reflectance(name, *base);
        let light = illuminant.unwrap_or(Illuminant::D65);
        spectra_plot(ui, light, &reflectance);
        comparison_ui(ui, light, *base, &reflectance);
    }
}

fn illuminant_ui(ui: &mut egui::Ui, illuminant: &mut Option<Illuminant>) {
    let name = illuminant.map_or_else(|| tr!("colour-no-spectrum"), Illuminant::name);
    egui::ComboBox::from_label(tr!("colour-illuminant"))
        .selected_text(name)
        .show_ui(ui, |ui| {
            ui.selectable_value(illuminant, None, tr!("colour-no-spectrum"))
                .on_hover_text(tr!("colour-no-spectrum-tip"));
            for i in Illuminant::NAMED {
                ui.selectable_value(illuminant, Some(i), i.name())
                    .on_hover_text(description(i));
            }
            let blackbody = Illuminant::Blackbody {
                kelvin: DEFAULT_BLACKBODY_K,
            };
            if ui
                .selectable_label(
                    matches!(illuminant, Some(Illuminant::Blackbody { .. })),
                    tr!("colour-blackbody"),
                )
                .on_hover_text(tr!("colour-blackbody-tip"))
                .clicked()
            {
                *illuminant = Some(blackbody);
            }
        })
        .response
        .on_hover_text(tr!("colour-illuminant-tip"));
    if let Some(Illuminant::Blackbody { kelvin }) = illuminant {
        ui.add(
            egui::Slider::new(kelvin, 1000.0..=25000.0)
                .logarithmic(true)
                .suffix(" K")
                .text(tr!("colour-temperature")),
        )
        .on_hover_text(tr!("colour-temperature-tip"));
    }
}

/// What a named illuminant is, in the current language.
fn description(illuminant: Illuminant) -> String {
    match illuminant {
        Illuminant::D65 => tr!("colour-d65-tip"),
        Illuminant::A => tr!("colour-a-tip"),
        Illuminant::Fl2 => tr!("colour-fl2-tip"),
        Illuminant::Fl11 => tr!("colour-fl11-tip"),
        Illuminant::LedB3 => tr!("colour-led-b3-tip"),
        Illuminant::Blackbody { kelvin } => {
            tr!(
                "colour-blackbody-at",
                temperature = format!("{} K", number(kelvin))
            )
        }
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
        .y_axis_label(tr!("colour-relative"))
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
        for (label, rgb) in [
            (tr!("colour-spectral"), spectral),
            (tr!("colour-rgb-product"), approx),
        ] {
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
        &tr!("colour-xyz-tip"),
    );
    ui.label(
        RichText::new(match delta_e {
            d if d < 1.0 => tr!("colour-delta-e-invisible"),
            d if d < 3.0 => tr!("colour-delta-e-visible"),
            _ => tr!("colour-delta-e-different"),
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
