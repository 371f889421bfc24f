//! Pass 1: depth from the light into a 2D texture array, one layer per
//! frustum (one, or the six cube faces). VSM/EVSM also write depth moments,
//! then blur them separably.

use super::binding;
use super::depth_ranges::{self, RangePass, RangeTextures};
use super::light_frustum::ShadowLayout;
use super::scene_buffers::{Meshes, Vertex};
use super::shaders::Shader;
use super::timing::{GpuTimer, Pass};
use super::uniforms::{BlurParamsRaw, DYNAMIC_STRIDE, ShadowLayerRaw, ShadowRaw, uniform_buffer};
use wgpu::ShaderStages;

pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Layers allocated at most (a cube).
pub const MAX_LAYERS: u32 = 6;
/// Shadow textures (depth, moments and their blur scratch) stay within this.
pub const MEMORY_BUDGET_BYTES: u64 = 1536 << 20;

// Constants of the camera pass's shadow-map lookup (shaders/shadow_map.wgsl),
// given to the WGSL by gpu::shaders.

/// tan 87°: steeper facets are biased and offset as if this steep.
pub const MAX_SLOPE: f32 = 20.0;
/// The widest radius a filter reaches (texels): PCSS's blocker search and
/// its penumbra filter are clamped to it.
pub const MAX_FILTER_RADIUS_TEXELS: f32 = 48.0;
/// The automatic bias's slack for float rounding and curvature: this many
/// texels of the receiver's footprint …
pub const AUTO_BIAS_SLACK_TEXELS: f32 = 0.05;
/// … plus this fraction of its depth from the light.
pub const AUTO_BIAS_SLACK_REL: f32 = 1e-5;

/// Which kind of map the filter reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MapKind {
    Depth,
    Vsm,
    Evsm,
    Msm,
}

/// The textures of the shadow map at one resolution and layer count.
pub struct ShadowTextures {
    pub resolution: u32,
    pub layers: u32,
    pub depth: wgpu::Texture,
    pub depth_array: wgpu::TextureView,
    depth_layers: Vec<wgpu::TextureView>,
    pub moments: Option<MomentTextures>,
    /// A depth map's ranges for PCF (a moment map has none).
    pub ranges: Option<RangeTextures>,
}

pub struct MomentTextures {
    pub array: wgpu::TextureView,
    layers: Vec<wgpu::TextureView>,
    scratch_array: wgpu::TextureView,
    scratch_layers: Vec<wgpu::TextureView>,
}

pub(super) fn array_texture(
    device: &wgpu::Device,
    label: &str,
    resolution: u32,
    layers: u32,
    format: wgpu::TextureFormat,
) -> (wgpu::Texture, wgpu::TextureView, Vec<wgpu::TextureView>) {
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: resolution,
            height: resolution,
            depth_or_array_layers: layers,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let array = texture.create_view(&wgpu::TextureViewDescriptor {
        label: Some(label),
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        ..Default::default()
    });
    let per_layer = (0..layers)
        .map(|layer| {
            texture.create_view(&wgpu::TextureViewDescriptor {
                label: Some(label),
                dimension: Some(wgpu::TextureViewDimension::D2),
                base_array_layer: layer,
                array_layer_count: Some(1),
                ..Default::default()
            })
        })
        .collect();
    (texture, array, per_layer)
}

impl ShadowTextures {
    /// `depth_ranges`: a depth map gets its ranges' textures (the device
    /// renders their format, `Capabilities::depth_ranges`).
    pub fn new(
        device: &wgpu::Device,
        resolution: u32,
        layers: u32,
        moments_format: Option<wgpu::TextureFormat>,
        depth_ranges: bool,
    ) -> Self {
        let (depth, depth_array, depth_layers) =
            array_texture(device, "shadow depth", resolution, layers, DEPTH_FORMAT);
        let moments = moments_format.map(|format| {
            let (_, array, layers_views) =
                array_texture(device, "shadow moments", resolution, layers, format);
            let (_, scratch_array, scratch_layers) =
                array_texture(device, "shadow moments scratch", resolution, layers, format);
            MomentTextures {
                array,
                layers: layers_views,
                scratch_array,
                scratch_layers,
            }
        });
        let ranges =
            (moments.is_none() && depth_ranges).then(|| RangeTextures::new(device, resolution, layers));
        Self {
            resolution,
            layers,
            depth,
            depth_array,
            depth_layers,
            moments,
            ranges,
        }
    }

    /// Bytes per texel of every layer: depth, plus moments and their
    /// scratch, or the depth ranges.
    pub fn bytes_per_texel(moments_format: Option<wgpu::TextureFormat>) -> u64 {
        4 + moments_format.map_or(depth_ranges::BYTES_PER_TEXEL, |f| {
            2 * f.block_copy_size(None).unwrap_or(16) as u64
        })
    }
}

/// The largest resolution ≤ `requested` that the device and the memory
/// budget allow, and whether it had to be reduced (and by what).
pub fn allowed_resolution(
    requested: u32,
    device_max: u32,
    layers: u32,
    moments_format: Option<wgpu::TextureFormat>,
) -> (u32, Option<String>) {
    let per_texel = ShadowTextures::bytes_per_texel(moments_format) * layers as u64;
    let budget_side = ((MEMORY_BUDGET_BYTES / per_texel) as f64).sqrt() as u32;
    if requested > device_max && device_max <= budget_side {
        return (
            device_max,
            Some(format!("{requested} exceeds the device limit {device_max}")),
        );
    }
    if requested > budget_side {
        let side = budget_side.max(256);
        return (
            side,
            Some(format!(
                "{requested} × {requested} × {layers} layer(s) exceeds the {} MiB shadow memory budget",
                MEMORY_BUDGET_BYTES >> 20
            )),
        );
    }
    (requested, None)
}

/// The shadow pass's pipelines and uniforms.
pub struct ShadowPass {
    uniform: wgpu::Buffer,
    /// Each layer of `uniform` again in a slot of its own (see [`Self::write`]).
    layers: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    depth_pipeline: wgpu::RenderPipeline,
    moments_pipeline: wgpu::RenderPipeline,
    blur: BlurPass,
    /// None where the device cannot render the ranges' format.
    pub ranges: Option<RangePass>,
    pub moments_format: wgpu::TextureFormat,
}

fn shadow_pipeline(
    device: &wgpu::Device,
    layout: &wgpu::PipelineLayout,
    module: &wgpu::ShaderModule,
    moments: Option<wgpu::TextureFormat>,
) -> wgpu::RenderPipeline {
    let targets = moments.map(|f| [Some(f.into())]);
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(if moments.is_some() {
            "shadow moments"
        } else {
            "shadow depth"
        }),
        layout: Some(layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some("vs"),
            compilation_options: Default::default(),
            buffers: &[Some(Vertex::position_layout())],
        },
        fragment: targets.as_ref().map(|targets| wgpu::FragmentState {
            module,
            entry_point: Some("fs_moments"),
            compilation_options: Default::default(),
            targets,
        }),
        // Both faces cast: thin and open meshes still block the light.
        primitive: wgpu::PrimitiveState {
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(true),
            // Reversed Z: nearer is larger.
            depth_compare: Some(wgpu::CompareFunction::Greater),
            stencil: Default::default(),
            // No raster bias: the camera pass applies the chosen bias mode so
            // that its trade-off (acne against peter-panning) can be seen.
            bias: wgpu::DepthBiasState::default(),
        }),
        multisample: Default::default(),
        multiview_mask: None,
        cache: None,
    })
}

impl ShadowPass {
    pub fn new(device: &wgpu::Device, moments_format: wgpu::TextureFormat, depth_ranges: bool) -> Self {
        let uniform = uniform_buffer::<ShadowRaw>(device, "shadow uniforms");
        let layers = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("shadow layers"),
            size: DYNAMIC_STRIDE * MAX_LAYERS as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let layout = binding::layout(
            device,
            "shadow pass",
            &[
                binding::uniform(0, ShaderStages::VERTEX_FRAGMENT),
                binding::dynamic_uniform(1, ShaderStages::VERTEX_FRAGMENT),
            ],
        );
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("shadow pass"),
            layout: &layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: uniform.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &layers,
                        offset: 0,
                        size: wgpu::BufferSize::new(std::mem::size_of::<ShadowLayerRaw>() as u64),
                    }),
                },
            ],
        });
        let pipeline_layout = binding::pipeline_layout(device, "shadow pass", &[&layout]);
        let module = Shader::Shadow.module(device);
        Self {
            depth_pipeline: shadow_pipeline(device, &pipeline_layout, &module, None),
            moments_pipeline: shadow_pipeline(device, &pipeline_layout, &module, Some(moments_format)),
            blur: BlurPass::new(device, moments_format),
            ranges: depth_ranges.then(|| RangePass::new(device, MAX_LAYERS)),
            uniform,
            layers,
            bind_group,
            moments_format,
        }
    }

    /// Writes the uniforms the next [`Self::encode`] draws with: `raw`,
    /// and each of its layers in the slot the layer's draws bind (a
    /// dynamic offset), so that the vertex stage reads its layer as a
    /// uniform of its own, not at an index into `raw.layers`.
    pub fn write(&self, queue: &wgpu::Queue, raw: &ShadowRaw) {
        queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(raw));
        for (i, layer) in raw.layers.iter().enumerate() {
            queue.write_buffer(&self.layers, DYNAMIC_STRIDE * i as u64, bytemuck::bytes_of(layer));
        }
    }

    /// Draws every active layer with its casters; for moment maps also blurs.
    #[allow(clippy::too_many_arguments)]
    pub fn encode(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        meshes: Meshes<'_>,
        layout: &ShadowLayout,
        casters: &[Vec<usize>],
        textures: &ShadowTextures,
        moments_clear: Option<[f64; 4]>,
        blur_radius: u32,
        mut timer: Option<&mut GpuTimer>,
    ) {
        let active = layout.active_layers();
        for (n, &layer) in active.iter().enumerate() {
            let moments = textures.moments.as_ref().zip(moments_clear);
            let color = moments.map(|(m, clear)| {
                let [r, g, b, a] = clear;
                binding::color_attachment(&m.layers[layer], wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a }))
            });
            let color_attachments = [color.flatten()];
            let timestamp_writes = timer
                .as_deref_mut()
                .and_then(|t| t.writes(Pass::Shadow, n == 0, n + 1 == active.len()));
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadow layer"),
                color_attachments: if moments.is_some() {
                    &color_attachments
                } else {
                    &[]
                },
                // Reversed Z: 0 is the far plane, "nothing here".
                depth_stencil_attachment: binding::depth_attachment(
                    &textures.depth_layers[layer],
                    wgpu::LoadOp::Clear(0.0),
                ),
                timestamp_writes,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(if moments.is_some() {
                &self.moments_pipeline
            } else {
                &self.depth_pipeline
            });
            pass.set_bind_group(0, &self.bind_group, &[(layer as u64 * DYNAMIC_STRIDE) as u32]);
            meshes.bind(&mut pass);
            for &object in &casters[layer] {
                meshes.draw(&mut pass, object);
            }
        }
        if let Some(moments) = &textures.moments
            && moments_clear.is_some()
            && blur_radius > 0
        {
            self.blur
                .encode(device, queue, encoder, moments, &active, blur_radius, timer);
        }
    }
}

/// The separable Gaussian blur of the moment layers.
struct BlurPass {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
    params: wgpu::Buffer,
}

impl BlurPass {
    fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Self {
        let layout = binding::layout(
            device,
            "moment blur",
            &[
                binding::float_array(0, ShaderStages::FRAGMENT),
                // The vertex stage reads the blur's radius (blur.wgsl).
                binding::dynamic_uniform(1, ShaderStages::VERTEX_FRAGMENT),
            ],
        );
        let pipeline_layout = binding::pipeline_layout(device, "moment blur", &[&layout]);
        let module = Shader::Blur.module(device);
        Self {
            pipeline: binding::fullscreen_pipeline(
                device,
                "moment blur",
                &pipeline_layout,
                &module,
                "fs",
                &[],
                format,
            ),
            params: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("moment blur params"),
                size: DYNAMIC_STRIDE * 2 * MAX_LAYERS as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            layout,
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn encode(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        moments: &MomentTextures,
        layers: &[usize],
        radius: u32,
        mut timer: Option<&mut GpuTimer>,
    ) {
        let group = |source: &wgpu::TextureView| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("moment blur"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::TextureView(source),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                            buffer: &self.params,
                            offset: 0,
                            size: wgpu::BufferSize::new(16),
                        }),
                    },
                ],
            })
        };
        let from_moments = group(&moments.array);
        let from_scratch = group(&moments.scratch_array);
        let steps = 2 * layers.len();
        for (n, &layer) in layers.iter().enumerate() {
            for (direction, (source, target)) in [
                (&from_moments, &moments.scratch_layers[layer]),
                (&from_scratch, &moments.layers[layer]),
            ]
            .into_iter()
            .enumerate()
            {
                let slot = (2 * layer + direction) as u64;
                let step = if direction == 0 { [1, 0] } else { [0, 1] };
                let params = BlurParamsRaw {
                    step,
                    radius_texels: radius as i32,
                    layer: layer as i32,
                };
                queue.write_buffer(&self.params, slot * DYNAMIC_STRIDE, bytemuck::bytes_of(&params));
                prefilter_pass(
                    encoder,
                    ("moment blur", target, &self.pipeline),
                    (source, (slot * DYNAMIC_STRIDE) as u32),
                    timer.as_deref_mut(),
                    (2 * n + direction, steps),
                );
            }
        }
    }
}

/// Step `index` of the `steps` passes of a map's prefilter (the moment
/// blur, or the depth ranges): a full-screen pass into `target`, the steps
/// timed as one span.
pub(super) fn prefilter_pass(
    encoder: &mut wgpu::CommandEncoder,
    (label, target, pipeline): (&str, &wgpu::TextureView, &wgpu::RenderPipeline),
    group: (&wgpu::BindGroup, u32),
    timer: Option<&mut GpuTimer>,
    (index, steps): (usize, usize),
) {
    let timestamp_writes = timer.and_then(|t| t.writes(Pass::Blur, index == 0, index + 1 == steps));
    binding::fullscreen_pass(encoder, label, target, pipeline, group, timestamp_writes);
}
