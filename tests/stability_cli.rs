//! `lumlab stability`: every hard case passes in f64, f32 and on the GPU, the
//! naive formulas visibly break, and a missing GPU is a one-line error.

mod cli_support;

use cli_support::{csv_rows, lumlab, lumlab_with_env, stderr_lines, stdout};

/// The CSV contract scripts rely on.
const HEADER: &str = "quantity,case,f64,f32,gpu,diff_f32,diff_gpu,tol_f32,tol_gpu,abs_floor,defined,naive_f32,diff_naive,naive_flag,status,why";

fn finite(field: &str) -> bool {
    field.parse::<f64>().is_ok_and(f64::is_finite)
}

#[test]
fn every_case_is_ok_on_the_gpu_and_naive_formulas_break() {
    let out = lumlab(&["stability", "--format", "csv"]);
    assert!(out.status.success(), "{:?}", stderr_lines(&out));
    let rows = csv_rows(&stdout(&out), HEADER);
    assert!(rows.len() > 250, "{} rows", rows.len());
    for row in &rows {
        let case = format!("{} {}", row["quantity"], row["case"]);
        assert_eq!(row["status"], "ok", "{case}: {}", row["why"]);
        for column in ["f64", "f32", "gpu", "diff_f32", "diff_gpu"] {
            assert!(finite(&row[column]), "{case}: {column} = {}", row[column]);
        }
    }
    let flags: Vec<&str> = rows.iter().map(|r| r["naive_flag"].as_str()).collect();
    for flag in ["NaN", "Inf", "error"] {
        assert!(flags.contains(&flag), "no naive value flagged {flag}");
    }
    // Every quantity of the issue is in the grid.
    for quantity in ["norm", "lobe", "brdf", "irradiance", "sphere", "depth", "shadow"] {
        assert!(rows.iter().any(|r| r["quantity"] == quantity), "{quantity}");
    }
    // The defined values of DESIGN.md are checked, not only compared.
    for rule in [
        "0^0 = 1",
        "l + o = 0 → 0",
        "Φ = 0 → 0",
        "r < 1 µm",
        "1 mm behind → hidden",
    ] {
        assert!(rows.iter().any(|r| r["defined"].contains(rule)), "{rule}");
    }
}

#[test]
fn the_table_explains_each_group_and_sums_up() {
    let out = lumlab(&["stability"]);
    assert!(out.status.success(), "{:?}", stderr_lines(&out));
    let text = stdout(&out);
    for group in ["norm", "lobe", "brdf", "irradiance", "sphere", "depth", "shadow"] {
        assert!(text.contains(&format!("\n== {group}: ")), "no group {group}");
    }
    assert!(text.contains("naive f32: pow(cos θh, m)"));
    assert!(text.contains("tolerance: Δ ≤"));
    assert!(text.contains("== summary"));
    assert!(text.contains("cases ok"));
    assert!(!text.contains("FAIL"));
}

#[test]
fn without_an_adapter_the_install_hint_is_one_line_unless_cpu_only() {
    // No Metal on the machines the tests run on: no adapter at all.
    let no_gpu = [("WGPU_BACKEND", "metal")];
    let out = lumlab_with_env(&["stability"], &no_gpu);
    assert_eq!(out.status.code(), Some(1));
    let err = stderr_lines(&out);
    assert_eq!(err.len(), 1, "{err:?}");
    assert!(
        err[0].contains("apt-get install") && err[0].contains("--cpu-only"),
        "{}",
        err[0]
    );
    assert!(stdout(&out).is_empty());

    let out = lumlab_with_env(&["stability", "--cpu-only", "--format", "csv"], &no_gpu);
    assert!(out.status.success(), "{:?}", stderr_lines(&out));
    let rows = csv_rows(&stdout(&out), HEADER);
    assert!(rows.iter().all(|r| r["gpu"].is_empty() && r["status"] == "ok"));
}

#[test]
fn an_unknown_format_is_a_usage_error() {
    let out = lumlab(&["stability", "--format", "json"]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr_lines(&out);
    assert_eq!(err.len(), 1, "{err:?}");
    assert!(err[0].contains("table|csv"), "{}", err[0]);
}
