//! `lumlab --drag-bench N` (hidden, for measuring): a scripted run that
//! drags the pointer for N frames after a warm-up, prints the frame rate the
//! window reached and the render scales chosen, and quits. What it drags
//! (`--drag-bench-target`, [`DragTarget`]): the camera's orbit over the
//! viewport, the light gizmo, or the light radius slider, since each
//! changes different parts of the frame (the light's position shows in the
//! light panel, a slider's value in its panel). A frame's time is the
//! interval between two frames' input hooks: everything a frame costs
//! (egui's layout and painting, the renderer, the copy to the window) is in
//! it. The CPU time the process spent over the measured frames (all
//! threads: the UI thread and a software adapter's rasterizer threads) is
//! given per frame beside it: unlike the frame rate it hardly depends on
//! what else the machine runs. Where the view renders on a device of its
//! own (`--drag-device`), a frame may show no new image: the images the
//! view showed are counted apart, with their own rate.

use egui::{Event, PointerButton, Pos2, Rect, vec2};
use std::time::Instant;

/// Idle frames first: the shaders compile, the first GPU times come back.
const WARM_UP_FRAMES: u32 = 30;
/// Drag frames not counted: the render scale learns the frame cost.
const SETTLE_FRAMES: u32 = 10;
/// The drag turns back after this many frames, so that it stays on its
/// target (see [`DragTarget::step_points`]).
const SWING_FRAMES: u32 = 60;

crate::named_enum! {
    /// What the bench drags; its name on the command line and in the report.
    #[derive(Default)]
    pub enum DragTarget {
        /// The camera, from the viewport's centre: only the image changes.
        #[default]
        Orbit = "orbit",
        /// The light gizmo: the image, the shadow map and the light panel's
        /// position fields change.
        Light = "light",
        /// The light radius slider: its panel (the value, the derived
        /// radiance) and the image change.
        Slider = "slider",
    }
}

impl DragTarget {
    /// Where the drag starts on the target's rectangle.
    fn press_at(self, rect: Rect) -> Pos2 {
        match self {
            Self::Orbit | Self::Light => rect.center(),
            // The rectangle is the slider's rail followed by its value: a
            // press near the rail's left end leaves it room to move right.
            Self::Slider => rect.left_center() + vec2(40.0, 0.0),
        }
    }

    /// Pointer motion per frame (points). Over a swing of [`SWING_FRAMES`]:
    /// a steady orbit; the light across a good part of the image; the
    /// slider along most of its 190-point rail (lab.rs's style).
    fn step_points(self) -> f32 {
        match self {
            Self::Orbit => 4.0,
            Self::Light | Self::Slider => 2.0,
        }
    }
}

/// What the frame before did, as the next frame's input hook reads it.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct FrameBefore {
    /// Render scale of the view's last image.
    pub scale: f64,
    /// CPU time of the UI pass, rendering included (ms).
    pub ui_ms: f64,
    /// GPU time of the renderer's passes, as last measured (ms).
    pub gpu_ms: f64,
    /// GPU time of the shadow pass among them (ms).
    pub shadow_ms: f64,
    /// Side of the shadow map the view's last image read (texels; 0: it
    /// read none, under ray-traced visibility or without shadows).
    pub map_side: u32,
    /// Images the view has shown so far.
    pub images: u64,
    /// The scene's simplified meshes are being built: the warm-up waits
    /// for them, so that every measured frame draws what a drag draws.
    pub simplifying: bool,
    /// The view's last image drew the simplified meshes.
    pub simplified: bool,
}

pub(super) struct DragBench {
    target: DragTarget,
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
    /// GPU time of the shadow pass among them (ms; 0 where the map was
    /// kept): a light drag draws it every frame.
    shadow_ms: Vec<f64>,
    /// Side of the shadow map each measured frame's image read (texels).
    map_sides: Vec<f64>,
    /// When the view showed a new image, over the measured frames.
    image_times: Vec<Instant>,
    /// Measured frames whose image drew the simplified meshes.
    simplified_frames: usize,
    /// The view's image count at the frame before.
    images: u64,
    /// CPU time (process, UI thread) when the measured frames began (s).
    cpu_start: Option<CpuTime>,
    /// CPU time spent over the measured frames (s).
    cpu_spent: Option<CpuTime>,
    /// Where the drag started (points); None before the press.
    start: Option<Pos2>,
    /// The pointer's offset from where the drag started (points).
    offset: f32,
    /// The target was not on screen when the drag was to start.
    missing: bool,
    released: bool,
    reported: bool,
}

impl DragBench {
    pub(super) fn new(frames: u32, target: DragTarget) -> Self {
        Self {
            target,
            frames: frames.max(1),
            frame: 0,
            last: None,
            intervals_s: Vec::new(),
            scales: Vec::new(),
            ui_ms: Vec::new(),
            gpu_ms: Vec::new(),
            shadow_ms: Vec::new(),
            map_sides: Vec::new(),
            image_times: Vec::new(),
            simplified_frames: 0,
            images: 0,
            cpu_start: None,
            cpu_spent: None,
            start: None,
            offset: 0.0,
            missing: false,
            released: false,
            reported: false,
        }
    }

    /// What it drags.
    pub(super) fn target(&self) -> DragTarget {
        self.target
    }

    /// Adds this frame's pointer events. `target`: the rectangle of what it
    /// drags, as last laid out (read when the drag starts; None: not on
    /// screen). `before`: what the frame before did.
    pub(super) fn inject(&mut self, raw: &mut egui::RawInput, target: Option<Rect>, before: FrameBefore) {
        let now = Instant::now();
        let new_image = before.images > self.images;
        self.images = before.images;
        if before.simplifying && self.start.is_none() {
            return;
        }
        let k = self.frame;
        self.frame += 1;
        if k < WARM_UP_FRAMES || self.released || self.missing {
            return;
        }
        let d = k - WARM_UP_FRAMES;
        let Some(start) = self
            .start
            .or_else(|| target.map(|rect| self.target.press_at(rect)))
        else {
            self.missing = true;
            return;
        };
        self.start = Some(start);
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
            self.offset += direction * self.target.step_points();
            raw.events.push(Event::PointerMoved(at(self.offset)));
            if d == SETTLE_FRAMES + 1 {
                self.cpu_start = CpuTime::now();
            }
            if d > SETTLE_FRAMES + 1
                && let Some(last) = self.last
            {
                self.intervals_s.push((now - last).as_secs_f64());
                self.scales.push(before.scale);
                self.ui_ms.push(before.ui_ms);
                self.gpu_ms.push(before.gpu_ms);
                self.shadow_ms.push(before.shadow_ms);
                self.map_sides.push(f64::from(before.map_side));
                self.simplified_frames += before.simplified as usize;
                if new_image {
                    self.image_times.push(now);
                }
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

    /// The result line, once, when done (or when there was nothing to drag).
    pub(super) fn report(&mut self, viewport: (u32, u32)) -> Option<String> {
        if !(self.done() || self.missing) || self.reported {
            return None;
        }
        self.reported = true;
        if self.missing {
            return Some(format!(
                "app drag, {}: nothing on screen to press on",
                self.target.name()
            ));
        }
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
        let images: Vec<f64> = self
            .image_times
            .windows(2)
            .map(|w| (w[1] - w[0]).as_secs_f64())
            .collect();
        Some(format!(
            "{}; {}; median UI pass (layout, panels, render submit) {:.1} ms, renderer's GPU passes {:.1} ms (shadow {:.1}, {}){cpu}; simplified meshes in {} of {n} frames",
            summary(self.target, &self.intervals_s, &self.scales, viewport),
            image_summary(&images),
            median(&self.ui_ms),
            median(&self.gpu_ms),
            median(&self.shadow_ms),
            map_side(median(&self.map_sides)),
            self.simplified_frames,
        ))
    }
}

/// "map side N texels", or "no map read" for a side of 0.
fn map_side(side: f64) -> String {
    if side > 0.0 {
        format!("map side {side} texels")
    } else {
        "no map read".into()
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

/// "app drag, TARGET: N frames, viewport W×H px: F frames/s (…), render scale …".
fn summary(target: DragTarget, intervals_s: &[f64], scales: &[f64], viewport: (u32, u32)) -> String {
    let n = intervals_s.len();
    let mean_fps = n as f64 / intervals_s.iter().sum::<f64>();
    let mut fps: Vec<f64> = intervals_s.iter().map(|t| 1.0 / t).collect();
    fps.sort_by(f64::total_cmp);
    let mut scales = scales.to_vec();
    scales.sort_by(f64::total_cmp);
    format!(
        "app drag, {}: {n} frames, viewport {}×{} px: {mean_fps:.1} frames/s \
         (per frame: median {:.1}, 10–90 % {:.1}–{:.1}, min {:.1}); \
         render scale median {:.2} (range {:.2}–{:.2})",
        target.name(),
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

/// "N images: F images/s (…)" from the intervals between new images.
fn image_summary(intervals_s: &[f64]) -> String {
    if intervals_s.is_empty() {
        return "fewer than 2 images".into();
    }
    let mut rates: Vec<f64> = intervals_s.iter().map(|t| 1.0 / t).collect();
    rates.sort_by(f64::total_cmp);
    format!(
        "{} images: {:.1} images/s (per image: median {:.1}, 10–90 % {:.1}–{:.1}, min {:.1})",
        intervals_s.len() + 1,
        intervals_s.len() as f64 / intervals_s.iter().sum::<f64>(),
        quantile(&rates, 0.5),
        quantile(&rates, 0.1),
        quantile(&rates, 0.9),
        rates[0],
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_summary_gives_the_mean_rate_over_all_frames() {
        // 3 frames of 50 ms and one of 100 ms: 4 frames in 0.25 s.
        let line = summary(
            DragTarget::Orbit,
            &[0.05, 0.05, 0.1, 0.05],
            &[0.5, 0.25, 0.5, 0.5],
            (800, 600),
        );
        assert!(line.starts_with("app drag, orbit: 4 frames"), "{line}");
        assert!(line.contains("16.0 frames/s"), "{line}");
        assert!(line.contains("median 20.0"), "{line}");
        assert!(line.contains("min 10.0"), "{line}");
        assert!(
            line.contains("render scale median 0.50 (range 0.25–0.50)"),
            "{line}"
        );
    }

    #[test]
    fn images_are_counted_apart_from_frames() {
        // 4 images, 3 intervals in 0.2 s: 15 images/s.
        let line = image_summary(&[0.05, 0.05, 0.1]);
        assert!(line.starts_with("4 images: 15.0 images/s"), "{line}");
        assert!(line.contains("median 20.0"), "{line}");
        assert!(line.contains("min 10.0"), "{line}");
        assert_eq!(image_summary(&[]), "fewer than 2 images");
    }

    #[test]
    fn cpu_time_is_read_after_the_command_name() {
        // utime 250 ticks, stime 50 ticks: 3 s; the name holds a space and a ')'.
        let line = "1234 (llvm pipe) x) S 1 2 3 4 5 6 7 8 9 10 250 50 0 0 20 0 3 0";
        assert_eq!(stat_cpu_s(line), Some(3.0));
        assert_eq!(stat_cpu_s("1234 (name) S 1 2"), None);
    }

    /// Runs a bench of `frames` to its end over a target that `target`
    /// gives for each frame; all the events it injected.
    fn run(bench: &mut DragBench, target: impl Fn(u32) -> Option<Rect>) -> Vec<Event> {
        let mut events = Vec::new();
        let mut frame = 0;
        while !bench.done() && !bench.missing {
            let mut raw = egui::RawInput::default();
            bench.inject(&mut raw, target(frame), FrameBefore::default());
            events.extend(raw.events);
            frame += 1;
        }
        let mut raw = egui::RawInput::default();
        bench.inject(&mut raw, target(frame), FrameBefore::default());
        events.extend(raw.events);
        events
    }

    fn pointer_at(event: &Event) -> Option<Pos2> {
        match event {
            Event::PointerMoved(p) | Event::PointerButton { pos: p, .. } => Some(*p),
            _ => None,
        }
    }

    #[test]
    fn the_drag_presses_moves_then_releases_and_measures_n_frames() {
        let mut bench = DragBench::new(5, DragTarget::Orbit);
        let viewport = Rect::from_min_size(Pos2::ZERO, vec2(200.0, 100.0));
        let events = run(&mut bench, |_| Some(viewport));
        let pressed = |e: &Event| matches!(e, Event::PointerButton { pressed: true, .. });
        let released = |e: &Event| matches!(e, Event::PointerButton { pressed: false, .. });
        assert_eq!(events.iter().filter(|e| pressed(e)).count(), 1);
        assert!(events.last().is_some_and(released));
        assert_eq!(bench.intervals_s.len(), 5);
        assert!(bench.report((200, 100)).is_some());
        assert!(bench.report((200, 100)).is_none(), "reported once");
    }

    #[test]
    fn each_target_is_pressed_where_it_can_be_dragged_and_the_drag_stays_on_it() {
        // The light radius slider: 190 points of rail, then its value.
        let slider = Rect::from_min_size(Pos2::new(10.0, 300.0), vec2(260.0, 18.0));
        let rail = Rect::from_min_size(slider.min, vec2(190.0, 18.0));
        let gizmo = Rect::from_center_size(Pos2::new(500.0, 400.0), vec2(28.0, 28.0));
        let viewport = Rect::from_min_size(Pos2::new(300.0, 30.0), vec2(1000.0, 800.0));
        for (target, rect, stays_in) in [
            (DragTarget::Orbit, viewport, viewport),
            (DragTarget::Light, gizmo, viewport),
            (DragTarget::Slider, slider, rail),
        ] {
            let mut bench = DragBench::new(3 * SWING_FRAMES, target);
            let events = run(&mut bench, |_| Some(rect));
            let points: Vec<Pos2> = events.iter().filter_map(pointer_at).collect();
            assert!(rect.contains(points[0]), "{target:?} pressed at {:?}", points[0]);
            assert!(
                points.iter().all(|p| stays_in.contains(*p)),
                "{target:?} leaves {stays_in:?}"
            );
            assert!(
                points.iter().any(|p| p.x > points[0].x + 50.0),
                "{target:?} moves"
            );
        }
    }

    #[test]
    fn the_target_is_read_once_when_the_drag_starts() {
        // The gizmo follows the pointer: the drag keeps its own course.
        let mut bench = DragBench::new(20, DragTarget::Light);
        let moving = |frame: u32| {
            Some(Rect::from_center_size(
                Pos2::new(100.0 + 10.0 * frame as f32, 50.0),
                vec2(20.0, 20.0),
            ))
        };
        let events = run(&mut bench, moving);
        let xs: Vec<f32> = events.iter().filter_map(pointer_at).map(|p| p.x).collect();
        let start = moving(WARM_UP_FRAMES).map(|r| r.center().x);
        assert_eq!(Some(xs[0]), start);
        let steps: Vec<f32> = xs.windows(2).map(|w| w[1] - w[0]).collect();
        assert!(steps.iter().all(|s| s.abs() <= 2.0), "{steps:?}");
    }

    #[test]
    fn a_target_off_screen_ends_the_bench_with_a_message() {
        let mut bench = DragBench::new(5, DragTarget::Slider);
        let events = run(&mut bench, |_| None);
        assert!(events.is_empty(), "nothing pressed");
        let line = bench.report((200, 100));
        assert_eq!(
            line.as_deref(),
            Some("app drag, slider: nothing on screen to press on")
        );
    }

    #[test]
    fn targets_are_named_on_the_command_line() {
        for &target in DragTarget::ALL {
            assert_eq!(target.name().parse(), Ok(target));
        }
        let error = "knob".parse::<DragTarget>().unwrap_err();
        assert_eq!(error, "unknown name 'knob' (allowed: orbit|light|slider)");
    }
}
