//! Exercise 15: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 15.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 15,
            name: "workload time: built once, rebuilt every frame, and 0 or 1 frames",
            points: 4,
            run: |e| {
                let close = |x: f64, want: f64| (x - want).abs() <= 1e-9 * want.abs().max(1.0);
                close(e.workload_ms(10.0, 2.0, false, 60), 130.0)
                    && close(e.workload_ms(10.0, 2.0, true, 60), 720.0)
                    && close(e.workload_ms(10.0, 2.0, false, 0), 10.0)
                    && close(e.workload_ms(10.0, 2.0, true, 0), 0.0)
                    && close(e.workload_ms(3.5, 0.25, false, 1), 3.75)
                    && close(e.workload_ms(3.5, 0.25, true, 1), 3.75)
            },
        },
        Check {
            exercise: 15,
            name: "Pareto front: a staircase with dominated points",
            points: 3,
            run: |e| {
                e.pareto_front(&[(1.0, 5.0), (2.0, 2.0), (3.0, 3.0), (4.0, 1.0), (5.0, 5.0)])
                    == [0, 1, 3]
                    && e.pareto_front(&[]).is_empty()
                    && e.pareto_front(&[(7.0, 7.0)]) == [0]
            },
        },
        Check {
            exercise: 15,
            name: "Pareto front: ties, duplicates, and random points on a small grid",
            points: 3,
            run: |e| {
                let ties =
                    e.pareto_front(&[(2.0, 2.0), (2.0, 2.0), (2.0, 3.0), (3.0, 2.0)]) == [0, 1];
                let mut s = 0x9e37_79b9_7f4a_7c15u64;
                let random = (0..40).all(|_| {
                    let points: Vec<(f64, f64)> = (0..12)
                        .map(|_| {
                            s = s.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
                            (((s >> 33) % 5) as f64, ((s >> 45) % 5) as f64)
                        })
                        .collect();
                    e.pareto_front(&points) == Reference.pareto_front(&points)
                });
                ties && random
            },
        },
    ]
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 4;

    pub fn workload_ms(which: u32, build: f64, query: f64, rebuild: bool, frames: usize) -> f64 {
        let n = frames as f64;
        match which {
            // Ignores the motion: always builds once.
            1 => build + n * query,
            // Rebuilds every frame and once more before the first.
            2 if rebuild => (n + 1.0) * build + n * query,
            _ => Reference.workload_ms(build, query, rebuild, frames),
        }
    }

    pub fn pareto_front(which: u32, points: &[(f64, f64)]) -> Vec<usize> {
        let dominated = |i: usize, strict: bool| {
            let (t, x) = points[i];
            points.iter().enumerate().any(|(j, &(u, y))| {
                j != i
                    && if strict {
                        u < t && y < x
                    } else {
                        u <= t && y <= x && (u < t || y < x)
                    }
            })
        };
        match which {
            // Dominance only when better on both: keeps points that tie on one.
            3 => (0..points.len()).filter(|&i| !dominated(i, true)).collect(),
            // Keeps only the first of equal points.
            4 => (0..points.len())
                .filter(|&i| !dominated(i, false) && !points[..i].contains(&points[i]))
                .collect(),
            _ => Reference.pareto_front(points),
        }
    }
}
