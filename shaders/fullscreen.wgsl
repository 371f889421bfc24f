// The vertex stage of gpu::binding::fullscreen_pipeline: one triangle that
// covers the target, for the passes that shade every pixel of it.

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    return fullscreen_position(i);
}
