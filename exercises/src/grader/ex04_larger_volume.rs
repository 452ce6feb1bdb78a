//! Exercise 4: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 4.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 4,
            name: "never opens a leaf",
            points: 3,
            run: |e| {
                let big = node([0.0; 3], [10.0; 3], false);
                let small_leaf = node([0.0; 3], [1.0; 3], true);
                let big_leaf = node([0.0; 3], [10.0; 3], true);
                let small = node([0.0; 3], [1.0; 3], false);
                e.descend_a(&big, &small_leaf)
                    && e.descend_a(&small, &big_leaf)
                    && !e.descend_a(&big_leaf, &small)
                    && !e.descend_a(&small_leaf, &big)
            },
        },
        Check {
            exercise: 4,
            name: "opens the larger of two internal nodes (A on a tie)",
            points: 4,
            run: |e| {
                let big = node([0.0; 3], [10.0; 3], false);
                let small = node([0.0; 3], [1.0; 3], false);
                e.descend_a(&big, &small)
                    && !e.descend_a(&small, &big)
                    && e.descend_a(&small, &small)
            },
        },
        Check {
            exercise: 4,
            name: "size means volume, not the length along one axis",
            points: 3,
            run: |e| {
                let long_thin = node([0.0; 3], [20.0, 0.1, 0.1], false);
                let cube = node([0.0; 3], [2.0; 3], false);
                !e.descend_a(&long_thin, &cube) && e.descend_a(&cube, &long_thin)
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

    pub fn descend_a(which: u32, a: &Node<Aabb>, b: &Node<Aabb>) -> bool {
        match which {
            1 => a.bv.volume() >= b.bv.volume(), // forgets the leaves
            2 => b.is_leaf() || (!a.is_leaf() && a.bv.extent().x >= b.bv.extent().x),
            _ => Reference.descend_a(a, b),
        }
    }
}
