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
                    .all(|(s, what)| replay(s, what, &e.bottom_up_merges(s), false))
            },
        },
        Check {
            exercise: 8,
            name: "every merge has the smallest merged volume of its step",
            points: 5,
            run: |e| {
                merge_sets()
                    .iter()
                    .all(|(s, what)| replay(s, what, &e.bottom_up_merges(s), true))
            },
        },
        Check {
            exercise: 8,
            name: "no box and one box need no merge; two need one",
            points: 2,
            run: |e| {
                let one = [b([0.0; 3], [1.0; 3])];
                let two = [b([0.0; 3], [1.0; 3]), b([5.0; 3], [6.0; 3])];
                same("bottom_up_merges([])", vec![], e.bottom_up_merges(&[]))
                    && same(
                        format!("bottom_up_merges([{}])", show_box(&one[0])),
                        vec![],
                        e.bottom_up_merges(&one),
                    )
                    && replay(
                        &two,
                        &format!("[{}, {}]", show_box(&two[0]), show_box(&two[1])),
                        &e.bottom_up_merges(&two),
                        true,
                    )
            },
        },
    ]
}

/// Replays a merge sequence: whether every merge joins two live clusters and
/// exactly one cluster is left, explained with the first merge that goes
/// wrong. With `check_greedy`, each merge must also have the smallest merged
/// volume among the live pairs of its step.
fn replay(boxes: &[Aabb], what: &str, merges: &[(u32, u32)], check_greedy: bool) -> bool {
    let n = boxes.len();
    let call = format!("bottom_up_merges({what})");
    if merges.len() != n.saturating_sub(1) {
        return fail(format!(
            "{call} returned {} merges, expected {} (n - 1)",
            merges.len(),
            n.saturating_sub(1)
        ));
    }
    let mut live: Vec<Option<Aabb>> = boxes.iter().copied().map(Some).collect();
    for (k, &(a, b)) in merges.iter().enumerate() {
        let (a, b) = (a as usize, b as usize);
        let alive = |i: usize, live: &[Option<Aabb>]| match live.get(i) {
            Some(Some(x)) => Ok(*x),
            Some(None) => Err(format!("cluster {i} was already merged")),
            None => Err(format!(
                "cluster {i} does not exist yet (the boxes are 0..{n}, merge k creates {n} + k)"
            )),
        };
        let (x, y) = match (alive(a, &live), alive(b, &live)) {
            (Ok(x), Ok(y)) if a != b => (x, y),
            (Err(why), _) | (_, Err(why)) => {
                return fail(format!("{call}: merge {k} is ({a}, {b}), but {why}"))
            }
            _ => {
                return fail(format!(
                    "{call}: merge {k} is ({a}, {b}), a cluster with itself"
                ))
            }
        };
        let cost = x.union(&y).volume();
        if check_greedy {
            let ids: Vec<usize> = (0..live.len()).filter(|&i| live[i].is_some()).collect();
            let best = ids
                .iter()
                .enumerate()
                .flat_map(|(s, &i)| ids[s + 1..].iter().map(move |&j| (i, j)))
                .map(|(i, j)| {
                    let (Some(p), Some(q)) = (live[i], live[j]) else {
                        return (f32::INFINITY, i, j);
                    };
                    (p.union(&q).volume(), i, j)
                })
                .fold((f32::INFINITY, 0, 0), |m, c| if c.0 < m.0 { c } else { m });
            if cost > best.0 * (1.0 + 1e-5) {
                return fail(format!(
                    "{call}: merge {k} is ({a}, {b}), whose merged box has volume {cost}, but \
                     merging ({}, {}) gives only {}",
                    best.1, best.2, best.0
                ));
            }
        }
        live[a] = None;
        live[b] = None;
        live.push(Some(x.union(&y)));
    }
    live.iter().flatten().count() == 1
        || fail(format!(
            "{call}: more than one cluster is left after the merges"
        ))
}

fn merge_sets() -> Vec<(Vec<Aabb>, String)> {
    let mut r = Rng(99);
    let mut sets: Vec<(Vec<Aabb>, String)> = (0..6)
        .map(|k| {
            let n = 5 + 7 * k;
            let set = (0..n)
                .map(|_| {
                    let lo = r.point(20.0, Vec3::ZERO);
                    Aabb::new(lo, lo + Vec3::new(r.next(), r.next(), r.next()) * 3.0 + 0.1)
                })
                .collect();
            (set, format!("{n} random boxes in a cube of side 20"))
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
    sets.push((
        group(Vec3::ZERO).chain(group(Vec3::splat(100.0))).collect(),
        "two rows of 4 unit cubes 0.1 apart, the rows 100 apart".into(),
    ));
    sets
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;
    use crate::grader::wrong::LOOPS;
    use std::time::Duration;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 7;

    /// Greedy merging with the slips of the wrong answers: `which` as in
    /// [`bottom_up_merges`].
    fn greedy(which: u32, boxes: &[Aabb]) -> Vec<(u32, u32)> {
        let n = boxes.len() as u32;
        let mut live: Vec<(u32, Aabb)> = boxes
            .iter()
            .enumerate()
            .map(|(i, b)| (i as u32, *b))
            .collect();
        let mut out = Vec::new();
        // 7: `n - 1` steps, which underflows for no box at all.
        let steps = if which == 7 {
            boxes.len() - 1
        } else {
            boxes.len().saturating_sub(1)
        };
        for _ in 0..steps {
            let mut best = (f32::INFINITY, 0, 1);
            for i in 0..live.len() {
                for j in i + 1..live.len() {
                    let (x, y) = (live[i].1, live[j].1);
                    let v = match which {
                        2 => x.volume() + y.volume(),
                        5 => x.center().distance(y.center()),
                        6 if j != i + 1 => continue,
                        _ => x.union(&y).volume(),
                    };
                    if v < best.0 {
                        best = (v, i, j);
                    }
                }
            }
            let (_, i, j) = best;
            out.push((live[i].0, live[j].0));
            let id = match which {
                3 => n + out.len() as u32, // one too far
                4 => live[i].0,            // keeps its first member's id
                _ => n + out.len() as u32 - 1,
            };
            live[i] = (id, live[i].1.union(&live[j].1));
            live.remove(j);
        }
        out
    }

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
            // 2: greedy by the sum of the two volumes, not the merged volume.
            // 3: the k-th merge creates cluster n + k + 1.
            // 4: a merged cluster keeps the id of its first member.
            // 5: greedy by the distance between the boxes' centres.
            // 6: considers only neighbours in the list of live clusters.
            // 7: loops `n - 1` times: panics on no box at all.
            2..=7 => greedy(which, boxes),
            _ => Reference.bottom_up_merges(boxes),
        }
    }
}
