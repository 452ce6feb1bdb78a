//! Exercise 21: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 21.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 21,
            name: "touching and nested boxes overlap",
            points: 3,
            run: |e| {
                let cube = |c: Vec3| Obb {
                    center: c,
                    axes: [Vec3::X, Vec3::Y, Vec3::Z],
                    half_extents: Vec3::ONE,
                };
                let (a, touching) = (cube(Vec3::ZERO), cube(Vec3::new(2.0, 0.5, 0.0)));
                let inner = Obb {
                    half_extents: Vec3::splat(0.25),
                    ..turned(Vec3::ZERO, 0.7, 0.3)
                };
                e.obb_overlaps(&a, &touching)
                    && e.obb_overlaps(&touching, &a)
                    && e.obb_overlaps(&a, &inner)
                    && e.obb_overlaps(&inner, &a)
            },
        },
        Check {
            exercise: 21,
            name: "random turned boxes, edge-to-edge misses included, against the library",
            points: 7,
            run: |e| {
                let mut r = Rng(21);
                let mut clear = 0;
                let agree = (0..4000).all(|_| {
                    let a = turned(r.point(0.5, Vec3::ZERO), r.next() * 6.0, r.next() * 6.0);
                    let b = turned(r.point(5.0, Vec3::ZERO), r.next() * 6.0, r.next() * 6.0);
                    // Only pairs the answer of which does not change when
                    // both boxes grow or shrink by 1%: no rounding question.
                    let scaled = |x: &Obb, f: f32| Obb {
                        half_extents: x.half_extents * f,
                        ..*x
                    };
                    let lo = scaled(&a, 0.99).overlaps(&scaled(&b, 0.99));
                    let hi = scaled(&a, 1.01).overlaps(&scaled(&b, 1.01));
                    if lo != hi {
                        return true;
                    }
                    clear += 1;
                    e.obb_overlaps(&a, &b) == lo && e.obb_overlaps(&b, &a) == lo
                });
                agree && clear > 3000
            },
        },
    ]
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 2;

    pub fn obb_overlaps(which: u32, a: &Obb, b: &Obb) -> bool {
        let apart = |l: Vec3, strict: bool| {
            let radius = |x: &Obb| {
                (0..3)
                    .map(|k| x.half_extents[k] * x.axes[k].dot(l).abs())
                    .sum::<f32>()
            };
            let d = (b.center - a.center).dot(l).abs();
            let r = radius(a) + radius(b);
            if strict {
                d >= r
            } else {
                d > r
            }
        };
        let faces = || a.axes.iter().chain(&b.axes).any(|&l| apart(l, false));
        match which {
            // Face axes only: misses boxes that pass edge to edge.
            1 => !faces(),
            // Touching counts as apart.
            2 => {
                !a.axes.iter().chain(&b.axes).any(|&l| apart(l, true))
                    && Reference.obb_overlaps(a, b)
            }
            _ => Reference.obb_overlaps(a, b),
        }
    }
}
