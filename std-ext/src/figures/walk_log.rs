//! A tally that also records the order of a query's tests, so that a figure
//! drawing a walk can check its own replay against the library's walk.

use bvhkit::{Counts, Tally};
use std::cell::RefCell;

/// What the library reports while it walks, in order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Event {
    /// One volume test (`Nv`): a node, or a pair of nodes.
    Node,
    /// A leaf's (or leaf pair's) primitive tests (`Np`).
    Prims(u32),
    /// A primitive found (region) or tested against the ray.
    Prim(u32),
    /// A primitive pair reported.
    Pair(u32, u32),
}

/// A [`Tally`] that counts and also writes the order of the tests.
pub(super) struct Log<'a> {
    pub(super) counts: Counts,
    pub(super) events: &'a RefCell<Vec<Event>>,
}

impl Tally for Log<'_> {
    fn bv_tests(&mut self, n: u32) {
        self.counts.bv_tests(n);
        self.events.borrow_mut().extend((0..n).map(|_| Event::Node));
    }
    fn prim_tests(&mut self, n: u32) {
        self.counts.prim_tests(n);
        self.events.borrow_mut().push(Event::Prims(n));
    }
    fn updates(&mut self, n: u32) {
        self.counts.updates(n);
    }
}
