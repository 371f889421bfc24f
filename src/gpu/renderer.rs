//! The renderer: one object per device, long-lived, that draws a scene with
//! the given settings into textures. What changes per frame comes in as plain
//! data (`Settings`, the image size); the shadow map is redrawn only when
//! the light, the geometry or the shadow settings change.

use super::display::{DISPLAY_FORMAT, DisplayInputs, DisplayPass};
use super::light_frustum::{Frustum, LayoutKind, ShadowLayout, select_casters};
use super::lines::FrustumOverlay;
use super::readback::{PendingRead, ReadState, read_texture};
use super::scene_buffers::GpuScene;
use super::shade::ShadePass;
use super::shadow::{DEPTH_FORMAT, MapKind, ShadowPass, ShadowTextures, allowed_resolution};
use super::timing::{GpuTimer, Pass, PassTimes};
use super::uniforms::{DisplayParamsRaw, GlobalsRaw, ShadowLayerRaw, ShadowRaw, mat};
use crate::physics::Normalization;
use crate::scene::{Aabb, Camera, Scene};
use crate::settings::{BiasMode, DebugView, Filter, Settings};
use glam::DVec3;

/// What this device can do, as the lab uses it.
#[derive(Clone, Debug)]
pub struct Capabilities {
    /// Adapter name and backend, for people.
    pub adapter: String,
    pub max_texture_side: u32,
    /// The camera pass's float targets: Rgba32Float where renderable.
    pub hdr_format: wgpu::TextureFormat,
    /// VSM/EVSM moments: Rgba32Float where renderable and filterable.
    pub moments_format: wgpu::TextureFormat,
    pub timestamps: bool,
    /// The GL backend decides a texture's kind from its layer count.
    pub gl: bool,
}

impl Capabilities {
    pub fn of(adapter: &wgpu::Adapter, device: &wgpu::Device) -> Self {
        let renderable = |f: wgpu::TextureFormat| {
            adapter
                .get_texture_format_features(f)
                .allowed_usages
                .contains(wgpu::TextureUsages::RENDER_ATTACHMENT)
        };
        let f32_ok = renderable(wgpu::TextureFormat::Rgba32Float);
        let pick = |ok: bool| {
            if ok {
                wgpu::TextureFormat::Rgba32Float
            } else {
                wgpu::TextureFormat::Rgba16Float
            }
        };
        Self {
            adapter: super::context::describe_adapter(adapter),
            max_texture_side: device.limits().max_texture_dimension_2d,
            hdr_format: pick(f32_ok),
            moments_format: pick(f32_ok && device.features().contains(wgpu::Features::FLOAT32_FILTERABLE)),
            timestamps: device.features().contains(wgpu::Features::TIMESTAMP_QUERY),
            gl: adapter.get_info().backend == wgpu::Backend::Gl,
        }
    }

    /// Layers to allocate for a 2D array of `n`: on GL a single layer makes a
    /// plain 2D texture and six square layers a cube map, neither of which
    /// binds as a 2D array, so GL gets one more layer (unused).
    pub fn array_layers(&self, n: u32) -> u32 {
        if self.gl && (n == 1 || n.is_multiple_of(6)) {
            n + 1
        } else {
            n
        }
    }

    /// The EVSM warp exponent the moment format can hold without overflow.
    pub fn evsm_exponent(&self) -> f32 {
        if self.moments_format == wgpu::TextureFormat::Rgba32Float {
            30.0
        } else {
            5.0
        }
    }
}

/// A reference image to compare with: rgb = radiance L (W/m²/sr), a = V.
#[derive(Clone, Debug, PartialEq)]
pub struct ComparisonImage {
    pub width: u32,
    pub height: u32,
    pub texels: Vec<[f32; 4]>,
}

/// What a frame did, for the timings panel, the report and the tests.
#[derive(Clone, Debug, Default)]
pub struct FrameReport {
    pub size: (u32, u32),
    /// This frame drew the shadow map (otherwise it reused the last one).
    pub shadow_redrawn: bool,
    /// The light's layers; None when shadows are off or nothing is drawn.
    pub layout: Option<ShadowLayout>,
    /// Casters drawn per layer by the current shadow map.
    pub casters_per_layer: Vec<usize>,
    /// Objects that cast shadows at all.
    pub casters_total: usize,
    /// Objects inside the camera's frustum.
    pub visible_objects: usize,
    /// Shadow-map resolution in use (texels per side).
    pub resolution: u32,
    /// Why the resolution is below the requested one, if it is.
    pub resolution_note: Option<String>,
    /// Camera near and far planes (m), fitted to the scene.
    pub camera_near_far: (f64, f64),
}

impl FrameReport {
    /// "single frustum" or "cube, k of 6 faces".
    pub fn layout_summary(&self) -> String {
        match &self.layout {
            None => "no shadow map".into(),
            Some(l) if l.kind == LayoutKind::Single => "one frustum fitted to the scene".into(),
            Some(l) => format!("cube map, {} of 6 faces drawn", l.active_mask().count_ones()),
        }
    }
}

/// Texels by which cube faces overlap: the widest kernel (PCSS, 48) and two more.
const CUBE_MARGIN_TEXELS: f64 = 50.0;

/// What the shadow map was drawn for: when it is unchanged, so is the map.
#[derive(Clone, Debug, PartialEq)]
struct ShadowKey {
    layout: ShadowLayout,
    casters: Vec<Vec<usize>>,
    resolution: u32,
    kind: MapKind,
    blur_texels: u32,
    scene_generation: u64,
}

/// Textures sized like the image.
struct FrameTargets {
    size: (u32, u32),
    quantity: wgpu::Texture,
    quantity_view: wgpu::TextureView,
    aux: wgpu::Texture,
    aux_view: wgpu::TextureView,
    depth_view: wgpu::TextureView,
    display: wgpu::Texture,
    display_view: wgpu::TextureView,
    comparison: wgpu::Texture,
    comparison_view: wgpu::TextureView,
}

impl FrameTargets {
    fn new(device: &wgpu::Device, size: (u32, u32), hdr: wgpu::TextureFormat) -> Self {
        let texture = |label: &str, format, usage| {
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
        };
        use wgpu::TextureUsages as U;
        let target = U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC;
        let quantity = texture("quantity", hdr, target);
        let aux = texture("aux", hdr, target);
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

/// Index of a variant in its enum's declaration order: the shaders' constants.
fn code<T: PartialEq>(all: &[T], value: &T) -> u32 {
    all.iter().position(|v| v == value).unwrap_or(0) as u32
}

pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    caps: Capabilities,
    scene: GpuScene,
    scene_generation: u64,
    shadow: ShadowPass,
    shade: ShadePass,
    display: DisplayPass,
    overlay: FrustumOverlay,
    shadow_textures: ShadowTextures,
    dummy_moments: wgpu::TextureView,
    targets: Option<FrameTargets>,
    shadow_key: Option<ShadowKey>,
    /// The last shadow key's casters per layer (for the report of reused maps).
    has_comparison: bool,
    comparison: Option<ComparisonImage>,
    timer: Option<GpuTimer>,
}

impl Renderer {
    pub fn new(adapter: &wgpu::Adapter, device: &wgpu::Device, queue: &wgpu::Queue, scene: &Scene) -> Self {
        let caps = Capabilities::of(adapter, device);
        let shadow = ShadowPass::new(device, caps.moments_format);
        shadow.init(queue);
        let mut shade = ShadePass::new(device, caps.hdr_format);
        let gpu_scene = GpuScene::new(device, queue, scene, &caps);
        shade.set_scene(device, &gpu_scene, &shadow.uniform);
        let dummy_moments = ShadowTextures::new(
            device,
            1,
            caps.array_layers(1),
            Some(wgpu::TextureFormat::Rgba16Float),
        )
        .moments
        .map(|m| m.array)
        .expect("moments requested");
        Self {
            overlay: FrustumOverlay::new(device, &shade.globals),
            display: DisplayPass::new(device),
            shadow_textures: ShadowTextures::new(device, 256, caps.array_layers(1), None),
            timer: GpuTimer::new(device, queue),
            device: device.clone(),
            queue: queue.clone(),
            caps,
            scene: gpu_scene,
            scene_generation: 0,
            shadow,
            shade,
            dummy_moments,
            targets: None,
            shadow_key: None,
            has_comparison: false,
            comparison: None,
        }
    }

    pub fn capabilities(&self) -> &Capabilities {
        &self.caps
    }

    /// Uploads another scene; the shadow map will be redrawn.
    pub fn set_scene(&mut self, scene: &Scene) {
        self.scene = GpuScene::new(&self.device, &self.queue, scene, &self.caps);
        self.shade
            .set_scene(&self.device, &self.scene, &self.shadow.uniform);
        self.scene_generation += 1;
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
        let camera = settings.camera;
        let bounds = self.scene.scene_bounds();
        let (near, far) = camera_depth_range(&camera, &bounds);
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
        let visible: Vec<usize> = (0..self.scene.bounds.len())
            .filter(|&i| camera_frustum.intersects(&self.scene.bounds[i]))
            .collect();
        let visible_bounds = visible
            .iter()
            .fold(Aabb::EMPTY, |b, &i| b.union(&self.scene.bounds[i]));

        let light = settings.light.position.as_dvec3();
        let mut report = FrameReport {
            size,
            visible_objects: visible.len(),
            casters_total: self.scene.caster_bounds.iter().flatten().count(),
            camera_near_far: (near, far),
            ..Default::default()
        };
        let shadow_raw = self.prepare_shadows(settings, light, &visible_bounds, &mut report);
        self.queue
            .write_buffer(&self.shadow.uniform, 0, bytemuck::bytes_of(&shadow_raw));

        let eye = camera.eye.as_dvec3();
        let m = &settings.material;
        let globals = GlobalsRaw {
            view_proj: mat(view_proj),
            light_rel: (light - eye).as_vec3().extend(settings.light.radius_m).to_array(),
            eye: camera.eye.extend(1.0).to_array(),
            light_color_power: settings.light.color.extend(settings.light.power_w).to_array(),
            material: [
                m.k,
                m.m,
                m.use_scene_materials as u32 as f32,
                m.color_override.is_some() as u32 as f32,
            ],
            color_override: m.color_override.unwrap_or_default().extend(1.0).to_array(),
            modes: [
                code(DebugView::ALL, &settings.view.mode),
                code(Normalization::ALL, &m.norm),
                0,
                0,
            ],
            viewport: [size.0 as f32, size.1 as f32, 0.0, 0.0],
        };
        self.queue
            .write_buffer(&self.shade.globals, 0, bytemuck::bytes_of(&globals));
        let display_params = DisplayParamsRaw {
            modes: [
                code(DebugView::ALL, &settings.view.mode),
                0,
                0,
                self.has_comparison as u32,
            ],
            values: [settings.view.exposure_ev, 0.0, size.0 as f32, size.1 as f32],
        };
        self.queue
            .write_buffer(&self.display.params, 0, bytemuck::bytes_of(&display_params));
        if settings.view.mode == DebugView::Frustum
            && let Some(layout) = &report.layout
        {
            self.overlay.update(&self.queue, layout, eye);
        }
        self.encode_frame(settings, &visible, &report);
        report
    }

    /// Fits the light's layers, picks casters and textures, decides whether
    /// the map must be redrawn; returns the shadow uniforms.
    fn prepare_shadows(
        &mut self,
        settings: &Settings,
        light: DVec3,
        visible_bounds: &Aabb,
        report: &mut FrameReport,
    ) -> ShadowRaw {
        let s = &settings.shadow;
        let kind = match s.filter {
            Filter::Vsm => MapKind::Vsm,
            Filter::Evsm => MapKind::Evsm,
            _ => MapKind::Depth,
        };
        let moments_format = (kind != MapKind::Depth).then_some(self.caps.moments_format);
        let mut raw = ShadowRaw {
            light_position: light.as_vec3().extend(1.0).to_array(),
            ..Default::default()
        };
        report.resolution = self.shadow_textures.resolution;
        if !s.enabled || self.scene.bounds.is_empty() {
            self.shadow_key = None;
            return raw;
        }
        let layers = match ShadowLayout::fit(light, &self.scene.bounds, 0.0).kind {
            LayoutKind::Single => 1,
            LayoutKind::Cube => 6,
        };
        let (resolution, note) = allowed_resolution(
            s.resolution,
            self.caps.max_texture_side,
            self.caps.array_layers(layers),
            moments_format,
        );
        // Cube faces overlap by the widest filter kernel so taps near a face's
        // edge stay on it; taps off a single frustum see no geometry (lit).
        // The margin does not depend on the filter, so that switching between
        // depth filters reuses the map.
        let margin = if layers == 6 {
            CUBE_MARGIN_TEXELS / resolution as f64
        } else {
            0.0
        };
        let layout = ShadowLayout::fit(light, &self.scene.bounds, margin);
        let casters = select_casters(&layout, &self.scene.caster_bounds, visible_bounds);
        let texture_layers = self.caps.array_layers(layout.layers.len() as u32);
        if self.shadow_textures.resolution != resolution
            || self.shadow_textures.layers != texture_layers
            || self.shadow_textures.moments.is_some() != moments_format.is_some()
        {
            self.shadow_textures =
                ShadowTextures::new(&self.device, resolution, texture_layers, moments_format);
            self.shadow_key = None;
        }
        let key = ShadowKey {
            layout: layout.clone(),
            casters: casters.clone(),
            resolution,
            kind,
            blur_texels: if moments_format.is_some() {
                s.vsm_blur_texels
            } else {
                0
            },
            scene_generation: self.scene_generation,
        };
        report.shadow_redrawn = self.shadow_key.as_ref() != Some(&key);
        self.shadow_key = Some(key);
        report.resolution = resolution;
        report.resolution_note = note;
        report.casters_per_layer = casters.iter().map(Vec::len).collect();

        for (i, layer) in layout.layers.iter().enumerate() {
            let f = &layer.frustum;
            let (a, b) = crate::scene::camera::reversed_z_coefficients(f.near, f.far);
            raw.layers[i] = ShadowLayerRaw {
                rotation: mat(f.rotation()),
                proj: mat(f.projection()),
                tan_bounds: f.tan.map(|t| t as f32),
                depth: [f.near as f32, f.far as f32, a as f32, b as f32],
            };
        }
        raw.mode = [
            1,
            (layout.kind == LayoutKind::Cube) as u32,
            layout.active_mask(),
            code(Filter::ALL, &s.filter),
        ];
        raw.counts = [
            s.pcf_size,
            s.poisson_samples,
            s.pcss_blocker_samples,
            code(BiasMode::ALL, &s.bias.mode),
        ];
        raw.bias = [
            s.poisson_radius_texels,
            s.bias.depth_m,
            s.bias.slope,
            s.bias.normal_texels,
        ];
        raw.misc = [
            resolution as f32,
            s.vsm_bleed_reduction,
            self.caps.evsm_exponent(),
            settings.light.radius_m,
        ];
        report.layout = Some(layout);
        raw
    }

    fn moments_clear(&self, filter: Filter) -> Option<[f64; 4]> {
        let c = self.caps.evsm_exponent() as f64;
        match filter {
            // The far plane: u = 1.
            Filter::Vsm => Some([1.0, 1.0, 0.0, 0.0]),
            Filter::Evsm => Some([c.exp(), (2.0 * c).exp(), -(-c).exp(), (-2.0 * c).exp()]),
            _ => None,
        }
    }

    fn encode_frame(&mut self, settings: &Settings, visible: &[usize], report: &FrameReport) {
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("lumlab frame"),
            });
        if let Some(timer) = &mut self.timer {
            timer.begin_frame();
        }
        if report.shadow_redrawn
            && let (Some(layout), Some(key)) = (&report.layout, &self.shadow_key)
        {
            self.shadow.encode(
                &self.device,
                &self.queue,
                &mut encoder,
                &self.scene,
                layout,
                &key.casters,
                &self.shadow_textures,
                self.moments_clear(settings.shadow.filter),
                settings.shadow.vsm_blur_texels,
                self.timer.as_mut(),
            );
        }
        let targets = self
            .targets
            .as_ref()
            .expect("targets exist after render() sized them");
        let shadow_group = self
            .shade
            .shadow_group(&self.device, &self.shadow_textures, &self.dummy_moments);
        let writes = self
            .timer
            .as_mut()
            .and_then(|t| t.writes(Pass::Shade, true, true));
        self.shade.encode(
            &mut encoder,
            &self.scene,
            &shadow_group,
            &targets.quantity_view,
            &targets.aux_view,
            &targets.depth_view,
            visible,
            writes,
        );
        let inputs = DisplayInputs {
            quantity: &targets.quantity_view,
            aux: &targets.aux_view,
            comparison: &targets.comparison_view,
            shadow_depth: &self.shadow_textures.depth_array,
            shadow_uniform: &self.shadow.uniform,
            target: &targets.display_view,
            size: targets.size,
        };
        let writes = self
            .timer
            .as_mut()
            .and_then(|t| t.writes(Pass::Display, true, true));
        self.display.encode(&self.device, &mut encoder, &inputs, writes);
        if settings.view.mode == DebugView::Frustum && report.layout.is_some() {
            self.overlay
                .encode(&mut encoder, &targets.display_view, &targets.depth_view);
        }
        let timed = self.timer.as_mut().is_some_and(|t| t.end_frame(&mut encoder));
        self.queue.submit([encoder.finish()]);
        if timed && let Some(timer) = &self.timer {
            timer.request_readback();
        }
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

    fn read_float_target(&self, texture: &wgpu::Texture) -> Vec<[f32; 4]> {
        let bytes_per_texel = texture.format().block_copy_size(None).unwrap_or(16);
        let bytes = read_texture(&self.device, &self.queue, texture, 0, bytes_per_texel);
        decode_float_texels(&bytes, bytes_per_texel)
    }

    /// Starts reading a rectangle of the last frame's quantity or aux target
    /// without blocking (the app's pixel probe and error statistics); None
    /// before the first frame or when the rectangle leaves the image.
    pub fn request_texels(
        &self,
        target: FloatTarget,
        origin: (u32, u32),
        size: (u32, u32),
    ) -> Option<PendingTexels> {
        let t = self.targets.as_ref()?;
        let fits = |o: u32, s: u32, side: u32| s > 0 && o.checked_add(s).is_some_and(|end| end <= side);
        if !(fits(origin.0, size.0, t.size.0) && fits(origin.1, size.1, t.size.1)) {
            return None;
        }
        let texture = match target {
            FloatTarget::Quantity => &t.quantity,
            FloatTarget::Aux => &t.aux,
        };
        let bytes_per_texel = texture.format().block_copy_size(None).unwrap_or(16);
        Some(PendingTexels {
            read: PendingRead::texture_region(
                &self.device,
                &self.queue,
                texture,
                origin,
                size,
                bytes_per_texel,
            ),
            bytes_per_texel,
        })
    }

    /// Starts reading the last false-colour scale (see [`Self::read_scale`])
    /// without blocking.
    pub fn request_scale(&self) -> PendingScale {
        PendingScale(PendingRead::buffer(
            &self.device,
            &self.queue,
            self.display.scale_buffer(),
            16,
        ))
    }

    /// The last frame's view quantity, row-major from the top (W/m²/sr for `shaded`).
    pub fn read_quantity(&self) -> Vec<[f32; 4]> {
        self.targets
            .as_ref()
            .map_or_else(Vec::new, |t| self.read_float_target(&t.quantity))
    }

    /// The last frame's aux target: V, texel density, cos θ, coverage.
    pub fn read_aux(&self) -> Vec<[f32; 4]> {
        self.targets
            .as_ref()
            .map_or_else(Vec::new, |t| self.read_float_target(&t.aux))
    }

    /// The last frame's displayed image.
    pub fn read_display(&self) -> image::RgbaImage {
        let Some(t) = &self.targets else {
            return image::RgbaImage::new(0, 0);
        };
        let bytes = read_texture(&self.device, &self.queue, &t.display, 0, 4);
        image::RgbaImage::from_raw(t.size.0, t.size.1, bytes).unwrap_or_default()
    }

    /// The largest value of the last false-colour view (its scale).
    pub fn read_scale(&self) -> f32 {
        self.display.read_scale(&self.device, &self.queue)
    }
}

/// The frame's float targets that can be read back.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FloatTarget {
    /// The view's quantity (radiance L in W/m²/sr for `shaded`).
    Quantity,
    /// V, shadow-map texels per pixel, max(0, n·l), coverage.
    Aux,
}

/// Texels on their way back (see [`Renderer::request_texels`]).
pub struct PendingTexels {
    read: PendingRead,
    bytes_per_texel: u32,
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

/// A false-colour scale on its way back (see [`Renderer::request_scale`]).
pub struct PendingScale(PendingRead);

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
fn decode_float_texels(bytes: &[u8], bytes_per_texel: u32) -> Vec<[f32; 4]> {
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

/// Near and far planes (m) around the scene's bounds as the camera sees them.
pub fn camera_depth_range(camera: &Camera, bounds: &Aabb) -> (f64, f64) {
    if bounds.is_empty() {
        return (0.01, 100.0);
    }
    let eye = camera.eye.as_dvec3();
    let forward = camera.frame().forward;
    let depths = bounds.corners().map(|c| (c.as_dvec3() - eye).dot(forward));
    let far = depths.iter().copied().fold(f64::MIN, f64::max).max(1e-6) * 1.01;
    let nearest = depths.iter().copied().fold(f64::MAX, f64::min);
    // Reversed-Z float depth keeps its precision for near/far ratios far
    // beyond 1e6, so a camera inside the bounds can use a tiny near plane.
    let near = if nearest > 0.0 { nearest * 0.99 } else { 0.0 }.max(far * 1e-7);
    (near, far)
}
