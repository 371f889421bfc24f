//! CPU mirrors of the WGSL uniform and storage structs of `shaders/common.wgsl`.
//! `#[repr(C)]` + Pod, one named field per quantity (enums and flags as u32);
//! a test checks each size and each field's offset against naga's layout of
//! the WGSL struct so padding mistakes cannot hide.

use bytemuck::{Pod, Zeroable};

/// `Globals`: what the camera pass needs per frame.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct GlobalsRaw {
    /// Eye-relative world position → clip space.
    pub view_proj: [[f32; 4]; 4],
    /// The light's centre relative to the eye (m).
    pub light_rel: [f32; 3],
    /// Sphere light radius R (m); 0 is a point light.
    pub light_radius_m: f32,
    /// The eye (m, world).
    pub eye: [f32; 3],
    /// Light power Φ (W).
    pub light_power_w: f32,
    /// The light's colour (linear RGB factors of Φ).
    pub light_color: [f32; 3],
    /// The BRDF's k where the scene gives none (or scene materials are off).
    pub k: f32,
    /// The colour that replaces every material's, when `use_color_override`.
    pub color_override: [f32; 3],
    /// The Blinn-Phong exponent m where the scene gives none.
    pub m: f32,
    /// settings::DebugView code (`VIEW_*`).
    pub view: u32,
    /// settings::Visibility code (`VISIBILITY_*`): where V comes from.
    pub visibility: u32,
    /// Materials' own k and m are used where they give them (0/1).
    pub use_scene_materials: u32,
    /// `color_override` replaces the materials' colour (0/1).
    pub use_color_override: u32,
    /// N(m) of `m` under the settings' normalization, computed here in f64:
    /// the camera pass reads it instead of evaluating the normalization per
    /// pixel (the materials' own, N(own m), are in their buffer).
    pub norm_factor: f32,
    pub _padding: [u32; 3],
    /// Where the shadow map is drawn from, relative to the eye (m): the
    /// light, or its stand-in for a far light (`light_frustum::shadow_apex`).
    pub shadow_apex_rel: [f32; 3],
    /// The `delta-e` view's fields (see `gpu::delta_e`): exposure (EV)
    /// the colours are compared at.
    pub exposure_ev: f32,
    /// The other colour model's light colour.
    pub other_light_color: [f32; 3],
    /// ΔE is defined: a spectral illuminant is on (0/1).
    pub delta_e_defined: u32,
    /// The other colour model's override colour.
    pub other_color_override: [f32; 3],
    pub _padding_delta_e: u32,
    /// Linear sRGB → XYZ over the illuminant's white (columns, vec4-padded).
    pub lab_white_relative: [[f32; 4]; 3],
}

/// `ShadowLayer`: one frustum of the light.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct ShadowLayerRaw {
    /// Light-relative world direction → light view (looks down −Z).
    pub rotation: [[f32; 4]; 4],
    /// Light view → clip, reversed Z.
    pub proj: [[f32; 4]; 4],
    /// The frustum's extents as tangents (x/z, y/z).
    pub tan_left: f32,
    pub tan_right: f32,
    pub tan_bottom: f32,
    pub tan_top: f32,
    /// Near and far planes (m).
    pub near_m: f32,
    pub far_m: f32,
    /// The stored depth is d = depth_a / z + depth_b (reversed Z).
    pub depth_a: f32,
    pub depth_b: f32,
}

/// `Shadow`: the shadow map's layout and settings.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct ShadowRaw {
    pub layers: [ShadowLayerRaw; 6],
    /// The light's centre (m, world), for the shadow pass.
    pub light_position: [f32; 3],
    /// A shadow map is drawn and tested (0/1); 0 gives V = 1.
    pub enabled: u32,
    /// Six cube faces (1) or one fitted frustum (0).
    pub cube: u32,
    /// Bit i set: layer i was drawn.
    pub layer_mask: u32,
    /// settings::Filter code (`FILTER_*`).
    pub filter_mode: u32,
    /// settings::BiasMode code (`BIAS_*`).
    pub bias_mode: u32,
    /// Kernel size n of `pcf`.
    pub pcf_size: u32,
    /// Samples of `poisson` and of the filtering step of `pcss`.
    pub poisson_samples: u32,
    /// Samples of the blocker search of `pcss`.
    pub pcss_blocker_samples: u32,
    /// Texels per side of every layer.
    pub resolution_texels: u32,
    /// Radius of the `poisson` disc (texels).
    pub poisson_radius_texels: f32,
    /// Constant depth bias D (m) of `constant` and `slope`.
    pub bias_depth_m: f32,
    /// Slope factor S of `slope`.
    pub bias_slope: f32,
    /// Normal offset N (texels) of `normal`.
    pub normal_offset_texels: f32,
    /// The part of Chebyshev's bound cut off by `vsm`/`evsm`.
    pub vsm_bleed_reduction: f32,
    /// The EVSM warp exponent c.
    pub evsm_exponent: f32,
    /// Sphere light radius R (m) for `pcss`.
    pub light_radius_m: f32,
    /// The moment bias α of `msm`.
    pub msm_bias: f32,
    /// Block size B (texels) of the depth ranges `pcf` reads
    /// (gpu::depth_ranges); 0: none are ready for this map.
    pub range_block: u32,
    pub _padding: [u32; 3],
}

/// `Material`: one entry of the materials storage buffer.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct MaterialRaw {
    /// Linear RGB base colour factor, and in w N(own m) under the frame's
    /// normalization (`GpuScene::write_norm_factors`).
    pub base_color: [f32; 4],
    pub words: MaterialWordsRaw,
    /// The base colour under the other colour model (the `delta-e` view).
    pub other_model_color: [f32; 4],
}

/// [`MaterialRaw::words`]: what `Material.words` (a `vec4<u32>`) holds,
/// one load for the vertex stage where six scalars took six.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct MaterialWordsRaw {
    /// The material's own k and m, where its flags say so.
    pub own_k: f32,
    pub own_m: f32,
    /// Base-colour texture layer + 1; 0 is none.
    pub texture_layer_plus_one: u32,
    /// [`MATERIAL_OWN_K`], [`MATERIAL_OWN_M`], [`MATERIAL_DOUBLE_SIDED`],
    /// [`MATERIAL_NO_SHADOWS_RECEIVED`].
    pub flags: u32,
}

/// Flags of [`MaterialWordsRaw::flags`] (the shaders' `MATERIAL_*`, from
/// these: `shaders::shared_u32_constants`):
/// the material has its own k, its own m, both faces shaded; the object
/// drawn with it receives no shadows (`Object::receives_shadows`: its V is 1
/// under every visibility source, as in the reference), set in the second
/// of each material's two slots (`gpu::scene_buffers::Draw::slot`).
pub const MATERIAL_OWN_K: u32 = 1;
pub const MATERIAL_OWN_M: u32 = 2;
pub const MATERIAL_DOUBLE_SIDED: u32 = 4;
pub const MATERIAL_NO_SHADOWS_RECEIVED: u32 = 8;

/// `DisplayParams`: how the display pass shows the view.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct DisplayParamsRaw {
    /// Image size (px).
    pub size_px: [f32; 2],
    /// settings::DebugView code (`VIEW_*`).
    pub view: u32,
    /// A comparison (reference) image is bound (0/1).
    pub has_comparison: u32,
    /// Exposure (EV): the radiance is scaled by 2^EV.
    pub exposure_ev: f32,
    pub _padding: [u32; 1],
}

/// `BlurParams` of `blur.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct BlurParamsRaw {
    /// One texel along the blur's direction: (1, 0) or (0, 1).
    pub step: [i32; 2],
    /// Blur radius (texels).
    pub radius_texels: i32,
    /// The layer blurred.
    pub layer: i32,
}

/// `RangeParams` of `depth_ranges.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct RangeParamsRaw {
    /// Block side B (texels of the depth map).
    pub block_texels: i32,
    /// The layer reduced.
    pub layer: i32,
    pub _padding: [i32; 2],
}

/// Stride of per-layer (per-material) uniforms selected with a dynamic
/// offset: the largest alignment of a dynamic offset any device asks for.
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
