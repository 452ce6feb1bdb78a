//! Exercise 53: binning along one axis, and the partition that must agree
//! with it. The checks, and the plausible wrong answers they must reject.
//!
//! A binned builder takes the children's boxes from the bins; the partition
//! then moves every primitive to a side by its own test. If the two disagree
//! on one primitive, that primitive sits in a child whose box was made
//! without it: a tree that misses overlaps. So the grader compares the
//! student's two functions with each other on the values where they can
//! disagree (on the planes and the floats beside them), besides checking
//! the bins themselves against the reference.

use super::common::*;

/// The checks of exercise 53.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 53,
            name: "each bin's middle is in that bin; values outside the extent go to the end bins",
            points: 3,
            run: |e| {
                grids().iter().all(|g| {
                    let top = g.lo + g.k as f32 / g.scale;
                    let mut cases: Vec<(f32, usize)> = (0..g.k)
                        .map(|j| (g.lo + (j as f32 + 0.5) / g.scale, j))
                        .collect();
                    cases.extend([
                        (g.lo, 0),
                        (top, g.k - 1), // the centroids' largest value
                        (g.lo - 1e3 / g.scale, 0),
                        (top + 1e3 / g.scale, g.k - 1),
                    ]);
                    cases.iter().all(|&(t, want)| {
                        let got = e.bin_index(t, g.lo, g.scale, g.k);
                        got == want
                            || fail(format!(
                                "bin_index(t {t}, lo {}, scale {}, k {}) returned {got}, expected {want}",
                                g.lo, g.scale, g.k
                            ))
                    })
                })
            },
        },
        Check {
            exercise: 53,
            name: "bins never decrease along the axis, and stay in 0..k",
            points: 2,
            run: |e| {
                grids().iter().all(|g| {
                    let mut values = near_planes(g);
                    values.sort_by(f32::total_cmp);
                    let mut last = 0;
                    values.iter().all(|&t| {
                        let bin = e.bin_index(t, g.lo, g.scale, g.k);
                        let ok = bin < g.k && bin >= last;
                        last = bin;
                        ok || fail(format!(
                            "bin_index(t {t}, lo {}, scale {}, k {}) returned {bin} after bin {last} \
                             for a smaller value",
                            g.lo, g.scale, g.k
                        ))
                    })
                })
            },
        },
        Check {
            exercise: 53,
            name: "the partition agrees with the bins on every plane and the floats beside it",
            points: 5,
            run: |e| {
                grids().iter().all(|g| {
                    near_planes(g).iter().all(|&t| {
                        let bin = e.bin_index(t, g.lo, g.scale, g.k);
                        (1..g.k).all(|boundary| {
                            let left = e.bin_goes_left(t, g.lo, g.scale, g.k, boundary);
                            left == (bin < boundary)
                                || fail(format!(
                                    "bin_goes_left(t {t}, lo {}, scale {}, k {}, boundary \
                                     {boundary}) returned {left}, but bin_index gave bin {bin}",
                                    g.lo, g.scale, g.k
                                ))
                        })
                    })
                })
            },
        },
    ]
}

/// One axis's bins: `k` of width `1 / scale` from `lo`.
struct Grid {
    lo: f32,
    scale: f32,
    k: usize,
}

/// Whole-number grids (where a plane falls exactly on a value) and grids
/// whose planes round (tenths, far from the origin, tiny).
fn grids() -> Vec<Grid> {
    let mut r = Rng(0x53b1_4e5a_77c2_0d19);
    let mut g = vec![
        Grid {
            lo: 0.0,
            scale: 1.0,
            k: 4,
        },
        Grid {
            lo: -8.0,
            scale: 0.5,
            k: 8,
        },
        Grid {
            lo: 0.1,
            scale: 10.0,
            k: 16,
        },
        Grid {
            lo: 1.0e5,
            scale: 16.0 / 3.0,
            k: 16,
        },
    ];
    for i in 0..40 {
        let k = [2, 3, 5, 8, 12, 16, 31, 32][i % 8];
        let lo = (r.next() - 0.5) * [1.0, 1e3, 1e6, 1e-3][i % 4];
        // Bins at least a few dozen floats wide, even far from the origin.
        let extent = (r.next() + 0.01) * lo.abs().max(1.0) * [1.0, 0.1, 0.01][i % 3];
        g.push(Grid {
            lo,
            scale: k as f32 / extent,
            k,
        });
    }
    g
}

/// Every plane of `g`, the two floats either side of it, the floats around
/// the extent's ends, and random values inside and outside.
fn near_planes(g: &Grid) -> Vec<f32> {
    let mut r = Rng(0x9e37_79b9 ^ g.k as u64 ^ g.lo.to_bits() as u64);
    let mut v = Vec::new();
    for j in 0..=g.k {
        let plane = g.lo + j as f32 / g.scale;
        for step in 0..=2u32 {
            v.push(f32::from_bits(plane.to_bits().wrapping_add(step)));
            v.push(f32::from_bits(plane.to_bits().wrapping_sub(step)));
        }
    }
    let extent = g.k as f32 / g.scale;
    for _ in 0..50 {
        v.push(g.lo + (r.next() * 1.4 - 0.2) * extent);
    }
    v.retain(|t| t.is_finite());
    v
}

/// Plausible wrong answers (for the grader's self-test).
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 5;

    /// Wrong answer `which` for the bin:
    /// 1 no clamp at the top: the largest centroid gets bin `k`;
    /// 3 rounds to the nearest bin instead of down;
    /// 5 clamps through `i32` and `usize`: a value below `lo` wraps to a huge
    ///   index, and the clamp at the top sends it to the last bin.
    pub fn bin_index(which: u32, t: f32, lo: f32, scale: f32, k: usize) -> usize {
        let x = (t - lo) * scale;
        match which {
            1 => x.max(0.0) as usize,
            3 => (x.max(0.0).round() as usize).min(k - 1),
            5 => (x as i32 as usize).min(k - 1),
            _ => Reference.bin_index(t, lo, scale, k),
        }
    }

    /// Wrong answer `which` for the partition:
    /// 2 compares the value with the plane's position, `lo + boundary / scale`,
    ///   which rounds differently from the bin's arithmetic;
    /// 4 sends a value on the plane left (`<=` for `<`).
    pub fn bin_goes_left(
        which: u32,
        t: f32,
        lo: f32,
        scale: f32,
        k: usize,
        boundary: usize,
    ) -> bool {
        match which {
            2 => t < lo + boundary as f32 / scale,
            4 => (t - lo) * scale <= boundary as f32,
            _ => Reference.bin_goes_left(t, lo, scale, k, boundary),
        }
    }
}
