// A separable Gaussian blur of one layer of the moment map (VSM/EVSM): run
// once along x into a scratch layer, once along y back.

// gpu::uniforms::BlurParamsRaw.
struct BlurParams {
    // One texel along the blur's direction: (1, 0) or (0, 1).
    step: vec2<i32>,
    radius_texels: i32,
    // The layer blurred.
    layer: i32,
}

@group(0) @binding(0) var source: texture_2d_array<f32>;
@group(0) @binding(1) var<uniform> params: BlurParams;

// The kernel's radius bounds the loop below.
@vertex
fn vs(@builtin(vertex_index) i: u32) -> FullscreenBound {
    return fullscreen_bound(i, params.radius_texels);
}

@fragment
fn fs(in: FullscreenBound) -> @location(0) vec4<f32> {
    let position = in.position;
    let step = params.step;
    let radius = in.bound;
    let layer = params.layer;
    let size = vec2<i32>(textureDimensions(source));
    let centre = vec2<i32>(position.xy);
    // σ = radius / 2: the kernel ends at two standard deviations.
    let sigma = max(f32(radius) * 0.5, 0.5);
    var sum = vec4<f32>(0.0);
    var weights = 0.0;
    for (var i = -radius; i <= radius; i++) {
        let texel = clamp(centre + step * i, vec2<i32>(0), size - 1);
        let w = exp(-0.5 * f32(i * i) / (sigma * sigma));
        sum += w * textureLoad(source, texel, layer, 0);
        weights += w;
    }
    return sum / weights;
}
