//! Ray casting against every triangle of the scene: a compressed wide BVH from
//! `obvhs`, traversed in f32, with each candidate triangle tested in f64.
//!
//! f32 traversal must never skip a node whose triangle the f64 ray hits. Three
//! measures make it conservative:
//! - the BVH lives in a normalized frame, (p − centre) / scale with scale the
//!   scene's largest extent, so every f32 coordinate is of order 1;
//! - each triangle's box is padded by [`PAD`] (10⁻⁵ of the scene's extent),
//!   about 100 times the worst rounding of an f32 ray (origin, direction,
//!   slab distances: a few units of 6·10⁻⁸ in this frame);
//! - a ray first clipped in f64 to the padded scene box starts its f32 copy
//!   just before the box (and before obvhs's own clamp of node entries at
//!   10⁻⁴), so a camera kilometres away loses no precision, and the f32 far
//!   limit is the f64 one plus a few pads.
//!
//! The f64 test decides every hit, so the BVH answers exactly what testing
//! every triangle would (see `closest_hit_brute_force` and the tests).
//! Single rays test a node's eight children in one AVX2 register where the
//! CPU has it (`node_avx`: obvhs's test, the same bits).

mod ball;
mod build;
mod collapse;
mod cone;
mod lanes;
#[cfg(target_arch = "x86_64")]
mod node_avx;
mod packet;

use super::intersect::{ShearedRay, TriangleHit};
#[cfg(target_arch = "x86_64")]
use super::simd::{self, Isa};
pub use ball::BallRegion;
pub use cone::Cone;
pub use packet::{PrimaryPacket, ShadowPacket};
// `UVec2` is named inside obvhs's `traverse!` macro.
use glam::{DVec3, UVec2, Vec3, Vec3A};
use obvhs::cwbvh::Traversal;
use obvhs::cwbvh::node::CwBvhNode;
use obvhs::ray::Ray;
use obvhs::{aabb::Aabb, cwbvh::CwBvh};
use rayon::prelude::*;

/// Padding of every triangle's box in the normalized frame (scene extent = 1).
pub const PAD: f64 = 1e-5;
/// How far (in the f32 ray's parameter s) its copy begins before the
/// segment: obvhs's node test only counts a node entered at s ≥ 10⁻⁴, and
/// this is also more than two pads of frame distance.
const EARLY_START: f64 = 2e-4;
/// How far (in s) beyond the segment's end the f32 copy reaches: four pads
/// of frame distance at least (its direction is at least 1 long).
const PAD_S: f64 = 4.0 * PAD;

/// A triangle to cast rays against.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BvhTriangle {
    /// In f32, as every scene's are: f64 holds them exactly (`widened`), and
    /// half the bytes keep more of a large model's corners in cache.
    pub corners: [Vec3; 3],
    /// Blocks shadow rays (the object casts shadows).
    pub occludes: bool,
}

impl BvhTriangle {
    /// Its corners in f64, exactly.
    pub fn corners_f64(&self) -> [DVec3; 3] {
        widened(&self.corners)
    }
}

/// Where a BVH reads its triangles from, by index: a list of them, or a
/// scene's meshes read in place (see `Reference::new`), which spares a
/// large scene a gathered copy (40 bytes a triangle).
pub trait TriangleSource: Sync {
    /// How many triangles it holds: indices 0 to count − 1.
    fn count(&self) -> usize;
    /// Triangle `i`'s corners, in f32 as scenes give them.
    fn corners(&self, i: usize) -> [Vec3; 3];
    /// Whether triangle `i` blocks shadow rays.
    fn occludes(&self, i: usize) -> bool;
}

impl TriangleSource for [BvhTriangle] {
    fn count(&self) -> usize {
        self.len()
    }

    fn corners(&self, i: usize) -> [Vec3; 3] {
        self[i].corners
    }

    fn occludes(&self, i: usize) -> bool {
        self[i].occludes
    }
}

/// f32 corners in f64, exactly: what every test of a ray takes.
#[inline(always)]
pub fn widened(corners: &[Vec3; 3]) -> [DVec3; 3] {
    corners.map(Vec3::as_dvec3)
}

/// The closest hit of a ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Index of the triangle in the list given to [`TriangleBvh::new`]
    /// (in the source given to [`TriangleBvh::of`]).
    pub triangle: usize,
    /// Distance along the ray (its direction's units) and barycentrics.
    pub at: TriangleHit,
}

/// Whether hit `a` on triangle `ta` wins over `b`: nearer, or as near with a
/// lower index (so that every way of casting agrees on shared edges).
pub fn closer(a: TriangleHit, ta: usize, b: Hit) -> bool {
    a.t < b.at.t || (a.t == b.at.t && ta < b.triangle)
}

pub struct TriangleBvh {
    /// None when there is nothing to hit.
    bvh: Option<CwBvh>,
    /// Corners, in the BVH's leaf order so that a leaf slot indexes them directly.
    corners: Vec<[Vec3; 3]>,
    occludes: Vec<bool>,
    /// Leaf slot → index in the caller's list.
    original: Vec<usize>,
    centre: DVec3,
    /// Units of the normalized frame per world metre.
    per_scale: f64,
    /// The padded scene box (world, f64).
    min: DVec3,
    max: DVec3,
}

impl TriangleBvh {
    /// Builds the BVH. Triangles with a non-finite corner or zero area can
    /// never be hit and are left out.
    pub fn new(triangles: &[BvhTriangle]) -> Self {
        Self::of(triangles)
    }

    /// [`Self::new`] of the triangles `source` gives: hits name their
    /// index there.
    pub fn of(source: &(impl TriangleSource + ?Sized)) -> Self {
        Self::in_groups(source, (build::MIN_GROUP, build::VERY_FAST_FROM))
    }

    /// [`Self::of`] built in parallel in groups of `min_group` triangles
    /// or more, by obvhs's very fast build from `very_fast_from` triangles
    /// (see `bvh/build.rs`).
    fn in_groups(
        source: &(impl TriangleSource + ?Sized),
        (min_group, very_fast_from): (usize, usize),
    ) -> Self {
        // On the pool, as the boxes below: the build's serial start took
        // some 32 ms of its 250 ms on 1 M triangles (the same values: each
        // keeps the triangles' order, and min and max round nothing). The
        // scene box and whether every triangle is usable come from one
        // pass; the usable ones are listed by a second only when some are
        // not (the list of a filter cost 14 ms of the 1 M scene's 34).
        let usable_corners = |i: usize| {
            let [a, b, c] = widened(&source.corners(i));
            let usable = a.is_finite()
                && b.is_finite()
                && c.is_finite()
                && (b - a).cross(c - a).length_squared() > 0.0;
            usable.then_some([a, b, c])
        };
        let empty = || (DVec3::INFINITY, DVec3::NEG_INFINITY, true);
        let count = source.count();
        let (min, max, every) = (0..count)
            .into_par_iter()
            .fold(empty, |(min, max, every), i| match usable_corners(i) {
                Some([a, b, c]) => (min.min(a).min(b).min(c), max.max(a).max(b).max(c), every),
                None => (min, max, false),
            })
            .reduce(empty, |(a0, a1, a), (b0, b1, b)| (a0.min(b0), a1.max(b1), a && b));
        let usable: Vec<u32> = if every {
            (0..count as u32).into_par_iter().collect()
        } else {
            (0..count as u32)
                .into_par_iter()
                .filter(|&i| usable_corners(i as usize).is_some())
                .collect()
        };
        if usable.is_empty() {
            return Self {
                bvh: None,
                corners: Vec::new(),
                occludes: Vec::new(),
                original: Vec::new(),
                centre: DVec3::ZERO,
                per_scale: 1.0,
                min: DVec3::ZERO,
                max: DVec3::ZERO,
            };
        }
        let centre = 0.5 * (min + max);
        let scale = (max - min).max_element().max(f64::MIN_POSITIVE);
        let to_frame = |p: DVec3| (p - centre) / scale;
        // Each triangle's padded box in the normalized frame.
        let boxes: Vec<Aabb> = usable
            .par_iter()
            .map(|&i| {
                let [a, b, c] = widened(&source.corners(i as usize)).map(to_frame);
                let lo = a.min(b).min(c) - DVec3::splat(PAD);
                let hi = a.max(b).max(c) + DVec3::splat(PAD);
                Aabb::new(lo.as_vec3a(), hi.as_vec3a())
            })
            .collect();
        let bvh = build::build_cwbvh(&boxes, min_group, very_fast_from);
        // In the leaves' order, on the pool: the shading data's gathering
        // beside the build is done by now on large scenes.
        let original: Vec<usize> = bvh
            .primitive_indices
            .par_iter()
            .map(|&slot| usable[slot as usize] as usize)
            .collect();
        let pad_world = DVec3::splat(PAD * scale);
        Self {
            corners: original.par_iter().map(|&i| source.corners(i)).collect(),
            occludes: original.par_iter().map(|&i| source.occludes(i)).collect(),
            original,
            bvh: Some(bvh),
            centre,
            per_scale: 1.0 / scale,
            min: min - pad_world,
            max: max + pad_world,
        }
    }

    /// Triangles that can be hit.
    pub fn len(&self) -> usize {
        self.corners.len()
    }

    pub fn is_empty(&self) -> bool {
        self.corners.is_empty()
    }

    /// The ray prepared for traversal: clipped in f64 to the padded scene
    /// box within (t_min, t_max) by the slab test when it starts outside
    /// the box; its f32 copy in the frame, with the same parameter t, begins
    /// a little before the clipped start and reaches a few pads beyond its
    /// end; None when it misses the box.
    #[inline(always)]
    fn query(&self, origin: DVec3, direction: DVec3, t_min: f64, t_max: f64) -> Option<Query> {
        let inside = origin.cmpge(self.min).all() && origin.cmple(self.max).all();
        let (t0, t1) = if inside {
            // Shadow rays: the segment as given (beyond the box is empty).
            (t_min, t_max)
        } else {
            // A zero component gives ±∞ and, on a slab face, NaN, which
            // min/max skip: a ray in a face's plane misses (no triangle lies
            // on the padded box's faces).
            let inv = direction.recip();
            let a = (self.min - origin) * inv;
            let b = (self.max - origin) * inv;
            (
                a.min(b).max_element().max(t_min),
                a.max(b).min_element().min(t_max),
            )
        };
        let meets_box = t0 <= t1;
        if !meets_box {
            return None;
        }
        // The f32 ray's direction is d in frame units scaled so that its
        // largest component is 1 (so obvhs's clamp of 1 / d_i at ±1/ε only
        // touches near-parallel axes, as for unit vectors); its parameter is
        // s = (t − t_start) · s_per_t, and |direction| ∈ [1, √3] makes a
        // frame distance D between D / √3 and D in s.
        let d_frame = direction * self.per_scale;
        let s_per_t = d_frame.abs().max_element();
        let t_per_s = 1.0 / s_per_t;
        let unit = (d_frame * t_per_s).as_vec3a();
        let limit = Vec3A::splat(1.0 / f32::EPSILON);
        // obvhs only enters nodes at s ≥ 10⁻⁴: begin well before that, and
        // before the box's padded face.
        let t_start = t0 - EARLY_START * t_per_s;
        let far = if t1.is_finite() {
            ((t1 - t_start) * s_per_t + PAD_S) as f32
        } else {
            f32::INFINITY
        };
        let ray = Ray {
            origin: ((origin - self.centre + direction * t_start) * self.per_scale).as_vec3a(),
            direction: unit,
            inv_direction: unit.recip().clamp(-limit, limit),
            tmin: 0.0,
            tmax: far,
        };
        Some(Query {
            ray,
            t_start,
            s_per_t,
            sheared: ShearedRay::new(origin, direction),
        })
    }

    /// The closest hit with t ∈ (t_min, t_max) (units of `direction`).
    pub fn closest_hit(&self, origin: DVec3, direction: DVec3, t_min: f64, t_max: f64) -> Option<Hit> {
        let bvh = self.bvh.as_ref()?;
        let query = self.query(origin, direction, t_min, t_max)?;
        let mut best: Option<Hit> = None;
        let mut limit = t_max;
        self.walk_ray(bvh, &query, |slot, far| {
            if let Some(at) = query
                .sheared
                .intersect(&widened(&self.corners[slot]), t_min, limit)
            {
                let triangle = self.original[slot];
                if best.is_none_or(|b| closer(at, triangle, b)) {
                    best = Some(Hit { triangle, at });
                    // Equal distances stay candidates (lowest index wins).
                    limit = at.t.next_up();
                    // Keep every node up to the new best (plus a few pads).
                    *far = ((at.t - query.t_start) * query.s_per_t + PAD_S) as f32;
                }
            }
            false
        });
        best
    }

    /// Whether an occluding triangle lies at t ∈ (t_min, t_max) along the ray.
    pub fn occluded(&self, origin: DVec3, direction: DVec3, t_min: f64, t_max: f64) -> bool {
        let Some(bvh) = self.bvh.as_ref() else {
            return false;
        };
        let Some(query) = self.query(origin, direction, t_min, t_max) else {
            return false;
        };
        let mut blocked = false;
        self.walk_ray(bvh, &query, |slot, _| {
            if self.occludes[slot] && query.sheared.hits(&widened(&self.corners[slot]), t_min, t_max) {
                blocked = true;
            }
            blocked
        });
        blocked
    }

    /// Walks the BVH along `query`'s f32 ray, calling `visit(slot, far)`
    /// for each triangle slot of the leaves it enters, until `visit` says
    /// stop (true); `far` is the f32 ray's far limit, which `visit` may
    /// bring nearer. A node's children are tested in AVX2 where the CPU
    /// has it (the same bits as obvhs's test).
    #[inline(always)]
    fn walk_ray(&self, bvh: &CwBvh, query: &Query, visit: impl FnMut(usize, &mut f32) -> bool) {
        #[cfg(target_arch = "x86_64")]
        if Isa::Avx2.runs() {
            // SAFETY: the CPU has AVX2 and the bit instructions with it.
            return unsafe { walk_ray_avx2(bvh, query, visit) };
        }
        walk_ray_with(bvh, query, visit, CwBvhNode::intersect_ray);
    }

    /// A ray's f32 copy from `origin` along `direction` and the BVH's
    /// nodes, for the node tests' tests.
    #[cfg(test)]
    fn ray_and_nodes(&self, origin: DVec3, direction: DVec3) -> Option<(Ray, &[CwBvhNode])> {
        let query = self.query(origin, direction, 0.0, f64::INFINITY)?;
        Some((query.ray, &self.bvh.as_ref()?.nodes))
    }
}

#[cfg(target_arch = "x86_64")]
simd::avx2_set! {
    /// [`TriangleBvh::walk_ray`] with the node test in AVX2 (and the walk's
    /// `count_ones` in POPCNT, as [`Isa::Avx2`]'s lane code).
    fn walk_ray_avx2(bvh: &CwBvh, query: &Query, visit: impl FnMut(usize, &mut f32) -> bool) {
        walk_ray_with(bvh, query, visit, |node, ray, octant| {
            node_avx::children_hit(node, ray, octant)
        });
    }
}

/// [`TriangleBvh::walk_ray`] with `children` as the node test.
#[inline(always)]
fn walk_ray_with(
    bvh: &CwBvh,
    query: &Query,
    mut visit: impl FnMut(usize, &mut f32) -> bool,
    children: impl Fn(&CwBvhNode, &Ray, u32) -> u32,
) {
    let mut ray = query.ray;
    TRAVERSAL.with_borrow_mut(|state| {
        state.reinit(ray.direction);
        let mut node;
        // A plain `break` would leave only the leaf's triangles and the walk
        // would go on: it leaves through the block's label, as obvhs's own
        // any-hit walk does.
        'walk: {
            obvhs::traverse!(bvh, node, state, children(node, &ray, state.oct_inv4), {
                if visit(state.primitive_id as usize, &mut ray.tmax) {
                    break 'walk;
                }
            });
        }
    });
}

thread_local! {
    /// Each thread's traversal state (a 32-entry stack), reused from ray to
    /// ray instead of being built and zeroed for every one.
    static TRAVERSAL: std::cell::RefCell<Traversal> = std::cell::RefCell::new(Traversal::default());
}

/// A ray ready for traversal (see [`TriangleBvh::query`]).
struct Query {
    /// The f32 copy in the normalized frame, parameter s = (t − t_start) · s_per_t.
    ray: Ray,
    /// The f64 parameter where the f32 copy begins.
    t_start: f64,
    s_per_t: f64,
    sheared: ShearedRay,
}

/// The closest hit by testing every triangle: what the BVH must reproduce.
pub fn closest_hit_brute_force(
    triangles: &[BvhTriangle],
    origin: DVec3,
    direction: DVec3,
    t_min: f64,
    t_max: f64,
) -> Option<Hit> {
    let sheared = ShearedRay::new(origin, direction);
    let mut best: Option<Hit> = None;
    for (i, tri) in triangles.iter().enumerate() {
        let limit = best.map_or(t_max, |b| b.at.t.next_up());
        if let Some(at) = sheared.intersect(&tri.corners_f64(), t_min, limit)
            && best.is_none_or(|b| closer(at, i, b))
        {
            best = Some(Hit { triangle: i, at });
        }
    }
    best
}

/// Whether any occluding triangle blocks the segment, by testing every one.
pub fn occluded_brute_force(
    triangles: &[BvhTriangle],
    origin: DVec3,
    direction: DVec3,
    t_min: f64,
    t_max: f64,
) -> bool {
    let sheared = ShearedRay::new(origin, direction);
    triangles
        .iter()
        .any(|tri| tri.occludes && sheared.hits(&tri.corners_f64(), t_min, t_max))
}

#[cfg(test)]
mod tests;
