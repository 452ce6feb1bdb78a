//! Exercise 7: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 7.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 7,
            name: "T for given counters and unit costs",
            points: 6,
            run: |e| {
                let counts = Counts {
                    bv_tests: 1200,
                    prim_tests: 340,
                    updates: 56,
                };
                let model = CostModel {
                    cv: 2.5,
                    cp: 31.0,
                    cu: 12.0,
                    co: 800.0,
                };
                let t = e.predicted_cost(&counts, &model);
                (t - (1200.0 * 2.5 + 340.0 * 31.0 + 56.0 * 12.0 + 800.0)).abs() < 1e-6
            },
        },
        Check {
            exercise: 7,
            name: "an empty query costs Co",
            points: 2,
            run: |e| {
                let model = CostModel {
                    cv: 2.5,
                    cp: 31.0,
                    cu: 12.0,
                    co: 800.0,
                };
                (e.predicted_cost(&Counts::default(), &model) - 800.0).abs() < 1e-9
            },
        },
        Check {
            exercise: 7,
            name: "no overflow with huge counters",
            points: 2,
            run: |e| {
                let counts = Counts {
                    bv_tests: u64::MAX / 2,
                    prim_tests: 3,
                    updates: 0,
                };
                let model = CostModel {
                    cv: 1.0,
                    cp: 1.0,
                    cu: 1.0,
                    co: 0.0,
                };
                let t = e.predicted_cost(&counts, &model);
                (t / (u64::MAX / 2) as f64 - 1.0).abs() < 1e-9
            },
        },
    ]
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 1;

    pub fn predicted_cost(which: u32, counts: &Counts, model: &CostModel) -> f64 {
        match which {
            1 => Reference.predicted_cost(counts, model) - model.co, // forgets Co
            _ => Reference.predicted_cost(counts, model),
        }
    }
}
