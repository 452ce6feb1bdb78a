//! Exercise 8: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 8.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 8,
            name: "n - 1 merges of live clusters, ending in one root",
            points: 3,
            run: |e| {
                merge_sets()
                    .iter()
                    .all(|s| replay(s, &e.bottom_up_merges(s), false))
            },
        },
        Check {
            exercise: 8,
            name: "every merge has the smallest merged volume of its step",
            points: 5,
            run: |e| {
                merge_sets()
                    .iter()
                    .all(|s| replay(s, &e.bottom_up_merges(s), true))
            },
        },
        Check {
            exercise: 8,
            name: "one box needs no merge; two need one",
            points: 2,
            run: |e| {
                let one = [b([0.0; 3], [1.0; 3])];
                let two = [b([0.0; 3], [1.0; 3]), b([5.0; 3], [6.0; 3])];
                e.bottom_up_merges(&one).is_empty() && replay(&two, &e.bottom_up_merges(&two), true)
            },
        },
    ]
}

/// Replays a merge sequence: whether every merge joins two live clusters and
/// exactly one cluster is left. With `check_greedy`, each merge must also have
/// the smallest merged volume among the live pairs of its step.
fn replay(boxes: &[Aabb], merges: &[(u32, u32)], check_greedy: bool) -> bool {
    let n = boxes.len();
    if merges.len() != n.saturating_sub(1) {
        return false;
    }
    let mut live: Vec<Option<Aabb>> = boxes.iter().copied().map(Some).collect();
    for &(a, b) in merges {
        let (a, b) = (a as usize, b as usize);
        let (Some(Some(x)), Some(Some(y))) = (live.get(a).copied(), live.get(b).copied()) else {
            return false;
        };
        if a == b {
            return false;
        }
        let cost = x.union(&y).volume();
        if check_greedy {
            let alive: Vec<Aabb> = live.iter().flatten().copied().collect();
            let best = (0..alive.len())
                .flat_map(|i| (i + 1..alive.len()).map(move |j| (i, j)))
                .map(|(i, j)| alive[i].union(&alive[j]).volume())
                .fold(f32::INFINITY, f32::min);
            if cost > best * (1.0 + 1e-5) {
                return false;
            }
        }
        live[a] = None;
        live[b] = None;
        live.push(Some(x.union(&y)));
    }
    live.iter().flatten().count() == 1
}

fn merge_sets() -> Vec<Vec<Aabb>> {
    let mut r = Rng(99);
    let mut sets: Vec<Vec<Aabb>> = (0..6)
        .map(|k| {
            (0..(5 + 7 * k))
                .map(|_| {
                    let lo = r.point(20.0, Vec3::ZERO);
                    Aabb::new(lo, lo + Vec3::new(r.next(), r.next(), r.next()) * 3.0 + 0.1)
                })
                .collect()
        })
        .collect();
    // Two tight groups far apart: the groups must close before they join.
    let group = |o: Vec3| {
        (0..4).map(move |i| {
            Aabb::new(
                o + Vec3::X * i as f32 * 1.1,
                o + Vec3::X * i as f32 * 1.1 + 1.0,
            )
        })
    };
    sets.push(group(Vec3::ZERO).chain(group(Vec3::splat(100.0))).collect());
    sets
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;
    use crate::grader::wrong::LOOPS;
    use std::time::Duration;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 2;

    pub fn bottom_up_merges(which: u32, boxes: &[Aabb]) -> Vec<(u32, u32)> {
        let n = boxes.len() as u32;
        if which == LOOPS {
            // Never removes the merged clusters: never returns (asleep,
            // so the abandoned thread costs no CPU).
            loop {
                std::thread::sleep(Duration::from_secs(3600));
            }
        }
        match which {
            // Merges in index order: a chain, not greedy.
            1 => (1..n)
                .map(|i| (if i == 1 { 0 } else { n + i - 2 }, i))
                .collect(),
            // Greedy, but by the sum of the two volumes, not the merged volume.
            2 => {
                let mut live: Vec<(u32, Aabb)> = boxes
                    .iter()
                    .enumerate()
                    .map(|(i, b)| (i as u32, *b))
                    .collect();
                let mut out = Vec::new();
                while live.len() > 1 {
                    let mut best = (f32::INFINITY, 0, 1);
                    for i in 0..live.len() {
                        for j in i + 1..live.len() {
                            let v = live[i].1.volume() + live[j].1.volume();
                            if v < best.0 {
                                best = (v, i, j);
                            }
                        }
                    }
                    let (_, i, j) = best;
                    out.push((live[i].0, live[j].0));
                    live[i] = (n + out.len() as u32 - 1, live[i].1.union(&live[j].1));
                    live.swap_remove(j);
                }
                out
            }
            _ => Reference.bottom_up_merges(boxes),
        }
    }
}
