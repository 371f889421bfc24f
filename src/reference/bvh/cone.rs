//! The cone a packet's rays lie in, and its tests: a triangle's corners
//! against its side planes, a node's eight child boxes against them and
//! against the rays' floor, with the allowances for rounding that keep
//! every test conservative (see `bvh/packet.rs`).

use super::TriangleBvh;
use glam::DVec3;
use obvhs::cwbvh::node::{CwBvhNode, extract_byte64};

/// Relative allowance for the rounding of depths and plane distances.
pub(super) const ROUNDING: f64 = 1e-12;

/// A cone of directions from its apex: what every ray of a packet lies in.
#[derive(Clone, Copy, Debug)]
pub struct Cone {
    pub(super) apex: DVec3,
    /// The inward normals of its four side planes through the apex.
    pub(super) planes: [DVec3; 4],
    /// The axis depths are measured along (unit).
    pub(super) axis: DVec3,
}

impl Cone {
    /// The cone spanned by four directions in order around it (the corner
    /// rays of a pixel): every convex combination of them lies inside.
    pub fn spanned(apex: DVec3, corners: [DVec3; 4]) -> Self {
        let axis = (corners[0] + corners[1] + corners[2] + corners[3]).normalize();
        let planes = std::array::from_fn(|k| {
            let n = corners[k].cross(corners[(k + 1) % 4]);
            if n.dot(axis) < 0.0 { -n } else { n }
        });
        Self { apex, planes, axis }
    }

    /// A cone from `apex` holding every point of `points` (at least one),
    /// about the direction of their mean; None when some point does not lie
    /// beyond the plane through the apex across it. (Unit directions
    /// summed instead cost a square root and a division a point: 0.8 % of
    /// the 110 k-triangle engine's process, a shadow packet holding 128.)
    #[inline(always)]
    pub fn around(apex: DVec3, points: impl Iterator<Item = DVec3> + Clone) -> Option<Self> {
        let frame = axis_about(apex, points.clone())?;
        Extent::EMPTY
            .with(apex, points, frame)
            .cone(apex, frame)
            .map(|(cone, _)| cone)
    }

    /// [`Self::around`] the points of a slice, with the least and the
    /// greatest depth of the points along its axis: four points at a time
    /// in AVX2 where the CPU has it (each lane the same operations; the
    /// engine's render: 1.7 % fewer instructions).
    #[inline(always)]
    pub fn around_reaching(apex: DVec3, points: &[DVec3]) -> Option<(Self, [f64; 2])> {
        let frame = axis_about(apex, points.iter().copied())?;
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2.
            let extent = unsafe { extent_avx2(apex, points, frame) };
            return extent.cone(apex, frame);
        }
        Extent::EMPTY
            .with(apex, points.iter().copied(), frame)
            .cone(apex, frame)
    }

    /// The square pyramid from `apex` about the unit `axis` whose four
    /// sides rise at `slope` from it (tan of their angle to the axis),
    /// widened by the rounding of its planes.
    pub fn square(apex: DVec3, axis: DVec3, slope: f64) -> Self {
        let (u, v) = axis.any_orthonormal_pair();
        let s = slope * (1.0 + ROUNDING) + ROUNDING;
        Self {
            apex,
            planes: [u + axis * s, axis * s - u, v + axis * s, axis * s - v],
            axis,
        }
    }

    pub fn axis(&self) -> DVec3 {
        self.axis
    }

    /// The larger of its two widths across the axis, as tangents of the
    /// angle from it (s₁ − s₀ or r₁ − r₀ of [`Self::around`]; twice the
    /// slope of [`Self::square`]). Not for [`Self::spanned`]'s cones, whose
    /// planes are not of unit length.
    pub fn width(&self) -> f64 {
        let [a, b, c, d] = self.planes.map(|n| n.dot(self.axis));
        (a + b).max(c + d)
    }

    /// The least depth along the axis of the triangle (corners relative to
    /// the apex), less `slack`.
    #[inline(always)]
    pub(super) fn least_depth(&self, relative: &[DVec3; 3], slack: f64) -> f64 {
        relative
            .iter()
            .fold(f64::INFINITY, |m, p| m.min(p.dot(self.axis)))
            - slack
    }

    /// Whether the triangle (corners relative to the apex) lies wholly
    /// outside one side plane, `slack` allowed.
    #[inline(always)]
    pub(super) fn misses(&self, relative: &[DVec3; 3], slack: f64) -> bool {
        self.planes.iter().fold(false, |m, &n| {
            m | wholly_below(relative, n, -slack * n.abs().element_sum())
        })
    }
}

/// Whether every corner (relative to the apex) has n · p below `bound`:
/// all three tested, without a branch between them (whether a corner is
/// below is a coin toss near the cone's sides).
#[inline(always)]
fn wholly_below(relative: &[DVec3; 3], n: DVec3, bound: f64) -> bool {
    relative.iter().fold(true, |all, p| all & (n.dot(*p) < bound))
}

/// The cone, for boxes of the BVH's normalized frame.
pub(super) struct FrameCone {
    pub(super) cone: Cone,
    /// The apex's distance from the frame's centre, for the rounding allowance.
    pub(super) apex_size: f64,
    /// The rays' floor, if any ([`Rays::floor`]).
    pub(super) floor: Option<(DVec3, f64)>,
}

impl FrameCone {
    /// `cone` for `bvh`'s boxes, with the rays' floor if any.
    pub(super) fn new(cone: Cone, bvh: &TriangleBvh, floor: Option<(DVec3, f64)>) -> Self {
        Self {
            cone,
            apex_size: (cone.apex - bvh.centre).abs().max_element(),
            floor,
        }
    }

    /// Whether the triangle (corners relative to the apex) lies wholly
    /// outside a side plane or below the floor, `slack` allowed.
    #[inline(always)]
    pub(super) fn misses(&self, relative: &[DVec3; 3], slack: f64) -> bool {
        // Both tests, without a branch between them.
        self.cone.misses(relative, slack)
            | self
                .floor
                .is_some_and(|(n, level)| wholly_below(relative, n, level - slack * n.abs().element_sum()))
    }

    /// obvhs's hit mask of the children of `node` that [`Self::children`] keeps.
    #[inline(always)]
    pub(super) fn child_mask(
        &self,
        bvh: &TriangleBvh,
        node: &CwBvhNode,
        farthest: f64,
        oct_inv4: u32,
    ) -> u32 {
        let (child_bits8, bit_index8) = node.get_child_and_index_bits(oct_inv4);
        let (kept, _) = self.kept_children(bvh, node, farthest);
        // Every child, kept or not: no loop over the kept ones to end in a
        // mispredicted branch.
        let mut hit_mask = 0;
        for child in 0..8 {
            let bits = extract_byte64(child_bits8, child) << extract_byte64(bit_index8, child);
            hit_mask |= bits & (kept >> child & 1).wrapping_neg();
        }
        hit_mask
    }

    /// Calls `keep(least depth, child)` for each child of `node` whose box
    /// meets the cone with a least depth no deeper than `farthest`.
    ///
    /// A child's box is p + e·q (q its quantized corners, 0 to 255), so a
    /// plane's value at the box's farthest corner along n is
    /// n·p + Σ_k (n_k e_k) q_k: three products per plane and child, for the
    /// eight children side by side. Every box lies within p … p + 255 e,
    /// whose size sets one rounding allowance for all of them (no smaller
    /// than each box's own; the rearranged sums round by some 10⁻¹⁵ of it).
    #[inline(always)]
    pub(super) fn children(
        &self,
        bvh: &TriangleBvh,
        node: &CwBvhNode,
        farthest: f64,
        mut keep: impl FnMut(f64, usize),
    ) {
        let (mut kept, depth) = self.kept_children(bvh, node, farthest);
        while kept != 0 {
            let child = kept.trailing_zeros() as usize;
            kept &= kept - 1;
            keep(depth[child], child);
        }
    }

    /// The children [`Self::children`] keeps, as bits (bit c: child c),
    /// and each child's least depth: without a branch a test and child,
    /// which was mispredicted often.
    #[inline(always)]
    fn kept_children(&self, bvh: &TriangleBvh, node: &CwBvhNode, farthest: f64) -> (u32, [f64; 8]) {
        let scale = 1.0 / bvh.per_scale;
        // In f64, relative to the apex, in world units.
        let e = node.compute_extent().as_dvec3() * scale;
        let p = node.p.as_dvec3() * scale + bvh.centre - self.cone.apex;
        let size = p.abs().max((p + e * 255.0).abs()).max_element();
        let slack = ROUNDING * (size + self.apex_size);
        let mut inside = [true; 8];
        for n in self.cone.planes {
            keep_above(
                &mut inside,
                corner_values(node, n, p, e, true),
                -slack * n.abs().element_sum(),
            );
        }
        if let Some((n, floor)) = self.floor {
            let bound = floor - slack * n.abs().element_sum();
            keep_above(&mut inside, corner_values(node, n, p, e, true), bound);
        }
        let depth = corner_values(node, self.cone.axis, p, e, false).map(|d| d - slack);
        let mut kept = 0_u32;
        for child in 0..8 {
            let keeps = inside[child] & !node.is_child_empty(child) & (depth[child] <= farthest);
            kept |= u32::from(keeps) << child;
        }
        (kept, depth)
    }
}

/// Keeps inside only the children whose farthest corner `values` lie at
/// or above `bound` (NaN, never for finite boxes, keeps the child).
#[inline(always)]
fn keep_above(inside: &mut [bool; 8], values: [f64; 8], bound: f64) {
    for c in 0..8 {
        inside[c] &= values[c] >= bound || values[c].is_nan();
    }
}

/// The value of n·x at each child box's corner farthest along n (nearest
/// when not `farthest`): the box is p + e·q, q its quantized corners.
#[inline(always)]
fn corner_values(node: &CwBvhNode, n: DVec3, p: DVec3, e: DVec3, farthest: bool) -> [f64; 8] {
    let lo = [&node.child_min_x, &node.child_min_y, &node.child_min_z];
    let hi = [&node.child_max_x, &node.child_max_y, &node.child_max_z];
    let q: [&[u8; 8]; 3] = std::array::from_fn(|k| if (n[k] > 0.0) == farthest { hi[k] } else { lo[k] });
    let (base, w) = (n.dot(p), n * e);
    std::array::from_fn(|c| base + w.x * q[0][c] as f64 + w.y * q[1][c] as f64 + w.z * q[2][c] as f64)
}

/// The unit direction of the mean of `points` from `apex` and two unit
/// directions across it (None when the mean is the apex, or not finite).
#[inline(always)]
fn axis_about(apex: DVec3, points: impl Iterator<Item = DVec3>) -> Option<(DVec3, DVec3, DVec3)> {
    let axis = points.fold(DVec3::ZERO, |s, p| s + (p - apex)).try_normalize()?;
    let (u, v) = axis.any_orthonormal_pair();
    Some((axis, u, v))
}

/// Points seen from an apex: their least and greatest depth along an axis
/// and the least and greatest of their two slopes across it, and whether
/// every one lies ahead, at a finite depth.
#[derive(Clone, Copy, Debug)]
struct Extent {
    near: f64,
    far: f64,
    s: [f64; 2],
    r: [f64; 2],
    ahead: bool,
}

impl Extent {
    const EMPTY: Self = Self {
        near: f64::INFINITY,
        far: 0.0,
        s: [f64::INFINITY, f64::NEG_INFINITY],
        r: [f64::INFINITY, f64::NEG_INFINITY],
        ahead: true,
    };

    /// One more point, at w from the apex.
    #[inline(always)]
    fn add(&mut self, w: DVec3, (axis, u, v): (DVec3, DVec3, DVec3)) {
        let along = w.dot(axis);
        // Two comparisons (NaN fails the first): `is_finite` and
        // `f64::min`'s NaN rule took some 60 instructions a point.
        self.ahead &= along > 0.0 && along < f64::INFINITY;
        self.near = if along < self.near { along } else { self.near };
        self.far = if along > self.far { along } else { self.far };
        let inverse = along.recip();
        let (s, r) = (w.dot(u) * inverse, w.dot(v) * inverse);
        // A NaN slope is passed over, as f64::min and max would.
        self.s = [
            if s < self.s[0] { s } else { self.s[0] },
            if s > self.s[1] { s } else { self.s[1] },
        ];
        self.r = [
            if r < self.r[0] { r } else { self.r[0] },
            if r > self.r[1] { r } else { self.r[1] },
        ];
    }

    /// With `points` too, seen from `apex`.
    #[inline(always)]
    fn with(
        mut self,
        apex: DVec3,
        points: impl Iterator<Item = DVec3>,
        frame: (DVec3, DVec3, DVec3),
    ) -> Self {
        for p in points {
            self.add(p - apex, frame);
        }
        self
    }

    /// The cone from `apex` about `axis` that holds the points, widened by
    /// the rounding of their slopes, with their least and greatest depth;
    /// None unless every point lies ahead.
    fn cone(&self, apex: DVec3, (axis, u, v): (DVec3, DVec3, DVec3)) -> Option<(Cone, [f64; 2])> {
        if !self.ahead {
            return None;
        }
        let widen = |x: f64| ROUNDING * (1.0 + x.abs());
        let ([s0, s1], [r0, r1]) = (self.s, self.r);
        let (s0, s1, r0, r1) = (s0 - widen(s0), s1 + widen(s1), r0 - widen(r0), r1 + widen(r1));
        let cone = Cone {
            apex,
            planes: [u - axis * s0, axis * s1 - u, v - axis * r0, axis * r1 - v],
            axis,
        };
        Some((cone, [self.near, self.far]))
    }
}

/// The [`Extent`] of `points` seen from `apex`, four points at a time,
/// each lane doing [`Extent::add`]'s operations in its order (packed
/// minimum and maximum choose as its comparisons do); the points past the
/// last four one by one.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn extent_avx2(apex: DVec3, points: &[DVec3], frame: (DVec3, DVec3, DVec3)) -> Extent {
    use std::arch::x86_64::*;
    let (axis, u, v) = frame;
    let set = |x: f64| _mm256_set1_pd(x);
    let dot = |w: [__m256d; 3], n: DVec3| {
        _mm256_add_pd(
            _mm256_add_pd(_mm256_mul_pd(w[0], set(n.x)), _mm256_mul_pd(w[1], set(n.y))),
            _mm256_mul_pd(w[2], set(n.z)),
        )
    };
    let (mut near, mut far) = (set(f64::INFINITY), set(0.0));
    let (mut s0, mut s1) = (set(f64::INFINITY), set(f64::NEG_INFINITY));
    let (mut r0, mut r1) = (s0, s1);
    let mut ahead = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
    let chunks = points.chunks_exact(4);
    let rest = chunks.remainder();
    // Each point's coordinates, three f64 apart.
    let index = _mm256_setr_epi64x(0, 3, 6, 9);
    for chunk in chunks {
        let at = chunk.as_ptr().cast::<f64>();
        // SAFETY: the four points' twelve coordinates lie in the chunk.
        let p = [0, 1, 2].map(|k| unsafe { _mm256_i64gather_pd::<8>(at.add(k), index) });
        let w = [0, 1, 2].map(|k| _mm256_sub_pd(p[k], set(apex[k])));
        let along = dot(w, axis);
        let fine = _mm256_and_pd(
            _mm256_cmp_pd::<_CMP_GT_OQ>(along, _mm256_setzero_pd()),
            _mm256_cmp_pd::<_CMP_LT_OQ>(along, set(f64::INFINITY)),
        );
        ahead = _mm256_and_pd(ahead, fine);
        (near, far) = (_mm256_min_pd(along, near), _mm256_max_pd(along, far));
        let inverse = _mm256_div_pd(set(1.0), along);
        let (s, r) = (
            _mm256_mul_pd(dot(w, u), inverse),
            _mm256_mul_pd(dot(w, v), inverse),
        );
        (s0, s1) = (_mm256_min_pd(s, s0), _mm256_max_pd(s, s1));
        (r0, r1) = (_mm256_min_pd(r, r0), _mm256_max_pd(r, r1));
    }
    let lanes = |x: __m256d| {
        let mut out = [0.0; 4];
        // SAFETY: four f64 into an array of four.
        unsafe { _mm256_storeu_pd(out.as_mut_ptr(), x) };
        out
    };
    let least = |x: __m256d| {
        lanes(x)
            .into_iter()
            .fold(f64::INFINITY, |m, x| if x < m { x } else { m })
    };
    let most = |x: __m256d, from: f64| lanes(x).into_iter().fold(from, |m, x| if x > m { x } else { m });
    let lanes = Extent {
        near: least(near),
        far: most(far, 0.0),
        s: [least(s0), most(s1, f64::NEG_INFINITY)],
        r: [least(r0), most(r1, f64::NEG_INFINITY)],
        ahead: _mm256_movemask_pd(ahead) == 0b1111,
    };
    lanes.with(apex, rest.iter().copied(), frame)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::sampling::Rng;

    /// The AVX2 extent of 1 to 13 points (some behind the apex, some at
    /// it, some not finite) is the one the points give one by one.
    #[test]
    #[cfg(target_arch = "x86_64")]
    fn the_lanes_extent_is_the_points_one_by_one() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            return;
        }
        let mut rng = Rng::new(43, 0, 0);
        let mut unit = || rng.next_f64() - 0.5;
        let (mut ahead, mut behind) = (0, 0);
        for case in 0..3000 {
            let apex = DVec3::new(unit(), unit(), unit()) * 10.0;
            let towards = DVec3::new(unit(), unit(), unit()) * 8.0;
            let spread = [1e-3, 0.3, 3.0][case % 3];
            let mut points: Vec<DVec3> = (0..1 + case % 13)
                .map(|_| apex + towards + DVec3::new(unit(), unit(), unit()) * spread * 8.0)
                .collect();
            let some = case % points.len();
            if case % 50 == 7 {
                points[some] = apex;
            }
            if case % 50 == 9 {
                points[some].y = f64::NAN;
            }
            let Some(frame) = axis_about(apex, points.iter().copied()) else {
                continue;
            };
            let one_by_one = Extent::EMPTY.with(apex, points.iter().copied(), frame);
            // SAFETY: the CPU has AVX2.
            let lanes = unsafe { extent_avx2(apex, &points, frame) };
            assert_eq!(lanes.ahead, one_by_one.ahead, "case {case}");
            if !one_by_one.ahead {
                behind += 1;
                continue;
            }
            ahead += 1;
            let values = |e: &Extent| [e.near, e.far, e.s[0], e.s[1], e.r[0], e.r[1]];
            assert_eq!(values(&lanes), values(&one_by_one), "case {case}");
        }
        assert!(
            ahead > 1000 && behind > 100,
            "ahead {ahead}, behind {behind}: too one-sided"
        );
    }
}
