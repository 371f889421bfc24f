//! The GPU renderer: draws a scene into textures on a given `wgpu::Device`.
//! The app shows them, the command line writes them, the tests read them back.
//! One file per pass: `shadow` (depth from the light), `shade` (the camera
//! pass), `display` (what people see), `lines` (the frustum overlay).
//! `shared` holds what the views of one scene share (the uploaded scene, the
//! shadow maps); `renderer` is one view over it, drawing into its `targets`.
//! Visibility V is a source of its own (settings::Visibility): the camera
//! pass's `visibility` in shaders/shade.wgsl dispatches on it, today to the
//! shadow map (shaders/shadow_map.wgsl) or the ray tracer (`raytrace`, over
//! the casters' BVH in `bvh`).

pub mod accumulate;
pub mod binding;
pub mod bvh;
pub mod bvh_build;
pub mod capabilities;
pub mod colormap;
pub mod context;
pub mod delta_e;
pub mod depth_ranges;
pub mod display;
pub mod flat;
pub mod frame_report;
pub mod light_frustum;
pub mod lines;
pub mod noise;
pub mod raytrace;
pub mod readback;
pub mod renderer;
pub mod scene_buffers;
pub mod shade;
pub mod shaders;
pub mod shadow;
pub mod shared;
pub mod specialise;
pub mod spectral;
pub mod targets;
pub mod timing;
pub mod uniforms;

pub use capabilities::Capabilities;
pub use context::{GpuContext, GpuError};
pub use frame_report::FrameReport;
pub use renderer::{ComparisonImage, Renderer};
pub use specialise::ShadeOptions;
pub use targets::{FloatTarget, PendingScale, PendingTexels};
