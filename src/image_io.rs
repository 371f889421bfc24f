//! PNG and EXR files, always written atomically.

use anyhow::Context;
use std::io::Cursor;
use std::path::Path;

/// The image formats the lab writes, chosen by the file's extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageFormat {
    /// 8-bit sRGB, what is displayed.
    Png,
    /// 32-bit float linear values, what was computed.
    Exr,
}

impl ImageFormat {
    /// The format named by the extension of `path` (`.png` or `.exr`).
    pub fn of_path(path: &Path) -> anyhow::Result<Self> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("png") => Ok(Self::Png),
            Some("exr") => Ok(Self::Exr),
            _ => anyhow::bail!("output '{}' must end in .png or .exr", path.display()),
        }
    }
}

/// The file's bytes, encoded in place (no copy of the image).
fn encode<P>(
    image: &image::ImageBuffer<P, Vec<P::Subpixel>>,
    format: image::ImageFormat,
) -> anyhow::Result<Vec<u8>>
where
    P: image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
{
    let mut bytes = Cursor::new(Vec::new());
    image.write_to(&mut bytes, format)?;
    Ok(bytes.into_inner())
}

fn write(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    crate::output::write_atomically(path, bytes).with_context(|| format!("cannot write '{}'", path.display()))
}

/// Writes an 8-bit RGB image as PNG.
pub fn write_png_rgb8(path: &Path, image: &image::RgbImage) -> anyhow::Result<()> {
    write(path, &encode(image, image::ImageFormat::Png)?)
}

/// Writes an 8-bit RGBA image (sRGB) as PNG.
pub fn write_png_rgba8(path: &Path, image: &image::RgbaImage) -> anyhow::Result<()> {
    write(path, &encode(image, image::ImageFormat::Png)?)
}

/// Writes linear float RGBA as OpenEXR.
pub fn write_exr(path: &Path, image: &image::Rgba32FImage) -> anyhow::Result<()> {
    write(path, &encode(image, image::ImageFormat::OpenExr)?)
}
