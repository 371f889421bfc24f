//! The viewport and what follows it: the image of each half with its
//! comparison to the reference, the banner and caption over it, the probe
//! kept on its point, the readbacks a fresh image needs.

use super::super::command::Command;
use super::super::probe::{self, ProbePixel, ReferenceSample};
use super::super::reference::reference_key;
use super::super::viewport::{Viewport, ViewportResponse};
use super::LabApp;
use crate::presets::Half;
use crate::reference::Reference;
use crate::scene::Scene;
use crate::settings::{DebugView, Settings};
use crate::tr;

impl LabApp {
    /// The image; a drag in it (camera, light, divider) edits copies that
    /// become commands.
    pub(super) fn viewport(&mut self, ui: &mut egui::Ui) -> ViewportResponse {
        self.update_comparisons();
        let banner = self.empty_banner().or_else(|| self.reference_banner());
        let caption = self.error_caption();
        if let Some(gpu) = &mut self.gpu {
            gpu.set_split(self.state.split.enabled);
        }
        let mut settings = self.state.settings.clone();
        let mut split = self.state.split;
        let response = Viewport {
            settings: &mut settings,
            split: &mut split,
            gpu: self.gpu.as_mut(),
            probe: self.probe.pixel,
            banner,
            caption,
            scale: self.scene.scale,
        }
        .show(ui);
        if settings != self.state.settings {
            self.emit(Command::SetSettings(Box::new(settings)));
        }
        if split != self.state.split {
            self.emit(Command::SetSplit(split));
        }
        response
    }

    /// The settings of half A, with the viewport's image size.
    fn keyed(&self, half: Half) -> Settings {
        reference_key(&Viewport::render_settings(
            &self.state.settings,
            &self.state.split,
            half,
            self.viewport_size,
        ))
    }

    /// Gives each half the reference it can compare with: A always (marked
    /// stale when it is), B only when its settings share A's reference.
    fn update_comparisons(&mut self) {
        let key_b = self.keyed(Half::B);
        let Some(gpu) = &mut self.gpu else { return };
        let result = self.reference.result.as_ref();
        let image = result.map(|r| &r.image);
        gpu.set_comparison(Half::A, image, 2 * self.reference_generation);
        let b_matches = result.is_some_and(|r| r.key == key_b);
        let b_image = if b_matches { image } else { None };
        gpu.set_comparison(Half::B, b_image, 2 * self.reference_generation + b_matches as u64);
    }

    /// The error view's RMSE, on the image where the class can read it.
    fn error_caption(&self) -> Option<String> {
        let stats = self
            .reference
            .stats
            .filter(|_| self.state.settings.view.mode == DebugView::Error)?;
        Some(tr!(
            "image-rmse",
            rmse = super::super::widgets::quantity(stats.rmse, "W/m²/sr"),
            percent = super::super::widgets::number(100.0 * stats.relative)
        ))
    }

    /// A valid file with nothing to draw says so over the empty image.
    fn empty_banner(&self) -> Option<String> {
        if self.file_scene.triangle_count() > 0 {
            return None;
        }
        let why = self
            .file_scene
            .warnings
            .iter()
            .find(|w| w.starts_with("nothing to draw"))
            .cloned()
            .unwrap_or_else(|| tr!("image-nothing-to-draw"));
        Some(format!("{}: {why}", self.shown.name()))
    }

    fn reference_banner(&self) -> Option<String> {
        let view = self.state.settings.view.mode;
        if !matches!(view, DebugView::Error | DebugView::RefVisibility) {
            return None;
        }
        match &self.reference.result {
            None if self.reference.is_running() => Some(tr!("image-reference-running")),
            None => Some(tr!("image-reference-none")),
            Some(r) if r.key != self.keyed(Half::A) => Some(tr!("image-reference-stale")),
            Some(_) => None,
        }
    }

    pub(super) fn after_viewport(&mut self, response: ViewportResponse) {
        if response.size != (0, 0) {
            self.viewport_size = response.size;
            self.viewport_rect = response.rect.unwrap_or(egui::Rect::NOTHING);
        }
        if let Some(p) = response.double_clicked {
            // The orbit's pivot: the point under the cursor, if any.
            let (settings, tracer, _) = self.traced_half(p);
            if let Some(hit) = probe::trace(tracer, &settings, p.pixel, p.size) {
                self.emit(Command::SetPivot(hit.position.as_vec3()));
            }
        }
        if let Some(pixel) = response.clicked {
            self.probe.pixel = Some(pixel);
            self.refresh_probe();
        } else if let Some(pixel) = self.probe.pixel
            && response.rendered[pixel.half as usize]
            && !response.preview
        {
            // A resized viewport (a panel widened by the probe's own rows, or
            // the window) keeps the probe on the same point of the image.
            self.probe.pixel = Some(pixel.resized(response.size));
            self.refresh_probe();
        }
        let fresh_reference = self
            .reference
            .result
            .as_ref()
            .is_some_and(|r| r.key == self.keyed(Half::A));
        if response.rendered[Half::A as usize] {
            self.reference.stats = None;
            self.jobs.pending_frame = None;
            if fresh_reference
                && !response.preview
                && self.state.settings.view.mode == DebugView::Error
                && let Some(gpu) = &self.gpu
            {
                self.jobs.pending_frame = gpu.request_frame();
            }
        }
    }

    /// The settings the half of `p` shows at its size, the scene's ray
    /// tracer (built at the first use) and the scene.
    fn traced_half(&mut self, p: ProbePixel) -> (Settings, &Reference, &Scene) {
        let settings = Viewport::render_settings(&self.state.settings, &self.state.split, p.half, p.size);
        let scene = &self.scene;
        let tracer = self.tracer.get_or_insert_with(|| Reference::new(scene));
        (settings, tracer, scene)
    }

    /// Recomputes the probe's terms and asks the GPU for its values there.
    pub(super) fn refresh_probe(&mut self) {
        let Some(p) = self.probe.pixel else { return };
        let (settings, tracer, scene) = self.traced_half(p);
        self.probe.terms = probe::evaluate(tracer, scene, &settings, p.pixel, p.size);
        self.probe.gpu = None;
        self.jobs.pending_probe = self.gpu.as_ref().and_then(|g| g.request_probe(p.half, p.pixel));
        self.probe.reference = self.reference.result.as_ref().and_then(|r| {
            let stale = r.key != self.keyed(p.half);
            ReferenceSample::at(&r.image, p.pixel, stale)
        });
    }
}
