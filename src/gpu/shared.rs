//! What the views of one scene share: the scene uploaded once and the shadow
//! maps. Each view (a [`super::Renderer`]; the split view has two) owns a
//! shadow-map slot; a view whose shadow map would hold exactly what another
//! slot holds (same light, geometry, resolution, kind of map, casters) reads
//! that slot instead of drawing its own, so a split view that differs only in
//! N(m), the view or the filter of a depth map draws the map once.

use super::capabilities::Capabilities;
use super::depth_ranges;
use super::frame_report::FrameReport;
use super::light_frustum::{LayoutKind, ShadowLayout, select_casters};
use super::renderer::code;
use super::scene_buffers::GpuScene;
use super::shadow::{MAX_FILTER_RADIUS_TEXELS, MapKind, ShadowPass, ShadowTextures, allowed_resolution};
use super::timing::GpuTimer;
use super::uniforms::{ShadowLayerRaw, ShadowRaw, mat};
use crate::scene::{Aabb, Scene};
use crate::settings::{BiasMode, Filter, Settings};
use glam::DVec3;

/// Texels by which cube faces of a moment map overlap: the widest kernel and
/// two more. Moments are sampled by the hardware and blurred within a layer,
/// so they cannot follow a tap onto the neighbouring face.
const CUBE_MARGIN_TEXELS: f64 = MAX_FILTER_RADIUS_TEXELS as f64 + 2.0;

/// Texels by which cube faces of a depth map overlap: PCF's widest kernel
/// (9×9: 4.5 texels each side of the receiver) and more than a texel for
/// rounding, so that the hardware 2×2 comparison, `none` and PCF read the
/// receiver's own face only (shadow_map.wgsl, `filter_none`; pcf.wgsl,
/// `filter_pcf`): lavapipe would run the neighbouring face's addressing for
/// every pixel. The Poisson disc and PCSS, whose taps reach up to 48 texels,
/// re-project those past the edge onto the neighbouring face (`tap`), so no
/// more texels are spent on a wide overlap (12 of a 2048² face's width).
const CUBE_DEPTH_MARGIN_TEXELS: f64 = 6.0;

/// What a shadow map was drawn for: when it is unchanged, so is the map.
#[derive(Clone, Debug, PartialEq)]
struct ShadowKey {
    layout: ShadowLayout,
    casters: Vec<Vec<usize>>,
    resolution: u32,
    kind: MapKind,
    blur_texels: u32,
    scene_generation: u64,
    /// Drawn from the simplified meshes (a drag's map): a full frame never
    /// reads it.
    simplified: bool,
}

/// One view's shadow map and what it was drawn for (None: not drawn yet).
struct ShadowSlot {
    textures: ShadowTextures,
    key: Option<ShadowKey>,
    /// The map these textures replaced, kept with its key: a drag scales the
    /// map down and its end scales it back, and the map before the drag is
    /// then often still right (the light did not move), or at least its
    /// textures fit (re-creating a 2048² cube took about a full frame's time
    /// on lavapipe). At most one map more in memory.
    spare: Option<(ShadowTextures, Option<ShadowKey>)>,
}

/// The shadow map a frame reads, chosen by [`SharedScene::prepare_shadows`].
pub(super) struct PreparedShadow {
    /// The uniforms the camera and display passes read.
    pub raw: ShadowRaw,
    /// The slot whose textures hold the map.
    pub slot: usize,
    /// The map must be drawn (into `slot`) this frame.
    pub redraw: bool,
    /// The level of depth ranges to build this frame, for a map drawn before.
    pub build_ranges: Option<usize>,
}

pub struct SharedScene {
    device: wgpu::Device,
    queue: wgpu::Queue,
    caps: Capabilities,
    pub(super) scene: GpuScene,
    /// Changes with every uploaded scene.
    pub(super) generation: u64,
    shadow: ShadowPass,
    /// One per live view, indexed by its id; None once the view is dropped.
    slots: Vec<Option<ShadowSlot>>,
    /// Bound in place of the moments when the map has none.
    pub(super) dummy_moments: wgpu::TextureView,
    /// Shadow maps drawn so far, by every view.
    pub(super) shadow_draws: u64,
}

impl SharedScene {
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, caps: Capabilities, scene: &Scene) -> Self {
        let shadow = ShadowPass::new(device, caps.moments_format, caps.depth_ranges);
        let dummy_moments = ShadowTextures::new(
            device,
            1,
            caps.array_layers(1),
            Some(wgpu::TextureFormat::Rgba16Float),
            false,
        )
        .moments
        .map(|m| m.array)
        .expect("moments requested");
        Self {
            scene: GpuScene::new(device, queue, scene, &caps),
            device: device.clone(),
            queue: queue.clone(),
            caps,
            generation: 0,
            shadow,
            slots: Vec::new(),
            dummy_moments,
            shadow_draws: 0,
        }
    }

    /// Uploads another scene; every shadow map will be redrawn.
    pub fn set_scene(&mut self, scene: &Scene) {
        self.scene = GpuScene::new(&self.device, &self.queue, scene, &self.caps);
        self.generation += 1;
    }

    /// A slot for a new view; returns its id.
    pub(super) fn add_view(&mut self) -> usize {
        let slot = ShadowSlot {
            textures: ShadowTextures::new(
                &self.device,
                256,
                self.caps.array_layers(1),
                None,
                self.caps.depth_ranges,
            ),
            key: None,
            spare: None,
        };
        match self.slots.iter().position(Option::is_none) {
            Some(free) => {
                self.slots[free] = Some(slot);
                free
            }
            None => {
                self.slots.push(Some(slot));
                self.slots.len() - 1
            }
        }
    }

    /// Frees a dropped view's shadow map (it can be large).
    pub(super) fn remove_view(&mut self, view: usize) {
        if let Some(slot) = self.slots.get_mut(view) {
            *slot = None;
        }
    }

    /// The textures of a slot (a live view's).
    pub(super) fn shadow_textures(&self, slot: usize) -> &ShadowTextures {
        &self.slots[slot]
            .as_ref()
            .expect("a live view's slot exists")
            .textures
    }

    /// Fits the light's layers, picks casters, finds a slot that already
    /// holds this map or takes the view's own to redraw (unless
    /// `report.shadow_map_unused`); returns the shadow uniforms with that
    /// choice. `simplified`: the map is drawn from the simplified meshes;
    /// `depth_ranges`: as [`super::ShadeOptions::depth_ranges`].
    #[allow(clippy::too_many_arguments)]
    pub(super) fn prepare_shadows(
        &mut self,
        view: usize,
        settings: &Settings,
        light: DVec3,
        visible_bounds: &Aabb,
        simplified: bool,
        depth_ranges: bool,
        report: &mut FrameReport,
    ) -> PreparedShadow {
        let s = &settings.shadow;
        let kind = match s.filter {
            Filter::Vsm => MapKind::Vsm,
            Filter::Evsm => MapKind::Evsm,
            Filter::Msm => MapKind::Msm,
            _ => MapKind::Depth,
        };
        let moments_format = (kind != MapKind::Depth).then_some(self.caps.moments_format);
        let mut raw = ShadowRaw {
            light_position: light.as_vec3().to_array(),
            ..Default::default()
        };
        let own = self.slots[view].as_mut().expect("a live view's slot exists");
        report.resolution = own.textures.resolution;
        if !s.enabled || self.scene.bounds.is_empty() {
            own.key = None;
            return PreparedShadow {
                raw,
                slot: view,
                redraw: false,
                build_ranges: None,
            };
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
        // Cube faces of a moment map overlap by the widest filter kernel so
        // taps near a face's edge stay on it; depth taps beyond a face read
        // the next face; taps off a single frustum see no geometry (lit).
        // The margin does not depend on the depth filter, so that switching
        // between depth filters reuses the map.
        let margin = match (layers, kind) {
            (6, MapKind::Depth) => CUBE_DEPTH_MARGIN_TEXELS / resolution as f64,
            (6, _) => CUBE_MARGIN_TEXELS / resolution as f64,
            _ => 0.0,
        };
        let layout = ShadowLayout::fit(light, &self.scene.bounds, margin);
        let casters = select_casters(&layout, &self.scene.caster_bounds, visible_bounds);
        let texture_layers = self.caps.array_layers(layout.layers.len() as u32);
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
            scene_generation: self.generation,
            simplified,
        };
        // The view's own slot first, so that a view alone behaves as before.
        let holding = std::iter::once(view).chain(0..self.slots.len()).find(|&i| {
            self.slots[i]
                .as_ref()
                .is_some_and(|slot| slot.key.as_ref() == Some(&key))
        });
        let (slot, redraw) = match holding {
            Some(i) => (i, false),
            // Nobody reads the map: the view's slot stays as it is (its key
            // still says what it holds), nothing is drawn.
            None if report.shadow_map_unused => (view, false),
            None => {
                let own = self.slots[view].as_mut().expect("a live view's slot exists");
                let fits = |t: &ShadowTextures| {
                    t.resolution == resolution
                        && t.layers == texture_layers
                        && t.moments.is_some() == moments_format.is_some()
                };
                let holds = own.spare.as_ref().is_some_and(|(_, k)| k.as_ref() == Some(&key));
                if holds || !fits(&own.textures) {
                    let (textures, spare_key) = match own.spare.take() {
                        Some(spare) if holds || fits(&spare.0) => spare,
                        _ => (
                            ShadowTextures::new(
                                &self.device,
                                resolution,
                                texture_layers,
                                moments_format,
                                self.caps.depth_ranges,
                            ),
                            None,
                        ),
                    };
                    let replaced = std::mem::replace(&mut own.textures, textures);
                    own.spare = Some((replaced, std::mem::replace(&mut own.key, spare_key)));
                }
                // The spare held this very map: nothing to draw.
                let redraw = !holds;
                own.key = Some(key);
                (view, redraw)
            }
        };
        // PCF, Poisson and PCSS read the ranges of a map drawn before this frame,
        // built on the first frame that reads them.
        let ranges = self.slots[slot].as_ref().and_then(|s| s.textures.ranges.as_ref());
        let level = depth_ranges::level_for(s)
            .filter(|_| depth_ranges && !report.shadow_map_unused && !redraw && ranges.is_some());
        let build_ranges = level.filter(|&l| !ranges.is_some_and(|r| r.is_built(l)));
        report.depth_ranges = level.map(depth_ranges::block_texels);
        raw.range_block = report.depth_ranges.unwrap_or(0);
        report.shadow_redrawn = redraw;
        report.resolution = resolution;
        report.resolution_note = note;
        report.casters_per_layer = casters.iter().map(Vec::len).collect();

        for (i, layer) in layout.layers.iter().enumerate() {
            let f = &layer.frustum;
            let (a, b) = crate::scene::camera::reversed_z_coefficients(f.near, f.far);
            let [tan_left, tan_right, tan_bottom, tan_top] = f.tan.map(|t| t as f32);
            raw.layers[i] = ShadowLayerRaw {
                rotation: mat(f.rotation()),
                proj: mat(f.projection()),
                tan_left,
                tan_right,
                tan_bottom,
                tan_top,
                near_m: f.near as f32,
                far_m: f.far as f32,
                depth_a: a as f32,
                depth_b: b as f32,
            };
        }
        raw.enabled = 1;
        raw.cube = (layout.kind == LayoutKind::Cube) as u32;
        raw.layer_mask = layout.active_mask();
        raw.filter_mode = code(Filter::ALL, &s.filter);
        raw.bias_mode = code(BiasMode::ALL, &s.bias.mode);
        raw.pcf_size = s.pcf_size;
        raw.poisson_samples = s.poisson_samples;
        raw.pcss_blocker_samples = s.pcss_blocker_samples;
        raw.resolution_texels = resolution;
        raw.poisson_radius_texels = s.poisson_radius_texels;
        raw.bias_depth_m = s.bias.depth_m;
        raw.bias_slope = s.bias.slope;
        raw.normal_offset_texels = s.bias.normal_texels;
        raw.vsm_bleed_reduction = s.vsm_bleed_reduction;
        raw.evsm_exponent = self.caps.evsm_exponent();
        raw.light_radius_m = settings.light.radius_m;
        raw.msm_bias = s.msm_bias;
        report.layout = Some(layout);
        PreparedShadow {
            raw,
            slot,
            redraw,
            build_ranges,
        }
    }

    /// Draws the map chosen by `prepare_shadows` into its slot where it
    /// must be redrawn, or builds the depth ranges it asked for.
    pub(super) fn encode_shadow(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        prepared: &PreparedShadow,
        settings: &Settings,
        layout: &ShadowLayout,
        mut timer: Option<&mut GpuTimer>,
    ) {
        let moments_clear = self.moments_clear(settings.shadow.filter);
        let Some(slot) = self.slots[prepared.slot].as_mut() else {
            return;
        };
        let Some(key) = &slot.key else { return };
        if prepared.redraw {
            self.shadow.write(&self.queue, &prepared.raw);
            self.shadow.encode(
                &self.device,
                &self.queue,
                encoder,
                self.scene.caster_meshes(key.simplified),
                layout,
                &key.casters,
                &slot.textures,
                moments_clear,
                settings.shadow.vsm_blur_texels,
                timer.as_deref_mut(),
            );
            self.shadow_draws += 1;
            if let Some(ranges) = &mut slot.textures.ranges {
                ranges.invalidate();
            }
        }
        if let (Some(level), Some(ranges), Some(pass)) = (
            prepared.build_ranges,
            &mut slot.textures.ranges,
            &self.shadow.ranges,
        ) {
            pass.encode(
                (&self.device, &self.queue),
                encoder,
                (&slot.textures.depth_array, &layout.active_layers()),
                (ranges, level),
                timer,
            );
        }
    }

    fn moments_clear(&self, filter: Filter) -> Option<[f64; 4]> {
        let c = self.caps.evsm_exponent() as f64;
        match filter {
            // The far plane: u = 1.
            Filter::Vsm => Some([1.0, 1.0, 0.0, 0.0]),
            Filter::Evsm => Some([c.exp(), (2.0 * c).exp(), -(-c).exp(), (-2.0 * c).exp()]),
            Filter::Msm => Some([1.0, 1.0, 1.0, 1.0]),
            _ => None,
        }
    }
}
