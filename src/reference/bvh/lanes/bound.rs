//! A block of eight lanes bounded for the first pass of [`Lines`]: a
//! centre and a spread, in f32 (the lanes side by side in AVX where the
//! CPU has it).

use super::{BOUND_ROUNDING, Block, LANES};
#[cfg(doc)]
use super::{Bounds, Lines};

/// A block's entries in [`Bounds`] but its limit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct BlockBound {
    pub(super) c: [f32; 3],
    pub(super) spread: f32,
    pub(super) reach: f32,
}

/// What [`Lines::fill`] adds to the group's first pass when a lane's
/// direction is not finite: no block is passed over for its spread.
pub(super) const UNBOUNDED: BlockBound = BlockBound {
    c: [0.0; 3],
    spread: f32::INFINITY,
    reach: f32::INFINITY,
};

/// A bound of a block's first `lanes` lanes (one at least), which also
/// sets each lane's |d|∞ in `block.reach`: a centre c (the middle of the
/// lanes' box) and a spread s with |E(lane) − (c · n)| ≤ s |n|₁ for every
/// lane, and their largest |d|∞, each with the first pass's allowance.
///
/// In f32: r ≥ |d − c|₂ ≥ |(d − c) · n| / |n|₁ for every lane, where the
/// square sums round by 3 ε₃₂ of their value at most and the root by ε₃₂ / 2
/// (8 ε₃₂ allowed), and underflow loses less than `R_FLOOR`; the lane test's
/// E differs from d · n, and its f32 value of c · n from c · n, by at most
/// 3 ε₃₂ (|d|∞ + |c|∞) |n|₁ together, with |d|∞ ≤ |c|∞ + r (here 16 ε₃₂).
/// The spread and the reach are then raised by the first pass's allowance
/// and by 10⁻⁶ for their own f32 rounding (a few operations of 6·10⁻⁸).
pub(super) fn block_bound(block: &mut Block, lanes: usize) -> BlockBound {
    let mut finite = true;
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for l in 0..lanes {
        block.reach[l] = (0..3).fold(0.0_f32, |m, i| m.max(block.d[i][l].abs()));
        for i in 0..3 {
            finite &= block.d[i][l].is_finite();
            (lo[i], hi[i]) = (lo[i].min(block.d[i][l]), hi[i].max(block.d[i][l]));
        }
    }
    if !finite {
        return UNBOUNDED;
    }
    let c: [f32; 3] = std::array::from_fn(|i| 0.5 * (lo[i] + hi[i]));
    let (mut r2, mut reach) = (0.0_f32, 0.0_f32);
    for l in 0..lanes {
        let [x, y, z] = std::array::from_fn(|i| block.d[i][l] - c[i]);
        r2 = r2.max((x * x + y * y) + z * z);
        reach = reach.max(block.reach[l]);
    }
    bound_from(c, r2, reach)
}

/// [`block_bound`] with the eight lanes in one AVX register (unused lanes
/// take lane 0's direction for the bound).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
pub(super) fn block_bound_avx(block: &mut Block, lanes: usize) -> BlockBound {
    use std::arch::x86_64::*;
    // SAFETY: each load and store moves eight in-bounds f32.
    let load = |a: &[f32; LANES]| unsafe { _mm256_loadu_ps(a.as_ptr()) };
    let index = _mm256_setr_ps(0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0);
    let used = _mm256_cmp_ps::<_CMP_LT_OQ>(index, _mm256_set1_ps(lanes as f32));
    let d = [0, 1, 2].map(|i| load(&block.d[i]));
    let magnitude = d.map(|d| _mm256_andnot_ps(_mm256_set1_ps(-0.0), d));
    let reach = _mm256_max_ps(magnitude[0], _mm256_max_ps(magnitude[1], magnitude[2]));
    // SAFETY: as above.
    unsafe { _mm256_storeu_ps(block.reach.as_mut_ptr(), reach) };
    let infinity = _mm256_set1_ps(f32::INFINITY);
    let finite = magnitude
        .map(|m| _mm256_cmp_ps::<_CMP_LT_OQ>(m, infinity))
        .into_iter()
        .fold(used, |all, f| _mm256_and_ps(all, f));
    if _mm256_movemask_ps(finite) != _mm256_movemask_ps(used) {
        return UNBOUNDED;
    }
    let d = [0, 1, 2].map(|i| _mm256_blendv_ps(_mm256_set1_ps(block.d[i][0]), d[i], used));
    let c: [f32; 3] = std::array::from_fn(|i| 0.5 * (across(d[i], _mm_min_ps) + across(d[i], _mm_max_ps)));
    let [x, y, z] = std::array::from_fn(|i| _mm256_sub_ps(d[i], _mm256_set1_ps(c[i])));
    let r2 = _mm256_add_ps(
        _mm256_add_ps(_mm256_mul_ps(x, x), _mm256_mul_ps(y, y)),
        _mm256_mul_ps(z, z),
    );
    bound_from(c, across(r2, _mm_max_ps), across(reach, _mm_max_ps))
}

/// `op` (min or max) across the eight lanes of `v`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
fn across(
    v: std::arch::x86_64::__m256,
    op: unsafe fn(std::arch::x86_64::__m128, std::arch::x86_64::__m128) -> std::arch::x86_64::__m128,
) -> f32 {
    use std::arch::x86_64::*;
    // SAFETY: `op` is an SSE min or max, which every x86-64 runs.
    unsafe {
        let m = op(_mm256_castps256_ps128(v), _mm256_extractf128_ps::<1>(v));
        let m = op(m, _mm_movehl_ps(m, m));
        _mm_cvtss_f32(op(m, _mm_shuffle_ps::<1>(m, m)))
    }
}

/// What underflow may take from the root of a sum of three f32 squares:
/// less than the root of three times the least normal f32, 2·10⁻¹⁹.
const R_FLOOR: f32 = 4e-19;

/// A block's bound from its centre c, the largest |d − c|₂² of its lanes
/// as f32 computes it and their largest |d|∞ (see [`block_bound`]).
fn bound_from(c: [f32; 3], r2: f32, reach: f32) -> BlockBound {
    let allowance = ((1.0 + BOUND_ROUNDING) * (1.0 + 1e-6)) as f32;
    let r = r2.sqrt() * (1.0 + 8.0 * f32::EPSILON) + R_FLOOR;
    let size = c.iter().fold(0.0_f32, |m, ci| m.max(ci.abs()));
    BlockBound {
        c,
        spread: (r + 16.0 * f32::EPSILON * (size + r)) * allowance,
        reach: reach * allowance,
    }
}
