//! The light panel: where the light is, how much power it emits, its size
//! and colour, and the intensity that follows.

use super::View;
use super::widgets::{derived, log_slider_with_zero, quantity};
use crate::physics::radiometry;
use crate::scene::SceneScale;
use crate::settings::LightSettings;
use crate::tr;

/// The largest power the slider offers on the built-in scene (W); the
/// settings file allows more.
const MAX_POWER_W: f32 = 1e6;

/// Where the radius slider was laid out last (rail and value, points),
/// for `lumlab --drag-bench-target slider`; None before the light panel
/// was first shown.
pub(super) fn radius_slider_rect(ctx: &egui::Context) -> Option<egui::Rect> {
    ctx.data(|d| d.get_temp(radius_slider_key()))
}

fn radius_slider_key() -> egui::Id {
    egui::Id::unique("lumlab light radius slider")
}

pub struct LightPanel<'a> {
    pub light: &'a mut LightSettings,
    /// The scene's scale: the sliders' ranges and drag speeds follow it.
    pub scale: SceneScale,
}

impl View for LightPanel<'_> {
    fn ui(&mut self, ui: &mut egui::Ui) {
        let LightSettings {
            position,
            power_w,
            radius_m,
            color,
        } = self.light;

        ui.horizontal(|ui| {
            ui.label(tr!("light-position"))
                .on_hover_text(tr!("light-position-tip"));
            // The built-in scene's ±10 km, moved with the scene.
            let reach = self.scale.length(1e4);
            let anchor = self.scale.anchor;
            for ((axis, value), centre) in ["x", "y", "z"]
                .into_iter()
                .zip(position.as_mut())
                .zip(anchor.to_array())
            {
                let range = (centre - reach)..=(centre + reach);
                ui.add(
                    egui::DragValue::new(value)
                        .speed(self.scale.length(0.02))
                        .range(range.clone())
                        .prefix(format!("{axis} "))
                        .suffix(" m")
                        // Four significant digits, as every read-out: a
                        // far light's 1.4e11 m keeps the row's width.
                        .custom_formatter(|x, _| super::widgets::number(x)),
                )
                .on_hover_text(tr!("light-position-axis-tip", axis = axis));
            }
        });

        let label = ui.label(tr!("light-power")).on_hover_text(tr!("light-power-tip"));
        log_slider_with_zero(
            ui,
            label.id,
            power_w,
            self.scale.power(0.01) as f64,
            self.scale.power(MAX_POWER_W) as f64,
            " W",
            &tr!("light-power-slider-tip"),
        );
        let intensity = radiometry::intensity(*power_w as f64);
        derived(
            ui,
            &format!("I = Φ / 4π = {}", quantity(intensity, "W/sr")),
            &tr!("light-intensity-tip"),
        );

        let label = ui
            .label(tr!("light-radius"))
            .on_hover_text(tr!("light-radius-tip"));
        let slider = ui
            .add(
                egui::Slider::new(radius_m, 0.0..=self.scale.max_light_radius_m())
                    .suffix(" m")
                    .custom_formatter(|x, _| super::widgets::number(x)),
            )
            .labelled_by(label.id)
            .on_hover_text(tr!("light-radius-slider-tip"));
        ui.data_mut(|d| d.insert_temp(radius_slider_key(), slider.rect));
        if *radius_m > 0.0 {
            let le = radiometry::sphere_radiance(*power_w as f64, *radius_m as f64);
            derived(
                ui,
                &format!("L_e = Φ / 4π²R² = {}", quantity(le, "W/m²/sr")),
                &tr!("light-sphere-radiance-tip"),
            );
        } else {
            ui.label(tr!("light-point"));
        }

        ui.horizontal(|ui| {
            ui.label(tr!("light-colour"))
                .on_hover_text(tr!("light-colour-tip"));
            let mut rgb = color.to_array();
            if ui
                .color_edit_button_rgb(&mut rgb)
                .on_hover_text(tr!("light-colour-button-tip"))
                .changed()
            {
                *color = glam::Vec3::from(rgb);
            }
            if ui
                .button(tr!("light-white"))
                .on_hover_text(tr!("light-white-tip"))
                .clicked()
            {
                *color = glam::Vec3::ONE;
            }
        });
    }
}
