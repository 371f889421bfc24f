//! The shadow casters as a BVH for the GPU ray tracer (`shaders/bvh.wgsl`):
//! a binary BVH built on the CPU by `obvhs` (PLOC, then reinsertion), flattened
//! into two storage buffers. Rebuilt with the scene buffers whenever the
//! geometry changes (`GpuScene::new`).
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

/// `BvhNode` of shaders/bvh.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct BvhNodeRaw {
    pub min: [f32; 3],
    /// Triangles in this leaf; 0: an inner node.
    pub count: u32,
    pub max: [f32; 3],
    /// Inner node: index of the first child; leaf: of the first triangle.
    pub first: u32,
}

/// `BvhPair` of shaders/bvh.wgsl: an inner node's two children, each a box
/// and its link (a [`BvhNodeRaw`] whose inner `first` is the child's pair).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct BvhPairRaw {
    pub children: [BvhNodeRaw; 2],
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
        let triangles: Vec<[Vec3; 3]> = scene
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
            .collect();
        Self::new(&triangles)
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
        let params = BvhBuildParams {
            max_prims_per_leaf: MAX_TRIANGLES_PER_LEAF,
            ..BvhBuildParams::fast_build()
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
    /// root's first), each with its children's boxes and links, an inner
    /// child's `first` the index of its entry. A root that is a leaf gets
    /// one entry whose children are both that leaf. Empty when `nodes` is.
    pub fn pairs(&self) -> Vec<BvhPairRaw> {
        let Some(&root) = self.nodes.first() else {
            return Vec::new();
        };
        if root.count > 0 {
            let leaf = BvhNodeRaw {
                first: leaf_link(root),
                ..root
            };
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
                        BvhNodeRaw {
                            first: if child.count > 0 {
                                leaf_link(child)
                            } else {
                                entry[c]
                            },
                            ..child
                        }
                    }),
                }
            })
            .collect()
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

        // The uploaded pairs reach every triangle once, through the same boxes.
        let pairs = flat.pairs();
        assert_eq!(pairs.len(), flat.nodes.iter().filter(|n| n.count == 0).count());
        let mut seen = vec![0; 200];
        let mut stack = vec![0];
        while let Some(p) = stack.pop() {
            for child in pairs[p].children {
                assert!(
                    flat.nodes
                        .iter()
                        .any(|n| (n.min, n.max) == (child.min, child.max))
                );
                if child.count == 0 {
                    stack.push(child.first as usize);
                } else {
                    assert_eq!(child.first >> 28, 8 | child.count, "a leaf's link");
                    let first = child.first & 0x0fff_ffff;
                    (first..first + child.count).for_each(|t| seen[t as usize] += 1);
                }
            }
        }
        assert!(seen.iter().all(|&n| n == 1));
    }

    #[test]
    fn a_root_leaf_is_one_pair_of_itself() {
        let flat = FlatBvh::new(&[[Vec3::ZERO, Vec3::X, Vec3::Y]]);
        let leaf = BvhNodeRaw {
            first: 1 << 31 | 1 << 28,
            ..flat.nodes[0]
        };
        assert_eq!(flat.pairs(), vec![BvhPairRaw { children: [leaf; 2] }]);
    }

    #[test]
    fn nothing_to_hit_gives_no_nodes() {
        assert!(FlatBvh::new(&[]).nodes.is_empty());
        assert!(FlatBvh::new(&[]).pairs().is_empty());
    }
}
