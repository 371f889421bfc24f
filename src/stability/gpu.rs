//! The GPU column: `shaders/stability.wgsl` evaluates every case with the
//! functions of `common.wgsl` the renderer calls, and the values are read back.

use super::eval::DepthPipeline;
use super::{Case, Input, Quantity};
use crate::gpu::GpuContext;
use crate::gpu::binding;
use crate::gpu::readback::map_and_read;
use crate::gpu::shaders::Shader;
use wgpu::util::DeviceExt;

/// Invocations per workgroup (`@workgroup_size` in stability.wgsl).
const WORKGROUP_SIZE: u32 = 64;

/// `Case` of stability.wgsl: one hard case's rounded inputs.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CaseRaw {
    /// x: the quantity (its index in `Quantity::ALL`), y: the normalization.
    pub kind: [u32; 4],
    pub a: [f32; 4],
    pub b: [f32; 4],
    pub c: [f32; 4],
}

impl CaseRaw {
    /// The inputs where stability.wgsl's `main` reads them.
    pub fn new(case: &Case) -> Self {
        let kind = Quantity::ALL
            .iter()
            .position(|&q| q == case.quantity)
            .unwrap_or_default() as u32;
        let mut raw = Self {
            kind: [kind, 0, 0, 0],
            ..Self::default()
        };
        match case.input {
            Input::Norm { m, norm } => {
                raw.kind[1] = norm_index(norm);
                raw.a[0] = m;
            }
            Input::Lobe { cos_theta, gap, m } => raw.a = [cos_theta, gap, m, 0.0],
            Input::Brdf { n, l, o, k, m, norm } => {
                raw.kind[1] = norm_index(norm);
                raw.a = n.extend(k).to_array();
                raw.b = l.extend(m).to_array();
                raw.c = o.extend(0.0).to_array();
            }
            Input::Irradiance { p, n, q, power_w } => {
                raw.a = p.extend(power_w).to_array();
                raw.b = n.extend(0.0).to_array();
                raw.c = q.extend(0.0).to_array();
            }
            Input::Sphere {
                power_w,
                radius_m,
                cos_theta,
                r_m,
            } => raw.a = [power_w, radius_m, cos_theta, r_m],
            Input::Depth { near_m, far_m, z_m } => {
                raw.depth(near_m, far_m);
                raw.b[2] = z_m;
            }
            Input::Shadow {
                near_m,
                far_m,
                caster_m,
                receiver_m,
            } => {
                raw.depth(near_m, far_m);
                raw.b[2] = caster_m;
                raw.b[3] = receiver_m;
            }
        }
        raw
    }

    /// a: the projection's z and w rows on the axis; b.xy: linear_depth's (a, b).
    fn depth(&mut self, near_m: f64, far_m: f64) {
        let d = DepthPipeline::<f32>::reversed(near_m, far_m);
        self.a = [d.zz, d.zw, d.wz, d.ww];
        self.b[0] = d.a;
        self.b[1] = d.b;
    }
}

/// norm_factor's switch follows `Normalization::ALL` (tests/shaders.rs).
fn norm_index(norm: crate::physics::Normalization) -> u32 {
    crate::physics::Normalization::ALL
        .iter()
        .position(|&n| n == norm)
        .unwrap_or_default() as u32
}

/// Every case's value computed by stability.wgsl on the context's device.
pub fn evaluate_on_gpu(gpu: &GpuContext, cases: &[Case]) -> Vec<f32> {
    if cases.is_empty() {
        return Vec::new();
    }
    let device = &gpu.device;
    let raw: Vec<CaseRaw> = cases.iter().map(CaseRaw::new).collect();
    let inputs = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("stability cases"),
        contents: bytemuck::cast_slice(&raw),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let size = (cases.len() * std::mem::size_of::<f32>()) as u64;
    let values = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("stability values"),
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("stability readback"),
        size,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let compute = wgpu::ShaderStages::COMPUTE;
    let layout = binding::layout(
        device,
        "stability",
        &[
            binding::storage(0, compute, true),
            binding::storage(1, compute, false),
        ],
    );
    let module = Shader::Stability.module(device);
    let pipeline = binding::compute_pipeline(device, "stability", &layout, &module, "main");
    let group = binding::group(
        device,
        "stability",
        &layout,
        &[inputs.as_entire_binding(), values.as_entire_binding()],
    );
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("stability"),
    });
    let workgroups = [(cases.len() as u32).div_ceil(WORKGROUP_SIZE), 1, 1];
    binding::compute_pass(&mut encoder, "stability", &pipeline, &group, workgroups);
    encoder.copy_buffer_to_buffer(&values, 0, &readback, 0, size);
    gpu.queue.submit([encoder.finish()]);
    let bytes = map_and_read(device, &readback, size as usize, size as usize);
    bytemuck::pod_collect_to_vec(&bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stability_source() -> String {
        Shader::Stability.source()
    }

    #[test]
    fn case_raw_matches_its_wgsl_size() {
        let module = naga::front::wgsl::parse_str(&stability_source()).expect("stability.wgsl parses");
        let span = module
            .types
            .iter()
            .find_map(|(_, t)| match (&t.name, &t.inner) {
                (Some(name), naga::TypeInner::Struct { span, .. }) if name == "Case" => Some(*span),
                _ => None,
            })
            .expect("struct Case");
        assert_eq!(span as usize, std::mem::size_of::<CaseRaw>());
    }

    #[test]
    fn case_kinds_follow_the_quantities() {
        let source = stability_source();
        for (i, q) in Quantity::ALL.iter().enumerate() {
            let wanted = format!("const CASE_{}: u32 = {i}u;", q.name().to_uppercase());
            assert!(source.contains(&wanted), "no `{wanted}` in stability.wgsl");
        }
    }
}
