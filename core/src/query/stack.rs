//! The fixed-capacity stack every depth-first traversal uses.

use crate::Error;

/// A stack of at most `N` entries on [`heapless::Vec`]. A push beyond `N` is
/// an [`Error::StackOverflow`] naming the tree's depth, never a panic.
#[derive(Debug)]
pub(crate) struct Stack<T, const N: usize> {
    items: heapless::Vec<T, N>,
    depth: usize,
}

impl<T: Copy, const N: usize> Stack<T, N> {
    /// A stack holding `first`, for a tree of `depth` (reported on overflow).
    #[inline(always)] // built in the caller's frame, not copied into it
    pub(crate) fn with(first: T, depth: usize) -> Self {
        // heapless leaves the unused entries uninitialised: a query on a small
        // tree pays nothing for the capacity it does not use.
        const { assert!(N > 0, "a traversal stack holds at least the root") };
        let mut items = heapless::Vec::new();
        let _ = items.push(first); // room: N > 0, checked above

        Stack { items, depth }
    }

    /// Empties the stack and pushes `first` (reuse without re-initialising).
    #[inline]
    pub(crate) fn reset(&mut self, first: T) {
        self.items.clear();
        let _ = self.items.push(first);
    }

    #[inline]
    pub(crate) fn push(&mut self, item: T) -> Result<(), Error> {
        self.items.push(item).map_err(|_| Error::StackOverflow {
            depth: self.depth,
            capacity: N,
        })
    }

    #[inline]
    pub(crate) fn pop(&mut self) -> Option<T> {
        self.items.pop()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overflow_is_an_error_and_order_is_last_in_first_out() {
        let mut s = Stack::<u32, 2>::with(1, 7);
        s.push(2).unwrap();
        assert_eq!(
            s.push(3),
            Err(Error::StackOverflow {
                depth: 7,
                capacity: 2
            })
        );
        assert_eq!((s.pop(), s.pop(), s.pop()), (Some(2), Some(1), None));
    }

    #[test]
    fn reset_leaves_only_the_new_first_entry() {
        let mut s = Stack::<u32, 4>::with(1, 3);
        s.push(2).unwrap();
        s.push(3).unwrap();
        s.reset(9);
        assert_eq!((s.pop(), s.pop()), (Some(9), None));
        // The whole capacity is free again after a reset.
        s.reset(5);
        for i in 0..3 {
            s.push(i).unwrap();
        }
        assert!(s.push(4).is_err());
    }
}
