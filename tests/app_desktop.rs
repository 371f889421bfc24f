//! The lab as a desktop app: the file dialog's result opens a scene through
//! the same command as a dropped file, recent files (a gone one shown as
//! missing), the title following the scene, errors shown as toasts, the
//! "Replace?" question before a save; and the binary installed away from
//! the checkout, with its completions and man page.

use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use lumlab::app::{Command, FileAction, LabApp};
use std::path::{Path, PathBuf};
use std::process::Command as Process;

mod app_support;
use app_support::{harness, step_until};

/// A copy of the built-in scene as a file in `dir`.
fn scene_file(dir: &Path, name: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, lumlab::scene::default_scene::ASSET).unwrap();
    path
}

fn opened_scenes(harness: &Harness<'_, LabApp>) -> Vec<Command> {
    harness
        .state()
        .applied_commands()
        .filter(|c| matches!(c, Command::OpenScene(_)))
        .cloned()
        .collect()
}

/// Steps until the window has been asked to take a title containing `part`.
fn wait_for_title(harness: &mut Harness<'_, LabApp>, part: &str) -> String {
    for _ in 0..300 {
        harness.step();
        let titles: Vec<String> = harness
            .output()
            .viewport_output
            .get(&egui::ViewportId::ROOT)
            .map(|v| {
                v.commands
                    .iter()
                    .filter_map(|c| match c {
                        egui::ViewportCommand::Title(t) => Some(t.clone()),
                        _ => None,
                    })
                    .collect()
            })
            .unwrap_or_default();
        if let Some(t) = titles.into_iter().find(|t| t.contains(part)) {
            return t;
        }
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    panic!("the window's title never named {part}");
}

/// A file dropped on the window, as eframe hands it over.
#[derive(Debug)]
struct Dropped(PathBuf);

impl egui::DroppedFile for Dropped {
    fn path(&self) -> &Path {
        &self.0
    }

    fn bytes(&self) -> Result<Vec<u8>, String> {
        std::fs::read(&self.0).map_err(|e| e.to_string())
    }
}

#[test]
fn the_dialogs_result_opens_the_scene_like_a_dropped_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = scene_file(dir.path(), "box.glb");
    std::fs::write(dir.path().join("notes.txt"), b"not a scene").unwrap();
    let mut harness = harness();
    harness.state_mut().state_mut().paths.last_folder = Some(dir.path().to_path_buf());

    harness.get_by_label("File").click();
    harness.run();
    harness.get_by_label("Open scene…").click();
    harness.run();
    assert!(harness.state().file_dialog_open());
    assert!(
        harness.query_by_label_contains("notes.txt").is_none(),
        "the dialog shows only glTF/GLB files"
    );
    harness.get_by_label_contains("box.glb").click();
    harness.run();
    harness.get_by_label("Open").click();
    harness.run_steps(2); // not run(): the load on its thread repaints when it ends
    let from_dialog = opened_scenes(&harness);
    assert_eq!(from_dialog, [Command::OpenScene(Some(path.clone()))]);
    assert_eq!(
        harness.state_mut().state_mut().paths.last_folder.as_deref(),
        Some(dir.path()),
        "the folder is remembered"
    );

    harness
        .input_mut()
        .dropped_files
        .push(std::sync::Arc::new(Dropped(path.clone())));
    harness.run_steps(2);
    let all = opened_scenes(&harness);
    assert_eq!(all.len(), 2);
    assert_eq!(all[1], from_dialog[0], "a dropped file emits the same command");
    step_until(&mut harness, "the scene to load", |app| {
        app.title() == "lumlab — box.glb"
    });
}

#[test]
fn a_recent_file_that_no_longer_exists_is_shown_as_missing() {
    let dir = tempfile::tempdir().unwrap();
    let here = scene_file(dir.path(), "here.glb");
    let gone = dir.path().join("gone.glb");
    let mut harness = harness();
    harness.state_mut().state_mut().recent.scenes = vec![gone.clone(), here.clone()];
    harness.run();
    assert!(
        harness.state().toasts().is_empty(),
        "no error for a gone recent file"
    );

    harness.get_by_label("File").click();
    harness.run();
    let missing = harness.get_by_label("gone.glb (missing)");
    assert!(missing.accesskit_node().is_disabled(), "a gone file is greyed");
    let present = harness.get_by_label("here.glb");
    assert!(!present.accesskit_node().is_disabled());
    present.click();
    harness.run_steps(2);
    assert_eq!(opened_scenes(&harness), [Command::OpenScene(Some(here.clone()))]);
    step_until(&mut harness, "the recent scene to load", |app| {
        app.title().contains("here.glb")
    });
    assert_eq!(harness.state_mut().state_mut().recent.scenes[0], here);
}

#[test]
fn the_title_follows_the_scene_and_marks_unsaved_settings() {
    let dir = tempfile::tempdir().unwrap();
    let path = scene_file(dir.path(), "room.glb");
    let mut harness = harness();
    assert_eq!(harness.state().title(), "lumlab — built-in");

    harness.state_mut().emit(Command::OpenScene(Some(path)));
    assert_eq!(wait_for_title(&mut harness, "room.glb"), "lumlab — room.glb");

    let settings = dir.path().join("lab.toml");
    harness
        .state_mut()
        .emit(Command::SaveSettings(Some(settings.clone())));
    harness.run();
    assert_eq!(harness.state().title(), "lumlab — room.glb");
    harness.state_mut().settings_mut().light.power_w += 1.0;
    assert_eq!(wait_for_title(&mut harness, "•"), "lumlab — room.glb •");
    harness
        .state_mut()
        .emit(Command::LoadSettings(Some(settings.clone())));
    assert_eq!(wait_for_title(&mut harness, "room"), "lumlab — room.glb");
    assert_eq!(harness.state_mut().state_mut().recent.settings[0], settings);

    harness.state_mut().emit(Command::BuiltInScene);
    wait_for_title(&mut harness, "built-in");
}

#[test]
fn a_failed_open_or_save_names_the_file_in_a_toast_and_changes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("broken.glb");
    std::fs::write(&bad, b"not a glTF at all").unwrap();
    let mut harness = harness();
    let before = harness.state().settings().clone();

    harness.state_mut().emit(Command::OpenScene(Some(bad.clone())));
    step_until(&mut harness, "the failed load", |app| !app.toasts().is_empty());
    let toast = harness.state().toasts()[0].clone();
    assert!(toast.contains("broken.glb"), "{toast}");
    harness.get_by_label_contains("the current scene is kept");
    assert_eq!(*harness.state().settings(), before);
    assert_eq!(harness.state().title(), "lumlab — built-in");

    let bad_settings = dir.path().join("bad.toml");
    std::fs::write(&bad_settings, "[light]\npower_w = -5.0\n").unwrap();
    harness
        .state_mut()
        .emit(Command::LoadSettings(Some(bad_settings)));
    harness.run();
    let toast = harness.state().toasts().last().unwrap().clone();
    assert!(toast.contains("bad.toml") && toast.contains("power_w"), "{toast}");
    assert_eq!(*harness.state().settings(), before);

    let unwritable = dir.path().join("no such folder").join("lab.toml");
    harness.state_mut().emit(Command::SaveSettings(Some(unwritable)));
    harness.run();
    assert!(harness.state().toasts().last().unwrap().contains("lab.toml"));

    let shown = harness.state().toasts().len();
    harness.get_all_by_label("Dismiss").next().unwrap().click();
    harness.run();
    assert_eq!(
        harness.state().toasts().len(),
        shown - 1,
        "a toast can be dismissed"
    );
}

#[test]
fn saving_over_a_file_asks_first() {
    let dir = tempfile::tempdir().unwrap();
    let existing = dir.path().join("lab.toml");
    std::fs::write(&existing, "# keep me\n").unwrap();
    let mut harness = harness();
    harness.state_mut().state_mut().paths.last_folder = Some(dir.path().to_path_buf());
    harness.state_mut().state_mut().paths.settings_file = existing.display().to_string();

    harness
        .state_mut()
        .emit(Command::ChooseFile(FileAction::SaveSettings));
    harness.run();
    harness.get_by_label("Save").click();
    harness.run();
    harness.get_by_label_contains("already exists");
    harness.get_by_label("Cancel").click();
    harness.run();
    assert_eq!(std::fs::read_to_string(&existing).unwrap(), "# keep me\n");

    harness
        .state_mut()
        .emit(Command::ChooseFile(FileAction::SaveSettings));
    harness.run();
    harness.get_by_label("Save").click();
    harness.run();
    harness.get_by_label("Replace").click();
    harness.run();
    let saved = lumlab::settings::Settings::load(&existing).expect("replaced by the settings");
    assert_eq!(&saved, harness.state().settings());
}

/// The binary, copied to `dir` as an installed one would be.
fn installed_binary(dir: &Path) -> PathBuf {
    let bin = dir.join("lumlab");
    std::fs::copy(env!("CARGO_BIN_EXE_lumlab"), &bin).unwrap();
    bin
}

#[test]
fn the_installed_binary_renders_the_built_in_scene_outside_the_checkout() {
    let dir = tempfile::tempdir().unwrap();
    let bin = installed_binary(dir.path());
    let out = Process::new(&bin)
        .args(["render", "--size", "64x36", "--out", "x.png"])
        .current_dir(dir.path())
        .env_remove("CARGO_MANIFEST_DIR")
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let image = image::open(dir.path().join("x.png")).unwrap().to_rgb8();
    assert_eq!(image.dimensions(), (64, 36));
    let lit = image.pixels().filter(|p| p.0.iter().any(|&c| c > 30)).count();
    assert!(
        lit > 64 * 36 / 4,
        "the built-in scene is drawn ({lit} lit pixels)"
    );
}

#[test]
fn completions_and_the_man_page_come_from_the_clap_definitions() {
    let dir = tempfile::tempdir().unwrap();
    let bin = installed_binary(dir.path());
    let run = |args: &[&str]| {
        let out = Process::new(&bin)
            .args(args)
            .current_dir(dir.path())
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap()
    };
    let bash = run(&["completions", "bash"]);
    assert!(bash.contains("complete -F") && bash.contains("render"), "{bash}");
    let man = run(&["manpage"]);
    assert!(man.starts_with(".ie") || man.contains(".TH lumlab"), "{man}");
    assert!(man.contains("render") && man.contains(".SH"));
    let bad = Process::new(&bin).args(["completions", "tcsh"]).output().unwrap();
    assert_eq!(bad.status.code(), Some(2));
}
