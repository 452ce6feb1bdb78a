//! Exercise 5: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 5.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 5,
            name: "finds exactly the brute-force pairs on overlapping grids",
            points: 6,
            run: |e| {
                traversal_cases()[..2]
                    .iter()
                    .all(|(a, b)| sorted(run_dfs(e, a, b)) == reference_pairs(a, b))
            },
        },
        Check {
            exercise: 5,
            name: "tiny trees (1-3 leaves), apart and touching",
            points: 5,
            run: |e| {
                traversal_cases()[2..]
                    .iter()
                    .all(|(a, b)| sorted(run_dfs(e, a, b)) == reference_pairs(a, b))
            },
        },
        Check {
            exercise: 5,
            name: "reports each pair once",
            points: 4,
            run: |e| {
                traversal_cases().iter().all(|(a, b)| {
                    let got = run_dfs(e, a, b);
                    let mut unique = sorted(got.clone());
                    unique.dedup();
                    unique.len() == got.len()
                })
            },
        },
    ]
}

fn run_dfs(e: &dyn Exercises, a: &Tree, b: &Tree) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    e.informed_dfs(&a.bvh(), &a.prims, &b.bvh(), &b.prims, &mut out);
    out
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 1;

    pub fn informed_dfs(
        which: u32,
        a: &Bvh<Aabb>,
        pa: &[Aabb],
        b: &Bvh<Aabb>,
        pb: &[Aabb],
        out: &mut Vec<(u32, u32)>,
    ) {
        match which {
            // Tests the leaves' volumes but not the primitives inside.
            1 => {
                for x in a.nodes().iter().filter(|n| n.is_leaf()) {
                    for y in b.nodes().iter().filter(|n| n.is_leaf()) {
                        if x.bv.overlaps(&y.bv) {
                            for &p in a.leaf_primitives(x) {
                                for &q in b.leaf_primitives(y) {
                                    out.push((p, q));
                                }
                            }
                        }
                    }
                }
            }
            _ => Reference.informed_dfs(a, pa, b, pb, out),
        }
    }
}
