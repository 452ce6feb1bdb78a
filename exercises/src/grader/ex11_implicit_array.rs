//! Exercise 11: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 11.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 11,
            name: "children of the first entries",
            points: 3,
            run: |e| {
                e.implicit_children(0) == (1, 2)
                    && e.implicit_children(1) == (3, 4)
                    && e.implicit_children(4) == (9, 10)
                    && e.implicit_children(1000) == (2001, 2002)
            },
        },
        Check {
            exercise: 11,
            name: "the parent inverts both children; the root has none",
            points: 4,
            run: |e| {
                e.implicit_parent(0).is_none()
                    && (0..5000).all(|i| {
                        let (l, r) = e.implicit_children(i);
                        e.implicit_parent(l) == Some(i) && e.implicit_parent(r) == Some(i)
                    })
            },
        },
        Check {
            exercise: 11,
            name: "array length of a complete tree of each depth",
            points: 3,
            run: |e| (0..30).all(|d: u32| e.implicit_len(d) == (1usize << (d + 1)) - 1),
        },
    ]
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;
    use crate::grader::wrong::PANICS;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 3;

    pub fn implicit_children(which: u32, i: usize) -> (usize, usize) {
        match which {
            1 => (2 * i, 2 * i + 1), // the one-based formula on a zero-based array
            _ => Reference.implicit_children(i),
        }
    }

    pub fn implicit_parent(which: u32, i: usize) -> Option<usize> {
        match which {
            2 => (i > 0).then_some(i / 2),
            _ => Reference.implicit_parent(i),
        }
    }

    pub fn implicit_len(which: u32, depth: u32) -> usize {
        match which {
            PANICS => panic!("a slip"),
            3 => 1 << depth, // only the last level
            _ => Reference.implicit_len(depth),
        }
    }
}
