//! `lumlab reference` from the outside: the files it writes, its one-line
//! summary, and its errors (one line, exit 2 for usage, 1 at run time, no
//! file left behind).

mod cli_support;

use cli_support::{lumlab, stderr};
use lumlab::reference::{Reference, ReferenceOptions, RenderControl};
use lumlab::scene;
use lumlab::settings::Settings;
use std::path::Path;

fn files_in(dir: &Path) -> usize {
    std::fs::read_dir(dir).map_or(0, |d| d.count())
}

#[test]
fn png_is_written_with_a_one_line_summary() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("ref.png");
    let out = lumlab(&["reference", "--size", "64x36", "--out", png.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stderr(&out);
    // Not a terminal: no progress bar, only the summary.
    assert_eq!(text.lines().count(), 1, "{text}");
    assert!(
        text.starts_with("reference 64×36") && text.contains("rays"),
        "{text}"
    );
    let image = image::open(&png).unwrap();
    assert_eq!((image.width(), image.height()), (64, 36));
}

#[test]
fn exr_holds_the_linear_radiance_of_the_library_render() {
    let dir = tempfile::tempdir().unwrap();
    let exr = dir.path().join("ref.exr");
    let args = [
        "reference",
        "--size",
        "40x30",
        "--light-radius",
        "0.3",
        "--light-samples",
        "4",
        "--seed",
        "5",
        "--out",
        exr.to_str().unwrap(),
    ];
    let out = lumlab(&args);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stderr(&out).contains("RMS standard error"), "{}", stderr(&out));
    let file = image::open(&exr).unwrap().into_rgba32f();
    let mut settings = Settings::default();
    (settings.image.width, settings.image.height) = (40, 30);
    settings.light.radius_m = 0.3;
    let options = ReferenceOptions {
        spp: 1,
        light_samples: 4,
        seed: 5,
        ..ReferenceOptions::DEFAULT
    };
    let image = Reference::new(&scene::default_scene())
        .render(&settings, &options, &RenderControl::default())
        .unwrap();
    for (pixel, (rgb, coverage)) in file.pixels().zip(image.radiance.iter().zip(&image.coverage)) {
        assert_eq!(pixel.0, [rgb[0] as f32, rgb[1] as f32, rgb[2] as f32, *coverage]);
    }
}

#[test]
fn bad_options_are_usage_errors_and_leave_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("bad.png");
    let png = png.to_str().unwrap();
    let jpg = dir.path().join("bad.jpg");
    for args in [
        vec!["reference", "--spp", "0", "--out", png],
        vec!["reference", "--light-samples", "many", "--out", png],
        vec!["reference", "--size", "0x10", "--out", png],
        vec!["reference", "--out", jpg.to_str().unwrap()],
        vec!["reference", "--k", "2", "--out", png],
    ] {
        let out = lumlab(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        assert_eq!(stderr(&out).lines().count(), 1, "{args:?}: {}", stderr(&out));
    }
    assert_eq!(files_in(dir.path()), 0);
}

#[test]
fn a_missing_scene_is_a_runtime_error_and_leaves_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("none.png");
    let missing = dir.path().join("missing.gltf");
    let out = lumlab(&[
        "reference",
        "--scene",
        missing.to_str().unwrap(),
        "--out",
        png.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert_eq!(stderr(&out).lines().count(), 1, "{}", stderr(&out));
    assert_eq!(files_in(dir.path()), 0);
}
