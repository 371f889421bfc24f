// Pass 1: the scene seen from the light, one layer (frustum) at a time.
// Depth only for the depth-test filters; VSM/EVSM/MSM also write depth moments.

@group(0) @binding(0) var<uniform> shadow: Shadow;
// The layer drawn: its slot bound by a dynamic offset (gpu::shadow::ShadowPass::write).
// A uniform lavapipe loads once, where `shadow.layers[i]` at a uniform's i it
// loads lane by lane (the engine's shadow vertex stage −45 %).
@group(0) @binding(1) var<uniform> layer: ShadowLayer;

struct VsOut {
    @builtin(position) clip: vec4<f32>,
    // Depth from the light along its view axis (m).
    @location(0) depth: f32,
}

@vertex
fn vs(@location(0) position: vec3<f32>) -> VsOut {
    let v = (layer.rotation * vec4<f32>(position - shadow.light_position, 0.0)).xyz;
    var out: VsOut;
    out.clip = layer.proj * vec4<f32>(v, 1.0);
    out.depth = -v.z;
    return out;
}

// Moments of the depth normalized to the layer's [near, far]: (u, u²) for
// VSM; for EVSM the moments of exp(c w) and −exp(−c w), w = 2u − 1.
@fragment
fn fs_moments(in: VsOut) -> @location(0) vec4<f32> {
    let u = clamp((in.depth - layer.near_m) / (layer.far_m - layer.near_m), 0.0, 1.0);
    let u2 = u * u;
    let c = shadow.evsm_exponent;
    let w = 2.0 * u - 1.0;
    let pos = exp(c * w);
    let neg = -exp(-c * w);
    // MSM: the first four powers of u (Peters & Klein 2015).
    let msm = vec4<f32>(u, u2, u2 * u, u2 * u2);
    let evsm = vec4<f32>(pos, pos * pos, neg, neg * neg);
    // Selects, not `if`s on the uniform: lavapipe would compile the shader
    // anew for each value (tests/uniform_branches.rs).
    let mode = shadow.filter_mode;
    return select(select(evsm, msm, mode == FILTER_MSM), vec4<f32>(u, u2, 0.0, 0.0), mode == FILTER_VSM);
}
