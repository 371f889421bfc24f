//! Bind-group layout entries, named for what they hold.

use wgpu::{BindGroupLayoutEntry as Entry, BindingType, ShaderStages};

pub fn uniform(binding: u32, visibility: ShaderStages) -> Entry {
    Entry {
        binding,
        visibility,
        ty: BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// A uniform selected per draw with a dynamic offset.
pub fn dynamic_uniform(binding: u32, visibility: ShaderStages) -> Entry {
    Entry {
        ty: BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: true,
            min_binding_size: None,
        },
        ..uniform(binding, visibility)
    }
}

pub fn storage(binding: u32, visibility: ShaderStages, read_only: bool) -> Entry {
    Entry {
        ty: BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        ..uniform(binding, visibility)
    }
}

pub fn texture(
    binding: u32,
    visibility: ShaderStages,
    sample_type: wgpu::TextureSampleType,
    view_dimension: wgpu::TextureViewDimension,
) -> Entry {
    Entry {
        ty: BindingType::Texture {
            sample_type,
            view_dimension,
            multisampled: false,
        },
        ..uniform(binding, visibility)
    }
}

/// A float texture read with `textureLoad` only (any float format).
pub fn float_texture(binding: u32, visibility: ShaderStages) -> Entry {
    unfilterable(binding, visibility, wgpu::TextureViewDimension::D2)
}

/// A 2D texture array read with `textureLoad` or a non-filtering sampler.
pub fn float_array(binding: u32, visibility: ShaderStages) -> Entry {
    unfilterable(binding, visibility, wgpu::TextureViewDimension::D2Array)
}

fn unfilterable(binding: u32, visibility: ShaderStages, dimension: wgpu::TextureViewDimension) -> Entry {
    texture(
        binding,
        visibility,
        wgpu::TextureSampleType::Float { filterable: false },
        dimension,
    )
}

pub fn sampler(binding: u32, visibility: ShaderStages, kind: wgpu::SamplerBindingType) -> Entry {
    Entry {
        ty: BindingType::Sampler(kind),
        ..uniform(binding, visibility)
    }
}

/// A bind group whose entries are the given resources at bindings 0, 1, 2…
pub fn group(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    resources: &[wgpu::BindingResource<'_>],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry<'_>> = resources
        .iter()
        .enumerate()
        .map(|(i, r)| wgpu::BindGroupEntry {
            binding: i as u32,
            resource: r.clone(),
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}

/// A buffer of `size` bytes, not mapped at creation.
pub fn buffer(device: &wgpu::Device, label: &str, size: u64, usage: wgpu::BufferUsages) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size,
        usage,
        mapped_at_creation: false,
    })
}

pub fn layout(device: &wgpu::Device, label: &str, entries: &[Entry]) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries,
    })
}

pub fn pipeline_layout(
    device: &wgpu::Device,
    label: &str,
    groups: &[&wgpu::BindGroupLayout],
) -> wgpu::PipelineLayout {
    let groups: Vec<Option<&wgpu::BindGroupLayout>> = groups.iter().map(|g| Some(*g)).collect();
    device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &groups,
        immediate_size: 0,
    })
}

/// A compute pipeline of `module`'s `entry`, its one bind group laid out
/// as `layout`.
pub fn compute_pipeline(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    module: &wgpu::ShaderModule,
    entry: &str,
) -> wgpu::ComputePipeline {
    device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout: Some(&pipeline_layout(device, label, &[layout])),
        module,
        entry_point: Some(entry),
        compilation_options: Default::default(),
        cache: None,
    })
}

/// A pass of [`compute_pipeline`]'s `pipeline` over `workgroups`, with
/// `group` bound.
pub fn compute_pass(
    encoder: &mut wgpu::CommandEncoder,
    label: &str,
    pipeline: &wgpu::ComputePipeline,
    group: &wgpu::BindGroup,
    workgroups: [u32; 3],
) {
    let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
        label: Some(label),
        timestamp_writes: None,
    });
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, group, &[]);
    pass.dispatch_workgroups(workgroups[0], workgroups[1], workgroups[2]);
}

/// A full-screen fragment pipeline (vertex entry `vs`, no vertex buffers),
/// its fragment stage given the override `constants`.
pub fn fullscreen_pipeline(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::PipelineLayout,
    module: &wgpu::ShaderModule,
    fragment_entry: &str,
    constants: &[(&str, f64)],
    format: wgpu::TextureFormat,
) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some("vs"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(fragment_entry),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants,
                ..Default::default()
            },
            targets: &[Some(format.into())],
        }),
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        multiview_mask: None,
        cache: None,
    })
}

/// A pass of [`fullscreen_pipeline`]'s triangle into `target` (cleared
/// first), with `group` bound at a dynamic offset.
pub fn fullscreen_pass(
    encoder: &mut wgpu::CommandEncoder,
    label: &str,
    target: &wgpu::TextureView,
    pipeline: &wgpu::RenderPipeline,
    (group, offset): (&wgpu::BindGroup, u32),
    timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
) {
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[color_attachment(
            target,
            wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
        )],
        depth_stencil_attachment: None,
        timestamp_writes,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, group, &[offset]);
    pass.draw(0..3, 0..1);
}

/// A colour attachment that loads or clears `view` and stores the result.
pub fn color_attachment(
    view: &wgpu::TextureView,
    load: wgpu::LoadOp<wgpu::Color>,
) -> Option<wgpu::RenderPassColorAttachment<'_>> {
    Some(wgpu::RenderPassColorAttachment {
        view,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations {
            load,
            store: wgpu::StoreOp::Store,
        },
    })
}

/// A depth attachment that loads or clears `view` and stores the result.
pub fn depth_attachment(
    view: &wgpu::TextureView,
    load: wgpu::LoadOp<f32>,
) -> Option<wgpu::RenderPassDepthStencilAttachment<'_>> {
    Some(wgpu::RenderPassDepthStencilAttachment {
        view,
        depth_ops: Some(wgpu::Operations {
            load,
            store: wgpu::StoreOp::Store,
        }),
        stencil_ops: None,
    })
}
