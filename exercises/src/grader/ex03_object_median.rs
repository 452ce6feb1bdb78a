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
                    e.median_partition(&c, &mut idx) == n / 2
                })
            },
        },
        Check {
            exercise: 3,
            name: "indices stay a permutation",
            points: 2,
            run: |e| {
                let mut r = Rng(4);
                let c = r.cloud(101, 10.0, Vec3::ZERO);
                let mut idx: Vec<u32> = (0..101).rev().collect();
                e.median_partition(&c, &mut idx);
                idx.sort_unstable();
                idx == (0..101).collect::<Vec<u32>>()
            },
        },
        Check {
            exercise: 3,
            name: "left half <= right half along the longest axis (y here)",
            points: 3,
            run: |e| median_ok(e, Vec3::new(1.0, 20.0, 3.0), 5),
        },
        Check {
            exercise: 3,
            name: "the axis comes from the centroids (z here), not fixed",
            points: 3,
            run: |e| {
                median_ok(e, Vec3::new(2.0, 1.0, 30.0), 6)
                    && median_ok(e, Vec3::new(40.0, 1.0, 3.0), 9)
            },
        },
    ]
}

fn median_ok(e: &dyn Exercises, stretch: Vec3, seed: u64) -> bool {
    let mut r = Rng(seed);
    let c: Vec<Vec3> = r
        .cloud(77, 1.0, Vec3::ZERO)
        .iter()
        .map(|p| *p * stretch)
        .collect();
    let axis = Aabb::fit(c.as_slice()).longest_axis();
    let mut idx: Vec<u32> = (0..77).collect();
    let mid = e.median_partition(&c, &mut idx);
    if mid != 38 {
        return false;
    }
    let left = idx[..mid]
        .iter()
        .map(|&i| c[i as usize][axis])
        .fold(f32::NEG_INFINITY, f32::max);
    let right = idx[mid..]
        .iter()
        .map(|&i| c[i as usize][axis])
        .fold(f32::INFINITY, f32::min);
    left <= right
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 2;

    pub fn median_partition(which: u32, centroids: &[Vec3], indices: &mut [u32]) -> usize {
        match which {
            1 => {
                let mid = indices.len() / 2;
                indices.sort_unstable_by(|&a, &b| {
                    centroids[a as usize].x.total_cmp(&centroids[b as usize].x)
                });
                mid
            }
            2 => indices.len() / 2, // no reordering at all
            _ => Reference.median_partition(centroids, indices),
        }
    }
}
