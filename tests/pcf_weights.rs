//! PCF's kernel weights summed in closed form (`pcf_weight_sum`, which a
//! single frustum's kernels use for their taps past the map's edge, all
//! lit) equal the weights summed one texel at a time, on the GPU, and the
//! known sums: 1 − f for the first texel, f for the last, 1 between.

mod common;

use bytemuck::{Pod, Zeroable};

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct Case {
    lo: i32,
    hi: i32,
    n: i32,
    f: f32,
}

const KERNEL: &str = r#"
struct Case {
    lo: i32,
    hi: i32,
    n: i32,
    f: f32,
}
// Named by shadow_map.wgsl, pcf.wgsl and disc.wgsl; unused here.
@group(2) @binding(0) var<uniform> shadow: Shadow;

// The closed form, then pcf_weight summed texel by texel.
fn sums(c: Case) -> vec2<f32> {
    var one_by_one = 0.0;
    for (var k = c.lo; k <= c.hi; k++) {
        one_by_one += pcf_weight(k, c.n, c.f);
    }
    return vec2<f32>(pcf_weight_sum(c.lo, c.hi, c.n, c.f), one_by_one);
}
"#;

#[test]
fn kernel_weights_sum_in_closed_form_as_one_by_one() {
    let mut cases = Vec::new();
    for n in [1, 3, 5, 7, 9] {
        for lo in 0..=n {
            // hi = lo − 1: no texel of the row on the map.
            for hi in lo - 1..=n {
                for f in [0.0, 0.25, 0.5, 0.999] {
                    cases.push(Case { lo, hi, n, f });
                }
            }
        }
    }
    let source = format!(
        "{}{}{}{KERNEL}",
        include_str!("../shaders/shadow_map.wgsl"),
        include_str!("../shaders/pcf.wgsl"),
        include_str!("../shaders/disc.wgsl")
    );
    let results: Vec<[f32; 2]> = common::kernel::run(&source, "vec2<f32>", "sums", &cases);
    for (c, [closed, one_by_one]) in cases.iter().zip(results) {
        let known: f64 = (c.lo..=c.hi)
            .map(|k| match k {
                0 => 1.0 - f64::from(c.f),
                k if k == c.n => f64::from(c.f),
                _ => 1.0,
            })
            .sum();
        assert!(
            (f64::from(closed) - known).abs() < 1e-6,
            "{c:?}: closed form {closed}, known {known}"
        );
        assert!(
            (closed - one_by_one).abs() < 1e-6,
            "{c:?}: closed form {closed}, one by one {one_by_one}"
        );
    }
}
