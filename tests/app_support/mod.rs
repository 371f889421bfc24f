//! The lab in an egui_kittest harness, on our own wgpu device: shared by the
//! app's UI tests.
#![allow(dead_code)]

use egui_kittest::{Harness, wgpu::WgpuTestRenderer};
use lumlab::app::{LabApp, LaunchOptions, Preloaded};
use std::sync::Arc;
use std::time::Duration;

pub const SIZE: egui::Vec2 = egui::vec2(1280.0, 800.0);

/// The lab on our own device (the adapter's limits and features), with a
/// kittest renderer sharing it so native textures can be drawn.
pub fn harness() -> Harness<'static, LabApp> {
    harness_with_storage(None)
}

/// The lab as `harness`, its state restored from `storage` as at start-up.
pub fn harness_with_storage(storage: Option<&dyn eframe::Storage>) -> Harness<'static, LabApp> {
    harness_with(storage, &LaunchOptions::default())
}

/// The lab as `harness`, started with `options`.
pub fn harness_with(
    storage: Option<&dyn eframe::Storage>,
    options: &LaunchOptions,
) -> Harness<'static, LabApp> {
    harness_preloaded(storage, options, Preloaded::default())
}

/// The lab as `harness_with`, with what `preloaded` gives (a scene built
/// in code) instead of reading files.
pub fn harness_preloaded(
    storage: Option<&dyn eframe::Storage>,
    options: &LaunchOptions,
    preloaded: Preloaded,
) -> Harness<'static, LabApp> {
    let mut setup = egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    setup.instance_descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
    setup.device_descriptor = Arc::new(lumlab::gpu::context::device_descriptor);
    let render_state = egui_kittest::wgpu::create_render_state(
        egui_wgpu::WgpuSetup::CreateNew(setup),
        egui_wgpu::RendererOptions::PREDICTABLE,
    );
    let app = LabApp::new(
        Some(render_state.clone()),
        storage,
        options,
        preloaded,
        Arc::default(),
    )
    .expect("the app starts on a wgpu device");
    let mut harness = Harness::builder()
        .with_size(SIZE)
        // `run` settles when no frame asks for another. The lab's GPU work
        // (renders, timings, readbacks) reports back asynchronously, and each
        // result that shows a widget for the first time asks one more frame
        // (egui styles a new widget on its second frame): on a loaded machine
        // that took 6 frames once, past kittest's default limit of 4. A UI
        // that never settles still fails, after 16.
        .with_max_steps(16)
        .renderer(WgpuTestRenderer::from_render_state(render_state))
        .with_render_cursor(false)
        .build_ui_state(
            |ui, app: &mut LabApp| {
                // The whole window, as eframe gives it (kittest adds a margin).
                let whole = ui.ctx().content_rect();
                let mut root = ui.new_child(egui::UiBuilder::new().max_rect(whole));
                app.show(&mut root);
            },
            app,
        );
    harness.run();
    harness
}

/// Steps until `done` holds (async readbacks), failing after a few seconds.
pub fn step_until(harness: &mut Harness<'_, LabApp>, what: &str, mut done: impl FnMut(&LabApp) -> bool) {
    for _ in 0..300 {
        harness.step();
        if done(harness.state()) {
            return;
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    panic!("timed out waiting for {what}");
}

/// Clicks the viewport halfway across, `down` of its height from its top
/// edge (0 … 1).
pub fn click_viewport(harness: &mut Harness<'_, LabApp>, down: f32) {
    let rect = harness.state().viewport_rect();
    click_at(
        harness,
        egui::pos2(rect.center().x, rect.top() + down * rect.height()),
    );
}

/// Steps until the probe has read its GPU values back.
pub fn wait_for_probe(harness: &mut Harness<'_, LabApp>) {
    step_until(harness, "the probe's GPU values", |app| app.probe_gpu().is_some());
}

/// Presses or releases the primary button at `pos` (the next step sees it).
pub fn primary_button(harness: &mut Harness<'_, LabApp>, pos: egui::Pos2, pressed: bool) {
    harness.event(egui::Event::PointerButton {
        pos,
        button: egui::PointerButton::Primary,
        pressed,
        modifiers: egui::Modifiers::NONE,
    });
}

/// A click of the primary button at `pos`, and a step.
pub fn click_at(harness: &mut Harness<'_, LabApp>, pos: egui::Pos2) {
    harness.event(egui::Event::PointerMoved(pos));
    for pressed in [true, false] {
        primary_button(harness, pos, pressed);
    }
    harness.step();
}
