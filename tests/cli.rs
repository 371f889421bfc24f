//! The command-line contract of DESIGN.md: outputs, exit codes, one-line
//! errors, and no partial files.

mod cli_support;

use cli_support::{assert_refused, lumlab, stderr};
use std::path::{Path, PathBuf};

/// A fresh empty directory for one test's files.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("lumlab-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn assert_fails(args: &[&str], code: i32, mentions: &str) {
    assert_refused(&lumlab(args), code, mentions);
}

fn no_files_in(dir: &Path) {
    let left: Vec<_> = std::fs::read_dir(dir).unwrap().collect();
    assert!(left.is_empty(), "left behind: {left:?}");
}

#[test]
fn energy_csv_has_the_known_values() {
    let out = lumlab(&[
        "energy",
        "--format",
        "csv",
        "--m",
        "8",
        "--norm",
        "approx,exact",
        "--angles",
        "0",
    ]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("norm,m,k,theta_deg,albedo"));
    for line in lines {
        let cols: Vec<&str> = line.split(',').collect();
        let albedo: f64 = cols[4].parse().unwrap();
        let significant = cols[4].trim_start_matches(['0', '.']).replace('.', "").len();
        assert!(significant >= 7, "{line}");
        match cols[0] {
            "approx" => assert!((albedo - 1.075).abs() < 1e-3, "{line}"),
            "exact" => assert!((albedo - 1.0).abs() < 1e-6, "{line}"),
            other => panic!("unexpected {other}"),
        }
    }
}

#[test]
fn energy_default_run_covers_the_lecture_table() {
    let out = lumlab(&["energy", "--format", "json"]);
    assert!(out.status.success());
    let rows: Vec<serde_json::Value> = serde_json::from_slice(&out.stdout).unwrap();
    // 4 normalizations × 10 exponents × 6 angles.
    assert_eq!(rows.len(), 240);
    for key in ["norm", "m", "k", "theta_deg", "albedo"] {
        assert!(rows[0].get(key).is_some(), "{key}");
    }
    let table = String::from_utf8(lumlab(&["energy"]).stdout).unwrap();
    assert!(table.contains("1.0750*"), "values above 1 are marked");
}

#[test]
fn energy_rejects_bad_input_in_one_line() {
    assert_fails(&["energy", "--m", "-3"], 2, "--m");
    assert_fails(&["energy", "--m", "abc"], 2, "--m");
    assert_fails(&["energy", "--angles", "95"], 2, "--angles");
    assert_fails(&["energy", "--norm", "foo"], 2, "none|ndf|approx|exact");
    assert_fails(
        &["energy", "--plot", "/no/such/dir/x.png"],
        2,
        "/no/such/dir/x.png",
    );
}

#[test]
fn energy_plot_is_a_png() {
    let dir = scratch("plot");
    let path = dir.join("albedo.png");
    let out = lumlab(&["energy", "--plot", path.to_str().unwrap(), "--format", "csv"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let image = image::open(&path).unwrap();
    assert!(image.width() > 600 && image.height() > 400);
}

#[test]
fn render_writes_png_and_exr() {
    let dir = scratch("render");
    let png = dir.join("shot.png");
    let out = lumlab(&[
        "render",
        "--size",
        "64x40",
        "--out",
        png.to_str().unwrap(),
        "--adapter-info",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stderr(&out).contains("adapter:"));
    let image = image::open(&png).unwrap().to_rgba8();
    assert_eq!(image.dimensions(), (64, 40));
    let exr = dir.join("shot.exr");
    let out = lumlab(&[
        "render",
        "--size",
        "64x40",
        "--view",
        "irradiance",
        "--out",
        exr.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let values = image::open(&exr).unwrap().to_rgba32f();
    let max = values.pixels().map(|p| p[0]).fold(0.0_f32, f32::max);
    // The default light (1000 W at 6 m above the ground) gives E of order I / r² ≈ 2 W/m².
    assert!(max > 0.5 && max < 100.0, "E max {max} W/m²");
}

#[test]
fn render_rejects_bad_input_without_leaving_files() {
    let dir = scratch("render-bad");
    let out = |name: &str| dir.join(name).to_str().unwrap().to_owned();
    assert_fails(
        &["render", "--filter", "blur", "--out", &out("a.png")],
        2,
        "--filter",
    );
    assert_fails(&["render", "--size", "0x10", "--out", &out("a.png")], 2, "--size");
    // Every value the command line gets wrong is a usage error (2).
    assert_fails(
        &["render", "--bias", "slope:1", "--out", &out("a.png")],
        2,
        "--bias",
    );
    assert_fails(
        &["render", "--shadow-res", "100", "--out", &out("a.png")],
        2,
        "--shadow-res",
    );
    assert_fails(
        &["render", "--pcf-size", "4", "--out", &out("a.png")],
        2,
        "--pcf-size",
    );
    assert_fails(
        &["render", "--light", "1e13,0,0", "--out", &out("a.png")],
        2,
        "light.position",
    );
    assert_fails(
        &["render", "--camera", "gltf:3", "--out", &out("a.png")],
        2,
        "camera",
    );
    assert_fails(&["render", "--out", &out("a.jpg")], 2, ".png or .exr");
    assert_fails(
        &["render", "--out", "/no/such/dir/a.png"],
        2,
        "/no/such/dir/a.png",
    );
    assert_fails(
        &["render", "--scene", &out("missing.gltf"), "--out", &out("a.png")],
        1,
        "missing.gltf",
    );
    no_files_in(&dir);
}

/// A negative number is a value, not an unknown flag: the error names the
/// option and the range it takes.
#[test]
fn negative_values_are_told_their_range() {
    let dir = scratch("negative");
    let out = |name: &str| dir.join(name).to_str().unwrap().to_owned();
    for (command, option, value, expected) in [
        ("render", "--power", "-5", "0 … 1e32"),
        ("render", "--light-radius", "-1", "0 … 1e32"),
        ("render", "--k", "-0.5", "0 … 1"),
        ("render", "--size", "-3x4", "1 … 16384"),
        ("render", "--accumulate", "-2", "1..=65536"),
        ("render", "--color", "-1,0,0", "light.color"),
        ("reference", "--spp", "-3", "1..=65536"),
    ] {
        let file = if command == "reference" { "a.exr" } else { "a.png" };
        assert_fails(&[command, option, value, "--out", &out(file)], 2, expected);
    }
    no_files_in(&dir);
}

#[test]
fn settings_file_feeds_the_command_line() {
    let dir = scratch("settings");
    let settings = dir.join("lab.toml");
    std::fs::write(&settings, "[light]\npower_w = 10\nbrightness = 2\n").unwrap();
    let png = dir.join("a.png");
    let args = [
        "render",
        "--settings",
        settings.to_str().unwrap(),
        "--out",
        png.to_str().unwrap(),
    ];
    assert_fails(&args, 1, "brightness");
    std::fs::write(&settings, "[material]\nk = 3\n").unwrap();
    assert_fails(&args, 1, "material.k");
    std::fs::remove_file(&settings).unwrap();
    no_files_in(&dir);
}
