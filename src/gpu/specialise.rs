//! The camera pass compiled per view, per filter and per visibility source.
//! shaders/shade.wgsl and shadow_map.wgsl read their mode through
//! pipeline-overridable constants (`SPECIALISED_VIEW`, `SPECIALISED_FILTER`,
//! `SPECIALISED_VISIBILITY`, `SPECIALISED_BIAS`, `SPECIALISED_CUBE`: the
//! shadow map's layout, `SPECIALISED_SHADOWS`: shadows on or off,
//! `SPECIALISED_SPHERE_LIGHT`: a sphere or a point light, under ray-traced
//! V `SPECIALISED_ACCUMULATING` and `SPECIALISED_RAYS_PER_WALK`,
//! `SPECIALISED_VERTEX_COLOURS` and
//! `SPECIALISED_TEXTURES`: the scene has vertex colours, textures); a
//! pipeline given one value keeps only that case of each `switch` (the
//! compiler folds the rest away), the default
//! value `SPECIALISE_ANY` reads the uniforms: the generic pipeline the tests
//! hold the specialised ones to. A new mode (another visibility source, a
//! bias mode) is one more constant here and one more `*_mode()` in WGSL.

use super::light_frustum::LayoutKind;
use super::raytrace::{rays_per_pixel, rays_per_walk};
use super::renderer::code;
use super::scene_buffers::Vertex;
use super::shadow::DEPTH_FORMAT;
use crate::settings::{BiasMode, DebugView, Filter, Settings, Visibility};

/// How a renderer runs its camera pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShadeOptions {
    /// One pipeline per view × filter × visibility source (the default), or
    /// the generic one that branches on the uniforms.
    pub specialised: bool,
    /// Also write the aux target (V, texel density, cos θ, coverage) that the
    /// probe and `Renderer::read_aux` read. The app's frames skip it but
    /// where [`Self::still`] asks for it (the probed half, ray-traced V).
    pub aux: bool,
    /// Draw the depth pre-pass first, so that each pixel is shaded once.
    /// It pays for itself on large images (less CPU on lavapipe at 1000 ×
    /// 680), not on the app's small interaction frames, which skip it,
    /// except those of large scenes under ray-traced shadows (see
    /// [`Specialisation::for_frame`]).
    pub depth_prepass: bool,
    /// Draw the scene's simplified meshes, in the camera pass and the shadow
    /// map, where it has them (large scenes, [`crate::scene::simplify`]);
    /// under ray-traced V the rays meet the same simplified triangles,
    /// through a BVH of their own: the app's drag frames, an approximation
    /// nobody reads back.
    pub simplified: bool,
    /// Under ray-traced V, trace one shadow ray a pixel towards a sphere
    /// light, whatever the settings' samples: the app's drag frames, which
    /// a change ends after a frame or two (the still frame after it traces
    /// them all, and its accumulation starts anew).
    pub one_light_sample: bool,
    /// PCF and Poisson read the depth ranges of a map that has held still
    /// for a frame (gpu::depth_ranges), built on the first frame that
    /// reuses it: a map drawn for one frame (a moving light) never pays for
    /// them. False: every tap is tested (a baseline to compare with).
    pub depth_ranges: bool,
}

impl ShadeOptions {
    /// The app's still frames: full size, the quantity only (see
    /// [`Self::still`]).
    pub const STILL: Self = Self {
        specialised: true,
        aux: false,
        depth_prepass: true,
        simplified: false,
        one_light_sample: false,
        depth_ranges: true,
    };

    /// The app's still frame of `settings`: [`Self::STILL`] with the aux
    /// target where the probe reads it (`probed`) or under ray-traced V,
    /// whose mean would start anew when the target is turned on (a click
    /// on the probe).
    pub fn still(settings: &Settings, probed: bool) -> Self {
        Self {
            aux: probed || settings.shadow.visibility == Visibility::RayTraced,
            ..Self::STILL
        }
    }

    /// The app's interaction frames (a drag): read back by nobody, so no aux
    /// target, simplified meshes where the scene has them and one ray a
    /// pixel towards a sphere light, and small, so no depth pre-pass (but
    /// see [`Specialisation::for_frame`]).
    pub const INTERACTION: Self = Self {
        specialised: true,
        aux: false,
        depth_prepass: false,
        simplified: true,
        one_light_sample: true,
        depth_ranges: true,
    };
}

impl Default for ShadeOptions {
    /// A still frame with both targets: the CLI, the report and the tests read the aux target back.
    fn default() -> Self {
        Self {
            aux: true,
            ..Self::STILL
        }
    }
}

/// What a scene holds that the camera pass would otherwise test for at
/// every pixel: lavapipe runs a branch no pixel takes under an empty mask,
/// so a scene without them gets a pass compiled without their code.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct SceneAttributes {
    /// Some object has vertex colours (`SPECIALISED_VERTEX_COLOURS`):
    /// without them the pass reads none, one varying less per pixel.
    pub vertex_colours: bool,
    /// Some material has a base-colour texture (`SPECIALISED_TEXTURES`):
    /// without one no texture is sampled (0.4 M instructions of 7.6 M a
    /// frame, shadows off, 250 × 170).
    pub textures: bool,
}

/// What one camera-pass pipeline is compiled for; None: any (read the uniform).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Specialisation {
    pub view: Option<DebugView>,
    pub filter: Option<Filter>,
    /// Shadows on (Settings::shadow.enabled): off, V = 1 is compiled in and
    /// none of the shadow map's code is (lavapipe would run it for every
    /// pixel, under a mask, on a uniform that says it is off).
    pub shadows: Option<bool>,
    pub visibility: Option<Visibility>,
    pub bias: Option<BiasMode>,
    /// The shadow map's layout (None also when no map is drawn).
    pub layout: Option<LayoutKind>,
    /// The light is a sphere (its irradiance's horizon case, and under
    /// ray-traced V its cone sampled) or a point (one ray), and, under
    /// ray-traced V only, the frame folds in the history of the frames
    /// before or starts it (`SPECIALISED_SPHERE_LIGHT`,
    /// `SPECIALISED_ACCUMULATING`). lavapipe runs a branch the uniforms
    /// skip under an empty mask: without these a point light's frame ran
    /// the sphere's code and every frame the history's loads.
    pub sphere_light: Option<bool>,
    pub accumulating: Option<bool>,
    /// Under ray-traced V, a sphere light's rays a walk: one (one a pixel:
    /// the app's drag frames, whose shading a walk for four made 45 %
    /// dearer on lavapipe), four or eight (`SPECIALISED_RAYS_PER_WALK`,
    /// [`super::raytrace::rays_per_walk`]).
    pub rays_per_walk: Option<u32>,
    /// What the scene's attributes leave out of the camera pass.
    pub attributes: Option<SceneAttributes>,
    /// Writes the aux target beside the quantity.
    pub aux: bool,
    /// Follows the depth pre-pass (depth test Equal, no writes).
    pub prepassed: bool,
}

impl Specialisation {
    /// The pipeline a frame with `settings` and a shadow map laid out as
    /// `layout` uses; `accumulating`: it folds in a ray-traced history;
    /// `simplified`: it draws the simplified copy of a large scene;
    /// `attributes`: the scene's.
    pub fn for_frame(
        settings: &Settings,
        layout: Option<LayoutKind>,
        options: ShadeOptions,
        accumulating: bool,
        simplified: bool,
        attributes: SceneAttributes,
    ) -> Self {
        let on = options.specialised;
        let ray_traced = settings.shadow.visibility == Visibility::RayTraced;
        let traced = on && ray_traced;
        Self {
            view: on.then_some(settings.view.mode),
            // Without shadows the filter never runs: one pipeline serves all,
            // compiled without any filter's code (the generic one, left in,
            // makes the pass three times slower on lavapipe).
            filter: on.then_some(if settings.shadow.enabled {
                settings.shadow.filter
            } else {
                Filter::None
            }),
            shadows: on.then_some(settings.shadow.enabled),
            visibility: on.then_some(settings.shadow.visibility),
            bias: on.then_some(settings.shadow.bias.mode),
            layout: layout.filter(|_| on),
            sphere_light: on.then_some(settings.light.is_sphere()),
            accumulating: traced.then_some(accumulating),
            rays_per_walk: traced.then(|| rays_per_walk(rays_per_pixel(settings, options.one_light_sample))),
            attributes: on.then_some(attributes),
            aux: options.aux,
            // A ray-traced fragment costs its rays. After the pre-pass each
            // pixel traces them once, instead of once per triangle drawn
            // over it: large scenes, drawn over many times, gain (the
            // engine's drag frames: 11–17 → 16–21 images/s), the default
            // scene loses (~30 → 19–32: the second pass costs more than the
            // few fragments drawn over save).
            prepassed: options.depth_prepass || (simplified && ray_traced && settings.shadow.enabled),
        }
    }

    /// The override constants' values (absent ones keep SPECIALISE_ANY).
    pub fn constants(&self) -> Vec<(&'static str, f64)> {
        let mut constants = Vec::new();
        if let Some(view) = self.view {
            constants.push(("SPECIALISED_VIEW", code(DebugView::ALL, &view) as f64));
        }
        if let Some(filter) = self.filter {
            constants.push(("SPECIALISED_FILTER", code(Filter::ALL, &filter) as f64));
        }
        if let Some(shadows) = self.shadows {
            constants.push(("SPECIALISED_SHADOWS", f64::from(u8::from(shadows))));
        }
        if let Some(visibility) = self.visibility {
            constants.push((
                "SPECIALISED_VISIBILITY",
                code(Visibility::ALL, &visibility) as f64,
            ));
        }
        if let Some(bias) = self.bias {
            constants.push(("SPECIALISED_BIAS", code(BiasMode::ALL, &bias) as f64));
        }
        if let Some(layout) = self.layout {
            let cube = layout == LayoutKind::Cube;
            constants.push(("SPECIALISED_CUBE", f64::from(u8::from(cube))));
        }
        if let Some(sphere) = self.sphere_light {
            constants.push(("SPECIALISED_SPHERE_LIGHT", f64::from(u8::from(sphere))));
        }
        if let Some(accumulating) = self.accumulating {
            constants.push(("SPECIALISED_ACCUMULATING", f64::from(u8::from(accumulating))));
        }
        if let Some(width) = self.rays_per_walk {
            constants.push(("SPECIALISED_RAYS_PER_WALK", f64::from(width)));
        }
        if let Some(attributes) = self.attributes {
            let flag = |on: bool| f64::from(u8::from(on));
            constants.push(("SPECIALISED_VERTEX_COLOURS", flag(attributes.vertex_colours)));
            constants.push(("SPECIALISED_TEXTURES", flag(attributes.textures)));
        }
        constants
    }

    /// A camera-pass pipeline for this specialisation.
    pub(super) fn pipeline(
        &self,
        device: &wgpu::Device,
        layout: &wgpu::PipelineLayout,
        module: &wgpu::ShaderModule,
        hdr_format: wgpu::TextureFormat,
    ) -> wgpu::RenderPipeline {
        let constants = self.constants();
        let compilation_options = wgpu::PipelineCompilationOptions {
            constants: &constants,
            ..Default::default()
        };
        let both = [Some(hdr_format.into()), Some(hdr_format.into())];
        let (entry_point, targets) = if self.aux {
            ("fs", &both[..])
        } else {
            ("fs_quantity", &both[..1])
        };
        device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(&format!("camera pass {self:?}")),
            layout: Some(layout),
            // Both stages specialised: the vertex stage reads a material's
            // other-colour field only for the delta-e view.
            vertex: wgpu::VertexState {
                module,
                entry_point: Some("vs"),
                compilation_options: compilation_options.clone(),
                buffers: &[Some(Vertex::layout())],
            },
            fragment: Some(wgpu::FragmentState {
                module,
                entry_point: Some(entry_point),
                compilation_options,
                targets,
            }),
            // No culling: back faces are shaded to 0 (n·o ≤ 0), as in the reference.
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(if self.prepassed {
                prepassed_depth_test()
            } else {
                camera_depth_test()
            }),
            multisample: Default::default(),
            multiview_mask: None,
            cache: None,
        })
    }
}

/// The camera pass after the depth pre-pass: only the fragments at the
/// nearest depth are shaded, each pixel once instead of once per surface
/// drawn over it (on a software adapter every hidden fragment shaded is
/// paid in full). Where coplanar surfaces tie exactly, the last one drawn
/// is shown (the first one without the pre-pass).
fn prepassed_depth_test() -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        depth_write_enabled: Some(false),
        depth_compare: Some(wgpu::CompareFunction::Equal),
        ..camera_depth_test()
    }
}

/// The camera's depth test: reversed Z, nearest wins (the depth pre-pass
/// and the flat pass).
pub(super) fn camera_depth_test() -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: DEPTH_FORMAT,
        depth_write_enabled: Some(true),
        depth_compare: Some(wgpu::CompareFunction::Greater),
        stencil: Default::default(),
        bias: Default::default(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A drag frame skips the depth pre-pass unless it draws a large
    /// scene's simplified copy and its fragments trace shadow rays: then
    /// every pixel traces them once, not once per triangle drawn over it.
    #[test]
    fn drag_frames_take_the_prepass_only_when_tracing_rays_on_large_scenes() {
        let prepassed = |visibility, enabled, simplified| {
            let mut settings = Settings::default();
            settings.shadow.visibility = visibility;
            settings.shadow.enabled = enabled;
            Specialisation::for_frame(
                &settings,
                None,
                ShadeOptions::INTERACTION,
                false,
                simplified,
                SceneAttributes::default(),
            )
            .prepassed
        };
        assert!(prepassed(Visibility::RayTraced, true, true));
        assert!(!prepassed(Visibility::RayTraced, true, false));
        assert!(!prepassed(Visibility::RayTraced, false, true));
        assert!(!prepassed(Visibility::ShadowMap, true, true));
        let full = Specialisation::for_frame(
            &Settings::default(),
            None,
            ShadeOptions::default(),
            false,
            false,
            SceneAttributes::default(),
        );
        assert!(full.prepassed);
    }
}
