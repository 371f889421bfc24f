//! One primary sample: the camera ray, its closest hit, and the reflected
//! radiance there, L = c · light colour · ∫ f_r L_e V cos⁺θ dω.
//!
//! Point light (R = 0): L = c · colour · (f_d + f_s)(l) · E · V with
//! E = I cos⁺θ / r², I = Φ / 4π, and V ∈ {0, 1} from one shadow ray.
//!
//! Sphere light (R > 0, `sphere.rs`): the cone the sphere subtends from p
//! (sin α = R / d) is sampled uniformly in solid angle over N strata; with Ω = 2π (1 − cos α) and
//! L_e = Φ / (4π² R²), L = c · colour · (Ω / N) Σ (f_d + f_s)(l_i) L_e V_i cos⁺θ_i.
//! It converges to the penumbra as N grows; unoccluded and above the horizon
//! its E-part equals `sphere_irradiance` (the point light's E). Where no
//! shadow ray can be blocked, the diffuse part is that closed form itself
//! and only a specular lobe is sampled (`closed_form_diffuse`).
//!
//! Shadow rays: from p moved off the surface by ε = [`SHADOW_OFFSET_REL`] ×
//! the largest |coordinate| of the hit triangle, along the geometric normal on
//! the viewer's side, to the light (its centre, or the sample's point on the
//! sphere), stopping [`STOP_SHORT_REL`] of the way short of it. The hit point
//! is interpolated from the corners, so it lies on the triangle's plane to a
//! few ulps of those coordinates (~10⁻¹⁶ relative); 10⁻⁹ is 10⁷ times that, so
//! the ray can never re-hit its own plane (no acne at any angle: the self-hit
//! distance stays negative whatever cos θ divides both by), while at 1 m
//! from the origin it is 1 nm: no occluder closer than that exists in a scene.

use super::bvh::BallRegion;
use super::grid::{Answer, DirectionGrid};
use super::image::luminance;
use super::light_packet::LightPacket;
use super::sampling::{Rng, Strata};
use super::spectral::SpectralLight;
use super::sphere::SphereSamples;
use super::surface::Surface;
use super::{Reference, ReferenceOptions, own_unreached};
use crate::colour::ColourModel;
use crate::colour::chart::illuminant_linear_srgb;
use crate::physics::brdf::blinn_phong;
use crate::physics::radiometry::{incidence, intensity, point_irradiance, sphere_irradiance};
use crate::physics::{BrdfParams, BrdfTerms, Normalization};
use crate::scene::Material;
use crate::scene::camera::PixelRays;
use crate::settings::Settings;
use glam::{DVec2, DVec3};

/// Shadow-ray origin offset, relative to the hit triangle's coordinates.
pub const SHADOW_OFFSET_REL: f64 = 1e-9;
/// Shadow rays end this fraction of their length before the light.
pub const STOP_SHORT_REL: f64 = 1e-9;

/// Everything a sample needs from the settings, in f64.
#[derive(Clone, Debug)]
pub(super) struct Setup {
    pub rays: PixelRays,
    pub width: u32,
    pub height: u32,
    pub light_position: DVec3,
    pub power_w: f64,
    /// I = Φ / 4π (W/sr), the point light's intensity.
    pub intensity_w_sr: f64,
    pub radius_m: f64,
    /// The light's RGB colour (under an illuminant in `rgb-approx`: the
    /// illuminant's linear sRGB at the light colour's luminance).
    pub light_color: DVec3,
    /// Under an illuminant in `spectral`: the light and reflectances the
    /// samples integrate over wavelengths (and `light_color` is unused).
    pub spectral: Option<SpectralLight>,
    pub k: f64,
    pub m: f64,
    pub norm: Normalization,
    pub use_scene_materials: bool,
    pub color_override: Option<DVec3>,
    pub shadows: bool,
    pub light_strata: Strata,
    /// See [`ReferenceOptions::sample_everywhere`].
    pub sample_everywhere: bool,
    pub seed: u64,
    /// Primary rays through a grid around the eye, and point-light shadow
    /// rays through one around the light (none: the BVH alone).
    pub eye_grid: Option<DirectionGrid>,
    pub light_grid: Option<DirectionGrid>,
}

impl Setup {
    /// `materials`: the reference's (for their reflectances).
    pub fn new(settings: &Settings, options: &ReferenceOptions, materials: &[Material]) -> Self {
        let (l, m) = (&settings.light, &settings.material);
        let colour = settings.colour;
        let (light_color, spectral) = match (colour.illuminant, colour.model) {
            (None, _) => (l.color.as_dvec3(), None),
            (Some(i), ColourModel::RgbApprox) => (
                illuminant_linear_srgb(&i.spectrum()) * luminance(l.color.as_dvec3().to_array()),
                None,
            ),
            (Some(i), ColourModel::Spectral) => (
                l.color.as_dvec3(),
                Some(SpectralLight::new(
                    i,
                    l.color.as_dvec3(),
                    materials,
                    m.color_override.map(|c| c.as_dvec3()),
                )),
            ),
        };
        Self {
            rays: settings
                .camera
                .pixel_rays(settings.image.width, settings.image.height),
            width: settings.image.width,
            height: settings.image.height,
            light_position: l.position.as_dvec3(),
            power_w: l.power_w as f64,
            intensity_w_sr: intensity(l.power_w as f64),
            radius_m: l.radius_m as f64,
            light_color,
            spectral,
            k: m.k as f64,
            m: m.m as f64,
            norm: m.norm,
            use_scene_materials: m.use_scene_materials,
            color_override: m.color_override.map(|c| c.as_dvec3()),
            shadows: settings.shadow.enabled,
            light_strata: Strata::new(options.light_samples),
            sample_everywhere: options.sample_everywhere,
            seed: options.seed,
            eye_grid: None,
            light_grid: None,
        }
    }

    pub fn is_sphere_light(&self) -> bool {
        self.radius_m > 0.0
    }
}

/// Everything known about one primary sample: what the pixel probe shows.
#[derive(Clone, Debug, PartialEq)]
pub struct ShadingSample {
    /// Index into `Scene::objects`.
    pub object: usize,
    /// Triangle within that object's mesh.
    pub triangle: usize,
    /// Index into `Scene::materials` (None: the object's index was invalid
    /// and the default material was used).
    pub material: Option<usize>,
    /// Distance from the eye (m).
    pub distance_m: f64,
    pub position: DVec3,
    /// The interpolated vertex normal, normalized, turned towards the viewer
    /// on double-sided materials.
    pub normal: DVec3,
    /// The triangle's own normal, on the viewer's side.
    pub geometric_normal: DVec3,
    pub uv: DVec2,
    /// The BRDF colour c (linear RGB): base colour × texture, or the override.
    pub color: DVec3,
    pub k: f64,
    pub m: f64,
    /// Unit direction to the light's centre, its distance (m) and n·l.
    pub to_light: DVec3,
    pub light_distance_m: f64,
    pub cos_theta: f64,
    /// Unoccluded irradiance E (W/m²) from `physics::radiometry`.
    pub irradiance: f64,
    /// f_r / c towards the light's centre (1/sr).
    pub brdf: BrdfTerms<f64>,
    /// Visibility V ∈ [0, 1] (see `ReferenceImage::visibility`).
    pub visibility: f64,
    /// Reflected radiance L (W/m²/sr).
    pub radiance: DVec3,
    /// L / ((f_r / c) E V): c · light colour in RGB; under a spectral light
    /// the reflected spectrum's colour, integrated over wavelengths.
    pub tint: DVec3,
    /// Standard error of L's luminance (W/m²/sr): 0 for a point light; None
    /// with a single light sample.
    pub std_error: Option<f64>,
    pub shadow_rays: u32,
}

/// Buffers reused from sample to sample by one thread.
#[derive(Debug, Default)]
pub(super) struct Scratch {
    /// A sphere light's samples at one shading point.
    pub(super) sphere_samples: SphereSamples,
    /// Occluders near the shadow rays of one shading point.
    pub(super) candidates: Vec<u32>,
    /// Those of a region about the block of pixels being shaded (see
    /// [`REGION_BLOCK`]), gathered once.
    pub(super) ball_region: BallRegion,
    /// That block, when a render or the probe says which it is.
    pub block: Option<(u32, u32)>,
    /// A pixel's shadow rays towards a point light.
    pub light_packet: LightPacket,
}

/// Pixels along each side of the blocks whose shading points share one
/// gathering of a sphere light's occluders, made for the centre of the
/// block's first pixel whichever point asks first: the same in every render
/// and in the probe. Callgrind, 1 thread, against 8 (4): the default scene
/// under R = 0.3 m, 64 light samples +2.5 % (+2.5 %), the 110 k-triangle
/// engine −3.1 % (−6.3 %), the sphere race's scene +3.4 % (−3.8 %).
pub(super) const REGION_BLOCK: u32 = 16;

/// The block of pixel (i, j) for the sphere light's shared gatherings: the
/// render's and the probe's alike.
pub(super) fn region_block(i: u32, j: u32) -> (u32, u32) {
    (i / REGION_BLOCK, j / REGION_BLOCK)
}

/// The light's contribution at a shading point: L / (c · colour) and V.
pub(super) struct LightEstimate {
    /// ∫ (f_d + f_s) L_e V cos⁺θ dω, or its estimate (W/m²/sr per unit c).
    pub scaled_radiance: f64,
    pub visibility: f64,
    /// Standard error of `scaled_radiance`.
    pub std_error: Option<f64>,
    pub shadow_rays: u32,
}

impl Reference {
    /// Everything about the primary sample through (x, y): the pixel probe.
    pub(super) fn probe(&self, setup: &Setup, x: f64, y: f64, rng: &mut Rng) -> Option<ShadingSample> {
        let (s, (distance_m, uv, color)) = self.probed_surface(setup, setup.rays.towards(x, y))?;
        // The pixel's block, for the region its render gathered from.
        let block = Some(region_block(x as u32, y as u32));
        let estimate = self.light(
            setup,
            &s,
            rng,
            false,
            &mut Scratch {
                block,
                ..Scratch::default()
            },
        );
        let tri = &self.triangles[s.triangle];
        let inc = incidence(s.p, s.n, setup.light_position);
        Some(ShadingSample {
            object: tri.object(),
            triangle: tri.index(),
            material: self.objects[tri.object()].material_index,
            distance_m,
            position: s.p,
            normal: s.n,
            geometric_normal: s.geometric_normal,
            uv,
            color,
            k: s.brdf.k,
            m: s.brdf.m,
            to_light: inc.l,
            light_distance_m: inc.r,
            cos_theta: inc.cos_theta,
            irradiance: sphere_irradiance(setup.power_w, setup.radius_m, inc.cos_theta, inc.r),
            brdf: blinn_phong(s.n, inc.l, s.o, &s.brdf),
            visibility: estimate.visibility,
            radiance: s.tint * estimate.scaled_radiance,
            tint: s.tint,
            std_error: estimate.std_error.map(|se| luminance(s.tint.to_array()) * se),
            shadow_rays: estimate.shadow_rays,
        })
    }

    /// Whether the segment from the shadow origin to the point light is
    /// blocked, through the light's grid when there is one.
    fn blocked_from_light(&self, setup: &Setup, s: &Surface, packet: &mut LightPacket) -> bool {
        self.blocked_from_point(
            setup,
            (s.triangle, s.p, s.geometric_normal),
            (s.shadow_origin, s.shadow_offset_m),
            packet,
        )
    }

    /// Whether the segment from `origin` to the point light is blocked,
    /// `origin` lifted by `offset_m` off the point p of the triangle whose
    /// face normal on the eye's side is g.
    pub(super) fn blocked_from_point(
        &self,
        setup: &Setup,
        (triangle, p, g): (usize, DVec3, DVec3),
        (origin, offset_m): (DVec3, f64),
        packet: &mut LightPacket,
    ) -> bool {
        let t_max = 1.0 - STOP_SHORT_REL;
        match setup.light_grid.as_ref().map(|grid| {
            let own = own_unreached(triangle, offset_m, g, setup.light_position - p);
            grid.blocked_towards_centre(&self.grid_triangles, origin, t_max, own)
        }) {
            Some(Answer::Known(blocked)) => blocked,
            _ => self.blocked_in_packet(setup, origin, packet),
        }
    }

    /// Whether the segment from `origin` (one of `packet`'s, else on its
    /// own) to the point light is blocked, through the BVH.
    #[inline(always)]
    pub(super) fn blocked_in_packet(&self, setup: &Setup, origin: DVec3, packet: &mut LightPacket) -> bool {
        packet
            .blocked(&self.bvh, setup.light_position, origin)
            .unwrap_or_else(|| self.blocked(origin, setup.light_position))
    }

    /// [`Self::blocked_in_packet`] for a ray the packet numbered `ray`
    /// (None: not one of its).
    #[inline(always)]
    pub(super) fn ray_blocked_in_packet(
        &self,
        setup: &Setup,
        (origin, ray): (DVec3, Option<usize>),
        packet: &mut LightPacket,
    ) -> bool {
        ray.and_then(|i| packet.blocked_ray(&self.bvh, setup.light_position, i))
            .unwrap_or_else(|| self.blocked(origin, setup.light_position))
    }

    /// Whether the segment from `origin` to `target` is blocked,
    /// stopping short of the target.
    pub(super) fn blocked(&self, origin: DVec3, target: DVec3) -> bool {
        self.bvh
            .occluded(origin, target - origin, 0.0, 1.0 - STOP_SHORT_REL)
    }

    /// [`point_light_at`] for the surface, its shadow ray known unblocked
    /// when `clear`.
    #[inline(always)]
    fn point_light(
        &self,
        setup: &Setup,
        s: &Surface,
        clear: bool,
        packet: &mut LightPacket,
    ) -> LightEstimate {
        point_light_at(setup, (s.p, s.n, s.o), &s.brdf, s.shadowed, || {
            !clear && self.blocked_from_light(setup, s, packet)
        })
    }

    /// The light's contribution at the surface: the point light's in
    /// closed form (inlined in the callers' loops), its shadow ray known
    /// unblocked when `shadows_clear` (see `render::cover`); the sphere
    /// light's estimated with the light-sample stream `rng`.
    #[inline(always)]
    pub(super) fn light(
        &self,
        setup: &Setup,
        s: &Surface,
        rng: &mut Rng,
        shadows_clear: bool,
        scratch: &mut Scratch,
    ) -> LightEstimate {
        if setup.is_sphere_light() {
            self.sphere(setup, s, rng, scratch)
        } else {
            self.point_light(setup, s, shadows_clear, &mut scratch.light_packet)
        }
    }
}

/// L / (c · colour) = (f_d + f_s)(l) · E · V at point p of shading normal n
/// seen along o (unit, towards the eye), with V from one shadow ray where
/// the point is `shadowed` and above the light's horizon (`blocked` casts
/// it).
#[inline(always)]
pub(super) fn point_light_at(
    setup: &Setup,
    point: (DVec3, DVec3, DVec3),
    brdf: &BrdfParams<f64>,
    shadowed: bool,
    blocked: impl FnOnce() -> bool,
) -> LightEstimate {
    let lit = PointLit::new(setup, point, brdf, shadowed);
    lit.estimate(lit.casts() && blocked())
}

/// [`point_light_at`] before its shadow ray: what the point gets where
/// the ray is not blocked, and whether it casts one.
#[derive(Clone, Copy, Debug)]
pub(super) struct PointLit {
    /// L / (c · colour) where the light reaches the point.
    scaled_radiance: f64,
    /// V before the shadow ray: 0 under the horizon of a shadowed point.
    visibility: f64,
    shadow_rays: u32,
}

impl PointLit {
    #[inline(always)]
    pub(super) fn new(
        setup: &Setup,
        (p, n, o): (DVec3, DVec3, DVec3),
        brdf: &BrdfParams<f64>,
        shadowed: bool,
    ) -> Self {
        let inc = incidence(p, n, setup.light_position);
        let (visibility, shadow_rays) = if !shadowed {
            (1.0, 0)
        } else if inc.cos_theta <= 0.0 {
            // Attached shadow: the light is below the surface's horizon.
            (0.0, 0)
        } else {
            (1.0, 1)
        };
        let scaled_radiance = if inc.cos_theta > 0.0 {
            let e = point_irradiance(setup.intensity_w_sr, inc.cos_theta, inc.r);
            blinn_phong(n, inc.l, o, brdf).total() * e
        } else {
            0.0
        };
        Self {
            scaled_radiance,
            visibility,
            shadow_rays,
        }
    }

    /// Whether the point casts a shadow ray.
    #[inline(always)]
    pub(super) fn casts(&self) -> bool {
        self.shadow_rays > 0
    }

    /// The light at the point, its shadow ray (if it casts one) `blocked`
    /// or not.
    #[inline(always)]
    pub(super) fn estimate(self, blocked: bool) -> LightEstimate {
        let visibility = if blocked { 0.0 } else { self.visibility };
        LightEstimate {
            scaled_radiance: if visibility > 0.0 {
                self.scaled_radiance
            } else {
                0.0
            },
            visibility,
            std_error: Some(0.0),
            shadow_rays: self.shadow_rays,
        }
    }
}
