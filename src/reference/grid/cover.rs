//! Pixels whose every ray meets one triangle first, and shadow rays that
//! nothing can block, known once for a whole pixel instead of ray by ray.
//!
//! A pixel's rays fill the convex cone of its four corner rays. For a
//! triangle with corners A, B, C (relative to the eye), ray d meets its
//! interior where the three triple products u₀ = d · (B × C), u₁ = d · (C × A),
//! u₂ = d · (A × B) share the sign of their sum, at t = A · (B × C) / Σuᵢ with
//! barycentrics uᵢ / Σuᵢ. Each uᵢ is linear in d, so where all three keep
//! that sign at the four corners, by a margin far above the rounding of
//! either test ([`MARGIN`]), every ray of the pixel meets the triangle, as
//! the watertight test in `intersect` decides it too; where one is surely
//! positive and another surely negative, no ray of the pixel meets it. The
//! triangle's depth along the face's axis is linear over the part of its
//! plane the pixel sees, so its largest value is at a corner; a listing
//! whose depth bound lies beyond that cannot come first for any ray of the
//! pixel. The triangle tried is the one the pixel's middle ray meets first;
//! every listing of the cells around the pixel not beyond it must be
//! surely missed (its neighbours on a tessellated surface are).
//!
//! The hit of each sample is then worked out from the triple products: the
//! same triangle, the same point to ~10⁻¹⁶ relative, not the same bits.

use super::{Answer, Cell, DirectionGrid, Item, cell_index, face_coordinates, to_cell};
use crate::reference::bvh::Hit;
use crate::reference::intersect::{TriangleHit, extent};
use glam::DVec3;

/// Triple products below this fraction of |d|∞ |X|∞ |Y|∞ (for the edge of
/// corners X, Y) are not trusted: both tests round them by ~10⁻¹⁴ of it.
const MARGIN: f64 = 1e-10;
/// Cells at most around a pixel's rays.
const LISTS: usize = 16;
/// Relative allowance on depths compared across the two tests' rounding.
const DEPTH_SLACK: f64 = 1e-9;
/// Distances from a plane below this fraction of the coordinates are not
/// trusted (rounding ~10⁻¹⁶; a shadow ray's origin is lifted 10⁻⁹).
const SIDE_MARGIN: f64 = 1e-12;

/// The triple products of a triangle with corners A, B, C (relative to
/// the apex of the rays): u = d · (B × C), d · (C × A), d · (A × B) for a
/// direction d, and A · (B × C).
#[derive(Clone, Copy, Debug)]
struct TripleProducts {
    edges: [DVec3; 3],
    volume: f64,
}

impl TripleProducts {
    fn of(&[a, b, c]: &[DVec3; 3]) -> Self {
        let edges = [b.cross(c), c.cross(a), a.cross(b)];
        Self {
            edges,
            volume: a.dot(edges[0]),
        }
    }

    /// The three products of direction `d`.
    #[inline(always)]
    fn at(&self, d: DVec3) -> [f64; 3] {
        self.edges.map(|n| d.dot(n))
    }
}

/// The triangle that every ray of a pixel meets first (see the module).
#[derive(Clone, Copy, Debug)]
pub struct Cover {
    triangle: usize,
    products: TripleProducts,
}

impl Cover {
    /// The index of the triangle (in the list the grid was built from).
    pub fn triangle(&self) -> usize {
        self.triangle
    }

    /// Where the ray from the eye along `d` (one of the pixel's) meets it.
    #[inline(always)]
    pub fn hit(&self, d: DVec3) -> Hit {
        let u = self.products.at(d);
        let inv = 1.0 / (u[0] + u[1] + u[2]);
        Hit {
            triangle: self.triangle,
            at: TriangleHit {
                t: self.products.volume * inv,
                barycentric: u.map(|x| x * inv),
            },
        }
    }
}

/// How the rays of a cone (its four corner directions) meet a triangle.
enum Seen {
    /// Every ray meets it, none deeper along its main axis than `deepest`.
    Inside { deepest: f64, products: TripleProducts },
    /// No ray does: one edge function is surely positive over the cone and
    /// another surely negative.
    Missed,
    /// Not sure.
    Unsure,
}

impl Seen {
    /// The cone of `corners` against the triangle of corners A, B, C
    /// (relative to the cone's apex), from the sign each triple product
    /// surely keeps at all four corners (it is linear in the direction).
    /// `slack`: an allowance on the corners' coordinates for a test done in
    /// coordinates relative to another point (its size), 0 for one done
    /// relative to the apex itself.
    fn of(triangle: &[DVec3; 3], corners: &[DVec3; 4], slack: f64) -> Self {
        let [a, b, c] = *triangle;
        let products = TripleProducts::of(triangle);
        let size = |x: DVec3| x.abs().max_element() + slack;
        let scales = [(b, c), (c, a), (a, b)].map(|(x, y)| size(x) * size(y));
        let (mut positive, mut negative) = ([true; 3], [true; 3]);
        let mut sums = [0.0; 4];
        for (d, sum) in corners.iter().zip(&mut sums) {
            let margin = MARGIN * d.abs().max_element();
            let u = products.at(*d);
            for i in 0..3 {
                positive[i] &= u[i] > margin * scales[i];
                negative[i] &= u[i] < -margin * scales[i];
            }
            *sum = u[0] + u[1] + u[2];
        }
        if positive.iter().any(|&p| p) && negative.iter().any(|&n| n) {
            return Seen::Missed;
        }
        if !(positive.iter().all(|&p| p) || negative.iter().all(|&n| n)) {
            return Seen::Unsure;
        }
        let mut deepest = 0.0_f64;
        for (d, sum) in corners.iter().zip(sums) {
            let t = products.volume / sum;
            if !(t > 0.0 && t.is_finite()) {
                return Seen::Unsure;
            }
            deepest = deepest.max(t * d.abs().max_element());
        }
        Seen::Inside { deepest, products }
    }
}

impl DirectionGrid {
    /// The triangle that every ray from the centre within the cone of the
    /// directions `corners` meets first, if one surely is: a listing of the
    /// cells around them that holds the whole cone, and every other one
    /// either surely missed by the whole cone or surely deeper.
    pub fn cover(&self, corners: &[DVec3; 4]) -> Option<Cover> {
        let (lists, count) = self.lists_around(corners)?;
        let lists = &lists[..count];
        // The one to try: the listing the cone's middle ray meets first.
        let middle: DVec3 = corners.iter().sum();
        let hit = match self.closest_from_centre(middle) {
            Answer::Known(hit) => hit?,
            Answer::AskBvh => return None,
        };
        let first = lists
            .iter()
            .flat_map(|list| list.iter())
            .find(|item| self.members[item.member as usize] as usize == hit.triangle)?
            .member;
        let Seen::Inside { deepest, products } = Seen::of(&self.relative[first as usize], corners, 0.0)
        else {
            return None;
        };
        // Each list is sorted by depth: past `deepest`, nothing can come first.
        let reach = deepest * (1.0 + DEPTH_SLACK);
        let alone = lists.iter().all(|list| {
            list.iter()
                .take_while(|item| item.depth as f64 <= reach)
                .all(|item| {
                    item.member == first
                        || matches!(
                            Seen::of(&self.relative[item.member as usize], corners, 0.0),
                            Seen::Missed
                        )
                })
        });
        alone.then_some(Cover {
            triangle: hit.triangle,
            products,
        })
    }

    /// The lists of the cells that hold every direction in the cone of `w`
    /// (directions from the centre), and how many there are: the
    /// rectangle of cells around their corners on the one face they share
    /// (the face's pyramid is convex, and a cone's section by the face's
    /// plane is the convex hull of its corners' points). None when they
    /// fall on different faces, on more than [`LISTS`] cells, or on a
    /// crowded one.
    fn lists_around(&self, w: &[DVec3; 4]) -> Option<([&[Item]; LISTS], usize)> {
        let mut shared = None;
        let (mut i0, mut i1, mut j0, mut j1) = (usize::MAX, 0, usize::MAX, 0);
        for &w in w {
            let (face, u, v) = face_coordinates(w)?;
            if *shared.get_or_insert(face) != face {
                return None;
            }
            let (i, j) = (to_cell(u), to_cell(v));
            (i0, i1, j0, j1) = (i0.min(i), i1.max(i), j0.min(j), j1.max(j));
        }
        let face = shared?;
        if (i1 - i0 + 1) * (j1 - j0 + 1) > LISTS {
            return None;
        }
        let mut lists: [&[Item]; LISTS] = [&[]; LISTS];
        let mut count = 0;
        for j in j0..=j1 {
            for i in i0..=i1 {
                lists[count] = self.items(Cell(cell_index(face, i, j)))?;
                count += 1;
            }
        }
        Some((lists, count))
    }

    /// Whether no shadow ray from a point of the convex hull of `origins`
    /// towards the centre can be blocked by any triangle but `own`, as
    /// [`Self::blocked_towards_centre`] decides each (`own` skipped or not).
    /// Of the triangles the lists of the cells around them put nearer the
    /// centre than the farthest origin, every one but `own` must have the
    /// centre and all the origins strictly on one side of its plane, so
    /// that no segment between them reaches it, or be surely missed by the
    /// whole cone of those segments from the centre.
    pub fn clear_towards_centre(&self, origins: &[DVec3; 4], own: usize) -> bool {
        let w = origins.map(|o| o - self.centre);
        let Some((lists, count)) = self.lists_around(&w) else {
            return false;
        };
        let reach = w.iter().fold(0.0_f64, |r, w| r.max(w.abs().max_element()));
        lists[..count]
            .iter()
            .flat_map(|list| {
                list.iter()
                    .take_while(|item| (item.depth as f64) < reach * (1.0 + DEPTH_SLACK))
            })
            .filter(|item| self.members[item.member as usize] as usize != own)
            .all(|item| {
                let corners = &self.relative[item.member as usize];
                // Either no segment reaches its plane, or none meets it
                // within (coordinates relative to the centre: the slack).
                self.beside(corners, &w, reach)
                    || matches!(
                        Seen::of(corners, &w, self.centre.abs().max_element()),
                        Seen::Missed
                    )
            })
    }

    /// Whether the centre and the points `w` (relative to it, none farther
    /// than `reach` along an axis) all lie strictly on one side of the
    /// plane of the triangle (corners relative to the centre), by far more
    /// than the rounding of either this test or the watertight one, done
    /// in coordinates relative to the ray's origin (~10⁻¹⁶ of the
    /// coordinates, the centre's own included).
    fn beside(&self, corners: &[DVec3; 3], w: &[DVec3; 4], reach: f64) -> bool {
        let [a, b, c] = *corners;
        let n = (b - a).cross(c - a);
        let size = extent(corners).max(reach);
        let margin = SIDE_MARGIN * n.abs().element_sum() * (size + self.centre.abs().max_element());
        let centre = -n.dot(a);
        let side = centre.signum();
        centre.abs() > margin && w.iter().all(|&w| n.dot(w - a) * side > margin)
    }
}
