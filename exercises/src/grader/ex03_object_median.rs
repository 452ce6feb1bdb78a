//! Exercise 3: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 3.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 3,
            name: "returns n / 2",
            points: 2,
            run: |e| {
                let mut r = Rng(3);
                (1..40).all(|n| {
                    let c = r.cloud(n, 10.0, Vec3::ZERO);
                    let mut idx: Vec<u32> = (0..n as u32).collect();
                    let got = e.median_partition(&c, &mut idx);
                    same(
                        format!("median_partition of {n} random centroids"),
                        n / 2,
                        got,
                    )
                })
            },
        },
        Check {
            exercise: 3,
            name: "indices stay a permutation",
            points: 1,
            run: |e| {
                let mut r = Rng(4);
                let c = r.cloud(101, 10.0, Vec3::ZERO);
                let mut idx: Vec<u32> = (0..101).rev().collect();
                e.median_partition(&c, &mut idx);
                idx.sort_unstable();
                idx == (0..101).collect::<Vec<u32>>()
                    || fail(
                        "median_partition of 101 random centroids: afterwards the indices \
                         were no longer 0..=100 each once (reorder them, do not overwrite them)",
                    )
            },
        },
        Check {
            exercise: 3,
            name: "left half <= right half along the longest axis (y here, with equal coordinates)",
            points: 2,
            run: |e| {
                let c = stretched(77, 5, Vec3::new(1.0, 20.0, 3.0), true);
                split_ok(
                    e,
                    &c,
                    (0..77).collect(),
                    "77 centroids spread (1, 20, 3), many sharing their y",
                )
            },
        },
        Check {
            exercise: 3,
            name: "the axis comes from the centroids (z, then x here), not fixed",
            points: 2,
            run: |e| {
                let z = stretched(77, 6, Vec3::new(2.0, 1.0, 30.0), false);
                let x = stretched(77, 9, Vec3::new(40.0, 1.0, 3.0), false);
                split_ok(e, &z, (0..77).collect(), "77 centroids spread (2, 1, 30)")
                    && split_ok(e, &x, (0..77).collect(), "77 centroids spread (40, 1, 3)")
            },
        },
        Check {
            exercise: 3,
            name: "the box is over the centroids that indices names, not the whole array",
            points: 2,
            run: |e| {
                // Even entries spread along x, odd ones along y; the indices
                // name the odd ones (in a builder, one node's primitives).
                let mut r = Rng(10);
                let c: Vec<Vec3> = (0..200)
                    .map(|i| {
                        let s = if i % 2 == 0 {
                            Vec3::new(40.0, 1.0, 1.0)
                        } else {
                            Vec3::new(1.0, 20.0, 1.0)
                        };
                        r.point(1.0, Vec3::ZERO) * s
                    })
                    .collect();
                split_ok(
                    e,
                    &c,
                    (0..100).map(|i| 2 * i + 1).collect(),
                    "200 centroids, the even ones spread 40 along x, the odd ones 20 along y; \
                     indices = the 100 odd ones (their box is longest in y)",
                )
            },
        },
        Check {
            exercise: 3,
            name: "a tie between axes goes to x, then y",
            points: 1,
            run: |e| {
                let c: Vec<Vec3> = (0..16)
                    .map(|i| Vec3::new((i % 4) as f32, (i / 4) as f32, 0.0))
                    .collect();
                split_ok(
                    e,
                    &c,
                    (0..16).collect(),
                    "16 centroids on a 4 x 4 grid in the xy plane (x and y extents both 3)",
                )
            },
        },
    ]
}

/// `n` random centroids in a unit cube scaled by `stretch`; `round`ed to
/// whole numbers (many equal coordinates) if asked.
fn stretched(n: usize, seed: u64, stretch: Vec3, round: bool) -> Vec<Vec3> {
    let mut r = Rng(seed);
    r.cloud(n, 1.0, Vec3::ZERO)
        .iter()
        .map(|p| {
            let q = *p * stretch;
            if round {
                q.round()
            } else {
                q
            }
        })
        .collect()
}

/// Runs `median_partition` on `idx` and checks the answer: `n / 2` back,
/// the same indices, and no centroid of the first half above one of the
/// second along the longest axis of the named centroids' box (x first, then
/// y, on a tie).
fn split_ok(e: &dyn Exercises, c: &[Vec3], mut idx: Vec<u32>, what: &str) -> bool {
    let named: Vec<Vec3> = idx.iter().map(|&i| c[i as usize]).collect();
    let axis = Aabb::fit(named.as_slice()).longest_axis();
    let name = ["x", "y", "z"][axis];
    let mut before = idx.clone();
    let n = idx.len();
    let mid = e.median_partition(c, &mut idx);
    if mid != n / 2 {
        return fail(format!(
            "median_partition({what}) returned {mid}, expected {}",
            n / 2
        ));
    }
    let mut after = idx.clone();
    before.sort_unstable();
    after.sort_unstable();
    if before != after {
        return fail(format!(
            "median_partition({what}): afterwards the indices were not the same ones \
             reordered"
        ));
    }
    let key = |i: &u32| c[*i as usize][axis];
    let high = idx[..mid]
        .iter()
        .copied()
        .max_by(|p, q| key(p).total_cmp(&key(q)));
    let low = idx[mid..]
        .iter()
        .copied()
        .min_by(|p, q| key(p).total_cmp(&key(q)));
    match (high, low) {
        (Some(h), Some(l)) if key(&h) > key(&l) => fail(format!(
            "median_partition({what}): the first {mid} indices should name the centroids \
             with the smallest {name} (the longest axis), but centroid {h} ({name} = {}) is \
             among them and centroid {l} ({name} = {}) is not",
            key(&h),
            key(&l)
        )),
        _ => true,
    }
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 7;

    pub fn median_partition(which: u32, centroids: &[Vec3], indices: &mut [u32]) -> usize {
        let named: Vec<Vec3> = indices.iter().map(|&i| centroids[i as usize]).collect();
        let cb = Aabb::fit(named.as_slice());
        let by = |axis: usize, indices: &mut [u32]| {
            indices.sort_unstable_by(|&a, &b| {
                centroids[a as usize][axis].total_cmp(&centroids[b as usize][axis])
            })
        };
        let mid = indices.len() / 2;
        match which {
            // Always splits along x.
            1 => {
                by(0, indices);
                mid
            }
            // No reordering at all.
            2 => mid,
            // The axis from the box of every centroid, not only the named ones.
            3 => {
                by(Aabb::fit(centroids).longest_axis(), indices);
                mid
            }
            // Sorted the wrong way round: the largest first.
            4 => {
                by(cb.longest_axis(), indices);
                indices.reverse();
                mid
            }
            // Rounds the half up.
            5 => {
                by(cb.longest_axis(), indices);
                indices.len().div_ceil(2)
            }
            // The spatial median: splits at the middle of the box instead
            // and returns how many fell below it.
            6 => {
                let axis = cb.longest_axis();
                let cut = (cb.min[axis] + cb.max[axis]) * 0.5;
                by(axis, indices);
                indices
                    .iter()
                    .filter(|&&i| centroids[i as usize][axis] < cut)
                    .count()
            }
            // On a tie between extents, takes the last axis.
            7 => {
                let x = cb.extent();
                let axis = if x.z >= x.x && x.z >= x.y {
                    2
                } else if x.y >= x.x {
                    1
                } else {
                    0
                };
                by(axis, indices);
                mid
            }
            _ => Reference.median_partition(centroids, indices),
        }
    }
}
