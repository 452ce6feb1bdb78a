//! Exercise 31: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 31.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 31,
            name: "broad phase: every overlapping pair a < b (touching counts) goes to the narrow phase once, no other",
            points: 5,
            run: |e| {
                let mut r = Rng(3131);
                object_scenes(&mut r).iter().all(|boxes| {
                    let mut calls = Vec::new();
                    let _ = e.collide_objects(boxes, &mut |a, b| {
                        calls.push((a, b));
                        Vec::new()
                    });
                    calls.sort_unstable();
                    calls == overlapping_object_pairs(boxes)
                })
            },
        },
        Check {
            exercise: 31,
            name: "results: every contact, ordered by object pair, in the narrow phase's order within one",
            points: 5,
            run: |e| {
                let mut r = Rng(3132);
                // A narrow phase whose answer depends on the pair: (a+b) % 3
                // contacts, in a fixed order.
                let narrow = |a: u32, b: u32| -> Vec<(u32, u32)> {
                    (0..(a + b) % 3).map(|k| (a * 10 + k, b * 10 + 2 - k)).collect()
                };
                object_scenes(&mut r).iter().all(|boxes| {
                    let want: Vec<((u32, u32), (u32, u32))> = overlapping_object_pairs(boxes)
                        .into_iter()
                        .flat_map(|(a, b)| narrow(a, b).into_iter().map(move |p| ((a, b), p)))
                        .collect();
                    e.collide_objects(boxes, &mut |a, b| narrow(a, b)) == want
                })
            },
        },
    ]
}

/// Object boxes for exercise 31: none, one, two touching at a face, an
/// empty box among others, a row where each touches the next, and random
/// scenes with duplicates.
fn object_scenes(r: &mut Rng) -> Vec<Vec<Aabb>> {
    let unit = |o: Vec3| Aabb::new(o, o + Vec3::ONE);
    let mut out = vec![
        Vec::new(),
        vec![unit(Vec3::ZERO)],
        vec![unit(Vec3::ZERO), unit(Vec3::X)],
        vec![unit(Vec3::ZERO), Aabb::EMPTY, unit(Vec3::splat(0.5))],
        (0..12).map(|i| unit(Vec3::X * i as f32)).collect(),
    ];
    for _ in 0..40 {
        let n = (r.next() * 30.0) as usize;
        let mut boxes: Vec<Aabb> = (0..n)
            .map(|_| {
                let o = r.point(6.0, Vec3::ZERO);
                Aabb::new(o, o + r.point(1.0, Vec3::splat(1.0)).abs())
            })
            .collect();
        if n > 2 {
            boxes[n - 1] = boxes[0];
        }
        out.push(boxes);
    }
    out
}

/// Every pair `a < b` of boxes that overlap, sorted: the brute-force broad
/// phase.
fn overlapping_object_pairs(boxes: &[Aabb]) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    for a in 0..boxes.len() {
        for b in a + 1..boxes.len() {
            if boxes[a].overlaps(&boxes[b]) {
                out.push((a as u32, b as u32));
            }
        }
    }
    out
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 3;

    pub fn collide_objects(
        which: u32,
        boxes: &[Aabb],
        narrow: &mut dyn FnMut(u32, u32) -> Vec<(u32, u32)>,
    ) -> Vec<((u32, u32), (u32, u32))> {
        let n = boxes.len() as u32;
        let strict = |x: &Aabb, y: &Aabb| x.min.cmplt(y.max).all() && y.min.cmplt(x.max).all();
        let mut out = Vec::new();
        match which {
            // Both orders of every pair.
            1 => {
                for a in 0..n {
                    for b in 0..n {
                        if a != b && boxes[a as usize].overlaps(&boxes[b as usize]) {
                            out.extend(narrow(a, b).into_iter().map(|p| ((a, b), p)));
                        }
                    }
                }
            }
            // Touching boxes left out.
            2 => {
                for a in 0..n {
                    for b in a + 1..n {
                        if strict(&boxes[a as usize], &boxes[b as usize]) {
                            out.extend(narrow(a, b).into_iter().map(|p| ((a, b), p)));
                        }
                    }
                }
            }
            // The narrow phase on every pair, its answers filtered after.
            3 => {
                for a in 0..n {
                    for b in a + 1..n {
                        let found = narrow(a, b);
                        if boxes[a as usize].overlaps(&boxes[b as usize]) {
                            out.extend(found.into_iter().map(|p| ((a, b), p)));
                        }
                    }
                }
            }
            _ => return Reference.collide_objects(boxes, narrow),
        }
        out
    }
}
