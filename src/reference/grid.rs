//! Rays that share an end point (every primary ray starts at the eye, every
//! shadow ray of a point light ends at the light) are cast through a
//! direction grid around that point, the "light buffer" of Haines & Greenberg
//! (1986): a cube map whose cells list every triangle seen in their cone of
//! directions. Every point of such a ray lies in the one direction of the
//! ray, so the triangles it can hit are all in one cell, and the closest hit
//! (or any hit) among that short list, by the same f64 test, is exactly what
//! testing every triangle gives.
//!
//! Binning is conservative: each triangle, relative to the centre, is clipped
//! to each face's pyramid widened by [`WIDEN`], projected, and its bounding
//! rectangle widened by [`MARGIN`] before it is rasterized into cells; a
//! triangle reaching the centre itself covers the whole face. Cells listing
//! more than [`MAX_LIST`] triangles answer "ask the BVH" instead.

use super::bvh::{BvhTriangle, Hit, closer};
use super::intersect::ShearedRay;
use glam::DVec3;

/// Cells per side of each cube face (each about 0.7° wide).
pub const CELLS: usize = 128;
/// Longest list a cell answers from; longer ones defer to the BVH.
pub const MAX_LIST: usize = 24;
/// The face pyramids overlap by this much (|u| ≤ 1 + WIDEN), so a direction
/// on the edge between two faces finds its triangles in either.
const WIDEN: f64 = 1e-9;
/// Widening of each projected rectangle, in face coordinates (width 2):
/// covers the rounding of clipping and projecting (~10⁻¹⁵ relative, at most
/// 10⁹ times that near the apex, see `APEX`).
const MARGIN: f64 = 1e-6;
/// A clipped vertex closer to the centre's face plane than this fraction of
/// the triangle's size projects unreliably: the triangle then covers the face.
const APEX: f64 = 1e-9;

/// What a cell says about a ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Answer<T> {
    /// The exact answer.
    Known(T),
    /// The cell is too crowded: ask the BVH.
    AskBvh,
}

#[derive(Clone, Debug)]
pub struct DirectionGrid {
    centre: DVec3,
    /// Per cell, (first, count) of its triangles in `items`; count
    /// `CROWDED` when the cell defers to the BVH.
    cells: Vec<(u32, u32)>,
    /// Indices into the triangle list the grid was built from.
    items: Vec<u32>,
}

/// The count of a cell listing more than [`MAX_LIST`] triangles.
const CROWDED: u32 = u32::MAX;

impl DirectionGrid {
    /// The grid around `centre` of the triangles `keep` accepts.
    pub fn new(centre: DVec3, triangles: &[BvhTriangle], keep: impl Fn(&BvhTriangle) -> bool) -> Self {
        let cells = 6 * CELLS * CELLS;
        let mut lists: Vec<Vec<u32>> = vec![Vec::new(); cells];
        for (index, tri) in triangles.iter().enumerate() {
            if !keep(tri) || !tri.corners.iter().all(|p| p.is_finite()) {
                continue;
            }
            let relative = tri.corners.map(|p| p - centre);
            for face in 0..6 {
                if let Some([i0, i1, j0, j1]) = cell_range(&relative, face) {
                    for j in j0..=j1 {
                        for i in i0..=i1 {
                            lists[cell_index(face, i, j)].push(index as u32);
                        }
                    }
                }
            }
        }
        let mut items = Vec::new();
        let cells = lists
            .iter()
            .map(|list| {
                let first = items.len() as u32;
                if list.len() > MAX_LIST {
                    return (first, CROWDED);
                }
                items.extend_from_slice(list);
                (first, list.len() as u32)
            })
            .collect();
        Self { centre, cells, items }
    }

    pub fn centre(&self) -> DVec3 {
        self.centre
    }

    /// The triangles in the direction w from the centre.
    #[inline]
    fn cell(&self, w: DVec3) -> Answer<&[u32]> {
        let Some((face, u, v)) = face_coordinates(w) else {
            return Answer::AskBvh;
        };
        let (first, count) = self.cells[cell_index(face, to_cell(u), to_cell(v))];
        if count == CROWDED {
            return Answer::AskBvh;
        }
        Answer::Known(&self.items[first as usize..(first + count) as usize])
    }

    /// The closest hit of the ray from the centre along `direction`, t > 0,
    /// among `triangles` (the list the grid was built from): among equal
    /// distances the lowest triangle index, as the BVH chooses.
    pub fn closest_from_centre(&self, triangles: &[BvhTriangle], direction: DVec3) -> Answer<Option<Hit>> {
        let items = match self.cell(direction) {
            Answer::Known(items) => items,
            Answer::AskBvh => return Answer::AskBvh,
        };
        let ray = ShearedRay::new(self.centre, direction);
        let mut best: Option<Hit> = None;
        for &item in items {
            let triangle = item as usize;
            let limit = best.map_or(f64::INFINITY, |b| b.at.t.next_up());
            if let Some(at) = ray.intersect(&triangles[triangle].corners, 0.0, limit)
                && best.is_none_or(|b| closer(at, triangle, b))
            {
                best = Some(Hit { triangle, at });
            }
        }
        Answer::Known(best)
    }

    /// Whether a listed triangle meets the segment origin + t (centre −
    /// origin), t ∈ (0, t_max): a shadow ray towards the centre.
    pub fn blocked_towards_centre(
        &self,
        triangles: &[BvhTriangle],
        origin: DVec3,
        t_max: f64,
    ) -> Answer<bool> {
        let items = match self.cell(origin - self.centre) {
            Answer::Known(items) => items,
            Answer::AskBvh => return Answer::AskBvh,
        };
        let ray = ShearedRay::new(origin, self.centre - origin);
        Answer::Known(
            items
                .iter()
                .any(|&t| ray.hits(&triangles[t as usize].corners, 0.0, t_max)),
        )
    }
}

fn cell_index(face: usize, i: usize, j: usize) -> usize {
    (face * CELLS + j) * CELLS + i
}

/// The cell of a face coordinate in [−1, 1] (clamped; the cast truncates,
/// which is the floor for the non-negative values it gets).
fn to_cell(u: f64) -> usize {
    // Clamped first (max and min drop a NaN): the cast then has nothing to saturate.
    ((u + 1.0) * (0.5 * CELLS as f64))
        .max(0.0)
        .min((CELLS - 1) as f64) as i32 as usize
}

/// The axes of face f: the major axis k, its sign and the two others.
fn face_axes(face: usize) -> (usize, f64, usize, usize) {
    let k = face / 2;
    let sign = if face.is_multiple_of(2) { 1.0 } else { -1.0 };
    (k, sign, (k + 1) % 3, (k + 2) % 3)
}

/// The face a direction falls on and its coordinates (u, v) there; None
/// for the zero vector.
#[inline]
fn face_coordinates(w: DVec3) -> Option<(usize, f64, f64)> {
    let a = w.abs();
    // The major axis k and the two others, (k + 1) % 3 and (k + 2) % 3 as
    // `face_axes` orders them, spelled out.
    let (k, major, wa, wb) = if a.x >= a.y && a.x >= a.z {
        (0, w.x, w.y, w.z)
    } else if a.y >= a.z {
        (1, w.y, w.z, w.x)
    } else {
        (2, w.z, w.x, w.y)
    };
    let valid = major.abs() > 0.0 && major.is_finite();
    if !valid {
        return None;
    }
    let face = 2 * k + usize::from(major < 0.0);
    let per_major = 1.0 / major.abs();
    Some((face, wa * per_major, wb * per_major))
}

/// The cells [i0, i1] × [j0, j1] of face f that the triangle (corners
/// relative to the centre) may be seen in; None when it is not on the face.
fn cell_range(relative: &[DVec3; 3], face: usize) -> Option<[usize; 4]> {
    let (k, sign, ia, ib) = face_axes(face);
    let size = relative.iter().fold(0.0_f64, |m, p| m.max(p.abs().max_element()));
    let mut polygon: Vec<DVec3> = relative.to_vec();
    // Keep (1 + WIDEN) s w_k ± w_a ≥ 0 and the same for b: the widened pyramid.
    for (axis, side) in [(ia, 1.0), (ia, -1.0), (ib, 1.0), (ib, -1.0)] {
        let f = |w: DVec3| (1.0 + WIDEN) * sign * w[k] + side * w[axis];
        polygon = clip(&polygon, f);
        if polygon.is_empty() {
            return None;
        }
    }
    let whole = [0, CELLS - 1, 0, CELLS - 1];
    let (mut u0, mut u1, mut v0, mut v1) =
        (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for w in &polygon {
        let depth = sign * w[k];
        if depth <= APEX * size {
            return Some(whole);
        }
        let (u, v) = (w[ia] / depth, w[ib] / depth);
        (u0, u1, v0, v1) = (u0.min(u), u1.max(u), v0.min(v), v1.max(v));
    }
    Some([
        to_cell(u0 - MARGIN),
        to_cell(u1 + MARGIN),
        to_cell(v0 - MARGIN),
        to_cell(v1 + MARGIN),
    ])
}

/// Sutherland–Hodgman: the part of a convex polygon where f ≥ 0 (f linear).
fn clip(polygon: &[DVec3], f: impl Fn(DVec3) -> f64) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(polygon.len() + 1);
    for (i, &p) in polygon.iter().enumerate() {
        let q = polygon[(i + 1) % polygon.len()];
        let (fp, fq) = (f(p), f(q));
        if fp >= 0.0 {
            out.push(p);
        }
        if (fp >= 0.0) != (fq >= 0.0) {
            out.push(p + (q - p) * (fp / (fp - fq)));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directions_map_to_faces_and_cells() {
        assert_eq!(face_coordinates(DVec3::new(2.0, 1.0, -1.0)), Some((0, 0.5, -0.5)));
        assert_eq!(face_coordinates(DVec3::new(0.0, -3.0, 0.0)), Some((3, 0.0, 0.0)));
        assert_eq!(face_coordinates(DVec3::ZERO), None);
        assert_eq!(to_cell(-1.0), 0);
        assert_eq!(to_cell(1.0), CELLS - 1);
        assert_eq!(to_cell(1.5), CELLS - 1);
    }

    #[test]
    fn a_triangle_around_an_axis_covers_the_middle_cells_only() {
        let tri = [
            DVec3::new(1.0, -0.1, -0.1),
            DVec3::new(1.0, 0.1, -0.1),
            DVec3::new(1.0, 0.0, 0.1),
        ];
        let [i0, i1, j0, j1] = cell_range(&tri, 0).unwrap();
        assert!(i0 <= CELLS / 2 && i1 >= CELLS / 2 - 1 && i1 - i0 < CELLS / 4);
        assert!(j0 <= CELLS / 2 && j1 >= CELLS / 2 - 1 && j1 - j0 < CELLS / 4);
        assert_eq!(cell_range(&tri, 1), None, "nothing on the −X face");
        assert_eq!(cell_range(&tri, 2), None, "nothing on the +Y face");
    }

    #[test]
    fn a_triangle_through_the_centre_covers_its_faces() {
        let tri = [
            DVec3::new(-1.0, 0.0, -1.0),
            DVec3::new(1.0, 0.0, -1.0),
            DVec3::new(0.0, 0.0, 1.0),
        ];
        assert_eq!(cell_range(&tri, 0), Some([0, CELLS - 1, 0, CELLS - 1]));
    }
}
