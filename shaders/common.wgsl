// Shared by every pass: the uniform layouts and the physics, mirrored line by
// line from src/physics/ (brdf.rs, radiometry.rs, display.rs). Keep in step.

const PI: f32 = 3.14159265358979;
// Light distances are clamped to at least this (m): physics::radiometry::MIN_LIGHT_DISTANCE_M.
const MIN_LIGHT_DISTANCE_M: f32 = 1e-6;

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

// Filters, in settings::Filter order.
const FILTER_NONE: u32 = 0u;
const FILTER_HW2X2: u32 = 1u;
const FILTER_PCF: u32 = 2u;
const FILTER_POISSON: u32 = 3u;
const FILTER_PCSS: u32 = 4u;
const FILTER_VSM: u32 = 5u;
const FILTER_EVSM: u32 = 6u;

// Bias modes, in settings::BiasMode order.
const BIAS_AUTO: u32 = 0u;
const BIAS_CONSTANT: u32 = 1u;
const BIAS_SLOPE: u32 = 2u;
const BIAS_NORMAL: u32 = 3u;

// Everything the camera pass needs that changes per frame (gpu::uniforms::GlobalsRaw).
struct Globals {
    // Eye-relative world position → clip space: clip = view_proj * (p − eye, 1).
    view_proj: mat4x4<f32>,
    // xyz: light − eye (m); w: sphere radius R (m).
    light_rel: vec4<f32>,
    // xyz: the eye (m, world); the camera pass works relative to it.
    eye: vec4<f32>,
    // rgb: light colour; w: power Φ (W).
    light_color_power: vec4<f32>,
    // x: k, y: m, z: use the scene's own k and m (0/1), w: colour override (0/1).
    material: vec4<f32>,
    // rgb: colour override.
    color_override: vec4<f32>,
    // x: view, y: normalization, z, w: unused.
    modes: vec4<u32>,
    // x, y: image size (px); z, w: unused.
    viewport: vec4<f32>,
}

// One shadow-map layer: a perspective frustum from the light (gpu::uniforms::ShadowLayerRaw).
struct ShadowLayer {
    // Light-relative world direction → light view (looks down −Z).
    rotation: mat4x4<f32>,
    // Light view → clip, reversed Z.
    proj: mat4x4<f32>,
    // left, right, bottom, top: the frustum's extents as tangents (x/z, y/z).
    tan_bounds: vec4<f32>,
    // near, far (m), and (a, b) of the stored depth d = a / z + b.
    depth: vec4<f32>,
}

// The shadow map's layout and settings (gpu::uniforms::ShadowRaw).
struct Shadow {
    layers: array<ShadowLayer, 6>,
    // x: enabled, y: cube (0/1), z: mask of drawn layers, w: filter.
    mode: vec4<u32>,
    // x: PCF size n, y: Poisson samples, z: PCSS blocker samples, w: bias mode.
    counts: vec4<u32>,
    // x: Poisson radius (texels), y: bias depth D (m), z: slope S, w: normal offset N (texels).
    bias: vec4<f32>,
    // x: resolution (texels), y: VSM bleed reduction, z: EVSM exponent, w: sphere light radius R (m).
    misc: vec4<f32>,
    // xyz: the light (m, world), for the shadow pass.
    light_position: vec4<f32>,
}

// A material (gpu::uniforms::MaterialRaw).
struct Material {
    // Linear RGBA base colour factor.
    base_color: vec4<f32>,
    // x: own k, y: own m, z: has own k (0/1), w: has own m (0/1).
    params: vec4<f32>,
    // x: texture layer + 1 (0 = none), y: double sided (0/1).
    flags: vec4<u32>,
}

// How a view is displayed (gpu::uniforms::DisplayParamsRaw).
struct DisplayParams {
    // x: view, y: unused, z: unused, w: a comparison image is bound (0/1).
    modes: vec4<u32>,
    // x: exposure (EV), y: unused, z, w: image size (px).
    values: vec4<f32>,
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
        case 0u: { return 1.0; }
        case 1u: { return (m + 1.0) / (2.0 * PI); }
        case 2u: { return (m + 8.0) / (8.0 * PI); }
        default: { return (m + 2.0) * (m + 4.0) / (8.0 * PI * (exp2(-m / 2.0) + m)); }
    }
}

// f_r / c split into k/π and (1 − k) N(m) cos^m θ_h (physics::brdf::blinn_phong).
fn blinn_phong(n: vec3<f32>, l: vec3<f32>, o: vec3<f32>, k: f32, m: f32, norm: u32) -> vec2<f32> {
    if !(dot(n, l) > 0.0 && dot(n, o) > 0.0) {
        return vec2<f32>(0.0);
    }
    let diffuse = k / PI;
    let sum = l + o;
    let len2 = dot(sum, sum);
    if !(len2 > 0.0) {
        return vec2<f32>(diffuse, 0.0);
    }
    let h = sum * (1.0 / sqrt(len2));
    let cos_h = dot(n, h);
    let gap = min(dot(n - h, n - h) * 0.5, 1.0);
    return vec2<f32>(diffuse, (1.0 - k) * norm_factor(norm, m) * lobe(cos_h, gap, m));
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
