//! The uploaded scene's vertex and index buffers can be bound as storage and
//! read by a compute pass (what a GPU ray-traced visibility needs): a kernel
//! that gathers every triangle corner through the index buffer gives back
//! the scene's own positions. Its BVH for ray-traced visibility comes
//! with the first frame that traces rays, or from a build in the background.

mod common;

use common::*;
use lumlab::gpu::bvh::{FlatBvh, GpuBvh};
use lumlab::gpu::readback::map_and_read;
use lumlab::gpu::scene_buffers::{GpuScene, Vertex};
use lumlab::gpu::{Capabilities, shaders::with_common};

/// corners[i] = the position of the vertex the i-th index names, the
/// object's base vertex added (one dispatch per object).
const KERNEL: &str = r#"
@group(0) @binding(0) var<storage, read> vertices: array<f32>;
@group(0) @binding(1) var<storage, read> indices: array<u32>;
@group(0) @binding(2) var<storage, read_write> corners: array<vec4<f32>>;
// first index, index count, base vertex, words per vertex.
@group(0) @binding(3) var<uniform> draw: vec4<u32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= draw.y {
        return;
    }
    let i = draw.x + id.x;
    let v = (indices[i] + draw.z) * draw.w;
    corners[i] = vec4<f32>(vertices[v], vertices[v + 1u], vertices[v + 2u], 1.0);
}
"#;

#[test]
fn a_compute_pass_reads_the_scene_triangles_from_the_vertex_and_index_buffers() {
    use wgpu::util::DeviceExt;
    let gpu = gpu();
    let device = &gpu.device;
    let scene = occluder_scene(6.0, aabb([-0.5, 0.0, -0.5], [0.5, 1.0, 0.5]));
    let uploaded = GpuScene::new(
        device,
        &gpu.queue,
        &scene,
        &Capabilities::of(&gpu.adapter, device),
    );
    let index_total: u32 = uploaded.draws.iter().map(|d| d.index_count).sum();
    let size = index_total as u64 * 16;
    let corners = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("corners"),
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("corners readback"),
        size,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("gather corners"),
        source: wgpu::ShaderSource::Wgsl(with_common(KERNEL).into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("gather corners"),
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let words_per_vertex = (std::mem::size_of::<Vertex>() / 4) as u32;
    let mut encoder = device.create_command_encoder(&Default::default());
    for d in &uploaded.draws {
        let draw = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("draw"),
            contents: bytemuck::cast_slice(&[
                d.first_index,
                d.index_count,
                d.base_vertex as u32,
                words_per_vertex,
            ]),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("gather corners"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: uploaded.vertices.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: uploaded.indices.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: corners.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: draw.as_entire_binding(),
                },
            ],
        });
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.dispatch_workgroups(d.index_count.div_ceil(64), 1, 1);
    }
    encoder.copy_buffer_to_buffer(&corners, 0, &readback, 0, size);
    gpu.queue.submit([encoder.finish()]);
    let bytes = map_and_read(device, &readback, size as usize, size as usize);
    let got: &[[f32; 4]] = bytemuck::cast_slice(&bytes);

    let expected: Vec<[f32; 4]> = scene
        .objects
        .iter()
        .flat_map(|o| {
            o.mesh
                .indices
                .iter()
                .map(|&i| o.mesh.positions[i as usize].extend(1.0).to_array())
        })
        .collect();
    assert_eq!(expected.len(), index_total as usize);
    assert_eq!(got, expected.as_slice());
}

/// The ray-traced visibility's BVH: an empty stand-in until a frame traces
/// rays; started in the background (as the app does), it arrives without
/// such a frame. Either way it is the scene's, every caster in it.
#[test]
fn the_scenes_bvh_comes_with_a_frame_that_traces_rays_or_from_the_background() {
    let gpu = gpu();
    let device = &gpu.device;
    let scene = occluder_scene(6.0, aabb([-0.5, 0.0, -0.5], [0.5, 1.0, 0.5]));
    let upload = || {
        GpuScene::new(
            device,
            &gpu.queue,
            &scene,
            &Capabilities::of(&gpu.adapter, device),
        )
    };
    let flat = FlatBvh::of_scene(&scene);
    let counts = |bvh: &GpuBvh| (bvh.pair_count, bvh.triangle_count);
    let expected = (flat.pairs().len() as u32, flat.triangles.len() as u32);
    assert!(expected.1 > 0);

    let lazy = upload();
    let (bvh, scene_bvh) = lazy.bvh(device, false, false);
    assert!(!scene_bvh && counts(bvh) == (0, 0), "no frame has traced rays");
    let (bvh, scene_bvh) = lazy.bvh(device, false, true);
    assert!(
        scene_bvh && counts(bvh) == expected,
        "a frame that traces rays builds it"
    );
    assert!(lazy.bvh(device, false, false).1, "and it stays");

    let waited = upload();
    waited.build_bvh_in_background(device);
    let (bvh, scene_bvh) = waited.bvh(device, false, true);
    assert!(
        scene_bvh && counts(bvh) == expected,
        "a frame that traces rays waits for it"
    );

    let background = upload();
    background.build_bvh_in_background(device);
    background.build_bvh_in_background(device);
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    loop {
        let (bvh, scene_bvh) = background.bvh(device, false, false);
        if scene_bvh {
            assert_eq!(counts(bvh), expected);
            break;
        }
        assert!(
            std::time::Instant::now() < deadline,
            "the background build never came"
        );
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    assert!(background.bvh(device, false, true).1, "taken once, kept");
}
