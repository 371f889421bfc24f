//! The report's files: `report.csv`, `normalization.csv`, `pareto.png`, the
//! images of every configuration and `index.html`, which shows them all
//! and opens from the folder without a server.

use super::metrics::{ErrorMetrics, Frame};
use super::{Measured, Report};
use crate::gpu::colormap;
use crate::physics::energy::LECTURE_ANGLES_DEG;
use crate::plot::{FONT, PALETTE};
use crate::settings::{DebugView, Filter, Visibility};
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::Path;

/// The CSV header: one row per configuration, then the reference.
pub const CSV_HEADER: &str = "config,device,filter,resolution_texels,bias,frame_ms,shadow_pass_ms,blur_pass_ms,\
shade_pass_ms,display_pass_ms,wall_ms,rmse_W_per_m2_sr,relative_rmse,max_abs_error_W_per_m2_sr,\
wrong_shadow_fraction,penumbra_mean_abs_dV,penumbra_pixels,pareto";

/// The signed luminance error as the app's `error` view colours it: the
/// diverging ramp, white at 0, saturated at ±`scale`; background dark grey.
pub fn error_image(
    signed: &[f64],
    frame: &Frame,
    (width, height): (u32, u32),
    scale: f64,
) -> image::RgbaImage {
    let mut out = image::RgbaImage::from_pixel(width, height, image::Rgba([40, 40, 40, 255]));
    for (i, (&e, &c)) in signed.iter().zip(&frame.coverage).enumerate() {
        if c <= 0.0 && e == 0.0 {
            continue;
        }
        let t = (0.5 + 0.5 * e / scale) as f32;
        let rgb = colormap::sample(&colormap::DIVERGING, t).map(|v| (v * 255.0).round() as u8);
        out.put_pixel(
            i as u32 % width,
            i as u32 / width,
            image::Rgba([rgb[0], rgb[1], rgb[2], 255]),
        );
    }
    out
}

/// Writes every file of the report into `dir` (which exists).
pub fn write(report: &Report, dir: &Path) -> anyhow::Result<()> {
    let images = dir.join("images");
    std::fs::create_dir_all(&images)?;
    crate::image_io::write_png_rgba8(&images.join("reference.png"), &report.reference_display)?;
    let legend = colormap::legend(DebugView::Error, report.error_scale as f32);
    for (i, c) in report.configurations.iter().enumerate() {
        crate::image_io::write_png_rgba8(&images.join(image_name(i, c, "shaded")), &c.shaded)?;
        let error = match &legend {
            Some(legend) => crate::plot::with_legend(&c.error_image, legend)?,
            None => c.error_image.clone(),
        };
        crate::image_io::write_png_rgba8(&images.join(image_name(i, c, "error")), &error)?;
    }
    crate::output::write_atomically(&dir.join("report.csv"), csv(report).as_bytes())?;
    crate::output::write_atomically(
        &dir.join("normalization.csv"),
        normalization_csv(report).as_bytes(),
    )?;
    pareto_plot(report, &dir.join("pareto.png"))?;
    crate::output::write_atomically(&dir.join("index.html"), html(report).as_bytes())?;
    Ok(())
}

/// `images/03-pcf3-512-auto-error.png`: numbered in sweep order.
fn image_name(index: usize, c: &Measured, kind: &str) -> String {
    let slug: String = c
        .label
        .chars()
        .map(|ch| {
            if ch.is_ascii_alphanumeric() || ch == '.' {
                ch
            } else {
                '-'
            }
        })
        .collect::<String>()
        .split('-')
        .filter(|s| !s.is_empty())
        .collect::<Vec<_>>()
        .join("-");
    format!("{:02}-{slug}-{kind}.png", index + 1)
}

/// A CSV field, quoted when it holds a comma or a quote.
fn field(text: &str) -> String {
    if text.contains([',', '"', '\n']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// One CSV row per configuration, then the reference (error 0 by construction).
pub fn csv(report: &Report) -> String {
    let mut out = format!("{CSV_HEADER}\n");
    let error_fields = |e: &ErrorMetrics| {
        format!(
            "{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{}",
            e.rmse,
            e.relative_rmse,
            e.max_abs,
            e.wrong_shadow_fraction,
            e.penumbra_mean_abs_dv,
            e.penumbra_pixels
        )
    };
    for (c, pareto) in report.configurations.iter().zip(&report.pareto) {
        let t = &c.times;
        let _ = writeln!(
            out,
            "{},gpu,{},{},{},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{},{}",
            field(&c.label),
            // The filter column names the method when there is no shadow map.
            match c.shadow.visibility {
                Visibility::ShadowMap => c.shadow.filter.to_string(),
                Visibility::RayTraced => Visibility::RayTraced.to_string(),
            },
            c.resolution_used,
            field(&c.shadow.bias.describe()),
            t.frame_ms,
            t.shadow_ms,
            t.blur_ms,
            t.shade_ms,
            t.display_ms,
            t.wall_ms,
            error_fields(&c.error),
            pareto
        );
    }
    let ms = report.reference_time.as_secs_f64() * 1e3;
    let _ = writeln!(
        out,
        "reference,cpu,raytraced,0,none,{ms:.3},0,0,0,0,{ms:.3},{},{}",
        error_fields(&report.reference_error),
        report.pareto.last().copied().unwrap_or(true)
    );
    out
}

fn angle_columns() -> String {
    LECTURE_ANGLES_DEG
        .iter()
        .map(|a| format!("albedo_{a}deg"))
        .collect::<Vec<_>>()
        .join(",")
}

fn normalization_csv(report: &Report) -> String {
    let mut out = format!("norm,m,k,{},mean_radiance_W_per_m2_sr\n", angle_columns());
    for row in &report.normalization {
        let albedo: Vec<String> = row.albedo.iter().map(|a| format!("{a:.7}")).collect();
        let _ = writeln!(
            out,
            "{},{},0,{},{:.6e}",
            row.norm,
            row.m,
            albedo.join(","),
            row.mean_radiance
        );
    }
    out
}

/// Time against error: every configuration coloured by filter, the
/// Pareto front drawn as a staircase and its points labelled.
fn pareto_plot(report: &Report, path: &Path) -> anyhow::Result<()> {
    let reference_ms = report.reference_time.as_secs_f64() * 1e3;
    let mut points: Vec<(f64, f64)> = report
        .configurations
        .iter()
        .map(|c| (c.times.frame_ms.max(1e-3), c.error.rmse))
        .collect();
    points.push((reference_ms.max(1e-3), report.reference_error.rmse));
    let labels: Vec<String> = report
        .configurations
        .iter()
        .map(|c| c.label.clone())
        .chain(std::iter::once("reference (CPU)".to_string()))
        .collect();
    let (t_min, t_max) = points
        .iter()
        .fold((f64::MAX, 0.0_f64), |(lo, hi), p| (lo.min(p.0), hi.max(p.0)));
    let e_max = points.iter().map(|p| p.1).fold(0.0_f64, f64::max).max(1e-9);
    let x_range = (t_min / 1.5)..(t_max * 1.5);
    let y_range = (-0.04 * e_max)..(e_max * 1.12);
    let frame_source = if report.gpu_timestamps {
        "GPU timestamps"
    } else {
        "wall clock"
    };
    crate::plot::write_png(path, (1200, 800), |root| {
        let mut chart = ChartBuilder::on(root)
            .caption(
                "Speed against error: every shadow configuration against the ray-traced reference",
                (FONT, 24),
            )
            .margin(20)
            .x_label_area_size(50)
            .y_label_area_size(80)
            .build_cartesian_2d(
                x_range.clone().log_scale().with_key_points(log_ticks(&x_range)),
                y_range.clone(),
            )?;
        chart
            .configure_mesh()
            .x_desc(format!(
                "frame time with a moving light (ms, {frame_source}; reference: CPU time), log scale"
            ))
            .y_desc("RMSE of radiance L − L_ref (W/m²/sr)")
            .label_style((FONT, 15))
            .axis_desc_style((FONT, 17))
            .light_line_style(TRANSPARENT)
            .x_labels(12)
            .x_label_formatter(&|ms| format!("{ms}"))
            .y_label_formatter(&|e| format!("{e:.3}"))
            .draw()?;
        // The front as a staircase: from each point right, then down to the next.
        let mut front: Vec<(f64, f64)> = points
            .iter()
            .zip(&report.pareto)
            .filter(|(_, on)| **on)
            .map(|(p, _)| *p)
            .collect();
        front.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut stairs = Vec::new();
        for (i, p) in front.iter().enumerate() {
            if i > 0 {
                stairs.push((p.0, front[i - 1].1));
            }
            stairs.push(*p);
        }
        if let Some(last) = front.last() {
            stairs.push((x_range.end, last.1));
        }
        // The staircase's segments in pixels, 2 px thick: the labels keep off them.
        let segments: Vec<(i32, i32, i32, i32)> = stairs
            .windows(2)
            .map(|w| {
                let (a, b) = (chart.backend_coord(&w[0]), chart.backend_coord(&w[1]));
                (
                    a.0.min(b.0) - 1,
                    a.1.min(b.1) - 1,
                    a.0.max(b.0) + 1,
                    a.1.max(b.1) + 1,
                )
            })
            .collect();
        chart
            .draw_series(LineSeries::new(stairs, BLACK.mix(0.6).stroke_width(2)))?
            .label("Pareto front (nothing is both faster and more accurate)")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLACK.mix(0.6).stroke_width(2)));
        for (f, &filter) in Filter::ALL.iter().enumerate() {
            let color = PALETTE[f % PALETTE.len()];
            let ours: Vec<(f64, f64, bool)> = report
                .configurations
                .iter()
                .zip(&points)
                .zip(&report.pareto)
                .filter(|((c, _), _)| {
                    c.shadow.visibility == Visibility::ShadowMap && c.shadow.filter == filter
                })
                .map(|((_, p), on)| (p.0, p.1, *on))
                .collect();
            if ours.is_empty() {
                continue;
            }
            chart
                .draw_series(ours.iter().map(|&(t, e, on)| {
                    let style = if on { color.filled() } else { color.stroke_width(2) };
                    Circle::new((t, e), 6, style)
                }))?
                .label(format!("{filter}"))
                .legend(move |(x, y)| Circle::new((x + 9, y), 5, color.filled()));
        }
        let traced: Vec<(f64, f64, bool)> = report
            .configurations
            .iter()
            .zip(&points)
            .zip(&report.pareto)
            .filter(|((c, _), _)| c.shadow.visibility == Visibility::RayTraced)
            .map(|((_, p), on)| (p.0, p.1, *on))
            .collect();
        if !traced.is_empty() {
            let color = BLACK.mix(0.8);
            chart
                .draw_series(traced.iter().map(|&(t, e, on)| {
                    let style = if on { color.filled() } else { color.stroke_width(2) };
                    Cross::new((t, e), 6, style)
                }))?
                .label("GPU ray traced (rays per frame × frames)")
                .legend(move |(x, y)| Cross::new((x + 9, y), 5, color.filled()));
        }
        chart
            .draw_series(std::iter::once(TriangleMarker::new(
                (reference_ms.max(1e-3), report.reference_error.rmse),
                8,
                BLACK.filled(),
            )))?
            .label("reference (CPU ray tracing, error 0)")
            .legend(|(x, y)| TriangleMarker::new((x + 9, y), 6, BLACK.filled()));
        // Labels of the front, each moved up or down until it overlaps no
        // other label, no marker and no step of the staircase.
        let mut placed = segments;
        placed.extend(points.iter().map(|p| {
            let (x, y) = chart.backend_coord(p);
            (x - 7, y - 7, x + 7, y + 7)
        }));
        for ((p, on), label) in points.iter().zip(&report.pareto).zip(&labels) {
            if !*on {
                continue;
            }
            let (x, y) = chart.backend_coord(p);
            let (width, height) = (7 * label.chars().count() as i32, 16);
            let overlaps = |top: i32| {
                placed
                    .iter()
                    .any(|&(l, t, r, b)| x + 10 < r && l < x + 10 + width && top < b && t < top + height)
            };
            let top = [0, -1, 1, -2, 2, -3, 3, -4, 4]
                .iter()
                .map(|k| y - height - 2 + k * (height + 2))
                .find(|&top| !overlaps(top))
                .unwrap_or(y - height - 2);
            placed.push((x + 10, top, x + 10 + width, top + height));
            if top != y - height - 2 {
                root.draw(&PathElement::new(
                    vec![(x + 4, y), (x + 10, top + height / 2)],
                    BLACK.mix(0.5),
                ))?;
            }
            root.draw(&Text::new(
                label.clone(),
                (x + 12, top),
                (FONT, 14).into_font().color(&BLACK),
            ))?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .label_font((FONT, 15))
            .draw()?;
        Ok(())
    })
}

/// Ticks of a log axis: 1, 2, 3 and 5 times each power of ten in `range`
/// (plotters' own marked only whole decades' multiples past the first).
fn log_ticks(range: &std::ops::Range<f64>) -> Vec<f64> {
    let (first, last) = (
        range.start.log10().floor() as i32,
        range.end.log10().ceil() as i32,
    );
    (first..=last)
        .flat_map(|k| {
            [1.0, 2.0, 3.0, 5.0].map(|m| {
                if k < 0 {
                    m / 10f64.powi(-k)
                } else {
                    m * 10f64.powi(k)
                }
            })
        })
        .filter(|t| range.contains(t))
        .collect()
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

const STYLE: &str = "body{font-family:system-ui,sans-serif;margin:2em auto;max-width:1280px;color:#222;padding:0 1em}\
table{border-collapse:collapse;font-size:14px;margin:1em 0}th,td{border:1px solid #ccc;padding:3px 8px;text-align:right}\
th{background:#f3f3f3;position:sticky;top:0}td:first-child,th:first-child{text-align:left}\
tr.front{background:#eaf6ea;font-weight:600}td.gain{color:#b00;font-weight:600}\
.grid{display:grid;grid-template-columns:repeat(auto-fill,minmax(300px,1fr));gap:14px}\
figure{margin:0;border:1px solid #ddd;padding:6px;background:#fafafa}figure img{width:100%}\
figcaption{font-size:13px;margin-top:4px}.note{color:#555;font-size:14px;max-width:70em}";

/// The page: what was measured, the plot, the table, the images and the
/// normalization table, each with a sentence on how to read it.
pub fn html(report: &Report) -> String {
    let s = &report.settings;
    let mut page = String::new();
    let _ = write!(
        page,
        "<!doctype html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>lumlab report</title>\
         <style>{STYLE}</style></head><body><h1>lumlab report: shadow maps, speed against error</h1>"
    );
    let light = if s.light.is_sphere() {
        format!("sphere light R = {} m", s.light.radius_m)
    } else {
        "point light".to_string()
    };
    let _ = write!(
        page,
        "<p class=\"note\">Each configuration below is the GPU renderer with one set of shadow-map settings, compared \
         pixel by pixel with the CPU reference, which ray-traces the visibility of the same camera, light and BRDF \
         exactly. Scene: {} ({} triangles), {}×{} pixels, {light} at ({}, {}, {}) m, Φ = {} W; \
         k = {}, m = {}, normalization {}. GPU: {}. Reference: {:.1} ms on the CPU. The whole report took {:.1} s.</p>",
        escape(
            &s.scene
                .as_ref()
                .map_or("the built-in default scene".into(), |p| p.display().to_string())
        ),
        report.triangles,
        s.image.width,
        s.image.height,
        s.light.position.x,
        s.light.position.y,
        s.light.position.z,
        s.light.power_w,
        s.material.k,
        s.material.m,
        s.material.norm,
        escape(&report.adapter),
        report.reference_time.as_secs_f64() * 1e3,
        report.elapsed.as_secs_f64(),
    );
    page.push_str(
        "<h2>Time against error</h2><p class=\"note\">Lower is more accurate, further left is faster. A configuration \
         on the Pareto front (filled dots, the staircase) is one for which no other is both faster and more \
         accurate; the others (hollow) are never the right choice for this scene and light. The frame time is \
         that of a frame whose light moved, so the shadow map is redrawn.</p><img src=\"pareto.png\" \
         alt=\"time against error\" style=\"max-width:100%\">",
    );
    table(&mut page, report);
    images(&mut page, report);
    normalization_table(&mut page, report);
    page.push_str("<p class=\"note\">Files: <a href=\"report.csv\">report.csv</a>, \
         <a href=\"normalization.csv\">normalization.csv</a>, <a href=\"pareto.png\">pareto.png</a>.</p></body></html>\n");
    page
}

fn table(page: &mut String, report: &Report) {
    page.push_str(
        "<h2>Every configuration</h2><p class=\"note\">RMSE and max: luminance of L − L_ref over the pixels that \
         show geometry. Wrong shadow: the fraction of pixels facing the light whose shadow state (V ≥ ½) differs \
         from the reference's. Penumbra |ΔV|: mean |V − V_ref| within 2 pixels of a reference shadow edge (and \
         where V_ref is fractional). Highlighted rows are on the Pareto front.</p><table><tr>\
         <th>#</th><th>configuration</th><th title=\"GPU time of a frame with a moving light\">frame (ms)</th>\
         <th>shadow pass (ms)</th><th>prefilter (ms)</th><th>shade (ms)</th>\
         <th title=\"root mean square of the luminance error\">RMSE (W/m²/sr)</th><th>relative RMSE</th>\
         <th>max |error| (W/m²/sr)</th><th>wrong shadow</th><th>penumbra |ΔV|</th></tr>",
    );
    let row = |page: &mut String, n: String, label: &str, times: [f64; 4], e: &ErrorMetrics, front: bool| {
        let _ = write!(
            page,
            "<tr{}><td>{n}</td><td>{}</td><td>{:.1}</td><td>{:.1}</td><td>{:.1}</td><td>{:.1}</td>\
             <td>{:.4}</td><td>{:.2} %</td><td>{:.3}</td><td>{:.3} %</td><td>{:.3}</td></tr>",
            if front { " class=\"front\"" } else { "" },
            escape(label),
            times[0],
            times[1],
            times[2],
            times[3],
            e.rmse,
            100.0 * e.relative_rmse,
            e.max_abs,
            100.0 * e.wrong_shadow_fraction,
            e.penumbra_mean_abs_dv,
        );
    };
    for (i, (c, &front)) in report.configurations.iter().zip(&report.pareto).enumerate() {
        let t = &c.times;
        row(
            page,
            (i + 1).to_string(),
            &c.label,
            [t.frame_ms, t.shadow_ms, t.blur_ms, t.shade_ms],
            &c.error,
            front,
        );
    }
    let ms = report.reference_time.as_secs_f64() * 1e3;
    row(
        page,
        "ref".into(),
        "reference (CPU ray tracing)",
        [ms, 0.0, 0.0, 0.0],
        &report.reference_error,
        report.pareto.last().copied().unwrap_or(true),
    );
    page.push_str("</table>");
}

fn images(page: &mut String, report: &Report) {
    let _ = write!(
        page,
        "<h2>Images</h2><p class=\"note\">Left of each pair: what the GPU shows; right: the signed error of \
         luminance L − L_ref (red: too bright, e.g. light leaking into a shadow; blue: too dark, e.g. acne or a \
         shadow too wide), saturated at ±{:.3} W/m²/sr, the mean radiance of the reference. Click an image for \
         full size.</p><div class=\"grid\"><figure><a href=\"images/reference.png\"><img src=\"images/reference.png\" \
         alt=\"reference\"></a><figcaption>reference (CPU ray tracing)</figcaption></figure></div><div class=\"grid\">",
        report.error_scale
    );
    for (i, c) in report.configurations.iter().enumerate() {
        let (shaded, error) = (image_name(i, c, "shaded"), image_name(i, c, "error"));
        let _ = write!(
            page,
            "<figure><a href=\"images/{shaded}\"><img src=\"images/{shaded}\" alt=\"shaded\"></a>\
             <a href=\"images/{error}\"><img src=\"images/{error}\" alt=\"error\"></a>\
             <figcaption>{}. {}: {:.1} ms, RMSE {:.4} W/m²/sr, wrong shadow {:.2} %</figcaption></figure>",
            i + 1,
            escape(&c.label),
            c.times.frame_ms,
            c.error.rmse,
            100.0 * c.error.wrong_shadow_fraction
        );
    }
    page.push_str("</div>");
}

fn normalization_table(page: &mut String, report: &Report) {
    page.push_str(
        "<h2>BRDF normalizations: energy against brightness</h2><p class=\"note\">The specular lobe alone \
         (k = 0) with each normalization N(m): its directional albedo a(θ) = ∫ f_r cos θ_o dω_o at the lecture's \
         angles (as <code>lumlab energy</code> prints it; red above 1: the BRDF reflects more than it receives), \
         beside the mean radiance of the scene rendered with that BRDF on every object. The mean falls with m under \
         every normalization: a sharp lobe sends its energy into a narrow cone that few pixels see. Compare the \
         rows at the same m instead: <code>none</code> (N = 1 ignores the lobe's width) creates energy at small m \
         and loses it at large m, <code>ndf</code> creates it at large m, while <code>approx</code> and <code>exact</code> keep a(0°) near 1, \
         so their images differ only in where the light goes, not in how much there is.</p><table><tr><th>normalization</th>\
         <th>m</th>",
    );
    for a in LECTURE_ANGLES_DEG {
        let _ = write!(page, "<th>a({a}°)</th>");
    }
    page.push_str("<th>mean radiance (W/m²/sr)</th></tr>");
    for row in &report.normalization {
        let _ = write!(page, "<tr><td>{}</td><td>{}</td>", row.norm, row.m);
        for &a in &row.albedo {
            let class = if a > 1.0 + 1e-6 { " class=\"gain\"" } else { "" };
            let _ = write!(page, "<td{class}>{a:.4}</td>");
        }
        let _ = write!(page, "<td>{:.4}</td></tr>", row.mean_radiance);
    }
    page.push_str("</table>");
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_log_axis_is_marked_in_every_decade_it_spans() {
        assert_eq!(
            super::log_ticks(&(25.0..1800.0)),
            [30.0, 50.0, 100.0, 200.0, 300.0, 500.0, 1000.0]
        );
        assert_eq!(super::log_ticks(&(0.15..0.4)), [0.2, 0.3]);
    }
}
