//! `lumlab report` from the outside: the folder it writes (CSV with units,
//! finite values, the reference scoring 0, a non-dominated Pareto set; the
//! figure, the images and the page), and its errors (one line, non-zero
//! exit, nothing half-written left behind).

mod cli_support;

use cli_support::{csv_fields, lumlab, names_in, stderr};
use std::path::Path;
use std::process::Output;

const SWEEP: &str = r#"
[[config]]
filter = "none"
resolution = 2048

[cross]
filter = ["pcf", "evsm"]
resolution = [256, 1024]
bias = ["auto"]
"#;

fn run_report(dir: &Path, out: &Path) -> Output {
    let sweep = dir.join("sweep.toml");
    std::fs::write(&sweep, SWEEP).unwrap();
    lumlab(&[
        "report",
        "--size",
        "96x54",
        "--frames",
        "1",
        "--sweep",
        sweep.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ])
}

#[test]
fn a_small_sweep_writes_the_csv_the_plot_the_images_and_the_page() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("report");
    let result = run_report(dir.path(), &out);
    assert!(result.status.success(), "{}", stderr(&result));
    assert_eq!(stderr(&result).lines().count(), 1, "{}", stderr(&result));

    let csv = std::fs::read_to_string(out.join("report.csv")).unwrap();
    let mut lines = csv.lines();
    let header = csv_fields(lines.next().unwrap());
    for column in [
        "config",
        "frame_ms",
        "shadow_pass_ms",
        "rmse_W_per_m2_sr",
        "max_abs_error_W_per_m2_sr",
        "wrong_shadow_fraction",
        "penumbra_mean_abs_dV",
        "pareto",
    ] {
        assert!(
            header.iter().any(|h| h == column),
            "no column {column} in {header:?}"
        );
    }
    let column = |name: &str| header.iter().position(|h| h == name).unwrap();
    let rows: Vec<Vec<String>> = lines.map(csv_fields).collect();
    assert_eq!(rows.len(), 1 + 4 + 1, "{csv}");
    let number = |row: &[String], name: &str| -> f64 { row[column(name)].parse().unwrap() };
    for row in &rows {
        assert_eq!(row.len(), header.len(), "{row:?}");
        for (name, value) in header.iter().zip(row) {
            if name.ends_with("_ms")
                || name.contains("error")
                || name.contains("rmse")
                || name.contains("fraction")
            {
                let v: f64 = value.parse().unwrap_or_else(|_| panic!("{name} = {value}"));
                assert!(v.is_finite() && v >= 0.0, "{name} = {value}");
            }
        }
    }
    let reference = rows.last().unwrap();
    assert_eq!(reference[column("config")], "reference");
    for name in [
        "rmse_W_per_m2_sr",
        "max_abs_error_W_per_m2_sr",
        "wrong_shadow_fraction",
        "penumbra_mean_abs_dV",
    ] {
        assert_eq!(number(reference, name), 0.0, "the reference's {name}");
    }
    // A 256² map with a 3×3 PCF is visibly worse than a 1024² one.
    let rmse_of = |label: &str| {
        let row = rows.iter().find(|r| r[column("config")] == label).unwrap();
        number(row, "rmse_W_per_m2_sr")
    };
    assert!(rmse_of("pcf3 256² auto") > rmse_of("pcf3 1024² auto"));
    assert!(rmse_of("pcf3 1024² auto") > 0.0);

    // The rows marked pareto are exactly the non-dominated ones.
    let points: Vec<(f64, f64, bool)> = rows
        .iter()
        .map(|r| {
            (
                number(r, "frame_ms"),
                number(r, "rmse_W_per_m2_sr"),
                r[column("pareto")] == "true",
            )
        })
        .collect();
    for &(t, e, on) in &points {
        let dominated = points
            .iter()
            .any(|&(t2, e2, _)| t2 <= t && e2 <= e && (t2 < t || e2 < e));
        assert_eq!(on, !dominated, "({t} ms, {e}) marked {on}");
    }

    let pareto = image::open(out.join("pareto.png")).unwrap();
    assert!(pareto.width() >= 800 && pareto.height() >= 600);
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.contains("<table") && html.contains("pareto.png") && html.contains("pcf3 256² auto"));
    // Every image the page shows is in the folder.
    for piece in html.split("src=\"").skip(1) {
        let file = piece.split('"').next().unwrap();
        assert!(
            out.join(file).is_file(),
            "the page shows {file}, which is missing"
        );
    }
    assert_eq!(names_in(&out.join("images")).len(), 1 + 2 * 5);
    let norms = std::fs::read_to_string(out.join("normalization.csv")).unwrap();
    assert!(norms.starts_with("norm,m,k,albedo_0deg,"));
    assert_eq!(norms.lines().count(), 1 + 4 * 4);
    // exact keeps a(0°) = 1.
    for line in norms.lines().filter(|l| l.starts_with("exact,")) {
        let a0: f64 = csv_fields(line)[3].parse().unwrap();
        assert!((a0 - 1.0).abs() < 1e-5, "{line}");
    }

    // Run again into the same folder: the earlier report's files are
    // replaced, the user's own file there stays, and nothing temporary stays
    // beside it.
    assert!(names_in(&out).contains(&".lumlab-report".to_string()));
    std::fs::write(out.join("notes.txt"), "the user's").unwrap();
    let again = run_report(dir.path(), &out);
    assert!(again.status.success(), "{}", stderr(&again));
    assert_eq!(
        std::fs::read_to_string(out.join("notes.txt")).unwrap(),
        "the user's"
    );
    assert_eq!(names_in(dir.path()), ["report", "sweep.toml"]);
}

fn assert_fails_cleanly(args: &[&str], dir: &Path, expected: &str) {
    let before = names_in(dir);
    let out = lumlab(args);
    let text = stderr(&out);
    assert!(!out.status.success(), "{args:?} succeeded");
    assert_eq!(text.lines().count(), 1, "{text}");
    assert!(text.contains(expected), "{args:?}: {text}");
    assert_eq!(names_in(dir), before, "{args:?} left files behind");
}

#[test]
fn bad_input_is_one_line_and_leaves_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("report");
    let out = out.to_str().unwrap();
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "[[config]]\nfilter = \"blurry\"\n").unwrap();
    let bad = bad.to_str().unwrap();
    assert_fails_cleanly(&["report", "--sweep", bad, "--out", out], dir.path(), "blurry");
    let missing = dir.path().join("missing.toml");
    assert_fails_cleanly(
        &["report", "--sweep", missing.to_str().unwrap(), "--out", out],
        dir.path(),
        "missing.toml",
    );
    assert_fails_cleanly(
        &["report", "--filter", "blurry", "--out", out],
        dir.path(),
        "blurry",
    );

    // A folder that cannot be created: its parent is a file.
    let file = dir.path().join("file.txt");
    std::fs::write(&file, "not a folder").unwrap();
    let inside_file = file.join("report");
    assert_fails_cleanly(
        &[
            "report",
            "--size",
            "32x18",
            "--out",
            inside_file.to_str().unwrap(),
        ],
        dir.path(),
        "is not a folder",
    );
    // A folder with someone else's files is not overwritten.
    let foreign = dir.path().join("photos");
    std::fs::create_dir(&foreign).unwrap();
    std::fs::write(foreign.join("cat.jpg"), "meow").unwrap();
    assert_fails_cleanly(
        &["report", "--size", "32x18", "--out", foreign.to_str().unwrap()],
        dir.path(),
        "not empty",
    );
    assert_eq!(names_in(&foreign), ["cat.jpg"]);
    // Nor is one that merely has a report.csv: only the marker a report
    // writes makes a folder the report's own.
    std::fs::write(foreign.join("report.csv"), "my own table").unwrap();
    let out = lumlab(&["report", "--size", "32x18", "--out", foreign.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains(".lumlab-report marker"), "{}", stderr(&out));
    assert_eq!(names_in(&foreign), ["cat.jpg", "report.csv"]);
    assert_eq!(
        std::fs::read_to_string(foreign.join("report.csv")).unwrap(),
        "my own table"
    );
}
