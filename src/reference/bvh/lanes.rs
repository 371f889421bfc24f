//! The miss test of the watertight triangle test for four rays at once: the
//! packets' first filter. It runs the very operations of the scalar test
//! (`ShearedRay::edges`) — the same subtractions, products and sign tests in
//! the same order, with no fused multiply-add — two lanes per SSE2 register
//! (part of every x86-64 CPU; plain pairs elsewhere), so each lane's edge
//! functions carry the scalar test's bits. A lane it calls a miss is one the
//! scalar test calls a miss; every other lane goes on to the scalar test,
//! which decides. The answers are the scalar path's, bit for bit.

use crate::reference::intersect::{Axes, ShearedRay, other_axes};
use glam::DVec3;

/// Rays per group.
pub const LANES: usize = 4;

/// Up to [`LANES`] rays with one set of axes, their shear and origins as
/// arrays (one entry per lane).
#[derive(Clone, Copy, Debug)]
pub struct Group {
    sx: [f64; LANES],
    sy: [f64; LANES],
    origin: [[f64; LANES]; 3],
    /// Bit l: lane l holds a ray.
    pub used: u32,
}

impl Group {
    /// The rays, in lane order (at most [`LANES`], all with the axes `axes`).
    pub fn new(rays: &[ShearedRay], axes: Axes) -> Self {
        debug_assert!(rays.len() <= LANES && rays.iter().all(|r| r.axes() == axes));
        let mut group = Self {
            sx: [0.0; LANES],
            sy: [0.0; LANES],
            origin: [[0.0; LANES]; 3],
            used: 0,
        };
        for (l, ray) in rays.iter().enumerate() {
            (group.sx[l], group.sy[l]) = ray.shear();
            for k in 0..3 {
                group.origin[k][l] = ray.origin[k];
            }
            group.used |= 1 << l;
        }
        group
    }

    /// Bit l set unless lane l's ray surely misses the triangle: its edge
    /// functions take both signs. `corners` relative to the rays' origins
    /// when `RELATIVE` (the lanes' origins then go unused), else absolute.
    #[inline(always)]
    pub fn may_hit<const KZ: usize, const SWAP: bool, const RELATIVE: bool>(
        &self,
        corners: &[DVec3; 3],
    ) -> u32 {
        let (kx, ky) = other_axes(KZ, SWAP);
        let mut mask = 0;
        for half in 0..LANES / 2 {
            let at = |p: &DVec3, k: usize| {
                let c = X2::splat(p[k]);
                if RELATIVE {
                    c
                } else {
                    // p − origin, as ShearedRay::relative computes it.
                    c - X2::load(&self.origin[k], half)
                }
            };
            let (sx, sy) = (X2::load(&self.sx, half), X2::load(&self.sy, half));
            let [a, b, c] = corners;
            let (ax, ay) = (at(a, kx) - sx * at(a, KZ), at(a, ky) - sy * at(a, KZ));
            let (bx, by) = (at(b, kx) - sx * at(b, KZ), at(b, ky) - sy * at(b, KZ));
            let (cx, cy) = (at(c, kx) - sx * at(c, KZ), at(c, ky) - sy * at(c, KZ));
            let u = cx * by - cy * bx;
            let v = ax * cy - ay * cx;
            let w = bx * ay - by * ax;
            let negative = u.negative_bits() | v.negative_bits() | w.negative_bits();
            let positive = u.positive_bits() | v.positive_bits() | w.positive_bits();
            mask |= (!(negative & positive) & 0b11) << (2 * half);
        }
        mask & self.used
    }
}

/// Runs `f` compiled with AVX2 enabled when the CPU has it (inlined code
/// then uses 256-bit registers and three-operand instructions), as it is
/// otherwise. Fused multiply-add stays off: every result keeps its bits.
#[inline(always)]
pub fn with_avx2<R>(f: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        #[target_feature(enable = "avx2")]
        fn avx2<R>(f: impl FnOnce() -> R) -> R {
            f()
        }
        // SAFETY: the CPU has AVX2.
        return unsafe { avx2(f) };
    }
    f()
}

/// Two f64 lanes: SSE2 on x86-64 (every such CPU has it), plain pairs
/// elsewhere; IEEE operations lane by lane either way.
#[derive(Clone, Copy)]
struct X2(Pair);

#[cfg(target_arch = "x86_64")]
type Pair = std::arch::x86_64::__m128d;
#[cfg(not(target_arch = "x86_64"))]
type Pair = [f64; 2];

#[cfg(target_arch = "x86_64")]
mod pair {
    use super::{LANES, X2};
    // SAFETY (every block below): SSE2 is part of the x86-64 baseline, and
    // the loads read two in-bounds f64 (half < LANES / 2).
    use std::arch::x86_64::*;

    impl X2 {
        #[inline(always)]
        pub fn splat(x: f64) -> Self {
            Self(unsafe { _mm_set1_pd(x) })
        }
        #[inline(always)]
        pub fn load(values: &[f64; LANES], half: usize) -> Self {
            Self(unsafe { _mm_loadu_pd(values[2 * half..2 * half + 2].as_ptr()) })
        }
        /// Bit l: lane l < 0.
        #[inline(always)]
        pub fn negative_bits(self) -> u32 {
            unsafe { _mm_movemask_pd(_mm_cmplt_pd(self.0, _mm_setzero_pd())) as u32 }
        }
        /// Bit l: lane l > 0.
        #[inline(always)]
        pub fn positive_bits(self) -> u32 {
            unsafe { _mm_movemask_pd(_mm_cmpgt_pd(self.0, _mm_setzero_pd())) as u32 }
        }
    }
    impl std::ops::Sub for X2 {
        type Output = Self;
        #[inline(always)]
        fn sub(self, o: Self) -> Self {
            Self(unsafe { _mm_sub_pd(self.0, o.0) })
        }
    }
    impl std::ops::Mul for X2 {
        type Output = Self;
        #[inline(always)]
        fn mul(self, o: Self) -> Self {
            Self(unsafe { _mm_mul_pd(self.0, o.0) })
        }
    }
}

#[cfg(not(target_arch = "x86_64"))]
mod pair {
    use super::{LANES, X2};

    impl X2 {
        pub fn splat(x: f64) -> Self {
            Self([x, x])
        }
        pub fn load(values: &[f64; LANES], half: usize) -> Self {
            Self([values[2 * half], values[2 * half + 1]])
        }
        pub fn negative_bits(self) -> u32 {
            u32::from(self.0[0] < 0.0) | u32::from(self.0[1] < 0.0) << 1
        }
        pub fn positive_bits(self) -> u32 {
            u32::from(self.0[0] > 0.0) | u32::from(self.0[1] > 0.0) << 1
        }
    }
    impl std::ops::Sub for X2 {
        type Output = Self;
        fn sub(self, o: Self) -> Self {
            Self([self.0[0] - o.0[0], self.0[1] - o.0[1]])
        }
    }
    impl std::ops::Mul for X2 {
        type Output = Self;
        fn mul(self, o: Self) -> Self {
            Self([self.0[0] * o.0[0], self.0[1] * o.0[1]])
        }
    }
}

/// Rays split into groups of [`LANES`] when they all share one set of axes
/// (None otherwise: each ray is then tested on its own).
#[derive(Debug, Default)]
pub struct Groups {
    pub axes: Option<Axes>,
    pub groups: Vec<Group>,
}

impl Groups {
    pub fn fill(&mut self, rays: &[ShearedRay]) {
        self.groups.clear();
        let first = rays.first().map(|r| r.axes());
        self.axes = first.filter(|&a| rays.iter().all(|r| r.axes() == a));
        if let Some(axes) = self.axes {
            self.groups
                .extend(rays.chunks(LANES).map(|chunk| Group::new(chunk, axes)));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::intersect::with_axes;
    use crate::reference::sampling::Rng;

    #[test]
    fn a_lane_called_a_miss_is_a_miss_of_the_scalar_test() {
        // Rays through corners, along edges and near them, from random
        // origins: whenever the scalar test finds the triangle (at any
        // distance), the lanes must not have ruled it out; and they do rule
        // out most misses.
        let mut rng = Rng::new(31, 0, 0);
        let mut point = |scale: f64| DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * scale;
        let (mut found, mut ruled_out, mut misses) = (0, 0, 0);
        for case in 0..4000 {
            let tri = [point(2.0), point(2.0), point(2.0)];
            let origin = point(8.0) - DVec3::splat(4.0);
            let aims = [
                tri[0],
                tri[1].lerp(tri[2], 0.5),
                tri[case % 3].lerp(tri[(case + 1) % 3], 0.3),
                tri[0].lerp(tri[1], 0.5).lerp(tri[2], 0.5),
            ];
            let jitter = [0.0, 1e-15, 1e-9, 1e-3][case % 4];
            let rays: Vec<ShearedRay> = aims
                .iter()
                .map(|&p| ShearedRay::new(origin, p - origin + point(jitter)))
                .collect();
            let axes = rays[0].axes();
            let same: Vec<ShearedRay> = rays.iter().copied().filter(|r| r.axes() == axes).collect();
            let group = Group::new(&same, axes);
            let relative = same[0].relative(&tri);
            let (shifted, rel) = with_axes!(axes, KZ, SWAP => (
                group.may_hit::<KZ, SWAP, false>(&tri),
                group.may_hit::<KZ, SWAP, true>(&relative),
            ));
            assert_eq!(
                shifted, rel,
                "case {case}: one origin, either way of giving the corners"
            );
            for (l, ray) in same.iter().enumerate() {
                let hit = ray.intersect(&tri, f64::NEG_INFINITY, f64::INFINITY).is_some();
                let kept = shifted & (1 << l) != 0;
                assert!(kept || !hit, "case {case}, lane {l}: a hit ruled out");
                found += usize::from(hit);
                misses += usize::from(!hit);
                ruled_out += usize::from(!kept);
            }
        }
        assert!(found > 4000, "too few hits to tell: {found}");
        assert!(
            ruled_out * 10 > misses * 9,
            "{ruled_out} of {misses} misses ruled out"
        );
    }
}
