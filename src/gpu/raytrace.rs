//! The ray-traced visibility source (`shaders/raytrace.wgsl`, `shaders/bvh.wgsl`):
//! its bind group (group 2 of the camera pass) and the progressive
//! accumulation. The camera pass traces the shadow rays; while the settings,
//! the image size and the scene stay the same, each frame is folded into the
//! running mean of the frames before (the previous targets, copied into a
//! history after the pass), up to `ShadowSettings::rt_max_frames`. Any change
//! starts the mean anew. Where the targets are f16 (GL), the camera pass
//! writes each frame as it is and `accumulate` folds it in f32 after.

use super::accumulate::{self, SeparateFold};
use super::binding;
use super::bvh::{BvhGridRaw, GpuBvh};
use super::noise::{self, NoiseEstimate};
use super::shared::SharedScene;
use crate::settings::{Settings, Visibility};
use bytemuck::{Pod, Zeroable};
use wgpu::ShaderStages;

/// `RayTrace` of shaders/raytrace.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct RayTraceRaw {
    pub frames_before: u32,
    pub weight: f32,
    pub rays: u32,
    pub first_sample: u32,
    pub pair_count: u32,
    pub _padding: [u32; 3],
    pub grid: BvhGridRaw,
}

/// Where the accumulation stands after a frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Accumulation {
    /// Frames in the running mean.
    pub frames: u32,
    /// Frames after which the image holds ([`Settings::ray_traced_frames`]:
    /// one under a point light).
    pub max_frames: u32,
    /// Shadow rays per pixel and frame (1 for a point light).
    pub rays_per_frame: u32,
    /// A bound on the standard error of V that remains, σ ≤ 0.5 / √(N·S)
    /// (N frames of S independent samples of a quantity in [0, 1]; the
    /// low-discrepancy samples make the real error smaller); 0 for a point
    /// light (exact).
    pub noise_bound: f32,
    /// This run of the mean: a number no other run of any renderer has.
    pub run: u64,
    /// The noise measured on the image, once a read of it is back
    /// (`Renderer::accumulation` fills it in).
    pub estimate: Option<NoiseEstimate>,
}

impl Accumulation {
    pub fn is_complete(&self) -> bool {
        self.frames >= self.max_frames
    }

    /// Whether the image holds under a noise target (percent of the mean,
    /// 0: none): complete, or its measured noise at most the target.
    pub fn holds(&self, noise_target_percent: f32) -> bool {
        self.is_complete() || self.meets(noise_target_percent)
    }

    /// Whether the noise measured on the mean is at most
    /// `noise_target_percent` % of it (never for a target of 0).
    pub fn meets(&self, noise_target_percent: f32) -> bool {
        noise_target_percent > 0.0
            && self
                .estimate
                .is_some_and(|e| 100.0 * e.relative <= f64::from(noise_target_percent))
    }
}

/// The layout of group 2 of the camera pass.
pub fn layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let fragment = ShaderStages::FRAGMENT;
    binding::layout(
        device,
        "ray-traced visibility",
        &[
            // The camera pass's vertex stage copies its knobs (shadow_map.wgsl).
            binding::uniform(0, ShaderStages::VERTEX_FRAGMENT),
            binding::storage(1, fragment, true),
            binding::storage(2, fragment, true),
            binding::float_texture(3, fragment),
            binding::float_texture(4, fragment),
        ],
    )
}

/// What the running mean was made with: when it changes, the mean restarts.
#[derive(Clone, Debug, PartialEq)]
struct Key {
    settings: Settings,
    size: (u32, u32),
    scene_generation: u64,
    variant: FrameVariant,
}

/// How a frame differs from what the settings say (see
/// [`super::ShadeOptions`]): a drag frame's rays, never folded into a still
/// frame's mean, and whether the frame writes the aux target, whose history
/// a mean begun without it lacks.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameVariant {
    /// Against the BVH of the scene's simplified meshes, where it has them.
    pub simplified: bool,
    /// One ray a pixel towards a sphere light.
    pub one_light_sample: bool,
    /// The frame writes the aux target (and its history).
    pub aux: bool,
}

/// The previous frame's quantity and aux targets.
struct History {
    size: (u32, u32),
    quantity: wgpu::Texture,
    aux: wgpu::Texture,
    group: wgpu::BindGroup,
    scene_generation: u64,
    /// The group binds the simplified meshes' BVH.
    simplified_bvh: bool,
    /// The group binds the scene's BVH, not the empty one that stands in
    /// until a frame traces rays (`GpuScene::bvh`).
    scene_bvh: bool,
}

pub struct RayTracePass {
    layout: wgpu::BindGroupLayout,
    /// The camera pass's target format: the history is a copy of its targets.
    format: wgpu::TextureFormat,
    uniform: wgpu::Buffer,
    history: Option<History>,
    /// Beside f16 targets: the mean folded in f32 after the camera pass,
    /// which then reads no history.
    separate: Option<SeparateFold>,
    /// This frame is folded by `separate` (a sphere light's, ray traced).
    separate_this_frame: bool,
    key: Option<Key>,
    frames: u32,
    run: u64,
    status: Option<Accumulation>,
}

impl RayTracePass {
    pub fn new(device: &wgpu::Device, layout: &wgpu::BindGroupLayout, format: wgpu::TextureFormat) -> Self {
        Self {
            layout: layout.clone(),
            format,
            uniform: super::uniforms::uniform_buffer::<RayTraceRaw>(device, "ray-traced visibility"),
            history: None,
            separate: (format == accumulate::TARGET_FORMAT).then(|| SeparateFold::new(device)),
            separate_this_frame: false,
            key: None,
            frames: 0,
            run: noise::new_run(),
            status: None,
        }
    }

    /// The accumulation after the last frame; None when V is not ray traced.
    pub fn accumulation(&self) -> Option<Accumulation> {
        self.status
    }

    /// Sets this frame's uniforms and returns the bind group the camera pass
    /// uses, and whether the camera pass folds in the history of the frames
    /// before (a sphere light's mean under way beside f32 targets; a point
    /// light's one frame is exact, and the same again).
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        settings: &Settings,
        size: (u32, u32),
        shared: &SharedScene,
        variant: FrameVariant,
    ) -> (&wgpu::BindGroup, bool) {
        let scene_generation = shared.generation;
        let s = &settings.shadow;
        let traced = s.visibility == Visibility::RayTraced;
        let (bvh, scene_bvh) = shared.scene.bvh(device, variant.simplified, traced);
        if self.history.as_ref().is_none_or(|h| {
            h.size != size
                || h.scene_generation != scene_generation
                || h.simplified_bvh != variant.simplified
                || h.scene_bvh != scene_bvh
        }) {
            let target = Target {
                size,
                // The camera pass reads no history beside f16 targets.
                texture_size: if self.separate.is_some() { (1, 1) } else { size },
                format: self.format,
                scene_generation,
                simplified_bvh: variant.simplified,
                scene_bvh,
            };
            self.history = Some(History::new(device, &self.layout, &self.uniform, bvh, target));
            self.key = None;
        }
        let mut key_settings = settings.clone();
        // The noise target says when the lab stops asking for frames, not
        // what a frame holds: a new target goes on with the mean.
        key_settings.shadow.rt_noise_target_percent = 0.0;
        let key = Key {
            settings: key_settings,
            size,
            scene_generation,
            variant,
        };
        if !traced || self.key.as_ref() != Some(&key) {
            self.frames = 0;
            self.run = noise::new_run();
        }
        self.key = traced.then_some(key);
        let max_frames = settings.ray_traced_frames();
        let frames_before = self.frames;
        let weight = if frames_before >= max_frames {
            0.0
        } else {
            self.frames += 1;
            1.0 / self.frames as f32
        };
        let sphere = settings.light.is_sphere();
        let rays_per_frame = rays_per_pixel(settings, variant.one_light_sample);
        self.status = traced.then(|| Accumulation {
            frames: self.frames,
            max_frames,
            rays_per_frame,
            noise_bound: if sphere {
                0.5 / ((self.frames * rays_per_frame) as f32).sqrt()
            } else {
                0.0
            },
            run: self.run,
            estimate: None,
        });
        let sphere_traced = traced && sphere;
        self.separate_this_frame = sphere_traced && self.separate.is_some();
        if let (Some(separate), true) = (&mut self.separate, self.separate_this_frame) {
            separate.prepare(device, queue, size, weight);
        }
        // The camera pass folds in its history only for a sphere light's
        // mean under way beside f32 targets; the uniform says 0 otherwise,
        // for the generic pipeline (whose history may not exist: 1 × 1
        // beside f16 targets).
        let accumulating = sphere_traced && !self.separate_this_frame && frames_before > 0;
        let raw = RayTraceRaw {
            frames_before: if accumulating { frames_before } else { 0 },
            weight,
            rays: rays_per_frame,
            first_sample: frames_before.wrapping_mul(rays_per_frame),
            pair_count: bvh.pair_count,
            _padding: [0; 3],
            grid: bvh.grid,
        };
        queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&raw));
        (&self.history.as_ref().expect("made above").group, accumulating)
    }

    /// This frame's mean is folded by a compute pass that reads the camera
    /// pass's targets (`gpu::accumulate`, beside f16 targets).
    pub fn folds_by_compute(&self) -> bool {
        self.separate_this_frame
    }

    /// Keeps this frame's targets as the history of the next, or beside f16
    /// targets folds them into the f32 mean (ray traced only; the aux target
    /// where the frame wrote it).
    pub fn encode_history(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        quantity: &wgpu::Texture,
        aux: &wgpu::Texture,
    ) {
        let (Some(history), Some(key)) = (&self.history, &self.key) else {
            return;
        };
        if let Some(separate) = &self.separate {
            if self.separate_this_frame {
                separate.encode(device, encoder, quantity, aux, key.variant.aux);
            }
            return;
        }
        let written = [quantity, &history.quantity];
        super::targets::copy_pairs(encoder, written, [aux, &history.aux], key.variant.aux);
    }
}

/// Shadow rays a pixel traces in a frame: the settings' (one to a point
/// light), or one where the frame traces `one_light_sample` (a drag's).
pub fn rays_per_pixel(settings: &Settings, one_light_sample: bool) -> u32 {
    if one_light_sample {
        1
    } else {
        settings.ray_traced_rays_per_frame()
    }
}

/// The fewest rays a pixel whose walks of the BVH trace four rays each (a
/// walk for four costs 45 % more than a walk for one on lavapipe).
pub const FOUR_RAYS_A_WALK_FROM: u32 = 2;
/// The fewest rays a pixel whose walks trace eight each (a walk for eight
/// costs some 60 % more than one for four).
pub const EIGHT_RAYS_A_WALK_FROM: u32 = 8;

/// Rays a walk of the BVH traces for `rays` a pixel: one, four or eight,
/// from the two thresholds above, which WGSL's `rays_per_walk`
/// (shaders/raytrace.wgsl) shares (`shaders::shared_u32_constants`).
pub fn rays_per_walk(rays: u32) -> u32 {
    if rays >= EIGHT_RAYS_A_WALK_FROM {
        8
    } else if rays >= FOUR_RAYS_A_WALK_FROM {
        4
    } else {
        1
    }
}

/// What a history is made for.
struct Target {
    size: (u32, u32),
    /// The textures' size: the image's, or 1 × 1 where nothing reads them.
    texture_size: (u32, u32),
    format: wgpu::TextureFormat,
    scene_generation: u64,
    simplified_bvh: bool,
    scene_bvh: bool,
}

impl History {
    fn new(
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        uniform: &wgpu::Buffer,
        bvh: &GpuBvh,
        target: Target,
    ) -> Self {
        let Target {
            size,
            texture_size,
            format,
            scene_generation,
            simplified_bvh,
            scene_bvh,
        } = target;
        let usage = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST;
        let texture = |label: &str| super::targets::image_texture(device, label, texture_size, format, usage);
        let quantity = texture("history quantity");
        let aux = texture("history aux");
        let group = binding::group(
            device,
            "ray-traced visibility",
            layout,
            &[
                uniform.as_entire_binding(),
                bvh.pairs.as_entire_binding(),
                bvh.triangles.as_entire_binding(),
                wgpu::BindingResource::TextureView(&quantity.create_view(&Default::default())),
                wgpu::BindingResource::TextureView(&aux.create_view(&Default::default())),
            ],
        );
        Self {
            size,
            quantity,
            aux,
            group,
            scene_generation,
            simplified_bvh,
            scene_bvh,
        }
    }
}
