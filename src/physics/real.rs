//! The two small traits that let one formula serve both precisions.

use super::brdf::ln_cos_from_gap;
use super::power;
pub use num_traits::{Float, FloatConst, One, Zero};
use std::ops::{Add, Mul, Neg, Sub};

/// A float type the physics runs in: `f32` (the GPU's precision) or `f64`
/// (the reference's).
pub trait Real:
    num_traits::Float + num_traits::FloatConst + Default + std::fmt::Debug + Send + Sync + 'static
{
    /// Converts a constant written in `f64`.
    fn lit(x: f64) -> Self;

    /// cos^m θ = e^(m ln cos θ) from the gap d = 1 − cos θ, m > 0.
    fn power_from_gap(gap: Self, m: Self) -> Self;
}

impl Real for f32 {
    fn lit(x: f64) -> Self {
        x as f32
    }

    /// As the shaders compute it: their series for small gaps, then `exp`.
    fn power_from_gap(gap: Self, m: Self) -> Self {
        (m * ln_cos_from_gap(gap)).exp()
    }
}

impl Real for f64 {
    fn lit(x: f64) -> Self {
        x
    }

    /// In plain arithmetic that runs in SIMD lanes ([`super::power`]).
    #[inline(always)]
    fn power_from_gap(gap: Self, m: Self) -> Self {
        power::exp(m * power::ln_one_minus(gap))
    }
}

/// A 3-vector in the precision `S`: implemented for `glam::Vec3` and `glam::DVec3`.
pub trait Vector3:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Self::S, Output = Self> + Neg<Output = Self>
{
    type S: Real;
    fn dot(self, other: Self) -> Self::S;
    fn length_squared(self) -> Self::S;
}

impl Vector3 for glam::Vec3 {
    type S = f32;
    fn dot(self, other: Self) -> f32 {
        glam::Vec3::dot(self, other)
    }
    fn length_squared(self) -> f32 {
        glam::Vec3::length_squared(self)
    }
}

impl Vector3 for glam::DVec3 {
    type S = f64;
    fn dot(self, other: Self) -> f64 {
        glam::DVec3::dot(self, other)
    }
    fn length_squared(self) -> f64 {
        glam::DVec3::length_squared(self)
    }
}
