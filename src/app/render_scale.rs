//! The viewport's render scale: while the user drags (the camera, the light,
//! the divider, a slider) the image is rendered at a reduced scale chosen
//! from the measured frame cost, so that frames stay fluid on a software
//! adapter; as soon as the drag ends the next frame is full resolution
//! (never a blurry still image). The shadow map's side follows the image's
//! scale, and where the image is already at its smallest and the map is a
//! large part of the frame's cost (a cube of six faces around a light
//! among the geometry), the map alone shrinks further.

use crate::gpu::timing::PassTimes;
use crate::settings::ShadowSettings;
use std::time::Instant;

/// The frame rate aimed at while dragging (frames/s).
pub const TARGET_FPS: f64 = 30.0;
/// Share of a frame's budget left to the renderer's passes; the rest is
/// egui's own drawing and the copy to the window.
const RENDER_SHARE: f64 = 0.6;
/// The smallest scale (per side): 1/32 of the pixels.
pub const MIN_SCALE: f64 = 0.125 * std::f64::consts::SQRT_2;
/// The scale used while dragging on adapters without GPU timestamps (no cost
/// measured).
const UNTIMED_SCALE: f64 = 0.5;
/// Frame intervals longer than this (s) are pauses, not frame times.
const PAUSE_S: f64 = 0.5;
/// The scales a drag may use: steps of √2 per side (half the pixels each),
/// so that a drag's images keep one size while the cost hovers near a
/// step, instead of a new size (new targets, new allocations, on a software
/// adapter new shader variants) every frame.
pub const STEPS: [f64; 6] = [
    MIN_SCALE,
    0.25,
    0.25 * std::f64::consts::SQRT_2,
    0.5,
    0.5 * std::f64::consts::SQRT_2,
    1.0,
];
/// The scales below [`MIN_SCALE`] the shadow map's side may take alone, in
/// the same √2 steps, then [`MIN_SCALE`] itself: down to 1/128 of the
/// chosen resolution's texels (never below
/// [`ShadowSettings::MIN_RESOLUTION`], see [`shadow_map_side`]).
pub const SHADOW_STEPS: [f64; 3] = [MIN_SCALE / 2.0, MIN_SCALE / std::f64::consts::SQRT_2, MIN_SCALE];
/// The least budget a map shrinking alone aims at, as a share of the
/// image's own cost: below it coarser texels would buy little frame time
/// (on lavapipe a map with few texels to fill costs its casters' setup,
/// whatever its side).
const SHADOW_FLOOR_SHARE: f64 = 0.5;
/// A drag moves up a step only when the cost model leaves this much room
/// above it: frame costs that wobble by less never flip the size.
const STEP_UP_MARGIN: f64 = 1.1;

/// A frame's scales, as fractions of the full size's side: the image's,
/// and the shadow map's (at most the image's; see [`shadow_map_side`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameScale {
    pub image: f64,
    pub shadow: f64,
}

impl FrameScale {
    pub const FULL: Self = Self {
        image: 1.0,
        shadow: 1.0,
    };
}

#[derive(Debug)]
pub struct RenderScale {
    /// The scales the next interaction frame uses, learned from the cost.
    interactive: FrameScale,
    /// A drag is under way this frame.
    pub interacting: bool,
    /// The scales of the image shown (1 when idle).
    pub shown: FrameScale,
    /// Frames per second while dragging (smoothed), once measured.
    pub drag_fps: Option<f64>,
    last_render: Option<Instant>,
}

impl Default for RenderScale {
    fn default() -> Self {
        Self {
            interactive: FrameScale {
                image: UNTIMED_SCALE,
                shadow: UNTIMED_SCALE,
            },
            interacting: false,
            shown: FrameScale::FULL,
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

    /// The scales of this frame: reduced while `interacting`, else 1.
    pub fn begin_frame(&mut self, interacting: bool) -> FrameScale {
        self.interacting = interacting;
        if interacting {
            self.interactive
        } else {
            FrameScale::FULL
        }
    }

    /// A frame was rendered at `scale`.
    pub fn rendered(&mut self, scale: FrameScale) {
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
    /// interaction scales follow from a cost model. The image's scale s
    /// takes every pass's cost as proportional to its pixel count, the map
    /// following the image (t(s) = t_image · (s / scale.image)² +
    /// t_map · (s / scale.shadow)²): s = √(budget / t(1)), rounded down to
    /// one of [`STEPS`]; a step up needs [`STEP_UP_MARGIN`] of room. At the
    /// smallest image scale the map's side goes down alone, over
    /// [`SHADOW_STEPS`], until the map fits what the image leaves of the
    /// budget, but never below half the image's own cost
    /// ([`SHADOW_FLOOR_SHARE`]). There its cost is taken as proportional
    /// to its side: between its casters' setup (the same at any side) and
    /// its fill (∝ side²), so that a map that did not get cheaper by
    /// shrinking grows back.
    pub fn observe(&mut self, scale: FrameScale, times: &PassTimes) {
        let total_ms = times.total_ms();
        if !(total_ms > 0.0 && scale.image > 0.0 && scale.shadow > 0.0) {
            return;
        }
        let map_ms = times.shadow_ms.unwrap_or(0.0) + times.blur_ms.unwrap_or(0.0);
        let image_ms = total_ms - map_ms;
        let budget = Self::budget_ms();
        let at_full = image_ms / (scale.image * scale.image) + map_ms / (scale.shadow * scale.shadow);
        let image = stepped(self.interactive.image, (budget / at_full).sqrt(), &STEPS);
        let shadow = if image > MIN_SCALE || map_ms <= 0.0 {
            image
        } else {
            let image_at_min = image_ms * (MIN_SCALE / scale.image).powi(2);
            let map_budget = (budget - image_at_min).max(SHADOW_FLOOR_SHARE * image_at_min);
            let current = self.interactive.shadow.min(MIN_SCALE);
            stepped(current, scale.shadow * map_budget / map_ms, &SHADOW_STEPS)
        };
        self.interactive = FrameScale { image, shadow };
    }
}

/// The shadow map's side (texels) at the shadow scale `scale`
/// ([`FrameScale::shadow`]): the chosen `resolution` times the scale. It is
/// the image's scale, so that a drag keeps the texels per pixel of the
/// still image (a moved light redraws the map every frame, at 2048² six
/// faces the largest pass of a light drag), or less where the image can
/// shrink no further ([`RenderScale::observe`]); a multiple of 64, at least
/// the settings' minimum, and the chosen resolution itself at scale 1.
pub fn shadow_map_side(resolution: u32, scale: f64) -> u32 {
    if scale >= 1.0 {
        return resolution;
    }
    let side = (resolution as f64 * scale / 64.0).round() as u32 * 64;
    side.clamp(ShadowSettings::MIN_RESOLUTION.min(resolution), resolution)
}

/// The next of `steps` (ascending) for a cost whose ideal scale is
/// `ideal`, from `current`: down to the largest step that fits at once; up
/// only as far as the largest step with [`STEP_UP_MARGIN`] of room.
fn stepped(current: f64, ideal: f64, steps: &[f64]) -> f64 {
    let fitting = largest_step(ideal, steps);
    if fitting < current {
        fitting
    } else {
        largest_step(ideal / STEP_UP_MARGIN, steps).max(current)
    }
}

/// The largest of `steps` at most `limit` (a rounding's worth of slack),
/// or the smallest.
fn largest_step(limit: f64, steps: &[f64]) -> f64 {
    steps
        .iter()
        .rev()
        .copied()
        .find(|&s| s <= limit * (1.0 + 1e-9))
        .unwrap_or(steps[0])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A frame whose map follows its image.
    fn even(scale: f64) -> FrameScale {
        FrameScale {
            image: scale,
            shadow: scale,
        }
    }

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
        scale.observe(even(1.0), &times(0.0, 4.0 * RenderScale::budget_ms()));
        assert!((scale.begin_frame(true).image - 0.5).abs() < 1e-12);
        // Measured at that scale on budget: it stays.
        scale.observe(even(0.5), &times(0.0, RenderScale::budget_ms()));
        assert!((scale.begin_frame(true).image - 0.5).abs() < 1e-12);
        // The shadow map's cost scales with the image too (its side follows
        // the scale): half of four budgets in each, half the side.
        scale.observe(
            even(1.0),
            &times(2.0 * RenderScale::budget_ms(), 2.0 * RenderScale::budget_ms()),
        );
        assert!((scale.begin_frame(true).image - 0.5).abs() < 1e-12);
        assert_eq!(
            scale.begin_frame(false),
            FrameScale::FULL,
            "idle frames are full resolution"
        );
    }

    #[test]
    fn the_scale_moves_by_steps_and_does_not_flip_on_a_wobble() {
        let mut scale = RenderScale::default();
        let budget = RenderScale::budget_ms();
        // Room for 0.6 per side: the step below, 0.5.
        scale.observe(even(1.0), &times(0.0, budget / 0.36));
        assert_eq!(scale.begin_frame(true).image, 0.5);
        // Costs that wobble around a step's boundary keep one size.
        // Measured at `shown`, a cost whose ideal scale is `ideal`.
        let at = |shown: f64, ideal: f64| times(0.0, budget * (shown / ideal).powi(2));
        for ideal in [0.72, 0.70, 0.73, 0.69, 0.75] {
            scale.observe(even(0.5), &at(0.5, ideal));
            assert_eq!(scale.begin_frame(true).image, 0.5, "ideal {ideal}");
        }
        // Clear room above the step: up one.
        scale.observe(even(0.5), &at(0.5, 0.8));
        assert_eq!(scale.begin_frame(true).image, STEPS[4]);
        // Down at once when over the budget.
        scale.observe(even(STEPS[4]), &at(STEPS[4], 0.6));
        assert_eq!(scale.begin_frame(true).image, 0.5);
        assert!(STEPS.windows(2).all(|w| w[0] < w[1]));
        assert!(SHADOW_STEPS.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(SHADOW_STEPS.last(), Some(&MIN_SCALE));
    }

    #[test]
    fn the_shadow_map_shrinks_with_the_image_only_while_it_is_scaled() {
        assert_eq!(shadow_map_side(2048, 1.0), 2048);
        assert_eq!(shadow_map_side(2048, 0.5), 1024);
        assert_eq!(shadow_map_side(2048, 0.25), 512);
        // √2 steps: a multiple of 64 near the exact side (1448.2, 362.0).
        assert_eq!(shadow_map_side(2048, STEPS[4]), 1472);
        assert_eq!(shadow_map_side(2048, MIN_SCALE), 384);
        assert_eq!(shadow_map_side(512, MIN_SCALE), ShadowSettings::MIN_RESOLUTION);
        // Never above what was chosen, even below the minimum.
        assert_eq!(shadow_map_side(100, 0.5), 100);
    }

    #[test]
    fn the_scale_keeps_to_its_floor_and_ceiling() {
        let mut scale = RenderScale::default();
        scale.observe(even(1.0), &times(0.0, 1e6));
        assert_eq!(scale.begin_frame(true).image, MIN_SCALE);
        scale.observe(even(1.0), &times(0.0, 1e-3));
        assert_eq!(scale.begin_frame(true).image, 1.0);
        scale.observe(even(1.0), &times(1e6, 1.0));
        assert_eq!(scale.begin_frame(true).image, MIN_SCALE);
        // Nothing measured: unchanged.
        scale.observe(even(1.0), &PassTimes::default());
        assert_eq!(scale.begin_frame(true).image, MIN_SCALE);
    }

    #[test]
    fn at_the_smallest_image_the_map_shrinks_alone_where_it_costs_much() {
        let budget = RenderScale::budget_ms();
        // A light among the geometry: five cube faces cost more than the
        // image, which is over the budget at its smallest. The map goes
        // down until it would cost half the image's own cost, its cost
        // taken as proportional to its side (0.55 / 1.4 of it: the step
        // below, an eighth).
        let mut scale = RenderScale::default();
        scale.observe(even(MIN_SCALE), &times(1.4 * budget, 1.1 * budget));
        let cube = scale.begin_frame(true);
        assert_eq!(cube.image, MIN_SCALE);
        assert_eq!(cube.shadow, SHADOW_STEPS[0]);
        // Measured there at half the cost: it stays.
        scale.observe(cube, &times(0.7 * budget, 1.1 * budget));
        assert_eq!(scale.begin_frame(true), cube);
        // A map that costs little there (its casters' setup, not its
        // fill) grows back to the image's scale.
        scale.observe(cube, &times(0.2 * budget, 1.4 * budget));
        assert_eq!(scale.begin_frame(true), even(MIN_SCALE));
        // A single map that costs little beside the image keeps the image's scale.
        let mut scale = RenderScale::default();
        scale.observe(even(MIN_SCALE), &times(0.2 * budget, 1.4 * budget));
        assert_eq!(scale.begin_frame(true), even(MIN_SCALE));
        // Room in the budget: the map fits what the image leaves of it
        // (0.6 of the budget for a map of 0.75: 0.8 of the side, the step below).
        let mut scale = RenderScale::default();
        scale.observe(even(MIN_SCALE), &times(0.75 * budget, 0.4 * budget));
        assert_eq!(scale.begin_frame(true).shadow, SHADOW_STEPS[1]);
        // Above the smallest image the map follows the image.
        let mut scale = RenderScale::default();
        scale.observe(even(1.0), &times(0.8 * budget, 3.2 * budget));
        assert_eq!(scale.begin_frame(true), even(0.5));
        // Idle frames draw the map at the chosen resolution.
        assert_eq!(scale.begin_frame(false), FrameScale::FULL);
    }
}
