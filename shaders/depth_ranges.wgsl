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

// A bound's half-width grown by the rounding of the sums that make and
// read it (relative to the largest stored value it covers).
fn with_rounding(b: vec4<f32>, high: f32) -> vec4<f32> {
    return vec4<f32>(b.xyz, b.w + 1e-6 * high);
}

// A block's side bounds fs_blocks' loops.
@vertex
fn vs(@builtin(vertex_index) i: u32) -> FullscreenBound {
    return fullscreen_bound(i, params.block_texels);
}

@fragment
fn fs_blocks(in: FullscreenBound) -> @location(0) vec4<f32> {
    let position = in.position;
    let b = in.bound;
    let first = vec2<i32>(position.xy) * b;
    // The plane through the first texel and its neighbours in x and y:
    // exact where one plane fills the block, a guess whose residuals the
    // loop measures anywhere else.
    let start = textureGather(0, source, nearest_clamped, corner(first), params.layer);
    let c = start.w;
    let g = vec2<f32>(start.z - c, start.x - c);
    var high = 0.0;
    var low = 3.0e38;
    var above = -3.0e38;
    var below = 3.0e38;
    // The block's texels 2×2 a gather, k along its rows: one loop, not a
    // loop of rows around a loop of columns (each level costs a software
    // rasterizer its own set-up and exit tests).
    for (var k = vec2<i32>(0); k.y < b; k = select(k + vec2<i32>(2, 0), vec2<i32>(0, k.y + 2), k.x + 2 >= b)) {
        let d = textureGather(0, source, nearest_clamped, corner(first + k), params.layer);
        // The plane at texels k + (0, 1), (1, 1), (1, 0), (0, 0).
        let at = plane_at(c, g, vec2<f32>(k));
        let residual = d - (at + vec4<f32>(g.y, g.x + g.y, g.x, 0.0));
        high = max(high, largest(d));
        low = min(low, smallest(d));
        above = max(above, largest(residual));
        below = min(below, smallest(residual));
    }
    var bound = vec4<f32>(0.5 * (high + low), 0.0, 0.0, 0.5 * (high - low));
    if above - below < high - low {
        bound = vec4<f32>(c + 0.5 * (above + below), g, 0.5 * (above - below));
    }
    return with_rounding(bound, high);
}

// How far the stored values of a block, bound b with its first texel at o
// (from the window's first texel), can lie from the plane c, g: b's
// half-width and the planes' largest gap over the block, at a corner, as
// their difference is affine.
fn block_gap(b: vec4<f32>, o: vec2<f32>, c: f32, g: vec2<f32>, side: f32) -> f32 {
    let gap = abs(plane_corners(b.x, b.yz, vec2<f32>(0.0), side) - plane_corners(c, g, o, side));
    return b.w + largest(gap);
}

// The bound of plane c, g over the four blocks of a window (columns of m,
// the blocks at (0, 0), (1, 0), (0, 1), (1, 1)), B texels a side.
fn window_bound(c: f32, g: vec2<f32>, m: mat4x4<f32>, b: f32) -> vec4<f32> {
    let s = b - 1.0;
    let h = max(
        max(block_gap(m[0], vec2<f32>(0.0, 0.0), c, g, s), block_gap(m[1], vec2<f32>(b, 0.0), c, g, s)),
        max(block_gap(m[2], vec2<f32>(0.0, b), c, g, s), block_gap(m[3], vec2<f32>(b, b), c, g, s)),
    );
    return vec4<f32>(c, g, h);
}

@fragment
fn fs_windows(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let e = vec2<i32>(position.xy);
    let b = f32(params.block_texels);
    // The four blocks a component at a time (textureGather's order: blocks
    // (0, 1), (1, 1), (1, 0), (0, 0)); four gathers cost lavapipe less
    // than four loads.
    let at = corner(e);
    let xs = textureGather(0, source, nearest_clamped, at, params.layer);
    let ys = textureGather(1, source, nearest_clamped, at, params.layer);
    let zs = textureGather(2, source, nearest_clamped, at, params.layer);
    let ws = textureGather(3, source, nearest_clamped, at, params.layer);
    let m = mat4x4<f32>(
        vec4<f32>(xs.w, ys.w, zs.w, ws.w),
        vec4<f32>(xs.z, ys.z, zs.z, ws.z),
        vec4<f32>(xs.x, ys.x, zs.x, ws.x),
        vec4<f32>(xs.y, ys.y, zs.y, ws.y),
    );
    // The blocks' extreme values, at their corners.
    let s = b - 1.0;
    let zero = vec2<f32>(0.0);
    let c0 = plane_corners(m[0].x, m[0].yz, zero, s);
    let c1 = plane_corners(m[1].x, m[1].yz, zero, s);
    let c2 = plane_corners(m[2].x, m[2].yz, zero, s);
    let c3 = plane_corners(m[3].x, m[3].yz, zero, s);
    let highs = max(max(c0 + m[0].w, c1 + m[1].w), max(c2 + m[2].w, c3 + m[3].w));
    let lows = min(min(c0 - m[0].w, c1 - m[1].w), min(c2 - m[2].w, c3 - m[3].w));
    let high = largest(highs);
    let low = smallest(lows);
    // The flat range or the first block's plane, whichever bounds the four
    // blocks closer. Where one plane fills the window every block has it;
    // where it does not, a block off the plane widens any block's plane
    // about alike (trying all four's cost the pass two thirds of the build).
    let flat = vec4<f32>(0.5 * (high + low), 0.0, 0.0, 0.5 * (high - low));
    let first = window_bound(m[0].x, m[0].yz, m, b);
    return with_rounding(select(flat, first, first.w < flat.w), high);
}
