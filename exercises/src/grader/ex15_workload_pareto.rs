//! Exercise 15: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 15.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 15,
            name: "workload time: built once, rebuilt every frame, 0 or 1 frames, in f64",
            points: 4,
            run: |e| {
                [
                    (10.0, 2.0, false, 60, 130.0),
                    (10.0, 2.0, true, 60, 720.0),
                    (10.0, 2.0, false, 0, 10.0),
                    (10.0, 2.0, true, 0, 0.0),
                    (3.5, 0.25, false, 1, 3.75),
                    (3.5, 0.25, true, 1, 3.75),
                    // 0.1 is not exact in binary: f32 arithmetic is off by 1e-8.
                    (0.3, 0.1, false, 1000, 100.3),
                    (0.3, 0.1, true, 1000, 400.0),
                ]
                .iter()
                .all(|&(build, query, rebuild, frames, want)| {
                    near(
                        format!("workload_ms({build}, {query}, {rebuild}, {frames})"),
                        want,
                        e.workload_ms(build, query, rebuild, frames),
                    )
                })
            },
        },
        Check {
            exercise: 15,
            name: "Pareto front: a staircase with dominated points, in index order",
            points: 3,
            run: |e| {
                [
                    (
                        vec![(1.0, 5.0), (2.0, 2.0), (3.0, 3.0), (4.0, 1.0), (5.0, 5.0)],
                        vec![0, 1, 3],
                    ),
                    // Not sorted by time: the answer is still in index order.
                    (
                        vec![(4.0, 1.0), (1.0, 5.0), (3.0, 3.5), (2.0, 2.0)],
                        vec![0, 1, 3],
                    ),
                    (vec![], vec![]),
                    (vec![(7.0, 7.0)], vec![0]),
                ]
                .iter()
                .all(|(points, want)| front_is(e, points, want))
            },
        },
        Check {
            exercise: 15,
            name: "Pareto front: ties, duplicates, and random points on a small grid",
            points: 3,
            run: |e| {
                let ties = front_is(
                    e,
                    &[(2.0, 2.0), (2.0, 2.0), (2.0, 3.0), (3.0, 2.0)],
                    &[0, 1],
                );
                let mut s = 0x9e37_79b9_7f4a_7c15u64;
                ties && (0..40).all(|_| {
                    let points: Vec<(f64, f64)> = (0..12)
                        .map(|_| {
                            s = s.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
                            (((s >> 33) % 5) as f64, ((s >> 45) % 5) as f64)
                        })
                        .collect();
                    front_is(e, &points, &Reference.pareto_front(&points))
                })
            },
        },
    ]
}

/// Whether the front of `points` is `want`, explained on failure.
fn front_is(e: &dyn Exercises, points: &[(f64, f64)], want: &[usize]) -> bool {
    let shown: Vec<String> = points.iter().map(|(t, x)| format!("({t}, {x})")).collect();
    same(
        format!("pareto_front([{}])", shown.join(", ")),
        want.to_vec(),
        e.pareto_front(points),
    )
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 8;

    pub fn workload_ms(which: u32, build: f64, query: f64, rebuild: bool, frames: usize) -> f64 {
        let n = frames as f64;
        match which {
            // Ignores the motion: always builds once.
            1 => build + n * query,
            // Rebuilds every frame and once more before the first.
            2 if rebuild => (n + 1.0) * build + n * query,
            // At least one build even with no frames to run.
            5 if rebuild => n.max(1.0) * build + n * query,
            // Sums in f32.
            6 => {
                let builds = if rebuild { frames as f32 } else { 1.0 };
                (builds * build as f32 + frames as f32 * query as f32) as f64
            }
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
            // "No worse on both" without "strictly better on one": equal
            // points knock each other out.
            7 => (0..points.len())
                .filter(|&i| {
                    let (t, x) = points[i];
                    !points
                        .iter()
                        .enumerate()
                        .any(|(j, &(u, y))| j != i && u <= t && y <= x)
                })
                .collect(),
            // In the order of a sweep by time, not by index.
            8 => {
                let mut front = Reference.pareto_front(points);
                front.sort_by(|&a, &b| points[a].0.total_cmp(&points[b].0));
                front
            }
            _ => Reference.pareto_front(points),
        }
    }
}
