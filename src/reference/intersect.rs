//! The ray–triangle test, in f64: the watertight algorithm of Woop, Benthin
//! & Wald (JCGT 2013). The ray is sheared so that it runs along +z through the
//! origin; the triangle's 2D edge functions U, V, W then decide the hit by their
//! signs alone, so a ray through an edge or a vertex shared by two triangles
//! hits at least one of them: no cracks, whatever the rounding.
//!
//! The axis permutation depends on the ray only. Loops that test one ray
//! against many triangles fix it at compile time (`with_axes!` and the
//! `*_in` methods), so that picking coordinates costs nothing; the
//! per-call methods dispatch on it once per triangle. Both run the same
//! operations in the same order: the same bits.

use glam::DVec3;

/// The largest |coordinate| of a triangle's corners (relative to a point:
/// its size seen from there), which the rounding allowances of the tests
/// on them scale with.
pub(super) fn extent(corners: &[DVec3; 3]) -> f64 {
    corners.iter().fold(0.0_f64, |m, p| m.max(p.abs().max_element()))
}

/// The permutation of a ray's axes: kz is the axis of its largest |d|
/// component; kx, ky the two others in cyclic order, swapped when d_kz < 0
/// so that the winding is kept.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Axes {
    pub kz: usize,
    pub swap: bool,
}

/// Runs `$body` with the const generics `$kz: usize` and `$swap: bool` set
/// to the value of `$axes` (an [`Axes`]): one match, six instantiations.
macro_rules! with_axes {
    ($axes:expr, $kz:ident, $swap:ident => $body:expr) => {{
        let axes: $crate::reference::intersect::Axes = $axes;
        match (axes.kz, axes.swap) {
            (0, false) => with_axes!(@arm 0, false, $kz, $swap, $body),
            (0, true) => with_axes!(@arm 0, true, $kz, $swap, $body),
            (1, false) => with_axes!(@arm 1, false, $kz, $swap, $body),
            (1, true) => with_axes!(@arm 1, true, $kz, $swap, $body),
            (_, false) => with_axes!(@arm 2, false, $kz, $swap, $body),
            (_, true) => with_axes!(@arm 2, true, $kz, $swap, $body),
        }
    }};
    (@arm $k:literal, $s:literal, $kz:ident, $swap:ident, $body:expr) => {{
        const $kz: usize = $k;
        const $swap: bool = $s;
        $body
    }};
}
pub(crate) use with_axes;

/// A ray prepared for many triangle tests: its origin, its direction and
/// their shear.
#[derive(Clone, Copy, Debug)]
pub struct ShearedRay {
    pub origin: DVec3,
    pub direction: DVec3,
    pub shear: Shear,
}

/// What the tests of triangles taken relative to a ray's origin need of
/// its direction: its axes and the shear constants (40 bytes, against a
/// whole ray's 88: a packet of rays from one point keeps only these).
#[derive(Clone, Copy, Debug)]
pub struct Shear {
    axes: Axes,
    /// d_kx / d_kz, d_ky / d_kz, 1 / d_kz.
    sx: f64,
    sy: f64,
    sz: f64,
}

/// Where a ray meets a triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit {
    /// Distance along the ray in units of its direction's length.
    pub t: f64,
    /// Barycentric weights of the corners a, b, c (sum 1).
    pub barycentric: [f64; 3],
}

/// The two other axes of kz, cyclic, swapped on request.
#[inline(always)]
pub(crate) const fn other_axes(kz: usize, swap: bool) -> (usize, usize) {
    let (kx, ky) = ((kz + 1) % 3, (kz + 2) % 3);
    if swap { (ky, kx) } else { (kx, ky) }
}

impl ShearedRay {
    /// `direction` need not be normalized but must not be zero.
    pub fn new(origin: DVec3, direction: DVec3) -> Self {
        Self {
            origin,
            direction,
            shear: Shear::new(direction),
        }
    }

    /// The corners relative to the ray's origin, as the `*_in` methods take them.
    #[inline(always)]
    pub fn relative(&self, corners: &[DVec3; 3]) -> [DVec3; 3] {
        corners.map(|p| p - self.origin)
    }

    /// The hit with t ∈ (t_min, t_max), both faces counted; None for a miss
    /// or a degenerate (zero-area in projection) triangle.
    #[inline]
    pub fn intersect(&self, corners: &[DVec3; 3], t_min: f64, t_max: f64) -> Option<TriangleHit> {
        let relative = self.relative(corners);
        let shear = &self.shear;
        with_axes!(shear.axes, KZ, SWAP => shear.intersect_in::<KZ, SWAP>(&relative, t_min, t_max))
    }

    /// Whether the ray meets the triangle at t ∈ (t_min, t_max), without
    /// any division (t = t_scaled / det compared as in Woop et al.).
    #[inline]
    pub fn hits(&self, corners: &[DVec3; 3], t_min: f64, t_max: f64) -> bool {
        self.shear.hits_from(self.origin, corners, t_min, t_max)
    }
}

impl Shear {
    /// `direction`'s (not normalized, not zero).
    pub fn new(direction: DVec3) -> Self {
        let a = direction.abs();
        let kz = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        let axes = Axes {
            kz,
            swap: direction[kz] < 0.0,
        };
        let (kx, ky) = other_axes(kz, axes.swap);
        let sz = 1.0 / direction[kz];
        Self {
            axes,
            sx: direction[kx] * sz,
            sy: direction[ky] * sz,
            sz,
        }
    }

    pub fn axes(&self) -> Axes {
        self.axes
    }

    /// The shear constants d_kx / d_kz and d_ky / d_kz.
    pub fn shear(&self) -> (f64, f64) {
        (self.sx, self.sy)
    }

    /// 1 / |d_kz|: a point at depth z along the ray's main axis is at t = z / |d_kz|.
    pub fn per_depth(&self) -> f64 {
        self.sz.abs()
    }

    /// [`ShearedRay::hits`] of the ray from `origin` along this shear's
    /// direction.
    #[inline]
    pub fn hits_from(&self, origin: DVec3, corners: &[DVec3; 3], t_min: f64, t_max: f64) -> bool {
        let relative = corners.map(|p| p - origin);
        with_axes!(self.axes, KZ, SWAP => self.hits_in::<KZ, SWAP>(&relative, t_min, t_max))
    }

    /// [`ShearedRay::intersect`] with the corners relative to the origin and
    /// the ray's own axes as `KZ`, `SWAP` (see `with_axes!`).
    #[inline(always)]
    pub fn intersect_in<const KZ: usize, const SWAP: bool>(
        &self,
        relative: &[DVec3; 3],
        t_min: f64,
        t_max: f64,
    ) -> Option<TriangleHit> {
        let e = self.edges::<KZ, SWAP>(relative)?;
        // A division-free test a little wider than the range first; then the
        // range on the computed t itself, so that the closest of several
        // hits is decided by their computed distances alone, in any order.
        let slack = 1.0 + 4.0 * f64::EPSILON;
        if !(e.t_scaled * slack > t_min * e.det && e.t_scaled < t_max * e.det * slack) {
            return None;
        }
        // One division serves the distance and the barycentrics.
        let inv = 1.0 / e.det;
        let t = e.t_scaled * inv;
        (t > t_min && t < t_max).then_some(TriangleHit {
            t,
            barycentric: [e.u * inv, e.v * inv, e.w * inv],
        })
    }

    /// [`ShearedRay::hits`] with the corners relative to the origin and the
    /// ray's own axes as `KZ`, `SWAP`.
    #[inline(always)]
    pub fn hits_in<const KZ: usize, const SWAP: bool>(
        &self,
        relative: &[DVec3; 3],
        t_min: f64,
        t_max: f64,
    ) -> bool {
        self.edges::<KZ, SWAP>(relative)
            .is_some_and(|e| e.t_scaled > t_min * e.det && e.t_scaled < t_max * e.det)
    }

    /// The edge functions and the scaled distance, with signs normalized so
    /// that det > 0; None when the ray misses the triangle's interior.
    #[inline(always)]
    fn edges<const KZ: usize, const SWAP: bool>(&self, [a, b, c]: &[DVec3; 3]) -> Option<Edges> {
        debug_assert_eq!(self.axes, Axes { kz: KZ, swap: SWAP });
        let (kx, ky) = other_axes(KZ, SWAP);
        let (ax, ay) = (a[kx] - self.sx * a[KZ], a[ky] - self.sy * a[KZ]);
        let (bx, by) = (b[kx] - self.sx * b[KZ], b[ky] - self.sy * b[KZ]);
        let (cx, cy) = (c[kx] - self.sx * c[KZ], c[ky] - self.sy * c[KZ]);
        // Twice the signed areas of the sub-triangles opposite a, b and c.
        let u = cx * by - cy * bx;
        let v = ax * cy - ay * cx;
        let w = bx * ay - by * ax;
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let t_scaled = u * self.sz * a[KZ] + v * self.sz * b[KZ] + w * self.sz * c[KZ];
        let sign = det.signum();
        Some(Edges {
            u: sign * u,
            v: sign * v,
            w: sign * w,
            det: sign * det,
            t_scaled: sign * t_scaled,
        })
    }
}

/// The unnormalized result of the test: t = t_scaled / det, barycentrics
/// (u, v, w) / det.
struct Edges {
    u: f64,
    v: f64,
    w: f64,
    det: f64,
    t_scaled: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    const TRI: [DVec3; 3] = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
    ];

    #[test]
    fn hit_distance_and_barycentrics_reproduce_the_point() {
        let o = DVec3::new(0.2, 0.3, 2.0);
        for d in [
            DVec3::NEG_Z,
            DVec3::new(0.1, -0.05, -1.0),
            DVec3::new(0.0, 0.0, -3.0),
        ] {
            let hit = ShearedRay::new(o, d).intersect(&TRI, 0.0, f64::INFINITY).unwrap();
            let p = o + d * hit.t;
            let q = TRI[0] * hit.barycentric[0] + TRI[1] * hit.barycentric[1] + TRI[2] * hit.barycentric[2];
            assert!((p - q).length() < 1e-15, "{p} vs {q}");
            assert!((hit.barycentric.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        }
    }

    #[test]
    fn both_faces_hit_and_the_range_is_open() {
        let up = ShearedRay::new(DVec3::new(0.25, 0.25, -1.0), DVec3::Z);
        assert_eq!(up.intersect(&TRI, 0.0, 2.0).map(|h| h.t), Some(1.0));
        assert!(up.intersect(&TRI, 1.0, 2.0).is_none());
        assert!(up.intersect(&TRI, 0.0, 1.0).is_none());
        let miss = ShearedRay::new(DVec3::new(0.75, 0.75, -1.0), DVec3::Z);
        assert!(miss.intersect(&TRI, 0.0, 2.0).is_none());
    }

    #[test]
    fn a_ray_through_a_shared_edge_hits_a_side() {
        // Two triangles sharing the diagonal of the unit square; rays exactly
        // on the diagonal must hit at least one of them.
        let other = [TRI[1], DVec3::new(1.0, 1.0, 0.0), TRI[2]];
        for i in 1..100 {
            let x = i as f64 / 100.0;
            let ray = ShearedRay::new(DVec3::new(x, 1.0 - x, 1.0), DVec3::new(0.0, 0.0, -1.0));
            let hits = [&TRI, &other]
                .iter()
                .filter(|t| ray.intersect(t, 0.0, 10.0).is_some())
                .count();
            assert!(hits >= 1, "x = {x}");
        }
    }

    #[test]
    fn degenerate_triangles_are_missed() {
        let line = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        let ray = ShearedRay::new(DVec3::new(0.5, 0.0, 1.0), DVec3::NEG_Z);
        assert!(ray.intersect(&line, 0.0, 10.0).is_none());
    }
}
