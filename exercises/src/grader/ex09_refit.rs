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
                [(50, 1), (300, 2)].iter().all(|&(n, seed)| {
                    let (got, want) = refit_case(e, n, seed);
                    got.iter()
                        .zip(&want)
                        .filter(|(_, w)| w.is_leaf())
                        .all(|(g, w)| g.bv == w.bv)
                })
            },
        },
        Check {
            exercise: 9,
            name: "every parent is the union of its children (up to the root)",
            points: 4,
            run: |e| {
                [(50, 3), (300, 4)].iter().all(|&(n, seed)| {
                    let (got, want) = refit_case(e, n, seed);
                    got == want
                })
            },
        },
        Check {
            exercise: 9,
            name: "a tree of one leaf",
            points: 2,
            run: |e| {
                let (got, want) = refit_case(e, 1, 5);
                got == want
            },
        },
    ]
}

/// Builds a tree over boxes, moves every third box, and returns the
/// student's refit next to the library's.
fn refit_case(e: &dyn Exercises, n: usize, seed: u64) -> (Vec<Node<Aabb>>, Vec<Node<Aabb>>) {
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
    (student, want)
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 2;

    pub fn refit(which: u32, nodes: &mut [Node<Aabb>], indices: &[u32], prims: &[Aabb]) {
        let leaf = |n: &Node<Aabb>| {
            indices[n.first as usize..(n.first + n.count) as usize]
                .iter()
                .fold(Aabb::EMPTY, |b, &p| b.union(&prims[p as usize]))
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
            _ => Reference.refit(nodes, indices, prims),
        }
    }
}
