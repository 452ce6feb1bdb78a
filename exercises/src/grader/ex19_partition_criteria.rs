//! Exercise 19: the checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 19.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 19,
            name: "balance and the SAH (counts weigh the areas, in f64)",
            points: 3,
            run: |e| {
                let (l, r) = (b([0.0; 3], [1.0, 1.0, 1.0]), b([0.0; 3], [2.0, 1.0, 1.0]));
                // 0.1, 0.2 and 0.3 are not exact in binary, and 2^24 + 1 is
                // not an f32: an f32 product is off by about 1e-7.
                let small = b([0.0; 3], [0.1, 0.2, 0.3]);
                let big = 16_777_217u32;
                let e64 = (small.max - small.min).as_dvec3();
                let area = 2.0 * (e64.x * e64.y + e64.y * e64.z + e64.z * e64.x);
                cost_is(e, Partition::Balance, (&l, 7), (&r, 3), 4.0)
                    && cost_is(e, Partition::Balance, (&l, 3), (&r, 7), 4.0)
                    && cost_is(e, Partition::Balance, (&l, 5), (&r, 5), 0.0)
                    // 7 * 6 + 3 * 10
                    && cost_is(e, Partition::SurfaceArea, (&l, 7), (&r, 3), 72.0)
                    && cost_is(
                        e,
                        Partition::SurfaceArea,
                        (&small, big),
                        (&l, 1),
                        big as f64 * area + 6.0,
                    )
            },
        },
        Check {
            exercise: 19,
            name: "volume sum and the larger child",
            points: 3,
            run: |e| {
                let (l, r) = (b([0.0; 3], [1.0, 2.0, 3.0]), b([5.0; 3], [9.0, 6.0, 6.0]));
                cost_is(e, Partition::Volume, (&l, 1), (&r, 1), 10.0)
                    && cost_is(e, Partition::LargerChild, (&l, 1), (&r, 1), 6.0)
                    && cost_is(e, Partition::LargerChild, (&r, 1), (&l, 1), 6.0)
            },
        },
        Check {
            exercise: 19,
            name: "overlap volume and separation, apart on one axis or on two",
            points: 4,
            run: |e| {
                let l = b([0.0; 3], [2.0, 2.0, 2.0]);
                let overlapping = b([1.0, 1.0, 1.5], [3.0, 3.0, 3.0]); // shares 1 x 1 x 0.5
                let apart_x = b([4.0, 0.5, 0.5], [5.0, 1.5, 1.5]); // 2 away along x only
                let apart_xy = b([3.0, 5.0, 0.0], [4.0, 6.0, 2.0]); // 1 along x, 3 along y
                let touching = b([2.0, 0.0, 0.0], [3.0, 2.0, 2.0]); // shares the face x = 2
                let cost = |c, r: &Aabb, want| cost_is(e, c, (&l, 1), (r, 1), want);
                cost(Partition::Overlap, &overlapping, 0.5)
                    && cost(Partition::Overlap, &apart_x, 0.0)
                    && cost(Partition::Overlap, &apart_xy, 0.0)
                    && cost(Partition::Overlap, &touching, 0.0)
                    && cost(Partition::Separation, &apart_x, -2.0)
                    && cost(Partition::Separation, &apart_xy, -3.0)
                    && cost(Partition::Separation, &overlapping, 0.5)
                    && cost(Partition::Separation, &touching, 0.0)
            },
        },
    ]
}

/// Whether `criterion` costs `want` for `l` (with its count) and `r`.
fn cost_is(e: &dyn Exercises, c: Partition, l: (&Aabb, u32), r: (&Aabb, u32), want: f64) -> bool {
    near(
        format!(
            "partition_cost(Partition::{c:?}, l = {}, nl = {}, r = {}, nr = {})",
            show_box(l.0),
            l.1,
            show_box(r.0),
            r.1
        ),
        want,
        e.partition_cost(c, l.0, l.1, r.0, r.1),
    )
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 7;

    pub fn partition_cost(which: u32, c: Partition, l: &Aabb, nl: u32, r: &Aabb, nr: u32) -> f64 {
        let ext = |b: &Aabb| (b.max - b.min).as_dvec3();
        match (which, c) {
            // Areas without the counts.
            (1, Partition::SurfaceArea) => {
                let a = |b: &Aabb| {
                    let e = ext(b);
                    2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
                };
                a(l) + a(r)
            }
            // Intersection extents not clamped.
            (2, Partition::Overlap) => {
                let s = (l.max.min(r.max) - l.min.max(r.min)).as_dvec3();
                if s.x < 0.0 && s.y < 0.0 && s.z < 0.0 {
                    0.0
                } else {
                    s.element_product()
                }
            }
            // The smallest gap over the axes.
            (3, Partition::Separation) => {
                -((l.min - r.max).max(r.min - l.max).min_element() as f64)
            }
            // The sum, not the larger.
            (4, Partition::LargerChild) => ext(l).element_product() + ext(r).element_product(),
            // The difference of the counts without its absolute value.
            (5, Partition::Balance) => nl as f64 - nr as f64,
            // The SAH in f32, widened at the end.
            (6, Partition::SurfaceArea) => {
                (nl as f32 * l.surface_area() + nr as f32 * r.surface_area()) as f64
            }
            // The gap itself, not minus the gap.
            (7, Partition::Separation) => (l.min - r.max).max(r.min - l.max).max_element() as f64,
            _ => Reference.partition_cost(c, l, nl, r, nr),
        }
    }
}
