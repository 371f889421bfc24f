//! `lumlab --drag-bench N` (hidden, for measuring): a scripted run that
//! orbits the camera with a pointer drag over the viewport for N frames
//! after a warm-up, prints the frame rate the window reached and the render
//! scales chosen, and quits. A frame's time is the interval between two
//! frames' input hooks: everything a frame costs (egui's layout and
//! painting, the renderer, the copy to the window) is in it. The CPU time
//! the process spent over the measured frames (all threads: the UI thread
//! and a software adapter's rasterizer threads) is given per frame beside
//! it: unlike the frame rate it hardly depends on what else the machine runs.

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
    /// CPU time (process, UI thread) when the measured frames began (s).
    cpu_start: Option<CpuTime>,
    /// CPU time spent over the measured frames (s).
    cpu_spent: Option<CpuTime>,
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
            cpu_start: None,
            cpu_spent: None,
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
            if d == SETTLE_FRAMES + 1 {
                self.cpu_start = CpuTime::now();
            }
            if d > SETTLE_FRAMES + 1
                && let Some(last) = self.last
            {
                self.intervals_s.push((now - last).as_secs_f64());
                self.scales.push(scale);
                self.ui_ms.push(ui_ms);
                self.gpu_ms.push(gpu_ms);
                if self.done() {
                    self.cpu_spent = self.cpu_start.zip(CpuTime::now()).map(|(a, b)| b.minus(a));
                }
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
        let n = self.intervals_s.len() as f64;
        let cpu = self.cpu_spent.map_or(String::new(), |c| {
            format!(
                "; CPU per frame {:.1} ms (all threads), UI thread {:.1} ms",
                c.process_s / n * 1e3,
                c.thread_s / n * 1e3
            )
        });
        Some(format!(
            "{}; median UI pass (layout, panels, render submit) {:.1} ms, renderer's GPU passes {:.1} ms{cpu}",
            summary(&self.intervals_s, &self.scales, viewport),
            median(&self.ui_ms),
            median(&self.gpu_ms),
        ))
    }
}

/// CPU time used so far (s): by the whole process and by the calling thread.
#[derive(Clone, Copy, Debug, PartialEq)]
struct CpuTime {
    process_s: f64,
    thread_s: f64,
}

impl CpuTime {
    /// From Linux's /proc (None elsewhere).
    fn now() -> Option<Self> {
        let read = |path: &str| std::fs::read_to_string(path).ok().and_then(|s| stat_cpu_s(&s));
        Some(Self {
            process_s: read("/proc/self/stat")?,
            thread_s: read("/proc/thread-self/stat")?,
        })
    }

    fn minus(self, earlier: Self) -> Self {
        Self {
            process_s: self.process_s - earlier.process_s,
            thread_s: self.thread_s - earlier.thread_s,
        }
    }
}

/// User + system CPU time (s) from a /proc `stat` line: fields 14 and 15,
/// in clock ticks of 1/100 s (Linux's USER_HZ). The command name (field 2,
/// in parentheses) may hold spaces: fields are counted after its `)`.
fn stat_cpu_s(stat: &str) -> Option<f64> {
    const TICKS_PER_S: f64 = 100.0;
    let after_name = &stat[stat.rfind(')')? + 1..];
    let mut fields = after_name.split_whitespace().skip(11);
    let user: u64 = fields.next()?.parse().ok()?;
    let system: u64 = fields.next()?.parse().ok()?;
    Some((user + system) as f64 / TICKS_PER_S)
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
    fn cpu_time_is_read_after_the_command_name() {
        // utime 250 ticks, stime 50 ticks: 3 s; the name holds a space and a ')'.
        let line = "1234 (llvm pipe) x) S 1 2 3 4 5 6 7 8 9 10 250 50 0 0 20 0 3 0";
        assert_eq!(stat_cpu_s(line), Some(3.0));
        assert_eq!(stat_cpu_s("1234 (name) S 1 2"), None);
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
