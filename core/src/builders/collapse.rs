//! Leaf collapse: turning small subtrees of a one-primitive-per-leaf tree
//! into leaves where the SAH says a leaf is cheaper.
//!
//! Lecture: *stopping criteria* and the cost function. Bottom-up merging and
//! insertion put every primitive in a leaf of its own, so the tree has
//! `2n - 1` nodes and a query visits an inner node for every pair of
//! primitives it tests. Top-down builders stop at a few primitives per leaf;
//! a bottom-up tree can get the same benefit afterwards. With the cost
//! function's weights `C_t` for visiting a node and `C_i` for testing a
//! primitive (here `C_i = 1`), a subtree of `k` primitives whose volume has
//! area `A` costs `k * A` as one leaf (each primitive tested whenever the
//! volume is hit) and `C_t * A + cost(left) + cost(right)` as it is. Taking
//! the cheaper of the two at every node, from the leaves up, gives the cut
//! of the tree with the lowest SAH cost among those whose leaves hold at
//! most `max_leaf_size` primitives: the decision at a node only needs its
//! children's best costs.

use crate::bv::BoundingVolume;
use crate::tree::{Node, MAX_DEPTH};
use crate::Error;

/// What a bottom-up or insertion build does with its one-primitive leaves.
///
/// ```
/// use bvhkit::builders::{BottomUp, BottomUpScratch, Cluster, Collapse};
/// use bvhkit::{Aabb, Node, Triangle};
/// use glam::Vec3;
/// let tris: Vec<Triangle> = (0..400).map(|i| {
///     let o = Vec3::new((i % 20) as f32, (i / 20) as f32, 0.0);
///     Triangle::new(o, o + Vec3::X * 0.8, o + Vec3::Y * 0.8)
/// }).collect();
/// let (nc, nw, nk) = BottomUp::scratch_len(tris.len());
/// let mut clusters = vec![Cluster::<Aabb>::EMPTY; nc];
/// let (mut work, mut keys) = (vec![0u32; nw], vec![0u64; nk]);
/// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(tris.len())];
/// let mut idx = vec![0u32; tris.len()];
/// let mut sah = |collapse| {
///     let mut scratch = BottomUpScratch { clusters: &mut clusters, work: &mut work, keys: &mut keys };
///     let bvh = BottomUp { collapse, ..BottomUp::default() }
///         .build(&tris, &mut nodes, &mut idx, &mut scratch)?;
///     Ok::<_, bvhkit::Error>((bvh.node_count(), bvh.stats().sah_cost))
/// };
/// let (one_each, one_each_sah) = sah(Collapse::None)?;
/// // Weighing a node visit like a primitive test minimises the SAH cost.
/// let (fewer, lowest_sah) = sah(Collapse::Sah { max_leaf_size: 4, traversal_cost: 1.0 })?;
/// assert_eq!(one_each, 2 * 400 - 1);
/// assert!(fewer <= one_each && lowest_sah <= one_each_sah);
/// // Pricier visits make larger leaves.
/// let (larger_leaves, _) = sah(Collapse::Sah { max_leaf_size: 4, traversal_cost: 3.0 })?;
/// assert!(larger_leaves < fewer);
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Collapse {
    /// Keep one primitive per leaf: the tree exactly as the merges or
    /// insertions made it (what the lectures' algorithms describe).
    None,
    /// Make a subtree of at most `max_leaf_size` primitives one leaf where
    /// that lowers the SAH cost with a node visit weighing `traversal_cost`
    /// primitive tests. The default is 4 and 3: leaves of the top-down
    /// builders' size, and the weight whose pair queries were fastest
    /// (`collapse_sweep` example, recorded in the book's bottom-up chapter).
    Sah {
        /// The largest leaf (at least 1; 1 is the same as [`Collapse::None`]).
        max_leaf_size: u32,
        /// `C_t / C_i`: what a node visit costs against a primitive test.
        /// 1 minimises the SAH cost [`TreeStats`](crate::TreeStats) reports;
        /// larger values make larger leaves.
        traversal_cost: f32,
    },
}

impl Default for Collapse {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl Collapse {
    /// [`Collapse::default`], for `const` contexts.
    pub const DEFAULT: Self = Collapse::Sah {
        max_leaf_size: 4,
        traversal_cost: 3.0,
    };

    /// The largest leaf this allows.
    pub const fn max_leaf_size(self) -> u32 {
        match self {
            Collapse::None => 1,
            Collapse::Sah { max_leaf_size, .. } => {
                if max_leaf_size == 0 {
                    1
                } else {
                    max_leaf_size
                }
            }
        }
    }

    /// Applies the collapse to `nodes[..count]`, a tree of depth `depth`
    /// written by `emit_layout` (depth first, left before right, children
    /// adjacent, one primitive per leaf): returns the new node count, the
    /// new depth and how many subtrees became leaves. Nothing is allocated: the first pass
    /// keeps the pending subtrees' costs on a stack of at most
    /// [`MAX_DEPTH`] levels, the second moves the nodes forward in place.
    pub(crate) fn apply<B: BoundingVolume>(
        self,
        nodes: &mut [Node<B>],
        count: usize,
        depth: u32,
    ) -> Result<Collapsed, Error> {
        let max = self.max_leaf_size();
        let traversal_cost = match self {
            // A NaN or negative weight would make no sense as a price:
            // nodes cost at least nothing.
            Collapse::Sah { traversal_cost, .. } if traversal_cost >= 0.0 => traversal_cost,
            _ => 0.0,
        };
        let collapsed = if max > 1 && count > 1 {
            choose_leaves(&mut nodes[..count], max, traversal_cost.min(f32::MAX))?
        } else {
            0
        };
        let (count, depth) = if collapsed > 0 {
            compact(nodes)?
        } else {
            (count, depth)
        };
        Ok(Collapsed {
            count,
            depth,
            collapsed,
        })
    }
}

/// What [`Collapse::apply`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Collapsed {
    /// Nodes in the tree now (at the front of the buffer).
    pub count: usize,
    /// Its depth.
    pub depth: u32,
    /// Inner nodes priced cheaper as leaves, nested ones included (0: the
    /// tree is unchanged).
    pub collapsed: u32,
}

fn too_deep() -> Error {
    Error::StackOverflow {
        depth: MAX_DEPTH + 1,
        capacity: MAX_DEPTH,
    }
}

/// First pass, post-order: at every inner node, the cheaper of keeping it
/// and making its subtree one leaf (rewritten in place: `first` becomes the
/// subtree's run in the index array). Returns how many nodes became leaves.
fn choose_leaves<B: BoundingVolume>(
    nodes: &mut [Node<B>],
    max: u32,
    traversal_cost: f32,
) -> Result<u32, Error> {
    // Areas in units of the root's size, so that costs neither overflow nor
    // vanish whatever the scene's scale.
    let extent = nodes[0].bv.aabb().extent().max_element();
    let scale = if extent > 0.0 && (1.0 / extent).is_finite() {
        1.0 / extent
    } else {
        1.0
    };
    // A finished subtree: its run in the index array (`first`, `count`)
    // and its best cost.
    #[derive(Clone, Copy)]
    struct Done {
        first: u32,
        count: u32,
        cost: f32,
    }
    // Slots to visit (with whether their children are done), and finished
    // subtrees waiting for their sibling: one per level at most, plus the
    // pair being combined.
    let mut todo = [(0u32, false); 2 * MAX_DEPTH + 2];
    let mut done = [Done {
        first: 0,
        count: 0,
        cost: 0.0,
    }; MAX_DEPTH + 2];
    let (mut top, mut ready, mut collapsed) = (1usize, 0usize, 0u32);
    while top > 0 {
        top -= 1;
        let (slot, children_done) = todo[top];
        let node = nodes[slot as usize];
        let area = node.bv.cost_area_scaled(scale);
        let result = if node.count > 0 {
            Done {
                first: node.first,
                count: node.count,
                cost: node.count as f32 * area,
            }
        } else if !children_done {
            let entries = [(slot, true), (node.first + 1, false), (node.first, false)];
            for entry in entries {
                *todo.get_mut(top).ok_or_else(too_deep)? = entry;
                top += 1;
            }
            continue;
        } else {
            let (l, r) = (done[ready - 2], done[ready - 1]);
            ready -= 2;
            let count = l.count + r.count;
            let inner = traversal_cost * area + l.cost + r.cost;
            let leaf = count as f32 * area;
            // Only a run of the index array can be a leaf; the emitted
            // layout always gives one (left's primitives, then right's).
            if count <= max && leaf <= inner && l.first + l.count == r.first {
                nodes[slot as usize] = Node {
                    bv: node.bv,
                    first: l.first,
                    count,
                };
                collapsed += 1;
                Done {
                    first: l.first,
                    count,
                    cost: leaf,
                }
            } else {
                Done {
                    first: l.first.min(r.first),
                    count,
                    cost: inner,
                }
            }
        };
        *done.get_mut(ready).ok_or_else(too_deep)? = result;
        ready += 1;
    }
    // Inner nodes above a collapsed one may now have leaf children only;
    // they were priced with their children's best costs, so the cut is
    // optimal as it stands.
    Ok(collapsed)
}

/// Second pass: rewrites the surviving nodes depth first, children
/// adjacent, without the subtrees under the new leaves. The new slots are
/// handed out in the order the emission handed out the old ones, skipping
/// the removed pairs, so a pair moves only to a slot whose old pair was
/// already moved (or removed): the nodes move forward in place.
fn compact<B: BoundingVolume>(nodes: &mut [Node<B>]) -> Result<(usize, u32), Error> {
    let mut stack = [(0u32, 0u32); MAX_DEPTH + 2];
    let (mut top, mut next, mut depth) = (1usize, 1u32, 0u32);
    while top > 0 {
        top -= 1;
        let (slot, d) = stack[top];
        depth = depth.max(d);
        let node = nodes[slot as usize];
        if node.count > 0 {
            continue;
        }
        let old = node.first as usize;
        let (left, right) = (nodes[old], nodes[old + 1]);
        nodes[slot as usize].first = next;
        nodes[next as usize] = left;
        nodes[next as usize + 1] = right;
        for entry in [(next + 1, d + 1), (next, d + 1)] {
            *stack.get_mut(top).ok_or_else(too_deep)? = entry;
            top += 1;
        }
        next += 2;
    }
    Ok((next as usize, depth))
}

#[cfg(test)]
/// The depth of a tree, for the tests.
fn tree_depth<B: BoundingVolume>(nodes: &[Node<B>]) -> Result<u32, Error> {
    if nodes.is_empty() {
        return Ok(0);
    }
    let mut stack = [(0u32, 0u32); MAX_DEPTH + 2];
    let (mut top, mut depth) = (1usize, 0u32);
    while top > 0 {
        top -= 1;
        let (slot, d) = stack[top];
        depth = depth.max(d);
        let node = nodes[slot as usize];
        if node.count == 0 {
            for entry in [(node.first + 1, d + 1), (node.first, d + 1)] {
                *stack.get_mut(top).ok_or_else(too_deep)? = entry;
                top += 1;
            }
        }
    }
    Ok(depth)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bv::Aabb;
    use glam::Vec3;

    /// Emits a balanced 1/leaf tree over boxes the way `emit_layout` does.
    fn emit(boxes: &[Aabb], nodes: &mut [Node<Aabb>]) -> usize {
        // Recursive halves over `lo..hi`, slots handed out at each pop.
        let mut stack = [(0usize, 0usize, 0u32); 64];
        stack[0] = (0, boxes.len(), 0);
        let (mut top, mut next) = (1, 1u32);
        while top > 0 {
            top -= 1;
            let (lo, hi, slot) = stack[top];
            let bv = boxes[lo..hi].iter().fold(Aabb::EMPTY, |b, x| b.union(x));
            if hi - lo == 1 {
                nodes[slot as usize] = Node {
                    bv,
                    first: lo as u32,
                    count: 1,
                };
                continue;
            }
            let mid = (lo + hi) / 2;
            nodes[slot as usize] = Node {
                bv,
                first: next,
                count: 0,
            };
            stack[top] = (mid, hi, next + 1);
            stack[top + 1] = (lo, mid, next);
            top += 2;
            next += 2;
        }
        next as usize
    }

    /// Nodes priced like primitives: the SAH cost `TreeStats` reports.
    const SAH_1: Collapse = Collapse::Sah {
        max_leaf_size: 4,
        traversal_cost: 1.0,
    };

    fn depth_of(nodes: &[Node<Aabb>], count: usize) -> u32 {
        tree_depth(&nodes[..count]).unwrap()
    }

    fn unit(x: f32) -> Aabb {
        Aabb::new(Vec3::new(x, 0.0, 0.0), Vec3::new(x + 1.0, 1.0, 1.0))
    }

    /// Every primitive reached exactly once, leaves within the limit, each
    /// node's box containing its children's. Returns the leaf count and the
    /// SAH cost (`C_t = C_i = 1`, areas as measured by the pass).
    fn check(nodes: &[Node<Aabb>], count: usize, n: u32, max: u32, ct: f32) -> (usize, f32) {
        let scale = 1.0 / nodes[0].bv.extent().max_element();
        let mut seen = [false; 64];
        let mut stack = [0u32; 128];
        let (mut top, mut reached, mut leaves, mut sah) = (1, 0, 0, 0.0);
        while top > 0 {
            top -= 1;
            let node = nodes[stack[top] as usize];
            reached += 1;
            let area = node.bv.cost_area_scaled(scale);
            if node.count > 0 {
                assert!(node.count <= max);
                leaves += 1;
                sah += node.count as f32 * area;
                for i in node.first..node.first + node.count {
                    assert!(!seen[i as usize]);
                    seen[i as usize] = true;
                }
            } else {
                sah += ct * area;
                assert!((node.first as usize) + 1 < count);
                for c in [node.first, node.first + 1] {
                    assert!(node.bv.contains(&nodes[c as usize].bv));
                    stack[top] = c;
                    top += 1;
                }
            }
        }
        assert_eq!(reached, count);
        assert_eq!(count, 2 * leaves - 1);
        assert!(seen[..n as usize].iter().all(|&s| s));
        assert!(seen[n as usize..].iter().all(|&s| !s));
        (leaves, sah)
    }

    /// The reference: the best cut's cost by plain recursion over the
    /// original tree, `(cost, primitives)`.
    fn best(nodes: &[Node<Aabb>], slot: u32, max: u32, ct: f32, scale: f32) -> (f32, u32) {
        let node = nodes[slot as usize];
        let area = node.bv.cost_area_scaled(scale);
        if node.count > 0 {
            return (node.count as f32 * area, node.count);
        }
        let (lc, ln) = best(nodes, node.first, max, ct, scale);
        let (rc, rn) = best(nodes, node.first + 1, max, ct, scale);
        let n = ln + rn;
        let keep = ct * area + lc + rc;
        if n <= max {
            ((n as f32 * area).min(keep), n)
        } else {
            (keep, n)
        }
    }

    #[test]
    fn a_tight_cluster_becomes_one_leaf_and_far_clusters_stay_apart() {
        // Four unit boxes staggered by 0.1, then four more a long way off:
        // each cluster is one leaf (4 * 3.6 against 3.6 + 2 * 2 * 3.2 in
        // half areas), the root stays an inner node (8 > 4 anyway). Four
        // boxes side by side would not be: 4 * 9 > 9 + 2 * 2 * 5.
        let boxes: [Aabb; 8] = core::array::from_fn(|i| {
            let x = (i % 4) as f32 * 0.1;
            unit(if i < 4 { x } else { 1000.0 + x })
        });
        let mut nodes = [Node::<Aabb>::EMPTY; 15];
        let count = emit(&boxes, &mut nodes);
        let depth = depth_of(&nodes, count);
        let done = SAH_1.apply(&mut nodes, count, depth).unwrap();
        // Six nodes were cheaper as leaves: both clusters and, before them,
        // their halves.
        assert_eq!((done.count, done.depth, done.collapsed), (3, 1, 6));
        assert_eq!((nodes[1].first, nodes[1].count), (0, 4));
        assert_eq!((nodes[2].first, nodes[2].count), (4, 4));
        check(&nodes, done.count, 8, 4, 1.0);
    }

    #[test]
    fn spread_out_primitives_keep_their_own_leaves() {
        // Two unit boxes 100 apart: one leaf would cost 2 * A(101 long),
        // two leaves A(101) + 2 * A(unit): the tree stays as it is.
        let boxes = [unit(0.0), unit(100.0)];
        let mut nodes = [Node::<Aabb>::EMPTY; 3];
        let count = emit(&boxes, &mut nodes);
        let depth = depth_of(&nodes, count);
        let done = SAH_1.apply(&mut nodes, count, depth).unwrap();
        assert_eq!((done.count, done.depth, done.collapsed), (3, 1, 0));
    }

    /// The deepest trees the builders make collapse too: a chain (every
    /// inner node a leaf on the left and the rest of the chain on the
    /// right) 63 levels deep keeps a finished left leaf waiting at every
    /// level, the most the pass's stack of pending costs ever holds, and it
    /// neither overflows nor errs.
    #[test]
    fn a_chain_as_deep_as_the_builders_go_collapses() {
        const N: usize = 64;
        let mut nodes = [Node::<Aabb>::EMPTY; 2 * N - 1];
        // Leaf j in slot 2j - 1 (slot 0 for none), inner node j in slot 2j:
        // children adjacent, left (the leaf) before right.
        // Spread out but for the last four, which share a box: those make
        // one leaf, the rest keep theirs.
        let boxes: [Aabb; N] = core::array::from_fn(|j| unit(1.5f32.powi(j.min(N - 4) as i32)));
        for j in (0..N - 1).rev() {
            let right = if j == N - 2 {
                Node {
                    bv: boxes[N - 1],
                    first: (N - 1) as u32,
                    count: 1,
                }
            } else {
                nodes[2 * j + 2]
            };
            nodes[2 * j + 1] = Node {
                bv: boxes[j],
                first: j as u32,
                count: 1,
            };
            nodes[2 * j + 2] = right;
            nodes[2 * j] = Node {
                bv: boxes[j].union(&right.bv),
                first: (2 * j + 1) as u32,
                count: 0,
            };
        }
        let count = 2 * N - 1;
        assert_eq!(depth_of(&nodes, count), (N - 1) as u32);
        let sah = Collapse::Sah {
            max_leaf_size: 4,
            traversal_cost: 1.0,
        };
        let done = sah.apply(&mut nodes, count, (N - 1) as u32).unwrap();
        let (leaves, _) = check(&nodes, done.count, N as u32, 4, 1.0);
        assert_eq!((done.collapsed, leaves), (3, N - 3), "{done:?}");
    }

    #[test]
    fn none_and_a_limit_of_one_change_nothing() {
        let boxes: [Aabb; 8] = core::array::from_fn(|i| unit(i as f32));
        let one = Collapse::Sah {
            max_leaf_size: 1,
            traversal_cost: 1.0,
        };
        for collapse in [Collapse::None, one] {
            let mut nodes = [Node::<Aabb>::EMPTY; 15];
            let count = emit(&boxes, &mut nodes);
            let before = nodes;
            let depth = depth_of(&nodes, count);
            let done = collapse.apply(&mut nodes, count, depth).unwrap();
            assert_eq!((done.count, done.depth, done.collapsed), (15, 3, 0));
            assert_eq!(nodes, before);
        }
    }

    #[test]
    fn the_cut_is_the_cheapest_and_compacts_in_place_to_a_valid_tree() {
        // Sizes 1 to 40, boxes in clusters of three with gaps, every limit
        // and three node weights: the compacted tree reaches each primitive
        // once, within the limit, with nested boxes, and costs what the best
        // cut of the original tree costs (plain recursion).
        let boxes: [Aabb; 40] =
            core::array::from_fn(|i| unit((i / 3) as f32 * 7.0 + (i % 3) as f32 * 0.5));
        let mut some_collapsed = false;
        for n in 1..=40usize {
            for max in 1..=9u32 {
                for ct in [0.0, 1.0, 3.0] {
                    let mut nodes = [Node::<Aabb>::EMPTY; 79];
                    let count = emit(&boxes[..n], &mut nodes);
                    let scale = 1.0 / nodes[0].bv.extent().max_element();
                    let (reference, _) = best(&nodes, 0, max, ct, scale);
                    let depth = depth_of(&nodes, count);
                    let collapse = Collapse::Sah {
                        max_leaf_size: max,
                        traversal_cost: ct,
                    };
                    let done = collapse.apply(&mut nodes, count, depth).unwrap();
                    let (leaves, sah) = check(&nodes, done.count, n as u32, max, ct);
                    assert!(
                        (sah - reference).abs() <= 1e-4 * reference,
                        "n {n} max {max} ct {ct}: {sah} against {reference}"
                    );
                    assert_eq!(done.depth, depth_of(&nodes, done.count));
                    assert!(max > 1 || leaves == n);
                    some_collapsed |= done.collapsed > 0;
                }
            }
        }
        assert!(some_collapsed);
    }
}
