//! The WGSL physics of `shaders/common.wgsl` and the Rust of `src/physics/`
//! agree on their fallback paths, not only on whole images: the BRDF
//! evaluated on the GPU by a compute kernel against `physics::brdf` in f32
//! (the k ≥ 1 shortcut, l + o = 0, back faces), the colour functions against
//! `physics::colour`, and tiny scenes built to hit the scene fallbacks
//! (missing and zero normals, a material index out of range) rendered by
//! the GPU and by the reference, compared pixel by pixel.

mod common;

use bytemuck::{Pod, Zeroable};
use glam::{DVec3, Vec3};
use lumlab::gpu::Renderer;
use lumlab::physics::{BrdfParams, Normalization, brdf, colour};
use lumlab::reference::{Reference, ReferenceOptions, RenderControl, luminance};
use lumlab::scene::shapes::{cuboid, ground};
use lumlab::scene::{Object, Scene};
use lumlab::settings::Settings;

/// One BRDF evaluation's inputs (the kernel's `Case`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct Case {
    n: [f32; 3],
    k: f32,
    l: [f32; 3],
    m: f32,
    o: [f32; 3],
    norm: u32,
}

/// Per case: blinn_phong's (diffuse, specular), then luminance of n and
/// the tint of n by l (as colours).
const KERNEL: &str = r#"
struct Case {
    n: vec3<f32>,
    k: f32,
    l: vec3<f32>,
    m: f32,
    o: vec3<f32>,
    norm: u32,
}
struct Result {
    brdf: vec2<f32>,
    luminance: f32,
    tint: vec3<f32>,
}

fn each(c: Case) -> Result {
    return Result(blinn_phong(c.n, c.l, c.o, c.k, c.m, c.norm), luminance(c.n), tint(c.n, c.l));
}
"#;

/// `Result` as the kernel writes it (vec3 aligned to 16: 32 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct GpuResult {
    brdf: [f32; 2],
    luminance: f32,
    _pad0: f32,
    tint: [f32; 3],
    _pad1: f32,
}

fn run_kernel(cases: &[Case]) -> Vec<GpuResult> {
    common::kernel::run(KERNEL, "Result", "each", cases)
}

fn case(n: Vec3, l: Vec3, o: Vec3, k: f32, m: f32, norm: Normalization) -> Case {
    let code = Normalization::ALL.iter().position(|&x| x == norm).unwrap() as u32;
    Case {
        n: n.to_array(),
        k,
        l: l.to_array(),
        m,
        o: o.to_array(),
        norm: code,
    }
}

#[test]
fn wgsl_brdf_and_colour_equal_the_rust_physics_on_every_path() {
    let n = Vec3::Y;
    let tilted = Vec3::new(0.3, 0.8, -0.2).normalize();
    let mirror = Vec3::new(-0.3, 0.8, 0.2).normalize();
    let mut cases = Vec::new();
    for norm in Normalization::ALL.iter().copied() {
        // The k ≥ 1 shortcut: N(10^20) overflows f32 with `exact`, and a
        // material's own k may exceed 1; the lobe must not be evaluated.
        for (k, m) in [
            (1.0, 1e20),
            (1.0, 64.0),
            (1.5, 8.0),
            (0.5, 8.0),
            (0.0, 0.0),
            (0.0, 1e6),
        ] {
            cases.push(case(n, n, n, k, m, norm));
            cases.push(case(n, tilted, mirror, k, m, norm));
            // l + o = 0 (no half vector) cannot happen above the surface;
            // grazing and back-facing directions give no light.
            cases.push(case(n, tilted, -tilted, k, m, norm));
            cases.push(case(n, -tilted, mirror, k, m, norm));
            cases.push(case(n, Vec3::X, Vec3::NEG_X, k, m, norm));
        }
    }
    let results = run_kernel(&cases);
    for (c, got) in cases.iter().zip(&results) {
        let (n, l, o) = (Vec3::from(c.n), Vec3::from(c.l), Vec3::from(c.o));
        let params = BrdfParams {
            k: c.k,
            m: c.m,
            norm: Normalization::ALL[c.norm as usize],
        };
        let want = brdf::blinn_phong(n, l, o, &params);
        for (part, g, w) in [
            ("diffuse", got.brdf[0], want.diffuse),
            ("specular", got.brdf[1], want.specular),
        ] {
            assert!(
                g.is_finite() && (g - w).abs() <= 1e-4 * w.abs().max(1.0),
                "{part} of {c:?}: WGSL {g}, Rust {w}"
            );
        }
        let y = colour::luminance(n.as_dvec3().to_array());
        assert!(
            (got.luminance as f64 - y).abs() < 1e-6,
            "luminance of {n}: WGSL {}, Rust {y}",
            got.luminance
        );
        let t = colour::tint(n.as_dvec3(), l.as_dvec3());
        for ch in 0..3 {
            assert!(
                (got.tint[ch] as f64 - t[ch]).abs() < 1e-6,
                "tint of {n} by {l}: WGSL {:?}, Rust {t}",
                got.tint
            );
        }
    }
}

/// Renders `scene` on the GPU and with the reference; every pixel must be
/// covered by both or neither, and each lit channel agree to 1e-3. Returns
/// the number of lit pixels compared.
fn gpu_equals_reference(scene: &Scene, settings: &Settings) -> usize {
    let gpu = common::gpu();
    let mut renderer = Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, scene);
    renderer.render(settings, (settings.image.width, settings.image.height));
    let (quantity, aux) = (renderer.read_quantity(), renderer.read_aux());
    let reference = Reference::new(scene)
        .render(settings, &ReferenceOptions::DEFAULT, &RenderControl::default())
        .unwrap();
    let peak = reference
        .radiance
        .iter()
        .map(|l| luminance(*l))
        .fold(0.0, f64::max);
    let mut checked = 0;
    for (idx, (l_ref, q)) in reference.radiance.iter().zip(&quantity).enumerate() {
        let pixel = (
            idx as u32 % settings.image.width,
            idx as u32 / settings.image.width,
        );
        assert_eq!(
            aux[idx][3] > 0.0,
            reference.coverage[idx] > 0.0,
            "pixel {pixel:?}: the GPU and the reference disagree on what it shows"
        );
        for c in 0..3 {
            let (g, r) = (q[c] as f64, l_ref[c]);
            assert!(
                (g - r).abs() <= 1e-3 * r.max(1e-3 * peak),
                "pixel {pixel:?} channel {c}: GPU {g} vs reference {r} W/m²/sr"
            );
        }
        checked += (luminance(*l_ref) > 1e-3 * peak) as usize;
    }
    checked
}

/// Looks at a box on the ground from above and to the side, lit from
/// another side, without shadows (so that only shading is compared).
fn box_settings() -> Settings {
    let mut s = common::settings(64, 48);
    s.shadow.enabled = false;
    s.camera.eye = Vec3::new(3.0, 2.5, 4.0);
    s.camera.target = Vec3::new(0.0, 0.4, 0.0);
    s.light.position = Vec3::new(-3.0, 2.0, 2.5);
    s.material.k = 0.6;
    s.material.m = 16.0;
    s
}

fn box_scene(clear_normals: impl Fn(&mut lumlab::scene::Mesh)) -> Scene {
    let mut boxed = cuboid(common::aabb([-0.5, 0.0, -0.5], [0.5, 1.0, 0.5]));
    clear_normals(&mut boxed);
    Scene {
        objects: vec![
            Object::new("ground", ground(Vec3::ZERO, 8.0), 0),
            Object::new("box", boxed, 0),
        ],
        materials: vec![common::material(Vec3::new(0.9, 0.7, 0.5))],
        ..Scene::default()
    }
}

#[test]
fn missing_normals_are_the_face_normal_on_both_sides() {
    // The box's sides face ±X and ±Z: a +Y stand-in would light them wrongly.
    let checked = gpu_equals_reference(&box_scene(|mesh| mesh.normals.clear()), &box_settings());
    assert!(checked > 300, "only {checked} lit pixels compared");
}

#[test]
fn zero_normals_are_the_face_normal_on_both_sides() {
    let scene = box_scene(|mesh| mesh.normals.iter_mut().for_each(|n| *n = Vec3::ZERO));
    let checked = gpu_equals_reference(&scene, &box_settings());
    assert!(checked > 300, "only {checked} lit pixels compared");
}

#[test]
fn a_material_index_out_of_range_is_the_default_material_on_both_sides() {
    let mut scene = box_scene(|_| {});
    // The last material is red: a GPU that clamped the index would paint the box red.
    scene.materials.push(common::material(Vec3::new(1.0, 0.0, 0.0)));
    scene.objects[1].material = 7;
    let checked = gpu_equals_reference(&scene, &box_settings());
    assert!(checked > 300, "only {checked} lit pixels compared");
    // And the default is what the scene says it is.
    let default = lumlab::scene::Material::default()
        .base_color
        .truncate()
        .as_dvec3();
    assert_eq!(
        scene
            .material_of(&scene.objects[1])
            .base_color
            .truncate()
            .as_dvec3(),
        default
    );
    assert!(default.distance(DVec3::splat(0.8)) < 1e-6);
}
