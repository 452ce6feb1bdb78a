//! Exercise 6: the checks, and the plausible wrong answers they must reject.

use super::common::*;
use super::ex05_recursive_pairs::{dense_cases, once, pairs_match, tampered_cases, tiny};

/// The checks of exercise 6.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 6,
            name: "finds exactly the brute-force pairs",
            points: 4,
            run: |e| {
                scenes().iter().all(|(a, b, what)| {
                    let size = 4 * (a.depth + b.depth) + 4;
                    let (ok, out) = run_stack(e, a, b, size);
                    finished(ok, what, size)
                        && pairs_match("stack_dfs", what, &reference_pairs(a, b), &out)
                })
            },
        },
        Check {
            exercise: 6,
            name: "prunes: nothing beneath a node whose box misses is reported",
            points: 3,
            run: |e| {
                tampered_cases().iter().all(|(a, b, want, what)| {
                    let size = 4 * (a.depth + b.depth) + 4;
                    let (ok, out) = run_stack(e, a, b, size);
                    finished(ok, what, size) && pairs_match("stack_dfs", what, want, &out)
                })
            },
        },
        Check {
            exercise: 6,
            name: "a stack that is too small gives false, not a panic",
            points: 3,
            run: |e| {
                let (a, b) = &traversal_cases()[0];
                [2, 0].iter().all(|&size| {
                    !run_stack(e, a, b, size).0
                        || fail(format!(
                            "stack_dfs on the grids of 300 and 250 boxes (depths {} and {}) \
                             with a stack of {size} entries returned true, expected false \
                             (the traversal cannot fit)",
                            a.depth, b.depth
                        ))
                })
            },
        },
        Check {
            exercise: 6,
            name: "depth(A) + depth(B) + 1 entries are enough, the last one included",
            points: 3,
            run: |e| {
                scenes().iter().all(|(a, b, what)| {
                    let size = a.depth + b.depth + 1;
                    let (ok, out) = run_stack(e, a, b, size);
                    finished(ok, what, size)
                        && pairs_match("stack_dfs", what, &reference_pairs(a, b), &out)
                })
            },
        },
        Check {
            exercise: 6,
            name: "reports each pair once",
            points: 2,
            run: |e| {
                scenes().iter().all(|(a, b, _)| {
                    let size = 4 * (a.depth + b.depth) + 4;
                    once("stack_dfs", &run_stack(e, a, b, size).1)
                })
            },
        },
    ]
}

/// The traversal scenes with a description: the grids, the tiny trees, and
/// the trees where every pair overlaps (a stack of depth(A) + depth(B) + 1
/// entries is exactly full on those).
fn scenes() -> Vec<(Tree, Tree, String)> {
    let mut v: Vec<(Tree, Tree, String)> = traversal_cases()
        .into_iter()
        .enumerate()
        .map(|(k, (a, b))| {
            let what = match k {
                0 => "the grids of 300 and 250 boxes (leaf sizes 1 and 3)".to_string(),
                1 => "the grids of 64 and 500 boxes (leaf sizes 4 and 1)".to_string(),
                _ => tiny(&a, &b),
            };
            (a, b, what)
        })
        .collect();
    v.extend(dense_cases());
    v
}

/// `ok`, explained: a traversal with a stack of `size` entries that should
/// have been enough returned false.
fn finished(ok: bool, what: &str, size: usize) -> bool {
    ok || fail(format!(
        "stack_dfs on {what} with a stack of {size} {} returned false, expected true \
         (that is enough)",
        if size == 1 { "entry" } else { "entries" }
    ))
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
    pub const COUNT: u32 = 7;

    /// The loop with the slips of the wrong answers: `which` as in
    /// [`stack_dfs`].
    fn walk(
        which: u32,
        a: &Bvh<Aabb>,
        pa: &[Aabb],
        b: &Bvh<Aabb>,
        pb: &[Aabb],
        stack: &mut [(u32, u32)],
        out: &mut Vec<(u32, u32)>,
    ) -> bool {
        // 2: believes the stack full one entry early.
        let cap = if which == 2 {
            stack.len().saturating_sub(1)
        } else {
            stack.len()
        };
        let mut top = 0;
        let push = |stack: &mut [(u32, u32)], top: &mut usize, pair| {
            if *top < cap {
                stack[*top] = pair;
                *top += 1;
                true
            } else {
                which == 3 // 3: drops the pair and carries on
            }
        };
        if !push(stack, &mut top, (0, 0)) {
            return false;
        }
        let mut first = true;
        while top > 0 {
            top -= 1;
            let (i, j) = stack[top];
            let (x, y) = (&a.nodes()[i as usize], &b.nodes()[j as usize]);
            // 7: the root pair is never tested.
            let test = !(which == 7 && first);
            first = false;
            if test && !x.bv.overlaps(&y.bv) {
                continue;
            }
            if x.is_leaf() && y.is_leaf() {
                for &p in a.leaf_primitives(x) {
                    for &q in b.leaf_primitives(y) {
                        // 6: the leaves' boxes decide, not the primitives'.
                        if which == 6 || pa[p as usize].overlaps(&pb[q as usize]) {
                            out.push((p, q));
                        }
                    }
                }
                continue;
            }
            let open_a = Reference.descend_a(x, y);
            let Some((l, r)) = (if open_a { x.children() } else { y.children() }) else {
                return false;
            };
            // 5: pushes the first child twice, never the second.
            let r = if which == 5 { l } else { r };
            for c in [r, l] {
                if !push(stack, &mut top, if open_a { (c, j) } else { (i, c) }) {
                    return false;
                }
            }
        }
        true
    }

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
            // No pruning and no stack: every pair of leaves in tree order.
            4 => {
                super::super::ex05_recursive_pairs::wrong::every_leaf_pair(a, pa, b, pb, out);
                true
            }
            2 | 3 | 5..=7 => walk(which, a, pa, b, pb, stack, out),
            _ => Reference.stack_dfs(a, pa, b, pb, stack, out),
        }
    }
}
