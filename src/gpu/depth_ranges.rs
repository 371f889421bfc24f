//! Bounds on the stored depths over windows of the shadow map, read by PCF,
//! the Poisson disc and PCSS's blocker search to decide a whole kernel at once
//! (shaders/depth_ranges.wgsl, and `range_verdict` in shaders/pcf.wgsl).
//! Where every texel under a kernel is farther than the receiver, or every
//! one nearer by more than the bias can reach, one read gives V = 1 or
//! V = 0 instead of (n + 1)² depth tests: on lavapipe a texel fetch costs
//! about a flat pass, and most pixels are fully lit or fully shadowed.
//!
//! A bound is a plane in the texel coordinates and a half-width: every
//! stored value of the window lies within it. A plane of the scene is
//! affine in the texel coordinates (reversed Z stores an affine function of
//! 1/z), so where the receiver's own surface, sloped in the light's view,
//! fills the window the bound is that surface to rounding, and the auto
//! bias's kernel is decided lit without a tap; a flat range (gradient 0)
//! could not tell it from an occluder on the side nearer the light.
//!
//! Built per map and kernel size on the first frame that reuses a map (a
//! map drawn for one frame, under a moving light, never pays for them), in
//! two passes per layer: blocks of B×B texels (the plane through the first
//! texel and its neighbours in x and y, or the flat range where it bounds
//! closer), then windows of 2×2 blocks (the flat range or the first block's
//! plane, bounding all four). The build reads every texel of the map once.

use super::binding;
use super::shaders::Shader;
use super::shadow::MAX_FILTER_RADIUS_TEXELS;
use super::timing::GpuTimer;
use super::uniforms::{DYNAMIC_STRIDE, RangeParamsRaw};
use crate::settings::{Filter, ShadowSettings};
use wgpu::ShaderStages;

/// The block sides B (texels) built: a kernel of n + 1 texels a side fits
/// in one window when n ≤ B. 128 serves PCSS's blocker search (n ≤ 99):
/// its windows are coarse, but where one plane fills 256² texels (the open
/// ground) every pixel skips all of its blocker taps.
const BLOCKS: [u32; 4] = [4, 8, 16, 128];
pub const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// Which level serves the filter of `shadow`: the smallest block B with
/// n ≤ B for a filter whose taps span at most n + 1 texels a side (PCF n×n;
/// a Poisson disc of radius R, ⌈2R⌉ + 3 with a texel of slack each side,
/// as `disc_verdict` bounds them; PCSS's search, a disc of up to
/// [`MAX_FILTER_RADIUS_TEXELS`]). None: the filter reads no ranges, or
/// its taps spread wider than any window.
pub fn level_for(shadow: &ShadowSettings) -> Option<usize> {
    let n = match shadow.filter {
        Filter::Pcf => shadow.pcf_size,
        Filter::Poisson => (2.0 * shadow.poisson_radius_texels).ceil() as u32 + 3,
        // PCSS's blocker search: a disc of up to the widest filter radius.
        Filter::Pcss => (2.0 * MAX_FILTER_RADIUS_TEXELS).ceil() as u32 + 3,
        _ => return None,
    };
    BLOCKS.iter().position(|&b| n <= b)
}

/// Block side B (texels) of a level.
pub fn block_texels(level: usize) -> u32 {
    BLOCKS[level]
}

/// Bytes per shadow-map texel the ranges of every level take, rounded up.
pub const BYTES_PER_TEXEL: u64 = 3;

/// One level's blocks and windows, each a 2D array with a layer per map layer.
struct Level {
    blocks: (wgpu::TextureView, Vec<wgpu::TextureView>),
    windows: (wgpu::TextureView, Vec<wgpu::TextureView>),
    /// The windows' texture, for reading them back.
    windows_texture: wgpu::Texture,
    /// The windows hold the current map's ranges.
    built: bool,
}

/// The ranges of one shadow map, at every level.
pub struct RangeTextures {
    levels: Vec<Level>,
}

impl RangeTextures {
    pub fn new(device: &wgpu::Device, resolution: u32, layers: u32) -> Self {
        let textures =
            |label: &str, side: u32| super::shadow::array_texture(device, label, side, layers, FORMAT);
        let levels = BLOCKS
            .iter()
            .map(|&b| {
                let side = resolution.div_ceil(b);
                let (_, blocks, per_layer) = textures("shadow depth blocks", side);
                let (windows_texture, windows, windows_per_layer) = textures("shadow depth ranges", side);
                Level {
                    blocks: (blocks, per_layer),
                    windows: (windows, windows_per_layer),
                    windows_texture,
                    built: false,
                }
            })
            .collect();
        Self { levels }
    }

    /// The map was drawn again: no range holds.
    pub fn invalidate(&mut self) {
        for level in &mut self.levels {
            level.built = false;
        }
    }

    pub fn is_built(&self, level: usize) -> bool {
        self.levels[level].built
    }

    /// The windows of a level, as the camera pass binds them.
    pub fn windows(&self, level: usize) -> &wgpu::TextureView {
        &self.levels[level].windows.0
    }

    /// The bounds of one layer's windows at a level, row by row: (the
    /// plane at the window's first texel, its steps per texel in x and y,
    /// the half-width), as shaders/depth_ranges.wgsl writes them.
    pub fn read_windows(
        &self,
        (device, queue): (&wgpu::Device, &wgpu::Queue),
        level: usize,
        layer: u32,
    ) -> Vec<[f32; 4]> {
        let bytes =
            super::readback::read_texture(device, queue, &self.levels[level].windows_texture, layer, 16);
        super::targets::decode_float_texels(&bytes, 16)
    }
}

/// The two pipelines, their bind group layout and per-layer parameters.
pub struct RangePass {
    layout: wgpu::BindGroupLayout,
    blocks: wgpu::RenderPipeline,
    windows: wgpu::RenderPipeline,
    sampler: wgpu::Sampler,
    params: wgpu::Buffer,
}

impl RangePass {
    pub fn new(device: &wgpu::Device, max_layers: u32) -> Self {
        let layout = binding::layout(
            device,
            "depth ranges",
            &[
                binding::float_array(0, ShaderStages::FRAGMENT),
                binding::sampler(1, ShaderStages::FRAGMENT, wgpu::SamplerBindingType::NonFiltering),
                // The vertex stage reads the block's side (depth_ranges.wgsl).
                binding::dynamic_uniform(2, ShaderStages::VERTEX_FRAGMENT),
            ],
        );
        let pipeline_layout = binding::pipeline_layout(device, "depth ranges", &[&layout]);
        let module = Shader::DepthRanges.module(device);
        let pipeline = |entry: &str| {
            binding::fullscreen_pipeline(
                device,
                "depth ranges",
                &pipeline_layout,
                &module,
                entry,
                &[],
                FORMAT,
            )
        };
        Self {
            blocks: pipeline("fs_blocks"),
            windows: pipeline("fs_windows"),
            sampler: device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some("depth ranges"),
                ..Default::default()
            }),
            params: binding::buffer(
                device,
                "depth range params",
                DYNAMIC_STRIDE * max_layers as u64,
                wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            ),
            layout,
        }
    }

    /// Builds `level` of `ranges` from the depth map `depth` (its layers
    /// `layers`), timed as the map's prefilter.
    pub fn encode(
        &self,
        (device, queue): (&wgpu::Device, &wgpu::Queue),
        encoder: &mut wgpu::CommandEncoder,
        (depth, layers): (&wgpu::TextureView, &[usize]),
        (ranges, level): (&mut RangeTextures, usize),
        mut timer: Option<&mut GpuTimer>,
    ) {
        let group = |source: &wgpu::TextureView| {
            binding::group(
                device,
                "depth ranges",
                &self.layout,
                &[
                    wgpu::BindingResource::TextureView(source),
                    wgpu::BindingResource::Sampler(&self.sampler),
                    wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &self.params,
                        offset: 0,
                        // 16: std140 backends (GL) round a uniform block up to 16 bytes.
                        size: wgpu::BufferSize::new(16),
                    }),
                ],
            )
        };
        let target = &ranges.levels[level];
        let from_depth = group(depth);
        let from_blocks = group(&target.blocks.0);
        let steps = 2 * layers.len();
        for (n, &layer) in layers.iter().enumerate() {
            let params = RangeParamsRaw {
                block_texels: BLOCKS[level] as i32,
                layer: layer as i32,
                ..Default::default()
            };
            let offset = layer as u64 * DYNAMIC_STRIDE;
            queue.write_buffer(&self.params, offset, bytemuck::bytes_of(&params));
            for (step, (pipeline, source, output)) in [
                (&self.blocks, &from_depth, &target.blocks.1[layer]),
                (&self.windows, &from_blocks, &target.windows.1[layer]),
            ]
            .into_iter()
            .enumerate()
            {
                super::shadow::prefilter_pass(
                    encoder,
                    ("depth ranges", output, pipeline),
                    (source, offset as u32),
                    timer.as_deref_mut(),
                    (2 * n + step, steps),
                );
            }
        }
        ranges.levels[level].built = true;
    }
}
