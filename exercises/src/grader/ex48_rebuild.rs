//! Exercise 48: rebuilding a dynamic tree's internal nodes in place. The
//! checks, and the plausible wrong answers they must reject.
//!
//! Every storage is left by a real [`DynamicTree`] after a run of inserts,
//! moves and removals (so its free list and generations are a real tree's).
//! The answer is checked structurally against the statement, and the
//! reference is held to the library: on every case its storage equals what
//! [`DynamicTree::rebuild`] leaves, node for node.

use super::common::*;
use bvhkit::builders::{DynNode, DynamicConfig, DynamicTree, Rotations, NULL};
use bvhkit::Hierarchy;

/// The checks of exercise 48.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 48,
            name: "random dynamic trees (boxes of very different sizes): every leaf kept, links, \
                   boxes, heights and generations right, the median split at every node",
            points: 3,
            run: |e| rebuilds(e, &random_cases()),
        },
        Check {
            exercise: 48,
            name: "ties: many equal centres (ordered by node index), centres on one plane, a \
                   box of centres with equal sides",
            points: 2,
            run: |e| rebuilds(e, &tie_cases()),
        },
        Check {
            exercise: 48,
            name: "one leaf, two leaves and three: the smallest trees",
            points: 1,
            run: |e| rebuilds(e, &small_cases()),
        },
        Check {
            exercise: 48,
            name: "an empty tree: nothing changes, (NULL, free) returned, no panic",
            points: 1,
            run: |e| rebuilds(e, &[case_of(&[], 1, 0)]),
        },
    ]
}

/// A dynamic tree's storage, root and free-list head, named for messages.
struct Case {
    storage: Vec<DynNode<Aabb>>,
    /// The storage after `DynamicTree::rebuild` on the same tree.
    library: Vec<DynNode<Aabb>>,
    root: u32,
    free: u32,
    leaves: usize,
    what: String,
}

/// The tree left by inserting `boxes` (without rotations, so the tree is
/// the insertion order's), then moving and removing some, by `seed`.
fn case_of(boxes: &[Aabb], seed: u64, churn: usize) -> Case {
    let (storage, root, leaves) = history(boxes, seed, churn, false);
    let (library, ..) = history(boxes, seed, churn, true);
    let free = free_head(&storage);
    Case {
        storage,
        library,
        root,
        free,
        leaves,
        what: format!(
            "{} leaves (seed {seed}, {churn} moves and removals)",
            leaves
        ),
    }
}

/// Runs the history of [`case_of`] (deterministic) and returns the storage,
/// the root and the number of leaves; with `rebuild`, the library's
/// rebuild runs last.
fn history(
    boxes: &[Aabb],
    seed: u64,
    churn: usize,
    rebuild: bool,
) -> (Vec<DynNode<Aabb>>, u32, usize) {
    let mut storage = vec![DynNode::<Aabb>::EMPTY; bvhkit::max_nodes(boxes.len().max(1)) + 4];
    let config = DynamicConfig {
        rotations: Rotations::Off,
        margin: 0.0,
        ..DynamicConfig::default()
    };
    let mut r = Rng(seed.max(1));
    let (root, leaves) = {
        let mut tree = DynamicTree::new(&mut storage, config).expect("fits");
        let mut live = Vec::new();
        for (i, b) in boxes.iter().enumerate() {
            live.push(tree.insert(i as u32, b).expect("fits"));
        }
        for _ in 0..churn {
            if live.len() < 2 {
                break;
            }
            let k = ((r.next() * live.len() as f32) as usize).min(live.len() - 1);
            if r.next() < 0.3 {
                tree.remove(live.swap_remove(k)).expect("live");
            } else {
                let o = r.point(20.0, Vec3::ZERO);
                let _ = tree.update(live[k], &Aabb::new(o, o + r.next() * 3.0));
            }
        }
        let root = if tree.is_empty() {
            NULL
        } else {
            Hierarchy::root(&tree)
        };
        if rebuild {
            let mut scratch = vec![0u32; tree.len()];
            tree.rebuild(&mut scratch).expect("room");
        }
        (root, tree.len())
    };
    (storage, root, leaves)
}

/// The head of the free list: the free node no other free node points to.
fn free_head(storage: &[DynNode<Aabb>]) -> u32 {
    let free: Vec<u32> = (0..storage.len() as u32)
        .filter(|&i| storage[i as usize].height == u32::MAX)
        .collect();
    free.iter()
        .copied()
        .find(|&i| !free.iter().any(|&j| storage[j as usize].parent == i))
        .unwrap_or(NULL)
}

fn random_cases() -> Vec<Case> {
    let mut r = Rng(0x48);
    [5usize, 9, 30, 100, 200]
        .iter()
        .enumerate()
        .map(|(k, &n)| {
            let boxes: Vec<Aabb> = (0..n)
                .map(|i| {
                    let o = r.point(40.0, Vec3::ZERO);
                    // Mostly small boxes, every seventh huge: the box of the
                    // centres and the box of the boxes point different ways.
                    let size = if i % 7 == 3 { 60.0 } else { 0.05 + r.next() };
                    Aabb::new(o, o + Vec3::new(size, size * 0.3, size * 0.1))
                })
                .collect();
            case_of(&boxes, 11 + k as u64, n)
        })
        .collect()
}

fn tie_cases() -> Vec<Case> {
    let unit = |o: Vec3| Aabb::new(o, o + 1.0);
    // 64 boxes over 4 centres: the median falls among equal centres.
    let equal: Vec<Aabb> = (0..64).map(|i| unit(Vec3::X * (i % 4) as f32)).collect();
    // Centres on the plane z = 0, spread on x and y.
    let plane: Vec<Aabb> = (0..40)
        .map(|i| unit(Vec3::new((i % 8) as f32 * 2.0, (i / 8) as f32 * 3.0, 0.0)))
        .collect();
    // A cube of centres: every side equally long (x wins).
    let cube: Vec<Aabb> = (0..27)
        .map(|i| {
            unit(Vec3::new(
                (i % 3) as f32,
                (i / 3 % 3) as f32,
                (i / 9) as f32,
            ))
        })
        .collect();
    vec![
        case_of(&equal, 5, 20),
        case_of(&equal, 6, 0),
        case_of(&plane, 7, 0),
        case_of(&cube, 8, 0),
    ]
}

fn small_cases() -> Vec<Case> {
    let boxes = [
        b([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]),
        b([5.0, 0.0, 0.0], [6.0, 1.0, 1.0]),
        b([2.0, 4.0, 0.0], [3.0, 5.0, 1.0]),
    ];
    (1..=3).map(|n| case_of(&boxes[..n], n as u64, 0)).collect()
}

fn rebuilds(e: &dyn Exercises, cases: &[Case]) -> bool {
    cases.iter().all(|c| {
        // The reference against the library, node for node.
        let mut by_reference = c.storage.clone();
        let mut scratch = vec![0u32; c.leaves];
        let want = Reference.rebuild_dynamic(&mut by_reference, c.root, c.free, &mut scratch);
        if by_reference != c.library {
            return fail(format!(
                "the reference and DynamicTree::rebuild differ on {} (a grader bug)",
                c.what
            ));
        }
        if let Err(why) = verify(c, &by_reference, want) {
            return fail(format!(
                "the reference fails on {}: {why} (a grader bug)",
                c.what
            ));
        }
        let mut got_storage = c.storage.clone();
        let mut scratch = vec![0u32; c.leaves];
        let got = e.rebuild_dynamic(&mut got_storage, c.root, c.free, &mut scratch);
        verify(c, &got_storage, got)
            .map_or_else(|why| fail(format!("on {}: {why}", c.what)), |()| true)
    })
}

/// A check of one internal node, given its left and right leaves.
type NodeCheck<'a> = dyn FnMut(u32, &[u32], &[u32]) -> Result<(), String> + 'a;

/// Whether `after` and `returned` are the rebuild the statement asks of
/// `c`'s storage.
fn verify(c: &Case, after: &[DynNode<Aabb>], returned: (u32, u32)) -> Result<(), String> {
    let before = &c.storage;
    if after.len() != before.len() {
        return Err("the storage changed length".into());
    }
    if c.root == NULL {
        return if returned == (NULL, c.free) && after == &before[..] {
            Ok(())
        } else {
            Err(format!(
                "an empty tree must stay as it is and return (NULL, {})",
                c.free
            ))
        };
    }
    let (root, free) = returned;
    let was_leaf = |i: u32| before[i as usize].height == 0 && before[i as usize].left == NULL;
    let was_internal = |i: u32| before[i as usize].height != u32::MAX && !was_leaf(i);
    let get = |i: u32| {
        after
            .get(i as usize)
            .ok_or(format!("node {i} is past the storage"))
    };
    if get(root)?.parent != NULL {
        return Err(format!(
            "the root {root} has parent {}, not NULL",
            get(root)?.parent
        ));
    }
    let mut in_tree = vec![false; after.len()];
    // Post-order walk returning each subtree's leaves.
    fn walk(
        i: u32,
        after: &[DynNode<Aabb>],
        in_tree: &mut [bool],
        check: &mut NodeCheck,
        depth: usize,
    ) -> Result<Vec<u32>, String> {
        let n = after
            .get(i as usize)
            .ok_or(format!("node {i} is past the storage"))?;
        if depth > 200 || in_tree[i as usize] {
            return Err(format!(
                "node {i} is reached twice (a cycle or a shared child)"
            ));
        }
        in_tree[i as usize] = true;
        if n.left == NULL {
            return Ok(vec![i]);
        }
        for child in [n.left, n.right] {
            let c = after
                .get(child as usize)
                .ok_or(format!("child {child} is past the storage"))?;
            if c.parent != i {
                return Err(format!("node {child}'s parent is {}, not {i}", c.parent));
            }
        }
        let l = walk(n.left, after, in_tree, check, depth + 1)?;
        let r = walk(n.right, after, in_tree, check, depth + 1)?;
        check(i, &l, &r)?;
        Ok([l, r].concat())
    }
    let mut check = |i: u32, l: &[u32], r: &[u32]| -> Result<(), String> {
        let n = after[i as usize];
        let (a, b) = (after[n.left as usize], after[n.right as usize]);
        if n.bv != a.bv.union(&b.bv) {
            return Err(format!("node {i}'s box is not the union of its children's"));
        }
        if n.height != 1 + a.height.max(b.height) || n.item != 0 {
            return Err(format!(
                "node {i}: height {} (item {}), expected {} (item 0)",
                n.height,
                n.item,
                1 + a.height.max(b.height)
            ));
        }
        if !(was_internal(i) || before[i as usize].height == u32::MAX) {
            return Err(format!("node {i} was a leaf and is now internal"));
        }
        let generation = before[i as usize]
            .generation
            .wrapping_add(u32::from(was_internal(i)));
        if n.generation != generation {
            return Err(format!("internal node {i} has generation {}, expected {generation} (released once if it was internal)", n.generation));
        }
        // The split rule over l + r.
        let mut all: Vec<u32> = [l, r].concat();
        let centre = |j: u32| after[j as usize].bv.center();
        let mut centres = Aabb::EMPTY;
        for &j in &all {
            centres.grow(centre(j));
        }
        let axis = centres.extent().max_position();
        all.sort_by(|&x, &y| centre(x)[axis].total_cmp(&centre(y)[axis]).then(x.cmp(&y)));
        let (mut want_l, mut got_l) = (all[..all.len() / 2].to_vec(), l.to_vec());
        want_l.sort_unstable();
        got_l.sort_unstable();
        if want_l != got_l {
            return Err(format!(
                "node {i} splits {} leaves into {} left and {} right, not at the median along axis {axis} (left should be {:?}...)",
                all.len(), l.len(), r.len(), &want_l[..want_l.len().min(6)]
            ));
        }
        Ok(())
    };
    let leaves = walk(root, after, &mut in_tree, &mut check, 0)?;
    let mut kept: Vec<u32> = leaves.clone();
    kept.sort_unstable();
    let mut want: Vec<u32> = (0..before.len() as u32).filter(|&i| was_leaf(i)).collect();
    want.sort_unstable();
    if kept != want {
        return Err(format!(
            "the tree holds {} leaves, the storage had {}",
            kept.len(),
            want.len()
        ));
    }
    for &i in &leaves {
        let (x, y) = (after[i as usize], before[i as usize]);
        if (x.bv, x.item, x.generation, x.height, x.left)
            != (y.bv, y.item, y.generation, y.height, y.left)
        {
            return Err(format!("leaf {i} changed (only its parent may)"));
        }
    }
    // The free list: every node outside the tree, each once, blank.
    let mut on_list = vec![false; after.len()];
    let mut at = free;
    while at != NULL {
        let n = get(at)?;
        if on_list[at as usize] || in_tree[at as usize] {
            return Err(format!(
                "the free list reaches node {at} twice or a node of the tree"
            ));
        }
        on_list[at as usize] = true;
        let generation = before[at as usize]
            .generation
            .wrapping_add(u32::from(was_internal(at)));
        let blank = DynNode {
            parent: n.parent,
            generation,
            ..DynNode::EMPTY
        };
        if *n != blank {
            return Err(format!(
                "free node {at} is not blank in generation {generation}"
            ));
        }
        at = n.parent;
    }
    if let Some(lost) = (0..after.len()).find(|&i| !on_list[i] && !in_tree[i]) {
        return Err(format!(
            "node {lost} is neither in the tree nor on the free list"
        ));
    }
    Ok(())
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 8;

    pub fn rebuild_dynamic(
        which: u32,
        storage: &mut [DynNode<Aabb>],
        root: u32,
        free: u32,
        scratch: &mut [u32],
    ) -> (u32, u32) {
        if root == NULL && which != 8 {
            return (NULL, free);
        }
        let (mut free, mut found) = (free, 0);
        let mut stack = vec![root];
        while let Some(i) = stack.pop() {
            let node = storage[i as usize];
            if node.left == NULL {
                scratch[found] = i;
                found += 1;
            } else {
                stack.push(node.left);
                stack.push(node.right);
                storage[i as usize] = if which == 4 {
                    // 4: released without moving to the next generation.
                    DynNode {
                        parent: free,
                        generation: node.generation,
                        ..DynNode::EMPTY
                    }
                } else {
                    node.released(free)
                };
                free = i;
            }
        }
        fn build(which: u32, s: &mut [DynNode<Aabb>], leaves: &mut [u32], free: &mut u32) -> u32 {
            if let [one] = leaves {
                return *one;
            }
            let centre = |s: &[DynNode<Aabb>], i: u32| s[i as usize].bv.center();
            let mut centres = Aabb::EMPTY;
            let mut all = Aabb::EMPTY;
            for &i in leaves.iter() {
                centres.grow(centre(s, i));
                all = all.union(&s[i as usize].bv);
            }
            // 2: the axis of the box of the boxes, not of their centres.
            let axis = if which == 2 { all } else { centres }
                .extent()
                .max_position();
            let mid = match which {
                // 1: the middle of the centres' extent, not the median.
                1 => {
                    let cut = 0.5 * (centres.min[axis] + centres.max[axis]);
                    leaves.sort_by(|&a, &b| {
                        centre(s, a)[axis]
                            .total_cmp(&centre(s, b)[axis])
                            .then(a.cmp(&b))
                    });
                    let m = leaves.iter().filter(|&&i| centre(s, i)[axis] < cut).count();
                    m.clamp(1, leaves.len() - 1)
                }
                // 3: equal centres in the order the walk found them.
                3 => {
                    leaves.sort_by(|&a, &b| centre(s, a)[axis].total_cmp(&centre(s, b)[axis]));
                    leaves.len() / 2
                }
                _ => {
                    leaves.sort_by(|&a, &b| {
                        centre(s, a)[axis]
                            .total_cmp(&centre(s, b)[axis])
                            .then(a.cmp(&b))
                    });
                    // 6: the larger half on the left.
                    if which == 6 {
                        leaves.len() - leaves.len() / 2
                    } else {
                        leaves.len() / 2
                    }
                }
            };
            let (lo, hi) = leaves.split_at_mut(mid);
            let left = build(which, s, lo, free);
            let right = build(which, s, hi, free);
            let parent = *free;
            *free = s[parent as usize].parent;
            let (l, r) = (s[left as usize], s[right as usize]);
            s[parent as usize] = DynNode {
                bv: l.bv.union(&r.bv),
                // 7 (with the root not reset below): the free list's link
                // kept, so the root points into the free list.
                parent: if which == 7 {
                    s[parent as usize].parent
                } else {
                    NULL
                },
                left,
                right,
                item: 0,
                // 5: every internal node at height 1.
                height: if which == 5 {
                    1
                } else {
                    1 + l.height.max(r.height)
                },
                generation: s[parent as usize].generation,
            };
            s[left as usize].parent = parent;
            s[right as usize].parent = parent;
            parent
        }
        let root = build(which, storage, &mut scratch[..found], &mut free);
        if which != 7 {
            storage[root as usize].parent = NULL;
        }
        (root, free)
    }
}
