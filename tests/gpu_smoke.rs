//! The GPU path works on this machine: an adapter (a software one on CI),
//! a triangle drawn offscreen, read back, with known pixel values. No adapter
//! is a failure with a message saying what to install, never a skip.

use lumlab::gpu::{GpuContext, readback};

const SHADER: &str = r#"
@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    // A triangle covering the left half of the target's centre row.
    var p = array<vec2<f32>, 3>(vec2(-1.0, -1.0), vec2(0.0, 1.0), vec2(-1.0, 1.0));
    return vec4<f32>(p[i], 0.0, 1.0);
}
@fragment
fn fs() -> @location(0) vec4<f32> {
    return vec4<f32>(1.0, 0.25, 0.0, 1.0);
}
"#;

#[test]
fn triangle_renders_and_reads_back() {
    let gpu = GpuContext::headless().unwrap_or_else(|e| panic!("GPU smoke test: {e}"));
    eprintln!("adapter: {}", gpu.describe());
    let (device, queue) = (&gpu.device, &gpu.queue);
    let size = 64;
    let target = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("smoke target"),
        size: wgpu::Extent3d {
            width: size,
            height: size,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("smoke shader"),
        source: wgpu::ShaderSource::Wgsl(SHADER.into()),
    });
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("smoke pipeline"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs"),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::TextureFormat::Rgba8Unorm.into())],
        }),
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        multiview_mask: None,
        cache: None,
    });
    let view = target.create_view(&Default::default());
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("smoke pass"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            ..Default::default()
        });
        pass.set_pipeline(&pipeline);
        pass.draw(0..3, 0..1);
    }
    queue.submit([encoder.finish()]);
    let pixels = readback::read_texture(device, queue, &target, 0, 4);
    let at = |x: u32, y: u32| &pixels[((y * size + x) * 4) as usize..][..4];
    // Inside the triangle (top-left), outside it (bottom-right).
    assert_eq!(at(4, 4), &[255, 64, 0, 255]);
    assert_eq!(at(60, 60), &[0, 0, 0, 255]);
}
