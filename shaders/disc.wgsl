// The Poisson-disc filters (`poisson`, `pcss`): taps at a disc's points,
// rotated per pixel, tested on the receiver's own layer in the loop over
// the taps and, past a cube face's edge, after it (cube addressing, as
// depth_test does).

// The taps of a filter that lie past the edge of a cube face, up to 64:
// tap s is bit s % 32 of word s / 32. Lavapipe runs both sides of every
// branch under a lane mask, so a filter that called depth_test tap by tap
// paid for the cube addressing at every tap. The filters test the taps on
// the receiver's own layer in their loop, keep the others in such a set
// and test those after it, in a loop of as many trips as the busiest pixel
// of a block has such taps (one masked trip where none has).
fn with_tap(taps: vec2<u32>, s: u32, past_edge: bool) -> vec2<u32> {
    let bit = select(0u, 1u << (s & 31u), past_edge);
    return taps | select(vec2<u32>(bit, 0u), vec2<u32>(0u, bit), s >= 32u);
}

// The lowest tap of a set that holds one.
fn first_tap(taps: vec2<u32>) -> u32 {
    return select(32u + firstTrailingBit(taps.y), firstTrailingBit(taps.x), taps.x != 0u);
}

// The set without its lowest tap.
fn without_first(taps: vec2<u32>) -> vec2<u32> {
    return select(vec2<u32>(taps.x, taps.y & (taps.y - 1u)), vec2<u32>(taps.x & (taps.x - 1u), taps.y), taps.x != 0u);
}

// depth_test for a texel on the receiver's own layer (stored value d) or
// past a single frustum's edge (lit); −1 for one past a cube face's edge,
// left to the caller's depth_test.
fn own_layer_test(r: Receiver, texel: vec2<i32>, d: f32) -> f32 {
    return select(select(1.0, -1.0, is_cube()), own_face_test_of(r, texel, d), in_map(texel));
}

// The stored value of a texel of `layer`, clamped to the map's edge.
fn stored_value(layer: u32, texel: vec2<i32>) -> f32 {
    let last = vec2<i32>(i32(resolution()) - 1);
    return textureLoad(shadow_depth_values, clamp(texel, vec2<i32>(0), last), i32(layer), 0).x;
}

// bilinear_test where none of its texels lies past a cube face's edge;
// −1 where one does.
fn own_layer_bilinear(r: Receiver, tc: vec2<f32>) -> f32 {
    let c = tc - 0.5;
    let base = vec2<i32>(floor(c));
    let f = fract(c);
    // Texels base + (0, 1), (1, 1), (1, 0) and base: one fetch.
    let d = gather_depths(r.layer, base);
    let t00 = own_layer_test(r, base, d.w);
    let t10 = own_layer_test(r, base + vec2<i32>(1, 0), d.z);
    let t01 = own_layer_test(r, base + vec2<i32>(0, 1), d.x);
    let t11 = own_layer_test(r, base + vec2<i32>(1, 1), d.y);
    let past_edge = min(min(t00, t10), min(t01, t11)) < 0.0;
    return select(mix(mix(t00, t10, f.x), mix(t01, t11, f.x), f.y), -1.0, past_edge);
}

// Interleaved gradient noise: a per-pixel rotation that tiles without pattern.
fn pixel_angle(pixel: vec2<f32>) -> f32 {
    return 6.2831853 * fract(52.9829189 * fract(dot(pixel, vec2<f32>(0.06711056, 0.00583715))));
}

// The rotation by a pixel's angle as (cos, sin), computed once per pixel
// and applied to each of its taps by `rotate`.
fn rotation(angle: f32) -> vec2<f32> {
    return vec2<f32>(cos(angle), sin(angle));
}

// v rotated by the rotation cs = (cos, sin).
fn rotate(v: vec2<f32>, cs: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(cs.x * v.x - cs.y * v.y, cs.y * v.x + cs.x * v.y);
}

// Where tap s of a disc of `radius` texels around the receiver lies.
fn disc_point(r: Receiver, s: u32, spin: vec2<f32>, radius: f32) -> vec2<f32> {
    return r.tc + rotate(POISSON_DISC[s], spin) * radius;
}

// The texel tap s of a disc of `radius` texels reads.
fn disc_texel(r: Receiver, s: u32, spin: vec2<f32>, radius: f32) -> vec2<i32> {
    return vec2<i32>(floor(disc_point(r, s, spin, radius)));
}

// range_verdict for every texel a disc of `radius` texels around the
// receiver reads: those from floor(tc − R) to floor(tc + R), one more each
// side for the rotation's rounding (gpu::depth_ranges::level_for bounds
// the span alike).
fn disc_verdict(r: Receiver, radius: f32) -> f32 {
    let base = vec2<i32>(floor(r.tc - radius)) - 1;
    let span = vec2<i32>(floor(r.tc + radius)) + 1 - base;
    return range_verdict(own_face(r, base), r, base, max(span.x, span.y));
}

fn filter_poisson(r: Receiver, pixel: vec2<f32>) -> f32 {
    let radius = shadow.poisson_radius_texels;
    let verdict = disc_verdict(r, radius);
    // Decided pixels take no tap (a loop of zero trips, as in filter_pcf).
    let count = select(knobs.filters.w, 0u, verdict >= 0.0);
    let spin = rotation(pixel_angle(pixel));
    var sum = 0.0;
    var past_edge = vec2<u32>(0u);
    for (var s = 0u; s < count; s++) {
        let texel = disc_texel(r, s, spin, radius);
        let v = own_layer_test(r, texel, stored_value(r.layer, texel));
        sum += max(v, 0.0);
        past_edge = with_tap(past_edge, s, v < 0.0);
    }
    // Each test is 0 or 1: their sum is the same in any order.
    for (var rest = past_edge; any(rest != vec2<u32>(0u)); rest = without_first(rest)) {
        sum += depth_test(r, disc_texel(r, first_tap(rest), spin, radius));
    }
    return select(sum / f32(knobs.filters.w), verdict, verdict >= 0.0);
}

// Percentage-closer soft shadows for the sphere light of radius R: the
// blockers' mean depth sizes the penumbra by similar triangles through the
// light's diameter, w = 2R (z − z_blocker) / z_blocker, and a filter of
// radius w/2 spreads the edge over w. A point light (R = 0) searches no
// blocker: its filter is the one bilinear test at tc (tap 0, offset 0).
// The taps on the receiver's own face are tested in the loops over the
// taps; those past a cube face's edge after them (see with_tap).
fn filter_pcss(r: Receiver, pixel: vec2<f32>) -> f32 {
    let radius_m = knobs.radius_m;
    let point = radius_m <= 0.0;
    let f = frustum();
    let near = f.near_m;
    let spin = rotation(pixel_angle(pixel));
    // Blockers lie between the light and the receiver: the light's disc seen
    // from the receiver covers at most this many texels at the near plane.
    let search = clamp(radius_m * (r.z - near) / (r.z * near) / (r.texel_m / r.z), 1.0, MAX_FILTER_RADIUS_TEXELS);
    var blocker_sum = 0.0;
    var blockers = 0.0;
    var past_edge = vec2<u32>(0u);
    // Where the depth ranges say that every texel of the search's square
    // lights the receiver, no tap finds a blocker: none is taken.
    let clear = disc_verdict(r, search) >= 1.0;
    for (var s = 0u; s < select(knobs.filters.z, 0u, point || clear); s++) {
        let texel = disc_texel(r, s, spin, search);
        let d = stored_value(r.layer, texel);
        // A blocker: a texel on the receiver's layer that hides it.
        let v = own_layer_test(r, texel, d);
        let blocks = v == 0.0;
        blocker_sum += select(0.0, stored_linear(d, f.depth_a, f.depth_b), blocks);
        blockers += select(0.0, 1.0, blocks);
        past_edge = with_tap(past_edge, s, v < 0.0);
    }
    for (var rest = past_edge; any(rest != vec2<u32>(0u)); rest = without_first(rest)) {
        let t = tap(r, disc_texel(r, first_tap(rest), spin, search));
        // On a neighbouring face both depths are along that face's axis.
        let z_s = stored_depth(t.r.layer, t.texel);
        let blocks = t.drawn && z_s < compared_depth(t.r, t.texel);
        // In the receiver's face's terms: the same ratio z_s / z.
        blocker_sum += select(0.0, z_s * (r.z / t.r.z), blocks);
        blockers += select(0.0, 1.0, blocks);
    }
    let z_blocker = blocker_sum / blockers;
    let penumbra_m = 2.0 * radius_m * (r.z - z_blocker) / z_blocker;
    let filter_texels = select(clamp(0.5 * penumbra_m / r.texel_m, 0.5, MAX_FILTER_RADIUS_TEXELS), 0.0, point);
    // Without blockers the receiver is lit: no filter tap.
    let lit = blockers == 0.0 && !point;
    let count = select(select(knobs.filters.w, 1u, point), 0u, lit);
    var sum = 0.0;
    past_edge = vec2<u32>(0u);
    for (var s = 0u; s < count; s++) {
        let v = own_layer_bilinear(r, disc_point(r, s, spin, filter_texels));
        sum += max(v, 0.0);
        past_edge = with_tap(past_edge, s, v < 0.0);
    }
    for (var rest = past_edge; any(rest != vec2<u32>(0u)); rest = without_first(rest)) {
        sum += bilinear_test(r, disc_point(r, first_tap(rest), spin, filter_texels));
    }
    return select(sum / f32(max(count, 1u)), 1.0, lit);
}
