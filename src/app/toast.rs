//! Errors where the user looks: besides the status line, a failed open or
//! save stays at the bottom right of the window until dismissed. egui has
//! no toast of its own; an `Area` with a close button is all it takes.

/// The messages shown, oldest first.
#[derive(Default)]
pub struct Toasts {
    messages: Vec<String>,
}

impl Toasts {
    /// Messages kept; an older one gives way to a newer.
    const KEPT: usize = 3;

    pub fn push(&mut self, message: impl Into<String>) {
        if self.messages.len() == Self::KEPT {
            self.messages.remove(0);
        }
        self.messages.push(message.into());
    }

    /// The messages shown now, oldest first.
    pub fn messages(&self) -> &[String] {
        &self.messages
    }

    /// Draws the messages stacked at the bottom right; a close button
    /// dismisses one.
    pub fn show(&mut self, ctx: &egui::Context) {
        if self.messages.is_empty() {
            return;
        }
        let mut dismissed = None;
        egui::Area::new(egui::Id::unique("lumlab toasts"))
            .anchor(egui::Align2::RIGHT_BOTTOM, [-12.0, -40.0])
            .order(egui::Order::Foreground)
            .show(ctx, |ui| {
                ui.set_max_width(460.0);
                for (i, message) in self.messages.iter().enumerate() {
                    egui::Frame::popup(ui.style())
                        .stroke(egui::Stroke::new(1.0, ui.visuals().error_fg_color))
                        .show(ui, |ui| {
                            ui.horizontal(|ui| {
                                ui.label(egui::RichText::new("⚠").color(ui.visuals().error_fg_color));
                                ui.add(egui::Label::new(message).wrap());
                                if ui.small_button(crate::tr!("toast-dismiss")).clicked() {
                                    dismissed = Some(i);
                                }
                            });
                        });
                }
            });
        if let Some(i) = dismissed {
            self.messages.remove(i);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_newest_messages_are_kept() {
        let mut toasts = Toasts::default();
        for i in 0..5 {
            toasts.push(format!("error {i}"));
        }
        assert_eq!(toasts.messages(), ["error 2", "error 3", "error 4"]);
    }
}
