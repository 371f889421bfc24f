// The running mean of a sphere light's ray-traced frames where the camera
// pass's targets are f16 (gpu::accumulate): the camera pass writes each
// frame as it is; this pass folds it into an f32 history and writes the mean
// for the targets. In f16 a mean stops moving once (V − mean) / (N + 1) is
// under half a step: some 64 frames.

struct Fold {
    // Weight of this frame in the running mean: 1 / (frames before + 1), or
    // 0 once the accumulation is complete (the history then holds).
    weight: f32,
    _padding0: u32,
    _padding1: u32,
    _padding2: u32,
}

@group(0) @binding(0) var<uniform> fold: Fold;
// This frame's targets (f16).
@group(0) @binding(1) var frame_quantity: texture_2d<f32>;
@group(0) @binding(2) var frame_aux: texture_2d<f32>;
// The running mean in f32: layers 0–3 the quantity's channels, 4–7 the aux's.
@group(0) @binding(3) var history: texture_storage_2d_array<r32float, read_write>;
// The mean, for the targets (copied there after this pass).
@group(0) @binding(4) var mean_quantity: texture_storage_2d<rgba16float, write>;
@group(0) @binding(5) var mean_aux: texture_storage_2d<rgba16float, write>;

// One target's texel folded into the history's layers first … first + 3. A
// frame of weight 1 starts the mean: the history's texels are not mixed in
// (0 · ∞ would leave a NaN where an f16 frame overflowed).
fn fold_texel(texel: vec2<u32>, first: u32, frame: vec4<f32>) -> vec4<f32> {
    var before: vec4<f32>;
    for (var c = 0u; c < 4u; c++) {
        before[c] = textureLoad(history, texel, first + c).x;
    }
    let mean = select(mix(before, frame, fold.weight), frame, fold.weight >= 1.0);
    for (var c = 0u; c < 4u; c++) {
        textureStore(history, texel, first + c, vec4<f32>(mean[c], 0.0, 0.0, 0.0));
    }
    return mean;
}

@compute @workgroup_size(8, 8)
fn fold_frame(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(frame_quantity);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let texel = id.xy;
    textureStore(mean_quantity, texel, fold_texel(texel, 0u, textureLoad(frame_quantity, texel, 0)));
    textureStore(mean_aux, texel, fold_texel(texel, 4u, textureLoad(frame_aux, texel, 0)));
}
