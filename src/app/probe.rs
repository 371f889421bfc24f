//! The pixel probe: click a pixel and see every term of L = f_r · E · V there,
//! with units and formulas. The terms come from the CPU reference tracing
//! the pixel's centre in f64 (the same code as the reference image, so V
//! and L there are exact); the shadow map's V from the renderer's aux target
//! (read back without blocking).

use super::widgets::{length, number, position, quantity, rgb, value_row, vector};
use crate::colour::shading::pixel_delta_e;
use crate::colour::tristimulus::linear_srgb_to_xyz;
use crate::gpu::ComparisonImage;
use crate::physics::{Normalization, brdf, radiometry};
use crate::presets::Half;
use crate::reference::{Reference, ReferenceOptions, ShadingSample};
use crate::scene::Scene;
use crate::settings::{DebugView, Settings, Visibility};
use crate::tr;
use glam::DVec3;

/// A probed pixel of one half of the image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProbePixel {
    pub half: Half,
    /// Pixel (i, j), row 0 at the top.
    pub pixel: (u32, u32),
    /// The image size it belongs to (pixels).
    pub size: (u32, u32),
}

impl ProbePixel {
    /// The pixel at the same place of an image of `size` pixels.
    pub fn resized(self, size: (u32, u32)) -> Self {
        let scale = |i: u32, from: u32, to: u32| {
            let x = (i as f64 + 0.5) * to as f64 / from.max(1) as f64;
            (x.floor() as u32).min(to.saturating_sub(1))
        };
        Self {
            pixel: (
                scale(self.pixel.0, self.size.0, size.0),
                scale(self.pixel.1, self.size.1, size.1),
            ),
            size,
            ..self
        }
    }
}

/// Every term of the rendering equation at the probed point (c = the
/// material's colour; all in f64 through `physics`).
#[derive(Clone, Debug, PartialEq)]
pub struct ProbeTerms {
    pub object: String,
    pub material: String,
    /// Where the pixel's ray meets the surface (m).
    pub position: DVec3,
    /// Shading normal, turned to the viewer on double-sided materials.
    pub n: DVec3,
    /// Unit direction to the light, l = (q − p) / r.
    pub l: DVec3,
    /// Unit direction to the eye.
    pub o: DVec3,
    /// Half vector, None when l + o = 0.
    pub h: Option<DVec3>,
    /// Distance to the light's centre (m).
    pub r_m: f64,
    /// n·l, signed.
    pub cos_theta: f64,
    /// I = Φ / 4π (W/sr).
    pub intensity_w_sr: f64,
    /// E (W/m²), the sphere light's closed form (the point light's when R = 0).
    pub irradiance_w_m2: f64,
    pub k: f64,
    pub m: f64,
    pub norm: Normalization,
    /// f_r / c split into k/π and (1 − k) N(m) cos^m θ_h (1/sr).
    pub brdf: brdf::BrdfTerms<f64>,
    /// The BRDF colour c (linear RGB): base colour × texture, or the override.
    pub color: DVec3,
    /// c · light colour (linear RGB); under a spectral light, the colour of
    /// the reflected spectrum integrated over wavelengths (see `colour::shading`).
    pub tint: DVec3,
    /// V ray traced from p (exact for a point light; the visible fraction of
    /// the sphere light's cosine-weighted solid angle otherwise).
    pub visibility: f64,
    /// L ray traced at the pixel's centre (W/m²/sr).
    pub radiance: DVec3,
    /// Under an illuminant: ΔE2000 between the spectral and the RGB result here.
    pub delta_e: Option<f64>,
}

impl ProbeTerms {
    /// L / V = c · colour · E · (f_d + f_s) (W/m²/sr): the radiance if fully lit.
    pub fn unshadowed_radiance(&self) -> DVec3 {
        self.tint * (self.irradiance_w_m2 * self.brdf.total())
    }
}

/// The primary sample through the centre of pixel (i, j) of an image of
/// `size` pixels rendered with `settings`, or None where it misses the
/// scene: what the probe shows and where a double-click sets the pivot.
pub fn trace(
    tracer: &Reference,
    settings: &Settings,
    pixel: (u32, u32),
    size: (u32, u32),
) -> Option<ShadingSample> {
    let mut settings = settings.clone();
    settings.image.width = size.0;
    settings.image.height = size.1;
    let (x, y) = (pixel.0 as f64 + 0.5, pixel.1 as f64 + 0.5);
    tracer.trace_pixel(&settings, &ReferenceOptions::DEFAULT, x, y)
}

/// The terms at pixel (i, j) of an image of `size` pixels rendered with
/// `settings`, or None where the pixel's ray misses the scene. `tracer` is
/// the reference prepared for `scene`.
pub fn evaluate(
    tracer: &Reference,
    scene: &Scene,
    settings: &Settings,
    pixel: (u32, u32),
    size: (u32, u32),
) -> Option<ProbeTerms> {
    let sample = trace(tracer, settings, pixel, size)?;
    let object = scene.objects.get(sample.object)?;
    let material = scene.material_of(object);
    let eye = settings.camera.eye.as_dvec3();
    let o = (eye - sample.position).normalize_or(sample.normal);
    let sum = sample.to_light + o;
    Some(ProbeTerms {
        object: object.name.clone(),
        material: material.name.clone(),
        position: sample.position,
        n: sample.normal,
        l: sample.to_light,
        o,
        h: (sum.length_squared() > 0.0).then(|| sum.normalize()),
        r_m: sample.light_distance_m,
        cos_theta: sample.cos_theta,
        intensity_w_sr: radiometry::intensity(settings.light.power_w as f64),
        irradiance_w_m2: sample.irradiance,
        k: sample.k,
        m: sample.m,
        norm: settings.material.norm,
        brdf: sample.brdf,
        color: sample.color,
        tint: sample.tint,
        visibility: sample.visibility,
        radiance: sample.radiance,
        delta_e: delta_e_at(tracer, settings, pixel, size, &sample),
    })
}

/// Under an illuminant: ΔE2000 between this pixel's spectral result and
/// its RGB approximation (whichever the settings show, the other traced
/// too), both exposed as displayed, in CIE Lab with the illuminant's white
/// at Y = 1 as reference (`colour::shading::pixel_delta_e`).
fn delta_e_at(
    tracer: &Reference,
    settings: &Settings,
    pixel: (u32, u32),
    size: (u32, u32),
    sample: &ShadingSample,
) -> Option<f64> {
    let illuminant = settings.colour.illuminant?;
    let mut other = settings.clone();
    other.colour.model = settings.colour.model.other();
    let other = trace(tracer, &other, pixel, size)?;
    let exposure = 2f64.powf(settings.view.exposure_ev as f64);
    Some(pixel_delta_e(
        illuminant,
        sample.radiance * exposure,
        other.radiance * exposure,
    ))
}

/// What the GPU says at the probed pixel (from its aux and quantity targets).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GpuSample {
    /// V from the half's visibility method.
    pub visibility: f32,
    /// That method: shadow map or GPU ray traced.
    pub method: Visibility,
    /// Shadow-map texels per pixel.
    pub texel_density: f32,
    /// The GPU's L (W/m²/sr), when the view's quantity is the radiance.
    pub radiance: Option<[f32; 3]>,
    /// The `delta-e` view's ΔE2000 here, where it is defined.
    pub delta_e: Option<f32>,
}

/// The reference's values at the probed pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReferenceSample {
    pub visibility: f32,
    pub radiance: [f32; 3],
    /// The reference was computed for other settings.
    pub stale: bool,
}

impl ReferenceSample {
    pub fn at(image: &ComparisonImage, pixel: (u32, u32), stale: bool) -> Option<Self> {
        if pixel.0 >= image.width || pixel.1 >= image.height {
            return None;
        }
        let t = image.texels.get((pixel.1 * image.width + pixel.0) as usize)?;
        Some(Self {
            visibility: t[3],
            radiance: [t[0], t[1], t[2]],
            stale,
        })
    }
}

/// Views whose quantity target holds the radiance L.
pub fn quantity_is_radiance(view: DebugView) -> bool {
    matches!(
        view,
        DebugView::Shaded | DebugView::Frustum | DebugView::RefVisibility | DebugView::Error
    )
}

/// The probe's state: the pixel, its terms and the values read back.
#[derive(Default)]
pub struct Probe {
    pub pixel: Option<ProbePixel>,
    pub terms: Option<ProbeTerms>,
    pub gpu: Option<GpuSample>,
    pub reference: Option<ReferenceSample>,
}

impl Probe {
    pub fn ui(&self, ui: &mut egui::Ui) {
        let Some(pixel) = self.pixel else {
            ui.label(tr!("probe-hint"));
            return;
        };
        let half = match pixel.half {
            Half::A => "A",
            Half::B => "B",
        };
        ui.label(tr!(
            "probe-pixel",
            x = pixel.pixel.0,
            y = pixel.pixel.1,
            width = pixel.size.0,
            height = pixel.size.1,
            half = half
        ));
        let Some(t) = &self.terms else {
            ui.label(tr!("probe-background"));
            return;
        };
        ui.label(tr!(
            "probe-object",
            object = t.object.as_str(),
            material = t.material.as_str()
        ));
        egui::Grid::new("probe grid")
            .num_columns(2)
            .striped(true)
            .show(ui, |ui| {
                for (symbol, value, formula) in self.rows(t) {
                    value_row(ui, &symbol, &value, &formula);
                }
            });
    }

    /// The probe's read-out: (symbol, value with unit, formula) per row.
    pub fn rows(&self, t: &ProbeTerms) -> Vec<(String, String, String)> {
        let theta_deg = t.cos_theta.clamp(-1.0, 1.0).acos().to_degrees();
        let times_c = |x: f64| quantity(x, "1/sr  × c");
        let mut rows = vec![
            ("p".into(), position(t.position), tr!("probe-p-tip")),
            ("n".into(), vector(t.n, ""), tr!("probe-n-tip")),
            ("l".into(), vector(t.l, ""), tr!("probe-l-tip")),
            ("o".into(), vector(t.o, ""), tr!("probe-o-tip")),
            ("r".into(), length(t.r_m), tr!("probe-r-tip")),
            (
                "cos θ".into(),
                format!("{}  (θ = {}°)", number(t.cos_theta), number(theta_deg)),
                tr!("probe-cos-tip"),
            ),
            (
                "I".into(),
                quantity(t.intensity_w_sr, "W/sr"),
                "I = Φ / 4π (W/sr)".into(),
            ),
            (
                "E".into(),
                quantity(t.irradiance_w_m2, "W/m²"),
                tr!("probe-e-tip"),
            ),
        ];
        if let Some(h) = t.h {
            rows.push((
                "cos θ_h".into(),
                number(t.n.dot(h).max(0.0)),
                "cos θ_h = max(0, n·h), h = normalize(l + o)".into(),
            ));
        }
        rows.extend([
            (
                "k, m, N(m)".into(),
                format!(
                    "{}, {}, {} ({})",
                    number(t.k),
                    number(t.m),
                    number(t.norm.factor(t.m)),
                    t.norm
                ),
                t.norm.formula().into(),
            ),
            (
                "f_d".into(),
                times_c(t.brdf.diffuse),
                "f_d = c · k / π (1/sr)".into(),
            ),
            (
                "f_s".into(),
                times_c(t.brdf.specular),
                "f_s = c · (1 − k) · N(m) · cos^m θ_h (1/sr)".into(),
            ),
            (
                "f_r".into(),
                times_c(t.brdf.total()),
                super::material::BRDF.into(),
            ),
            ("c".into(), rgb(t.color, ""), tr!("probe-c-tip")),
        ]);
        match &self.gpu {
            Some(g) => {
                let l = t.unshadowed_radiance() * g.visibility as f64;
                rows.push(match g.method {
                    Visibility::ShadowMap => (
                        tr!("probe-v-map"),
                        number(g.visibility as f64),
                        tr!("probe-v-map-tip"),
                    ),
                    Visibility::RayTraced => (
                        tr!("probe-v-gpu-traced"),
                        number(g.visibility as f64),
                        tr!("probe-v-gpu-traced-tip"),
                    ),
                });
                rows.extend([
                    (
                        tr!("probe-texels"),
                        number(g.texel_density as f64),
                        tr!("probe-texels-tip"),
                    ),
                    ("L".into(), rgb(l, "W/m²/sr"), tr!("probe-l-value-tip")),
                ]);
                if let Some(gpu_l) = g.radiance {
                    let v = DVec3::from_array(gpu_l.map(f64::from));
                    rows.push((tr!("probe-l-gpu"), rgb(v, "W/m²/sr"), tr!("probe-l-gpu-tip")));
                }
                if let Some(delta_e) = g.delta_e {
                    rows.push((
                        tr!("probe-delta-e-gpu"),
                        number(delta_e as f64),
                        tr!("probe-delta-e-gpu-tip"),
                    ));
                }
            }
            None => rows.extend([
                (tr!("probe-v-map"), "…".into(), tr!("probe-reading-tip")),
                (
                    "L / V".into(),
                    rgb(t.unshadowed_radiance(), "W/m²/sr"),
                    tr!("probe-unshadowed-tip"),
                ),
            ]),
        }
        rows.extend([
            (
                tr!("probe-v-traced"),
                number(t.visibility),
                tr!("probe-v-traced-tip"),
            ),
            (
                tr!("probe-l-traced"),
                rgb(t.radiance, "W/m²/sr"),
                tr!("probe-l-traced-tip"),
            ),
            (
                "X, Y, Z".to_string(),
                vector(linear_srgb_to_xyz(t.radiance), ""),
                tr!("probe-xyz-tip"),
            ),
        ]);
        if let Some(delta_e) = t.delta_e {
            rows.push(("ΔE2000".to_string(), number(delta_e), tr!("probe-delta-e-tip")));
        }
        if let Some(r) = &self.reference {
            let stale = if r.stale {
                tr!("probe-stale")
            } else {
                String::new()
            };
            let v = DVec3::from_array(r.radiance.map(f64::from));
            rows.push((
                tr!("probe-l-image"),
                format!("{}{stale}", rgb(v, "W/m²/sr")),
                tr!("probe-l-image-tip"),
            ));
        }
        rows
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ground_pixel_terms_match_the_formulas() {
        let scene = crate::scene::default_scene();
        let settings = Settings::default();
        let size = (320, 200);
        let t = evaluate(&Reference::new(&scene), &scene, &settings, (40, 190), size).unwrap();
        assert_eq!(t.object, "ground");
        let q = settings.light.position.as_dvec3();
        let r = (q - t.position).length();
        assert!((t.r_m - r).abs() < 1e-12);
        let cos = (q - t.position).normalize().y;
        let e = settings.light.power_w as f64 / (4.0 * std::f64::consts::PI) * cos / (r * r);
        assert!((t.irradiance_w_m2 / e - 1.0).abs() < 1e-12);
        assert!((t.brdf.diffuse - t.k / std::f64::consts::PI).abs() < 1e-15);
    }

    #[test]
    fn a_resized_probe_stays_on_the_same_point() {
        let p = ProbePixel {
            half: Half::A,
            pixel: (100, 50),
            size: (400, 200),
        };
        assert_eq!(p.resized((400, 200)), p);
        assert_eq!(p.resized((200, 100)).pixel, (50, 25));
        assert_eq!(p.resized((800, 400)).pixel, (201, 101));
        assert_eq!(p.resized((1, 1)).pixel, (0, 0));
    }

    #[test]
    fn sky_pixels_have_no_terms() {
        let scene = crate::scene::default_scene();
        let tracer = Reference::new(&scene);
        assert!(evaluate(&tracer, &scene, &Settings::default(), (5, 2), (320, 200)).is_none());
    }
}
