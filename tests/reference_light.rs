//! The reference against the radiometry of the lecture, where the answer is
//! known in closed form: a Lambert plane under a point light, the sphere
//! light's irradiance, shadows off, the umbra of a square occluder, and the
//! penumbra converging as the light's samples grow.

use glam::{DVec3, Vec3};
use lumlab::physics::brdf::blinn_phong;
use lumlab::physics::radiometry::{intensity, sphere_irradiance};
use lumlab::physics::{BrdfParams, Normalization};
use lumlab::reference::{Reference, ReferenceImage, ReferenceOptions, RenderControl, luminance};
use lumlab::scene::{Camera, Material, Object, Scene, shapes};
use lumlab::settings::Settings;
use std::f64::consts::PI;

const GROUND_COLOR: Vec3 = Vec3::new(0.5, 0.6, 0.7);
const LIGHT_COLOR: Vec3 = Vec3::new(1.0, 0.9, 0.8);

/// A 100 m ground (object 0) and optionally a square occluder of half side
/// `a` at height `h` (object 1).
fn plane_scene(occluder: Option<(f32, f32)>) -> Scene {
    let mut objects = vec![Object::new("ground", shapes::ground(Vec3::ZERO, 100.0), 0)];
    if let Some((h, a)) = occluder {
        objects.push(Object::new(
            "occluder",
            shapes::ground(Vec3::new(0.0, h, 0.0), 2.0 * a),
            0,
        ));
    }
    Scene {
        objects,
        materials: vec![Material {
            base_color: GROUND_COLOR.extend(1.0),
            ..Material::default()
        }],
        ..Scene::default()
    }
}

/// Lambert (k = 1) everywhere, the given camera, light and image size.
fn lambert_settings(eye: Vec3, target: Vec3, fovy_deg: f32, size: (u32, u32), light: Vec3) -> Settings {
    let mut s = Settings::default();
    s.camera.eye = eye;
    s.camera.target = target;
    s.camera.fovy_deg = fovy_deg;
    (s.image.width, s.image.height) = size;
    s.light.position = light;
    s.light.power_w = 500.0;
    s.light.color = LIGHT_COLOR;
    s.material.k = 1.0;
    s.material.use_scene_materials = false;
    s
}

fn render(scene: &Scene, settings: &Settings, light_samples: u32, seed: u64) -> ReferenceImage {
    render_with(scene, settings, light_samples, seed, false)
}

/// `render`, with the sphere light sampled even where nothing can block it.
fn render_with(
    scene: &Scene,
    settings: &Settings,
    light_samples: u32,
    seed: u64,
    sample_everywhere: bool,
) -> ReferenceImage {
    let options = ReferenceOptions {
        spp: 1,
        light_samples,
        seed,
        sample_everywhere,
    };
    Reference::new(scene)
        .render(settings, &options, &RenderControl::default())
        .unwrap()
}

fn camera(settings: &Settings) -> Camera {
    Camera {
        eye: settings.camera.eye,
        target: settings.camera.target,
        fovy_deg: settings.camera.fovy_deg,
    }
}

/// Where the ray through the centre of pixel (i, j) meets the plane y = 0,
/// in closed form.
fn ground_point(settings: &Settings, i: u32, j: u32) -> Option<DVec3> {
    let (w, h) = (settings.image.width, settings.image.height);
    let d = camera(settings).ray_direction(i as f64 + 0.5, j as f64 + 0.5, w, h);
    let eye = settings.camera.eye.as_dvec3();
    let t = -eye.y / d.y;
    (t > 0.0).then(|| eye + d * t)
}

/// c · light colour / π: the Lambert BRDF times the colours, per unit E.
fn lambert_tint() -> DVec3 {
    GROUND_COLOR.as_dvec3() * LIGHT_COLOR.as_dvec3() / PI
}

fn relative_error(got: [f64; 3], expected: DVec3) -> f64 {
    (DVec3::from_array(got) - expected).abs().max_element() / expected.max_element()
}

#[test]
fn lambert_plane_under_a_point_light_matches_the_inverse_square_law_to_1e9() {
    let q = Vec3::new(0.7, 3.0, -0.4);
    let settings = lambert_settings(Vec3::new(0.0, 4.0, 3.0), Vec3::ZERO, 40.0, (48, 32), q);
    let image = render(&plane_scene(None), &settings, 1, 0);
    let q = q.as_dvec3();
    for j in 0..32 {
        for i in 0..48 {
            let p = ground_point(&settings, i, j).unwrap();
            // E = (Φ / 4π) cos θ / r², with cos θ = (q − p)·n / r and n = +Y.
            let r = (q - p).length();
            let e = intensity(500.0) * ((q.y - p.y) / r) / (r * r);
            let expected = lambert_tint() * e;
            let at = image.index(i, j);
            let err = relative_error(image.radiance[at], expected);
            assert!(err < 1e-9, "pixel ({i}, {j}): relative error {err:e}");
            assert_eq!((image.coverage[at], image.visibility[at]), (1.0, 1.0));
        }
    }
    assert_eq!(image.noise_summary().rms_std_error, 0.0, "a point light is exact");
}

#[test]
fn blinn_phong_plane_under_a_point_light_matches_the_brdf_to_1e9() {
    let q = Vec3::new(0.2, 2.0, -1.5);
    let mut settings = lambert_settings(Vec3::new(0.0, 2.0, 3.0), Vec3::ZERO, 50.0, (48, 32), q);
    (settings.material.k, settings.material.m) = (0.3, 20.0);
    settings.material.norm = Normalization::Exact;
    // The settings hold f32: k is 0.3 rounded to f32, and so must the check's be.
    let params = BrdfParams {
        k: settings.material.k as f64,
        m: 20.0,
        norm: Normalization::Exact,
    };
    let image = render(&plane_scene(None), &settings, 1, 0);
    let (q, eye) = (q.as_dvec3(), settings.camera.eye.as_dvec3());
    for j in 0..32 {
        for i in 0..48 {
            let p = ground_point(&settings, i, j).unwrap();
            let r = (q - p).length();
            let (l, o) = ((q - p) / r, (eye - p).normalize());
            let e = intensity(500.0) * l.y / (r * r);
            // L = c · colour · f_r(l, o) · E, f_r / c from the BRDF itself.
            let f = blinn_phong(DVec3::Y, l, o, &params).total();
            let expected = lambert_tint() * PI * f * e;
            let err = relative_error(image.radiance[image.index(i, j)], expected);
            assert!(err < 1e-9, "pixel ({i}, {j}): relative error {err:e}");
        }
    }
}

/// Every pixel of the Lambert plane under the settings' sphere light against
/// the closed form of `sphere_irradiance`: each error within 6 σ (σ is itself
/// estimated from N/2 pairs of strata: allow its tail), and on average errors
/// the size σ says or smaller. Returns the worst relative error.
fn assert_sphere_light_matches_the_closed_form(settings: &Settings, light_samples: u32) -> f64 {
    let image = render_with(&plane_scene(None), settings, light_samples, 1, true);
    let (q, radius) = (settings.light.position.as_dvec3(), settings.light.radius_m as f64);
    let (mut worst, mut sum_z2, mut checked): (f64, f64, usize) = (0.0, 0.0, 0);
    for j in 0..settings.image.height {
        for i in 0..settings.image.width {
            let p = ground_point(settings, i, j).unwrap();
            let r = (q - p).length();
            let e = sphere_irradiance(500.0, radius, (q.y - p.y) / r, r);
            let expected = luminance((lambert_tint() * e).to_array());
            let at = image.index(i, j);
            let error = (luminance(image.radiance[at]) - expected).abs();
            let se = image.noise[at] as f64;
            assert!(
                error <= 6.0 * se + 1e-12 * expected,
                "pixel ({i}, {j}): error {error:e}, σ {se:e}"
            );
            if se > 0.0 {
                sum_z2 += (error / se).powi(2);
                checked += 1;
            }
            worst = worst.max(error / expected);
        }
    }
    let rms_z = (sum_z2 / checked as f64).sqrt();
    assert!(
        checked == image.pixel_count() && (0.2..1.5).contains(&rms_z),
        "{checked} pixels with noise, RMS of error / σ: {rms_z}"
    );
    worst
}

#[test]
fn an_unoccluded_sphere_light_gives_the_point_lights_irradiance_within_its_noise() {
    // Fully above the horizon: sphere_irradiance is the point light's E.
    let q = Vec3::new(0.5, 2.0, 0.2);
    let mut settings = lambert_settings(Vec3::new(0.0, 4.0, 3.0), Vec3::ZERO, 40.0, (40, 30), q);
    settings.light.radius_m = 0.3;
    let worst = assert_sphere_light_matches_the_closed_form(&settings, 64);
    assert!(worst < 1e-2, "worst relative error {worst}");
}

/// Where nothing can block the light, the default estimator gives the
/// closed form itself: no noise, no shadow ray (points inside the light
/// still sample their hemisphere). Returns the points checked.
fn assert_sphere_light_is_the_closed_form(settings: &Settings) -> usize {
    let image = render(&plane_scene(None), settings, 16, 1);
    let (q, radius) = (settings.light.position.as_dvec3(), settings.light.radius_m as f64);
    let mut checked = 0;
    for j in 0..settings.image.height {
        for i in 0..settings.image.width {
            let p = ground_point(settings, i, j).unwrap();
            let r = (q - p).length();
            if r <= radius {
                continue;
            }
            let e = sphere_irradiance(500.0, radius, (q.y - p.y) / r, r);
            let at = image.index(i, j);
            let err = relative_error(image.radiance[at], lambert_tint() * e);
            assert!(err < 1e-9, "pixel ({i}, {j}): relative error {err:e}");
            assert_eq!((image.noise[at], image.visibility[at]), (0.0, 1.0));
            checked += 1;
        }
    }
    assert_eq!(image.stats.shadow_rays, 0);
    checked
}

#[test]
fn an_unoccluded_sphere_light_is_the_closed_form_without_noise() {
    let q = Vec3::new(0.5, 2.0, 0.2);
    let mut settings = lambert_settings(Vec3::new(0.0, 4.0, 3.0), Vec3::ZERO, 40.0, (40, 30), q);
    settings.light.radius_m = 0.3;
    assert_eq!(assert_sphere_light_is_the_closed_form(&settings), 40 * 30);
    // Cut by every point's horizon, shadows off.
    settings.light.position = Vec3::new(0.0, 0.1, 0.0);
    settings.shadow.enabled = false;
    let checked = assert_sphere_light_is_the_closed_form(&settings);
    assert!(checked > 40 * 30 * 9 / 10, "{checked} points outside the light");
}

#[test]
fn a_specular_lobe_under_an_unoccluded_sphere_light_keeps_the_same_mean_with_less_noise() {
    // Only the lobe is sampled where nothing blocks the light: the same
    // integral as sampling everything, within both noise estimates.
    let q = Vec3::new(0.2, 2.0, -1.5);
    let mut settings = lambert_settings(Vec3::new(0.0, 2.0, 3.0), Vec3::ZERO, 50.0, (24, 16), q);
    (settings.material.k, settings.material.m) = (0.8, 20.0);
    settings.light.radius_m = 0.4;
    let scene = plane_scene(None);
    let split = render_with(&scene, &settings, 256, 1, false);
    let sampled = render_with(&scene, &settings, 256, 2, true);
    let (mut z2, mut split_var, mut sampled_var) = (0.0, 0.0, 0.0);
    for at in 0..split.pixel_count() {
        let (a, b) = (luminance(split.radiance[at]), luminance(sampled.radiance[at]));
        let (sa, sb) = (split.noise[at] as f64, sampled.noise[at] as f64);
        assert!(sa > 0.0 && sb > 0.0, "pixel {at}: σ {sa:e}, {sb:e}");
        z2 += (a - b).powi(2) / (sa * sa + sb * sb);
        (split_var, sampled_var) = (split_var + sa * sa, sampled_var + sb * sb);
    }
    let rms_z = (z2 / split.pixel_count() as f64).sqrt();
    assert!(rms_z < 1.5, "RMS of difference / σ: {rms_z}");
    assert!(
        split_var < 0.8 * sampled_var,
        "variance {split_var:e} vs {sampled_var:e}"
    );
    assert_eq!(split.stats.shadow_rays, 0);
}

#[test]
fn a_sphere_light_cut_by_the_horizon_matches_the_closed_form() {
    // The light's centre 0.1 m above the plane with R = 0.3: part of it lies
    // below every point's horizon (shadows off, so the plane hides nothing).
    let q = Vec3::new(0.0, 0.1, 0.0);
    let mut settings = lambert_settings(Vec3::new(0.0, 3.0, 2.0), Vec3::ZERO, 50.0, (40, 30), q);
    settings.light.radius_m = 0.3;
    settings.shadow.enabled = false;
    assert_sphere_light_matches_the_closed_form(&settings, 64);
}

#[test]
fn shadows_off_means_full_visibility_everywhere() {
    let scene = plane_scene(Some((1.0, 0.5)));
    for radius in [0.0, 0.2] {
        let mut settings = lambert_settings(
            Vec3::new(3.0, 3.0, 3.0),
            Vec3::ZERO,
            50.0,
            (32, 24),
            Vec3::new(0.0, 3.0, 0.0),
        );
        settings.light.radius_m = radius;
        settings.shadow.enabled = false;
        let image = render(&scene, &settings, 4, 0);
        for (at, &v) in image.visibility.iter().enumerate() {
            if image.coverage[at] > 0.0 {
                assert_eq!(v, 1.0, "R = {radius}, pixel {at}");
            }
        }
        assert_eq!(image.stats.shadow_rays, 0);
    }
}

#[test]
fn no_shadow_acne_at_grazing_light_far_from_the_origin() {
    // A tilted square 20 km from the origin, lit 0.5° above its plane (and
    // by a sphere light dipping below it): nothing can shadow it but itself,
    // so V must be exactly 1 wherever the light is above the horizon.
    let frame = glam::Mat4::from_translation(Vec3::new(1.0e4, 5.0e3, -2.0e4))
        * glam::Mat4::from_rotation_x(0.3)
        * glam::Mat4::from_rotation_z(-0.2);
    let square = shapes::ground(Vec3::ZERO, 4.0).transformed(frame);
    let scene = Scene {
        objects: vec![Object::new("square", square, 0)],
        materials: vec![Material::default()],
        ..Scene::default()
    };
    let normal = frame.transform_vector3(Vec3::Y).normalize();
    let along = frame.transform_vector3(Vec3::X).normalize();
    let centre = frame.transform_point3(Vec3::ZERO);
    let grazing = 0.5_f32.to_radians();
    let light = centre + (along * grazing.cos() + normal * grazing.sin()) * 50.0;
    let eye = centre + normal * 3.5 + along * 1.0;
    for radius in [0.0, 0.6] {
        let mut settings = lambert_settings(eye, centre, 45.0, (40, 30), light);
        settings.light.radius_m = radius;
        let image = render(&scene, &settings, 16, 0);
        let covered = image.coverage.iter().filter(|&&c| c > 0.0).count();
        assert!(covered > 1000, "{covered} pixels see the square");
        for (at, &v) in image.visibility.iter().enumerate() {
            if image.coverage[at] > 0.0 {
                assert_eq!(v, 1.0, "R = {radius}: acne at pixel {at}");
            }
        }
    }
}

/// Light straight above a square occluder: light at height H, radius R,
/// square of half side a at height h. Whether every point of the sphere is
/// hidden from the ground point p, or every point visible, in closed form per
/// axis: the segment from p to a sphere point s crosses y = h at
/// x = p_x + (s_x − p_x) h / s_y, with s_x ∈ [−R, R] and s_y ∈ [H − R, H + R].
struct SquareShadow {
    light_height: f64,
    radius: f64,
    height: f64,
    half: f64,
}

impl SquareShadow {
    fn crossing_bounds(&self, px: f64) -> (f64, f64) {
        let (hh, r, h) = (self.light_height, self.radius, self.height);
        let low = px.abs() * (1.0 - h / (hh - r)) - r * h / (hh - r);
        let high = px.abs() * (1.0 - h / (hh + r)) + r * h / (hh - r);
        (low, high)
    }

    /// Every segment from p to the light crosses inside the square (margin 1 %).
    fn umbra(&self, p: DVec3) -> bool {
        let limit = 0.99 * self.half;
        self.crossing_bounds(p.x).1 < limit && self.crossing_bounds(p.z).1 < limit
    }

    /// Every segment crosses outside the square (margin 1 %).
    fn fully_lit(&self, p: DVec3) -> bool {
        let limit = 1.01 * self.half;
        self.crossing_bounds(p.x).0 > limit || self.crossing_bounds(p.z).0 > limit
    }
}

#[test]
fn a_square_occluder_gives_exactly_zero_in_its_umbra() {
    let shadow = SquareShadow {
        light_height: 4.0,
        radius: 0.25,
        height: 1.0,
        half: 0.5,
    };
    let scene = plane_scene(Some((1.0, 0.5)));
    let reference = Reference::new(&scene);
    for radius in [0.0, shadow.radius] {
        let shadow = SquareShadow { radius, ..shadow };
        // A low camera sees the ground under the occluder.
        let (eye, light) = (Vec3::new(2.5, 0.5, 0.3), Vec3::new(0.0, 4.0, 0.0));
        let mut settings = lambert_settings(eye, Vec3::ZERO, 50.0, (48, 32), light);
        settings.light.radius_m = radius as f32;
        let options = ReferenceOptions {
            spp: 1,
            light_samples: 16,
            seed: 3,
            ..ReferenceOptions::DEFAULT
        };
        let image = reference
            .render(&settings, &options, &RenderControl::default())
            .unwrap();
        let (mut umbra, mut lit) = (0, 0);
        for j in 0..32 {
            for i in 0..48 {
                let at = image.index(i, j);
                let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
                let Some(sample) = reference.trace_pixel(&settings, &options, x, y) else {
                    assert_eq!(image.coverage[at], 0.0);
                    continue;
                };
                // The probe sees exactly what the render computed.
                assert_eq!(sample.radiance.to_array(), image.radiance[at]);
                if sample.object != 0 {
                    continue;
                }
                if shadow.umbra(sample.position) {
                    assert_eq!(
                        image.radiance[at], [0.0; 3],
                        "R = {radius}: ({i}, {j}) in the umbra"
                    );
                    assert_eq!(image.visibility[at], 0.0);
                    umbra += 1;
                } else if shadow.fully_lit(sample.position) {
                    assert_eq!(image.visibility[at], 1.0, "R = {radius}: ({i}, {j}) is fully lit");
                    lit += 1;
                }
            }
        }
        assert!(
            umbra > 30 && lit > 300,
            "R = {radius}: {umbra} umbra, {lit} lit pixels"
        );
    }
}

/// Log-log least-squares slope of y against x.
fn log_log_slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (lx, ly): (Vec<f64>, Vec<f64>) = points.iter().map(|&(x, y)| (x.ln(), y.ln())).unzip();
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = lx.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

#[test]
fn the_penumbra_converges_as_the_light_samples_grow() {
    // Looking straight down at the penumbra band of a square occluder under
    // a large sphere light.
    let scene = plane_scene(Some((1.0, 0.6)));
    let (eye, target) = (Vec3::new(0.95, 6.0, 0.01), Vec3::new(0.95, 0.0, 0.0));
    let mut settings = lambert_settings(eye, target, 9.0, (24, 24), Vec3::new(0.0, 3.0, 0.0));
    settings.light.radius_m = 0.5;
    let truth = render(&scene, &settings, 16384, 99);
    let mut rms = Vec::new();
    for n in [4u32, 16, 64, 256] {
        let image = render(&scene, &settings, n, n as u64);
        let (mut sum_sq, mut sum_var) = (0.0, 0.0);
        for (at, l) in image.radiance.iter().enumerate() {
            let e = luminance(*l) - luminance(truth.radiance[at]);
            sum_sq += e * e;
            sum_var += (image.noise[at] as f64).powi(2);
        }
        let pixels = image.radiance.len() as f64;
        let (error, predicted) = ((sum_sq / pixels).sqrt(), (sum_var / pixels).sqrt());
        // The reported noise is an honest estimate of the real error.
        let ratio = predicted / error;
        assert!(
            (0.7..4.0).contains(&ratio),
            "N = {n}: σ {predicted:e} vs error {error:e}"
        );
        rms.push((n as f64, error));
    }
    let slope = log_log_slope(&rms);
    eprintln!("RMS error against N: {rms:?}, log-log slope {slope:.3}");
    // Plain Monte Carlo falls as N^(−1/2); stratifying the cone does better
    // across a shadow edge (N^(−3/4) in theory), never worse.
    assert!((-0.95..=-0.35).contains(&slope), "slope {slope}");
    let last = rms.last().unwrap().1;
    let mean = truth.radiance.iter().map(|l| luminance(*l)).sum::<f64>() / truth.radiance.len() as f64;
    assert!(
        last / mean < 0.01,
        "RMS error at N = 256: {:.3} %",
        100.0 * last / mean
    );
}

/// Under a sphere light the pixel probe shows exactly what the render
/// computed at every pixel of the default scene, whose spheres, box, wall
/// and board give the shared gathering of occluders (a region for each block
/// of pixels) points at its edges, points outside it and crowded regions.
#[test]
fn the_probe_shows_the_render_under_a_sphere_light() {
    let scene = lumlab::scene::default_scene();
    let reference = Reference::new(&scene);
    let mut settings = Settings::default();
    (settings.image.width, settings.image.height) = (320, 180);
    settings.light.radius_m = 0.3;
    let options = ReferenceOptions {
        spp: 1,
        light_samples: 8,
        seed: 11,
        ..ReferenceOptions::DEFAULT
    };
    let image = reference
        .render(&settings, &options, &RenderControl::default())
        .unwrap();
    let mut shaded = 0;
    for j in 0..180 {
        for i in 0..320 {
            let at = image.index(i, j);
            let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
            let Some(sample) = reference.trace_pixel(&settings, &options, x, y) else {
                continue;
            };
            assert_eq!(sample.radiance.to_array(), image.radiance[at], "pixel ({i}, {j})");
            assert_eq!(sample.visibility as f32, image.visibility[at], "pixel ({i}, {j})");
            shaded += 1;
        }
    }
    assert!(shaded > 3000, "{shaded} pixels shaded");
}
