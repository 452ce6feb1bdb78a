//! Stopping and falling back: the depth budget that halves a node when the
//! levels left are only just enough, and the fallbacks of the lectures when
//! a strategy does not separate a node (another axis choice, then the object
//! median, which always separates by count).

use super::axes::longest_direction;
use super::criteria::Norm;
use super::partition::apply;
use super::source::Source;
use super::split_points::{plan, Plan};
use super::{Halves, Task, TopDown};
use crate::builders::strategy::{AxisChoice, OnFailure, Partition, SplitPoint};
use crate::bv::BoundingVolume;

impl TopDown {
    /// Tries the configured strategy, then the fallbacks of the lectures.
    pub(super) fn split<S: Source, B: BoundingVolume>(
        &self,
        src: &S,
        range: &mut [S::Item],
        scratch: &mut [u32],
        task: &Task,
        bv: &B,
    ) -> Option<Halves> {
        let norm = Norm::new(&task.bounds);
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
        let left = self.stop.max_depth.saturating_sub(task.depth);
        if needed >= left && leaves > 1 {
            let dir = longest_direction(task);
            let mid = range.len() / 2;
            return Some(apply(src, range, Plan::Order { dir, mid }));
        }
        let mut attempt = |axis: AxisChoice, split: SplitPoint, partition: Partition| {
            let plan = plan(src, range, scratch, task, bv, axis, split, partition, &norm)?;
            let h = apply(src, range, plan);
            (h.mid > 0 && h.mid < range.len()).then_some(h)
        };
        let acceptable = |h: &Halves| {
            !(norm.nearly_as_large(&h.bounds[0], &task.bounds)
                && norm.nearly_as_large(&h.bounds[1], &task.bounds))
        };
        if let Some(h) = attempt(self.axis, self.split, self.partition) {
            if acceptable(&h) {
                return Some(h);
            }
        }
        if self.axis != AxisChoice::BestOfXyz {
            if let Some(h) = attempt(AxisChoice::BestOfXyz, self.split, self.partition) {
                if acceptable(&h) {
                    return Some(h);
                }
            }
        }
        // The object median always separates by count, even identical centroids.
        let dir = longest_direction(task);
        let forced = apply(
            src,
            range,
            Plan::Order {
                dir,
                mid: range.len() / 2,
            },
        );
        match self.on_failure {
            OnFailure::ForceSplit => Some(forced),
            OnFailure::Leaf => acceptable(&forced).then_some(forced),
        }
    }
}
