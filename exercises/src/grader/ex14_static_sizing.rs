//! Exercise 14: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 14.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 14,
            name: "build memory: nodes and indices, for n = 0, 1 and many",
            points: 4,
            run: |e| {
                [(0, 32), (1, 32), (2, 32), (256, 32), (1000, 16), (77, 92)]
                    .iter()
                    .all(|&(n, s)| {
                        let want = if n == 0 { 0 } else { (2 * n - 1) * s + 4 * n };
                        same(
                            format!("top_down_bytes({n}, {s})"),
                            want,
                            e.top_down_bytes(n, s),
                        )
                    })
            },
        },
        Check {
            exercise: 14,
            name: "pair stack bound: equal depths and leaves",
            points: 3,
            run: |e| {
                [(0, 0, 1), (1, 1, 4), (7, 7, 22), (40, 40, 121)]
                    .iter()
                    .all(|&(a, b, want)| {
                        same(
                            format!("pair_stack_bound({a}, {b})"),
                            want,
                            e.pair_stack_bound(a, b),
                        )
                    })
            },
        },
        Check {
            exercise: 14,
            name: "pair stack bound: different depths, and enough for a real traversal",
            points: 3,
            run: |e| {
                let formula = (0..40).all(|a| {
                    (0..40).all(|b| {
                        same(
                            format!("pair_stack_bound({a}, {b})"),
                            a + b + a.min(b) + 1,
                            e.pair_stack_bound(a, b),
                        )
                    })
                });
                if !formula {
                    return false;
                }
                // Balanced trees of 64 and 16 boxes: the bound lets a
                // stack-only traversal of exactly that size finish.
                let (pa, pb) = (grid_boxes(64, 0.0), grid_boxes(16, 0.3));
                let (mut na, mut nb) = ([Node::<Aabb>::EMPTY; 127], [Node::<Aabb>::EMPTY; 31]);
                let (mut ia, mut ib) = ([0u32; 64], [0u32; 16]);
                let cfg = TopDown::median().with_max_leaf_size(1);
                let (Ok(ta), Ok(tb)) = (
                    cfg.build(&pa, &mut na, &mut ia),
                    cfg.build(&pb, &mut nb, &mut ib),
                ) else {
                    return fail("the grader could not build its trees");
                };
                let bound = e.pair_stack_bound(ta.depth(), tb.depth());
                let mut stack = vec![(0u32, 0u32); bound];
                let mut out = Vec::new();
                Reference.stack_dfs(&ta, &pa, &tb, &pb, &mut stack, &mut out)
                    || fail(format!(
                        "pair_stack_bound({}, {}) returned {bound}: a stack of that many pairs \
                         overflowed in a traversal of two balanced trees that deep",
                        ta.depth(),
                        tb.depth()
                    ))
            },
        },
    ]
}

/// `n` unit boxes in a row of a grid, shifted by `shift`.
fn grid_boxes(n: usize, shift: f32) -> Vec<Aabb> {
    (0..n)
        .map(|i| {
            let o = Vec3::new((i % 8) as f32 + shift, (i / 8) as f32 + shift, 0.0);
            Aabb::new(o, o + Vec3::ONE)
        })
        .collect()
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 8;

    pub fn top_down_bytes(which: u32, n: usize, node_bytes: usize) -> usize {
        match which {
            // Forgets the index array.
            1 => bvhkit::max_nodes(n) * node_bytes,
            // One node per primitive plus one, as for a list.
            2 => (n + 1) * node_bytes + 4 * n,
            // 2n - 1 nodes without minding n = 0 (wraps around).
            5 => (2 * n)
                .wrapping_sub(1)
                .wrapping_mul(node_bytes)
                .wrapping_add(4 * n),
            // 2n nodes: one too many.
            6 => 2 * n * node_bytes + 4 * n,
            _ => Reference.top_down_bytes(n, node_bytes),
        }
    }

    pub fn pair_stack_bound(which: u32, depth_a: usize, depth_b: usize) -> usize {
        match which {
            // Counts one waiting pair per step, as if only one side opened.
            3 => depth_a + depth_b + 1,
            // The larger depth three times: enough, but not the bound.
            4 => 3 * depth_a.max(depth_b) + 1,
            // Forgets the pair being expanded.
            7 => depth_a + depth_b + depth_a.min(depth_b),
            // Both sides opened as often as the deeper tree allows.
            8 => depth_a + depth_b + depth_a.max(depth_b) + 1,
            _ => Reference.pair_stack_bound(depth_a, depth_b),
        }
    }
}
