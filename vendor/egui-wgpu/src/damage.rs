//! lumlab patch (see `LUMLAB-PATCH.md`): which pixels of a kept backdrop
//! (`backdrop.rs`) a change of its paint jobs can touch, so that only those
//! are drawn again.
//!
//! Why: dragging a slider or the light changes a few numbers in a side
//! panel, and redrawing the whole backdrop for them cost a software
//! rasterizer as much as the rest of the frame.
//!
//! The rule: when the jobs keep their structure (as many, with the same
//! clip rectangles and textures) and the target its size, scale and clear
//! colour, each mesh is compared old against new as a sequence of
//! triangles (the three corner vertices of each, in order). Past the common
//! prefix and before the common suffix of triangles, the differing middle
//! triangles of the old and of the new mesh can touch only pixels inside
//! their corners' bounding rectangle (in pixels, rounded outwards, within
//! the job's clip rectangle): that is the mesh's damage. Every pixel outside
//! the damages is covered by the same triangles in the same order in both
//! frames, so it keeps its colour. Anything else is a full redraw.

use epaint::{ClippedPrimitive, Mesh, Primitive, Vertex};

use crate::ScreenDescriptor;

/// A rectangle of pixels: `min` inclusive, `max` exclusive.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelRect {
    pub min: [u32; 2],
    pub max: [u32; 2],
}

impl PixelRect {
    /// The pixels a rectangle in points can touch on a target of `size`
    /// pixels: rounded outwards, clamped to the target.
    fn around(rect: epaint::Rect, pixels_per_point: f32, size: [u32; 2]) -> Self {
        let clamp = |v: f32, axis: usize| (v.max(0.0) as u32).min(size[axis]);
        Self {
            min: [
                clamp((rect.min.x * pixels_per_point).floor(), 0),
                clamp((rect.min.y * pixels_per_point).floor(), 1),
            ],
            max: [
                clamp((rect.max.x * pixels_per_point).ceil(), 0),
                clamp((rect.max.y * pixels_per_point).ceil(), 1),
            ],
        }
    }

    /// A clip rectangle as the renderer's scissor takes it (rounded to the
    /// nearest pixel, clamped to the target).
    pub(crate) fn scissor(clip: epaint::Rect, pixels_per_point: f32, size: [u32; 2]) -> Self {
        let round = |v: f32, axis: usize| ((v * pixels_per_point).round() as u32).min(size[axis]);
        let min = [round(clip.min.x, 0), round(clip.min.y, 1)];
        Self {
            min,
            max: [round(clip.max.x, 0).max(min[0]), round(clip.max.y, 1).max(min[1])],
        }
    }

    /// Width and height (pixels).
    pub fn size(&self) -> [u32; 2] {
        [self.max[0] - self.min[0], self.max[1] - self.min[1]]
    }

    pub fn is_empty(&self) -> bool {
        self.min[0] >= self.max[0] || self.min[1] >= self.max[1]
    }

    pub fn intersect(&self, other: &Self) -> Self {
        Self {
            min: [self.min[0].max(other.min[0]), self.min[1].max(other.min[1])],
            max: [self.max[0].min(other.max[0]), self.max[1].min(other.max[1])],
        }
    }

    fn union(&self, other: &Self) -> Self {
        Self {
            min: [self.min[0].min(other.min[0]), self.min[1].min(other.min[1])],
            max: [self.max[0].max(other.max[0]), self.max[1].max(other.max[1])],
        }
    }
}

/// What of a kept backdrop must be drawn again.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Redraw {
    /// Nothing: the same pixels.
    Nothing,
    /// These disjoint rectangles only (cleared, then every job drawn within them).
    Damage(Vec<PixelRect>),
    /// Everything.
    Full,
}

/// What a kept backdrop was drawn from: CPU copies of its jobs and the
/// target's description, against which the next frame's are compared.
pub struct Drawn {
    jobs: Vec<ClippedPrimitive>,
    size_in_pixels: [u32; 2],
    pixels_per_point: f32,
    clear: [f32; 4],
}

impl Drawn {
    pub fn new(jobs: &[ClippedPrimitive], screen: &ScreenDescriptor, clear: [f32; 4]) -> Self {
        Self {
            jobs: jobs.to_vec(),
            size_in_pixels: screen.size_in_pixels,
            pixels_per_point: screen.pixels_per_point,
            clear,
        }
    }

    /// What must be drawn again to show `jobs` on `screen` cleared to `clear`
    /// (see the module's rule).
    pub fn redraw(&self, jobs: &[ClippedPrimitive], screen: &ScreenDescriptor, clear: [f32; 4]) -> Redraw {
        let ppp = screen.pixels_per_point;
        let size = screen.size_in_pixels;
        let same_target = self.size_in_pixels == size
            && self.pixels_per_point.to_bits() == ppp.to_bits()
            && self.clear.map(f32::to_bits) == clear.map(f32::to_bits);
        if !same_target || self.jobs.len() != jobs.len() {
            return Redraw::Full;
        }
        let mut damage: Vec<PixelRect> = Vec::new();
        for (old, new) in self.jobs.iter().zip(jobs) {
            let (Primitive::Mesh(a), Primitive::Mesh(b)) = (&old.primitive, &new.primitive) else {
                return Redraw::Full;
            };
            if old.clip_rect != new.clip_rect || a.texture_id != b.texture_id {
                return Redraw::Full;
            }
            let clip = PixelRect::scissor(new.clip_rect, ppp, size);
            if let Some(changed) = changed_triangles(a, b) {
                let rect = PixelRect::around(changed, ppp, size).intersect(&clip);
                if !rect.is_empty() {
                    add_disjoint(&mut damage, rect);
                }
            }
        }
        if damage.is_empty() {
            Redraw::Nothing
        } else {
            Redraw::Damage(damage)
        }
    }
}

/// The bounding rectangle (points) of the triangles that differ between
/// `old` and `new` once their common prefix and suffix are set aside; None
/// where they are the same triangles (the vertices or indices may differ).
fn changed_triangles(old: &Mesh, new: &Mesh) -> Option<epaint::Rect> {
    if old.indices == new.indices && old.vertices == new.vertices {
        return None;
    }
    let triangle = |mesh: &Mesh, i: usize| -> [Vertex; 3] {
        let corner = |k: usize| mesh.vertices[mesh.indices[3 * i + k] as usize];
        [corner(0), corner(1), corner(2)]
    };
    let (n_old, n_new) = (old.indices.len() / 3, new.indices.len() / 3);
    let shorter = n_old.min(n_new);
    let prefix = (0..shorter)
        .take_while(|&i| triangle(old, i) == triangle(new, i))
        .count();
    let suffix = (0..shorter - prefix)
        .take_while(|&i| triangle(old, n_old - 1 - i) == triangle(new, n_new - 1 - i))
        .count();
    let mut bounds: Option<epaint::Rect> = None;
    for (mesh, n) in [(old, n_old), (new, n_new)] {
        for v in (prefix..n - suffix).flat_map(|i| triangle(mesh, i)) {
            bounds
                .get_or_insert(epaint::Rect::from_min_max(v.pos, v.pos))
                .extend_with(v.pos);
        }
    }
    bounds
}

/// Adds `rect` to disjoint rectangles, merging it with those it overlaps
/// (into their bounding rectangle, again and again), so that no pixel is
/// drawn twice: a second blend would change it.
fn add_disjoint(rects: &mut Vec<PixelRect>, mut rect: PixelRect) {
    while let Some(i) = rects.iter().position(|r| !r.intersect(&rect).is_empty()) {
        rect = rect.union(&rects.swap_remove(i));
    }
    rects.push(rect);
}
