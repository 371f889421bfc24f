//! The `delta-e` view: its WGSL CIE Lab and CIEDE2000 (shaders/delta_e.wgsl)
//! run by a compute kernel against `colour` (whose ΔE2000 is held to Sharma,
//! Wu & Dalal's published pairs), and the view end to end on the default
//! scene: nothing under D65, where the RGB product is the spectral result by
//! construction; under A, at a lit pixel of each ColorChecker patch shown at
//! the patch's own brightness, the ΔE2000 `lumlab colour` prints for it.

mod common;

use bytemuck::{Pod, Zeroable};
use glam::{DVec2, DVec3, Vec3};
use lumlab::colour::chart::{compare_chart, illuminant_linear_srgb, patch_linear_srgb};
use lumlab::colour::shading::{ColourModel, pixel_delta_e, spectral_colour};
use lumlab::colour::{Illuminant, PATCH_COUNT, delta_e2000, patch_reflectance};
use lumlab::gpu::Renderer;
use lumlab::gpu::delta_e::{WGSL, lab_white_relative};
use lumlab::physics::colour::luminance;
use lumlab::scene::default_scene::{
    CHART_COLUMNS, CHART_FRONT_Z_M, CHART_GAP_M, CHART_ORIGIN_XY, CHART_PATCH_GAP_M, CHART_PATCH_M,
    CHART_PATCH_THICKNESS_M,
};
use lumlab::settings::{DebugView, Settings};

/// Two colours and the matrix to CIE Lab's white-relative XYZ (columns);
/// `lab`: 1 when a and b are already L*a*b*.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct Case {
    a: [f32; 3],
    lab: u32,
    b: [f32; 3],
    _pad: f32,
    columns: [[f32; 4]; 3],
}

const KERNEL: &str = r#"
struct Case {
    a: vec3<f32>,
    lab: u32,
    b: vec3<f32>,
    columns: mat3x3<f32>,
}

fn each(c: Case) -> f32 {
    if c.lab != 0u {
        return delta_e2000(c.a, c.b);
    }
    return pixel_delta_e(c.a, c.b, c.columns);
}
"#;

fn run(cases: &[Case]) -> Vec<f32> {
    common::kernel::run(&format!("{WGSL}{KERNEL}"), "f32", "each", cases)
}

fn lab_case(a: DVec3, b: DVec3) -> Case {
    Case {
        a: a.as_vec3().to_array(),
        lab: 1,
        b: b.as_vec3().to_array(),
        _pad: 0.0,
        columns: [[0.0; 4]; 3],
    }
}

/// A Lab colour from lightness, chroma and hue (degrees).
fn lch(l: f64, c: f64, h_deg: f64) -> DVec3 {
    let h = h_deg.to_radians();
    DVec3::new(l, c * h.cos(), c * h.sin())
}

#[test]
fn wgsl_ciede2000_equals_the_rust_and_sharmas_pairs() {
    // Sharma, Wu & Dalal (2005), Table 1, pairs 1, 7, 17, 19, 25, 28, 31
    // and 34: blue, neutral, large, and near-black differences. (Their
    // pairs 9–16 sit exactly on the 180° hue boundary, which f32 hues
    // cannot resolve; the Rust meets them to 1e-4.)
    let published = [
        ([50.0, 2.6772, -79.7751], [50.0, 0.0, -82.7485], 2.0425),
        ([50.0, 0.0, 0.0], [50.0, -1.0, 2.0], 2.3669),
        ([50.0, 2.5, 0.0], [73.0, 25.0, -18.0], 27.1492),
        ([50.0, 2.5, 0.0], [56.0, -27.0, -3.0], 31.9030),
        ([60.2574, -34.0099, 36.2677], [60.4626, -34.1751, 39.4387], 1.2644),
        ([35.0831, -44.1164, 3.7933], [35.0232, -40.0716, 1.5901], 1.8645),
        ([90.8027, -2.0831, 1.4410], [91.1528, -1.6435, 0.0447], 1.4441),
        ([2.0776, 0.0795, -1.1350], [0.9033, -0.0636, -0.5514], 0.9082),
    ];
    let mut pairs: Vec<(DVec3, DVec3)> = published
        .iter()
        .map(|(a, b, _)| (DVec3::from_array(*a), DVec3::from_array(*b)))
        .collect();
    // A sweep: every hue (across 0°/360°), neutral to saturated, dark to
    // light, with small and large differences in each of L*, C*, h.
    for l in [3.0, 25.0, 50.0, 75.0, 98.0] {
        for c in [0.0, 0.5, 8.0, 40.0, 90.0] {
            for step in 0..12 {
                let h = 5.0 + 30.0 * step as f64;
                let a = lch(l, c, h);
                for b in [
                    lch(l + 0.7, c, h),
                    lch(l, c * 1.1 + 0.3, h),
                    lch(l, c, h + 3.0),
                    lch(l - 9.0, c + 12.0, h + 40.0),
                    lch(l + 4.0, c * 0.5, h - 120.0),
                ] {
                    pairs.push((a, b));
                }
            }
        }
    }
    let cases: Vec<Case> = pairs.iter().map(|&(a, b)| lab_case(a, b)).collect();
    let got = run(&cases);
    let mut worst: f64 = 0.0;
    for (i, (&(a, b), &g)) in pairs.iter().zip(&got).enumerate() {
        // The inputs as the GPU holds them (f32), so that only the formula's
        // own rounding counts.
        let (a32, b32) = (a.as_vec3().as_dvec3(), b.as_vec3().as_dvec3());
        let want = delta_e2000(a32, b32);
        let diff = (g as f64 - want).abs();
        worst = worst.max(diff / want.max(1.0));
        // f32: about 1e-6 relative per step; the hue terms lose more
        // near the neutral axis, where atan2 is ill-conditioned.
        assert!(
            g.is_finite() && diff <= 2e-4 * want.max(1.0),
            "pair {i} {a} {b}: WGSL {g}, Rust {want}"
        );
        if let Some((_, _, published)) = published.get(i) {
            assert!(
                (g as f64 - published).abs() <= 2e-4 * published.max(1.0),
                "Sharma pair {i}: WGSL {g}, published {published}"
            );
        }
    }
    println!(
        "{} pairs, worst |WGSL − Rust| / max(ΔE, 1) = {worst:.2e}",
        pairs.len()
    );
}

#[test]
fn wgsl_pixel_delta_e_equals_the_probes() {
    // The chart's patches lit by each light, spectral against the RGB
    // product, from near black to well above white: the colours the view
    // compares, through linear sRGB → XYZ → Lab with the illuminant's white.
    let mut cases = Vec::new();
    let mut expected = Vec::new();
    for illuminant in [
        Illuminant::A,
        Illuminant::Fl11,
        Illuminant::Blackbody { kelvin: 1800.0 },
    ] {
        let s = illuminant.spectrum();
        let columns = lab_white_relative(illuminant).as_mat3();
        let columns = [columns.x_axis, columns.y_axis, columns.z_axis].map(|c| c.extend(0.0).to_array());
        for patch in 0..PATCH_COUNT {
            let spectral = spectral_colour(&s, &patch_reflectance(patch));
            let approx = patch_linear_srgb(patch) * illuminant_linear_srgb(&s);
            for brightness in [0.003, 0.05, 0.4, 1.0, 6.0] {
                let (a, b) = ((spectral * brightness).as_vec3(), (approx * brightness).as_vec3());
                cases.push(Case {
                    a: a.to_array(),
                    lab: 0,
                    b: b.to_array(),
                    _pad: 0.0,
                    columns,
                });
                expected.push(pixel_delta_e(illuminant, a.as_dvec3(), b.as_dvec3()));
            }
        }
    }
    let got = run(&cases);
    for (i, (&g, &want)) in got.iter().zip(&expected).enumerate() {
        assert!(
            g.is_finite() && (g as f64 - want).abs() <= 5e-4 * want.max(1.0),
            "case {i} {:?}: WGSL {g}, Rust {want}",
            cases[i]
        );
    }
}

/// The default scene's renderer and its settings under `illuminant`, at a
/// size where every chart patch covers many pixels.
fn default_scene_view(illuminant: Option<Illuminant>, model: ColourModel) -> (Renderer, Settings) {
    let gpu = common::gpu();
    let renderer = Renderer::new(
        &gpu.adapter,
        &gpu.device,
        &gpu.queue,
        &lumlab::scene::default_scene(),
    );
    let mut s = Settings::default();
    (s.image.width, s.image.height) = (384, 216);
    s.colour.illuminant = illuminant;
    s.colour.model = model;
    s.view.mode = DebugView::DeltaE;
    (renderer, s)
}

fn size(s: &Settings) -> (u32, u32) {
    (s.image.width, s.image.height)
}

/// The chart patches whose base colour (the glTF's, within 0…1) is not
/// their linear sRGB under D65: the cyan's red lies outside sRGB. The RGB
/// product cannot show their colour, even under D65.
fn clipped_patches() -> Vec<usize> {
    (0..PATCH_COUNT).filter(|&p| !unclipped(p)).collect()
}

/// The patch's base colour is its linear sRGB under D65 (to f32).
fn unclipped(patch: usize) -> bool {
    (base_colour(patch) - patch_linear_srgb(patch))
        .abs()
        .max_element()
        < 1e-6
}

/// Patch `patch`'s base colour in the default scene.
fn base_colour(patch: usize) -> DVec3 {
    let name = lumlab::colour::shading::chart_material_name(patch);
    lumlab::scene::default_scene()
        .materials
        .iter()
        .find(|m| m.name == name)
        .expect("the chart's materials")
        .base_color
        .truncate()
        .as_dvec3()
}

#[test]
fn under_d65_the_view_shows_no_difference_but_where_rgb_was_clipped() {
    let clipped = clipped_patches();
    assert_eq!(clipped.len(), 1, "the cyan patch only: {clipped:?}");
    for model in ColourModel::ALL {
        let (mut renderer, s) = default_scene_view(Some(Illuminant::D65), *model);
        renderer.render(&s, size(&s));
        let quantity = renderer.read_quantity();
        let mut shaded = s.clone();
        shaded.view.mode = DebugView::Shaded;
        renderer.render(&shaded, size(&s));
        let radiance = renderer.read_quantity();
        // The clipped patches' pixels, with a pixel's margin.
        let boxes: Vec<(DVec2, DVec2)> = clipped
            .iter()
            .map(|&p| {
                let corners = patch_corners(p).map(|c| pixel_of(&s, c));
                let min = corners.iter().fold(DVec2::MAX, |a, &c| a.min(c)) - 1.0;
                let max = corners.iter().fold(DVec2::MIN, |a, &c| a.max(c)) + 1.0;
                (min, max)
            })
            .collect();
        let (mut worst, mut above_white): (f32, f32) = (0.0, 0.0);
        let mut covered = 0;
        for (i, q) in quantity.iter().enumerate() {
            let at = DVec2::new(
                (i as u32 % s.image.width) as f64 + 0.5,
                (i as u32 / s.image.width) as f64 + 0.5,
            );
            if q[3] == 0.0
                || boxes
                    .iter()
                    .any(|(a, b)| at.cmpge(*a).all() && at.cmple(*b).all())
            {
                continue;
            }
            // CIE Lab describes surface colours up to the reference white
            // (Y/Yn ≤ 1); a highlight shown 15 times brighter (L* ≈ 270)
            // magnifies the uplift's small error on the gold sphere
            // (measured 0.059): those pixels get a looser bound.
            let y = luminance(radiance[i].map(f64::from)[..3].try_into().unwrap());
            if y * 2f64.powf(s.view.exposure_ev as f64) > 1.0 {
                above_white = above_white.max(q[0]);
                assert!(
                    (0.0..0.1).contains(&q[0]),
                    "{model}: ΔE2000 {} at {at} above white",
                    q[0]
                );
                continue;
            }
            covered += 1;
            worst = worst.max(q[0]);
            assert!(
                (0.0..0.05).contains(&q[0]),
                "{model}: ΔE2000 {} at {at} under D65",
                q[0]
            );
        }
        assert!(covered > quantity.len() / 2, "{model}: the scene fills the view");
        println!("D65, {model}: ΔE2000 ≤ {worst:.2e} on {covered} pixels, ≤ {above_white:.2e} above white");
    }
    // And there, the view shows what clipping costs (the chart test's check).
    chart_in_the_view(Illuminant::D65);
}

#[test]
fn without_an_illuminant_the_view_says_there_is_nothing_to_show() {
    let (mut renderer, s) = default_scene_view(None, ColourModel::Spectral);
    renderer.render(&s, size(&s));
    let quantity = renderer.read_quantity();
    let image = renderer.read_display();
    let mut covered = 0;
    for (q, p) in quantity.iter().zip(image.pixels()) {
        if q[3] > 0.0 {
            covered += 1;
            // −1: undefined, shown as the grey checker, never as ΔE = 0.
            assert_eq!(q[0], -1.0);
            assert!(p[0] == p[1] && p[1] == p[2], "a grey checker, not a ramp: {p:?}");
        }
    }
    assert!(covered > 0);
}

/// The centre of patch `patch`'s front face (m).
fn patch_centre(patch: usize) -> Vec3 {
    let pitch = CHART_PATCH_M + CHART_GAP_M;
    let rows = PATCH_COUNT.div_ceil(CHART_COLUMNS);
    let (column, row) = (patch % CHART_COLUMNS, patch / CHART_COLUMNS);
    Vec3::new(
        CHART_ORIGIN_XY.0 + column as f32 * pitch + 0.5 * CHART_PATCH_M,
        CHART_ORIGIN_XY.1 + (rows - 1 - row) as f32 * pitch + 0.5 * CHART_PATCH_M,
        CHART_FRONT_Z_M + CHART_PATCH_GAP_M + CHART_PATCH_THICKNESS_M,
    )
}

/// Where `point` appears in the image (pixels from the top left corner),
/// by the camera model of DESIGN.md §5.
fn pixel_of(s: &Settings, point: Vec3) -> DVec2 {
    let (c, f) = (&s.camera, s.camera.frame());
    let d = point.as_dvec3() - c.eye.as_dvec3();
    let depth = d.dot(f.forward);
    assert!(depth > 0.0, "{point} is in front of the camera");
    let (w, h) = (s.image.width as f64, s.image.height as f64);
    let t = c.tan_half_fovy();
    let (x, y) = (d.dot(f.right) / (depth * t * w / h), d.dot(f.up) / (depth * t));
    DVec2::new((x + 1.0) * 0.5 * w, (1.0 - y) * 0.5 * h)
}

/// The corners of patch `patch`'s front face (m).
fn patch_corners(patch: usize) -> [Vec3; 4] {
    let h = 0.5 * CHART_PATCH_M;
    let c = patch_centre(patch);
    [(-h, -h), (h, -h), (h, h), (-h, h)].map(|(x, y)| c + Vec3::new(x, y, 0.0))
}

#[test]
fn under_a_each_patch_shows_the_delta_e_of_lumlab_colour() {
    let (shown, printed) = chart_in_the_view(Illuminant::A);
    let range = |v: &[f64]| {
        let (min, max) = v
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
        format!(
            "{min:.3} … {max:.3}, mean {:.3}",
            v.iter().sum::<f64>() / v.len() as f64
        )
    };
    println!(
        "A: the view on the chart's patches {}; lumlab colour {}",
        range(&shown),
        range(&printed)
    );
}

/// For every chart patch under `illuminant`, with either model shown: at a
/// lit pixel at its centre, exposed so that the pixel shows the patch's own
/// colour (white's Y = 1), the view's ΔE2000 against the CPU's
/// `pixel_delta_e` of the patch's spectral colour and RGB product — which is
/// `lumlab colour`'s value wherever the base colour was not clipped.
/// Returns the view's values and `lumlab colour`'s, in chart order.
fn chart_in_the_view(illuminant: Illuminant) -> (Vec<f64>, Vec<f64>) {
    let spectrum = illuminant.spectrum();
    let light_rgb = illuminant_linear_srgb(&spectrum);
    let chart = compare_chart(illuminant);
    let mut as_lumlab_colour = 0;
    let mut worst: f64 = 0.0;
    let (mut shown, mut printed) = (Vec::new(), Vec::new());
    for model in ColourModel::ALL {
        let (mut renderer, mut s) = default_scene_view(Some(illuminant), *model);
        s.view.mode = DebugView::Shaded;
        renderer.render(&s, size(&s));
        let (radiance, aux) = (renderer.read_quantity(), renderer.read_aux());
        for (patch, row) in chart.iter().enumerate() {
            let base = base_colour(patch);
            // The two colours of the patch under the light, white's Y = 1 (the light
            // is white, Y = 1): the spectral one and the lecture's product.
            let spectral = spectral_colour(&spectrum, &patch_reflectance(patch));
            let product = base * light_rgb;
            let expected = pixel_delta_e(illuminant, spectral, product);
            // The chart's base colours are its linear sRGB under D65, clipped
            // to 0…1 as glTF wants: where nothing was clipped, the expected
            // value is the one `lumlab colour` prints.
            if unclipped(patch) {
                // (The base colour is stored in f32.)
                let d = (expected - row.delta_e2000).abs();
                assert!(d < 1e-4, "patch {patch}: {expected} against {}", row.delta_e2000);
                as_lumlab_colour += 1;
            }
            let centre = pixel_of(&s, patch_centre(patch));
            let index = (centre.y.floor() as u32 * s.image.width + centre.x.floor() as u32) as usize;
            assert!(aux[index][0] > 0.999, "patch {patch} is lit at {centre}");
            // Expose so that the pixel shows the patch's own colour: L · 2^EV
            // = the shown model's colour of the patch.
            let own = if *model == ColourModel::Spectral {
                spectral
            } else {
                product
            };
            let l = DVec3::from_array(radiance[index].map(f64::from)[..3].try_into().unwrap());
            let scale = luminance(l.to_array()) / luminance(own.to_array());
            let mut e = s.clone();
            e.view.mode = DebugView::DeltaE;
            e.view.exposure_ev = -scale.log2() as f32;
            renderer.render(&e, size(&e));
            let got = renderer.read_quantity()[index][0] as f64;
            worst = worst.max((got - expected).abs());
            // f32 shading and Lab, the colours stored in f32, the exposure
            // rounded to f32: measured 1.5e-4 at worst under A (ΔE up to
            // 12), so 1e-3 has a margin of about 7 and still catches a wrong
            // white, matrix or exposure (each moves ΔE by 0.1 or more).
            assert!(
                (got - expected).abs() < 1e-3,
                "{illuminant} {model}, patch {patch} {}: view {got}, CPU {expected}",
                row.name()
            );
            if *model == ColourModel::Spectral {
                shown.push(got);
                printed.push(row.delta_e2000);
            }
        }
    }
    assert_eq!(as_lumlab_colour, 2 * (PATCH_COUNT - clipped_patches().len()));
    println!("{illuminant}: worst |view − CPU| {worst:.2e}");
    for p in clipped_patches() {
        println!(
            "{illuminant}: clipped patch {} shows {:.3} (lumlab colour, unclipped: {:.3})",
            chart[p].name(),
            shown[p],
            printed[p]
        );
    }
    (shown, printed)
}

/// `lumlab render` with `args`, into `out` (EXR: ΔE in R, coverage in A);
/// returns the pixels and the standard error.
fn render_cli(args: &[&str], out: &std::path::Path) -> (Vec<[f32; 4]>, String) {
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_lumlab"))
        .args(["render", "--size", "96x54", "--out"])
        .arg(out)
        .args(args)
        .output()
        .expect("the lumlab binary runs");
    let stderr = String::from_utf8_lossy(&run.stderr).into_owned();
    assert!(run.status.success(), "{args:?}: {stderr}");
    let image = image::open(out).expect("an EXR").to_rgba32f();
    (image.pixels().map(|p| p.0).collect(), stderr)
}

#[test]
fn the_command_line_renders_the_view_from_its_flags_and_from_a_settings_file() {
    let dir = std::env::temp_dir().join(format!("lumlab-delta-e-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (flags, _) = render_cli(
        &["--view", "delta-e", "--illuminant", "A"],
        &dir.join("flags.exr"),
    );
    let covered: Vec<f32> = flags.iter().filter(|p| p[3] > 0.0).map(|p| p[0]).collect();
    assert!(covered.iter().all(|&d| d >= 0.0));
    // The chart's saturated patches, at least, are plainly off under A.
    assert!(covered.iter().any(|&d| d > 2.3));
    let settings = dir.join("delta-e.toml");
    std::fs::write(
        &settings,
        "[view]\nmode = \"delta-e\"\n\n[colour]\nilluminant = \"A\"\n",
    )
    .unwrap();
    let (from_file, _) = render_cli(&["--settings", settings.to_str().unwrap()], &dir.join("file.exr"));
    assert_eq!(from_file, flags);
    // No illuminant: said, and nothing that reads as a ΔE.
    let (rgb, stderr) = render_cli(&["--view", "delta-e"], &dir.join("rgb.exr"));
    assert!(stderr.contains("needs --illuminant"), "{stderr}");
    assert!(rgb.iter().filter(|p| p[3] > 0.0).all(|p| p[0] == -1.0));
    let _ = std::fs::remove_dir_all(&dir);
}
