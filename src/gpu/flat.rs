//! A minimal flat-colour pass over the camera pass's geometry and targets:
//! the same vertices, depth test and image size, one constant colour per
//! fragment. It is the floor the camera pass's cost is judged against
//! (benches/frame_cost.rs, `Renderer::minimal_pass_ms`); nothing draws it
//! in a frame.

use super::binding;
use super::readback::map_and_read;
use super::scene_buffers::{GpuScene, Vertex};
use super::shaders::with_common;
use super::specialise::camera_depth_test;
use std::time::Instant;

const FLAT_WGSL: &str = "
@group(0) @binding(0) var<uniform> globals: Globals;

@vertex
fn vs(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return globals.view_proj * vec4<f32>(position - globals.eye, 1.0);
}

@fragment
fn fs() -> @location(0) vec4<f32> {
    return vec4<f32>(0.5, 0.5, 0.5, 1.0);
}
";

/// Where the flat pass draws: the frame's quantity and depth targets.
pub(super) struct FlatTargets<'a> {
    pub(super) color: &'a wgpu::TextureView,
    pub(super) format: wgpu::TextureFormat,
    pub(super) depth: &'a wgpu::TextureView,
}

/// Draws every object of `scene` flat, waits, and returns the pass's GPU
/// time (ms) from timestamps, or the wall time around submit + wait on
/// adapters without them.
pub(super) fn time_flat_pass(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    scene: &GpuScene,
    globals: &wgpu::Buffer,
    targets: &FlatTargets<'_>,
) -> f64 {
    let layout = binding::layout(
        device,
        "flat pass",
        &[binding::uniform(0, wgpu::ShaderStages::VERTEX)],
    );
    let group = binding::group(device, "flat pass", &layout, &[globals.as_entire_binding()]);
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("flat pass"),
        source: wgpu::ShaderSource::Wgsl(with_common(FLAT_WGSL).into()),
    });
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("flat pass"),
        layout: Some(&binding::pipeline_layout(device, "flat pass", &[&layout])),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs"),
            compilation_options: Default::default(),
            buffers: &[Some(Vertex::layout())],
        },
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs"),
            compilation_options: Default::default(),
            targets: &[Some(targets.format.into())],
        }),
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: Some(camera_depth_test()),
        multisample: Default::default(),
        multiview_mask: None,
        cache: None,
    });
    let queries = device
        .features()
        .contains(wgpu::Features::TIMESTAMP_QUERY)
        .then(|| {
            device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("flat pass timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            })
        });
    use wgpu::BufferUsages as U;
    let resolve = binding::buffer(device, "flat pass resolve", 16, U::QUERY_RESOLVE | U::COPY_SRC);
    let readback = binding::buffer(device, "flat pass readback", 16, U::MAP_READ | U::COPY_DST);
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("flat pass"),
            color_attachments: &[binding::color_attachment(
                targets.color,
                wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
            )],
            depth_stencil_attachment: binding::depth_attachment(targets.depth, wgpu::LoadOp::Clear(0.0)),
            timestamp_writes: queries.as_ref().map(|q| wgpu::RenderPassTimestampWrites {
                query_set: q,
                beginning_of_pass_write_index: Some(0),
                end_of_pass_write_index: Some(1),
            }),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group, &[]);
        let meshes = scene.meshes(false);
        meshes.bind(&mut pass);
        for object in 0..scene.bounds.len() {
            meshes.draw(&mut pass, object);
        }
    }
    if let Some(q) = &queries {
        encoder.resolve_query_set(q, 0..2, &resolve, 0);
        encoder.copy_buffer_to_buffer(&resolve, 0, &readback, 0, 16);
    }
    let start = Instant::now();
    queue.submit([encoder.finish()]);
    let _ = device.poll(wgpu::PollType::wait_indefinitely());
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    if queries.is_none() {
        return wall_ms;
    }
    let bytes = map_and_read(device, &readback, 16, 16);
    let tick = |i: usize| u64::from_le_bytes(bytes[8 * i..8 * i + 8].try_into().unwrap_or([0; 8]));
    tick(1).saturating_sub(tick(0)) as f64 * queue.get_timestamp_period() as f64 / 1e6
}
