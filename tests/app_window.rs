//! The real binary opens its window under Xvfb, draws a frame that is not
//! blank, saves a screenshot of the whole window and exits on request; the
//! screenshot shows the settings panel and the rendered viewport. Without a
//! display it says so in one line and exits non-zero.
//!
//! Needs `xvfb-run` (scripts/test.sh installs it): without it the window
//! tests fail, saying so.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

const BIN: &str = env!("CARGO_BIN_EXE_lumlab");
/// The software adapter compiles shaders on the first frame: be patient.
const TIMEOUT: Duration = Duration::from_secs(240);

fn xvfb_run() -> PathBuf {
    let found = std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|dir| dir.join("xvfb-run"))
            .find(|p| p.is_file())
    });
    found.unwrap_or_else(|| {
        panic!(
            "xvfb-run is not installed: the window tests need a virtual X server. \
             Run scripts/test.sh (it installs Xvfb), or apt-get install xvfb"
        )
    })
}

/// A private home, runtime and data directory: a test never touches the
/// user's stored state, and lavapipe has its runtime directory.
fn sandbox(command: &mut Command, dir: &Path) {
    let runtime = dir.join("runtime");
    std::fs::create_dir_all(&runtime).unwrap();
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&runtime, std::fs::Permissions::from_mode(0o700)).unwrap();
    }
    command
        .env("HOME", dir)
        .env("XDG_DATA_HOME", dir.join("data"))
        .env("XDG_CONFIG_HOME", dir.join("config"))
        .env("XDG_RUNTIME_DIR", &runtime);
}

/// Runs to completion or kills it after `TIMEOUT`.
fn run(mut command: Command) -> Output {
    command.stdout(Stdio::piped()).stderr(Stdio::piped());
    let mut child = command.spawn().expect("the command starts");
    let start = Instant::now();
    loop {
        if child.try_wait().expect("wait").is_some() {
            return child.wait_with_output().expect("output");
        }
        if start.elapsed() > TIMEOUT {
            let _ = child.kill();
            let output = child.wait_with_output().expect("output");
            panic!(
                "the lab did not exit within {TIMEOUT:?}; stderr: {}",
                String::from_utf8_lossy(&output.stderr)
            );
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

fn in_xvfb(dir: &Path, args: &[&str]) -> Output {
    let mut command = Command::new(xvfb_run());
    command
        .args(["-a", "-s", "-screen 0 1280x800x24", BIN])
        .args(args);
    sandbox(&mut command, dir);
    run(command)
}

/// Mean and standard deviation of the luminance, and the number of distinct
/// colours, in a rectangle of the image.
fn stats(image: &image::RgbaImage, x: (u32, u32), y: (u32, u32)) -> (f64, f64, usize) {
    let mut values = Vec::new();
    let mut colours = std::collections::HashSet::new();
    for j in y.0..y.1 {
        for i in x.0..x.1 {
            let p = image.get_pixel(i, j).0;
            values.push(0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64);
            colours.insert([p[0], p[1], p[2]]);
        }
    }
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
    (mean, var.sqrt(), colours.len())
}

#[test]
fn window_draws_panel_and_viewport_and_saves_a_screenshot() {
    let dir = tempfile::tempdir().unwrap();
    let shot = dir.path().join("window.png");
    let output = in_xvfb(
        dir.path(),
        &["--screenshot", shot.to_str().unwrap(), "--quit-after-frames", "5"],
    );
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success(),
        "exit {:?}; stderr: {stderr}",
        output.status
    );
    let image = image::open(&shot)
        .unwrap_or_else(|e| panic!("screenshot {}: {e}; stderr: {stderr}", shot.display()))
        .to_rgba8();
    let (w, h) = image.dimensions();
    assert!(w >= 900 && h >= 600, "window of {w}×{h}");

    // The settings panel on the left: a flat dark panel with text on it.
    let (panel_mean, panel_std, _) = stats(&image, (10, 250), (60, h - 60));
    assert!(panel_mean < 90.0, "panel mean luminance {panel_mean}");
    assert!(
        panel_std > 8.0,
        "the panel shows text and widgets (std {panel_std})"
    );

    // The viewport in the middle: the rendered scene, many shades, not the panel.
    let (view_mean, view_std, view_colours) = stats(&image, (w * 2 / 5, w * 3 / 5), (h / 2, h - 60));
    assert!(
        view_colours > 50,
        "the viewport has {view_colours} colours: blank?"
    );
    assert!(view_std > 5.0, "the viewport varies (std {view_std})");
    assert!(
        (view_mean - panel_mean).abs() > 10.0,
        "viewport {view_mean} vs panel {panel_mean}"
    );
}

#[test]
fn window_exits_after_the_frames_asked_for() {
    let dir = tempfile::tempdir().unwrap();
    let output = in_xvfb(dir.path(), &["--quit-after-frames", "2"]);
    assert!(
        output.status.success(),
        "exit {:?}; stderr: {}",
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );
}

#[test]
fn without_a_display_it_says_so_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let mut command = Command::new(BIN);
    command.env_remove("DISPLAY").env_remove("WAYLAND_DISPLAY");
    sandbox(&mut command, dir.path());
    let output = run(command);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "stderr: {stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("display") && stderr.contains("lumlab render"),
        "{stderr}"
    );
}

#[test]
fn a_bad_scene_or_screenshot_path_is_refused_before_the_window_opens() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&[&str], &str); 3] = [
        (&["--scene", "/nonexistent/scene.glb"], "scene.glb"),
        (&["--screenshot", "shot.exr"], ".png"),
        (&["--settings", "/nonexistent/s.toml"], "s.toml"),
    ];
    for (args, needle) in cases {
        let mut command = Command::new(BIN);
        command.args(args);
        sandbox(&mut command, dir.path());
        let output = run(command);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(
            stderr.contains(needle) && stderr.trim().lines().count() == 1,
            "{args:?}: {stderr}"
        );
    }
    let mut command = Command::new(BIN);
    command.args(["--screenshot", "x.png", "energy"]);
    let output = run(command);
    assert_eq!(output.status.code(), Some(2), "a misplaced flag is a usage error");
    assert!(String::from_utf8_lossy(&output.stderr).contains("after its name"));
}
