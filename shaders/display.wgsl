// The image people see: radiance exposed (2^EV) and sRGB encoded by the
// target's format, or a debug quantity in grey or false colour.

// Alpha: coverage, so a frame drawn without the aux target displays the same.
@group(0) @binding(0) var quantity: texture_2d<f32>;
@group(0) @binding(1) var comparison: texture_2d<f32>;
// The light's depth map read as plain floats (GLSL cannot load depth textures).
@group(0) @binding(2) var shadow_depth: texture_2d_array<f32>;
@group(0) @binding(3) var<uniform> shadow: Shadow;
@group(0) @binding(4) var<uniform> params: DisplayParams;
@group(0) @binding(5) var<storage, read> scale: array<u32, 4>;

// The view this pipeline is compiled for (gpu::display); SPECIALISE_ANY
// reads the uniform instead.
override SPECIALISED_VIEW: u32 = SPECIALISE_ANY;

fn display_view() -> u32 {
    return select(SPECIALISED_VIEW, params.view, SPECIALISED_VIEW == SPECIALISE_ANY);
}

// A grey level that displays as `value` (the target re-encodes to sRGB).
fn grey(value: f32) -> vec3<f32> {
    return vec3<f32>(srgb_decode(clamp(value, 0.0, 1.0)));
}

// Piecewise-linear colour ramps through sRGB stops (gpu::colormap).
fn ramp(t_in: f32, diverging: bool) -> vec3<f32> {
    let t = clamp(t_in, 0.0, 1.0) * f32(RAMP_STOPS - 1u);
    let i = min(u32(floor(t)), RAMP_STOPS - 2u);
    let f = t - f32(i);
    var c: vec3<f32>;
    if diverging {
        c = mix(DIVERGING[i], DIVERGING[i + 1u], f);
    } else {
        c = mix(SEQUENTIAL[i], SEQUENTIAL[i + 1u], f);
    }
    return vec3<f32>(srgb_decode(c.x), srgb_decode(c.y), srgb_decode(c.z));
}

fn scale_max() -> f32 {
    return max(bitcast<f32>(scale[0]), 1e-30);
}

// A checker that says "nothing to show here".
fn missing(position: vec2<f32>) -> vec3<f32> {
    let cell = vec2<u32>(position / 12.0);
    return grey(select(0.25, 0.35, ((cell.x + cell.y) & 1u) == 0u));
}

// The light's depth map: one layer, or the six cube faces in a 3 × 2 grid.
fn depth_view(position: vec2<f32>) -> vec3<f32> {
    let size = params.size_px;
    // Selects, not an `if` on the uniforms (tests/uniform_branches.rs).
    let cube = shadow.cube != 0u;
    let cols = select(1.0, 3.0, cube);
    let rows = select(1.0, 2.0, cube);
    let cell_size = min(size.x / cols, size.y / rows);
    let origin = 0.5 * (size - vec2<f32>(cols, rows) * cell_size);
    let local = (position - origin) / cell_size;
    if any(local < vec2<f32>(0.0)) || local.x >= cols || local.y >= rows {
        return grey(0.08);
    }
    let cell = vec2<u32>(floor(local));
    let layer = cell.y * 3u + cell.x;
    if (shadow.layer_mask & (1u << layer)) == 0u {
        return missing(position);
    }
    let texel = vec2<i32>(fract(local) * f32(shadow.resolution_texels));
    let d = textureLoad(shadow_depth, texel, i32(layer), 0).x;
    if d <= 0.0 {
        return grey(0.0);
    }
    let f = shadow.layers[layer];
    let z = linear_depth(d, f.depth_a, f.depth_b);
    // Near is white, far is dark.
    return grey(1.0 - 0.9 * clamp((z - f.near_m) / (f.far_m - f.near_m), 0.0, 1.0));
}

@fragment
fn fs(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let view = display_view();
    if view == VIEW_DEPTH {
        return vec4<f32>(depth_view(position.xy), 1.0);
    }
    let texel = vec2<i32>(position.xy);
    let sample = textureLoad(quantity, texel, 0);
    if sample.a == 0.0 {
        // Background: a quiet grey, darker at the bottom.
        return vec4<f32>(grey(0.16 + 0.06 * (1.0 - position.y / params.size_px.y)), 1.0);
    }
    let q = sample.rgb;
    let has_reference = params.has_comparison != 0u;
    var color: vec3<f32>;
    switch view {
        case VIEW_VISIBILITY, VIEW_NDOTL: {
            color = grey(q.x);
        }
        case VIEW_IRRADIANCE: {
            color = ramp(q.x / scale_max(), false);
        }
        case VIEW_BRDF: {
            // Two decades below the largest value, log scale.
            color = ramp(1.0 + log2(max(q.x, 1e-30) / scale_max()) / (2.0 * log2(10.0)), false);
        }
        case VIEW_TEXEL_DENSITY: {
            // log2 of texels per pixel in [−4, 4]: under 1 (red) is magnified and aliased.
            color = ramp(0.5 - log2(max(q.x, 1e-6)) / 8.0, true);
        }
        case VIEW_REF_VISIBILITY: {
            color = select(missing(position.xy), grey(textureLoad(comparison, texel, 0).a), has_reference);
        }
        case VIEW_ERROR: {
            let error = luminance(q) - luminance(textureLoad(comparison, texel, 0).rgb);
            color = select(missing(position.xy), ramp(0.5 + 0.5 * error / scale_max(), true), has_reference);
        }
        case VIEW_DELTA_E: {
            // ΔE2000 on a fixed scale; negative: no spectral illuminant, no ΔE.
            if q.x < 0.0 {
                color = missing(position.xy);
            } else {
                color = ramp(q.x / DELTA_E_VIEW_MAX, false);
            }
        }
        default: {
            color = q * exp2(params.exposure_ev);
        }
    }
    return vec4<f32>(color, 1.0);
}
