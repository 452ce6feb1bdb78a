//! Exercise 7: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The unit costs most checks use: all different, one of them fractional.
const MODEL: CostModel = CostModel {
    cv: 2.5,
    cp: 31.0,
    cu: 12.0,
    co: 800.0,
};

/// The checks of exercise 7.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 7,
            name: "T for given counters and unit costs",
            points: 4,
            run: |e| cost_is(e, counts(1200, 340, 56), MODEL),
        },
        Check {
            exercise: 7,
            name: "each counter goes with its own unit cost",
            points: 2,
            run: |e| {
                cost_is(e, counts(1, 0, 0), MODEL)
                    && cost_is(e, counts(0, 1, 0), MODEL)
                    && cost_is(e, counts(0, 0, 1), MODEL)
            },
        },
        Check {
            exercise: 7,
            name: "an empty query costs Co",
            points: 1,
            run: |e| cost_is(e, Counts::default(), MODEL),
        },
        Check {
            exercise: 7,
            name: "f64 throughout: counters past f32's 24 bits and past u32",
            points: 3,
            run: |e| {
                let ones = CostModel {
                    cv: 1.0,
                    cp: 1.0,
                    cu: 1.0,
                    co: 0.0,
                };
                let fine = CostModel {
                    cv: 0.37,
                    cp: 0.1,
                    cu: 3.0,
                    co: 25.0,
                };
                cost_is(e, counts(123_456_789, 4_567, 89), fine)
                    && cost_is(e, counts(3, 5_000_000_001, 7), fine)
                    && cost_is(e, counts(u64::MAX / 2, 3, 0), ones)
            },
        },
    ]
}

fn counts(bv_tests: u64, prim_tests: u64, updates: u64) -> Counts {
    Counts {
        bv_tests,
        prim_tests,
        updates,
    }
}

/// `predicted_cost` against `Nv*Cv + Np*Cp + Nu*Cu + Co` in `f64`, to within
/// a relative 1e-9, explained with every input written out.
fn cost_is(e: &dyn Exercises, c: Counts, m: CostModel) -> bool {
    let want =
        c.bv_tests as f64 * m.cv + c.prim_tests as f64 * m.cp + c.updates as f64 * m.cu + m.co;
    let got = e.predicted_cost(&c, &m);
    close(got, want)
        || fail(format!(
            "predicted_cost(Nv = {}, Np = {}, Nu = {}; Cv = {}, Cp = {}, Cu = {}, Co = {}) \
             returned {got}, expected {want} (in f64, to within 1e-9 of it)",
            c.bv_tests, c.prim_tests, c.updates, m.cv, m.cp, m.cu, m.co
        ))
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 6;

    pub fn predicted_cost(which: u32, c: &Counts, m: &CostModel) -> f64 {
        match which {
            // Forgets Co.
            1 => Reference.predicted_cost(c, m) - m.co,
            // f32 arithmetic throughout.
            2 => {
                (c.bv_tests as f32 * m.cv as f32
                    + c.prim_tests as f32 * m.cp as f32
                    + c.updates as f32 * m.cu as f32
                    + m.co as f32) as f64
            }
            // Integer arithmetic: the unit costs truncated.
            3 => {
                (c.bv_tests.wrapping_mul(m.cv as u64)
                    + c.prim_tests.wrapping_mul(m.cp as u64)
                    + c.updates.wrapping_mul(m.cu as u64)
                    + m.co as u64) as f64
            }
            // Np with Cu and Nu with Cp.
            4 => {
                c.bv_tests as f64 * m.cv
                    + c.prim_tests as f64 * m.cu
                    + c.updates as f64 * m.cp
                    + m.co
            }
            // The counters through u32.
            5 => {
                c.bv_tests as u32 as f64 * m.cv
                    + c.prim_tests as u32 as f64 * m.cp
                    + c.updates as u32 as f64 * m.cu
                    + m.co
            }
            // Leaves out the updates term.
            6 => c.bv_tests as f64 * m.cv + c.prim_tests as f64 * m.cp + m.co,
            _ => Reference.predicted_cost(c, m),
        }
    }
}
