//! The app itself: owns the persisted state, the renderers and the
//! background work, lays out the panels and routes what they ask for.

use super::energy::{Curve, EnergyKey, EnergyPanel};
use super::files::{FileAction, FilesPanel};
use super::gpu_view::{GpuViews, PendingFrame, PendingProbe};
use super::light::LightPanel;
use super::material::MaterialPanel;
use super::probe::{Probe, ReferenceSample};
use super::reference::{ReferenceAction, ReferencePanel, error_stats, reference_key};
use super::shadow::ShadowPanel;
use super::state::State;
use super::timings::FrameClock;
use super::undo::UndoStack;
use super::view::ViewPanel;
use super::viewport::{Viewport, ViewportResponse};
use super::{LaunchOptions, Preloaded, View, help};
use crate::gpu::readback::ReadState;
use crate::presets::{ComparisonAxis, Half, Preset};
use crate::reference::Reference;
use crate::scene::Scene;
use crate::settings::{CameraSettings, DebugView, Settings};
use egui::{Key, KeyboardShortcut, Modifiers, RichText};
use std::path::{Path, PathBuf};
use std::sync::mpsc::{Receiver, Sender};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// A run driven by `--screenshot` / `--quit-after-frames`.
struct Script {
    screenshot: Option<PathBuf>,
    frames: u32,
    requested: bool,
}

/// A one-line message in the status bar.
struct Status {
    text: String,
    error: bool,
}

type SceneLoad = (PathBuf, Result<Scene, String>);

pub struct LabApp {
    state: State,
    gpu: Option<GpuViews>,
    scene: Arc<Scene>,
    scene_name: String,
    scene_load: Option<Receiver<SceneLoad>>,
    undo: UndoStack,
    probe: Probe,
    /// The scene prepared for ray tracing, built at the first probe.
    tracer: Option<Reference>,
    pending_probe: Option<PendingProbe>,
    pending_frame: Option<PendingFrame>,
    energy: EnergyPanel,
    reference: ReferencePanel,
    reference_generation: u64,
    files: FilesPanel,
    clock: FrameClock,
    status: Option<Status>,
    help_open: bool,
    screenshot_tx: Sender<Arc<egui::ColorImage>>,
    screenshot_rx: Receiver<Arc<egui::ColorImage>>,
    screenshot_path: Option<PathBuf>,
    script: Option<Script>,
    outcome: Arc<Mutex<Option<String>>>,
    frames: u64,
    viewport_size: (u32, u32),
    viewport_rect: egui::Rect,
    styled: bool,
}

/// Text sizes readable from the back of a room.
fn set_style(ctx: &egui::Context) {
    use egui::{FontFamily, FontId, TextStyle};
    ctx.all_styles_mut(|style| {
        style.text_styles = [
            (TextStyle::Heading, FontId::new(22.0, FontFamily::Proportional)),
            (TextStyle::Body, FontId::new(16.5, FontFamily::Proportional)),
            (TextStyle::Button, FontId::new(16.5, FontFamily::Proportional)),
            (TextStyle::Monospace, FontId::new(15.5, FontFamily::Monospace)),
            (TextStyle::Small, FontId::new(13.0, FontFamily::Proportional)),
        ]
        .into();
        style.spacing.item_spacing = egui::vec2(8.0, 6.0);
        style.spacing.slider_width = 190.0;
        style.spacing.interact_size.y = 24.0;
    });
}

impl LabApp {
    /// The app on `render_state`'s device (None: the panels work, the
    /// viewport says there is no renderer).
    pub fn new(
        render_state: Option<egui_wgpu::RenderState>,
        storage: Option<&dyn eframe::Storage>,
        options: &LaunchOptions,
        preloaded: Preloaded,
        outcome: Arc<Mutex<Option<String>>>,
    ) -> Result<Self, String> {
        let scripted = options.is_scripted();
        let mut state = if scripted {
            State::default()
        } else {
            State::restore(storage).unwrap_or_default()
        };
        if let Some(settings) = preloaded.settings {
            state.settings = settings;
        }
        let mut status = None;
        let (scene, scene_name) = match preloaded.scene {
            Some((path, scene)) => {
                state.settings.scene = Some(path.clone());
                (scene, display_name(&path))
            }
            None => match state.settings.scene.clone() {
                Some(path) => match crate::scene::load(&path) {
                    Ok(scene) => (scene, display_name(&path)),
                    Err(e) => {
                        status = Some(Status {
                            text: format!("{e}; showing the built-in scene"),
                            error: true,
                        });
                        state.settings.scene = None;
                        (crate::scene::default_scene(), "built-in".into())
                    }
                },
                None => (crate::scene::default_scene(), "built-in".into()),
            },
        };
        let gpu = render_state.map(|rs| GpuViews::new(rs, &scene));
        if gpu.is_none() {
            return Err("eframe started without the wgpu renderer".into());
        }
        let (screenshot_tx, screenshot_rx) = std::sync::mpsc::channel();
        let script = scripted.then(|| Script {
            screenshot: options.screenshot.clone(),
            frames: options
                .quit_after_frames
                .unwrap_or(LaunchOptions::DEFAULT_SCREENSHOT_FRAMES)
                .max(1),
            requested: false,
        });
        Ok(Self {
            undo: UndoStack::new(&state.settings),
            state,
            gpu,
            scene: Arc::new(scene),
            scene_name,
            scene_load: None,
            probe: Probe::default(),
            tracer: None,
            pending_probe: None,
            pending_frame: None,
            energy: EnergyPanel::default(),
            reference: ReferencePanel::default(),
            reference_generation: 1,
            files: FilesPanel::default(),
            clock: FrameClock::default(),
            status,
            help_open: false,
            screenshot_tx,
            screenshot_rx,
            screenshot_path: None,
            script,
            outcome,
            frames: 0,
            viewport_size: (0, 0),
            viewport_rect: egui::Rect::NOTHING,
            styled: false,
        })
    }

    /// The settings as the panels left them.
    pub fn settings(&self) -> &Settings {
        &self.state.settings
    }

    pub fn settings_mut(&mut self) -> &mut Settings {
        &mut self.state.settings
    }

    /// The probe's terms at the last clicked pixel, if it hit the scene.
    pub fn probe_terms(&self) -> Option<&super::ProbeTerms> {
        self.probe.terms.as_ref()
    }

    /// The GPU's V and L at the probed pixel, once read back.
    pub fn probe_gpu(&self) -> Option<super::probe::GpuSample> {
        self.probe.gpu
    }

    /// The probed pixel, if any.
    pub fn probe_pixel(&self) -> Option<super::ProbePixel> {
        self.probe.pixel
    }

    /// The renderer of half A (B is the split view's right half).
    pub fn renderer(&self) -> Option<&crate::gpu::Renderer> {
        self.gpu.as_ref().and_then(|g| g.renderer(Half::A))
    }

    /// A CPU reference is being computed.
    pub fn reference_running(&self) -> bool {
        self.reference.is_running()
    }

    /// A reference image has been computed (it may be stale).
    pub fn has_reference(&self) -> bool {
        self.reference.result.is_some()
    }

    /// RMSE and friends of the GPU image against the reference, once computed.
    pub fn error_stats(&self) -> Option<super::ErrorStats> {
        self.reference.stats
    }

    /// Where the image is in the window (points), on the last frame.
    pub fn viewport_rect(&self) -> egui::Rect {
        self.viewport_rect
    }

    /// Frames rendered by half A so far (the lab renders only on change).
    pub fn renders(&self) -> u64 {
        self.gpu.as_ref().map_or(0, |g| g.renders(Half::A))
    }

    /// The persisted state (settings, split view, panels, paths).
    pub fn state_mut(&mut self) -> &mut State {
        &mut self.state
    }

    /// The viewport's image size (pixels) on the last frame.
    pub fn viewport_size(&self) -> (u32, u32) {
        self.viewport_size
    }

    /// Replaces the CPU reference's implementation (tests).
    pub fn set_reference_fn(&mut self, compute: Arc<super::ReferenceFn>) {
        self.reference = ReferencePanel::new(compute);
    }

    fn say(&mut self, text: impl Into<String>, error: bool) {
        self.status = Some(Status {
            text: text.into(),
            error,
        });
    }

    /// One frame of the whole window.
    pub fn show(&mut self, ui: &mut egui::Ui) {
        let start = self.clock.begin();
        let ctx = ui.ctx().clone();
        if !self.styled {
            set_style(&ctx);
            self.styled = true;
        }
        self.frames += 1;
        self.collect_background_work(&ctx);
        self.handle_dropped_files(&ctx);
        self.handle_keys(&ctx);

        let mut action = None;
        egui::Panel::top("top bar").show(ui, |ui| self.top_bar(ui));
        egui::Panel::bottom("status bar").show(ui, |ui| self.status_bar(ui));
        if self.state.panels.settings {
            egui::Panel::left("settings panel")
                .resizable(true)
                .default_size(330.0)
                .size_range(260.0..=560.0)
                .show(ui, |ui| {
                    egui::ScrollArea::vertical().show(ui, |ui| action = self.settings_panel(ui));
                });
        }
        if self.state.panels.analysis {
            egui::Panel::right("analysis panel")
                .resizable(true)
                .default_size(420.0)
                .size_range(280.0..=640.0)
                .show(ui, |ui| {
                    // Scrolled both ways: wide rows (the probe's vectors) never
                    // widen the panel, which would shrink the image under the probe.
                    egui::ScrollArea::both().show(ui, |ui| self.analysis_panel(ui, &ctx));
                });
        }
        let response = egui::CentralPanel::no_frame()
            .show(ui, |ui| self.viewport(ui))
            .inner;
        self.after_viewport(response);
        if let Some(action) = action {
            self.file_action(action, &ctx);
        }
        help::window(&ctx, &mut self.help_open);

        let busy = ctx.input(|i| i.pointer.any_down()) || ctx.egui_wants_keyboard_input();
        let now = ctx.input(|i| i.time);
        if self.undo.observe(&self.state.settings, busy, now) {
            ctx.request_repaint_after(Duration::from_secs_f64(UndoStack::QUIET_S));
        }
        self.schedule_repaint(&ctx);
        self.run_script(&ctx);
        self.clock.end(start);
    }

    fn top_bar(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            ui.heading("lumlab");
            ui.separator();
            let settings = &mut self.state.settings;
            if ui
                .add_enabled(self.undo.can_undo(settings), egui::Button::new("Undo"))
                .on_hover_text("Undo the last settings change (Ctrl+Z)")
                .clicked()
            {
                self.undo.undo(settings);
            }
            if ui
                .add_enabled(self.undo.can_redo(), egui::Button::new("Redo"))
                .on_hover_text("Redo (Ctrl+Shift+Z or Ctrl+Y)")
                .clicked()
            {
                self.undo.redo(settings);
            }
            if ui
                .button("Reset view")
                .on_hover_text("Camera back to its start (R)")
                .clicked()
            {
                self.reset_view();
            }
            ui.toggle_value(&mut self.state.split.enabled, "Split A | B")
                .on_hover_text("Compare two settings side by side (S)");
            ui.separator();
            ui.toggle_value(&mut self.state.panels.settings, "Settings")
                .on_hover_text("Show the settings panel (F9 hides both panels)");
            ui.toggle_value(&mut self.state.panels.analysis, "Analysis")
                .on_hover_text("Show the probe, energy, reference and timings panel");
            ui.toggle_value(&mut self.help_open, "Help (F1)")
                .on_hover_text("Keyboard and mouse shortcuts");
        });
    }

    fn status_bar(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            match &self.status {
                Some(s) if s.error => {
                    ui.label(RichText::new(&s.text).color(ui.visuals().error_fg_color));
                }
                Some(s) => {
                    ui.label(&s.text);
                }
                None => {
                    ui.label("Drag: orbit · Shift+drag: pan · wheel: zoom · click: probe · F1: help");
                }
            }
            ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                if let Some(gpu) = &self.gpu {
                    let caps = gpu.capabilities();
                    let name = caps.adapter.split(" (").next().unwrap_or(&caps.adapter);
                    ui.label(format!(
                        "{}×{} px · {name} ({})",
                        self.viewport_size.0,
                        self.viewport_size.1,
                        gpu.backend()
                    ))
                    .on_hover_text(caps.adapter.as_str());
                }
            });
        });
    }

    fn settings_panel(&mut self, ui: &mut egui::Ui) -> Option<FileAction> {
        let settings = &mut self.state.settings;
        egui::CollapsingHeader::new(RichText::new("Experiments").heading())
            .default_open(true)
            .show(ui, |ui| {
                ui.horizontal_wrapped(|ui| {
                    for &preset in Preset::ALL {
                        if ui
                            .button(preset.title())
                            .on_hover_text(preset.description())
                            .clicked()
                        {
                            // On the built-in scene, presets start from its own view
                            // (their light positions are tuned for it).
                            if settings.scene.is_none() {
                                settings.camera = CameraSettings::default();
                            }
                            preset.apply(settings);
                            self.status = Some(Status {
                                text: format!("preset: {} (Ctrl+Z to undo)", preset.title()),
                                error: false,
                            });
                        }
                    }
                });
            });
        section(ui, "Light", true, |ui| {
            LightPanel {
                light: &mut settings.light,
            }
            .ui(ui)
        });
        section(ui, "Material", true, |ui| {
            MaterialPanel {
                material: &mut settings.material,
            }
            .ui(ui)
        });
        let (max_side, note) = match &self.gpu {
            Some(gpu) => (
                gpu.capabilities().max_texture_side,
                gpu.half(Half::A)
                    .and_then(|h| h.report.resolution_note.clone().map(|n| (h.report.resolution, n))),
            ),
            None => (crate::settings::ShadowSettings::MAX_RESOLUTION, None),
        };
        section(ui, "Shadow", true, |ui| {
            ShadowPanel {
                shadow: &mut settings.shadow,
                light_radius_m: &mut settings.light.radius_m,
                max_texture_side: max_side,
                resolution_note: note,
            }
            .ui(ui)
        });
        section(ui, "View", true, |ui| {
            ViewPanel {
                view: &mut settings.view,
                split: &mut self.state.split,
                max_texture_side: max_side,
            }
            .ui(ui)
        });
        let mut action = None;
        section(ui, "Files", false, |ui| {
            action = self.files.ui(ui, &mut self.state.paths, &self.scene_name);
        });
        action
    }

    fn analysis_panel(&mut self, ui: &mut egui::Ui, ctx: &egui::Context) {
        section(ui, "Pixel probe", true, |ui| self.probe.ui(ui));
        let curves = self.energy_curves();
        let incidence = self.incidence_for_lobe();
        section(ui, "Energy: albedo a(θ)", true, |ui| {
            self.energy
                .ui(ui, &curves, incidence.as_ref().map(|(t, s)| (*t, s.as_str())))
        });
        let mut action = ReferenceAction::None;
        let settings_a = Viewport::render_settings(
            &self.state.settings,
            &self.state.split,
            Half::A,
            self.viewport_size,
        );
        section(ui, "Reference and error", true, |ui| {
            action = self.reference.ui(ui, &settings_a, self.viewport_size);
        });
        match action {
            ReferenceAction::None => {}
            ReferenceAction::Compute => self.start_reference(ctx),
            ReferenceAction::Show(view) => self.state.settings.view.mode = view,
        }
        section(ui, "Timings", false, |ui| {
            super::timings::ui(ui, &self.clock, self.gpu.as_ref())
        });
    }

    /// The BRDF of the material settings; both halves' when the split view
    /// compares normalizations.
    fn energy_curves(&self) -> Vec<Curve> {
        let split = &self.state.split;
        let halves: &[(Half, &str)] =
            if split.enabled && split.comparison.axis == ComparisonAxis::Normalization {
                &[(Half::A, "A: "), (Half::B, "B: ")]
            } else {
                &[(Half::A, "")]
            };
        halves
            .iter()
            .map(|&(half, name)| {
                let m = Viewport::settings_for(&self.state.settings, split, half).material;
                Curve {
                    name: name.into(),
                    key: EnergyKey {
                        k: m.k as f64,
                        m: m.m as f64,
                        norm: m.norm,
                    },
                }
            })
            .collect()
    }

    /// θ_i for the lobe plot: at the probed point, else from the light to
    /// the scene's centre on its floor (normal +Y).
    fn incidence_for_lobe(&self) -> Option<(f64, String)> {
        if let Some(t) = &self.probe.terms {
            return Some((
                t.cos_theta.clamp(-1.0, 1.0).acos().to_degrees(),
                "at the probed point".into(),
            ));
        }
        let bounds = self.scene.bounds();
        if bounds.is_empty() {
            return None;
        }
        let mut centre = bounds.center().as_dvec3();
        centre.y = bounds.min.y as f64;
        let to_light = self.state.settings.light.position.as_dvec3() - centre;
        let cos = to_light.normalize_or_zero().y;
        Some((
            cos.clamp(-1.0, 1.0).acos().to_degrees(),
            "light to scene centre, n = +Y".into(),
        ))
    }

    fn viewport(&mut self, ui: &mut egui::Ui) -> ViewportResponse {
        self.update_comparisons();
        let banner = self.reference_banner();
        let caption = self.error_caption();
        if let Some(gpu) = &mut self.gpu {
            gpu.set_split(self.state.split.enabled);
        }
        Viewport {
            settings: &mut self.state.settings,
            split: &mut self.state.split,
            gpu: self.gpu.as_mut(),
            probe: self.probe.pixel,
            banner,
            caption,
        }
        .show(ui)
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
        Some(format!(
            "RMSE = {} ({} % of mean L_ref)",
            super::widgets::quantity(stats.rmse, "W/m²/sr"),
            super::widgets::number(100.0 * stats.relative)
        ))
    }

    fn reference_banner(&self) -> Option<String> {
        let view = self.state.settings.view.mode;
        if !matches!(view, DebugView::Error | DebugView::RefVisibility) {
            return None;
        }
        match &self.reference.result {
            None if self.reference.is_running() => Some("Computing the CPU reference…".into()),
            None => Some("No CPU reference yet: press F5 (Reference panel)".into()),
            Some(r) if r.key != self.keyed(Half::A) => {
                Some("Reference is STALE: settings or size changed since (F5 recomputes)".into())
            }
            Some(_) => None,
        }
    }

    fn after_viewport(&mut self, response: ViewportResponse) {
        if response.size != (0, 0) {
            self.viewport_size = response.size;
            self.viewport_rect = response.rect.unwrap_or(egui::Rect::NOTHING);
        }
        if let Some(pixel) = response.clicked {
            self.probe.pixel = Some(pixel);
            self.refresh_probe();
        } else if let Some(pixel) = self.probe.pixel
            && response.rendered[pixel.half as usize]
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
            self.pending_frame = None;
            if fresh_reference
                && self.state.settings.view.mode == DebugView::Error
                && let Some(gpu) = &self.gpu
            {
                self.pending_frame = gpu.request_frame();
            }
        }
    }

    /// Recomputes the probe's terms and asks the GPU for its values there.
    fn refresh_probe(&mut self) {
        let Some(p) = self.probe.pixel else { return };
        let settings = Viewport::render_settings(&self.state.settings, &self.state.split, p.half, p.size);
        let tracer = self.tracer.get_or_insert_with(|| Reference::new(&self.scene));
        self.probe.terms = super::probe::evaluate(tracer, &self.scene, &settings, p.pixel, p.size);
        self.probe.gpu = None;
        self.pending_probe = self.gpu.as_ref().and_then(|g| g.request_probe(p.half, p.pixel));
        self.probe.reference = self.reference.result.as_ref().and_then(|r| {
            let stale = r.key != self.keyed(p.half);
            ReferenceSample::at(&r.image, p.pixel, stale)
        });
    }

    fn collect_background_work(&mut self, ctx: &egui::Context) {
        if let Some(gpu) = &mut self.gpu {
            gpu.poll();
        }
        if let Some(pending) = &mut self.pending_probe {
            match pending.poll() {
                ReadState::Waiting => {}
                ReadState::Ready(sample) => {
                    self.probe.gpu = Some(sample);
                    self.pending_probe = None;
                }
                ReadState::Failed => self.pending_probe = None,
            }
        }
        if let Some(pending) = &mut self.pending_frame {
            match pending.poll() {
                ReadState::Waiting => {}
                ReadState::Ready(frame) => {
                    self.pending_frame = None;
                    if let Some(r) = &self.reference.result {
                        self.reference.stats = error_stats(&frame.quantity, &frame.aux, &r.image);
                    }
                }
                ReadState::Failed => self.pending_frame = None,
            }
        }
        if self.reference.poll() {
            self.reference_generation += 1;
            self.say("CPU reference ready: the error view compares with it", false);
            self.refresh_probe();
        }
        if let Some(rx) = &self.scene_load
            && let Ok((path, result)) = rx.try_recv()
        {
            self.scene_load = None;
            match result {
                Ok(scene) => self.use_scene(Some(path), scene),
                Err(e) => self.say(format!("{e}; the current scene is kept"), true),
            }
        }
        while let Ok(image) = self.screenshot_rx.try_recv() {
            self.save_screenshot(&image, ctx);
        }
    }

    fn use_scene(&mut self, path: Option<PathBuf>, scene: Scene) {
        let name = path.as_deref().map_or_else(|| "built-in".into(), display_name);
        let mut text = format!("scene: {name}, {} triangles", scene.triangle_count());
        if !scene.warnings.is_empty() {
            text += &format!(
                " ({} warnings: {})",
                scene.warnings.len(),
                scene.warnings.join("; ")
            );
        }
        if let Some(first) = scene.cameras.first() {
            self.state.settings.camera = CameraSettings {
                eye: first.camera.eye,
                target: first.camera.target,
                fovy_deg: first.camera.fovy_deg,
            };
        }
        if let Some(gpu) = &mut self.gpu {
            gpu.set_scene(&scene);
        }
        self.scene = Arc::new(scene);
        self.tracer = None;
        self.scene_name = name;
        self.state.settings.scene = path;
        self.reference.clear();
        self.reference_generation += 1;
        self.probe = Default::default();
        self.pending_probe = None;
        self.say(text, false);
    }

    /// Loads a scene on a thread; the current one stays until it succeeds.
    fn open_scene(&mut self, path: PathBuf, ctx: &egui::Context) {
        let (tx, rx) = std::sync::mpsc::channel();
        let ctx = ctx.clone();
        let thread_path = path.clone();
        let spawned = std::thread::Builder::new()
            .name("lumlab scene load".into())
            .spawn(move || {
                let result = crate::scene::load(&thread_path).map_err(|e| e.to_string());
                let _ = tx.send((thread_path, result));
                ctx.request_repaint();
            });
        match spawned {
            Ok(_) => {
                self.scene_load = Some(rx);
                self.say(format!("loading {}…", path.display()), false);
            }
            Err(e) => self.say(format!("cannot start loading: {e}"), true),
        }
    }

    fn start_reference(&mut self, ctx: &egui::Context) {
        if self.viewport_size.0 == 0 {
            return;
        }
        let settings = Viewport::render_settings(
            &self.state.settings,
            &self.state.split,
            Half::A,
            self.viewport_size,
        );
        self.reference
            .start(Arc::clone(&self.scene), &settings, self.viewport_size, ctx);
    }

    fn reset_view(&mut self) {
        self.state.settings.camera = self
            .scene
            .cameras
            .first()
            .map(|c| CameraSettings {
                eye: c.camera.eye,
                target: c.camera.target,
                fovy_deg: c.camera.fovy_deg,
            })
            .unwrap_or_default();
    }

    fn handle_dropped_files(&mut self, ctx: &egui::Context) {
        let dropped: Vec<PathBuf> = ctx.input(|i| {
            i.raw
                .dropped_files
                .iter()
                .map(|f| f.path().to_path_buf())
                .filter(|p| !p.as_os_str().is_empty())
                .collect()
        });
        for path in dropped {
            let ext = path
                .extension()
                .and_then(|e| e.to_str())
                .map(str::to_ascii_lowercase);
            match ext.as_deref() {
                Some("gltf" | "glb") => {
                    self.state.paths.scene_file = path.display().to_string();
                    self.open_scene(path, ctx);
                }
                Some("toml") => self.file_action(FileAction::LoadSettings(path), ctx),
                _ => self.say(
                    format!("'{}': drop a .gltf, .glb or .toml file", path.display()),
                    true,
                ),
            }
        }
    }

    fn handle_keys(&mut self, ctx: &egui::Context) {
        if ctx.egui_wants_keyboard_input() {
            return;
        }
        let cmd = Modifiers::COMMAND;
        let pressed =
            |m: Modifiers, k: Key| ctx.input_mut(|i| i.consume_shortcut(&KeyboardShortcut::new(m, k)));
        if pressed(cmd | Modifiers::SHIFT, Key::Z) || pressed(cmd, Key::Y) {
            self.undo.redo(&mut self.state.settings);
        }
        if pressed(cmd, Key::Z) {
            self.undo.undo(&mut self.state.settings);
        }
        if pressed(cmd, Key::S) {
            let path = PathBuf::from(self.state.paths.settings_file.trim());
            self.file_action(FileAction::SaveSettings(path), ctx);
        }
        if pressed(cmd, Key::O) {
            let path = PathBuf::from(self.state.paths.scene_file.trim());
            self.file_action(FileAction::OpenScene(path), ctx);
        }
        if pressed(Modifiers::NONE, Key::F1)
            || pressed(Modifiers::SHIFT, Key::Questionmark)
            || pressed(Modifiers::NONE, Key::Questionmark)
        {
            self.help_open = !self.help_open;
        }
        if pressed(Modifiers::NONE, Key::Escape) {
            if self.reference.is_running() {
                self.reference.cancel();
            } else {
                self.help_open = false;
            }
        }
        if pressed(Modifiers::NONE, Key::F5) && !self.reference.is_running() {
            self.start_reference(ctx);
        }
        if pressed(Modifiers::NONE, Key::F12) {
            let path = PathBuf::from(self.state.paths.screenshot_file.trim());
            self.file_action(FileAction::Screenshot(path), ctx);
        }
        if pressed(Modifiers::NONE, Key::R) {
            self.reset_view();
        }
        if pressed(Modifiers::NONE, Key::S) {
            self.state.split.enabled = !self.state.split.enabled;
        }
        if pressed(Modifiers::NONE, Key::F9) {
            let show = !(self.state.panels.settings || self.state.panels.analysis);
            self.state.panels.settings = show;
            self.state.panels.analysis = show;
        }
        let step = if pressed(Modifiers::SHIFT, Key::V) {
            DebugView::ALL.len() - 1
        } else if pressed(Modifiers::NONE, Key::V) {
            1
        } else {
            0
        };
        if step != 0 {
            let view = &mut self.state.settings.view.mode;
            let i = DebugView::ALL.iter().position(|v| v == view).unwrap_or(0);
            *view = DebugView::ALL[(i + step) % DebugView::ALL.len()];
        }
    }

    fn file_action(&mut self, action: FileAction, ctx: &egui::Context) {
        match action {
            FileAction::SaveSettings(path) => match self.state.settings.save(&path) {
                Ok(()) => self.say(format!("settings saved to {}", path.display()), false),
                Err(e) => self.say(e.to_string(), true),
            },
            FileAction::LoadSettings(path) => match crate::settings::Settings::load(&path) {
                Ok(loaded) => {
                    let scene_changes = loaded.scene != self.state.settings.scene;
                    let scene = loaded.scene.clone();
                    self.state.settings = loaded;
                    self.say(
                        format!("settings loaded from {} (Ctrl+Z to undo)", path.display()),
                        false,
                    );
                    if scene_changes {
                        match scene {
                            Some(p) => self.open_scene(p, ctx),
                            None => self.use_scene(None, crate::scene::default_scene()),
                        }
                    }
                }
                Err(e) => self.say(e.to_string(), true),
            },
            FileAction::OpenScene(path) => {
                if path.as_os_str().is_empty() {
                    self.say("type or browse to a .gltf/.glb file first", true);
                } else {
                    self.open_scene(path, ctx);
                }
            }
            FileAction::BuiltInScene => self.use_scene(None, crate::scene::default_scene()),
            FileAction::Screenshot(path) => {
                self.screenshot_path = Some(path);
                let tx = self.screenshot_tx.clone();
                let wake = ctx.clone();
                ctx.request_screenshot(move |image| {
                    let _ = tx.send(image);
                    wake.request_repaint();
                });
            }
            FileAction::ExportExr(path) => {
                let result = self.export_exr(&path);
                match result {
                    Ok(()) => self.say(format!("linear values written to {}", path.display()), false),
                    Err(e) => self.say(crate::cli::one_line(&e), true),
                }
            }
            FileAction::ResetEverything => {
                let paths = self.state.paths.clone();
                self.state = State {
                    paths,
                    ..State::default()
                };
                ctx.memory_mut(|m| *m = Default::default());
                self.use_scene(None, crate::scene::default_scene());
                self.say("everything reset (Ctrl+Z brings the settings back)", false);
            }
        }
    }

    fn export_exr(&self, path: &Path) -> anyhow::Result<()> {
        crate::image_io::ImageFormat::of_path(path)?;
        let half = self
            .gpu
            .as_ref()
            .and_then(|g| g.half(Half::A))
            .filter(|h| h.report.size != (0, 0))
            .ok_or_else(|| anyhow::anyhow!("no image to export yet"))?;
        let renderer = half.renderer();
        let (w, h) = half.report.size;
        let texels = renderer.read_quantity();
        let flat: Vec<f32> = texels.iter().flatten().copied().collect();
        let image = image::Rgba32FImage::from_raw(w, h, flat)
            .ok_or_else(|| anyhow::anyhow!("the image changed size while reading it; try again"))?;
        crate::image_io::write_exr(path, &image)
    }

    fn save_screenshot(&mut self, image: &egui::ColorImage, ctx: &egui::Context) {
        let scripted = self.script.as_ref().and_then(|s| s.screenshot.clone());
        let Some(path) = scripted.or_else(|| self.screenshot_path.take()) else {
            return;
        };
        let [w, h] = image.size;
        let mut rgba = image::RgbaImage::new(w as u32, h as u32);
        for (out, c) in rgba.pixels_mut().zip(&image.pixels) {
            // The window is opaque: the PNG is too.
            *out = image::Rgba([c.r(), c.g(), c.b(), 255]);
        }
        let result = crate::image_io::write_png_rgba8(&path, &rgba);
        if self.script.is_some() {
            if let Err(e) = &result
                && let Ok(mut outcome) = self.outcome.lock()
            {
                *outcome = Some(crate::cli::one_line(e));
            }
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            return;
        }
        match result {
            Ok(()) => self.say(format!("screenshot saved to {}", path.display()), false),
            Err(e) => self.say(crate::cli::one_line(&e), true),
        }
    }

    fn run_script(&mut self, ctx: &egui::Context) {
        let Some(script) = &mut self.script else { return };
        ctx.request_repaint();
        if script.requested || self.frames < script.frames as u64 {
            return;
        }
        script.requested = true;
        if script.screenshot.is_some() {
            let tx = self.screenshot_tx.clone();
            let wake = ctx.clone();
            ctx.request_screenshot(move |image| {
                let _ = tx.send(image);
                wake.request_repaint();
            });
        } else {
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        }
    }

    /// Repaints soon while background work is on its way; otherwise only on input.
    fn schedule_repaint(&mut self, ctx: &egui::Context) {
        let gpu_waiting = self.gpu.as_mut().is_some_and(GpuViews::poll);
        if gpu_waiting || self.pending_probe.is_some() || self.pending_frame.is_some() {
            ctx.request_repaint_after(Duration::from_millis(16));
        }
        if self.reference.is_running() || self.scene_load.is_some() {
            ctx.request_repaint_after(Duration::from_millis(100));
        }
    }
}

/// A collapsible section of a side panel, its title in heading size.
fn section(ui: &mut egui::Ui, title: &str, open: bool, add: impl FnOnce(&mut egui::Ui)) {
    egui::CollapsingHeader::new(RichText::new(title).heading())
        .default_open(open)
        .show(ui, add);
}

fn display_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

impl eframe::App for LabApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.show(ui);
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        if self.script.is_none() {
            self.state.store(storage);
        }
    }

    fn persist_egui_memory(&self) -> bool {
        self.script.is_none()
    }

    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        visuals.panel_fill.to_normalized_gamma_f32()
    }
}
