//! The fixed-capacity min-queue for best-first traversals.

use core::cmp::Ordering;
use heapless::binary_heap::{BinaryHeap, Min};

/// Entries the best-first queue holds before it falls back to depth-first.
pub const BEST_FIRST_QUEUE: usize = 64;

/// A queued node and its key, ordered by key (`f64::total_cmp`, so the order
/// is total even for keys no traversal produces, such as NaN), then by node.
#[derive(Clone, Copy, Debug)]
struct Entry(f64, u32);

impl PartialEq for Entry {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Entry {}

impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.total_cmp(&other.0).then(self.1.cmp(&other.1))
    }
}

/// Min-queue of `(key, node)` on [`heapless::BinaryHeap`]: no allocation.
/// `push` refuses (returns `false`) when full, and the traversal then handles
/// the node depth-first instead, so nothing is dropped.
#[derive(Debug)]
pub(crate) struct MinHeap<const N: usize> {
    items: BinaryHeap<Entry, Min, N>,
}

impl<const N: usize> MinHeap<N> {
    pub(crate) const fn new() -> Self {
        MinHeap {
            items: BinaryHeap::new(),
        }
    }

    #[inline]
    pub(crate) fn push(&mut self, key: f64, node: u32) -> bool {
        self.items.push(Entry(key, node)).is_ok()
    }

    #[inline]
    pub(crate) fn pop(&mut self) -> Option<(f64, u32)> {
        self.items.pop().map(|Entry(key, node)| (key, node))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pops_in_key_order_and_refuses_when_full() {
        let mut h = MinHeap::<4>::new();
        for (k, n) in [(3.0, 3), (1.0, 1), (2.0, 2), (0.5, 0)] {
            assert!(h.push(k, n));
        }
        assert!(!h.push(9.0, 9));
        let order: [u32; 4] = core::array::from_fn(|_| h.pop().map_or(99, |e| e.1));
        assert_eq!(order, [0, 1, 2, 3]);
        assert_eq!(h.pop(), None);
    }

    #[test]
    fn entries_are_equal_exactly_when_their_order_says_so() {
        // `total_cmp` tells -0.0 from 0.0 and calls NaN equal to itself; `==`
        // must agree with it, as `Eq` and `Ord` promise.
        assert_eq!(Entry(0.5, 3), Entry(0.5, 3));
        assert_ne!(Entry(0.5, 3), Entry(0.5, 4));
        assert_ne!(Entry(-0.0, 3), Entry(0.0, 3));
        assert_eq!(Entry(f64::NAN, 3), Entry(f64::NAN, 3));
        assert!(Entry(0.25, 9) < Entry(0.5, 0));
        assert!(Entry(0.5, 0) < Entry(0.5, 1));
    }
}
