//! Spectral colour: what the lecture's RGB triplets approximate.
//!
//! Colour is the eye's response to the energy of visible light, wavelength by
//! wavelength. This module keeps that energy as a [`Spectrum`] sampled on
//! 380–780 nm every 5 nm, reduces it to the CIE 1931 tristimulus values
//! X, Y, Z the way CIE 015:2018 prescribes, and measures how far the
//! lecture's shortcut — one RGB triplet for the light, one for the material,
//! multiplied — lands from that spectral result (ΔE2000).
//!
//! - [`spectrum`] — the sampled spectrum, products, Planck's law;
//! - [`data`] — the published tables (CMFs, CIE illuminants, ColorChecker);
//! - [`tristimulus`] — spectrum → XYZ, XYZ ↔ linear sRGB, XYZ → CIE Lab;
//! - [`delta_e`] — CIEDE2000;
//! - [`uplift`] — a smooth reflectance for an RGB colour (Jakob & Hanika 2019);
//! - [`chart`] — the ColorChecker under an illuminant, spectral against RGB;
//! - [`shading`] — the colours a renderer shades with under an illuminant.
//!
//! Pure functions: no GPU, no UI, no files (the tables are compiled in).

pub mod chart;
pub mod data;
pub mod delta_e;
pub mod shading;
pub mod spectrum;
pub mod tristimulus;
pub mod uplift;

pub use chart::{PatchComparison, compare_chart};
pub use data::{Illuminant, PATCH_COUNT, patch_names, patch_reflectance};
pub use delta_e::delta_e2000;
pub use shading::{ColourModel, ShadingColours, shading_colours};
pub use spectrum::{Spectrum, blackbody};
pub use tristimulus::{lab, linear_srgb_to_xyz, reflectance_xyz, white_xyz, xyz_to_linear_srgb};
pub use uplift::{SigmoidReflectance, uplift_linear_srgb};
