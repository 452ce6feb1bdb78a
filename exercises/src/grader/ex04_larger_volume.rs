//! Exercise 4: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 4.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 4,
            name: "never opens a leaf",
            points: 3,
            run: |e| {
                let big = node([0.0; 3], [10.0; 3], false);
                let small_leaf = node([0.0; 3], [1.0; 3], true);
                let big_leaf = node([0.0; 3], [10.0; 3], true);
                let small = node([0.0; 3], [1.0; 3], false);
                opens(e, &big, &small_leaf, true)
                    && opens(e, &small, &big_leaf, true)
                    && opens(e, &big_leaf, &small, false)
                    && opens(e, &small_leaf, &big, false)
            },
        },
        Check {
            exercise: 4,
            name: "opens the larger of two internal nodes (A on a tie)",
            points: 4,
            run: |e| {
                let big = node([0.0; 3], [10.0; 3], false);
                let small = node([0.0; 3], [1.0; 3], false);
                let other_small = node([5.0; 3], [6.0; 3], false);
                opens(e, &big, &small, true)
                    && opens(e, &small, &big, false)
                    && opens(e, &small, &small, true)
                    && opens(e, &other_small, &small, true)
                    && opens(e, &small, &other_small, true)
            },
        },
        Check {
            exercise: 4,
            name: "size means volume, not the length along one axis nor the surface area",
            points: 3,
            run: |e| {
                let long_thin = node([0.0; 3], [20.0, 0.1, 0.1], false);
                let cube = node([0.0; 3], [2.0; 3], false);
                let plate = node([0.0; 3], [10.0, 10.0, 0.01], false);
                let block = node([0.0; 3], [1.5; 3], false);
                opens(e, &long_thin, &cube, false)
                    && opens(e, &cube, &long_thin, true)
                    && opens(e, &plate, &block, false)
                    && opens(e, &block, &plate, true)
            },
        },
    ]
}

/// `descend_a(a, b) == want`, explained with both nodes written out.
fn opens(e: &dyn Exercises, a: &Node<Aabb>, b: &Node<Aabb>, want: bool) -> bool {
    let show = |n: &Node<Aabb>| {
        format!(
            "{} {} (volume {})",
            if n.is_leaf() { "leaf" } else { "internal" },
            show_box(&n.bv),
            n.bv.volume()
        )
    };
    let side = |x: bool| if x { "true (open a)" } else { "false (open b)" };
    let got = e.descend_a(a, b);
    got == want
        || fail(format!(
            "descend_a(a = {}, b = {}) returned {}, expected {}",
            show(a),
            show(b),
            side(got),
            side(want)
        ))
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 5;

    pub fn descend_a(which: u32, a: &Node<Aabb>, b: &Node<Aabb>) -> bool {
        match which {
            // Forgets the leaves: compares volumes only.
            1 => a.bv.volume() >= b.bv.volume(),
            // Size as the length along x.
            2 => b.is_leaf() || (!a.is_leaf() && a.bv.extent().x >= b.bv.extent().x),
            // `>` for `>=`: a tie opens b.
            3 => b.is_leaf() || (!a.is_leaf() && a.bv.volume() > b.bv.volume()),
            // Size as the surface area.
            4 => b.is_leaf() || (!a.is_leaf() && a.bv.surface_area() >= b.bv.surface_area()),
            // Checks only whether a is a leaf: may open a leaf b.
            5 => !a.is_leaf() && a.bv.volume() >= b.bv.volume(),
            _ => Reference.descend_a(a, b),
        }
    }
}
