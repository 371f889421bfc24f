//! `lumlab --drag-bench N` (hidden, for measuring): a scripted run that
//! orbits the camera with a pointer drag over the viewport for N frames
//! after a warm-up, prints the frame rate the window reached and the render
//! scales chosen, and quits. A frame's time is the interval between two
//! frames' input hooks: everything a frame costs (egui's layout and
//! painting, the renderer, the copy to the window) is in it.

use egui::{Event, PointerButton, Pos2, Rect};
use std::time::Instant;

/// Idle frames first: the shaders compile, the first GPU times come back.
const WARM_UP_FRAMES: u32 = 30;
/// Drag frames not counted: the render scale learns the frame cost.
const SETTLE_FRAMES: u32 = 10;
/// Pointer motion per frame (points): a steady orbit.
const STEP_POINTS: f32 = 4.0;
/// The drag turns back after this many frames, so it stays in the viewport.
const SWING_FRAMES: u32 = 60;

pub(super) struct DragBench {
    /// Frames to measure.
    frames: u32,
    /// Frames seen so far.
    frame: u32,
    last: Option<Instant>,
    intervals_s: Vec<f64>,
    scales: Vec<f64>,
    /// CPU time of each measured frame's UI pass, rendering included (ms).
    ui_ms: Vec<f64>,
    /// GPU time of the renderer's passes, as last measured (ms).
    gpu_ms: Vec<f64>,
    /// The pointer's offset from where the drag started (points).
    offset: f32,
    released: bool,
    reported: bool,
}

impl DragBench {
    pub(super) fn new(frames: u32) -> Self {
        Self {
            frames: frames.max(1),
            frame: 0,
            last: None,
            intervals_s: Vec::new(),
            scales: Vec::new(),
            ui_ms: Vec::new(),
            gpu_ms: Vec::new(),
            offset: 0.0,
            released: false,
            reported: false,
        }
    }

    /// Adds this frame's pointer events. `before`: the render scale, the UI
    /// pass's CPU time and the renderer's last GPU time (ms) of the frame before.
    pub(super) fn inject(&mut self, raw: &mut egui::RawInput, viewport: Rect, before: [f64; 3]) {
        let [scale, ui_ms, gpu_ms] = before;
        let now = Instant::now();
        let k = self.frame;
        self.frame += 1;
        if k < WARM_UP_FRAMES || self.released {
            return;
        }
        let d = k - WARM_UP_FRAMES;
        let start = viewport.center();
        let at = |offset: f32| Pos2::new(start.x + offset, start.y);
        let button = |pos: Pos2, pressed: bool| Event::PointerButton {
            pos,
            button: PointerButton::Primary,
            pressed,
            modifiers: Default::default(),
        };
        if self.done() {
            raw.events.push(button(at(self.offset), false));
            self.released = true;
        } else if d == 0 {
            raw.events.push(Event::PointerMoved(start));
            raw.events.push(button(start, true));
        } else {
            let direction = if (d / SWING_FRAMES).is_multiple_of(2) {
                1.0
            } else {
                -1.0
            };
            self.offset += direction * STEP_POINTS;
            raw.events.push(Event::PointerMoved(at(self.offset)));
            if d > SETTLE_FRAMES + 1
                && let Some(last) = self.last
            {
                self.intervals_s.push((now - last).as_secs_f64());
                self.scales.push(scale);
                self.ui_ms.push(ui_ms);
                self.gpu_ms.push(gpu_ms);
            }
        }
        self.last = Some(now);
    }

    /// Every frame asked for is measured.
    pub(super) fn done(&self) -> bool {
        self.intervals_s.len() as u32 >= self.frames
    }

    /// The result line, once, when done.
    pub(super) fn report(&mut self, viewport: (u32, u32)) -> Option<String> {
        if !self.done() || self.reported {
            return None;
        }
        self.reported = true;
        let median = |values: &[f64]| {
            let mut sorted = values.to_vec();
            sorted.sort_by(f64::total_cmp);
            quantile(&sorted, 0.5)
        };
        Some(format!(
            "{}; median UI pass (layout, panels, render submit) {:.1} ms, renderer's GPU passes {:.1} ms",
            summary(&self.intervals_s, &self.scales, viewport),
            median(&self.ui_ms),
            median(&self.gpu_ms),
        ))
    }
}

/// `q`-quantile of sorted values (nearest rank).
fn quantile(sorted: &[f64], q: f64) -> f64 {
    let i = ((sorted.len() as f64 - 1.0) * q).round() as usize;
    sorted[i.min(sorted.len() - 1)]
}

/// "app drag: N frames, viewport W×H px: F frames/s (…), render scale …".
fn summary(intervals_s: &[f64], scales: &[f64], viewport: (u32, u32)) -> String {
    let n = intervals_s.len();
    let mean_fps = n as f64 / intervals_s.iter().sum::<f64>();
    let mut fps: Vec<f64> = intervals_s.iter().map(|t| 1.0 / t).collect();
    fps.sort_by(f64::total_cmp);
    let mut scales = scales.to_vec();
    scales.sort_by(f64::total_cmp);
    format!(
        "app drag: {n} frames, viewport {}×{} px: {mean_fps:.1} frames/s \
         (per frame: median {:.1}, 10–90 % {:.1}–{:.1}, min {:.1}); \
         render scale median {:.2} (range {:.2}–{:.2})",
        viewport.0,
        viewport.1,
        quantile(&fps, 0.5),
        quantile(&fps, 0.1),
        quantile(&fps, 0.9),
        fps[0],
        quantile(&scales, 0.5),
        scales[0],
        scales[scales.len() - 1],
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use egui::vec2;

    #[test]
    fn the_summary_gives_the_mean_rate_over_all_frames() {
        // 3 frames of 50 ms and one of 100 ms: 4 frames in 0.25 s.
        let line = summary(&[0.05, 0.05, 0.1, 0.05], &[0.5, 0.25, 0.5, 0.5], (800, 600));
        assert!(line.contains("16.0 frames/s"), "{line}");
        assert!(line.contains("median 20.0"), "{line}");
        assert!(line.contains("min 10.0"), "{line}");
        assert!(
            line.contains("render scale median 0.50 (range 0.25–0.50)"),
            "{line}"
        );
    }

    #[test]
    fn the_drag_presses_moves_then_releases_and_measures_n_frames() {
        let mut bench = DragBench::new(5);
        let viewport = Rect::from_min_size(Pos2::ZERO, vec2(200.0, 100.0));
        let mut events = Vec::new();
        while !bench.done() {
            let mut raw = egui::RawInput::default();
            bench.inject(&mut raw, viewport, [0.5, 1.0, 1.0]);
            events.extend(raw.events);
        }
        let mut raw = egui::RawInput::default();
        bench.inject(&mut raw, viewport, [0.5, 1.0, 1.0]);
        events.extend(raw.events);
        let pressed = |e: &Event| matches!(e, Event::PointerButton { pressed: true, .. });
        let released = |e: &Event| matches!(e, Event::PointerButton { pressed: false, .. });
        assert_eq!(events.iter().filter(|e| pressed(e)).count(), 1);
        assert!(events.last().is_some_and(released));
        assert_eq!(bench.intervals_s.len(), 5);
        assert!(bench.report((200, 100)).is_some());
        assert!(bench.report((200, 100)).is_none(), "reported once");
    }
}
