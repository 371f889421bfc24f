// Shared by every pass: the uniform layouts and the physics, mirrored line by
// line from src/physics/ (brdf.rs, radiometry.rs, colour.rs, display.rs).
// Keep in step: tests/wgsl_parity.rs runs these functions on the GPU against
// the Rust ones. Numeric constants shared with Rust (PI, MIN_LIGHT_DISTANCE_M,
// the luminance weights, the shadow filters' limits) are not written here:
// gpu::shaders prepends them, generated from the Rust constants.

// Debug views, in settings::DebugView order.
const VIEW_SHADED: u32 = 0u;
const VIEW_DEPTH: u32 = 1u;
const VIEW_VISIBILITY: u32 = 2u;
const VIEW_NDOTL: u32 = 3u;
const VIEW_IRRADIANCE: u32 = 4u;
const VIEW_BRDF: u32 = 5u;
const VIEW_DIFFUSE: u32 = 6u;
const VIEW_SPECULAR: u32 = 7u;
const VIEW_TEXEL_DENSITY: u32 = 8u;
const VIEW_FRUSTUM: u32 = 9u;
const VIEW_REF_VISIBILITY: u32 = 10u;
const VIEW_ERROR: u32 = 11u;
const VIEW_DELTA_E: u32 = 12u;

// Filters, in settings::Filter order.
const FILTER_NONE: u32 = 0u;
const FILTER_HW2X2: u32 = 1u;
const FILTER_PCF: u32 = 2u;
const FILTER_POISSON: u32 = 3u;
const FILTER_PCSS: u32 = 4u;
const FILTER_VSM: u32 = 5u;
const FILTER_EVSM: u32 = 6u;
const FILTER_MSM: u32 = 7u;

// Bias modes, in settings::BiasMode order.
const BIAS_AUTO: u32 = 0u;
const BIAS_CONSTANT: u32 = 1u;
const BIAS_SLOPE: u32 = 2u;
const BIAS_NORMAL: u32 = 3u;

// Normalizations N(m), in physics::Normalization order.
const NORM_NONE: u32 = 0u;
const NORM_NDF: u32 = 1u;
const NORM_APPROX: u32 = 2u;
const NORM_EXACT: u32 = 3u;

// Visibility sources, in settings::Visibility order.
const VISIBILITY_SHADOW_MAP: u32 = 0u;
const VISIBILITY_RAY_TRACED: u32 = 1u;

// A specialisation constant's value for "any": read the uniform instead.
const SPECIALISE_ANY: u32 = 0xffffffffu;

// Everything the camera pass needs that changes per frame (gpu::uniforms::GlobalsRaw).
struct Globals {
    // Eye-relative world position → clip space: clip = view_proj * (p − eye, 1).
    view_proj: mat4x4<f32>,
    // The light's centre relative to the eye (m).
    light_rel: vec3<f32>,
    // Sphere light radius R (m); 0 is a point light.
    light_radius_m: f32,
    // The eye (m, world); the camera pass works relative to it.
    eye: vec3<f32>,
    // Light power Φ (W).
    light_power_w: f32,
    // The light's colour (linear RGB factors of Φ).
    light_color: vec3<f32>,
    // k where the scene gives none (or scene materials are off).
    k: f32,
    // Replaces every material's colour when use_color_override != 0.
    color_override: vec3<f32>,
    // m where the scene gives none.
    m: f32,
    // VIEW_*.
    view: u32,
    // VISIBILITY_*: where V comes from.
    visibility: u32,
    // Materials' own k and m are used where they give them (0/1).
    use_scene_materials: u32,
    // 0/1.
    use_color_override: u32,
    // N(m) for m under the settings' normalization (computed on the CPU).
    norm_factor: f32,
    // Where the shadow map is drawn from, relative to the eye (m): the light,
    // or its stand-in on the same line for a far light.
    shadow_apex_rel: vec3<f32>,
    // The `delta-e` view (shaders/delta_e.wgsl, gpu::delta_e): the exposure
    // (EV) the two colours are compared at, displayed = L · 2^EV;
    exposure_ev: f32,
    // the other colour model's light colour (spectral ↔ RGB approximation);
    other_light_color: vec3<f32>,
    // 1 under a spectral illuminant, where ΔE is defined (0: RGB mode);
    delta_e_defined: u32,
    // the other colour model's override colour;
    other_color_override: vec3<f32>,
    // linear sRGB → XYZ / XYZ of the illuminant's white, CIE Lab's reference.
    lab_white_relative: mat3x3<f32>,
}

// One shadow-map layer: a perspective frustum from the light (gpu::uniforms::ShadowLayerRaw).
struct ShadowLayer {
    // Light-relative world direction → light view (looks down −Z).
    rotation: mat4x4<f32>,
    // Light view → clip, reversed Z.
    proj: mat4x4<f32>,
    // The frustum's extents as tangents (x/z, y/z).
    tan_left: f32,
    tan_right: f32,
    tan_bottom: f32,
    tan_top: f32,
    // Near and far planes (m).
    near_m: f32,
    far_m: f32,
    // The stored depth d = depth_a / z + depth_b.
    depth_a: f32,
    depth_b: f32,
}

// The shadow map's layout and settings (gpu::uniforms::ShadowRaw).
struct Shadow {
    layers: array<ShadowLayer, 6>,
    // The light's centre (m, world), for the shadow pass.
    light_position: vec3<f32>,
    // 0: no shadow map, V = 1.
    enabled: u32,
    // Six cube faces (1) or one fitted frustum (0).
    cube: u32,
    // Bit i set: layer i was drawn.
    layer_mask: u32,
    // FILTER_*.
    filter_mode: u32,
    // BIAS_*.
    bias_mode: u32,
    // Kernel size n of pcf.
    pcf_size: u32,
    // Samples of poisson and of the filtering step of pcss.
    poisson_samples: u32,
    // Samples of the blocker search of pcss.
    pcss_blocker_samples: u32,
    // Texels per side of every layer.
    resolution_texels: u32,
    poisson_radius_texels: f32,
    // Constant depth bias D (m) of constant and slope.
    bias_depth_m: f32,
    // Slope factor S of slope.
    bias_slope: f32,
    // Normal offset N (texels) of normal.
    normal_offset_texels: f32,
    // The part of Chebyshev's bound cut off by vsm/evsm.
    vsm_bleed_reduction: f32,
    // The EVSM warp exponent c.
    evsm_exponent: f32,
    // Sphere light radius R (m) for pcss.
    light_radius_m: f32,
    // The moment bias α of msm.
    msm_bias: f32,
    // The block size B of the depth ranges pcf may read (gpu::depth_ranges),
    // 0 where none are ready for this map.
    range_block: u32,
}

// A material (gpu::uniforms::MaterialRaw).
struct Material {
    // Linear RGB base colour factor; w: N(own m) under the frame's
    // normalization (gpu::scene_buffers::GpuScene::write_norm_factors).
    base_color: vec4<f32>,
    // Own k and m (f32 bits), the base-colour texture layer + 1 (0 = none),
    // flags (MATERIAL_*, generated from gpu::uniforms): one vec4, one load
    // (gpu::uniforms::MaterialWordsRaw).
    words: vec4<u32>,
    // The base colour under the other colour model (the `delta-e` view).
    other_model_color: vec4<f32>,
}

// How a view is displayed (gpu::uniforms::DisplayParamsRaw).
struct DisplayParams {
    // Image size (px).
    size_px: vec2<f32>,
    // VIEW_*.
    view: u32,
    // A comparison image is bound (0/1).
    has_comparison: u32,
    // Exposure (EV).
    exposure_ev: f32,
}

// The largest and smallest of four values.
fn largest(v: vec4<f32>) -> f32 {
    return max(max(v.x, v.y), max(v.z, v.w));
}

fn smallest(v: vec4<f32>) -> f32 {
    return min(min(v.x, v.y), min(v.z, v.w));
}

// A plane over texel offsets p (from its first texel): c + g·p (the
// depth ranges' bounds, gpu::depth_ranges).
fn plane_at(c: f32, g: vec2<f32>, p: vec2<f32>) -> f32 {
    return c + dot(g, p);
}

// The plane c, g at the corners o + (0, 0), (s, 0), (0, s), (s, s).
fn plane_corners(c: f32, g: vec2<f32>, o: vec2<f32>, s: f32) -> vec4<f32> {
    return plane_at(c, g, o) + vec4<f32>(0.0, g.x, g.y, g.x + g.y) * s;
}

// Y of a linear RGB colour (physics::colour::luminance).
fn luminance(c: vec3<f32>) -> f32 {
    return dot(c, LUMINANCE_WEIGHTS);
}

// The colour light of colour `light` takes from a surface of colour `surface`:
// the RGB product, where a spectral mode would put its tristimulus values
// (physics::colour::tint).
fn tint(surface: vec3<f32>, light: vec3<f32>) -> vec3<f32> {
    return surface * light;
}

// ln(cos θ) from the gap d = 1 − cos θ: −2 atanh(d / (2 − d)) as a series
// below 0.1 (physics::brdf::ln_cos_from_gap).
fn ln_cos_from_gap(gap: f32) -> f32 {
    if gap < 0.1 {
        let x = gap / (2.0 - gap);
        let x2 = x * x;
        let tail = 1.0 / 7.0 + x2 * (1.0 / 9.0 + x2 * (1.0 / 11.0 + x2 * (1.0 / 13.0)));
        return -2.0 * x * (1.0 + x2 * (1.0 / 3.0 + x2 * (0.2 + x2 * tail)));
    }
    return log(1.0 - gap);
}

// cos^m θ: 1 when m = 0 (0^0 = 1), 0 when cos θ ≤ 0 (physics::brdf::lobe).
fn lobe(cos_theta: f32, gap: f32, m: f32) -> f32 {
    if m <= 0.0 {
        return 1.0;
    }
    if cos_theta <= 0.0 {
        return 0.0;
    }
    return exp(m * ln_cos_from_gap(gap));
}

// N(m) (physics::brdf::Normalization::factor).
fn norm_factor(norm: u32, m: f32) -> f32 {
    switch norm {
        case NORM_NONE: { return 1.0; }
        case NORM_NDF: { return (m + 1.0) / (2.0 * PI); }
        case NORM_APPROX: { return (m + 8.0) / (8.0 * PI); }
        default: { return (m + 2.0) * (m + 4.0) / (8.0 * PI * (exp2(-m / 2.0) + m)); }
    }
}

// f_r / c split into k/π and (1 − k) N(m) cos^m θ_h (physics::brdf::blinn_phong).
fn blinn_phong(n: vec3<f32>, l: vec3<f32>, o: vec3<f32>, k: f32, m: f32, norm: u32) -> vec2<f32> {
    return blinn_phong_scaled(n, l, o, k, m, norm_factor(norm, m));
}

// blinn_phong given N(m) = n_m.
fn blinn_phong_scaled(n: vec3<f32>, l: vec3<f32>, o: vec3<f32>, k: f32, m: f32, n_m: f32) -> vec2<f32> {
    // Written with selects, not early returns: a software rasterizer runs
    // every branch anyway, and the branches cost it more than the selects.
    let lit = dot(n, l) > 0.0 && dot(n, o) > 0.0;
    let sum = l + o;
    let len2 = dot(sum, sum);
    let h = sum * (1.0 / sqrt(max(len2, 1e-30)));
    let cos_h = dot(n, h);
    let gap = min(dot(n - h, n - h) * 0.5, 1.0);
    // Lambert alone (k ≥ 1) drops N(m) before the product: an N(m) that
    // overflows f32 (m ≳ 10^19 with exact) would give 0 · ∞.
    let n_kept = select(n_m, 0.0, k >= 1.0);
    let specular = select(0.0, (1.0 - k) * n_kept * lobe(cos_h, gap, m), len2 > 0.0);
    return select(vec2<f32>(0.0), vec2<f32>(k / PI, specular), lit);
}

// Where the light is seen from a surface point (physics::radiometry::incidence).
struct LightIncidence {
    // Unit direction towards the light; the normal when the light is on the point.
    l: vec3<f32>,
    // Distance to the light (m), clamped to MIN_LIGHT_DISTANCE_M.
    r: f32,
    // n·l, signed.
    cos_theta: f32,
}

fn light_incidence(to_light: vec3<f32>, n: vec3<f32>) -> LightIncidence {
    let r2 = dot(to_light, to_light);
    var l = n;
    if r2 > 0.0 {
        l = to_light * (1.0 / sqrt(r2));
    }
    return LightIncidence(l, max(sqrt(r2), MIN_LIGHT_DISTANCE_M), dot(n, l));
}

// E = I max(0, cos θ) / r² (physics::radiometry::point_irradiance).
fn point_irradiance(intensity: f32, cos_theta: f32, r_m: f32) -> f32 {
    let r = max(r_m, MIN_LIGHT_DISTANCE_M);
    return intensity * max(cos_theta, 0.0) / (r * r);
}

// L_e = Φ / (4π² R²) (physics::radiometry::sphere_radiance).
fn sphere_radiance(power_w: f32, radius_m: f32) -> f32 {
    let r = max(radius_m, MIN_LIGHT_DISTANCE_M);
    return power_w / (4.0 * PI * PI * r * r);
}

// E from a sphere light, horizon clipped (physics::radiometry::sphere_irradiance).
fn sphere_irradiance(power_w: f32, radius_m: f32, cos_theta_in: f32, r_m: f32) -> f32 {
    let intensity = power_w / (4.0 * PI);
    if radius_m <= 0.0 {
        return point_irradiance(intensity, cos_theta_in, r_m);
    }
    let r = max(r_m, MIN_LIGHT_DISTANCE_M);
    let sin2_alpha = (radius_m * radius_m) / (r * r);
    if sin2_alpha >= 1.0 {
        return PI * sphere_radiance(power_w, radius_m);
    }
    let cos_theta = clamp(cos_theta_in, -1.0, 1.0);
    if cos_theta > 0.0 && cos_theta * cos_theta >= sin2_alpha {
        return point_irradiance(intensity, cos_theta, r);
    }
    if cos_theta <= 0.0 && cos_theta * cos_theta >= sin2_alpha {
        return 0.0;
    }
    let sin_theta = sqrt(max(1.0 - cos_theta * cos_theta, 0.0));
    let x = sqrt(1.0 / sin2_alpha - 1.0);
    let y = clamp(-x * cos_theta / sin_theta, -1.0, 1.0);
    let s = sin_theta * sqrt(max(1.0 - y * y, 0.0));
    // Snyder's F rewritten so that its terms do not cancel for a small sphere.
    let t = s / x;
    let form = sin2_alpha * (cos_theta * acos(y) + t) - t_minus_atan(t);
    return sphere_radiance(power_w, radius_m) * max(form, 0.0);
}

// t − atan t without cancellation (physics::radiometry::t_minus_atan).
fn t_minus_atan(t: f32) -> f32 {
    if t < 0.05 {
        let t2 = t * t;
        let tail = 1.0 / 11.0 - t2 * (1.0 / 13.0 - t2 * (1.0 / 15.0));
        return t * t2 * (1.0 / 3.0 - t2 * (0.2 - t2 * (1.0 / 7.0 - t2 * (1.0 / 9.0 - t2 * tail))));
    }
    return t - atan(t);
}

// The sRGB transfer of a linear value clamped to [0, 1] (physics::display::srgb_encode).
fn srgb_encode(linear: f32) -> f32 {
    let x = clamp(linear, 0.0, 1.0);
    if x <= 0.0031308 {
        return 12.92 * x;
    }
    return 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}

fn srgb_decode(encoded: f32) -> f32 {
    if encoded <= 0.04045 {
        return encoded / 12.92;
    }
    return pow((encoded + 0.055) / 1.055, 2.4);
}

// Reversed-Z depth d = a / z + b back to the view depth z (m).
fn linear_depth(d: f32, a: f32, b: f32) -> f32 {
    return a / (d - b);
}

// Vertex i of the one triangle that covers a fullscreen pass's target
// (fullscreen.wgsl, and the passes with a vertex stage of their own).
fn fullscreen_position(i: u32) -> vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

// The fullscreen triangle with a uniform that bounds a loop of the
// fragment stage, handed over as a flat varying: lavapipe compiles a
// shader anew whenever a uniform that alone bounds a loop changes
// (tests/uniform_branches.rs).
struct FullscreenBound {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) bound: i32,
}

fn fullscreen_bound(i: u32, bound: i32) -> FullscreenBound {
    return FullscreenBound(fullscreen_position(i), bound);
}
