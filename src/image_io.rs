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
/// the same bytes.
pub fn write_exr(path: &Path, image: &image::Rgba32FImage) -> anyhow::Result<()> {
    use exr::prelude::{
        AnyChannel, AnyChannels, Blocks, Compression, Encoding, FlatSamples, Image, Layer, LayerAttributes,
        LineOrder, SmallVec, Vec2, WritableImage,
    };
    let plane = |c: usize| FlatSamples::F32(image.pixels().map(|p| p.0[c]).collect());
    let channels = ["R", "G", "B", "A"]
        .into_iter()
        .enumerate()
        .map(|(c, name)| AnyChannel::new(name, plane(c)))
        .collect();
    let size = (image.width() as usize, image.height() as usize);
    let layer = Layer::new(
        size,
        LayerAttributes::default(),
        Encoding {
            compression: Compression::RLE,
            blocks: Blocks::Tiles(Vec2(64, 64)),
            line_order: LineOrder::Increasing,
        },
        AnyChannels::sort(SmallVec::from_vec(channels)),
    );
    let mut bytes = Cursor::new(Vec::new());
    Image::from_layer(layer).write().to_buffered(&mut bytes)?;
    write(path, &bytes.into_inner())
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
        let dir = tempfile::tempdir().unwrap();
        let (first, second) = (dir.path().join("a.exr"), dir.path().join("b.exr"));
        write_exr(&first, &image).unwrap();
        write_exr(&second, &image).unwrap();
        assert_eq!(std::fs::read(&first).unwrap(), std::fs::read(&second).unwrap());
        let read = image::open(&first).unwrap().into_rgba32f();
        assert_eq!(read.dimensions(), (width, height));
        for (a, b) in image.pixels().zip(read.pixels()) {
            assert_eq!(a.0.map(f32::to_bits), b.0.map(f32::to_bits));
        }
    }
}
