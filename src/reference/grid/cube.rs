//! The cube around a grid's centre: each direction's face and cell, and the
//! cells a triangle may be seen in (clipped to a face's pyramid where it
//! leaves it).

use super::{APEX, CELLS, MARGIN, WHOLE_FACE, WIDEN};
use crate::reference::intersect::extent;
use glam::DVec3;

pub(super) fn cell_index(face: usize, i: usize, j: usize) -> usize {
    (face * CELLS + j) * CELLS + i
}

/// The face and cell (i, j) of [`cell_index`]'s index.
pub(super) fn cell_parts(cell: usize) -> (usize, usize, usize) {
    (cell / (CELLS * CELLS), cell % CELLS, cell / CELLS % CELLS)
}

/// The cell of a face coordinate in [−1, 1] (clamped; the cast truncates,
/// which is the floor for the non-negative values it gets).
pub(super) fn to_cell(u: f64) -> usize {
    // Clamped first (max and min drop a NaN): the cast then has nothing to saturate.
    ((u + 1.0) * (0.5 * CELLS as f64))
        .max(0.0)
        .min((CELLS - 1) as f64) as i32 as usize
}

/// The axes of face f: the major axis k, its sign and the two others.
pub(super) fn face_axes(face: usize) -> (usize, f64, usize, usize) {
    let k = face / 2;
    let sign = if face.is_multiple_of(2) { 1.0 } else { -1.0 };
    (k, sign, (k + 1) % 3, (k + 2) % 3)
}

/// The face a direction falls on and its coordinates (u, v) there; None
/// for the zero vector.
#[inline]
pub(super) fn face_coordinates(w: DVec3) -> Option<(usize, f64, f64)> {
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
pub(super) fn cell_range(relative: &[DVec3; 3], face: usize) -> Option<[usize; 4]> {
    let (k, sign, ia, ib) = face_axes(face);
    let size = extent(relative);
    // The face's pyramid, widened: |u|, |v| ≤ 1 + WIDEN.
    let widened = (-1.0 - WIDEN, 1.0 + WIDEN);
    // Wholly inside that pyramid (most triangles), the triangle is its own
    // clipped polygon: its corners project to the same rectangle.
    let rectangle = |points: &[DVec3]| {
        let (mut u0, mut u1, mut v0, mut v1) =
            (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
        for w in points {
            let depth = sign * w[k];
            if depth <= APEX * size {
                return None;
            }
            let (u, v) = (w[ia] / depth, w[ib] / depth);
            (u0, u1, v0, v1) = (u0.min(u), u1.max(u), v0.min(v), v1.max(v));
        }
        Some([u0, u1, v0, v1])
    };
    let inside = |&[u0, u1, v0, v1]: &[f64; 4]| {
        u0 >= widened.0 && u1 <= widened.1 && v0 >= widened.0 && v1 <= widened.1
    };
    let projected = match rectangle(relative).filter(inside) {
        Some(corners) => Some(corners),
        None => rectangle(clip_to_pyramid(relative, face, widened, widened)?.points()),
    };
    // A vertex at the centre's face plane: the whole face.
    let Some([u0, u1, v0, v1]) = projected else {
        return Some(WHOLE_FACE);
    };
    Some([
        to_cell(u0 - MARGIN),
        to_cell(u1 + MARGIN),
        to_cell(v0 - MARGIN),
        to_cell(v1 + MARGIN),
    ])
}

/// The part of the triangle (corners relative to the centre) inside the
/// pyramid of face f where u ∈ [u0, u1] and v ∈ [v0, v1]; None when empty.
pub(super) fn clip_to_pyramid(
    relative: &[DVec3; 3],
    face: usize,
    (u0, u1): (f64, f64),
    (v0, v1): (f64, f64),
) -> Option<Polygon> {
    let (k, sign, ia, ib) = face_axes(face);
    // u ≥ u0 ⇔ w_a − u0 · depth ≥ 0, and so on, with depth = sign · w_k.
    let sides = [(ia, 1.0, u0), (ia, -1.0, u1), (ib, 1.0, v0), (ib, -1.0, v1)]
        .map(|(axis, side, bound)| move |w: DVec3| side * (w[axis] - bound * sign * w[k]));
    // Corners all outside one side (most faces of most triangles): nothing
    // is left, as clipping would find at greater cost.
    if sides.iter().any(|f| relative.iter().all(|&w| f(w) < 0.0)) {
        return None;
    }
    let mut polygon = Polygon::triangle(relative);
    for f in sides {
        polygon = polygon.clip(f);
        if polygon.is_empty() {
            return None;
        }
    }
    Some(polygon)
}

/// A convex polygon: a triangle clipped by at most five planes.
#[derive(Clone, Copy)]
pub(super) struct Polygon {
    points: [DVec3; 8],
    len: usize,
}

impl Polygon {
    fn triangle(corners: &[DVec3; 3]) -> Self {
        let mut points = [DVec3::ZERO; 8];
        points[..3].copy_from_slice(corners);
        Self { points, len: 3 }
    }

    pub(super) fn points(&self) -> &[DVec3] {
        &self.points[..self.len]
    }

    fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Sutherland–Hodgman: the part where f ≥ 0 (f linear). Each plane
    /// adds at most one vertex.
    fn clip(&self, f: impl Fn(DVec3) -> f64) -> Self {
        let mut out = Self {
            points: [DVec3::ZERO; 8],
            len: 0,
        };
        let mut push = |p: DVec3| {
            out.points[out.len] = p;
            out.len += 1;
        };
        let points = self.points();
        for (i, &p) in points.iter().enumerate() {
            let q = points[(i + 1) % points.len()];
            let (fp, fq) = (f(p), f(q));
            if fp >= 0.0 {
                push(p);
            }
            if (fp >= 0.0) != (fq >= 0.0) {
                push(p + (q - p) * (fp / (fp - fq)));
            }
        }
        out
    }
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
