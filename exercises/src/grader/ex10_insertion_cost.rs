//! Exercise 10: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 10.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 10,
            name: "a sibling without ancestors: the new parent's area",
            points: 3,
            run: |e| {
                let (s, n) = (b([0.0; 3], [1.0; 3]), b([2.0, 0.0, 0.0], [3.0, 1.0, 1.0]));
                // Union is 3 x 1 x 1: area 2 * (3 + 1 + 3) = 14.
                (e.insertion_cost(&s, &[], &n) - 14.0).abs() < 1e-9
            },
        },
        Check {
            exercise: 10,
            name: "ancestors add only their growth (zero when they contain the object)",
            points: 4,
            run: |e| {
                let (s, n) = (b([0.0; 3], [1.0; 3]), b([2.0, 0.0, 0.0], [3.0, 1.0, 1.0]));
                let big = b([-5.0; 3], [5.0; 3]);
                let small = b([0.0; 3], [2.0, 1.0, 1.0]); // grows to 3 x 1 x 1: 10 -> 14
                (e.insertion_cost(&s, &[big], &n) - 14.0).abs() < 1e-9
                    && (e.insertion_cost(&s, &[small, big], &n) - 18.0).abs() < 1e-9
            },
        },
        Check {
            exercise: 10,
            name: "agrees with the library's DynamicTree on random trees",
            points: 3,
            run: |e| {
                use bvhkit::builders::{DynNode, DynamicConfig, DynamicTree, NULL};
                let prims = boxes(60, 11, Vec3::ZERO);
                let mut storage = vec![DynNode::<Aabb>::EMPTY; 2 * 61 - 1];
                let handles: Vec<u32> = {
                    let Ok(mut tree) = DynamicTree::new(&mut storage, DynamicConfig::default())
                    else {
                        return false;
                    };
                    prims
                        .iter()
                        .enumerate()
                        .filter_map(|(i, p)| tree.insert(i as u32, p).ok())
                        .collect()
                };
                let new = b([3.3, 4.1, 0.2], [4.0, 5.0, 0.9]);
                handles.iter().all(|&h| {
                    let mut ancestors = Vec::new();
                    let mut a = storage[h as usize].parent;
                    while a != NULL {
                        ancestors.push(storage[a as usize].bv);
                        a = storage[a as usize].parent;
                    }
                    let mine = e.insertion_cost(&storage[h as usize].bv, &ancestors, &new);
                    let lib = DynamicTree::insertion_cost_of(&storage, h, &new);
                    (mine - lib).abs() <= 1e-6 * lib.abs().max(1.0)
                })
            },
        },
    ]
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 2;

    pub fn insertion_cost(which: u32, sibling: &Aabb, ancestors: &[Aabb], new: &Aabb) -> f64 {
        let area = |b: &Aabb| b.surface_area() as f64;
        match which {
            1 => area(&sibling.union(new)), // forgets the ancestors
            2 => {
                area(&sibling.union(new))
                    + ancestors.iter().map(|a| area(&a.union(new))).sum::<f64>()
            }
            _ => Reference.insertion_cost(sibling, ancestors, new),
        }
    }
}
