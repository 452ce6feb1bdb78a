//! Exercise 6: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 6.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 6,
            name: "finds exactly the brute-force pairs",
            points: 6,
            run: |e| {
                traversal_cases().iter().all(|(a, b)| {
                    let (ok, out) = run_stack(e, a, b, 4 * (a.depth + b.depth) + 4);
                    ok && sorted(out) == reference_pairs(a, b)
                })
            },
        },
        Check {
            exercise: 6,
            name: "a stack that is too small gives false, not a panic",
            points: 5,
            run: |e| {
                let (a, b) = &traversal_cases()[0];
                !run_stack(e, a, b, 2).0 && !run_stack(e, a, b, 0).0
            },
        },
        Check {
            exercise: 6,
            name: "one waiting pair per level is enough (depth-bounded stack)",
            points: 4,
            run: |e| {
                traversal_cases()
                    .iter()
                    .all(|(a, b)| run_stack(e, a, b, a.depth + b.depth + 2).0)
            },
        },
    ]
}

fn run_stack(e: &dyn Exercises, a: &Tree, b: &Tree, size: usize) -> (bool, Vec<(u32, u32)>) {
    let mut out = Vec::new();
    let mut stack = vec![(0u32, 0u32); size];
    let ok = e.stack_dfs(&a.bvh(), &a.prims, &b.bvh(), &b.prims, &mut stack, &mut out);
    (ok, out)
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 1;

    pub fn stack_dfs(
        which: u32,
        a: &Bvh<Aabb>,
        pa: &[Aabb],
        b: &Bvh<Aabb>,
        pb: &[Aabb],
        stack: &mut [(u32, u32)],
        out: &mut Vec<(u32, u32)>,
    ) -> bool {
        match which {
            // Indexes the stack without a bound check.
            1 => {
                let _ = stack[stack.len().max(64)];
                Reference.stack_dfs(a, pa, b, pb, stack, out)
            }
            _ => Reference.stack_dfs(a, pa, b, pb, stack, out),
        }
    }
}
