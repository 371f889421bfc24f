// The vertex stage of gpu::binding::fullscreen_pipeline: one triangle that
// covers the target, for the passes that shade every pixel of it.

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}
