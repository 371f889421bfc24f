//! Work that finishes on a later frame: a scene loading on a thread, GPU
//! readbacks for the probe and the error statistics, screenshots, the
//! reference job's results; dropped files; and the scripted run.

use super::super::LaunchOptions;
use super::super::command::Command;
use super::super::gpu_view::GpuViews;
use super::super::reference::error_stats;
use super::super::view_readback::PendingProbe;
use super::LabApp;
use crate::gpu::PendingTexels;
use crate::gpu::readback::ReadState;
use crate::scene::Scene;
use crate::tr;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::mpsc::{Receiver, Sender};
use std::time::Duration;

type SceneLoad = (PathBuf, Result<Scene, String>);

/// A run driven by `--screenshot` / `--quit-after-frames`.
pub(super) struct Script {
    screenshot: Option<PathBuf>,
    frames: u32,
    requested: bool,
}

impl Script {
    pub(super) fn new(options: &LaunchOptions) -> Self {
        Self {
            screenshot: options.screenshot.clone(),
            // A drag bench quits when it has measured its frames.
            frames: options
                .quit_after_frames
                .unwrap_or(match options.drag_bench_frames {
                    Some(_) => u32::MAX,
                    None => LaunchOptions::DEFAULT_SCREENSHOT_FRAMES,
                })
                .max(1),
            requested: false,
        }
    }
}

/// The background jobs' handles.
pub(super) struct Jobs {
    scene_load: Option<Receiver<SceneLoad>>,
    pub(super) pending_probe: Option<PendingProbe>,
    pub(super) pending_frame: Option<PendingTexels>,
    /// The image read back for auto exposure.
    pending_exposure: Option<PendingTexels>,
    screenshot_tx: Sender<Arc<egui::ColorImage>>,
    screenshot_rx: Receiver<Arc<egui::ColorImage>>,
    screenshot_path: Option<PathBuf>,
}

impl Default for Jobs {
    fn default() -> Self {
        let (screenshot_tx, screenshot_rx) = std::sync::mpsc::channel();
        Self {
            scene_load: None,
            pending_probe: None,
            pending_frame: None,
            pending_exposure: None,
            screenshot_tx,
            screenshot_rx,
            screenshot_path: None,
        }
    }
}

impl Jobs {
    /// Starts loading `path` on a thread.
    pub(super) fn load_scene(&mut self, path: PathBuf, ctx: &egui::Context) -> std::io::Result<()> {
        let (tx, rx) = std::sync::mpsc::channel();
        let ctx = ctx.clone();
        std::thread::Builder::new()
            .name("lumlab scene load".into())
            .spawn(move || {
                let result = crate::scene::load(&path).map_err(|e| e.to_string());
                let _ = tx.send((path, result));
                ctx.request_repaint();
            })?;
        self.scene_load = Some(rx);
        Ok(())
    }

    /// Asks egui for a picture of the window, to be saved to `path`.
    pub(super) fn request_screenshot(&mut self, path: PathBuf, ctx: &egui::Context) {
        self.screenshot_path = Some(path);
        let tx = self.screenshot_tx.clone();
        let wake = ctx.clone();
        ctx.request_screenshot(move |image| {
            let _ = tx.send(image);
            wake.request_repaint();
        });
    }
}

impl LabApp {
    pub(super) fn collect_background_work(&mut self, ctx: &egui::Context) {
        if let Some(gpu) = &mut self.gpu {
            gpu.poll();
        }
        if let Some(pending) = &mut self.jobs.pending_probe {
            match pending.poll() {
                ReadState::Waiting => {}
                ReadState::Ready(sample) => {
                    self.probe.gpu = Some(sample);
                    self.jobs.pending_probe = None;
                }
                ReadState::Failed => self.jobs.pending_probe = None,
            }
        }
        if let Some(pending) = &mut self.jobs.pending_frame {
            match pending.poll() {
                ReadState::Waiting => {}
                ReadState::Ready(quantity) => {
                    self.jobs.pending_frame = None;
                    if let Some(r) = &self.reference.result {
                        self.reference.stats = error_stats(&quantity, &r.image);
                    }
                }
                ReadState::Failed => self.jobs.pending_frame = None,
            }
        }
        if let Some(pending) = &mut self.jobs.pending_exposure {
            match pending.poll() {
                ReadState::Waiting => {}
                ReadState::Ready(quantity) => {
                    self.jobs.pending_exposure = None;
                    self.set_exposure_from(&quantity);
                }
                ReadState::Failed => self.jobs.pending_exposure = None,
            }
        }
        if self.reference.poll() {
            self.reference_generation += 1;
            self.say(tr!("status-reference-ready"), false);
            self.refresh_probe();
        }
        if let Some(rx) = &self.jobs.scene_load
            && let Ok((path, result)) = rx.try_recv()
        {
            self.jobs.scene_load = None;
            match result {
                Ok(scene) => self.use_scene(Some(path), scene),
                Err(e) => self.say(tr!("error-scene-kept", message = e.to_string()), true),
            }
        }
        while let Ok(image) = self.jobs.screenshot_rx.try_recv() {
            self.save_screenshot(&image, ctx);
        }
    }

    /// Reads half A's image back for [`Command::AutoExposure`].
    pub(super) fn start_auto_exposure(&mut self) {
        self.jobs.pending_exposure = self.gpu.as_ref().and_then(GpuViews::request_frame);
        if self.jobs.pending_exposure.is_none() {
            self.say(tr!("status-exposure-no-image"), true);
        }
    }

    /// The exposure that shows the lit pixels' bright end near white.
    fn set_exposure_from(&mut self, quantity: &[[f32; 4]]) {
        let lit: Vec<f64> = quantity
            .iter()
            .filter(|q| q[3] > 0.0)
            .map(|q| crate::physics::colour::luminance([q[0] as f64, q[1] as f64, q[2] as f64]))
            .collect();
        match crate::physics::display::auto_exposure_ev(&lit) {
            Some(ev) => {
                self.settings_in_one_step(|s| s.view.exposure_ev = ev as f32);
                self.say(tr!("status-exposure", ev = format!("{ev:+.2}")), false);
            }
            None => self.say(tr!("status-exposure-nothing-lit"), true),
        }
    }

    /// Files dropped on the window become the commands that open them.
    pub(super) fn take_dropped_files(&mut self, ctx: &egui::Context) {
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
                Some("gltf" | "glb") => self.emit(Command::OpenScene(Some(path))),
                Some("toml") => self.emit(Command::LoadSettings(Some(path))),
                _ => self.say(
                    tr!("status-drop-unknown", path = path.display().to_string()),
                    true,
                ),
            }
        }
    }

    fn save_screenshot(&mut self, image: &egui::ColorImage, ctx: &egui::Context) {
        let Some(path) = self.jobs.screenshot_path.take() else {
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
            Ok(()) => {
                let path = path.display().to_string();
                self.say(tr!("status-screenshot-saved", path = path), false)
            }
            Err(e) => self.say(super::desktop::file_error(&path, crate::cli::one_line(&e)), true),
        }
    }

    /// The scripted run: after its frames, a screenshot command (the same
    /// as F12's) or closing the window.
    /// `--drag-bench`: frames follow one another; once measured, the
    /// result on standard output and the window closes.
    pub(super) fn run_drag_bench(&mut self, ctx: &egui::Context) {
        let own_device = self.has_drag_device();
        let Some(bench) = &mut self.drag_bench else { return };
        ctx.request_repaint();
        if let Some(line) = bench.report(self.viewport_size) {
            let device = if own_device {
                "a device of their own"
            } else {
                "the window's device"
            };
            println!("{line}; drag frames on {device}");
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        }
    }

    pub(super) fn run_script(&mut self, ctx: &egui::Context) {
        let Some(script) = &mut self.script else { return };
        ctx.request_repaint();
        if script.requested || self.frames < script.frames as u64 {
            return;
        }
        script.requested = true;
        match script.screenshot.clone() {
            Some(path) => self.emit(Command::Screenshot(Some(path))),
            None => ctx.send_viewport_cmd(egui::ViewportCommand::Close),
        }
    }

    /// Repaints soon while background work is on its way; otherwise only on input.
    pub(super) fn schedule_repaint(&mut self, ctx: &egui::Context) {
        let gpu_waiting = self.gpu.as_mut().is_some_and(GpuViews::poll);
        if gpu_waiting
            || self.jobs.pending_probe.is_some()
            || self.jobs.pending_frame.is_some()
            || self.jobs.pending_exposure.is_some()
        {
            ctx.request_repaint_after(Duration::from_millis(16));
        }
        if self.reference.is_running() || self.jobs.scene_load.is_some() {
            ctx.request_repaint_after(Duration::from_millis(100));
        }
    }
}
