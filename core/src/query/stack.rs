//! The fixed-capacity stack every depth-first traversal uses.

use crate::Error;

/// A stack on an array of `N` entries. A push beyond `N` is an
/// [`Error::StackOverflow`] naming the tree's depth, never a panic.
#[derive(Debug)]
pub(crate) struct Stack<T, const N: usize> {
    items: [T; N],
    len: usize,
    depth: usize,
}

impl<T: Copy + Default, const N: usize> Stack<T, N> {
    /// A stack holding `first`, for a tree of `depth` (reported on overflow).
    #[inline(always)] // built in the caller's frame, not copied into it
    pub(crate) fn with(first: T, depth: usize) -> Self {
        // Filled with zeros (one block clear), not with copies of `first`
        // (one store per entry): a query on a small tree pays this per call.
        let mut items = [T::default(); N];
        items[0] = first;
        Stack {
            items,
            len: 1,
            depth,
        }
    }

    /// Empties the stack and pushes `first` (reuse without re-initialising).
    #[inline]
    pub(crate) fn reset(&mut self, first: T) {
        self.items[0] = first;
        self.len = 1;
    }

    #[inline]
    pub(crate) fn push(&mut self, item: T) -> Result<(), Error> {
        let slot = self.items.get_mut(self.len).ok_or(Error::StackOverflow {
            depth: self.depth,
            capacity: N,
        })?;
        *slot = item;
        self.len += 1;
        Ok(())
    }

    #[inline]
    pub(crate) fn pop(&mut self) -> Option<T> {
        self.len = self.len.checked_sub(1)?;
        Some(self.items[self.len])
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
}
