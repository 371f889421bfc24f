//! The GPU ray tracer's BVH traversal against what it must equal: one ray
//! or four a walk against testing every triangle, in a compute kernel, on
//! random segments and on a degenerate tree deeper than its stack; its
//! structs against their WGSL layout.

mod common;

use glam::{Vec3, Vec4};
use lumlab::gpu::GpuContext;
use lumlab::gpu::bvh::{BvhGridRaw, BvhNodeRaw, BvhPairRaw, BvhTriangleRaw, FlatBvh, GpuBvh};
use lumlab::gpu::raytrace::RayTraceRaw;
use lumlab::gpu::shaders::Shader;
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
    answers[i] = vec2<u32>(select(0u, 1u, bvh_occluded(o, d, t_max, counts.n.y, counts.grid)), brute);
}

// The same for the packet walks: packet g holds rays WIDTH·g … WIDTH·g +
// WIDTH − 1 (bvh_occluded8, `eight` where WIDTH is 8), from the origin and
// with the t_max of the first, each along its own direction; ray j is left
// out where (g + j) % 5 == 0 (its brute-force answer 0).
override WIDTH: u32 = 4u;

fn packet_rays(first: u32) -> BvhRays4 {
    return BvhRays4(rays[first + 1u].xyz, rays[first + 3u].xyz, rays[first + 5u].xyz, rays[first + 7u].xyz);
}

fn packet_live(g: u32, j: u32) -> vec4<bool> {
    return (vec4<u32>(g + j) + vec4<u32>(0u, 1u, 2u, 3u)) % 5u != vec4<u32>(0u);
}

@compute @workgroup_size(64)
fn packets(@builtin(global_invocation_id) id: vec3<u32>) {
    let g = id.x;
    if WIDTH * g >= counts.n.x {
        return;
    }
    let first = 2u * WIDTH * g;
    let o = rays[first].xyz;
    let t_max = rays[first].w;
    let eight = WIDTH == 8u;
    var d = array<BvhRays4, 2>(packet_rays(first), packet_rays(first));
    if eight {
        d[1] = packet_rays(first + 8u);
    }
    let walked = bvh_occluded8(o, d[0], d[1], t_max, packet_live(g, 0u), packet_live(g, 4u), eight, counts.n.y, counts.grid);
    let answers_walked = array<vec4<bool>, 2>(walked.lo, walked.hi);
    for (var j = 0u; j < WIDTH; j++) {
        let live = packet_live(g, j).x;
        var brute = 0u;
        for (var t = 0u; t < counts.n.z; t++) {
            if live && bvh_hits_triangle(bvh_triangles[t], o, d[j / 4u][j % 4u], t_max) {
                brute = 1u;
            }
        }
        answers[WIDTH * g + j] = vec2<u32>(select(0u, 1u, answers_walked[j / 4u][j % 4u]), brute);
    }
}";

/// The walks a test runs: one ray an invocation, or four or eight
/// (`packets`).
#[derive(Clone, Copy, Debug)]
enum Walk {
    Single,
    Packets(u32),
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
            Walk::Packets(_) => "packets",
        }),
        compilation_options: wgpu::PipelineCompilationOptions {
            constants: &match walk {
                Walk::Single => vec![],
                Walk::Packets(width) => vec![("WIDTH", f64::from(width))],
            },
            ..Default::default()
        },
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
            Walk::Packets(width) => {
                assert_eq!(n % width as usize, 0, "whole packets");
                n / width as usize
            }
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

/// The rays whose walk and brute force answer differently.
fn disagreeing(answers: &[[u32; 2]]) -> Vec<usize> {
    (0..answers.len())
        .filter(|&i| answers[i][0] != answers[i][1])
        .collect()
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
    let differ = disagreeing(&answers);
    assert!(differ.is_empty(), "the BVH disagrees on rays {differ:?}");
}

/// Four or eight rays from one point in one walk, as a sphere light's rays
/// are traced: each answer is what testing every triangle answers, whether
/// the rays diverge (random directions) or nearly coincide (towards a ball
/// of 5 cm; an eight-ray packet holds four of each), some of them left out.
#[test]
fn packet_walks_answer_what_testing_every_triangle_answers() {
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
    for width in [4, 8] {
        let answers = trace(&gpu, &flat, &rays, Walk::Packets(width));
        let blocked = answers.iter().filter(|a| a[1] == 1).count();
        assert!(
            blocked > 400 && blocked < 3000,
            "{blocked} of 4096 blocked: the rays do not test much"
        );
        let differ = disagreeing(&answers);
        assert!(
            differ.is_empty(),
            "the {width}-ray walk disagrees on rays {differ:?}"
        );
    }
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
    let differ = disagreeing(&answers);
    assert!(differ.is_empty(), "the BVH 300 deep disagrees on rays {differ:?}");
    // Four or eight rays a walk: packet g's rays start at its first ray's
    // triangle, those left out aside.
    for width in [4, 8] {
        let answers = trace(&gpu, &flat, &rays, Walk::Packets(width));
        let differ = disagreeing(&answers);
        assert!(answers.iter().any(|a| a[1] == 1));
        assert!(
            differ.is_empty(),
            "the {width}-ray walk 300 deep disagrees on rays {differ:?}"
        );
    }
}
