// The range of stored depth values over blocks of the shadow map, for PCF to
// decide a whole kernel with one read where the range leaves no doubt
// (pcf.wgsl, range_verdict). Two passes per layer, each a full-screen
// triangle over the output: `fs_blocks` reduces B×B texels of the depth map
// to (largest, smallest) stored value; `fs_windows` merges blocks e and
// e + 1 along both axes, so window e covers texels B e … B e + 2B − 1 and
// holds every kernel of at most B + 1 texels that starts in block e.
// Stored values are reversed-Z: the largest is the nearest surface, 0 is
// the cleared far plane (nothing drawn).

// gpu::uniforms::RangeParamsRaw.
struct RangeParams {
    // B (texels of the depth map along a block's side).
    block_texels: i32,
    // The layer reduced.
    layer: i32,
}

// The depth map's values (fs_blocks) or the blocks (fs_windows).
@group(0) @binding(0) var source: texture_2d_array<f32>;
// Nearest, clamped to the edge: past the last texel the edge texel repeats,
// which keeps a range true (it only widens).
@group(0) @binding(1) var nearest_clamped: sampler;
@group(0) @binding(2) var<uniform> params: RangeParams;

// Where textureGather reads the 2×2 texels t … t + 1: the corner they share.
fn corner(t: vec2<i32>) -> vec2<f32> {
    return vec2<f32>(t + 1) / vec2<f32>(textureDimensions(source));
}

fn largest(v: vec4<f32>) -> f32 {
    return max(max(v.x, v.y), max(v.z, v.w));
}

fn smallest(v: vec4<f32>) -> f32 {
    return min(min(v.x, v.y), min(v.z, v.w));
}

@fragment
fn fs_blocks(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let b = params.block_texels;
    let first = vec2<i32>(position.xy) * b;
    var high = 0.0;
    var low = 3.0e38;
    for (var j = 0; j < b; j += 2) {
        for (var i = 0; i < b; i += 2) {
            let d = textureGather(0, source, nearest_clamped, corner(first + vec2<i32>(i, j)), params.layer);
            high = max(high, largest(d));
            low = min(low, smallest(d));
        }
    }
    return vec4<f32>(high, low, 0.0, 0.0);
}

@fragment
fn fs_windows(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let at = corner(vec2<i32>(position.xy));
    let high = textureGather(0, source, nearest_clamped, at, params.layer);
    let low = textureGather(1, source, nearest_clamped, at, params.layer);
    return vec4<f32>(largest(high), smallest(low), 0.0, 0.0);
}
