//! The light's frustum drawn over the displayed image (the `frustum` view):
//! edges behind geometry dim, edges in front bright.

use super::binding;
use super::display::DISPLAY_FORMAT;
use super::light_frustum::ShadowLayout;
use super::shaders::Shader;
use super::shadow::DEPTH_FORMAT;
use bytemuck::{Pod, Zeroable};
use glam::DVec3;
use wgpu::ShaderStages;

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct LineVertex {
    /// Position relative to the eye (m).
    pub rel: [f32; 3],
    pub color: [f32; 4],
}

/// Vertices the overlay holds at most: six frusta of twelve edges and a light marker.
const CAPACITY: u64 = 6 * 24 + 6;

/// Edge colour of drawn layers (linear RGB) and of skipped cube faces.
const ACTIVE: [f32; 4] = [1.0, 0.75, 0.1, 1.0];
const SKIPPED: [f32; 4] = [0.35, 0.35, 0.45, 1.0];

pub struct FrustumOverlay {
    vertices: wgpu::Buffer,
    count: u32,
    group: wgpu::BindGroup,
    visible: wgpu::RenderPipeline,
    hidden: wgpu::RenderPipeline,
}

impl FrustumOverlay {
    pub fn new(device: &wgpu::Device, globals: &wgpu::Buffer) -> Self {
        let layout = binding::layout(
            device,
            "frustum overlay",
            &[binding::uniform(0, ShaderStages::VERTEX)],
        );
        let pipeline_layout = binding::pipeline_layout(device, "frustum overlay", &[&layout]);
        let module = Shader::Lines.module(device);
        let attributes = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x4];
        let pipeline = |entry: &str, compare| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(entry),
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs"),
                    compilation_options: Default::default(),
                    buffers: &[Some(wgpu::VertexBufferLayout {
                        array_stride: std::mem::size_of::<LineVertex>() as u64,
                        step_mode: wgpu::VertexStepMode::Vertex,
                        attributes: &attributes,
                    })],
                },
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    targets: &[Some(DISPLAY_FORMAT.into())],
                }),
                primitive: wgpu::PrimitiveState {
                    topology: wgpu::PrimitiveTopology::LineList,
                    ..Default::default()
                },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: DEPTH_FORMAT,
                    depth_write_enabled: Some(false),
                    depth_compare: Some(compare),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: Default::default(),
                multiview_mask: None,
                cache: None,
            })
        };
        Self {
            vertices: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("frustum overlay"),
                size: CAPACITY * std::mem::size_of::<LineVertex>() as u64,
                usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            count: 0,
            group: binding::group(device, "frustum overlay", &layout, &[globals.as_entire_binding()]),
            // Reversed Z: in front is greater.
            visible: pipeline("fs_visible", wgpu::CompareFunction::GreaterEqual),
            hidden: pipeline("fs_hidden", wgpu::CompareFunction::Less),
        }
    }

    /// The frusta's edges and a marker at the light, relative to `eye`.
    pub fn update(&mut self, queue: &wgpu::Queue, layout: &ShadowLayout, eye: DVec3) {
        let mut vertices = Vec::new();
        let mut line = |a: DVec3, b: DVec3, color: [f32; 4]| {
            for p in [a, b] {
                vertices.push(LineVertex {
                    rel: (p - eye).as_vec3().to_array(),
                    color,
                });
            }
        };
        for layer in &layout.layers {
            let c = layer.frustum.corners();
            let color = if layer.active { ACTIVE } else { SKIPPED };
            for i in 0..4 {
                line(c[i], c[(i + 1) % 4], color);
                line(c[4 + i], c[4 + (i + 1) % 4], color);
                line(c[i], c[4 + i], color);
            }
        }
        if let Some(layer) = layout.layers.first() {
            let light = layer.frustum.apex;
            let size = 0.02 * (layer.frustum.far - layer.frustum.near).max(1e-6);
            for axis in [DVec3::X, DVec3::Y, DVec3::Z] {
                line(light - axis * size, light + axis * size, [1.0, 1.0, 1.0, 1.0]);
            }
        }
        vertices.truncate(CAPACITY as usize);
        self.count = vertices.len() as u32;
        queue.write_buffer(&self.vertices, 0, bytemuck::cast_slice(&vertices));
    }

    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        depth: &wgpu::TextureView,
    ) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("frustum overlay"),
            color_attachments: &[binding::color_attachment(target, wgpu::LoadOp::Load)],
            depth_stencil_attachment: binding::depth_attachment(depth, wgpu::LoadOp::Load),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(0, &self.group, &[]);
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        for pipeline in [&self.hidden, &self.visible] {
            pass.set_pipeline(pipeline);
            pass.draw(0..self.count, 0..1);
        }
    }
}
