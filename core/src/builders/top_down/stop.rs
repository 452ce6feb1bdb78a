//! Stopping and falling back: the depth budget that halves a node when the
//! levels left are only just enough, and the fallbacks of the lectures when
//! a strategy does not separate a node (another axis choice, then the SAH,
//! then the object median, which always separates by count). Each fallback
//! is counted in the tree's [`BuildReport`].

use super::axes::longest_direction;
use super::criteria::Norm;
use super::partition::apply;
use super::source::Source;
use super::split_points::{plan, Plan};
use super::{Halves, Task, TopDown};
use crate::builders::strategy::{AxisChoice, OnFailure, Partition, SplitPoint};
use crate::builders::BuildReport;
use crate::bv::BoundingVolume;

impl TopDown {
    /// Tries the configured strategy, then the fallbacks of the lectures.
    pub(super) fn split<S: Source, B: BoundingVolume>(
        &self,
        src: &S,
        range: &mut [S::Item],
        scratch: &mut [u32],
        task: &mut Task,
        bv: &B,
        report: &mut BuildReport,
    ) -> Option<Halves> {
        let norm = Norm::new(&task.bounds);
        // Binned SAH on x, y and z bins over any box that holds the
        // centroids; every other strategy, and every fallback, reads the
        // centroids' own box.
        let loose_ok = self.is_binned_sah() && self.axis == AxisChoice::BestOfXyz;
        if !loose_ok {
            task.tighten(src, range);
        }
        // Depth budget: a node of n primitives needs log2(n / max leaf)
        // more levels even when halved exactly. A criterion that splits off
        // a few primitives at a time (minimum overlap, maximum separation on
        // a curved surface) would spend the levels left and end in a leaf
        // far over the limit at `max_depth`; once the levels left are only
        // just enough, the node is halved at its object median instead.
        let leaves = range
            .len()
            .div_ceil(self.stop.max_leaf_size.max(1) as usize);
        let needed = usize::BITS - (leaves.max(1) - 1).leading_zeros(); // ceil(log2)
        let left = self.stop.max_depth.saturating_sub(u32::from(task.depth));
        if needed >= left && leaves > 1 {
            report.depth_limited += 1;
            task.tighten(src, range);
            let dir = longest_direction(task);
            let mid = range.len() / 2;
            return Some(apply(src, range, Plan::Order { dir, mid }));
        }
        let n = range.len();
        let mut attempt = |range: &mut [S::Item],
                           task: &Task,
                           axis: AxisChoice,
                           split: SplitPoint,
                           partition: Partition| {
            let plan = plan(src, range, scratch, task, bv, axis, split, partition, &norm)?;
            let h = apply(src, range, plan);
            (h.mid > 0 && h.mid < range.len()).then_some(h)
        };
        let parent = task.bounds;
        let acceptable = |h: &Halves| {
            !(norm.nearly_as_large(&h.bounds[0], &parent)
                && norm.nearly_as_large(&h.bounds[1], &parent))
        };
        // A criterion that ignores how many primitives each side holds can
        // be satisfied by cutting off a sliver (one triangle at the edge of a
        // curved mesh has no overlap with the rest): under 1% of a node of
        // 100 or more on one side counts as a failure for those.
        let count_blind = !self.partition.weighs_counts();
        let lopsided = |h: &Halves| count_blind && n >= 100 && h.mid.min(n - h.mid) * 100 < n;
        // At most twice: when the bins spanned the node's box, once more
        // over the centroids' own box. Every attempt lands in the one `h`:
        // a separate `Option<Halves>` per attempt (104 bytes each) would
        // each take its own stack slot.
        let good = |h: &Option<Halves>| h.as_ref().is_some_and(|h| acceptable(h) && !lopsided(h));
        let mut h;
        loop {
            h = attempt(range, task, self.axis, self.split, self.partition);
            if good(&h) {
                return h;
            }
            if task.tight {
                break;
            }
            task.tighten(src, range);
        }
        report.fallback_splits += 1;
        if self.axis != AxisChoice::BestOfXyz {
            h = attempt(
                range,
                task,
                AxisChoice::BestOfXyz,
                self.split,
                self.partition,
            );
            if good(&h) {
                return h;
            }
        }
        if count_blind {
            // Another criterion: binned SAH, which prices each side's count.
            h = attempt(
                range,
                task,
                AxisChoice::BestOfXyz,
                SplitPoint::Bins(16),
                Partition::SurfaceArea,
            );
            if h.as_ref().is_some_and(acceptable) {
                return h;
            }
        }
        // The object median always separates by count, even identical centroids.
        let dir = longest_direction(task);
        h = Some(apply(
            src,
            range,
            Plan::Order {
                dir,
                mid: range.len() / 2,
            },
        ));
        match self.on_failure {
            OnFailure::ForceSplit => h,
            OnFailure::Leaf => h.filter(acceptable),
        }
    }
}

// The count-blind criteria are compiled with the `strategies` feature.
// Two attributes, not `cfg(all(test, ..))`: cargo-mutants skips a module
// marked `#[cfg(test)]` and would otherwise mutate these tests' own code.
#[cfg(test)]
#[cfg(feature = "strategies")]
mod tests {
    use crate::builders::BuildReport;
    use crate::{Aabb, Node, Partition, TopDown, Triangle};
    use glam::Vec3;

    /// `cluster` triangles in a 10 x 10 x k block, plus one far away.
    fn cluster_and_one_far(cluster: usize) -> [Triangle; 1000] {
        core::array::from_fn(|i| {
            let o = if i == cluster {
                Vec3::splat(100.0)
            } else {
                let i = i as f32;
                Vec3::new(i % 10.0, (i / 10.0).floor() % 10.0, (i / 100.0).floor()) * 0.1
            };
            Triangle::new(o, o + Vec3::X * 0.3, o + Vec3::Y * 0.3)
        })
    }

    fn report(partition: Partition, prims: &[Triangle]) -> BuildReport {
        let mut nodes = [Node::<Aabb>::ZERO; 2 * 1000 - 1];
        let mut idx = [0u32; 1000];
        let cfg = TopDown {
            partition,
            ..TopDown::sah()
        };
        cfg.build(prims, &mut nodes, &mut idx)
            .unwrap()
            .build_report()
    }

    /// The sliver rule: cutting 1 of 1,000 off is a failed split for a
    /// count-blind criterion (the root's, here), not for the SAH; 1 of 100
    /// is exactly 1%, not under it.
    #[test]
    fn a_cut_under_one_percent_is_a_failed_split_for_count_blind_criteria() {
        let far = cluster_and_one_far(999);
        assert_eq!(report(Partition::Overlap, &far).fallback_splits, 1);
        assert_eq!(report(Partition::Volume, &far).fallback_splits, 1);
        assert_eq!(report(Partition::SurfaceArea, &far).fallback_splits, 0);
        let hundred = &cluster_and_one_far(99)[..100];
        assert_eq!(report(Partition::Overlap, hundred).fallback_splits, 0);
        assert!(!Partition::Separation.weighs_counts());
        assert!(Partition::Balance.weighs_counts() && Partition::SurfaceArea.weighs_counts());
        let weighted = |surface_area, balance| Partition::Weighted {
            surface_area,
            volume: 1.0,
            overlap: 1.0,
            balance,
        };
        assert!(!weighted(0.0, 0.0).weighs_counts());
        assert!(weighted(0.5, 0.0).weighs_counts() && weighted(0.0, 0.5).weighs_counts());
    }
}
