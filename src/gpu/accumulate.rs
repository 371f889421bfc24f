//! The running mean of a sphere light's ray-traced frames where the camera
//! pass's targets are f16 (`shaders/accumulate.wgsl`). wgpu's GL back end
//! finds no renderable Rgba32Float on llvmpipe, and a mean stored in f16
//! stops moving once (V − mean) / (N + 1) is under half a step, after some
//! 64 frames. There the camera pass writes each frame as it is; this compute
//! pass folds it into a history in f32 and copies the mean back into the
//! targets. Where the targets are f32 the camera pass folds the frame itself
//! (`raytrace`).

use super::binding;
use bytemuck::{Pod, Zeroable};
use wgpu::ShaderStages;

/// The f16 format of the targets this pass folds (`shaders/accumulate.wgsl`'s
/// `rgba16float`).
pub const TARGET_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// The history's layers: the quantity's four channels, then the aux's.
const HISTORY_LAYERS: u32 = 8;

/// `Fold` of shaders/accumulate.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct FoldRaw {
    pub weight: f32,
    pub _padding: [u32; 3],
}

/// The pass, and its history once a frame needs one.
pub struct SeparateFold {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
    uniform: wgpu::Buffer,
    history: Option<F32History>,
}

/// The running mean in f32 and the textures its f16 copy passes through.
struct F32History {
    size: (u32, u32),
    history: wgpu::TextureView,
    mean_quantity: wgpu::Texture,
    mean_aux: wgpu::Texture,
}

impl SeparateFold {
    pub fn new(device: &wgpu::Device) -> Self {
        let compute = ShaderStages::COMPUTE;
        let storage = |binding, format, access, view_dimension| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: compute,
            ty: wgpu::BindingType::StorageTexture {
                access,
                format,
                view_dimension,
            },
            count: None,
        };
        use wgpu::{StorageTextureAccess as Access, TextureViewDimension as Dim};
        let layout = binding::layout(
            device,
            "ray-traced mean in f32",
            &[
                binding::uniform(0, compute),
                binding::float_texture(1, compute),
                binding::float_texture(2, compute),
                storage(3, wgpu::TextureFormat::R32Float, Access::ReadWrite, Dim::D2Array),
                storage(4, TARGET_FORMAT, Access::WriteOnly, Dim::D2),
                storage(5, TARGET_FORMAT, Access::WriteOnly, Dim::D2),
            ],
        );
        let module = super::shaders::Shader::Accumulate.module(device);
        let pipeline =
            binding::compute_pipeline(device, "ray-traced mean in f32", &layout, &module, "fold_frame");
        Self {
            layout,
            pipeline,
            uniform: super::uniforms::uniform_buffer::<FoldRaw>(device, "ray-traced mean in f32"),
            history: None,
        }
    }

    /// Sets the weight of the next frame in the mean (see `FoldRaw`), with a
    /// history sized like the image.
    pub fn prepare(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, size: (u32, u32), weight: f32) {
        if self.history.as_ref().is_none_or(|h| h.size != size) {
            self.history = Some(F32History::new(device, size));
        }
        let raw = FoldRaw {
            weight,
            _padding: [0; 3],
        };
        queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&raw));
    }

    /// Folds the frame in `quantity` and `aux` into the history and puts the
    /// mean in their place (the aux target only where the frame wrote it).
    pub fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        quantity: &wgpu::Texture,
        aux: &wgpu::Texture,
        aux_written: bool,
    ) {
        let history = self.history.as_ref().expect("prepare() made the history");
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let (quantity_view, aux_view) = (view(quantity), view(aux));
        let (mean_quantity, mean_aux) = (view(&history.mean_quantity), view(&history.mean_aux));
        let group = binding::group(
            device,
            "ray-traced mean in f32",
            &self.layout,
            &[
                self.uniform.as_entire_binding(),
                wgpu::BindingResource::TextureView(&quantity_view),
                wgpu::BindingResource::TextureView(&aux_view),
                wgpu::BindingResource::TextureView(&history.history),
                wgpu::BindingResource::TextureView(&mean_quantity),
                wgpu::BindingResource::TextureView(&mean_aux),
            ],
        );
        let workgroups = [history.size.0.div_ceil(8), history.size.1.div_ceil(8), 1];
        binding::compute_pass(
            encoder,
            "ray-traced mean in f32",
            &self.pipeline,
            &group,
            workgroups,
        );
        let means = [&history.mean_quantity, quantity];
        super::targets::copy_pairs(encoder, means, [&history.mean_aux, aux], aux_written);
    }
}

impl F32History {
    fn new(device: &wgpu::Device, size: (u32, u32)) -> Self {
        use wgpu::TextureUsages as U;
        let history = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("ray-traced mean in f32"),
            size: wgpu::Extent3d {
                width: size.0,
                height: size.1,
                depth_or_array_layers: HISTORY_LAYERS,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::R32Float,
            usage: U::STORAGE_BINDING,
            view_formats: &[],
        });
        let mean = |label: &str| {
            super::targets::image_texture(
                device,
                label,
                size,
                TARGET_FORMAT,
                U::STORAGE_BINDING | U::COPY_SRC,
            )
        };
        Self {
            size,
            history: history.create_view(&wgpu::TextureViewDescriptor {
                dimension: Some(wgpu::TextureViewDimension::D2Array),
                ..Default::default()
            }),
            mean_quantity: mean("ray-traced mean quantity"),
            mean_aux: mean("ray-traced mean aux"),
        }
    }
}
