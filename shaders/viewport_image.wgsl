// The viewport's image drawn straight into the window's render pass
// (app::viewport_image): the renderer's 8-bit display frame, its sRGB bytes
// held in an Rgba8Unorm texture, stretched over the rectangle egui gives it.
// The image is opaque: no blending, no vertex colour and no dithering, which
// egui's mesh shader would pay for on every pixel of it.

struct ImageParams {
    // The part of the texture shown (0..1), top left and bottom right.
    uv_min: vec2<f32>,
    uv_max: vec2<f32>,
}

@group(0) @binding(0) var<uniform> image_params: ImageParams;
@group(0) @binding(1) var image: texture_2d<f32>;
@group(0) @binding(2) var image_sampler: sampler;

struct ImageOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
}

// One triangle over the viewport egui sets to the image's rectangle.
@vertex
fn vs(@builtin(vertex_index) i: u32) -> ImageOut {
    let corner = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    // From the top left (0, 0) to the bottom right (1, 1) of the rectangle.
    let t = vec2<f32>(corner.x, 1.0 - corner.y);
    var out: ImageOut;
    out.clip = vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);
    out.uv = mix(image_params.uv_min, image_params.uv_max, t);
    return out;
}

// A window whose format stores the bytes written (egui's choice where it can).
@fragment
fn fs(in: ImageOut) -> @location(0) vec4<f32> {
    return vec4<f32>(textureSampleLevel(image, image_sampler, in.uv, 0.0).rgb, 1.0);
}

// A window whose format sRGB-encodes what is written: the bytes are decoded
// first, so that they reach the screen unchanged.
@fragment
fn fs_srgb_target(in: ImageOut) -> @location(0) vec4<f32> {
    let c = textureSampleLevel(image, image_sampler, in.uv, 0.0).rgb;
    return vec4<f32>(srgb_decode(c.r), srgb_decode(c.g), srgb_decode(c.b), 1.0);
}
