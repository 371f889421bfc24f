//! The lab's window: an eframe app on the wgpu renderer, with our own device
//! (the adapter's real limits and timestamp queries). The only module that
//! knows egui and eframe.
//!
//! Layout: the settings panels on the left (one file each: `light`,
//! `material`, `shadow`, `view`, plus presets and `files`), the analysis on
//! the right (`probe`, `energy`, `reference`, `timings`), the renderer's
//! image in the middle (`viewport`, drawn by `gpu_view`). What is persisted
//! (`state`) is kept apart from every GPU object.
//!
//! Every action is a [`Command`] (`command`): panels, shortcuts
//! (`shortcuts`, one table for the keys and the help), dropped files and
//! scripts emit them; `lab` applies them in one place and records undo.
//!
//! The desktop around it: file dialogs and the File menu (`files`), recent
//! files (`recent`), error toasts (`toast`), the window's icon (`icon`) and
//! a title naming the scene.

mod camera_control;
mod colour;
mod command;
mod drag_device;
mod energy;
mod files;
mod gpu_view;
pub mod icon;
mod lab;
mod lecture;
mod legend;
mod light;
mod material;
mod names;
mod probe;
mod recent;
mod reference;
mod render_scale;
mod scene_panel;
mod shadow;
mod shortcuts;
mod state;
mod timings;
mod toast;
mod undo;
mod view;
mod view_readback;
mod viewport;
mod viewport_image;
mod visibility;
mod widgets;

pub use command::Command;
pub use drag_device::DragDevice;
pub use files::FileAction;
pub use lab::{DragTarget, LabApp};
pub use lecture::panel_title;
pub use probe::{GpuSample, ProbePixel, ProbeTerms, evaluate as probe_terms};
pub use reference::{ErrorStats, ReferenceFn};
pub use shortcuts::{GESTURES, SHORTCUTS, Shortcut};
pub use state::{MemoryStorage, SplitLayout, State};

use crate::scene::Scene;
use crate::settings::Settings;
use anyhow::Context;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

/// A panel: draws itself into a `Ui`, changing what it borrows.
pub trait View {
    fn ui(&mut self, ui: &mut egui::Ui);
}

/// What the command line asks of the window.
#[derive(Clone, Debug, Default)]
pub struct LaunchOptions {
    /// `--settings FILE`: start from these settings instead of the stored ones.
    pub settings: Option<PathBuf>,
    /// `--scene FILE`: open this glTF/GLB.
    pub scene: Option<PathBuf>,
    /// `--screenshot FILE.png`: save a screenshot of the window, then quit.
    pub screenshot: Option<PathBuf>,
    /// `--quit-after-frames N`: quit (or take the screenshot) after N frames.
    pub quit_after_frames: Option<u32>,
    /// `--tour [FILE]`: open at the first step of the lecture tour (None
    /// inside: the built-in tour).
    pub tour: Option<Option<PathBuf>>,
    /// `--drag-bench N` (hidden): drag for N frames, print the frame rate, quit.
    pub drag_bench_frames: Option<u32>,
    /// `--drag-bench-target` (hidden): what the drag bench drags.
    pub drag_bench_target: DragTarget,
    /// `--drag-device` (hidden): where drag frames render.
    pub drag_device: DragDevice,
}

impl LaunchOptions {
    /// Frames before a scripted screenshot when `--quit-after-frames` is not given.
    pub const DEFAULT_SCREENSHOT_FRAMES: u32 = 3;

    /// A scripted run (screenshot or a frame count) neither reads nor
    /// writes the stored state, so that it is reproducible.
    pub fn is_scripted(&self) -> bool {
        self.screenshot.is_some() || self.quit_after_frames.is_some() || self.drag_bench_frames.is_some()
    }
}

/// What the flags name, loaded before any window opens so that a bad file
/// is a one-line error.
#[derive(Default)]
pub struct Preloaded {
    pub settings: Option<Settings>,
    pub scene: Option<(PathBuf, Scene)>,
    /// The tour `--tour` asked for.
    pub tour: Option<crate::tour::Tour>,
}

/// Reads the settings and scene files the options name.
pub fn preload(options: &LaunchOptions) -> anyhow::Result<Preloaded> {
    let mut settings = match &options.settings {
        Some(path) => Some(Settings::load(path)?),
        None => None,
    };
    let scene_path = options
        .scene
        .clone()
        .or_else(|| settings.as_ref().and_then(|s| s.scene.clone()));
    let scene = match scene_path {
        Some(path) => {
            let scene = crate::scene::load(&path)?;
            if let Some(s) = &mut settings {
                s.scene = Some(path.clone());
            }
            Some((path, scene))
        }
        None => None,
    };
    if let Some(path) = &options.screenshot {
        match crate::image_io::ImageFormat::of_path(path)? {
            crate::image_io::ImageFormat::Png => {}
            crate::image_io::ImageFormat::Exr => {
                anyhow::bail!("--screenshot '{}' must end in .png", path.display())
            }
        }
    }
    let tour = match &options.tour {
        Some(Some(path)) => Some(crate::tour::Tour::load(path)?),
        Some(None) => Some(crate::tour::Tour::built_in()?),
        None => None,
    };
    Ok(Preloaded {
        settings,
        scene,
        tour,
    })
}

/// The app id: desktops group the lab's windows under it and match it to
/// `assets/lumlab.desktop` (X11 `WM_CLASS`, Wayland `app_id`).
pub const APP_ID: &str = "lumlab";

/// Hint appended to the errors that keep the window from opening.
const HEADLESS_HINT: &str = "for images without a window use 'lumlab render --out FILE.png'";

/// Fails early, with one clear line, when there is no display to open a window on.
fn check_display() -> anyhow::Result<()> {
    if cfg!(target_os = "linux") {
        let set = |name: &str| std::env::var_os(name).is_some_and(|v| !v.is_empty());
        if !set("DISPLAY") && !set("WAYLAND_DISPLAY") {
            anyhow::bail!("no display (DISPLAY and WAYLAND_DISPLAY are unset); {HEADLESS_HINT}");
        }
    }
    Ok(())
}

/// Opens the lab and runs until its window closes.
pub fn run(options: LaunchOptions) -> anyhow::Result<()> {
    let preloaded = preload(&options)?;
    // The text's language until the stored state names the one picked.
    crate::i18n::set_current(crate::i18n::system_language());
    check_display()?;
    // No adapter: say so (and what to install) before eframe tries.
    crate::gpu::context::pick_adapter(&crate::gpu::context::instance())
        .map_err(|e| anyhow::anyhow!("{e}; {HEADLESS_HINT}"))?;

    let mut setup = egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    setup.instance_descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
    setup.device_descriptor = Arc::new(crate::gpu::context::device_descriptor);
    let scripted = options.is_scripted();
    // The title names the scene from the first frame on (`LabApp::title`).
    let mut viewport = egui::ViewportBuilder::default()
        .with_title("lumlab")
        .with_app_id(APP_ID)
        .with_inner_size([1600.0, 900.0])
        .with_min_inner_size([480.0, 320.0])
        .with_drag_and_drop(true);
    if let Some(icon) = icon::window_icon() {
        viewport = viewport.with_icon(icon);
    }
    let native = eframe::NativeOptions {
        viewport,
        wgpu_options: egui_wgpu::WgpuConfiguration {
            wgpu_setup: egui_wgpu::WgpuSetup::CreateNew(setup),
            ..Default::default()
        },
        persist_window: !scripted,
        ..Default::default()
    };
    let outcome: Arc<Mutex<Option<String>>> = Arc::default();
    let app_outcome = Arc::clone(&outcome);
    eframe::run_native(
        "lumlab",
        native,
        Box::new(move |cc| {
            let app = LabApp::new(
                cc.wgpu_render_state.clone(),
                cc.storage,
                &options,
                preloaded,
                app_outcome,
            )
            .map_err(|e| -> Box<dyn std::error::Error + Send + Sync> { e.into() })?;
            Ok(Box::new(app.on_window_cleared_to_panel_fill()))
        }),
    )
    .map_err(|e| {
        anyhow::anyhow!(
            "cannot open the lab window: {}; {HEADLESS_HINT}",
            one_line(&e.to_string())
        )
    })?;
    let failure = outcome.lock().ok().and_then(|mut o| o.take());
    match failure {
        Some(message) => Err(anyhow::anyhow!(message)).context("scripted run"),
        None => Ok(()),
    }
}

fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}
