//! Exercise 11: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The deepest tree for which `(1 << (depth + 1)) - 1` does not overflow a
/// 64-bit `usize` (depth 63's length, `usize::MAX`, fits; its shift does not).
const DEEPEST: u32 = 62;

/// The checks of exercise 11.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 11,
            name: "children of the first entries",
            points: 3,
            run: |e| {
                [
                    (0, (1, 2)),
                    (1, (3, 4)),
                    (2, (5, 6)),
                    (4, (9, 10)),
                    (1000, (2001, 2002)),
                ]
                .iter()
                .all(|&(i, want)| {
                    same(
                        format!("implicit_children({i})"),
                        want,
                        e.implicit_children(i),
                    )
                })
            },
        },
        Check {
            exercise: 11,
            name: "the parent inverts both children; the root has none",
            points: 4,
            run: |e| {
                same("implicit_parent(0)", None, e.implicit_parent(0))
                    && (0..5000).all(|i| {
                        let (l, r) = e.implicit_children(i);
                        let back = |c: usize| {
                            same(
                                format!("implicit_parent({c}) (a child of {i})"),
                                Some(i),
                                e.implicit_parent(c),
                            )
                        };
                        back(l) && back(r)
                    })
            },
        },
        Check {
            exercise: 11,
            name: "array length of a complete tree of each depth, up to 62",
            points: 3,
            run: |e| {
                (0..=DEEPEST).all(|d: u32| {
                    same(
                        format!("implicit_len({d})"),
                        (1usize << (d + 1)) - 1,
                        e.implicit_len(d),
                    )
                })
            },
        },
    ]
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;
    use crate::grader::wrong::PANICS;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 7;

    pub fn implicit_children(which: u32, i: usize) -> (usize, usize) {
        match which {
            // The one-based formula on a zero-based array.
            1 => (2 * i, 2 * i + 1),
            // The right child first.
            6 => (2 * i + 2, 2 * i + 1),
            _ => Reference.implicit_children(i),
        }
    }

    pub fn implicit_parent(which: u32, i: usize) -> Option<usize> {
        match which {
            // The one-based formula: right children get the wrong parent.
            2 => (i > 0).then_some(i / 2),
            // Forgets the root: it gets itself as a parent.
            7 => Some(i.saturating_sub(1) / 2),
            _ => Reference.implicit_parent(i),
        }
    }

    pub fn implicit_len(which: u32, depth: u32) -> usize {
        match which {
            PANICS => panic!("a slip"),
            // Only the last level.
            3 => 1 << depth,
            // u32 arithmetic: overflows from depth 31 on.
            4 => ((1u32 << (depth + 1)) - 1) as usize,
            // One too many: forgets the `- 1`.
            5 => 1 << (depth + 1),
            _ => Reference.implicit_len(depth),
        }
    }
}
