//! `lumlab energy`: the directional albedo a(θ) of the BRDF, as a table for
//! people, CSV or JSON for scripts, and a PNG of the curves.

use super::args::{List, number_list};
use crate::physics::Normalization;
use crate::physics::energy::{AlbedoRow, LECTURE_ANGLES_DEG, MAX_THETA_DEG, albedo_table};
use plotters::prelude::*;
use std::path::PathBuf;

named_enum! {
    /// Output format of `lumlab energy`.
    pub enum EnergyFormat {
        Table = "table",
        Csv = "csv",
        Json = "json",
    }
}

#[derive(Debug, clap::Args)]
pub struct EnergyArgs {
    /// Blinn-Phong exponents, comma separated, each in 0 … 1e6.
    #[arg(long = "m", value_name = "LIST", default_value = "1,2,4,8,16,32,64,128,256,512",
          value_parser = exponents, allow_hyphen_values = true)]
    pub m: List<f64>,
    /// Diffuse/specular mix k ∈ [0, 1]; 0 is the specular lobe alone.
    #[arg(long, value_name = "K", default_value = "0", value_parser = mix, allow_hyphen_values = true)]
    pub k: f64,
    /// Normalizations, comma separated (none, ndf, approx, exact), or all.
    #[arg(long, value_name = "LIST|all", default_value = "all", value_parser = norms)]
    pub norm: List<Normalization>,
    /// Incidence angles θ (degrees), comma separated, each in 0 … 89.99.
    #[arg(long, value_name = "LIST", default_value = "0,30,45,60,75,89",
          value_parser = angles, allow_hyphen_values = true)]
    pub angles: List<f64>,
    /// table (for people), csv or json.
    #[arg(long, value_name = "FORMAT", default_value = "table", value_parser = format)]
    pub format: EnergyFormat,
    /// Also write the a(θ) curves as a PNG figure.
    #[arg(long, value_name = "FILE.png")]
    pub plot: Option<PathBuf>,
}

fn exponents(text: &str) -> Result<List<f64>, String> {
    number_list(
        text,
        "m",
        |m| (0.0..=1e6).contains(&m),
        "each m must be a number in 0 … 1e6",
    )
    .map(List)
}

fn angles(text: &str) -> Result<List<f64>, String> {
    number_list(
        text,
        "angle",
        |t| (0.0..=MAX_THETA_DEG).contains(&t),
        "each angle must be in 0 … 89.99 degrees",
    )
    .map(List)
}

fn mix(text: &str) -> Result<f64, String> {
    super::args::number_in(text, 0.0, 1.0)
}

fn norms(text: &str) -> Result<List<Normalization>, String> {
    if text == "all" {
        return Ok(List(Normalization::ALL.to_vec()));
    }
    text.split(',')
        .map(|n| {
            Normalization::from_name(n.trim()).ok_or_else(|| {
                format!(
                    "unknown normalization '{}' (allowed: {}, or all)",
                    crate::input::escape_controls(n),
                    Normalization::choices()
                )
            })
        })
        .collect::<Result<_, _>>()
        .map(List)
}

fn format(text: &str) -> Result<EnergyFormat, String> {
    text.parse()
}

pub fn run(args: &EnergyArgs) -> anyhow::Result<()> {
    if let Some(path) = &args.plot {
        super::render::check_out("--plot", path)?;
    }
    let rows = albedo_table(&args.norm.0, &args.m.0, args.k, &args.angles.0);
    if let Some(path) = &args.plot {
        write_plot(path, &args.norm.0, &args.m.0, args.k)?;
    }
    let text = match args.format {
        EnergyFormat::Table => table(&rows, &args.angles.0),
        EnergyFormat::Csv => csv(&rows),
        EnergyFormat::Json => serde_json::to_string_pretty(&rows)? + "\n",
    };
    print!("{text}");
    Ok(())
}

/// A number with ten significant digits (CSV keeps at least seven).
fn significant(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x:.9}");
    }
    let decimals = (9 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.decimals$}")
}

fn csv(rows: &[AlbedoRow]) -> String {
    let mut out = String::from("norm,m,k,theta_deg,albedo\n");
    for r in rows {
        out += &format!(
            "{},{},{},{},{}\n",
            r.norm,
            r.m,
            r.k,
            r.theta_deg,
            significant(r.albedo)
        );
    }
    out
}

fn table(rows: &[AlbedoRow], angles: &[f64]) -> String {
    let mut out = String::new();
    let mut any_gain = false;
    for block in rows.chunk_by(|a, b| a.norm == b.norm) {
        let first = block[0];
        out += &format!("{}: {}   (k = {})\n", first.norm, first.norm.formula(), first.k);
        out += &format!("{:>9}", "m");
        for a in angles {
            out += &format!("{:>10}", format!("{a}°"));
        }
        out += "\n";
        for line in block.chunks(angles.len()) {
            out += &format!("{:>9}", line[0].m);
            for r in line {
                let mark = if r.gains_energy() { "*" } else { " " };
                any_gain |= r.gains_energy();
                out += &format!("{:>9.4}{mark}", r.albedo);
            }
            out += "\n";
        }
        out += "\n";
    }
    if any_gain {
        out += "* a(θ) > 1: the BRDF reflects more energy than it receives.\n";
    }
    out
}

/// θ samples for the curves: every degree, then denser towards grazing.
fn curve_angles() -> Vec<f64> {
    let mut t: Vec<f64> = (0..=88).map(f64::from).collect();
    t.extend([88.5, 89.0, 89.5, 89.8, 89.9, MAX_THETA_DEG]);
    t
}

fn write_plot(path: &std::path::Path, norms: &[Normalization], ms: &[f64], k: f64) -> anyhow::Result<()> {
    let thetas = curve_angles();
    let rows = albedo_table(norms, ms, k, &thetas);
    let cols = if norms.len() > 1 { 2 } else { 1 };
    let panel_rows = norms.len().div_ceil(cols);
    let size = (700 * cols as u32, 480 * panel_rows as u32 + 50);
    crate::plot::write_png(path, size, |root| {
        let (title, body) = root.split_vertically(50);
        title.titled(
            &format!(
                "Directional albedo a(θ) = ∫ f_r cos θ_o dω_o   (k = {k}; above 1 the BRDF creates energy)"
            ),
            (crate::plot::FONT, 22),
        )?;
        let panels = body.split_evenly((panel_rows, cols));
        for (panel, (norm_rows, &norm)) in panels.iter().zip(rows.chunks(ms.len() * thetas.len()).zip(norms))
        {
            let y_max = norm_rows.iter().map(|r| r.albedo).fold(1.2_f64, f64::max) * 1.05;
            let mut chart = ChartBuilder::on(panel)
                .caption(format!("{}: {}", norm, norm.formula()), (crate::plot::FONT, 18))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(55)
                .build_cartesian_2d(0.0..90.0, 0.0..y_max)?;
            chart
                .configure_mesh()
                .x_desc("incidence θ (degrees)")
                .y_desc("albedo a(θ) (unitless)")
                .label_style((crate::plot::FONT, 14))
                .x_labels(10)
                .draw()?;
            chart.draw_series(std::iter::once(PathElement::new(
                vec![(0.0, 1.0), (90.0, 1.0)],
                RED.stroke_width(2),
            )))?;
            for (i, curve) in norm_rows.chunks(thetas.len()).enumerate() {
                let color = crate::plot::PALETTE[i % crate::plot::PALETTE.len()];
                chart
                    .draw_series(LineSeries::new(
                        curve.iter().map(|r| (r.theta_deg, r.albedo)),
                        color.stroke_width(2),
                    ))?
                    .label(format!("m = {}", curve[0].m))
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2)));
            }
            for &angle in &LECTURE_ANGLES_DEG {
                chart.draw_series(std::iter::once(PathElement::new(
                    vec![(angle, 0.0), (angle, y_max * 0.03)],
                    BLACK.stroke_width(1),
                )))?;
            }
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::LowerLeft)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .label_font((crate::plot::FONT, 13))
                .draw()?;
        }
        Ok(())
    })
}
