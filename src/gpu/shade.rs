//! Pass 2: the camera pass. Shades every visible point and writes the view's
//! quantity and the aux target (V, texel density, cos θ, coverage).

use super::binding;
use super::depth_ranges;
use super::scene_buffers::{GpuScene, Meshes, Vertex};
use super::shaders::Shader;
use super::shadow::ShadowTextures;
use super::specialise::{Specialisation, camera_depth_test};
use super::uniforms::{GlobalsRaw, MaterialRaw, uniform_buffer};
use std::collections::HashMap;
use std::thread::JoinHandle;
use wgpu::ShaderStages;

pub struct ShadePass {
    pub globals: wgpu::Buffer,
    scene_layout: wgpu::BindGroupLayout,
    shadow_layout: wgpu::BindGroupLayout,
    pipeline_layout: wgpu::PipelineLayout,
    module: wgpu::ShaderModule,
    hdr_format: wgpu::TextureFormat,
    /// Compiled on first use, kept: switching views or filters back is free.
    pipelines: HashMap<Specialisation, wgpu::RenderPipeline>,
    /// Pipelines compiling on threads of their own ([`Self::compile_ahead`]).
    ahead: HashMap<Specialisation, JoinHandle<wgpu::RenderPipeline>>,
    /// How many pipelines in use were compiled ahead.
    pub compiled_ahead: u64,
    /// The depth pre-pass: the nearest depth of every pixel, no colour.
    depth_pipeline: wgpu::RenderPipeline,
    /// Group 2: the ray tracer's (gpu::raytrace).
    pub raytrace_layout: wgpu::BindGroupLayout,
    texture_sampler: wgpu::Sampler,
    compare_sampler: wgpu::Sampler,
    moments_sampler: wgpu::Sampler,
    /// Gathers four stored depths at a time for PCF (shadow_map.wgsl).
    depth_gather_sampler: wgpu::Sampler,
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
                // The vertex stage copies the knobs (shadow_map.wgsl).
                binding::uniform(1, ShaderStages::VERTEX_FRAGMENT),
                // The drawn object's material slot (scene_buffers::Meshes::material_offset).
                binding::dynamic_uniform(2, ShaderStages::VERTEX),
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
                binding::float_array(4, fragment),
                binding::sampler(5, fragment, wgpu::SamplerBindingType::NonFiltering),
                binding::float_array(6, fragment),
            ],
        );
        let raytrace_layout = super::raytrace::layout(device);
        let pipeline_layout = binding::pipeline_layout(
            device,
            "camera pass",
            &[&scene_layout, &shadow_layout, &raytrace_layout],
        );
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
        let module = Shader::Shade.module(device);
        let depth_pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("camera depth pre-pass"),
            layout: Some(&binding::pipeline_layout(
                device,
                "camera depth pre-pass",
                &[&scene_layout],
            )),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_depth"),
                compilation_options: Default::default(),
                buffers: &[Some(Vertex::layout())],
            },
            fragment: None,
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(camera_depth_test()),
            multisample: Default::default(),
            multiview_mask: None,
            cache: None,
        });
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
            depth_gather_sampler: sampler(
                "shadow depth gather",
                wgpu::FilterMode::Nearest,
                wgpu::AddressMode::ClampToEdge,
                None,
            ),
            scene_layout,
            shadow_layout,
            pipeline_layout,
            module,
            hdr_format,
            pipelines: HashMap::new(),
            ahead: HashMap::new(),
            compiled_ahead: 0,
            depth_pipeline,
            raytrace_layout,
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
                wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: &scene.materials,
                    offset: 0,
                    size: wgpu::BufferSize::new(std::mem::size_of::<MaterialRaw>() as u64),
                }),
                wgpu::BindingResource::TextureView(&scene.texture_view),
                wgpu::BindingResource::Sampler(&self.texture_sampler),
            ],
        ));
    }

    /// The bind group of the shadow map's textures, with the depth ranges
    /// the filter of `settings` reads.
    pub fn shadow_group(
        &self,
        device: &wgpu::Device,
        shadow: &ShadowTextures,
        dummy_moments: &wgpu::TextureView,
        settings: &crate::settings::ShadowSettings,
    ) -> wgpu::BindGroup {
        let moments = shadow.moments.as_ref().map_or(dummy_moments, |m| &m.array);
        // Unread (Shadow::range_block = 0) where no ranges were built.
        let ranges = shadow
            .ranges
            .as_ref()
            .zip(depth_ranges::level_for(settings))
            .map_or(dummy_moments, |(r, level)| r.windows(level));
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
                wgpu::BindingResource::Sampler(&self.depth_gather_sampler),
                wgpu::BindingResource::TextureView(ranges),
            ],
        )
    }

    /// Compiles the pipeline of a specialisation unless it already is
    /// (waiting for the rest of its compilation if it was started ahead).
    pub fn prepare(&mut self, device: &wgpu::Device, specialisation: Specialisation) {
        if self.pipelines.contains_key(&specialisation) {
            return;
        }
        // A compilation that failed on its thread is done again here, where
        // its error shows as it would have.
        let ahead = self
            .ahead
            .remove(&specialisation)
            .and_then(|thread| thread.join().ok());
        self.compiled_ahead += u64::from(ahead.is_some());
        let pipeline = ahead.unwrap_or_else(|| {
            specialisation.pipeline(device, &self.pipeline_layout, &self.module, self.hdr_format)
        });
        self.pipelines.insert(specialisation, pipeline);
    }

    /// Starts compiling the pipeline of a specialisation on a thread of its
    /// own, unless it is compiled or compiling: lavapipe takes ~150 ms for
    /// one, which the first frame needing it would otherwise wait for.
    pub fn compile_ahead(&mut self, device: &wgpu::Device, specialisation: Specialisation) {
        if self.pipelines.contains_key(&specialisation) || self.ahead.contains_key(&specialisation) {
            return;
        }
        let (device, layout, module) = (device.clone(), self.pipeline_layout.clone(), self.module.clone());
        let format = self.hdr_format;
        let thread = std::thread::Builder::new()
            .name("camera pass pipeline".to_owned())
            .spawn(move || specialisation.pipeline(&device, &layout, &module, format));
        // Without a thread it is compiled when first needed, as before.
        if let Ok(thread) = thread {
            self.ahead.insert(specialisation, thread);
        }
    }

    /// The depth pre-pass: the visible objects' nearest depths into `depth`
    /// (cleared first), for [`Self::encode`] to shade each pixel once.
    pub fn encode_depth(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        meshes: Meshes<'_>,
        depth: &wgpu::TextureView,
        visible: &[usize],
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("camera depth pre-pass"),
            color_attachments: &[],
            depth_stencil_attachment: binding::depth_attachment(depth, wgpu::LoadOp::Clear(0.0)),
            timestamp_writes,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        let Some(scene_group) = &self.scene_group else {
            return;
        };
        pass.set_pipeline(&self.depth_pipeline);
        // vs_depth reads no material: any slot.
        pass.set_bind_group(0, scene_group, &[0]);
        meshes.bind(&mut pass);
        for &object in visible {
            meshes.draw(&mut pass, object);
        }
    }

    /// Shades the visible objects with the pipeline of `specialisation`
    /// (compiled by [`Self::prepare`]): where they are nearest after
    /// [`Self::encode_depth`] filled `depth` when the specialisation is
    /// pre-passed, else with its own depth test from a cleared `depth`; the
    /// aux target is written only when the specialisation says so.
    #[allow(clippy::too_many_arguments)]
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        specialisation: Specialisation,
        meshes: Meshes<'_>,
        shadow_group: &wgpu::BindGroup,
        raytrace_group: &wgpu::BindGroup,
        quantity: &wgpu::TextureView,
        aux: &wgpu::TextureView,
        depth: &wgpu::TextureView,
        visible: &[usize],
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        let clear = wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT);
        let both = [
            binding::color_attachment(quantity, clear),
            binding::color_attachment(aux, clear),
        ];
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("camera pass"),
            color_attachments: if specialisation.aux { &both } else { &both[..1] },
            depth_stencil_attachment: binding::depth_attachment(
                depth,
                if specialisation.prepassed {
                    wgpu::LoadOp::Load
                } else {
                    wgpu::LoadOp::Clear(0.0)
                },
            ),
            timestamp_writes,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        let (Some(scene_group), Some(pipeline)) = (&self.scene_group, self.pipelines.get(&specialisation))
        else {
            return;
        };
        pass.set_pipeline(pipeline);
        pass.set_bind_group(1, shadow_group, &[]);
        pass.set_bind_group(2, raytrace_group, &[]);
        meshes.bind(&mut pass);
        // Bound again only where the slot changes: objects in a row often
        // share a material.
        let mut bound = None;
        for &object in visible {
            let slot = meshes.material_offset(object);
            if bound != Some(slot) {
                pass.set_bind_group(0, scene_group, &[slot]);
                bound = Some(slot);
            }
            meshes.draw(&mut pass, object);
        }
    }
}

impl Drop for ShadePass {
    /// Waits for the pipelines still compiling ahead, so that each is
    /// dropped here. Left to its own thread, a pipeline finished after the
    /// last view was gone held the last reference to the device and the
    /// instance: its drop unloaded the Vulkan driver on that thread while
    /// the process exited, and a test binary crashed in the driver's exit
    /// handler about once in 20–40 runs.
    fn drop(&mut self) {
        for (_, thread) in self.ahead.drain() {
            let _ = thread.join();
        }
    }
}
