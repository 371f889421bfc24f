//! The image people see: the view's quantity exposed and sRGB encoded, or in
//! grey or false colour. A compute pass first finds the largest value so that
//! false-colour views scale to the image (only for the views that scale).
//! The pass is compiled per view (`SPECIALISED_VIEW` in display.wgsl): a
//! software adapter runs every case of a branch on a uniform for each pixel,
//! so one generic shader made every view pay for the depth map's, the
//! ramps' and the error views' code.

use super::binding;
use super::readback::map_and_read;
use super::renderer::code;
use super::shaders::Shader;
use super::uniforms::{DisplayParamsRaw, uniform_buffer};
use crate::settings::DebugView;
use std::collections::HashMap;
use wgpu::ShaderStages;

/// The display target: 8-bit sRGB, what PNG files and the app show.
pub const DISPLAY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

/// The textures a display pass reads and writes.
pub struct DisplayInputs<'a> {
    pub quantity: &'a wgpu::TextureView,
    pub comparison: &'a wgpu::TextureView,
    pub shadow_depth: &'a wgpu::TextureView,
    pub shadow_uniform: &'a wgpu::Buffer,
    pub target: &'a wgpu::TextureView,
    pub size: (u32, u32),
    pub view: DebugView,
}

pub struct DisplayPass {
    pub params: wgpu::Buffer,
    scale: wgpu::Buffer,
    scale_readback: wgpu::Buffer,
    layout: wgpu::BindGroupLayout,
    reduce_layout: wgpu::BindGroupLayout,
    pipeline_layout: wgpu::PipelineLayout,
    module: wgpu::ShaderModule,
    /// One per view, compiled on first use and kept.
    pipelines: HashMap<DebugView, wgpu::RenderPipeline>,
    reduce: wgpu::ComputePipeline,
}

/// Whether the view's false colours scale to the image's largest value
/// (the reduce pass finds it; the legend reads it).
pub fn scales_to_image(view: DebugView) -> bool {
    matches!(view, DebugView::Irradiance | DebugView::Brdf | DebugView::Error)
}

impl DisplayPass {
    pub fn new(device: &wgpu::Device) -> Self {
        let fragment = ShaderStages::FRAGMENT;
        let layout = binding::layout(
            device,
            "display",
            &[
                binding::float_texture(0, fragment),
                binding::float_texture(1, fragment),
                binding::texture(
                    2,
                    fragment,
                    wgpu::TextureSampleType::Float { filterable: false },
                    wgpu::TextureViewDimension::D2Array,
                ),
                binding::uniform(3, fragment),
                binding::uniform(4, fragment),
                binding::storage(5, fragment, true),
            ],
        );
        let compute = ShaderStages::COMPUTE;
        let reduce_layout = binding::layout(
            device,
            "display scale",
            &[
                binding::float_texture(0, compute),
                binding::float_texture(1, compute),
                binding::storage(2, compute, false),
                binding::uniform(3, compute),
            ],
        );
        let pipeline_layout = binding::pipeline_layout(device, "display", &[&layout]);
        let reduce_module = Shader::Reduce.module(device);
        let reduce =
            binding::compute_pipeline(device, "display scale", &reduce_layout, &reduce_module, "main");
        let buffer = |label: &str, usage| binding::buffer(device, label, 16, usage);
        Self {
            params: uniform_buffer::<DisplayParamsRaw>(device, "display params"),
            scale: buffer(
                "display scale",
                wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
            ),
            scale_readback: buffer(
                "display scale readback",
                wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            ),
            layout,
            reduce_layout,
            pipeline_layout,
            module: Shader::Display.module(device),
            pipelines: HashMap::new(),
            reduce,
        }
    }

    /// The view's scale where it has one, then the displayed image, with the
    /// view's own pipeline (compiled the first time the view is shown).
    pub fn encode(
        &mut self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        inputs: &DisplayInputs<'_>,
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        encoder.clear_buffer(&self.scale, 0, None);
        if scales_to_image(inputs.view) {
            self.encode_reduce(device, encoder, inputs);
        }
        let pipeline = self.pipelines.entry(inputs.view).or_insert_with(|| {
            binding::fullscreen_pipeline(
                device,
                &format!("display {:?}", inputs.view),
                &self.pipeline_layout,
                &self.module,
                "fs",
                &[("SPECIALISED_VIEW", code(DebugView::ALL, &inputs.view) as f64)],
                DISPLAY_FORMAT,
            )
        });
        let group = binding::group(
            device,
            "display",
            &self.layout,
            &[
                wgpu::BindingResource::TextureView(inputs.quantity),
                wgpu::BindingResource::TextureView(inputs.comparison),
                wgpu::BindingResource::TextureView(inputs.shadow_depth),
                inputs.shadow_uniform.as_entire_binding(),
                self.params.as_entire_binding(),
                self.scale.as_entire_binding(),
            ],
        );
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("display"),
            color_attachments: &[binding::color_attachment(
                inputs.target,
                wgpu::LoadOp::Clear(wgpu::Color::BLACK),
            )],
            depth_stencil_attachment: None,
            timestamp_writes,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.draw(0..3, 0..1);
    }

    /// The compute pass that finds the view's largest value into `scale`.
    fn encode_reduce(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        inputs: &DisplayInputs<'_>,
    ) {
        let reduce_group = binding::group(
            device,
            "display scale",
            &self.reduce_layout,
            &[
                wgpu::BindingResource::TextureView(inputs.quantity),
                wgpu::BindingResource::TextureView(inputs.comparison),
                self.scale.as_entire_binding(),
                self.params.as_entire_binding(),
            ],
        );
        let workgroups = [inputs.size.0.div_ceil(8), inputs.size.1.div_ceil(8), 1];
        binding::compute_pass(encoder, "display scale", &self.reduce, &reduce_group, workgroups);
    }

    /// The buffer holding the last view's scale (an f32 in its first 4 bytes).
    pub fn scale_buffer(&self) -> &wgpu::Buffer {
        &self.scale
    }

    /// The largest value of the last displayed view (its false-colour scale).
    /// Blocks until the GPU is done.
    pub fn read_scale(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> f32 {
        let mut encoder = device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&self.scale, 0, &self.scale_readback, 0, 16);
        queue.submit([encoder.finish()]);
        let bytes = map_and_read(device, &self.scale_readback, 16, 16);
        f32::from_bits(u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The reduce pass runs for exactly the views whose legend depends on
    /// the image's largest value.
    #[test]
    fn the_scale_is_found_for_the_views_that_use_it() {
        for &view in DebugView::ALL {
            let legend = |scale| super::super::colormap::legend(view, scale);
            assert_eq!(scales_to_image(view), legend(1.0) != legend(2.0), "{view:?}");
        }
    }
}
