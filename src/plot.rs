//! Figures written as PNG by the command line (energy curves, Pareto plots):
//! plotters drawing into memory with egui's own font, so that no system font
//! is needed, then encoded and written atomically.

use plotters::prelude::*;
use std::path::Path;
use std::sync::Once;

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
    draw: impl FnOnce(&DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    register_fonts();
    let mut rgb = vec![255u8; (width * height * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (width, height)).into_drawing_area();
        root.fill(&WHITE)?;
        draw(&root)?;
        root.present()?;
    }
    let image =
        image::RgbImage::from_raw(width, height, rgb).ok_or_else(|| anyhow::anyhow!("figure buffer size"))?;
    crate::image_io::write_png_rgb8(path, &image)
}
