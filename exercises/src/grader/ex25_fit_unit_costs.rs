//! Exercise 25: fitting unit costs. The checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 25.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 25,
            name: "times made by a known model come back exactly, also from nearly proportional rows (f64)",
            points: 2,
            run: |e| {
                let exact: Vec<(u64, u64, f64)> = (0..12)
                    .map(|i| {
                        let (nv, np) = (100 + 997 * i as u64, 50 + (i as u64 * 7919) % 3001);
                        (nv, np, 6.0 * nv as f64 + 30.0 * np as f64)
                    })
                    .collect();
                // Rows (Nv, Np) close to proportional: the 2x2 system is
                // badly conditioned, and sums in f32 lose the answer.
                let steep: Vec<(u64, u64, f64)> = (0..10)
                    .map(|i| {
                        let (nv, np) = (10_000 + i as u64, 10_000 + 2 * i as u64);
                        (nv, np, 6.0 * nv as f64 + 30.0 * np as f64)
                    })
                    .collect();
                fit_is(e, "12 samples made by Cv = 6, Cp = 30", &exact, (6.0, 30.0))
                    && fit_is(
                        e,
                        "10 samples made by Cv = 6, Cp = 30, rows (10000 + i, 10000 + 2i)",
                        &steep,
                        (6.0, 30.0),
                    )
            },
        },
        Check {
            exercise: 25,
            name: "noisy samples of small and large queries: the relative error decides, not the absolute",
            points: 3,
            run: |e| {
                let mut r = Rng(2525);
                // Small and large queries with +-20% noise: a fit on absolute
                // error lets the large ones decide; the relative one does not.
                (0..200).all(|_| {
                    let d: Vec<(u64, u64, f64)> = (0..10)
                        .map(|i| {
                            let scale = if i % 2 == 0 { 1u64 } else { 10_000 };
                            let nv = scale * (1 + (r.next() * 50.0) as u64);
                            let np = scale * (1 + (r.next() * 20.0) as u64);
                            let t = (5.0 * nv as f64 + 40.0 * np as f64)
                                * (0.8 + 0.4 * r.next() as f64);
                            (nv, np, t)
                        })
                        .collect();
                    fit_is(e, &format!("10 samples of t = 5 Nv + 40 Np with +-20% noise, every other one 10,000 times larger: {d:?}"), &d, Reference.fit_unit_costs(&d))
                })
            },
        },
        Check {
            exercise: 25,
            name: "costs never negative: the better one-cost fit when the pair has a negative entry",
            points: 3,
            run: |e| {
                // t = 5 Nv - 1 Np: the unconstrained fit makes Cp negative.
                let negative: Vec<(u64, u64, f64)> = (1..10u64)
                    .map(|i| {
                        (
                            100 * i,
                            30 * i * i,
                            500.0 * i as f64 - 30.0 * (i * i) as f64,
                        )
                    })
                    .collect();
                // Cv alone, fitted on relative error: sum(x) / sum(x^2), x = Nv/t.
                let xs: Vec<f64> = negative.iter().map(|&(nv, _, t)| nv as f64 / t).collect();
                let alone = xs.iter().sum::<f64>() / xs.iter().map(|x| x * x).sum::<f64>();
                let mut r = Rng(2526);
                fit_is(e, "9 samples made by t = 5 Nv - Np", &negative, (alone, 0.0))
                    && (0..300).all(|_| {
                        // Random signs of the true costs: both clamps happen.
                        let (a, b) = (r.next() as f64 * 20.0 - 5.0, r.next() as f64 * 20.0 - 5.0);
                        let d: Vec<(u64, u64, f64)> = (0..6)
                            .map(|_| {
                                let (nv, np) =
                                    (1 + (r.next() * 90.0) as u64, 1 + (r.next() * 90.0) as u64);
                                (nv, np, (a * nv as f64 + b * np as f64).abs() + 1.0)
                            })
                            .collect();
                        fit_is(e, &format!("6 samples of t = |a Nv + b Np| + 1: {d:?}"), &d, Reference.fit_unit_costs(&d))
                    })
            },
        },
        Check {
            exercise: 25,
            name: "samples with t <= 0 skipped; no usable sample (or only zero counts) gives (0, 0)",
            points: 2,
            run: |e| {
                fit_is(e, "no samples", &[], (0.0, 0.0))
                    && fit_is(
                        e,
                        "[(0, 0, 5.0), (3, 4, 0.0)]",
                        &[(0, 0, 5.0), (3, 4, 0.0)],
                        (0.0, 0.0),
                    )
                    && fit_is(
                        e,
                        "[(10, 0, 50.0), (20, 0, -1.0)]",
                        &[(10, 0, 50.0), (20, 0, -1.0)],
                        (5.0, 0.0),
                    )
                    && fit_is(
                        e,
                        "[(0, 10, 80.0), (7, 3, 0.0), (0, 20, 160.0)]",
                        &[(0, 10, 80.0), (7, 3, 0.0), (0, 20, 160.0)],
                        (0.0, 8.0),
                    )
            },
        },
    ]
}

/// Whether `fit_unit_costs(samples)` is `want`, each cost within 1e-6
/// (relative); `what` describes the samples.
fn fit_is(e: &dyn Exercises, what: &str, samples: &[(u64, u64, f64)], want: (f64, f64)) -> bool {
    let got = e.fit_unit_costs(samples);
    let near = |x: f64, w: f64| (x - w).abs() <= 1e-6 * w.abs().max(1e-9);
    (near(got.0, want.0) && near(got.1, want.1))
        || fail(format!(
            "fit_unit_costs({what}) returned (Cv, Cp) = {got:?}, expected {want:?}"
        ))
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 7;

    pub fn fit_unit_costs(which: u32, samples: &[(u64, u64, f64)]) -> (f64, f64) {
        // The 2x2 normal equations with weights w per sample.
        let solve = |weight: &dyn Fn(f64) -> f64| {
            let (mut xx, mut xy, mut yy, mut xt, mut yt) = (0.0, 0.0, 0.0, 0.0, 0.0);
            for &(nv, np, t) in samples.iter().filter(|s| s.2 > 0.0) {
                let w = weight(t);
                let (x, y) = (nv as f64 * w, np as f64 * w);
                (xx, xy, yy) = (xx + x * x, xy + x * y, yy + y * y);
                (xt, yt) = (xt + x * t * w, yt + y * t * w);
            }
            let det = xx * yy - xy * xy;
            if det.abs() <= 1e-12 * xx * yy {
                return (0.0, 0.0, xx, yy, xt, yt);
            }
            (
                (xt * yy - yt * xy) / det,
                (xx * yt - xy * xt) / det,
                xx,
                yy,
                xt,
                yt,
            )
        };
        match which {
            // Absolute error: the large queries decide.
            1 => {
                let (cv, cp, ..) = solve(&|_| 1.0);
                (cv.max(0.0), cp.max(0.0))
            }
            // The unconstrained answer, negative cost and all.
            2 => {
                let (cv, cp, ..) = solve(&|t| 1.0 / t);
                (cv, cp)
            }
            // Clamps a negative cost to 0 without refitting the other.
            3 => {
                let (cv, cp, ..) = solve(&|t| 1.0 / t);
                (cv.max(0.0), cp.max(0.0))
            }
            // Keeps the samples with t <= 0 (a negative t flips its row).
            4 => {
                let (mut xx, mut xy, mut yy, mut x1, mut y1) = (0.0, 0.0, 0.0, 0.0, 0.0);
                for &(nv, np, t) in samples.iter().filter(|s| s.2 != 0.0) {
                    let (x, y) = (nv as f64 / t, np as f64 / t);
                    (xx, xy, yy, x1, y1) = (xx + x * x, xy + x * y, yy + y * y, x1 + x, y1 + y);
                }
                let det = xx * yy - xy * xy;
                if det.abs() > 1e-12 * xx * yy {
                    let (cv, cp) = ((x1 * yy - y1 * xy) / det, (xx * y1 - xy * x1) / det);
                    if cv >= 0.0 && cp >= 0.0 {
                        return (cv, cp);
                    }
                }
                let cv = if xx > 0.0 { (x1 / xx).max(0.0) } else { 0.0 };
                (cv, 0.0)
            }
            // Whichever cost comes out negative, holds Cp at 0 and refits Cv.
            5 => {
                let (cv, cp) = Reference.fit_unit_costs(samples);
                if cv == 0.0 && cp > 0.0 {
                    let (mut xx, mut x1) = (0.0, 0.0);
                    for &(nv, _, t) in samples.iter().filter(|s| s.2 > 0.0) {
                        let x = nv as f64 / t;
                        (xx, x1) = (xx + x * x, x1 + x);
                    }
                    ((x1 / xx).max(0.0), 0.0)
                } else {
                    (cv, cp)
                }
            }
            // The sums in f32.
            6 => {
                let (mut xx, mut xy, mut yy, mut x1, mut y1) = (0f32, 0f32, 0f32, 0f32, 0f32);
                for &(nv, np, t) in samples.iter().filter(|s| s.2 > 0.0) {
                    let (x, y) = (nv as f32 / t as f32, np as f32 / t as f32);
                    (xx, xy, yy, x1, y1) = (xx + x * x, xy + x * y, yy + y * y, x1 + x, y1 + y);
                }
                let det = xx * yy - xy * xy;
                if det > 1e-12 * xx * yy {
                    let (cv, cp) = ((x1 * yy - y1 * xy) / det, (xx * y1 - xy * x1) / det);
                    if cv >= 0.0 && cp >= 0.0 {
                        return (cv as f64, cp as f64);
                    }
                }
                Reference.fit_unit_costs(samples)
            }
            // No guard for nothing to fit: 0 / 0.
            7 => {
                let (mut xx, mut x1, mut yy, mut y1) = (0.0, 0.0, 0.0, 0.0);
                for &(nv, np, t) in samples.iter().filter(|s| s.2 > 0.0) {
                    let (x, y) = (nv as f64 / t, np as f64 / t);
                    (xx, x1, yy, y1) = (xx + x * x, x1 + x, yy + y * y, y1 + y);
                }
                if xx == 0.0 || yy == 0.0 {
                    return (x1 / xx, y1 / yy);
                }
                Reference.fit_unit_costs(samples)
            }
            _ => Reference.fit_unit_costs(samples),
        }
    }
}
