//! How close the f32 mirror and the GPU must come to the f64 reference for
//! each hard case, and why each bound is what it is.

/// How close the f32 and GPU values must come to the f64 reference.
///
/// A difference is Δ = |x − f64| / max(|f64|, floor × scale), with `scale`
/// the quantity's natural size for the case (the lobe's peak, the irradiance
/// at normal incidence, the depth itself): relative, or absolute near zero.
/// The largest Δ allowed is `f32` (or `gpu`) + `per_sqrt_m` × √m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// Largest Δ of the f32 mirror on the CPU.
    pub f32: f64,
    /// Largest Δ of the GPU.
    pub gpu: f64,
    /// Added per √m, for the BRDF: see [`BRDF_TOLERANCE`].
    pub per_sqrt_m: f64,
    /// Below floor × scale, Δ is absolute.
    pub floor: f64,
}

impl Tolerance {
    const fn relative(f32: f64, gpu: f64, floor: f64) -> Self {
        Self {
            f32,
            gpu,
            per_sqrt_m: 0.0,
            floor,
        }
    }

    /// The limits (f32, GPU) for the exponent m.
    pub fn limits(&self, m: f64) -> (f64, f64) {
        let widening = self.per_sqrt_m * m.max(0.0).sqrt();
        (self.f32 + widening, self.gpu + widening)
    }
}

/// N(m): a few roundings of a rational function.
pub const NORM_TOLERANCE: Tolerance = Tolerance::relative(1e-6, 1e-6, 1.0);
/// cos^m θ_h = exp(m ln cos θ_h) from an exact gap 1 − cos θ_h: exp amplifies
/// the rounding of its argument (up to 7 above the floor). On the GPU, WGSL
/// allows log an absolute error of 2^-21, which costs m × 2^-21 where
/// ln(1 − d) is used (d ≥ 0.1, so m < 70 above the floor).
pub const LOBE_TOLERANCE: Tolerance = Tolerance::relative(4e-6, 5e-5, 1e-3);
/// f_r / c, relative to its peak k/π + (1 − k) N(m). In f32, n − h (whose
/// length is the angle θ_h) comes from unit vectors rounded to 6e-8, so θ_h
/// is known to about 6e-8 rad, and the lobe exp(−m θ_h²/2) turns an angle
/// error δ into a relative error m θ_h δ: up to 3.7 √m δ above the floor
/// (θ_h ≤ 3.7/√m). Measured on random geometry: 2.1e-7 √m (2e-4 at m = 10^6).
/// Any f32 renderer has this limit; the naive pow(n·h, m) loses m × 6e-8.
pub const BRDF_TOLERANCE: Tolerance = Tolerance {
    f32: 4e-6,
    gpu: 5e-5,
    per_sqrt_m: 5e-7,
    floor: 1e-3,
};
/// E of a point light: absolute, relative to E at normal incidence (I / r²):
/// at 89.99° cos θ = 1.7e-4 is a difference of unit vectors' products.
pub const IRRADIANCE_TOLERANCE: Tolerance = Tolerance::relative(1e-6, 2e-6, 1.0);
/// E of a sphere light, relative to E at normal incidence (π L_e sin²α).
/// WGSL allows acos and atan thousands of ulps: the GPU gets more room.
pub const SPHERE_TOLERANCE: Tolerance = Tolerance::relative(2e-6, 1e-4, 1.0);
/// The reversed-Z round trip z → d → z: about 1e-7 at every distance.
pub const DEPTH_TOLERANCE: f64 = 1e-6;
pub(super) const DEPTH_ROUND_TRIP: Tolerance = Tolerance::relative(DEPTH_TOLERANCE, DEPTH_TOLERANCE, 1.0);
/// The shadow test's visibility V is 0 or 1 and must be exact.
pub(super) const SHADOW_TEST: Tolerance = Tolerance::relative(0.0, 0.0, 1.0);
