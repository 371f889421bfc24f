//! One hard case evaluated by the generic physics in f64 and in f32, and by
//! the naive f32 formula it is contrasted with.

use super::Input;
use crate::physics::brdf::{BrdfParams, blinn_phong, lobe};
use crate::physics::radiometry::{incidence, intensity, sphere_irradiance};
use crate::physics::real::{Real, Vector3, Zero};
use crate::scene::camera::{reversed_z_coefficients, reversed_z_projection};
use glam::Vec3;

/// The f64 reference and the f32 mirror of the case: the same functions.
pub fn evaluate(input: &Input) -> (f64, f32) {
    (
        physics(input, |v: Vec3| v.as_dvec3()),
        physics(input, |v: Vec3| v),
    )
}

/// The case through `physics` (and the depth pipeline) in V's precision.
fn physics<V: Vector3>(input: &Input, vector: impl Fn(Vec3) -> V) -> V::S {
    let s = |x: f32| V::S::lit(f64::from(x));
    match *input {
        Input::Norm { m, norm } => norm.factor(s(m)),
        Input::Lobe { cos_theta, gap, m } => lobe(s(cos_theta), s(gap), s(m)),
        Input::Brdf { n, l, o, k, m, norm } => {
            let params = BrdfParams {
                k: s(k),
                m: s(m),
                norm,
            };
            blinn_phong(vector(n), vector(l), vector(o), &params).total()
        }
        Input::Irradiance { p, n, q, power_w } => {
            // As the camera pass calls it: a point light is the sphere light with R = 0.
            let inc = incidence(vector(p), vector(n), vector(q));
            sphere_irradiance(s(power_w), V::S::zero(), inc.cos_theta, inc.r)
        }
        Input::Sphere {
            power_w,
            radius_m,
            cos_theta,
            r_m,
        } => sphere_irradiance(s(power_w), s(radius_m), s(cos_theta), s(r_m)),
        Input::Depth { near_m, far_m, z_m } => {
            let depth = DepthPipeline::<V::S>::reversed(near_m, far_m);
            depth.read(depth.store(s(z_m)))
        }
        Input::Shadow {
            near_m,
            far_m,
            caster_m,
            receiver_m,
        } => DepthPipeline::<V::S>::reversed(near_m, far_m).visibility(s(caster_m), s(receiver_m)),
    }
}

/// What a first implementation would write, in f32 (None where the case has
/// no such contrast). These are the formulas the lab's guards replace.
pub fn naive(input: &Input) -> Option<f32> {
    match *input {
        Input::Norm { .. } | Input::Sphere { .. } => None,
        // pow(cos θ_h, m): the gap 1 − cos θ_h is lost when cos θ_h rounds.
        Input::Lobe { cos_theta, m, .. } => Some(cos_theta.powf(m)),
        Input::Brdf { n, l, o, k, m, norm } => {
            // h = normalize(l + o) unguarded: 0/0 when l + o = 0.
            let h = (l + o).normalize();
            let specular = (1.0 - k) * norm.factor(m) * n.dot(h).powf(m);
            Some(k / std::f32::consts::PI + specular)
        }
        Input::Irradiance { p, n, q, power_w } => {
            // 1/r² with r unclamped: Inf when the light lies on the surface.
            let cos_theta = incidence(p, n, q).cos_theta;
            let r = (q - p).length();
            Some(intensity(power_w) * cos_theta.max(0.0) / (r * r))
        }
        Input::Depth { near_m, far_m, z_m } => {
            let depth = DepthPipeline::<f32>::conventional(near_m, far_m);
            Some(depth.read(depth.store(z_m)))
        }
        Input::Shadow {
            near_m,
            far_m,
            caster_m,
            receiver_m,
        } => Some(DepthPipeline::<f32>::conventional(near_m, far_m).visibility(caster_m, receiver_m)),
    }
}

/// A depth buffer's round trip in the precision S, as the renderer holds it:
/// the z and w rows of the layer's projection on its axis (clip.z =
/// zz·v_z + zw, clip.w = wz·v_z + ww, with v_z = −z: the light looks down −Z)
/// and the (a, b) of z = a / (d − b) the camera pass reads it back with.
#[derive(Clone, Copy, Debug)]
pub(super) struct DepthPipeline<S> {
    pub zz: S,
    pub zw: S,
    pub wz: S,
    pub ww: S,
    pub a: S,
    pub b: S,
}

impl<S: Real> DepthPipeline<S> {
    /// Reversed Z, d = a/z + b: the projection of `reversed_z_projection`
    /// and the layer's uniform `depth.zw`, each rounded once from f64.
    pub fn reversed(near_m: f64, far_m: f64) -> Self {
        let proj = reversed_z_projection(-1.0, 1.0, -1.0, 1.0, near_m, far_m);
        let (a, b) = reversed_z_coefficients(near_m, far_m);
        Self {
            zz: S::lit(proj.z_axis.z),
            zw: S::lit(proj.w_axis.z),
            wz: S::lit(proj.z_axis.w),
            ww: S::lit(proj.w_axis.w),
            a: S::lit(a),
            b: S::lit(b),
        }
    }

    /// Conventional depth d = A + B/z with A = f/(f − n), B = −n f/(f − n)
    /// (near → 0, far → 1), read back as z = B / (d − A).
    pub fn conventional(near_m: f64, far_m: f64) -> Self {
        let span = far_m - near_m;
        let (a, b) = (far_m / span, -near_m * far_m / span);
        Self {
            zz: S::lit(-a),
            zw: S::lit(b),
            wz: S::lit(-1.0),
            ww: S::zero(),
            a: S::lit(b),
            b: S::lit(a),
        }
    }

    /// The stored d = clip.z / clip.w of a point at depth z (m) on the axis.
    pub fn store(&self, z_m: S) -> S {
        let v_z = -z_m;
        (self.zz * v_z + self.zw) / (self.wz * v_z + self.ww)
    }

    /// z (m) from the stored d (`linear_depth`).
    pub fn read(&self, d: S) -> S {
        self.a / (d - self.b)
    }

    /// V of the camera pass's depth test without bias: 1 when the receiver is
    /// no further from the light than the caster stored at its texel.
    pub fn visibility(&self, caster_m: S, receiver_m: S) -> S {
        if receiver_m <= self.read(self.store(caster_m)) {
            S::one()
        } else {
            S::zero()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_depth_pipelines_round_trip_in_f64() {
        for (near, far) in [(0.1, 1e3), (1e-3, 1e5)] {
            for z in [near, 1.0, 0.5 * far, far] {
                // Conventional depth loses far/near × ε even in f64 at the far plane.
                for (depth, tolerance) in [
                    (DepthPipeline::<f64>::reversed(near, far), 1e-14),
                    (DepthPipeline::<f64>::conventional(near, far), 1e-7),
                ] {
                    let error = (depth.read(depth.store(z)) / z - 1.0).abs();
                    assert!(error < tolerance, "{near} {far} {z}: {error:e}");
                }
            }
        }
        let reversed = DepthPipeline::<f64>::reversed(0.5, 200.0);
        assert!((reversed.store(0.5) - 1.0).abs() < 1e-15 && reversed.store(200.0).abs() < 1e-15);
        let conventional = DepthPipeline::<f64>::conventional(0.5, 200.0);
        assert!(conventional.store(0.5).abs() < 1e-15 && (conventional.store(200.0) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn naive_formulas_break_where_the_guards_are() {
        let l = Vec3::X;
        let brdf = Input::Brdf {
            n: Vec3::Y,
            l,
            o: -l,
            k: 0.0,
            m: 8.0,
            norm: crate::physics::Normalization::Exact,
        };
        assert!(naive(&brdf).is_some_and(f32::is_nan));
        assert_eq!(evaluate(&brdf), (0.0, 0.0));
        let on_surface = Input::Irradiance {
            p: Vec3::ZERO,
            n: Vec3::Y,
            q: Vec3::ZERO,
            power_w: 1.0,
        };
        assert!(naive(&on_surface).is_some_and(f32::is_infinite));
        assert!(evaluate(&on_surface).1.is_finite());
    }
}
