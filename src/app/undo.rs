//! Undo and redo of settings changes. Sliders and drags change the settings
//! continuously; a change is committed to the undo stack once the pointer is
//! released and the settings have been quiet for a moment, so one drag is
//! one undo step.

use crate::settings::Settings;
use std::collections::VecDeque;

pub struct UndoStack {
    /// The settings as of the last commit.
    committed: Settings,
    /// The settings seen on the last frame, to tell when they last changed.
    last_seen: Settings,
    changed_at: f64,
    undo: VecDeque<Settings>,
    redo: Vec<Settings>,
}

impl UndoStack {
    /// Steps kept.
    pub const DEPTH: usize = 100;
    /// Seconds without change before a change is committed.
    pub const QUIET_S: f64 = 0.4;

    pub fn new(settings: &Settings) -> Self {
        Self {
            committed: settings.clone(),
            last_seen: settings.clone(),
            changed_at: 0.0,
            undo: VecDeque::new(),
            redo: Vec::new(),
        }
    }

    /// Called once per frame with the current settings; `busy` while a
    /// pointer button is held or a text field has focus. Returns true while
    /// a change waits to be committed (the caller repaints a little later).
    pub fn observe(&mut self, current: &Settings, busy: bool, now_s: f64) -> bool {
        if *current != self.last_seen {
            self.last_seen = current.clone();
            self.changed_at = now_s;
        }
        if *current == self.committed {
            return false;
        }
        if busy || now_s - self.changed_at < Self::QUIET_S {
            return true;
        }
        let previous = std::mem::replace(&mut self.committed, current.clone());
        self.push_undo(previous);
        self.redo.clear();
        false
    }

    /// Commits `current` at once, as an undo step of its own: called before
    /// and after a discrete command (a preset, a loaded file), so that the
    /// command is exactly one step and a pending slider change another.
    pub fn checkpoint(&mut self, current: &Settings) {
        if *current != self.committed {
            let previous = std::mem::replace(&mut self.committed, current.clone());
            self.push_undo(previous);
            self.redo.clear();
        }
        self.last_seen = current.clone();
    }

    fn push_undo(&mut self, settings: Settings) {
        self.undo.push_back(settings);
        if self.undo.len() > Self::DEPTH {
            self.undo.pop_front();
        }
    }

    /// Goes back one step: first to the last commit if there are
    /// uncommitted changes, then through the stack.
    pub fn undo(&mut self, current: &mut Settings) -> bool {
        if *current != self.committed {
            self.redo.push(std::mem::replace(current, self.committed.clone()));
        } else if let Some(previous) = self.undo.pop_back() {
            self.redo.push(std::mem::replace(current, previous.clone()));
            self.committed = previous;
        } else {
            return false;
        }
        self.last_seen = current.clone();
        true
    }

    pub fn redo(&mut self, current: &mut Settings) -> bool {
        let Some(next) = self.redo.pop() else {
            return false;
        };
        let previous = std::mem::replace(&mut self.committed, next.clone());
        self.push_undo(previous);
        *current = next;
        self.last_seen = current.clone();
        true
    }

    pub fn can_undo(&self, current: &Settings) -> bool {
        *current != self.committed || !self.undo.is_empty()
    }

    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn with_power(p: f32) -> Settings {
        let mut s = Settings::default();
        s.light.power_w = p;
        s
    }

    #[test]
    fn a_drag_is_one_step() {
        let mut stack = UndoStack::new(&with_power(1.0));
        let mut t = 0.0;
        for p in [2.0, 3.0, 4.0] {
            t += 0.016;
            assert!(stack.observe(&with_power(p), true, t));
        }
        // Released, then quiet: committed once.
        assert!(stack.observe(&with_power(4.0), false, t + 0.1));
        assert!(!stack.observe(&with_power(4.0), false, t + 1.0));
        let mut current = with_power(4.0);
        assert!(stack.undo(&mut current));
        assert_eq!(current.light.power_w, 1.0);
        assert!(!stack.undo(&mut current));
        assert!(stack.redo(&mut current));
        assert_eq!(current.light.power_w, 4.0);
        assert!(!stack.can_redo());
    }

    #[test]
    fn undo_first_drops_uncommitted_changes() {
        let mut stack = UndoStack::new(&with_power(1.0));
        stack.observe(&with_power(2.0), false, 0.0);
        stack.observe(&with_power(2.0), false, 1.0);
        let mut current = with_power(3.0);
        stack.observe(&current, true, 1.1);
        assert!(stack.undo(&mut current));
        assert_eq!(current.light.power_w, 2.0);
        assert!(stack.undo(&mut current));
        assert_eq!(current.light.power_w, 1.0);
    }

    #[test]
    fn a_checkpoint_is_one_step_apart_from_a_pending_drag() {
        let mut stack = UndoStack::new(&with_power(1.0));
        // A drag still held...
        assert!(stack.observe(&with_power(2.0), true, 0.0));
        // ...then a preset: the drag and the preset are two steps.
        stack.checkpoint(&with_power(2.0));
        let mut current = with_power(9.0);
        stack.checkpoint(&current);
        assert!(!stack.observe(&current, false, 5.0));
        assert!(stack.undo(&mut current));
        assert_eq!(current.light.power_w, 2.0);
        assert!(stack.undo(&mut current));
        assert_eq!(current.light.power_w, 1.0);
        assert!(!stack.undo(&mut current));
    }

    #[test]
    fn a_new_change_clears_redo() {
        let mut stack = UndoStack::new(&with_power(1.0));
        stack.observe(&with_power(2.0), false, 0.0);
        stack.observe(&with_power(2.0), false, 1.0);
        let mut current = with_power(2.0);
        stack.undo(&mut current);
        assert!(stack.can_redo());
        stack.observe(&with_power(5.0), false, 2.0);
        stack.observe(&with_power(5.0), false, 3.0);
        assert!(!stack.can_redo());
    }
}
