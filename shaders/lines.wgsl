// The light's frustum drawn over the image: edges hidden behind geometry
// dim, visible edges bright (two pipelines, reversed-Z depth tests).

@group(0) @binding(0) var<uniform> globals: Globals;

struct VsOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) color: vec4<f32>,
}

@vertex
fn vs(@location(0) rel: vec3<f32>, @location(1) color: vec4<f32>) -> VsOut {
    var out: VsOut;
    out.clip = globals.view_proj * vec4<f32>(rel, 1.0);
    out.color = color;
    return out;
}

@fragment
fn fs_visible(in: VsOut) -> @location(0) vec4<f32> {
    return in.color;
}

@fragment
fn fs_hidden(in: VsOut) -> @location(0) vec4<f32> {
    return vec4<f32>(in.color.rgb * 0.45, in.color.a);
}
