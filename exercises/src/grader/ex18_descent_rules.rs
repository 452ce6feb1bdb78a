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
                [0, 1, 2, 3, 4, 5, 31, 32, 33, u32::MAX].iter().all(|&depth| {
                    let d = Decision {
                        a: &a,
                        b: &b,
                        a_children: None,
                        b_children: None,
                        depth,
                    };
                    open_is(e, Descent::AFirst, &d, Open::A)
                        && open_is(e, Descent::BFirst, &d, Open::B)
                        && open_is(e, Descent::Simultaneous, &d, Open::Both)
                })
            },
        },
        Check {
            exercise: 18,
            name: "alternate: A at even depths, B at odd (depths past 31 too)",
            points: 2,
            run: |e| {
                let (a, b) = (unit_at(0.0), unit_at(0.5));
                (0..8)
                    .chain([31, 32, 33, 64, u32::MAX - 1, u32::MAX])
                    .all(|depth| {
                        let d = Decision {
                            a: &a,
                            b: &b,
                            a_children: None,
                            b_children: None,
                            depth,
                        };
                        let want = if depth % 2 == 0 { Open::A } else { Open::B };
                        open_is(e, Descent::Alternate, &d, want)
                    })
            },
        },
        Check {
            exercise: 18,
            name: "by overlap: opens the side whose children stay least inside (not the larger)",
            points: 3,
            run: |e| {
                let slab = |x0: f32, x1: f32| b([x0, 0.0, 0.0], [x1, 4.0, 4.0]);
                // A = [0,4] split at 2: on average a quarter of A's children
                // lies in B. B = [3,10] split at 4: half of B's children lies
                // in A. So A is opened, although B is the larger node.
                let (a, ac) = (slab(0.0, 4.0), [slab(0.0, 2.0), slab(2.0, 4.0)]);
                let (bb, bc) = (slab(3.0, 10.0), [slab(3.0, 4.0), slab(4.0, 10.0)]);
                overlap_opens(e, (&a, &ac), (&bb, &bc), Open::A)
                    && overlap_opens(e, (&bb, &bc), (&a, &ac), Open::B)
                    // The same node on both sides: a tie, which goes to A.
                    && overlap_opens(e, (&a, &ac), (&a, &ac), Open::A)
            },
        },
        Check {
            exercise: 18,
            name: "by overlap: a child apart on two axes is not inside, and means over 4 or 2 children",
            points: 2,
            run: |e| {
                // A's corner child [0,1]^3 is apart from B along x and y:
                // nothing of it lies inside B (two negative shared extents
                // must not multiply to a positive fraction). A's children:
                // 0 and 1/4 inside B, mean 1/8; B's: 1/2 and 0, mean 1/4.
                let cube = |lo: [f32; 3], hi: [f32; 3]| b(lo, hi);
                let a = cube([0.0; 3], [10.0; 3]);
                let ac = [cube([0.0; 3], [1.0; 3]), a];
                let bb = cube([5.0, 5.0, 0.0], [15.0, 15.0, 10.0]);
                let bc = [
                    cube([5.0, 5.0, 0.0], [10.0, 15.0, 10.0]),
                    cube([10.0, 5.0, 0.0], [15.0, 15.0, 10.0]),
                ];
                // A wide node: four slices of A = [0,8], a quarter of each
                // inside B = [6,11] (mean 1/4, sum 1); B's two slices are
                // each 2/5 inside A (mean 2/5, sum 4/5). Means open A.
                let slab = |x0: f32, x1: f32, y0: f32, y1: f32| b([x0, y0, 0.0], [x1, y1, 4.0]);
                let wa = slab(0.0, 8.0, 0.0, 4.0);
                let wac: Vec<Aabb> = (0..4)
                    .map(|i| slab(0.0, 8.0, i as f32, i as f32 + 1.0))
                    .collect();
                let wb = slab(6.0, 11.0, 0.0, 4.0);
                let wbc = [slab(6.0, 11.0, 0.0, 2.0), slab(6.0, 11.0, 2.0, 4.0)];
                overlap_opens(e, (&a, &ac), (&bb, &bc), Open::A)
                    && overlap_opens(e, (&bb, &bc), (&a, &ac), Open::B)
                    && overlap_opens(e, (&wa, &wac), (&wb, &wbc), Open::A)
                    && overlap_opens(e, (&wb, &wbc), (&wa, &wac), Open::B)
            },
        },
    ]
}

/// Whether `rule` on `d` opens `want`, explained with the decision.
fn open_is(e: &dyn Exercises, rule: Descent, d: &Decision<'_, Aabb>, want: Open) -> bool {
    let kids = |c: Option<&[Aabb]>| match c {
        Some(c) => {
            let all: Vec<String> = c.iter().map(show_box).collect();
            format!(" (children {})", all.join(", "))
        }
        None => String::new(),
    };
    let call = format!(
        "descent_open(Descent::{rule:?}, a = {}{}, b = {}{}, depth {})",
        show_box(d.a),
        kids(d.a_children),
        show_box(d.b),
        kids(d.b_children),
        d.depth
    );
    same(call, want, e.descent_open(rule, d))
}

/// The overlap rule on A (with its children) and B (with its children).
fn overlap_opens(e: &dyn Exercises, a: (&Aabb, &[Aabb]), b: (&Aabb, &[Aabb]), want: Open) -> bool {
    let d = Decision {
        a: a.0,
        b: b.0,
        a_children: Some(a.1),
        b_children: Some(b.1),
        depth: 0,
    };
    open_is(e, Descent::Overlap, &d, want)
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 7;

    /// The overlap rule written out, each factor clamped by `clamp`, the
    /// children's fractions combined by `combine`, ties to A unless `ties_b`.
    fn by_overlap(
        d: &Decision<'_, Aabb>,
        clamp: impl Fn(f32) -> f32,
        combine: impl Fn(&[f32]) -> f32,
        ties_b: bool,
    ) -> Open {
        let inside = |c: &Aabb, o: &Aabb| {
            let shared = c.max.min(o.max) - c.min.max(o.min);
            let own = c.max - c.min;
            (0..3).map(|k| clamp(shared[k] / own[k])).product::<f32>()
        };
        let stays = |cs: &[Aabb], o: &Aabb| {
            let f: Vec<f32> = cs.iter().map(|c| inside(c, o)).collect();
            combine(&f)
        };
        let (a, b) = (
            stays(d.a_children.unwrap_or(&[]), d.b),
            stays(d.b_children.unwrap_or(&[]), d.a),
        );
        if a < b || (a == b && !ties_b) {
            Open::A
        } else {
            Open::B
        }
    }

    pub fn descent_open(which: u32, rule: Descent, d: &Decision<'_, Aabb>) -> Open {
        let larger = || {
            if d.a.volume() >= d.b.volume() {
                Open::A
            } else {
                Open::B
            }
        };
        let mean = |f: &[f32]| f.iter().sum::<f32>() / f.len().max(1) as f32;
        let clamped = |x: f32| x.clamp(0.0, 1.0);
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
            // Sums the children's fractions instead of averaging them.
            (5, Descent::Overlap) => by_overlap(d, clamped, |f| f.iter().sum(), false),
            // Clamps each factor at 1 only: two negative extents make a positive fraction.
            (6, Descent::Overlap) => by_overlap(d, |x| x.min(1.0), mean, false),
            // A tie opens B.
            (7, Descent::Overlap) => by_overlap(d, clamped, mean, true),
            _ => Reference.descent_open(rule, d),
        }
    }
}
