// Percentage-closer filtering of the depth map (`pcf`): n×n bilinear
// tests summed as separable weights, gathered 2×2 texels at a time on the
// receiver's own face, and decided at once where the depth range of the
// texels under the kernel leaves no doubt (gpu::depth_ranges).

// Bounds on the stored values over windows of 2×2 blocks of B×B texels, B =
// knobs.filters.y, Shadow's range_block (0: not built for this map, nothing
// to read): window e covers texels B e … B e + 2B − 1, where every stored
// value d lies within w of the plane x + y i + z j (i, j from the window's
// first texel; gpu::depth_ranges). 0 is the far plane (nothing drawn).
@group(1) @binding(6) var depth_ranges: texture_2d_array<f32>;

// The separable weight of texel i of the n + 1 a row of n bilinear tests
// touches, at fraction f: the first and last are partly covered.
fn pcf_weight(i: i32, n: i32, f: f32) -> f32 {
    return select(select(1.0, f, i == n), 1.0 - f, i == 0);
}

// pcf_weight summed over the texels lo … hi of a row (none when hi < lo).
fn pcf_weight_sum(lo: i32, hi: i32, n: i32, f: f32) -> f32 {
    let sum = f32(hi - lo + 1) - select(0.0, f, lo == 0) - select(0.0, 1.0 - f, hi == n);
    return select(0.0, sum, hi >= lo);
}

// What the taps of a PCF kernel on the receiver's own face share, computed
// once per receiver instead of once per tap: the layer's depth conversion,
// and compared_depth's terms as functions of the offset k (texels) from
// the kernel's first texel `base`. tangent_of_texel is affine on a face, so
// plane_depth's denominator dot(n_v, (t, −1)) is affine in k; its reach
// grows with the distance from base's centre + k to tc.
struct OwnFace {
    depth_a: f32,
    depth_b: f32,
    // Bias modes other than auto: the one compared depth.
    fixed: f32,
    // Auto: dot(n_v, v), the denominator at base's centre and its steps per
    // texel in x and y, base's centre − tc, and MAX_SLOPE × texel_m.
    numerator: f32,
    denominator: f32,
    step: vec2<f32>,
    offset: vec2<f32>,
    reach: f32,
}

fn own_face(r: Receiver, base: vec2<i32>) -> OwnFace {
    let f = frustum();
    let centre = vec2<f32>(base) + 0.5;
    let t = tangent_of_texel(centre);
    let per_texel = vec2<f32>(f.tan_right - f.tan_left, f.tan_bottom - f.tan_top) / resolution();
    return OwnFace(
        f.depth_a,
        f.depth_b,
        fixed_compared_depth(r),
        dot(r.n_v, r.v),
        dot(r.n_v, vec3<f32>(t, -1.0)),
        r.n_v.xy * per_texel,
        centre - r.tc,
        MAX_SLOPE * r.texel_m,
    );
}

// own_face_test for the texel base + k holding the stored value d (the
// same formulas; plane_depth's terms stepped from o's).
fn own_face_tap(o: OwnFace, r: Receiver, k: vec2<f32>, d: f32) -> f32 {
    let stored = stored_linear(d, o.depth_a, o.depth_b);
    var compared = o.fixed;
    if bias_mode() == BIAS_AUTO {
        let denom = o.denominator + dot(o.step, k);
        let reach = o.reach * max(length(o.offset + k), 0.5);
        compared = auto_compared_depth(r, plane_along(r, o.numerator, denom, reach));
    }
    return select(0.0, 1.0, compared <= stored);
}

// The weighted test of texel base + k of an n×n kernel at fraction f: 0
// outside the offsets lo … hi (off the kernel, k > n, or off the face: the
// second loop of filter_pcf).
fn own_face_texel(o: OwnFace, r: Receiver, lo: vec2<i32>, hi: vec2<i32>, k: vec2<i32>, n: i32, f: vec2<f32>, d: f32) -> f32 {
    let w = pcf_weight(k.x, n, f.x) * pcf_weight(k.y, n, f.y);
    let counted = all(k >= lo) && all(k <= hi);
    return select(0.0, w * own_face_tap(o, r, vec2<f32>(k), d), counted);
}

// n×n bilinear PCF: the average of n×n bilinear tests one texel apart,
// summed as separable weights over the (n + 1)² texels they touch.
fn filter_pcf(r: Receiver) -> f32 {
    let n = i32(knobs.filters.x);
    let c = r.tc - 0.5;
    let base = vec2<i32>(floor(c)) - vec2<i32>((n - 1) / 2);
    let f = fract(c);
    let o = own_face(r, base);
    let verdict = range_verdict(o, r, base, n);
    // Decided pixels run the loop below zero times. Lavapipe runs every
    // branch of a block of pixels under a mask, and a loop's body at least
    // once (its exit is tested at the end), but no more trips than its
    // busiest pixel needs. One loop, not one over rows and one over
    // columns: each loop level costs lavapipe its own set-up and exit tests
    // (the camera pass −11 % of instructions on the default scene).
    let last = select(n, -1, verdict >= 0.0);
    var sum = 0.0;
    // The taps, 2×2 texels a gather, k stepping along rows of the kernel.
    // A cube's faces overlap by more than the widest kernel (gpu::shared,
    // CUBE_DEPTH_MARGIN_TEXELS): a kernel never leaves its face. A single
    // frustum's may: its offsets k on the map are one bound per pixel, not
    // in_map per texel.
    let lo = max(-base, vec2<i32>(0));
    let hi = min(vec2<i32>(i32(resolution()) - 1) - base, vec2<i32>(n));
    for (var k = vec2<i32>(0); k.y <= last; k = select(k + vec2<i32>(2, 0), vec2<i32>(0, k.y + 2), k.x + 2 > last)) {
        // Texels k + (0, 1), (1, 1), (1, 0), k (textureGather's order).
        let d = gather_depths(r.layer, base + k);
        sum += own_face_texel(o, r, lo, hi, k + vec2<i32>(0, 1), n, f, d.x)
            + own_face_texel(o, r, lo, hi, k + vec2<i32>(1, 1), n, f, d.y)
            + own_face_texel(o, r, lo, hi, k + vec2<i32>(1, 0), n, f, d.z)
            + own_face_texel(o, r, lo, hi, k, n, f, d.w);
    }
    // Some of the kernel is off the map: its bounds on it are not 0 … n.
    let crossing = any(lo != vec2<i32>(0)) || any(hi != vec2<i32>(n));
    // A single frustum drew nothing past its edge: those taps are lit, the
    // kernel's weight off the map in closed form (no loop to pay for).
    let on_map = pcf_weight_sum(lo.x, hi.x, n, f.x) * pcf_weight_sum(lo.y, hi.y, n, f.y);
    sum += select(0.0, f32(n * n) - on_map, crossing && !is_cube());
    return select(sum / f32(n * n), verdict, verdict >= 0.0);
}

// What the window of depth_ranges holding the texels base … base + n a
// filter reads (PCF's kernel, or the square around a Poisson disc) says
// of all its tests at once: 1 every texel lights the receiver, 0 every
// texel hides it, −1 undecided (each is tested). The window's plane at the
// kernel's corners bounds the stored values under it. The compared depth
// of own_face_tap is at most r.z − slack (auto) and at least
// r.z − reach − slack, reach taken at the kernel's corner farthest from tc;
// the other biases compare one depth. The auto bias also lights a receiver
// whose own plane is what the map stored (plane_lights). The margin covers
// rounding: deciding fewer pixels is always right, and the decided ones
// get the value the loops would have summed (1 up to the weights'
// rounding, or exactly 0).
fn range_verdict(o: OwnFace, r: Receiver, base: vec2<i32>, n: i32) -> f32 {
    let block = i32(knobs.filters.y);
    let known = block >= n && n >= 0 && block > 0 && in_map(base) && in_map(base + vec2<i32>(n)) && (shadow.layer_mask & (1u << r.layer)) != 0u;
    var verdict = -1.0;
    if known {
        let window = base / block;
        let bound = textureLoad(depth_ranges, window, i32(r.layer), 0);
        // The plane at the kernel's corners k = (0, 0), (n, 0), (0, n), (n, n).
        let first = vec2<f32>(base - window * block);
        let span = f32(n);
        let along = plane_corners(bound.x, bound.yz, first, span);
        let nearest = stored_linear(largest(along) + bound.w, o.depth_a, o.depth_b);
        let farthest = stored_linear(smallest(along) - bound.w, o.depth_a, o.depth_b);
        var highest = o.fixed;
        var lowest = o.fixed;
        var own_plane = false;
        if bias_mode() == BIAS_AUTO {
            let corner = max(abs(o.offset), abs(o.offset + span));
            let slack = auto_bias_slack(r);
            highest = r.z - slack;
            lowest = highest - o.reach * max(length(corner), 0.5);
            own_plane = plane_lights(o, r, along + bound.w, slack, nearest, span);
        }
        let margin = 1e-5 * r.z;
        verdict = select(select(-1.0, 0.0, lowest - margin > farthest), 1.0, highest + margin <= nearest || own_plane);
    }
    return verdict;
}

// Whether every own_face_tap of the auto bias over a kernel of n + 1
// texels a side lights the receiver, given `above`, the largest stored
// value d at the kernel's corners (as range_verdict orders them) along the
// window's plane, and `nearest`, the nearest stored depth under the kernel.
// A tap at k compares max(min(P, r.z), r.z − reach) − slack with the stored
// depth, P the receiver's plane along the texel's ray. It lights where
//   the stored depth ≥ r.z − reach − slack: reach ≥ o.reach / 2 at every
//     texel, so nearest ≥ r.z − o.reach / 2 − slack is enough; and
//   the stored depth ≥ P − slack: in inverse depths, 1 / stored =
//     (d − depth_b) / depth_a and 1 / P = denominator / numerator are both
//     affine in k, and 1 / (P − slack) ≥ 1 / P + slack / P², so
//     1 / stored − 1 / P ≤ slack / P_max² is enough. An affine difference
//     is largest at a corner.
// The receiver's plane must face the light over the whole kernel.
fn plane_lights(o: OwnFace, r: Receiver, above: vec4<f32>, slack: f32, nearest: f32, span: f32) -> bool {
    let denominators = plane_corners(o.denominator, o.step, vec2<f32>(0.0), span);
    let facing = o.numerator < 0.0 && all(denominators < vec4<f32>(-1e-4));
    let inverse_plane = denominators / o.numerator;
    let inverse_stored = (above - o.depth_b) / o.depth_a;
    let gap = inverse_stored - inverse_plane;
    let least = smallest(inverse_plane);
    let most = largest(inverse_plane);
    let below_plane = largest(gap) <= slack * least * least - 1e-5 * most;
    let within_reach = nearest >= r.z - 0.5 * o.reach - slack + 1e-5 * r.z;
    return facing && below_plane && within_reach;
}

// The stored values of texels t + (0, 1), (1, 1), (1, 0) and t of a layer
// (textureGather's order), clamped to the map's edge: one fetch for four.
// The sample point is the corner the four share.
fn gather_depths(layer: u32, t: vec2<i32>) -> vec4<f32> {
    let corner = vec2<f32>(t + 1) / resolution();
    return textureGather(0, shadow_depth_values, shadow_depth_gather, corner, i32(layer));
}
