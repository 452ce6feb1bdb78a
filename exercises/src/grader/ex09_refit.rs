//! Exercise 9: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 9.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 9,
            name: "leaves fit their moved primitives exactly",
            points: 4,
            run: |e| {
                [(50, 1), (300, 2)]
                    .iter()
                    .all(|&(n, seed)| refit_ok(e, n, seed, |w| w.is_leaf()))
            },
        },
        Check {
            exercise: 9,
            name: "every parent is the union of its children (up to the root)",
            points: 4,
            run: |e| {
                [(50, 3), (300, 4)]
                    .iter()
                    .all(|&(n, seed)| refit_ok(e, n, seed, |_| true))
            },
        },
        Check {
            exercise: 9,
            name: "a tree of one leaf",
            points: 2,
            run: |e| refit_ok(e, 1, 5, |_| true),
        },
    ]
}

/// Builds a tree over `n` boxes (leaf size 2), moves every third box, has
/// the student refit it and compares the nodes `which` picks (by the
/// library's answer) with the library's refit, explained with the first
/// node that differs.
fn refit_ok(e: &dyn Exercises, n: usize, seed: u64, which: fn(&Node<Aabb>) -> bool) -> bool {
    let (got, want, indices) = refit_case(e, n, seed);
    let what = format!(
        "refit of a tree over {n} box{} on a jittered grid (leaf size 2, {} node{}) after \
         every third box moved",
        if n == 1 { "" } else { "es" },
        want.len(),
        if want.len() == 1 { "" } else { "s" }
    );
    if got.len() != want.len() {
        return fail(format!(
            "{what}: the node array changed length ({} nodes, expected {})",
            got.len(),
            want.len()
        ));
    }
    let bad = (0..want.len()).find(|&i| which(&want[i]) && got[i] != want[i]);
    let Some(i) = bad else {
        return true;
    };
    let (g, w) = (&got[i], &want[i]);
    let kind = match w.children() {
        Some((l, r)) => format!("the internal node with children {l} and {r}"),
        None => {
            let (f, c) = (w.first as usize, w.count as usize);
            format!(
                "a leaf holding indices[{f}..{}] (primitive{} {:?})",
                f + c,
                if c == 1 { "" } else { "s" },
                &indices[f..f + c]
            )
        }
    };
    if g.first != w.first || g.count != w.count {
        return fail(format!(
            "{what}: node {i} ({kind}) had its first/count changed to {}/{}; a refit changes \
             boxes only",
            g.first, g.count
        ));
    }
    fail(format!(
        "{what}: node {i} ({kind}) got the box {}, expected {}",
        show_box(&g.bv),
        show_box(&w.bv)
    ))
}

/// Builds a tree over boxes, moves every third box, and returns the
/// student's refit next to the library's, and the tree's index array.
fn refit_case(
    e: &dyn Exercises,
    n: usize,
    seed: u64,
) -> (Vec<Node<Aabb>>, Vec<Node<Aabb>>, Vec<u32>) {
    let t = Tree::new(boxes(n, seed, Vec3::ZERO), 2);
    let used = t.bvh().node_count();
    let mut r = Rng(seed + 1);
    let moved: Vec<Aabb> = t
        .prims
        .iter()
        .enumerate()
        .map(|(i, b)| {
            if i % 3 == 0 {
                let d = r.point(6.0, Vec3::ZERO);
                Aabb::new(b.min + d, b.max + d)
            } else {
                *b
            }
        })
        .collect();
    let mut student = t.nodes[..used].to_vec();
    e.refit(&mut student, &t.indices, &moved);
    let mut want = t.nodes[..used].to_vec();
    if let Err(err) = bvhkit::builders::refit_all(&mut want, &t.indices, &moved, 0.0, ()) {
        panic!("grader refit: {err}");
    }
    (student, want, t.indices)
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 6;

    pub fn refit(which: u32, nodes: &mut [Node<Aabb>], indices: &[u32], prims: &[Aabb]) {
        let leaf = |n: &Node<Aabb>| {
            let (f, c) = (n.first as usize, n.count as usize);
            match which {
                // The leaf's first primitive only.
                3 => prims[indices[f] as usize],
                // One primitive short: `first .. first + count - 1`.
                4 => indices[f..f + c - 1]
                    .iter()
                    .fold(Aabb::EMPTY, |b, &p| b.union(&prims[p as usize])),
                // Grows the old box instead of starting afresh: never shrinks.
                5 => indices[f..f + c]
                    .iter()
                    .fold(n.bv, |b, &p| b.union(&prims[p as usize])),
                // Skips the index array: `prims[first + k]`.
                6 => prims[f..f + c].iter().fold(Aabb::EMPTY, |b, p| b.union(p)),
                _ => indices[f..f + c]
                    .iter()
                    .fold(Aabb::EMPTY, |b, &p| b.union(&prims[p as usize])),
            }
        };
        match which {
            // Only the leaves: parents keep their old boxes.
            1 => {
                for n in nodes.iter_mut().filter(|n| n.is_leaf()) {
                    n.bv = leaf(n);
                }
            }
            // Front to back: parents are merged from stale children.
            2 => {
                for i in 0..nodes.len() {
                    nodes[i].bv = match nodes[i].children() {
                        Some((l, r)) => nodes[l as usize].bv.union(&nodes[r as usize].bv),
                        None => leaf(&nodes[i]),
                    };
                }
            }
            // 3 to 6: back to front as asked, with a slip in the leaves.
            3..=6 => {
                for i in (0..nodes.len()).rev() {
                    nodes[i].bv = match nodes[i].children() {
                        Some((l, r)) => nodes[l as usize].bv.union(&nodes[r as usize].bv),
                        None => leaf(&nodes[i]),
                    };
                }
            }
            _ => Reference.refit(nodes, indices, prims),
        }
    }
}
