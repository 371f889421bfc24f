//! The command layer driven through egui_kittest: a shortcut and its button
//! emit the same command, every row of the shortcut table emits its command,
//! the help window lists exactly that table, undo reverts a command, and a
//! scene's own view is adopted the same way at start-up and later.

use egui::Modifiers;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use lumlab::app::{Command, GESTURES, LabApp, SHORTCUTS};
use lumlab::scene::Camera;
use lumlab::settings::{DebugView, Settings};
use std::sync::Arc;

mod app_support;
mod scene_support;
use app_support::harness;

fn last_command(harness: &Harness<'_, LabApp>) -> Option<Command> {
    harness.state().applied_commands().last().cloned()
}

/// The last command applied that is not a settings edit (a panel's copy).
fn last_action(harness: &Harness<'_, LabApp>) -> Option<Command> {
    harness
        .state()
        .applied_commands()
        .filter(|c| !matches!(c, Command::SetSettings(_)))
        .last()
        .cloned()
}

/// No file lands in the working directory, and F5 runs a stand-in reference.
fn sandboxed(harness: &mut Harness<'_, LabApp>, dir: &std::path::Path) {
    let state = harness.state_mut().state_mut();
    state.paths.settings_file = dir.join("s.toml").display().to_string();
    state.paths.screenshot_file = dir.join("shot.png").display().to_string();
    state.paths.exr_file = dir.join("l.exr").display().to_string();
    harness.state_mut().set_reference_fn(Arc::new(
        |_scene: &lumlab::scene::Scene, s: &Settings, _control: &lumlab::reference::RenderControl| {
            let n = (s.image.width * s.image.height) as usize;
            Ok(lumlab::gpu::ComparisonImage {
                width: s.image.width,
                height: s.image.height,
                texels: vec![[0.0, 0.0, 0.0, 1.0]; n],
            })
        },
    ));
}

#[test]
fn a_shortcut_and_its_button_emit_the_same_command() {
    let mut harness = harness();
    harness.key_press(egui::Key::R);
    harness.run();
    assert_eq!(last_command(&harness), Some(Command::ResetView));
    harness.get_by_label("Split A | B").click();
    harness.run();
    assert_eq!(last_action(&harness), Some(Command::ToggleSplit));
    assert!(harness.state_mut().state_mut().split.enabled);
    harness.key_press(egui::Key::S);
    harness.run();
    assert_eq!(last_action(&harness), Some(Command::ToggleSplit));
    assert!(!harness.state_mut().state_mut().split.enabled);
    harness.get_by_label("Reset view").click();
    harness.run();
    assert_eq!(last_action(&harness), Some(Command::ResetView));
}

#[test]
fn every_row_of_the_shortcut_table_emits_its_command() {
    let dir = tempfile::tempdir().unwrap();
    let mut harness = harness();
    sandboxed(&mut harness, dir.path());
    for shortcut in SHORTCUTS {
        let key = shortcut.keys[0];
        harness.key_press_modifiers(key.modifiers, key.logical_key);
        harness.run();
        assert_eq!(
            last_action(&harness).as_ref(),
            Some(&shortcut.command),
            "{} ({})",
            shortcut.keys_text(),
            (shortcut.does)()
        );
    }
}

#[test]
fn the_help_window_lists_exactly_the_shortcut_table() {
    let mut harness = harness();
    harness.key_press(egui::Key::F1);
    harness.run();
    assert!(harness.state().help_open());
    for s in SHORTCUTS {
        harness.get_by_label(&s.keys_text());
        // A description may also be a button's tooltip elsewhere: at least one.
        let does = (s.does)();
        assert!(harness.query_all_by_label(&does).count() >= 1, "{does}");
    }
    for (gesture, does) in GESTURES {
        harness.get_by_label(&gesture());
        harness.get_by_label(&does());
    }
    // Each row once: the help is made from the table, not beside it.
    for s in SHORTCUTS {
        assert_eq!(
            harness.query_all_by_label(&s.keys_text()).count(),
            1,
            "{}",
            s.keys_text()
        );
    }
    harness.key_press(egui::Key::Escape);
    harness.run();
    assert!(!harness.state().help_open());
}

#[test]
fn undo_reverts_a_command_as_one_step() {
    let mut harness = harness();
    harness.state_mut().emit(Command::ShowView(DebugView::Ndotl));
    harness.run();
    assert_eq!(harness.state().settings().view.mode, DebugView::Ndotl);
    harness.key_press(egui::Key::V);
    harness.run();
    let next = harness.state().settings().view.mode;
    assert_ne!(next, DebugView::Ndotl);
    harness.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    harness.run();
    assert_eq!(harness.state().settings().view.mode, DebugView::Ndotl);
    harness.get_by_label("Undo").click();
    harness.run();
    assert_eq!(
        harness.state().settings().view.mode,
        Settings::default().view.mode
    );
    harness.key_press_modifiers(Modifiers::COMMAND, egui::Key::Y);
    harness.run();
    assert_eq!(harness.state().settings().view.mode, DebugView::Ndotl);
}

#[test]
fn reset_view_is_undone_in_one_step() {
    let mut harness = harness();
    let moved = Camera {
        eye: glam::Vec3::new(4.0, 2.0, 3.0),
        ..Camera::default()
    };
    let mut s = harness.state().settings().clone();
    s.camera = moved;
    harness.state_mut().emit(Command::SetSettings(Box::new(s)));
    harness.run();
    harness.key_press(egui::Key::R);
    harness.run();
    assert_eq!(harness.state().settings().camera, Camera::default());
    harness.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    harness.run();
    assert_eq!(harness.state().settings().camera, moved);
}

#[test]
fn a_preset_button_emits_the_preset_command() {
    let mut harness = harness();
    let preset = lumlab::presets::Preset::Penumbra;
    harness.get_by_label(preset.title()).click();
    harness.run();
    assert_eq!(last_action(&harness), Some(Command::ApplyPreset(preset)));
}

#[test]
fn opening_a_model_frames_it_and_undo_restores_the_view() {
    let Some(samples) = scene_support::samples::samples_dir() else {
        eprintln!("no ../shared/gltf-samples: skipped");
        return;
    };
    let path = samples.join("Box/Box.gltf");
    let framed = lumlab::scene::load(&path).unwrap().home_camera();
    let mut harness = harness();
    let before = harness.state().settings().camera;
    assert_ne!(before, framed);
    harness.state_mut().emit(Command::OpenScene(Some(path.clone())));
    app_support::step_until(&mut harness, "the scene to load", |app| {
        app.settings().scene.as_deref() == Some(path.as_path())
    });
    harness.run();
    assert_eq!(harness.state().settings().camera, framed);
    // The light moved to the model: above it, on the camera's side.
    let light = harness.state().settings().light.position;
    assert!(light.y > 0.5 && light.length() < 10.0, "{light}");
    harness.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    harness.run();
    assert_eq!(harness.state().settings().camera, before);
}

#[test]
fn an_impossible_light_is_said_in_the_status_bar() {
    let mut harness = harness();
    assert!(harness.state().impossible_setups().is_empty());
    let mut s = harness.state().settings().clone();
    // A sphere light cutting through the ground.
    s.light.position = glam::Vec3::new(0.0, 0.1, 0.0);
    s.light.radius_m = 0.5;
    harness.state_mut().emit(Command::SetSettings(Box::new(s)));
    harness.run();
    let lines = harness.state().impossible_setups().to_vec();
    assert!(!lines.is_empty());
    assert!(
        harness.query_all_by_label_contains("Impossible set-up").count() >= 1,
        "{lines:?}"
    );
}
