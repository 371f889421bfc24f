//! The GPU renderer against the CPU reference on the default scene: with
//! shadows off both compute the same L = c · f_r · E pixel by pixel (same
//! camera convention, same physics), so they must agree to 1e-3 relative on
//! every lit pixel, give or take what L changes within the rasterizer's
//! sub-pixel grid (`common::SUBPIXEL_PX`) where it is steep: first estimated
//! from the neighbouring pixels, then, where the GPU lies beyond that
//! estimate, the reference traced over the sub-pixel square itself.
//!
//! Every GPU frame is drawn on the binary's one GPU thread
//! (`common::gpu_thread`): run on the test threads, each with a device of its
//! own, these tests hung on an NVIDIA H200.

mod common;

use lumlab::colour::{ColourModel, Illuminant};
use lumlab::reference::{Reference, ReferenceOptions, RenderControl, luminance};
use lumlab::scene::Scene;
use lumlab::settings::Settings;

/// A `width` × `height` image of the default settings, shadows off.
fn unshadowed(width: u32, height: u32) -> Settings {
    let mut settings = Settings::default();
    settings.image.width = width;
    settings.image.height = height;
    settings.shadow.enabled = false;
    settings
}

/// `compare_on` the default scene.
fn agree(settings: &Settings, what: &str) {
    agree_on(&lumlab::scene::default_scene(), settings, what);
}

/// `compare_on`, which checks every lit pixel, over at least a third of the
/// image; prints the worst relative difference under `what`.
fn agree_on(scene: &Scene, settings: &Settings, what: &str) {
    let (checked, worst) = compare_on(scene, settings);
    let pixels = settings.image.width * settings.image.height;
    assert!(
        checked > pixels as usize / 3,
        "{what}: only {checked} pixels compared"
    );
    eprintln!("{what}: {checked} lit pixels, worst relative difference {worst:.2e}");
}

fn compare_on(scene: &Scene, settings: &Settings) -> (usize, f64) {
    let (_, quantity, aux) = common::gpu_thread::render(scene, settings);
    let model = Reference::new(scene);
    let reference = model
        .render(settings, &ReferenceOptions::DEFAULT, &RenderControl::default())
        .unwrap();
    // Channel c of the reference's L at image point (x, y), 0 on background.
    let traced = |x: f64, y: f64, c: usize| {
        model
            .trace_pixel(settings, &ReferenceOptions::DEFAULT, x, y)
            .map_or(0.0, |sample| sample.radiance[c])
    };
    let mean =
        reference.radiance.iter().map(|l| luminance(*l)).sum::<f64>() / reference.radiance.len() as f64;
    let width = settings.image.width;
    let (mut checked, mut worst) = (0, 0.0_f64);
    for (idx, (l_ref, q)) in reference.radiance.iter().zip(&quantity).enumerate() {
        assert_eq!(
            aux[idx][3] > 0.0,
            reference.coverage[idx] > 0.0,
            "pixel {idx}: the GPU and the reference disagree on what it shows"
        );
        if luminance(*l_ref) <= 1e-3 * mean {
            continue;
        }
        for c in 0..3 {
            if l_ref[c] <= 1e-3 * mean {
                continue;
            }
            let relative = (q[c] as f64 / l_ref[c] - 1.0).abs();
            worst = worst.max(relative);
            let slack = subpixel_slack(&reference.radiance, width, idx, c);
            let gpu = q[c] as f64;
            if (gpu - l_ref[c]).abs() >= 1e-3 * l_ref[c] + slack {
                // The estimate undercounts where L bends (a terminator):
                // the reference over the square the GPU's pixel may land in.
                let (x, y) = (
                    (idx as u32 % width) as f64 + 0.5,
                    (idx as u32 / width) as f64 + 0.5,
                );
                let (low, high) = common::subpixel_range(x, y, |x, y| traced(x, y, c));
                assert!(
                    gpu > low * (1.0 - 1e-3) && gpu < high * (1.0 + 1e-3),
                    "pixel ({x}, {y}) channel {c}: GPU {gpu} vs reference {} W/m²/sr, {low} … {high} within {} px",
                    l_ref[c],
                    common::SUBPIXEL_PX
                );
            }
        }
        checked += 1;
    }
    (checked, worst)
}

/// What channel `c` of L may change within `common::SUBPIXEL_PX` of pixel
/// `idx`'s centre, from the reference image itself: per axis the smaller of
/// the differences to the two neighbours (alike where L is smooth; across an
/// edge between surfaces one is the jump, the other the slope), times the
/// sub-pixel distance. Pixels on the image's border get none.
fn subpixel_slack(radiance: &[[f64; 3]], width: u32, idx: usize, c: usize) -> f64 {
    let w = width as usize;
    let (x, y) = (idx % w, idx / w);
    if x == 0 || y == 0 || x + 1 == w || idx + w >= radiance.len() {
        return 0.0;
    }
    let here = radiance[idx][c];
    let slope = |before: usize, after: usize| {
        (here - radiance[before][c])
            .abs()
            .min((radiance[after][c] - here).abs())
    };
    (slope(idx - 1, idx + 1) + slope(idx - w, idx + w)) * common::SUBPIXEL_PX
}

#[test]
fn without_shadows_the_gpu_equals_the_reference_on_every_lit_pixel() {
    let mut settings = unshadowed(192, 108);
    agree(&settings, "scene materials");

    // One sharp lobe everywhere, the light moved.
    settings.material.use_scene_materials = false;
    settings.material.k = 0.1;
    settings.material.m = 1e4;
    settings.light.position = glam::Vec3::new(-3.0, 4.0, 3.0);
    agree(&settings, "m = 1e4");
}

#[test]
fn vertex_colours_modulate_the_base_colour_alike_on_both() {
    let settings = unshadowed(160, 90);
    let plain = lumlab::scene::default_scene();
    let mut coloured = plain.clone();
    for object in &mut coloured.objects {
        let mesh = &mut object.mesh;
        mesh.colours = mesh
            .positions
            .iter()
            .map(|p| {
                glam::Vec3::new(
                    0.2 + 0.8 * p.x.sin().abs(),
                    0.2 + 0.8 * (2.0 * p.y).cos().abs(),
                    0.5,
                )
            })
            .collect();
    }
    agree_on(&coloured, &settings, "vertex colours");
    // The colours show: blue is halved everywhere against the plain scene.
    let blue = |scene: &Scene| {
        let image = Reference::new(scene)
            .render(&settings, &ReferenceOptions::DEFAULT, &RenderControl::default())
            .unwrap();
        image.radiance.iter().map(|l| l[2]).sum::<f64>()
    };
    let ratio = blue(&coloured) / blue(&plain);
    assert!((ratio - 0.5).abs() < 1e-9, "blue ratio {ratio}");
}

/// A base-colour texture tints the scene alike on both (the camera pass
/// compiled with textures), and the colour override replaces colour and
/// texture alike (applied per vertex on the GPU). The texel's bytes are 0
/// and 255, which every adapter's sRGB decoding maps exactly (lavapipe's
/// approximates others to ~0.3 %).
#[test]
fn textures_and_the_colour_override_shade_alike_on_both() {
    let mut settings = unshadowed(160, 90);
    let mut textured = lumlab::scene::default_scene();
    textured.textures.push(lumlab::scene::Texture {
        width: 1,
        height: 1,
        rgba8: vec![255, 0, 255, 255],
    });
    for material in &mut textured.materials {
        material.base_color_texture = Some(0);
    }
    agree_on(&textured, &settings, "textured");
    // Green, compared nowhere above (0 in the reference), is 0 on the GPU too.
    let (_, quantity, _) = common::gpu_thread::render(&textured, &settings);
    assert!(quantity.iter().all(|q| q[1] == 0.0));
    settings.material.color_override = Some(glam::Vec3::new(0.3, 0.6, 0.9));
    agree_on(&textured, &settings, "colour override over a texture");
}

#[test]
fn under_a_spectral_light_the_gpu_equals_the_spectral_reference() {
    // The GPU shades with each material's tristimulus computed once on the
    // CPU; the reference integrates reflectance × emission against the CMFs
    // per sample. Measured chart spectra and uplifted RGB colours, a smooth
    // and a spiky illuminant.
    let mut settings = unshadowed(192, 108);
    for illuminant in [Illuminant::A, Illuminant::Fl11] {
        for model in ColourModel::ALL {
            settings.colour.illuminant = Some(illuminant);
            settings.colour.model = *model;
            agree(&settings, &format!("{illuminant} {model}"));
        }
    }
}

/// Pixels whose visibility is strictly inside (0.05, 0.95): the penumbra.
fn penumbra_pixels(visibility: impl Iterator<Item = f64>) -> usize {
    visibility.filter(|v| *v > 0.05 && *v < 0.95).count()
}

#[test]
fn pcss_penumbra_is_as_wide_as_the_sphere_lights() {
    // A close look at the thin occluder's shadow under a 0.25 m sphere light.
    let mut settings = Settings::default();
    settings.image.width = 240;
    settings.image.height = 135;
    settings.camera.eye = glam::Vec3::new(-3.7, 2.4, 2.4);
    settings.camera.target = glam::Vec3::new(-3.7, 0.0, -0.1);
    settings.camera.fovy_deg = 40.0;
    settings.light.radius_m = 0.25;
    settings.shadow.resolution = 2048;
    settings.shadow.filter = lumlab::settings::Filter::Pcss;
    settings.shadow.pcss_blocker_samples = 32;
    settings.shadow.poisson_samples = 32;
    let scene = lumlab::scene::default_scene();
    let (_, _, aux) = common::gpu_thread::render(&scene, &settings);
    let gpu_penumbra = penumbra_pixels(aux.iter().map(|a| a[0] as f64));
    let options = ReferenceOptions {
        light_samples: 256,
        ..ReferenceOptions::DEFAULT
    };
    let reference = Reference::new(&scene)
        .render(&settings, &options, &RenderControl::default())
        .unwrap();
    let reference_penumbra = penumbra_pixels(reference.visibility.iter().map(|&v| v as f64));
    let ratio = gpu_penumbra as f64 / reference_penumbra as f64;
    eprintln!("penumbra pixels: PCSS {gpu_penumbra}, reference {reference_penumbra} (ratio {ratio:.2})");
    assert!(reference_penumbra > 1000, "{reference_penumbra}");
    assert!(
        (0.75..1.33).contains(&ratio),
        "PCSS penumbra {ratio:.2} × the reference's"
    );
}

/// The fraction of light-facing pixels whose shadow state differs from the
/// reference's, on the default scene at 320×180 with a 2048² map.
fn wrong_shadow_fraction(filter: lumlab::settings::Filter, bias: &str) -> f64 {
    let mut settings = Settings::default();
    settings.image.width = 320;
    settings.image.height = 180;
    settings.shadow.filter = filter;
    settings.shadow.bias = settings.shadow.bias.parse_onto(bias).unwrap();
    let scene = lumlab::scene::default_scene();
    let (_, quantity, aux) = common::gpu_thread::render(&scene, &settings);
    let reference = Reference::new(&scene)
        .render(&settings, &ReferenceOptions::DEFAULT, &RenderControl::default())
        .unwrap();
    let comparison = lumlab::report::metrics::Comparison::new(&reference, &aux);
    let frame = lumlab::report::metrics::Frame::from_gpu(&quantity, &aux);
    comparison.measure(&frame).wrong_shadow_fraction
}

#[test]
fn shadow_maps_agree_with_ray_traced_visibility_except_at_edges() {
    use lumlab::settings::Filter;
    let auto = wrong_shadow_fraction(Filter::None, "auto");
    let none = wrong_shadow_fraction(Filter::None, "constant:0");
    eprintln!("wrong shadow states: auto bias {auto:.4}, no bias {none:.4}");
    // Automatic bias: only pixels on shadow edges (a texel's width) disagree.
    assert!(auto < 0.003, "auto bias: {auto}");
    // Without bias, acne shadows lit surfaces: the lesson shows.
    assert!(none > 10.0 * auto && none > 0.01, "no bias: {none}");
}

#[test]
fn moment_shadow_maps_agree_with_ray_traced_visibility_except_at_edges() {
    use lumlab::settings::Filter;
    let vsm = wrong_shadow_fraction(Filter::Vsm, "auto");
    let msm = wrong_shadow_fraction(Filter::Msm, "auto");
    eprintln!("wrong shadow states: vsm {vsm:.4}, msm {msm:.4}");
    // Four moments bound the occluded fraction far tighter than two: only
    // shadow edges, blurred over a few texels, disagree.
    assert!(msm < 0.01, "msm: {msm}");
    assert!(msm <= vsm, "msm {msm} against vsm {vsm}");
}
