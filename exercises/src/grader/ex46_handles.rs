//! Exercise 46: generational handles on a dynamic tree's free list. The
//! checks, and the plausible wrong answers they must reject.
//!
//! Every storage the checks ask about is left by a real [`DynamicTree`]
//! after a random run of inserts, moves and removals, and every expected
//! answer is the tree's own: [`DynamicTree::contains`] for 46a (asked
//! before the tree lets go of its storage), `DynNode::released` for 46b.

use super::common::*;
use bvhkit::builders::{DynNode, DynamicConfig, DynamicTree, LeafHandle, NULL};

/// The checks of exercise 46.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 46,
            name: "46a: the handle of every object still in the tree is live",
            points: 1,
            run: |e| asks(e, |a| a.expected && a.kind == Kind::Own),
        },
        Check {
            exercise: 46,
            name: "46a: a removed object's handle is dead while its node is free",
            points: 1,
            run: |e| asks(e, |a| a.kind == Kind::Own && a.now == Now::Free),
        },
        Check {
            exercise: 46,
            name: "46a: a removed object's handle is dead once its node holds another object \
                   (a leaf of a later generation)",
            points: 1,
            run: |e| {
                asks(e, |a| {
                    a.kind == Kind::Own && !a.expected && a.now == Now::Leaf
                })
            },
        },
        Check {
            exercise: 46,
            name: "46a: a handle naming an internal node is dead, even in that node's \
                   generation",
            points: 1,
            run: |e| asks(e, |a| a.kind == Kind::Restored && a.now == Now::Internal),
        },
        Check {
            exercise: 46,
            name: "46a: a handle naming a free node is dead, even in that node's generation; \
                   another tree's handles are live only where they name a live leaf of their \
                   generation here",
            points: 1,
            run: |e| {
                asks(e, |a| {
                    (a.kind == Kind::Restored && a.now == Now::Free) || a.kind == Kind::Foreign
                })
            },
        },
        Check {
            exercise: 46,
            name: "46a: a handle past the end of the storage is dead (no panic)",
            points: 1,
            run: |e| asks(e, |a| a.kind == Kind::PastTheEnd),
        },
        Check {
            exercise: 46,
            name: "46b: a freed node is blank but for its link to the old head and the next \
                   generation, and heads the free list",
            points: 1,
            run: |e| releases(e, false),
        },
        Check {
            exercise: 46,
            name: "46b: freeing node after node chains the free list through parent",
            points: 1,
            run: |e| releases(e, true),
        },
        Check {
            exercise: 46,
            name: "46b: the generation wraps past u32::MAX to 0",
            points: 1,
            run: wraps,
        },
    ]
}

/// Where a handle came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    /// Issued by this tree's `insert`.
    Own,
    /// Issued by another tree (a bigger one, over other storage).
    Foreign,
    /// Restored from numbers ([`LeafHandle::from_parts`]): each node of the
    /// storage in its final generation, whatever it holds.
    Restored,
    /// Made up, naming a node past the end of the storage.
    PastTheEnd,
}

/// What the handle's node is at the end of the run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Now {
    Leaf,
    Internal,
    Free,
    Missing,
}

/// One question of 46a with the tree's answer.
#[derive(Clone, Copy, Debug)]
struct Asked {
    handle: LeafHandle,
    kind: Kind,
    now: Now,
    expected: bool,
}

/// A storage left by a tree, and the questions about it.
struct Scene {
    storage: Vec<DynNode<Aabb>>,
    asked: Vec<Asked>,
}

/// Runs `steps` random operations on a tree over `storage`; returns every
/// handle it issued (as [`Kind::Own`]) and the `extra` handles, each with
/// the tree's answer to [`DynamicTree::contains`] at the end of the run.
fn run(
    storage: &mut [DynNode<Aabb>],
    seed: u64,
    steps: usize,
    extra: &[(LeafHandle, Kind)],
) -> Vec<(LeafHandle, Kind, bool)> {
    let mut r = Rng(seed);
    let Ok(mut tree) = DynamicTree::new(storage, DynamicConfig::default()) else {
        return Vec::new();
    };
    let (mut issued, mut live) = (Vec::new(), Vec::new());
    for step in 0..steps {
        let roll = r.next();
        let at = r.point(20.0, Vec3::ZERO);
        let bounds = Aabb::new(at, at + Vec3::splat(0.5 + r.next()));
        if roll < 0.5 || live.is_empty() {
            if let Ok(h) = tree.insert(step as u32, &bounds) {
                issued.push((h, Kind::Own));
                live.push(h);
            }
        } else if roll < 0.8 {
            let k = ((r.next() * live.len() as f32) as usize).min(live.len() - 1);
            let _ = tree.remove(live.swap_remove(k));
        } else {
            let k = ((r.next() * live.len() as f32) as usize).min(live.len() - 1);
            let _ = tree.update(live[k], &bounds);
        }
    }
    issued
        .iter()
        .chain(extra)
        .map(|&(h, kind)| (h, kind, tree.contains(h)))
        .collect()
}

/// Three scenes: a tree of up to 12, 40 and 150 objects, each asked about
/// its own handles, a bigger tree's, and made-up ones past its end.
fn scenes() -> Vec<Scene> {
    [(12usize, 1u64), (40, 2), (150, 3)]
        .iter()
        .map(|&(objects, seed)| {
            let mut storage = vec![DynNode::<Aabb>::EMPTY; bvhkit::max_nodes(objects)];
            let mut other = vec![DynNode::<Aabb>::EMPTY; bvhkit::max_nodes(objects * 2)];
            let mut extra: Vec<(LeafHandle, Kind)> =
                run(&mut other, seed * 7919, objects * 12, &[])
                    .into_iter()
                    .map(|(h, _, _)| (h, Kind::Foreign))
                    .collect();
            let n = storage.len() as u32;
            for i in [n, n + 1, n + 1000, u32::MAX - 1] {
                for g in [0, 1] {
                    extra.push((LeafHandle::from_parts(i, g), Kind::PastTheEnd));
                }
            }
            // A first run of the same (deterministic) operations tells each
            // node's final generation, to restore a handle of it.
            let mut probe = storage.clone();
            run(&mut probe, seed, objects * 12, &[]);
            for (i, node) in probe.iter().enumerate() {
                extra.push((
                    LeafHandle::from_parts(i as u32, node.generation),
                    Kind::Restored,
                ));
            }
            let answered = run(&mut storage, seed, objects * 12, &extra);
            assert!(probe == storage, "the grader's runs are deterministic");
            // What each handle's node is once the tree is gone.
            let now = |h: LeafHandle| match storage.get(h.index() as usize) {
                None => Now::Missing,
                Some(n) if n.height == u32::MAX => Now::Free,
                Some(n) if n.left == NULL => Now::Leaf,
                Some(_) => Now::Internal,
            };
            let asked = answered
                .iter()
                .map(|&(handle, kind, expected)| Asked {
                    handle,
                    kind,
                    now: now(handle),
                    expected,
                })
                .collect();
            Scene { storage, asked }
        })
        .collect()
}

/// Asks `e` about every handle `pick` selects, in every scene; the check
/// also fails if it selects none (the scenes must exercise the case).
fn asks(e: &dyn Exercises, pick: impl Fn(&Asked) -> bool) -> bool {
    let mut asked = 0;
    for scene in scenes() {
        for a in scene.asked.iter().filter(|a| pick(a)) {
            asked += 1;
            let got = e.handle_is_live(&scene.storage, a.handle.index(), a.handle.generation());
            if got != a.expected {
                let node = scene.storage.get(a.handle.index() as usize).map_or(
                    "past the end".to_string(),
                    |n| {
                        format!(
                            "height {}, left {}, generation {}",
                            n.height, n.left, n.generation
                        )
                    },
                );
                return fail(format!(
                    "handle_is_live(storage of {} nodes, index {}, generation {}) returned \
                     {got}, expected {} (the node: {node})",
                    scene.storage.len(),
                    a.handle.index(),
                    a.handle.generation(),
                    a.expected
                ));
            }
        }
    }
    asked > 0 || fail("the grader's scenes asked nothing here (a grader bug)".to_string())
}

/// Frees live leaves of each scene's storage with `e` and with the library;
/// `chain` frees several in a row (each call given the head the last one
/// returned) and compares the whole storage, otherwise one node at a time
/// on a fresh copy.
fn releases(e: &dyn Exercises, chain: bool) -> bool {
    for scene in scenes() {
        let leaves: Vec<u32> = (0..scene.storage.len() as u32)
            .filter(|&i| {
                scene.storage[i as usize].is_live_leaf(scene.storage[i as usize].generation)
            })
            .take(6)
            .collect();
        if leaves.is_empty() {
            return fail("a scene without leaves (a grader bug)".to_string());
        }
        let (mut got, mut want) = (scene.storage.clone(), scene.storage.clone());
        // Any head will do: the first free node, or none.
        let head = (0..want.len() as u32)
            .find(|&i| want[i as usize].height == u32::MAX)
            .unwrap_or(NULL);
        let (mut got_head, mut want_head) = (head, head);
        for &node in &leaves {
            if !chain {
                got = scene.storage.clone();
                want = scene.storage.clone();
                (got_head, want_head) = (head, head);
            }
            let before = got_head;
            got_head = e.release_node(&mut got, got_head, node);
            want[node as usize] = want[node as usize].released(want_head);
            want_head = node;
            if got_head != want_head || got != want {
                let shown = |n: &DynNode<Aabb>| {
                    format!(
                        "parent {}, left {}, right {}, item {}, height {}, generation {}",
                        n.parent, n.left, n.right, n.item, n.height, n.generation
                    )
                };
                let changed =
                    (0..got.len())
                        .find(|&i| got[i] != want[i])
                        .map_or(String::new(), |i| {
                            format!(
                                "; node {i} is ({}), expected ({})",
                                shown(&got[i]),
                                shown(&want[i])
                            )
                        });
                return fail(format!(
                    "release_node(storage, free {before}, node {node}) returned {got_head}, \
                     expected {want_head}{changed}"
                ));
            }
        }
    }
    true
}

/// A leaf whose generation is `u32::MAX` is freed into generation 0.
fn wraps(e: &dyn Exercises) -> bool {
    let leaf = DynNode {
        bv: b([0.0; 3], [1.0; 3]),
        parent: NULL,
        left: NULL,
        right: NULL,
        item: 4,
        height: 0,
        generation: u32::MAX,
    };
    let mut storage = vec![DynNode::<Aabb>::EMPTY, leaf];
    let head = e.release_node(&mut storage, 0, 1);
    let n = storage[1];
    (head == 1 && n == leaf.released(0))
        || fail(format!(
            "release_node on a node of generation u32::MAX (free 0, node 1) returned {head} \
             and left generation {}, parent {}, height {}; expected 1, generation 0, parent 0, \
             height {}",
            n.generation,
            n.parent,
            n.height,
            u32::MAX
        ))
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 9;

    pub fn handle_is_live(
        which: u32,
        storage: &[DynNode<Aabb>],
        index: u32,
        generation: u32,
    ) -> bool {
        let node = |i: u32| storage.get(i as usize);
        match which {
            // 1: the generation forgotten: any leaf at that index.
            1 => node(index).is_some_and(|n| n.height == 0 && n.left == NULL),
            // 2: not free is taken for a leaf: internal nodes pass.
            2 => node(index).is_some_and(|n| n.height != u32::MAX && n.generation == generation),
            // 3: no children is taken for a leaf: free nodes pass.
            3 => node(index).is_some_and(|n| n.left == NULL && n.generation == generation),
            // 4: indexes without a bound check: panics past the end.
            4 => {
                let n = &storage[index as usize];
                n.is_live_leaf(generation)
            }
            _ => crate::reference::Reference.handle_is_live(storage, index, generation),
        }
    }

    pub fn release_node(which: u32, storage: &mut [DynNode<Aabb>], free: u32, node: u32) -> u32 {
        let n = &mut storage[node as usize];
        match which {
            // 5: the generation not advanced: old handles match again.
            5 => {
                *n = DynNode {
                    parent: free,
                    generation: n.generation,
                    ..DynNode::EMPTY
                };
                node
            }
            // 6: returns the old head: the node is lost from the list.
            6 => {
                *n = n.released(free);
                free
            }
            // 7: links it and advances the generation but keeps the rest:
            // the freed node still reads as a leaf.
            7 => {
                n.parent = free;
                n.generation = n.generation.wrapping_add(1);
                node
            }
            // 8: the generation saturates at u32::MAX instead of wrapping.
            8 => {
                *n = DynNode {
                    parent: free,
                    generation: n.generation.saturating_add(1),
                    ..DynNode::EMPTY
                };
                node
            }
            // 9: blank and in the next generation, but not linked: the
            // rest of the free list is lost.
            9 => {
                *n = n.released(NULL);
                node
            }
            _ => crate::reference::Reference.release_node(storage, free, node),
        }
    }
}
