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
//! to each face's pyramid widened by `WIDEN`, projected, and its bounding
//! rectangle widened by `MARGIN` before it is rasterized into cells; a
//! triangle reaching the centre itself covers the whole face. Cells listing
//! more than [`MAX_LIST`] triangles answer "ask the BVH" instead.
//!
//! Each cell's list is sorted by a lower bound of each triangle's depth
//! inside the cell (along the face's axis), so searches end early and still
//! exactly: a closest hit once the next bound lies beyond it, a shadow ray
//! once the next bound reaches its origin's depth (nothing farther from the
//! light can block it). The triangles' corners relative to the centre are
//! stored once, which is the first step of every test of a ray from it; and
//! all rays through one pixel share their cell when its four corners do.
//!
//! Lists are kept only where some triangle is seen, and the eye's grid
//! builds only the cells towards the image ([`DirectionGrid::towards`]):
//! the others defer to the BVH (see `faces`).

mod cover;
mod cube;
mod depth;
mod faces;

pub use cover::Cover;

use super::bvh::{BvhTriangle, Hit, closer};
use super::intersect::{ShearedRay, extent, with_axes};
use crate::scene::camera::PixelRays;
use cube::{cell_index, cell_parts, cell_range, clip_to_pyramid, face_axes, face_coordinates, to_cell};
use faces::{Faces, Rect, Slot};
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
    /// Which cells of each face have lists (see [`faces`]).
    faces: Faces,
    /// Per listed cell, (first, count) of its members in `items`; count
    /// `CROWDED` when the cell defers to the BVH.
    cells: Vec<(u32, u32)>,
    /// The members of the cells, each cell's sorted by `Item::depth`.
    items: Vec<Item>,
    /// The triangles listed in some cell: their indices in the list the
    /// grid was built from, and their corners relative to the centre (the
    /// first step of every ray test from the centre, done once).
    members: Vec<u32>,
    relative: Vec<[DVec3; 3]>,
    /// Whether some listed cell defers to the BVH.
    crowded: bool,
}

/// The cell range of a triangle seen on a whole face.
const WHOLE_FACE: Rect = [0, CELLS - 1, 0, CELLS - 1];

/// The count of a cell listing more than [`MAX_LIST`] triangles.
const CROWDED: u32 = u32::MAX;

/// A triangle listed in a cell.
#[derive(Clone, Copy, Debug)]
struct Item {
    /// Index into `DirectionGrid::members`.
    member: u32,
    /// A lower bound of the depth (along the face's axis) of the part of
    /// the triangle inside the cell's pyramid: a ray from the centre with
    /// direction d meets it at t ≥ depth / |d_k|.
    depth: f32,
}

/// A cell of a grid, as [`DirectionGrid::cell_of`] finds it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cell(usize);

impl DirectionGrid {
    /// The grid around `centre` of the triangles `keep` accepts.
    pub fn new(centre: DVec3, triangles: &[BvhTriangle], keep: impl Fn(&BvhTriangle) -> bool) -> Self {
        Self::build(centre, triangles, keep, None)
    }

    /// [`Self::new`] for the rays towards `region` (triangles), such as the
    /// image's rectangle ahead of the eye: the cells of other directions
    /// defer to the BVH, and are not built. (Cells a cell wider than the
    /// region's are built, far more than the rounding of any ray towards it.)
    pub fn towards(
        centre: DVec3,
        triangles: &[BvhTriangle],
        keep: impl Fn(&BvhTriangle) -> bool,
        region: &[[DVec3; 3]],
    ) -> Self {
        let mut rects = [None; 6];
        for corners in region {
            let relative = corners.map(|p| p - centre);
            for (face, rect) in rects.iter_mut().enumerate() {
                if let Some([i0, i1, j0, j1]) = cell_range(&relative, face) {
                    let wider = [
                        i0.saturating_sub(1),
                        (i1 + 1).min(CELLS - 1),
                        j0.saturating_sub(1),
                        (j1 + 1).min(CELLS - 1),
                    ];
                    *rect = Some(faces::union(*rect, wider));
                }
            }
        }
        Self::build(centre, triangles, keep, Some(&rects))
    }

    /// The grid, its cells built inside `region`'s rectangles where given.
    fn build(
        centre: DVec3,
        triangles: &[BvhTriangle],
        keep: impl Fn(&BvhTriangle) -> bool,
        region: Option<&[Option<Rect>; 6]>,
    ) -> Self {
        // Each triangle's rectangle of cells on each face, then the built
        // cells' lists in one array (a counting sort: lists keep the
        // triangle order).
        let mut spans = Vec::new();
        for (index, tri) in triangles.iter().enumerate() {
            if !keep(tri) || !tri.corners.iter().all(|p| p.is_finite()) {
                continue;
            }
            let relative = tri.corners_f64().map(|p| p - centre);
            for face in 0..6 {
                if let Some(range) = cell_range(&relative, face) {
                    spans.push((index as u32, face, range));
                }
            }
        }
        let faces = Faces::new(spans.iter().map(|&(_, face, rect)| (face, rect)), region);
        let cells_of = |&(_, face, rect): &(u32, usize, Rect)| faces.lists_in(face, rect);
        let mut starts = vec![0usize; faces.len() + 1];
        for span in &spans {
            for cell in cells_of(span) {
                starts[cell + 1] += 1;
            }
        }
        for cell in 1..starts.len() {
            starts[cell] += starts[cell - 1];
        }
        // With each listing, whether the triangle covers the whole face (it
        // may reach the centre itself, where rounding decides hits at t ≈ 0
        // that no clipping predicts: its depth bound is 0).
        let mut listed = vec![(0u32, false); starts[starts.len() - 1]];
        let mut fill = starts.clone();
        for span in &spans {
            for cell in cells_of(span) {
                listed[fill[cell]] = (span.0, span.2 == WHOLE_FACE);
                fill[cell] += 1;
            }
        }
        let lists = starts.windows(2).map(|w| &listed[w[0]..w[1]]);
        // Members are numbered as they are first listed by an uncrowded cell.
        let mut member_of = vec![u32::MAX; triangles.len()];
        let (mut members, mut relative, mut items) = (Vec::new(), Vec::new(), Vec::new());
        let mut seen = Vec::new();
        let cells: Vec<(u32, u32)> = lists
            .zip(faces.cells())
            .map(|(list, (face, i, j))| {
                let first = items.len();
                if list.len() > MAX_LIST {
                    return (first as u32, CROWDED);
                }
                // A lone triangle needs no order and ends no search early.
                let pyramid = (list.len() > 1).then(|| depth::Pyramid::new(cell_index(face, i, j)));
                for &(triangle, whole) in list {
                    let member = &mut member_of[triangle as usize];
                    if *member == u32::MAX {
                        *member = members.len() as u32;
                        members.push(triangle);
                        let corners = triangles[triangle as usize].corners_f64().map(|p| p - centre);
                        relative.push(corners);
                        seen.push(depth::Seen::new(corners));
                    }
                    let depth = match &pyramid {
                        Some(pyramid) if !whole => round_down(pyramid.depth_of(&seen[*member as usize])),
                        _ => 0.0,
                    };
                    items.push(Item {
                        member: *member,
                        depth,
                    });
                }
                items[first..].sort_by(|a, b| a.depth.total_cmp(&b.depth));
                (first as u32, list.len() as u32)
            })
            .collect();
        Self {
            centre,
            crowded: cells.iter().any(|&(_, count)| count == CROWDED),
            faces,
            cells,
            items,
            members,
            relative,
        }
    }

    pub fn centre(&self) -> DVec3 {
        self.centre
    }

    /// The cell that direction w from the centre falls in; None for the
    /// zero vector (or a non-finite one). Any w whose cone of directions
    /// lies in this cell (to 10⁻¹² or so) may be cast through it: the
    /// cells' lists are widened by far more than the rounding of w.
    #[inline]
    pub fn cell_of(&self, w: DVec3) -> Option<Cell> {
        let (face, u, v) = face_coordinates(w)?;
        Some(Cell(cell_index(face, to_cell(u), to_cell(v))))
    }

    /// The cell that holds every ray of `rays` through pixel (i, j) (the
    /// grid around their eye), if one does: the pixel's rays fill the convex
    /// cone of its four corner rays, and a cell is a convex cone too, so when
    /// the corners share a cell every sample of the pixel lies in it.
    pub fn pixel_cell(&self, rays: &PixelRays, i: f64, j: f64) -> Option<Cell> {
        let cell = self.cell_of(rays.towards(i, j))?;
        let corners = [(i + 1.0, j), (i, j + 1.0), (i + 1.0, j + 1.0)];
        corners
            .iter()
            .all(|&(x, y)| self.cell_of(rays.towards(x, y)) == Some(cell))
            .then_some(cell)
    }

    /// Where the cell's list is.
    #[inline]
    fn slot(&self, Cell(cell): Cell) -> Slot {
        let (face, i, j) = cell_parts(cell);
        self.faces.slot(face, i, j)
    }

    /// Whether the cell lists no triangle: every ray in it misses them all.
    pub fn is_empty(&self, cell: Cell) -> bool {
        match self.slot(cell) {
            Slot::Listed(k) => self.cells[k].1 == 0,
            Slot::Empty => true,
            Slot::Unbuilt => false,
        }
    }

    /// Whether the cell defers to the BVH: it lists too many triangles, or
    /// lies outside the region the grid was built for.
    pub fn is_crowded(&self, cell: Cell) -> bool {
        match self.slot(cell) {
            Slot::Listed(k) => self.cells[k].1 == CROWDED,
            Slot::Empty => false,
            Slot::Unbuilt => true,
        }
    }

    /// Whether some cell of its region defers to the BVH (else every ray
    /// towards the region but one from the centre itself is answered here;
    /// a grid made by [`Self::new`] serves every direction).
    pub fn is_crowded_anywhere(&self) -> bool {
        self.crowded
    }

    /// The items of a cell, or None when it defers to the BVH.
    #[inline]
    fn items(&self, cell: Cell) -> Option<&[Item]> {
        match self.slot(cell) {
            Slot::Listed(k) => {
                let (first, count) = self.cells[k];
                (count != CROWDED).then(|| &self.items[first as usize..(first + count) as usize])
            }
            Slot::Empty => Some(&[]),
            Slot::Unbuilt => None,
        }
    }

    /// The closest hit of the ray from the centre along `direction`, t > 0,
    /// among the triangles of the list the grid was built from: among equal
    /// distances the lowest triangle index, as the BVH chooses.
    pub fn closest_from_centre(&self, direction: DVec3) -> Answer<Option<Hit>> {
        match self.cell_of(direction) {
            Some(cell) => self.closest_in(cell, direction),
            None => Answer::AskBvh,
        }
    }

    /// [`Self::closest_from_centre`] for a direction known to lie in `cell`.
    #[inline]
    pub fn closest_in(&self, cell: Cell, direction: DVec3) -> Answer<Option<Hit>> {
        let Some(items) = self.items(cell) else {
            return Answer::AskBvh;
        };
        let ray = ShearedRay::new(self.centre, direction);
        Answer::Known(with_axes!(ray.shear.axes(), KZ, SWAP => self.closest_among::<KZ, SWAP>(&ray, items)))
    }

    /// The closest hit among the items, nearest first: the search ends at
    /// the first item whose depth bound puts it beyond the best hit so far
    /// (t ≥ depth / |d_k| = depth · |sz|, the bound already rounded down).
    #[inline(always)]
    fn closest_among<const KZ: usize, const SWAP: bool>(
        &self,
        ray: &ShearedRay,
        items: &[Item],
    ) -> Option<Hit> {
        let per_depth = ray.shear.per_depth();
        let mut best: Option<Hit> = None;
        for item in items {
            if best.is_some_and(|b| item.depth as f64 * per_depth > b.at.t) {
                break;
            }
            let member = item.member as usize;
            let limit = best.map_or(f64::INFINITY, |b| b.at.t.next_up());
            let Some(at) = ray
                .shear
                .intersect_in::<KZ, SWAP>(&self.relative[member], 0.0, limit)
            else {
                continue;
            };
            let triangle = self.members[member] as usize;
            if best.is_none_or(|b| closer(at, triangle, b)) {
                best = Some(Hit { triangle, at });
            }
        }
        best
    }

    /// Whether a listed triangle meets the segment origin + t (centre −
    /// origin), t ∈ (0, t_max): a shadow ray towards the centre.
    /// `triangles` is the list the grid was built from; `skip`, a triangle
    /// of it the caller knows cannot meet the segment (the one the origin
    /// was lifted off, towards the centre), or None.
    ///
    /// Only triangles nearer the centre than the origin can block: points of
    /// the segment have depth (1 − t) · depth(origin), so the search ends at
    /// the first item whose depth bound reaches the origin's depth.
    #[inline]
    pub fn blocked_towards_centre(
        &self,
        triangles: &[BvhTriangle],
        origin: DVec3,
        t_max: f64,
        skip: Option<usize>,
    ) -> Answer<bool> {
        let w = origin - self.centre;
        let Some(items) = self.cell_of(w).and_then(|cell| self.items(cell)) else {
            return Answer::AskBvh;
        };
        let reach = w.abs().max_element();
        let mut candidates = items
            .iter()
            .take_while(|item| (item.depth as f64) < reach)
            .map(|item| self.members[item.member as usize] as usize)
            .filter(|&triangle| skip != Some(triangle))
            .peekable();
        // Most shadow rays have nothing left to test: no ray to prepare.
        if candidates.peek().is_none() {
            return Answer::Known(false);
        }
        let ray = ShearedRay::new(origin, -w);
        let blocked = with_axes!(ray.shear.axes(), KZ, SWAP => candidates.any(|triangle| {
            ray.shear.hits_in::<KZ, SWAP>(&ray.relative(&triangles[triangle].corners_f64()), 0.0, t_max)
        }));
        Answer::Known(blocked)
    }
}

/// The f32 at or below x (for bounds that must not grow).
fn round_down(x: f64) -> f32 {
    let y = x as f32;
    if y as f64 > x { y.next_down() } else { y }
}
