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
pub(crate) fn encode<P>(
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

/// Writes linear float RGBA as OpenEXR: 32-bit float channels R, G, B, A,
/// run-length encoded in tiles of 64 × 64 pixels (what `image` writes), the
/// tiles compressed in parallel and written in order: the same image gives
/// the same bytes. `pixel(x, y)` is the [R, G, B, A] of the `size` (width,
/// height) image's pixel (x, y): each tile reads the caller's data through
/// it, without a copy of the image as RGBA or in channel planes (with both
/// copies, in fresh memory, the 512 × 384 reference's EXR took 12–16 ms;
/// without, 6–7 ms).
pub fn write_exr(
    path: &Path,
    (width, height): (u32, u32),
    pixel: impl Fn(usize, usize) -> [f32; 4] + Sync,
) -> anyhow::Result<()> {
    use exr::prelude::{
        Blocks, Compression, Encoding, Image, LineOrder, SpecificChannels, Vec2, WritableImage,
    };
    let channels = SpecificChannels::rgba(|Vec2(x, y)| {
        let [r, g, b, a] = pixel(x, y);
        (r, g, b, a)
    });
    let encoding = Encoding {
        compression: Compression::RLE,
        blocks: Blocks::Tiles(Vec2(64, 64)),
        line_order: LineOrder::Increasing,
    };
    let image = Image::from_encoded_channels((width as usize, height as usize), encoding, channels);
    let mut bytes = Cursor::new(Vec::new());
    image.write().to_buffered(&mut bytes)?;
    write(path, &bytes.into_inner())
}

/// [`write_exr`] of `texels`, the rows of a `size` (width, height) image
/// one after the other; an error when they are not as many as its pixels.
pub fn write_exr_texels(path: &Path, size: (u32, u32), texels: &[[f32; 4]]) -> anyhow::Result<()> {
    let width = size.0 as usize;
    anyhow::ensure!(
        texels.len() == width * size.1 as usize,
        "the image read back has {} pixels, not {} × {}",
        texels.len(),
        size.0,
        size.1
    );
    write_exr(path, size, |x, y| texels[y * width + x])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What `write_exr` writes reads back, through `image`'s own decoder,
    /// as the same f32 values in every channel and pixel, on an image that
    /// is not a whole number of tiles; and the same image gives the same
    /// bytes (tiles compressed in parallel are written in order).
    #[test]
    fn exr_reads_back_bit_for_bit_and_writes_the_same_bytes() {
        let (width, height) = (131, 70);
        let image = image::Rgba32FImage::from_fn(width, height, |x, y| {
            let v = (x * 7 + y * 13) as f32;
            // Runs of equal values (the run-length encoding's case) and noise.
            let noisy = (v * 0.618).fract() * 1e3 - 5e2;
            image::Rgba([if x < 40 { 0.0 } else { noisy }, v * 1e-3, -v, 1.0 / (1.0 + v)])
        });
        let texels: Vec<[f32; 4]> = image.pixels().map(|p| p.0).collect();
        let dir = tempfile::tempdir().unwrap();
        let (first, second) = (dir.path().join("a.exr"), dir.path().join("b.exr"));
        write_exr_texels(&first, (width, height), &texels).unwrap();
        write_exr(&second, (width, height), |x, y| {
            image.get_pixel(x as u32, y as u32).0
        })
        .unwrap();
        assert_eq!(std::fs::read(&first).unwrap(), std::fs::read(&second).unwrap());
        let read = image::open(&first).unwrap().into_rgba32f();
        assert_eq!(read.dimensions(), (width, height));
        for (a, b) in image.pixels().zip(read.pixels()) {
            assert_eq!(a.0.map(f32::to_bits), b.0.map(f32::to_bits));
        }
    }

    /// Texels that are not as many as the image's pixels are refused, and
    /// nothing is written.
    #[test]
    fn exr_texels_of_another_size_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.exr");
        let error = write_exr_texels(&path, (3, 2), &[[0.0; 4]; 5]).unwrap_err();
        assert_eq!(error.to_string(), "the image read back has 5 pixels, not 3 × 2");
        assert!(!path.exists());
    }
}
