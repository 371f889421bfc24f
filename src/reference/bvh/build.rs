//! The BVH build, in parallel on large scenes: obvhs builds on one thread,
//! so the boxes are first split in up to [`GROUPS`] groups by median cuts of
//! their centres, each group becomes a CWBVH of its own on the thread pool,
//! and a new root node takes the groups' roots as its children.
//!
//! The root quantizes its children's boxes outward (in f64: each stored
//! box holds its group's whole box), so every node a ray may need is still
//! entered: the joined BVH is as conservative as one built whole.

use obvhs::BvhBuildParams;
use obvhs::aabb::Aabb;
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::reinsertion::ReinsertionOptimizer;
use obvhs::cwbvh::bvh2_to_cwbvh::{Bvh2Converter, Decision};
use obvhs::cwbvh::{CwBvh, node::CwBvhNode};
use obvhs::ploc::PlocBuilder;
use rayon::prelude::*;

use super::collapse;

/// Boxes per group at least on scenes: fewer boxes are built as one BVH.
/// Groups this small let each thread build several with one warm scratch,
/// each group's arrays nearer the caches. Against 32 k (2 groups on the
/// 110 k-triangle engine, 8 now): the engine's BVH 0.045 → 0.033 s, its
/// process 7–10 % shorter and its render 2–4 %; a 78 k-triangle scene of
/// bumpy spheres BVH −20 %, process −5 %, render +0–4 % (20–30
/// alternated runs each; the same hits, as from any BVH).
pub const MIN_GROUP: usize = 8_192;
/// Groups at most: the children of one CWBVH node.
const GROUPS: usize = 8;
/// Scenes of this many boxes or more take obvhs's very fast build: on 1 M
/// triangles it runs 21 % fewer instructions than the fast build and the
/// packets' walks 0.8 % more (the build is most of that scene's process);
/// on 110 k triangles 26 % fewer, but the walks 5–7 % more (callgrind, 1
/// thread, 16 spp).
pub const VERY_FAST_FROM: usize = 500_000;
/// Largest value of a quantized child coordinate.
const QUANTA: f64 = 255.0;

/// The CWBVH of `boxes`, in groups of `min_group` boxes or more, by
/// obvhs's very fast build from `very_fast_from` boxes: its primitive
/// indices index `boxes`.
pub fn build_cwbvh(boxes: &[Aabb], min_group: usize, very_fast_from: usize) -> CwBvh {
    let very_fast = boxes.len() >= very_fast_from;
    let params = if very_fast {
        BvhBuildParams::very_fast_build()
    } else {
        // Against medium_build: 8 % less build time on 1 M triangles,
        // no slower traversal (rendering within the runs' spread on
        // 110 k and 1 M triangles).
        BvhBuildParams::fast_build()
    };
    let least = 2 * min_group.max(1);
    if boxes.len() < least {
        return Scratch::default().build(boxes, params, !very_fast);
    }
    // Each box's centre beside its index, split in place: each level then
    // reads them in order, where it read each box by index before (the 1 M
    // scene's splits 23 → 15.5 ms, 74 M instructions fewer).
    let mut centred: Vec<Centred> = boxes
        .par_iter()
        .enumerate()
        .map(|(i, b)| (b.center().to_array(), i as u32))
        .collect();
    let mut parts = vec![&mut centred[..]];
    while parts.len() * 2 <= GROUPS && parts.iter().all(|g| g.len() >= least) {
        parts = parts.into_iter().flat_map(halves).collect();
    }
    let groups: Vec<Vec<u32>> = parts
        .iter()
        .map(|part| part.iter().map(|&(_, i)| i).collect())
        .collect();
    // Each thread builds a run of groups with one scratch. On 1 M
    // triangles a thread's first group took 28–100 ms (its ~40 MB of
    // arrays fresh from the kernel), the next ones some 22 ms; with fresh
    // arrays for each group, 27–55 ms.
    let run = groups.len().div_ceil(rayon::current_num_threads());
    let built: Vec<CwBvh> = groups
        .par_chunks(run)
        .flat_map_iter(|run| {
            let largest = run.iter().map(Vec::len).max().unwrap_or(0);
            let (mut scratch, mut group) = (Scratch::for_boxes(largest), Vec::with_capacity(largest));
            run.iter()
                .map(|g| {
                    group.clear();
                    group.extend(g.iter().map(|&i| boxes[i as usize]));
                    scratch.build(&group, params, !very_fast)
                })
                .collect::<Vec<_>>()
        })
        .collect();
    let members: Vec<&[u32]> = groups.iter().map(Vec::as_slice).collect();
    join(&built, &members)
}

/// What one thread's builds reuse from one group to the next: obvhs's
/// builders and binary BVH, and the collapse's cost table.
#[derive(Default)]
struct Scratch {
    ploc: PlocBuilder,
    bvh2: Bvh2,
    reinsertion: ReinsertionOptimizer,
    decisions: Vec<Decision>,
}

impl Scratch {
    /// A scratch whose arrays already hold a group of `boxes` boxes (the
    /// largest of its run). Grown as the groups came, an array that met a
    /// group one box larger than the last (median cuts leave groups a box
    /// apart) doubled, into memory fresh from the kernel, and was copied:
    /// on 1 M triangles 13 % more page faults, the BVH line 4.5–7.5 %
    /// longer (three rounds of 15–30 alternated runs).
    fn for_boxes(boxes: usize) -> Self {
        let nodes = (2 * boxes).saturating_sub(1);
        let mut scratch = Self {
            ploc: PlocBuilder::with_capacity(boxes),
            ..Self::default()
        };
        scratch.bvh2.nodes.reserve_exact(nodes);
        scratch.decisions.reserve_exact(nodes * 7);
        scratch
    }

    /// One BVH of `boxes` by obvhs on this thread: its `build_cwbvh`
    /// (PLOC, reinsertion, the collapse to CWBVH, whose cost table
    /// `collapse::fill` fills), each node's children ordered by the eight
    /// ray octants or not (`ordered`). That order only steers which child
    /// obvhs's traversal (single rays, the shadow packets) visits first;
    /// the primary packets order children by depth themselves. The very
    /// fast build leaves it out: on 1 M triangles it was 16 % of the
    /// build's instructions, and without it the process runs 7.5 % fewer
    /// and the walks 1 % more; on the 110 k-triangle engine the walks ran
    /// 2.4 % more (the shadow walk 5 %) for a build 13 % cheaper
    /// (callgrind, 4 and 16 spp); the same hits either way.
    fn build(&mut self, boxes: &[Aabb], params: BvhBuildParams, ordered: bool) -> CwBvh {
        binary_into(&mut self.ploc, &mut self.bvh2, boxes, params);
        let bvh2 = &mut self.bvh2;
        self.reinsertion.run(bvh2, params.reinsertion_batch_ratio, None);
        if bvh2.nodes.is_empty() {
            return CwBvh::default();
        }
        // obvhs's bvh2_to_cwbvh, with the cost table filled by
        // collapse::fill into this scratch's table: the converter is made
        // on an empty BVH (`new` would allocate and clear a table of its
        // own), then given the BVH, the table and `new`'s reserves.
        let empty = Bvh2::default();
        let mut converter = Bvh2Converter::new(&empty, ordered, false);
        converter.bvh2 = bvh2;
        let primitives = bvh2.primitive_indices.len();
        converter.nodes.reserve(primitives);
        converter.primitive_indices.reserve(primitives);
        // Every entry the conversion reads (those of the nodes under the
        // root) is filled anew: the last group's entries need no clearing.
        let mut decisions = std::mem::take(&mut self.decisions);
        decisions.resize(bvh2.nodes.len() * 7, Decision::default());
        collapse::fill(bvh2, params.max_prims_per_leaf.clamp(1, 3), &mut decisions);
        converter.decisions = decisions;
        converter.convert_to_cwbvh();
        self.decisions = std::mem::take(&mut converter.decisions);
        CwBvh {
            nodes: converter.nodes,
            primitive_indices: converter.primitive_indices,
            total_aabb: *bvh2.nodes[0].aabb(),
            exact_node_aabbs: None,
            uses_spatial_splits: bvh2.uses_spatial_splits,
        }
    }
}

/// obvhs's binary BVH of `boxes` by PLOC, one box a leaf, before
/// reinsertion.
#[cfg(test)]
pub(super) fn binary(boxes: &[Aabb], params: BvhBuildParams) -> Bvh2 {
    let mut bvh2 = Bvh2::default();
    binary_into(&mut PlocBuilder::default(), &mut bvh2, boxes, params);
    bvh2
}

/// obvhs's binary BVH of `boxes` into `bvh2` (PLOC, one box a leaf,
/// before reinsertion), with `ploc`'s arrays.
fn binary_into(ploc: &mut PlocBuilder, bvh2: &mut Bvh2, boxes: &[Aabb], params: BvhBuildParams) {
    ploc.build_with_bvh(
        bvh2,
        params.ploc_search_distance,
        boxes,
        (0..boxes.len() as u32).collect(),
        params.sort_precision,
        params.search_depth_threshold,
    );
}

/// A box's centre and its index among the boxes.
type Centred = ([f32; 3], u32);

/// The group split at the median of its boxes' centres along the axis
/// where those centres spread most.
fn halves(group: &mut [Centred]) -> [&mut [Centred]; 2] {
    let mut bounds = Aabb::empty();
    for &(centre, _) in group.iter() {
        bounds.extend(centre.into());
    }
    let axis = (bounds.max - bounds.min).max_position();
    let middle = group.len() / 2;
    group.select_nth_unstable_by(middle, |a, b| a.0[axis].total_cmp(&b.0[axis]));
    group.split_at_mut(middle).into()
}

/// One CWBVH whose root has the groups' BVHs as its children:
/// `members[g]` lists the indices (into the caller's boxes) of group g's.
fn join(groups: &[CwBvh], members: &[&[u32]]) -> CwBvh {
    let total = groups.iter().fold(Aabb::empty(), |b, g| b.union(&g.total_aabb));
    let mut root = quantizing_root(&total);
    let quantize = Quantizer::of(&root);
    // The groups' roots follow the new root in slots 0…; each group's other
    // nodes and primitives come after all of them, group by group.
    let mut nodes = vec![CwBvhNode::default(); 1 + groups.len()];
    let mut primitive_indices = Vec::with_capacity(members.iter().map(|m| m.len()).sum());
    root.child_base_idx = 1;
    for (slot, (group, member)) in groups.iter().zip(members).enumerate() {
        let (first_node, first_primitive) = (nodes.len() as u32, primitive_indices.len() as u32);
        // A node index k ≥ 1 of the group moves to first_node + k − 1.
        let moved = |mut node: CwBvhNode| {
            node.child_base_idx = (node.child_base_idx + first_node).saturating_sub(1);
            node.primitive_base_idx += first_primitive;
            node
        };
        nodes[1 + slot] = moved(group.nodes[0]);
        nodes.extend(group.nodes[1..].iter().map(|&n| moved(n)));
        primitive_indices.extend(group.primitive_indices.iter().map(|&i| member[i as usize]));
        quantize.child(&mut root, slot, &group.total_aabb);
    }
    nodes[0] = root;
    CwBvh {
        nodes,
        primitive_indices,
        total_aabb: total,
        exact_node_aabbs: None,
        uses_spatial_splits: false,
    }
}

/// A node at the box's low corner with the least power-of-two steps per
/// axis that span it in [`QUANTA`] steps; no children yet.
fn quantizing_root(total: &Aabb) -> CwBvhNode {
    let extent = (total.max - total.min).to_array();
    let e = extent.map(|x| {
        let mut step = (x as f64 / QUANTA).max(1e-20).log2().floor().exp2();
        while step * QUANTA < x as f64 {
            step *= 2.0;
        }
        // A power of two in f32's normal range: its exponent byte.
        ((step as f32).to_bits() >> 23) as u8
    });
    CwBvhNode {
        p: total.min.into(),
        e,
        ..CwBvhNode::default()
    }
}

/// Quantizes child boxes outward onto a node's grid, in f64.
struct Quantizer {
    p: [f64; 3],
    step: [f64; 3],
}

impl Quantizer {
    fn of(node: &CwBvhNode) -> Self {
        Self {
            p: node.p.to_array().map(f64::from),
            step: node.compute_extent().to_array().map(f64::from),
        }
    }

    /// Makes `slot` of `node` an internal child (the next in its child
    /// list) with a box holding `child`.
    fn child(&self, node: &mut CwBvhNode, slot: usize, child: &Aabb) {
        let q = |k: usize, x: f32, up: bool| {
            let steps = (x as f64 - self.p[k]) / self.step[k];
            (if up { steps.ceil() } else { steps.floor() }).clamp(0.0, QUANTA) as u8
        };
        let (lo, hi) = (child.min.to_array(), child.max.to_array());
        node.child_min_x[slot] = q(0, lo[0], false);
        node.child_min_y[slot] = q(1, lo[1], false);
        node.child_min_z[slot] = q(2, lo[2], false);
        node.child_max_x[slot] = q(0, hi[0], true);
        node.child_max_y[slot] = q(1, hi[1], true);
        node.child_max_z[slot] = q(2, hi[2], true);
        node.imask |= 1 << slot;
        // obvhs's layout of an internal child: 001 and 24 + its slot.
        node.child_meta[slot] = 0b0010_0000 | (24 + slot as u8);
    }
}

/// `n` random boxes in [−1, 1]³ (seed `seed`), of sides up to 0.01, or
/// up to 0.25 for a share `large` of them.
#[cfg(test)]
pub(super) fn random_boxes(seed: u64, n: usize, large: f32) -> Vec<Aabb> {
    use glam::Vec3A;
    let mut rng = crate::reference::sampling::Rng::new(seed, 0, 0);
    let mut r = || rng.next_f64() as f32;
    (0..n)
        .map(|_| {
            let lo = Vec3A::new(r(), r(), r()) * 2.0 - 1.0;
            let side = if r() < large { 0.25 } else { 0.01 };
            Aabb::new(lo, lo + Vec3A::new(r(), r(), r()) * side)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// Every box sits once in a leaf, inside its leaf's box (to obvhs's own
    /// f32 rounding) and inside the root's stored box of its group, exactly
    /// (in f64: quantized outward).
    #[test]
    fn a_joined_bvh_holds_every_box_once_inside_its_group() {
        let boxes = random_boxes(5, 5000, 0.0);
        let bvh = build_cwbvh(&boxes, 1000, VERY_FAST_FROM);
        assert_eq!(bvh.nodes[0].imask, 0b1111, "four groups");
        let mut seen = vec![0; boxes.len()];
        // (node, the root's box of its group)
        let mut stack: Vec<(usize, Option<[DVec3; 2]>)> = vec![(0, None)];
        while let Some((index, group)) = stack.pop() {
            let node = &bvh.nodes[index];
            let mut next_internal = node.child_base_idx as usize;
            for slot in (0..8).filter(|&s| !node.is_child_empty(s)) {
                if node.imask & (1 << slot) != 0 {
                    stack.push((next_internal, group.or_else(|| Some(stored(node, slot)))));
                    next_internal += 1;
                    continue;
                }
                let leaf = node.child_aabb(slot);
                let (first, count) = node.child_primitives(slot);
                for p in first..first + count {
                    let i = bvh.primitive_indices[p as usize] as usize;
                    seen[i] += 1;
                    let (lo, hi) = (boxes[i].min, boxes[i].max);
                    assert!(
                        lo.cmpge(leaf.min - 1e-6).all() && hi.cmple(leaf.max + 1e-6).all(),
                        "box {i} outside its leaf"
                    );
                    let [glo, ghi] = group.expect("under the root");
                    assert!(
                        lo.as_dvec3().cmpge(glo).all() && hi.as_dvec3().cmple(ghi).all(),
                        "box {i} outside its group"
                    );
                }
            }
        }
        assert!(seen.iter().all(|&s| s == 1));
    }

    /// A child's stored box p + e·q, in f64.
    fn stored(node: &CwBvhNode, slot: usize) -> [DVec3; 2] {
        let (p, e) = (node.p.as_dvec3(), node.compute_extent().as_dvec3());
        let q = |c: [&[u8; 8]; 3]| DVec3::from(c.map(|x| f64::from(x[slot])));
        [
            p + e * q([&node.child_min_x, &node.child_min_y, &node.child_min_z]),
            p + e * q([&node.child_max_x, &node.child_max_y, &node.child_max_z]),
        ]
    }
}
