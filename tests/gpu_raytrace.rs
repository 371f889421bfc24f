//! The GPU ray-traced visibility against what it must equal: its BVH
//! traversal, one ray or four a walk, against testing every triangle (a
//! compute kernel; also on a degenerate tree deeper than its stack), its hard shadows against the CPU
//! reference's V pixel by pixel, and its progressive
//! accumulation under a sphere light converging to the reference's V as 1/√N.

mod common;

use glam::{Vec3, Vec4};
use lumlab::gpu::bvh::{BvhGridRaw, BvhNodeRaw, BvhPairRaw, BvhTriangleRaw, FlatBvh, GpuBvh};
use lumlab::gpu::raytrace::RayTraceRaw;
use lumlab::gpu::shaders::Shader;
use lumlab::gpu::{GpuContext, Renderer, ShadeOptions};
use lumlab::reference::{Reference, ReferenceOptions, RenderControl};
use lumlab::scene::Scene;
use lumlab::settings::{Settings, Visibility};
use wgpu::util::DeviceExt;

fn struct_size(module: &naga::Module, name: &str) -> usize {
    module
        .types
        .iter()
        .find_map(|(_, t)| match (&t.name, &t.inner) {
            (Some(n), naga::TypeInner::Struct { span, .. }) if n == name => Some(*span as usize),
            _ => None,
        })
        .unwrap_or_else(|| panic!("struct {name} not in shade.wgsl"))
}

#[test]
fn ray_tracer_structs_match_their_wgsl_size() {
    let module = naga::front::wgsl::parse_str(&Shader::Shade.source()).expect("the camera pass parses");
    assert_eq!(struct_size(&module, "RayTrace"), size_of::<RayTraceRaw>());
    assert_eq!(struct_size(&module, "BvhPair"), size_of::<BvhPairRaw>());
    assert_eq!(struct_size(&module, "BvhGrid"), size_of::<BvhGridRaw>());
    assert_eq!(struct_size(&module, "BvhTriangle"), size_of::<BvhTriangleRaw>());
}

/// For each ray (origin, t_max in w; direction), 1 if blocked, by the BVH
/// and by every triangle in turn: the same triangle test, so any difference
/// is the traversal's.
const KERNEL: &str = "
@group(0) @binding(0) var<storage, read> rays: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read_write> answers: array<vec2<u32>>;
// Rays, pairs, triangles; the grid.
struct Counts {
    n: vec4<u32>,
    grid: BvhGrid,
}
@group(0) @binding(2) var<uniform> counts: Counts;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= counts.n.x {
        return;
    }
    let o = rays[2u * i].xyz;
    let t_max = rays[2u * i].w;
    let d = rays[2u * i + 1u].xyz;
    var brute = 0u;
    for (var t = 0u; t < counts.n.z; t++) {
        if bvh_hits_triangle(bvh_triangles[t], o, d, t_max) {
            brute = 1u;
        }
    }
    var stack: BvhStack;
    answers[i] = vec2<u32>(select(0u, 1u, bvh_occluded(o, d, t_max, counts.n.y, counts.grid, &stack)), brute);
}

// The same for the four-ray walk: packet g holds rays 4g … 4g + 3, from the
// origin and with the t_max of the first, each along its own direction;
// ray j is left out where (g + j) % 5 == 0 (its brute-force answer 0).
@compute @workgroup_size(64)
fn packets(@builtin(global_invocation_id) id: vec3<u32>) {
    let g = id.x;
    if 4u * g >= counts.n.x {
        return;
    }
    let o = rays[8u * g].xyz;
    let t_max = rays[8u * g].w;
    let d = BvhRays4(rays[8u * g + 1u].xyz, rays[8u * g + 3u].xyz, rays[8u * g + 5u].xyz, rays[8u * g + 7u].xyz);
    let live = (vec4<u32>(g) + vec4<u32>(0u, 1u, 2u, 3u)) % 5u != vec4<u32>(0u);
    var stack: BvhStack;
    let walked = bvh_occluded4(o, d, t_max, live, counts.n.y, counts.grid, &stack);
    for (var j = 0u; j < 4u; j++) {
        var brute = 0u;
        for (var t = 0u; t < counts.n.z; t++) {
            if live[j] && bvh_hits_triangle(bvh_triangles[t], o, d[j], t_max) {
                brute = 1u;
            }
        }
        answers[4u * g + j] = vec2<u32>(select(0u, 1u, walked[j]), brute);
    }
}
";

/// The walks a test runs: one ray an invocation, or four (`packets`).
#[derive(Clone, Copy, Debug)]
enum Walk {
    Single,
    Packets,
}

fn storage(gpu: &GpuContext, label: &str, bytes: &[u8], usage: wgpu::BufferUsages) -> wgpu::Buffer {
    gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: bytes,
        usage,
    })
}

/// (BVH answer, brute-force answer) per ray.
fn trace(gpu: &GpuContext, flat: &FlatBvh, rays: &[[f32; 4]], walk: Walk) -> Vec<[u32; 2]> {
    let device = &gpu.device;
    let source = format!("{}{KERNEL}", include_str!("../shaders/bvh.wgsl"));
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("bvh test"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("bvh test"),
        layout: None,
        module: &module,
        entry_point: Some(match walk {
            Walk::Single => "main",
            Walk::Packets => "packets",
        }),
        compilation_options: Default::default(),
        cache: None,
    });
    let bvh = GpuBvh::new(device, flat);
    let n = rays.len() / 2;
    let ray_buffer = storage(
        gpu,
        "rays",
        bytemuck::cast_slice(rays),
        wgpu::BufferUsages::STORAGE,
    );
    let size = (n * 8) as u64;
    let answers = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("answers"),
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let mut counts: Vec<u8> =
        bytemuck::cast_slice(&[n as u32, bvh.pair_count, bvh.triangle_count, 0]).to_vec();
    counts.extend_from_slice(bytemuck::bytes_of(&bvh.grid));
    let counts = storage(gpu, "counts", &counts, wgpu::BufferUsages::UNIFORM);
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let group = |index: u32, resources: &[&wgpu::Buffer], first: u32| {
        let entries: Vec<_> = resources
            .iter()
            .enumerate()
            .map(|(i, b)| wgpu::BindGroupEntry {
                binding: first + i as u32,
                resource: b.as_entire_binding(),
            })
            .collect();
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(index),
            entries: &entries,
        })
    };
    let rays_group = group(0, &[&ray_buffer, &answers, &counts], 0);
    let bvh_group = group(2, &[&bvh.pairs, &bvh.triangles], 1);
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &rays_group, &[]);
        pass.set_bind_group(2, &bvh_group, &[]);
        let invocations = match walk {
            Walk::Single => n,
            Walk::Packets => n.div_ceil(4),
        };
        pass.dispatch_workgroups((invocations as u32).div_ceil(64), 1, 1);
    }
    encoder.copy_buffer_to_buffer(&answers, 0, &readback, 0, size);
    gpu.queue.submit([encoder.finish()]);
    readback
        .slice(..)
        .map_async(wgpu::MapMode::Read, |r| r.expect("map"));
    device.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
    let bytes = readback.slice(..).get_mapped_range().expect("mapped").to_vec();
    bytemuck::pod_collect_to_vec(&bytes)
}

/// xorshift64*: reproducible test rays.
struct Random(u64);

impl Random {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 40) as f32 / (1u64 << 24) as f32
    }

    fn point(&mut self, lo: Vec3, hi: Vec3) -> Vec3 {
        lo + (hi - lo) * Vec3::new(self.next(), self.next(), self.next())
    }
}

#[test]
fn bvh_traversal_answers_what_testing_every_triangle_answers() {
    let gpu = common::gpu();
    let scene = lumlab::scene::default_scene();
    let flat = FlatBvh::of_scene(&scene);
    assert!(flat.triangles.len() > 100, "{} triangles", flat.triangles.len());
    let bounds = scene.bounds();
    let (lo, hi) = (bounds.min - Vec3::splat(1.0), bounds.max + Vec3::splat(1.0));
    let mut random = Random(0x1234_5678_9abc_def1);
    let mut rays = Vec::new();
    for i in 0..4096 {
        let o = random.point(lo, hi);
        let q = random.point(lo, hi);
        // Segments of every length: many end just before or after a surface.
        let t_max = if i % 2 == 0 { 1.0 } else { random.next() };
        rays.push(o.extend(t_max).to_array());
        rays.push(Vec4::from((q - o, 0.0)).to_array());
    }
    let answers = trace(&gpu, &flat, &rays, Walk::Single);
    let blocked = answers.iter().filter(|a| a[1] == 1).count();
    assert!(
        blocked > 400 && blocked < 3700,
        "{blocked} of 4096 blocked: the rays do not test much"
    );
    let differ: Vec<usize> = (0..answers.len())
        .filter(|&i| answers[i][0] != answers[i][1])
        .collect();
    assert!(differ.is_empty(), "the BVH disagrees on rays {differ:?}");
}

/// Four rays from one point in one walk, as a sphere light's strata are
/// traced: each answer is what testing every triangle answers, whether the
/// four diverge (random directions) or nearly coincide (towards a ball of
/// 5 cm), some of them left out.
#[test]
fn four_ray_walks_answer_what_testing_every_triangle_answers() {
    let gpu = common::gpu();
    let scene = lumlab::scene::default_scene();
    let flat = FlatBvh::of_scene(&scene);
    let bounds = scene.bounds();
    let (lo, hi) = (bounds.min - Vec3::splat(1.0), bounds.max + Vec3::splat(1.0));
    let mut random = Random(0x0fed_cba9_8765_4321);
    let mut rays = Vec::new();
    for packet in 0..1024 {
        let o = random.point(lo, hi);
        let t_max = if packet % 3 == 0 { 1.0 } else { random.next() };
        let target = random.point(lo, hi);
        for _ in 0..4 {
            let q = if packet % 2 == 0 {
                random.point(lo, hi)
            } else {
                target + random.point(Vec3::splat(-0.05), Vec3::splat(0.05))
            };
            rays.push(o.extend(t_max).to_array());
            rays.push(Vec4::from((q - o, 0.0)).to_array());
        }
    }
    let answers = trace(&gpu, &flat, &rays, Walk::Packets);
    let blocked = answers.iter().filter(|a| a[1] == 1).count();
    assert!(
        blocked > 400 && blocked < 3000,
        "{blocked} of 4096 blocked: the rays do not test much"
    );
    let differ: Vec<usize> = (0..answers.len())
        .filter(|&i| answers[i][0] != answers[i][1])
        .collect();
    assert!(
        differ.is_empty(),
        "the four-ray walk disagrees on rays {differ:?}"
    );
}

/// The aux target (x: V, z: max(0, n·l)) of the ray tracer after each
/// number of `frames`.
fn ray_traced_aux(
    gpu: &GpuContext,
    scene: &Scene,
    settings: &Settings,
    frames: &[u32],
) -> Vec<Vec<[f32; 4]>> {
    let mut renderer = Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, scene);
    let size = (settings.image.width, settings.image.height);
    let mut out = Vec::new();
    let mut done = 0;
    for &n in frames {
        while done < n {
            renderer.render(settings, size);
            done += 1;
        }
        let a = renderer.accumulation().expect("ray traced");
        assert_eq!(a.frames, n.min(settings.ray_traced_frames()));
        assert_eq!(a.is_complete(), n >= settings.ray_traced_frames());
        out.push(renderer.read_aux());
    }
    out
}

/// Whether pixel `i`'s 3×3 neighbourhood in the reference holds a change
/// of V or of what is seen: a shadow's or an object's silhouette.
fn on_silhouette(v: &[f32], coverage: &[f32], width: usize, i: usize) -> bool {
    let (x, y) = ((i % width) as i64, (i / width) as i64);
    let height = (v.len() / width) as i64;
    let mut seen = Vec::new();
    for dy in -1..=1 {
        for dx in -1..=1 {
            let (nx, ny) = (x + dx, y + dy);
            if nx >= 0 && ny >= 0 && nx < width as i64 && ny < height {
                let j = (ny * width as i64 + nx) as usize;
                seen.push((v[j], coverage[j]));
            }
        }
    }
    seen.iter().any(|s| *s != seen[0])
}

/// Hard shadows of a point light: at most 0.01 % of the pixels differ from
/// the reference's V, each on a silhouette. Its one ray per pixel is exact:
/// after three frames the accumulation still holds one, complete.
fn point_light_matches_the_reference(scene: &Scene, settings: &Settings) {
    let gpu = common::gpu();
    assert!(settings.shadow.rt_max_frames >= 3);
    let gpu_v: Vec<f32> = ray_traced_aux(&gpu, scene, settings, &[3])[0]
        .iter()
        .map(|t| t[0])
        .collect();
    let reference = Reference::new(scene)
        .render(settings, &ReferenceOptions::DEFAULT, &RenderControl::default())
        .unwrap();
    let width = settings.image.width as usize;
    let mut differ = Vec::new();
    let mut shadowed = 0;
    for (i, (&g, &r)) in gpu_v.iter().zip(&reference.visibility).enumerate() {
        if reference.coverage[i] == 0.0 {
            continue;
        }
        shadowed += (r == 0.0) as usize;
        if (g - r).abs() > 1e-6 {
            assert!(
                on_silhouette(&reference.visibility, &reference.coverage, width, i),
                "pixel ({}, {}): GPU V {g}, reference {r}, away from any silhouette",
                i % width,
                i / width
            );
            differ.push(i);
        }
    }
    let pixels = gpu_v.len();
    eprintln!(
        "{} of {pixels} pixels differ ({shadowed} in shadow)",
        differ.len()
    );
    assert!(shadowed > pixels / 100, "only {shadowed} pixels in shadow");
    assert!(
        differ.len() as f64 <= 1e-4 * pixels as f64,
        "{} pixels differ",
        differ.len()
    );
}

fn ray_traced(width: u32, height: u32) -> Settings {
    let mut s = Settings::default();
    (s.image.width, s.image.height) = (width, height);
    s.shadow.visibility = Visibility::RayTraced;
    s.light.radius_m = 0.0;
    s
}

#[test]
fn point_light_shadows_are_the_references_on_the_default_scene() {
    point_light_matches_the_reference(&lumlab::scene::default_scene(), &ray_traced(320, 180));
}

#[test]
fn point_light_shadows_are_the_references_on_a_100k_triangle_scene() {
    let scene = lumlab::scene::stress::sphere_field(100_000);
    assert!(scene.triangle_count() >= 100_000);
    let mut settings = ray_traced(320, 180);
    lumlab::scene::framing::adopt(&mut settings, &scene);
    // Low and to the side: long shadows across the ground and the spheres.
    settings.light.position = Vec3::new(2.5, 1.2, 1.0);
    point_light_matches_the_reference(&scene, &settings);
}

/// Ray-traced V at 96 × 54 under a sphere light of R = 0.3 m.
fn under_a_sphere_light() -> Settings {
    let mut settings = ray_traced(96, 54);
    settings.light.radius_m = 0.3;
    settings
}

#[test]
fn sphere_light_accumulation_converges_to_the_reference_as_one_over_root_n() {
    let gpu = common::gpu();
    let scene = lumlab::scene::default_scene();
    let settings = under_a_sphere_light();
    let frames = [1, 4, 16, 64, 256];
    let runs = ray_traced_aux(&gpu, &scene, &settings, &frames);
    let options = ReferenceOptions {
        light_samples: 4096,
        ..ReferenceOptions::DEFAULT
    };
    let tracer = Reference::new(&scene);
    let reference = tracer
        .render(&settings, &options, &RenderControl::default())
        .unwrap();
    // Pixels where both see the same surface (the same cos θ to the light's
    // centre: a pixel centre on an object's silhouette can fall on the
    // object for the rasterizer and beside it for the ray), away from the
    // terminator: where the sphere straddles the horizon (|cos θ| < R / d)
    // V hangs on rays grazing the facets, which f32 and f64 offsets treat
    // differently, and the radiance there is nearly 0.
    let width = settings.image.width;
    let one_sample = ReferenceOptions {
        light_samples: 1,
        ..ReferenceOptions::DEFAULT
    };
    let all: Vec<usize> = (0..reference.coverage.len())
        .filter(|&i| reference.coverage[i] > 0.0)
        .collect();
    let covered: Vec<usize> = all
        .iter()
        .copied()
        .filter(|&i| {
            let (x, y) = ((i as u32 % width) as f64 + 0.5, (i as u32 / width) as f64 + 0.5);
            tracer.trace_pixel(&settings, &one_sample, x, y).is_some_and(|s| {
                let straddles = s.cos_theta.abs() < 0.3 / s.light_distance_m;
                (s.cos_theta.max(0.0) - runs[0][i][2] as f64).abs() < 1e-3 && !straddles
            })
        })
        .collect();
    eprintln!(
        "{} of {} covered pixels on the same surface, off the terminator",
        covered.len(),
        all.len()
    );
    assert!(covered.len() as f64 > 0.97 * all.len() as f64);
    let mean = covered
        .iter()
        .map(|&i| reference.visibility[i] as f64)
        .sum::<f64>()
        / covered.len() as f64;
    let rmse: Vec<f64> = runs
        .iter()
        .map(|v| {
            let sum: f64 = covered
                .iter()
                .map(|&i| (v[i][0] as f64 - reference.visibility[i] as f64).powi(2))
                .sum();
            (sum / covered.len() as f64).sqrt()
        })
        .collect();
    eprintln!("mean V {mean:.4}; RMSE at N = {frames:?}: {rmse:.5?}");
    for (k, &n) in frames.iter().enumerate() {
        // 1/√N with 25 % slack for the randomness of the estimate itself.
        let bound = 1.25 * rmse[0] / (n as f64).sqrt();
        assert!(rmse[k] <= bound, "N = {n}: RMSE {} above {bound}", rmse[k]);
    }
    assert!(
        rmse[4] < 0.02 * mean,
        "RMSE {} at 256 frames, mean {mean}",
        rmse[4]
    );
}

#[test]
fn accumulate_needs_ray_traced_visibility_and_renders_n_frames() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("v.png");
    let run = |extra: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_lumlab"))
            .args([
                "render",
                "--size",
                "64x36",
                "--light-radius",
                "0.3",
                "--accumulate",
                "3",
            ])
            .args(extra)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap()
    };
    let refused = run(&[]);
    assert_eq!(refused.status.code(), Some(2));
    let message = String::from_utf8_lossy(&refused.stderr);
    assert!(
        message.contains("--accumulate needs --visibility ray-traced"),
        "{message}"
    );
    assert!(!out.exists());
    let traced = run(&["--visibility", "ray-traced"]);
    let message = String::from_utf8_lossy(&traced.stderr);
    assert!(traced.status.success(), "{message}");
    assert!(
        message.contains("ray traced, 3 frame(s) × 4 ray(s) per pixel"),
        "{message}"
    );
    assert!(out.exists());
}

#[test]
fn a_mean_begun_without_the_aux_target_restarts_when_it_is_asked_for() {
    // The app's frames skip the aux target until the probe reads it; the
    // frames of the mean before then left none in the history.
    let gpu = common::gpu();
    let scene = lumlab::scene::default_scene();
    let settings = under_a_sphere_light();
    let size = (settings.image.width, settings.image.height);
    let mut renderer = Renderer::new(&gpu.adapter, &gpu.device, &gpu.queue, &scene);
    let quantity_only = ShadeOptions {
        aux: false,
        ..ShadeOptions::default()
    };
    renderer.set_shade_options(quantity_only);
    for _ in 0..3 {
        renderer.render(&settings, size);
    }
    assert_eq!(renderer.accumulation().unwrap().frames, 3);
    assert!(renderer.read_aux().is_empty(), "no aux target was written");
    renderer.set_shade_options(ShadeOptions::default());
    renderer.render(&settings, size);
    assert_eq!(renderer.accumulation().unwrap().frames, 1, "the mean restarted");
    let aux = renderer.read_aux();
    assert_eq!(aux.len(), (size.0 * size.1) as usize);
    // Coverage is 0 or 1 and V within [0, 1] (and an f32 rounding: the
    // H200 gives 1 + 1 ulp): no frame without aux in the mean.
    let odd = |a: &&[f32; 4]| !((a[3] == 0.0 || a[3] == 1.0) && (0.0..=1.0 + 1e-6).contains(&a[0]));
    let odd: Vec<_> = aux.iter().filter(odd).take(5).collect();
    assert!(odd.is_empty(), "{odd:?}");
    assert!(aux.iter().filter(|a| a[3] == 1.0).count() > aux.len() / 2);
    // Without the aux target the mean goes on as before: the quantity's
    // alpha still marks the pixels covered.
    renderer.set_shade_options(quantity_only);
    renderer.render(&settings, size);
    renderer.render(&settings, size);
    assert_eq!(renderer.accumulation().unwrap().frames, 2);
    let covered = renderer.read_quantity().iter().filter(|q| q[3] > 0.0).count();
    assert_eq!(covered, aux.iter().filter(|a| a[3] == 1.0).count());
}

/// A caterpillar BVH as deep as it has triangles (node 0 the root, an
/// inner node's children at `first` and `first + 1`): each inner node's
/// first child is the rest of the chain, its second an inner node whose
/// children are both triangle k's leaf. Every box is the whole scene's, so
/// the traversal visits every node and keeps one pending inner node per
/// level (it tests leaves as it meets them): far more than its stack holds.
fn caterpillar(triangles: &[[Vec3; 3]]) -> FlatBvh {
    let (lo, hi) = triangles
        .iter()
        .flatten()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
    let node = |count: u32, first: u32| BvhNodeRaw {
        min: (lo - 1.0).to_array(),
        count,
        max: (hi + 1.0).to_array(),
        first,
    };
    let n = triangles.len() as u32;
    let mut nodes = vec![node(0, 0)];
    let mut chain = 0;
    for k in 0..n - 1 {
        let first = nodes.len();
        nodes[chain].first = first as u32;
        let side_first = first as u32 + 2;
        nodes.extend([node(0, 0), node(0, side_first), node(1, k), node(1, k)]);
        chain = first;
    }
    nodes[chain] = node(1, n - 1);
    let triangles = triangles
        .iter()
        .map(|[a, b, c]| BvhTriangleRaw {
            v0: a.to_array(),
            e1: (*b - *a).to_array(),
            e2: (*c - *a).to_array(),
            ..Default::default()
        })
        .collect();
    FlatBvh { nodes, triangles }
}

#[test]
fn a_bvh_deeper_than_the_traversal_stack_loses_no_triangle() {
    // 300 small triangles side by side in the plane z = 0; each ray crosses
    // one of them, through it (t_max 1) or stopping short (0.4).
    let triangles: Vec<[Vec3; 3]> = (0..300)
        .map(|k| {
            let x = k as f32;
            [
                Vec3::new(x, 0.0, 0.0),
                Vec3::new(x + 0.5, 0.0, 0.0),
                Vec3::new(x, 0.5, 0.0),
            ]
        })
        .collect();
    let flat = caterpillar(&triangles);
    let mut rays = Vec::new();
    for k in 0..triangles.len() {
        for t_max in [1.0, 0.4] {
            rays.push([k as f32 + 0.1, 0.1, -1.0, t_max]);
            rays.push([0.0, 0.0, 2.0, 0.0]);
        }
    }
    let gpu = common::gpu();
    let answers = trace(&gpu, &flat, &rays, Walk::Single);
    let blocked = answers.iter().filter(|a| a[1] == 1).count();
    assert_eq!(blocked, triangles.len(), "each triangle blocks its own ray");
    let differ: Vec<usize> = (0..answers.len())
        .filter(|&i| answers[i][0] != answers[i][1])
        .collect();
    assert!(differ.is_empty(), "the BVH 300 deep disagrees on rays {differ:?}");
    // Four rays a walk: packet g's rays start at triangle 2g's, those left
    // out aside.
    let answers = trace(&gpu, &flat, &rays, Walk::Packets);
    let differ: Vec<usize> = (0..answers.len())
        .filter(|&i| answers[i][0] != answers[i][1])
        .collect();
    assert!(answers.iter().any(|a| a[1] == 1));
    assert!(
        differ.is_empty(),
        "the four-ray walk 300 deep disagrees on rays {differ:?}"
    );
}
