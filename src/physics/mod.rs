//! The physics of direct lighting, as pure functions: no GPU, no UI, no files.
//!
//! Every formula lives here once. It is generic over the float type so that
//! the CPU reference evaluates it in `f64` and the tests can run the very same
//! code in `f32`, mirroring what the WGSL shaders compute on the GPU.
//!
//! Conventions (DESIGN.md): right-handed, +Y up, metres, linear RGB, radiance
//! in W/m²/sr, irradiance in W/m², intensity in W/sr, power in W.

pub mod brdf;
pub mod colour;
pub mod display;
pub mod energy;
pub mod power;
pub mod radiometry;
pub mod real;

pub use brdf::{BrdfParams, BrdfTerms, Normalization};
pub use real::{Real, Vector3};
