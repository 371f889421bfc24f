//! CPU mirrors of the WGSL uniform and storage structs of `shaders/common.wgsl`.
//! `#[repr(C)]` + Pod; a test checks each size against naga's layout of the
//! WGSL struct so padding mistakes cannot hide.

use bytemuck::{Pod, Zeroable};

/// `Globals`: what the camera pass needs per frame.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct GlobalsRaw {
    pub view_proj: [[f32; 4]; 4],
    pub light_rel: [f32; 4],
    pub eye: [f32; 4],
    pub light_color_power: [f32; 4],
    pub material: [f32; 4],
    pub color_override: [f32; 4],
    pub modes: [u32; 4],
    pub viewport: [f32; 4],
}

/// `ShadowLayer`: one frustum of the light.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct ShadowLayerRaw {
    pub rotation: [[f32; 4]; 4],
    pub proj: [[f32; 4]; 4],
    pub tan_bounds: [f32; 4],
    pub depth: [f32; 4],
}

/// `Shadow`: the shadow map's layout and settings.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct ShadowRaw {
    pub layers: [ShadowLayerRaw; 6],
    pub mode: [u32; 4],
    pub counts: [u32; 4],
    pub bias: [f32; 4],
    pub misc: [f32; 4],
    pub light_position: [f32; 4],
}

/// `Material`: one entry of the materials storage buffer.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct MaterialRaw {
    pub base_color: [f32; 4],
    pub params: [f32; 4],
    pub flags: [u32; 4],
}

/// `DisplayParams`: how the display pass shows the view.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct DisplayParamsRaw {
    pub modes: [u32; 4],
    pub values: [f32; 4],
}

/// `BlurParams` of `blur.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct BlurParamsRaw {
    pub step_radius_layer: [i32; 4],
}

/// Stride of per-layer uniforms selected with a dynamic offset.
pub const DYNAMIC_STRIDE: u64 = 256;

/// A uniform buffer holding one `T`, written with `queue.write_buffer`.
pub fn uniform_buffer<T: Pod>(device: &wgpu::Device, label: &str) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: std::mem::size_of::<T>() as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// Column-major f32 array of a matrix.
pub fn mat(m: glam::DMat4) -> [[f32; 4]; 4] {
    m.as_mat4().to_cols_array_2d()
}
