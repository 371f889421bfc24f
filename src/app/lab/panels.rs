//! The layout around the viewport: the top bar, the status bar, the settings
//! panel on the left and the analysis panel on the right. Panels edit copies
//! and emit commands; nothing here changes the app's state itself.

use super::super::View;
use super::super::colour::ColourPanel;
use super::super::command::Command;
use super::super::energy::{Curve, EnergyKey};
use super::super::lecture::section;
use super::super::light::LightPanel;
use super::super::material::MaterialPanel;
use super::super::names::{preset_description, preset_title};
use super::super::scene_panel::ScenePanel;
use super::super::shadow::ShadowPanel;
use super::super::view::ViewPanel;
use super::super::viewport::Viewport;
use super::LabApp;
use crate::presets::{ComparisonAxis, Half, Preset};
use crate::tour::Panel;
use crate::tr;
use egui::RichText;

/// Runs `add` in a Ui that knows it lies on the panels' colour even when
/// the panel painted no fill ([`LabApp::panel_frame`]): a scroll area's
/// fade at its edges is painted in that colour (`UiStack::bg_color`).
fn on_panel_fill<R>(ui: &mut egui::Ui, add: impl FnOnce(&mut egui::Ui) -> R) -> R {
    let fill = egui::Frame::NONE.fill(ui.visuals().panel_fill);
    let info = egui::UiStackInfo::new(egui::UiKind::GenericArea).with_frame(fill);
    ui.scope_builder(egui::UiBuilder::new().ui_stack_info(info), add)
        .inner
}

impl LabApp {
    pub(super) fn top_bar(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            ui.heading("lumlab");
            self.file_menu(ui);
            ui.separator();
            let can_undo = self.undo.can_undo(&self.state.settings);
            if ui
                .add_enabled(can_undo, egui::Button::new(tr!("top-undo")))
                .on_hover_text(tr!("top-undo-tip"))
                .clicked()
            {
                self.emit(Command::Undo);
            }
            if ui
                .add_enabled(self.undo.can_redo(), egui::Button::new(tr!("top-redo")))
                .on_hover_text(tr!("top-redo-tip"))
                .clicked()
            {
                self.emit(Command::Redo);
            }
            if ui
                .button(tr!("top-reset-view"))
                .on_hover_text(tr!("top-reset-view-tip"))
                .clicked()
            {
                self.emit(Command::ResetView);
            }
            if ui
                .selectable_label(self.state.split.enabled, tr!("top-split"))
                .on_hover_text(tr!("top-split-tip"))
                .clicked()
            {
                self.emit(Command::ToggleSplit);
            }
            ui.separator();
            let mut panels = self.state.panels;
            ui.toggle_value(&mut panels.settings, tr!("top-settings"))
                .on_hover_text(tr!("top-settings-tip"));
            ui.toggle_value(&mut panels.analysis, tr!("top-analysis"))
                .on_hover_text(tr!("top-analysis-tip"));
            ui.toggle_value(&mut panels.lecture, tr!("top-lecture"))
                .on_hover_text(tr!("top-lecture-tip"));
            if panels != self.state.panels {
                self.emit(Command::SetPanels(panels));
            }
            if ui
                .selectable_label(self.help_open, tr!("top-help"))
                .on_hover_text(tr!("top-help-tip"))
                .clicked()
            {
                self.emit(Command::ToggleHelp);
            }
            self.language_menu(ui);
        });
    }

    pub(super) fn status_bar(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            match &self.status {
                Some(s) if s.error => {
                    ui.label(RichText::new(&s.text).color(ui.visuals().error_fg_color));
                }
                Some(s) => {
                    ui.label(&s.text);
                }
                None => {
                    ui.label(tr!("status-hint"));
                }
            }
            if let Some(first) = self.impossible_setups().first() {
                let more = self.impossible_setups().len() - 1;
                let first = first.as_str();
                let text = match more {
                    0 => tr!("status-impossible", first = first),
                    n => tr!("status-impossible-more", first = first, more = n),
                };
                ui.separator();
                ui.label(RichText::new(text).color(ui.visuals().warn_fg_color))
                    .on_hover_text(tr!(
                        "status-impossible-tip",
                        lines = self.impossible_setups().join("\n")
                    ));
            }
            ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                if let Some(gpu) = &self.gpu {
                    let caps = gpu.capabilities();
                    let name = caps.adapter.split(" (").next().unwrap_or(&caps.adapter);
                    ui.label(format!(
                        "{}×{} px · {name} ({})",
                        self.viewport_size.0,
                        self.viewport_size.1,
                        gpu.backend()
                    ))
                    .on_hover_text(caps.adapter.as_str());
                }
            });
        });
    }

    /// The frame of the panels around the viewport. Where the window is
    /// already cleared to the panels' colour their fill is left out: on a
    /// software rasterizer every pixel painted costs, and the fills cover
    /// half the window (`lumlab --drag-bench`: 211 → 144 ms of CPU a drag
    /// frame on lavapipe with egui's stock shader).
    pub(super) fn panel_frame(&self, ui: &egui::Ui) -> egui::Frame {
        let frame = egui::Frame::side_top_panel(ui.style());
        if self.window_cleared_to_panel_fill {
            frame.fill(egui::Color32::TRANSPARENT)
        } else {
            frame
        }
    }

    /// The settings panel (left) and the analysis panel (right), as the
    /// panel state shows them.
    pub(super) fn side_panels(&mut self, ui: &mut egui::Ui) {
        if self.state.panels.settings {
            egui::Panel::left("settings panel")
                .resizable(true)
                .default_size(330.0)
                .size_range(260.0..=560.0)
                .frame(self.panel_frame(ui))
                .show(ui, |ui| {
                    on_panel_fill(ui, |ui| {
                        egui::ScrollArea::vertical().show(ui, |ui| self.settings_panel(ui));
                    });
                });
        }
        if self.state.panels.analysis {
            egui::Panel::right("analysis panel")
                .resizable(true)
                .default_size(420.0)
                .size_range(280.0..=640.0)
                .frame(self.panel_frame(ui))
                .show(ui, |ui| {
                    // Scrolled both ways: wide rows (the probe's vectors) never
                    // widen the panel, which would shrink the image under the probe.
                    on_panel_fill(ui, |ui| {
                        egui::ScrollArea::both().show(ui, |ui| self.analysis_panel(ui));
                    });
                });
        }
    }

    fn settings_panel(&mut self, ui: &mut egui::Ui) {
        section(ui, Panel::Experiments, |ui| {
            ui.horizontal_wrapped(|ui| {
                for &preset in Preset::ALL {
                    if ui
                        .button(preset_title(preset))
                        .on_hover_text(preset_description(preset))
                        .clicked()
                    {
                        self.emit(Command::ApplyPreset(preset));
                    }
                }
            });
        });
        let mut settings = self.state.settings.clone();
        let mut split = self.state.split;
        section(ui, Panel::Scene, |ui| {
            let panel = ScenePanel {
                scene: &self.file_scene,
                name: &self.shown.name(),
                ground: &mut settings.ground,
            };
            if let Some(command) = panel.ui(ui) {
                self.queue.push(command);
            }
        });
        let (max_side, note) = match &self.gpu {
            Some(gpu) => (
                gpu.capabilities().max_texture_side,
                gpu.half(Half::A)
                    .and_then(|h| h.report.resolution_note.clone().map(|n| (h.report.resolution, n))),
            ),
            None => (crate::settings::ShadowSettings::MAX_RESOLUTION, None),
        };
        section(ui, Panel::Light, |ui| {
            LightPanel {
                light: &mut settings.light,
                scale: self.scene.scale,
            }
            .ui(ui)
        });
        section(ui, Panel::Colour, |ui| {
            ColourPanel {
                colour: &mut settings.colour,
                materials: self
                    .scene
                    .materials
                    .iter()
                    .map(|m| (m.name.clone(), m.base_color.truncate().as_dvec3()))
                    .collect(),
            }
            .ui(ui)
        });
        section(ui, Panel::Material, |ui| {
            MaterialPanel {
                material: &mut settings.material,
            }
            .ui(ui)
        });
        section(ui, Panel::Shadow, |ui| {
            ShadowPanel {
                shadow: &mut settings.shadow,
                light_radius_m: &mut settings.light.radius_m,
                scale: self.scene.scale,
                max_texture_side: max_side,
                resolution_note: note,
            }
            .ui(ui)
        });
        section(ui, Panel::View, |ui| {
            ViewPanel {
                view: &mut settings.view,
                split: &mut split,
                max_texture_side: max_side,
            }
            .ui(ui)
        });
        if settings != self.state.settings {
            self.emit(Command::SetSettings(Box::new(settings)));
        }
        if split != self.state.split {
            self.emit(Command::SetSplit(split));
        }
        section(ui, Panel::Files, |ui| {
            if let Some(command) = self.files.ui(ui, &self.state.paths, &self.shown.name()) {
                self.queue.push(command);
            }
        });
    }

    fn analysis_panel(&mut self, ui: &mut egui::Ui) {
        section(ui, Panel::Probe, |ui| self.probe.ui(ui));
        let curves = self.energy_curves();
        let incidence = self.incidence_for_lobe();
        section(ui, Panel::Energy, |ui| {
            self.energy
                .ui(ui, &curves, incidence.as_ref().map(|(t, s)| (*t, s.as_str())))
        });
        let settings_a = Viewport::render_settings(
            &self.state.settings,
            &self.state.split,
            Half::A,
            self.viewport_size,
        );
        section(ui, Panel::Reference, |ui| {
            if let Some(command) = self.reference.ui(ui, &settings_a, self.viewport_size) {
                self.queue.push(command);
            }
        });
        section(ui, Panel::Timings, |ui| {
            super::super::timings::ui(ui, &self.clock, self.gpu.as_ref())
        });
    }

    /// The BRDF of the material settings; both halves' when the split view
    /// compares normalizations.
    fn energy_curves(&self) -> Vec<Curve> {
        let split = &self.state.split;
        let halves: &[(Half, &str)] =
            if split.enabled && split.comparison.axis == ComparisonAxis::Normalization {
                &[(Half::A, "A: "), (Half::B, "B: ")]
            } else {
                &[(Half::A, "")]
            };
        halves
            .iter()
            .map(|&(half, name)| {
                let m = Viewport::settings_for(&self.state.settings, split, half).material;
                Curve {
                    name: name.into(),
                    key: EnergyKey {
                        k: m.k as f64,
                        m: m.m as f64,
                        norm: m.norm,
                    },
                }
            })
            .collect()
    }

    /// θ_i for the lobe plot: at the probed point, else from the light to
    /// the scene's centre on its floor (normal +Y).
    fn incidence_for_lobe(&self) -> Option<(f64, String)> {
        if let Some(t) = &self.probe.terms {
            return Some((
                t.cos_theta.clamp(-1.0, 1.0).acos().to_degrees(),
                tr!("lobe-at-probe"),
            ));
        }
        let bounds = self.scene.bounds();
        if bounds.is_empty() {
            return None;
        }
        let mut centre = bounds.center().as_dvec3();
        centre.y = bounds.min.y as f64;
        let to_light = self.state.settings.light.position.as_dvec3() - centre;
        let cos = to_light.normalize_or_zero().y;
        Some((cos.clamp(-1.0, 1.0).acos().to_degrees(), tr!("lobe-at-centre")))
    }
}
