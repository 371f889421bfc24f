//! The textures a frame is drawn into, sized like the image, and the
//! float targets on their way back to the CPU.

use super::display::DISPLAY_FORMAT;
use super::readback::{PendingRead, ReadState};
use super::shadow::DEPTH_FORMAT;

/// Textures sized like the image.
pub(super) struct FrameTargets {
    pub(super) size: (u32, u32),
    pub(super) quantity: wgpu::Texture,
    pub(super) quantity_view: wgpu::TextureView,
    pub(super) aux: wgpu::Texture,
    pub(super) aux_view: wgpu::TextureView,
    pub(super) depth_view: wgpu::TextureView,
    pub(super) display: wgpu::Texture,
    pub(super) display_view: wgpu::TextureView,
    pub(super) comparison: wgpu::Texture,
    pub(super) comparison_view: wgpu::TextureView,
}

impl FrameTargets {
    pub(super) fn new(device: &wgpu::Device, size: (u32, u32), hdr: wgpu::TextureFormat) -> Self {
        let texture = |label: &str, format, usage| image_texture(device, label, size, format, usage);
        use wgpu::TextureUsages as U;
        let target = U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC;
        // A ray-traced mean kept in f32 beside f16 targets is copied back
        // into them (gpu::accumulate).
        let float_target = target | U::COPY_DST;
        let quantity = texture("quantity", hdr, float_target);
        let aux = texture("aux", hdr, float_target);
        let depth = texture("camera depth", DEPTH_FORMAT, U::RENDER_ATTACHMENT);
        let display = texture("display", DISPLAY_FORMAT, target);
        let comparison = texture(
            "comparison",
            wgpu::TextureFormat::Rgba32Float,
            U::TEXTURE_BINDING | U::COPY_DST,
        );
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        Self {
            size,
            quantity_view: view(&quantity),
            aux_view: view(&aux),
            depth_view: view(&depth),
            display_view: view(&display),
            comparison_view: view(&comparison),
            quantity,
            aux,
            display,
            comparison,
        }
    }
}

/// Copies the whole of `quantity[0]` into `quantity[1]`, and of `aux[0]`
/// into `aux[1]` where `with_aux` (a frame's two float targets and their
/// copies).
pub(super) fn copy_pairs(
    encoder: &mut wgpu::CommandEncoder,
    quantity: [&wgpu::Texture; 2],
    aux: [&wgpu::Texture; 2],
    with_aux: bool,
) {
    for [from, to] in [quantity, aux].iter().take(1 + usize::from(with_aux)) {
        encoder.copy_texture_to_texture(from.as_image_copy(), to.as_image_copy(), from.size());
    }
}

/// A 2D texture of one layer sized like the image.
pub(super) fn image_texture(
    device: &wgpu::Device,
    label: &str,
    size: (u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: size.0,
            height: size.1,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

/// The frame's float targets that can be read back.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FloatTarget {
    /// The view's quantity (radiance L in W/m²/sr for `shaded`).
    Quantity,
    /// V, shadow-map texels per pixel, max(0, n·l), coverage.
    Aux,
}

/// Texels on their way back (see [`super::Renderer::request_texels`]).
pub struct PendingTexels {
    pub(super) read: PendingRead,
    pub(super) bytes_per_texel: u32,
}

impl PendingTexels {
    /// The texels, row-major from the top of the rectangle, once they are here.
    pub fn poll(&self) -> ReadState<Vec<[f32; 4]>> {
        match self.read.poll() {
            ReadState::Ready(bytes) => ReadState::Ready(decode_float_texels(&bytes, self.bytes_per_texel)),
            ReadState::Waiting => ReadState::Waiting,
            ReadState::Failed => ReadState::Failed,
        }
    }
}

/// A false-colour scale on its way back (see [`super::Renderer::request_scale`]).
pub struct PendingScale(pub(super) PendingRead);

impl PendingScale {
    pub fn poll(&self) -> ReadState<f32> {
        match self.0.poll() {
            ReadState::Ready(bytes) if bytes.len() >= 4 => {
                ReadState::Ready(f32::from_bits(u32::from_le_bytes([
                    bytes[0], bytes[1], bytes[2], bytes[3],
                ])))
            }
            ReadState::Waiting => ReadState::Waiting,
            _ => ReadState::Failed,
        }
    }
}

/// RGBA texels from Rgba32Float (16 bytes) or Rgba16Float (8 bytes) rows.
pub(super) fn decode_float_texels(bytes: &[u8], bytes_per_texel: u32) -> Vec<[f32; 4]> {
    if bytes_per_texel == 16 {
        bytes
            .chunks_exact(16)
            .map(|t| {
                std::array::from_fn(|c| {
                    f32::from_le_bytes([t[4 * c], t[4 * c + 1], t[4 * c + 2], t[4 * c + 3]])
                })
            })
            .collect()
    } else {
        bytes
            .chunks_exact(8)
            .map(|t| std::array::from_fn(|c| half::f16::from_le_bytes([t[2 * c], t[2 * c + 1]]).to_f32()))
            .collect()
    }
}
