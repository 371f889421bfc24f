// The largest value the view shows, for false-colour scales: one atomic max
// per workgroup into result[0]. Positive floats order like their bits.

@group(0) @binding(0) var quantity: texture_2d<f32>;
@group(0) @binding(1) var comparison: texture_2d<f32>;
@group(0) @binding(2) var<storage, read_write> result: array<atomic<u32>, 4>;
@group(0) @binding(3) var<uniform> params: DisplayParams;

// The value a false-colour view scales by (its largest over the image).
// A select, not an `if` on the uniform: lavapipe would compile the shader
// anew for each value (tests/uniform_branches.rs).
fn scaled_value(q: vec3<f32>, reference: vec3<f32>) -> f32 {
    return select(q.x, abs(luminance(q) - luminance(reference)), params.view == VIEW_ERROR);
}

var<workgroup> group_max: atomic<u32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local: u32) {
    if local == 0u {
        atomicStore(&group_max, 0u);
    }
    workgroupBarrier();
    let size = textureDimensions(quantity);
    if id.x < size.x && id.y < size.y {
        let texel = vec2<i32>(id.xy);
        let q = textureLoad(quantity, texel, 0);
        // Alpha: coverage (0 on the background).
        if q.a > 0.0 {
            let value = scaled_value(q.rgb, textureLoad(comparison, texel, 0).rgb);
            if value > 0.0 && value < 3.0e38 {
                atomicMax(&group_max, bitcast<u32>(value));
            }
        }
    }
    workgroupBarrier();
    if local == 0u {
        atomicMax(&result[0], atomicLoad(&group_max));
    }
}
