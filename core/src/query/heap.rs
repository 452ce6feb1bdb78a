//! A fixed-capacity min-heap for best-first traversals.

/// Entries the best-first queue holds before it falls back to depth-first.
pub const BEST_FIRST_QUEUE: usize = 64;

/// Binary min-heap of `(key, node)` on an array: no allocation. `push`
/// refuses (returns `false`) when full, and the traversal then handles the
/// node depth-first instead, so nothing is dropped.
#[derive(Debug)]
pub(crate) struct MinHeap<const N: usize> {
    items: [(f64, u32); N],
    len: usize,
}

impl<const N: usize> MinHeap<N> {
    pub(crate) const fn new() -> Self {
        MinHeap {
            items: [(0.0, 0); N],
            len: 0,
        }
    }

    pub(crate) fn push(&mut self, key: f64, node: u32) -> bool {
        if self.len == N {
            return false;
        }
        let mut i = self.len;
        self.items[i] = (key, node);
        self.len += 1;
        while i > 0 {
            let parent = (i - 1) / 2;
            if self.items[parent].0 <= self.items[i].0 {
                break;
            }
            self.items.swap(parent, i);
            i = parent;
        }
        true
    }

    pub(crate) fn pop(&mut self) -> Option<(f64, u32)> {
        if self.len == 0 {
            return None;
        }
        let top = self.items[0];
        self.len -= 1;
        self.items[0] = self.items[self.len];
        let mut i = 0;
        loop {
            let (l, r) = (2 * i + 1, 2 * i + 2);
            let mut m = i;
            if l < self.len && self.items[l].0 < self.items[m].0 {
                m = l;
            }
            if r < self.len && self.items[r].0 < self.items[m].0 {
                m = r;
            }
            if m == i {
                break;
            }
            self.items.swap(i, m);
            i = m;
        }
        Some(top)
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
}
