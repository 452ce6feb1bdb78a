//! Exercise 25: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 25.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 25,
            name: "fit (Cv, Cp) on relative error: exact data back, noisy data as the reference",
            points: 5,
            run: |e| {
                let close = |(a, b): (f64, f64), (c, d): (f64, f64)| {
                    (a - c).abs() <= 1e-6 * c.abs().max(1e-9)
                        && (b - d).abs() <= 1e-6 * d.abs().max(1e-9)
                };
                let mut r = Rng(2525);
                // Times made by a known model come back exactly.
                let exact: Vec<(u64, u64, f64)> = (0..12)
                    .map(|i| {
                        let (nv, np) = (100 + 997 * i as u64, 50 + (i as u64 * 7919) % 3001);
                        (nv, np, 6.0 * nv as f64 + 30.0 * np as f64)
                    })
                    .collect();
                // Small and large queries with +-20% noise: a fit on absolute
                // error lets the large ones decide; the relative one does not.
                let noisy = |r: &mut Rng| -> Vec<(u64, u64, f64)> {
                    (0..10)
                        .map(|i| {
                            let scale = if i % 2 == 0 { 1u64 } else { 10_000 };
                            let nv = scale * (1 + (r.next() * 50.0) as u64);
                            let np = scale * (1 + (r.next() * 20.0) as u64);
                            let t = (5.0 * nv as f64 + 40.0 * np as f64)
                                * (0.8 + 0.4 * r.next() as f64);
                            (nv, np, t)
                        })
                        .collect()
                };
                close(e.fit_unit_costs(&exact), (6.0, 30.0))
                    && (0..200).all(|_| {
                        let d = noisy(&mut r);
                        close(e.fit_unit_costs(&d), Reference.fit_unit_costs(&d))
                    })
            },
        },
        Check {
            exercise: 25,
            name: "costs never negative (the other refitted alone); no usable sample gives (0, 0)",
            points: 5,
            run: |e| {
                let close = |(a, b): (f64, f64), (c, d): (f64, f64)| {
                    (a - c).abs() <= 1e-6 * c.abs().max(1e-9)
                        && (b - d).abs() <= 1e-6 * d.abs().max(1e-9)
                };
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
                let (cv, cp) = e.fit_unit_costs(&negative);
                // Cv alone, fitted on relative error: sum(x) / sum(x^2), x = Nv/t.
                let xs: Vec<f64> = negative.iter().map(|&(nv, _, t)| nv as f64 / t).collect();
                let alone = xs.iter().sum::<f64>() / xs.iter().map(|x| x * x).sum::<f64>();
                let mut r = Rng(2526);
                cp == 0.0
                    && (cv - alone).abs() <= 1e-6 * alone
                    && close(e.fit_unit_costs(&[]), (0.0, 0.0))
                    && close(e.fit_unit_costs(&[(0, 0, 5.0), (3, 4, 0.0)]), (0.0, 0.0))
                    && close(
                        e.fit_unit_costs(&[(10, 0, 50.0), (20, 0, -1.0)]),
                        (5.0, 0.0),
                    )
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
                        let got = e.fit_unit_costs(&d);
                        got.0 >= 0.0 && got.1 >= 0.0 && close(got, Reference.fit_unit_costs(&d))
                    })
            },
        },
    ]
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 3;

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
            _ => Reference.fit_unit_costs(samples),
        }
    }
}
