//! The keyboard shortcuts, in one table from which both the key handling and
//! the help window are made, so that they can never disagree; and the mouse
//! gestures the help lists beside them.

use super::command::Command;
use crate::tr;
use egui::{Key, KeyboardShortcut, ModifierNames, Modifiers};

/// One row of the help: the keys that emit `command`.
pub struct Shortcut {
    /// Alternatives; the first is the one a test presses.
    pub keys: &'static [KeyboardShortcut],
    /// What the keys do, in the current language.
    pub does: Text,
    pub command: Command,
}

const fn key(modifiers: Modifiers, key: Key) -> KeyboardShortcut {
    KeyboardShortcut::new(modifiers, key)
}

const NONE: Modifiers = Modifiers::NONE;
const SHIFT: Modifiers = Modifiers::SHIFT;
const CMD: Modifiers = Modifiers::COMMAND;
const CMD_SHIFT: Modifiers = Modifiers::COMMAND.plus(Modifiers::SHIFT);

/// The table. A key pattern matches with extra Shift held (egui's logical
/// matching), so a row with Shift comes before the same key without it.
pub static SHORTCUTS: &[Shortcut] = &[
    Shortcut {
        keys: &[
            key(NONE, Key::F1),
            key(SHIFT, Key::Questionmark),
            key(NONE, Key::Questionmark),
        ],
        does: || tr!("shortcut-help"),
        command: Command::ToggleHelp,
    },
    Shortcut {
        keys: &[key(CMD_SHIFT, Key::Z), key(CMD, Key::Y)],
        does: || tr!("shortcut-redo"),
        command: Command::Redo,
    },
    Shortcut {
        keys: &[key(CMD, Key::Z)],
        does: || tr!("shortcut-undo"),
        command: Command::Undo,
    },
    Shortcut {
        keys: &[key(CMD, Key::S)],
        does: || tr!("shortcut-save-settings"),
        command: Command::SaveSettings(None),
    },
    Shortcut {
        keys: &[key(CMD, Key::O)],
        does: || tr!("shortcut-open-scene"),
        command: Command::ChooseFile(super::files::FileAction::OpenScene),
    },
    Shortcut {
        keys: &[key(NONE, Key::R)],
        does: || tr!("shortcut-reset-view"),
        command: Command::ResetView,
    },
    Shortcut {
        keys: &[key(NONE, Key::F)],
        does: || tr!("shortcut-frame-all"),
        command: Command::FrameAll,
    },
    Shortcut {
        keys: &[key(NONE, Key::E)],
        does: || tr!("shortcut-auto-exposure"),
        command: Command::AutoExposure,
    },
    Shortcut {
        keys: &[key(NONE, Key::S)],
        does: || tr!("shortcut-split"),
        command: Command::ToggleSplit,
    },
    Shortcut {
        keys: &[key(SHIFT, Key::V)],
        does: || tr!("shortcut-previous-view"),
        command: Command::StepView(-1),
    },
    Shortcut {
        keys: &[key(NONE, Key::V)],
        does: || tr!("shortcut-next-view"),
        command: Command::StepView(1),
    },
    Shortcut {
        keys: &[key(NONE, Key::F5)],
        does: || tr!("shortcut-reference"),
        command: Command::StartReference,
    },
    Shortcut {
        keys: &[key(NONE, Key::Escape)],
        does: || tr!("shortcut-cancel"),
        command: Command::Cancel,
    },
    Shortcut {
        keys: &[key(NONE, Key::F12)],
        does: || tr!("shortcut-screenshot"),
        command: Command::Screenshot(None),
    },
    Shortcut {
        keys: &[key(NONE, Key::F9)],
        does: || tr!("shortcut-panels"),
        command: Command::TogglePanels,
    },
];

/// A text in the current language, made when shown.
pub type Text = fn() -> String;

/// (gesture, what it does): the mouse, which has no command of its own
/// (the viewport turns a drag into new settings).
pub const GESTURES: &[(Text, Text)] = &[
    (|| tr!("gesture-left-drag"), || tr!("gesture-left-drag-does")),
    (|| tr!("gesture-pan"), || tr!("gesture-pan-does")),
    (|| tr!("gesture-wheel"), || tr!("gesture-wheel-does")),
    (|| tr!("gesture-click"), || tr!("gesture-click-does")),
    (
        || tr!("gesture-double-click"),
        || tr!("gesture-double-click-does"),
    ),
    (|| tr!("gesture-drag-light"), || tr!("gesture-drag-light-does")),
    (
        || tr!("gesture-ctrl-drag-light"),
        || tr!("gesture-ctrl-drag-light-does"),
    ),
];

impl Shortcut {
    /// The keys as the help shows them, e.g. "Ctrl+Shift+Z or Ctrl+Y".
    pub fn keys_text(&self) -> String {
        let mac = cfg!(target_os = "macos");
        let names = if mac {
            ModifierNames::SYMBOLS
        } else {
            ModifierNames::NAMES
        };
        self.keys
            .iter()
            .map(|k| k.format(&names, mac))
            .collect::<Vec<_>>()
            .join(&tr!("shortcut-or"))
    }
}

/// The commands of the shortcuts pressed this frame (none while a text
/// field has the keyboard).
pub fn pressed(ctx: &egui::Context) -> Vec<Command> {
    if ctx.egui_wants_keyboard_input() {
        return Vec::new();
    }
    ctx.input_mut(|input| {
        SHORTCUTS
            .iter()
            .filter(|s| {
                // Every alternative is consumed, so that none falls through
                // to a later row (so no short-circuiting `any`).
                s.keys.iter().filter(|k| input.consume_shortcut(k)).count() > 0
            })
            .map(|s| s.command.clone())
            .collect()
    })
}

/// The help window: the shortcut table, then the gestures.
pub fn help_window(ctx: &egui::Context, open: &mut bool) {
    egui::Window::new(tr!("help-title"))
        .open(open)
        .collapsible(false)
        .resizable(false)
        .anchor(egui::Align2::CENTER_CENTER, [0.0, 0.0])
        .show(ctx, |ui| {
            egui::Grid::new("shortcuts")
                .num_columns(2)
                .striped(true)
                .show(ui, |ui| {
                    let keys = SHORTCUTS.iter().map(|s| (s.keys_text(), (s.does)()));
                    let gestures = GESTURES.iter().map(|(g, does)| (g(), does()));
                    for (keys, does) in keys.chain(gestures) {
                        ui.label(egui::RichText::new(keys).strong().monospace());
                        ui.label(does);
                        ui.end_row();
                    }
                });
            ui.add_space(6.0);
            ui.label(tr!("help-footer"));
        });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_two_rows_share_a_key() {
        let all: Vec<_> = SHORTCUTS.iter().flat_map(|s| s.keys.iter()).collect();
        for (i, a) in all.iter().enumerate() {
            assert!(!all[i + 1..].contains(a), "{a:?} is bound twice");
        }
    }

    #[test]
    fn a_shifted_key_comes_before_the_same_key_unshifted() {
        for (i, s) in SHORTCUTS.iter().enumerate() {
            for k in s.keys.iter().filter(|k| !k.modifiers.shift) {
                let later_shifted = SHORTCUTS[i + 1..]
                    .iter()
                    .flat_map(|t| t.keys.iter())
                    .any(|t| t.logical_key == k.logical_key && t.modifiers.shift);
                assert!(!later_shifted, "{:?} would swallow its shifted form", k);
            }
        }
    }
}
