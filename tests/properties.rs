//! Properties that must hold for every input, not only the grid's: the BRDF
//! is non-negative, finite and reciprocal; the `exact` normalization never
//! creates energy; irradiance scales as Φ / r²; shadow filters keep V in
//! [0, 1]; settings survive their TOML file unchanged.

mod common;

use common::{aabb, gpu, occluder_scene, settings};
use glam::{DVec3, Vec3};
use lumlab::gpu::Renderer;
use lumlab::physics::brdf::{BrdfParams, blinn_phong};
use lumlab::physics::energy::{MAX_THETA_DEG, directional_albedo};
use lumlab::physics::radiometry::{incidence, intensity, point_irradiance, sphere_irradiance};
use lumlab::physics::{Normalization, Vector3};
use lumlab::settings::{BiasMode, DebugView, Filter, Settings, ShadowSettings};
use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};

/// A unit vector, uniform on the sphere.
fn unit() -> impl Strategy<Value = DVec3> {
    (-1.0..=1.0_f64, 0.0..std::f64::consts::TAU).prop_map(|(z, phi)| {
        let s = (1.0 - z * z).max(0.0).sqrt();
        DVec3::new(s * phi.cos(), z, s * phi.sin())
    })
}

/// An exponent in [0, 1e6], spread over the decades, with the ends themselves.
fn exponent() -> impl Strategy<Value = f64> {
    prop_oneof![
        1 => Just(0.0),
        1 => Just(1e6),
        8 => (-3.0..=6.0_f64).prop_map(|e| 10f64.powf(e)),
    ]
}

fn norm() -> impl Strategy<Value = Normalization> {
    proptest::sample::select(Normalization::ALL.to_vec())
}

/// n, l, o: random, or l = −o (l + o = 0), or l = o.
fn directions() -> impl Strategy<Value = (DVec3, DVec3, DVec3)> {
    prop_oneof![
        4 => (unit(), unit(), unit()),
        1 => (unit(), unit()).prop_map(|(n, l)| (n, l, -l)),
        1 => (unit(), unit()).prop_map(|(n, l)| (n, l, l)),
    ]
}

/// f_r / c in the precision of V.
fn brdf<V: Vector3>(n: V, l: V, o: V, k: V::S, m: V::S, norm: Normalization) -> V::S {
    blinn_phong(n, l, o, &BrdfParams { k, m, norm }).total()
}

proptest! {
    #![proptest_config(Config::with_cases(2000))]

    #[test]
    fn brdf_is_non_negative_and_finite_everywhere(
        (n, l, o) in directions(), k in 0.0..=1.0_f64, m in exponent(), norm in norm(),
    ) {
        let f64v = brdf(n, l, o, k, m, norm);
        prop_assert!(f64v.is_finite() && f64v >= 0.0, "f64: {f64v}");
        let f32v = brdf(n.as_vec3(), l.as_vec3(), o.as_vec3(), k as f32, m as f32, norm);
        prop_assert!(f32v.is_finite() && f32v >= 0.0, "f32: {f32v}");
    }

    #[test]
    fn brdf_is_reciprocal(
        (n, l, o) in directions(), k in 0.0..=1.0_f64, m in exponent(), norm in norm(),
    ) {
        prop_assert_eq!(brdf(n, l, o, k, m, norm), brdf(n, o, l, k, m, norm));
        let (n, l, o) = (n.as_vec3(), l.as_vec3(), o.as_vec3());
        prop_assert_eq!(
            brdf(n, l, o, k as f32, m as f32, norm),
            brdf(n, o, l, k as f32, m as f32, norm)
        );
    }
}

proptest! {
    // Each albedo is an adaptive quadrature: a modest number of cases.
    #![proptest_config(Config::with_cases(40))]

    #[test]
    fn exact_normalization_never_reflects_more_than_it_receives(
        m in exponent(), theta_deg in 0.0..=MAX_THETA_DEG, k in 0.0..=1.0_f64,
    ) {
        let params = BrdfParams { k, m, norm: Normalization::Exact };
        let a = directional_albedo(theta_deg, &params).value;
        prop_assert!(a <= 1.0 + 1e-6, "m = {m}, θ = {theta_deg}°, k = {k}: a = {a}");
        prop_assert!(a >= 0.0);
    }
}

proptest! {
    #![proptest_config(Config::with_cases(2000))]

    #[test]
    fn irradiance_scales_as_inverse_square_and_linearly_in_power(
        power_w in (-6.0..=9.0_f64).prop_map(|e| 10f64.powf(e)),
        r_m in (-5.0..=5.0_f64).prop_map(|e| 10f64.powf(e)),
        s in (-1.0..=1.0_f64).prop_map(|e| 10f64.powf(e)),
        a in (-3.0..=3.0_f64).prop_map(|e| 10f64.powf(e)),
        cos_theta in 0.0..=1.0_f64,
    ) {
        let e = |power: f64, r: f64| point_irradiance(intensity(power), cos_theta, r);
        let base = e(power_w, r_m);
        // Both distances stay above the 1 µm clamp.
        prop_assert!((e(power_w, r_m * s) * s * s - base).abs() <= 1e-12 * base);
        prop_assert!((e(a * power_w, r_m) - a * base).abs() <= 1e-12 * a * base);
        // The same in f32, the GPU's precision, to a few roundings.
        let e32 = |power: f64, r: f64| {
            point_irradiance(intensity(power as f32), cos_theta as f32, r as f32) as f64
        };
        let base32 = e32(power_w, r_m);
        prop_assert!((e32(power_w, r_m * s) * s * s - base32).abs() <= 1e-6 * base32);
        prop_assert!((e32(a * power_w, r_m) - a * base32).abs() <= 1e-6 * a * base32);
    }

    #[test]
    fn irradiance_is_finite_at_any_distance_even_zero(
        p in (-1e3..1e3_f64, -1e3..1e3_f64, -1e3..1e3_f64),
        n in unit(), offset in unit(),
        r_m in prop_oneof![Just(0.0), (-9.0..=6.0_f64).prop_map(|e| 10f64.powf(e))],
        power_w in prop_oneof![Just(0.0), Just(1e9), 0.0..=1e9_f64],
        radius_m in prop_oneof![Just(0.0), 0.0..=1.0_f64],
    ) {
        let p = DVec3::new(p.0, p.1, p.2);
        let q = p + offset * r_m;
        let (p32, n32, q32) = (p.as_vec3(), n.as_vec3(), q.as_vec3());
        let inc = incidence(p32, n32, q32);
        let e32 = sphere_irradiance(power_w as f32, radius_m as f32, inc.cos_theta, inc.r);
        prop_assert!(e32.is_finite() && e32 >= 0.0, "f32: {e32}");
        let inc = incidence(p, n, q);
        let e64 = sphere_irradiance(power_w, radius_m, inc.cos_theta, inc.r);
        prop_assert!(e64.is_finite() && e64 >= 0.0, "f64: {e64}");
    }
}

/// One shadow configuration drawn at random.
#[derive(Clone, Debug)]
struct ShadowCase {
    filter: Filter,
    bias: String,
    resolution: u32,
    pcf_size: u32,
    light: Vec3,
    radius_m: f32,
}

fn shadow_case() -> impl Strategy<Value = ShadowCase> {
    let bias = prop_oneof![
        Just("auto".to_string()),
        (0.0..0.1_f32).prop_map(|d| format!("constant:{d}")),
        (0.0..0.05_f32, 0.0..4.0_f32).prop_map(|(d, s)| format!("slope:{d},{s}")),
        (0.0..4.0_f32).prop_map(|n| format!("normal:{n}")),
    ];
    // Above the occluder, or among the geometry (cube faces).
    let light = prop_oneof![
        3 => (-3.0..3.0_f32, 1.7..8.0_f32, -3.0..3.0_f32),
        1 => (-2.0..2.0_f32, 0.2..1.4_f32, -2.0..2.0_f32),
    ];
    (
        proptest::sample::select(Filter::ALL.to_vec()),
        bias,
        256u32..=1024,
        proptest::sample::select(ShadowSettings::PCF_SIZES.to_vec()),
        light,
        0.0..0.5_f32,
    )
        .prop_map(
            |(filter, bias, resolution, pcf_size, (x, y, z), radius_m)| ShadowCase {
                filter,
                bias,
                resolution,
                pcf_size,
                light: Vec3::new(x, y, z),
                radius_m,
            },
        )
}

#[test]
fn shadow_filters_keep_visibility_in_the_unit_interval() {
    let gpu = gpu();
    let occluder = aabb([-0.5, 1.5, -0.5], [0.5, 1.55, 0.5]);
    let scene = occluder_scene(8.0, occluder);
    // The runner takes an `Fn`: one renderer for every case, borrowed per case.
    let renderer = std::cell::RefCell::new(Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, &scene));
    // A few dozen small renders: each one is a shadow pass and a camera pass.
    let mut runner = TestRunner::new(Config::with_cases(32));
    runner
        .run(&shadow_case(), |case| {
            let mut s = settings(48, 36);
            s.camera.eye = Vec3::new(0.0, 3.0, 5.0);
            s.camera.target = Vec3::new(0.0, 0.5, 0.0);
            s.light.position = case.light;
            s.light.radius_m = case.radius_m;
            s.shadow.filter = case.filter;
            s.shadow.resolution = case.resolution;
            s.shadow.pcf_size = case.pcf_size;
            s.shadow.bias = s
                .shadow
                .bias
                .parse_onto(&case.bias)
                .map_err(TestCaseError::fail)?;
            s.view.mode = DebugView::Visibility;
            let mut renderer = renderer.borrow_mut();
            renderer.render(&s, (s.image.width, s.image.height));
            // aux.x is V and aux.w marks the pixels that see geometry.
            let visibility = renderer
                .read_aux()
                .into_iter()
                .filter(|a| a[3] > 0.0)
                .map(|a| a[0]);
            let (mut seen, mut worst) = (0, None);
            for v in visibility {
                seen += 1;
                // NaN fails `contains` too.
                if !(0.0..=1.0).contains(&v) {
                    worst = Some(v);
                }
            }
            prop_assert!(seen > 0, "{case:?}: no geometry in view");
            prop_assert_eq!(worst, None, "{:?}: V outside [0, 1]", case);
            Ok(())
        })
        .unwrap_or_else(|e| panic!("{e}"));
}

fn in_range(min: f32, max: f32) -> impl Strategy<Value = f32> {
    prop_oneof![1 => Just(min), 1 => Just(max), 6 => min..=max]
}

fn vec_in(min: f32, max: f32) -> impl Strategy<Value = Vec3> {
    (in_range(min, max), in_range(min, max), in_range(min, max)).prop_map(Vec3::from)
}

fn any_settings() -> impl Strategy<Value = Settings> {
    let scene = proptest::option::of("[a-z]{1,8}/[a-z ]{1,8}\\.gl(b|tf)");
    let camera = (vec_in(-1e7, 1e7), vec_in(-1e7, 1e7), in_range(1.0, 179.0));
    let image = (1u32..=16384, 1u32..=16384);
    let light = (
        vec_in(-1e7, 1e7),
        in_range(0.0, 1e12),
        in_range(0.0, 1e6),
        vec_in(0.0, 1e6),
    );
    let material = (
        in_range(0.0, 1.0),
        in_range(0.0, 1e6),
        norm(),
        any::<bool>(),
        proptest::option::of(vec_in(0.0, 1.0)),
    );
    let shadow = (
        any::<bool>(),
        ShadowSettings::MIN_RESOLUTION..=ShadowSettings::MAX_RESOLUTION,
        proptest::sample::select(Filter::ALL.to_vec()),
        proptest::sample::select(ShadowSettings::PCF_SIZES.to_vec()),
        (
            4u32..=64,
            in_range(0.0, 64.0),
            4u32..=64,
            0u32..=16,
            in_range(0.0, 0.99),
        ),
        (
            proptest::sample::select(BiasMode::ALL.to_vec()),
            in_range(0.0, 1e3),
            in_range(0.0, 1e3),
            in_range(0.0, 1e3),
        ),
    );
    let view = (
        proptest::sample::select(DebugView::ALL.to_vec()),
        in_range(-30.0, 30.0),
    );
    (scene, camera, image, light, material, shadow, view).prop_map(
        |(scene, camera, image, light, material, shadow, view)| {
            let mut s = Settings {
                scene: scene.map(Into::into),
                ..Settings::default()
            };
            (s.camera.eye, s.camera.target, s.camera.fovy_deg) = camera;
            if (s.camera.eye - s.camera.target).length() < 1e-6 {
                s.camera.target += Vec3::ONE;
            }
            (s.image.width, s.image.height) = image;
            (s.light.position, s.light.power_w, s.light.radius_m, s.light.color) = light;
            let m = &mut s.material;
            (m.k, m.m, m.norm, m.use_scene_materials, m.color_override) = material;
            let (enabled, resolution, filter, pcf_size, counts, bias) = shadow;
            let sh = &mut s.shadow;
            (sh.enabled, sh.resolution, sh.filter, sh.pcf_size) = (enabled, resolution, filter, pcf_size);
            (
                sh.poisson_samples,
                sh.poisson_radius_texels,
                sh.pcss_blocker_samples,
                sh.vsm_blur_texels,
                sh.vsm_bleed_reduction,
            ) = counts;
            (
                sh.bias.mode,
                sh.bias.depth_m,
                sh.bias.slope,
                sh.bias.normal_texels,
            ) = bias;
            (s.view.mode, s.view.exposure_ev) = view;
            s
        },
    )
}

proptest! {
    #![proptest_config(Config::with_cases(500))]

    #[test]
    fn settings_round_trip_through_their_file_unchanged(s in any_settings()) {
        prop_assert!(s.validate().is_ok(), "{:?}", s.validate());
        let text = s.to_toml();
        let back = Settings::from_toml(&text).map_err(TestCaseError::fail)?;
        prop_assert_eq!(&back, &s, "{}", text);
        prop_assert!(back.validate().is_ok());
    }
}
