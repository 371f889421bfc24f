//! Pass 2: the camera pass. Shades every visible point and writes the view's
//! quantity and the aux target (V, texel density, cos θ, coverage).

use super::binding;
use super::scene_buffers::{GpuScene, Vertex};
use super::shaders::Shader;
use super::shadow::{DEPTH_FORMAT, ShadowTextures};
use super::uniforms::{GlobalsRaw, uniform_buffer};
use wgpu::ShaderStages;

pub struct ShadePass {
    pub globals: wgpu::Buffer,
    scene_layout: wgpu::BindGroupLayout,
    shadow_layout: wgpu::BindGroupLayout,
    /// Group 2: the ray tracer's (gpu::raytrace).
    pub raytrace_layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
    texture_sampler: wgpu::Sampler,
    compare_sampler: wgpu::Sampler,
    moments_sampler: wgpu::Sampler,
    scene_group: Option<wgpu::BindGroup>,
}

impl ShadePass {
    pub fn new(device: &wgpu::Device, hdr_format: wgpu::TextureFormat) -> Self {
        let fragment = ShaderStages::FRAGMENT;
        let scene_layout = binding::layout(
            device,
            "camera pass scene",
            &[
                binding::uniform(0, ShaderStages::VERTEX_FRAGMENT),
                binding::uniform(1, fragment),
                binding::storage(2, fragment, true),
                binding::texture(
                    3,
                    fragment,
                    wgpu::TextureSampleType::Float { filterable: true },
                    wgpu::TextureViewDimension::D2Array,
                ),
                binding::sampler(4, fragment, wgpu::SamplerBindingType::Filtering),
            ],
        );
        let shadow_layout = binding::layout(
            device,
            "camera pass shadow map",
            &[
                binding::texture(
                    0,
                    fragment,
                    wgpu::TextureSampleType::Depth,
                    wgpu::TextureViewDimension::D2Array,
                ),
                binding::sampler(1, fragment, wgpu::SamplerBindingType::Comparison),
                binding::texture(
                    2,
                    fragment,
                    wgpu::TextureSampleType::Float { filterable: true },
                    wgpu::TextureViewDimension::D2Array,
                ),
                binding::sampler(3, fragment, wgpu::SamplerBindingType::Filtering),
                binding::texture(
                    4,
                    fragment,
                    wgpu::TextureSampleType::Float { filterable: false },
                    wgpu::TextureViewDimension::D2Array,
                ),
            ],
        );
        let raytrace_layout = super::raytrace::layout(device);
        let pipeline_layout = binding::pipeline_layout(
            device,
            "camera pass",
            &[&scene_layout, &shadow_layout, &raytrace_layout],
        );
        let module = Shader::Shade.module(device);
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("camera pass"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs"),
                compilation_options: Default::default(),
                buffers: &[Some(Vertex::layout())],
            },
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs"),
                compilation_options: Default::default(),
                targets: &[Some(hdr_format.into()), Some(hdr_format.into())],
            }),
            // No culling: back faces are shaded to 0 (n·o ≤ 0), as in the reference.
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Greater),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            multiview_mask: None,
            cache: None,
        });
        let sampler = |label: &str, filter: wgpu::FilterMode, address: wgpu::AddressMode, compare| {
            device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some(label),
                address_mode_u: address,
                address_mode_v: address,
                mag_filter: filter,
                min_filter: filter,
                compare,
                ..Default::default()
            })
        };
        let linear = wgpu::FilterMode::Linear;
        Self {
            globals: uniform_buffer::<GlobalsRaw>(device, "camera globals"),
            texture_sampler: sampler("base colour", linear, wgpu::AddressMode::Repeat, None),
            // Reversed Z: lit where the reference depth is ≥ the stored one.
            compare_sampler: sampler(
                "shadow compare",
                linear,
                wgpu::AddressMode::ClampToEdge,
                Some(wgpu::CompareFunction::GreaterEqual),
            ),
            moments_sampler: sampler("shadow moments", linear, wgpu::AddressMode::ClampToEdge, None),
            scene_layout,
            shadow_layout,
            raytrace_layout,
            pipeline,
            scene_group: None,
        }
    }

    /// Binds a newly uploaded scene.
    pub fn set_scene(&mut self, device: &wgpu::Device, scene: &GpuScene, shadow_uniform: &wgpu::Buffer) {
        self.scene_group = Some(binding::group(
            device,
            "camera pass scene",
            &self.scene_layout,
            &[
                self.globals.as_entire_binding(),
                shadow_uniform.as_entire_binding(),
                scene.materials.as_entire_binding(),
                wgpu::BindingResource::TextureView(&scene.texture_view),
                wgpu::BindingResource::Sampler(&self.texture_sampler),
            ],
        ));
    }

    /// The bind group of the shadow map's textures.
    pub fn shadow_group(
        &self,
        device: &wgpu::Device,
        shadow: &ShadowTextures,
        dummy_moments: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        let moments = shadow.moments.as_ref().map_or(dummy_moments, |m| &m.array);
        binding::group(
            device,
            "camera pass shadow map",
            &self.shadow_layout,
            &[
                wgpu::BindingResource::TextureView(&shadow.depth_array),
                wgpu::BindingResource::Sampler(&self.compare_sampler),
                wgpu::BindingResource::TextureView(moments),
                wgpu::BindingResource::Sampler(&self.moments_sampler),
                wgpu::BindingResource::TextureView(&shadow.depth_array),
            ],
        )
    }

    #[allow(clippy::too_many_arguments)]
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        shadow_group: &wgpu::BindGroup,
        raytrace_group: &wgpu::BindGroup,
        quantity: &wgpu::TextureView,
        aux: &wgpu::TextureView,
        depth: &wgpu::TextureView,
        visible: &[usize],
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        let clear = wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT);
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("camera pass"),
            color_attachments: &[
                binding::color_attachment(quantity, clear),
                binding::color_attachment(aux, clear),
            ],
            depth_stencil_attachment: binding::depth_attachment(depth, wgpu::LoadOp::Clear(0.0)),
            timestamp_writes,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        let Some(scene_group) = &self.scene_group else {
            return;
        };
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, scene_group, &[]);
        pass.set_bind_group(1, shadow_group, &[]);
        pass.set_bind_group(2, raytrace_group, &[]);
        scene.bind_buffers(&mut pass);
        for &object in visible {
            scene.draw(&mut pass, object);
        }
    }
}
