//! Exercise 18: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 18.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 18,
            name: "A first, B first and simultaneous, at every depth",
            points: 3,
            run: |e| {
                let (a, b) = (unit_at(0.0), unit_at(0.5));
                (0..6).all(|depth| {
                    let d = Decision {
                        a: &a,
                        b: &b,
                        a_children: None,
                        b_children: None,
                        depth,
                    };
                    e.descent_open(Descent::AFirst, &d) == Open::A
                        && e.descent_open(Descent::BFirst, &d) == Open::B
                        && e.descent_open(Descent::Simultaneous, &d) == Open::Both
                })
            },
        },
        Check {
            exercise: 18,
            name: "alternate: A at even depths, B at odd",
            points: 3,
            run: |e| {
                let (a, b) = (unit_at(0.0), unit_at(0.5));
                (0..8).all(|depth| {
                    let d = Decision {
                        a: &a,
                        b: &b,
                        a_children: None,
                        b_children: None,
                        depth,
                    };
                    let want = if depth % 2 == 0 { Open::A } else { Open::B };
                    e.descent_open(Descent::Alternate, &d) == want
                })
            },
        },
        Check {
            exercise: 18,
            name: "by overlap: opens the side whose children stay least inside (not the larger)",
            points: 4,
            run: |e| {
                let slab = |x0: f32, x1: f32| b([x0, 0.0, 0.0], [x1, 4.0, 4.0]);
                // A = [0,4] split at 2: on average a quarter of A's children
                // lies in B. B = [3,10] split at 4: half of B's children lies
                // in A. So A is opened, although B is the larger node.
                let (a, ac) = (slab(0.0, 4.0), [slab(0.0, 2.0), slab(2.0, 4.0)]);
                let (bb, bc) = (slab(3.0, 10.0), [slab(3.0, 4.0), slab(4.0, 10.0)]);
                let d = Decision {
                    a: &a,
                    b: &bb,
                    a_children: Some(&ac),
                    b_children: Some(&bc),
                    depth: 0,
                };
                let swapped = Decision {
                    a: &bb,
                    b: &a,
                    a_children: Some(&bc),
                    b_children: Some(&ac),
                    depth: 1,
                };
                let same = Decision {
                    a: &a,
                    b: &a,
                    a_children: Some(&ac),
                    b_children: Some(&ac),
                    depth: 0,
                };
                e.descent_open(Descent::Overlap, &d) == Open::A
                    && e.descent_open(Descent::Overlap, &swapped) == Open::B
                    && e.descent_open(Descent::Overlap, &same) == Open::A
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

    pub fn descent_open(which: u32, rule: Descent, d: &Decision<'_, Aabb>) -> Open {
        let larger = || {
            if d.a.volume() >= d.b.volume() {
                Open::A
            } else {
                Open::B
            }
        };
        match (which, rule) {
            // Odd depths open A.
            (1, Descent::Alternate) => {
                if d.depth % 2 == 1 {
                    Open::A
                } else {
                    Open::B
                }
            }
            // Opens the side whose children stay *most* inside.
            (2, Descent::Overlap) => match Reference.descent_open(rule, d) {
                Open::A => Open::B,
                _ => Open::A,
            },
            // Simultaneous opens one side only.
            (3, Descent::Simultaneous) => Open::A,
            // By overlap falls back to the larger volume.
            (4, Descent::Overlap) => larger(),
            _ => Reference.descent_open(rule, d),
        }
    }
}
