//! Random numbers, stratification and the noise estimate of a stratified mean.
//!
//! Every random number is a pure function of (seed, pixel, sample), so an image
//! is the same whatever the number of threads or the order of the tiles, and
//! one pixel traced alone (the probe) gives the value the full render gave it.

use crate::physics::power::below_2_52;
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, TAU};

/// SplitMix64 (Steele, Lea & Flood 2014): a tiny generator whose outputs pass
/// BigCrush; here seeded per pixel sample by hashing its coordinates.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// The stream of one sample of one pixel.
    pub fn new(seed: u64, pixel: u64, sample: u64) -> Self {
        PixelStreams::new(seed, pixel).sample(sample)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(GAMMA);
        mix(self.0)
    }

    /// Uniform in [0, 1): the top 53 bits as the mantissa.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// SplitMix64's step: its state after n steps is the first plus n · GAMMA.
const GAMMA: u64 = 0x9e37_79b9_7f4a_7c15;

/// SplitMix64's output for a state.
#[inline(always)]
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// [`Rng::next_f64`] of an output, in lanes: its top 53 bits t are twice
/// t/2 plus t's last bit, each below 2⁵² (`below_2_52`): the same exact
/// integer.
#[inline(always)]
fn unit(x: u64) -> f64 {
    let t = x >> 11;
    (below_2_52(t >> 1) * 2.0 + below_2_52(t & 1)) * (1.0 / (1u64 << 53) as f64)
}

/// Cell (cx, cy) (as f64) jittered by the two draws of a stream at
/// `state`, as [`Strata::jittered`] makes it (`per`: the cell's size); in
/// lanes, each draw's output a function of the state.
#[inline(always)]
fn jittered_after(state: u64, (cx, cy): (f64, f64), (per_x, per_y): (f64, f64)) -> (f64, f64) {
    let first = state.wrapping_add(GAMMA);
    (
        (cx + unit(mix(first))) * per_x,
        (cy + unit(mix(first.wrapping_add(GAMMA)))) * per_y,
    )
}

/// The streams of one pixel's samples, [`Rng::new`] for each: the hashing
/// of the seed and the pixel done once for all of them.
#[derive(Clone, Copy, Debug)]
pub struct PixelStreams(u64);

impl PixelStreams {
    pub fn new(seed: u64, pixel: u64) -> Self {
        let mut rng = Rng(seed ^ 0x5851_f42d_4c95_7f2d);
        let a = rng.next_u64() ^ pixel.wrapping_mul(0x9e37_79b9_7f4a_7c15);
        Self(Rng(a).next_u64())
    }

    /// The stream of sample `sample`.
    #[inline]
    pub fn sample(self, sample: u64) -> Rng {
        Rng(self.0 ^ sample.wrapping_mul(0xc2b2_ae3d_27d4_eb4f))
    }

    /// The first `u.len()` cells of `strata` jittered each from its own
    /// sample's stream, as [`Strata::jittered`] draws them from
    /// `self.sample(s)`, into `u` and `v`, and each stream as it is after
    /// its two draws into `streams`; `(cx, cy)`: each cell's (ix, iy) as
    /// f64. A loop without branches, for lanes.
    #[inline(always)]
    pub fn jittered_all(
        self,
        strata: Strata,
        (cx, cy): (&[f64], &[f64]),
        (u, v, streams): (&mut [f64], &mut [f64], &mut [Rng]),
    ) {
        let n = u.len();
        let (cx, cy, v, streams) = (&cx[..n], &cy[..n], &mut v[..n], &mut streams[..n]);
        let per = strata.per_cell();
        for s in 0..n {
            let state = self.sample(s as u64).0;
            (u[s], v[s]) = jittered_after(state, (cx[s], cy[s]), per);
            streams[s] = Rng(state.wrapping_add(GAMMA.wrapping_mul(2)));
        }
    }
}

/// The strata of `n` samples over the unit square: a grid of nx × ny = n cells,
/// the factor pair of n closest to a square (8 × 8 for 64, 4 × 8 for 32; a
/// prime n gives 1 × n strips). Square counts stratify best.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Strata {
    pub nx: u32,
    pub ny: u32,
}

impl Strata {
    pub fn new(n: u32) -> Self {
        let n = n.max(1);
        let mut nx = (n as f64).sqrt().floor() as u32;
        while nx > 1 && !n.is_multiple_of(nx) {
            nx -= 1;
        }
        let nx = nx.max(1);
        Self { nx, ny: n / nx }
    }

    pub fn count(self) -> u32 {
        self.nx * self.ny
    }

    /// The cells (ix, iy), row-major, x fastest, so that cells 2j and
    /// 2j + 1 are neighbours whenever nx is even.
    pub fn cells(self) -> impl Iterator<Item = (u32, u32)> {
        (0..self.ny).flat_map(move |iy| (0..self.nx).map(move |ix| (ix, iy)))
    }

    /// [`Self::jittered`] for the first `u.len()` cells in order, as that
    /// many calls draw them from `rng` (which moves on as far), into `u`
    /// and `v`; `(cx, cy)`: each cell's (ix, iy) as f64. A loop without
    /// branches, for lanes: SplitMix64's n-th output is a function of n.
    #[inline(always)]
    pub fn jittered_all(self, rng: &mut Rng, (cx, cy): (&[f64], &[f64]), (u, v): (&mut [f64], &mut [f64])) {
        let n = u.len();
        let (cx, cy, v) = (&cx[..n], &cy[..n], &mut v[..n]);
        let per = self.per_cell();
        let first = rng.0;
        for k in 0..n {
            let state = first.wrapping_add(GAMMA.wrapping_mul(2 * k as u64));
            (u[k], v[k]) = jittered_after(state, (cx[k], cy[k]), per);
        }
        rng.0 = first.wrapping_add(GAMMA.wrapping_mul(2 * n as u64));
    }

    /// Each cell's (ix, iy) as f64, in the order of [`Self::cells`]: what
    /// the lane steps ([`Self::jittered_all`], [`PixelStreams::jittered_all`])
    /// take.
    pub fn cell_coordinates(self) -> (Vec<f64>, Vec<f64>) {
        self.cells().map(|(ix, iy)| (ix as f64, iy as f64)).unzip()
    }

    /// A cell's width and height, 1/nx and 1/ny.
    #[inline(always)]
    fn per_cell(self) -> (f64, f64) {
        (1.0 / self.nx as f64, 1.0 / self.ny as f64)
    }

    /// A point jittered uniformly inside cell (ix, iy).
    #[inline]
    pub fn jittered(self, (ix, iy): (u32, u32), rng: &mut Rng) -> (f64, f64) {
        // Reciprocals that a loop over the cells computes once.
        let (per_x, per_y) = self.per_cell();
        (
            (ix as f64 + rng.next_f64()) * per_x,
            (iy as f64 + rng.next_f64()) * per_y,
        )
    }
}

/// Directions uniform in solid angle inside the cone of half-angle α around
/// the unit axis `w`: cos θ = 1 − u (1 − cos α), φ = 2π v. The map is area
/// preserving, so equal strata of (u, v) are equal solid angles.
#[derive(Clone, Copy, Debug)]
pub struct Cone {
    w: DVec3,
    t1: DVec3,
    t2: DVec3,
    /// 1 − cos α, kept apart so that tiny cones keep their precision.
    one_minus_cos: f64,
}

impl Cone {
    /// The cone with sin²α = `sin2_alpha` ∈ [0, 1]; 1 − cos α is computed as
    /// sin²α / (1 + cos α) so that distant lights do not round to an empty cone.
    pub fn new(w: DVec3, sin2_alpha: f64) -> Self {
        let sin2 = sin2_alpha.clamp(0.0, 1.0);
        let cos = (1.0 - sin2).sqrt();
        Self::with_gap(w, sin2 / (1.0 + cos))
    }

    /// The hemisphere around `w` (a point inside a sphere light sees it everywhere).
    pub fn hemisphere(w: DVec3) -> Self {
        Self::with_gap(w, 1.0)
    }

    fn with_gap(w: DVec3, one_minus_cos: f64) -> Self {
        let (t1, t2) = w.any_orthonormal_pair();
        Self {
            w,
            t1,
            t2,
            one_minus_cos,
        }
    }

    /// Ω = 2π (1 − cos α) (sr).
    pub fn solid_angle(&self) -> f64 {
        TAU * self.one_minus_cos
    }

    /// The direction for (u, v) ∈ [0, 1)² (inlined: the sphere light's
    /// samples take it in lanes).
    #[inline(always)]
    pub fn direction(&self, (u, v): (f64, f64)) -> ConeSample {
        let gap = u * self.one_minus_cos;
        let cos_theta = 1.0 - gap;
        // sin²θ = 1 − cos²θ = gap (2 − gap), exact for small gaps.
        let sin2_theta = (gap * (2.0 - gap)).max(0.0);
        let (s, c) = sin_cos_turns(v);
        ConeSample {
            direction: self.w * cos_theta + (self.t1 * c + self.t2 * s) * sin2_theta.sqrt(),
            cos_theta,
            sin2_theta,
        }
    }
}

/// (sin 2πv, cos 2πv) for v ∈ [0, 1], within 2 ulp of 1 of `sin_cos` and a
/// third of its instructions (the sphere light's samples spent 17 % of theirs
/// in libm's `sin_cos`). The nearest quarter turn q is found exactly (4v and
/// 4v − q are exact), leaving an angle |a| ≤ π/4 whose sine and cosine are
/// their Taylor series up to a¹⁷ and a¹⁶: the first terms left out,
/// a¹⁹/19! and a¹⁸/18!, stay below 2e-18.
#[inline(always)]
fn sin_cos_turns(v: f64) -> (f64, f64) {
    let x = 4.0 * v;
    // Rounded to the nearest integer by adding 1.5 · 2⁵²: its low bits are
    // then that integer (round() is a libm call without SSE4.1).
    const ROUNDER: f64 = 6_755_399_441_055_744.0;
    let rounded = x + ROUNDER;
    let quarter = rounded.to_bits();
    let a = (x - (rounded - ROUNDER)) * FRAC_PI_2;
    let a2 = a * a;
    let a4 = a2 * a2;
    // The series' terms after a and 1 (±1/n!), paired for a shorter chain
    // of dependent operations than Horner's.
    let sin_tail = (-1.0 / 6.0 + a2 * (1.0 / 120.0))
        + a4 * (-1.0 / 5040.0 + a2 * (1.0 / 362_880.0))
        + a4 * a4
            * ((-1.0 / 39_916_800.0 + a2 * (1.0 / 6_227_020_800.0))
                + a4 * (-1.0 / 1_307_674_368_000.0 + a2 * (1.0 / 355_687_428_096_000.0)));
    let cos_tail = (-1.0 / 2.0 + a2 * (1.0 / 24.0))
        + a4 * (-1.0 / 720.0 + a2 * (1.0 / 40_320.0))
        + a4 * a4
            * ((-1.0 / 3_628_800.0 + a2 * (1.0 / 479_001_600.0))
                + a4 * (-1.0 / 87_178_291_200.0 + a2 * (1.0 / 20_922_789_888_000.0)));
    let (sin_a, cos_a) = (a + a * a2 * sin_tail, 1.0 + a2 * cos_tail);
    match quarter & 3 {
        0 => (sin_a, cos_a),
        1 => (cos_a, -sin_a),
        2 => (-sin_a, -cos_a),
        _ => (-cos_a, sin_a),
    }
}

/// A direction in a cone and its angle θ to the axis.
#[derive(Clone, Copy, Debug)]
pub struct ConeSample {
    /// Unit direction.
    pub direction: DVec3,
    pub cos_theta: f64,
    /// sin²θ, accurate even when θ is tiny.
    pub sin2_theta: f64,
}

/// The variance of the mean of stratified samples `y` (one per equal-weight
/// stratum) by the collapsed-strata estimator: neighbouring strata are grouped
/// in pairs (a last triple when the count is odd) and each group of g values
/// contributes g/(g − 1) Σ (y − ȳ_group)², the unbiased variance of its sum
/// had its strata been merged; the total divided by n² is the variance of the
/// mean. It errs on the safe side: differences between neighbouring strata
/// count as noise. None when fewer than two samples leave nothing to compare.
pub fn collapsed_strata_variance(y: &[f64]) -> Option<f64> {
    let n = y.len();
    if n < 2 {
        return None;
    }
    // A pair contributes 2 · ((a − b) / 2)² · 2 = (a − b)²; an odd count
    // ends with a triple.
    let (pairs, triple) = if n % 2 == 1 {
        (&y[..n - 3], Some(&y[n - 3..]))
    } else {
        (y, None)
    };
    let mut sum: f64 = pairs.chunks_exact(2).map(|p| (p[0] - p[1]) * (p[0] - p[1])).sum();
    if let Some(group) = triple {
        let mean = group.iter().sum::<f64>() / 3.0;
        sum += 1.5 * group.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>();
    }
    Some(sum / (n * n) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sin_cos_turns_is_libms_within_its_rounding() {
        let mut rng = Rng::new(7, 0, 0);
        // The quarter turns' edges, where the reduction switches, and random v.
        let edges = (0..=8).flat_map(|k| {
            let v = k as f64 / 8.0;
            [v, v.next_up(), v.next_down().max(0.0)]
        });
        for v in edges
            .chain((0..100_000).map(|_| rng.next_f64()))
            .filter(|v| (0.0..=1.0).contains(v))
        {
            let (s, c) = sin_cos_turns(v);
            // libm's own argument 2πv is rounded: half an ulp of it more.
            let (s0, c0) = (TAU * v).sin_cos();
            let tolerance = 2.3e-16 + TAU * v * f64::EPSILON / 2.0;
            assert!(
                (s - s0).abs() <= tolerance && (c - c0).abs() <= tolerance,
                "v = {v}: ({s}, {c}) against ({s0}, {c0})"
            );
            assert!((s * s + c * c - 1.0).abs() <= 4.5e-16, "v = {v}");
        }
    }

    #[test]
    fn strata_are_the_squarest_factor_pair() {
        assert_eq!(Strata::new(64), Strata { nx: 8, ny: 8 });
        assert_eq!(Strata::new(32), Strata { nx: 4, ny: 8 });
        assert_eq!(Strata::new(7), Strata { nx: 1, ny: 7 });
        assert_eq!(Strata::new(1), Strata { nx: 1, ny: 1 });
        assert_eq!(Strata::new(0).count(), 1);
    }

    #[test]
    fn all_cells_jittered_at_once_take_the_bits_of_one_by_one() {
        for n in [1, 7, 12, 64] {
            let strata = Strata::new(n);
            let cells: Vec<_> = strata.cells().collect();
            let (cx, cy) = strata.cell_coordinates();
            for isa in crate::reference::simd::Isa::available() {
                let (mut one, mut all) = (Rng::new(5, n as u64, 6), Rng::new(5, n as u64, 6));
                let (mut u, mut v) = (vec![0.0; n as usize], vec![0.0; n as usize]);
                crate::reference::simd::with(isa, || {
                    strata.jittered_all(&mut all, (&cx, &cy), (&mut u, &mut v))
                });
                for (k, &cell) in cells.iter().enumerate() {
                    let (a, b) = strata.jittered(cell, &mut one);
                    assert_eq!(
                        (a.to_bits(), b.to_bits()),
                        (u[k].to_bits(), v[k].to_bits()),
                        "{isa:?} {n} {k}"
                    );
                }
                assert_eq!(one.next_u64(), all.next_u64());
            }
        }
    }

    #[test]
    fn each_sample_jittered_from_its_stream_at_once_takes_the_bits_of_one_by_one() {
        for n in [2, 7, 12, 64] {
            let strata = Strata::new(n);
            let cells: Vec<_> = strata.cells().collect();
            let (cx, cy) = strata.cell_coordinates();
            let streams = PixelStreams::new(9, 1000 + n as u64);
            for isa in crate::reference::simd::Isa::available() {
                let (mut u, mut v) = (vec![0.0; n as usize], vec![0.0; n as usize]);
                let mut after = vec![Rng(0); n as usize];
                crate::reference::simd::with(isa, || {
                    streams.jittered_all(strata, (&cx, &cy), (&mut u, &mut v, &mut after))
                });
                for (s, &cell) in cells.iter().enumerate() {
                    let mut one = streams.sample(s as u64);
                    let (a, b) = strata.jittered(cell, &mut one);
                    assert_eq!(
                        (a.to_bits(), b.to_bits()),
                        (u[s].to_bits(), v[s].to_bits()),
                        "{isa:?} {n} {s}"
                    );
                    assert_eq!(one.next_u64(), after[s].next_u64(), "{isa:?} {n} {s}");
                }
            }
        }
    }

    #[test]
    fn jittered_points_stay_in_their_cell() {
        let strata = Strata::new(12);
        let mut rng = Rng::new(3, 4, 5);
        let cells: Vec<_> = strata.cells().collect();
        assert_eq!(cells.len(), 12);
        for (i, &cell) in cells.iter().enumerate() {
            let (u, v) = strata.jittered(cell, &mut rng);
            let (ix, iy) = ((u * strata.nx as f64) as u32, (v * strata.ny as f64) as u32);
            assert_eq!(iy * strata.nx + ix, i as u32);
        }
    }

    #[test]
    fn random_numbers_are_uniform_and_reproducible() {
        let mut a = Rng::new(1, 2, 3);
        let mut b = Rng::new(1, 2, 3);
        let n = 100_000;
        let mut sum = 0.0;
        for _ in 0..n {
            let x = a.next_f64();
            assert_eq!(x, b.next_f64());
            assert!((0.0..1.0).contains(&x));
            sum += x;
        }
        // The mean of n uniforms has standard deviation 1/√(12 n).
        assert!((sum / n as f64 - 0.5).abs() < 5.0 / (12.0 * n as f64).sqrt());
        assert_ne!(Rng::new(1, 2, 3).next_u64(), Rng::new(1, 2, 4).next_u64());
        assert_ne!(Rng::new(1, 2, 3).next_u64(), Rng::new(1, 3, 3).next_u64());
    }

    #[test]
    fn cone_directions_stay_inside_the_cone_and_cover_its_solid_angle() {
        let w = DVec3::new(1.0, 2.0, -0.5).normalize();
        let sin2: f64 = 0.09;
        let cone = Cone::new(w, sin2);
        let cos_alpha = (1.0 - sin2).sqrt();
        assert!((cone.solid_angle() - TAU * (1.0 - cos_alpha)).abs() < 1e-15);
        let mut rng = Rng::new(0, 0, 0);
        for _ in 0..1000 {
            let s = cone.direction((rng.next_f64(), rng.next_f64()));
            assert!((s.direction.length() - 1.0).abs() < 1e-12);
            assert!((s.direction.dot(w) - s.cos_theta).abs() < 1e-12 && s.cos_theta >= cos_alpha - 1e-12);
            assert!((s.sin2_theta + s.cos_theta * s.cos_theta - 1.0).abs() < 1e-12);
        }
        // A light 10^9 radii away still has a cone (Ω ≈ π sin²α).
        let tiny = Cone::new(w, 1e-18);
        assert!((tiny.solid_angle() / (std::f64::consts::PI * 1e-18) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn collapsed_strata_variance_matches_the_pair_formula() {
        assert_eq!(collapsed_strata_variance(&[1.0]), None);
        assert_eq!(collapsed_strata_variance(&[2.0, 2.0, 2.0, 2.0]), Some(0.0));
        // Pairs (1, 3) and (0, 4): ((1 − 3)² + (0 − 4)²) / 4².
        let v = collapsed_strata_variance(&[1.0, 3.0, 0.0, 4.0]).unwrap();
        assert!((v - 20.0 / 16.0).abs() < 1e-15);
        // A triple (0, 3, 6): 3/2 · 18 over 3².
        let v = collapsed_strata_variance(&[0.0, 3.0, 6.0]).unwrap();
        assert!((v - 27.0 / 9.0).abs() < 1e-15);
    }
}
