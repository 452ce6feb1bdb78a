//! Exercise 24: stopping and falling back. The checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 24.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 24,
            name: "stopping and the depth budget (leaf size, max depth, ceil(log2(ceil(n/k))))",
            points: 5,
            run: |e| {
                let stop = |k: u32, d: u32| Stop {
                    max_leaf_size: k,
                    max_depth: d,
                    min_volume: 0.0,
                };
                use NodeStep::{Halve, Leaf, Split};
                // (n, depth, leaf size, max depth, want), the split balanced.
                let fixed = [
                    (4, 0, 4, 64, Leaf),    // at the leaf size
                    (500, 64, 4, 64, Leaf), // at the depth limit, however large
                    (500, 10, 4, 10, Leaf),
                    (9, 62, 4, 64, Halve), // 3 leaves need 2 levels: 2 left
                    (9, 61, 4, 64, Split), // 3 left
                    (8, 63, 4, 64, Halve), // 2 leaves need 1 level
                    (8, 62, 4, 64, Split),
                    (5000, 0, 4, 3, Halve), // a cap the input cannot meet
                    (5000, 0, 4, 64, Split),
                    (2, 63, 1, 64, Halve),
                    (1000, 54, 1, 64, Halve), // 1000 leaves need 10 levels: 10 left
                    (1000, 53, 1, 64, Split),
                    // 2^24 + 1 leaves need 25 levels (f32 rounds the count to 2^24).
                    (16_777_217, 39, 1, 64, Halve),
                    (16_777_216, 40, 1, 64, Halve),
                    (16_777_217, 38, 1, 64, Split),
                    // More than 31 levels left: 2^levels does not fit a u32.
                    (4_000_000_000, 32, 1, 64, Halve),
                    (4_000_000_000, 31, 1, 64, Split),
                    (4_000_000_000, 0, 1, 32, Halve),
                ];
                let mut r = Rng(2424);
                fixed.iter().all(|&(n, depth, k, d, want)| {
                    step_is(e, n, depth, &stop(k, d), n / 2, true, want)
                }) && (0..2000).all(|_| {
                    let n = 1 + (r.next() * 3000.0) as u32;
                    let k = 1 + (r.next() * 8.0) as u32;
                    let d = (r.next() * 65.0) as u32;
                    let depth = (r.next() * 66.0) as u32;
                    let s = stop(k, d);
                    let want = Reference.node_step(n, depth, &s, n / 2, true);
                    step_is(e, n, depth, &s, n / 2, true, want)
                })
            },
        },
        Check {
            exercise: 24,
            name: "failed splits: nothing on one side; a sliver under 1% for count-blind criteria",
            points: 5,
            run: |e| {
                let s = Stop {
                    max_leaf_size: 4,
                    max_depth: 64,
                    min_volume: 0.0,
                };
                use NodeStep::{FallBack, Split};
                // (n, left, weighs counts, want), far from the depth limit.
                let fixed = [
                    (1000, 0, true, FallBack),
                    (1000, 1000, true, FallBack),
                    (1000, 0, false, FallBack),
                    (1000, 1, true, Split), // the SAH prices a 1-in-1000 cut
                    (1000, 1, false, FallBack),
                    (1000, 999, false, FallBack), // either side
                    (1000, 9, false, FallBack),
                    (1000, 10, false, Split), // exactly 1%: not under it
                    (100, 1, false, Split),
                    (101, 1, false, FallBack),
                    (99, 0, false, FallBack),
                    (99, 1, false, Split), // under 100 primitives: no sliver rule
                    // Just under 1%: a ratio in f32 rounds it to exactly 1%.
                    (100_000_001, 1_000_000, false, FallBack),
                    (100_000_000, 1_000_000, false, Split),
                    // 100 times the smaller side does not fit a u32.
                    (4_000_000_000, 39_999_999, false, FallBack),
                    (4_000_000_000, 40_000_000, false, Split),
                    (4_000_000_000, 2_000_000_000, false, Split),
                ];
                let mut r = Rng(2425);
                fixed
                    .iter()
                    .all(|&(n, left, w, want)| step_is(e, n, 0, &s, left, w, want))
                    && (0..3000).all(|_| {
                        let n = 5 + (r.next() * 3000.0) as u32;
                        let left = if r.next() < 0.5 {
                            (r.next() * 0.03 * n as f32) as u32
                        } else {
                            (r.next() * (n + 1) as f32) as u32
                        }
                        .min(n);
                        let left = if r.next() < 0.5 { left } else { n - left };
                        let w = r.next() < 0.3;
                        let want = Reference.node_step(n, 0, &s, left, w);
                        step_is(e, n, 0, &s, left, w, want)
                    })
            },
        },
    ]
}

/// Whether `node_step` answers `want`, explained when it does not.
fn step_is(
    e: &dyn Exercises,
    n: u32,
    depth: u32,
    s: &Stop,
    left: u32,
    w: bool,
    want: NodeStep,
) -> bool {
    let call = format!(
        "node_step(n = {n}, depth = {depth}, stop with max_leaf_size {} and max_depth {}, \
         left = {left}, weighs_counts = {w})",
        s.max_leaf_size, s.max_depth
    );
    same(call, want, e.node_step(n, depth, s, left, w))
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 11;

    pub fn node_step(which: u32, n: u32, depth: u32, stop: &Stop, left: u32, w: bool) -> NodeStep {
        let k = stop.max_leaf_size;
        let levels_left = stop.max_depth.saturating_sub(depth);
        let budget = |needed: u32| {
            if n <= k || depth >= stop.max_depth {
                Some(NodeStep::Leaf)
            } else if levels_left <= needed {
                Some(NodeStep::Halve)
            } else {
                None
            }
        };
        let ceil_log2 = |x: u32| u32::BITS - (x.max(1) - 1).leading_zeros();
        let rest = |slivers: &dyn Fn(u32) -> bool| {
            let smaller = left.min(n - left.min(n));
            if smaller == 0 || slivers(smaller) {
                NodeStep::FallBack
            } else {
                NodeStep::Split
            }
        };
        let normal = |smaller: u32| !w && n >= 100 && smaller as u64 * 100 < n as u64;
        match which {
            // floor(log2) levels needed instead of ceil.
            1 => budget(u32::BITS - 1 - n.div_ceil(k).leading_zeros())
                .unwrap_or_else(|| rest(&normal)),
            // The leaf count rounded down.
            2 => budget(ceil_log2(n / k)).unwrap_or_else(|| rest(&normal)),
            // Forgets that the depth limit stops the build: the budget
            // halves a node at the limit.
            3 => {
                if n <= k {
                    NodeStep::Leaf
                } else if levels_left <= ceil_log2(n.div_ceil(k)) {
                    NodeStep::Halve
                } else {
                    rest(&normal)
                }
            }
            // The sliver rule for every criterion, the SAH included.
            4 => budget(ceil_log2(n.div_ceil(k)))
                .unwrap_or_else(|| rest(&|smaller| n >= 100 && smaller as u64 * 100 < n as u64)),
            // "At most 1%" instead of "under 1%".
            5 => budget(ceil_log2(n.div_ceil(k))).unwrap_or_else(|| {
                rest(&|smaller| !w && n >= 100 && smaller as u64 * 100 <= n as u64)
            }),
            // `<` for `<=`: a node with exactly the levels it needs is not halved.
            6 => {
                if n <= k || depth >= stop.max_depth {
                    NodeStep::Leaf
                } else if levels_left < ceil_log2(n.div_ceil(k)) {
                    NodeStep::Halve
                } else {
                    rest(&normal)
                }
            }
            // `>` for `>=`: a node at the depth limit is halved, not a leaf.
            7 => {
                if n <= k || depth > stop.max_depth {
                    NodeStep::Leaf
                } else if levels_left <= ceil_log2(n.div_ceil(k)) {
                    NodeStep::Halve
                } else {
                    rest(&normal)
                }
            }
            // ceil(log2) in f32: 2^24 + 1 leaves round to 2^24, one level short.
            8 => {
                budget((n.div_ceil(k) as f32).log2().ceil() as u32).unwrap_or_else(|| rest(&normal))
            }
            // The sliver test as an f32 ratio: just under 1% rounds to 1%.
            9 => budget(ceil_log2(n.div_ceil(k))).unwrap_or_else(|| {
                rest(&|smaller| !w && n >= 100 && (smaller as f32 / n as f32) < 0.01)
            }),
            // Compares 2^(levels left) with twice the leaves in u32: past 31
            // levels the power wraps.
            10 => {
                if n <= k || depth >= stop.max_depth {
                    NodeStep::Leaf
                } else if (1u32.wrapping_shl(levels_left) as u64) < 2 * n.div_ceil(k) as u64 {
                    NodeStep::Halve
                } else {
                    rest(&normal)
                }
            }
            // 100 times the smaller side in u32, wrapping past 4.29e9.
            11 => budget(ceil_log2(n.div_ceil(k))).unwrap_or_else(|| {
                rest(&|smaller| !w && n >= 100 && smaller.wrapping_mul(100) < n)
            }),
            _ => Reference.node_step(n, depth, stop, left, w),
        }
    }
}
