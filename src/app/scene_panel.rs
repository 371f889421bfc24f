//! The scene panel: what is shown (the file, its size), the ground the lab
//! adds under a model, the file's own cameras, framing and exposure.

use super::command::Command;
use super::widgets::{length, quantity};
use crate::scene::Scene;
use crate::settings::{GroundMode, GroundSettings};
use crate::tr;

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
            ui.label(tr!(
                "scene-size",
                triangles = scene.triangle_count(),
                size = length(size)
            ))
            .on_hover_text(tr!("scene-size-tip"));
        } else {
            ui.label(tr!("scene-empty"));
        }
        ui.horizontal(|ui| {
            if ui
                .button(tr!("scene-frame-all"))
                .on_hover_text(tr!("scene-frame-all-tip"))
                .clicked()
            {
                command = Some(Command::FrameAll);
            }
            if ui
                .button(tr!("scene-auto-exposure"))
                .on_hover_text(tr!("scene-auto-exposure-tip"))
                .clicked()
            {
                command = Some(Command::AutoExposure);
            }
        });
        if !scene.cameras.is_empty() {
            ui.horizontal_wrapped(|ui| {
                ui.label(tr!("scene-cameras"));
                for (i, c) in scene.cameras.iter().enumerate() {
                    if ui
                        .button(&c.name)
                        .on_hover_text(tr!("scene-camera-tip", index = i))
                        .clicked()
                    {
                        command = Some(Command::UseSceneCamera(i));
                    }
                }
            });
        }
        for light in &scene.lights {
            ui.label(tr!(
                "scene-file-light",
                name = light.name.as_str(),
                intensity = quantity(light.intensity_w_sr as f64, "W/sr")
            ))
            .on_hover_text(tr!(
                "scene-file-light-tip",
                efficacy = crate::scene::gltf::LUMINOUS_EFFICACY_LM_PER_W.to_string()
            ));
        }
        let GroundSettings { mode, k, m } = ground;
        ui.horizontal(|ui| {
            ui.label(tr!("scene-ground"))
                .on_hover_text(tr!("scene-ground-tip"));
            for &choice in GroundMode::ALL {
                ui.selectable_value(mode, choice, choice.name())
                    .on_hover_text(match choice {
                        GroundMode::Auto => tr!("scene-ground-auto-tip"),
                        GroundMode::On => tr!("scene-ground-on-tip"),
                        GroundMode::Off => tr!("scene-ground-off-tip"),
                    });
            }
        });
        ui.add(egui::Slider::new(k, 0.0..=1.0).text(tr!("scene-ground-k")))
            .on_hover_text(tr!("scene-ground-k-tip"));
        ui.add(
            egui::Slider::new(m, 0.0..=1000.0)
                .logarithmic(true)
                .text(tr!("scene-ground-m")),
        )
        .on_hover_text(tr!("scene-ground-m-tip"));
        command
    }
}
