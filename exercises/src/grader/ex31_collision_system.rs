//! Exercise 31: the collision system. The checks, and the plausible wrong answers they must reject.

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
                object_scenes(&mut r).iter().all(|(what, boxes)| {
                    let mut calls = Vec::new();
                    // One contact per pair: an answer that asks again when
                    // the first call found something shows here.
                    let _ = e.collide_objects(boxes, &mut |a, b| {
                        calls.push((a, b));
                        vec![(a, b)]
                    });
                    let want = overlapping_object_pairs(boxes);
                    let call = format!("collide_objects({what})");
                    let mut seen = std::collections::BTreeSet::new();
                    if let Some(twice) = calls.iter().find(|&&p| !seen.insert(p)) {
                        return fail(format!(
                            "{call} called narrow{twice:?} more than once; each pair goes to \
                             the narrow phase once"
                        ));
                    }
                    if let Some(extra) = calls.iter().find(|p| want.binary_search(p).is_err()) {
                        let (a, b) = *extra;
                        let why = if a >= b {
                            "pairs are (a, b) with a < b".to_string()
                        } else {
                            format!(
                                "boxes {} and {} do not overlap",
                                show_box(&boxes[a as usize]),
                                show_box(&boxes[b as usize])
                            )
                        };
                        return fail(format!(
                            "{call} called narrow{extra:?}, expected never ({why}); {} calls \
                             in all, {} wanted",
                            calls.len(),
                            want.len()
                        ));
                    }
                    match want.iter().find(|p| !seen.contains(p)) {
                        Some(&(a, b)) => fail(format!(
                            "{call} never called narrow{:?}, expected once: boxes {} and {} \
                             overlap (touching counts)",
                            (a, b),
                            show_box(&boxes[a as usize]),
                            show_box(&boxes[b as usize])
                        )),
                        None => true,
                    }
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
                // contacts, in an order that is not sorted.
                let narrow = |a: u32, b: u32| -> Vec<(u32, u32)> {
                    (0..(a + b) % 3).map(|k| (a * 10 + 2 - k, b * 10 + k)).collect()
                };
                object_scenes(&mut r).iter().all(|(what, boxes)| {
                    let want: Vec<((u32, u32), (u32, u32))> = overlapping_object_pairs(boxes)
                        .into_iter()
                        .flat_map(|(a, b)| narrow(a, b).into_iter().map(move |p| ((a, b), p)))
                        .collect();
                    let got = e.collide_objects(boxes, &mut |a, b| narrow(a, b));
                    if got == want {
                        return true;
                    }
                    let call = format!(
                        "collide_objects({what}, a narrow phase giving (a + b) % 3 contacts \
                         (10a + 2 - k, 10b + k) per pair)"
                    );
                    match got.iter().zip(&want).position(|(g, w)| g != w) {
                        Some(i) => fail(format!(
                            "{call} returned {:?} as contact {i}, expected {:?} ({} contacts \
                             returned, {} expected)",
                            got[i],
                            want[i],
                            got.len(),
                            want.len()
                        )),
                        None => fail(format!(
                            "{call} returned {} contacts, expected {}; the first missing or \
                             extra is {:?}",
                            got.len(),
                            want.len(),
                            got.get(want.len()).or(want.get(got.len()))
                        )),
                    }
                })
            },
        },
    ]
}

/// Object boxes for exercise 31: none, one, two touching at a face, an
/// empty box among others, a row where each touches the next, and random
/// scenes with duplicates.
fn object_scenes(r: &mut Rng) -> Vec<(String, Vec<Aabb>)> {
    let unit = |o: Vec3| Aabb::new(o, o + Vec3::ONE);
    let show = |boxes: &[Aabb]| {
        let all: Vec<String> = boxes.iter().map(show_box).collect();
        format!("[{}]", all.join(", "))
    };
    let small = [
        Vec::new(),
        vec![unit(Vec3::ZERO)],
        vec![unit(Vec3::ZERO), unit(Vec3::X)],
        vec![unit(Vec3::ZERO), Aabb::EMPTY, unit(Vec3::splat(0.5))],
    ];
    let mut out: Vec<(String, Vec<Aabb>)> = small.into_iter().map(|s| (show(&s), s)).collect();
    out.push((
        "12 unit boxes in a row along x, each touching the next".into(),
        (0..12).map(|i| unit(Vec3::X * i as f32)).collect(),
    ));
    for k in 0..40 {
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
        let what = format!(
            "random scene {k}: {n} boxes up to 1.5 wide in a cube of side 6, the last a copy of the first"
        );
        out.push((what, boxes));
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
    pub const COUNT: u32 = 9;

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
            // Pairs in the order (b, a) loops find them, not sorted by (a, b).
            4 => {
                for b in 0..n {
                    for a in 0..b {
                        if boxes[a as usize].overlaps(&boxes[b as usize]) {
                            out.extend(narrow(a, b).into_iter().map(|p| ((a, b), p)));
                        }
                    }
                }
            }
            // A tree over every box: the empty one makes the build fail, and
            // the broad phase finds nothing.
            5 => {
                if boxes.iter().any(|x| x.min.cmpgt(x.max).any()) {
                    return Vec::new();
                }
                return Reference.collide_objects(boxes, narrow);
            }
            // `a <= b`: every object is also paired with itself.
            6 => {
                for a in 0..n {
                    for b in a..n {
                        if boxes[a as usize].overlaps(&boxes[b as usize]) {
                            out.extend(narrow(a, b).into_iter().map(|p| ((a, b), p)));
                        }
                    }
                }
            }
            // Sorts every contact at the end, reordering those within a pair.
            7 => {
                let mut all = Reference.collide_objects(boxes, narrow);
                all.sort_unstable();
                return all;
            }
            // Calls the narrow phase twice per pair: once to see whether
            // there is any contact, once to collect them.
            8 => {
                for a in 0..n {
                    for b in a + 1..n {
                        if boxes[a as usize].overlaps(&boxes[b as usize])
                            && !narrow(a, b).is_empty()
                        {
                            out.extend(narrow(a, b).into_iter().map(|p| ((a, b), p)));
                        }
                    }
                }
            }
            // Keeps only the first contact of each pair.
            9 => {
                for a in 0..n {
                    for b in a + 1..n {
                        if boxes[a as usize].overlaps(&boxes[b as usize]) {
                            out.extend(narrow(a, b).into_iter().take(1).map(|p| ((a, b), p)));
                        }
                    }
                }
            }
            _ => return Reference.collide_objects(boxes, narrow),
        }
        out
    }
}
