//! The Lecture panel: the tour's current step, in large type under the
//! image — its title, text and formula, what to observe with the live
//! number, and a question for the class — with Previous and Next. A step
//! is applied by emitting [`Command::TourStep`]; the panel never changes
//! the lab itself. Its words follow the app's language (`i18n::current`).
//!
//! Also here: the side panels' sections as the tour names them
//! ([`Panel`]), their titles, and the highlight of the step's panel.

use super::command::Command;
use super::state::PanelState;
use crate::settings::Settings;
use crate::tour::{Panel, Tour};
use crate::tr;
use egui::{Color32, FontFamily, FontId, RichText};

/// Type sizes readable from the back of a room (points).
const TITLE_PT: f32 = 28.0;
const TEXT_PT: f32 = 21.0;
const FORMULA_PT: f32 = 23.0;
/// The highlight around the step's panel.
const HIGHLIGHT: Color32 = Color32::from_rgb(255, 190, 60);
const HIGHLIGHT_WIDTH_PT: f32 = 3.0;

/// The title of a side panel's section.
pub fn panel_title(panel: Panel) -> String {
    match panel {
        Panel::Experiments => tr!("section-experiments"),
        Panel::Scene => tr!("section-scene"),
        Panel::Light => tr!("section-light"),
        Panel::Colour => tr!("section-colour"),
        Panel::Material => tr!("section-material"),
        Panel::Shadow => tr!("section-shadow"),
        Panel::View => tr!("section-view"),
        Panel::Files => tr!("section-files"),
        Panel::Probe => tr!("section-probe"),
        Panel::Energy => tr!("section-energy"),
        Panel::Reference => tr!("section-reference"),
        Panel::Timings => tr!("section-timings"),
    }
}

/// Whether a section is open before the user or a step opens or closes it.
fn open_by_default(panel: Panel) -> bool {
    !matches!(panel, Panel::Files | Panel::Timings | Panel::Colour)
}

/// The section is in the settings panel (left); else in the analysis panel.
pub fn on_the_left(panel: Panel) -> bool {
    !matches!(
        panel,
        Panel::Probe | Panel::Energy | Panel::Reference | Panel::Timings
    )
}

/// The step's panel, kept in egui's memory for the frame so that
/// [`section`] can find it.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Highlight {
    panel: Panel,
    /// Open it and scroll to it (the first frame after the step).
    open_now: bool,
}

fn highlight_id() -> egui::Id {
    egui::Id::unique("lumlab tour highlight")
}

/// A collapsible section of a side panel, its title in heading size; the
/// tour's current panel framed, and opened when its step begins.
pub fn section(ui: &mut egui::Ui, panel: Panel, add: impl FnOnce(&mut egui::Ui)) {
    let highlight = ui
        .ctx()
        .data(|d| d.get_temp::<Highlight>(highlight_id()))
        .filter(|h| h.panel == panel);
    let header = egui::CollapsingHeader::new(RichText::new(panel_title(panel)).heading())
        .id_salt(panel.name())
        .default_open(open_by_default(panel))
        .open(highlight.filter(|h| h.open_now).map(|_| true));
    let Some(highlight) = highlight else {
        header.show(ui, add);
        return;
    };
    let shown = egui::Frame::new()
        .stroke(egui::Stroke::new(HIGHLIGHT_WIDTH_PT, HIGHLIGHT))
        .inner_margin(4.0)
        .corner_radius(4.0)
        .show(ui, |ui| header.show(ui, add));
    if highlight.open_now {
        shown.inner.header_response.scroll_to_me(Some(egui::Align::Min));
    }
}

/// The tour and where the class is in it.
pub struct LecturePanel {
    tour: Tour,
    /// The step shown (the last one applied).
    current: usize,
    /// Open the step's section on the next frame.
    open_now: bool,
    /// The observed number, for the step and settings it was computed for.
    cache: Option<(usize, Settings, f64)>,
}

impl LecturePanel {
    pub fn new(tour: Tour) -> Self {
        Self {
            tour,
            current: 0,
            open_now: false,
            cache: None,
        }
    }

    pub fn tour(&self) -> &Tour {
        &self.tour
    }

    /// The step shown.
    pub fn current(&self) -> usize {
        self.current
    }

    /// The step `index` was applied: show it and open its panel.
    pub fn select(&mut self, index: usize) {
        self.current = index;
        self.open_now = true;
    }

    /// The panel of the step shown, if the tour has steps.
    pub fn highlighted(&self) -> Option<Panel> {
        self.tour.steps.get(self.current).map(|s| s.panel)
    }

    /// Publishes the highlight for this frame's sections (before the side
    /// panels are drawn), while the Lecture panel is `shown`; the step's
    /// panel is opened once per step.
    pub fn publish_highlight(&mut self, ctx: &egui::Context, shown: bool) {
        let highlight = self.highlighted().filter(|_| shown).map(|panel| Highlight {
            panel,
            open_now: std::mem::take(&mut self.open_now),
        });
        ctx.data_mut(|d| match highlight {
            Some(h) => {
                d.insert_temp(highlight_id(), h);
            }
            None => d.remove::<Highlight>(highlight_id()),
        });
    }

    /// The observed number of the step shown, from `settings`.
    pub fn observed(&mut self, settings: &Settings) -> Option<f64> {
        let step = self.tour.steps.get(self.current)?;
        match &self.cache {
            Some((i, s, v)) if *i == self.current && s == settings => Some(*v),
            _ => {
                let value = step.observed(settings);
                self.cache = Some((self.current, settings.clone(), value));
                Some(value)
            }
        }
    }

    /// The panel's contents; returns the command a button asked for.
    pub fn ui(&mut self, ui: &mut egui::Ui, settings: &Settings, panels: PanelState) -> Option<Command> {
        let language = crate::i18n::current();
        let count = self.tour.steps.len();
        let value = self.observed(settings);
        let Some(step) = self.tour.steps.get(self.current) else {
            ui.label(tr!("lecture-no-steps"));
            return None;
        };
        let text = step.text(language);
        let mut command = None;
        ui.horizontal(|ui| {
            let i = self.current;
            if ui
                .add_enabled(i > 0, egui::Button::new(tr!("lecture-previous")))
                .clicked()
            {
                command = Some(Command::TourStep(i - 1));
            }
            egui::ComboBox::new("tour step", tr!("lecture-steps"))
                .selected_text(format!("{} / {count}", i + 1))
                .show_ui(ui, |ui| {
                    for (j, s) in self.tour.steps.iter().enumerate() {
                        let label = format!("{}. {}", j + 1, s.text(language).title);
                        if ui.selectable_label(j == i, label).clicked() {
                            command = Some(Command::TourStep(j));
                        }
                    }
                });
            if ui
                .add_enabled(i + 1 < count, egui::Button::new(tr!("lecture-next")))
                .clicked()
            {
                command = Some(Command::TourStep(i + 1));
            }
            ui.separator();
            ui.label(RichText::new(&text.title).size(TITLE_PT).strong());
            ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                if ui.button(tr!("lecture-close")).clicked() {
                    command = Some(Command::SetPanels(PanelState {
                        lecture: false,
                        ..panels
                    }));
                }
            });
        });
        ui.separator();
        let number = value.map_or_else(|| "—".into(), |v| step.observe.format(v, language));
        ui.columns(2, |columns| {
            let [left, right] = columns else { return };
            left.label(RichText::new(&text.text).size(TEXT_PT));
            left.add_space(6.0);
            egui::Frame::group(left.style()).show(left, |ui| {
                ui.label(
                    RichText::new(&text.formula)
                        .font(FontId::new(FORMULA_PT, FontFamily::Proportional))
                        .strong(),
                );
            });
            right.label(
                RichText::new(tr!("lecture-observe"))
                    .size(TEXT_PT)
                    .strong()
                    .color(HIGHLIGHT),
            );
            right.label(RichText::new(text.observe_with(&number)).size(TEXT_PT));
            right.add_space(10.0);
            right.label(
                RichText::new(tr!("lecture-question"))
                    .size(TEXT_PT)
                    .strong()
                    .color(HIGHLIGHT),
            );
            right.label(RichText::new(&text.question).size(TEXT_PT).italics());
        });
        command
    }
}
