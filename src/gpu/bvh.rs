//! The shadow casters as a BVH for the GPU ray tracer (`shaders/bvh.wgsl`):
//! a binary BVH built on the CPU by `obvhs` (PLOC, then reinsertion), flattened
//! into two storage buffers. Built anew for each scene uploaded, when a
//! frame first traces rays or on a thread of its own (`super::bvh_build`).
//!
//! Layout built: node 0 is the root; an inner node (`count` = 0) has its
//! children at `first` and `first + 1`; a leaf holds triangles
//! `first .. first + count`, stored in leaf order. Each triangle is kept as v0
//! and its two edges, what the Möller–Trumbore test reads.
//!
//! Layout uploaded ([`FlatBvh::pairs`]): one entry per inner node, holding
//! both children's boxes and links: an inner child's entry, or a leaf's
//! count and first triangle packed in one u32, so that a leaf's step reads
//! no node and an inner node's step one entry (the nodes themselves took
//! three loads a step: the node, then its two children for their boxes).
//! The boxes lie on a grid of 2¹⁶ steps an axis (`Grid`), u16 corners
//! packed two to a u32: an entry is 32 bytes, not 64, and lavapipe, which
//! loads a storage buffer lane by lane, runs 8–10 % fewer instructions in
//! the ray-traced camera pass (callgrind: the default scene's still at
//! 202×210 98.6 → 89.2 M, the engine model's 146.3 → 134.5 M; the same
//! images).
//! With the traversal's inner nodes walked before each leaf ("while-while",
//! Aila & Laine 2009: on lavapipe's SIMD lanes the leaves are then tested
//! together), lavapipe's compiled shading ran 574.6 → 505.5 M instructions
//! over four drag frames of the default scene and 544.0 → 467.4 M over six
//! of the engine model's simplified copy (callgrind). Testing a pair's
//! leaves inline instead ran 697.7 M; visiting the nearer child first
//! changed nothing (506.6 M).

use crate::scene::Scene;
use bytemuck::{Pod, Zeroable};
use glam::{Vec3, Vec3A};
use obvhs::{BvhBuildParams, triangle::Triangle};
use wgpu::util::DeviceExt;

/// Most triangles per leaf: fewer node visits against more triangle tests.
const MAX_TRIANGLES_PER_LEAF: u32 = 4;
/// A leaf's link (`leaf_link`, `BVH_LEAF` and its fields in
/// shaders/bvh.wgsl): the top bit set, its count from bit 28 (at most 7),
/// its first triangle below.
const LEAF_LINK: u32 = 1 << 31;
const LINK_COUNT_SHIFT: u32 = 28;
const LINK_MAX_COUNT: u32 = 7;
const _: () = assert!(MAX_TRIANGLES_PER_LEAF <= LINK_MAX_COUNT);
/// Boxes are widened by this fraction of (largest |coordinate| + scene
/// extent): a few hundred f32 ulps, so that the slab test's rounding never
/// drops a triangle that touches its box's face.
const BOX_PAD_REL: f32 = 1e-6;

/// A node of the binary BVH as built, f32 box and all ([`FlatBvh::nodes`]);
/// [`FlatBvh::pairs`] turns the nodes into the layout the shader reads.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BvhNodeRaw {
    pub min: [f32; 3],
    /// Triangles in this leaf; 0: an inner node.
    pub count: u32,
    pub max: [f32; 3],
    /// Inner node: index of the first child; leaf: of the first triangle.
    pub first: u32,
}

/// A child of `BvhPair` in shaders/bvh.wgsl (a `vec4<u32>`): its box on the BVH's grid of 2¹⁶
/// steps an axis, three u16 corners a side packed two to a u32 (low, high:
/// min x, min y | min z, max x | max y, max z), and its link: an inner
/// child's pair, or its leaf (`leaf_link`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct BvhChildRaw {
    pub corners: [u32; 3],
    pub first: u32,
}

/// `BvhPair` of shaders/bvh.wgsl: an inner node's two children; the root's
/// are in entry 0.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct BvhPairRaw {
    pub children: [BvhChildRaw; 2],
}

/// `BvhGrid` of shaders/bvh.wgsl: the grid of the pairs' boxes
/// ([`FlatBvh::grid`]), a corner q at q · step + origin (m). The camera
/// pass reads it from its uniforms (`RayTrace` of shaders/raytrace.wgsl),
/// where lavapipe reads a value once for all lanes, not lane by lane as in
/// a storage buffer: 2.5 % fewer instructions than as the pairs' entry 0.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct BvhGridRaw {
    pub origin: [f32; 3],
    pub _padding0: u32,
    pub step: [f32; 3],
    pub _padding1: u32,
}

/// `BvhTriangle` of shaders/bvh.wgsl: corner v0 and edges e1 = v1 − v0, e2 = v2 − v0 (m).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct BvhTriangleRaw {
    pub v0: [f32; 3],
    pub _padding0: u32,
    pub e1: [f32; 3],
    pub _padding1: u32,
    pub e2: [f32; 3],
    pub _padding2: u32,
}

/// The corners of each triangle of the objects that cast shadows, each
/// object's triangles given by its list in `indices` (one per object, into
/// its vertices); a corner index out of range leaves its triangle out.
pub fn caster_triangles<'a>(scene: &Scene, indices: impl IntoIterator<Item = &'a [u32]>) -> Vec<[Vec3; 3]> {
    scene
        .objects
        .iter()
        .zip(indices)
        .filter(|(o, _)| o.casts_shadows)
        .flat_map(|(o, indices)| {
            let p = &o.mesh.positions;
            indices.chunks_exact(3).filter_map(move |ids| {
                Some([
                    *p.get(ids[0] as usize)?,
                    *p.get(ids[1] as usize)?,
                    *p.get(ids[2] as usize)?,
                ])
            })
        })
        .collect()
}

/// A BVH flattened for upload.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FlatBvh {
    /// Empty when nothing casts shadows.
    pub nodes: Vec<BvhNodeRaw>,
    pub triangles: Vec<BvhTriangleRaw>,
}

impl FlatBvh {
    /// The triangles of every object that casts shadows; triangles with an
    /// index out of range, a non-finite corner or zero area are left out
    /// (they block nothing, as in the reference).
    pub fn of_scene(scene: &Scene) -> Self {
        Self::of_casters(scene, scene.objects.iter().map(|o| &o.mesh.indices[..]))
    }

    /// As [`Self::of_scene`], each object's triangles given by its list in
    /// `indices` (one per object, into its vertices): a simplified copy.
    pub fn of_casters<'a>(scene: &Scene, indices: impl IntoIterator<Item = &'a [u32]>) -> Self {
        Self::new(&caster_triangles(scene, indices))
    }

    pub fn new(triangles: &[[Vec3; 3]]) -> Self {
        let usable: Vec<Triangle> = triangles
            .iter()
            .filter(|[a, b, c]| {
                a.is_finite()
                    && b.is_finite()
                    && c.is_finite()
                    && (*b - *a).cross(*c - *a).length_squared() > 0.0
            })
            .map(|&[a, b, c]| Triangle {
                v0: a.into(),
                v1: b.into(),
                v2: c.into(),
            })
            .collect();
        if usable.is_empty() {
            return Self::default();
        }
        // obvhs's medium build (a wider PLOC search, more reinsertion): on
        // lavapipe the ray-traced pass ran 7.9 % (default scene) and 3.1 %
        // (engine model) fewer instructions than with its fast build, for
        // some 25 ms more at the engine's load and 0.3 s at 1 M triangles.
        let params = BvhBuildParams {
            max_prims_per_leaf: MAX_TRIANGLES_PER_LEAF,
            ..BvhBuildParams::medium_build()
        };
        let bvh = obvhs::bvh2::builder::build_bvh2(&usable, params, &mut std::time::Duration::default());
        let (mut lo, mut hi) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY);
        for t in &usable {
            lo = lo.min(t.v0).min(t.v1).min(t.v2);
            hi = hi.max(t.v0).max(t.v1).max(t.v2);
        }
        let pad = BOX_PAD_REL * (lo.abs().max(hi.abs()).max_element() + (hi - lo).max_element());
        let nodes = bvh
            .nodes
            .iter()
            .map(|n| BvhNodeRaw {
                min: (Vec3::from(n.aabb.min) - pad).to_array(),
                count: n.prim_count,
                max: (Vec3::from(n.aabb.max) + pad).to_array(),
                first: n.first_index,
            })
            .collect();
        let triangles = bvh
            .primitive_indices
            .iter()
            .map(|&i| {
                let t = &usable[i as usize];
                BvhTriangleRaw {
                    v0: Vec3::from(t.v0).to_array(),
                    e1: Vec3::from(t.v1 - t.v0).to_array(),
                    e2: Vec3::from(t.v2 - t.v0).to_array(),
                    ..Default::default()
                }
            })
            .collect();
        Self { nodes, triangles }
    }

    /// The uploaded layout: an entry per inner node, in node order (the
    /// root's first), each with its children's boxes on the grid and their
    /// links, an inner child's `first` the index of its entry. A root that
    /// is a leaf gets one entry whose children are both that leaf. Empty
    /// when `nodes` is.
    pub fn pairs(&self) -> Vec<BvhPairRaw> {
        let Some(&root) = self.nodes.first() else {
            return Vec::new();
        };
        let grid = Grid::of(&root);
        if root.count > 0 {
            let leaf = grid.child(&root, leaf_link(root));
            return vec![BvhPairRaw { children: [leaf; 2] }];
        }
        let mut entry = vec![u32::MAX; self.nodes.len()];
        let inner: Vec<usize> = (0..self.nodes.len())
            .filter(|&i| self.nodes[i].count == 0)
            .collect();
        for (k, &i) in inner.iter().enumerate() {
            entry[i] = k as u32;
        }
        inner
            .iter()
            .map(|&i| {
                let first = self.nodes[i].first as usize;
                BvhPairRaw {
                    children: [first, first + 1].map(|c| {
                        let child = self.nodes[c];
                        let link = if child.count > 0 {
                            leaf_link(child)
                        } else {
                            entry[c]
                        };
                        grid.child(&child, link)
                    }),
                }
            })
            .collect()
    }

    /// The grid the boxes of [`Self::pairs`] lie on (zero when `nodes` is
    /// empty).
    pub fn grid(&self) -> BvhGridRaw {
        self.nodes.first().map_or(BvhGridRaw::default(), |root| {
            let grid = Grid::of(root);
            BvhGridRaw {
                origin: grid.origin.to_array(),
                step: grid.step.to_array(),
                ..Default::default()
            }
        })
    }
}

/// The grid the uploaded boxes lie on: 2¹⁶ steps an axis over the root's
/// box. On lavapipe a storage buffer is read lane by lane, a load a value
/// (16 of them a pair of f32 boxes and links): the packed boxes take 8.
#[derive(Clone, Copy, Debug)]
struct Grid {
    origin: Vec3,
    step: Vec3,
}

/// The largest corner on a [`Grid`].
const GRID_MAX: f64 = 65535.0;

impl Grid {
    /// The grid over `root`'s box, wider by twice [`Self::slack`] and two
    /// steps on each side, so that every box inside it lies inside the
    /// grid once widened by both.
    fn of(root: &BvhNodeRaw) -> Self {
        let (lo, hi) = (Vec3::from(root.min), Vec3::from(root.max));
        let wide = 2.0 * Self::slack(lo.abs().max(hi.abs()) + (hi - lo));
        let (lo, hi) = (lo - wide, hi + wide);
        let step = ((hi - lo) / (GRID_MAX as f32 - 4.0)).max(Vec3::splat(f32::MIN_POSITIVE));
        Self {
            origin: lo - 2.0 * step,
            step,
        }
    }

    /// More than the shader's q · step + origin rounds by in f32 (twice, a
    /// half ulp each) where |q · step| + |origin| ≤ `reach`.
    fn slack(reach: Vec3) -> Vec3 {
        4.0 * f32::EPSILON * reach
    }

    /// `node`'s box on the grid, outward and wider by [`Self::slack`], so
    /// that the shader's q · step + origin in f32 still holds it: the
    /// traversal meets every box it met before the grid (the padding's
    /// allowance for the slab test is kept whole). Then `link`.
    fn child(&self, node: &BvhNodeRaw, first: u32) -> BvhChildRaw {
        let slack = Self::slack(self.origin.abs() + GRID_MAX as f32 * self.step);
        let q = |k: usize, x: f32, up: bool| {
            let x = f64::from(x) + f64::from(if up { slack[k] } else { -slack[k] });
            let steps = (x - f64::from(self.origin[k])) / f64::from(self.step[k]);
            (if up { steps.ceil() } else { steps.floor() }).clamp(0.0, GRID_MAX) as u32
        };
        let lo: [u32; 3] = std::array::from_fn(|k| q(k, node.min[k], false));
        let hi: [u32; 3] = std::array::from_fn(|k| q(k, node.max[k], true));
        BvhChildRaw {
            corners: [lo[0] | lo[1] << 16, lo[2] | hi[0] << 16, hi[1] | hi[2] << 16],
            first,
        }
    }

    /// A child's box in world coordinates, as the shader computes it.
    #[cfg(test)]
    fn world(&self, child: &BvhChildRaw) -> [Vec3; 2] {
        let [a, b, c] = child.corners;
        let lo = Vec3::new((a & 0xffff) as f32, (a >> 16) as f32, (b & 0xffff) as f32);
        let hi = Vec3::new((b >> 16) as f32, (c & 0xffff) as f32, (c >> 16) as f32);
        [lo * self.step + self.origin, hi * self.step + self.origin]
    }
}

/// A leaf as a pair's child links to it ([`LEAF_LINK`]).
fn leaf_link(leaf: BvhNodeRaw) -> u32 {
    assert!(
        leaf.count <= LINK_MAX_COUNT && leaf.first < 1 << LINK_COUNT_SHIFT,
        "a leaf the GPU's links cannot name"
    );
    LEAF_LINK | leaf.count << LINK_COUNT_SHIFT | leaf.first
}

/// The flattened BVH on the GPU.
pub struct GpuBvh {
    /// [`FlatBvh::pairs`].
    pub pairs: wgpu::Buffer,
    pub triangles: wgpu::Buffer,
    /// Pairs in use: 0 when nothing casts shadows (the buffers then hold one
    /// unused element each: bindings cannot be empty).
    pub pair_count: u32,
    pub triangle_count: u32,
    /// [`FlatBvh::grid`].
    pub grid: BvhGridRaw,
}

impl GpuBvh {
    pub fn new(device: &wgpu::Device, flat: &FlatBvh) -> Self {
        let upload = |label: &str, contents: &[u8]| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage: wgpu::BufferUsages::STORAGE,
            })
        };
        let pairs = flat.pairs();
        let pair_buffer = if pairs.is_empty() {
            upload("bvh pairs", bytemuck::bytes_of(&BvhPairRaw::default()))
        } else {
            upload("bvh pairs", bytemuck::cast_slice(&pairs))
        };
        let triangles = if flat.triangles.is_empty() {
            upload("bvh triangles", bytemuck::bytes_of(&BvhTriangleRaw::default()))
        } else {
            upload("bvh triangles", bytemuck::cast_slice(&flat.triangles))
        };
        Self {
            pairs: pair_buffer,
            triangles,
            pair_count: pairs.len() as u32,
            grid: flat.grid(),
            triangle_count: flat.triangles.len() as u32,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_usable_triangle_is_in_exactly_one_leaf_inside_its_box() {
        let mut triangles: Vec<[Vec3; 3]> = (0..200)
            .map(|i| {
                let o = Vec3::new((i % 10) as f32, (i / 10) as f32 * 0.3, (i % 7) as f32);
                [o, o + Vec3::X, o + Vec3::Y]
            })
            .collect();
        // Degenerate and non-finite triangles block nothing.
        triangles.push([Vec3::ZERO, Vec3::X, 2.0 * Vec3::X]);
        triangles.push([Vec3::NAN, Vec3::X, Vec3::Y]);
        let flat = FlatBvh::new(&triangles);
        assert_eq!(flat.triangles.len(), 200);
        let mut seen = vec![0; 200];
        let mut stack = vec![(0usize, flat.nodes[0])];
        while let Some((_, node)) = stack.pop() {
            if node.count == 0 {
                for c in [node.first, node.first + 1] {
                    let child = flat.nodes[c as usize];
                    for k in 0..3 {
                        assert!(child.min[k] >= node.min[k] && child.max[k] <= node.max[k]);
                    }
                    stack.push((c as usize, child));
                }
                continue;
            }
            for t in node.first..node.first + node.count {
                seen[t as usize] += 1;
                let tri = flat.triangles[t as usize];
                let v0 = Vec3::from(tri.v0);
                for p in [v0, v0 + Vec3::from(tri.e1), v0 + Vec3::from(tri.e2)] {
                    for k in 0..3 {
                        assert!(p[k] >= node.min[k] && p[k] <= node.max[k]);
                    }
                }
            }
        }
        assert!(seen.iter().all(|&n| n == 1));

        // The uploaded pairs reach every triangle once, through boxes on
        // the grid that hold the nodes' own.
        let pairs = flat.pairs();
        assert_eq!(pairs.len(), flat.nodes.iter().filter(|n| n.count == 0).count());
        let grid = Grid::of(&flat.nodes[0]);
        let mut seen = vec![0; 200];
        let mut stack = vec![(0, 0)];
        while let Some((p, node)) = stack.pop() {
            let first = flat.nodes[node].first as usize;
            for (child, c) in pairs[p].children.iter().zip([first, first + 1]) {
                let own = flat.nodes[c];
                let [lo, hi] = grid.world(child);
                assert!(lo.cmple(Vec3::from(own.min)).all() && hi.cmpge(Vec3::from(own.max)).all());
                if own.count == 0 {
                    stack.push((child.first as usize, c));
                } else {
                    assert_eq!(child.first >> 28, 8 | own.count, "a leaf's link");
                    let first = child.first & 0x0fff_ffff;
                    (first..first + own.count).for_each(|t| seen[t as usize] += 1);
                }
            }
        }
        assert!(seen.iter().all(|&n| n == 1));
    }

    #[test]
    fn a_root_leaf_is_one_pair_of_itself() {
        let flat = FlatBvh::new(&[[Vec3::ZERO, Vec3::X, Vec3::Y]]);
        let pairs = flat.pairs();
        assert_eq!(pairs.len(), 1, "the root's");
        let [a, b] = pairs[0].children;
        assert_eq!((a, a.first), (b, 1 << 31 | 1 << 28));
    }

    #[test]
    fn boxes_on_the_grid_hold_their_padded_box_at_any_magnitude() {
        // Small triangles far from the world's origin, and small triangles
        // by it in a scene 10 km across (where q · step + origin rounds by
        // far more than their coordinates' own ulp): the shader's rounding
        // never takes a grid box inside the box the traversal met before.
        let mut rng = crate::reference::sampling::Rng::new(3, 0, 0);
        let far = Vec3::splat(-1e4);
        let cases = [
            (Vec3::new(12345.0, -6789.0, 4321.0), 1.0, None),
            (Vec3::ZERO, 1e-3, Some([far, far + Vec3::X, far + Vec3::Y])),
        ];
        for (o, size, extra) in cases {
            let mut r = || 0.1 + rng.next_f64() as f32;
            let triangles: Vec<[Vec3; 3]> = (0..3000)
                .map(|_| {
                    let p = o + Vec3::new(r(), r(), r()) * size;
                    [
                        p,
                        p + Vec3::X * 0.02 * size * r(),
                        p + Vec3::Y * 0.02 * size * r(),
                    ]
                })
                .chain(extra)
                .collect();
            let flat = FlatBvh::new(&triangles);
            assert_eq!(flat.triangles.len(), triangles.len());
            let grid = Grid::of(&flat.nodes[0]);
            for node in &flat.nodes {
                let [lo, hi] = grid.world(&grid.child(node, 0));
                assert!(lo.cmple(Vec3::from(node.min)).all() && hi.cmpge(Vec3::from(node.max)).all());
            }
        }
    }

    #[test]
    fn nothing_to_hit_gives_no_nodes() {
        assert!(FlatBvh::new(&[]).nodes.is_empty());
        assert!(FlatBvh::new(&[]).pairs().is_empty());
    }
}
