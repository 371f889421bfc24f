//! What a device can do, as the lab uses it: formats, limits, timestamps.

use super::depth_ranges;

/// The near / far ratio of a camera inside the scene: reversed-Z float
/// depth keeps its precision for ratios far beyond 10⁻⁶.
pub const NEAR_RATIO: f64 = 1e-7;

/// The same on GL: wgpu's GL back end maps clip depth to [−1, 1] (z · 2 − w,
/// no clip control), so window depth n/d is computed as (2n/d − 1 + 1) / 2
/// in f32 and keeps only some 6·10⁻⁸ of absolute precision: with 10⁻⁷ the
/// ground's underside, 10 cm below its top, showed through at a close
/// camera. 10⁻⁴ separates surfaces 1 cm apart 20 m away.
pub const NEAR_RATIO_GL: f64 = 1e-4;

/// What this device can do, as the lab uses it.
#[derive(Clone, Debug)]
pub struct Capabilities {
    /// Adapter name and backend, for people.
    pub adapter: String,
    pub max_texture_side: u32,
    /// The camera pass's float targets: Rgba32Float where renderable.
    pub hdr_format: wgpu::TextureFormat,
    /// VSM/EVSM moments: Rgba32Float where renderable and filterable.
    pub moments_format: wgpu::TextureFormat,
    pub timestamps: bool,
    /// Rgba32Float is renderable: the depth ranges PCF and Poisson read
    /// (gpu::depth_ranges) can be built; without, every tap is tested.
    /// On Mesa's GL once it names float colour buffers to wgpu (see
    /// `context::mesa_extension_override`).
    pub depth_ranges: bool,
    /// The GL backend decides a texture's kind from its layer count.
    pub gl: bool,
}

impl Capabilities {
    pub fn of(adapter: &wgpu::Adapter, device: &wgpu::Device) -> Self {
        let renderable = |f: wgpu::TextureFormat| {
            adapter
                .get_texture_format_features(f)
                .allowed_usages
                .contains(wgpu::TextureUsages::RENDER_ATTACHMENT)
        };
        let f32_ok = renderable(wgpu::TextureFormat::Rgba32Float);
        let pick = |ok: bool| {
            if ok {
                wgpu::TextureFormat::Rgba32Float
            } else {
                wgpu::TextureFormat::Rgba16Float
            }
        };
        Self {
            adapter: super::context::describe_adapter(adapter),
            max_texture_side: device.limits().max_texture_dimension_2d,
            hdr_format: pick(f32_ok),
            moments_format: pick(f32_ok && device.features().contains(wgpu::Features::FLOAT32_FILTERABLE)),
            timestamps: device.features().contains(wgpu::Features::TIMESTAMP_QUERY),
            depth_ranges: renderable(depth_ranges::FORMAT),
            gl: adapter.get_info().backend == wgpu::Backend::Gl,
        }
    }

    /// Layers to allocate for a 2D array of `n`: on GL a single layer makes a
    /// plain 2D texture and six square layers a cube map, neither of which
    /// binds as a 2D array, so GL gets one more layer (unused).
    pub fn array_layers(&self, n: u32) -> u32 {
        if self.gl && (n == 1 || n.is_multiple_of(6)) {
            n + 1
        } else {
            n
        }
    }

    /// The smallest near / far ratio of the camera's depth range
    /// ([`super::renderer::camera_depth_range`]).
    pub fn near_ratio(&self) -> f64 {
        if self.gl { NEAR_RATIO_GL } else { NEAR_RATIO }
    }

    /// The EVSM warp exponent the moment format can hold without overflow.
    pub fn evsm_exponent(&self) -> f32 {
        if self.moments_format == wgpu::TextureFormat::Rgba32Float {
            30.0
        } else {
            5.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gl_keeps_a_near_plane_its_depth_arithmetic_can_hold() {
        let mut caps = Capabilities {
            adapter: String::new(),
            max_texture_side: 8192,
            hdr_format: wgpu::TextureFormat::Rgba16Float,
            moments_format: wgpu::TextureFormat::Rgba16Float,
            timestamps: false,
            depth_ranges: false,
            gl: true,
        };
        assert_eq!(caps.near_ratio(), NEAR_RATIO_GL);
        caps.gl = false;
        assert_eq!(caps.near_ratio(), NEAR_RATIO);
    }
}
