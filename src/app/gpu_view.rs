//! The renderers behind the viewport: one per half of the split view, each
//! drawing into its own display texture, which egui shows as a native
//! texture (no CPU round trip). B shares A's uploaded scene and, when their
//! shadow settings give the same map, A's shadow map (`Renderer::sharing`).
//! A half re-renders only when what it shows changed: its settings, the
//! image size, the scene or the reference. Drag frames may render on a
//! device of their own (`drag_device`).

use super::drag_device::{DragDevice, DragRenderer, Job};
use super::render_scale::{FrameScale, RenderScale, shadow_map_side};
use super::view_readback::PendingProbe;
use super::viewport_image::ImagePipeline;
use crate::gpu::raytrace::Accumulation;
use crate::gpu::readback::ReadState;
use crate::gpu::{Capabilities, ShadeOptions};
use crate::gpu::{ComparisonImage, FloatTarget, PendingTexels, Renderer};
use crate::presets::Half;
use crate::scene::Scene;
use crate::scene::simplify::{SimplifiedMeshes, TriangleCounts, simplify_in_background};
use crate::settings::Settings;
use half::HalfView;
use std::sync::Arc;
use std::sync::mpsc::{Receiver, TryRecvError};
use std::time::{Duration, Instant};

mod half;

/// What a frame was rendered from: when it is unchanged, so is the image.
#[derive(Clone, PartialEq)]
struct RenderKey {
    settings: Settings,
    size: (u32, u32),
    scene_generation: u64,
    comparison_generation: u64,
    /// Drawn as a drag frame (simplified meshes, no aux target, one ray a
    /// pixel to a sphere light): the frame after the drag renders again
    /// even where the drag's render scale had reached 1.
    interaction: bool,
    /// A still frame writes the aux target (V, texel density) for the
    /// probe; the shading pass costs ~10 % less without it.
    aux: bool,
}

/// How long a drag frame waits for the drag device's image on its way
/// (a third of a 30 frames/s frame).
const DRAG_FRAME_WAIT: Duration = Duration::from_millis(10);

/// What comes back with a drag frame rendered on the drag device.
struct DragTag {
    key: RenderKey,
    scale: FrameScale,
}

/// The settings a frame at render scale `scale` is drawn with: the
/// shadow map's side scaled by `scale.shadow` ([`shadow_map_side`]). The
/// key keeps the settings as chosen, so the drag's end renders again.
fn drawn_at(settings: &Settings, scale: FrameScale) -> Settings {
    let mut drawn = settings.clone();
    drawn.shadow.resolution = shadow_map_side(settings.shadow.resolution, scale.shadow);
    drawn
}

pub struct GpuViews {
    render_state: egui_wgpu::RenderState,
    halves: [Option<HalfView>; 2],
    scene_generation: u64,
    caps: Capabilities,
    /// Reduced while the user drags, full when idle.
    pub render_scale: RenderScale,
    /// This frame's render scales (see [`Self::begin_frame`]).
    frame_scale: FrameScale,
    image_pipeline: ImagePipeline,
    /// Where drag frames render when not on the window's device.
    drag: Option<DragRenderer<DragTag>>,
    /// The scene's simplified meshes on their way (a large scene's: drag
    /// frames draw them once they are uploaded).
    simplifying: Option<Receiver<SimplifiedMeshes>>,
    /// Triangles of the simplified meshes and of the full ones, once uploaded.
    pub simplified: Option<TriangleCounts>,
}

impl GpuViews {
    pub fn new(render_state: egui_wgpu::RenderState, scene: &Arc<Scene>, drag_device: DragDevice) -> Self {
        let renderer = Renderer::new(
            &render_state.adapter,
            &render_state.device,
            &render_state.queue,
            scene,
        );
        renderer.build_bvh_in_background();
        let a = HalfView::new(renderer, 0);
        let caps = a.renderer.capabilities().clone();
        let image_pipeline = ImagePipeline::new(&render_state.device, render_state.target_format);
        let drag = drag_device
            .own_on(&render_state.adapter)
            .then(|| DragRenderer::new(&render_state.adapter, Arc::clone(scene)))
            .flatten();
        Self {
            render_state,
            halves: [Some(a), None],
            scene_generation: 0,
            caps,
            render_scale: RenderScale::default(),
            frame_scale: FrameScale::FULL,
            image_pipeline,
            drag,
            simplifying: simplify_in_background(scene),
            simplified: None,
        }
    }

    /// Whether drag frames render on a device of their own.
    pub fn has_drag_device(&self) -> bool {
        self.drag.is_some()
    }

    pub fn capabilities(&self) -> &Capabilities {
        &self.caps
    }

    pub fn backend(&self) -> String {
        format!("{:?}", self.render_state.adapter.get_info().backend)
    }

    pub fn half(&self, half: Half) -> Option<&HalfView> {
        self.halves[half as usize].as_ref()
    }

    /// Uploads a new scene, once for both halves (they share it).
    pub fn set_scene(&mut self, scene: &Arc<Scene>) {
        self.scene_generation += 1;
        if let Some(a) = &mut self.halves[Half::A as usize] {
            a.renderer.set_scene(scene);
            a.renderer.build_bvh_in_background();
        }
        if let Some(drag) = &self.drag {
            drag.set_scene(Arc::clone(scene));
        }
        for h in self.halves.iter_mut().flatten() {
            h.scene_generation = self.scene_generation;
        }
        // The last scene's meshes, if still on their way, are dropped with
        // their receiver.
        self.simplifying = simplify_in_background(scene);
        self.simplified = None;
    }

    /// Whether the scene's simplified meshes are still being built.
    pub fn simplifying(&self) -> bool {
        self.simplifying.is_some()
    }

    /// Uploads the simplified meshes once built, for the renderers that draw
    /// drag frames (A's, which B shares, and the drag device's).
    fn take_simplified(&mut self) {
        let meshes = match self.simplifying.as_ref().map(Receiver::try_recv) {
            Some(Ok(meshes)) => meshes,
            Some(Err(TryRecvError::Disconnected)) => {
                self.simplifying = None;
                return;
            }
            _ => return,
        };
        self.simplifying = None;
        if let Some(a) = &mut self.halves[Half::A as usize] {
            a.renderer.set_simplified(&meshes);
        }
        self.simplified = Some(meshes.counts);
        if let Some(drag) = &self.drag {
            drag.set_simplified(Arc::new(meshes));
        }
    }

    /// Creates the B renderer when the split view is on, sharing A's scene
    /// and shadow maps; drops it when off (its own shadow map can be large).
    pub fn set_split(&mut self, on: bool) {
        if let Some(drag) = &self.drag
            && on != self.halves[Half::B as usize].is_some()
        {
            drag.set_split(on);
        }
        let [a, b] = &mut self.halves;
        match (on, b.is_some()) {
            (true, false) => {
                if let Some(a) = a {
                    *b = Some(HalfView::new(a.renderer.sharing(), self.scene_generation));
                }
            }
            (false, true) => *b = None,
            _ => {}
        }
    }

    /// The reference image a half compares with; `generation` changes with it.
    pub fn set_comparison(&mut self, half: Half, image: Option<&Arc<ComparisonImage>>, generation: u64) {
        if let Some(h) = &mut self.halves[half as usize]
            && h.comparison_generation != generation
        {
            h.renderer.set_comparison(image.map(|i| (**i).clone()));
            if let Some(drag) = &self.drag {
                drag.set_comparison(half, image.cloned());
            }
            h.comparison_generation = generation;
            h.has_comparison = image.is_some();
        }
    }

    /// The render scale of this frame's images: reduced while `interacting`
    /// (a drag), else 1. Frames rendered while interacting skip the aux
    /// target: nothing reads them back.
    pub fn begin_frame(&mut self, interacting: bool) -> f64 {
        self.frame_scale = self.render_scale.begin_frame(interacting);
        self.frame_scale.image
    }

    /// Renders a half if what it shows changed; true when a new image is
    /// shown. `size`: the image size at this frame's render scale; `probed`:
    /// the probe reads this half (see [`ShadeOptions::still`]). On a
    /// drag device, a drag frame shows the last image that came back and
    /// sends the next job; `wake` repaints when its image is back.
    pub fn prepare(
        &mut self,
        half: Half,
        settings: &Settings,
        size: (u32, u32),
        probed: bool,
        wake: &egui::Context,
    ) -> bool {
        let Some(h) = &mut self.halves[half as usize] else {
            return false;
        };
        h.poll_noise(wake);
        let still = ShadeOptions::still(settings, probed);
        let key = RenderKey {
            settings: settings.clone(),
            size,
            scene_generation: h.scene_generation,
            comparison_generation: h.comparison_generation,
            interaction: self.render_scale.interacting,
            aux: still.aux,
        };
        if self.drag.as_ref().is_some_and(DragRenderer::is_gone) {
            self.drag = None;
        }
        if let Some(drag) = &mut self.drag {
            // A frame back after its drag ended is dropped. While dragging,
            // a frame that would show no new image waits a little for it:
            // it leaves the cores to the drag device instead of painting
            // the same image again.
            let wait = if self.render_scale.interacting {
                DRAG_FRAME_WAIT
            } else {
                Duration::ZERO
            };
            let frame = drag.take(half, wait);
            if self.render_scale.interacting {
                let shown = frame.is_some_and(|frame| {
                    if half == Half::A {
                        self.render_scale.rendered(frame.tag.scale);
                        if let Some(t) = &frame.times {
                            self.render_scale.observe(frame.tag.scale, t);
                        }
                    }
                    h.show_drag_frame(frame, &self.render_state, &self.image_pipeline);
                    true
                });
                if !drag.busy(half) && h.rendered.as_ref() != Some(&key) {
                    let tag = DragTag {
                        key,
                        scale: self.frame_scale,
                    };
                    drag.render(
                        Job {
                            half,
                            settings: drawn_at(settings, self.frame_scale),
                            size,
                            tag,
                        },
                        wake.clone(),
                    );
                }
                return shown;
            }
        }
        // A ray-traced image still accumulating renders on, unchanged settings or not.
        if h.rendered.as_ref() == Some(&key) && !h.accumulating() {
            return false;
        }
        let interacting = self.render_scale.interacting;
        h.renderer.set_shade_options(if interacting {
            ShadeOptions::INTERACTION
        } else {
            still
        });
        let drawn = drawn_at(settings, self.frame_scale);
        let start = Instant::now();
        h.report = h.renderer.render(&drawn, size);
        h.render_cpu_ms = start.elapsed().as_secs_f64() * 1e3;
        if !interacting {
            // The next drag's pipeline compiles while the user looks.
            match &self.drag {
                Some(drag) => drag.compile_ahead(half, drawn.clone()),
                None => h.renderer.compile_ahead(&drawn, ShadeOptions::INTERACTION),
            }
        }
        let accumulation = h.renderer.accumulation();
        h.shows(key, drawn, self.frame_scale, accumulation, start);
        if half == Half::A {
            self.render_scale.rendered(self.frame_scale);
        }
        if self.caps.timestamps {
            h.times_due = Some(Instant::now() + Duration::from_secs(1));
        }
        h.scale = None;
        h.pending_scale = None;
        // Only the views that scale to the image have a scale to read.
        if crate::gpu::display::scales_to_image(settings.view.mode) {
            h.pending_scale = Some(h.renderer.request_scale());
        }
        h.show_texture(&self.render_state, &self.image_pipeline);
        true
    }

    /// The render scale of a half's last frame (1: full resolution).
    pub fn rendered_scale(&self, half: Half) -> f64 {
        self.half(half).map_or(1.0, |h| h.rendered_scale.image)
    }

    /// The ray-traced accumulation of the image a half shows (None: V from
    /// the shadow map).
    pub fn accumulation(&self, half: Half) -> Option<Accumulation> {
        self.half(half)?.shown_accumulation
    }

    /// How long the ray-traced mean a half shows has taken so far.
    pub fn accumulation_elapsed(&self, half: Half) -> Option<Duration> {
        self.half(half)?.accumulation_elapsed
    }

    /// Whether a half's renderer has ray-traced frames still to fold in:
    /// the viewport asks for frames until it is done (a drag frame's mean,
    /// which no frame continues on the drag device, asks for none).
    pub fn accumulating(&self, half: Half) -> bool {
        self.half(half).is_some_and(HalfView::accumulating)
    }

    /// The shape that shows the part `uv` (0..1) of a half's last frame over `area`.
    pub fn image(&self, half: Half, area: egui::Rect, uv: egui::Rect) -> Option<egui::Shape> {
        let image = self.half(half)?.image.as_ref()?;
        Some(self.image_pipeline.shape(image, area, uv))
    }

    /// Collects timings and scales without blocking; true while some are still on their way.
    pub fn poll(&mut self) -> bool {
        self.take_simplified();
        let mut waiting = false;
        for (i, h) in self.halves.iter_mut().enumerate() {
            let Some(h) = h else { continue };
            if let Some(t) = h.renderer.poll_timings() {
                if i == Half::A as usize {
                    self.render_scale.observe(h.rendered_scale, &t);
                }
                if let Some(shadow) = t.shadow_ms {
                    h.last_shadow_ms = Some(shadow + t.blur_ms.unwrap_or(0.0));
                }
                h.times = Some(t);
                h.times_due = None;
            }
            if h.times_due.is_some_and(|due| Instant::now() > due) {
                h.times_due = None;
            }
            waiting |= h.times_due.is_some();
            if let Some(pending) = &h.pending_scale {
                match pending.poll() {
                    ReadState::Waiting => waiting = true,
                    ReadState::Ready(s) => {
                        h.scale = Some(s);
                        h.pending_scale = None;
                    }
                    ReadState::Failed => h.pending_scale = None,
                }
            }
        }
        waiting
    }

    /// Starts reading pixel `pixel` of a half's last frame for the probe.
    pub fn request_probe(&self, half: Half, pixel: (u32, u32)) -> Option<PendingProbe> {
        let h = self.half(half)?;
        let settings = &h.rendered.as_ref()?.settings;
        Some(PendingProbe::new(
            settings.view.mode,
            settings.shadow.visibility,
            h.renderer.request_texels(FloatTarget::Aux, pixel, (1, 1))?,
            h.renderer.request_texels(FloatTarget::Quantity, pixel, (1, 1))?,
        ))
    }

    /// Starts reading half A's whole quantity target: a pixel is covered
    /// where its alpha is above 0 (the camera pass writes 1, the clear 0).
    pub fn request_frame(&self) -> Option<PendingTexels> {
        let h = self.half(Half::A)?;
        let size = h.rendered.as_ref()?.size;
        h.renderer.request_texels(FloatTarget::Quantity, (0, 0), size)
    }

    /// Frames rendered by a half so far.
    pub fn renders(&self, half: Half) -> u64 {
        self.half(half).map_or(0, |h| h.renders)
    }

    /// The image a half shows, read back (blocking), with the settings it
    /// was drawn with: for tests.
    pub fn shown_image(&self, half: Half) -> Option<(Settings, image::RgbaImage)> {
        let h = self.half(half)?;
        let (texture, drawn) = (h.shown.as_ref()?, h.drawn.clone()?);
        let rs = &self.render_state;
        let bytes = crate::gpu::readback::read_texture(&rs.device, &rs.queue, texture, 0, 4);
        Some((
            drawn,
            image::RgbaImage::from_raw(texture.width(), texture.height(), bytes)?,
        ))
    }

    /// A half's renderer (exports read from A).
    pub fn renderer(&self, half: Half) -> Option<&Renderer> {
        self.half(half).map(|h| &h.renderer)
    }
}
