// The shadow map as a source of visibility V for the camera pass: where a
// receiver falls in the map, its bias, and the filters that turn depth tests
// into V ∈ [0, 1]. shade.wgsl asks `shadow_map_visibility` when the
// visibility method is the shadow map; nothing here knows the BRDF.

@group(1) @binding(0) var shadow_depth: texture_depth_2d_array;
@group(1) @binding(1) var shadow_compare: sampler_comparison;
@group(1) @binding(2) var moments: texture_2d_array<f32>;
@group(1) @binding(3) var moments_sampler: sampler;
// The same depth texture read as plain floats: GLSL cannot textureLoad a
// depth texture, so the software filters read it through this binding.
@group(1) @binding(4) var shadow_depth_values: texture_2d_array<f32>;
// Nearest, clamped to the edge: PCF gathers four stored values at a time.
@group(1) @binding(5) var shadow_depth_gather: sampler;

// The uniforms that decide branches and loop exits in the camera pass,
// read per pixel: shade.wgsl's vertex stage copies them into flat varyings,
// its fragment stage into `knobs`. lavapipe (Mesa 22.3) folds a uniform that
// alone decides a branch into the shader each time the pipeline is bound,
// and compiles the result anew whenever its value changed: a dragged light
// or slider compiled a shader every frame (tests/uniform_branches.rs).
struct Knobs {
    // Shadow's pcf_size, range_block, pcss_blocker_samples, poisson_samples.
    filters: vec4<u32>,
    // RayTrace's rays, first_sample and pair_count, Globals' delta_e_defined.
    rays: vec4<u32>,
    // The light's radius (m): Globals' light_radius_m (Shadow holds the same).
    radius_m: f32,
}
var<private> knobs: Knobs;

// The filter a specialised pipeline is compiled for (FILTER_*), or
// SPECIALISE_ANY to read shadow.filter_mode (see shade.wgsl).
override SPECIALISED_FILTER: u32 = SPECIALISE_ANY;

fn filter_mode() -> u32 {
    return select(SPECIALISED_FILTER, shadow.filter_mode, SPECIALISED_FILTER == SPECIALISE_ANY);
}

// The bias mode (BIAS_*) and the map's layout (0: one frustum, 1: six cube
// faces) a pipeline is compiled for, or SPECIALISE_ANY to read the uniform.
// A software rasterizer runs every case of a switch on a uniform, and a
// filter's every tap paid for all four biases and for the cube faces'
// addressing; specialised, a single-frustum map's taps keep none of it.
override SPECIALISED_BIAS: u32 = SPECIALISE_ANY;
override SPECIALISED_CUBE: u32 = SPECIALISE_ANY;

fn bias_mode() -> u32 {
    return select(SPECIALISED_BIAS, shadow.bias_mode, SPECIALISED_BIAS == SPECIALISE_ANY);
}

fn is_cube() -> bool {
    return select(SPECIALISED_CUBE, shadow.cube, SPECIALISED_CUBE == SPECIALISE_ANY) != 0u;
}

// Where a receiver falls in the shadow map.
struct Receiver {
    layer: u32,
    // Light-view position (m); the view looks down −Z.
    v: vec3<f32>,
    // Depth from the light along its view axis (m).
    z: f32,
    // Continuous texel coordinates (texel centres at i + 0.5).
    tc: vec2<f32>,
    // The normal in light view.
    n_v: vec3<f32>,
    // World size of one texel at the receiver's depth (m).
    texel_m: f32,
    // tan of the angle between n and l, clamped to the steepest slope handled.
    tan_theta: f32,
}

fn choose_layer(p_l: vec3<f32>) -> u32 {
    if !is_cube() {
        return 0u;
    }
    // Cube faces in the order +X, −X, +Y, −Y, +Z, −Z.
    let a = abs(p_l);
    if a.x >= a.y && a.x >= a.z {
        return select(1u, 0u, p_l.x > 0.0);
    }
    if a.y >= a.z {
        return select(3u, 2u, p_l.y > 0.0);
    }
    return select(5u, 4u, p_l.z > 0.0);
}

fn resolution() -> f32 {
    return f32(shadow.resolution_texels);
}

// The layers of a map share their tangents, near and far planes and depth
// conversion (a single frustum is one layer, and the cube's faces are alike:
// gpu::light_frustum), so they are read from layer 0, the same for every
// pixel. Read from a cube face that changes from pixel to pixel, each field
// is loaded lane by lane by a software rasterizer.
fn frustum() -> ShadowLayer {
    return shadow.layers[0];
}

// A light-relative direction d in the view of `layer` (looking down −Z).
// The cube's faces look along ±X, ±Y, ±Z (scene::camera::look_frame: up +Y,
// or +Z for the ±Y faces), so their rotations only permute and negate
// coordinates: written out, the same values as the matrix product, without
// loading a face's matrix lane by lane.
fn to_view(d: vec3<f32>, layer: u32) -> vec3<f32> {
    if !is_cube() {
        return (shadow.layers[0].rotation * vec4<f32>(d, 0.0)).xyz;
    }
    let axis = layer / 2u;
    let s = select(1.0, -1.0, (layer & 1u) == 1u);
    // +X (z, y, −x), −X (−z, y, x), +Y (x, z, −y), −Y (−x, z, y), +Z (−x, y, −z), −Z (x, y, z).
    let x = select(select(-s * d.x, s * d.x, axis == 1u), s * d.z, axis == 0u);
    let y = select(d.y, d.z, axis == 1u);
    let z = -s * select(select(d.z, d.y, axis == 1u), d.x, axis == 0u);
    return vec3<f32>(x, y, z);
}

// The inverse of to_view: a direction v in the view of `layer` relative to
// the light. The cube's faces undo their permutation and signs (the same
// values as v · M for the face's rotation M, its transpose).
fn from_view(v: vec3<f32>, layer: u32) -> vec3<f32> {
    if !is_cube() {
        return (vec4<f32>(v, 0.0) * shadow.layers[0].rotation).xyz;
    }
    let axis = layer / 2u;
    let s = select(1.0, -1.0, (layer & 1u) == 1u);
    // +X (−z, y, x), −X (z, y, −x), +Y (x, −z, y), −Y (−x, z, y), +Z (−x, y, −z), −Z (x, y, z).
    let x = select(select(-s * v.x, s * v.x, axis == 1u), -s * v.z, axis == 0u);
    let y = select(v.y, -s * v.z, axis == 1u);
    let z = select(select(-s * v.z, v.y, axis == 1u), s * v.x, axis == 0u);
    return vec3<f32>(x, y, z);
}

// Texel coordinates of the direction with tangents t (on any layer).
fn texel_of_tangent(t: vec2<f32>) -> vec2<f32> {
    let f = frustum();
    let uv = vec2<f32>((t.x - f.tan_left) / (f.tan_right - f.tan_left), (f.tan_top - t.y) / (f.tan_top - f.tan_bottom));
    return uv * resolution();
}

fn tangent_of_texel(tc: vec2<f32>) -> vec2<f32> {
    let f = frustum();
    let uv = tc / resolution();
    return vec2<f32>(f.tan_left + uv.x * (f.tan_right - f.tan_left), f.tan_top - uv.y * (f.tan_top - f.tan_bottom));
}

fn make_receiver(p_l: vec3<f32>, n: vec3<f32>, cos_theta: f32) -> Receiver {
    let c = clamp(cos_theta, 1e-4, 1.0);
    return placed_on(choose_layer(p_l), p_l, n, min(sqrt(1.0 - c * c) / c, MAX_SLOPE));
}

// The receiver at p_l (relative to the light) with normal n, seen on
// `layer`: its view position, depth, texel coordinates, normal and texel
// footprint there.
fn placed_on(layer: u32, p_l: vec3<f32>, n: vec3<f32>, tan_theta: f32) -> Receiver {
    var r: Receiver;
    r.layer = layer;
    let f = frustum();
    r.v = to_view(p_l, layer);
    r.z = max(-r.v.z, 1e-30);
    r.tc = texel_of_tangent(r.v.xy / r.z);
    r.n_v = to_view(n, layer);
    r.texel_m = r.z * max(f.tan_right - f.tan_left, f.tan_top - f.tan_bottom) / resolution();
    r.tan_theta = tan_theta;
    return r;
}

fn stored_depth(layer: u32, texel: vec2<i32>) -> f32 {
    let d = textureLoad(shadow_depth_values, texel, i32(layer), 0).x;
    let f = frustum();
    return stored_linear(d, f.depth_a, f.depth_b);
}

// A stored value d as a depth (m) with the layer's conversion a, b; d = 0
// is the cleared far plane: nothing drawn there.
fn stored_linear(d: f32, depth_a: f32, depth_b: f32) -> f32 {
    return select(linear_depth(d, depth_a, depth_b), 3.0e38, d <= 0.0);
}

// The receiver's depth predicted at a texel centre: its tangent plane
// intersected with the light ray through that texel, within the slope limit.
fn plane_depth(r: Receiver, texel: vec2<i32>) -> f32 {
    let centre = vec2<f32>(texel) + 0.5;
    let t = tangent_of_texel(centre);
    let reach = MAX_SLOPE * r.texel_m * max(length(centre - r.tc), 0.5);
    return plane_along(r, dot(r.n_v, r.v), dot(r.n_v, vec3<f32>(t, -1.0)), reach);
}

// The tangent plane's depth along a light ray: numerator dot(n_v, v),
// denominator dot(n_v, dir) for the ray's direction dir = (t, −1), the
// answer no nearer than `reach` before the receiver's depth (and the
// receiver's depth where the plane does not face the ray). Its only use,
// auto_compared_depth, takes min(·, r.z): a clamp's upper end at
// r.z + reach would change nothing, and costs a software rasterizer an
// operation a texel. A select, not an early return: lavapipe runs both.
fn plane_along(r: Receiver, numerator: f32, denom: f32, reach: f32) -> f32 {
    return select(max(numerator / denom, r.z - reach), r.z, denom > -1e-6);
}

// The automatic bias's slack for float rounding and curvature (m).
fn auto_bias_slack(r: Receiver) -> f32 {
    return AUTO_BIAS_SLACK_TEXELS * r.texel_m + AUTO_BIAS_SLACK_REL * r.z;
}

// The depth the receiver is compared with at a texel, per bias mode.
fn compared_depth(r: Receiver, texel: vec2<i32>) -> f32 {
    if bias_mode() == BIAS_AUTO {
        // The facet's plane predicts its own depth at texels nearer the
        // light (where acne comes from); further texels compare with the
        // receiver's depth so that neighbouring geometry there (a concave
        // corner) is not taken for an occluder.
        return auto_compared_depth(r, plane_depth(r, texel));
    }
    return fixed_compared_depth(r);
}

// The auto bias's compared depth given the plane's depth at the texel: a
// small slack covers float rounding and curvature.
fn auto_compared_depth(r: Receiver, plane: f32) -> f32 {
    return min(plane, r.z) - auto_bias_slack(r);
}

// The depth compared at every texel by the bias modes other than auto.
fn fixed_compared_depth(r: Receiver) -> f32 {
    switch bias_mode() {
        case BIAS_CONSTANT: {
            return r.z - shadow.bias_depth_m;
        }
        case BIAS_SLOPE: {
            return r.z - (shadow.bias_depth_m + shadow.bias_slope * r.texel_m * r.tan_theta);
        }
        default: {
            // Normal offset: the receiver was already moved along its normal.
            return r.z;
        }
    }
}

fn in_map(texel: vec2<i32>) -> bool {
    let res = i32(resolution());
    return all(texel >= vec2<i32>(0)) && all(texel < vec2<i32>(res));
}

// A texel a filter reads, and the receiver as seen from that texel's layer.
struct Tap {
    r: Receiver,
    texel: vec2<i32>,
    // False when the tap lands where nothing was drawn: it counts lit.
    drawn: bool,
}

// The receiver r expressed in another layer's view (placed_on, as
// make_receiver places it), so its depth is compared on that face.
fn receiver_on_layer(r: Receiver, layer: u32) -> Receiver {
    return placed_on(layer, from_view(r.v, r.layer), from_view(r.n_v, r.layer), r.tan_theta);
}

// The texel a filter reads for the one it asks for. Beyond a single fitted
// frustum nothing was drawn (lit). Beyond the edge of a cube face the map
// continues on the neighbouring face: the tap's direction, from its texel
// centre's tangents on this face, picks that face (choose_layer) and its
// texel there, and the receiver is compared with the depth it has on it.
// (Reading this face's edge texel instead drew a line along the seams.)
fn tap(r: Receiver, texel: vec2<i32>) -> Tap {
    if in_map(texel) {
        return Tap(r, texel, true);
    }
    if !is_cube() {
        return Tap(r, texel, false);
    }
    let dir_v = vec3<f32>(tangent_of_texel(vec2<f32>(texel) + 0.5), -1.0);
    let dir = from_view(dir_v, r.layer);
    let layer = choose_layer(dir);
    let q = receiver_on_layer(r, layer);
    let d = to_view(dir, layer);
    let t = vec2<i32>(floor(texel_of_tangent(d.xy / max(-d.z, 1e-30))));
    let last = vec2<i32>(i32(resolution()) - 1);
    // A face with no geometry in it was not drawn (its texels are stale).
    let drawn = (shadow.layer_mask & (1u << layer)) != 0u;
    return Tap(q, clamp(t, vec2<i32>(0), last), drawn);
}

// 1 when the stored depth of a texel on the receiver's own layer
// (in_map(texel)) does not hide the receiver.
fn own_face_test(r: Receiver, texel: vec2<i32>) -> f32 {
    return own_face_test_of(r, texel, textureLoad(shadow_depth_values, texel, i32(r.layer), 0).x);
}

// own_face_test given the texel's stored value d.
fn own_face_test_of(r: Receiver, texel: vec2<i32>, d: f32) -> f32 {
    let f = frustum();
    return select(0.0, 1.0, compared_depth(r, texel) <= stored_linear(d, f.depth_a, f.depth_b));
}

// 1 when the texel's stored depth does not hide the receiver.
fn depth_test(r: Receiver, texel: vec2<i32>) -> f32 {
    let t = tap(r, texel);
    if !t.drawn {
        return 1.0;
    }
    return own_face_test(t.r, t.texel);
}

// Bilinearly weighted tests of the 2×2 texels around the continuous position tc.
fn bilinear_test(r: Receiver, tc: vec2<f32>) -> f32 {
    let c = tc - 0.5;
    let base = vec2<i32>(floor(c));
    let f = fract(c);
    let t00 = depth_test(r, base);
    let t10 = depth_test(r, base + vec2<i32>(1, 0));
    let t01 = depth_test(r, base + vec2<i32>(0, 1));
    let t11 = depth_test(r, base + vec2<i32>(1, 1));
    return mix(mix(t00, t10, f.x), mix(t01, t11, f.x), f.y);
}

// The one texel under the receiver. A cube's faces reach past tan 1 by
// more than PCF's widest kernel (gpu::shared, CUBE_DEPTH_MARGIN_TEXELS),
// so that texel lies on the receiver's own face, and depth_test's
// addressing of the neighbouring face, which lavapipe would run for every
// pixel, is not needed. Past a single frustum's edge nothing was drawn: lit.
fn filter_none(r: Receiver) -> f32 {
    let texel = vec2<i32>(floor(r.tc));
    let last = vec2<i32>(i32(resolution()) - 1);
    return select(1.0, own_face_test(r, clamp(texel, vec2<i32>(0), last)), in_map(texel) || is_cube());
}

fn filter_hw2x2(r: Receiver) -> f32 {
    var z_ref = r.z;
    switch bias_mode() {
        case BIAS_AUTO: {
            // The four texels lie up to one texel away: one texel of slope.
            z_ref = r.z - (r.texel_m * r.tan_theta + auto_bias_slack(r));
        }
        case BIAS_CONSTANT: {
            z_ref = r.z - shadow.bias_depth_m;
        }
        case BIAS_SLOPE: {
            z_ref = r.z - (shadow.bias_depth_m + shadow.bias_slope * r.texel_m * r.tan_theta);
        }
        default: {}
    }
    let f = frustum();
    let d_ref = f.depth_a / z_ref + f.depth_b;
    return textureSampleCompareLevel(shadow_depth, shadow_compare, r.tc / resolution(), i32(r.layer), d_ref);
}

// One-sided Chebyshev bound P(z ≤ depth) ≤ σ² / (σ² + (t − μ)²), with the
// part below `bleed` cut off to reduce light bleeding.
fn chebyshev(m: vec2<f32>, t: f32, min_variance: f32) -> f32 {
    if t <= m.x {
        return 1.0;
    }
    let variance = max(m.y - m.x * m.x, min_variance);
    let d = t - m.x;
    let p = variance / (variance + d * d);
    let bleed = shadow.vsm_bleed_reduction;
    return clamp((p - bleed) / (1.0 - bleed), 0.0, 1.0);
}

// Moment shadow mapping, Hamburger 4MSM (Peters & Klein 2015, algorithm 2):
// V = 1 − G, G the smallest fraction of occluders in front of z_f over every
// depth distribution with the biased moments b' = (1 − α) b + α (½, ½, ½, ½).
fn hamburger_4msm(b: vec4<f32>, z_f: f32, alpha: f32) -> f32 {
    let m = mix(b, vec4<f32>(0.5), alpha);
    // Solve the Hankel system [1 b1 b2; b1 b2 b3; b2 b3 b4] c = (1, z_f, z_f²)
    // by its Cholesky factor L = [1 0 0; l21 d22 0; l31 l32 d33] (row-wise).
    let l21 = m.x;
    let l31 = m.y;
    let d22 = sqrt(max(m.y - l21 * l21, 1e-12));
    let l32 = (m.z - l21 * l31) / d22;
    let d33 = sqrt(max(m.w - l31 * l31 - l32 * l32, 1e-12));
    // Forward substitution L y = (1, z_f, z_f²), then back substitution Lᵀ c = y.
    let y1 = 1.0;
    let y2 = (z_f - l21 * y1) / d22;
    let y3 = (z_f * z_f - l31 * y1 - l32 * y2) / d33;
    let c3 = y3 / d33;
    let c2 = (y2 - l32 * c3) / d22;
    let c1 = y1 - l21 * c2 - l31 * c3;
    // The other two support points z2 ≤ z3: roots of c3 z² + c2 z + c1 = 0.
    let disc = sqrt(max(c2 * c2 - 4.0 * c3 * c1, 0.0));
    let ra = (-c2 - disc) / (2.0 * c3);
    let rb = (-c2 + disc) / (2.0 * c3);
    let z2 = min(ra, rb);
    let z3 = max(ra, rb);
    var g = 0.0;
    if z_f <= z2 {
        g = 0.0;
    } else if z_f <= z3 {
        g = (z_f * z3 - m.x * (z_f + z3) + m.y) / ((z3 - z2) * (z_f - z2));
    } else {
        g = 1.0 - (z2 * z3 - m.x * (z2 + z3) + m.y) / ((z_f - z2) * (z_f - z3));
    }
    return 1.0 - clamp(g, 0.0, 1.0);
}

fn filter_moments(r: Receiver) -> f32 {
    let f = frustum();
    let u = clamp((r.z - f.near_m) / (f.far_m - f.near_m), 0.0, 1.0);
    let m = textureSampleLevel(moments, moments_sampler, r.tc / resolution(), i32(r.layer), 0.0);
    if filter_mode() == FILTER_VSM {
        return chebyshev(m.xy, u, 1e-6);
    }
    if filter_mode() == FILTER_MSM {
        return hamburger_4msm(m, u, shadow.msm_bias);
    }
    // EVSM: both exponential warps of u, the smaller bound wins.
    let c = shadow.evsm_exponent;
    let w = 2.0 * u - 1.0;
    let pos = exp(c * w);
    let neg = -exp(-c * w);
    let p_pos = chebyshev(m.xy, pos, 1e-6 * pos * pos);
    let p_neg = chebyshev(m.zw, neg, 1e-6 * neg * neg);
    return min(p_pos, p_neg);
}

// V ∈ [0, 1]: filter weights sum to one only up to rounding.
fn filtered_visibility(r: Receiver, pixel: vec2<f32>) -> f32 {
    return clamp(filter_taps(r, pixel), 0.0, 1.0);
}

fn filter_taps(r: Receiver, pixel: vec2<f32>) -> f32 {
    switch filter_mode() {
        case FILTER_NONE: { return filter_none(r); }
        case FILTER_HW2X2: { return filter_hw2x2(r); }
        case FILTER_PCF: { return filter_pcf(r); }
        case FILTER_POISSON: { return filter_poisson(r, pixel); }
        case FILTER_PCSS: { return filter_pcss(r, pixel); }
        default: { return filter_moments(r); }
    }
}

// Shadow-map texels per pixel at the point p_l (relative to the light) of a
// facet of normal n_geo lit from l. Uses derivatives: call it in uniform
// control flow.
fn shadow_map_texel_density(p_l: vec3<f32>, n_geo: vec3<f32>, l: vec3<f32>) -> f32 {
    let receiver = make_receiver(p_l, n_geo, dot(n_geo, l));
    return max(length(dpdx(receiver.tc)), length(dpdy(receiver.tc)));
}

// V from the shadow map at p_l (relative to the light) on a facet of normal
// n_geo lit from l (n_geo · l > 0), filtered and biased as the settings say.
fn shadow_map_visibility(p_l: vec3<f32>, n_geo: vec3<f32>, l: vec3<f32>, pixel: vec2<f32>) -> f32 {
    var receiver = make_receiver(p_l, n_geo, dot(n_geo, l));
    let mode = bias_mode();
    if mode == BIAS_NORMAL || mode == BIAS_AUTO {
        // Normal offset: N texels (one for auto) along the facet normal
        // lifts the lookup off its own surface and out of concave corners.
        let texels = select(1.0, shadow.normal_offset_texels, mode == BIAS_NORMAL);
        receiver = make_receiver(p_l + n_geo * (texels * receiver.texel_m), n_geo, dot(n_geo, l));
    }
    return filtered_visibility(receiver, pixel);
}
