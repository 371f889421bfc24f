//! The light panel: where the light is, how much power it emits, its size
//! and colour, and the intensity that follows.

use super::View;
use super::widgets::{derived, log_slider_with_zero, quantity};
use crate::physics::radiometry;
use crate::scene::SceneScale;
use crate::settings::LightSettings;

/// The largest power the slider offers on the built-in scene (W); the
/// settings file allows more.
const MAX_POWER_W: f32 = 1e6;

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
            ui.label("Position q").on_hover_text(
                "Centre of the light (m). Drag the yellow gizmo in the image: \
                 parallel to the image, or Ctrl+drag for the height.",
            );
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
                        .suffix(" m"),
                )
                .on_hover_text(format!("Light position, {axis} coordinate (m); +Y is up"));
            }
        });

        let label = ui
            .label("Power Φ")
            .on_hover_text("Radiant power emitted in all directions (W)");
        log_slider_with_zero(
            ui,
            label.id,
            power_w,
            self.scale.power(0.01) as f64,
            self.scale.power(MAX_POWER_W) as f64,
            " W",
            "Φ (W), scaled by the colour. I = Φ / 4π; E = I cos θ / r²",
        );
        let intensity = radiometry::intensity(*power_w as f64);
        derived(
            ui,
            &format!("I = Φ / 4π = {}", quantity(intensity, "W/sr")),
            "Intensity of an isotropic point light: power per steradian, I = Φ / 4π (W/sr)",
        );

        let label = ui.label("Sphere radius R").on_hover_text(
            "R = 0: a point light (hard shadows). R > 0: a sphere light of the same power \
             (soft shadows with the PCSS filter).",
        );
        ui.add(
            egui::Slider::new(radius_m, 0.0..=self.scale.max_light_radius_m())
                .suffix(" m")
                .custom_formatter(|x, _| super::widgets::number(x)),
        )
        .labelled_by(label.id)
        .on_hover_text("R (m); the sphere's radiance is L_e = Φ / (4π² R²)");
        if *radius_m > 0.0 {
            let le = radiometry::sphere_radiance(*power_w as f64, *radius_m as f64);
            derived(
                ui,
                &format!("L_e = Φ / 4π²R² = {}", quantity(le, "W/m²/sr")),
                "Uniform radiance of the sphere light's surface (W/m²/sr)",
            );
        } else {
            ui.label("point light");
        }

        ui.horizontal(|ui| {
            ui.label("Colour")
                .on_hover_text("Linear RGB factors multiplying Φ");
            let mut rgb = color.to_array();
            if ui
                .color_edit_button_rgb(&mut rgb)
                .on_hover_text("Light colour (linear RGB): Φ_rgb = Φ · colour")
                .changed()
            {
                *color = glam::Vec3::from(rgb);
            }
            if ui.button("white").on_hover_text("Colour (1, 1, 1)").clicked() {
                *color = glam::Vec3::ONE;
            }
        });
    }
}
