//! The lecture tour in the lab: applying a step (`Command::TourStep`) and
//! placing the Lecture panel under the image.

use super::super::lecture::on_the_left;
use super::super::state::{SplitLayout, SplitState};
use super::{LabApp, ShownScene};
use crate::settings::Settings;
use crate::tour::{SplitChoice, TourScene};
use crate::tr;
use std::sync::Arc;

impl LabApp {
    /// Shows step `index`: its scene; its settings, camera and view as one
    /// undo step (the image size stays the lab's); its split view; its
    /// panel shown, opened and highlighted. An index past the end does
    /// nothing.
    pub(super) fn go_to_step(&mut self, index: usize) {
        let Some(step) = self.lecture.tour().steps.get(index).cloned() else {
            return;
        };
        self.show_tour_scene(step.scene);
        let image = self.state.settings.image;
        self.settings_in_one_step(|s| {
            *s = Settings {
                image,
                ..step.settings.clone()
            }
        });
        self.state.split = SplitState {
            enabled: step.split != SplitChoice::Off,
            layout: match step.split {
                SplitChoice::SideBySide => SplitLayout::SideBySide,
                SplitChoice::Off | SplitChoice::Wipe => SplitLayout::Wipe,
            },
            comparison: step.comparison,
            ..self.state.split
        };
        let panels = &mut self.state.panels;
        panels.lecture = true;
        if on_the_left(step.panel) {
            panels.settings = true;
        } else {
            panels.analysis = true;
        }
        self.lecture.select(index);
        let count = self.lecture.tour().steps.len();
        let title = &step.text(crate::i18n::current()).title;
        self.say(
            tr!(
                "tour-status",
                step = index + 1,
                count = count,
                title = title.as_str()
            ),
            false,
        );
    }

    /// Replaces the scene by the built-in one the step names, unless it is
    /// already shown.
    fn show_tour_scene(&mut self, which: TourScene) {
        let shown = ShownScene::BuiltIn(which);
        if self.state.settings.scene.is_none() && self.shown == shown {
            return;
        }
        let scene = match which {
            TourScene::BuiltIn => crate::scene::default_scene(),
            TourScene::Spheres => crate::scene::lecture_scene::scene(),
        };
        self.file_scene = Arc::new(scene);
        self.shown = shown;
        self.redraw_scene();
    }

    /// The Lecture panel under the image, when shown.
    pub(super) fn lecture_panel(&mut self, ui: &mut egui::Ui) {
        self.lecture
            .publish_highlight(ui.ctx(), self.state.panels.lecture);
        if !self.state.panels.lecture {
            return;
        }
        // As tall as the step's words: nothing of them is ever cut off.
        egui::Panel::bottom("lecture panel")
            .resizable(false)
            .frame(self.panel_frame(ui))
            .show(ui, |ui| {
                let panels = self.state.panels;
                if let Some(command) = self.lecture.ui(ui, &self.state.settings, panels) {
                    self.queue.push(command);
                }
            });
    }

    /// The tour step shown, and the panel it highlights (tests).
    pub fn tour_position(&self) -> (usize, Option<crate::tour::Panel>) {
        (self.lecture.current(), self.lecture.highlighted())
    }

    /// The tour the Lecture panel walks through.
    pub fn tour(&self) -> &crate::tour::Tour {
        self.lecture.tour()
    }

    /// The live number of the step shown, from the current settings.
    pub fn tour_observed(&mut self) -> Option<f64> {
        self.lecture.observed(&self.state.settings)
    }
}
