//! The viewport's image drawn by our own pipeline inside egui's render pass
//! (an `egui_wgpu` paint callback) instead of as an egui image mesh. The
//! image is opaque and its bytes are final, so it needs no blending, no
//! vertex colour and no dithering: on a software adapter egui's shader paid
//! for all three on each of the viewport's ~0.68 Mpixel every frame
//! (`shaders/viewport_image.wgsl`). Same pixels at full scale (one texel a
//! pixel, nearest); the reduced images of a drag are filtered linearly.

use crate::gpu::binding;
use crate::gpu::shaders::Shader;
use wgpu::ShaderStages;

/// The pipeline, built once for the window's format.
pub struct ImagePipeline {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    nearest: wgpu::Sampler,
    linear: wgpu::Sampler,
}

/// One texture bound for drawing: its sampler and the part of it shown.
#[derive(Clone)]
pub struct ImageBinding {
    group: wgpu::BindGroup,
    params: wgpu::Buffer,
}

impl ImagePipeline {
    pub fn new(device: &wgpu::Device, target_format: wgpu::TextureFormat) -> Self {
        let fragment = ShaderStages::FRAGMENT;
        let layout = binding::layout(
            device,
            "viewport image",
            &[
                binding::uniform(0, ShaderStages::VERTEX),
                binding::texture(
                    1,
                    fragment,
                    wgpu::TextureSampleType::Float { filterable: true },
                    wgpu::TextureViewDimension::D2,
                ),
                binding::sampler(2, fragment, wgpu::SamplerBindingType::Filtering),
            ],
        );
        let pipeline_layout = binding::pipeline_layout(device, "viewport image", &[&layout]);
        // The window stores what is written, or sRGB-encodes it (then the
        // shader decodes the bytes first).
        let entry = if target_format.is_srgb() {
            "fs_srgb_target"
        } else {
            "fs"
        };
        let pipeline = binding::fullscreen_pipeline(
            device,
            "viewport image",
            &pipeline_layout,
            &Shader::ViewportImage.module(device),
            entry,
            &[],
            target_format,
        );
        let sampler = |filter: wgpu::FilterMode| {
            device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some("viewport image"),
                mag_filter: filter,
                min_filter: filter,
                ..Default::default()
            })
        };
        Self {
            pipeline,
            layout,
            nearest: sampler(wgpu::FilterMode::Nearest),
            linear: sampler(wgpu::FilterMode::Linear),
        }
    }

    /// Binds `view` (Rgba8Unorm holding sRGB bytes), filtered linearly or not.
    pub fn bind(&self, device: &wgpu::Device, view: &wgpu::TextureView, linear: bool) -> ImageBinding {
        let params = binding::buffer(
            device,
            "viewport image params",
            std::mem::size_of::<[f32; 4]>() as u64,
            wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        );
        let sampler = if linear { &self.linear } else { &self.nearest };
        let group = binding::group(
            device,
            "viewport image",
            &self.layout,
            &[
                params.as_entire_binding(),
                wgpu::BindingResource::TextureView(view),
                wgpu::BindingResource::Sampler(sampler),
            ],
        );
        ImageBinding { group, params }
    }

    /// The shape that draws the part `uv` (0..1) of a bound texture over `area`.
    pub fn shape(&self, image: &ImageBinding, area: egui::Rect, uv: egui::Rect) -> egui::Shape {
        egui::Shape::Callback(egui_wgpu::Callback::new_paint_callback(
            area,
            ImageCallback {
                pipeline: self.pipeline.clone(),
                image: image.clone(),
                uv: [uv.min.x, uv.min.y, uv.max.x, uv.max.y],
            },
        ))
    }
}

struct ImageCallback {
    pipeline: wgpu::RenderPipeline,
    image: ImageBinding,
    /// uv_min.x, uv_min.y, uv_max.x, uv_max.y.
    uv: [f32; 4],
}

impl egui_wgpu::CallbackTrait for ImageCallback {
    fn prepare(
        &self,
        _device: &wgpu::Device,
        queue: &wgpu::Queue,
        _screen: &egui_wgpu::ScreenDescriptor,
        _encoder: &mut wgpu::CommandEncoder,
        _resources: &mut egui_wgpu::CallbackResources,
    ) -> Vec<wgpu::CommandBuffer> {
        queue.write_buffer(&self.image.params, 0, bytemuck::cast_slice(&self.uv));
        Vec::new()
    }

    /// egui has set the viewport to the image's rectangle and the scissor to its clip.
    fn paint(
        &self,
        _info: egui::PaintCallbackInfo,
        pass: &mut wgpu::RenderPass<'static>,
        _resources: &egui_wgpu::CallbackResources,
    ) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.image.group, &[]);
        pass.draw(0..3, 0..1);
    }
}
