//! The depth bound of a triangle in a cell: a lower bound of the depth
//! (along the face's axis) of the triangle's part inside the cell's pyramid,
//! widened by `MARGIN` as the binning is, by which the cell's list is sorted.
//!
//! For a triangle wholly in front of the face it comes without clipping:
//! the least depth of its corners, raised to the least depth of its plane
//! inside the pyramid where the pyramid's four edge rays all meet that plane
//! (the plane's part inside the pyramid is then the quadrilateral of their
//! hits, and depth is linear on it: for a triangle covering the cell this is
//! the exact least depth), or no depth at all where a side plane through
//! the apex, the pyramid's or the triangle's, surely separates them.
//! Otherwise the triangle is clipped to the pyramid.

use super::{APEX, CELLS, MARGIN, cell_parts, clip_to_pyramid, extent, face_axes};
use glam::DVec3;

/// Triangles thinner than this (|n| against |e₁||e₂|, the sine of their
/// sharpest angle or so) and planes met more obliquely than this (|n · r|
/// against |n||r|) give no plane bound: their depths would round too coarsely.
const WELL_CONDITIONED: f64 = 1e-3;
/// Relative allowance for the rounding of every depth and side test here
/// (a few units of 10⁻¹⁶ each, 10⁻⁹ or so once divided by a conditioned
/// n · r).
const ROUNDING: f64 = 1e-8;

/// |p|∞.
fn norm(p: DVec3) -> f64 {
    p.abs().max_element()
}

/// A triangle (corners relative to the apex) as the bounds see it from the
/// apex, worked out once for all its cells.
pub(super) struct Seen {
    relative: [DVec3; 3],
    size: f64,
    /// Its three side planes through the apex, inward, each with the scale
    /// of its rounding; None when its orientation from the apex is unsure.
    sides: Option<[(DVec3, f64); 3]>,
    /// Its plane, n · x = offset, when well conditioned.
    plane: Option<(DVec3, f64)>,
}

impl Seen {
    pub fn new(relative: [DVec3; 3]) -> Self {
        let [a, b, c] = relative;
        let towards = a.dot(b.cross(c));
        let sure = towards.abs() > ROUNDING * norm(a) * norm(b) * norm(c);
        let side = |p: DVec3, q: DVec3| (p.cross(q) * towards.signum(), norm(p) * norm(q));
        let (e1, e2) = (b - a, c - a);
        let n = e1.cross(e2);
        let conditioned = n.length() >= WELL_CONDITIONED * e1.length() * e2.length();
        Self {
            relative,
            size: extent(&relative),
            sides: sure.then(|| [side(a, b), side(b, c), side(c, a)]),
            plane: conditioned.then(|| (n, n.dot(a))),
        }
    }
}

/// A cell's pyramid: its face and bounds, edge rays and side planes.
pub(super) struct Pyramid {
    face: usize,
    u: (f64, f64),
    v: (f64, f64),
    /// Its edge rays, each of depth 1, in order around it.
    rays: [DVec3; 4],
    /// Its side planes, inward, each with the scale of its rounding.
    walls: [(DVec3, f64); 4],
}

impl Pyramid {
    pub fn new(cell: usize) -> Self {
        let (face, i, j) = cell_parts(cell);
        let edge = |n: usize| -1.0 + 2.0 * n as f64 / CELLS as f64;
        let u = (edge(i) - MARGIN, edge(i + 1) + MARGIN);
        let v = (edge(j) - MARGIN, edge(j + 1) + MARGIN);
        let (k, sign, ia, ib) = face_axes(face);
        let ray = |u: f64, v: f64| DVec3::AXES[k] * sign + DVec3::AXES[ia] * u + DVec3::AXES[ib] * v;
        let rays = [ray(u.0, v.0), ray(u.1, v.0), ray(u.1, v.1), ray(u.0, v.1)];
        let inward = rays[0].cross(rays[1]).dot(rays[2]).signum();
        let walls = std::array::from_fn(|i| {
            let (p, q) = (rays[i], rays[(i + 1) % 4]);
            (p.cross(q) * inward, norm(p) * norm(q))
        });
        Self {
            face,
            u,
            v,
            rays,
            walls,
        }
    }

    /// The triangle's depth bound in this cell: never below 0, infinite
    /// when nothing of it is inside.
    pub fn depth_of(&self, seen: &Seen) -> f64 {
        self.unclipped(seen)
            .or_else(|| self.plane_only(seen))
            .unwrap_or_else(|| self.clipped(&seen.relative))
    }

    /// The bound without clipping; None when a corner is not in front of
    /// the face by more than `APEX` or the triangle's orientation is unsure.
    fn unclipped(&self, seen: &Seen) -> Option<f64> {
        let (k, sign, _, _) = face_axes(self.face);
        let depths = seen.relative.map(|p| sign * p[k]);
        if !depths.iter().all(|&d| d > APEX * seen.size) {
            return None;
        }
        // Wholly outside a side plane of the other, by more than the rounding.
        let outside = |(n, scale): (DVec3, f64), points: &[DVec3]| {
            points.iter().all(|&p| n.dot(p) < -ROUNDING * scale * norm(p))
        };
        let sides = seen.sides?;
        if sides.iter().any(|&side| outside(side, &self.rays))
            || self.walls.iter().any(|&wall| outside(wall, &seen.relative))
        {
            return Some(f64::INFINITY);
        }
        let corners = depths.iter().fold(f64::INFINITY, |m, &d| m.min(d));
        let least = corners.max(self.plane_depth(seen));
        Some((least * (1.0 - ROUNDING) - ROUNDING * seen.size).max(0.0))
    }

    /// The bound of the triangle's plane alone, for a triangle not wholly
    /// in front of the face (a ground plane around the eye): its part inside
    /// the pyramid lies on the plane's, whose least depth is at an edge
    /// ray's hit. Less the rounding of the plane's offset, worked out from a
    /// corner that may lie far from both the apex and the cell (10⁻⁸ of its
    /// distance, far above it). None where the plane gives no bound.
    fn plane_only(&self, seen: &Seen) -> Option<f64> {
        let least = self.plane_depth(seen);
        let slack = ROUNDING * (seen.size + norm(seen.relative[0]));
        (least > 0.0).then(|| (least * (1.0 - ROUNDING) - slack).max(0.0))
    }

    /// The least depth where the edge rays meet the triangle's plane, when
    /// each meets it in front at a conditioned angle; else 0.
    fn plane_depth(&self, seen: &Seen) -> f64 {
        let Some((n, offset)) = seen.plane else {
            return 0.0;
        };
        let length = n.length();
        let mut least = f64::INFINITY;
        for r in &self.rays {
            let along = n.dot(*r);
            // False for NaN too.
            let ahead = along * offset > 0.0;
            if !ahead || along.abs() < WELL_CONDITIONED * length * r.length() {
                return 0.0;
            }
            least = least.min(offset / along);
        }
        least
    }

    /// The bound by clipping the triangle to the pyramid: its least depth
    /// is at a vertex of the clipped polygon; less the rounding of clipping
    /// (10⁻⁹ of the triangle's size, far above it). Infinite where nothing
    /// is left.
    fn clipped(&self, relative: &[DVec3; 3]) -> f64 {
        let (k, sign, _, _) = face_axes(self.face);
        let Some(polygon) = clip_to_pyramid(relative, self.face, self.u, self.v) else {
            // Listed by the wider per-face bounds only: it cannot be hit here.
            return f64::INFINITY;
        };
        let least = polygon
            .points()
            .iter()
            .fold(f64::INFINITY, |m, w| m.min(sign * w[k]));
        (least - 1e-9 * extent(relative)).max(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::sampling::Rng;

    /// Triangles in front of the +X face, large (covering many cells, some
    /// obliquely) and small: wherever the bound without clipping answers,
    /// it lies at or below the clipped one, equals it within 10⁻⁶ where the
    /// triangle covers the cell, and calls a cell empty only where
    /// clipping leaves nothing. Taking the planes' hits' greatest depth
    /// instead of their least fails it.
    #[test]
    fn the_bound_without_clipping_never_exceeds_the_clipped_one() {
        let mut rng = Rng::new(41, 0, 0);
        let mut unit = || 2.0 * rng.next_f64() - 1.0;
        let (mut covered, mut empty, mut answered) = (0, 0, 0);
        for case in 0..80 {
            let reach = if case % 2 == 0 { 2.5 } else { 0.05 };
            let centre = DVec3::new(1.5 + unit().abs(), 0.8 * unit(), 0.8 * unit());
            let mut corner = || centre + DVec3::new(unit(), unit(), unit()) * reach;
            let seen = Seen::new([corner(), corner(), corner()]);
            for cell in (0..CELLS * CELLS).step_by(3) {
                let pyramid = Pyramid::new(cell);
                let Some(bound) = pyramid.unclipped(&seen) else {
                    continue;
                };
                answered += 1;
                // The clipped polygon's least depth itself, without its margin.
                let least = pyramid.clipped(&seen.relative) + 1e-9 * seen.size;
                if bound == f64::INFINITY {
                    empty += 1;
                    assert_eq!(
                        least,
                        f64::INFINITY,
                        "a cell called empty holds part of the triangle"
                    );
                    continue;
                }
                assert!(bound <= least, "{bound} above {least}");
                let inside = pyramid.rays.iter().all(|&r| {
                    let sides = seen.sides.expect("answered");
                    sides.iter().all(|&(n, _)| n.dot(r) > 0.0)
                });
                if inside {
                    covered += 1;
                    assert!(bound >= least - 1e-6 * (1.0 + least), "{bound} far below {least}");
                }
            }
        }
        assert!(
            covered > 1000 && empty > 1000 && answered > covered + empty,
            "{covered} {empty} {answered}"
        );
    }

    /// Triangles across the +X face's plane (one corner behind the apex, as
    /// a ground is around an eye above it): wherever the plane's bound
    /// answers, it lies at or below the clipped one, and equals it within
    /// 10⁻⁶ where the triangle covers the cell. Taking the edge rays'
    /// farthest hit instead of their nearest fails it.
    #[test]
    fn the_planes_bound_never_exceeds_the_clipped_one() {
        let mut rng = Rng::new(43, 0, 0);
        let mut unit = || 2.0 * rng.next_f64() - 1.0;
        let (mut covered, mut answered) = (0, 0);
        for _ in 0..60 {
            // x: one corner behind the apex, two ahead of it.
            let mut corners = [-1.0, 1.0, 1.0].map(|side: f64| {
                let x = side * (0.2 + 2.0 * unit().abs());
                DVec3::new(x, 3.0 * unit(), 3.0 * unit())
            });
            corners.rotate_left(1);
            let seen = Seen::new(corners);
            for cell in (0..CELLS * CELLS).step_by(3) {
                let pyramid = Pyramid::new(cell);
                let Some(bound) = pyramid.plane_only(&seen) else {
                    continue;
                };
                let least = pyramid.clipped(&seen.relative) + 1e-9 * seen.size;
                if least == f64::INFINITY {
                    continue;
                }
                answered += 1;
                assert!(bound <= least, "{bound} above {least}");
                let inside = seen.sides.is_some_and(|sides| {
                    pyramid
                        .rays
                        .iter()
                        .all(|&r| sides.iter().all(|&(n, _)| n.dot(r) > 0.0))
                });
                if inside {
                    covered += 1;
                    assert!(bound >= least - 1e-6 * (1.0 + least), "{bound} far below {least}");
                }
            }
        }
        assert!(covered > 1000 && answered > covered, "{covered} {answered}");
    }
}
