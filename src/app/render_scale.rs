//! The viewport's render scale: while the user drags (the camera, the light,
//! the divider, a slider) the image is rendered at a reduced scale chosen
//! from the measured frame cost, so that frames stay fluid on a software
//! adapter; as soon as the drag ends the next frame is full resolution
//! (never a blurry still image).

use crate::gpu::timing::PassTimes;
use crate::settings::ShadowSettings;
use std::time::Instant;

/// The frame rate aimed at while dragging (frames/s).
pub const TARGET_FPS: f64 = 30.0;
/// Share of a frame's budget left to the renderer's passes; the rest is
/// egui's own drawing and the copy to the window.
const RENDER_SHARE: f64 = 0.6;
/// The smallest scale (per side): 1/16 of the pixels.
pub const MIN_SCALE: f64 = 0.25;
/// The scale used while dragging on adapters without GPU timestamps (no cost
/// measured).
const UNTIMED_SCALE: f64 = 0.5;
/// Frame intervals longer than this (s) are pauses, not frame times.
const PAUSE_S: f64 = 0.5;
/// The scales a drag may use: steps of √2 per side (half the pixels each),
/// so that a drag's images keep one size while the cost hovers near a
/// step, instead of a new size (new targets, new allocations, on a software
/// adapter new shader variants) every frame.
pub const STEPS: [f64; 5] = [
    MIN_SCALE,
    0.25 * std::f64::consts::SQRT_2,
    0.5,
    0.5 * std::f64::consts::SQRT_2,
    1.0,
];
/// A drag moves up a step only when the cost model leaves this much room
/// above it: frame costs that wobble by less never flip the size.
const STEP_UP_MARGIN: f64 = 1.1;

#[derive(Debug)]
pub struct RenderScale {
    /// The scale the next interaction frame uses, learned from the cost.
    interactive: f64,
    /// A drag is under way this frame.
    pub interacting: bool,
    /// The scale of the image shown (1 when idle).
    pub shown: f64,
    /// Frames per second while dragging (smoothed), once measured.
    pub drag_fps: Option<f64>,
    last_render: Option<Instant>,
}

impl Default for RenderScale {
    fn default() -> Self {
        Self {
            interactive: UNTIMED_SCALE,
            interacting: false,
            shown: 1.0,
            drag_fps: None,
            last_render: None,
        }
    }
}

impl RenderScale {
    /// The renderer's share of a frame at the target rate (ms).
    pub fn budget_ms() -> f64 {
        RENDER_SHARE * 1e3 / TARGET_FPS
    }

    /// The scale of this frame's image: reduced while `interacting`, else 1.
    pub fn begin_frame(&mut self, interacting: bool) -> f64 {
        self.interacting = interacting;
        if interacting { self.interactive } else { 1.0 }
    }

    /// A frame was rendered at `scale` (its pixel size is what counts).
    pub fn rendered(&mut self, scale: f64) {
        let now = Instant::now();
        if self.interacting
            && let Some(last) = self.last_render
        {
            let interval_s = (now - last).as_secs_f64();
            if interval_s > 0.0 && interval_s < PAUSE_S {
                let fps = 1.0 / interval_s;
                // Exponential smoothing over about four frames.
                self.drag_fps = Some(self.drag_fps.map_or(fps, |f| 0.75 * f + 0.25 * fps));
            }
        }
        self.last_render = Some(now);
        self.shown = scale;
    }

    /// GPU times of a frame rendered at `scale` came back: the next
    /// interaction scale s follows from the cost model
    /// t(s) = t_pixels · (s / scale)², every pass's cost proportional to its
    /// pixel count (the camera and display passes at the image's scale, the
    /// shadow map and its blur at [`shadow_map_side`]'s, which follows it):
    /// s = scale · √(budget / t_pixels), rounded down to one of [`STEPS`]; a
    /// step up needs [`STEP_UP_MARGIN`] of room.
    pub fn observe(&mut self, scale: f64, times: &PassTimes) {
        let pixels_ms = times.total_ms();
        if !(pixels_ms > 0.0 && scale > 0.0) {
            return;
        }
        let ideal = scale * (Self::budget_ms() / pixels_ms).sqrt();
        // Down to the largest step that fits at once; up only as far as the
        // largest step with room to spare.
        let fitting = largest_step(ideal);
        self.interactive = if fitting < self.interactive {
            fitting
        } else {
            largest_step(ideal / STEP_UP_MARGIN).max(self.interactive)
        };
    }
}

/// The shadow map's side (texels) for an image rendered at `scale`: the
/// chosen `resolution` times the scale, so that a drag keeps the texels per
/// pixel of the still image (a moved light redraws the map every frame, at
/// 2048² six faces the largest pass of a light drag); a multiple of 64, at
/// least the settings' minimum, and the chosen resolution itself at scale 1.
pub fn shadow_map_side(resolution: u32, scale: f64) -> u32 {
    if scale >= 1.0 {
        return resolution;
    }
    let side = (resolution as f64 * scale / 64.0).round() as u32 * 64;
    side.clamp(ShadowSettings::MIN_RESOLUTION.min(resolution), resolution)
}

/// The largest of [`STEPS`] at most `limit` (a rounding's worth of slack),
/// or the smallest.
fn largest_step(limit: f64) -> f64 {
    STEPS
        .into_iter()
        .rev()
        .find(|&s| s <= limit * (1.0 + 1e-9))
        .unwrap_or(MIN_SCALE)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn times(shadow: f64, shade: f64) -> PassTimes {
        PassTimes {
            shadow_ms: Some(shadow),
            shade_ms: Some(shade),
            ..Default::default()
        }
    }

    #[test]
    fn the_scale_fits_the_pixel_cost_into_the_budget() {
        let mut scale = RenderScale::default();
        // A full frame 4× over the budget: half the side, a quarter of the pixels.
        scale.observe(1.0, &times(0.0, 4.0 * RenderScale::budget_ms()));
        assert!((scale.begin_frame(true) - 0.5).abs() < 1e-12);
        // Measured at that scale on budget: it stays.
        scale.observe(0.5, &times(0.0, RenderScale::budget_ms()));
        assert!((scale.begin_frame(true) - 0.5).abs() < 1e-12);
        // The shadow map's cost scales with the image too (its side follows
        // the scale): half of four budgets in each, half the side.
        scale.observe(
            1.0,
            &times(2.0 * RenderScale::budget_ms(), 2.0 * RenderScale::budget_ms()),
        );
        assert!((scale.begin_frame(true) - 0.5).abs() < 1e-12);
        assert_eq!(scale.begin_frame(false), 1.0, "idle frames are full resolution");
    }

    #[test]
    fn the_scale_moves_by_steps_and_does_not_flip_on_a_wobble() {
        let mut scale = RenderScale::default();
        let budget = RenderScale::budget_ms();
        // Room for 0.6 per side: the step below, 0.5.
        scale.observe(1.0, &times(0.0, budget / 0.36));
        assert_eq!(scale.begin_frame(true), 0.5);
        // Costs that wobble around a step's boundary keep one size.
        // Measured at `shown`, a cost whose ideal scale is `ideal`.
        let at = |shown: f64, ideal: f64| times(0.0, budget * (shown / ideal).powi(2));
        for ideal in [0.72, 0.70, 0.73, 0.69, 0.75] {
            scale.observe(0.5, &at(0.5, ideal));
            assert_eq!(scale.begin_frame(true), 0.5, "ideal {ideal}");
        }
        // Clear room above the step: up one.
        scale.observe(0.5, &at(0.5, 0.8));
        assert_eq!(scale.begin_frame(true), STEPS[3]);
        // Down at once when over the budget.
        scale.observe(STEPS[3], &at(STEPS[3], 0.6));
        assert_eq!(scale.begin_frame(true), 0.5);
        assert!(STEPS.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn the_shadow_map_shrinks_with_the_image_only_while_it_is_scaled() {
        assert_eq!(shadow_map_side(2048, 1.0), 2048);
        assert_eq!(shadow_map_side(2048, 0.5), 1024);
        assert_eq!(shadow_map_side(2048, MIN_SCALE), 512);
        // √2 steps: a multiple of 64 near the exact side (1448.2).
        assert_eq!(shadow_map_side(2048, STEPS[3]), 1472);
        assert_eq!(shadow_map_side(512, MIN_SCALE), ShadowSettings::MIN_RESOLUTION);
        // Never above what was chosen, even below the minimum.
        assert_eq!(shadow_map_side(100, 0.5), 100);
    }

    #[test]
    fn the_scale_keeps_to_its_floor_and_ceiling() {
        let mut scale = RenderScale::default();
        scale.observe(1.0, &times(0.0, 1e6));
        assert_eq!(scale.begin_frame(true), MIN_SCALE);
        scale.observe(1.0, &times(0.0, 1e-3));
        assert_eq!(scale.begin_frame(true), 1.0);
        scale.observe(1.0, &times(1e6, 1.0));
        assert_eq!(scale.begin_frame(true), MIN_SCALE);
        // Nothing measured: unchanged.
        scale.observe(1.0, &PassTimes::default());
        assert_eq!(scale.begin_frame(true), MIN_SCALE);
    }
}
