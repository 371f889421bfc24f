//! The CPU reference, computed on a background thread (progress, cancel),
//! and the error of the GPU image against it: the `error` view, its RMSE,
//! and a mark when the settings have changed since it was computed.
//!
//! The seam is [`ReferenceFn`]: a function of the scene, the settings (whose
//! image size is the viewport's) and a progress/cancel control, returning the
//! image the renderer compares with (rgb = L_ref, a = V_ref).

use super::command::Command;
use super::widgets::{number, quantity};
use crate::gpu::ComparisonImage;
use crate::reference::{Reference, ReferenceOptions, RenderControl};
use crate::scene::Scene;
use crate::settings::{DebugView, Settings, ShadowSettings, ViewSettings};
use crate::tr;
use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::sync::mpsc::{Receiver, TryRecvError};
use std::time::{Duration, Instant};

/// Computes the reference image for `settings` (size: `settings.image`),
/// reporting progress and stopping when cancelled through the control.
pub type ReferenceFn =
    dyn Fn(&Scene, &Settings, &RenderControl) -> Result<ComparisonImage, String> + Send + Sync;

/// The CPU ray tracer with its default sampling (pixel centres; 64 strata of
/// a sphere light).
pub fn cpu_reference(
    scene: &Scene,
    settings: &Settings,
    control: &RenderControl,
) -> Result<ComparisonImage, String> {
    Reference::new(scene)
        .render(settings, &ReferenceOptions::DEFAULT, control)
        .map(|image| image.to_comparison())
        .map_err(|e| e.to_string())
}

/// What a reference depends on: everything but the shadow map's own
/// settings and the view. Two settings with the same key share a reference.
pub fn reference_key(settings: &Settings) -> Settings {
    let mut key = settings.clone();
    key.shadow = ShadowSettings {
        enabled: settings.shadow.enabled,
        ..ShadowSettings::default()
    };
    key.view = ViewSettings::default();
    key
}

/// A finished reference.
pub struct ReferenceResult {
    pub image: Arc<ComparisonImage>,
    /// `reference_key` of the settings it was computed for.
    pub key: Settings,
    pub elapsed: Duration,
}

impl ReferenceResult {
    /// The settings (or the image size) changed since it was computed.
    pub fn is_stale(&self, settings: &Settings, size: (u32, u32)) -> bool {
        let mut key = reference_key(settings);
        key.image.width = size.0;
        key.image.height = size.1;
        key != self.key
    }
}

/// The GPU image against the reference, over the covered pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorStats {
    /// Root mean square of L − L_ref in luminance (W/m²/sr).
    pub rmse: f64,
    /// The RMSE over the mean reference luminance.
    pub relative: f64,
    pub max_abs: f64,
    pub pixels: usize,
}

/// Y of the first three channels, as the display shader's error view uses.
fn luminance(rgb: &[f32]) -> f64 {
    crate::physics::colour::luminance([rgb[0], rgb[1], rgb[2]].map(f64::from))
}

/// Statistics of L − L_ref where the GPU covered the pixel (its quantity's
/// alpha above 0).
pub fn error_stats(quantity: &[[f32; 4]], reference: &ComparisonImage) -> Option<ErrorStats> {
    if quantity.len() != reference.texels.len() {
        return None;
    }
    let (mut sum2, mut sum_ref, mut max_abs, mut n) = (0.0, 0.0, 0.0_f64, 0usize);
    for (q, r) in quantity.iter().zip(&reference.texels) {
        if q[3] <= 0.0 {
            continue;
        }
        let l_ref = luminance(&r[..3]);
        let e = luminance(&q[..3]) - l_ref;
        if !e.is_finite() {
            continue;
        }
        sum2 += e * e;
        sum_ref += l_ref;
        max_abs = max_abs.max(e.abs());
        n += 1;
    }
    (n > 0).then(|| {
        let rmse = (sum2 / n as f64).sqrt();
        let mean = sum_ref / n as f64;
        ErrorStats {
            rmse,
            relative: if mean > 0.0 { rmse / mean } else { 0.0 },
            max_abs,
            pixels: n,
        }
    })
}

struct Job {
    control: Arc<RenderControl>,
    total: usize,
    key: Settings,
    started: Instant,
    result: Receiver<Result<ComparisonImage, String>>,
}

pub struct ReferencePanel {
    compute: Arc<ReferenceFn>,
    job: Option<Job>,
    pub result: Option<ReferenceResult>,
    pub stats: Option<ErrorStats>,
    message: Option<String>,
}

impl Default for ReferencePanel {
    fn default() -> Self {
        Self::new(Arc::new(cpu_reference))
    }
}

impl ReferencePanel {
    pub fn new(compute: Arc<ReferenceFn>) -> Self {
        Self {
            compute,
            job: None,
            result: None,
            stats: None,
            message: None,
        }
    }

    pub fn is_running(&self) -> bool {
        self.job.is_some()
    }

    /// Starts computing for `settings` at `size` on a thread; `ctx` is woken when done.
    pub fn start(&mut self, scene: Arc<Scene>, settings: &Settings, size: (u32, u32), ctx: &egui::Context) {
        self.cancel();
        let mut settings = settings.clone();
        settings.image.width = size.0;
        settings.image.height = size.1;
        let control = Arc::new(RenderControl::default());
        let (sender, receiver) = std::sync::mpsc::channel();
        let compute = Arc::clone(&self.compute);
        let thread_control = Arc::clone(&control);
        let thread_settings = settings.clone();
        let ctx = ctx.clone();
        let spawned = std::thread::Builder::new()
            .name("lumlab reference".into())
            .spawn(move || {
                let result = compute(&scene, &thread_settings, &thread_control);
                let _ = sender.send(result);
                ctx.request_repaint();
            });
        match spawned {
            Ok(_) => {
                self.message = None;
                self.job = Some(Job {
                    control,
                    total: (size.0 as usize * size.1 as usize).max(1),
                    key: reference_key(&settings),
                    started: Instant::now(),
                    result: receiver,
                });
            }
            Err(e) => self.message = Some(tr!("reference-cannot-start", message = e.to_string())),
        }
    }

    /// Asks a running computation to stop (its result is dropped).
    pub fn cancel(&mut self) {
        if let Some(job) = self.job.take() {
            job.control.cancel();
            self.message = Some(tr!("reference-cancelled"));
        }
    }

    /// Collects a finished computation; true when a new reference arrived.
    pub fn poll(&mut self) -> bool {
        let Some(job) = &self.job else {
            return false;
        };
        match job.result.try_recv() {
            Err(TryRecvError::Empty) => false,
            Err(TryRecvError::Disconnected) => {
                self.message = Some(tr!("reference-stopped"));
                self.job = None;
                false
            }
            Ok(Err(e)) => {
                self.message = Some(e);
                self.job = None;
                false
            }
            Ok(Ok(image)) => {
                let elapsed = job.started.elapsed();
                self.result = Some(ReferenceResult {
                    image: Arc::new(image),
                    key: job.key.clone(),
                    elapsed,
                });
                self.stats = None;
                self.message = None;
                self.job = None;
                true
            }
        }
    }

    /// Forgets the reference (e.g. a new scene).
    pub fn clear(&mut self) {
        self.cancel();
        self.result = None;
        self.stats = None;
        self.message = None;
    }

    pub fn ui(&mut self, ui: &mut egui::Ui, settings: &Settings, size: (u32, u32)) -> Option<Command> {
        let mut action = None;
        ui.horizontal(|ui| {
            if ui
                .add_enabled(self.job.is_none(), egui::Button::new(tr!("reference-compute")))
                .on_hover_text(tr!("reference-compute-tip"))
                .clicked()
            {
                action = Some(Command::StartReference);
            }
            if self.job.is_some()
                && ui
                    .button(tr!("reference-cancel"))
                    .on_hover_text(tr!("reference-cancel-tip"))
                    .clicked()
            {
                action = Some(Command::Cancel);
            }
        });
        if let Some(job) = &self.job {
            let done = job.control.pixels_done.load(Ordering::Relaxed).min(job.total);
            let fraction = done as f32 / job.total as f32;
            ui.add(egui::ProgressBar::new(fraction).show_percentage().animate(true))
                .on_hover_text(tr!("reference-progress-tip", done = done, total = job.total));
            ui.label(format!("{} s", number(job.started.elapsed().as_secs_f64())));
        }
        if let Some(message) = &self.message {
            ui.label(egui::RichText::new(message).color(ui.visuals().warn_fg_color));
        }
        let Some(result) = &self.result else {
            ui.label(tr!("reference-none"));
            return action;
        };
        ui.label(tr!(
            "reference-done",
            width = result.image.width,
            height = result.image.height,
            seconds = number(result.elapsed.as_secs_f64())
        ));
        if result.is_stale(settings, size) {
            ui.label(
                egui::RichText::new(tr!("reference-stale"))
                    .color(ui.visuals().warn_fg_color)
                    .strong(),
            );
        }
        if let Some(s) = &self.stats {
            egui::Grid::new("error stats").num_columns(2).show(ui, |ui| {
                super::widgets::value_row(
                    ui,
                    "RMSE",
                    &quantity(s.rmse, "W/m²/sr"),
                    &tr!("reference-rmse-tip"),
                );
                super::widgets::value_row(
                    ui,
                    &tr!("reference-relative"),
                    &format!("{} %", number(100.0 * s.relative)),
                    "RMSE / mean L_ref",
                );
                super::widgets::value_row(
                    ui,
                    &tr!("reference-max-error"),
                    &quantity(s.max_abs, "W/m²/sr"),
                    "max |L − L_ref|",
                );
                super::widgets::value_row(
                    ui,
                    &tr!("reference-pixels"),
                    &s.pixels.to_string(),
                    &tr!("reference-pixels-tip"),
                );
            });
        } else {
            ui.label(tr!("reference-rmse-in-error-view"));
        }
        ui.horizontal(|ui| {
            if ui
                .button(tr!("reference-error-view"))
                .on_hover_text(tr!("reference-error-view-tip"))
                .clicked()
            {
                action = Some(Command::ShowView(DebugView::Error));
            }
            if ui
                .button(tr!("reference-visibility"))
                .on_hover_text(tr!("reference-visibility-tip"))
                .clicked()
            {
                action = Some(Command::ShowView(DebugView::RefVisibility));
            }
        });
        action
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat(width: u32, height: u32, l: f32) -> ComparisonImage {
        ComparisonImage {
            width,
            height,
            texels: vec![[l, l, l, 1.0]; (width * height) as usize],
        }
    }

    #[test]
    fn shadow_settings_do_not_make_a_reference_stale() {
        let s = Settings::default();
        let mut t = s.clone();
        t.shadow.filter = crate::settings::Filter::Vsm;
        t.shadow.resolution = 512;
        t.view.mode = DebugView::Error;
        assert_eq!(reference_key(&s), reference_key(&t));
        t.light.power_w *= 2.0;
        assert_ne!(reference_key(&s), reference_key(&t));
    }

    #[test]
    fn rmse_of_a_constant_offset_is_the_offset() {
        let reference = flat(4, 2, 1.0);
        let mut quantity = vec![[1.5, 1.5, 1.5, 1.0]; 8];
        quantity[0] = [9.0, 9.0, 9.0, 0.0];
        let s = error_stats(&quantity, &reference).unwrap();
        assert!((s.rmse - 0.5).abs() < 1e-6 && (s.relative - 0.5).abs() < 1e-6);
        assert_eq!(s.pixels, 7);
        assert!(error_stats(&quantity[..4], &reference).is_none());
    }

    #[test]
    fn a_job_runs_on_a_thread_and_can_be_cancelled() {
        let ctx = egui::Context::default();
        let compute: Arc<ReferenceFn> = Arc::new(|_, s, c| {
            c.pixels_done.store(1, Ordering::Relaxed);
            Ok(flat(s.image.width, s.image.height, 2.0))
        });
        let mut panel = ReferencePanel::new(compute);
        let scene = Arc::new(crate::scene::default_scene());
        let settings = Settings::default();
        panel.start(Arc::clone(&scene), &settings, (3, 2), &ctx);
        let t0 = Instant::now();
        while !panel.poll() {
            assert!(t0.elapsed() < Duration::from_secs(10), "job never finished");
            std::thread::sleep(Duration::from_millis(5));
        }
        let result = panel.result.as_ref().unwrap();
        assert_eq!((result.image.width, result.image.height), (3, 2));
        assert!(!result.is_stale(&settings, (3, 2)));
        assert!(result.is_stale(&settings, (4, 2)));

        let slow: Arc<ReferenceFn> = Arc::new(|_, _, c| {
            while !c.cancel.load(Ordering::Relaxed) {
                std::thread::sleep(Duration::from_millis(1));
            }
            Err("cancelled".into())
        });
        let mut panel = ReferencePanel::new(slow);
        panel.start(scene, &settings, (3, 2), &ctx);
        assert!(panel.is_running());
        panel.cancel();
        assert!(!panel.is_running());
    }
}
