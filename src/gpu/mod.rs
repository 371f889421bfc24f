//! The GPU renderer: draws a scene into textures on a given `wgpu::Device`.
//! The app shows them, the command line writes them, the tests read them back.
//! One file per pass: `shadow` (depth from the light), `shade` (the camera
//! pass), `display` (what people see), `lines` (the frustum overlay).

pub mod binding;
pub mod capabilities;
pub mod colormap;
pub mod context;
pub mod display;
pub mod light_frustum;
pub mod lines;
pub mod readback;
pub mod renderer;
pub mod scene_buffers;
pub mod shade;
pub mod shaders;
pub mod shadow;
pub mod shared;
pub mod targets;
pub mod timing;
pub mod uniforms;

pub use capabilities::Capabilities;
pub use context::{GpuContext, GpuError};
pub use renderer::{ComparisonImage, FrameReport, Renderer};
pub use targets::{FloatTarget, PendingScale, PendingTexels};
