//! The sphere light at one shading point: N strata of the cone the sphere
//! subtends, one direction each (see `shading`'s module note for the
//! estimator). The samples are taken step by step over all N at once: their
//! jittered points (from the point's stream) and directions (lanes), their
//! shadow rays (one by one), then the BRDF and each sample's term (lanes).
//! A lane step is a loop without branches that the compiler turns into SIMD
//! instructions (`simd::with`): 4 samples at once with AVX2, kept where the
//! CPU has AVX-512, whose eight lanes ran the default scene at 64 samples
//! 7 % slower on the 2-core host (0.47–0.48 s against 0.45 s, medians of 6
//! alternated runs; such CPUs may lower their clock for long runs of 512-bit
//! arithmetic). Each lane does the operations the sample-by-sample loop did,
//! in the same order, so the bits are the same (the lobe's power in plain
//! arithmetic: `physics::power`).

use super::Reference;
use super::sampling::{Cone, Rng, Strata, collapsed_strata_variance};
use super::shading::{LightEstimate, REGION_BLOCK, STOP_SHORT_REL, Scratch, Setup};
use super::simd::{self, Isa};
use super::surface::Surface;
use crate::physics::BrdfTerms;
use crate::physics::brdf::LaneBrdf;
use crate::physics::radiometry::{MIN_LIGHT_DISTANCE_M, sphere_irradiance, sphere_radiance};
use glam::DVec3;
use std::f64::consts::PI;

/// Gathered occluders beyond this many: each shadow ray goes through the BVH.
const MAX_CANDIDATES: usize = 24;

/// One shading point's light samples, value by value (reused from point to
/// point by one thread).
#[derive(Debug, Default)]
pub(super) struct SphereSamples {
    /// Each stratum's cell (ix, iy), as f64.
    cx: Vec<f64>,
    cy: Vec<f64>,
    /// Each stratum's jittered point of the unit square.
    u: Vec<f64>,
    v: Vec<f64>,
    /// Each sample's unit direction, by coordinate.
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
    /// Its cos θ and sin²θ to the cone's axis, and cos⁺ to the normal.
    cos_theta: Vec<f64>,
    sin2_theta: Vec<f64>,
    cos: Vec<f64>,
    /// Its V (0 or 1).
    visible: Vec<f64>,
    /// Its term of the estimate, for the mean and the noise estimate.
    terms: Vec<f64>,
}

impl SphereSamples {
    /// Each of the `strata`'s cells jittered with the point's stream.
    #[inline(always)]
    fn draw(&mut self, strata: Strata, rng: &mut Rng) {
        let count = strata.count() as usize;
        // Every point of a render takes as many: sized once.
        if self.u.len() != count {
            self.resize(strata);
        }
        strata.jittered_all(rng, (&self.cx, &self.cy), (&mut self.u, &mut self.v));
    }

    fn resize(&mut self, strata: Strata) {
        let count = strata.count() as usize;
        (self.cx, self.cy) = strata.cell_coordinates();
        for values in [
            &mut self.u,
            &mut self.v,
            &mut self.x,
            &mut self.y,
            &mut self.z,
            &mut self.cos_theta,
            &mut self.sin2_theta,
            &mut self.cos,
            &mut self.visible,
            &mut self.terms,
        ] {
            values.resize(count, 0.0);
        }
    }

    /// Each sample's direction in `cone`, cos θ and sin²θ, and cos⁺ to `n`.
    #[inline(always)]
    fn directions(&mut self, cone: &Cone, n: DVec3) {
        let count = self.u.len();
        let (u, v) = (&self.u[..count], &self.v[..count]);
        let (x, y, z) = (&mut self.x[..count], &mut self.y[..count], &mut self.z[..count]);
        let (cos_theta, sin2_theta) = (&mut self.cos_theta[..count], &mut self.sin2_theta[..count]);
        let cos = &mut self.cos[..count];
        for i in 0..count {
            let sample = cone.direction((u[i], v[i]));
            let l = sample.direction;
            (x[i], y[i], z[i]) = (l.x, l.y, l.z);
            cos_theta[i] = sample.cos_theta;
            sin2_theta[i] = sample.sin2_theta;
            cos[i] = n.dot(l).max(0.0);
        }
    }

    /// Each sample's term: weight · (f_d + f_s) · V · cos⁺, or with the
    /// diffuse part in closed form, `diffuse` + weight · f_s · cos⁺.
    #[inline(always)]
    fn terms(&mut self, s: &Surface, weight: f64, closed: Option<f64>) {
        let brdf = LaneBrdf::new(&s.brdf);
        // Lambert alone: no lobe to compute in the lanes.
        if brdf.is_lambert() {
            self.terms_with::<true>(s, &brdf, weight, closed);
        } else {
            self.terms_with::<false>(s, &brdf, weight, closed);
        }
    }

    #[inline(always)]
    fn terms_with<const LAMBERT: bool>(
        &mut self,
        s: &Surface,
        brdf: &LaneBrdf<f64>,
        weight: f64,
        closed: Option<f64>,
    ) {
        let count = self.u.len();
        let (x, y, z) = (&self.x[..count], &self.y[..count], &self.z[..count]);
        let (visible, cos) = (&self.visible[..count], &self.cos[..count]);
        let terms = &mut self.terms[..count];
        let (closed_form, closed) = (closed.is_some(), closed.unwrap_or(0.0));
        for i in 0..count {
            let (v, cos) = (visible[i], cos[i]);
            let l = DVec3::new(x[i], y[i], z[i]);
            let BrdfTerms { diffuse, specular } = if LAMBERT {
                brdf.lambert_terms(s.n, l, s.o)
            } else {
                brdf.terms(s.n, l, s.o)
            };
            let lit = v * cos > 0.0;
            let (diffuse, specular) = if lit { (diffuse, specular) } else { (0.0, 0.0) };
            terms[i] = if closed_form {
                closed + weight * specular * cos
            } else {
                weight * (diffuse + specular) * v * cos
            };
        }
    }
}

impl Reference {
    /// The sphere light's contribution at the surface, estimated with the
    /// light-sample stream `rng` (see the module).
    pub(super) fn sphere(
        &self,
        setup: &Setup,
        s: &Surface,
        rng: &mut Rng,
        scratch: &mut Scratch,
    ) -> LightEstimate {
        let (q, radius) = (setup.light_position, setup.radius_m);
        // Every shadow ray of this point runs from its shadow origin to the
        // sphere: gather the occluders near that path once (from those of
        // a region shared with the points about it), then test each ray
        // against those few (or, when there are many, through the BVH).
        let Scratch {
            sphere_samples: samples,
            candidates,
            ball_region,
            block,
            ..
        } = scratch;
        if s.shadowed
            && let Some(block) = *block
            && ball_region.block() != Some(block)
        {
            let anchor = self.region_anchor(setup, block);
            ball_region.make(&self.bvh, block, anchor, (q, radius));
        }
        // Without a block (no render or probe said which) the region is
        // never made, and each point walks on its own.
        let gathered = s.shadowed
            && self.bvh.gather_near_ball_in(
                ball_region,
                (s.shadow_origin, s.geometric_normal),
                (q, radius),
                MAX_CANDIDATES,
                candidates,
            );
        let le = sphere_radiance(setup.power_w, radius);
        let to_centre = q - s.p;
        let d2 = to_centre.length_squared();
        let d = d2.sqrt();
        let inside = d <= radius;
        // No shadow ray can be blocked: the diffuse part in closed form, and
        // only a specular lobe left to sample.
        let clear = !s.shadowed || gathered && candidates.is_empty();
        let closed = if clear && !setup.sample_everywhere {
            closed_form_diffuse(setup, s, to_centre, d)
        } else {
            None
        };
        if let Some(diffuse) = closed
            && s.brdf.k >= 1.0
        {
            return LightEstimate {
                scaled_radiance: diffuse,
                visibility: 1.0,
                std_error: Some(0.0),
                shadow_rays: 0,
            };
        }
        let cone = if inside {
            // Inside the light: emission from every direction of the hemisphere.
            Cone::hemisphere(s.n)
        } else {
            Cone::new(to_centre / d, radius * radius / d2)
        };
        let strata = setup.light_strata;
        let weight = cone.solid_angle() * le;
        simd::with(
            Isa::Avx2,
            #[inline(always)]
            || {
                samples.draw(strata, rng);
                samples.directions(&cone, s.n);
            },
        );
        let (mut cos_sum, mut visible_cos_sum) = (0.0, 0.0);
        let mut shadow_rays = 0;
        for i in 0..samples.u.len() {
            let cos = samples.cos[i];
            let mut v = 1.0;
            if cos > 0.0 && s.shadowed && closed.is_none() {
                let l = DVec3::new(samples.x[i], samples.y[i], samples.z[i]);
                // Distance along l to the sphere: the near root outside it,
                // the far one inside; R² − d² sin²θ is the half-chord squared.
                let b = if inside {
                    l.dot(to_centre)
                } else {
                    d * samples.cos_theta[i]
                };
                let half_chord = if inside {
                    (radius * radius - d2 + b * b).max(0.0).sqrt()
                } else {
                    (radius * radius - d2 * samples.sin2_theta[i]).max(0.0).sqrt()
                };
                let t = if inside { b + half_chord } else { b - half_chord };
                shadow_rays += 1;
                let target = s.p + l * t;
                let blocked = if gathered {
                    let d = target - s.shadow_origin;
                    self.bvh
                        .blocked_by(candidates, s.shadow_origin, d, 1.0 - STOP_SHORT_REL)
                } else {
                    self.blocked(s.shadow_origin, target)
                };
                if blocked {
                    v = 0.0;
                }
            }
            samples.visible[i] = v;
            cos_sum += cos;
            visible_cos_sum += v * cos;
        }
        simd::with(
            Isa::Avx2,
            #[inline(always)]
            || samples.terms(s, weight, closed),
        );
        let n = samples.terms.len() as f64;
        let visibility = if !s.shadowed || closed.is_some() {
            1.0
        } else if cos_sum > 0.0 {
            visible_cos_sum / cos_sum
        } else {
            0.0
        };
        LightEstimate {
            scaled_radiance: samples.terms.iter().sum::<f64>() / n,
            visibility,
            std_error: collapsed_strata_variance(&samples.terms).map(f64::sqrt),
            shadow_rays,
        }
    }

    /// The shadow origin and surface normal at the centre of the first
    /// pixel of `block`, where a shadowed surface lies: what its region of
    /// a sphere light's occluders is made for.
    fn region_anchor(&self, setup: &Setup, (bx, by): (u32, u32)) -> Option<(DVec3, DVec3)> {
        let (x, y) = ((bx * REGION_BLOCK) as f64 + 0.5, (by * REGION_BLOCK) as f64 + 0.5);
        let (s, _) = self.probed_surface(setup, setup.rays.towards(x, y))?;
        s.shadowed.then_some((s.shadow_origin, s.geometric_normal))
    }
}

/// k/π · E of the sphere light where no shadow ray can be blocked (V = 1
/// over the whole cone): E is the closed form `sphere_irradiance` (Snyder's,
/// the horizon included), exact and without noise. None inside the light or
/// nearer than [`MIN_LIGHT_DISTANCE_M`], where the light is sampled. The
/// sampled estimator's expectation with every V = 1 is the same integral;
/// only its variance changes. `to_centre`: from the surface point to the
/// light's centre, `d` its length.
fn closed_form_diffuse(setup: &Setup, s: &Surface, to_centre: DVec3, d: f64) -> Option<f64> {
    // False for NaN too.
    let outside = d > setup.radius_m && d >= MIN_LIGHT_DISTANCE_M;
    if !outside {
        return None;
    }
    // blinn_phong is zero for a viewer below the shading normal's horizon.
    Some(if s.n.dot(s.o) > 0.0 {
        s.brdf.k / PI * sphere_irradiance(setup.power_w, setup.radius_m, s.n.dot(to_centre) / d, d)
    } else {
        0.0
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::brdf::blinn_phong;
    use crate::physics::{BrdfParams, Normalization};

    fn unit(rng: &mut Rng) -> DVec3 {
        let z = 2.0 * rng.next_f64() - 1.0;
        let phi = std::f64::consts::TAU * rng.next_f64();
        let r = (1.0 - z * z).max(0.0).sqrt();
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
    }

    fn surface(n: DVec3, o: DVec3, brdf: BrdfParams<f64>) -> Surface {
        Surface {
            triangle: 0,
            p: DVec3::ZERO,
            n,
            geometric_normal: n,
            o,
            tint: DVec3::ONE,
            brdf,
            shadow_origin: DVec3::ZERO,
            shadow_offset_m: 0.0,
            shadowed: true,
        }
    }

    /// What the sample-by-sample loop made of sample i.
    fn term(s: &Surface, l: DVec3, (v, cos): (f64, f64), weight: f64, closed: Option<f64>) -> f64 {
        let f = if v * cos > 0.0 {
            blinn_phong(s.n, l, s.o, &s.brdf)
        } else {
            Default::default()
        };
        match closed {
            Some(diffuse) => diffuse + weight * f.specular * cos,
            None => weight * f.total() * v * cos,
        }
    }

    #[test]
    fn the_lanes_give_each_sample_the_bits_of_its_own_loop() {
        let mut rng = Rng::new(7, 8, 9);
        let strata = Strata::new(37);
        let mut checked = [0; 2];
        for case in 0..400 {
            let n = unit(&mut rng);
            let o = if case % 5 == 0 {
                -unit(&mut rng)
            } else {
                unit(&mut rng)
            };
            let brdf = BrdfParams {
                k: [0.0, 0.5, 1.0, 0.9][case % 4],
                m: [0.0, 1.0, 32.0, 1e4, 1e6][case % 5],
                norm: [
                    Normalization::None,
                    Normalization::Ndf,
                    Normalization::Approx,
                    Normalization::Exact,
                ][case / 4 % 4],
            };
            let s = surface(n, o, brdf);
            // Cones about the normal, about −o (l + o near 0) and anywhere.
            let axis = [n, -o, unit(&mut rng)][case % 3];
            let cone = Cone::new(axis, [0.9, 1e-4, 0.3, 1.0][case % 4]);
            let closed = (case % 2 == 0).then_some(0.25);
            for isa in crate::reference::simd::Isa::available() {
                let mut samples = SphereSamples::default();
                samples.draw(strata, &mut Rng::new(1, case as u64, 2));
                simd::with(isa, || samples.directions(&cone, n));
                for i in 0..samples.u.len() {
                    samples.visible[i] = f64::from(i % 3 != 0);
                }
                simd::with(isa, || samples.terms(&s, 0.7, closed));
                for i in 0..samples.u.len() {
                    let sample = cone.direction((samples.u[i], samples.v[i]));
                    let l = sample.direction;
                    assert_eq!(l, DVec3::new(samples.x[i], samples.y[i], samples.z[i]));
                    assert_eq!(sample.cos_theta.to_bits(), samples.cos_theta[i].to_bits());
                    assert_eq!(sample.sin2_theta.to_bits(), samples.sin2_theta[i].to_bits());
                    let cos = n.dot(l).max(0.0);
                    assert_eq!(cos.to_bits(), samples.cos[i].to_bits());
                    let expected = term(&s, l, (samples.visible[i], cos), 0.7, closed);
                    assert_eq!(
                        expected.to_bits(),
                        samples.terms[i].to_bits(),
                        "{isa:?}, case {case}, sample {i}: {expected} against {}",
                        samples.terms[i]
                    );
                    checked[usize::from(expected != 0.0 && expected != closed.unwrap_or(0.0))] += 1;
                }
            }
        }
        // Both terms that are zero (or the closed form alone) and lobes.
        assert!(checked.iter().all(|&c| c > 1000), "{checked:?}");
    }
}
