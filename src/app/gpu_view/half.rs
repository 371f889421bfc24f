//! One half of the viewport: its renderer, the texture the window shows
//! and what that image was drawn from (see `gpu_view`).

use super::{DragTag, RenderKey};
use crate::app::drag_device::DragFrame;
use crate::app::render_scale::FrameScale;
use crate::app::viewport_image::{ImageBinding, ImagePipeline};
use crate::gpu::raytrace::Accumulation;
use crate::gpu::timing::PassTimes;
use crate::gpu::{FrameReport, PendingScale, Renderer};
use crate::settings::Settings;
use std::time::{Duration, Instant};

/// One half of the viewport: a renderer and the texture the window shows.
pub struct HalfView {
    pub(super) renderer: Renderer,
    /// The window shows the sRGB-encoded bytes as they are (Rgba8Unorm), the
    /// renderer writes Rgba8UnormSrgb: the bytes are copied on the GPU into
    /// this texture so that they reach the screen unchanged.
    pub(super) shown: Option<wgpu::Texture>,
    pub(super) image: Option<ImageBinding>,
    pub(super) rendered: Option<RenderKey>,
    /// The settings the shown image was drawn with (the shadow map's side
    /// reduced with the image during a drag).
    pub(super) drawn: Option<Settings>,
    pub(super) scene_generation: u64,
    pub(super) comparison_generation: u64,
    /// A reference image is set (the error views have something to show).
    pub has_comparison: bool,
    /// The last frame's report.
    pub report: FrameReport,
    /// GPU time of each pass of the latest timed frame.
    pub times: Option<PassTimes>,
    /// GPU time of the last frame that drew the shadow map (and its blur).
    pub last_shadow_ms: Option<f64>,
    /// CPU time of the last `render` call (encoding and submitting).
    pub render_cpu_ms: f64,
    /// Frames rendered so far (the lab renders only on change).
    pub renders: u64,
    /// The render scales of the last frame (1: the viewport's full size).
    pub(super) rendered_scale: FrameScale,
    /// The ray-traced accumulation of the image shown: the drag device's
    /// while a drag frame is shown, not the still frame's before it.
    pub(super) shown_accumulation: Option<Accumulation>,
    /// The run of the ray-traced mean shown and when its first frame was
    /// asked for.
    accumulation_started: Option<(u64, Instant)>,
    /// From the first frame of the mean shown to the end of the render
    /// call of its last.
    pub(super) accumulation_elapsed: Option<Duration>,
    /// Until when to keep polling for the last frame's GPU times.
    pub(super) times_due: Option<Instant>,
    /// The false-colour scale of the displayed frame, once read back.
    pub scale: Option<f32>,
    pub(super) pending_scale: Option<PendingScale>,
}

impl HalfView {
    pub fn renderer(&self) -> &Renderer {
        &self.renderer
    }

    pub(super) fn new(renderer: Renderer, scene_generation: u64) -> Self {
        Self {
            renderer,
            shown: None,
            image: None,
            rendered: None,
            drawn: None,
            scene_generation,
            comparison_generation: 0,
            has_comparison: false,
            report: FrameReport::default(),
            times: None,
            last_shadow_ms: None,
            render_cpu_ms: 0.0,
            renders: 0,
            rendered_scale: FrameScale::FULL,
            shown_accumulation: None,
            accumulation_started: None,
            accumulation_elapsed: None,
            times_due: None,
            scale: None,
            pending_scale: None,
        }
    }

    /// Copies the renderer's display texture into the one the window shows,
    /// and binds it.
    pub(super) fn show_texture(&mut self, render_state: &egui_wgpu::RenderState, pipeline: &ImagePipeline) {
        let Some(size) = self.renderer.display_texture().map(wgpu::Texture::size) else {
            return;
        };
        let recreated = self.resize_shown(&render_state.device, size);
        let (Some(display), Some(shown)) = (self.renderer.display_texture(), &self.shown) else {
            return;
        };
        let mut encoder = render_state
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("lumlab display copy"),
            });
        // Same bytes, formats that differ only in their sRGB flag: a plain copy.
        encoder.copy_texture_to_texture(display.as_image_copy(), shown.as_image_copy(), size);
        render_state.queue.submit([encoder.finish()]);
        self.bind_shown(&render_state.device, pipeline, recreated);
    }

    /// Picks up the noise measured on the ray-traced mean shown once its
    /// read is back, asking for a repaint while it is on its way.
    pub(super) fn poll_noise(&mut self, wake: &egui::Context) {
        if self.renderer.poll_noise() {
            wake.request_repaint();
        }
        if let (Some(shown), Some(now)) = (&mut self.shown_accumulation, self.renderer.accumulation())
            && shown.run == now.run
        {
            shown.estimate = now.estimate;
        }
    }

    /// Whether its renderer's ray-traced mean is still under way: frames
    /// left, and its measured noise above the settings' target.
    pub(super) fn accumulating(&self) -> bool {
        let target = self
            .drawn
            .as_ref()
            .map_or(0.0, |s| s.shadow.rt_noise_target_percent);
        self.renderer.accumulation().is_some_and(|a| !a.holds(target))
    }

    /// Counts a new image, rendered from `key` with `drawn` at render scales
    /// `scale`, its accumulation `accumulation`, its render asked for at
    /// `asked`.
    pub(super) fn shows(
        &mut self,
        key: RenderKey,
        drawn: Settings,
        scale: FrameScale,
        accumulation: Option<Accumulation>,
        asked: Instant,
    ) {
        self.renders += 1;
        self.accumulation_elapsed = accumulation.map(|a| {
            let started = match self.accumulation_started {
                Some((run, started)) if run == a.run => started,
                _ => asked,
            };
            self.accumulation_started = Some((a.run, started));
            started.elapsed()
        });
        self.shown_accumulation = accumulation;
        self.rendered = Some(key);
        self.drawn = Some(drawn);
        self.rendered_scale = scale;
    }

    /// Shows a frame rendered on the drag device: its bytes are written into
    /// the texture the window shows.
    pub(super) fn show_drag_frame(
        &mut self,
        frame: DragFrame<DragTag>,
        render_state: &egui_wgpu::RenderState,
        pipeline: &ImagePipeline,
    ) {
        let (width, height) = frame.image.dimensions();
        let size = wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        };
        self.report = frame.report;
        self.render_cpu_ms = frame.render_cpu_ms;
        if frame.times.is_some() {
            self.times = frame.times;
        }
        self.scale = frame.scale;
        self.pending_scale = None;
        self.shows(
            frame.tag.key,
            frame.settings,
            frame.tag.scale,
            frame.accumulation,
            Instant::now(),
        );
        let recreated = self.resize_shown(&render_state.device, size);
        let Some(shown) = &self.shown else { return };
        render_state.queue.write_texture(
            shown.as_image_copy(),
            &frame.image,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4 * width),
                rows_per_image: Some(height),
            },
            size,
        );
        self.bind_shown(&render_state.device, pipeline, recreated);
    }

    /// Makes the texture the window shows `size` (a new one when the size
    /// changed: true then).
    fn resize_shown(&mut self, device: &wgpu::Device, size: wgpu::Extent3d) -> bool {
        if self.shown.as_ref().is_some_and(|t| t.size() == size) {
            return false;
        }
        self.shown = Some(device.create_texture(&wgpu::TextureDescriptor {
            label: Some("lumlab display (egui)"),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8Unorm,
            // COPY_SRC: tests read back what the window shows.
            usage: wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_DST
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        }));
        true
    }

    /// Binds the shown texture for egui when it is new or not bound yet.
    fn bind_shown(&mut self, device: &wgpu::Device, pipeline: &ImagePipeline, recreated: bool) {
        let Some(shown) = &self.shown else { return };
        if !recreated && self.image.is_some() {
            return;
        }
        let view = shown.create_view(&wgpu::TextureViewDescriptor::default());
        // Nearest at full scale: one texel per pixel. Linear for the
        // reduced images of interaction frames.
        self.image = Some(pipeline.bind(device, &view, self.rendered_scale.image < 1.0));
    }
}
