//! The app itself: a small shell that owns the persisted state, the
//! renderers and the background jobs, lays out the panels and routes the
//! commands they emit.
//!
//! Where things go:
//! - a new action: a [`Command`] variant (`command.rs`), carried out in
//!   `lab/apply.rs`, the one place that changes the app's state;
//! - a new key: a row in `shortcuts.rs` (the help window is made from it);
//! - a new panel: its own file with a `View`, placed in `lab/panels.rs`;
//! - new background work: `lab/jobs.rs`.

mod apply;
mod desktop;
mod drag_bench;
mod image;
mod jobs;
mod panels;
mod tour;

pub use drag_bench::DragTarget;

use super::command::{Command, SceneView};
use super::energy::EnergyPanel;
use super::files::FilesPanel;
use super::gpu_view::GpuViews;
use super::lecture::LecturePanel;
use super::probe::Probe;
use super::reference::ReferencePanel;
use super::state::State;
use super::timings::FrameClock;
use super::toast::Toasts;
use super::undo::UndoStack;
use super::{LaunchOptions, Preloaded, shortcuts};
use crate::presets::Half;
use crate::reference::Reference;
use crate::scene::Scene;
use crate::scene::framing::with_ground;
use crate::settings::{GroundSettings, Settings};
use crate::tour::TourScene;
use crate::tr;
use jobs::{Jobs, Script};
use std::collections::VecDeque;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// Which scene is shown: a built-in one, named in the app's language each
/// time the name is shown, or a file's.
#[derive(Clone, Debug, PartialEq)]
enum ShownScene {
    BuiltIn(TourScene),
    File(String),
}

impl ShownScene {
    fn from_path(path: Option<&Path>) -> Self {
        path.map_or(Self::BuiltIn(TourScene::BuiltIn), |p| Self::File(display_name(p)))
    }

    fn name(&self) -> String {
        match self {
            Self::BuiltIn(TourScene::BuiltIn) => tr!("scene-built-in"),
            Self::BuiltIn(TourScene::Spheres) => tr!("scene-lecture-spheres"),
            Self::File(name) => name.clone(),
        }
    }
}

/// A one-line message in the status bar.
struct Status {
    text: String,
    error: bool,
}

pub struct LabApp {
    state: State,
    gpu: Option<GpuViews>,
    /// The scene drawn: the file's, with the ground the settings ask for.
    scene: Arc<Scene>,
    /// The scene as loaded, and the ground settings `scene` was made with.
    file_scene: Arc<Scene>,
    ground: GroundSettings,
    shown: ShownScene,
    undo: UndoStack,
    probe: Probe,
    /// The scene prepared for ray tracing, built at the first probe.
    tracer: Option<Reference>,
    energy: EnergyPanel,
    reference: ReferencePanel,
    reference_generation: u64,
    files: FilesPanel,
    /// The lecture tour and the step shown.
    lecture: LecturePanel,
    toasts: Toasts,
    /// The settings as in the settings file last loaded or saved (the
    /// title's mark compares with them); None before any.
    saved: Option<Settings>,
    /// The title last given to the window.
    title_sent: Option<String>,
    clock: FrameClock,
    status: Option<Status>,
    help_open: bool,
    jobs: Jobs,
    script: Option<Script>,
    drag_bench: Option<drag_bench::DragBench>,
    /// The host clears the window to the panels' colour (eframe, through
    /// `clear_color`): the panels then paint no fill of their own.
    window_cleared_to_panel_fill: bool,
    outcome: Arc<Mutex<Option<String>>>,
    frames: u64,
    viewport_size: (u32, u32),
    viewport_rect: egui::Rect,
    styled: bool,
    /// Commands emitted and not yet applied.
    queue: Vec<Command>,
    /// The last commands applied, newest last.
    applied: VecDeque<Command>,
    /// Physically impossible parts of the set-up (a light inside an object,
    /// a sphere light cutting a surface or holding the camera), for the
    /// light, camera and scene they were computed for.
    impossible: Option<(PlausibilityKey, Vec<String>)>,
}

/// What the plausibility check depends on: the light, the eye and the
/// drawn scene (by identity: a new scene is a new `Arc`, and holding the
/// old one keeps its address from being reused).
type PlausibilityKey = (glam::Vec3, f32, glam::Vec3, Arc<Scene>);

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
    /// For a host that clears the window to [`eframe::App::clear_color`],
    /// the panels' fill (eframe does): the panels then paint none.
    pub(super) fn on_window_cleared_to_panel_fill(mut self) -> Self {
        self.window_cleared_to_panel_fill = true;
        self
    }

    /// Commands kept in [`LabApp::applied_commands`].
    const APPLIED_KEPT: usize = 64;

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
        // Else the language set before (the system's, by `app::run`).
        if let Some(language) = state.language {
            crate::i18n::set_current(language);
        }
        if let Some(settings) = preloaded.settings {
            state.settings = settings;
        }
        let mut status = None;
        let (path, scene) = match preloaded.scene {
            Some((path, scene)) => (Some(path), scene),
            None => match state.settings.scene.clone() {
                Some(path) => match crate::scene::load(&path) {
                    Ok(scene) => (Some(path), scene),
                    Err(e) => {
                        status = Some(Status {
                            text: tr!("error-showing-built-in", message = e.to_string()),
                            error: true,
                        });
                        (None, crate::scene::default_scene())
                    }
                },
                None => (None, crate::scene::default_scene()),
            },
        };
        // The same rule as a scene opened later: its own view, unless the
        // settings were saved for it.
        adopt_scene(&mut state.settings, path.as_deref(), &scene);
        let ground = state.settings.ground;
        let file_scene = Arc::new(scene);
        let scene = Arc::new(with_ground((*file_scene).clone(), &ground));
        let gpu = render_state.map(|rs| GpuViews::new(rs, &scene, options.drag_device));
        if gpu.is_none() {
            return Err("eframe started without the wgpu renderer".into());
        }
        let script = scripted.then(|| Script::new(options));
        let mut queue = Vec::new();
        let tour = match preloaded.tour {
            Some(tour) => {
                // `--tour`: the lecture opens at its first step.
                queue.push(Command::TourStep(0));
                tour
            }
            None => crate::tour::Tour::built_in().unwrap_or_else(|e| {
                status = Some(Status {
                    text: e.to_string(),
                    error: true,
                });
                crate::tour::Tour { steps: Vec::new() }
            }),
        };
        let saved = Settings::load(Path::new(state.paths.settings_file.trim())).ok();
        Ok(Self {
            undo: UndoStack::new(&state.settings),
            state,
            gpu,
            scene,
            file_scene,
            ground,
            shown: ShownScene::from_path(path.as_deref()),
            probe: Probe::default(),
            tracer: None,
            energy: EnergyPanel::default(),
            reference: ReferencePanel::default(),
            reference_generation: 1,
            files: FilesPanel::default(),
            lecture: LecturePanel::new(tour),
            toasts: Toasts::default(),
            saved,
            title_sent: None,
            clock: FrameClock::default(),
            status,
            help_open: false,
            jobs: Jobs::default(),
            script,
            drag_bench: options
                .drag_bench_frames
                .map(|frames| drag_bench::DragBench::new(frames, options.drag_bench_target)),
            window_cleared_to_panel_fill: false,
            outcome,
            frames: 0,
            viewport_size: (0, 0),
            viewport_rect: egui::Rect::NOTHING,
            styled: false,
            queue,
            applied: VecDeque::new(),
            impossible: None,
        })
    }

    /// The settings as the panels left them.
    pub fn settings(&self) -> &Settings {
        &self.state.settings
    }

    pub fn settings_mut(&mut self) -> &mut Settings {
        &mut self.state.settings
    }

    /// Queues a command, applied on the next frame as if a panel or a key
    /// had emitted it (the lecture tour and the tests drive the lab so).
    pub fn emit(&mut self, command: Command) {
        self.queue.push(command);
    }

    /// The last commands applied (at most 64), oldest first.
    pub fn applied_commands(&self) -> impl Iterator<Item = &Command> {
        self.applied.iter()
    }

    /// The help window is open.
    pub fn help_open(&self) -> bool {
        self.help_open
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

    /// The image a half shows and the settings it was drawn with (see
    /// `GpuViews::shown_image`).
    pub fn shown_image(&self, half: Half) -> Option<(Settings, ::image::RgbaImage)> {
        self.gpu.as_ref()?.shown_image(half)
    }

    /// The ray-traced accumulation of the image a half shows, as the
    /// viewport's label gives it (None: V from the shadow map).
    pub fn shown_accumulation(&self, half: Half) -> Option<crate::gpu::raytrace::Accumulation> {
        self.gpu.as_ref()?.accumulation(half)
    }

    /// The scene the viewport draws (the file's, with the ground).
    pub fn drawn_scene(&self) -> &Scene {
        &self.scene
    }

    /// What half A's last image drew (see `FrameReport`).
    pub fn report(&self) -> Option<&crate::gpu::FrameReport> {
        self.gpu.as_ref()?.half(Half::A).map(|h| &h.report)
    }

    /// Triangles of the scene's simplified meshes and of its full ones, once
    /// built and uploaded (large scenes only).
    pub fn simplified_meshes(&self) -> Option<crate::scene::simplify::TriangleCounts> {
        self.gpu.as_ref()?.simplified
    }

    /// Whether drag frames render on a device of their own.
    pub fn has_drag_device(&self) -> bool {
        self.gpu.as_ref().is_some_and(GpuViews::has_drag_device)
    }

    /// The renderer of half A (B is the split view's right half).
    pub fn renderer(&self) -> Option<&crate::gpu::Renderer> {
        self.renderer_of(Half::A)
    }

    /// A half's renderer (B exists while the split view is on).
    pub fn renderer_of(&self, half: Half) -> Option<&crate::gpu::Renderer> {
        self.gpu.as_ref().and_then(|g| g.renderer(half))
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
        self.renders_of(Half::A)
    }

    /// Images a half has shown so far.
    pub fn renders_of(&self, half: Half) -> u64 {
        self.gpu.as_ref().map_or(0, |g| g.renders(half))
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

    /// A message in the status line; an error also as a toast.
    fn say(&mut self, text: impl Into<String>, error: bool) {
        let text = text.into();
        if error {
            self.toasts.push(text.clone());
        }
        self.status = Some(Status { text, error });
    }

    /// One frame of the whole window: input becomes commands, panels emit
    /// theirs, and each batch is applied before what depends on it is drawn.
    pub fn show(&mut self, ui: &mut egui::Ui) {
        let start = self.clock.begin();
        let ctx = ui.ctx().clone();
        if !self.styled {
            set_style(&ctx);
            self.styled = true;
        }
        self.frames += 1;
        self.collect_background_work(&ctx);
        self.take_dropped_files(&ctx);
        self.queue.extend(shortcuts::pressed(&ctx));
        self.apply_queued(&ctx);

        egui::Panel::top("top bar")
            .frame(self.panel_frame(ui))
            .show(ui, |ui| self.top_bar(ui));
        egui::Panel::bottom("status bar")
            .frame(self.panel_frame(ui))
            .show(ui, |ui| self.status_bar(ui));
        self.lecture_panel(ui);
        self.side_panels(ui);
        self.apply_queued(&ctx);
        self.sync_ground();
        let response = egui::CentralPanel::no_frame()
            .show(ui, |ui| self.viewport(ui))
            .inner;
        self.after_viewport(response);
        shortcuts::help_window(&ctx, &mut self.help_open);
        self.desktop(&ctx);
        self.apply_queued(&ctx);

        let busy = ctx.input(|i| i.pointer.any_down()) || ctx.egui_wants_keyboard_input();
        if !busy {
            // Not during a drag: the check reads every triangle near the light.
            self.check_plausibility();
        }
        let now = ctx.input(|i| i.time);
        if self.undo.observe(&self.state.settings, busy, now) {
            ctx.request_repaint_after(Duration::from_secs_f64(UndoStack::QUIET_S));
        }
        self.schedule_repaint(&ctx);
        self.run_script(&ctx);
        self.run_drag_bench(&ctx);
        self.clock.end(start);
    }

    fn apply_queued(&mut self, ctx: &egui::Context) {
        for command in std::mem::take(&mut self.queue) {
            if self.applied.len() == Self::APPLIED_KEPT {
                self.applied.pop_front();
            }
            self.applied.push_back(command.clone());
            self.apply(command, ctx);
        }
    }

    /// Re-checks the set-up when the light, the eye or the scene changed;
    /// the status bar shows what is impossible.
    fn check_plausibility(&mut self) {
        let s = &self.state.settings;
        let unchanged = self.impossible.as_ref().is_some_and(|((q, r, eye, scene), _)| {
            (*q, *r, *eye) == (s.light.position, s.light.radius_m, s.camera.eye)
                && Arc::ptr_eq(scene, &self.scene)
        });
        if !unchanged {
            let lines = crate::scene::plausibility::impossible_setups(&self.scene, s);
            let key = (
                s.light.position,
                s.light.radius_m,
                s.camera.eye,
                Arc::clone(&self.scene),
            );
            self.impossible = Some((key, lines));
        }
    }

    /// The impossible parts of the set-up, one line each (empty: none).
    pub fn impossible_setups(&self) -> &[String] {
        self.impossible
            .as_ref()
            .map_or(&[], |(_, lines)| lines.as_slice())
    }

    /// What commands need to know of the scene shown.
    fn scene_view(&self) -> SceneView {
        SceneView {
            home: self.scene.home_camera(),
            scale: self.scene.scale,
            bounds: self.scene.model_bounds(),
            cameras: self.scene.cameras.iter().map(|c| c.camera).collect(),
        }
    }
}

/// Makes `settings` show `scene` (at `path`; None: built-in): its home
/// view and its light (`scene::framing::adopt`), unless the settings were
/// saved for this very scene (they then carry the view and light the user
/// left). The one rule for a scene opened at start-up, from the Files
/// panel, by drag and drop or with a settings file; the command line
/// follows it too.
fn adopt_scene(settings: &mut Settings, path: Option<&Path>, scene: &Scene) {
    if settings.scene.as_deref() != path {
        crate::scene::framing::adopt(settings, scene);
    }
    settings.scene = path.map(Path::to_path_buf);
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

    fn raw_input_hook(&mut self, ctx: &egui::Context, raw_input: &mut egui::RawInput) {
        if let Some(bench) = &mut self.drag_bench {
            let target = match bench.target() {
                DragTarget::Orbit => Some(self.viewport_rect),
                DragTarget::Light => ctx.read_response(super::viewport::gizmo_id()).map(|r| r.rect),
                DragTarget::Slider => super::light::radius_slider_rect(ctx),
            };
            let gpu = self.gpu.as_ref();
            let a = gpu.and_then(|g| g.half(Half::A));
            let before = drag_bench::FrameBefore {
                scale: gpu.map_or(1.0, |g| g.rendered_scale(Half::A)),
                ui_ms: self.clock.ui_ms,
                gpu_ms: a.and_then(|h| h.times).map_or(0.0, |t| t.total_ms()),
                shadow_ms: a.and_then(|h| h.times?.shadow_ms).unwrap_or(0.0),
                map_side: a
                    .filter(|h| !h.report.shadow_map_unused)
                    .map_or(0, |h| h.report.resolution),
                images: a.map_or(0, |h| h.renders),
                simplifying: gpu.is_some_and(GpuViews::simplifying),
                simplified: a.is_some_and(|h| h.report.simplified_triangles.is_some()),
            };
            bench.inject(raw_input, target, before);
        }
    }

    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        visuals.panel_fill.to_normalized_gamma_f32()
    }
}

/// The path a command names (remembered as the kind's `last`), or else
/// the kind's file used last.
fn chosen(path: Option<PathBuf>, last: &mut String) -> PathBuf {
    match path {
        Some(path) => {
            *last = path.display().to_string();
            path
        }
        None => PathBuf::from(last.trim()),
    }
}
