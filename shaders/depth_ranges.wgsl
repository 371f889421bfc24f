// Bounds on the stored depth values over blocks of the shadow map, for PCF
// to decide a whole kernel with one read where they leave no doubt
// (pcf.wgsl, range_verdict). Two passes per layer, each a full-screen
// triangle over the output: `fs_blocks` bounds B×B texels of the depth map,
// `fs_windows` merges blocks e … e + 1 along both axes, so window e covers
// texels B e … B e + 2B − 1 and holds every kernel of at most B + 1 texels
// that starts in block e.
//
// A bound is a plane and a half-width: vec4(c, gx, gy, h) says that the
// stored value d of every texel (i, j) from the first texel of its block
// or window lies within h of c + gx i + gy j. A surface flat in the map
// has gx = gy = 0 (c ± h is the range of d); a plane of the scene, sloped
// in the light's view, is affine in the texel coordinates (reversed Z
// stores an affine function of 1/z, which is affine on the screen for a
// plane), so its h is only rounding where one surface fills the block.
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
// Nearest, clamped to the edge: past the last texel the edge texel repeats.
// A bound then covers a few texels more than its own, which keeps it true.
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

fn load(t: vec2<i32>) -> f32 {
    let last = vec2<i32>(textureDimensions(source)) - 1;
    return textureLoad(source, clamp(t, vec2<i32>(0), last), params.layer, 0).x;
}

// The plane c + g·p (p from the first texel).
fn plane_at(c: f32, g: vec2<f32>, p: vec2<f32>) -> f32 {
    return c + dot(g, p);
}

// A bound's half-width grown by the rounding of the sums that make and
// read it (relative to the largest stored value it covers).
fn with_rounding(b: vec4<f32>, high: f32) -> vec4<f32> {
    return vec4<f32>(b.xyz, b.w + 1e-6 * high);
}

@fragment
fn fs_blocks(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let b = params.block_texels;
    let first = vec2<i32>(position.xy) * b;
    // The plane through three corners of the block: exact where one plane
    // fills it, a guess whose residuals the loop measures anywhere else.
    let c = load(first);
    let g = vec2<f32>(load(first + vec2<i32>(b - 1, 0)) - c, load(first + vec2<i32>(0, b - 1)) - c) / f32(b - 1);
    var high = 0.0;
    var low = 3.0e38;
    var above = -3.0e38;
    var below = 3.0e38;
    for (var j = 0; j < b; j += 2) {
        for (var i = 0; i < b; i += 2) {
            let d = textureGather(0, source, nearest_clamped, corner(first + vec2<i32>(i, j)), params.layer);
            // The plane at texels (i, j + 1), (i + 1, j + 1), (i + 1, j), (i, j).
            let at = plane_at(c, g, vec2<f32>(f32(i), f32(j)));
            let residual = d - (at + vec4<f32>(g.y, g.x + g.y, g.x, 0.0));
            high = max(high, largest(d));
            low = min(low, smallest(d));
            above = max(above, largest(residual));
            below = min(below, smallest(residual));
        }
    }
    var bound = vec4<f32>(0.5 * (high + low), 0.0, 0.0, 0.5 * (high - low));
    if above - below < high - low {
        bound = vec4<f32>(c + 0.5 * (above + below), g, 0.5 * (above - below));
    }
    return with_rounding(bound, high);
}

// The largest distance between the plane of bound `a` and the plane `c`, g
// over the block of side B whose first texel is at `o` (both planes
// relative to the window's first texel, a's from o): at a corner, as
// their difference is affine.
fn apart(a: vec4<f32>, o: vec2<f32>, c: f32, g: vec2<f32>, side: f32) -> f32 {
    var most = 0.0;
    for (var k = 0; k < 4; k++) {
        let p = vec2<f32>(f32(k & 1), f32(k >> 1u)) * side;
        most = max(most, abs(plane_at(a.x, a.yz, p) - plane_at(c, g, o + p)));
    }
    return most;
}

@fragment
fn fs_windows(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let e = vec2<i32>(position.xy);
    let b = f32(params.block_texels);
    let last = vec2<i32>(textureDimensions(source)) - 1;
    var blocks: array<vec4<f32>, 4>;
    var high = 0.0;
    var low = 3.0e38;
    for (var q = 0; q < 4; q++) {
        let o = vec2<i32>(q & 1, q >> 1u);
        blocks[q] = textureLoad(source, min(e + o, last), params.layer, 0);
        // The block's extreme values, at its corners.
        for (var k = 0; k < 4; k++) {
            let at = plane_at(blocks[q].x, blocks[q].yz, vec2<f32>(f32(k & 1), f32(k >> 1u)) * (b - 1.0));
            high = max(high, at + blocks[q].w);
            low = min(low, at - blocks[q].w);
        }
    }
    // Candidates: the flat range, then each block's plane; the window takes
    // the one that bounds its four blocks closest.
    var best = vec4<f32>(0.5 * (high + low), 0.0, 0.0, 0.5 * (high - low));
    for (var candidate = 0; candidate < 4; candidate++) {
        let start = vec2<f32>(f32(candidate & 1), f32(candidate >> 1u)) * b;
        let own = blocks[candidate];
        // The candidate's plane from the window's first texel.
        let c = own.x - dot(own.yz, start);
        var h = 0.0;
        for (var q = 0; q < 4; q++) {
            let o = vec2<f32>(f32(q & 1), f32(q >> 1u)) * b;
            h = max(h, blocks[q].w + apart(blocks[q], o, c, own.yz, b - 1.0));
        }
        if h < best.w {
            best = vec4<f32>(c, own.yz, h);
        }
    }
    return with_rounding(best, high);
}
