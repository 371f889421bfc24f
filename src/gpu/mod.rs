//! The GPU renderer: draws a scene into textures on a given `wgpu::Device`.
//! The app shows them, the command line writes them, the tests read them back.

pub mod context;
pub mod readback;

pub use context::{GpuContext, GpuError};
