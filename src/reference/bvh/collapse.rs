//! The cost table that decides how a binary BVH collapses into eight-wide
//! CWBVH nodes: obvhs's own (`Bvh2Converter::calculate_cost`, after Ylitie
//! et al. 2017) with the same arithmetic in the same order, so the same
//! decisions bit for bit, in 58 % of its instructions. obvhs's table
//! recurses and indexes every entry with a bounds check; this one visits
//! the nodes children first from a list and keeps each pair of children's
//! seven costs in registers. On 1 M triangles obvhs's table was 0.76 G
//! instructions of the 2.3 G BVH build, this one 0.44 G (callgrind, 1
//! thread).

use obvhs::bvh2::Bvh2;
use obvhs::cwbvh::bvh2_to_cwbvh::{Decision, DecisionKind};

/// Entries per node: a subtree spread over 1 to 7 of a node's 8 slots
/// (entry 0: the subtree as one child, a leaf or an internal node).
const ENTRIES: usize = 7;
/// obvhs's cost of a primitive against a node test.
const PRIM_COST: f32 = 0.3;
/// obvhs's mark of "no split found".
const NONE: u8 = u8::MAX;

/// Fills `decisions` (7 per node of `bvh2`, as obvhs's converter lays them
/// out) as obvhs's `calculate_cost(max_prims_per_leaf)` fills them. Each
/// leaf holds one primitive, as obvhs requires.
pub fn fill(bvh2: &Bvh2, max_prims_per_leaf: u32, decisions: &mut [Decision]) {
    let nodes = &bvh2.nodes;
    // Pre-order; walked backwards, every node comes after its children.
    let mut order = Vec::with_capacity(nodes.len());
    let mut stack = vec![0u32];
    while let Some(i) = stack.pop() {
        order.push(i);
        let node = &nodes[i as usize];
        if !node.is_leaf() {
            stack.extend([node.first_index, node.first_index + 1]);
        }
    }
    let mut primitives = vec![0u32; nodes.len()];
    for &i in order.iter().rev() {
        let (i, node) = (i as usize, &nodes[i as usize]);
        let half_area = node.aabb().half_area();
        if node.is_leaf() {
            primitives[i] = node.prim_count;
            let cost = half_area * node.prim_count as f32 * PRIM_COST;
            decisions[i * ENTRIES..][..ENTRIES].fill(decision(DecisionKind::LEAF, cost, (0, 0)));
            continue;
        }
        let (left, right) = (node.first_index as usize, node.first_index as usize + 1);
        let count = primitives[left] + primitives[right];
        primitives[i] = count;
        let [l, r] = [left, right].map(|c| costs(&decisions[c * ENTRIES..][..ENTRIES]));
        let table = &mut decisions[i * ENTRIES..][..ENTRIES];
        // Entry 0: a leaf of all the subtree's primitives, or an internal
        // node whose 8 slots the two children share (7 + 1 … 1 + 7).
        let (spread, split) = cheapest(&l, &r, ENTRIES, f32::INFINITY);
        let leaf = if count <= max_prims_per_leaf {
            count as f32 * half_area * PRIM_COST
        } else {
            f32::INFINITY
        };
        let internal = spread + half_area;
        table[0] = if leaf < internal {
            decision(DecisionKind::LEAF, leaf, split)
        } else {
            decision(DecisionKind::INTERNAL, internal, split)
        };
        // Entry e ≥ 1: e + 1 slots, shared by the children if that is
        // cheaper, else as entry e − 1.
        for e in 1..ENTRIES {
            let (cost, split) = cheapest(&l, &r, e, table[e - 1].cost);
            table[e] = if split.0 == NONE {
                table[e - 1]
            } else {
                decision(DecisionKind::DISTRIBUTE, cost, split)
            };
        }
    }
}

/// The costs of a node's seven entries.
fn costs(table: &[Decision]) -> [f32; ENTRIES] {
    std::array::from_fn(|e| table[e].cost)
}

/// The least l[k] + r[e − 1 − k] over k < e below `bound` (the first such k
/// on ties, as obvhs), with (k, e − 1 − k); or `bound` and no split.
#[inline(always)]
fn cheapest(l: &[f32; ENTRIES], r: &[f32; ENTRIES], e: usize, bound: f32) -> (f32, (u8, u8)) {
    let mut best = (bound, (NONE, NONE));
    for k in 0..e {
        let cost = l[k] + r[e - 1 - k];
        if cost < best.0 {
            best = (cost, (k as u8, (e - 1 - k) as u8));
        }
    }
    best
}

fn decision(kind: DecisionKind, cost: f32, (left, right): (u8, u8)) -> Decision {
    Decision {
        cost,
        kind,
        distribute_left: left,
        distribute_right: right,
    }
}

#[cfg(test)]
mod tests {
    use super::super::build;
    use super::*;
    use obvhs::BvhBuildParams;
    use obvhs::cwbvh::bvh2_to_cwbvh::Bvh2Converter;

    /// On BVHs of boxes of mixed sizes, each of obvhs's presets and leaf
    /// sizes: every entry equal to obvhs's table, costs bit for bit.
    #[test]
    fn the_table_is_obvhs_s_bit_for_bit() {
        for (n, params) in [
            (1, BvhBuildParams::very_fast_build()),
            (2, BvhBuildParams::fast_build()),
            (3000, BvhBuildParams::very_fast_build()),
            (3000, BvhBuildParams::fast_build()),
        ] {
            let boxes = build::random_boxes(9 + n as u64, n, 0.1);
            let bvh2 = build::binary(&boxes, params);
            for max in 1..=3 {
                let mut theirs = Bvh2Converter::new(&bvh2, false, false);
                theirs.calculate_cost(max);
                let mut ours = Bvh2Converter::new(&bvh2, false, false);
                fill(&bvh2, max, &mut ours.decisions);
                for (i, (a, b)) in theirs.decisions.iter().zip(&ours.decisions).enumerate() {
                    let same = a.cost.to_bits() == b.cost.to_bits()
                        && a.kind == b.kind
                        && a.distribute_left == b.distribute_left
                        && a.distribute_right == b.distribute_right;
                    assert!(same, "{n} boxes, {max} a leaf: entry {i} differs");
                }
            }
        }
    }
}
