//! `lumlab stability`: the hard-case grid, f64 reference / f32 mirror / GPU,
//! with the naive formulas beside them. A table for class, CSV for scripts;
//! exits with 1 when any value is non-finite or beyond its tolerance.

use crate::gpu::GpuContext;
use crate::stability::{Report, Row, Summary, run};
use anyhow::Context;

named_enum! {
    /// Output format of `lumlab stability`.
    pub enum StabilityFormat {
        Table = "table",
        Csv = "csv",
    }
}

#[derive(Debug, clap::Args)]
pub struct StabilityArgs {
    /// table (grouped by quantity, for people) or csv.
    #[arg(long, value_name = "FORMAT", default_value = "table", value_parser = parse_format)]
    pub format: StabilityFormat,
    /// Leave out the GPU column: no adapter needed.
    #[arg(long)]
    pub cpu_only: bool,
}

fn parse_format(text: &str) -> Result<StabilityFormat, String> {
    text.parse()
}

pub fn run_command(args: &StabilityArgs) -> anyhow::Result<()> {
    let gpu = if args.cpu_only {
        None
    } else {
        Some(GpuContext::headless().context("the GPU column needs an adapter (or pass --cpu-only)")?)
    };
    let report = run(gpu.as_ref());
    let text = match args.format {
        StabilityFormat::Table => table(&report),
        StabilityFormat::Csv => csv(&report),
    };
    print!("{text}");
    let failed = report.failed();
    if failed > 0 {
        anyhow::bail!(
            "{failed} of {} hard cases failed (a non-finite value, a difference beyond its tolerance or a defined value not met)",
            report.rows.len()
        );
    }
    Ok(())
}

/// A value in the table: six significant digits, and a plain 0.
fn value(x: f64) -> String {
    if x == 0.0 { "0".into() } else { format!("{x:.5e}") }
}

/// A difference in the table: two significant digits, 0 when equal.
fn diff(d: f64) -> String {
    if d == 0.0 { "0".into() } else { format!("{d:.1e}") }
}

/// A tolerance as written in the source: 1e-6, 4e-6 + 8e-7√m, 0.
fn tol(base: f64, per_sqrt_m: f64) -> String {
    match (base, per_sqrt_m) {
        (0.0, 0.0) => "0 (exact)".into(),
        (b, 0.0) => format!("{b:e}"),
        (b, p) => format!("{b:e} + {p:e}√m"),
    }
}

fn table(report: &Report) -> String {
    let mut out = format!(
        "lumlab stability: {} hard cases, each computed by the same physics in f64 (the reference),\nin f32 on the CPU (the GPU's precision) and on the GPU by the renderer's own WGSL functions.\n",
        report.rows.len()
    );
    out += &match &report.adapter {
        Some(name) => format!("GPU: {name}\n"),
        None => "GPU: not run (--cpu-only)\n".into(),
    };
    out += "Inputs are rounded to f32 first, so Δ measures arithmetic: Δ = |x − f64| / max(|f64|, floor × scale).\n";
    out += "Naive f32 values show what the guards are for; flagged (NaN, Inf, error = Δ beyond the f32\ntolerance), they never fail a case.\n";
    for block in report.rows.chunk_by(|a, b| a.case.quantity == b.case.quantity) {
        out += &group(block);
    }
    out += &summary(report);
    out
}

fn group(rows: &[Row]) -> String {
    let quantity = rows[0].case.quantity;
    let t = quantity.tolerance();
    let mut out = format!("\n== {}: {}\n", quantity, quantity.title());
    for line in quantity.explanation() {
        out += &format!("   {line}\n");
    }
    out += &if t.f32 == 0.0 && t.gpu == 0.0 {
        "   tolerance: none, every column must give the defined value\n".to_string()
    } else {
        let against = match (quantity.scale_name(), t.floor) {
            (None, _) => "relative".to_string(),
            (Some(scale), 1.0) => format!("relative to max(|f64|, {scale})"),
            (Some(scale), floor) => format!("relative to max(|f64|, {floor:e} × {scale})"),
        };
        format!(
            "   tolerance: Δ ≤ {} (f32), {} (GPU), {against}\n",
            tol(t.f32, t.per_sqrt_m),
            tol(t.gpu, t.per_sqrt_m),
        )
    };
    let has_naive = rows.iter().any(|r| r.naive.is_some());
    let width = rows
        .iter()
        .map(|r| r.case.label.chars().count())
        .max()
        .unwrap_or(0);
    out += &format!(
        "   {:<width$} {:>12} {:>12} {:>12} {:>7} {:>7}",
        "case", "f64", "f32", "GPU", "Δf32", "ΔGPU"
    );
    if has_naive {
        out += &format!(" {:>12} {:>7} {:<5}", "naive f32", "Δnaive", "");
    }
    out += "\n";
    for r in rows {
        out += &format!(
            "   {:<width$} {:>12} {:>12} {:>12} {:>7} {:>7}",
            r.case.label,
            value(r.f64),
            value(r.f32),
            r.gpu.map_or("-".into(), value),
            diff(r.diff_f32()),
            r.diff_gpu().map_or("-".into(), diff),
        );
        if has_naive {
            match (r.naive, r.naive_flag()) {
                (Some(x), Some(flag)) => {
                    let d = if x.is_finite() {
                        diff(r.diff(x))
                    } else {
                        "-".into()
                    };
                    out += &format!(" {:>12} {:>7} {:<5}", value(x), d, flag.name())
                }
                _ => out += &format!(" {:>12} {:>7} {:<5}", "-", "", ""),
            }
        }
        out += &format!(" {:<4}", if r.ok() { "ok" } else { "FAIL" });
        if let Some(d) = r.case.defined {
            out += &format!(" {}", d.rule);
        }
        if let Some(why) = r.failure() {
            out += &format!(" ({why})");
        }
        out = out.trim_end().to_string() + "\n";
    }
    out
}

fn summary(report: &Report) -> String {
    let summaries = report.summaries();
    let mut out = String::from("\n== summary: worst Δ against f64, and how many naive values broke\n");
    out += &format!(
        "   {:<11} {:>5} {:>10} {:>15} {:>10} {:>15} {:>13} {:>6}\n",
        "quantity", "cases", "worst f32", "tol f32", "worst GPU", "tol GPU", "naive broken", "failed"
    );
    for s in &summaries {
        out += &summary_line(s);
    }
    let failed = report.failed();
    let naive_broken: usize = summaries.iter().map(|s| s.naive_broken).sum();
    let naive_cases: usize = summaries.iter().map(|s| s.naive_cases).sum();
    out += &format!(
        "   naive formulas: {naive_broken} of {naive_cases} values broke (NaN, Inf or beyond tolerance).\n"
    );
    if failed == 0 {
        out += &format!(
            "   lumlab: all {} cases ok: every value finite, within tolerance of f64 or equal to its defined value.\n",
            report.rows.len()
        );
    } else {
        out += &format!("   lumlab: {failed} of {} cases FAILED.\n", report.rows.len());
    }
    out
}

fn summary_line(s: &Summary) -> String {
    let t = s.quantity.tolerance();
    let naive = if s.naive_cases == 0 {
        "-".to_string()
    } else {
        format!("{} of {}", s.naive_broken, s.naive_cases)
    };
    format!(
        "   {:<11} {:>5} {:>10} {:>15} {:>10} {:>15} {:>13} {:>6}\n",
        s.quantity.name(),
        s.cases,
        diff(s.worst_f32),
        tol(t.f32, t.per_sqrt_m),
        s.worst_gpu.map_or("-".into(), diff),
        tol(t.gpu, t.per_sqrt_m),
        naive,
        s.failed
    )
}

/// A CSV field, quoted when it holds a comma or a quote.
fn field(text: &str) -> String {
    if text.contains([',', '"', '\n']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// The CSV header: one row per case, every number in full precision.
pub const CSV_HEADER: &str = "quantity,case,f64,f32,gpu,diff_f32,diff_gpu,tol_f32,tol_gpu,abs_floor,defined,naive_f32,diff_naive,naive_flag,status,why";

fn csv(report: &Report) -> String {
    let mut out = format!("{CSV_HEADER}\n");
    for r in &report.rows {
        let (f32_limit, gpu_limit) = r.limits();
        let optional = |x: Option<f64>| x.map_or(String::new(), |x| format!("{x:e}"));
        let cells = [
            r.case.quantity.name().to_string(),
            field(&r.case.label),
            format!("{:e}", r.f64),
            format!("{:e}", r.f32),
            optional(r.gpu),
            format!("{:e}", r.diff_f32()),
            optional(r.diff_gpu()),
            format!("{f32_limit:e}"),
            format!("{gpu_limit:e}"),
            format!("{:e}", r.abs_floor()),
            field(r.case.defined.map_or("", |d| d.rule)),
            optional(r.naive),
            optional(r.naive.map(|x| r.diff(x))),
            r.naive_flag().map_or("", |f| f.name()).to_string(),
            if r.ok() { "ok" } else { "FAIL" }.to_string(),
            field(&r.failure().unwrap_or_default()),
        ];
        out += &cells.join(",");
        out += "\n";
    }
    out
}
