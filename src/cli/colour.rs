//! `lumlab colour`: the 24 ColorChecker patches under an illuminant, the
//! spectral truth against the lecture's RGB product, as a table for people,
//! CSV or JSON for scripts (DESIGN.md's contract), and a PNG figure.

use crate::colour::chart::{illuminant_linear_srgb, mean_and_max};
use crate::colour::data::cmfs;
use crate::colour::tristimulus::{srgb_encode, xyz_to_linear_srgb};
use crate::colour::{Illuminant, PatchComparison, compare_chart};
use crate::plot::Area;
use glam::DVec3;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

named_enum! {
    /// Output format of `lumlab colour`.
    pub enum ColourFormat {
        Table = "table",
        Csv = "csv",
        Json = "json",
    }
}

#[derive(Debug, clap::Args)]
pub struct ColourArgs {
    /// Light source: D65, A, FL2, FL11, LED-B3 (CIE 015:2018 tables) or
    /// blackbody:K (Planck's law, K in 1000 … 25000). Without it, all five
    /// named illuminants, one after another (D65 first: the reference, where
    /// RGB and spectral agree).
    #[arg(long, value_name = "NAME", value_parser = illuminant)]
    pub illuminant: Option<Illuminant>,
    /// table (for people), csv or json.
    #[arg(long, value_name = "FORMAT", default_value = "table", value_parser = format)]
    pub format: ColourFormat,
    /// Also draw the illuminant's spectrum, the CIE 1931 colour-matching
    /// functions and the chart (spectral above, RGB product below, ΔE2000
    /// in each cell) as a PNG figure.
    #[arg(long, value_name = "FILE.png", value_parser = png_path)]
    pub plot: Option<PathBuf>,
}

fn illuminant(text: &str) -> Result<Illuminant, String> {
    text.parse()
}

fn format(text: &str) -> Result<ColourFormat, String> {
    text.parse()
}

fn png_path(text: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(text);
    match path.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("png") => Ok(path),
        _ => Err(format!("'{text}' must end in .png")),
    }
}

/// One illuminant's chart, what every format prints.
#[derive(serde::Serialize)]
struct Block {
    illuminant: String,
    description: String,
    /// The illuminant's linear sRGB, Y = 1: the RGB product's light colour.
    light_linear_srgb: [f64; 3],
    mean_delta_e2000: f64,
    max_delta_e2000: f64,
    patches: Vec<PatchRow>,
}

#[derive(serde::Serialize)]
struct PatchRow {
    patch: &'static str,
    xyz: [f64; 3],
    approx_xyz: [f64; 3],
    delta_e2000: f64,
}

fn block(illuminant: Illuminant) -> (Block, Vec<PatchComparison>) {
    let rows = compare_chart(illuminant);
    let (mean, max) = mean_and_max(&rows);
    let block = Block {
        illuminant: illuminant.name(),
        description: illuminant.description(),
        light_linear_srgb: illuminant_linear_srgb(&illuminant.spectrum()).to_array(),
        mean_delta_e2000: mean,
        max_delta_e2000: max,
        patches: rows
            .iter()
            .map(|r| PatchRow {
                patch: r.name(),
                xyz: r.spectral_xyz.to_array(),
                approx_xyz: r.approx_xyz.to_array(),
                delta_e2000: r.delta_e2000,
            })
            .collect(),
    };
    (block, rows)
}

pub fn run(args: &ColourArgs) -> anyhow::Result<()> {
    let illuminants = match args.illuminant {
        Some(i) => vec![i],
        None => Illuminant::NAMED.to_vec(),
    };
    let charts: Vec<(Illuminant, (Block, Vec<PatchComparison>))> =
        illuminants.iter().map(|&i| (i, block(i))).collect();
    if let Some(path) = &args.plot {
        let figures: Vec<(Illuminant, &[PatchComparison])> = charts
            .iter()
            .map(|(i, (_, rows))| (*i, rows.as_slice()))
            .collect();
        write_plot(path, &figures)?;
    }
    let blocks: Vec<&Block> = charts.iter().map(|(_, (b, _))| b).collect();
    let text = match args.format {
        ColourFormat::Table => table(&blocks),
        ColourFormat::Csv => csv(&blocks),
        ColourFormat::Json => serde_json::to_string_pretty(&blocks)? + "\n",
    };
    print!("{text}");
    Ok(())
}

/// The CSV contract of DESIGN.md: one row per illuminant and patch.
fn csv(blocks: &[&Block]) -> String {
    let mut out = String::from("illuminant,patch,X,Y,Z,approx_X,approx_Y,approx_Z,delta_e2000\n");
    for b in blocks {
        for p in &b.patches {
            let [x, y, z] = p.xyz;
            let [ax, ay, az] = p.approx_xyz;
            out += &format!(
                "{},{},{x:.6},{y:.6},{z:.6},{ax:.6},{ay:.6},{az:.6},{:.6}\n",
                b.illuminant, p.patch, p.delta_e2000
            );
        }
    }
    out
}

fn table(blocks: &[&Block]) -> String {
    let mut out = String::new();
    for b in blocks {
        let [r, g, bl] = b.light_linear_srgb;
        out += &format!(
            "{} — {}   (light's linear sRGB at Y = 1: {r:.3}, {g:.3}, {bl:.3})\n",
            b.illuminant, b.description
        );
        out += &format!(
            "{:<14}{:>27}{:>27}{:>9}\n",
            "patch", "spectral X, Y, Z", "RGB product X, Y, Z", "ΔE2000"
        );
        for p in &b.patches {
            let xyz = |v: [f64; 3]| format!("{:>9.3}{:>9.3}{:>9.3}", v[0], v[1], v[2]);
            out += &format!(
                "{:<14}{}{}{:>9.2}\n",
                p.patch,
                xyz(p.xyz),
                xyz(p.approx_xyz),
                p.delta_e2000
            );
        }
        out += &format!(
            "mean ΔE2000 {:.2}, max {:.2}\n\n",
            b.mean_delta_e2000, b.max_delta_e2000
        );
    }
    out += "How far the RGB product (patch colour under white × light colour) is from the spectral result:\n";
    out += &format!(
        "{:<18}{:>12}{:>12}  {}\n",
        "illuminant", "mean ΔE2000", "max ΔE2000", "worst patch"
    );
    for b in blocks {
        let worst = b
            .patches
            .iter()
            .max_by(|a, c| a.delta_e2000.total_cmp(&c.delta_e2000))
            .map_or("", |p| p.patch);
        out += &format!(
            "{:<18}{:>12.2}{:>12.2}  {worst}\n",
            b.illuminant, b.mean_delta_e2000, b.max_delta_e2000
        );
    }
    out += "(ΔE2000 ≈ 1: just noticeable side by side; above 3: plainly different.)\n";
    out
}

/// 8-bit sRGB for display of a linear colour, clamped to the gamut.
fn display(rgb: DVec3) -> RGBColor {
    let c = rgb
        .clamp(DVec3::ZERO, DVec3::ONE)
        .to_array()
        .map(|v| (255.0 * srgb_encode(v)).round() as u8);
    RGBColor(c[0], c[1], c[2])
}

/// Black or white text, whichever reads on `background`.
fn ink(background: RGBColor) -> RGBColor {
    let RGBColor(r, g, b) = background;
    let luma = 0.299 * f64::from(r) + 0.587 * f64::from(g) + 0.114 * f64::from(b);
    if luma > 140.0 { BLACK } else { WHITE }
}

const ROW_HEIGHT: u32 = 480;
/// Height of the wavelength-hue strip below the curves (plot units).
const STRIP: f64 = 0.1;
const TITLE_HEIGHT: u32 = 56;

fn write_plot(path: &Path, charts: &[(Illuminant, &[PatchComparison])]) -> anyhow::Result<()> {
    let size = (1500, TITLE_HEIGHT + ROW_HEIGHT * charts.len() as u32);
    crate::plot::write_png(path, size, |root| {
        let (title, body) = root.split_vertically(TITLE_HEIGHT);
        title.titled(
            "ColorChecker: spectral (top of each cell) against the RGB product (bottom), ΔE2000 per patch",
            (crate::plot::FONT, 24),
        )?;
        let rows = body.split_evenly((charts.len(), 1));
        for (row, (illuminant, patches)) in rows.iter().zip(charts) {
            let (left, right) = row.split_horizontally(640);
            draw_spectra(&left, *illuminant)?;
            draw_swatches(&right, *illuminant, patches)?;
        }
        Ok(())
    })
}

/// The illuminant's relative power (peak = 1) over the CIE 1931 x̄, ȳ, z̄,
/// with the colour of each wavelength along the axis.
fn draw_spectra(area: &Area<'_>, illuminant: Illuminant) -> anyhow::Result<()> {
    let power = illuminant.spectrum().normalized_to_peak();
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!("{}: spectrum and CIE 1931 2° CMFs", illuminant.name()),
            (crate::plot::FONT, 19),
        )
        .margin(14)
        .x_label_area_size(52)
        .y_label_area_size(50)
        .build_cartesian_2d(380.0..780.0, -STRIP..1.9)?;
    chart
        .configure_mesh()
        .x_desc("wavelength λ (nm)")
        .y_desc("relative value")
        .label_style((crate::plot::FONT, 14))
        .x_labels(9)
        .x_label_formatter(&|nm| format!("{nm:.0}"))
        .y_label_formatter(&|v| {
            if *v < 0.0 {
                String::new()
            } else {
                format!("{v:.1}")
            }
        })
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    // The hue of each wavelength, in a strip under the curves: linear sRGB
    // of the CMFs, scaled to the brightest component, clamped to the gamut
    // and dimmed where the eye is least sensitive.
    let [x_bar, y_bar, z_bar] = cmfs();
    for (i, nm) in crate::colour::Spectrum::wavelengths_nm().enumerate() {
        let rgb = xyz_to_linear_srgb(DVec3::new(x_bar.0[i], y_bar.0[i], z_bar.0[i]));
        let rgb = rgb.max(DVec3::ZERO);
        let hue = display(rgb / rgb.max_element().max(1e-9) * (y_bar.0[i] * 4.0).min(1.0));
        chart.draw_series(std::iter::once(Rectangle::new(
            [(nm - 2.5, -STRIP), (nm + 2.5, -0.2 * STRIP)],
            hue.filled(),
        )))?;
    }
    chart
        .draw_series(
            AreaSeries::new(power.samples(), 0.0, RGBColor(0, 0, 0).mix(0.08))
                .border_style(BLACK.stroke_width(3)),
        )?
        .label(format!("S(λ) of {}, peak = 1", illuminant.name()))
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLACK.stroke_width(3)));
    let curves = [
        // The font has no combining macron: "x-bar" rather than a broken x̄.
        ("x-bar(λ)", x_bar, RGBColor(214, 39, 40)),
        ("y-bar(λ)", y_bar, RGBColor(44, 160, 44)),
        ("z-bar(λ)", z_bar, RGBColor(31, 119, 180)),
    ];
    for (name, cmf, color) in curves {
        chart
            .draw_series(LineSeries::new(cmf.samples(), color.stroke_width(2)))?
            .label(name)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2)));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((crate::plot::FONT, 14))
        .draw()?;
    Ok(())
}

/// The 6 × 4 chart: each cell the spectral colour above the RGB product's,
/// both white-balanced for this light (linear sRGB ÷ the light's linear
/// sRGB), as an adapted eye sees them and as ΔE2000 relative to the light's
/// white measures them. So balanced, the RGB product is the patch's daylight
/// colour: what changes from the top half to the bottom is what RGB misses.
fn draw_swatches(area: &Area<'_>, illuminant: Illuminant, patches: &[PatchComparison]) -> anyhow::Result<()> {
    let (mean, max) = mean_and_max(patches);
    let (caption, grid) = area.split_vertically(44);
    caption.draw(&Text::new(
        format!(
            "{} — ΔE2000 mean {mean:.2}, max {max:.2} (white-balanced)",
            illuminant.description()
        ),
        (10, 14),
        (crate::plot::FONT, 18).into_font().color(&BLACK),
    ))?;
    let balance = DVec3::ONE / illuminant_linear_srgb(&illuminant.spectrum()).max(DVec3::splat(1e-9));
    let (width, height) = grid.dim_in_pixel();
    let (cols, rows) = (6_i32, 4_i32);
    let gap = 6;
    let cell_w = (width as i32 - 20 - gap * (cols - 1)) / cols;
    let cell_h = (height as i32 - 20 - gap * (rows - 1)) / rows;
    let name_style = (crate::plot::FONT, 13).into_font();
    let value_style = (crate::plot::FONT, 17).into_font();
    for p in patches {
        let (col, row) = (p.patch as i32 % cols, p.patch as i32 / cols);
        let x0 = 10 + col * (cell_w + gap);
        let y0 = row * (cell_h + gap);
        let mid = y0 + cell_h / 2;
        let spectral = display(xyz_to_linear_srgb(p.spectral_xyz / 100.0) * balance);
        let approx = display(xyz_to_linear_srgb(p.approx_xyz / 100.0) * balance);
        grid.draw(&Rectangle::new([(x0, y0), (x0 + cell_w, mid)], spectral.filled()))?;
        grid.draw(&Rectangle::new(
            [(x0, mid), (x0 + cell_w, y0 + cell_h)],
            approx.filled(),
        ))?;
        grid.draw(&Text::new(
            p.name(),
            (x0 + 5, y0 + 4),
            name_style.clone().color(&ink(spectral)),
        ))?;
        grid.draw(&Text::new(
            format!("ΔE {:.2}", p.delta_e2000),
            (x0 + 5, y0 + cell_h - 22),
            value_style.clone().color(&ink(approx)),
        ))?;
    }
    Ok(())
}
