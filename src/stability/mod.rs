//! Numerical stability on hard cases: where direct lighting breaks numerically,
//! and the proof that lumlab does not.
//!
//! A grid of hard cases (exponents up to m = 10^6, angles up to 89.99°,
//! l + o → 0, lights from 1 µm to 1000 km and on the surface, Φ = 0 … 10^9 W,
//! shadow-map depth ranges with far/near up to 10^8) is evaluated three ways:
//!
//! - **f64**: the generic `physics` functions with `glam::DVec3`/`f64`, the
//!   reference;
//! - **f32**: the same functions with `glam::Vec3`/`f32`, the CPU mirror of
//!   what the GPU computes;
//! - **GPU**: `shaders/stability.wgsl`, a compute shader that calls the very
//!   functions of `common.wgsl` the renderer uses, read back.
//!
//! Every case is built in f64, its inputs are rounded to f32, and the f64
//! reference is evaluated on the rounded inputs: the differences measure the
//! arithmetic, not the rounding of the inputs. Each value must be finite and
//! within its quantity's [`Tolerance`] of the f64 value, or equal to the value
//! DESIGN.md defines ([`Defined`]). Beside them, a naive f32 formula (the one a
//! first implementation would write) shows what the guards are for; naive
//! values never make a case fail.
//!
//! # Shadow-map depth
//!
//! The shadow map (and the camera) store depth as `Depth32Float` with
//! reversed Z: a point at view depth z (m) in a layer [near, far] is stored as
//! d = a / z + b, with a = near·far / (far − near) and b = −near / (far − near)
//! (`scene::camera::reversed_z_coefficients`), so near → 1 and far → 0. The
//! rasterizer computes d = clip.z / clip.w from the layer's projection
//! (`reversed_z_projection`); the floats' density near 0 cancels the
//! hyperbola's, so the relative precision of z is about 1e-7 (a few ulps of
//! f32) at every distance, for any near/far ratio. The camera pass reads d
//! back in metres, z = a / (d − b) (`linear_depth` in common.wgsl), and
//! compares it with the receiver's own depth in metres. The grid's depth rows
//! check the round trip (ratios up to 10^8) and that a receiver 1 mm behind
//! its caster still tests as hidden at 1 mm … 1 km: any gap above
//! [`DEPTH_TOLERANCE`] × z is resolved (1 mm up to 1 km; beyond 8 km 1 mm is
//! below f32's spacing of z itself). The naive column stores conventional depth
//! (near → 0, far → 1), whose precision collapses far from the near plane.
//!
//! `tests/depth_precision.rs` renders the same thin-plate scene at scales 1 mm
//! … 10 km and bounds the pixels whose visibility differs from exact ray
//! casting by 0.2 % of the pixels away from the shadow's edge; it measures 0.

mod eval;
mod gpu;
mod grid;
mod tolerance;

pub use eval::{evaluate, naive};
pub use gpu::{CaseRaw, evaluate_on_gpu};
pub use grid::grid;
pub use tolerance::{
    BRDF_TOLERANCE, DEPTH_TOLERANCE, IRRADIANCE_TOLERANCE, LOBE_TOLERANCE, NORM_TOLERANCE, SPHERE_TOLERANCE,
    Tolerance,
};
use tolerance::{DEPTH_ROUND_TRIP, SHADOW_TEST};

use crate::physics::Normalization;
use glam::Vec3;

named_enum! {
    /// What a hard case computes; the table groups its rows by it.
    pub enum Quantity {
        /// N(m), the lobe's normalization.
        Norm = "norm",
        /// cos^m θ_h from cos θ_h and 1 − cos θ_h.
        Lobe = "lobe",
        /// f_r / c from the vectors n, l, o.
        Brdf = "brdf",
        /// E of a point light at q seen from p.
        Irradiance = "irradiance",
        /// E of a sphere light from its distance and angle.
        Sphere = "sphere",
        /// A shadow-map depth stored and read back in metres.
        Depth = "depth",
        /// V of a receiver 1 mm behind its caster.
        Shadow = "shadow",
    }
}

impl Quantity {
    /// The group's title in the table: the formula and its unit.
    pub fn title(self) -> &'static str {
        match self {
            Self::Norm => "N(m), the normalization of the lobe (1/sr)",
            Self::Lobe => "cos^m θh, the Blinn-Phong lobe (unitless)",
            Self::Brdf => "f_r / c = k/π + (1 − k) N(m) cos^m θh (1/sr)",
            Self::Irradiance => "E = I max(0, n·l) / r², point light (W/m²)",
            Self::Sphere => "E of a sphere light, clipped by the horizon (W/m²)",
            Self::Depth => "shadow-map depth z → d = a/z + b → z (m), reversed Z",
            Self::Shadow => "V of a receiver 1 mm behind its caster (0 = hidden)",
        }
    }

    /// How lumlab computes it and where a naive formula breaks.
    pub fn explanation(self) -> &'static [&'static str] {
        match self {
            Self::Norm => &[
                "none 1, ndf (m+1)/2π, approx (m+8)/8π, exact (m+2)(m+4)/(8π(2^(−m/2)+m)):",
                "2^(−m/2) underflows harmlessly to 0; (m+2)(m+4) stays far below f32's range.",
            ],
            Self::Lobe => &[
                "exp(m ln cos θh), ln cos θh from the gap 1 − cos θh (a series below 0.1),",
                "so m = 1e6 keeps its digits at the peak; 0^0 = 1 and cos θh ≤ 0 gives 0.",
                "naive f32: pow(cos θh, m); near the peak cos θh rounds towards 1 and",
                "m × that rounding becomes the error (θh = 1e-4 rad: cos θh rounds to 1).",
                "(Rust's pow(0, 0) is 1; WGSL leaves it undefined, GPUs often give NaN.)",
            ],
            Self::Brdf => &[
                "\"θh = x rad (30°)\": l and o mirrored 30° ± θh from n, so h lies θh from n.",
                "h = (l + o) / |l + o| only when |l + o| > 0, 1 − cos θh from |n − h|² / 2,",
                "nothing when n·l ≤ 0 or n·o ≤ 0 (DESIGN.md: l + o = 0 has no specular term).",
                "naive f32: k/π + (1 − k) N(m) pow(n·normalize(l + o), m), no guard:",
                "NaN when l + o = 0 (0/0), light below the horizon still reflects.",
            ],
            Self::Irradiance => &[
                "l = (q − p)/r, r clamped to 1 µm (MIN_LIGHT_DISTANCE_M): a light on the",
                "surface (r = 0) gives the finite I / (1 µm)², with l = n.",
                "naive f32: I max(0, n·l) / r² with r unclamped: Inf at r = 0 (NaN if Φ = 0).",
            ],
            Self::Sphere => &[
                "Snyder's closed form; straddling the horizon it is written as",
                "sin²α (cos θ acos y + t) − (t − atan t) so that a small sphere does not cancel.",
            ],
            Self::Depth => &[
                "Depth32Float, d = a/z + b from the layer's projection (near → 1, far → 0),",
                "read back as z = a/(d − b) (linear_depth): ≈ 1e-7 relative at every distance.",
                "naive f32: conventional depth d = A + B/z (near → 0, far → 1): the floats",
                "near 1 are sparse, so far from the near plane z loses its digits.",
            ],
            Self::Shadow => &[
                "the camera pass compares the receiver's depth with the stored caster's,",
                "in metres: V = 1 when z_receiver ≤ z_caster (no bias, filter none).",
                "naive f32: the same comparison through conventional depth.",
            ],
        }
    }

    /// The tolerance of every case of this quantity.
    pub fn tolerance(self) -> Tolerance {
        match self {
            Self::Norm => NORM_TOLERANCE,
            Self::Lobe => LOBE_TOLERANCE,
            Self::Brdf => BRDF_TOLERANCE,
            Self::Irradiance => IRRADIANCE_TOLERANCE,
            Self::Sphere => SPHERE_TOLERANCE,
            Self::Depth => DEPTH_ROUND_TRIP,
            Self::Shadow => SHADOW_TEST,
        }
    }

    /// What the floor of Δ is a fraction of, for the table's header; None
    /// where the scale is the value itself (Δ purely relative).
    pub fn scale_name(self) -> Option<&'static str> {
        match self {
            Self::Norm | Self::Depth | Self::Shadow => None,
            Self::Lobe => Some("the peak (1)"),
            Self::Brdf => Some("the peak k/π + (1 − k) N(m)"),
            Self::Irradiance | Self::Sphere => Some("E at normal incidence"),
        }
    }
}

/// A result DESIGN.md (or the function's contract) fixes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Defined {
    pub value: f64,
    /// The rule, for the table: "0^0 = 1", "Φ = 0 → 0".
    pub rule: &'static str,
    /// Every column must give exactly this value (0 and 1); otherwise within
    /// the quantity's tolerance (a clamp's value).
    pub exact: bool,
}

/// A hard case's inputs, already rounded to f32.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Input {
    Norm {
        m: f32,
        norm: Normalization,
    },
    Lobe {
        cos_theta: f32,
        /// 1 − cos θ_h, computed accurately.
        gap: f32,
        m: f32,
    },
    Brdf {
        n: Vec3,
        l: Vec3,
        o: Vec3,
        k: f32,
        m: f32,
        norm: Normalization,
    },
    Irradiance {
        /// The receiver (m).
        p: Vec3,
        n: Vec3,
        /// The light (m).
        q: Vec3,
        power_w: f32,
    },
    Sphere {
        power_w: f32,
        radius_m: f32,
        cos_theta: f32,
        r_m: f32,
    },
    /// Depth range of the layer (m, f64 as the light's frustum holds them)
    /// and the caster's depth.
    Depth {
        near_m: f64,
        far_m: f64,
        z_m: f32,
    },
    Shadow {
        near_m: f64,
        far_m: f64,
        caster_m: f32,
        receiver_m: f32,
    },
}

/// One row of the grid.
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    pub quantity: Quantity,
    /// Short, without commas: "m = 1e6  θh = 1e-3 rad".
    pub label: String,
    pub input: Input,
    /// Δ's floor is `tolerance().floor` × this (f64).
    pub scale: f64,
    pub defined: Option<Defined>,
}

/// How a naive value fares.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NaiveFlag {
    /// Within the f32 tolerance.
    Fine,
    Nan,
    Inf,
    /// Finite, but beyond the f32 tolerance lumlab meets.
    Error,
}

impl NaiveFlag {
    pub fn name(self) -> &'static str {
        match self {
            Self::Fine => "",
            Self::Nan => "NaN",
            Self::Inf => "Inf",
            Self::Error => "error",
        }
    }

    pub fn broke(self) -> bool {
        self != Self::Fine
    }
}

/// A case evaluated.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    pub case: Case,
    pub f64: f64,
    pub f32: f64,
    /// None with `--cpu-only`.
    pub gpu: Option<f64>,
    /// None where no naive formula applies.
    pub naive: Option<f64>,
}

impl Row {
    pub fn tolerance(&self) -> Tolerance {
        self.case.quantity.tolerance()
    }

    /// The largest Δ allowed to (f32, GPU) for this case.
    pub fn limits(&self) -> (f64, f64) {
        let m = match self.case.input {
            Input::Brdf { m, .. } => f64::from(m),
            _ => 0.0,
        };
        self.tolerance().limits(m)
    }

    /// floor × scale: below it Δ is absolute.
    pub fn abs_floor(&self) -> f64 {
        self.tolerance().floor * self.case.scale
    }

    /// Δ of a value against the f64 reference (infinite if not finite).
    pub fn diff(&self, x: f64) -> f64 {
        if x == self.f64 {
            return 0.0;
        }
        if !x.is_finite() {
            return f64::INFINITY;
        }
        let d = (x - self.f64).abs() / self.f64.abs().max(self.abs_floor());
        if d.is_nan() { f64::INFINITY } else { d }
    }

    pub fn diff_f32(&self) -> f64 {
        self.diff(self.f32)
    }

    pub fn diff_gpu(&self) -> Option<f64> {
        self.gpu.map(|g| self.diff(g))
    }

    pub fn naive_flag(&self) -> Option<NaiveFlag> {
        let x = self.naive?;
        Some(if x.is_nan() {
            NaiveFlag::Nan
        } else if x.is_infinite() {
            NaiveFlag::Inf
        } else if self.diff(x) > self.limits().0 {
            NaiveFlag::Error
        } else {
            NaiveFlag::Fine
        })
    }

    /// Why the row fails, if it does: a non-finite value, a difference above
    /// the tolerance, or a defined value not met.
    pub fn failure(&self) -> Option<String> {
        let (f32_limit, gpu_limit) = self.limits();
        let mut columns = vec![("f64", self.f64, 0.0), ("f32", self.f32, f32_limit)];
        if let Some(g) = self.gpu {
            columns.push(("GPU", g, gpu_limit));
        }
        for &(name, x, limit) in &columns {
            if !x.is_finite() {
                return Some(format!("{name} is {x}"));
            }
            if let Some(d) = self.case.defined {
                let meets = if d.exact {
                    x == d.value
                } else {
                    (x - d.value).abs() <= limit.max(1e-12) * d.value.abs().max(self.abs_floor())
                };
                if !meets {
                    return Some(format!("{name} = {x:e}, defined {} = {:e}", d.rule, d.value));
                }
            }
            if self.diff(x) > limit {
                return Some(format!("{name} differs by {:.1e} > {limit:e}", self.diff(x)));
            }
        }
        None
    }

    pub fn ok(&self) -> bool {
        self.failure().is_none()
    }
}

/// The whole grid evaluated, with the adapter that ran the GPU column.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    pub rows: Vec<Row>,
    /// None with `--cpu-only`.
    pub adapter: Option<String>,
}

/// Worst differences and naive breakage of one quantity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary {
    pub quantity: Quantity,
    pub cases: usize,
    pub worst_f32: f64,
    pub worst_gpu: Option<f64>,
    pub naive_cases: usize,
    pub naive_broken: usize,
    pub failed: usize,
}

impl Report {
    pub fn failed(&self) -> usize {
        self.rows.iter().filter(|r| !r.ok()).count()
    }

    /// One summary per quantity present, in `Quantity::ALL` order.
    pub fn summaries(&self) -> Vec<Summary> {
        Quantity::ALL
            .iter()
            .filter_map(|&quantity| {
                let rows: Vec<&Row> = self.rows.iter().filter(|r| r.case.quantity == quantity).collect();
                if rows.is_empty() {
                    return None;
                }
                let worst = |d: &mut dyn Iterator<Item = f64>| d.fold(0.0_f64, f64::max);
                let flags: Vec<NaiveFlag> = rows.iter().filter_map(|r| r.naive_flag()).collect();
                Some(Summary {
                    quantity,
                    cases: rows.len(),
                    worst_f32: worst(&mut rows.iter().map(|r| r.diff_f32())),
                    worst_gpu: self
                        .adapter
                        .is_some()
                        .then(|| worst(&mut rows.iter().filter_map(|r| r.diff_gpu()))),
                    naive_cases: flags.len(),
                    naive_broken: flags.iter().filter(|f| f.broke()).count(),
                    failed: rows.iter().filter(|r| !r.ok()).count(),
                })
            })
            .collect()
    }
}

/// Evaluates the grid in f64 and f32, and on the GPU when one is given.
pub fn run(gpu: Option<&crate::gpu::GpuContext>) -> Report {
    let cases = grid();
    let gpu_values = gpu.map(|g| evaluate_on_gpu(g, &cases));
    let rows = cases
        .into_iter()
        .enumerate()
        .map(|(i, case)| {
            let (f64, f32) = evaluate(&case.input);
            Row {
                f64,
                f32: f32 as f64,
                gpu: gpu_values.as_ref().map(|v| v[i] as f64),
                naive: naive(&case.input).map(f64::from),
                case,
            }
        })
        .collect();
    Report {
        rows,
        adapter: gpu.map(|g| g.describe()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use std::f64::consts::TAU;

    /// xorshift64*: a deterministic stream of numbers in [0, 1).
    fn stream(mut state: u64) -> impl FnMut() -> f64 {
        move || {
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// A unit vector at angle θ from `axis`, at azimuth φ around it.
    fn around(axis: DVec3, theta: f64, phi: f64) -> DVec3 {
        let (t, b) = axis.any_orthonormal_pair();
        (t * phi.cos() + b * phi.sin()) * theta.sin() + axis * theta.cos()
    }

    #[test]
    fn brdf_tolerance_holds_for_random_geometry_on_the_visible_lobe() {
        // The grid's few geometries could miss the worst case: random normals,
        // half-vectors up to 3.7/√m from n (the lobe above the floor) and
        // mirror pairs l, o around them.
        let mut next = stream(0x1234_5678_9abc_def1);
        for m in [1e3, 1e4, 1e5, 1e6] {
            let mut worst: f64 = 0.0;
            for _ in 0..20_000 {
                let n = DVec3::new(next() - 0.5, 1.0, next() - 0.5).normalize();
                let h = around(n, next() * 3.7 / f64::sqrt(m), next() * TAU);
                let l = around(h, next() * 1.4, next() * TAU);
                let o = h * (2.0 * l.dot(h)) - l;
                let input = Input::Brdf {
                    n: n.as_vec3(),
                    l: l.as_vec3(),
                    o: o.as_vec3(),
                    k: 0.0,
                    m: m as f32,
                    norm: Normalization::None,
                };
                let (f64, f32) = evaluate(&input);
                let case = Case {
                    quantity: Quantity::Brdf,
                    label: String::new(),
                    input,
                    scale: 1.0,
                    defined: None,
                };
                let row = Row {
                    case,
                    f64,
                    f32: f32.into(),
                    gpu: None,
                    naive: None,
                };
                worst = worst.max(row.diff_f32());
                assert!(row.ok(), "m = {m}: {:?}", row.failure());
            }
            // The bound is not loose either: the √m law is what f32 reaches.
            assert!(worst > 0.1 * row_limit(m), "m = {m}: worst {worst:e}");
        }
    }

    fn row_limit(m: f64) -> f64 {
        BRDF_TOLERANCE.limits(m).0
    }

    #[test]
    fn the_whole_grid_passes_on_the_cpu() {
        let report = run(None);
        let failures: Vec<String> = report
            .rows
            .iter()
            .filter_map(|r| r.failure().map(|why| format!("{}: {why}", r.case.label)))
            .collect();
        assert!(failures.is_empty(), "{failures:#?}");
        let broken: usize = report.summaries().iter().map(|s| s.naive_broken).sum();
        assert!(broken > 0, "the naive formulas should break somewhere");
    }

    #[test]
    fn differences_are_relative_or_absolute_near_zero() {
        let row = |f64: f64, scale: f64| Row {
            case: Case {
                quantity: Quantity::Lobe,
                label: String::new(),
                input: Input::Lobe {
                    cos_theta: 1.0,
                    gap: 0.0,
                    m: 1.0,
                },
                scale,
                defined: None,
            },
            f64,
            f32: f64,
            gpu: None,
            naive: None,
        };
        assert!((row(0.5, 1.0).diff(0.5005) - 1e-3).abs() < 1e-12);
        // Below 1e-3 × the peak, the difference is measured against 1e-3.
        assert!((row(1e-9, 1.0).diff(2e-9) - 1e-6).abs() < 1e-18);
        assert_eq!(row(0.0, 0.0).diff(1e-30), f64::INFINITY);
        assert_eq!(row(1.0, 1.0).diff(f64::NAN), f64::INFINITY);
    }
}
