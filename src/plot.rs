//! Figures written as PNG by the command line (energy curves, Pareto plots):
//! plotters drawing into memory with egui's own font, so that no system font
//! is needed, then encoded and written atomically.

mod figure;

pub use figure::Figure;
use plotters::prelude::*;
use std::path::Path;
use std::sync::Once;

/// What a figure's drawing code draws on.
pub type Area<'a> = DrawingArea<Figure<'a>, plotters::coord::Shift>;

/// The font family every figure uses.
pub const FONT: &str = "sans-serif";

/// A palette that stays distinct for up to 12 curves (Tableau 10 + 2).
pub const PALETTE: [RGBColor; 12] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
    RGBColor(0, 0, 0),
    RGBColor(255, 187, 120),
];

fn register_fonts() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        for style in [
            FontStyle::Normal,
            FontStyle::Bold,
            FontStyle::Italic,
            FontStyle::Oblique,
        ] {
            // The bytes are egui's bundled Ubuntu Light: a valid font by construction.
            let _ = plotters::style::register_font(FONT, style, epaint_default_fonts::UBUNTU_LIGHT);
        }
    });
}

/// Draws a `width`×`height` figure with `draw` and writes it to `path` as PNG.
pub fn write_png(
    path: &Path,
    (width, height): (u32, u32),
    draw: impl FnOnce(&Area<'_>) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    register_fonts();
    let mut rgb = vec![255u8; (width * height * 3) as usize];
    {
        let root = Figure(BitMapBackend::with_buffer(&mut rgb, (width, height))).into_drawing_area();
        root.fill(&WHITE)?;
        draw(&root)?;
        root.present()?;
    }
    let image =
        image::RgbImage::from_raw(width, height, rgb).ok_or_else(|| anyhow::anyhow!("figure buffer size"))?;
    crate::image_io::write_png_rgb8(path, &image)
}

/// The image with a colour bar and its labelled ticks drawn below it.
pub fn with_legend(
    image: &image::RgbaImage,
    legend: &crate::gpu::colormap::Legend,
) -> anyhow::Result<image::RgbaImage> {
    register_fonts();
    let width = image.width().max(320);
    let strip_height = 64;
    let mut rgb = vec![255u8; (width * strip_height * 3) as usize];
    {
        let root = Figure(BitMapBackend::with_buffer(&mut rgb, (width, strip_height))).into_drawing_area();
        root.fill(&WHITE)?;
        let (x0, x1) = (40_i32, width as i32 - 40);
        let bar_top = 24;
        for x in x0..x1 {
            let t = (x - x0) as f32 / (x1 - x0 - 1).max(1) as f32;
            let c = crate::gpu::colormap::sample(legend.ramp, t).map(|v| (v * 255.0).round() as u8);
            root.draw(&PathElement::new(
                vec![(x, bar_top), (x, bar_top + 14)],
                RGBColor(c[0], c[1], c[2]),
            ))?;
        }
        root.draw(&Text::new(
            legend.title.clone(),
            (x0, 4),
            (FONT, 15).into_font().color(&BLACK),
        ))?;
        for (t, label) in &legend.ticks {
            let x = x0 + (t * (x1 - x0 - 1) as f32) as i32;
            root.draw(&PathElement::new(
                vec![(x, bar_top + 14), (x, bar_top + 19)],
                BLACK,
            ))?;
            let style = (FONT, 13)
                .into_font()
                .color(&BLACK)
                .pos(plotters::style::text_anchor::Pos::new(
                    plotters::style::text_anchor::HPos::Center,
                    plotters::style::text_anchor::VPos::Top,
                ));
            root.draw(&Text::new(label.clone(), (x, bar_top + 21), style))?;
        }
        root.present()?;
    }
    let mut out = image::RgbaImage::from_pixel(
        width,
        image.height() + strip_height,
        image::Rgba([255, 255, 255, 255]),
    );
    image::imageops::overlay(&mut out, image, 0, 0);
    for (i, px) in rgb.chunks(3).enumerate() {
        let (x, y) = (i as u32 % width, i as u32 / width);
        out.put_pixel(x, image.height() + y, image::Rgba([px[0], px[1], px[2], 255]));
    }
    Ok(out)
}
