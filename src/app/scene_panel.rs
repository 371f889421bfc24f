//! The scene panel: what is shown (the file, its size), the ground the lab
//! adds under a model, the file's own cameras, framing and exposure.

use super::command::Command;
use super::widgets::{length, quantity};
use crate::scene::Scene;
use crate::settings::{GroundMode, GroundSettings};

pub struct ScenePanel<'a> {
    pub scene: &'a Scene,
    pub name: &'a str,
    pub ground: &'a mut GroundSettings,
}

impl ScenePanel<'_> {
    /// The panel; returns the command a button emits.
    pub fn ui(self, ui: &mut egui::Ui) -> Option<Command> {
        let Self { scene, name, ground } = self;
        let mut command = None;
        let bounds = scene.model_bounds();
        ui.label(egui::RichText::new(name).strong());
        if !bounds.is_empty() {
            let size = bounds.extent().length() as f64;
            ui.label(format!(
                "{} triangles · {} across",
                scene.triangle_count(),
                length(size)
            ))
            .on_hover_text("The model's bounding-box diagonal: the lab's lengths follow it");
        } else {
            ui.label("nothing to draw: the file has no triangles");
        }
        ui.horizontal(|ui| {
            if ui
                .button("Frame all (F)")
                .on_hover_text("Move the camera along its direction until the model fills the view")
                .clicked()
            {
                command = Some(Command::FrameAll);
            }
            if ui
                .button("Auto exposure (E)")
                .on_hover_text(
                    "EV such that the 95th percentile of the lit pixels' luminance shows at 0.8 (linear)",
                )
                .clicked()
            {
                command = Some(Command::AutoExposure);
            }
        });
        if !scene.cameras.is_empty() {
            ui.horizontal_wrapped(|ui| {
                ui.label("File cameras:");
                for (i, c) in scene.cameras.iter().enumerate() {
                    if ui
                        .button(&c.name)
                        .on_hover_text(format!("The file's camera {i} (--camera gltf:{i})"))
                        .clicked()
                    {
                        command = Some(Command::UseSceneCamera(i));
                    }
                }
            });
        }
        for light in &scene.lights {
            ui.label(format!(
                "File light '{}': I = {}",
                light.name,
                quantity(light.intensity_w_sr as f64, "W/sr")
            ))
            .on_hover_text(format!(
                "KHR_lights_punctual gives candela; I (W/sr) = I (cd) / {} lm/W, the efficacy of \
                 555 nm light (a white source emits more watts for the same candela). The lab's \
                 light starts there with Φ = 4π I.",
                crate::scene::gltf::LUMINOUS_EFFICACY_LM_PER_W
            ));
        }
        let GroundSettings { mode, k, m } = ground;
        ui.horizontal(|ui| {
            ui.label("Ground")
                .on_hover_text("A shadow-receiving ground at the model's lowest point (--ground)");
            for &choice in GroundMode::ALL {
                ui.selectable_value(mode, choice, choice.name())
                    .on_hover_text(match choice {
                        GroundMode::Auto => "Under a model that has none",
                        GroundMode::On => "Always",
                        GroundMode::Off => "Never: the file's geometry only",
                    });
            }
        });
        ui.add(egui::Slider::new(k, 0.0..=1.0).text("ground k"))
            .on_hover_text("The ground's diffuse/specular mix: f_r = c (k/π + (1 − k) N(m) cos^m θ_h)");
        ui.add(
            egui::Slider::new(m, 0.0..=1000.0)
                .logarithmic(true)
                .text("ground m"),
        )
        .on_hover_text("The ground's Blinn-Phong exponent m");
        command
    }
}
