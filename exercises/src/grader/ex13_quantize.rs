//! Exercise 13: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 13.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 13,
            name: "the decoded box contains the child (grid-line and rounding cases)",
            points: 4,
            run: |e| {
                quantize_cases()
                    .iter()
                    .all(|(p, c)| quantized_contains(e, p, c))
            },
        },
        Check {
            exercise: 13,
            name: "as tight as the grid allows",
            points: 3,
            run: |e| {
                quantize_cases().iter().all(|(p, c)| {
                    let (lo, hi) = e.quantize(p, c);
                    quantized_contains(e, p, c)
                        && (0..3).all(|k| {
                            (lo[k] == 255 || crate::dequantize(p, k, lo[k] + 1) > c.min[k])
                                && (hi[k] == 0 || crate::dequantize(p, k, hi[k] - 1) < c.max[k])
                        })
                })
            },
        },
        Check {
            exercise: 13,
            name: "a child equal to its parent, and flat boxes",
            points: 3,
            run: |e| {
                let p = b([-3.0, 1.0, 5.0], [7.0, 1.0, 9.5]);
                let flat = b([0.0, 1.0, 6.0], [4.0, 1.0, 6.0]);
                e.quantize(&p, &p).0[0] == 0
                    && e.quantize(&p, &p).1[0] == 255
                    && quantized_contains(e, &p, &p)
                    && quantized_contains(e, &p, &flat)
            },
        },
    ]
}

/// Whether the quantized child decodes to a box containing it.
fn quantized_contains(e: &dyn Exercises, p: &Aabb, c: &Aabb) -> bool {
    let (lo, hi) = e.quantize(p, c);
    (0..3).all(|k| {
        crate::dequantize(p, k, lo[k]) <= c.min[k] && crate::dequantize(p, k, hi[k]) >= c.max[k]
    })
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

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 3;

    pub fn quantize(which: u32, parent: &Aabb, child: &Aabb) -> ([u8; 3], [u8; 3]) {
        let grid =
            |k: usize, x: f32| (x - parent.min[k]) / ((parent.max[k] - parent.min[k]) / 255.0);
        match which {
            // Round to the nearest grid line: can cut into the child.
            1 => {
                let (mut lo, mut hi) = ([0u8; 3], [0u8; 3]);
                for k in 0..3 {
                    lo[k] = grid(k, child.min[k]).round().clamp(0.0, 255.0) as u8;
                    hi[k] = grid(k, child.max[k]).round().clamp(0.0, 255.0) as u8;
                }
                (lo, hi)
            }
            // floor / ceil in f32, never checked against the decoder.
            2 => {
                let (mut lo, mut hi) = ([0u8; 3], [0u8; 3]);
                for k in 0..3 {
                    let (a, b) = (grid(k, child.min[k]), grid(k, child.max[k]));
                    lo[k] = if a.is_finite() {
                        a.floor().clamp(0.0, 255.0) as u8
                    } else {
                        0
                    };
                    hi[k] = if b.is_finite() {
                        b.ceil().clamp(0.0, 255.0) as u8
                    } else {
                        255
                    };
                }
                (lo, hi)
            }
            // Always the whole parent: safe, but useless.
            3 => ([0; 3], [255; 3]),
            _ => Reference.quantize(parent, child),
        }
    }
}
