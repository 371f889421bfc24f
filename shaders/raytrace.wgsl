// Ray-traced visibility (settings::Visibility::RayTraced): shadow rays from
// the shaded point through the casters' BVH (bvh.wgsl), and the progressive
// accumulation of the frames while nothing changes (gpu::raytrace).
//
// Conventions of the CPU reference (reference/shading.rs), in f32: the ray
// starts off the surface along the facet's normal on the viewer's side and
// stops short of the light; a point light gets one ray (V ∈ {0, 1}); a sphere
// light gets S directions in the solid angle of its cone a frame, the next S
// points of a low-discrepancy sequence of the pixel's (rt_r2), so that the
// frames' mean is that of one well-spread set of N · S directions,
// V = Σ V_i cos⁺θ_i / Σ cos⁺θ_i a frame.

struct RayTrace {
    // Frames already in the history this pass folds the frame into; 0: it
    // folds nothing in (a mean starting, a point light's frame, or f16
    // targets, whose mean gpu::accumulate keeps after the pass).
    frames_before: u32,
    // Weight of this frame in the running mean: 1 / (frames_before + 1), or
    // 0 once the accumulation is complete (the history then holds).
    weight: f32,
    // Rays towards the sphere light per pixel and frame, S.
    rays: u32,
    // This frame's first sample in each pixel's sequence: frames_before · S.
    first_sample: u32,
    // Entries of the BVH's pairs (0: nothing casts shadows).
    pair_count: u32,
    _padding0: u32,
    _padding1: u32,
    _padding2: u32,
    // The grid of the BVH's boxes (bvh.wgsl).
    grid: BvhGrid,
}

@group(2) @binding(0) var<uniform> rt: RayTrace;

// A pipeline-overridable constant (gpu::specialise), SPECIALISE_ANY to read
// the uniform. A software rasterizer runs the code of a branch the uniforms
// skip under an empty mask: a frame that starts the mean compiles none of
// the history's loads (and a point light's, shade.wgsl's sphere_light, none
// of the cone's sampling). This frame is folded into the history (1) or
// starts it (0):
override SPECIALISED_ACCUMULATING: u32 = SPECIALISE_ANY;

// A sphere light's rays traced one at a time (1), four to a walk (4,
// bvh_occluded8 with `eight` false) or eight (8), as gpu::raytrace's
// rays_per_walk picks from S, with its thresholds: a walk for four costs
// some 45 % more than a walk for one and about half as much as four walks;
// one for eight some 60 % more than one for four (lavapipe, callgrind).
override SPECIALISED_RAYS_PER_WALK: u32 = SPECIALISE_ANY;

fn rays_per_walk() -> u32 {
    let rays = knobs.rays.x;
    let width = select(select(4u, 8u, rays >= EIGHT_RAYS_A_WALK_FROM), 1u, rays < FOUR_RAYS_A_WALK_FROM);
    return select(SPECIALISED_RAYS_PER_WALK, width, SPECIALISED_RAYS_PER_WALK == SPECIALISE_ANY);
}

fn accumulating() -> bool {
    let history_read = u32(rt.frames_before > 0u);
    return select(SPECIALISED_ACCUMULATING, history_read, SPECIALISED_ACCUMULATING == SPECIALISE_ANY) != 0u;
}

// The previous frame's targets (quantity, aux): the running mean so far.
@group(2) @binding(3) var history_quantity: texture_2d<f32>;
@group(2) @binding(4) var history_aux: texture_2d<f32>;

// Shadow-ray origin offset along the facet normal, relative to the point's
// magnitude (largest |world coordinate| and its distance to the eye): f32
// keeps ~6·10⁻⁸ of it, and the rasterized position carries the depth
// interpolation's rounding; 10⁻⁵ is ~100 times both (0.1 mm at 10 m).
const RT_OFFSET_REL: f32 = 1e-5;
// Shadow rays end this fraction of their length before the light.
const RT_STOP_SHORT_REL: f32 = 1e-5;

// PCG hash (Jarzynski & Olano 2020): one well-mixed u32 per input.
fn rt_hash(x: u32) -> u32 {
    let state = x * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// 2³² / φ₂ and 2³² / φ₂², φ₂ the plastic number (x³ = x + 1): the steps
// of the R2 sequence (Roberts 2018), point i = frac(i · (1/φ₂, 1/φ₂²)).
const RT_R2_STEP: vec2<u32> = vec2<u32>(3242174889u, 2447445414u);

// Point i of the R2 sequence turned by `offset` (a Cranley–Patterson
// rotation, in 32-bit fixed point: exact however long the sequence), in
// [0, 1)² (the top 24 bits). Any run of consecutive points is spread
// evenly over the square, so a pixel's rays of one frame and those of all
// its frames together are both well spread: the mean converges faster
// than 1/√N where the integrand has edges (a shadow's across the light).
fn rt_r2(i: u32, offset: vec2<u32>) -> vec2<f32> {
    let q = vec2<u32>(i) * RT_R2_STEP + offset;
    return vec2<f32>(q >> vec2<u32>(8u)) * (1.0 / 16777216.0);
}

// Whether the segment from `origin_rel` along d (both relative to the eye)
// is blocked before its end.
fn rt_blocked(origin_rel: vec3<f32>, d: vec3<f32>) -> bool {
    return bvh_occluded(origin_rel + globals.eye, d, 1.0 - RT_STOP_SHORT_REL, knobs.rays.z, rt.grid);
}

// rt_blocked for four segments from one origin, those `live_lo`, and where
// `eight` four more, those `live_hi` (bvh_occluded8).
fn rt_blocked8(origin_rel: vec3<f32>, d_lo: BvhRays4, d_hi: BvhRays4, live_lo: vec4<bool>, live_hi: vec4<bool>, eight: bool) -> BvhBlocked8 {
    return bvh_occluded8(origin_rel + globals.eye, d_lo, d_hi, 1.0 - RT_STOP_SHORT_REL, live_lo, live_hi, eight, knobs.rays.z, rt.grid);
}

// A sphere light's cone of directions seen from a point: its axis w and a
// frame (t1, t2) around it, 1 − cos α of its half-angle, the distance d to
// the light's centre, R² and d²; the point, the shadow rays' origin (both
// relative to the eye) and the shading normal there.
struct RtCone {
    w: vec3<f32>,
    t1: vec3<f32>,
    t2: vec3<f32>,
    gap_max: f32,
    dist: f32,
    r2: f32,
    d2: f32,
    rel: vec3<f32>,
    origin: vec3<f32>,
    n: vec3<f32>,
}

// Ray k of this frame's S (knobs.rays.x) towards the cone: the segment from
// the ray's origin to the near side of the sphere along the direction of
// the pixel's sample first_sample + k (knobs.rays.y + k), turned by
// `offset` (xyz), and its cos⁺θ at the point (w); w = 0 for k ≥ S. (u, v)
// uniform in the square is a direction uniform in the cone's solid angle.
fn rt_ray(cone: RtCone, k: u32, offset: vec2<u32>) -> vec4<f32> {
    let uv = rt_r2(knobs.rays.y + k, offset);
    let gap = uv.x * cone.gap_max;
    let cos_theta = 1.0 - gap;
    let sin2_theta = max(gap * (2.0 - gap), 0.0);
    let phi = 2.0 * PI * uv.y;
    let l = cone.w * cos_theta + (cone.t1 * cos(phi) + cone.t2 * sin(phi)) * sqrt(sin2_theta);
    let c = select(0.0, max(dot(cone.n, l), 0.0), k < knobs.rays.x);
    // The near intersection with the sphere along l.
    let t = cone.dist * cos_theta - sqrt(max(cone.r2 - cone.d2 * sin2_theta, 0.0));
    return vec4<f32>(cone.rel + l * t - cone.origin, c);
}

// Rays k … k + 3 of rt_ray: their segments (the columns of d) and cos⁺θ.
struct RtRays4 {
    d: BvhRays4,
    c: vec4<f32>,
}

fn rt_rays4(cone: RtCone, k: u32, offset: vec2<u32>) -> RtRays4 {
    let s0 = rt_ray(cone, k, offset);
    let s1 = rt_ray(cone, k + 1u, offset);
    let s2 = rt_ray(cone, k + 2u, offset);
    let s3 = rt_ray(cone, k + 3u, offset);
    return RtRays4(BvhRays4(s0.xyz, s1.xyz, s2.xyz, s3.xyz), vec4<f32>(s0.w, s1.w, s2.w, s3.w));
}

// Adds four rays' cos⁺θ to `cos_sum` and those not `blocked` to
// `visible_cos_sum`, one ray after the other.
fn rt_sum4(cos_sum: ptr<function, f32>, visible_cos_sum: ptr<function, f32>, c: vec4<f32>, blocked: vec4<bool>) {
    let seen = select(c, vec4<f32>(0.0), blocked);
    for (var j = 0u; j < 4u; j++) {
        *cos_sum += c[j];
        *visible_cos_sum += seen[j];
    }
}

// V at the point p = eye + rel with shading normal n and facet normal n_geo
// (on the viewer's side).
fn ray_traced_visibility(rel: vec3<f32>, n: vec3<f32>, n_geo: vec3<f32>, pixel: vec2<f32>) -> f32 {
    if !shadows_enabled() {
        return 1.0;
    }
    let p = rel + globals.eye;
    let offset = RT_OFFSET_REL * max(max(abs(p.x), abs(p.y)), max(abs(p.z), length(rel)));
    let origin = rel + n_geo * offset;
    let to_centre = globals.light_rel - rel;
    let radius = knobs.radius_m;
    if !sphere_light() {
        // Attached shadow: the light below the surface's horizon.
        if dot(n, to_centre) <= 0.0 {
            return 0.0;
        }
        return select(1.0, 0.0, rt_blocked(origin, globals.light_rel - origin));
    }
    let d2 = dot(to_centre, to_centre);
    if d2 <= radius * radius {
        // Inside the light: it is seen in every direction.
        return 1.0;
    }
    let dist = sqrt(d2);
    let w = to_centre / dist;
    let sin2_alpha = radius * radius / d2;
    // An orthonormal frame around w (Duff et al. 2017).
    let sign = select(-1.0, 1.0, w.z >= 0.0);
    let a = -1.0 / (sign + w.z);
    let b = w.x * w.y * a;
    let cone = RtCone(
        w,
        vec3<f32>(1.0 + sign * w.x * w.x * a, sign * b, -sign * w.x),
        vec3<f32>(b, sign + w.y * w.y * a, -w.y),
        // 1 − cos α without cancellation for far lights.
        sin2_alpha / (1.0 + sqrt(1.0 - sin2_alpha)),
        dist,
        radius * radius,
        d2,
        rel,
        origin,
        n,
    );
    // The pixel's own rotation of the sequence, the same in every frame.
    let seed = rt_hash(u32(pixel.x) ^ rt_hash(u32(pixel.y)));
    let turn = vec2<u32>(seed, rt_hash(seed));
    var cos_sum = 0.0;
    var visible_cos_sum = 0.0;
    let width = rays_per_walk();
    if width == 1u {
        for (var k = 0u; k < knobs.rays.x; k++) {
            let s = rt_ray(cone, k, turn);
            cos_sum += s.w;
            if s.w > 0.0 && !rt_blocked(origin, s.xyz) {
                visible_cos_sum += s.w;
            }
        }
        return select(0.0, visible_cos_sum / cos_sum, cos_sum > 0.0);
    }
    // The rays four or eight at a time, traced in one walk (bvh_occluded8).
    let eight = width == 8u;
    for (var k = 0u; k < knobs.rays.x; k += width) {
        let lo = rt_rays4(cone, k, turn);
        var hi = lo;
        if eight {
            hi = rt_rays4(cone, k + 4u, turn);
        }
        let blocked = rt_blocked8(origin, lo.d, hi.d, lo.c > vec4<f32>(0.0), hi.c > vec4<f32>(0.0), eight);
        // In the rays' order, as one ray at a time would sum them.
        rt_sum4(&cos_sum, &visible_cos_sum, lo.c, blocked.lo);
        if eight {
            rt_sum4(&cos_sum, &visible_cos_sum, hi.c, blocked.hi);
        }
    }
    return select(0.0, visible_cos_sum / cos_sum, cos_sum > 0.0);
}

// This frame's targets folded into the running mean of the frames before.
// (visibility_mode(): a pipeline specialised to the shadow map compiles
// none of it; a software rasterizer would load the history texels anyway.)
fn accumulated(quantity: vec4<f32>, aux: vec4<f32>, pixel: vec2<f32>) -> array<vec4<f32>, 2> {
    if visibility_mode() != VISIBILITY_RAY_TRACED || !accumulating() {
        return array<vec4<f32>, 2>(quantity, aux);
    }
    let texel = vec2<i32>(pixel);
    return array<vec4<f32>, 2>(
        mix(textureLoad(history_quantity, texel, 0), quantity, rt.weight),
        mix(textureLoad(history_aux, texel, 0), aux, rt.weight),
    );
}
