//! The renderer: one object per view, long-lived, that draws a scene with
//! the given settings into textures. What changes per frame comes in as plain
//! data (`Settings`, the image size). The scene and the shadow maps live in a
//! [`SharedScene`] that renderers made with [`Renderer::sharing`] share (the
//! split view): a shadow map is drawn only when the light, the geometry or
//! the shadow settings change, and once for every view that needs that map.

use super::capabilities::Capabilities;
use super::display::{DisplayInputs, DisplayPass};
use super::flat::{FlatTargets, time_flat_pass};
use super::frame_report::FrameReport;
use super::light_frustum::{Frustum, LayoutKind, shadow_apex};
use super::lines::FrustumOverlay;
use super::noise::NoiseProbe;
use super::raytrace::{Accumulation, FrameVariant, RayTracePass};
use super::shade::ShadePass;
use super::shared::SharedScene;
use super::specialise::{ShadeOptions, Specialisation};
use super::targets::FrameTargets;
use super::timing::{GpuTimer, Pass, PassTimes};
use super::uniforms::{DisplayParamsRaw, GlobalsRaw, ShadowRaw, mat, uniform_buffer};
use crate::scene::{Aabb, Camera, Scene};
use crate::settings::{DebugView, Settings, Visibility};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

mod reads;

/// A reference image to compare with: rgb = radiance L (W/m²/sr), a = V.
#[derive(Clone, Debug, PartialEq)]
pub struct ComparisonImage {
    pub width: u32,
    pub height: u32,
    pub texels: Vec<[f32; 4]>,
}

/// Index of a variant in its enum's declaration order: the shaders' constants.
pub(super) fn code<T: PartialEq>(all: &[T], value: &T) -> u32 {
    all.iter().position(|v| v == value).unwrap_or(0) as u32
}

pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    caps: Capabilities,
    shared: Arc<Mutex<SharedScene>>,
    /// This view's id in the shared scene (its shadow-map slot).
    view: usize,
    /// The shared scene's generation the camera pass is bound to.
    scene_generation: Option<u64>,
    shade: ShadePass,
    shade_options: ShadeOptions,
    /// The shadow map's layout in the last frame (None: no map).
    layout_kind: Option<LayoutKind>,
    /// The last frame wrote the aux target (else it holds an older frame's).
    aux_written: bool,
    raytrace: RayTracePass,
    /// This view's shadow uniforms (filter and bias may differ between views
    /// that share a map).
    shadow_uniform: wgpu::Buffer,
    display: DisplayPass,
    overlay: FrustumOverlay,
    targets: Option<FrameTargets>,
    has_comparison: bool,
    comparison: Option<ComparisonImage>,
    timer: Option<GpuTimer>,
    /// The noise left in a ray-traced mean, measured on the image.
    noise: NoiseProbe,
    /// Light and material colours under the colour settings.
    colours: super::spectral::ColourCache,
}

impl Renderer {
    pub fn new(adapter: &wgpu::Adapter, device: &wgpu::Device, queue: &wgpu::Queue, scene: &Scene) -> Self {
        Self::with_capabilities(device, queue, Capabilities::of(adapter, device), scene)
    }

    /// A renderer that takes `caps` for what the device can do: the tests
    /// draw with the f16 targets of GL's fallback on any adapter.
    pub fn with_capabilities(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        caps: Capabilities,
        scene: &Scene,
    ) -> Self {
        let shared = SharedScene::new(device, queue, caps.clone(), scene);
        Self::on(device, queue, caps, Arc::new(Mutex::new(shared)))
    }

    /// Another view of this renderer's scene: it shares the uploaded scene
    /// and the shadow maps, and draws into targets of its own.
    pub fn sharing(&self) -> Self {
        Self::on(&self.device, &self.queue, self.caps.clone(), self.shared.clone())
    }

    fn on(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        caps: Capabilities,
        shared: Arc<Mutex<SharedScene>>,
    ) -> Self {
        let view = lock(&shared).add_view();
        let shade = ShadePass::new(device, caps.hdr_format);
        Self {
            raytrace: RayTracePass::new(device, &shade.raytrace_layout, caps.hdr_format),
            overlay: FrustumOverlay::new(device, &shade.globals),
            display: DisplayPass::new(device),
            timer: GpuTimer::new(device, queue),
            shadow_uniform: uniform_buffer::<ShadowRaw>(device, "camera pass shadow uniforms"),
            device: device.clone(),
            queue: queue.clone(),
            caps,
            shared,
            view,
            scene_generation: None,
            shade,
            shade_options: ShadeOptions::default(),
            layout_kind: None,
            aux_written: false,
            targets: None,
            has_comparison: false,
            comparison: None,
            noise: NoiseProbe::default(),
            colours: Default::default(),
        }
    }

    pub fn capabilities(&self) -> &Capabilities {
        &self.caps
    }

    /// Specialised or generic camera pass, with or without the aux target,
    /// from the next frame on.
    pub fn set_shade_options(&mut self, options: ShadeOptions) {
        self.shade_options = options;
    }

    /// Uploads another scene for every view that shares it; the shadow
    /// maps will be redrawn.
    pub fn set_scene(&mut self, scene: &Scene) {
        lock(&self.shared).set_scene(scene);
    }

    /// Starts building the current scene's BVH for ray-traced visibility
    /// on a thread of its own, not on the first frame that traces rays (the
    /// app's scenes; see [`super::bvh_build`]).
    pub fn build_bvh_in_background(&self) {
        lock(&self.shared).scene.build_bvh_in_background(&self.device);
    }

    /// Uploads the simplified meshes of the current scene, for every view
    /// that shares it: frames with [`ShadeOptions::simplified`] draw them.
    pub fn set_simplified(&mut self, meshes: &crate::scene::simplify::SimplifiedMeshes) {
        lock(&self.shared).scene.set_simplified(&self.device, meshes);
    }

    /// Shadow maps drawn so far by every view sharing this one's scene.
    pub fn shadow_draws(&self) -> u64 {
        lock(&self.shared).shadow_draws
    }

    /// The reference image the `error` and `ref-visibility` views compare
    /// with; it is used while its size is the frame's.
    pub fn set_comparison(&mut self, image: Option<ComparisonImage>) {
        self.comparison = image;
        self.has_comparison = false;
        if let Some(targets) = &self.targets {
            self.has_comparison = self.upload_comparison(targets);
        }
    }

    fn upload_comparison(&self, targets: &FrameTargets) -> bool {
        let Some(image) = &self.comparison else {
            return false;
        };
        if (image.width, image.height) != targets.size
            || image.texels.len() != (image.width * image.height) as usize
        {
            return false;
        }
        self.queue.write_texture(
            targets.comparison.as_image_copy(),
            bytemuck::cast_slice(&image.texels),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(16 * image.width),
                rows_per_image: Some(image.height),
            },
            targets.comparison.size(),
        );
        true
    }

    /// Starts compiling, on a thread of its own, the camera pass that a
    /// frame with `settings` and `options` will need (the shadow map laid out
    /// as in the last frame): the app asks for a drag's pipeline after each
    /// full frame, so the drag's first frame does not wait for it, and the
    /// other light's too: the radius slider turns a point light into a
    /// sphere, or back, during its drag.
    pub fn compile_ahead(&mut self, settings: &Settings, options: ShadeOptions) {
        // A drag's first frame starts its mean, if V is ray traced.
        let (simplified, attributes) = {
            let shared = lock(&self.shared);
            let scene = &shared.scene;
            (
                options.simplified && scene.simplified_triangles().is_some(),
                scene.attributes,
            )
        };
        let specialisation =
            Specialisation::for_frame(settings, self.layout_kind, options, false, simplified, attributes);
        self.shade.compile_ahead(&self.device, specialisation);
        if let Some(sphere) = specialisation.sphere_light {
            let other = Specialisation {
                sphere_light: Some(!sphere),
                ..specialisation
            };
            self.shade.compile_ahead(&self.device, other);
        }
    }

    /// How many camera-pass pipelines in use were compiled ahead.
    pub fn pipelines_compiled_ahead(&self) -> u64 {
        self.shade.compiled_ahead
    }

    /// Draws a frame of `size` pixels and submits it.
    pub fn render(&mut self, settings: &Settings, size: (u32, u32)) -> FrameReport {
        let size = (
            size.0.clamp(1, self.caps.max_texture_side),
            size.1.clamp(1, self.caps.max_texture_side),
        );
        if self.targets.as_ref().is_none_or(|t| t.size != size) {
            let targets = FrameTargets::new(&self.device, size, self.caps.hdr_format);
            self.has_comparison = self.upload_comparison(&targets);
            self.targets = Some(targets);
        }
        let shared = self.shared.clone();
        let mut shared = lock(&shared);
        if self.scene_generation != Some(shared.generation) {
            self.shade
                .set_scene(&self.device, &shared.scene, &self.shadow_uniform);
            self.scene_generation = Some(shared.generation);
        }
        let camera = settings.camera;
        let bounds = shared.scene.scene_bounds();
        let (near, far) = camera_depth_range(&camera, &bounds, self.caps.near_ratio());
        let aspect = size.0 as f64 / size.1 as f64;
        let view_proj = camera.projection(aspect, near, far) * camera.view_rotation();
        let camera_frustum = {
            let t = camera.tan_half_fovy();
            Frustum {
                apex: camera.eye.as_dvec3(),
                frame: camera.frame(),
                tan: [-t * aspect, t * aspect, -t, t],
                near,
                far,
            }
        };
        let visible: Vec<usize> = (0..shared.scene.bounds.len())
            .filter(|&i| camera_frustum.intersects(&shared.scene.bounds[i]))
            .collect();
        let visible_bounds = visible
            .iter()
            .fold(Aabb::EMPTY, |b, &i| b.union(&shared.scene.bounds[i]));

        let light = settings.light.position.as_dvec3();
        let mut report = FrameReport {
            size,
            visible_objects: visible.len(),
            casters_total: shared.scene.caster_bounds.iter().flatten().count(),
            camera_near_far: (near, far),
            simplified_triangles: shared
                .scene
                .simplified_triangles()
                .filter(|_| self.shade_options.simplified),
            ..Default::default()
        };
        let apex = shadow_apex(light, &shared.scene.scene_bounds());
        report.shadow_map_unused = !reads_shadow_map(settings);
        let simplified = report.simplified_triangles.is_some();
        let prepared = shared.prepare_shadows(
            self.view,
            settings,
            apex,
            &visible_bounds,
            simplified,
            self.shade_options.depth_ranges,
            &mut report,
        );
        self.queue
            .write_buffer(&self.shadow_uniform, 0, bytemuck::bytes_of(&prepared.raw));

        let eye = camera.eye.as_dvec3();
        let m = &settings.material;
        let generation = shared.generation;
        let colours = self
            .colours
            .apply(settings, &mut shared.scene, generation, &self.queue);
        shared.scene.write_norm_factors(&self.queue, m.norm);
        let globals = GlobalsRaw {
            view_proj: mat(view_proj),
            light_rel: (light - eye).as_vec3().to_array(),
            shadow_apex_rel: (apex - eye).as_vec3().to_array(),
            light_radius_m: settings.light.radius_m,
            eye: camera.eye.to_array(),
            light_power_w: settings.light.power_w,
            light_color: colours.shown.light.as_vec3().to_array(),
            k: m.k,
            color_override: colours
                .shown
                .color_override
                .unwrap_or_default()
                .as_vec3()
                .to_array(),
            m: m.m,
            view: code(DebugView::ALL, &settings.view.mode),
            norm_factor: m.norm.factor(f64::from(m.m)) as f32,
            visibility: code(Visibility::ALL, &settings.shadow.visibility),
            use_scene_materials: m.use_scene_materials as u32,
            use_color_override: m.color_override.is_some() as u32,
            ..Default::default()
        };
        let globals = super::delta_e::with_delta_e(globals, settings, colours);
        self.queue
            .write_buffer(&self.shade.globals, 0, bytemuck::bytes_of(&globals));
        let display_params = DisplayParamsRaw {
            size_px: [size.0 as f32, size.1 as f32],
            view: code(DebugView::ALL, &settings.view.mode),
            has_comparison: self.has_comparison as u32,
            exposure_ev: settings.view.exposure_ev,
            ..Default::default()
        };
        self.queue
            .write_buffer(&self.display.params, 0, bytemuck::bytes_of(&display_params));
        if settings.view.mode == DebugView::Frustum
            && let Some(layout) = &report.layout
        {
            self.overlay.update(&self.queue, layout, eye);
        }

        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("lumlab frame"),
            });
        if let Some(timer) = &mut self.timer {
            timer.begin_frame();
        }
        if (prepared.redraw || prepared.build_ranges.is_some())
            && let Some(layout) = &report.layout
        {
            shared.encode_shadow(&mut encoder, &prepared, settings, layout, self.timer.as_mut());
        }
        self.encode_views(&mut encoder, &shared, prepared.slot, settings, &visible, &report);
        drop(shared);
        let timed = self.timer.as_mut().is_some_and(|t| t.end_frame(&mut encoder));
        self.queue.submit([encoder.finish()]);
        if timed && let Some(timer) = &self.timer {
            timer.request_readback();
        }
        self.read_for_noise();
        report
    }

    /// The camera pass, the display pass and the frustum overlay of the
    /// frame `report` describes (its shadow map's layout, its meshes).
    fn encode_views(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        shared: &SharedScene,
        slot: usize,
        settings: &Settings,
        visible: &[usize],
        report: &FrameReport,
    ) {
        let layout = report.layout.as_ref();
        let simplified = report.simplified_triangles.is_some();
        let meshes = shared.scene.meshes(simplified);
        let targets = self
            .targets
            .as_ref()
            .expect("targets exist after render() sized them");
        let shadow_textures = shared.shadow_textures(slot);
        let shadow_group = self.shade.shadow_group(
            &self.device,
            shadow_textures,
            &shared.dummy_moments,
            &settings.shadow,
        );
        self.layout_kind = layout.map(|l| l.kind);
        let (raytrace_group, accumulating) = self.raytrace.prepare(
            &self.device,
            &self.queue,
            settings,
            targets.size,
            shared,
            FrameVariant {
                simplified,
                one_light_sample: self.shade_options.one_light_sample,
                aux: self.shade_options.aux,
            },
        );
        let specialisation = Specialisation::for_frame(
            settings,
            self.layout_kind,
            self.shade_options,
            accumulating,
            simplified,
            shared.scene.attributes,
        );
        self.shade.prepare(&self.device, specialisation);
        self.aux_written = specialisation.aux;
        // The pre-pass and the camera pass are timed as one span: the cost of shading.
        let prepass = specialisation.prepassed;
        if prepass {
            let writes = self
                .timer
                .as_mut()
                .and_then(|t| t.writes(Pass::Shade, true, false));
            self.shade
                .encode_depth(encoder, meshes, &targets.depth_view, visible, writes);
        }
        let writes = self
            .timer
            .as_mut()
            .and_then(|t| t.writes(Pass::Shade, !prepass, true));
        self.shade.encode(
            encoder,
            specialisation,
            meshes,
            &shadow_group,
            raytrace_group,
            &targets.quantity_view,
            &targets.aux_view,
            &targets.depth_view,
            visible,
            writes,
        );
        if self.caps.gl
            && (super::display::scales_to_image(settings.view.mode) || self.raytrace.folds_by_compute())
        {
            self.finish_drawing(encoder);
        }
        self.raytrace
            .encode_history(&self.device, encoder, &targets.quantity, &targets.aux);
        let inputs = DisplayInputs {
            quantity: &targets.quantity_view,
            comparison: &targets.comparison_view,
            shadow_depth: &shadow_textures.depth_array,
            shadow_uniform: &self.shadow_uniform,
            target: &targets.display_view,
            size: targets.size,
            view: settings.view.mode,
        };
        let writes = self
            .timer
            .as_mut()
            .and_then(|t| t.writes(Pass::Display, true, true));
        self.display.encode(&self.device, encoder, &inputs, writes);
        if settings.view.mode == DebugView::Frustum && layout.is_some() {
            self.overlay
                .encode(encoder, &targets.display_view, &targets.depth_view);
        }
    }

    /// GPU time (ms) of a minimal flat-colour pass over the last frame's
    /// geometry, camera and image size (see [`super::flat`]): the floor of
    /// the camera pass's cost. Waits for the GPU; overwrites the quantity
    /// target. None before the first frame.
    pub fn minimal_pass_ms(&self) -> Option<f64> {
        let targets = self.targets.as_ref()?;
        let flat = FlatTargets {
            color: &targets.quantity_view,
            format: self.caps.hdr_format,
            depth: &targets.depth_view,
        };
        let shared = lock(&self.shared);
        Some(time_flat_pass(
            &self.device,
            &self.queue,
            &shared.scene,
            &self.shade.globals,
            &flat,
        ))
    }

    /// The ray-traced visibility's accumulation after the last frame (None
    /// when V comes from the shadow map), with the last estimate of its
    /// noise (see [`Self::poll_noise`]).
    pub fn accumulation(&self) -> Option<Accumulation> {
        let a = self.raytrace.accumulation()?;
        Some(Accumulation {
            estimate: self.noise.estimate(a.run),
            ..a
        })
    }

    /// The display texture (8-bit sRGB) of the last frame.
    pub fn display_texture(&self) -> Option<&wgpu::Texture> {
        self.targets.as_ref().map(|t| &t.display)
    }

    /// Times of the latest frame whose timestamps have come back, without waiting.
    pub fn poll_timings(&mut self) -> Option<PassTimes> {
        let _ = self.device.poll(wgpu::PollType::Poll);
        self.timer.as_mut().and_then(GpuTimer::collect)
    }

    /// Waits for the GPU and returns the last frame's pass times (None without
    /// timestamp queries).
    pub fn wait_timings(&mut self) -> Option<PassTimes> {
        let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
        self.timer.as_mut().and_then(GpuTimer::collect)
    }

    /// Waits until every submitted frame is done.
    pub fn wait_idle(&self) {
        let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
    }

    /// Submits what `encoder` holds and waits for it, going on in a new
    /// encoder: on GL before a compute pass reads the camera pass's targets.
    /// Mesa 22.3's llvmpipe lets a dispatch read a texture that its
    /// rasterizer threads are still drawing, GL's ordering notwithstanding:
    /// a view's false-colour scale came out 0.67 for 15.8 in 12 of 14 runs
    /// of tests/specialised_shading.rs in one spell, and in none with
    /// `LP_NUM_THREADS=0`.
    fn finish_drawing(&self, encoder: &mut wgpu::CommandEncoder) {
        let next = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("lumlab frame, after the camera pass"),
            });
        self.queue.submit([std::mem::replace(encoder, next).finish()]);
        self.wait_idle();
    }
}

impl Drop for Renderer {
    fn drop(&mut self) {
        lock(&self.shared).remove_view(self.view);
    }
}

/// Whether a frame with `settings` reads the shadow map's textures: V comes
/// from it, or the `depth` view shows it. Under ray-traced visibility every
/// other view needs only the map's layout (texel density, frustum overlay),
/// which is fitted without drawing.
fn reads_shadow_map(settings: &Settings) -> bool {
    settings.shadow.visibility == Visibility::ShadowMap || settings.view.mode == DebugView::Depth
}

/// The shared scene, even if another view panicked while holding it (its
/// state is plain data and buffers, still usable).
fn lock(shared: &Mutex<SharedScene>) -> MutexGuard<'_, SharedScene> {
    shared.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Near and far planes (m) around the scene's bounds as the camera sees
/// them, the near plane at least `near_ratio` of the far one (a camera
/// inside the bounds; see [`super::capabilities::NEAR_RATIO`]).
pub fn camera_depth_range(camera: &Camera, bounds: &Aabb, near_ratio: f64) -> (f64, f64) {
    if bounds.is_empty() {
        return (0.01, 100.0);
    }
    let eye = camera.eye.as_dvec3();
    let forward = camera.frame().forward;
    let depths = bounds.corners().map(|c| (c.as_dvec3() - eye).dot(forward));
    let far = depths.iter().copied().fold(f64::MIN, f64::max).max(1e-6) * 1.01;
    let nearest = depths.iter().copied().fold(f64::MAX, f64::min);
    let near = if nearest > 0.0 { nearest * 0.99 } else { 0.0 }.max(far * near_ratio);
    (near, far)
}
