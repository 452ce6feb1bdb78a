//! Exercise 13: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 13.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 13,
            name: "the decoded box contains the child (random children, far from the origin too)",
            points: 3,
            run: |e| quantize_cases().iter().all(|(p, c)| contains(e, p, c)),
        },
        Check {
            exercise: 13,
            name: "as tight as the grid allows",
            points: 2,
            run: |e| quantize_cases().iter().all(|(p, c)| tightest(e, p, c)),
        },
        Check {
            exercise: 13,
            name: "faces exactly on a grid line, or one f32 step beside it",
            points: 2,
            run: |e| grid_line_cases().iter().all(|(p, c)| tightest(e, p, c)),
        },
        Check {
            exercise: 13,
            name: "a child equal to its parent, flat children, and a flat parent",
            points: 3,
            run: |e| {
                let p = b([-3.0, 1.0, 5.0], [7.0, 1.0, 9.5]); // flat along y
                let flat = b([0.0, 1.0, 6.0], [4.0, 1.0, 6.0]);
                let thin = b([-3.0, 1.0, 7.25], [-3.0, 1.0, 7.25]);
                let q = b([0.0; 3], [255.0; 3]);
                let point = b([17.0, 0.0, 255.0], [17.0, 0.0, 255.0]);
                [(p, p), (p, flat), (p, thin), (q, point)]
                    .iter()
                    .all(|(p, c)| tightest(e, p, c))
            },
        },
    ]
}

/// The call in words.
fn call(p: &Aabb, c: &Aabb) -> String {
    format!("quantize(parent {}, child {})", show_box(p), show_box(c))
}

/// Whether the quantized child decodes to a box containing it; explained
/// by the first axis where it does not.
fn contains(e: &dyn Exercises, p: &Aabb, c: &Aabb) -> bool {
    let (lo, hi) = e.quantize(p, c);
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        let (l, h) = (
            crate::dequantize(p, k, lo[k]),
            crate::dequantize(p, k, hi[k]),
        );
        if l > c.min[k] {
            return fail(format!(
                "{} returned lo {lo:?}, hi {hi:?}: on {axis}, lo {} decodes to {l}, above \
                 the child's min {} (the decoded box must contain the child)",
                call(p, c),
                lo[k],
                c.min[k]
            ));
        }
        if h < c.max[k] {
            return fail(format!(
                "{} returned lo {lo:?}, hi {hi:?}: on {axis}, hi {} decodes to {h}, below \
                 the child's max {} (the decoded box must contain the child)",
                call(p, c),
                hi[k],
                c.max[k]
            ));
        }
    }
    true
}

/// Whether the answer is the largest `lo` and smallest `hi` that contain
/// the child (there is exactly one such answer).
fn tightest(e: &dyn Exercises, p: &Aabb, c: &Aabb) -> bool {
    let want = Reference.quantize(p, c);
    let got = e.quantize(p, c);
    if got == want {
        return true;
    }
    if !contains(e, p, c) {
        return false;
    }
    let k = (0..3)
        .find(|&k| got.0[k] != want.0[k] || got.1[k] != want.1[k])
        .unwrap_or(0);
    fail(format!(
        "{} returned lo {:?}, hi {:?}, expected lo {:?}, hi {:?}: on {} the grid line \
         lo {} decodes to {} and hi {} to {}, for a child from {} to {} (the largest lo \
         that decodes at or below the child's min, the smallest hi at or above its max)",
        call(p, c),
        got.0,
        got.1,
        want.0,
        want.1,
        ["x", "y", "z"][k],
        want.0[k],
        crate::dequantize(p, k, want.0[k]),
        want.1[k],
        crate::dequantize(p, k, want.1[k]),
        c.min[k],
        c.max[k]
    ))
}

/// Parent/child pairs for exercise 13: random children, children whose faces
/// lie on grid lines or one `f32` step beside them, far from the origin.
fn quantize_cases() -> Vec<(Aabb, Aabb)> {
    let mut r = Rng(0x51ed_270b_9a3c_4e5f);
    let mut out = Vec::new();
    for i in 0..400 {
        let off = if i % 3 == 0 {
            Vec3::new(1.0e5, -7.3e3, 0.1)
        } else {
            Vec3::ZERO
        };
        let p = Aabb::fit(&[r.point(20.0, off), r.point(20.0, off)]);
        let mut c = Aabb::fit(&[
            p.min + (p.max - p.min) * Vec3::new(r.next(), r.next(), r.next()),
            p.min + (p.max - p.min) * Vec3::new(r.next(), r.next(), r.next()),
        ]);
        if i % 2 == 1 {
            // Snap the faces to grid lines, then nudge by one ulp either way.
            for k in 0..3 {
                let q = (r.next() * 254.0) as u8;
                let g = crate::dequantize(&p, k, q);
                let nudge = match i % 4 {
                    1 => g,
                    _ => f32::from_bits(g.to_bits().wrapping_sub(1)).max(p.min[k]),
                };
                c.min[k] = nudge.min(c.max[k]);
                c.max[k] = c.max[k].max(c.min[k]);
            }
        }
        out.push((p, c));
    }
    out
}

/// Children whose min and max faces both lie exactly on grid lines, or one
/// `f32` step below or above one, in parents near and far from the origin.
fn grid_line_cases() -> Vec<(Aabb, Aabb)> {
    let mut r = Rng(0x1313_5eed);
    let step = |x: f32, s: i32| match s {
        0 => x,
        _ if (x > 0.0) == (s > 0) => f32::from_bits(x.to_bits() + 1),
        _ if x == 0.0 => x,
        _ => f32::from_bits(x.to_bits() - 1),
    };
    let mut out = Vec::new();
    for i in 0..240 {
        let off = [Vec3::ZERO, Vec3::new(3.0e4, -1.0e3, 7.0)][i % 2];
        let p = Aabb::fit(&[r.point(30.0, off), r.point(30.0, off)]);
        let mut c = p;
        for k in 0..3 {
            let (qa, qb) = ((r.next() * 255.0) as u8, (r.next() * 255.0) as u8);
            let (ga, gb) = (
                crate::dequantize(&p, k, qa.min(qb)),
                crate::dequantize(&p, k, qa.max(qb)),
            );
            let (sa, sb) = ((i / 2 % 3) as i32 - 1, (i / 6 % 3) as i32 - 1);
            let lo = step(ga, sa).clamp(p.min[k], p.max[k]);
            let hi = step(gb, sb).clamp(p.min[k], p.max[k]);
            (c.min[k], c.max[k]) = (lo.min(hi), lo.max(hi));
        }
        out.push((p, c));
    }
    out
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 7;

    pub fn quantize(which: u32, parent: &Aabb, child: &Aabb) -> ([u8; 3], [u8; 3]) {
        let grid =
            |k: usize, x: f32| (x - parent.min[k]) / ((parent.max[k] - parent.min[k]) / 255.0);
        // Per axis, `lo` and `hi` from the grid coordinates of the faces.
        let each = |f: &dyn Fn(f32, f32) -> (f32, f32)| {
            let (mut lo, mut hi) = ([0u8; 3], [0u8; 3]);
            for k in 0..3 {
                let (a, b) = f(grid(k, child.min[k]), grid(k, child.max[k]));
                let u = |x: f32, nan: u8| {
                    if x.is_finite() {
                        x.clamp(0.0, 255.0) as u8
                    } else {
                        nan
                    }
                };
                (lo[k], hi[k]) = (u(a, 0), u(b, 255));
            }
            (lo, hi)
        };
        match which {
            // Round to the nearest grid line: can cut into the child.
            1 => each(&|a, b| (a.round(), b.round())),
            // floor / ceil in f32, never checked against the decoder.
            2 => each(&|a, b| (a.floor(), b.ceil())),
            // Always the whole parent: safe, but useless.
            3 => ([0; 3], [255; 3]),
            // Rounds the wrong way: ceil for lo, floor for hi (cuts into the child).
            4 => each(&|a, b| (a.ceil(), b.floor())),
            // Strict: a grid line exactly on the face is not accepted, so lo
            // and hi step one line too far.
            5 => {
                let (mut lo, mut hi) = Reference.quantize(parent, child);
                for k in 0..3 {
                    if lo[k] > 0 && crate::dequantize(parent, k, lo[k]) == child.min[k] {
                        lo[k] -= 1;
                    }
                    if hi[k] < 255 && crate::dequantize(parent, k, hi[k]) == child.max[k] {
                        hi[k] += 1;
                    }
                }
                (lo, hi)
            }
            // A flat parent axis gives (0, 0): not the largest lo.
            6 => {
                let (mut lo, mut hi) = Reference.quantize(parent, child);
                for k in 0..3 {
                    if parent.max[k] == parent.min[k] {
                        (lo[k], hi[k]) = (0, 0);
                    }
                }
                (lo, hi)
            }
            // One grid line of margin each way "to be safe": not tight.
            7 => {
                let (lo, hi) = Reference.quantize(parent, child);
                (
                    lo.map(|l| l.saturating_sub(1)),
                    hi.map(|h| h.saturating_add(1)),
                )
            }
            _ => Reference.quantize(parent, child),
        }
    }
}
