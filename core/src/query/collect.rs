//! A fixed-capacity result buffer for callbacks.

use crate::Error;

/// Collects query results into a caller-provided slice and remembers how many
/// there were in total, so a full buffer is an error, never a silent truncation.
///
/// ```
/// use bvhkit::Collector;
/// let mut buf = [0u32; 2];
/// let mut out = Collector::new(&mut buf);
/// for i in 0..3 { out.push(i); }
/// assert_eq!(out.finish(), Err(bvhkit::Error::ResultCapacity { found: 3, capacity: 2 }));
/// ```
#[derive(Debug)]
pub struct Collector<'a, T> {
    buf: &'a mut [T],
    found: usize,
}

impl<'a, T> Collector<'a, T> {
    /// An empty collector over `buf`.
    pub fn new(buf: &'a mut [T]) -> Self {
        Collector { buf, found: 0 }
    }

    /// Records one result (stored while there is room, always counted).
    #[inline]
    pub fn push(&mut self, item: T) {
        if let Some(slot) = self.buf.get_mut(self.found) {
            *slot = item;
        }
        self.found += 1;
    }

    /// How many results were pushed.
    pub fn found(&self) -> usize {
        self.found
    }

    /// The results, or [`Error::ResultCapacity`] if any did not fit.
    pub fn finish(self) -> Result<&'a [T], Error> {
        if self.found > self.buf.len() {
            return Err(Error::ResultCapacity {
                found: self.found,
                capacity: self.buf.len(),
            });
        }
        let buf: &'a [T] = self.buf;
        Ok(&buf[..self.found])
    }
}
