//! `lumlab colour`: the CSV contract of DESIGN.md, the published white
//! points, the agreement under D65, and one-line usage errors.

mod cli_support;

use cli_support::{csv_rows, lumlab, stderr, stdout};
use std::collections::HashMap;

/// DESIGN.md's columns, exactly.
const HEADER: &str = "illuminant,patch,X,Y,Z,approx_X,approx_Y,approx_Z,delta_e2000";

fn number(row: &HashMap<String, String>, column: &str) -> f64 {
    row[column]
        .parse()
        .unwrap_or_else(|_| panic!("{column} = '{}' is a number", row[column]))
}

#[test]
fn csv_has_the_contract_columns_and_24_rows_per_illuminant() {
    let out = lumlab(&["colour", "--format", "csv"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let rows = csv_rows(&stdout(&out), HEADER);
    let mut order: Vec<String> = Vec::new();
    let mut counts: HashMap<String, usize> = HashMap::new();
    for r in &rows {
        if order.last() != Some(&r["illuminant"]) {
            order.push(r["illuminant"].clone());
        }
        *counts.entry(r["illuminant"].clone()).or_default() += 1;
        for c in ["X", "Y", "Z", "approx_X", "approx_Y", "approx_Z", "delta_e2000"] {
            assert!(number(r, c).is_finite());
        }
    }
    // Without --illuminant: the five named illuminants, D65 first.
    assert_eq!(order, ["D65", "A", "FL2", "FL11", "LED-B3"]);
    assert!(counts.values().all(|&n| n == 24), "{counts:?}");
    assert_eq!(rows[0]["patch"], "dark skin");
    assert_eq!(rows[23]["patch"], "black 2");
}

#[test]
fn white_patch_under_d65_is_near_the_cie_white_point() {
    // The white patch reflects about 88 % (N. Ohta), so its XYZ is about
    // 0.88 × (95.047, 100, 108.883): chromaticity near D65's (0.3127, 0.3290).
    let out = lumlab(&["colour", "--illuminant", "D65", "--format", "csv"]);
    let rows = csv_rows(&stdout(&out), HEADER);
    assert_eq!(rows.len(), 24);
    let white = rows
        .iter()
        .find(|r| r["patch"] == "white 9.5")
        .expect("white patch");
    let (x, y, z) = (number(white, "X"), number(white, "Y"), number(white, "Z"));
    let sum = x + y + z;
    assert!((x / sum - 0.3127).abs() < 5e-3 && (y / sum - 0.3290).abs() < 5e-3);
    assert!((80.0..95.0).contains(&y), "Y = {y}");
}

#[test]
fn under_d65_the_rgb_product_equals_the_spectral_result() {
    let out = lumlab(&["colour", "--illuminant", "D65", "--format", "csv"]);
    for r in csv_rows(&stdout(&out), HEADER) {
        assert!(
            number(&r, "delta_e2000") < 0.05,
            "{}: {}",
            r["patch"],
            r["delta_e2000"]
        );
    }
}

#[test]
fn blackbody_illuminant_is_accepted_and_named() {
    let out = lumlab(&["colour", "--illuminant", "blackbody:3000", "--format", "csv"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let rows = csv_rows(&stdout(&out), HEADER);
    assert_eq!(rows.len(), 24);
    assert!(rows.iter().all(|r| r["illuminant"] == "blackbody:3000"));
}

#[test]
fn table_ends_with_each_illuminants_mean_and_max() {
    let out = lumlab(&["colour"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    let summary = text.rsplit("How far").next().expect("a summary");
    for name in ["D65", "A", "FL2", "FL11", "LED-B3"] {
        assert!(
            summary.lines().any(|l| l.split_whitespace().next() == Some(name)),
            "{name} in\n{summary}"
        );
    }
    assert!(summary.contains("mean ΔE2000") && summary.contains("max ΔE2000"));
}

#[test]
fn json_lists_each_illuminant_with_its_patches() {
    let out = lumlab(&["colour", "--illuminant", "FL11", "--format", "json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("valid JSON");
    assert_eq!(v[0]["illuminant"], "FL11");
    assert_eq!(v[0]["patches"].as_array().map(Vec::len), Some(24));
    assert!(v[0]["max_delta_e2000"].as_f64().is_some_and(|m| m > 0.0));
}

#[test]
fn bad_illuminant_is_one_line_and_exit_2() {
    for bad in ["D50", "blackbody:500", "blackbody:hot"] {
        let out = lumlab(&["colour", "--illuminant", bad]);
        assert_eq!(out.status.code(), Some(2), "{bad}");
        let err = stderr(&out);
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains("illuminant") || err.contains("blackbody"), "{err}");
        assert!(out.stdout.is_empty());
    }
}

#[test]
fn plot_is_a_png_and_a_bad_plot_path_leaves_nothing() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let png = dir.path().join("colour-A.png");
    let out = lumlab(&["colour", "--illuminant", "A", "--plot", png.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    let bytes = std::fs::read(&png).expect("the figure was written");
    assert!(bytes.starts_with(b"\x89PNG"));

    let wrong = dir.path().join("colour.jpg");
    let out = lumlab(&["colour", "--plot", wrong.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(stderr(&out).trim_end().lines().count(), 1);

    let missing = dir.path().join("no-such-dir").join("colour.png");
    let out = lumlab(&["colour", "--plot", missing.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(stderr(&out).trim_end().lines().count(), 1);
    let leftovers: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .flatten()
        .map(|e| e.file_name())
        .collect();
    assert_eq!(leftovers, vec![std::ffi::OsString::from("colour-A.png")]);
}
