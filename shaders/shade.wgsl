// The camera pass: shades every visible point with the point or sphere light,
// the BRDF and the visibility V, and writes the quantity the chosen view shows
// (target 0) plus V, texel density, cos θ and coverage (target 1). V comes
// from the source the visibility method selects (`visibility`); the radiance
// (`view_quantity`) takes it as an input. Positions are relative to the eye
// for precision far from the origin.

@group(0) @binding(0) var<uniform> globals: Globals;
@group(0) @binding(1) var<uniform> shadow: Shadow;
// The drawn object's material, read by the vertex stage (VsOut carries it):
// its slot bound for each draw (gpu::scene_buffers::Meshes::material_offset).
@group(0) @binding(2) var<uniform> material: Material;
@group(0) @binding(3) var base_textures: texture_2d_array<f32>;
@group(0) @binding(4) var base_sampler: sampler;
// Group 1: the visibility source's resources (shadow_map.wgsl); group 2:
// the ray tracer's (bvh.wgsl, raytrace.wgsl).

// Pipeline-overridable constants: a pipeline specialised to one view and one
// visibility source (gpu::specialise) holds its VIEW_* / VISIBILITY_* here,
// and the compiler drops every other case; SPECIALISE_ANY (the default)
// reads the uniform instead, the one generic pipeline.
override SPECIALISED_VIEW: u32 = SPECIALISE_ANY;
override SPECIALISED_VISIBILITY: u32 = SPECIALISE_ANY;
// Shadows on (1) or off (0), or SPECIALISE_ANY to read shadow.enabled.
override SPECIALISED_SHADOWS: u32 = SPECIALISE_ANY;
// The scene has vertex colours (1) or none (0: every vertex's is 1, and
// the colour is not read), or SPECIALISE_ANY to read them anyway.
override SPECIALISED_VERTEX_COLOURS: u32 = SPECIALISE_ANY;
// Some material has a base-colour texture (1) or none (0: no texture is
// sampled), or SPECIALISE_ANY to test each fragment's material.
override SPECIALISED_TEXTURES: u32 = SPECIALISE_ANY;
// The light is a sphere (1) or a point (0), or SPECIALISE_ANY to read its
// radius: a point light's pipeline keeps neither the sphere's horizon case
// of the irradiance nor, under ray-traced V, the cone's sampling.
override SPECIALISED_SPHERE_LIGHT: u32 = SPECIALISE_ANY;

// The vertex colour at a fragment (1 where the scene has none).
fn vertex_colour(in: VsOut) -> vec3<f32> {
    return select(in.colour, vec3<f32>(1.0), SPECIALISED_VERTEX_COLOURS == 0u);
}

fn view_mode() -> u32 {
    return select(SPECIALISED_VIEW, globals.view, SPECIALISED_VIEW == SPECIALISE_ANY);
}

fn visibility_mode() -> u32 {
    return select(SPECIALISED_VISIBILITY, globals.visibility, SPECIALISED_VISIBILITY == SPECIALISE_ANY);
}

fn sphere_light() -> bool {
    let radius_read = u32(globals.light_radius_m > 0.0);
    return select(SPECIALISED_SPHERE_LIGHT, radius_read, SPECIALISED_SPHERE_LIGHT == SPECIALISE_ANY) != 0u;
}

fn shadows_enabled() -> bool {
    return select(SPECIALISED_SHADOWS, shadow.enabled, SPECIALISED_SHADOWS == SPECIALISE_ANY) != 0u;
}

struct VsIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    // The vertex colour multiplying the base colour (1 without one).
    @location(3) colour: vec3<f32>,
}

struct VsOut {
    // Invariant: the depth pre-pass (vs_depth) must give the same depth bit for bit.
    @builtin(position) @invariant clip: vec4<f32>,
    // p − eye (m).
    @location(0) rel: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    // The triangle's material, read once per vertex (`vs`): a software
    // rasterizer would load a per-pixel index's fields lane by lane.
    @location(3) @interpolate(flat) texture_layer_plus_one: u32,
    // 0: the object receives no shadows (V = 1).
    @location(4) @interpolate(flat) receives_shadows: u32,
    @location(5) colour: vec3<f32>,
    @location(6) @interpolate(flat) base_color: vec3<f32>,
    @location(7) @interpolate(flat) other_model_color: vec3<f32>,
    // k, m and N(m) (the settings' or the material's own), double-sided (0/1).
    @location(8) @interpolate(flat) brdf: vec4<f32>,
    // The knobs (shadow_map.wgsl), the same at every vertex.
    @location(9) @interpolate(flat) knob_filter: vec4<u32>,
    @location(10) @interpolate(flat) knob_rays: vec4<u32>,
    @location(11) @interpolate(flat) knob_radius_m: f32,
}

// The clip position of a vertex: shared by both vertex stages below.
fn clip_position(position: vec3<f32>) -> vec4<f32> {
    return globals.view_proj * vec4<f32>(position - globals.eye, 1.0);
}

// The depth pre-pass: only the nearest depth of each pixel, so that the
// camera pass (depth test Equal, no writes) shades every pixel once.
@vertex
fn vs_depth(@location(0) position: vec3<f32>) -> @builtin(position) @invariant vec4<f32> {
    return clip_position(position);
}

@vertex
fn vs(in: VsIn) -> VsOut {
    var out: VsOut;
    out.rel = in.position - globals.eye;
    out.clip = clip_position(in.position);
    out.normal = in.normal;
    // Neither the uv nor the vertex colour where a pipeline specialised to
    // a scene without textures, or without vertex colours, never reads
    // them: a software rasterizer computes every output of this stage (the
    // engine's vertex stage −10 %).
    out.uv = select(in.uv, vec2<f32>(0.0), SPECIALISED_TEXTURES == 0u);
    let mat = material;
    out.receives_shadows = u32((mat.words.w & MATERIAL_NO_SHADOWS_RECEIVED) == 0u);
    // The colour override replaces the base colour, its texture and the
    // vertex colour, here once a vertex: lavapipe ran the fragment's `if`
    // on the uniform for every pixel (0.6 M instructions a frame, 8 %).
    let overridden = globals.use_color_override != 0u;
    out.colour = select(in.colour, vec3<f32>(1.0), overridden | (SPECIALISED_VERTEX_COLOURS == 0u));
    out.texture_layer_plus_one = select(mat.words.z, 0u, overridden);
    out.base_color = select(mat.base_color.rgb, globals.color_override, overridden);
    // The other colour model's colour feeds the delta-e view alone: a
    // pipeline specialised to another view loads none. Lavapipe loads a
    // per-vertex material's field lane by lane, and computes outputs the
    // fragment stage never reads (the engine's vertex stage −16 %).
    // A select, not an `if` on uniforms (tests/uniform_branches.rs).
    let other = (view_mode() == VIEW_DELTA_E) & !overridden;
    out.other_model_color = select(globals.other_color_override, mat.other_model_color.rgb, other);
    // Selects, not an `if` on the uniform: see Knobs in shadow_map.wgsl.
    let scene = globals.use_scene_materials != 0u;
    let own_k = scene & ((mat.words.w & MATERIAL_OWN_K) != 0u);
    let own_m = scene & ((mat.words.w & MATERIAL_OWN_M) != 0u);
    let k = select(globals.k, bitcast<f32>(mat.words.x), own_k);
    let m = select(globals.m, bitcast<f32>(mat.words.y), own_m);
    let norm_factor = select(globals.norm_factor, mat.base_color.w, own_m);
    out.brdf = vec4<f32>(k, m, norm_factor, select(0.0, 1.0, (mat.words.w & MATERIAL_DOUBLE_SIDED) != 0u));
    out.knob_filter = vec4<u32>(shadow.pcf_size, shadow.range_block, shadow.pcss_blocker_samples, shadow.poisson_samples);
    out.knob_rays = vec4<u32>(rt.rays, rt.first_sample, rt.pair_count, globals.delta_e_defined);
    out.knob_radius_m = globals.light_radius_m;
    return out;
}

// The surface at a fragment, as the BRDF sees it.
struct Surface {
    // Shading normal (towards the viewer on double-sided materials).
    n: vec3<f32>,
    // Unit direction to the eye.
    o: vec3<f32>,
    // The facet's own normal, on the side of n: the tangent plane the shadow
    // map really holds (the interpolated normal of a curved mesh is not that plane).
    n_geo: vec3<f32>,
    // BRDF colour c (linear RGB), k and m.
    c: vec3<f32>,
    // c under the other colour model (spectral ↔ RGB approximation), for
    // the delta-e view.
    other_c: vec3<f32>,
    k: f32,
    m: f32,
    // N(m) under the chosen normalization, computed on the CPU (globals, or
    // the material's own m): no switch on a uniform, nor its exp2.
    norm_factor: f32,
    // The object receives shadows (Object::receives_shadows).
    receives_shadows: bool,
}

// Normals, colour, k and m at the fragment. Uses derivatives: call it in
// uniform control flow.
fn surface_at(in: VsOut, front_facing: bool) -> Surface {
    var s: Surface;
    s.o = normalize(-in.rel);
    let facet = normalize(cross(dpdx(in.rel), dpdy(in.rel)));
    let facet_to_eye = select(facet, -facet, dot(facet, s.o) < 0.0);
    // The face normal of the winding (counter-clockwise, as in the reference):
    // it is towards the eye exactly on front faces.
    let face = select(-facet_to_eye, facet_to_eye, front_facing);
    // Missing vertex normals are uploaded as zero: where the interpolated
    // normal vanishes the face's own is used, as the reference does
    // (normalize_or(face) in reference::Reference::new and surface).
    // (1e-30, not 0: GPUs that flush denormals would make inverseSqrt infinite.)
    let len2 = dot(in.normal, in.normal);
    s.n = select(face, in.normal * inverseSqrt(len2), len2 > 1e-30);
    if in.brdf.w != 0.0 && dot(s.n, s.o) < 0.0 {
        s.n = -s.n;
    }
    s.n_geo = select(facet, -facet, dot(facet, s.n) < 0.0);
    s.receives_shadows = in.receives_shadows != 0u;

    s.k = in.brdf.x;
    s.m = in.brdf.y;
    s.norm_factor = in.brdf.z;
    let colour = vertex_colour(in);
    s.c = in.base_color * colour;
    s.other_c = in.other_model_color * colour;
    if SPECIALISED_TEXTURES != 0u && in.texture_layer_plus_one > 0u {
        let layer = i32(in.texture_layer_plus_one - 1u);
        let texel = textureSampleLevel(base_textures, base_sampler, in.uv, layer, 0.0).rgb;
        s.c *= texel;
        s.other_c *= texel;
    }
    return s;
}

// V(p, q) ∈ [0, 1] from the source globals.visibility selects. A new source
// (a V texture, a GPU ray tracer) is one more case here; the radiance code
// does not change. p_l: the point relative to the light.
fn visibility(p_l: vec3<f32>, s: Surface, incidence: LightIncidence, pixel: vec2<f32>) -> f32 {
    // The reference's rule for every source: no shadow rays, V = 1.
    if !s.receives_shadows {
        return 1.0;
    }
    if visibility_mode() == VISIBILITY_RAY_TRACED {
        // Its own attached-shadow rule: a sphere light straddling the horizon is partly seen.
        return ray_traced_visibility(p_l + globals.shadow_apex_rel, s.n, s.n_geo, pixel);
    }
    if !shadows_enabled() {
        return 1.0;
    }
    // Attached shadow: the surface faces away from the light.
    if incidence.cos_theta <= 0.0 {
        return 0.0;
    }
    switch visibility_mode() {
        case VISIBILITY_SHADOW_MAP, default: {
            return shadow_map_visibility(p_l, s.n_geo, incidence.l, pixel);
        }
    }
}

// The delta-e view's value: ΔE2000 between the pixel shaded with this
// colour model and with the other one (both as displayed, × 2^EV); −1 where
// no spectral illuminant makes ΔE defined (the display shows "nothing").
// The BRDF's shape, E and V do not depend on the wavelength (colour::shading),
// so the two radiances differ only by their tints: radiance = tint · scale,
// scale = f_r/c · E · V.
fn delta_e_quantity(s: Surface, radiance: vec3<f32>, scale: f32) -> f32 {
    if knobs.rays.w == 0u {
        return -1.0;
    }
    let exposure = exp2(globals.exposure_ev);
    let other = tint(s.other_c, globals.other_light_color) * scale;
    return pixel_delta_e(radiance * exposure, other * exposure, globals.lab_white_relative);
}

// E at the fragment. A point light's pipeline passes the radius 0 as a
// constant, so that sphere_irradiance keeps only its point-light case.
fn light_irradiance(incidence: LightIncidence) -> f32 {
    let radius_m = select(0.0, knobs.radius_m, sphere_light());
    return sphere_irradiance(globals.light_power_w, radius_m, incidence.cos_theta, incidence.r);
}

// The quantity the chosen view shows, L = tint · (f_d + f_s) E V for
// `shaded`, given the visibility v from whichever source.
fn view_quantity(s: Surface, incidence: LightIncidence, v: f32, density: f32) -> vec3<f32> {
    let e = light_irradiance(incidence);
    let f = blinn_phong_scaled(s.n, incidence.l, s.o, s.k, s.m, s.norm_factor);
    let radiance_scale = tint(s.c, globals.light_color) * e * v;
    switch view_mode() {
        case VIEW_VISIBILITY: { return vec3<f32>(v); }
        case VIEW_NDOTL: { return vec3<f32>(max(incidence.cos_theta, 0.0)); }
        case VIEW_IRRADIANCE: { return vec3<f32>(e * v); }
        case VIEW_BRDF: { return vec3<f32>(f.x + f.y); }
        case VIEW_DIFFUSE: { return radiance_scale * f.x; }
        case VIEW_SPECULAR: { return radiance_scale * f.y; }
        case VIEW_TEXEL_DENSITY: { return vec3<f32>(density); }
        case VIEW_DELTA_E: {
            let brdf = f.x + f.y;
            return vec3<f32>(delta_e_quantity(s, radiance_scale * brdf, e * v * brdf), 0.0, 0.0);
        }
        default: { return radiance_scale * (f.x + f.y); }
    }
}

struct FsOut {
    // The chosen view's quantity (see settings::DebugView).
    @location(0) quantity: vec4<f32>,
    // x: V, y: shadow-map texels per pixel, z: max(0, n·l), w: 1 (covered).
    @location(1) aux: vec4<f32>,
}

// Both targets of a fragment; the entry points below write what they need.
fn shade_fragment(in: VsOut, front_facing: bool) -> FsOut {
    knobs = Knobs(in.knob_filter, in.knob_rays, in.knob_radius_m);
    let s = surface_at(in, front_facing);
    let incidence = light_incidence(globals.light_rel - in.rel, s.n);
    // The shadow map's own apex: the light, or a far light's stand-in.
    let p_l = in.rel - globals.shadow_apex_rel;
    // Derivatives: before any per-pixel branch.
    let density = shadow_map_texel_density(p_l, s.n_geo, incidence.l);
    let v = visibility(p_l, s, incidence, in.clip.xy);
    var out: FsOut;
    out.quantity = vec4<f32>(view_quantity(s, incidence, v, density), 1.0);
    out.aux = vec4<f32>(v, density, max(incidence.cos_theta, 0.0), 1.0);
    let mean = accumulated(out.quantity, out.aux, in.clip.xy);
    out.quantity = mean[0];
    out.aux = mean[1];
    return out;
}

@fragment
fn fs(in: VsOut, @builtin(front_facing) front_facing: bool) -> FsOut {
    return shade_fragment(in, front_facing);
}

// The same pass writing the quantity only (interaction frames, where nothing
// reads V or the texel density back): the aux terms are never computed.
@fragment
fn fs_quantity(in: VsOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return shade_fragment(in, front_facing).quantity;
}
