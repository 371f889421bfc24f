// The shadow casters' BVH (gpu::bvh): any-hit traversal of a segment, for the
// ray-traced visibility. Portable: storage buffers and a loop with a small
// stack, no ray-query extension.

// An inner node: its two children (gpu::bvh, `FlatBvh::pairs`), each its
// box on the BVH's grid (gpu::bvh, `Grid`), u16 corners packed two to a u32
// (xyz: min x, min y | min z, max x | max y, max z), and its link (w): an
// inner child's pair, or its leaf, BVH_LEAF | count << 28 | first triangle.
// A child is one vec4, which lavapipe loads in one pass over its lanes (a
// vec3 and a u32 took two). Pair 0 holds the root's children.
struct BvhPair {
    a: vec4<u32>,
    b: vec4<u32>,
}

// The grid of the boxes (gpu::bvh, `BvhGridRaw`): a corner q lies at
// q · step + origin (m). The caller passes it from a uniform, which
// lavapipe reads once for all lanes (a storage buffer's entry took two
// loads lane by lane a ray).
struct BvhGrid {
    origin: vec3<f32>,
    step: vec3<f32>,
}

// Corner v0 and the edges e1 = v1 − v0, e2 = v2 − v0 (m, world).
struct BvhTriangle {
    v0: vec3<f32>,
    e1: vec3<f32>,
    e2: vec3<f32>,
}

@group(2) @binding(1) var<storage, read> bvh_pairs: array<BvhPair>;
@group(2) @binding(2) var<storage, read> bvh_triangles: array<BvhTriangle>;

// Nodes waiting to be visited. A ray keeps one for each node on its path
// where it met both children: at most 17 for 200 k shadow rays of the
// engine model and 12 of the 1 M-triangle scene (trees 30 and 34 deep).
// lavapipe keeps the array in scratch memory and writes its zero
// initializer into it lane by lane, so its cost grows with its size: 64 →
// 32 entries ran 8 % fewer instructions. One stack an invocation, at module
// scope: a pixel's several rays (a sphere light's strata) pay the
// initializer once, and no function takes it through a pointer, which
// naga's GLSL makes an `inout` array that Mesa's GL copies in and out at
// every step (the walk ran ~3.7× slower on llvmpipe's GL than on lavapipe).
// A deeper (degenerate) tree does not lose nodes: a ray whose stack
// overflows and finds no hit in the nodes it kept tests every triangle.
const BVH_STACK_SIZE: u32 = 32u;
var<private> bvh_stack: array<u32, BVH_STACK_SIZE>;
// A child's `first` that names a leaf, and its fields.
const BVH_LEAF: u32 = 0x80000000u;
const BVH_COUNT_SHIFT: u32 = 28u;
const BVH_COUNT_MASK: u32 = 7u;
const BVH_FIRST_MASK: u32 = 0x0fffffffu;
// Barycentric slack of the triangle test: triangles grow by 2·10⁻⁶ of their
// size, so that a ray through an edge shared by two triangles hits one of
// them despite f32 rounding (no light leaking through a closed mesh).
const BARYCENTRIC_SLACK: f32 = 2e-6;

// Möller–Trumbore: does o + t d meet the triangle for 0 < t < t_max?
fn bvh_hits_triangle(tri: BvhTriangle, o: vec3<f32>, d: vec3<f32>, t_max: f32) -> bool {
    let p = cross(d, tri.e2);
    let det = dot(tri.e1, p);
    if det == 0.0 {
        return false;
    }
    let inv_det = 1.0 / det;
    let s = o - tri.v0;
    let u = dot(s, p) * inv_det;
    if u < -BARYCENTRIC_SLACK || u > 1.0 + BARYCENTRIC_SLACK {
        return false;
    }
    let q = cross(s, tri.e1);
    let v = dot(d, q) * inv_det;
    if v < -BARYCENTRIC_SLACK || u + v > 1.0 + BARYCENTRIC_SLACK {
        return false;
    }
    let t = dot(tri.e2, q) * inv_det;
    return t > 0.0 && t < t_max;
}

// A child's box: its corners q on the BVH's grid, at q · step + origin.
struct BvhBox {
    low: vec3<f32>,
    high: vec3<f32>,
}

fn bvh_box(child: vec4<u32>) -> BvhBox {
    let c = child.xyz;
    return BvhBox(
        vec3<f32>(vec3<u32>(c.x & 0xffffu, c.x >> 16u, c.y & 0xffffu)),
        vec3<f32>(vec3<u32>(c.y >> 16u, c.z & 0xffffu, c.z >> 16u)),
    );
}

// Slab test: whether the segment's parameters [0, t_max] meet a box whose
// corners lie at the ray's parameters t0 and t1 along each axis.
fn bvh_slabs_meet(t0: vec3<f32>, t1: vec3<f32>, t_max: f32) -> bool {
    let near = min(t0, t1);
    let far = max(t0, t1);
    let enter = max(max(near.x, near.y), max(near.z, 0.0));
    let leave = min(min(far.x, far.y), min(far.z, t_max));
    return enter <= leave;
}

// 1 / d, a zero component first made a tiny one: its slabs then span ±∞,
// never NaN.
fn bvh_inverse(d: vec3<f32>) -> vec3<f32> {
    return 1.0 / select(d, vec3<f32>(1e-30), abs(d) < vec3<f32>(1e-30));
}

// One ray's slabs on the grid: a corner q lies at its parameter q · scale
// + offset along each axis (scale = step / d, offset = (origin − o) / d),
// one multiply-add a corner and axis where (q · step + origin − o) / d
// took three operations. Its rounding, a few ulps of |q · step| +
// |origin − o|, is well within the boxes' padding (gpu::bvh,
// `BOX_PAD_REL`). (The packet walks keep the corners relative to their
// shared origin instead: one subtraction for all their rays.)
struct BvhSlabs {
    scale: vec3<f32>,
    offset: vec3<f32>,
}

fn bvh_slabs(grid: BvhGrid, o: vec3<f32>, d: vec3<f32>) -> BvhSlabs {
    let inv_d = bvh_inverse(d);
    return BvhSlabs(grid.step * inv_d, (grid.origin - o) * inv_d);
}

// Whether the segment o + t d, 0 ≤ t ≤ t_max, meets a child's box.
fn bvh_hits_box(child: vec4<u32>, ray: BvhSlabs, t_max: f32) -> bool {
    let q = bvh_box(child);
    return bvh_slabs_meet(q.low * ray.scale + ray.offset, q.high * ray.scale + ray.offset, t_max);
}

// Where a walk stands: the item it visits, a pair (its index) or a leaf
// (BVH_LEAF, its count in bits 28–30 and its first triangle in bits 0–27,
// as a child's link (w) holds them, so that a leaf's step reads no node);
// the nodes kept on the stack, whether any was lost to its size, and
// whether nothing is left to visit.
struct BvhWalk {
    item: u32,
    depth: u32,
    overflowed: bool,
    done: bool,
}

// One step from a pair whose children a and b the walk's rays meet, or
// not: down to the one met (b kept for later where both are), else to the
// last node kept. True when nothing is left (the walk is done).
fn bvh_step(walk: ptr<function, BvhWalk>, pair: BvhPair, hit_a: bool, hit_b: bool) -> bool {
    if hit_a && hit_b {
        if (*walk).depth < BVH_STACK_SIZE {
            bvh_stack[(*walk).depth] = pair.b.w;
            (*walk).depth += 1u;
        } else {
            (*walk).overflowed = true;
        }
    }
    // To a child met: lavapipe runs each branch under a mask, and a select
    // costs less than a branch.
    if hit_a || hit_b {
        (*walk).item = select(pair.b.w, pair.a.w, hit_a);
        return false;
    }
    if (*walk).depth == 0u {
        (*walk).done = true;
        return true;
    }
    (*walk).depth -= 1u;
    (*walk).item = bvh_stack[(*walk).depth];
    return false;
}

// The triangles to test after the inner nodes, first and end: the leaf's;
// none when nothing was left. Where subtrees were lost, the last step
// tests every triangle instead (the slow, exact answer): in the leaf's
// loop, not one of its own after it, which lavapipe would enter once under
// an empty mask on every ray.
fn bvh_leaf_triangles(walk: BvhWalk) -> vec2<u32> {
    let first = walk.item & BVH_FIRST_MASK;
    let end = select(first + ((walk.item >> BVH_COUNT_SHIFT) & BVH_COUNT_MASK), first, walk.done);
    let all = (walk.done || walk.depth == 0u) && walk.overflowed;
    return select(vec2<u32>(first, end), vec2<u32>(0u, arrayLength(&bvh_triangles)), all);
}

// After a leaf's triangles: on to the last node kept, or false when none
// is left.
fn bvh_next(walk: ptr<function, BvhWalk>) -> bool {
    if (*walk).done || (*walk).depth == 0u {
        return false;
    }
    (*walk).depth -= 1u;
    (*walk).item = bvh_stack[(*walk).depth];
    return true;
}

// Whether any caster meets o + t d for 0 < t < t_max (d need not be unit).
// Inner nodes are walked until a leaf or the end, then the leaf's triangles
// tested: lanes reach their leaves together, and test them together.
fn bvh_occluded(o: vec3<f32>, d: vec3<f32>, t_max: f32, pair_count: u32, grid: BvhGrid) -> bool {
    let ray = bvh_slabs(grid, o, d);
    if pair_count == 0u {
        return false;
    }
    var walk = BvhWalk(0u, 0u, false, false);
    loop {
        while (walk.item & BVH_LEAF) == 0u {
            let pair = bvh_pairs[walk.item];
            let hit_a = bvh_hits_box(pair.a, ray, t_max);
            if bvh_step(&walk, pair, hit_a, bvh_hits_box(pair.b, ray, t_max)) {
                break;
            }
        }
        let triangles = bvh_leaf_triangles(walk);
        for (var i = triangles.x; i < triangles.y; i++) {
            if bvh_hits_triangle(bvh_triangles[i], o, d, t_max) {
                return true;
            }
        }
        if !bvh_next(&walk) {
            break;
        }
    }
    return false;
}

// Four rays of one walk (a sphere light's strata at one point): each
// column a ray's direction, or its reciprocal.
alias BvhRays4 = mat4x3<f32>;

// bvh_hits_box for each of the four rays from o: the corners relative to o
// once for all, then each ray's 1 / d.
fn bvh_hits_box4(child: vec4<u32>, grid: BvhGrid, o: vec3<f32>, inv_d: BvhRays4, t_max: f32) -> vec4<bool> {
    let q = bvh_box(child);
    let low = q.low * grid.step + grid.origin - o;
    let high = q.high * grid.step + grid.origin - o;
    return vec4<bool>(
        bvh_slabs_meet(low * inv_d[0], high * inv_d[0], t_max),
        bvh_slabs_meet(low * inv_d[1], high * inv_d[1], t_max),
        bvh_slabs_meet(low * inv_d[2], high * inv_d[2], t_max),
        bvh_slabs_meet(low * inv_d[3], high * inv_d[3], t_max),
    );
}

// bvh_hits_triangle for each of the four rays.
fn bvh_hits_triangle4(tri: BvhTriangle, o: vec3<f32>, d: BvhRays4, t_max: f32) -> vec4<bool> {
    return vec4<bool>(
        bvh_hits_triangle(tri, o, d[0], t_max),
        bvh_hits_triangle(tri, o, d[1], t_max),
        bvh_hits_triangle(tri, o, d[2], t_max),
        bvh_hits_triangle(tri, o, d[3], t_max),
    );
}

// The rays' answers of an eight-ray walk: those of the columns of d_lo,
// and of d_hi.
struct BvhBlocked8 {
    lo: vec4<bool>,
    hi: vec4<bool>,
}

// bvh_occluded for up to eight rays from one origin o, along the columns of
// d_lo and, where `eight`, of d_hi, those `in_lo` and `in_hi` (the others:
// false). One walk for all: it visits a node where any live ray meets it,
// and loads each node and triangle once for all, where lavapipe loads a
// storage buffer lane by lane. A ray found blocked leaves the walk. Each
// ray's triangle tests are bvh_occluded's, and its box tests differ from
// them only by rounding far inside the boxes' padding, so every triangle a
// ray meets is tested and each answer is the one bvh_occluded gives. `eight`
// false (a constant once inlined) compiles the four-ray walk: a walk for
// four costs some 45 % more than a walk for one on lavapipe, one for eight
// some 60 % more than one for four.
fn bvh_occluded8(o: vec3<f32>, d_lo: BvhRays4, d_hi: BvhRays4, t_max: f32, in_lo: vec4<bool>, in_hi: vec4<bool>, eight: bool, pair_count: u32, grid: BvhGrid) -> BvhBlocked8 {
    let inv_lo = BvhRays4(bvh_inverse(d_lo[0]), bvh_inverse(d_lo[1]), bvh_inverse(d_lo[2]), bvh_inverse(d_lo[3]));
    let inv_hi = BvhRays4(bvh_inverse(d_hi[0]), bvh_inverse(d_hi[1]), bvh_inverse(d_hi[2]), bvh_inverse(d_hi[3]));
    var blocked = BvhBlocked8(vec4<bool>(false), vec4<bool>(false));
    var live = BvhBlocked8(in_lo, in_hi & vec4<bool>(eight));
    if pair_count == 0u {
        return blocked;
    }
    // bvh_occluded's walk, a node met where any live ray meets it.
    var walk = BvhWalk(0u, 0u, false, false);
    loop {
        while (walk.item & BVH_LEAF) == 0u {
            let pair = bvh_pairs[walk.item];
            let hit_a = any(live.lo & bvh_hits_box4(pair.a, grid, o, inv_lo, t_max))
                || (eight && any(live.hi & bvh_hits_box4(pair.a, grid, o, inv_hi, t_max)));
            let hit_b = any(live.lo & bvh_hits_box4(pair.b, grid, o, inv_lo, t_max))
                || (eight && any(live.hi & bvh_hits_box4(pair.b, grid, o, inv_hi, t_max)));
            if bvh_step(&walk, pair, hit_a, hit_b) {
                break;
            }
        }
        let triangles = bvh_leaf_triangles(walk);
        for (var i = triangles.x; i < triangles.y; i++) {
            let tri = bvh_triangles[i];
            let hits_lo = live.lo & bvh_hits_triangle4(tri, o, d_lo, t_max);
            blocked.lo |= hits_lo;
            live.lo &= !hits_lo;
            if eight {
                let hits_hi = live.hi & bvh_hits_triangle4(tri, o, d_hi, t_max);
                blocked.hi |= hits_hi;
                live.hi &= !hits_hi;
            }
            if !any(live.lo) && !any(live.hi) {
                return blocked;
            }
        }
        if !bvh_next(&walk) {
            break;
        }
    }
    return blocked;
}
