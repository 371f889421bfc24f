//! A pixel's primary rays, several samples, side by side: each sample's
//! jittered point (from its own stream) and its direction from the eye,
//! each step a loop without branches over the pixel's samples, compiled
//! for AVX2 where the CPU has it (inside the covered pixels' lanes, for
//! their set: AVX2 nested there cost the small race's scene 0.033 →
//! 0.0355 s). Each lane does the operations of
//! `Strata::jittered` and `PixelRays::towards`, in the same order: the same
//! bits as sample by sample.

use super::pixel_streams;
use crate::reference::sampling::{Rng, Strata};
use crate::reference::shading::Setup;
use crate::reference::simd::{self, Isa};
use glam::DVec3;

/// One pixel's primary sample directions and streams.
#[derive(Debug, Default)]
pub(super) struct PrimaryDirections {
    /// The strata of `cx` and `cy`, each cell's (ix, iy) as f64.
    strata: Option<Strata>,
    cx: Vec<f64>,
    cy: Vec<f64>,
    /// Each sample's image point.
    u: Vec<f64>,
    v: Vec<f64>,
    /// Each sample's direction from the eye (not normalized), by coordinate.
    pub(super) x: Vec<f64>,
    pub(super) y: Vec<f64>,
    pub(super) z: Vec<f64>,
    /// Each sample's stream, after the two draws of its point.
    pub(super) streams: Vec<Rng>,
}

impl PrimaryDirections {
    /// Pixel (i, j)'s `spp` samples (several: one is the pixel's centre).
    pub(super) fn of(&mut self, setup: &Setup, spp: Strata, pixel: (u32, u32)) {
        simd::with(
            Isa::Avx2,
            #[inline(always)]
            || self.of_here(setup, spp, pixel),
        );
    }

    /// [`Self::of`], inlined into lane code compiled for its own set.
    #[inline(always)]
    pub(super) fn of_here(&mut self, setup: &Setup, spp: Strata, (i, j): (u32, u32)) {
        debug_assert!(spp.count() > 1, "one sample a pixel is its centre, not jittered");
        let n = spp.count() as usize;
        if self.strata != Some(spp) {
            self.strata = Some(spp);
            (self.cx, self.cy) = spp.cell_coordinates();
            for v in [&mut self.u, &mut self.v, &mut self.x, &mut self.y, &mut self.z] {
                v.resize(n, 0.0);
            }
            // Placeholders: every pixel's step writes each one.
            self.streams = vec![Rng::new(0, 0, 0); n];
        }
        let streams = pixel_streams(setup, i, j);
        let (x0, y0) = (i as f64, j as f64);
        let (u, v) = (&mut self.u[..n], &mut self.v[..n]);
        streams.jittered_all(spp, (&self.cx, &self.cy), (u, v, &mut self.streams));
        for k in 0..n {
            u[k] += x0;
            v[k] += y0;
        }
        let out = [&mut self.x[..], &mut self.y[..], &mut self.z[..]];
        setup.rays.towards_all((u, v), out);
    }

    /// Sample s's direction.
    pub(super) fn direction(&self, s: usize) -> DVec3 {
        DVec3::new(self.x[s], self.y[s], self.z[s])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::ReferenceOptions;
    use crate::settings::Settings;
    use glam::Vec3;

    /// Each sample's direction and stream, on every ISA the CPU runs, have
    /// the bits of `Strata::jittered` from the sample's own stream and
    /// `PixelRays::towards` at the pixel's corner plus the jitter.
    #[test]
    fn each_lane_takes_the_bits_of_its_own_sample() {
        let mut settings = Settings::default();
        settings.camera.eye = Vec3::new(1.3, 2.9, -4.1);
        settings.camera.fovy_deg = 63.0;
        (settings.image.width, settings.image.height) = (97, 41);
        for spp in [2, 7, 16, 64] {
            let options = ReferenceOptions {
                spp,
                ..ReferenceOptions::default()
            };
            let setup = Setup::new(&settings, &options, &[]);
            let strata = Strata::new(spp);
            for isa in Isa::available() {
                let mut lanes = PrimaryDirections::default();
                for (i, j) in [(0, 0), (96, 40), (13, 29), (50, 7)] {
                    simd::with(isa, || lanes.of_here(&setup, strata, (i, j)));
                    let streams = pixel_streams(&setup, i, j);
                    for (s, cell) in strata.cells().enumerate() {
                        let mut one = streams.sample(s as u64);
                        let (dx, dy) = strata.jittered(cell, &mut one);
                        let d = setup.rays.towards(i as f64 + dx, j as f64 + dy);
                        let lane = lanes.direction(s);
                        assert_eq!(d.to_array().map(f64::to_bits), lane.to_array().map(f64::to_bits));
                        assert_eq!(one.next_u64(), lanes.streams[s].clone().next_u64(), "{isa:?} {s}");
                    }
                }
            }
        }
    }
}
