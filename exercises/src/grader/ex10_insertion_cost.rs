//! Exercise 10: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 10.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 10,
            name: "a sibling without ancestors: the new parent's area",
            points: 2,
            run: |e| {
                let (s, n) = (b([0.0; 3], [1.0; 3]), b([2.0, 0.0, 0.0], [3.0, 1.0, 1.0]));
                // Union is 3 x 1 x 1: area 2 * (3 + 1 + 3) = 14.
                cost_is(e, &s, &[], &n, None)
            },
        },
        Check {
            exercise: 10,
            name: "ancestors add only their growth (zero when they contain the object)",
            points: 2,
            run: |e| {
                let (s, n) = (b([0.0; 3], [1.0; 3]), b([2.0, 0.0, 0.0], [3.0, 1.0, 1.0]));
                let big = b([-5.0; 3], [5.0; 3]);
                let small = b([0.0; 3], [2.0, 1.0, 1.0]); // grows to 3 x 1 x 1: 10 -> 14
                cost_is(e, &s, &[big], &n, None) && cost_is(e, &s, &[small, big], &n, None)
            },
        },
        Check {
            exercise: 10,
            name: "every ancestor that grows counts, the parent and the root too",
            points: 2,
            run: |e| {
                let (s, n) = (b([0.0; 3], [1.0; 3]), b([2.0, 0.0, 0.0], [3.0, 1.0, 1.0]));
                let ancestors = [
                    b([0.0; 3], [1.0, 2.0, 1.0]),
                    b([0.0; 3], [1.0, 2.0, 2.0]),
                    b([-1.0, 0.0, 0.0], [1.0, 2.0, 2.0]),
                ];
                // 14, plus growths 12, 16 and 16.
                cost_is(e, &s, &ancestors, &n, None)
            },
        },
        Check {
            exercise: 10,
            name: "agrees with the library's DynamicTree on random trees",
            points: 2,
            run: |e| {
                use bvhkit::builders::{DynNode, DynamicConfig, DynamicTree, NULL};
                let prims = boxes(60, 11, Vec3::ZERO);
                let mut storage = vec![DynNode::<Aabb>::EMPTY; 2 * 61 - 1];
                let handles: Vec<u32> = {
                    let Ok(mut tree) = DynamicTree::new(&mut storage, DynamicConfig::default())
                    else {
                        return false;
                    };
                    prims
                        .iter()
                        .enumerate()
                        .filter_map(|(i, p)| tree.insert(i as u32, p).ok().map(|h| h.index()))
                        .collect()
                };
                let new = b([3.3, 4.1, 0.2], [4.0, 5.0, 0.9]);
                handles.iter().all(|&h| {
                    let mut ancestors = Vec::new();
                    let mut a = storage[h as usize].parent;
                    while a != NULL {
                        ancestors.push(storage[a as usize].bv);
                        a = storage[a as usize].parent;
                    }
                    let mine = e.insertion_cost(&storage[h as usize].bv, &ancestors, &new);
                    let lib = DynamicTree::insertion_cost_of(&storage, h, &new);
                    (mine - lib).abs() <= 1e-6 * lib.abs().max(1.0)
                        || fail(format!(
                            "insertion_cost next to node {h} of a DynamicTree over 60 boxes on \
                             a jittered grid ({} ancestors), new = {}, returned {mine}, \
                             expected {lib}",
                            ancestors.len(),
                            show_box(&new)
                        ))
                })
            },
        },
        Check {
            exercise: 10,
            name: "summed in f64: an object a million units away",
            points: 2,
            run: |e| {
                // Every area here is a whole number an f32 holds exactly, but
                // the total passes 2^25, where f32 steps by 4: a sum kept in
                // f32 comes out a few units off.
                let s = b([0.0; 3], [1.0; 3]);
                let n = b([1_000_001.0, 0.0, 0.0], [1_000_002.0, 1.0, 1.0]);
                let ancestors: Vec<Aabb> = [
                    [2.0, 2.0, 1.0],
                    [2.0, 2.0, 2.0],
                    [2.0, 3.0, 2.0],
                    [2.0, 3.0, 3.0],
                    [4.0, 3.0, 3.0],
                    [4.0, 4.0, 3.0],
                    [4.0, 4.0, 4.0],
                ]
                .iter()
                .map(|&hi| b([0.0; 3], hi))
                .collect();
                cost_is(
                    e,
                    &s,
                    &ancestors,
                    &n,
                    Some("the unit cube at the origin, 7 nested ancestors from 2 x 2 x 1 up to 4 x 4 x 4, and new = the unit cube at x = 1 000 001"),
                )
            },
        },
    ]
}

/// `insertion_cost` against the parent's area plus each ancestor's growth,
/// every area from `surface_area` and the sum in `f64`, to within 1e-9
/// (relative), explained with the inputs (or `what`, for long ones).
fn cost_is(e: &dyn Exercises, s: &Aabb, ancestors: &[Aabb], n: &Aabb, what: Option<&str>) -> bool {
    let area = |b: &Aabb| b.surface_area() as f64;
    let want = area(&s.union(n))
        + ancestors
            .iter()
            .map(|a| area(&a.union(n)) - area(a))
            .sum::<f64>();
    let got = e.insertion_cost(s, ancestors, n);
    let call = match what {
        Some(w) => format!("insertion_cost for {w}"),
        None => {
            let a: Vec<String> = ancestors.iter().map(show_box).collect();
            format!(
                "insertion_cost(sibling {}, ancestors [{}], new {})",
                show_box(s),
                a.join(", "),
                show_box(n)
            )
        }
    };
    close(got, want) || fail(format!("{call} returned {got}, expected {want}"))
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 7;

    pub fn insertion_cost(which: u32, sibling: &Aabb, ancestors: &[Aabb], new: &Aabb) -> f64 {
        let area = |b: &Aabb| b.surface_area() as f64;
        let parent = area(&sibling.union(new));
        let growth = |a: &Aabb| area(&a.union(new)) - area(a);
        match which {
            // Forgets the ancestors.
            1 => parent,
            // Adds the ancestors' whole areas, not their growth.
            2 => parent + ancestors.iter().map(|a| area(&a.union(new))).sum::<f64>(),
            // Only the parent's growth, not the rest of the path.
            3 => parent + ancestors.first().map_or(0.0, growth),
            // Stops before the root.
            4 => {
                let path = &ancestors[..ancestors.len().saturating_sub(1)];
                parent + path.iter().map(growth).sum::<f64>()
            }
            // Growth in volume instead of surface area.
            5 => {
                parent
                    + ancestors
                        .iter()
                        .map(|a| (a.union(new).volume() - a.volume()) as f64)
                        .sum::<f64>()
            }
            // The new parent's growth over the sibling, not its whole area.
            6 => parent - area(sibling) + ancestors.iter().map(growth).sum::<f64>(),
            // Right terms, summed in f32.
            7 => {
                let mut t = sibling.union(new).surface_area();
                for a in ancestors {
                    t += a.union(new).surface_area() - a.surface_area();
                }
                t as f64
            }
            _ => Reference.insertion_cost(sibling, ancestors, new),
        }
    }
}
